#!/usr/bin/python3
"""--import restores the hourglass state (issue 14): a run stopped half-way and continued with
--import of its last frame ends where the uninterrupted run ends.

Usage: check_hourglass_import.py XPL OUT_DIR

The deck (written here) holds four coarse, elastic, vibrating bodies whose hourglass state
carries a large part of their stiffness: two C3D8R cantilevers one element thick (8 x 1 x 1),
one with the enhanced form (the default since issue 32: its frame stresses) and one with
HOURGLASS=STIFFNESS (its resultants), and two clamped S4R plates (4 x 4), one with the
physical hourglass form (the default) and one with HOURGLASS=STIFFNESS. They start from a
bending velocity field and run 1 ms; the same deck is also run to 0.5 ms and continued for
0.5 ms with --import.

- The result file holds HGSTATE (n_elements x 12) with S in every frame; frame 0 of the
  continued run holds the HGSTATE and STH of the first run's last frame, unchanged.
- The continued run's final displacements are within 0.1 % of the uninterrupted run's largest
  displacement (not bitwise: the continued run restarts its central differences from the
  frame velocity V(t) instead of V(t - dt/2), a difference of order dt; 0.0017 % measured).
- The same import without HGSTATE (the dataset deleted from a copy of the file) misses by at
  least 10 times as much (60 % measured: the hourglass state carries 70 % of ALLIE here),
  so the test fails if the state is not restored.
"""

import pathlib
import shutil
import subprocess
import sys

import h5py
import numpy as np

PERIOD = 1.0e-3


def check(condition, message):
    if not condition:
        sys.exit(f"check_hourglass_import.py: FAILED: {message}")


def run(xpl, deck, out, *extra):
    result = subprocess.run([xpl, "run", str(deck), "-o", str(out), "--quiet", *extra],
                            capture_output=True, text=True, timeout=300)
    check(result.returncode == 0,
          f"xpl run {deck.name} {' '.join(extra)} exited {result.returncode}:\n"
          f"{result.stdout}{result.stderr}")
    return out / (deck.stem + ".h5")


def deck_text(period):
    lines = ["*HEADING", "Hourglass state across --import: two C3D8R beams and two S4R plates",
             "*NODE"]
    # C3D8R cantilevers 0.1 x 0.01 x 0.01 m, 8 x 1 x 1: node 1 + i + 9 (j + 2 k) (+ 100 for the
    # second, 0.05 m aside).
    beams = (0, 100)
    beam = lambda i, j, k, b=0: 1 + b + i + 9 * (j + 2 * k)  # noqa: E731
    for b in beams:
        for k in range(2):
            for j in range(2):
                for i in range(9):
                    lines.append(f"{beam(i, j, k, b)}, {0.0125 * i:.6g}, "
                                 f"{0.01 * j + 0.0005 * b:.6g}, {0.01 * k:.6g}")
    # Two S4R plates 0.1 x 0.1 m, 4 x 4, at z = 0.05 and z = 0.1: node base + i + 5 j.
    plate = lambda base, i, j: base + i + 5 * j  # noqa: E731
    for base, z in ((1000, 0.05), (2000, 0.1)):
        for j in range(5):
            for i in range(5):
                lines.append(f"{plate(base, i, j)}, {0.025 * i:.6g}, {0.025 * j:.6g}, {z:g}")
    for b, name in zip(beams, ("BEAM", "BEAM_STIFF")):
        lines.append(f"*ELEMENT, TYPE=C3D8R, ELSET={name}")
        for i in range(8):
            lines.append(f"{i + 1 + (8 if b else 0)}, {beam(i, 0, 0, b)}, "
                         f"{beam(i + 1, 0, 0, b)}, {beam(i + 1, 1, 0, b)}, {beam(i, 1, 0, b)}, "
                         f"{beam(i, 0, 1, b)}, {beam(i + 1, 0, 1, b)}, {beam(i + 1, 1, 1, b)}, "
                         f"{beam(i, 1, 1, b)}")
    for base, name in ((1000, "PHYSICAL"), (2000, "STIFF")):
        lines.append(f"*ELEMENT, TYPE=S4R, ELSET={name}")
        for j in range(4):
            for i in range(4):
                lines.append(f"{base + i + 4 * j}, {plate(base, i, j)}, {plate(base, i + 1, j)}, "
                             f"{plate(base, i + 1, j + 1)}, {plate(base, i, j + 1)}")
    lines.append("*NSET, NSET=ROOT")
    lines += [str(beam(0, j, k, b)) for b in beams for k in range(2) for j in range(2)]
    lines += [str(plate(base, 0, j)) for base in (1000, 2000) for j in range(5)]
    lines += ["*MATERIAL, NAME=STEEL", "*DENSITY", "7850", "*ELASTIC", "2.1e11, 0.3",
              "*SOLID SECTION, ELSET=BEAM, MATERIAL=STEEL",
              "*SHELL SECTION, ELSET=PHYSICAL, MATERIAL=STEEL", "0.002, 5",
              "*SECTION CONTROLS, NAME=OLD, HOURGLASS=STIFFNESS",
              "*SOLID SECTION, ELSET=BEAM_STIFF, MATERIAL=STEEL, CONTROLS=OLD",
              "*SHELL SECTION, ELSET=STIFF, MATERIAL=STEEL, CONTROLS=OLD", "0.002, 5",
              "*INITIAL CONDITIONS, TYPE=VELOCITY"]
    for b in beams:
        for k in range(2):
            for j in range(2):
                for i in range(1, 9):
                    x = 0.0125 * i
                    lines.append(f"{beam(i, j, k, b)}, 3, {5.0 * (x / 0.1) ** 2:.9g}")
    for base in (1000, 2000):
        for j in range(5):
            for i in range(1, 5):
                x, y = 0.025 * i, 0.025 * j
                lines.append(f"{plate(base, i, j)}, 3, {2.0 * (x / 0.1) ** 2 * (1 + y / 0.1):.9g}")
    lines += ["*BOUNDARY", "ROOT, ENCASTRE", "*STEP", "*DYNAMIC, EXPLICIT", f", {period:g}",
              "*OUTPUT, FIELD, NUMBER INTERVAL=2", "*NODE OUTPUT", "U, V",
              "*ELEMENT OUTPUT", "S, STH", "*OUTPUT, HISTORY, TIME INTERVAL=1e-05",
              "*ENERGY OUTPUT", "ALLAE, ALLIE", "*END STEP"]
    return "\n".join(lines) + "\n"


def last_frame(path):
    with h5py.File(path, "r") as f:
        name = sorted(f["frames"])[-1]
        frame = f["frames"][name]
        return {k: frame[k][()] for k in frame}


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    xpl = sys.argv[1]
    out = pathlib.Path(sys.argv[2])
    shutil.rmtree(out, ignore_errors=True)
    out.mkdir(parents=True)

    whole = out / "whole.inp"
    whole.write_text(deck_text(PERIOD))
    whole_h5 = run(xpl, whole, out / "whole")
    first = out / "first.inp"
    first.write_text(deck_text(PERIOD / 2))
    first_h5 = run(xpl, first, out / "first")
    end_first = last_frame(first_h5)
    check("HGSTATE" in end_first, "the last frame has no HGSTATE")
    check(end_first["HGSTATE"].shape == (16 + 32, 12),
          f"HGSTATE shape {end_first['HGSTATE'].shape}")
    with h5py.File(first_h5, "r") as f:
        history = f["history/step_1/energy"]
        allae, allie = history["ALLAE"][-1], history["ALLIE"][-1]
    print(f"check_hourglass_import.py: at {PERIOD / 2:g} s ALLAE {allae:.4g} J of ALLIE {allie:.4g} J")
    check(np.abs(end_first["HGSTATE"]).max() > 0.0, "the hourglass state is all zero")

    second = out / "second.inp"
    second.write_text(deck_text(PERIOD / 2))
    second_h5 = run(xpl, second, out / "second", "--import", str(first_h5))
    with h5py.File(second_h5, "r") as f:
        frame0 = f["frames"][sorted(f["frames"])[0]]
        for name in ("HGSTATE", "STH"):
            check(np.array_equal(frame0[name][()], end_first[name], equal_nan=True),
                  f"frame 0 of the continued run does not hold the imported {name}")

    stripped_h5 = out / "stripped.h5"
    shutil.copy(first_h5, stripped_h5)
    with h5py.File(stripped_h5, "r+") as f:
        frames = f["frames"]
        for name in frames:
            if "HGSTATE" in frames[name]:
                del frames[name]["HGSTATE"]
    third = out / "third.inp"
    third.write_text(deck_text(PERIOD / 2))
    third_h5 = run(xpl, third, out / "third", "--import", str(stripped_h5))

    reference = last_frame(whole_h5)["U"]
    scale = np.abs(reference).max()
    error = np.abs(last_frame(second_h5)["U"] - reference).max() / scale
    without = np.abs(last_frame(third_h5)["U"] - reference).max() / scale
    print(f"check_hourglass_import.py: continued run's final U off by {error:.3g} of the largest "
          f"U ({scale:.4g} m); without HGSTATE {without:.3g}")
    check(error < 1e-3, f"continued run off by {error:.3g} of the largest displacement")
    check(without > 10.0 * error,
          f"without the hourglass state the continued run is off by {without:.3g} only "
          f"(with it {error:.3g}): the test does not show the state")


if __name__ == "__main__":
    main()
