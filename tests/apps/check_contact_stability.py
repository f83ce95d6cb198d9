#!/usr/bin/python3
"""Contact stability stress test, CI part (issue 20, items 2 and 4).

Usage: check_contact_stability.py XPL REPO WORK_DIR

Two-body decks of benchmarks/make_contact_pair.py on the coarse mesh (1 mm elements): a body
1 um above a lower one, moving down, default general contact (ALL EXTERIOR, default penalty).
Pairs hex-hex, hex-shell (upper block of 1 or 3 element layers on a 3 x 3 x 2 block or an S4R
plate) and shell-shell, lower body fixed or free, at 1 m/s, and the hex-hex single layer also
at 0.1 and 10 m/s: 12 decks. Each must
- complete at scale factor 1 and at 1.05 (the target first failing factor is >= 1.05; the
  full table with the bisected factor is benchmarks/RESULTS.md, benchmarks/contact_stability.py);
- keep |ETOTAL drift| (largest over the run) below 0.5 % of ALLKE(0), the issue's target
  (measured 0.05 to 0.21 %; 0.5 to 3.4 % before ALLKE was measured as ½ v(n-½)·M·v(n+½) and
  ALLVD by the trapezoidal rule), and ALLPW after the rebound within 4 % of ALLKE(0) of zero.
  The latter bounds the default penalty's own stepping error (a spring that closes or opens
  inside an increment: -0.1 to +1.8 % measured), not the issue's target (~0), which is not met
  yet.
"""

import pathlib
import subprocess
import sys

import h5py
import numpy as np

DRIFT_BOUND = 0.005
ALLPW_BOUND = 0.04


def cases():
    for upper, lower, layers in (("hex", "hex", 1), ("hex", "hex", 3), ("hex", "shell", 1),
                                 ("hex", "shell", 3), ("shell", "shell", 1)):
        for free in (False, True):
            yield upper, lower, layers, free, 1.0
    yield "hex", "hex", 1, False, 0.1
    yield "hex", "hex", 1, True, 10.0


def build(gen, work, upper, lower, layers, free, v, scale):
    name = (f"{upper}-{lower}_{layers}L_{'free' if free else 'fixed'}_{v:g}_sf{scale:g}")
    d = work / name
    d.mkdir(parents=True, exist_ok=True)
    h = 1e-3
    args = ["--upper", upper, "--lower", lower, "--h", str(h), "--lnx", "3", "--unx", "4",
            "--lnz", "2", "--unz", str(layers), "--thickness", str(h), "--gap", str(0.001 * h),
            "--velocity", str(v), "--period", str(0.001 * h / v + 20e-6), "--scale", str(scale),
            "--out", str(d / "d.inp")]
    if free:
        args.append("--free")
    a = gen.parser().parse_args(args)
    a.uh = a.h
    (d / "d.inp").write_text(gen.build(a))
    return name, d


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    xpl, repo, work = sys.argv[1], pathlib.Path(sys.argv[2]), pathlib.Path(sys.argv[3])
    sys.path.insert(0, str(repo / "benchmarks"))
    import make_contact_pair as gen

    failures = []
    for upper, lower, layers, free, v in cases():
        for scale in (1.0, 1.05):
            name, d = build(gen, work, upper, lower, layers, free, v, scale)
            r = subprocess.run([xpl, "run", "d.inp", "--threads", "1", "--quiet"], cwd=d,
                               capture_output=True, text=True, timeout=120)
            if r.returncode != 0:
                failures.append(f"{name}: exit code {r.returncode}: {r.stderr.strip()[-200:]}")
                continue
            if scale != 1.0:
                print(f"{name}: completed")
                continue
            with h5py.File(d / "d.h5", "r") as f:
                g = f["history/step_1/energy"]
                e, ke0, pw = g["ETOTAL"][:], g["ALLKE"][0], g["ALLPW"][:]
            drift, pw_end, pw_peak = np.abs(e - e[0]).max() / ke0, pw[-1] / ke0, pw.max() / ke0
            print(f"{name}: completed, |ETOTAL drift| {100 * drift:.2f} % of ALLKE(0), ALLPW "
                  f"{100 * pw_peak:.1f} % at its peak, {100 * pw_end:+.2f} % after the rebound")
            if not pw_peak > 0:
                failures.append(f"{name}: no contact (ALLPW never positive)")
            if drift > DRIFT_BOUND:
                failures.append(f"{name}: ETOTAL drift {100 * drift:.2f} % > {100 * DRIFT_BOUND} %")
            if abs(pw_end) > ALLPW_BOUND:
                failures.append(f"{name}: ALLPW {100 * pw_end:+.2f} % of ALLKE(0) after the "
                                f"rebound (bound {100 * ALLPW_BOUND} %)")
    for failure in failures:
        print("FAILED:", failure)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
