#!/usr/bin/env python3
"""Contact stability stress test (issue 20, draft): for each case, run at scale factor 1 and
check it completes with |ETOTAL drift| < 0.5 % of the initial kinetic energy (largest over the
run), then find the first failing scale factor by bisection in (1, 1.5] to 0.008 (a run "fails"
when xpl stops); a case that fails at 1 is bisected in (0.5, 1] instead. Cases: mesh (coarse 1 mm, fine 0.5 mm), upper layers (1, 3),
pair (hex-hex, hex-shell, shell-shell), support (fixed lower body, both free), speed
(0.1, 1, 10 m/s). Each deck has < 200 elements and runs ~100-300 increments (tens of ms).

Usage: contact_stability.py XPL [--quick] [--table OUT.md]
Standard library + h5py/numpy (read the energies).
"""
import argparse, itertools, pathlib, subprocess, sys, tempfile
sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import make_contact_pair as gen
import h5py, numpy as np

DRIFT_LIMIT = 5e-3

def run_case(xpl, case, scale, work):
    d = work / f"{case['name']}_{scale:.4f}"
    d.mkdir(parents=True, exist_ok=True)
    args = gen.parser().parse_args(case["args"] + ["--scale", str(scale), "--out", str(d / "d.inp")])
    if args.uh is None: args.uh = args.h
    (d / "d.inp").write_text(gen.build(args))
    r = subprocess.run([xpl, "run", "d.inp", "--threads", "1", "--quiet"], cwd=d,
                       capture_output=True, text=True, timeout=120,
                       env={"OMP_WAIT_POLICY": "PASSIVE", "PATH": "/usr/bin:/bin"})
    with h5py.File(d / "d.h5") as f:
        g = f["history/step_1/energy"]
        e = g["ETOTAL"][:]; ke0 = g["ALLKE"][0]
        drift = np.max(np.abs(e - e[0])) / ke0
        pw_end = g["ALLPW"][-1] / ke0 if "ALLPW" in g else 0.0
    return r.returncode == 0, drift, pw_end

def first_failure(xpl, case, work, lo=1.0, hi=1.5, steps=6):
    """The first failing scale factor in (lo, hi] to (hi - lo)/2^steps: lo runs, hi fails."""
    ok, _, _ = run_case(xpl, case, hi, work)
    if ok and hi > 1.0: return f">{hi:g}"
    for _ in range(steps):
        mid = 0.5 * (lo + hi)
        ok, _, _ = run_case(xpl, case, mid, work)
        lo, hi = (mid, hi) if ok else (lo, mid)
    return f"{hi:.3f}"

def cases(quick):
    for h, layers, pair, free, v in itertools.product(
            [1e-3, 0.5e-3], [1, 3], ["hex-hex", "hex-shell", "shell-shell"], [False, True],
            [0.1, 1.0, 10.0]):
        if quick and (h != 1e-3 or v != 1.0): continue
        upper, lower = pair.split("-")
        n = 4 if h == 1e-3 else 8
        a = ["--upper", upper, "--lower", lower, "--h", str(h), "--lnx", str(n - 1), "--unx", str(n),
             "--lnz", "2", "--unz", str(layers), "--thickness", str(h), "--gap", str(0.001 * h),
             "--velocity", str(v), "--period", str(0.001 * h / v + 20e-6 * h / 1e-3)]
        if free: a.append("--free")
        if upper == "shell" and layers != 1: continue  # a shell has one layer
        yield {"name": f"{'coarse' if h == 1e-3 else 'fine'}_{layers}L_{pair}_{'free' if free else 'fixed'}_{v:g}",
               "args": a}

def main():
    p = argparse.ArgumentParser(); p.add_argument("xpl"); p.add_argument("--quick", action="store_true")
    p.add_argument("--table", type=pathlib.Path); p.add_argument("--no-bisect", action="store_true")
    a = p.parse_args()
    rows = ["| case | SF 1 | max drift / KE0 | ALLPW end / KE0 | first failing SF |", "|---|---|---|---|---|"]
    bad = 0
    with tempfile.TemporaryDirectory() as t:
        work = pathlib.Path(t)
        for c in cases(a.quick):
            ok, drift, pw = run_case(a.xpl, c, 1.0, work)
            if not ok:  # the stable factor below 1, by bisection in [0.5, 1]
                ff = first_failure(a.xpl, c, work, 0.5, 1.0, 5) if not a.no_bisect else "<1"
            else:
                ff = "-" if a.no_bisect else first_failure(a.xpl, c, work)
            bad += (not ok) or drift >= DRIFT_LIMIT or (ff[0] not in "->" and float(ff) < 1.05)
            rows.append(f"| {c['name']} | {'ok' if ok else 'FAIL'} | {drift:.2e} | {pw:+.1e} | {ff} |")
            print(rows[-1], flush=True)
    if a.table: a.table.write_text("\n".join(rows) + "\n")
    sys.exit(1 if bad else 0)

if __name__ == "__main__":
    main()
