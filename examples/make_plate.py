#!/usr/bin/env python3
"""Write S4R plate decks: a simply supported square steel plate under a suddenly applied
uniform pressure (the shell acceptance case), optionally with a hex block resting on it.

The plate lies in the xy-plane, [0, L] x [0, L], normal +z, with n x n S4R elements. The
edges are held in z (simply supported, rotations free); two corners remove the in-plane
rigid motion. A pressure of --pressure Pa acts on the SPOS face (pushing along -z) from
t = 0 (STEP amplitude). Navier's series for the undamped plate gives a first peak of the
centre deflection of 0.4436 mm at 10.42 ms (L = 1 m, t = 10 mm, 1 kPa).

--block adds a 2 x 2 x 1 hex block in the middle of the plate sharing its bottom nodes with
the plate (a mixed shell + hex model).

Standard library only. The committed examples/plate_pressure/plate_pressure.inp is the
output with default arguments:  python3 examples/make_plate.py
"""

import argparse
import pathlib

SIDE = 1.0  # m
THICKNESS = 0.01  # m
YOUNGS_MODULUS = 200.0e9  # Pa
POISSONS_RATIO = 0.3
DENSITY = 7850.0  # kg/m^3

DEFAULT_OUT = pathlib.Path(__file__).resolve().parent / "plate_pressure" / "plate_pressure.inp"


def node_id(n, i, j, layer=0):
    """Sparse ids: 100000 * layer + 1000 * j + i + 1 (readable grid position)."""
    return 100000 * layer + 1000 * j + i + 1


def data_lines(values, per_line=8):
    values = list(values)
    return [", ".join(str(v) for v in values[k:k + per_line])
            for k in range(0, len(values), per_line)]


def build(n, pressure, period, block):
    h = SIDE / n
    out = ["*HEADING",
           f"Simply supported plate {SIDE} m x {SIDE} m x {THICKNESS} m, {n} x {n} S4R, "
           f"sudden pressure {pressure} Pa" + (", hex block on top" if block else ""),
           "*NODE"]
    for j in range(n + 1):
        for i in range(n + 1):
            out.append(f"{node_id(n, i, j)}, {i * h:.10g}, {j * h:.10g}, 0.")
    c = n // 2 - 1
    if block:
        for j in range(c, c + 3):
            for i in range(c, c + 3):
                out.append(f"{node_id(n, i, j, 1)}, {i * h:.10g}, {j * h:.10g}, {h:.10g}")
    out.append("*ELEMENT, TYPE=S4R, ELSET=PLATE")
    for j in range(n):
        for i in range(n):
            out.append(f"{1000 * j + i + 1}, {node_id(n, i, j)}, {node_id(n, i + 1, j)}, "
                       f"{node_id(n, i + 1, j + 1)}, {node_id(n, i, j + 1)}")
    if block:
        out.append("*ELEMENT, TYPE=C3D8R, ELSET=BLOCK")
        for j in range(c, c + 2):
            for i in range(c, c + 2):
                bottom = [node_id(n, i, j), node_id(n, i + 1, j), node_id(n, i + 1, j + 1),
                          node_id(n, i, j + 1)]
                top = [node_id(n, i, j, 1), node_id(n, i + 1, j, 1), node_id(n, i + 1, j + 1, 1),
                       node_id(n, i, j + 1, 1)]
                out.append(f"{900000 + 1000 * j + i}, " + ", ".join(map(str, bottom + top)))
    edges = sorted({node_id(n, i, j) for j in range(n + 1) for i in range(n + 1)
                    if i in (0, n) or j in (0, n)})
    out.append("*NSET, NSET=EDGES")
    out += data_lines(edges)
    out.append("*NSET, NSET=CENTER")
    out.append(f"{node_id(n, n // 2, n // 2)}")
    out.append("*NSET, NSET=CORNER_XY")
    out.append(f"{node_id(n, 0, 0)}")
    out.append("*NSET, NSET=CORNER_Y")
    out.append(f"{node_id(n, n, 0)}")
    out.append("*SURFACE, TYPE=ELEMENT, NAME=TOP")
    out.append("PLATE, SPOS")
    out += ["*MATERIAL, NAME=STEEL", "*DENSITY", f"{DENSITY}", "*ELASTIC",
            f"{YOUNGS_MODULUS:.6g}, {POISSONS_RATIO}"]
    out += ["*SHELL SECTION, ELSET=PLATE, MATERIAL=STEEL", f"{THICKNESS}, 5"]
    if block:
        out += ["*SOLID SECTION, ELSET=BLOCK, MATERIAL=STEEL"]
    out += ["*STEP, NAME=PRESSURE", "*DYNAMIC, EXPLICIT", f", {period}",
            "*BOUNDARY", "EDGES, 3, 3", "CORNER_XY, 1, 2", "CORNER_Y, 2, 2",
            "*DSLOAD", f"TOP, P, {pressure}",
            "*OUTPUT, FIELD, NUMBER INTERVAL=12", "*NODE OUTPUT", "U, V", "*ELEMENT OUTPUT",
            "S, STH",
            "*OUTPUT, HISTORY, TIME INTERVAL=2e-5", "*NODE OUTPUT, NSET=CENTER", "U3",
            "*ENERGY OUTPUT", "*END STEP"]
    return "\n".join(out) + "\n"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--elements", type=int, default=20, help="elements per side")
    parser.add_argument("--pressure", type=float, default=1000.0, help="Pa")
    parser.add_argument("--period", type=float, default=0.012, help="step time, s")
    parser.add_argument("--block", action="store_true", help="add a hex block on the plate")
    parser.add_argument("-o", "--output", type=pathlib.Path, default=DEFAULT_OUT)
    args = parser.parse_args()
    if args.elements < 2 or args.elements % 2:
        parser.error("--elements must be even and at least 2")
    args.output.parent.mkdir(parents=True, exist_ok=True)
    args.output.write_text(build(args.elements, args.pressure, args.period, args.block))


if __name__ == "__main__":
    main()
