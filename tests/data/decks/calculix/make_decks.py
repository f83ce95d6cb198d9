#!/usr/bin/python3
"""Writes the CalculiX-style decks of this folder (our own, in the style of CalculiX's explicit
test decks: N, mm, t, s; upper-case keywords; model-level *CONTACT PAIR; *NODE PRINT/*EL FILE).

  massless_cubes.inp   two 10 mm cubes (2 x 2 x 2 C3D8R each), the upper one 0.01 mm above the
                       lower and moving down at 1 m/s; the lower one's base fixed;
                       *CONTACT PAIR, TYPE=MASSLESS and *DYNAMIC, ALPHA=-0.05, EXPLICIT.
  clearance_cubes.inp  the same cubes 0.1 mm apart with a node-to-surface pair and
                       *CLEARANCE, VALUE=0.02: contact starts when the upper cube has moved
                       0.02 mm (at 20 us), not 0.1 mm (100 us).
  refused.inp          *STATIC, *EQUATION and a C3D20 element, as CalculiX decks have them:
                       one error each.

Usage: make_decks.py [DIR] (default: this script's folder).
"""

import pathlib
import sys

SIZE = 10.0  # mm
N = 2


def cube(first_node, first_element, z0):
    """Nodes (id, x, y, z) and C3D8R elements (id, 8 node ids) of a cube with its base at z0."""
    def nid(i, j, k):
        return first_node + i + (N + 1) * (j + (N + 1) * k)
    nodes = [(nid(i, j, k), i * SIZE / N, j * SIZE / N, z0 + k * SIZE / N)
             for k in range(N + 1) for j in range(N + 1) for i in range(N + 1)]
    elements = []
    for k in range(N):
        for j in range(N):
            for i in range(N):
                elements.append((first_element + i + N * (j + N * k),
                                 [nid(i, j, k), nid(i + 1, j, k), nid(i + 1, j + 1, k),
                                  nid(i, j + 1, k), nid(i, j, k + 1), nid(i + 1, j, k + 1),
                                  nid(i + 1, j + 1, k + 1), nid(i, j + 1, k + 1)]))
    return nodes, elements


def mesh(gap):
    lower = cube(1, 1, 0.0)
    upper = cube(101, 101, SIZE + gap)
    out = ["*NODE, NSET=Nall"]
    for nodes, _ in (lower, upper):
        out += [f"{n:6d},{x:12.6f},{y:12.6f},{z:12.6f}" for n, x, y, z in nodes]
    out.append("*ELEMENT, TYPE=C3D8R, ELSET=Elower")
    out += [f"{e:6d}," + ",".join(f"{n:6d}" for n in nn) for e, nn in lower[1]]
    out.append("*ELEMENT, TYPE=C3D8R, ELSET=Eupper")
    out += [f"{e:6d}," + ",".join(f"{n:6d}" for n in nn) for e, nn in upper[1]]
    base = [n for n, _, _, z in lower[0] if z == 0.0]
    moving = [n for n, *_ in upper[0]]
    top_corner = upper[0][-1][0]
    out += ["*ELSET,ELSET=Eall", "Elower,", "Eupper,"]
    out += ["*NSET,NSET=Nfix"] + [f"{n}," for n in base]
    out += ["*NSET,NSET=Nmove,GENERATE", f"{moving[0]},{moving[-1]},1"]
    out += ["*NSET,NSET=N1", f"{top_corner},"]
    # Slave: the upper cube's bottom faces (S1); master: the lower cube's top faces (S2).
    out += ["*SURFACE,NAME=Sslav"] + [f"{e},S1" for e, _ in upper[1][:N * N]]
    out += ["*SURFACE,NAME=Smast"] + [f"{e},S2" for e, _ in lower[1][-N * N:]]
    return out


MATERIAL = ["*MATERIAL,NAME=EL", "*ELASTIC", "210000.,.3", "*DENSITY", "7.85E-9",
            "*SOLID SECTION,ELSET=Eall,MATERIAL=EL"]


def massless():
    out = ["**", "**   Structure: two cubes on top of each other.",
           "**   Test objective: massless explicit contact, the upper cube falling.", "**"]
    out += mesh(0.01)
    out += ["*BOUNDARY", "Nfix,1,3",
            "*CONTACT PAIR,INTERACTION=SI1,TYPE=MASSLESS", "Sslav,Smast",
            "*SURFACE INTERACTION,NAME=SI1", "*SURFACE BEHAVIOR,PRESSURE-OVERCLOSURE=HARD"]
    out += MATERIAL + ["*INITIAL CONDITIONS,TYPE=VELOCITY", "Nmove,3,-1000.",
                       "*STEP,INC=100000,NLGEOM", "*DYNAMIC,ALPHA=-0.05,EXPLICIT",
                       "1.E-8,2.E-5", "*NODE PRINT,NSET=N1,FREQUENCY=1", "U", "*EL FILE",
                       "S", "*END STEP"]
    return out


def clearance():
    out = ["**", "**   Structure: two cubes on top of each other, 0.1 mm apart.",
           "**   Test objective: *CLEARANCE of a contact pair (0.02 mm).", "**"]
    out += mesh(0.1)
    out += ["*BOUNDARY", "Nfix,1,3",
            "*CONTACT PAIR,INTERACTION=SI1,TYPE=NODE TO SURFACE", "Sslav,Smast",
            "*SURFACE INTERACTION,NAME=SI1",
            "*SURFACE BEHAVIOR,PRESSURE-OVERCLOSURE=HARD",
            "*CLEARANCE,MASTER=Smast,SLAVE=Sslav,VALUE=0.02"]
    out += MATERIAL + ["*INITIAL CONDITIONS,TYPE=VELOCITY", "Nmove,3,-1000.",
                       "*STEP,INC=100000", "*DYNAMIC,EXPLICIT", ",6.E-5",
                       "*NODE PRINT,NSET=N1,FREQUENCY=1", "U", "*END STEP"]
    return out


def refused():
    out = ["**", "**   What xpl refuses in CalculiX decks: one error each.", "**",
           "*NODE,NSET=Nall"]
    out += [f"{n},{x},{y},{z}" for n, x, y, z in cube(1, 1, 0.0)[0]]
    out += ["*ELEMENT,TYPE=C3D20,ELSET=Equad",
            "1001,1,3,9,7,19,21,27,25,2,6,8,4,20,24,26,22,10,12,18,16",
            "*ELEMENT,TYPE=C3D8R,ELSET=Eall"]
    out += [f"{e}," + ",".join(str(n) for n in nn) for e, nn in cube(1, 1, 0.0)[1]]
    out += ["*EQUATION", "2", "27,1,1.,25,1,-1."]
    out += MATERIAL + ["*SOLID SECTION,ELSET=Equad,MATERIAL=EL", "*STEP", "*STATIC",
                       "*BOUNDARY", "Nall,1,3", "*END STEP", "*STEP", "*DYNAMIC,EXPLICIT",
                       ",1.E-5", "*END STEP"]
    return out


def main():
    folder = pathlib.Path(sys.argv[1]) if len(sys.argv) > 1 else pathlib.Path(__file__).parent
    for name, lines in (("massless_cubes", massless()), ("clearance_cubes", clearance()),
                        ("refused", refused())):
        (folder / f"{name}.inp").write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
