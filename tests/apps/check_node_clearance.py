#!/usr/bin/python3
"""A contact clearance on a node-based surface (SPEC C7, C10, C13; issue 35 item 1): the
node_clear_* decks of examples/clearance hold a 0.8 mm cube's four bottom nodes 0.02 mm inside
a plate, with a clearance of 0.01 mm, once as the cube's element-based face S1 (elem) and once
as a node-based surface (nodes), with ADJUST=YES (adjust) and ADJUST=NO (offset).

Usage: check_node_clearance.py XPL OUT

OUT holds clearance_node_clear_<kind>_<mode>/ of `xpl run`. Checks, per mode: the four nodes of
the node-based surface get the clearance (moved 0.03 mm up, or a permanent offset of 0.03 mm
and no move), none skipped; the cube hits the plate once it has closed by the clearance
(1e-5 s at 1 m/s); and `xpl compare` finds the element-based run and the node-based run
bitwise the same (tolerance 0: coordinates, clearance tables, every history series, last
frame). Exits non-zero on the first failed check.
"""

import pathlib
import re
import subprocess
import sys

import h5py
import numpy as np

H = 1.0e-3
TOL = 1e-9 * H
SLAVES = [200001, 200002, 200101, 200102]
OVERLAP, CLEARANCE, SPEED = 0.02e-3, 0.01e-3, 1.0


def check(condition, message):
    if not condition:
        sys.exit(f"check_node_clearance.py: FAILED: {message}")
    print(f"check_node_clearance.py: ok: {message}")


def result(out, kind, mode):
    name = f"node_clear_{kind}_{mode}"
    d = out / f"clearance_{name}"
    return d / f"{name}.h5", d / f"{name}.msg"


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    xpl, out = sys.argv[1], pathlib.Path(sys.argv[2])
    for mode in ("adjust", "offset"):
        h5, msg = result(out, "nodes", mode)
        f = h5py.File(h5, "r")
        t = f["overclosure/step_1/clearances"]
        check(sorted(int(n) for n in t["node"][:]) == SLAVES,
              f"{mode}: the four nodes of the node-based surface get the clearance")
        check(int(f["overclosure/step_1/clearance_skipped"].attrs["rows"]) == 0, f"{mode}: none skipped")
        check(np.abs(t["gap_before"][:] + OVERLAP).max() <= TOL, f"{mode}: each 0.02 mm inside the plate as read")
        frames = f["frames"]
        u0 = frames[sorted(frames.keys())[0]]["U"][:]
        if mode == "adjust":
            check(np.abs(t["distance"][:] - (OVERLAP + CLEARANCE)).max() <= TOL
                  and np.abs(t["direction"][:] - [0.0, 0.0, 1.0]).max() < 1e-12
                  and np.abs(t["offset"][:]).max() == 0.0,
                  "adjust: each moved 0.03 mm up (to the clearance), strain free, no offset")
            check(abs(np.abs(u0).max() - (OVERLAP + CLEARANCE)) <= TOL, "adjust: U of frame 0 is the move")
        else:
            check(np.abs(t["offset"][:] - (OVERLAP + CLEARANCE)).max() <= TOL
                  and np.abs(t["distance"][:]).max() == 0.0,
                  "offset: permanent offsets of 0.03 mm, nothing moved")
            check(np.abs(u0).max() == 0.0, "offset: U of frame 0 is zero")
        text = msg.read_text()
        check(len(re.findall(r"contact clearance CNODE: node \d+ \(slave surface CUBE_BOTTOM, master "
                             r"surface PLATE_TOP", text)) == 4, f"{mode}: the .msg lists the four nodes")
        h = f["history/step_1"]
        time, cfn = h["time"][:], h["contact/CUBE_BOTTOM-PLATE_TOP/CFN"][:]
        touching = np.nonzero(np.abs(cfn) > 0.0)[0]
        onset = time[touching[0]] if touching.size else float("nan")
        closing = CLEARANCE / SPEED
        check(touching.size > 0 and closing <= onset <= closing + 3 * (time[1] - time[0]),
              f"{mode}: the force starts once the cube has closed by the clearance "
              f"({onset:.3e} s, closing time {closing:.1e} s)")
        check(np.abs(cfn).max() > 1.0, f"{mode}: the cube hits the plate (peak CFN {np.abs(cfn).max():.3f} N)")
        ref, _ = result(out, "elem", mode)
        compare = subprocess.run([xpl, "compare", str(ref), str(h5)], capture_output=True, text=True)
        if compare.returncode != 0:
            print("\n".join(line for line in compare.stdout.splitlines() if not line.startswith("pass")))
        check(compare.returncode == 0,
              f"{mode}: xpl compare: the element-based and the node-based runs are bitwise the same")


if __name__ == "__main__":
    main()
