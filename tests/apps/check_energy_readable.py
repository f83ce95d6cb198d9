#!/usr/bin/python3
"""Energies a user can read (issue 32, item 6; SPEC R5): ALLKE is never negative.

Usage: check_energy_readable.py XPL REPO WORK_DIR

1. A rigid rod (4 C3D8R, 10 x 10 x 320 mm steel, *RIGID BODY, mass 0.2512 kg) given -40 m/s
   by *BOUNDARY, TYPE=VELOCITY from t = 0, beside a free deformable block that sets the
   increment:
   - "axial": reference node at the centre of mass, V3 = -40, all else fixed: ALLKE and ALLWK
     are ½mv² = 200.96 J after the jump, ALLKE(0) = 0 (it showed -201 J, and ALLWK 402 J,
     while the body's jump was booked by the trapezoidal rule);
   - "struck": reference node at the rod's end, V1 = -40, rotations free: the body turns
     about its centre as well, ALLKE = ALLWK = ½ v²·m J/(J + m c²) = 54.8 J (lumped inertia
     J = 0.0096 m about the centre, c = 0.16 m).
   Both: ALLKE >= 0 on every history row, |ETOTAL| < 1e-9 of ALLKE, one jump warning in the .msg.
2. The one-element deck of issue 15 (benchmarks/make_block.py -n 1 --direction 2, a steel cube
   fixed on one face, its energy in modes near omega dt = 2): ALLKE >= 0 on every history
   row (it reached -11 % of the largest energy while ALLKE was the product of the half-step
   velocities; ALLKD holds that part now and is negative somewhere), and ETOTAL =
   ALLKE + ALLKD + ALLIE + ALLVD - ALLWK row by row.
3. A deformable steel block (benchmarks/make_block.py -n 3, 0.1 m) whose face x = 0 is given
   -40 m/s by *BOUNDARY, TYPE=VELOCITY from t = 0 (an impulse on free DOFs), reversed to
   +40 m/s at the start of a second step: ALLKE(0) = 0, ALLKE >= 0 on every row of both
   steps, |ETOTAL - ETOTAL(0)| < 1e-3 of the largest ALLKE (3.6e-4 measured, the elastic
   waves' stepping error at 0.7 % strain; 3.9e-3 while the shifts at the short last increment
   went unbooked).
4. The S4R strip of benchmarks/strip_torsion.py (20 x 4, clamped, free vibration) for 1.03 ms
   (the step ends on a short increment), twisted from rest by a twist rate given as U3 alone
   (the rotations start at rest: energy in the rotational modes near omega dt = 2) and bent:
   |ETOTAL - ETOTAL(0)| < 1e-6 of ETOTAL(0) in both (2e-10 and 3e-13 measured; the twisted
   strip drifted 0.6 % here and 4.7 % over the benchmark's 4 ms, 60 times the bent one, while
   the shift of the conserved energy at the short last increment went unbooked).
   Then the benchmark's own runs (issue 32 item 6: "the torsion strip drifts no more than the
   bending strips"): torsion over 4 ms from the twist rate with the rotations (dof 4) and
   without them, bending over 4 ms and over the benchmark's 60 ms. Each torsion drift is at
   most the bending strips' level: the largest bending drift, or 1e-8 of ETOTAL(0) where that
   is lower (the bending drift is round-off, 1e-12 to 7e-10, and the floor keeps the check
   from comparing two round-offs; measured 2026-12-06: torsion 4.5e-11 with rotations, 2.2e-9
   without, bending 9.8e-13 over 4 ms and 6.6e-10 over 60 ms; the issue's 2.2 % against
   0.2 % was before ALLKD booked the shift of the conserved energy at a change of increment).
"""

import pathlib
import re
import subprocess
import sys

import h5py
import numpy as np

MASS = 7850.0 * 0.01 * 0.01 * 0.32  # kg, the rod


def rod_deck(ref_z, fixed, driven):
    """The rigid rod deck; reference node at z = ref_z, BC lines `fixed` (DOF ranges held at
    zero) and the driven DOF (-40 m/s)."""
    out = ["*HEADING", "rigid rod driven at -40 m/s from t = 0", "*NODE"]
    nid = 1
    for k in range(5):
        for j in range(2):
            for i in range(2):
                out.append(f"{nid}, {0.01 * i}, {0.01 * j}, {0.1 + 0.08 * k}")
                nid += 1

    def n(i, j, k):
        return 1 + i + 2 * j + 4 * k

    out.append("*ELEMENT, TYPE=C3D8R, ELSET=ROD")
    for k in range(4):
        out.append(f"{k + 1}, {n(0, 0, k)}, {n(1, 0, k)}, {n(1, 1, k)}, {n(0, 1, k)}, "
                   f"{n(0, 0, k + 1)}, {n(1, 0, k + 1)}, {n(1, 1, k + 1)}, {n(0, 1, k + 1)}")
    out.append("*NODE")
    for k in range(3):
        for j in range(3):
            for i in range(3):
                out.append(f"{100 + i + 3 * j + 9 * k}, {0.005 * i}, {0.005 * j}, "
                           f"{0.005 * k - 0.05}")

    def m(i, j, k):
        return 100 + i + 3 * j + 9 * k

    out.append("*ELEMENT, TYPE=C3D8R, ELSET=BLOCK")
    e = 100
    for k in range(2):
        for j in range(2):
            for i in range(2):
                out.append(f"{e}, {m(i, j, k)}, {m(i + 1, j, k)}, {m(i + 1, j + 1, k)}, "
                           f"{m(i, j + 1, k)}, {m(i, j, k + 1)}, {m(i + 1, j, k + 1)}, "
                           f"{m(i + 1, j + 1, k + 1)}, {m(i, j + 1, k + 1)}")
                e += 1
    out += ["*NODE", f"999, 0.005, 0.005, {ref_z}", "*NSET, NSET=REF", "999",
            "*RIGID BODY, REF NODE=999, ELSET=ROD",
            "*MATERIAL, NAME=STEEL", "*DENSITY", "7850.", "*ELASTIC", "2.1e11, 0.3",
            "*SOLID SECTION, ELSET=ROD, MATERIAL=STEEL",
            "*SOLID SECTION, ELSET=BLOCK, MATERIAL=STEEL",
            "*STEP", "*DYNAMIC, EXPLICIT", ", 2e-5", "*BOUNDARY"]
    out += [f"REF, {a}, {b}" for a, b in fixed]
    out += ["*BOUNDARY, TYPE=VELOCITY", f"REF, {driven}, {driven}, -40.",
            "*OUTPUT, HISTORY, TIME INTERVAL=1e-6", "*ENERGY OUTPUT", "*END STEP"]
    return "\n".join(out) + "\n"


def run(xpl, deck, out):
    out.mkdir(parents=True, exist_ok=True)
    return subprocess.run([xpl, "run", str(deck), "-o", str(out), "--threads", "1", "--quiet"],
                          capture_output=True, text=True, timeout=120,
                          env={"OMP_WAIT_POLICY": "PASSIVE"})


def energies(h5):
    with h5py.File(h5) as f:
        return {k: np.concatenate([f["history"][s]["energy"][k][:] for s in f["history"]])
                for k in ("ALLKE", "ALLWK", "ETOTAL")}


def rigid_rod(xpl, work, failures):
    cases = {
        # name: (reference z, fixed DOF ranges, driven DOF, expected ALLKE after the jump)
        "axial": (0.26, [(1, 2), (4, 6)], 3, 0.5 * MASS * 40.0**2),
        "struck": (0.1, [(2, 3)], 1, 0.5 * MASS * 40.0**2 * 0.0096 / (0.0096 + 0.16**2)),
    }
    for name, (ref_z, fixed, driven, expected) in cases.items():
        deck = work / f"rod_{name}.inp"
        deck.write_text(rod_deck(ref_z, fixed, driven))
        r = run(xpl, deck, work / f"rod_{name}")
        if r.returncode != 0:
            failures.append(f"rod {name}: exit {r.returncode}: {r.stderr.strip()[-300:]}")
            continue
        e = energies(work / f"rod_{name}" / f"rod_{name}.h5")
        ke, wk, total = e["ALLKE"], e["ALLWK"], e["ETOTAL"]
        print(f"rod {name}: ALLKE(0) {ke[0]:.4g} J, after {ke[1]:.6g} J (expected {expected:.6g}),"
              f" ALLWK {wk[1]:.6g} J, largest |ETOTAL| {np.abs(total).max():.3g} J")
        if ke.min() < 0.0:
            failures.append(f"rod {name}: ALLKE {ke.min():.4g} J < 0")
        if abs(ke[0]) > 1e-12 * expected:
            failures.append(f"rod {name}: ALLKE(0) = {ke[0]:.4g} J, the rod is at rest then")
        # The lumped inertia of the struck rod is exact; 0.5 %: the rod turns and its end is
        # held at 40 m/s over the microsecond to the first history row.
        if abs(ke[1] - expected) > 5e-3 * expected:
            failures.append(f"rod {name}: ALLKE {ke[1]:.6g} J after the jump, expected "
                            f"{expected:.6g} J")
        if abs(wk[1] - ke[1]) > 1e-9 * expected:
            failures.append(f"rod {name}: ALLWK {wk[1]:.6g} J differs from ALLKE {ke[1]:.6g} J")
        if np.abs(total).max() > 1e-9 * expected:
            failures.append(f"rod {name}: ETOTAL drifts by {np.abs(total).max():.3g} J")
        msg = (work / f"rod_{name}" / f"rod_{name}.msg").read_text()
        if len(re.findall(r"prescribed velocity jump at t = 0 s on 1 DOF", msg)) != 1:
            failures.append(f"rod {name}: no single jump warning in the .msg")


def one_element(xpl, repo, work, failures):
    deck = work / "one_element.inp"
    subprocess.run([sys.executable, str(repo / "benchmarks/make_block.py"), "-n", "1",
                    "--direction", "2", "--out", str(deck)], check=True, capture_output=True)
    deck.write_text(deck.read_text().replace(
        "*END STEP", "*OUTPUT, HISTORY, TIME INTERVAL=1e-9\n*ENERGY OUTPUT\n*END STEP"))
    r = run(xpl, deck, work / "one_element")
    if r.returncode != 0:
        failures.append(f"one element: exit {r.returncode}: {r.stderr.strip()[-300:]}")
        return
    with h5py.File(work / "one_element" / "one_element.h5") as f:
        e = {k: v[:] for k, v in f["history/step_1/energy"].items()}
    scale = max(e["ALLKE"].max(), e["ALLIE"].max())
    balance = e["ALLKE"] + e["ALLKD"] + e["ALLIE"] + e["ALLVD"] - e["ALLWK"] - e["ETOTAL"]
    print(f"one element: {len(e['ALLKE'])} rows, smallest ALLKE {e['ALLKE'].min() / scale:.3g}, "
          f"smallest ALLKD {e['ALLKD'].min() / scale:.3g} of the largest energy {scale:.4g} J")
    if e["ALLKE"].min() < 0.0:
        failures.append(f"one element: ALLKE {e['ALLKE'].min():.4g} J < 0")
    if not e["ALLKD"].min() < -0.01 * scale:
        failures.append("one element: ALLKD never below -1 % of the energy: the deck no longer "
                        "tests what it should (energy near omega dt = 2)")
    if np.abs(balance).max() > 1e-12 * scale:
        failures.append(f"one element: ETOTAL is not the sum of its terms "
                        f"({np.abs(balance).max():.3g} J off)")


def impulsive_block(xpl, repo, work, failures):
    deck = work / "impulsive_block.inp"
    subprocess.run([sys.executable, str(repo / "benchmarks/make_block.py"), "-n", "3",
                    "--velocity", "0", "--out", str(deck)], check=True, capture_output=True)
    text = deck.read_text()
    text = text[:text.index("*INITIAL CONDITIONS")]  # at rest; the steps follow

    def step(name, velocity):
        return (f"*STEP, NAME={name}\n*DYNAMIC, EXPLICIT\n, 2e-4\n"
                f"*BOUNDARY, TYPE=VELOCITY, OP=NEW\nFIXED, 1, 1, {velocity}\nFIXED, 2, 3, 0.\n"
                "*OUTPUT, HISTORY, TIME INTERVAL=1e-6\n*ENERGY OUTPUT\n*END STEP\n")

    deck.write_text(text + step("PUSH", -40.0) + step("REVERSE", 40.0))
    r = run(xpl, deck, work / "impulsive_block")
    if r.returncode != 0:
        failures.append(f"impulsive block: exit {r.returncode}: {r.stderr.strip()[-300:]}")
        return
    e = energies(work / "impulsive_block" / "impulsive_block.h5")
    ke, total = e["ALLKE"], e["ETOTAL"]
    drift = np.abs(total - total[0]).max() / ke.max()
    print(f"impulsive block: ALLKE(0) {ke[0]:.3g} J, smallest {ke.min():.4g} J, largest "
          f"{ke.max():.4g} J, largest |ETOTAL drift| {drift:.3g} of it")
    if ke.min() < 0.0 or ke[0] != 0.0:
        failures.append(f"impulsive block: ALLKE(0) = {ke[0]:.4g} J, smallest {ke.min():.4g} J")
    if drift > 1e-3:
        failures.append(f"impulsive block: ETOTAL drifts by {drift:.3g} of the largest ALLKE")


def strips(xpl, repo, work, failures):
    sys.path.insert(0, str(repo / "benchmarks"))
    import strip_torsion

    drifts = {}
    # name: (mode, step length, rotations given with the twist rate)
    runs = {"torsion": ("torsion", 1.03e-3, False), "bending": ("bending", 1.03e-3, False),
            "torsion_4ms": ("torsion", 4.0e-3, True),
            "torsion_4ms_u3": ("torsion", 4.0e-3, False),
            "bending_4ms": ("bending", 4.0e-3, False), "bending_60ms": ("bending", 0.06, False)}
    for name, (mode, period, rotations) in runs.items():
        deck = work / f"strip_{name}.inp"
        text = strip_torsion.build(20, 4, mode, period, rotations=rotations)
        deck.write_text(text.replace(
            "*END STEP", "*OUTPUT, HISTORY, TIME INTERVAL=1e-5\n*ENERGY OUTPUT\n*END STEP"))
        r = run(xpl, deck, work / f"strip_{name}")
        if r.returncode != 0:
            failures.append(f"strip {name}: exit {r.returncode}: {r.stderr.strip()[-300:]}")
            continue
        total = energies(work / f"strip_{name}" / f"strip_{name}.h5")["ETOTAL"]
        drifts[name] = np.abs(total - total[0]).max() / abs(total[0])
        print(f"strip {name}: largest |ETOTAL drift| {drifts[name]:.3g} of ETOTAL(0)")
        if drifts[name] > 1e-6:
            failures.append(f"strip {name}: ETOTAL drifts by {drifts[name]:.3g} of ETOTAL(0)")
    bending = [d for n, d in drifts.items() if n.startswith("bending")]
    if len(bending) == 3:
        level = max(max(bending), 1e-8)
        for name in ("torsion", "torsion_4ms", "torsion_4ms_u3"):
            if name in drifts and drifts[name] > level:
                failures.append(f"strip {name}: ETOTAL drifts by {drifts[name]:.3g} of ETOTAL(0), "
                                f"more than the bending strips' level {level:.3g}")


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    xpl, repo, work = sys.argv[1], pathlib.Path(sys.argv[2]), pathlib.Path(sys.argv[3])
    work.mkdir(parents=True, exist_ok=True)
    failures = []
    rigid_rod(xpl, work, failures)
    one_element(xpl, repo, work, failures)
    impulsive_block(xpl, repo, work, failures)
    strips(xpl, repo, work, failures)
    for f in failures:
        print(f"FAIL: {f}")
    if failures:
        sys.exit(1)
    print("check_energy_readable: all passed")


if __name__ == "__main__":
    main()
