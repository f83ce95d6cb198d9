#!/usr/bin/env python3
"""Two-body contact stability decks (issue 20, draft): a body moving down onto a lower one.

Default: the issue-20 deck, a 4 x 4 x 1 mm steel block of 1 mm C3D8R (one layer) 1 um above
a 3 x 3 x 2 mm block fixed at its bottom, at 1 m/s, *CONTACT ALL EXTERIOR with all defaults.
  python3 benchmarks/make_contact_pair.py --out two.inp [--free] [--lower shell] [--unz 2]

Lower: hex block NX x NY x NZ (fixed bottom, or free) or an S4R plate (pinned edges, or free).
Upper: hex block (layers) or S4R plate. Units m, kg, s, N, Pa. Standard library only.
"""
import argparse, pathlib

E, NU, RHO = 200e9, 0.3, 7850.0

class Deck:
    def __init__(self):
        self.nodes, self.elements, self.sets, self.lines = [], {}, {}, []

def hex_block(deck, base, name, nx, ny, nz, h, x0, y0, z0):
    nid = lambda i, j, k: base + i + 100 * j + 10000 * k
    nodes = []
    for k in range(nz + 1):
        for j in range(ny + 1):
            for i in range(nx + 1):
                nodes.append((nid(i, j, k), x0 + i * h, y0 + j * h, z0 + k * h))
    els = []
    for k in range(nz):
        for j in range(ny):
            for i in range(nx):
                c = [nid(i, j, k), nid(i + 1, j, k), nid(i + 1, j + 1, k), nid(i, j + 1, k),
                     nid(i, j, k + 1), nid(i + 1, j, k + 1), nid(i + 1, j + 1, k + 1), nid(i, j + 1, k + 1)]
                els.append((base + 1 + i + 100 * j + 10000 * k, c))
    deck.nodes += nodes
    deck.elements[name] = ("C3D8R", els)
    deck.sets[name + "_BOTTOM"] = [nid(i, j, 0) for j in range(ny + 1) for i in range(nx + 1)]
    deck.sets[name + "_NODES"] = [n[0] for n in nodes]

def shell_plate(deck, base, name, nx, ny, h, x0, y0, z0):
    nid = lambda i, j: base + i + 100 * j
    nodes = [(nid(i, j), x0 + i * h, y0 + j * h, z0) for j in range(ny + 1) for i in range(nx + 1)]
    els = [(base + 1 + i + 100 * j, [nid(i, j), nid(i + 1, j), nid(i + 1, j + 1), nid(i, j + 1)])
           for j in range(ny) for i in range(nx)]
    deck.nodes += nodes
    deck.elements[name] = ("S4R", els)
    deck.sets[name + "_EDGES"] = [nid(i, j) for j in range(ny + 1) for i in range(nx + 1)
                                  if i in (0, nx) or j in (0, ny)]
    deck.sets[name + "_NODES"] = [n[0] for n in nodes]

def build(a):
    d = Deck()
    h = a.h
    gap = a.gap
    t = a.thickness
    # lower body: top surface at z = 0
    if a.lower == "hex":
        hex_block(d, 100000, "LOWER", a.lnx, a.lnx, a.lnz, h, 0, 0, -a.lnz * h)
        ltop = 0.0
    else:
        shell_plate(d, 100000, "LOWER", a.lnx, a.lnx, h, 0, 0, -0.5 * t)
    off = -0.5 * (a.unx - a.lnx) * h + a.shift * h
    if a.upper == "hex":
        hex_block(d, 300000, "UPPER", a.unx, a.unx, a.unz, a.uh, off, off, gap)
    else:
        shell_plate(d, 300000, "UPPER", a.unx, a.unx, a.uh, off, off, gap + 0.5 * t)
    L = []
    L.append("*HEADING")
    L.append(f"Contact stability: {a.upper} above {a.lower}, v = {a.velocity} m/s")
    L.append("*NODE")
    for n in d.nodes:
        L.append(f"{n[0]}, {n[1]:.12g}, {n[2]:.12g}, {n[3]:.12g}")
    for name, (typ, els) in d.elements.items():
        L.append(f"*ELEMENT, TYPE={typ}, ELSET={name}")
        for e, c in els:
            L.append(f"{e}, " + ", ".join(map(str, c)))
    for name, ids in d.sets.items():
        L.append(f"*NSET, NSET={name}")
        for i in range(0, len(ids), 12):
            L.append(", ".join(map(str, ids[i:i + 12])))
    L.append("*MATERIAL, NAME=STEEL")
    L.append("*DENSITY")
    L.append(f"{RHO:g}")
    L.append("*ELASTIC")
    L.append(f"{E:g}, {NU:g}")
    for name, (typ, els) in d.elements.items():
        if typ == "C3D8R":
            L.append(f"*SOLID SECTION, ELSET={name}, MATERIAL=STEEL")
        else:
            L.append(f"*SHELL SECTION, ELSET={name}, MATERIAL=STEEL")
            L.append(f"{t:g}, 5")
    L.append("*INITIAL CONDITIONS, TYPE=VELOCITY")
    L.append(f"{a.ic_set}, 3, {-a.velocity:g}")
    if a.free_lower_velocity:
        L.append(f"LOWER_NODES, 3, {a.free_lower_velocity:g}")
    L.append("*STEP, NAME=IMPACT")
    L.append("*DYNAMIC, EXPLICIT" + (f", SCALE FACTOR={a.scale:g}" if a.scale != 1.0 else ""))
    L.append(f", {a.period:g}")
    if not a.free:
        L.append("*BOUNDARY")
        L.append("LOWER_BOTTOM, 1, 3" if a.lower == "hex" else "LOWER_EDGES, 1, 3")
    if not a.no_contact:
      L.append("*CONTACT")
      L.append("*CONTACT INCLUSIONS, ALL EXTERIOR")
    if not a.no_contact and a.penalty != 1.0:
        L.append("*CONTACT CONTROLS ASSIGNMENT, TYPE=SCALE PENALTY")
        L.append(f", , {a.penalty:g}")
    L.append(f"*OUTPUT, HISTORY, TIME INTERVAL={a.period / a.frames:g}")
    L.append("*ENERGY OUTPUT")
    L.append("*END STEP")
    return "\n".join(L) + "\n"

def parser():
    p = argparse.ArgumentParser()
    p.add_argument("--out", type=pathlib.Path, required=True)
    p.add_argument("--lower", choices=["hex", "shell"], default="hex")
    p.add_argument("--upper", choices=["hex", "shell"], default="hex")
    p.add_argument("--lnx", type=int, default=3)
    p.add_argument("--lnz", type=int, default=2)
    p.add_argument("--unx", type=int, default=4)
    p.add_argument("--unz", type=int, default=1)
    p.add_argument("--h", type=float, default=1e-3)
    p.add_argument("--uh", type=float, default=None)
    p.add_argument("--shift", type=float, default=0.0, help="upper offset, element sizes")
    p.add_argument("--thickness", type=float, default=1e-3)
    p.add_argument("--gap", type=float, default=1e-6)
    p.add_argument("--velocity", type=float, default=1.0)
    p.add_argument("--free", action="store_true")
    p.add_argument("--free-lower-velocity", type=float, default=0.0)
    p.add_argument("--scale", type=float, default=1.0)
    p.add_argument("--ic-set", default="UPPER_NODES")
    p.add_argument("--penalty", type=float, default=1.0)
    p.add_argument("--no-contact", action="store_true")
    p.add_argument("--period", type=float, default=20e-6)
    p.add_argument("--frames", type=int, default=200)
    return p

if __name__ == "__main__":
    a = parser().parse_args()
    if a.uh is None: a.uh = a.h
    a.out.parent.mkdir(parents=True, exist_ok=True)
    a.out.write_text(build(a))
