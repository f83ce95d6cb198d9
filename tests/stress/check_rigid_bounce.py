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

from scene_run import check_scenes

HELD = ("completed", "drift", "kinetic", "penetration")


def check(_scene, report, _folder, summary):
    lines = [line.strip() for line in report.splitlines()]
    held = {c: any(line.startswith(f"ok   {c}") for line in lines) for c in HELD}
    ok = summary["status"] == "completed" and all(held.values())
    missing = [c for c, h in held.items() if not h]
    said = summary.get("exit_reason", "") or (f"not held: {', '.join(missing)}" if missing
                                              else "every criterion of the four held")
    return ok, [f"status {summary['status']}: {said[:300]}"]


def main():
    return check_scenes(__doc__, [6062, 6639], check)


if __name__ == "__main__":
    sys.exit(main())
