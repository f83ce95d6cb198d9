#!/usr/bin/env python3
"""Write the everyday impact decks of issue 32 (examples/impacts/<name>/<name>.inp, with
<name>.json beside each: the bodies and measures tests/stress/impact_check.py reads).

Every deck uses the defaults a new user would: `*CONTACT`, `*CONTACT INCLUSIONS, ALL
EXTERIOR` (self contact included), no penalty, no `*SECTION CONTROLS` (the default hourglass
form), no `*BULK VISCOSITY`. Units m, kg, s, N, Pa. Materials (tests/stress/impact_scenes.py):
steel E = 200 GPa, nu = 0.3, rho = 7850, yield 300 MPa + 500 MPa per unit plastic strain;
aluminium 70 GPa, 0.33, 2700, 150 MPa + 300 MPa; copper (Wilkins-Guinan) 117 GPa, 0.35, 8930,
400 MPa + 100 MPa.

The five impacts of the issue (its "hourglass energy" paragraph):
  block_oblique     aluminium block 20 x 20 x 10 mm (8 x 8 x 4 C3D8R) onto a rigid plate
                    at 100 m/s, 30 degrees from the plate's normal
  box_drop          closed S4R steel box, 100 mm, t = 1 mm (10 x 10 per face), dropped
                    corner first at 10 m/s onto a rigid floor
  rod_plate         rigid rod (R = 5 mm, C3D8R) driven by *BOUNDARY, TYPE=VELOCITY at 40 m/s
                    from t = 0 (no initial velocity: an impulsive start) into a clamped S4R
                    steel plate 100 x 100 x 2 mm (20 x 20)
  blocks_offset     plastic steel cubes of 20 mm, 6^3 and 5^3 C3D8R (non-matching), one at
                    150 m/s onto the other at rest, offset by 6 and 4 mm sideways
  tube_crush_hex    aluminium tube of C3D8R (outer R = 20 mm, t = 2 mm, 60 mm long; 32 around,
                    2 through the wall, 20 along) on a fixed rigid base, crushed by a rigid
                    plate driven at 20 m/s (initial velocity and velocity BC alike)
The Taylor bar (Wilkins and Guinan: copper, L0 = 32.4 mm, R0 = 3.2 mm, 227 m/s, final length
21.45 mm) as a full 360-degree model (the O-grid of examples/plasticity/make_taylor_bar.py
turned four times: 84 quads per section, 40 along, 3360 C3D8R), 10 um above the plate, 80 us:
  taylor_wall       the reference: U3 = 0 on the impact face (no contact), as the example
  taylor_rigid      onto a rigid plate (C3D8R, 24 x 24 x 4 mm, its reference node held)
  taylor_steel      onto an elastic steel plate (24 x 24 x 8 mm, 12 x 12 x 4 C3D8R) held at
                    its back face
  taylor_rigid_rot37, taylor_steel_rot37   the same, the whole scene turned by 37 degrees
                    about (1, 2, 3)
Plastic steel blocks meeting at a closing speed of 600, 1000, 2000, 3000 m/s (each at half of
it): 10 mm cubes of 4^3 and 5^3 C3D8R, 50 um apart, 30 us:
  blocks_600, blocks_1000, blocks_2000, blocks_3000

Usage: python3 examples/impacts/make_impact_decks.py [OUT_DIR] [--only NAME | --all]
(default OUT_DIR: examples/impacts; standard library only). Without --only or --all it writes
the decks kept in the repository (all but the Taylor bars, 450 KB each); write those into a
folder of your own (`--only taylor_rigid build/impacts`, or `--all build/impacts`, as the
test does): a deck left under examples/ joins the regression suite's list
(tests/regression/decks.txt).
"""

import argparse
import json
import math
import pathlib
import sys

HERE = pathlib.Path(__file__).resolve().parent
REPO = HERE.parent.parent
sys.path.insert(0, str(REPO / "tests" / "stress"))
sys.path.insert(0, str(REPO / "examples" / "plasticity"))
import impact_scenes as sc  # noqa: E402
import make_taylor_bar  # noqa: E402

BASES = (100000, 200000, 300000)

TAYLOR_SPEED = 227.0
TAYLOR_GAP = 10e-6
TAYLOR_PERIOD = 80e-6
TAYLOR_AXIS = (1.0, 2.0, 3.0)
TAYLOR_TURN = 37.0  # degrees
TAYLOR_REFERENCE_LENGTH = 21.45e-3  # Wilkins and Guinan


# ---------------------------------------------------------------------------------------------
# Bodies the scenes do not have: cylinders (O-grid) and tubes


def full_section(n, m, radius):
    """The O-grid of make_taylor_bar.py (a quarter section) turned four times about the axis:
    points (x, y) and quads (counter-clockwise) of the whole circle of `radius`."""
    points, quads = make_taylor_bar.section_points(n, m)
    factor = radius / make_taylor_bar.RADIUS
    merged, index, out = [], {}, []
    for turn in range(4):
        c, s = (1, 0, -1, 0)[turn], (0, 1, 0, -1)[turn]
        local = []
        for x, y in points:
            p = (factor * (c * x - s * y), factor * (s * x + c * y))
            key = (round(p[0] / radius * 1e9), round(p[1] / radius * 1e9))
            if key not in index:
                index[key] = len(merged)
                merged.append(p)
            local.append(index[key])
        out += [[local[q] for q in quad] for quad in quads]
    return merged, out


def cylinder(name, radius, length, n, m, nz):
    """Solid cylinder of C3D8R along z from 0 to `length`; `back` = the face z = 0."""
    body = sc.Body(name, "solid")
    section, quads = full_section(n, m, radius)
    per_layer = len(section)
    for k in range(nz + 1):
        body.points += [(x, y, length * k / nz) for x, y in section]
    for k in range(nz):
        for q in quads:
            body.elements.append(("C3D8R", [per_layer * k + v for v in q]
                                  + [per_layer * (k + 1) + v for v in q]))
    body.back = list(range(per_layer))
    return body


def tube(name, outer, thickness, length, around, through, along):
    """Circular tube of C3D8R along z from 0 to `length`; `back` = the end z = 0."""
    body = sc.Body(name, "solid")
    index = {}
    for k in range(along + 1):
        for j in range(through + 1):
            r = outer - thickness + thickness * j / through
            for i in range(around):
                a = 2.0 * math.pi * i / around
                index[(i, j, k)] = len(body.points)
                body.points.append((r * math.cos(a), r * math.sin(a), length * k / along))
    for k in range(along):
        for j in range(through):
            for i in range(around):
                face = [(i, j, k), (i, j + 1, k), ((i + 1) % around, j + 1, k),
                        ((i + 1) % around, j, k)]
                lower = [index[f] for f in face]
                upper = [index[(a, b, c + 1)] for a, b, c in face]
                body.elements.append(("C3D8R", lower + upper))
    body.back = [index[(i, j, 0)] for j in range(through + 1) for i in range(around)]
    return body


def hex_slab(name, size, counts, top=0.0):
    """Block of C3D8R with its top face at z = top, centred on the axis; back = bottom."""
    body = sc.solid_block(name, size, counts, "C3D8R")
    body.moved(shift=(0.0, 0.0, top - 0.5 * size[2]))
    return body


def element_size(body):
    """Shortest element edge over all edges of each element (cylinders are not boxes)."""
    size = math.inf
    for kind, nodes in body.elements:
        ring = nodes[:4]
        pairs = [(ring[i], ring[(i + 1) % 4]) for i in range(4)]
        if kind != "S4R":
            pairs += [(nodes[i], nodes[i + 4]) for i in range(4)]
        for a, b in pairs:
            size = min(size, sc.norm(sc.sub(body.points[a], body.points[b])))
    return size


# ---------------------------------------------------------------------------------------------
# Decks


def finish(name, parts, heading, comments, period, pair, normal, speed, target_thickness,
           extra=None, history=()):
    text, bodies = sc.deck_lines(parts, heading, ["Generated by examples/impacts/"
                                                  "make_impact_decks.py; edit the generator, "
                                                  "not this file. Units m, kg, s, N, Pa."]
                                 + comments, period, history)
    for part in parts:
        bodies[part.body.name]["element_size"] = element_size(part.body)
    meta = {"id": name, "class": name, "bodies": bodies, "pair": pair, "normal": list(normal),
            "period": period, "speed": speed, "target_thickness": target_thickness}
    meta.update(extra or {})
    return text, meta


def block_oblique():
    speed, angle = 100.0, math.radians(30.0)
    block = sc.solid_block("BLOCK", (20e-3, 20e-3, 10e-3), (8, 8, 4), "C3D8R")
    block.moved(shift=(0.0, 0.0, 5e-3 + 0.1e-3))
    plate = hex_slab("PLATE", (60e-3, 60e-3, 5e-3), (6, 6, 1))
    velocity = (speed * math.sin(angle), 0.0, -speed * math.cos(angle))
    parts = [sc.Part(block, BASES[0], "ALUMINIUM", plastic=True, velocity=velocity),
             sc.Part(plate, BASES[1], "STEEL", rigid=True, hold="ref")]
    return finish("block_oblique", parts, "Aluminium block onto a rigid plate at 100 m/s, 30 "
                  "degrees from the normal",
                  ["Block 20 x 20 x 10 mm, 8 x 8 x 4 C3D8R, 0.1 mm above the plate; rigid plate "
                   "60 x 60 x 5 mm (6 x 6 x 1 C3D8R), reference node held."],
                  80e-6, ["BLOCK", "PLATE"], (0, 0, 1), speed, 5e-3)


def box_drop():
    speed, side, t = 10.0, 100e-3, 1e-3
    box = sc.shell_box("BOX", (side, side, side), (10, 10, 10), t)
    down = sc.unit((-1.0, -1.0, -1.0))
    axis = sc.cross(down, (0.0, 0.0, -1.0))
    box.moved(sc.rotation(axis, math.acos(sc.dot(down, (0.0, 0.0, -1.0)))))
    lowest = min(p[2] for p in box.points) - 0.5 * t
    box.moved(shift=(0.0, 0.0, 0.5e-3 - lowest))
    floor = hex_slab("FLOOR", (300e-3, 300e-3, 10e-3), (6, 6, 1))
    parts = [sc.Part(box, BASES[0], "STEEL", plastic=True, velocity=(0.0, 0.0, -speed)),
             sc.Part(floor, BASES[1], "STEEL", rigid=True, hold="ref")]
    return finish("box_drop", parts, "S4R steel box dropped corner first onto a rigid floor "
                  "at 10 m/s",
                  ["Box 100 mm (mid-surface), t = 1 mm, 10 x 10 S4R per face, its body diagonal "
                   "vertical, lowest corner 0.5 mm above the floor (shell face); floor 300 x 300 "
                   "x 10 mm, 6 x 6 x 1 C3D8R, rigid, reference node held."],
                  3e-3, ["BOX", "FLOOR"], (0, 0, 1), speed, 10e-3)


def rod_plate():
    speed, t = 40.0, 2e-3
    rod = cylinder("ROD", 5e-3, 40e-3, 2, 2, 8)
    rod.moved(shift=(0.0, 0.0, 0.5 * t + 1e-3))
    plate = sc.shell_plate("PLATE", (100e-3, 100e-3), (20, 20), t)
    parts = [sc.Part(rod, BASES[0], "STEEL", rigid=True, hold=(0.0, 0.0, -speed)),
             sc.Part(plate, BASES[1], "STEEL", plastic=True, hold="back")]
    return finish("rod_plate", parts, "Rigid rod driven at 40 m/s into a clamped S4R steel plate",
                  ["Rod R = 5 mm, 40 mm long, flat end 1 mm above the plate's upper face, C3D8R "
                   "under *RIGID BODY; its reference node driven by *BOUNDARY, TYPE=VELOCITY "
                   "U3 = -40 m/s from t = 0 (no initial velocity: the start is impulsive).",
                   "Plate 100 x 100 mm, t = 2 mm, 20 x 20 S4R, edges ENCASTRE, plastic steel."],
                  0.5e-3, ["ROD", "PLATE"], (0, 0, 1), speed, t)


def blocks_offset():
    speed = 150.0
    a = sc.solid_block("BLOCK_A", (20e-3, 20e-3, 20e-3), (6, 6, 6), "C3D8R")
    a.moved(shift=(6e-3, 4e-3, 10e-3 + 0.1e-3))
    b = hex_slab("BLOCK_B", (20e-3, 20e-3, 20e-3), (5, 5, 5))
    parts = [sc.Part(a, BASES[0], "STEEL", plastic=True, velocity=(0.0, 0.0, -speed)),
             sc.Part(b, BASES[1], "STEEL", plastic=True)]
    return finish("blocks_offset", parts, "Plastic steel blocks, non-matching meshes, offset, "
                  "at 150 m/s",
                  ["Cubes of 20 mm: A 6 x 6 x 6 C3D8R at 150 m/s (-z), 0.1 mm above B (5 x 5 x 5, "
                   "at rest), A offset by (6, 4) mm sideways; both free."],
                  60e-6, ["BLOCK_A", "BLOCK_B"], (0, 0, 1), speed, 20e-3)


def tube_crush_hex():
    speed, length = 20.0, 60e-3
    body = tube("TUBE", 20e-3, 2e-3, length, 32, 2, 20)
    body.moved(shift=(0.0, 0.0, 10e-6))
    base = hex_slab("BASE", (60e-3, 60e-3, 5e-3), (6, 6, 1))
    top = hex_slab("TOP", (60e-3, 60e-3, 5e-3), (6, 6, 1), top=length + 10e-6 + 0.5e-3 + 5e-3)
    velocity = (0.0, 0.0, -speed)
    parts = [sc.Part(body, BASES[0], "ALUMINIUM", plastic=True),
             sc.Part(base, BASES[1], "STEEL", rigid=True, hold="ref"),
             sc.Part(top, BASES[2], "STEEL", rigid=True, velocity=velocity, hold=velocity)]
    return finish("tube_crush_hex", parts, "C3D8R aluminium tube crushed by a rigid plate at "
                  "20 m/s",
                  ["Tube: outer radius 20 mm, wall 2 mm, 60 mm long; 32 around, 2 through the "
                   "wall, 20 along (1280 C3D8R); 10 um above the rigid base (reference node "
                   "held).",
                   "Top plate (rigid) 0.5 mm above the tube, initial velocity and *BOUNDARY, "
                   "TYPE=VELOCITY of -20 m/s on its reference node: 17.5 mm of crush in 0.9 ms."],
                  0.9e-3, ["TOP", "TUBE"], (0, 0, 1), speed, 2e-3,
                  history=[("TOP_REF", "U3, RF3"), ("BASE_REF", "RF3")])


def taylor(plate_kind, turned):
    """The full Taylor bar onto a rigid or steel plate ("wall": U3 = 0, no plate, no contact)."""
    name = f"taylor_{plate_kind}" + ("_rot37" if turned else "")
    bar = cylinder("BAR", make_taylor_bar.RADIUS, make_taylor_bar.LENGTH, 3, 2, 40)
    gap = 0.0 if plate_kind == "wall" else TAYLOR_GAP
    bar.moved(shift=(0.0, 0.0, gap))
    velocity = (0.0, 0.0, -TAYLOR_SPEED)
    top_nodes = [i for i, p in enumerate(bar.points)
                 if abs(p[2] - gap - make_taylor_bar.LENGTH) < 1e-9]
    face_nodes = list(bar.back)
    parts = [sc.Part(bar, BASES[0], "COPPER", plastic=True, velocity=velocity)]
    if plate_kind == "rigid":
        plate = hex_slab("PLATE", (24e-3, 24e-3, 4e-3), (8, 8, 1))
        parts.append(sc.Part(plate, BASES[1], "STEEL", rigid=True, hold="ref"))
        plate_text = "a rigid plate 24 x 24 x 4 mm (8 x 8 x 1 C3D8R, reference node held)"
    elif plate_kind == "steel":
        plate = hex_slab("PLATE", (24e-3, 24e-3, 8e-3), (12, 12, 4))
        parts.append(sc.Part(plate, BASES[1], "STEEL", hold="back"))
        plate_text = "an elastic steel plate 24 x 24 x 8 mm (12 x 12 x 4 C3D8R) held at its back"
    else:
        plate_text = "a wall: U3 = 0 on the impact face (no contact), as examples/plasticity"
    axis, origin = (0.0, 0.0, 1.0), (0.0, 0.0, 0.0)
    if turned:
        turn = sc.rotation(TAYLOR_AXIS, math.radians(TAYLOR_TURN))
        for part in parts:
            part.body.moved(turn)
        velocity = sc.apply(turn, velocity)
        parts[0].velocity = velocity
        axis = sc.apply(turn, axis)
    comments = [f"Wilkins-Guinan copper bar, L0 = 32.4 mm, R0 = 3.2 mm, at 227 m/s onto "
                f"{plate_text}; full 360-degree model: 84 C3D8R per section (O-grid), 40 "
                f"along; final length 21.45 mm (Wilkins and Guinan)."]
    if turned:
        comments.append("The whole scene turned by 37 degrees about (1, 2, 3).")
    extra = {"taylor": {"axis": list(axis), "origin": list(origin),
                        "top_nodes": [BASES[0] + 1 + i for i in top_nodes],
                        "face_nodes": [BASES[0] + 1 + i for i in face_nodes],
                        "reference_length": TAYLOR_REFERENCE_LENGTH}}
    if plate_kind == "wall":
        text, meta = wall_deck(parts[0], comments)
        meta.update(extra)
        return text, meta
    return finish(name, parts, f"Taylor bar onto {plate_kind} plate" + (", turned" if turned
                                                                       else ""),
                  comments, TAYLOR_PERIOD + gap / TAYLOR_SPEED, ["BAR", "PLATE"], axis,
                  TAYLOR_SPEED, 4e-3 if plate_kind == "rigid" else 8e-3,
                  extra)


def wall_deck(part, comments):
    """The U3 = 0 reference: the bar's impact face held in z, the other nodes moving."""
    text, meta = finish("taylor_wall", [part], "Taylor bar onto a U3 = 0 wall (reference)",
                        comments, TAYLOR_PERIOD, [], (0, 0, 1), TAYLOR_SPEED, None)
    face = sorted(part.base + 1 + i for i in part.body.back)
    moving = sorted(set(range(part.base + 1, part.base + 1 + len(part.body.points))) - set(face))
    lines = text.splitlines()
    # Initial velocity on the moving nodes only (a held DOF given a velocity would jump).
    i = lines.index("*INITIAL CONDITIONS, TYPE=VELOCITY")
    lines[i + 1:i + 4] = ["BAR_MOVING, 3, " + sc.num(-TAYLOR_SPEED)]
    lines[i:i] = ["*NSET, NSET=BAR_FACE"] + sc.id_lines(face) + ["*NSET, NSET=BAR_MOVING"] \
        + sc.id_lines(moving)
    j = lines.index("*CONTACT")
    lines[j:j + 2] = ["*BOUNDARY", "BAR_FACE, 3, 3"]
    meta["pair"] = None
    return "\n".join(lines) + "\n", meta


def fast_blocks(speed):
    a = sc.solid_block("BLOCK_A", (10e-3, 10e-3, 10e-3), (4, 4, 4), "C3D8R")
    a.moved(shift=(0.0, 0.0, 5e-3 + 50e-6))
    b = hex_slab("BLOCK_B", (10e-3, 10e-3, 10e-3), (5, 5, 5))
    parts = [sc.Part(a, BASES[0], "STEEL", plastic=True, velocity=(0.0, 0.0, -0.5 * speed)),
             sc.Part(b, BASES[1], "STEEL", plastic=True, velocity=(0.0, 0.0, 0.5 * speed))]
    return finish(f"blocks_{speed}", parts, f"Plastic steel blocks meeting at {speed} m/s",
                  [f"Cubes of 10 mm, A 4 x 4 x 4 C3D8R at {0.5 * speed:g} m/s (-z), B 5 x 5 x 5 "
                   f"at {0.5 * speed:g} m/s (+z), 50 um apart, aligned; both free."],
                  30e-6, ["BLOCK_A", "BLOCK_B"], (0, 0, 1), speed, 10e-3)


DECKS = {
    "block_oblique": block_oblique,
    "box_drop": box_drop,
    "rod_plate": rod_plate,
    "blocks_offset": blocks_offset,
    "tube_crush_hex": tube_crush_hex,
    "taylor_wall": lambda: taylor("wall", False),
    "taylor_rigid": lambda: taylor("rigid", False),
    "taylor_steel": lambda: taylor("steel", False),
    "taylor_rigid_rot37": lambda: taylor("rigid", True),
    "taylor_steel_rot37": lambda: taylor("steel", True),
    "blocks_600": lambda: fast_blocks(600),
    "blocks_1000": lambda: fast_blocks(1000),
    "blocks_2000": lambda: fast_blocks(2000),
    "blocks_3000": lambda: fast_blocks(3000),
}


def write(name, out_dir):
    text, meta = DECKS[name]()
    folder = pathlib.Path(out_dir) / name
    folder.mkdir(parents=True, exist_ok=True)
    deck = folder / f"{name}.inp"
    deck.write_text(text)
    (folder / f"{name}.json").write_text(json.dumps(meta, indent=1) + "\n")
    return deck


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("out", nargs="?", default=str(HERE))
    parser.add_argument("--only", choices=sorted(DECKS))
    parser.add_argument("--all", action="store_true", help="the Taylor bars too")
    args = parser.parse_args()
    names = [args.only] if args.only else [n for n in DECKS
                                           if args.all or not n.startswith("taylor_")]
    for name in names:
        print(write(name, args.out))


if __name__ == "__main__":
    main()
