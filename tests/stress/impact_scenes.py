#!/usr/bin/python3
"""Impact scenes for the stress test of issue 32, item 7 (SPEC R6): seeded, coarse, default
general contact.

A scene is one projectile hitting one target, written as a deck with everything a new user
would leave at its default: `*CONTACT`, `*CONTACT INCLUSIONS, ALL EXTERIOR`, no penalty, no
`*SECTION CONTROLS`, no `*BULK VISCOSITY`. Scene `ID` is drawn from `random.Random(ID)`, so a
deck is the same on every machine and Python version (integer seeds; only `random()`,
`uniform()` and `choice()` are used).

Class of scene `ID`: CLASSES[ID % 16], written `projectile-target-support`:
  projectile  solid   block of C3D8R (a quarter of the scenes C3D8), 2-6 elements across
              shell   closed box of S4R, 2-6 elements along each edge
              rigid   block of C3D8R under *RIGID BODY, free, moving
  target      solid   slab of C3D8R / C3D8, 3-6 elements across, 2-3 through the thickness
              shell   square S4R plate, 3-6 elements across
  support     free    the target floats (deformable, at rest)
              fixed   the target is deformable and held: the slab's back face (U1-U3 = 0) or
                      the plate's edges (ENCASTRE)
              rigid   the target is a *RIGID BODY with its reference node held (1-6 = 0)
(a rigid projectile against a rigid target is left out: 16 classes.)

Each deformable body is elastic or elastic-plastic (*PLASTIC, linear hardening); materials
steel, aluminium, copper. Speed 1-300 m/s (log-uniform), oblique (0-60 degrees from the
target's normal, a third of the scenes head-on), the projectile tilted (up to 45 degrees
about a random axis, a third of them flat), the whole scene turned by a random rotation
(four scenes in five), a lateral offset, a gap closed in at most two wave transits. The step
lasts the gap's closing time plus a contact time: the time the projectile needs to travel its
own size, held between 20 and 200 wave transits of it (the rebound of a slow elastic impact,
the crush of a fast plastic one, and what follows: about 100-3000 increments).

Usage (/usr/bin/python3, standard library only):
  impact_scenes.py deck ID [--out DIR]   write DIR/scene_ID/scene_ID.inp and scene_ID.json
                                          (the scene's metadata, read by impact_check.py);
                                          prints the deck path
  impact_scenes.py list FIRST COUNT      one line per scene: id, class, speed, angle, ...
Units m, kg, s, N, Pa.
"""

import argparse
import json
import math
import pathlib
import random
import sys

MATERIALS = {
    # name: density, Young's modulus, Poisson's ratio, yield stress, hardening (Pa per unit
    # plastic strain; linear, a two-point *PLASTIC table)
    "STEEL": (7850.0, 200.0e9, 0.30, 300.0e6, 500.0e6),
    "ALUMINIUM": (2700.0, 70.0e9, 0.33, 150.0e6, 300.0e6),
    "COPPER": (8930.0, 117.0e9, 0.35, 400.0e6, 100.0e6),
}
TABLE_END_STRAIN = 10.0  # the hardening stays linear far beyond any strain reached

PROJECTILES = ("solid", "shell", "rigid")
TARGETS = ("solid", "shell")
SUPPORTS = ("free", "fixed", "rigid")
CLASSES = tuple(f"{p}-{t}-{s}" for p in PROJECTILES for t in TARGETS for s in SUPPORTS
                if not (p == "rigid" and s == "rigid"))

SPEED_RANGE = (1.0, 300.0)  # m/s
HISTORY_ROWS = 100
FIELD_FRAMES = 4


# ---------------------------------------------------------------------------------------------
# Small vector helpers (tuples of three floats)


def add(a, b):
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def scale(a, s):
    return (a[0] * s, a[1] * s, a[2] * s)


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def norm(a):
    return math.sqrt(dot(a, a))


def unit(a):
    return scale(a, 1.0 / norm(a))


def rotation(axis, angle):
    """Rows of the rotation matrix by `angle` (rad) about `axis` (Rodrigues)."""
    x, y, z = unit(axis)
    c, s = math.cos(angle), math.sin(angle)
    t = 1.0 - c
    return ((t * x * x + c, t * x * y - s * z, t * x * z + s * y),
            (t * x * y + s * z, t * y * y + c, t * y * z - s * x),
            (t * x * z - s * y, t * y * z + s * x, t * z * z + c))


def apply(matrix, v):
    return tuple(dot(row, v) for row in matrix)


def random_axis(rng):
    """A direction uniformly distributed on the sphere."""
    z = rng.uniform(-1.0, 1.0)
    phi = rng.uniform(0.0, 2.0 * math.pi)
    r = math.sqrt(max(0.0, 1.0 - z * z))
    return (r * math.cos(phi), r * math.sin(phi), z)


def num(x):
    return f"{x:.12g}"


# ---------------------------------------------------------------------------------------------
# Bodies: nodes (local index -> point), elements (type, local node indices)


class Body:
    """One part of a scene: its nodes and elements with local indices, placed by `moved`."""

    def __init__(self, name, kind):
        self.name = name  # element set name in the deck
        self.kind = kind  # "solid" or "shell"
        self.points = []
        self.elements = []  # (type, [local node indices])
        self.thickness = 0.0  # shells
        self.back = []  # local indices of the nodes a "fixed" support holds

    def moved(self, matrix=None, shift=(0.0, 0.0, 0.0)):
        if matrix is not None:
            self.points = [apply(matrix, p) for p in self.points]
        self.points = [add(p, shift) for p in self.points]

    def element_size(self):
        """Shortest element edge, m (the mesh is made of boxes: edges 0-1, 0-3, 0-4)."""
        size = math.inf
        for kind, nodes in self.elements:
            pairs = ((0, 1), (0, 3)) if kind == "S4R" else ((0, 1), (0, 3), (0, 4))
            for a, b in pairs:
                size = min(size, norm(sub(self.points[nodes[a]], self.points[nodes[b]])))
        return size

    def centroid(self):
        n = len(self.points)
        return tuple(sum(p[i] for p in self.points) / n for i in range(3))


def solid_block(name, size, counts, element_type):
    """Box of size (lx, ly, lz) centred at the origin, counts (nx, ny, nz) hexes."""
    body = Body(name, "solid")
    nx, ny, nz = counts
    index = {}
    for k in range(nz + 1):
        for j in range(ny + 1):
            for i in range(nx + 1):
                index[(i, j, k)] = len(body.points)
                body.points.append(((i / nx - 0.5) * size[0], (j / ny - 0.5) * size[1],
                                    (k / nz - 0.5) * size[2]))
    for k in range(nz):
        for j in range(ny):
            for i in range(nx):
                corners = [(i, j, k), (i + 1, j, k), (i + 1, j + 1, k), (i, j + 1, k)]
                lower = [index[c] for c in corners]
                upper = [index[(a, b, c + 1)] for a, b, c in corners]
                body.elements.append((element_type, lower + upper))
    body.back = [index[(i, j, 0)] for j in range(ny + 1) for i in range(nx + 1)]
    return body


def shell_plate(name, size, counts, thickness):
    """Square S4R plate in the plane z = 0, centred at the origin; `back` = its edge nodes."""
    body = Body(name, "shell")
    body.thickness = thickness
    nx, ny = counts
    index = {}
    for j in range(ny + 1):
        for i in range(nx + 1):
            index[(i, j)] = len(body.points)
            body.points.append(((i / nx - 0.5) * size[0], (j / ny - 0.5) * size[1], 0.0))
    for j in range(ny):
        for i in range(nx):
            body.elements.append(("S4R", [index[(i, j)], index[(i + 1, j)],
                                          index[(i + 1, j + 1)], index[(i, j + 1)]]))
    body.back = [index[(i, j)] for j in range(ny + 1) for i in range(nx + 1)
                 if i in (0, nx) or j in (0, ny)]
    return body


def shell_box(name, size, counts, thickness):
    """Closed box of S4R (mid-surface size (lx, ly, lz), centred at the origin), normals out."""
    body = Body(name, "shell")
    body.thickness = thickness
    nx, ny, nz = counts
    index = {}
    for k in range(nz + 1):
        for j in range(ny + 1):
            for i in range(nx + 1):
                if i in (0, nx) or j in (0, ny) or k in (0, nz):
                    index[(i, j, k)] = len(body.points)
                    body.points.append(((i / nx - 0.5) * size[0], (j / ny - 0.5) * size[1],
                                        (k / nz - 0.5) * size[2]))
    quads = []
    for (a, na), (b, nb), (c, fixed) in (((0, nx), (1, ny), (2, (0, nz))),
                                         ((0, nx), (2, nz), (1, (0, ny))),
                                         ((1, ny), (2, nz), (0, (0, nx)))):
        for level in fixed:
            for u in range(na):
                for w in range(nb):
                    quad = []
                    for du, dw in ((0, 0), (1, 0), (1, 1), (0, 1)):
                        key = [0, 0, 0]
                        key[a], key[b], key[c] = u + du, w + dw, level
                        quad.append(index[tuple(key)])
                    quads.append(quad)
    for quad in quads:
        p = [body.points[q] for q in quad]
        normal = cross(sub(p[2], p[0]), sub(p[3], p[1]))
        centre = scale(add(add(p[0], p[1]), add(p[2], p[3])), 0.25)
        if dot(normal, centre) < 0.0:  # the box is centred at the origin
            quad = quad[::-1]
        body.elements.append(("S4R", quad))
    return body


# ---------------------------------------------------------------------------------------------
# Scenes


def wave_speed(material, kind):
    rho, e, nu = MATERIALS[material][:3]
    if kind == "shell":
        return math.sqrt(e / (rho * (1.0 - nu * nu)))
    return math.sqrt(e * (1.0 - nu) / (rho * (1.0 + nu) * (1.0 - 2.0 * nu)))


def log_uniform(rng, lo, hi):
    return math.exp(rng.uniform(math.log(lo), math.log(hi)))


def draw(scene_id):
    """The scene's parameters, drawn from random.Random(scene_id)."""
    rng = random.Random(scene_id)
    projectile, target, support = CLASSES[scene_id % len(CLASSES)].split("-")
    p = {"id": scene_id, "class": CLASSES[scene_id % len(CLASSES)],
         "projectile": projectile, "target": target, "support": support}
    p["speed"] = log_uniform(rng, *SPEED_RANGE)
    p["angle"] = 0.0 if rng.random() < 1.0 / 3.0 else rng.uniform(5.0, 60.0)  # degrees
    p["azimuth"] = rng.uniform(0.0, 360.0)
    p["tilt"] = 0.0 if rng.random() < 1.0 / 3.0 else rng.uniform(5.0, 45.0)
    p["tilt_axis"] = random_axis(rng)
    p["rotated"] = rng.random() < 0.8
    p["scene_axis"] = random_axis(rng)
    p["scene_angle"] = rng.uniform(0.0, 360.0) if p["rotated"] else 0.0
    # Projectile: 5-20 mm, aspect within 0.6-1.6 of its size
    length = rng.uniform(5e-3, 20e-3)
    p["projectile_size"] = [length * rng.uniform(0.6, 1.6) for _ in range(3)]
    p["projectile_counts"] = [rng.choice((2, 3, 4, 5, 6)) for _ in range(3)]
    p["projectile_material"] = rng.choice(sorted(MATERIALS))
    p["projectile_plastic"] = projectile != "rigid" and rng.random() < 0.5
    p["projectile_element"] = "C3D8" if projectile == "solid" and rng.random() < 0.25 \
        else "C3D8R"
    p["projectile_thickness"] = length * rng.uniform(0.03, 0.1) if projectile == "shell" else 0.0
    # Target: 1.5-3 projectile sizes wide, lateral offset up to a quarter of its width
    width = max(p["projectile_size"]) * rng.uniform(1.5, 3.0)
    p["target_size"] = [width, width * rng.uniform(0.8, 1.25),
                        length * rng.uniform(0.3, 1.0)]
    p["target_counts"] = [rng.choice((3, 4, 5, 6)), rng.choice((3, 4, 5, 6)),
                          rng.choice((2, 3))]
    p["target_material"] = rng.choice(sorted(MATERIALS))
    p["target_plastic"] = support != "rigid" and rng.random() < 0.5
    p["target_element"] = "C3D8" if target == "solid" and rng.random() < 0.25 else "C3D8R"
    p["target_thickness"] = width * rng.uniform(0.02, 0.06) if target == "shell" else 0.0
    p["offset"] = [rng.uniform(-0.25, 0.25) * width, rng.uniform(-0.25, 0.25) * width]
    p["gap_fraction"] = rng.uniform(0.02, 0.3)  # of the projectile's element size
    return p


def build(p):
    """Bodies, velocity, step time and the deck text of the scene with parameters p."""
    # Target: its contact surface at z = 0 (the top face of the slab, the plate's top side).
    if p["target"] == "solid":
        target = solid_block("TARGET", p["target_size"], p["target_counts"], p["target_element"])
        target.moved(shift=(0.0, 0.0, -0.5 * p["target_size"][2]))
        top = 0.0
    else:
        target = shell_plate("TARGET", p["target_size"][:2], p["target_counts"][:2],
                             p["target_thickness"])
        target.moved(shift=(0.0, 0.0, -0.5 * p["target_thickness"]))
        top = 0.0
    # Projectile: tilted about its centre, lowest surface point a gap above the target.
    if p["projectile"] == "shell":
        projectile = shell_box("PROJECTILE", p["projectile_size"], p["projectile_counts"],
                               p["projectile_thickness"])
    else:
        element = "C3D8R" if p["projectile"] == "rigid" else p["projectile_element"]
        projectile = solid_block("PROJECTILE", p["projectile_size"], p["projectile_counts"],
                                 element)
    projectile.moved(rotation(p["tilt_axis"], math.radians(p["tilt"])))
    h = min(projectile.element_size(), target.element_size())
    c_max = max(wave_speed(p["projectile_material"], projectile.kind),
                wave_speed(p["target_material"], target.kind))
    size = max(p["projectile_size"])
    angle, azimuth = math.radians(p["angle"]), math.radians(p["azimuth"])
    velocity = (p["speed"] * math.sin(angle) * math.cos(azimuth),
                p["speed"] * math.sin(angle) * math.sin(azimuth), -p["speed"] * math.cos(angle))
    closing = -velocity[2]
    # The gap: a fraction of the element, but closed within two wave transits at low speed.
    gap = min(p["gap_fraction"] * projectile.element_size(), closing * 2.0 * size / c_max)
    lowest = min(q[2] for q in projectile.points) - 0.5 * projectile.thickness
    projectile.moved(shift=(p["offset"][0], p["offset"][1], top + gap - lowest))
    # Step: the gap's closing time plus the contact time.
    contact_time = min(max(size / p["speed"], 20.0 * size / c_max), 200.0 * size / c_max)
    period = gap / closing + contact_time
    # The whole scene turned about the origin.
    turn = rotation(p["scene_axis"], math.radians(p["scene_angle"]))
    for body in (projectile, target):
        body.moved(turn)
    velocity = apply(turn, velocity)
    normal = apply(turn, (0.0, 0.0, 1.0))  # the target's surface normal, towards the projectile
    return projectile, target, velocity, normal, gap, period, h


def material_lines(name, material, plastic):
    rho, e, nu, yield_stress, hardening = MATERIALS[material]
    lines = [f"*MATERIAL, NAME={name}", "*DENSITY", num(rho), "*ELASTIC", f"{num(e)}, {num(nu)}"]
    if plastic:
        lines += ["*PLASTIC", f"{num(yield_stress)}, 0.",
                  f"{num(yield_stress + hardening * TABLE_END_STRAIN)}, {num(TABLE_END_STRAIN)}"]
    return lines


def id_lines(ids, per_line=12):
    ids = list(ids)
    return [", ".join(str(i) for i in ids[k:k + per_line]) for k in range(0, len(ids), per_line)]


class Part:
    """A body placed in a deck: ids from `base` (nodes base+1..., elements base+1..., reference
    node base+90001), its material, and how it moves or is held.

    hold: None (free), "back" (the body's `back` nodes held: U1-U3, ENCASTRE for shells),
    "ref" (rigid: reference node held, 1-6), or a velocity vector (rigid: the reference node
    driven by *BOUNDARY, TYPE=VELOCITY at that velocity, its rotations held)."""

    def __init__(self, body, base, material, plastic=False, rigid=False, velocity=None,
                 hold=None):
        self.body, self.base = body, base
        self.material, self.plastic, self.rigid = material, plastic, rigid
        self.velocity, self.hold = velocity, hold

    @property
    def ref(self):
        return self.base + 90001


def deck_lines(parts, heading, comments, period, history_nsets=(), frames=FIELD_FRAMES,
               history_rows=HISTORY_ROWS):
    """Deck text of the parts with default general contact, and the bodies' metadata."""
    lines = ["*HEADING", heading] + [f"** {c}" for c in comments]
    meta = {}
    for part in parts:
        body, base = part.body, part.base
        lines.append("*NODE")
        lines += [f"{base + 1 + i}, {num(x)}, {num(y)}, {num(z)}"
                  for i, (x, y, z) in enumerate(body.points)]
        by_type = {}
        for e, (kind, nodes) in enumerate(body.elements):
            by_type.setdefault(kind, []).append((base + 1 + e, nodes))
        for kind, items in sorted(by_type.items()):
            lines.append(f"*ELEMENT, TYPE={kind}, ELSET={body.name}")
            lines += [f"{e}, " + ", ".join(str(base + 1 + n) for n in nodes) for e, nodes in items]
        lines += [f"*NSET, NSET={body.name}_NODES, GENERATE",
                  f"{base + 1}, {base + len(body.points)}, 1"]
        if part.rigid:
            x, y, z = body.centroid()
            lines += ["*NODE", f"{part.ref}, {num(x)}, {num(y)}, {num(z)}",
                      f"*NSET, NSET={body.name}_REF", str(part.ref),
                      f"*RIGID BODY, REF NODE={part.ref}, ELSET={body.name}"]
        if part.hold == "back":
            lines.append(f"*NSET, NSET={body.name}_BACK")
            lines += id_lines(base + 1 + i for i in sorted(body.back))
        meta[body.name] = {"kind": body.kind, "thickness": body.thickness,
                           "element_size": body.element_size(),
                           "nodes": [base + 1, base + len(body.points)], "rigid": part.rigid}
    for part in parts:
        body = part.body
        name = f"{body.name}_{part.material}"
        lines += material_lines(name, part.material, part.plastic)
        if body.kind == "shell":
            lines += [f"*SHELL SECTION, ELSET={body.name}, MATERIAL={name}",
                      f"{num(body.thickness)}, 5"]
        else:
            lines.append(f"*SOLID SECTION, ELSET={body.name}, MATERIAL={name}")
    moving = [p for p in parts if p.velocity is not None]
    if moving:
        lines.append("*INITIAL CONDITIONS, TYPE=VELOCITY")
        for part in moving:
            nsets = [f"{part.body.name}_NODES"] + ([f"{part.body.name}_REF"] if part.rigid else [])
            for nset in nsets:
                lines += [f"{nset}, {dof + 1}, {num(part.velocity[dof])}" for dof in range(3)]
    lines += ["*STEP, NAME=IMPACT", "*DYNAMIC, EXPLICIT", f", {num(period)}"]
    for part in parts:
        name = part.body.name
        if part.hold == "back":
            lines += ["*BOUNDARY", f"{name}_BACK, ENCASTRE" if part.body.kind == "shell"
                      else f"{name}_BACK, 1, 3"]
        elif part.hold == "ref":
            lines += ["*BOUNDARY", f"{name}_REF, 1, 6"]
        elif part.hold is not None:
            lines += ["*BOUNDARY, TYPE=VELOCITY"]
            lines += [f"{name}_REF, {dof + 1}, {dof + 1}, {num(part.hold[dof])}"
                      for dof in range(3)]
            lines += [f"{name}_REF, 4, 6, 0."]
    lines += ["*CONTACT", "*CONTACT INCLUSIONS, ALL EXTERIOR",
              f"*OUTPUT, FIELD, NUMBER INTERVAL={frames}", "*NODE OUTPUT", "U",
              f"*OUTPUT, HISTORY, TIME INTERVAL={num(period / history_rows)}"]
    for nset, variables in history_nsets:
        lines += [f"*NODE OUTPUT, NSET={nset}", variables]
    lines += ["*ENERGY OUTPUT", "*END STEP"]
    return "\n".join(lines) + "\n", meta


def deck_text(p):
    """The deck of scene p and its metadata for the checker."""
    projectile, target, velocity, normal, gap, period, h = build(p)
    parts = [Part(projectile, 100000, p["projectile_material"], p["projectile_plastic"],
                  rigid=p["projectile"] == "rigid", velocity=velocity),
             Part(target, 200000, p["target_material"], p["target_plastic"],
                  rigid=p["support"] == "rigid",
                  hold={"free": None, "fixed": "back", "rigid": "ref"}[p["support"]])]
    heading = (f"Impact stress scene {p['id']}: {p['class']}, {p['speed']:.4g} m/s, "
               f"{p['angle']:.3g} deg from the normal")
    comments = [f"Written by tests/stress/impact_scenes.py (issue 32, item 7); regenerate with: "
                f"impact_scenes.py deck {p['id']}",
                "Parameters: " + json.dumps({k: p[k] for k in (
                    "projectile", "target", "support", "speed", "angle", "tilt", "rotated",
                    "projectile_material", "projectile_plastic", "projectile_element",
                    "target_material", "target_plastic", "target_element")}, sort_keys=True)]
    text, bodies = deck_lines(parts, heading, comments, period)
    meta = {"id": p["id"], "class": p["class"], "parameters": p, "bodies": bodies,
            "pair": ["PROJECTILE", "TARGET"], "velocity": list(velocity),
            "normal": list(normal), "gap": gap, "period": period, "element_size": h,
            "speed": p["speed"], "target_thickness": p["target_thickness"] or p["target_size"][2]}
    return text, meta


def write_scene(scene_id, out_dir):
    """Write OUT/scene_ID/scene_ID.inp and .json; returns the deck path."""
    text, meta = deck_text(draw(scene_id))
    folder = pathlib.Path(out_dir) / f"scene_{scene_id}"
    folder.mkdir(parents=True, exist_ok=True)
    deck = folder / f"scene_{scene_id}.inp"
    deck.write_text(text)
    (folder / f"scene_{scene_id}.json").write_text(json.dumps(meta, indent=1) + "\n")
    return deck


def describe(p):
    plastic = "+".join(k for k in ("projectile", "target") if p[f"{k}_plastic"]) or "elastic"
    return (f"{p['id']:4d}  {p['class']:18s} {p['speed']:7.1f} m/s  {p['angle']:4.1f} deg  "
            f"tilt {p['tilt']:4.1f}  {'rotated' if p['rotated'] else 'aligned'}  "
            f"plastic: {plastic}  {p['projectile_element'] if p['projectile'] == 'solid' else ''}")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    sub_parsers = parser.add_subparsers(dest="command", required=True)
    deck = sub_parsers.add_parser("deck", help="write one scene's deck, print its path")
    deck.add_argument("id", type=int)
    deck.add_argument("--out", default=".", help="output folder (default: .)")
    listing = sub_parsers.add_parser("list", help="describe scenes")
    listing.add_argument("first", type=int)
    listing.add_argument("count", type=int)
    args = parser.parse_args(argv)
    if args.command == "deck":
        print(write_scene(args.id, args.out))
    else:
        for i in range(args.first, args.first + args.count):
            print(describe(draw(i)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
