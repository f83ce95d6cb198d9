#!/usr/bin/python3
"""Checks xpl result files with the tools users read them with.

Usage: check_results.py DIRECTORY JOB

h5py: the documented layout of JOB.h5 (shapes, ids, status, history).
meshio: JOB.xdmf through meshio.xdmf.TimeSeriesReader (mesh and every frame's point data U),
compared with the datasets in JOB.h5. Exits non-zero with a message on the first mismatch.
"""

import pathlib
import sys

import h5py
import meshio
import numpy as np


def check(condition, message):
    if not condition:
        sys.exit(f"check_results.py: FAILED: {message}")


def check_h5(path):
    with h5py.File(path, "r") as f:
        check(f.attrs["status"] == "completed", f"status is {f.attrs['status']!r}")
        check(f.attrs["error"] == "", "error text is not empty")
        for name in ("xpl_version", "job", "heading"):
            check(isinstance(f.attrs[name], str), f"attribute {name} is not a string")
        n_nodes = f["mesh/node_ids"].shape[0]
        n_elements = f["mesh/element_ids"].shape[0]
        check(f["mesh/coordinates"].shape == (n_nodes, 3), "coordinates shape")
        connectivity = f["mesh/C3D8R/connectivity"][()]
        check(connectivity.shape == (f["mesh/C3D8R/element_ids"].shape[0], 8), "connectivity")
        check(connectivity.min() >= 0 and connectivity.max() < n_nodes, "connectivity rows")
        check(f["mesh/node_ids"].dtype == np.int64, "node_ids dtype")
        frames = sorted(f["frames"].keys())
        check(len(frames) > 0, "no frames")
        times = []
        for name in frames:
            frame = f["frames"][name]
            times.append(frame.attrs["time"])
            for field in ("U", "V", "A", "RF"):
                if field in frame:
                    check(frame[field].shape == (n_nodes, 3), f"{name}/{field} shape")
            if "S" in frame:
                check(frame["S"].shape == (n_elements, 6), f"{name}/S shape")
                check(frame["MISES"].shape == (n_elements,), f"{name}/MISES shape")
        check(all(np.diff(times) >= 0), "frame times decrease")
        for step in f["history"].values():
            nt = step["time"].shape[0]
            check(nt > 0, "empty history")

            def visit(name, obj, nt=nt):
                if isinstance(obj, h5py.Dataset):
                    check(obj.shape[0] == nt, f"history {name} has {obj.shape[0]} rows, not {nt}")
                    if obj.ndim == 2:
                        check(obj.attrs["node_ids"].shape == (obj.shape[1],), f"{name} node_ids")

            step.visititems(visit)
        return f["mesh/coordinates"][()], {name: f["frames"][name]["U"][()] for name in frames}, times


def check_xdmf(path, coordinates, displacements, times):
    with meshio.xdmf.TimeSeriesReader(path) as reader:
        points, cells = reader.read_points_cells()
        check(np.array_equal(points, coordinates), "XDMF geometry differs from /mesh/coordinates")
        check(len(cells) == 1 and cells[0].type == "hexahedron", f"cells: {cells}")
        check(reader.num_steps == len(displacements), f"{reader.num_steps} XDMF time steps")
        for k, (name, u) in enumerate(sorted(displacements.items())):
            t, point_data, cell_data = reader.read_data(k)
            check(t == times[k], f"time of step {k}: {t} != {times[k]}")
            check(np.array_equal(point_data["U"], u), f"U of frame {name}")
            check(point_data["V"].shape == u.shape, f"V of frame {name}")
            if "S" in cell_data:
                check(cell_data["S"][0].shape == (cells[0].data.shape[0], 6), f"S of {name}")
    return reader.num_steps


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    directory, job = pathlib.Path(sys.argv[1]), sys.argv[2]
    coordinates, displacements, times = check_h5(directory / f"{job}.h5")
    steps = check_xdmf(directory / f"{job}.xdmf", coordinates, displacements, times)
    print(f"check_results.py: {job}: h5py layout and {steps} XDMF frames OK")


if __name__ == "__main__":
    main()
