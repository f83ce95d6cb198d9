#!/usr/bin/python3
"""Interference fit against Lame (SPEC C15, issue 35 item 3): a steel ring on a solid steel
shaft, the radial interference resolved by the penalty over the first half of the step.

Usage: check_shrink_fit.py XPL WORK_DIR [COARSE_N FINE_N]

Writes examples/overclosure/make_shrink_fit.py's deck on two meshes (default n = 4 and 8: 8
and 16 elements around the quarter), runs both and checks on each
  - the interface pressure p (CFN of the pair over the quarter's interface area pi/2 b t) and
    the ring's outer radial displacement u_c (mean over the RING_OUT nodes), both as means over
    the last 10 % of the step, against Lame's p = E delta (c^2 - b^2) / (2 b c^2) and
    u_c = 2 p b^2 c / (E (c^2 - b^2)): within 5 % on the fine mesh, the error smaller than on
    the coarse one;
  - the ramp: CFN is 0 at t = 0 and grows smoothly (no jump: every history step of CFN during
    the ramp below 10 % of its final value), and the contact pressure at the middle of the
    ramp is about half the final one (30 % .. 70 %);
  - the energy balance: |ETOTAL - ETOTAL(0)| below 1 % of the largest ALLIE, and ALLWK (the
    ramp's work) equals ALLIE + ALLKE + ALLPW + ALLVD within that 1 %;
  - the stable increment is not lowered: the .sta increment at the end within 1 % of the first;
  - the .msg reports the interference fits (the count of the nodes whose overclosure is
    ramped) and no node is adjusted by the automatic pass.
It prints the penalty's compliance: how much of the interference the springs take up (the
mean penetration left, p/k, against delta).
"""

import math
import pathlib
import re
import shutil
import subprocess
import sys

import h5py
import numpy as np

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parents[1] / "examples" / "overclosure"))
import make_shrink_fit as fit  # noqa: E402

FAILED = []


def check(condition, message):
    print(("PASS " if condition else "FAIL ") + message)
    if not condition:
        FAILED.append(message)


def sta_increments(path):
    rows = []
    for line in path.read_text().splitlines():
        m = re.match(r"^\s+\d+\s+(\d+)\s+([-\d.E+]+)\s+[-\d.E+]+\s+([-\d.E+]+)", line)
        if m:
            rows.append((int(m.group(1)), float(m.group(2)), float(m.group(3))))
    return rows


def run(xpl, work, n):
    out = work / f"n{n}"
    shutil.rmtree(out, ignore_errors=True)
    deck = fit.write(out, n)
    result = subprocess.run([xpl, "run", str(deck), "-o", str(out)], capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit(f"FAIL: n = {n}: xpl run exited {result.returncode}\n{result.stdout}\n{result.stderr}")
    _, _, _, _, t = fit.mesh(n)
    return out, t


def measure(out, t, n):
    f = h5py.File(out / "shrink_fit.h5", "r")
    check(f.attrs["status"] == "completed", f"n = {n}: the run completes")
    h = f["history/step_1"]
    time = h["time"][:]
    period = fit.PERIOD
    last = time >= 0.9 * period - 1e-12
    cfn = h["contact/SHAFT_OUT-RING_IN/CFN"][:]
    area = 0.5 * math.pi * fit.B * t
    pressure = cfn / area
    ids = f["mesh/node_ids"][:]
    row = {int(i): k for k, i in enumerate(ids)}
    xyz = f["mesh/coordinates"][:]
    # The RING_OUT history columns are in the set's order (ascending ids).
    out_ids = sorted(i for i in ids if i > fit.RING and
                     abs(math.hypot(*xyz[row[int(i)], :2]) - fit.C) < 1e-9)
    xy = np.array([xyz[row[int(i)], :2] for i in out_ids])
    radial = xy / np.linalg.norm(xy, axis=1)[:, None]
    u1, u2 = h["node/RING_OUT/U1"][:], h["node/RING_OUT/U2"][:]
    u_r = (u1 * radial[None, :, 0] + u2 * radial[None, :, 1]).mean(axis=1)
    e = {k: h["energy"][k][:] for k in ("ETOTAL", "ALLIE", "ALLKE", "ALLPW", "ALLVD", "ALLWK")}
    return time, last, pressure, u_r, e


def compliance(out):
    """The interference the penalty springs take up at the end (m): delta less what the
    radial displacements of the ring's inner nodes and the shaft's outer nodes achieved."""
    f = h5py.File(out / "shrink_fit.h5", "r")
    frame = f["frames"][sorted(f["frames"].keys())[-1]]
    xyz = f["mesh/coordinates"][:]
    ids = f["mesh/node_ids"][:]
    u = frame["U"][:]
    r = np.hypot(xyz[:, 0], xyz[:, 1])
    u_r = (u[:, 0] * xyz[:, 0] + u[:, 1] * xyz[:, 1]) / np.maximum(r, 1e-30)
    ring_in = (ids > fit.RING) & (np.abs(r - (fit.B - fit.DELTA)) < 1e-9)
    shaft_out = (ids < fit.RING) & (np.abs(r - fit.B) < 1e-9)
    achieved = u_r[ring_in].mean() - u_r[shaft_out].mean()
    return fit.DELTA - achieved


def main():
    if len(sys.argv) not in (3, 5):
        sys.exit(__doc__)
    xpl, work = sys.argv[1], pathlib.Path(sys.argv[2])
    coarse_n, fine_n = (int(sys.argv[3]), int(sys.argv[4])) if len(sys.argv) == 5 else (4, 8)
    work.mkdir(parents=True, exist_ok=True)
    p_ref, u_ref = fit.lame()
    print(f"Lame: p = {p_ref / 1e6:.3f} MPa, u_c = {u_ref * 1e6:.4f} um "
          f"(b = {fit.B * 1e3} mm, c = {fit.C * 1e3} mm, delta = {fit.DELTA * 1e6} um)")
    errors = {}
    for n in (coarse_n, fine_n):
        out, t = run(xpl, work, n)
        time, last, pressure, u_r, e = measure(out, t, n)
        p_mean, u_mean = pressure[last].mean(), u_r[last].mean()
        ep, eu = p_mean / p_ref - 1.0, u_mean / u_ref - 1.0
        errors[n] = (abs(ep), abs(eu))
        print(f"n = {n}: p = {p_mean / 1e6:.3f} MPa ({100 * ep:+.2f} %), u_c = {u_mean * 1e6:.4f} um "
              f"({100 * eu:+.2f} %), oscillation of p over the last 10 %: "
              f"{100 * (pressure[last].max() - pressure[last].min()) / p_ref:.2f} % of p")
        # The penalty's compliance: the interference the springs take up, about p/k. The
        # ring's radial displacement at b plus the shaft's is what the fit achieved; Lame's
        # split of delta is the same up to the springs' share.
        ramp_end = fit.FRACTION * fit.PERIOD
        check(pressure[0] == 0.0, f"n = {n}: no contact force at t = 0 (CFN {pressure[0]:.3g})")
        during = time <= ramp_end
        jumps = np.abs(np.diff(pressure[during])).max() / p_mean
        check(jumps < 0.10, f"n = {n}: CFN grows smoothly over the ramp (largest step between "
              f"history points {100 * jumps:.1f} % of the final value)")
        half = pressure[np.argmin(np.abs(time - 0.5 * ramp_end))] / p_mean
        check(0.3 < half < 0.7, f"n = {n}: half way through the ramp the pressure is "
              f"{100 * half:.0f} % of the final one")
        scale = e["ALLIE"].max()
        drift = np.abs(e["ETOTAL"] - e["ETOTAL"][0]).max() / scale
        check(drift < 0.01, f"n = {n}: ETOTAL drifts {100 * drift:.3f} % of the largest ALLIE")
        balance = e["ALLIE"][-1] + e["ALLKE"][-1] + e["ALLPW"][-1] + e["ALLVD"][-1]
        check(abs(e["ALLWK"][-1] - balance) < 0.01 * scale,
              f"n = {n}: the ramp's work ALLWK {e['ALLWK'][-1]:.4g} J = ALLIE + ALLKE + ALLPW + "
              f"ALLVD {balance:.4g} J (ALLPW {e['ALLPW'][-1]:.3g} J held by the springs)")
        sta = sta_increments(out / "shrink_fit.sta")
        # The last row is the increment cut to end the step on its period.
        dt0, dt1 = sta[0][2], min(row[2] for row in sta[:-1])
        check(abs(dt1 / dt0 - 1.0) < 0.01, f"n = {n}: stable increment {dt0:.4e} s at the start, "
              f"{dt1:.4e} s at its smallest (not lowered by the fit)")
        taken = compliance(out)
        print(f"n = {n}: the penalty springs take up {taken * 1e6:.3f} um of the {fit.DELTA * 1e6} um "
              f"interference ({100 * taken / fit.DELTA:.2f} %) at the end of the step")
        msg = (out / "shrink_fit.msg").read_text()
        fits = re.search(r"interference fits, step 1 \(FIT\): (\d+) overclosure\(s\)", msg)
        expected = 2 * 2 * (2 * n + 1)  # both surfaces' nodes, two layers, 2n + 1 around
        check(fits is not None and int(fits.group(1)) == expected,
              f"n = {n}: the .msg reports {fits.group(1) if fits else 'no'} interference "
              f"overclosures ({expected} interface nodes)")
        check("0 node(s) adjusted" in msg, f"n = {n}: no node is adjusted strain free")
    (cp, cu), (fp, fu) = errors[coarse_n], errors[fine_n]
    check(fp < 0.05 and fu < 0.05,
          f"fine mesh within 5 % of Lame: p {100 * fp:.2f} %, u_c {100 * fu:.2f} %")
    check(fp < cp and fu < cu, f"the errors shrink from the coarse mesh (p {100 * cp:.2f} %, "
          f"u_c {100 * cu:.2f} %) to the fine one (p {100 * fp:.2f} %, u_c {100 * fu:.2f} %)")
    if FAILED:
        sys.exit(f"{len(FAILED)} check(s) failed")


if __name__ == "__main__":
    main()
