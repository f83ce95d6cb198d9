#!/usr/bin/python3
"""Checks the results of `xpl check examples/bar_impact/bar_impact.inp` (see run_xpl.py).

Usage: check_data_check.py DIRECTORY

A data check builds the model and writes frame 0 and the logs, without time stepping:
status "checked", exactly one frame (at t = 0, increment 0), at most one history row, the
.sta says DATA CHECK, and stdout says the data check completed.
"""

import pathlib
import sys

import h5py
import numpy as np

JOB = "bar_impact"
N_NODES = 1025
N_ELEMENTS = 640


def check(condition, message):
    if not condition:
        sys.exit(f"check_data_check.py: FAILED: {message}")


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    directory = pathlib.Path(sys.argv[1])
    h5_path = directory / f"{JOB}.h5"
    check(h5_path.is_file(), f"{h5_path} missing")
    with h5py.File(h5_path, "r") as f:
        check(f.attrs["status"] == "checked", f"status is {f.attrs['status']!r}, not 'checked'")
        check(f.attrs["error"] == "", f"error attribute is {f.attrs['error']!r}")
        check(f["mesh/node_ids"].shape == (N_NODES,), "node_ids shape")
        check(f["mesh/C3D8R/connectivity"].shape == (N_ELEMENTS, 8), "connectivity shape")
        frames = sorted(f["frames"].keys())
        check(len(frames) == 1, f"{len(frames)} frames, expected exactly one: {frames}")
        frame = f["frames"][frames[0]]
        check(frame.attrs["time"] == 0.0, f"frame time {frame.attrs['time']}")
        check(frame.attrs["increment"] == 0, f"frame increment {frame.attrs['increment']}")
        check(frame["U"].shape == (N_NODES, 3), "frame U shape")
        check(np.all(frame["U"][()] == 0.0), "frame 0 has non-zero displacements")
        # The initial velocity (*INITIAL CONDITIONS, MOVING, 1, -10) is in frame 0.
        v = frame["V"][()]
        check(v.shape == (N_NODES, 3), "frame V shape")
        check(np.isclose(v[:, 0].min(), -10.0), f"frame 0 V1 min {v[:, 0].min()}, expected -10")
        for name, step in f["history"].items():
            rows = step["time"].shape[0]
            check(rows <= 1, f"history {name} has {rows} rows; a data check writes at most one")
            if rows == 1:
                check(step["time"][0] == 0.0, f"history {name} row at t = {step['time'][0]}")
    sta = directory / f"{JOB}.sta"
    check(sta.is_file(), f"{sta} missing")
    sta_text = sta.read_text()
    check("DATA CHECK COMPLETED" in sta_text, ".sta does not say DATA CHECK COMPLETED")
    check("THE ANALYSIS HAS COMPLETED" not in sta_text, ".sta claims a completed analysis")
    check((directory / f"{JOB}.msg").is_file(), ".msg missing")
    check((directory / f"{JOB}.xdmf").is_file(), ".xdmf missing")
    stdout = (directory / "stdout.txt").read_text()
    check("data check of bar_impact completed" in stdout, f"stdout:\n{stdout}")
    check("element cycles per second" not in stdout, "a data check printed a run summary")
    print("check_data_check.py: status checked, one frame, no history rows, .sta DATA CHECK OK")


if __name__ == "__main__":
    main()
