#!/usr/bin/python3
"""Checks `xpl run` on the S4R plate decks of examples/make_plate.py (see run_xpl.py).

Usage: check_plate.py DIRECTORY JOB [--block]

plate:  the simply supported plate under a sudden 1 kPa: first peak of the centre deflection
        against Navier's series (0.4436 mm at 10.42 ms, 3 %), energy balance (1 % of the
        largest energy), shell output (UR, S_SNEG/S_SPOS, STH) and the XDMF through meshio.
--block: the same plate with a 2 x 2 x 1 hex block sharing plate nodes (a mixed model): the
        run completes, the mesh has both types, the XDMF is one Mixed topology that meshio
        reads as quad and hexahedron cells, and the block's bottom nodes move with the plate.
Exits non-zero with a message on the first failed check.
"""

import pathlib
import sys

import h5py
import meshio
import numpy as np

PEAK = 0.4436e-3  # m, Navier series, first peak of the undamped centre deflection
PEAK_TIME = 10.42e-3  # s
THICKNESS = 0.01


def check(condition, message):
    if not condition:
        sys.exit(f"check_plate.py: FAILED: {message}")


def first_peak(time, deflection):
    """First local maximum of the deflection (parabolic refinement)."""
    for k in range(1, len(deflection) - 1):
        a, b, c = deflection[k - 1:k + 2]
        if b > a and b >= c and b > 0:
            denom = a - 2 * b + c
            shift = 0.5 * (a - c) / denom if denom else 0.0
            return b - 0.25 * (a - c) * shift, time[k] + shift * (time[k + 1] - time[k])
    return 0.0, 0.0


def main():
    directory = pathlib.Path(sys.argv[1])
    job = sys.argv[2]
    block = "--block" in sys.argv[3:]
    with h5py.File(directory / f"{job}.h5", "r") as f:
        check(f.attrs["status"] == "completed", f"status is {f.attrs['status']!r}")
        mesh = f["mesh"]
        check("S4R" in mesh, "no /mesh/S4R")
        check(("C3D8R" in mesh) == block, "hex group present/absent wrongly")
        history = f["history/step_1"]
        time = history["time"][()]
        w = -history["node/CENTER/U3"][()].ravel()
        peak, at = first_peak(time, w)
        energy = history["energy"]
        etotal = energy["ETOTAL"][()]
        largest = max(energy["ALLKE"][()].max(), energy["ALLIE"][()].max(),
                      np.abs(energy["ALLWK"][()]).max())
        drift = np.abs(etotal - etotal[0]).max()
        check(drift < 0.01 * largest, f"ETOTAL drift {drift:.3g} J of {largest:.3g} J")
        if not block:
            check(abs(peak / PEAK - 1) < 0.03, f"first peak {peak * 1e3:.4f} mm, expected 0.4436")
            check(abs(at / PEAK_TIME - 1) < 0.03, f"peak at {at * 1e3:.3f} ms, expected 10.42")
        else:
            peak, at = w.max(), time[np.argmax(w)]
            check(peak > 1e-6, "the plate with a block does not deflect")
        frames = sorted(f["frames"].keys())
        last = f["frames"][frames[-1]]
        for name in ("U", "UR", "V", "VR", "S", "S_SNEG", "S_SPOS", "STH"):
            check(name in last, f"frame {frames[-1]} has no {name}")
        n_el = len(mesh["element_ids"])
        check(last["STH"].shape == (n_el,), f"STH shape {last['STH'].shape}")
        shell_rows = mesh["S4R/element_rows"][()] if block else np.arange(n_el)
        sth = last["STH"][()]
        check(np.all(np.abs(sth[shell_rows] / THICKNESS - 1) < 1e-3), "shell thickness off")
        if block:
            hex_rows = mesh["C3D8R/element_rows"][()]
            check(np.all(np.isnan(sth[hex_rows])), "STH of hexes is not NaN")
            check(np.all(np.isnan(last["S_SNEG"][()][hex_rows])), "S_SNEG of hexes is not NaN")
        # Bending: bottom and top section stresses of the shells have opposite signs.
        bottom = last["S_SNEG"][()][shell_rows, 0]
        top = last["S_SPOS"][()][shell_rows, 0]
        check(np.all(bottom * top <= 0.0) or np.abs(bottom + top).max() < 0.2 * np.abs(top).max(),
              "S_SNEG and S_SPOS do not show bending")
        check(np.abs(last["UR"][()]).max() > 0.0, "UR is all zero")
        if block:
            # Shared nodes: a block bottom node has the plate's displacement (one row each).
            coordinates = mesh["coordinates"][()]
            u = last["U"][()]
            centre = np.argmin(np.linalg.norm(coordinates - [0.5, 0.5, 0.0], axis=1))
            check(abs(u[centre, 2]) > 0.0, "the shared centre node does not move")

    reader = meshio.xdmf.TimeSeriesReader(str(directory / f"{job}.xdmf"))
    points, cells = reader.read_points_cells()
    types = sorted({c.type for c in cells})
    expected = ["hexahedron", "quad"] if block else ["quad"]
    check(types == expected, f"XDMF cell types {types}, expected {expected}")
    t, point_data, cell_data = reader.read_data(reader.num_steps - 1)
    check("UR" in point_data and "STH" in cell_data, "XDMF lacks UR or STH")
    print(f"check_plate.py: {job}: first peak {peak * 1e3:.4f} mm at {at * 1e3:.3f} ms, "
          f"ETOTAL drift {drift / largest:.2e} of the largest energy")


if __name__ == "__main__":
    main()
