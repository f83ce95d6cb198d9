#!/usr/bin/python3
"""A velocity BC that jumps: its work is counted as an impulsive input (issue 20, item 3).

Usage: check_bc_jump.py XPL WORK_DIR

Writes two decks into WORK_DIR (emptied first): a steel block of 4 x 4 x 2 mm, 1 mm C3D8R
cubes (32 elements, mass 2.512e-4 kg), at rest, given 1 m/s by `*BOUNDARY, TYPE=VELOCITY` at
t = 0 (step PUSH, default STEP amplitude: the velocity jumps) and reversed to -1 m/s in a
second step (PULL).

- `rigid`: every node prescribed in x. The block translates as a rigid body: no strain, the
  work of the two impulses is exactly the kinetic energy ½mv² = 1.256e-4 J, so ETOTAL must
  stay at 0 to round-off: |drift| < 1e-9 of ALLKE.
- `face`: only the face z = 0 prescribed, in z. The block deforms: the jump rings the highest
  modes of this two-layer mesh (ω Δt close to 2). Measured with the whole-step velocity, their
  kinetic energy was off by about (ω Δt)² / 4 (ETOTAL some 20 % off ALLKE, beyond the default
  --energy-limit); ALLKE = ½ v(n-½)·M·v(n+½) is what the scheme conserves, and what is left is
  the increment following the element shapes (0.8 % measured): |drift| < 3 % of ALLKE, under
  the default energy limit.
- `face_fine`: the same at a fixed increment of PERIOD / 128, about 1/9 of the stable one:
  |drift| < 1e-5 of ALLKE (1.7e-7 measured; 1.65e-6 J, 0.4 %, with the whole-step velocity).
  Counted by the trapezoidal reaction rule, the start alone was off by ½mΔv² of the face
  nodes, 3.14e-5 J = 7 % of ALLKE, whatever the increment.
Both runs must complete (exit code 0, status "completed"), and JOB.msg must name the jump of
each step: "prescribed velocity jump at t = ..." with the energy it put in.
"""

import pathlib
import re
import shutil
import subprocess
import sys

import h5py
import numpy as np

NX, NY, NZ = 4, 4, 2
H = 1e-3  # element edge, m
DENSITY = 7850.0
SPEED = 1.0
PERIOD = 2e-6  # per step, s: about 5 wave transits of the 2 mm height
MASS = NX * NY * NZ * H**3 * DENSITY


def check(condition, message):
    if not condition:
        sys.exit(f"check_bc_jump.py: FAILED: {message}")


def node_id(ix, iy, iz):
    return 1 + ix + (NX + 1) * (iy + (NY + 1) * iz)


def deck(case, increment=None):
    out = [f"** check_bc_jump.py: block {NX} x {NY} x {NZ} mm, velocity BC jump, case {case}"]
    out.append("*NODE")
    for iz in range(NZ + 1):
        for iy in range(NY + 1):
            for ix in range(NX + 1):
                out.append(f"{node_id(ix, iy, iz)}, {ix * H:.6g}, {iy * H:.6g}, {iz * H:.6g}")
    out.append("*ELEMENT, TYPE=C3D8R, ELSET=BLOCK")
    element = 1
    for ez in range(NZ):
        for ey in range(NY):
            for ex in range(NX):
                n = [node_id(ex, ey, ez), node_id(ex + 1, ey, ez), node_id(ex + 1, ey + 1, ez),
                     node_id(ex, ey + 1, ez)]
                n += [k + (NX + 1) * (NY + 1) for k in n]
                out.append(f"{element}, " + ", ".join(map(str, n)))
                element += 1
    if case == "rigid":
        driven = [node_id(ix, iy, iz) for iz in range(NZ + 1) for iy in range(NY + 1)
                  for ix in range(NX + 1)]
        dof = 1
    else:
        driven = [node_id(ix, iy, 0) for iy in range(NY + 1) for ix in range(NX + 1)]
        dof = 3
    out.append("*NSET, NSET=DRIVEN")
    out.extend(", ".join(map(str, driven[k:k + 8])) for k in range(0, len(driven), 8))
    out += ["*MATERIAL, NAME=STEEL", "*DENSITY", f"{DENSITY:g}", "*ELASTIC", "2.1e11, 0.3",
            "*SOLID SECTION, ELSET=BLOCK, MATERIAL=STEEL"]
    for name, speed in (("PUSH", SPEED), ("PULL", -SPEED)):
        dynamic = ["*DYNAMIC, EXPLICIT", f", {PERIOD:g}"]
        if increment:
            dynamic = ["*DYNAMIC, EXPLICIT, DIRECT USER CONTROL", f"{increment:g}, {PERIOD:g}"]
        out += [f"*STEP, NAME={name}", *dynamic,
                "*BOUNDARY, TYPE=VELOCITY", f"DRIVEN, {dof}, {dof}, {speed:g}",
                f"*OUTPUT, HISTORY, TIME INTERVAL={PERIOD / 40:g}", "*ENERGY OUTPUT",
                "*END STEP"]
    return "\n".join(out) + "\n"


def run(xpl, work, case, tolerance, increment=None):
    job = f"bc_jump_{case}"
    path = work / f"{job}.inp"
    path.write_text(deck(case.removesuffix("_fine"), increment))
    out = work / case
    result = subprocess.run([xpl, "run", str(path), "-o", str(out), "--threads", "1"],
                            capture_output=True, text=True, timeout=120)
    check(result.returncode == 0, f"{case}: exit code {result.returncode}, expected 0\n"
                                  f"stdout:\n{result.stdout}\nstderr:\n{result.stderr}")
    with h5py.File(out / f"{job}.h5", "r") as f:
        check(f.attrs["status"] == "completed", f"{case}: status {f.attrs['status']!r}")
        kinetic, total = [], []
        for step in ("step_1", "step_2"):
            energy = f[f"history/{step}/energy"]
            kinetic.append(energy["ALLKE"][()])
            total.append(energy["ETOTAL"][()])
        kinetic, total = np.concatenate(kinetic), np.concatenate(total)
    scale = kinetic.max()
    check(scale > 0.1 * MASS * SPEED**2, f"{case}: largest ALLKE {scale:.4g} J is too small")
    drift = np.abs(total - total[0]).max()
    check(drift <= tolerance * scale,
          f"{case}: ETOTAL drifts by {drift:.4g} J, more than {tolerance:g} of ALLKE "
          f"{scale:.4g} J")
    msg = (out / f"{job}.msg").read_text()
    jumps = re.findall(r"step (\w+): a prescribed velocity jump at t = (\S+) s .*?put "
                       r"(\S+) J into the model", msg)
    check([j[0] for j in jumps] == ["PUSH", "PULL"],
          f"{case}: .msg names the jumps {jumps}, expected one in PUSH and one in PULL")
    # Of a start from rest the energy is the kinetic energy of the driven nodes (½mv²);
    # of the reversal, nothing (the velocity changes sign, not size).
    push_energy, pull_energy = float(jumps[0][2]), float(jumps[1][2])
    check(push_energy > 0.0, f"{case}: the start put {push_energy} J")
    check(abs(pull_energy) < 1e-3 * push_energy, f"{case}: the reversal put {pull_energy} J")
    if case == "rigid":
        check(abs(push_energy - 0.5 * MASS * SPEED**2) < 1e-3 * push_energy,
              f"{case}: the start put {push_energy} J, expected ½mv² = {0.5 * MASS:.4g} J")
    print(f"check_bc_jump.py: {case}: completed, |ETOTAL drift| {drift:.3g} J "
          f"({drift / scale:.2g} of ALLKE {scale:.4g} J), jumps {jumps}")


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    xpl, work = sys.argv[1], pathlib.Path(sys.argv[2])
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir(parents=True)
    run(xpl, work, "rigid", 1e-9)
    run(xpl, work, "face", 3e-2)
    run(xpl, work, "face_fine", 1e-5, PERIOD / 128)


if __name__ == "__main__":
    main()
