#!/usr/bin/python3
"""Elements that turn inside out stop the run, naming the element (issue 33, item 6).

Usage: check_inverted_element.py XPL WORK_DIR

Writes its decks into WORK_DIR (emptied first) and runs them:

- `hex_corner`: one C3D8R steel cube of 10 mm, every node held but node 7 (the corner at
  (10, 10, 10) mm), driven at -100 m/s in x, y and z towards node 1. It crosses the plane of
  its three neighbours at 33.3 us (at (6.67, 6.67, 6.67) mm) and its corner is turned over by
  30 deg, the limit HEX_FOLD_LIMIT, at 43.0 us (5.70 mm); the volume stays positive until
  133 us. At 100 us the node reaches node 1 (a quarter of the volume left): that run used to
  complete (stresses up to 2.4e11 Pa). It must stop with exit code 3 before 45 us, status "failed", naming
  element 71.
- `shell_corner`: one S4R steel square of 10 mm, nodes 1, 2 and 4 clamped, node 3 driven in
  the plane at -100 m/s in x and y towards node 1: it crosses the diagonal of nodes 2 and 4
  at 50 us and its corner passes 210 deg (SHELL_FOLD_LIMIT) at 63.4 us; the 80 us run used to
  complete, folded. It must stop before 70 us, naming element 72.
- The same two decks over 30 us (before the corner turns over) must complete: the check does
  not stop a sound element.
"""

import pathlib
import re
import shutil
import subprocess
import sys

import h5py

HEX = """*HEADING
one C3D8R, corner node 7 driven through the element
*NODE
1, 0, 0, 0
2, 0.01, 0, 0
3, 0.01, 0.01, 0
4, 0, 0.01, 0
5, 0, 0, 0.01
6, 0.01, 0, 0.01
7, 0.01, 0.01, 0.01
8, 0, 0.01, 0.01
*ELEMENT, TYPE=C3D8R, ELSET=BLOCK
71, 1, 2, 3, 4, 5, 6, 7, 8
*NSET, NSET=HELD
1, 2, 3, 4, 5, 6, 8
*MATERIAL, NAME=STEEL
*DENSITY
7850.
*ELASTIC
2.1e11, 0.3
*SOLID SECTION, ELSET=BLOCK, MATERIAL=STEEL
*STEP
*DYNAMIC, EXPLICIT
, {period}
*BOUNDARY
HELD, 1, 3
*BOUNDARY, TYPE=VELOCITY
7, 1, 3, -100.
*END STEP
"""

SHELL = """*HEADING
one S4R, corner node 3 driven across the diagonal of nodes 2 and 4
*NODE
1, 0, 0, 0
2, 0.01, 0, 0
3, 0.01, 0.01, 0
4, 0, 0.01, 0
*ELEMENT, TYPE=S4R, ELSET=PLATE
72, 1, 2, 3, 4
*NSET, NSET=HELD
1, 2, 4
*MATERIAL, NAME=STEEL
*DENSITY
7850.
*ELASTIC
2.1e11, 0.3
*SHELL SECTION, ELSET=PLATE, MATERIAL=STEEL
0.001
*STEP
*DYNAMIC, EXPLICIT
, {period}
*BOUNDARY
HELD, 1, 6
3, 3, 6
*BOUNDARY, TYPE=VELOCITY
3, 1, 2, -100.
*END STEP
"""


def check(condition, message):
    if not condition:
        sys.exit(f"check_inverted_element.py: FAILED: {message}")


def run(xpl, work, name, text):
    deck = work / f"{name}.inp"
    deck.write_text(text)
    out = work / name
    result = subprocess.run([xpl, "run", str(deck), "-o", str(out)], capture_output=True,
                            text=True, timeout=120)
    return result, out / f"{name}.h5", out / f"{name}.sta"


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    xpl, work = sys.argv[1], pathlib.Path(sys.argv[2])
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir(parents=True)
    for name, deck, element, before in (("hex_corner", HEX, 71, 45e-6),
                                        ("shell_corner", SHELL, 72, 70e-6)):
        period = "1e-4" if name == "hex_corner" else "8e-5"
        result, h5, sta = run(xpl, work, name, deck.format(period=period))
        check(result.returncode == 3, f"{name}: exit code {result.returncode}, expected 3\n"
                                      f"stderr:\n{result.stderr}")
        expected = (f"element {element}: non-positive or undefined volume, area or corner "
                    "Jacobian")
        check(expected in result.stderr, f"{name}: stderr lacks {expected!r}:\n{result.stderr}")
        with h5py.File(h5, "r") as f:
            check(f.attrs["status"] == "failed", f"{name}: status {f.attrs['status']!r}")
            check(f"element {element}" in f.attrs["error"], f"{name}: error {f.attrs['error']!r}")
        sta_text = sta.read_text()
        check("THE ANALYSIS HAS NOT BEEN COMPLETED" in sta_text, f"{name}: .sta claims success")
        when = re.search(r"at increment \d+", result.stderr)
        check(when is not None, f"{name}: no increment in {result.stderr!r}")
        with h5py.File(h5, "r") as f:
            time = max(float(f[f"history/{s}/time"][-1]) for s in f["history"])
        check(time < before, f"{name}: stopped at t = {time:g} s, expected before {before:g} s")
        print(f"check_inverted_element.py: {name}: stopped at t = {time:.3g} s: "
              f"{result.stderr.strip().splitlines()[-2]}")

        sound = f"{name}_30us"
        result, h5, _ = run(xpl, work, sound, deck.format(period="3e-5"))
        check(result.returncode == 0, f"{sound}: exit code {result.returncode}\n{result.stderr}")
        with h5py.File(h5, "r") as f:
            check(f.attrs["status"] == "completed", f"{sound}: status {f.attrs['status']!r}")
    print("check_inverted_element.py: passed")


if __name__ == "__main__":
    main()
