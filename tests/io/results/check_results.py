#!/usr/bin/python3
"""Checks xpl result files with the tools users read them with.

Usage: check_results.py DIRECTORY JOB

h5py: the documented layout of JOB.h5 (shapes, ids, per-type connectivity, the mixed
topology of hex + shell meshes, status, history).
meshio: JOB.xdmf through meshio.xdmf.TimeSeriesReader (mesh and every frame's point and cell
data), and JOB_last.xdmf (the last frame alone) through meshio.read (which reads one grid, not
a temporal collection), compared with the datasets in JOB.h5; the cell data must line up with
the cells (shell-only fields are NaN exactly on the hexahedra). Tensors reach the XDMF in VTK
order (XX YY ZZ XY YZ XZ = S11 S22 S33 S12 S23 S13) and global axes from /xdmf/NNNNNN (issue
19); solids' rows there are their S columns reordered, shells' local-axes copies are S_LOCAL
etc. The XDMF also carries node_id / element_id (deck ids) and, in both XDMF files, one 0/1
attribute per set (NSET_NAME / ELSET_NAME; issue 34: no XDMF Set elements). Exits non-zero on
the first mismatch.
"""

import pathlib
import sys

import h5py
import meshio
import numpy as np

# Abaqus element type (group below /mesh): meshio cell type, nodes, XDMF Mixed cell code.
ELEMENT_TYPES = {"C3D8R": ("hexahedron", 8, 9), "S4R": ("quad", 4, 5)}
NODE_FIELDS = ("U", "V", "A", "RF")
ROTATIONS = {"U": "UR", "V": "VR", "RF": "RM"}  # written with U/V/RF on shell models
CELL_WIDTHS = {"S": 6, "MISES": 1, "EVOL": 1, "S_SNEG": 6, "S_SPOS": 6, "STH": 1}
SHELL_ONLY = ("S_SNEG", "S_SPOS", "STH")  # NaN on the rows of solid elements


def check(condition, message):
    if not condition:
        sys.exit(f"check_results.py: FAILED: {message}")


def element_cells(mesh):
    """meshio type and node rows of every element, in the row order of the cell fields."""
    n_nodes = mesh["node_ids"].shape[0]
    element_ids = mesh["element_ids"][()]
    types = [name for name in ELEMENT_TYPES if name in mesh]
    mixed = len(types) > 1
    check(types or len(element_ids) == 0, "no element type group below /mesh")
    kinds = [None] * len(element_ids)
    nodes = [None] * len(element_ids)
    for name in types:
        group = mesh[name]
        meshio_type, corners, _ = ELEMENT_TYPES[name]
        ids = group["element_ids"][()]
        connectivity = group["connectivity"][()]
        check(connectivity.shape == (len(ids), corners), f"{name}/connectivity shape")
        check(connectivity.min() >= 0 and connectivity.max() < n_nodes, f"{name} node rows")
        check(("element_rows" in group) == mixed, f"{name}/element_rows only in mixed meshes")
        rows = group["element_rows"][()] if mixed else np.arange(len(ids))
        check(np.array_equal(element_ids[rows], ids), f"{name}/element_rows do not match ids")
        for row, element_nodes in zip(rows, connectivity):
            check(kinds[row] is None, f"element row {row} in two type groups")
            kinds[row], nodes[row] = meshio_type, element_nodes
    check(all(kind is not None for kind in kinds), "an element is in no type group")
    check(("mixed_topology" in mesh) == mixed, "/mesh/mixed_topology only in mixed meshes")
    if mixed:
        codes = {meshio_type: code for meshio_type, _, code in ELEMENT_TYPES.values()}
        expected = np.concatenate([[codes[k], *n] for k, n in zip(kinds, nodes)])
        check(np.array_equal(mesh["mixed_topology"][()], expected), "mixed_topology")
    return kinds, nodes


def cell_blocks(kinds, nodes):
    """The cell blocks meshio makes of elements in this order: one per run of a type."""
    blocks = []
    for kind, element_nodes in zip(kinds, nodes):
        if blocks and blocks[-1][0] == kind:
            blocks[-1][1].append(element_nodes)
        else:
            blocks.append((kind, [element_nodes]))
    return [(kind, np.array(rows)) for kind, rows in blocks]


def check_frame(name, frame, n_nodes, kinds):
    shells = "quad" in kinds
    for field in NODE_FIELDS + tuple(ROTATIONS.values()):
        if field in frame:
            check(frame[field].shape == (n_nodes, 3), f"{name}/{field} shape")
    for base, rotation in ROTATIONS.items():
        check((rotation in frame) == (shells and base in frame), f"{name}/{rotation} with {base}")
    for field, width in CELL_WIDTHS.items():
        if field not in frame:
            continue
        expected = (len(kinds),) if width == 1 else (len(kinds), width)
        check(frame[field].shape == expected, f"{name}/{field} shape")
        if field in SHELL_ONLY:
            values = frame[field][()].reshape(len(kinds), -1)
            finite = np.isfinite(values).all(axis=1)
            check(np.array_equal(finite, np.array(kinds) == "quad"), f"{name}/{field} NaN rows")
    check(("MISES" in frame) == ("S" in frame), f"{name}: MISES with S")
    for field in ("S_SNEG", "S_SPOS"):
        check((field in frame) == (shells and "S" in frame), f"{name}/{field} with S")
    check(shells or "STH" not in frame, f"{name}/STH without shells")


def check_h5(path):
    with h5py.File(path, "r") as f:
        check(f.attrs["status"] == "completed", f"status is {f.attrs['status']!r}")
        check(f.attrs["error"] == "", "error text is not empty")
        for name in ("xpl_version", "job", "heading"):
            check(isinstance(f.attrs[name], str), f"attribute {name} is not a string")
        n_nodes = f["mesh/node_ids"].shape[0]
        check(f["mesh/coordinates"].shape == (n_nodes, 3), "coordinates shape")
        check(f["mesh/node_ids"].dtype == np.int64, "node_ids dtype")
        kinds, nodes = element_cells(f["mesh"])
        frames = sorted(f["frames"].keys())
        check(len(frames) > 0, "no frames")
        data, times = [], []
        node_ids, element_ids = f["mesh/node_ids"][()], f["mesh/element_ids"][()]
        for name in frames:
            frame = f["frames"][name]
            check_frame(name, frame, n_nodes, kinds)
            times.append(frame.attrs["time"])
            data.append(xdmf_fields(f, name, kinds, node_ids, element_ids))
        check(all(np.diff(times) >= 0), "frame times decrease")
        for step in f["history"].values():
            nt = step["time"].shape[0]
            check(nt > 0, "empty history")

            def visit(name, obj, nt=nt):
                if isinstance(obj, h5py.Dataset):
                    check(obj.shape[0] == nt, f"history {name} has {obj.shape[0]} rows, not {nt}")
                    if obj.ndim == 2:
                        check(obj.attrs["node_ids"].shape == (obj.shape[1],), f"{name} node_ids")
                    # Issue 19: node series are (nt, n) for any n; every series has units.
                    check(not name.startswith("node/") or obj.ndim == 2, f"history {name} 1-D")
                    check("units" in obj.attrs, f"history {name} has no units")
                    check(name == "time" or "components" in obj.attrs,
                          f"history {name} has no components")

            step.visititems(visit)
        return f["mesh/coordinates"][()], cell_blocks(kinds, nodes), data, times


INTERNAL_FIELDS = {"HGSTATE"}
VTK_ORDER = [0, 1, 2, 3, 5, 4]  # S11 S22 S33 S12 S23 S13 = XX YY ZZ XY YZ XZ


def check_rotation(f, frame, field, copy, kinds):
    """Shell rows of the XDMF copy: the local tensor rotated to global axes, E^T L E, with the
    shell frame (e1 bisecting the unit diagonals, e3 normal) of the deformed corners."""
    if "S4R" not in f["mesh"]:
        return
    x = f["mesh/coordinates"][()] + frame["U"][()]
    group = f["mesh/S4R"]
    rows = group["element_rows"][()] if "element_rows" in group else np.arange(len(kinds))
    local = frame[field][()]
    for row, corners in zip(rows, group["connectivity"][()]):
        p = x[corners]
        d13, d24 = p[2] - p[0], p[3] - p[1]
        e3 = np.cross(d13, d24)
        e3 /= np.linalg.norm(e3)
        e1 = d13 / np.linalg.norm(d13) - d24 / np.linalg.norm(d24)
        e1 /= np.linalg.norm(e1)
        rotation = np.array([e1, np.cross(e3, e1), e3])
        s = local[row]
        tensor = np.array([[s[0], s[3], s[4]], [s[3], s[1], s[5]], [s[4], s[5], s[2]]])
        g = rotation.T @ tensor @ rotation
        expected = np.array([g[0, 0], g[1, 1], g[2, 2], g[0, 1], g[1, 2], g[0, 2]])
        # Rounding of two rotations written in another order: 1e-12 of the largest component.
        scale = max(np.abs(s).max(), 1e-300)
        check(np.abs(copy[row] - expected).max() <= 1e-12 * scale,
              f"{field} of shell row {row}: the global copy is not E^T S E")


def xdmf_fields(f, name, kinds, node_ids, element_ids):
    """The fields the XDMF file shows for frame `name`, from the datasets of JOB.h5."""
    frame = f["frames"][name]
    shells = "quad" in kinds
    hex_rows = np.array(kinds) == "hexahedron"
    out = {"node_id": node_ids, "element_id": element_ids}
    for field in frame:
        if field in INTERNAL_FIELDS:
            continue
        values = frame[field][()]
        check("components" in frame[field].attrs and "units" in frame[field].attrs,
              f"{name}/{field}: components / units attributes")
        if values.ndim == 2 and values.shape[1] == 6:
            check(list(frame[field].attrs["components"].split(",")) == [
                field.split("_")[0] + c for c in ("11", "22", "33", "12", "13", "23")],
                f"{name}/{field} components {frame[field].attrs['components']}")
            copy = f["xdmf"][name][field][()]
            # Solid rows: the same stresses (global axes), columns in VTK order.
            check(np.array_equal(copy[hex_rows], values[hex_rows][:, VTK_ORDER], equal_nan=True),
                  f"/xdmf/{name}/{field} solid rows are not {field} in VTK order")
            out[field] = copy
            if shells:
                local = f["xdmf"][name][field + "_LOCAL"][()]
                check(np.array_equal(local[~hex_rows], values[~hex_rows][:, VTK_ORDER]),
                      f"/xdmf/{name}/{field}_LOCAL shell rows")
                check(np.isnan(local[hex_rows]).all(), f"/xdmf/{name}/{field}_LOCAL solid rows")
                out[field + "_LOCAL"] = local
                if "U" in frame:
                    check_rotation(f, frame, field, copy, kinds)
        else:
            out[field] = values
    return out


def check_cells(cells, blocks, what):
    check([c.type for c in cells] == [kind for kind, _ in blocks], f"{what}: cells {cells}")
    for cell, (kind, rows) in zip(cells, blocks):
        check(np.array_equal(cell.data, rows), f"{what}: {kind} connectivity differs from h5")


def check_fields(point_data, cell_data, cells, frame, what):
    """meshio's point and cell data equal the frame's datasets; cell data split by block."""
    node_fields = {f for f in frame if f in NODE_FIELDS or f in ROTATIONS.values()}
    node_fields.add("node_id")
    check(set(point_data) == node_fields, f"{what}: point data {sorted(point_data)}")
    for field in node_fields:
        check(np.array_equal(point_data[field], frame[field]), f"{what}: {field}")
    # HGSTATE is internal state for --import (docs/user/cli.md), deliberately not in the XDMF (nor in
    # `frame`, the XDMF's fields).
    check(not set(cell_data) & INTERNAL_FIELDS, f"{what}: internal fields in the XDMF")
    check(set(cell_data) == set(frame) - node_fields,
          f"{what}: cell data {sorted(cell_data)}")
    for field, blocks in cell_data.items():
        check([len(b) for b in blocks] == [len(c.data) for c in cells], f"{what}: {field} blocks")
        check(np.array_equal(np.concatenate(blocks), frame[field], equal_nan=True),
              f"{what}: {field} differs from h5")
        if field in SHELL_ONLY:
            for cell, block in zip(cells, blocks):
                finite = np.isfinite(block).all()
                check(finite == (cell.type == "quad"), f"{what}: {field} on {cell.type} cells")


def deck_sets(h5_path):
    """(node ids, element ids, {NSET_NAME / ELSET_NAME: (node set?, deck ids)}) of JOB.h5."""
    with h5py.File(h5_path, "r") as f:
        node_ids, element_ids = f["mesh/node_ids"][()], f["mesh/element_ids"][()]
        sets = {"NSET_" + n: (True, f["mesh/node_sets"][n][()]) for n in f["mesh/node_sets"]}
        sets.update({"ELSET_" + n: (False, f["mesh/element_sets"][n][()])
                     for n in f["mesh/element_sets"]})
    check(sets, "the test models have sets")
    return node_ids, element_ids, sets


def pop_sets(point_data, cell_data, h5_path, what):
    """Checks and removes the 0/1 set arrays from meshio's point and cell data."""
    node_ids, element_ids, sets = deck_sets(h5_path)
    for name, (node, members) in sets.items():
        data = point_data.pop(name, None) if node else cell_data.pop(name, None)
        check(data is not None, f"{what}: set {name} missing")
        flags = data if node else np.concatenate(data)
        ids = node_ids if node else element_ids
        check(np.array_equal(np.sort(ids[flags.astype(bool)]), np.sort(members)),
              f"{what}: set {name} members")


def check_time_series(path, coordinates, blocks, data, times, h5_path):
    with meshio.xdmf.TimeSeriesReader(path) as reader:
        points, cells = reader.read_points_cells()
        check(np.array_equal(points, coordinates), "XDMF geometry differs from /mesh/coordinates")
        check_cells(cells, blocks, "TimeSeriesReader")
        check(reader.num_steps == len(data), f"{reader.num_steps} XDMF time steps")
        for k, frame in enumerate(data):
            t, point_data, cell_data = reader.read_data(k)
            check(t == times[k], f"time of step {k}: {t} != {times[k]}")
            point_data, cell_data = dict(point_data), dict(cell_data)
            pop_sets(point_data, cell_data, h5_path, f"XDMF step {k}")
            check_fields(point_data, cell_data, cells, frame, f"XDMF step {k}")
    return reader.num_steps


def check_last_frame(path, coordinates, blocks, frame, h5_path):
    """meshio.read reads one grid: JOB_last.xdmf, the last frame alone, with the sets as 0/1
    point and cell data."""
    mesh = meshio.read(path)
    check(np.array_equal(mesh.points, coordinates), "meshio.read: points")
    check_cells(mesh.cells, blocks, "meshio.read")
    point_data, cell_data = dict(mesh.point_data), dict(mesh.cell_data)
    pop_sets(point_data, cell_data, h5_path, "meshio.read")
    check_fields(point_data, cell_data, mesh.cells, frame, "meshio.read JOB_last.xdmf")


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    directory, job = pathlib.Path(sys.argv[1]), sys.argv[2]
    coordinates, blocks, data, times = check_h5(directory / f"{job}.h5")
    xdmf = directory / f"{job}.xdmf"
    steps = check_time_series(xdmf, coordinates, blocks, data, times, directory / f"{job}.h5")
    check_last_frame(directory / f"{job}_last.xdmf", coordinates, blocks, data[-1],
                     directory / f"{job}.h5")
    types = ", ".join(f"{len(rows)} {kind}" for kind, rows in blocks)
    print(f"check_results.py: {job}: h5py layout and {steps} XDMF frames ({types}) OK")


if __name__ == "__main__":
    main()
