#!/usr/bin/python3
"""Energy balance of the coarse impact decks (issue 20 acceptance, issue 15 item 8).

Usage: check_energy_balance.py XPL REPO WORK_DIR

1. The two-block decks of issue 20 (benchmarks/make_contact_pair.py, 1 mm steel C3D8R, general
   contact ALL EXTERIOR, all defaults, scale factor 1): a 4 x 4 x 1 mm block 1 um above
   - a 3 x 3 x 2 mm block fixed at its bottom ("two_block"),
   - a pinned 3 x 3 S4R plate ("block_on_shell"),
   - a free 3 x 3 x 2 mm block ("both_free"),
   moving down at 1 m/s. Each completes under the default --energy-limit with
   |ETOTAL - ETOTAL(0)| < 0.5 % of ALLKE(0) at every history row, and the force history and
   the rebound are those of an impact: no force before the gap closes, a peak, no force over
   the last quarter of the run; the upper block moves up again (fixed or pinned lower body)
   or the two separate (both free: the upper block slower than the lower one, mean nodal V3).
2. The one-element decks of issue 15 (benchmarks/make_block.py -n 1 --direction 1, 2, 3: a
   steel cube fixed on one face, the others moving) complete at scale factor 1 under the
   default --energy-limit with |ETOTAL drift| < 0.5 % of the largest energy (the .msg summary),
   and fail first above it: the first of SCALE FACTOR=1.05, 1.1, ... 2 that ends in an
   instability is above 1.05.
"""

import pathlib
import re
import subprocess
import sys

import h5py
import numpy as np

DRIFT_LIMIT = 0.005  # of ALLKE(0): issue 20's acceptance
# % of the largest energy. Measured 0.052 % (direction 1) and 0.0036 % (2 and 3); 0.8 % and
# 4.4 % before ALLKD booked the shift at the step's shortened last increment (a change of the
# increment changes the energy central differences conserve for a mode at ω by (ωΔt/2)² of
# its energy, docs/theory/energy.md, and this element's energy sits in modes near ωΔt = 2). What is left is
# the element's geometric nonlinearity at 10 m/s; 0.5 % leaves it a factor 10.
ONE_ELEMENT_DRIFT = 0.5
FACTORS = (1.05, 1.1, 1.15, 1.2, 1.3, 1.4, 1.5, 1.75, 2.0)  # scanned for the first failure


def run(xpl, deck, out):
    out.mkdir(parents=True, exist_ok=True)
    return subprocess.run([xpl, "run", str(deck), "-o", str(out), "--threads", "1", "--quiet"],
                          capture_output=True, text=True, env={"OMP_WAIT_POLICY": "PASSIVE"},
                          timeout=120)


def two_block_cases(xpl, gen, work, failures):
    velocity_out = ("*OUTPUT, HISTORY, TIME INTERVAL=1e-07\n*NODE OUTPUT, NSET=UPPER_NODES\nV3\n"
                    "*NODE OUTPUT, NSET=LOWER_NODES\nV3\n*END STEP\n")
    for name, extra in (("two_block", []), ("block_on_shell", ["--lower", "shell"]),
                        ("both_free", ["--free"])):
        a = gen.parser().parse_args(["--out", "unused.inp", *extra])
        a.uh = a.h
        deck = work / f"{name}.inp"
        deck.write_text(gen.build(a).replace("*END STEP\n", velocity_out))
        r = run(xpl, deck, work / name)
        if r.returncode != 0:
            failures.append(f"{name}: exit code {r.returncode}: {r.stderr.strip()[-300:]}")
            continue
        with h5py.File(work / name / f"{name}.h5") as f:
            h = f["history/step_1"]
            g = h["energy"]
            e, ke = g["ETOTAL"][:], g["ALLKE"][:]
            pw = g["ALLPW"][:]
            time = h["time"][:]
            cfn = h["contact/ALL_EXTERIOR/CFN"][:]
            v_up = h["node/UPPER_NODES/V3"][:].mean(axis=1)
            v_low = h["node/LOWER_NODES/V3"][:].mean(axis=1)
        drift = np.abs(e - e[0]).max() / ke[0]
        closing = a.gap / a.velocity
        touched = time[np.argmax(cfn > 0)]
        late = time > 0.75 * time[-1]
        rebound = v_up[-1] - (v_low[-1] if a.free else 0.0)
        print(f"{name}: |ETOTAL drift| {100 * drift:.3f} % of ALLKE(0) (limit "
              f"{100 * DRIFT_LIMIT} %), contact from {touched * 1e6:.2f} us, peak CFN "
              f"{cfn.max():.3g} N, ALLPW at the end {100 * pw[-1] / ke[0]:+.2f} %, mean V3 "
              f"upper {v_up[-1]:+.3f} lower {v_low[-1]:+.3f} m/s")
        if drift > DRIFT_LIMIT:
            failures.append(f"{name}: ETOTAL drift {100 * drift:.3f} % of ALLKE(0)")
        if not cfn.max() > 0 or np.any(cfn[time < 0.9 * closing] != 0.0):
            failures.append(f"{name}: the contact force does not start after the gap closes")
        if touched > closing + 2e-6:
            failures.append(f"{name}: contact starts at {touched * 1e6:.2f} us, not near "
                            f"{closing * 1e6:.2f} us")
        if np.any(cfn[late] != 0.0):
            failures.append(f"{name}: still in contact over the last quarter of the run")
        if not rebound > 0.1 * a.velocity:
            failures.append(f"{name}: no rebound (relative V3 {rebound:+.3f} m/s)")


def one_element_cases(xpl, repo, work, failures):
    for direction in (1, 2, 3):
        name = f"one_element_{direction}"
        deck = work / f"{name}.inp"
        subprocess.run([sys.executable, str(repo / "benchmarks/make_block.py"), "-n", "1",
                        "--direction", str(direction), "--out", str(deck)], check=True,
                       capture_output=True)
        r = run(xpl, deck, work / name)
        msg = (work / name / f"{name}.msg").read_text() if r.returncode == 0 else ""
        m = re.search(r"largest energy balance drift: ETOTAL drift \S+ J, (\S+) %", msg)
        drift = float(m.group(1)) if m else (0.0 if "drift: none" in msg else None)
        print(f"{name}: exit code {r.returncode}, largest drift {drift} % of the largest energy")
        if r.returncode != 0 or drift is None:
            failures.append(f"{name}: exit code {r.returncode} at scale factor 1: "
                            f"{r.stderr.strip()[-300:]}")
        elif drift > ONE_ELEMENT_DRIFT:
            failures.append(f"{name}: drift {drift} % > {ONE_ELEMENT_DRIFT} %")
        first = None
        for factor in FACTORS:
            hot = work / f"{name}_sf{factor:g}.inp"
            hot.write_text(deck.read_text().replace("*DYNAMIC, EXPLICIT",
                                                    f"*DYNAMIC, EXPLICIT, SCALE FACTOR={factor:g}"))
            r = run(xpl, hot, work / f"{name}_sf{factor:g}")
            if r.returncode != 0:
                if r.returncode != 3 or "NaN/instability" not in r.stdout + r.stderr:
                    failures.append(f"{name}: scale factor {factor:g}: exit code "
                                    f"{r.returncode}: {r.stderr.strip()[-200:]}")
                first = factor
                break
        print(f"{name}: first failing scale factor {first}")
        if first is None or first <= FACTORS[0]:
            failures.append(f"{name}: first failing scale factor {first}, expected in "
                            f"({FACTORS[0]}, {FACTORS[-1]}]")


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    xpl, repo, work = sys.argv[1], pathlib.Path(sys.argv[2]), pathlib.Path(sys.argv[3])
    work.mkdir(parents=True, exist_ok=True)
    sys.path.insert(0, str(repo / "benchmarks"))
    import make_contact_pair as gen

    failures = []
    two_block_cases(xpl, gen, work, failures)
    one_element_cases(xpl, repo, work, failures)
    for f in failures:
        print("FAILED:", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
