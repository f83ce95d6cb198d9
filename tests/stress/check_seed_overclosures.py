#!/usr/bin/env python3
"""Stress sweep scenes whose shell boxes start beside a solid slab's edge (issue 32): none of
their nodes may be seeded as an initial overclosure (the nodes are outside the slab), and the
run must complete. Scenes 86, 120 and 199 of impact_scenes.py once started with box nodes 2.9,
7.1 and 10.2 mm "deep" behind a slab's side face (a node above the slab's top face, beside the
side face's edge, taken as behind that face) and stopped when the penalty's push inverted an
element. Scene 7272 (a box at 10 m/s) started with two nodes 0.22 mm above the top face and
1.5 mm in from the side face seeded 1.5 mm deep: within the rim's tolerance in front of the
top face, though far from the rim. The other criteria of these scenes are the sweep's
(benchmarks/RESULTS.md).

Usage: check_seed_overclosures.py XPL WORK_DIR [ID ...]   (default IDs: 86 120 199 7272)
Standard library only.
"""

import sys

from scene_run import check_scenes


def check(scene, _report, folder, summary):
    msg = (folder / f"scene_{scene}.msg").read_text()
    status = summary["status"]
    seeded = [line for line in msg.splitlines() if "initial overclosure: node" in line]
    ok = status == "completed" and not seeded
    return ok, [f"status {status}, {len(seeded)} initial overclosure(s)"] + [
        line[:240] for line in seeded[:3]]


def main():
    return check_scenes(__doc__, [86, 120, 199, 7272], check)


if __name__ == "__main__":
    sys.exit(main())
