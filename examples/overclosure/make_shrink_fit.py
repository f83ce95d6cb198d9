#!/usr/bin/env python3
"""Write the shrink-fit deck (examples/overclosure/shrink_fit/shrink_fit.inp), SPEC C15.

A steel ring (inner radius b - delta, outer radius c) on a solid steel shaft (radius b): the
radial interference delta is resolved by *CONTACT INITIALIZATION DATA, INTERFERENCE FIT over
the first half of the step, so the parts push each other apart and end stressed. A quarter of
a thin slice of C3D8R: symmetry planes x = 0 and y = 0, z = 0 held along z (the mid-plane of a
slice twice as thick), the face z = t free (plane stress). Lame's thick cylinders give the
interface pressure and the outer radial displacement of the ring:

    p   = E delta (c^2 - b^2) / (2 b c^2)
    u_c = 2 p b^2 c / (E (c^2 - b^2))

The step is long against the ring's lowest period (about 35 us for its ovalization, 11 us for
the breathing of the assembly): 300 us, the interference ramped away over the first 150 us.

  --n N          elements along each straight edge of the shaft's core square (2N around the
                 quarter circle); the ring and the shaft's outer band follow
  --spelling S   initialization (default): *CONTACT INITIALIZATION DATA / ASSIGNMENT;
                 distance: the same with INTERFERENCE FIT=delta (the interference given,
                 not measured)

Units m, kg, s, N, Pa. Standard library only:
    python3 examples/overclosure/make_shrink_fit.py [OUT_DIR] [--n N] [--spelling S]
"""

import argparse
import math
import pathlib

YOUNG = 210.0e9
POISSON = 0.3
DENSITY = 7800.0
B = 10.0e-3  # shaft radius, m
C = 20.0e-3  # ring outer radius, m
DELTA = 10.0e-6  # radial interference, m (0.1 % of b)
PERIOD = 3.0e-4  # step, s
FRACTION = 0.5  # of the step over which the interference is resolved
RING = 100000  # id offset of the ring's nodes and elements
DEFAULT_OUT = pathlib.Path(__file__).resolve().parent


def lame():
    """Lame's interface pressure (Pa) and the ring's outer radial displacement (m)."""
    p = YOUNG * DELTA * (C * C - B * B) / (2.0 * B * C * C)
    u = 2.0 * p * B * B * C / (YOUNG * (C * C - B * B))
    return p, u


def fmt(v):
    return f"{v:.12g}"


def mesh(n):
    """Nodes {id: (x, y, z)}, shaft and ring elements [(id, 8 node ids)], and the sets."""
    t = 0.5 * (0.5 * math.pi * B / (2 * n))  # slice thickness: half the arc element length
    s = 0.55 * B  # side of the shaft's core square
    m = max(2, n // 2)  # layers from the core square to the shaft's surface
    mr = n  # layers across the ring
    nodes, shaft, ring = {}, [], []
    sets = {"X0": [], "Y0": [], "Z0": [], "RING_OUT": [], "SHAFT_OUT_E": [], "RING_IN_E": []}

    def add(nid, x, y, z):
        nodes[nid] = (x, y, z)
        if abs(x) < 1e-15:
            sets["X0"].append(nid)
        if abs(y) < 1e-15:
            sets["Y0"].append(nid)
        if z == 0.0:
            sets["Z0"].append(nid)

    # Shaft: core grid (i, j) and the band (k, l) from the core's outer edges to the circle.
    core = {}
    band = {}
    next_id = [1]

    def new_id():
        next_id[0] += 1
        return next_id[0] - 1

    for j in range(n + 1):
        for i in range(n + 1):
            core[i, j] = new_id()
    for k in range(2 * n + 1):
        for l in range(m + 1):
            if l == 0:
                band[k, 0] = core[n, k] if k <= n else core[2 * n - k, n]
            else:
                band[k, l] = new_id()
    xy = {}
    for (i, j), nid in core.items():
        xy[nid] = (s * i / n, s * j / n)
    for k in range(2 * n + 1):
        theta = 0.5 * math.pi * k / (2 * n)
        bx, by = xy[band[k, 0]]
        ax, ay = B * math.cos(theta), B * math.sin(theta)
        for l in range(1, m + 1):
            f = l / m
            xy[band[k, l]] = (bx + f * (ax - bx), by + f * (ay - by))
    layer = next_id[0]  # ids of the top layer: + layer
    for nid, (x, y) in xy.items():
        add(nid, x, y, 0.0)
        add(nid + layer, x, y, t)

    def hexa(quad):
        return list(quad) + [q + layer for q in quad]

    eid = 1
    for j in range(n):
        for i in range(n):
            shaft.append((eid, hexa((core[i, j], core[i + 1, j], core[i + 1, j + 1], core[i, j + 1]))))
            eid += 1
    for k in range(2 * n):
        for l in range(m):
            shaft.append((eid, hexa((band[k, l], band[k, l + 1], band[k + 1, l + 1], band[k + 1, l]))))
            if l == m - 1:
                sets["SHAFT_OUT_E"].append(eid)  # face S4: the edge (k, l+1)-(k+1, l+1)
            eid += 1

    # Ring: (k, l), k around, l outward from the inner radius b - delta.
    rid = {}
    for k in range(2 * n + 1):
        theta = 0.5 * math.pi * k / (2 * n)
        for l in range(mr + 1):
            r = (B - DELTA) + (C - B + DELTA) * l / mr
            nid = RING + k * (mr + 1) + l + 1
            rid[k, l] = nid
            x, y = r * math.cos(theta), r * math.sin(theta)
            if k == 2 * n:
                x = 0.0
            if k == 0:
                y = 0.0
            add(nid, x, y, 0.0)
            add(nid + RING // 2, x, y, t)
            if l == mr:
                sets["RING_OUT"] += [nid, nid + RING // 2]
    eid = RING + 1
    for k in range(2 * n):
        for l in range(mr):
            quad = (rid[k, l], rid[k, l + 1], rid[k + 1, l + 1], rid[k + 1, l])
            ring.append((eid, list(quad) + [q + RING // 2 for q in quad]))
            if l == 0:
                sets["RING_IN_E"].append(eid)  # face S6: the edge (k+1, l)-(k, l)
            eid += 1
    return nodes, shaft, ring, sets, t


def write(out_dir, n, spelling="initialization"):
    nodes, shaft, ring, sets, t = mesh(n)
    p, u = lame()
    name = "shrink_fit"
    lines = ["*HEADING", f"Shrink fit of a steel ring on a steel shaft, Lame check (n = {n})",
             "** Generated by examples/overclosure/make_shrink_fit.py; edit the generator.",
             "** Units: m, kg, s, N, Pa.",
             f"** b = {fmt(B)} m, c = {fmt(C)} m, radial interference delta = {fmt(DELTA)} m,",
             f"** slice thickness {fmt(t)} m (z = 0 held along z, z = t free: plane stress).",
             f"** Lame: interface pressure p = {fmt(p)} Pa, outer radial displacement of the",
             f"** ring u_c = {fmt(u)} m, reached at the end of the step (mean of its last 10 %).",
             "*NODE"]
    for nid in sorted(nodes):
        x, y, z = nodes[nid]
        lines.append(f"{nid}, {fmt(x)}, {fmt(y)}, {fmt(z)}")

    def element_block(elset, elements):
        lines.append(f"*ELEMENT, TYPE=C3D8R, ELSET={elset}")
        for eid, conn in elements:
            lines.append(f"{eid}, " + ", ".join(str(c) for c in conn))

    def id_set(keyword, set_name, ids):
        lines.append(f"*{keyword}, {'NSET' if keyword == 'NSET' else 'ELSET'}={set_name}")
        ids = sorted(ids)
        for i in range(0, len(ids), 16):
            lines.append(", ".join(str(v) for v in ids[i:i + 16]))

    element_block("SHAFT", shaft)
    element_block("RING", ring)
    for set_name in ("X0", "Y0", "Z0", "RING_OUT"):
        id_set("NSET", set_name, sets[set_name])
    id_set("ELSET", "SHAFT_OUT_E", sets["SHAFT_OUT_E"])
    id_set("ELSET", "RING_IN_E", sets["RING_IN_E"])
    fit = "INTERFERENCE FIT" if spelling == "initialization" else f"INTERFERENCE FIT={fmt(DELTA)}"
    lines += ["*SURFACE, NAME=SHAFT_OUT", "SHAFT_OUT_E, S4",
              "*SURFACE, NAME=RING_IN", "RING_IN_E, S6",
              "*MATERIAL, NAME=STEEL", "*DENSITY", fmt(DENSITY), "*ELASTIC",
              f"{fmt(YOUNG)}, {fmt(POISSON)}",
              "*SOLID SECTION, ELSET=SHAFT, MATERIAL=STEEL",
              "*SOLID SECTION, ELSET=RING, MATERIAL=STEEL",
              "** The interference: resolved by the penalty over the first half of the step.",
              f"*CONTACT INITIALIZATION DATA, NAME=FIT, {fit}, STEP FRACTION={fmt(FRACTION)}",
              "*BOUNDARY", "X0, 1", "Y0, 2", "Z0, 3",
              "*STEP, NAME=FIT", "*DYNAMIC, EXPLICIT", f", {fmt(PERIOD)}",
              "*CONTACT", "*CONTACT INCLUSIONS", "SHAFT_OUT, RING_IN",
              "*CONTACT INITIALIZATION ASSIGNMENT", "SHAFT_OUT, RING_IN, FIT",
              f"*OUTPUT, FIELD, TIME INTERVAL={fmt(PERIOD / 10)}", "*NODE OUTPUT", "U",
              "*ELEMENT OUTPUT", "S",
              f"*OUTPUT, HISTORY, TIME INTERVAL={fmt(PERIOD / 200)}", "*ENERGY OUTPUT",
              "*NODE OUTPUT, NSET=RING_OUT", "U1, U2",
              "*END STEP"]
    folder = pathlib.Path(out_dir) / name
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / f"{name}.inp"
    path.write_text("\n".join(lines) + "\n")
    return path


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("out", nargs="?", default=str(DEFAULT_OUT))
    parser.add_argument("--n", type=int, default=8)
    parser.add_argument("--spelling", choices=("initialization", "distance"),
                        default="initialization")
    args = parser.parse_args()
    print(write(args.out, args.n, args.spelling))


if __name__ == "__main__":
    main()
