#!/usr/bin/env python3
"""Stress sweep scenes where a body passes through a shell (issue 32 item 4, SPEC C16): the
run must not end "completed" with the bodies on the wrong side of each other. Scene 116 (a
C3D8 block's corner at 108 m/s into a clamped plastic S4R plate three elements across) and
153 (an S4R box at 289 m/s onto a free S4R plate) once ended "completed" with a projectile
node 1.3 and 1.7 mm beyond the plate's mid-surface; 5163 (an S4R box corner-first at 214 m/s
onto a rigid S4R plate) with its corner 1.35 mm through the plate (the node's side memory lost
to an open touch of the next element); 6623 (a rigid copper block at 249 m/s onto a clamped
0.58 mm plate) with a corner 1.07 mm through (pressed behind the mid-surface, it slid past its
face's edge, and the open touch of the next element's corner was taken as holding it).
Either a scene completes and the checker finds no pass-through, or the run fails and its
reason names the node that passed through a shell.

Usage: check_pass_through.py XPL WORK_DIR [ID ...]   (default IDs: 116 153 5163 6623)
Standard library only.
"""

import sys

from scene_run import check_scenes


def check(_scene, out, _folder, summary):
    status, reason = summary["status"], summary.get("exit_reason", "")
    crossed = [line.strip() for line in out.splitlines() if "passed through" in line]
    if status == "completed":
        ok = not crossed
        said = crossed[0] if crossed else "no pass-through found by the checker"
    else:
        ok = "passed through the shell" in reason
        said = reason
    return ok, [f"status {status}: {said[:300]}"]


def main():
    return check_scenes(__doc__, [116, 153, 5163, 6623], check)


if __name__ == "__main__":
    sys.exit(main())
