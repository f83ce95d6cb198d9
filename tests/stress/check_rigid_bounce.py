#!/usr/bin/env python3
"""Stress sweep scenes where a light rigid block bounces off a plate on its default springs
(SPEC R6): the run must complete with its energy balanced. Scenes 6062 (an aluminium block at
131 m/s onto a free steel S4R plate) and 6639 (at 1.3 m/s onto a clamped plate) stopped at
increment 10 with "contact created energy": the body's springs, sized by the plate's node
masses, made its bounce last about three increments, and their onset and release inside an
increment gave back 11-14 % more energy than they took. The body's own budget
(DEFAULT_PENALTY_BODY_BUDGET) spreads the bounce over six or more. Each scene must complete
and hold the drift, kinetic and penetration criteria of impact_check.py.

Usage: check_rigid_bounce.py XPL WORK_DIR [ID ...]   (default IDs: 6062 6639)
Standard library only.
"""

import sys

from scene_run import arguments, run_scene

HELD = ("completed", "drift", "kinetic", "penetration")


def main():
    args = arguments(__doc__, [6062, 6639])
    if args is None:
        return 2
    xpl, work, ids = args
    failures = 0
    for scene in ids:
        report, _, summary = run_scene(xpl, work, scene)
        lines = [line.strip() for line in report.splitlines()]
        held = {c: any(line.startswith(f"ok   {c}") for line in lines) for c in HELD}
        ok = summary["status"] == "completed" and all(held.values())
        missing = [c for c, h in held.items() if not h]
        said = summary.get("exit_reason", "") or (f"not held: {', '.join(missing)}" if missing
                                                  else "every criterion of the four held")
        print(f"scene {scene}: {'ok' if ok else 'FAILED'}: status {summary['status']}: "
              f"{said[:300]}")
        failures += 0 if ok else 1
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
