#!/usr/bin/python3
"""Checks the results of `xpl run examples/bar_impact/bar_impact.inp` (see run_xpl.py).

Usage: check_bar_impact.py DIRECTORY

DIRECTORY holds bar_impact.{h5,xdmf,sta,msg} and the run's stdout.txt. Checks the documented
HDF5 layout with h5py, the wall reaction against the one-dimensional bar-wave solution, the
energy balance, the XDMF through meshio's TimeSeriesReader, the .sta/.msg logs and the
summary printed on stdout. Exits non-zero with a message on the first failed check.
"""

import math
import pathlib
import re
import sys

import h5py
import meshio
import numpy as np

JOB = "bar_impact"
N_NODES = 41 * 5 * 5  # 40 x 4 x 4 C3D8R
N_ELEMENTS = 40 * 4 * 4
N_WALL_NODES = 5 * 5
PERIOD = 1.0e-4  # s, *DYNAMIC data line

# Bar data, as in examples/make_bar.py.
LENGTH = 0.100  # m
AREA = 0.010 * 0.010  # m^2
DENSITY = 7850.0  # kg/m^3
YOUNGS_MODULUS = 200.0e9  # Pa
SPEED = 10.0  # m/s, |initial velocity|
C0 = math.sqrt(YOUNGS_MODULUS / DENSITY)  # one-dimensional wave speed (nu = 0)
WALL_FORCE = DENSITY * C0 * SPEED * AREA  # N, ~39.62 kN while the compressive wave runs


def check(condition, message):
    if not condition:
        sys.exit(f"check_bar_impact.py: FAILED: {message}")


def check_h5(path):
    """Returns the coordinates, connectivity, frame times and U of every frame."""
    check(path.is_file(), f"{path} missing")
    with h5py.File(path, "r") as f:
        check(f.attrs["status"] == "completed", f"status is {f.attrs['status']!r}")
        check(f.attrs["error"] == "", f"error attribute is {f.attrs['error']!r}")
        check("xpl_version" in f.attrs, "no xpl_version attribute")
        check(isinstance(f.attrs["xpl_version"], str) and f.attrs["xpl_version"] != "",
              f"xpl_version is {f.attrs['xpl_version']!r}")
        check(f.attrs["job"] == JOB, f"job is {f.attrs['job']!r}")

        # Mesh.
        node_ids = f["mesh/node_ids"][()]
        check(node_ids.shape == (N_NODES,), f"node_ids shape {node_ids.shape}")
        check(len(np.unique(node_ids)) == N_NODES, "node ids are not unique")
        coordinates = f["mesh/coordinates"][()]
        check(coordinates.shape == (N_NODES, 3), f"coordinates shape {coordinates.shape}")
        check(np.allclose(coordinates.min(axis=0), 0.0)
              and np.allclose(coordinates.max(axis=0), [LENGTH, 0.01, 0.01]),
              "coordinates do not span the 100 x 10 x 10 mm bar")
        check(f["mesh/element_ids"].shape == (N_ELEMENTS,),
              f"element_ids shape {f['mesh/element_ids'].shape}")
        check(f["mesh/C3D8R/element_ids"].shape == (N_ELEMENTS,), "C3D8R/element_ids shape")
        connectivity = f["mesh/C3D8R/connectivity"][()]
        check(connectivity.shape == (N_ELEMENTS, 8), f"connectivity shape {connectivity.shape}")
        check(connectivity.min() >= 0 and connectivity.max() < N_NODES,
              f"connectivity rows out of range [{connectivity.min()}, {connectivity.max()}]")
        check(len(np.unique(connectivity)) == N_NODES, "some nodes are in no element")
        check(f["mesh/node_sets/FIXED"].shape == (N_WALL_NODES,), "node set FIXED size")

        # Field output frames: TIME INTERVAL=1e-5 over 1e-4 s, plus frame 0.
        names = sorted(f["frames"].keys())
        check(len(names) >= 2, f"only {len(names)} frames")
        times, increments, displacements = [], [], {}
        for name in names:
            frame = f["frames"][name]
            times.append(frame.attrs["time"])
            increments.append(frame.attrs["increment"])
            for field in ("U", "V", "A", "RF"):
                check(field in frame, f"frame {name} has no {field}")
                check(frame[field].shape == (N_NODES, 3), f"{name}/{field} shape {frame[field].shape}")
                check(np.all(np.isfinite(frame[field][()])), f"{name}/{field} not finite")
            check("S" in frame, f"frame {name} has no S")
            check(frame["S"].shape == (N_ELEMENTS, 6), f"{name}/S shape {frame['S'].shape}")
            displacements[name] = frame["U"][()]
        check(times[0] == 0.0, f"first frame at t = {times[0]}")
        check(all(np.diff(times) > 0), f"frame times do not increase: {times}")
        check(all(np.diff(increments) > 0), f"frame increments do not increase: {increments}")
        check(math.isclose(times[-1], PERIOD, rel_tol=1e-9), f"last frame at t = {times[-1]}")
        check(len(names) == 11, f"{len(names)} frames, expected 11 (t = 0, 1e-5, ..., 1e-4)")
        # The bar moves towards the wall (-x): the free end is displaced in -x at the end.
        free_end = np.isclose(coordinates[:, 0], LENGTH)
        check(np.all(displacements[names[-1]][free_end, 0] < 0.0), "free end did not move in -x")

        # History output.
        history = f["history/step_1"]
        t = history["time"][()]
        check(t.ndim == 1 and t.shape[0] > 100, f"history time shape {t.shape}")
        check(t[0] == 0.0, f"history starts at t = {t[0]}")
        check(all(np.diff(t) > 0), "history time does not increase")
        check(math.isclose(t[-1], PERIOD, rel_tol=1e-9), f"history ends at t = {t[-1]}")
        rf1 = history["node/FIXED/RF1"]
        check(rf1.shape == (t.shape[0], N_WALL_NODES), f"RF1 shape {rf1.shape}")
        check(sorted(rf1.attrs["node_ids"]) == sorted(f["mesh/node_sets/FIXED"][()]),
              "RF1 node_ids are not the FIXED set")
        wall_force = rf1[()].sum(axis=1)

        # Sign convention (looked up in the data): RF is the reaction the support applies to
        # the bar. The bar moves in -x into the wall at x = 0, the wall pushes it back, so
        # sum(RF1) is POSITIVE (+rho*c0*v*A) while the compressive wave runs (t < 2L/c0) and
        # turns negative afterwards, when the fixed nodes hold the rebounding bar.
        two_l_over_c = 2.0 * LENGTH / C0
        window = (t >= 0.1 * two_l_over_c) & (t <= 0.9 * two_l_over_c)
        check(np.count_nonzero(window) >= 20, "too few history rows in the plateau window")
        plateau = wall_force[window].mean()
        check(abs(plateau - WALL_FORCE) <= 0.02 * WALL_FORCE,
              f"wall force plateau {plateau:.1f} N, expected {WALL_FORCE:.1f} N within 2 %")
        check(np.all(wall_force[window] > 0.0), "wall force changes sign in the plateau window")

        # Energy balance: ETOTAL is conserved (no external work at a fixed wall).
        energy = history["energy"]
        for name in ("ALLKE", "ALLSE", "ALLAE", "ALLIE", "ALLVD", "ALLWK", "ETOTAL"):
            check(energy[name].shape == t.shape, f"energy/{name} shape {energy[name].shape}")
        kinetic_0 = energy["ALLKE"][0]
        # Lumped mass: the wall nodes (half of the first of 40 element layers, 1/80 of the
        # mass) start at rest, every other node at SPEED.
        expected_ke = 0.5 * DENSITY * LENGTH * AREA * SPEED**2 * (1.0 - 1.0 / 80.0)
        # ALLKE(0) = ½ m v(0)² − ⅛ Δt² Σ f(0)²/m (docs/theory/energy.md, "What ALLKE measures"): the bulk
        # viscosity of the first layer, squeezed against the wall from t = 0, acts already
        # (−2.7e-5 of the energy here; ALLKE(0) from the whole-step velocity matched to 1e-6).
        check(math.isclose(kinetic_0, expected_ke, rel_tol=1e-4),
              f"ALLKE(0) = {kinetic_0} J, expected {expected_ke} J")
        etotal = energy["ETOTAL"][()]
        drift = np.abs(etotal - etotal[0]).max()
        check(drift < 0.01 * kinetic_0,
              f"ETOTAL drifts by {drift:.4g} J, more than 1 % of ALLKE(0) = {kinetic_0:.4g} J")
        check(energy["ALLKE"][-1] < 0.5 * kinetic_0, "kinetic energy was not converted")

        return coordinates, connectivity, times, displacements


def check_xdmf(path, coordinates, connectivity, times, displacements):
    check(path.is_file(), f"{path} missing")
    with meshio.xdmf.TimeSeriesReader(str(path)) as reader:
        points, cells = reader.read_points_cells()
        check(np.array_equal(points, coordinates), "XDMF geometry differs from /mesh/coordinates")
        check(len(cells) == 1 and cells[0].type == "hexahedron", f"XDMF cells: {cells}")
        check(cells[0].data.shape == (N_ELEMENTS, 8), f"XDMF cells shape {cells[0].data.shape}")
        check(np.array_equal(cells[0].data, connectivity), "XDMF topology differs from h5")
        check(reader.num_steps == len(displacements),
              f"{reader.num_steps} XDMF time steps, {len(displacements)} frames")
        for k, name in enumerate(sorted(displacements)):
            t, point_data, _ = reader.read_data(k)
            check(t == times[k], f"XDMF time of step {k}: {t} != {times[k]}")
            check("U" in point_data, f"XDMF step {k} has no U")
            check(np.array_equal(point_data["U"], displacements[name]),
                  f"XDMF U of step {k} differs from frame {name}")
        return reader.num_steps


def check_logs(directory, h5_path):
    sta = directory / f"{JOB}.sta"
    msg = directory / f"{JOB}.msg"
    check(sta.is_file(), f"{sta} missing")
    check(msg.is_file(), f"{msg} missing")
    sta_text = sta.read_text()
    check("COMPLETED" in sta_text, ".sta does not say COMPLETED")
    check("THE ANALYSIS HAS COMPLETED SUCCESSFULLY" in sta_text,
          ".sta lacks 'THE ANALYSIS HAS COMPLETED SUCCESSFULLY'")
    check("NOT BEEN COMPLETED" not in sta_text, ".sta says the analysis did not complete")
    check(msg.stat().st_size > 0, ".msg is empty")
    check("ERROR" not in msg.read_text(), ".msg reports an error")
    # Phase names in the .sta timing table, to compare with stdout.
    table = sta_text.split("WALL CLOCK TIME PER PHASE", 1)
    check(len(table) == 2, ".sta has no WALL CLOCK TIME PER PHASE table")
    phases = []
    for line in table[1].splitlines():
        m = re.match(r"^\s+(\S.*?)\s+[0-9.]+ s$", line)
        if m and m.group(1) != "total":
            phases.append(m.group(1))
    check(len(phases) >= 4, f".sta phase table: {phases}")
    return phases


def check_stdout(path, phases):
    check(path.is_file(), f"{path} missing (run through run_xpl.py)")
    text = path.read_text()
    m = re.search(r"^xpl: element cycles per second: (\S+) \((\d+) elements x (\d+) increments, "
                  r"(\d+) threads\)$", text, re.MULTILINE)
    check(m is not None, f"no 'xpl: element cycles per second:' line on stdout:\n{text}")
    check(float(m.group(1)) > 0.0, f"element cycles per second {m.group(1)}")
    check(int(m.group(2)) == N_ELEMENTS, f"{m.group(2)} elements on stdout")
    check(int(m.group(3)) > 0, f"{m.group(3)} increments on stdout")
    printed = re.findall(r"^xpl: phase (.+): ([0-9.]+) s$", text, re.MULTILINE)
    check(len(printed) > 0, f"no 'xpl: phase' lines on stdout:\n{text}")
    check([name for name, _ in printed] == phases,
          f"stdout phases {[name for name, _ in printed]} differ from the .sta table {phases}")
    check(f"xpl: {JOB} completed" in text, "stdout lacks the completion line")


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    directory = pathlib.Path(sys.argv[1])
    h5_path = directory / f"{JOB}.h5"
    coordinates, connectivity, times, displacements = check_h5(h5_path)
    steps = check_xdmf(directory / f"{JOB}.xdmf", coordinates, connectivity, times, displacements)
    phases = check_logs(directory, h5_path)
    check_stdout(directory / "stdout.txt", phases)
    print(f"check_bar_impact.py: h5 layout, wall force, energy balance, {steps} XDMF steps, "
          f"logs and stdout OK")


if __name__ == "__main__":
    main()
