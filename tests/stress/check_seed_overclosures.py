#!/usr/bin/env python3
"""Stress sweep scenes whose shell boxes start beside a solid slab's edge (issue 32): none of
their nodes may be seeded as an initial overclosure (the nodes are outside the slab), and the
run must complete. Scenes 86, 120 and 199 of impact_scenes.py once started with box nodes 2.9,
7.1 and 10.2 mm "deep" behind a slab's side face (a node above the slab's top face, beside the
side face's edge, taken as behind that face) and stopped when the penalty's push inverted an
element. The other criteria of these scenes are the sweep's (benchmarks/RESULTS.md).

Usage: check_seed_overclosures.py XPL WORK_DIR [ID ...]   (default IDs: 86 120 199)
Standard library only.
"""

import sys

from scene_run import arguments, run_scene


def main():
    args = arguments(__doc__, [86, 120, 199])
    if args is None:
        return 2
    xpl, work, ids = args
    failures = 0
    for scene in ids:
        _, folder, summary = run_scene(xpl, work, scene)
        msg = (folder / f"scene_{scene}.msg").read_text()
        status = summary["status"]
        seeded = [line for line in msg.splitlines() if "initial overclosure: node" in line]
        ok = status == "completed" and not seeded
        print(f"scene {scene}: {'ok' if ok else 'FAILED'}: status {status}, "
              f"{len(seeded)} initial overclosure(s)")
        for line in seeded[:3]:
            print(f"  {line[:240]}")
        failures += 0 if ok else 1
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
