#!/usr/bin/python3
"""S4R rotary inertia check (issue 21): first torsion and first bending frequency of a
narrow cantilever strip, coarse against fine meshes, and the stable increment.

Strip 0.2 m x 0.02 m x 0.002 m, aluminium (E = 70 GPa, nu = 0.33, rho = 2700 kg/m^3),
clamped at x = 0 (all six dofs), free elsewhere. Torsion: the run starts from the twist rate
of the first torsion mode, phi'(x) = W0 sin(pi x / 2L), given node by node with
*INITIAL CONDITIONS, TYPE=VELOCITY (U3 = phi' (y - w/2) and dof 4 = phi', which needs the
rotational dofs of issue 21); the tip twist UR1 is fitted with a sin + b cos + c. Bending:
the run starts from V3 = V0 (1 - cos(pi x / 2L)) and the tip deflection is fitted the same
way. The stable increment is read from the run summary.

    strip_torsion.py --xpl NEW [--old OLD] [--meshes 20x4,40x8,80x16] [--csv OUT.csv]
                     [--rotary ISOTROPIC,EXACT]

The reference frequencies are the finest mesh's, and for torsion also St Venant's
f = (1/4L) sqrt(G J / (rho I_p)), J = w t^3/3 (1 - 0.63 t/w), I_p = t w (w^2 + t^2)/12.
"""

import argparse
import csv
import json
import math
import pathlib
import subprocess

import h5py
import numpy as np

L, WIDTH, T = 0.2, 0.02, 0.002
E, NU, RHO = 70.0e9, 0.33, 2700.0


def st_venant():
    g = E / (2 * (1 + NU))
    j = WIDTH * T**3 / 3 * (1 - 0.63 * T / WIDTH)
    ip = T * WIDTH * (WIDTH**2 + T**2) / 12
    return math.sqrt(g * j / (RHO * ip)) / (4 * L)


def build(nx, ny, mode, period, rotations=True, rotary="ISOTROPIC"):
    hx, hy = L / nx, WIDTH / ny
    nid = lambda i, j: j * (nx + 1) + i + 1  # noqa: E731
    out = ["*HEADING", f"Cantilever strip {L} x {WIDTH} x {T} m, {nx} x {ny} S4R, {mode}",
           "*NODE"]
    for j in range(ny + 1):
        for i in range(nx + 1):
            out.append(f"{nid(i, j)}, {i * hx:.12g}, {j * hy:.12g}, 0.")
    out.append("*ELEMENT, TYPE=S4R, ELSET=STRIP")
    for j in range(ny):
        for i in range(nx):
            out.append(f"{j * nx + i + 1}, {nid(i, j)}, {nid(i + 1, j)}, {nid(i + 1, j + 1)}, "
                       f"{nid(i, j + 1)}")
    out += ["*NSET, NSET=ROOT"] + [str(nid(0, j)) for j in range(ny + 1)]
    out += ["*NSET, NSET=TIP", str(nid(nx, ny // 2))]
    out += ["*MATERIAL, NAME=AL", "*DENSITY", f"{RHO}", "*ELASTIC", f"{E:.6g}, {NU}",
            "*SHELL SECTION, ELSET=STRIP, MATERIAL=AL"
            + ("" if rotary == "ISOTROPIC" else f", ROTARY INERTIA={rotary}"), f"{T}, 5",
            "*INITIAL CONDITIONS, TYPE=VELOCITY"]
    for j in range(ny + 1):
        for i in range(1, nx + 1):
            x, y = i * hx, j * hy - WIDTH / 2
            if mode == "torsion":
                rate = 10.0 * math.sin(math.pi * x / (2 * L))  # rad/s
                out.append(f"{nid(i, j)}, 3, {rate * y:.12g}")
                if rotations:
                    out.append(f"{nid(i, j)}, 4, {rate:.12g}")
            else:
                out.append(f"{nid(i, j)}, 3, {0.1 * (1 - math.cos(math.pi * x / (2 * L))):.12g}")
    out += ["*BOUNDARY", "ROOT, 1, 6", "*STEP", "*DYNAMIC, EXPLICIT", f", {period}",
            "*OUTPUT, HISTORY, TIME INTERVAL=" + ("2e-6" if mode == "torsion" else "5e-5"),
            "*NODE OUTPUT, NSET=TIP", "UR1" if mode == "torsion" else "U3", "*END STEP"]
    return "\n".join(out) + "\n"


def fit_frequency(time, u, f_lo, f_hi):
    def residual(f):
        basis = np.column_stack([np.sin(2 * math.pi * f * time), np.cos(2 * math.pi * f * time),
                                 np.ones_like(time)])
        coef, *_ = np.linalg.lstsq(basis, u, rcond=None)
        return float(np.sum((basis @ coef - u) ** 2))
    grid = np.linspace(f_lo, f_hi, 801)
    best = grid[int(np.argmin([residual(f) for f in grid]))]
    lo, hi = best - (f_hi - f_lo) / 800, best + (f_hi - f_lo) / 800
    for _ in range(60):
        m1, m2 = lo + 0.382 * (hi - lo), lo + 0.618 * (hi - lo)
        if residual(m1) < residual(m2):
            hi = m2
        else:
            lo = m1
    return 0.5 * (lo + hi)


def run(xpl, nx, ny, mode, out_dir, rotations=True, rotary="ISOTROPIC"):
    name = f"strip_{mode}_{nx}x{ny}" + ("" if rotary == "ISOTROPIC" else "_" + rotary.lower())
    deck = out_dir / f"{name}.inp"
    period = 4.0e-3 if mode == "torsion" else 0.06
    deck.write_text(build(nx, ny, mode, period, rotations, rotary))
    subprocess.run([xpl, "run", str(deck), "-o", str(out_dir)], check=True, capture_output=True)
    with h5py.File(out_dir / f"{name}.h5", "r") as f:
        h = f["history/step_1"]
        time = h["time"][()]
        u = h["node/TIP/" + ("UR1" if mode == "torsion" else "U3")][()].ravel()
    summary = json.loads((out_dir / f"{name}.summary.json").read_text())
    bounds = (300.0, 1500.0) if mode == "torsion" else (10.0, 120.0)
    return fit_frequency(time, u, *bounds), summary


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--xpl", default="build/release/apps/xpl")
    parser.add_argument("--old")
    parser.add_argument("--meshes", default="20x4,40x8,80x16")
    parser.add_argument("--csv", type=pathlib.Path)
    parser.add_argument("--rotary", default="ISOTROPIC",
                        help="comma-separated *SHELL SECTION ROTARY INERTIA= values to run with "
                             "the new binary (ISOTROPIC, EXACT)")
    args = parser.parse_args()
    binaries = [("new", args.xpl, r) for r in args.rotary.split(",")]
    binaries += [("old", args.old, "ISOTROPIC")] if args.old else []
    rows = []
    print(f"St Venant torsion (Kirchhoff strip with the edge correction): {st_venant():.2f} Hz")
    for label, xpl, rotary in binaries:
        out_dir = pathlib.Path("build/strip_torsion") / label
        out_dir.mkdir(parents=True, exist_ok=True)
        for mesh in args.meshes.split(","):
            nx, ny = map(int, mesh.split("x"))
            # A binary from before issue 21 refuses dof 4: its torsion start is U3 alone.
            ft, summary = run(xpl, nx, ny, "torsion", out_dir, rotations=label == "new",
                              rotary=rotary)
            fb, bending = run(xpl, nx, ny, "bending", out_dir, rotary=rotary)
            rows.append({"binary": label, "rotary": rotary, "mesh": mesh, "torsion_hz": ft,
                         "bending_hz": fb, "torsion_increments": summary.get("increments", ""),
                         "bending_increments": bending.get("increments", "")})
            print(f"{label} {rotary} {mesh:>6}: torsion {ft:.2f} Hz, bending {fb:.3f} Hz, "
                  f"{summary.get('increments', '')} increments")
    for label, _, rotary in binaries:
        mine = [r for r in rows if r["binary"] == label and r["rotary"] == rotary]
        ref = mine[-1]
        for r in mine:
            print(f"{label} {rotary} {r['mesh']:>6}: torsion "
                  f"{100 * (r['torsion_hz'] / ref['torsion_hz'] - 1):+.2f} % "
                  f"of the finest, {100 * (r['torsion_hz'] / st_venant() - 1):+.2f} % of St Venant; "
                  f"bending {100 * (r['bending_hz'] / ref['bending_hz'] - 1):+.2f} % of the finest")
    if args.csv:
        with args.csv.open("w", newline="") as f:
            writer = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
            writer.writeheader()
            writer.writerows(rows)


if __name__ == "__main__":
    main()
