#!/usr/bin/python3
"""C3D8 with C3D8R and S4R in one mesh, *FIXED MASS SCALING and a CalculiX-style *DYNAMIC line
(issue 18, items 2-4).

Usage: check_c3d8.py XPL OUT_DIR

Writes its own deck: a plastic C3D8 block (4 x 4 x 2) on an elastic C3D8R block (4 x 4 x 2)
sharing the nodes of their interface, an S4R plate on the top face of the C3D8 block, the
bottom fixed, everything else moving down at up to 20 m/s; `*DYNAMIC, EXPLICIT` with CalculiX's
initial increment and a maximum increment; `*FIXED MASS SCALING, FACTOR=2, ELSET=TOP` on the
C3D8 block. Checks:
- `xpl run` at 1 and 2 threads completes, with identical results bit for bit;
- S, MISES and PEEQ are written for every element, PEEQ > 0 in some C3D8 elements only;
- /mesh/C3D8, /mesh/C3D8R and /mesh/S4R exist;
- the .msg reports the mass scaling (added mass = ρV of the C3D8 block, by hand) and the
  ignored initial increment; the .sta file has the scaling summary;
- no increment exceeds the maximum increment; ETOTAL drifts by less than 1 % of ALLWK + ALLKE(0);
- a deck with C3D8I exits 1 with the refusal at its line.
"""

import json
import pathlib
import shutil
import subprocess
import sys

import h5py
import numpy as np

H = 1e-3  # element size, m
RHO = 7850.0
MAX_INCREMENT = 1.2e-7  # s, below the stable increment of the C3D8R block (~1.6e-7 s)


def check(condition, message):
    if not condition:
        sys.exit(f"check_c3d8.py: FAILED: {message}")


def xpl(binary, *args):
    result = subprocess.run([binary, *args], capture_output=True, text=True, timeout=120)
    return result.returncode, result.stdout + result.stderr


def node_id(i, j, k):
    return 1 + i + 5 * (j + 5 * k)


def deck_text(element_type_top="C3D8"):
    lines = ["*HEADING", "C3D8 on C3D8R with an S4R plate (tests/apps/check_c3d8.py)", "*NODE"]
    for k in range(5):
        for j in range(5):
            for i in range(5):
                lines.append(f"{node_id(i, j, k)}, {i * H:.6g}, {j * H:.6g}, {k * H:.6g}")
    eid = 1
    for name, etype, layers in (("BOTTOM", "C3D8R", (0, 1)), ("TOP", element_type_top, (2, 3))):
        lines.append(f"*ELEMENT, TYPE={etype}, ELSET={name}")
        for k in layers:
            for j in range(4):
                for i in range(4):
                    c = [node_id(i, j, k), node_id(i + 1, j, k), node_id(i + 1, j + 1, k),
                         node_id(i, j + 1, k), node_id(i, j, k + 1), node_id(i + 1, j, k + 1),
                         node_id(i + 1, j + 1, k + 1), node_id(i, j + 1, k + 1)]
                    lines.append(f"{eid}, " + ", ".join(map(str, c)))
                    eid += 1
    lines.append("*ELEMENT, TYPE=S4R, ELSET=PLATE")
    for j in range(4):
        for i in range(4):
            c = [node_id(i, j, 4), node_id(i + 1, j, 4), node_id(i + 1, j + 1, 4),
                 node_id(i, j + 1, 4)]
            lines.append(f"{eid}, " + ", ".join(map(str, c)))
            eid += 1
    lines += ["*NSET, NSET=BASE, GENERATE", "1, 25, 1",
              "*NSET, NSET=MOVING, GENERATE", "26, 125, 1",
              "*MATERIAL, NAME=STEEL", "*DENSITY", f"{RHO:g}", "*ELASTIC", "2e11, 0.3",
              "*MATERIAL, NAME=SOFT", "*DENSITY", f"{RHO:g}", "*ELASTIC", "2e11, 0.3",
              "*PLASTIC", "2e8, 0.", "4e8, 0.2",
              "*SOLID SECTION, ELSET=BOTTOM, MATERIAL=STEEL",
              "*SOLID SECTION, ELSET=TOP, MATERIAL=SOFT",
              "*SHELL SECTION, ELSET=PLATE, MATERIAL=STEEL", "0.0002",
              "*INITIAL CONDITIONS, TYPE=VELOCITY"]
    # Down at up to 20 m/s, in proportion to the height (a sudden uniform start against the fixed
    # base makes an energy error of 1.4 % in the first increments, C3D8R alike).
    for k in range(1, 5):
        for j in range(5):
            for i in range(5):
                lines.append(f"{node_id(i, j, k)}, 3, {-20.0 * k / 4:g}")
    lines += [
              "*BOUNDARY", "BASE, 1, 3",
              "*STEP", "*DYNAMIC, EXPLICIT", f"1e-8, 3e-6, , {MAX_INCREMENT:g}",
              "*FIXED MASS SCALING, FACTOR=2, ELSET=TOP",
              "*OUTPUT, FIELD, NUMBER INTERVAL=4", "*NODE OUTPUT", "U, V",
              "*ELEMENT OUTPUT", "S, MISES, PEEQ",
              "*OUTPUT, HISTORY, TIME INTERVAL=1e-7", "*ENERGY OUTPUT",
              "*END STEP"]
    return "\n".join(lines) + "\n"


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    binary, out = sys.argv[1], pathlib.Path(sys.argv[2])
    shutil.rmtree(out, ignore_errors=True)
    out.mkdir(parents=True)
    deck = out / "mixed.inp"
    deck.write_text(deck_text())
    results = []
    for threads in (1, 2):
        run_dir = out / f"t{threads}"
        code, text = xpl(binary, "run", str(deck), "-o", str(run_dir), "--threads", str(threads))
        check(code == 0, f"xpl run with {threads} thread(s) exited {code}:\n{text}")
        results.append(run_dir / "mixed.h5")

    with h5py.File(results[0], "r") as a, h5py.File(results[1], "r") as b:
        check(a.attrs["status"] == "completed", f"status {a.attrs['status']!r}")
        for group in ("/mesh/C3D8", "/mesh/C3D8R", "/mesh/S4R"):
            check(group in a, f"{group} missing")
        frames = sorted(a["frames"])
        check(frames == sorted(b["frames"]), "frames differ between 1 and 2 threads")
        for name in frames:
            for field in a["frames"][name]:
                check(np.array_equal(a["frames"][name][field][()], b["frames"][name][field][()],
                                     equal_nan=True),
                      f"frame {name} {field} differs between 1 and 2 threads")
        last = a["frames"][frames[-1]]
        for field in ("S", "MISES", "PEEQ"):
            check(field in last, f"the last frame has no {field}")
        peeq = last["PEEQ"][()]
        rows = a["/mesh/C3D8/element_rows"][()]
        c3d8 = np.zeros(peeq.shape[0], dtype=bool)
        c3d8[rows] = True
        check(np.all(np.isfinite(last["MISES"][()])), "MISES not finite")
        check(peeq[c3d8].max() > 0.0, "no plastic strain in the C3D8 block")
        check(np.all(peeq[~c3d8] == 0.0), "plastic strain outside the C3D8 block")
        energy = a["history/step_1/energy"]
        etotal, ke, wk = energy["ETOTAL"][()], energy["ALLKE"][()], energy["ALLWK"][()]
        scale = ke[0] + np.abs(wk).max()
        check(np.abs(etotal - etotal[0]).max() < 0.01 * scale,
              f"ETOTAL drifts by {np.abs(etotal - etotal[0]).max() / scale:.2%}")
        for key in ("ETOTAL", "ALLKE", "ALLSE", "ALLPD"):
            check(np.array_equal(energy[key][()], b["history/step_1/energy"][key][()]),
                  f"history {key} differs between 1 and 2 threads")

    msg = (out / "t1" / "mixed.msg").read_text()
    added = 2.0 * RHO * (4 * H) * (4 * H) * (2 * H) - RHO * (4 * H) * (4 * H) * (2 * H)
    check("*FIXED MASS SCALING (ELSET=TOP): 32 of 32 elements scaled" in msg,
          "the .msg has no mass-scaling line for ELSET=TOP")
    check(f"mass added {added:.4g} kg" in msg, f"added mass {added:.4g} kg not in the .msg")
    check("initial time increment 1e-08 ignored" in msg, "no note on the initial increment")
    check("C3D8 elements: 32" in msg, "no C3D8 block line in the .msg")
    sta = (out / "t1" / "mixed.sta").read_text()
    check("fixed mass scaling: +" in sta, "no mass-scaling summary in the .sta")
    # 3e-6 s at the maximum increment: no increment is longer.
    increments = json.loads((out / "t1" / "mixed.summary.json").read_text())["increments"]
    check(increments >= int(np.ceil(3e-6 / MAX_INCREMENT - 1e-9)),
          f"{increments} increments: some longer than the maximum increment")

    bad = out / "bad.inp"
    bad.write_text(deck_text("C3D8I"))
    code, text = xpl(binary, "check", str(bad), "-o", str(out / "bad"))
    line = deck_text("C3D8I").splitlines().index("*ELEMENT, TYPE=C3D8I, ELSET=TOP") + 1
    check(code == 1, f"C3D8I deck exited {code}")
    check(f"bad.inp:{line}: *ELEMENT: element type C3D8I (incompatible modes) is not supported"
          in text, f"no C3D8I refusal at line {line}:\n{text}")
    print("check_c3d8.py: OK")


if __name__ == "__main__":
    main()
