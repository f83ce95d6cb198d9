#!/usr/bin/env python3
"""Write the general contact acceptance decks (examples/contact/<name>/<name>.inp).

Each deck is a small impact problem with an analytic reference value, written in its
header comments:

  bar_bar          two equal steel bars (nu = 0), one at 10 m/s, ALL EXTERIOR general contact:
                   the velocities are exchanged after 2L/c0 of contact
  bar_bar_pair     the same with *CONTACT INCLUSIONS of the two end faces (balanced views)
  bar_bar_oneway   the same with a model-level *CONTACT PAIR (CalculiX style, one-way)
  bar_wall         one bar against a fixed rigid wall: stress rho*c0*v, rebound at -v
  hertz            elastic sphere on a rigid plane (quarter model): Hertz peak force, duration
  shell_block      hex block dropped on a pinned S4R plate from above (both shell faces are
  shell_block_below  in the contact domain) or from below
  tube_crush       S4R square tube crushed between rigid plates (self contact of the walls)
  friction_block   block sliding on a rigid plate under gravity, friction 0.3: deceleration mu*g
  shell_slide      puck sliding frictionless over a fixed S4R strip with a convex and a concave
                   fold: momentum along each straight part as for frictionless sliding

Units m, kg, s, N, Pa. Every body has its own sparse id range (offsets of 100000), so the
solver has to map ids to rows. Rigid bodies are ordinary C3D8R elements with a section
(mass from the density) under *RIGID BODY, with a reference node of their own.

Standard library only:  python3 examples/contact/make_contact_decks.py [OUT_DIR] [--only NAME]
"""

import argparse
import math
import pathlib

YOUNGS_MODULUS = 200.0e9  # Pa
DENSITY = 7850.0  # kg/m^3
POISSONS_RATIO = 0.3  # STEEL; the bars use STEEL_NU0 (nu = 0, one-dimensional waves)

BODY = 100000  # id offset between bodies
REF_OFFSET = 90001  # a rigid body's reference node: its body offset + this

DEFAULT_OUT = pathlib.Path(__file__).resolve().parent

# Bars (bar_bar, bar_wall)
BAR_LENGTH = 0.100
BAR_SIDE = 0.010
BAR_ELEMENTS = (40, 4, 4)
BAR_GAP = 0.001
BAR_SPEED = 10.0
BAR_PERIOD = 160e-6

# Sphere (hertz)
SPHERE_RADIUS = 0.010
SPHERE_SPEED = 5.0
SPHERE_GAP = 0.1e-3
SPHERE_HALF_FACE = 12  # cubed sphere: elements along half a cube face
SPHERE_LAYERS = 10  # radial element layers between the core and the surface
SPHERE_SURFACE_LAYER = 0.25e-3  # thickness of the outer layer, m
SPHERE_POLE_EDGE = 0.23e-3  # target element edge at the contact pole, m
SPHERE_CORE = 0.5  # core cube half size / R
SPHERE_CORE_INFLATION = 0.45  # 0: flat core faces; 1: spherical core surface

# Shell plate and block (shell_block)
PLATE_SIDE = 0.040
PLATE_THICKNESS = 0.002
PLATE_ELEMENTS = 16
CUBE_SIDE = 0.010
CUBE_ELEMENTS = 4
CUBE_GAP = 0.001
CUBE_SPEED = 5.0
SHELL_BLOCK_PERIOD = 600e-6

# Tube (tube_crush)
TUBE_SIDE = 0.020  # mid-surface
TUBE_THICKNESS = 0.0005
TUBE_LENGTH = 0.060
TUBE_ELEMENT = 0.0025
TUBE_SPEED = 10.0
TUBE_GAP = 0.5e-3  # top plate to the tube's top edge (beyond the half thickness)
TUBE_IMPERFECTION = 0.2  # bulge amplitude / wall thickness
TUBE_HALF_WAVES = 3  # bulge half waves along the length
TUBE_PERIOD = 1.9e-3

# Friction (friction_block)
FRICTION = 0.3
GRAVITY = 9.81
SLIDE_SPEED = 1.0
SLIDE_BLOCK = (0.010, 0.010, 0.005)
SLIDE_ELEMENTS = (2, 2, 1)
FRICTION_PERIOD = 0.020

# Puck sliding over a folded S4R strip (shell_slide)
FOLD_ANGLE = 15.0  # degrees: the strip turns down by this at the convex fold, back at the concave
FOLD_PARTS = ((0.012, 9), (0.006, 5), (0.008, 6))  # (length, S4R) of flat A, slope, flat B
FOLD_SPACING = 0.35  # element lengths vary by +-35 % along each part
FOLD_SKEW = 0.15  # edges across the path lean by up to atan(0.15) = 8.5 deg, none at the folds
FOLD_WIDTH = 0.012
FOLD_WIDTH_ELEMENTS = 6  # edges along the path at y = 0, +-2, +-4 mm
FOLD_THICKNESS = 0.5e-3  # below every element length: see the note in shell_slide()
PUCK_RADIUS = 0.004  # the puck's bottom: facets inscribed in a cylinder (axis y) of this radius
PUCK_ELEMENTS = (5, 2, 2)  # facets of FOLD_ANGLE each; odd: it rests on a facet, not on a node
PUCK_WIDTH = 0.006  # its nodes at y = 0 slide along an edge of the strip, the others do not
PUCK_HEIGHT = 0.0078  # puts its centre of mass close to the cylinder's axis
PUCK_START = -0.008  # x of its lowest facet's centre at t = 0 (convex fold at x = 0)
PUCK_SPEED = 5.0
PUCK_GRAVITY = 1.0e5  # m/s^2 in -z, ramped in over PUCK_RAMP
PUCK_RAMP = 20e-6  # s
PUCK_PAST = 0.0045  # the step ends when the puck is about this far past the concave fold, m


# ---------------------------------------------------------------------------------------------
# Deck text helpers


def num(value):
    return f"{value:.10g}"


def decimal_stride(count):
    """Smallest power of ten strictly greater than count, so ids read as digits."""
    return 10 ** len(str(count))


def data_lines(values, per_line=8):
    values = list(values)
    return [", ".join(str(v) for v in values[i:i + per_line])
            for i in range(0, len(values), per_line)]


def generate_lines(ids):
    """`first, last, step` lines covering the sorted ids (maximal arithmetic runs)."""
    ids = sorted(set(ids))
    lines = []
    i = 0
    while i < len(ids):
        j = i
        step = ids[i + 1] - ids[i] if i + 1 < len(ids) else 1
        while j + 1 < len(ids) and ids[j + 1] - ids[j] == step:
            j += 1
        if j == i:
            step = 1
        lines.append(f"{ids[i]}, {ids[j]}, {step}")
        i = j + 1
    return lines


class Deck:
    """Lines of one deck plus the node coordinates (kept for checks and id collisions)."""

    def __init__(self, name):
        self.name = name
        self.lines = []
        self.coordinates = {}  # node id -> (x, y, z)
        self.element_ids = set()

    def add(self, *lines):
        self.lines.extend(lines)

    def comment(self, *texts):
        self.lines.extend(f"** {t}" if t else "**" for t in texts)

    def nodes(self, items, title=None):
        if title:
            self.comment(title)
        self.add("*NODE")
        for node, (x, y, z) in items:
            assert node not in self.coordinates, f"node {node} defined twice"
            self.coordinates[node] = (x, y, z)
            self.add(f"{node}, {num(x)}, {num(y)}, {num(z)}")

    def elements(self, kind, elset, items):
        self.add(f"*ELEMENT, TYPE={kind}, ELSET={elset}")
        for element, nodes in items:
            assert element not in self.element_ids, f"element {element} defined twice"
            assert all(n in self.coordinates for n in nodes), f"element {element}: undefined node"
            self.element_ids.add(element)
            self.add(f"{element}, " + ", ".join(map(str, nodes)))

    def nset(self, name, ids):
        ids = sorted(set(ids))
        assert ids, f"empty node set {name}"
        assert all(n in self.coordinates for n in ids), f"node set {name}: undefined node"
        self.add(f"*NSET, NSET={name}, GENERATE", *generate_lines(ids))

    def elset(self, name, ids):
        ids = sorted(set(ids))
        assert ids and all(e in self.element_ids for e in ids), f"element set {name}"
        self.add(f"*ELSET, ELSET={name}, GENERATE", *generate_lines(ids))

    def text(self):
        return "\n".join(self.lines) + "\n"


def materials(deck, names=("STEEL",)):
    for name in names:
        nu = 0.0 if name == "STEEL_NU0" else POISSONS_RATIO
        deck.add(f"*MATERIAL, NAME={name}", "*DENSITY", num(DENSITY), "*ELASTIC",
                 f"{num(YOUNGS_MODULUS)}, {num(nu)}")


def rigid_body(deck, name, elset, ref_node, position):
    """Reference node (no element) at `position`, node set NAME_REF, *RIGID BODY."""
    deck.nodes([(ref_node, position)], f"Reference node of the rigid body {elset}.")
    deck.nset(f"{name}_REF", [ref_node])
    deck.add(f"*RIGID BODY, REF NODE={ref_node}, ELSET={elset}")


def output_requests(deck, period, frames, history_nodes, history_rows=400):
    """Field output every period/frames (U, V, S, contact), history ~history_rows rows."""
    deck.add(f"*OUTPUT, FIELD, NUMBER INTERVAL={frames}", "*NODE OUTPUT", "U, V",
             "*ELEMENT OUTPUT", "S", "*CONTACT OUTPUT", "CSTRESS, CSTATUS")
    deck.add(f"*OUTPUT, HISTORY, TIME INTERVAL={num(period / history_rows)}")
    for nset, variables in history_nodes:
        deck.add(f"*NODE OUTPUT, NSET={nset}", variables)
    deck.add("*ENERGY OUTPUT")


def general_contact(deck, inclusions="ALL EXTERIOR", properties=None):
    deck.add("*CONTACT")
    if inclusions == "ALL EXTERIOR":
        deck.add("*CONTACT INCLUSIONS, ALL EXTERIOR")
    else:
        deck.add("*CONTACT INCLUSIONS", inclusions)
    if properties:
        deck.add("*CONTACT PROPERTY ASSIGNMENT", properties)


# ---------------------------------------------------------------------------------------------
# Meshes


class HexGrid:
    """Structured nx × ny × nz box of C3D8R with sparse, readable ids.

    node id    = base + ix + sy*iy + sz*iz,   element id = base + 1 + ex + ty*ey + tz*ez
    (strides are powers of ten, as in examples/make_bar.py).
    """

    def __init__(self, base, origin, size, counts):
        self.base = base
        self.origin, self.size = origin, size
        self.nx, self.ny, self.nz = counts
        self.sy = decimal_stride(self.nx)
        self.sz = self.sy * decimal_stride(self.ny)
        self.ty = decimal_stride(self.nx - 1)
        self.tz = self.ty * decimal_stride(self.ny - 1)
        assert self.node_id(self.nx, self.ny, self.nz) < base + REF_OFFSET
        assert self.element_id(self.nx - 1, self.ny - 1, self.nz - 1) < base + REF_OFFSET

    def node_id(self, ix, iy, iz):
        return self.base + ix + self.sy * iy + self.sz * iz

    def element_id(self, ex, ey, ez):
        return self.base + 1 + ex + self.ty * ey + self.tz * ez

    def point(self, ix, iy, iz):
        (x0, y0, z0), (lx, ly, lz) = self.origin, self.size
        return (x0 + lx * ix / self.nx, y0 + ly * iy / self.ny, z0 + lz * iz / self.nz)

    def node_items(self):
        return [(self.node_id(ix, iy, iz), self.point(ix, iy, iz))
                for iz in range(self.nz + 1) for iy in range(self.ny + 1)
                for ix in range(self.nx + 1)]

    def element_items(self):
        """Abaqus C3D8R order: 1-4 at the lower z counter-clockwise seen from +z, 5-8 above."""
        n = self.node_id
        items = []
        for ez in range(self.nz):
            for ey in range(self.ny):
                for ex in range(self.nx):
                    bottom = [n(ex, ey, ez), n(ex + 1, ey, ez), n(ex + 1, ey + 1, ez),
                              n(ex, ey + 1, ez)]
                    top = [n(ex, ey, ez + 1), n(ex + 1, ey, ez + 1), n(ex + 1, ey + 1, ez + 1),
                           n(ex, ey + 1, ez + 1)]
                    items.append((self.element_id(ex, ey, ez), bottom + top))
        return items

    def count(self):
        return self.nx * self.ny * self.nz

    def nodes_where(self, ix=None, iy=None, iz=None):
        return [self.node_id(i, j, k) for k in range(self.nz + 1) for j in range(self.ny + 1)
                for i in range(self.nx + 1)
                if (ix is None or i == ix) and (iy is None or j == iy) and (iz is None or k == iz)]

    def elements_where(self, ex=None, ey=None, ez=None):
        return [self.element_id(i, j, k) for k in range(self.nz) for j in range(self.ny)
                for i in range(self.nx)
                if (ex is None or i == ex) and (ey is None or j == ey) and (ez is None or k == ez)]

    def write(self, deck, elset, title):
        deck.nodes(self.node_items(), title)
        deck.elements("C3D8R", elset, self.element_items())


def add_hex_grid(deck, elset, title, base, origin, size, counts):
    grid = HexGrid(base, origin, size, counts)
    grid.write(deck, elset, title)
    return grid


def corner_jacobians(points):
    """Triple products of the three edges at each corner of a hex in Abaqus order."""
    def sub(a, b):
        return (a[0] - b[0], a[1] - b[1], a[2] - b[2])

    def det(a, b, c):
        return (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
                + a[2] * (b[0] * c[1] - b[1] * c[0]))

    values = []
    for k in range(4):
        p, nxt, prv = points[k], points[(k + 1) % 4], points[(k + 3) % 4]
        values.append(det(sub(nxt, p), sub(prv, p), sub(points[k + 4], p)))
        p, nxt, prv = points[k + 4], points[(k + 1) % 4 + 4], points[(k + 3) % 4 + 4]
        values.append(det(sub(nxt, p), sub(prv, p), sub(p, points[k])))
    return values


def scaled_jacobians(points):
    """Corner Jacobians divided by the product of the three edge lengths (1 = right angles)."""
    def length(a, b):
        return math.dist(a, b)

    out = []
    jac = corner_jacobians(points)
    for k in range(4):
        p = points[k]
        edges = length(points[(k + 1) % 4], p) * length(points[(k + 3) % 4], p) * \
            length(points[k + 4], p)
        out.append(jac[2 * k] / edges)
        p = points[k + 4]
        edges = length(points[(k + 1) % 4 + 4], p) * length(points[(k + 3) % 4 + 4], p) * \
            length(points[k], p)
        out.append(jac[2 * k + 1] / edges)
    return out


GAUSS = (-1.0 / math.sqrt(3.0), 1.0 / math.sqrt(3.0))
CORNER_SIGNS = ((-1, -1, -1), (1, -1, -1), (1, 1, -1), (-1, 1, -1),
                (-1, -1, 1), (1, -1, 1), (1, 1, 1), (-1, 1, 1))


def hex_volume(points, weight=None):
    """Exact volume of a trilinear hex (2x2x2 Gauss: det J has degree 2 in each variable), or
    the integral over it of `weight`, a function of the point at most linear in each of x, y, z
    (degree 3 in each variable with det J: still exact)."""
    volume = 0.0
    for xi in GAUSS:
        for eta in GAUSS:
            for zeta in GAUSS:
                jac = [[0.0] * 3 for _ in range(3)]
                at = [0.0, 0.0, 0.0]
                for (sx, sy, sz), p in zip(CORNER_SIGNS, points):
                    n = (1 + sx * xi) * (1 + sy * eta) * (1 + sz * zeta) / 8
                    at = [a + n * q for a, q in zip(at, p)]
                    d = (sx * (1 + sy * eta) * (1 + sz * zeta) / 8,
                         sy * (1 + sx * xi) * (1 + sz * zeta) / 8,
                         sz * (1 + sx * xi) * (1 + sy * eta) / 8)
                    for r in range(3):
                        for c in range(3):
                            jac[r][c] += p[r] * d[c]
                det = (jac[0][0] * (jac[1][1] * jac[2][2] - jac[1][2] * jac[2][1])
                       - jac[0][1] * (jac[1][0] * jac[2][2] - jac[1][2] * jac[2][0])
                       + jac[0][2] * (jac[1][0] * jac[2][1] - jac[1][1] * jac[2][0]))
                assert det > 0.0, "negative Jacobian at a Gauss point"
                volume += det if weight is None else det * weight(at)
    return volume


def quarter_sphere_mesh():
    """Quarter (x >= 0, y >= 0) cubed-sphere hex mesh of the whole ball, refined at the pole
    (0, 0, -R).

    Topology: a core block (the cube [0,1] x [0,1] x [-1,1] in lattice coordinates, its
    faces slightly inflated towards the sphere) and four outer blocks on its faces x = 1,
    y = 1, z = -1, z = +1, each a face grid times SPHERE_LAYERS radial layers along rays from
    the centre. Face grids are equiangular; the radial layers grow geometrically from
    SPHERE_SURFACE_LAYER at the surface to the core on every ray. Nodes are keyed by lattice
    indices, so shared nodes are merged exactly and the mesh is conforming.
    Then a smooth, axisymmetric warp pulls the nodes towards the pole along meridians:
    polar angle theta (from -z) -> theta + w(r) (f(theta) - theta), f(theta) =
    theta (kappa + (1 - kappa) theta / pi), w = (r/R)^2; f' > 0 keeps the map orientation
    preserving, kappa sets the pole element edge to SPHERE_POLE_EDGE.

    Returns (points {key: xyz}, hexes [8 keys], info dict).
    """
    n, m = SPHERE_HALF_FACE, SPHERE_LAYERS
    radius, core = SPHERE_RADIUS, SPHERE_CORE * SPHERE_RADIUS
    beta = SPHERE_CORE_INFLATION

    def lattice(index, offset=0):
        return math.tan(math.pi / 4.0 * (index - offset) / n)

    def cube_point(i, j, k):
        return (lattice(i), lattice(j), lattice(k, n))

    def core_point(c):
        norm2 = math.sqrt(c[0] ** 2 + c[1] ** 2 + c[2] ** 2)
        if norm2 == 0.0:
            return (0.0, 0.0, 0.0)
        inf = max(abs(c[0]), abs(c[1]), abs(c[2]))
        t = inf * inf
        scale = core * ((1.0 - beta * t) + beta * t * inf / norm2)
        return (c[0] * scale, c[1] * scale, c[2] * scale)

    def growth(thickness):
        """Ratio q with SPHERE_SURFACE_LAYER (q^m - 1)/(q - 1) = thickness."""
        h0 = SPHERE_SURFACE_LAYER
        assert thickness > m * h0 * 0.5
        lo, hi = 0.5, 3.0
        for _ in range(200):
            q = 0.5 * (lo + hi)
            total = h0 * m if abs(q - 1.0) < 1e-12 else h0 * (q ** m - 1.0) / (q - 1.0)
            lo, hi = (q, hi) if total < thickness else (lo, q)
        return 0.5 * (lo + hi)

    points = {}
    for i in range(n + 1):
        for j in range(n + 1):
            for k in range(2 * n + 1):
                points[(i, j, k, 0)] = core_point(cube_point(i, j, k))

    def on_boundary(i, j, k):
        return i == n or j == n or k == 0 or k == 2 * n

    growth_range = [math.inf, 0.0]
    for (i, j, k, _), inner in list(points.items()):
        if not on_boundary(i, j, k):
            continue
        c = cube_point(i, j, k)
        norm2 = math.sqrt(sum(v * v for v in c))
        d = tuple(v / norm2 for v in c)
        thickness = radius - math.sqrt(sum(v * v for v in inner))
        q = growth(thickness)
        growth_range = [min(growth_range[0], q), max(growth_range[1], q)]
        for layer in range(1, m + 1):
            below = m - layer  # layers between this node and the surface
            depth = SPHERE_SURFACE_LAYER * below if abs(q - 1.0) < 1e-12 else \
                SPHERE_SURFACE_LAYER * (q ** below - 1.0) / (q - 1.0)
            points[(i, j, k, layer)] = tuple((radius - depth) * v for v in d)

    hexes = []

    def brick(key):  # key(a, b, c) for the 8 corners in tensor order
        return [key(0, 0, 0), key(1, 0, 0), key(1, 1, 0), key(0, 1, 0),
                key(0, 0, 1), key(1, 0, 1), key(1, 1, 1), key(0, 1, 1)]

    for i in range(n):
        for j in range(n):
            for k in range(2 * n):
                hexes.append(brick(lambda a, b, c: (i + a, j + b, k + c, 0)))
    for l in range(m):
        for p in range(n):
            for k in range(2 * n):  # face x = 1: axes (y, z, out)
                hexes.append(brick(lambda a, b, c: (n, p + a, k + b, l + c)))
                hexes.append(brick(lambda a, b, c: (p + b, n, k + a, l + c)))  # y = 1: (z, x, out)
            for q in range(n):
                hexes.append(brick(lambda a, b, c: (q + b, p + a, 0, l + c)))  # z = -1: (y, x, out)
                hexes.append(brick(lambda a, b, c: (p + a, q + b, 2 * n, l + c)))  # z = +1

    # Pole warp. The undeformed pole edge is R * (pi/4) / n (equiangular face grid).
    kappa = SPHERE_POLE_EDGE / (radius * math.pi / 4.0 / n)
    assert 0.0 < kappa <= 1.0

    def warp(p):
        x, y, z = p
        r = math.sqrt(x * x + y * y + z * z)
        rho = math.hypot(x, y)
        if rho == 0.0:
            return p
        theta = math.atan2(rho, -z)
        f = theta * (kappa + (1.0 - kappa) * theta / math.pi)
        new_theta = theta + (r / radius) ** 2 * (f - theta)
        scale = r * math.sin(new_theta) / rho
        return (x * scale, y * scale, -r * math.cos(new_theta))

    points = {key: warp(p) for key, p in points.items()}

    # Orientation and quality: every corner Jacobian must be positive.
    min_scaled = math.inf
    for h in range(len(hexes)):
        jac = corner_jacobians([points[key] for key in hexes[h]])
        if all(v < 0.0 for v in jac):
            hexes[h] = hexes[h][4:] + hexes[h][:4]
            jac = corner_jacobians([points[key] for key in hexes[h]])
        assert all(v > 0.0 for v in jac), f"hex {h}: corner Jacobians of mixed sign {jac}"
        min_scaled = min(min_scaled, min(scaled_jacobians([points[key] for key in hexes[h]])))
    # Conforming: every interior face is shared by exactly two hexes, every boundary face
    # lies on the sphere or on a symmetry plane.
    faces = {}
    face_corners = ((0, 1, 2, 3), (4, 7, 6, 5), (0, 4, 5, 1), (1, 5, 6, 2), (2, 6, 7, 3),
                    (3, 7, 4, 0))
    for hexa in hexes:
        for corners in face_corners:
            key = frozenset(hexa[c] for c in corners)
            faces[key] = faces.get(key, 0) + 1
    assert max(faces.values()) == 2
    for key, count in faces.items():
        if count == 1:
            xyz = [points[k] for k in key]
            on_sphere = all(abs(math.dist(p, (0, 0, 0)) - radius) < 1e-12 for p in xyz)
            on_plane = all(abs(p[0]) < 1e-15 for p in xyz) or all(abs(p[1]) < 1e-15 for p in xyz)
            assert on_sphere or on_plane, "open face inside the mesh"

    pole = points[(0, 0, 0, m)]
    assert math.dist(pole, (0.0, 0.0, -radius)) < 1e-15
    pole_edges = [math.dist(pole, points[(1, 0, 0, m)]), math.dist(pole, points[(0, 1, 0, m)]),
                  math.dist(pole, points[(0, 0, 0, m - 1)])]
    volume = sum(hex_volume([points[key] for key in hexa]) for hexa in hexes)
    info = {"kappa": kappa, "growth": growth_range, "min_scaled_jacobian": min_scaled,
            "pole_edges": pole_edges, "volume": volume}
    return points, hexes, info


# ---------------------------------------------------------------------------------------------
# Decks


def header(deck, title, *comments):
    deck.add("*HEADING", title)
    deck.comment("Generated by examples/contact/make_contact_decks.py; edit the generator, not "
                 "this file.", "Units: m, kg, s, N, Pa.", *comments)


def bar_numbers():
    c0 = math.sqrt(YOUNGS_MODULUS / DENSITY)
    return c0, 2.0 * BAR_LENGTH / c0, DENSITY * c0 * BAR_SPEED


def add_bar(deck, name, base, x0, title):
    grid = HexGrid(base, (x0, 0.0, 0.0), (BAR_LENGTH, BAR_SIDE, BAR_SIDE), BAR_ELEMENTS)
    grid.write(deck, name, title)
    return grid


def bar_bar(variant="general"):
    """Two equal bars; variant 'general' (ALL EXTERIOR), 'pair' (*CONTACT INCLUSIONS of the
    end faces) or 'oneway' (model-level *CONTACT PAIR)."""
    name = {"general": "bar_bar", "pair": "bar_bar_pair", "oneway": "bar_bar_oneway"}[variant]
    c0, duration, stress = bar_numbers()
    impact = BAR_GAP / BAR_SPEED
    nx, ny, nz = BAR_ELEMENTS
    deck = Deck(name)
    contact_text = {
        "general": "general contact, *CONTACT INCLUSIONS, ALL EXTERIOR",
        "pair": "general contact, *CONTACT INCLUSIONS A_END, B_END (both views)",
        "oneway": "*CONTACT PAIR (model data, CalculiX style): slave A_END, master B_END",
    }[variant]
    header(deck,
           f"Bar on bar: steel bar A at {BAR_SPEED:g} m/s hits bar B at rest, "
           f"{nx}x{ny}x{nz} C3D8R each, {contact_text}",
           f"Bar A x in [0, {num(BAR_LENGTH)}], bar B x in [{num(BAR_LENGTH + BAR_GAP)}, "
           f"{num(2 * BAR_LENGTH + BAR_GAP)}], {BAR_SIDE * 1e3:g} x {BAR_SIDE * 1e3:g} mm, "
           f"gap {BAR_GAP * 1e3:g} mm, nu = 0, no boundary conditions.",
           f"c0 = sqrt(E/rho) = {c0:.1f} m/s. Impact at t = gap/v = {impact * 1e6:.1f} us; "
           f"contact lasts 2L/c0 = {duration * 1e6:.2f} us",
           f"(separation at t = {(impact + duration) * 1e6:.1f} us); contact stress "
           f"rho*c0*v/2 = {stress / 2e6:.1f} MPa (each bar takes half the velocity jump), "
           f"contact force {stress / 2 * BAR_SIDE ** 2 / 1e3:.2f} kN.",
           f"After separation: bar A at rest, bar B at {BAR_SPEED:g} m/s (equal impedances: "
           f"the velocities are exchanged); kinetic energy "
           f"{0.5 * DENSITY * BAR_LENGTH * BAR_SIDE ** 2 * BAR_SPEED ** 2:.4f} J before and after "
           "(strain energy in between).",
           "History: V1 of A_TAIL (x = 0, the far end of A) and B_TAIL (far end of B): "
           f"A_TAIL stays at {BAR_SPEED:g} m/s until the",
           f"compression wave reaches it at t = {(impact + duration / 2) * 1e6:.1f} us, then 0; "
           f"B_TAIL jumps to {BAR_SPEED:g} m/s at t = {(impact + duration / 2) * 1e6:.1f} us.",
           "Ids: bar A nodes 100000 + ix + 100 iy + 1000 iz, bar B 200000 + ...; elements "
           "base + 1 + ex + 100 ey + 1000 ez.")
    bar_a = add_bar(deck, "A", 1 * BODY, 0.0, "Bar A (moving).")
    bar_b = add_bar(deck, "B", 2 * BODY, BAR_LENGTH + BAR_GAP, "Bar B (at rest).")
    deck.add("*NSET, NSET=A_NODES, ELSET=A")
    deck.nset("A_TAIL", [bar_a.node_id(0, ny // 2, nz // 2)])
    deck.nset("B_TAIL", [bar_b.node_id(nx, ny // 2, nz // 2)])
    deck.comment("End layers at the contact: the x = L face of A is S4, the x = L + gap face "
                 "of B is S6.")
    deck.elset("A_END_LAYER", bar_a.elements_where(ex=nx - 1))
    deck.elset("B_END_LAYER", bar_b.elements_where(ex=0))
    if variant != "general":
        deck.add("*SURFACE, TYPE=ELEMENT, NAME=A_END", "A_END_LAYER, S4",
                 "*SURFACE, TYPE=ELEMENT, NAME=B_END", "B_END_LAYER, S6")
    materials(deck, ("STEEL_NU0",))
    deck.add("*SOLID SECTION, ELSET=A, MATERIAL=STEEL_NU0",
             "*SOLID SECTION, ELSET=B, MATERIAL=STEEL_NU0")
    if variant == "oneway":
        deck.add("*SURFACE INTERACTION, NAME=STEEL",
                 "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=HARD",
                 "*CONTACT PAIR, INTERACTION=STEEL", "A_END, B_END")
    deck.add("*INITIAL CONDITIONS, TYPE=VELOCITY", f"A_NODES, 1, {num(BAR_SPEED)}")
    deck.add("*STEP, NAME=IMPACT", "*DYNAMIC, EXPLICIT", f", {num(BAR_PERIOD)}")
    if variant == "general":
        general_contact(deck)
    elif variant == "pair":
        general_contact(deck, "A_END, B_END")
    output_requests(deck, BAR_PERIOD, 32, [("A_TAIL", "V1"), ("B_TAIL", "V1")])
    deck.add("*END STEP")
    return deck, {"elements": 2 * bar_a.count(), "C3D8R": 2 * bar_a.count()}


def bar_wall():
    c0, duration, stress = bar_numbers()
    impact = BAR_GAP / BAR_SPEED
    nx, ny, nz = BAR_ELEMENTS
    deck = Deck("bar_wall")
    header(deck,
           f"Bar on a rigid wall: steel bar at {BAR_SPEED:g} m/s, {nx}x{ny}x{nz} C3D8R, fixed "
           "rigid C3D8R wall, ALL EXTERIOR general contact",
           f"Bar x in [0, {num(BAR_LENGTH)}], nu = 0; wall face at x = "
           f"{num(BAR_LENGTH + BAR_GAP)} (gap {BAR_GAP * 1e3:g} mm), wall 20 x 20 x 2.5 mm, "
           "4 x 4 x 1 C3D8R, *RIGID BODY, reference node fixed in 6 dofs.",
           f"c0 = {c0:.1f} m/s. Impact at t = {impact * 1e6:.1f} us; contact lasts 2L/c0 = "
           f"{duration * 1e6:.2f} us (release at t = {(impact + duration) * 1e6:.1f} us).",
           f"Contact stress rho*c0*v = {stress / 1e6:.1f} MPa, wall force rho*c0*v*A = "
           f"{stress * BAR_SIDE ** 2 / 1e3:.2f} kN (history RF1 of WALL_REF: "
           f"-{stress * BAR_SIDE ** 2 / 1e3:.2f} kN).",
           f"Rebound: the bar leaves at -{BAR_SPEED:g} m/s with its kinetic energy "
           f"{0.5 * DENSITY * BAR_LENGTH * BAR_SIDE ** 2 * BAR_SPEED ** 2:.4f} J; "
           "A_TAIL (x = 0) reverses at t = "
           f"{(impact + duration / 2) * 1e6:.1f} us.",
           "Ids: bar nodes 100000 + ix + 100 iy + 1000 iz; wall 300000 + ...; wall reference "
           "node 390001.")
    bar = add_bar(deck, "A", 1 * BODY, 0.0, "The bar.")
    thickness = BAR_LENGTH / nx
    wall_origin = (BAR_LENGTH + BAR_GAP, -0.005, -0.005)
    wall = add_hex_grid(deck, "WALL", "The wall (rigid).", 3 * BODY, wall_origin,
                        (thickness, 0.020, 0.020), (1, 4, 4))
    rigid_body(deck, "WALL", "WALL", 3 * BODY + REF_OFFSET,
               (wall_origin[0] + thickness / 2, 0.005, 0.005))
    deck.add("*NSET, NSET=A_NODES, ELSET=A")
    deck.nset("A_TAIL", [bar.node_id(0, ny // 2, nz // 2)])
    deck.nset("A_HEAD", [bar.node_id(nx, ny // 2, nz // 2)])
    deck.elset("A_END_LAYER", bar.elements_where(ex=nx - 1))
    materials(deck, ("STEEL_NU0",))
    deck.add("*SOLID SECTION, ELSET=A, MATERIAL=STEEL_NU0",
             "*SOLID SECTION, ELSET=WALL, MATERIAL=STEEL_NU0")
    deck.add("*INITIAL CONDITIONS, TYPE=VELOCITY", f"A_NODES, 1, {num(BAR_SPEED)}")
    deck.add("*STEP, NAME=IMPACT", "*DYNAMIC, EXPLICIT", f", {num(BAR_PERIOD)}",
             "*BOUNDARY", "WALL_REF, 1, 6")
    general_contact(deck)
    output_requests(deck, BAR_PERIOD, 32,
                    [("A_TAIL", "V1"), ("A_HEAD", "U1, V1"), ("WALL_REF", "RF1")])
    deck.add("*END STEP")
    return deck, {"elements": bar.count() + wall.count(), "C3D8R": bar.count() + wall.count(),
                  "rigid": wall.count()}


def hertz_numbers():
    nu = POISSONS_RATIO
    e_star = YOUNGS_MODULUS / (1.0 - nu * nu)  # sphere on a rigid plane
    mass = 4.0 / 3.0 * math.pi * SPHERE_RADIUS ** 3 * DENSITY
    r, v = SPHERE_RADIUS, SPHERE_SPEED
    delta = (15.0 * mass * v * v / (16.0 * e_star * math.sqrt(r))) ** 0.4
    force = 4.0 / 3.0 * e_star * math.sqrt(r) * delta ** 1.5
    duration = 2.943 * delta / v  # 2 * 1.4716 (integral of the Hertz impact)
    radius = math.sqrt(r * delta)
    pressure = 3.0 * force / (2.0 * math.pi * radius * radius)
    return {"e_star": e_star, "mass": mass, "delta": delta, "force": force,
            "duration": duration, "contact_radius": radius, "pressure": pressure}


def hertz():
    h = hertz_numbers()
    points, hexes, info = quarter_sphere_mesh()
    period = SPHERE_GAP / SPHERE_SPEED + 50e-6
    deck = Deck("hertz")
    keys = sorted(points)
    node_of = {key: BODY + 2 * index + 1 for index, key in enumerate(keys)}  # odd ids
    mesh_mass = info["volume"] * DENSITY * 4.0
    plane_top = -SPHERE_RADIUS - SPHERE_GAP
    c_d = math.sqrt(YOUNGS_MODULUS * (1 - POISSONS_RATIO) /
                    (DENSITY * (1 + POISSONS_RATIO) * (1 - 2 * POISSONS_RATIO)))
    header(deck,
           f"Hertz impact: elastic steel sphere R = {SPHERE_RADIUS * 1e3:g} mm at "
           f"{SPHERE_SPEED:g} m/s on a rigid plane, quarter model, {len(hexes)} C3D8R",
           f"Sphere centre at the origin, pole (first contact) at (0, 0, -R); plane top face "
           f"z = {num(plane_top)} (gap {SPHERE_GAP * 1e3:g} mm), rigid, fixed.",
           "Quarter model x >= 0, y >= 0 of the whole sphere: U1 = 0 on x = 0 (XSYM_NODES), "
           "U2 = 0 on y = 0 (YSYM_NODES).",
           f"E = {YOUNGS_MODULUS:g} Pa, nu = {POISSONS_RATIO:g}, rho = {DENSITY:g}. Hertz "
           f"(sphere on a rigid plane): E* = E/(1 - nu^2) = {h['e_star']:.4g} Pa,",
           f"m = 4/3 pi R^3 rho = {h['mass'] * 1e3:.4f} g (whole sphere; the quarter mesh "
           f"holds {mesh_mass / 4 * 1e3:.4f} g, i.e. {mesh_mass / h['mass'] * 100:.2f} % of "
           "a quarter: facets),",
           f"delta_max = (15 m v^2 / (16 E* sqrt(R)))^(2/5) = {h['delta'] * 1e6:.2f} um,",
           f"F_max = 4/3 E* sqrt(R) delta_max^(3/2) = {h['force'] / 1e3:.2f} kN (whole "
           f"sphere); this quarter model carries F_max/4 = {h['force'] / 4e3:.3f} kN,",
           f"contact time t_c = 2.943 delta_max / v = {h['duration'] * 1e6:.2f} us, contact "
           f"radius a = sqrt(R delta_max) = {h['contact_radius'] * 1e3:.3f} mm, peak pressure "
           f"3F/(2 pi a^2) = {h['pressure'] / 1e9:.2f} GPa.",
           f"First touch at t = gap/v = {SPHERE_GAP / SPHERE_SPEED * 1e6:.1f} us, peak force "
           f"at {(SPHERE_GAP / SPHERE_SPEED + h['duration'] / 2) * 1e6:.1f} us, separation at "
           f"{(SPHERE_GAP / SPHERE_SPEED + h['duration']) * 1e6:.1f} us; rebound at "
           f"{SPHERE_SPEED:g} m/s (elastic).",
           "History: RF3 of PLANE_REF = + the quarter contact force (the sphere pushes the plane "
           "down); U3, V3 of POLE; V3 of TOP (the far pole).",
           f"Mesh: cubed sphere ({SPHERE_HALF_FACE} elements per half cube face, "
           f"{SPHERE_LAYERS} radial layers, outer layer {SPHERE_SURFACE_LAYER * 1e3:g} mm), "
           f"warped towards the pole: pole element edges "
           + ", ".join(f"{e * 1e3:.3f}" for e in info["pole_edges"]) + " mm;",
           f"smallest scaled corner Jacobian {info['min_scaled_jacobian']:.3f}; stable "
           f"increment about 0.9 * {min(info['pole_edges']) * 1e3:.3f} mm / c_d = "
           f"{0.9 * min(info['pole_edges']) / c_d * 1e9:.0f} ns (c_d = {c_d:.0f} m/s).",
           "Ids: sphere nodes and elements 100001, 100003, ... (odd); plane 200000 + ..., "
           "its reference node 290001.")
    deck.nodes([(node_of[key], points[key]) for key in keys], "The sphere.")
    deck.elements("C3D8R", "SPHERE",
                  [(BODY + 2 * index + 1, [node_of[key] for key in hexa])
                   for index, hexa in enumerate(hexes)])
    plane = add_hex_grid(deck, "PLANE",
                         "The plane (rigid): 6 x 6 mm from x, y = -1 mm, so that none of its "
                         "nodes lies on a symmetry plane or inside the contact circle.",
                         2 * BODY, (-0.001, -0.001, plane_top - 0.001), (0.006, 0.006, 0.001),
                         (3, 3, 1))
    rigid_body(deck, "PLANE", "PLANE", 2 * BODY + REF_OFFSET, (0.0, 0.0, plane_top - 0.0005))
    deck.add("*NSET, NSET=SPHERE_NODES, ELSET=SPHERE")
    deck.nset("XSYM_NODES", [node_of[k] for k in keys if points[k][0] == 0.0])
    deck.nset("YSYM_NODES", [node_of[k] for k in keys if points[k][1] == 0.0])
    deck.nset("POLE", [node_of[(0, 0, 0, SPHERE_LAYERS)]])
    deck.nset("TOP", [node_of[(0, 0, 2 * SPHERE_HALF_FACE, SPHERE_LAYERS)]])
    materials(deck)
    deck.add("*SOLID SECTION, ELSET=SPHERE, MATERIAL=STEEL",
             "*SOLID SECTION, ELSET=PLANE, MATERIAL=STEEL")
    deck.add("*INITIAL CONDITIONS, TYPE=VELOCITY", f"SPHERE_NODES, 3, {num(-SPHERE_SPEED)}")
    deck.add("*STEP, NAME=IMPACT", "*DYNAMIC, EXPLICIT", f", {num(period)}",
             "*BOUNDARY", "XSYM_NODES, 1, 1", "YSYM_NODES, 2, 2", "PLANE_REF, 1, 6")
    general_contact(deck)
    output_requests(deck, period, 28, [("PLANE_REF", "RF3"), ("POLE", "U3, V3"), ("TOP", "V3")])
    deck.add("*END STEP")
    return deck, {"elements": len(hexes) + plane.count(), "C3D8R": len(hexes) + plane.count(),
                  "rigid": plane.count(), "sphere": len(hexes), "nodes": len(points),
                  "hertz": h, "mesh": info, "mesh_mass_full": mesh_mass}


def shell_block(from_below=False):
    name = "shell_block_below" if from_below else "shell_block"
    n = PLATE_ELEMENTS
    half = PLATE_SIDE / 2
    side = 1.0 if not from_below else -1.0  # the block's side of the plate
    rigidity = YOUNGS_MODULUS * PLATE_THICKNESS ** 3 / (12 * (1 - POISSONS_RATIO ** 2))
    omega = 2 * math.pi ** 2 / PLATE_SIDE ** 2 * math.sqrt(rigidity / (DENSITY * PLATE_THICKNESS))
    block_mass = DENSITY * CUBE_SIDE ** 3
    plate_mass = DENSITY * PLATE_SIDE ** 2 * PLATE_THICKNESS
    deck = Deck(name)
    header(deck,
           f"Hex block on a shell plate: 10 mm C3D8R cube at {CUBE_SPEED:g} m/s hits a pinned "
           f"S4R plate from {'below' if from_below else 'above'}, ALL EXTERIOR general contact",
           f"Plate {PLATE_SIDE * 1e3:g} x {PLATE_SIDE * 1e3:g} mm, t = "
           f"{PLATE_THICKNESS * 1e3:g} mm, mid-surface z = 0, {n} x {n} S4R, edges U1 = U2 = "
           "U3 = 0. Both shell faces are in the contact domain.",
           f"Block {CUBE_SIDE * 1e3:g} mm cube, {CUBE_ELEMENTS}^3 C3D8R, centred on the plate's "
           f"centre normal, its near face {CUBE_GAP * 1e3:g} mm from the plate's "
           f"{'lower' if from_below else 'upper'} face (z = "
           f"{num(side * (PLATE_THICKNESS / 2 + CUBE_GAP))}), velocity "
           f"{num(-side * CUBE_SPEED)} m/s in z.",
           f"Impact at t = gap/v = {CUBE_GAP / CUBE_SPEED * 1e6:.0f} us (with the shell "
           f"thickness; {(CUBE_GAP + PLATE_THICKNESS / 2) / CUBE_SPEED * 1e6:.0f} us if the "
           "mid-surface were the contact surface).",
           f"The plate must be pushed {'up (+z)' if from_below else 'down (-z)'}: CENTRE U3 "
           f"{'> 0' if from_below else '< 0'}. Block mass {block_mass * 1e3:.3f} g, momentum "
           f"{block_mass * CUBE_SPEED:.5f} kg m/s, kinetic energy "
           f"{0.5 * block_mass * CUBE_SPEED ** 2:.5f} J;",
           f"plate mass {plate_mass * 1e3:.3f} g, first plate frequency (simply supported) "
           f"{omega / 2 / math.pi:.0f} Hz (period {2 * math.pi / omega * 1e6:.0f} us).",
           "Ids: plate nodes 100000 + 1 + i + 100 j, elements the same; block 200000 + ix + "
           "10 iy + 100 iz.")
    plate_nodes = []
    for j in range(n + 1):
        for i in range(n + 1):
            plate_nodes.append((BODY + 1 + i + 100 * j,
                                (-half + PLATE_SIDE * i / n, -half + PLATE_SIDE * j / n, 0.0)))
    deck.nodes(plate_nodes, "The plate.")
    deck.elements("S4R", "PLATE",
                  [(BODY + 1 + i + 100 * j,
                    [BODY + 1 + i + 100 * j, BODY + 2 + i + 100 * j, BODY + 102 + i + 100 * j,
                     BODY + 101 + i + 100 * j]) for j in range(n) for i in range(n)])
    z_near = side * (PLATE_THICKNESS / 2 + CUBE_GAP)
    z0 = z_near if not from_below else z_near - CUBE_SIDE
    cube = add_hex_grid(deck, "BLOCK", "The block.", 2 * BODY,
                        (-CUBE_SIDE / 2, -CUBE_SIDE / 2, z0), (CUBE_SIDE,) * 3,
                        (CUBE_ELEMENTS,) * 3)
    edges = [BODY + 1 + i + 100 * j for j in range(n + 1) for i in range(n + 1)
             if i in (0, n) or j in (0, n)]
    deck.nset("EDGES", edges)
    deck.nset("CENTRE", [BODY + 1 + n // 2 + 100 * (n // 2)])
    c = CUBE_ELEMENTS // 2
    far = CUBE_ELEMENTS if not from_below else 0
    deck.nset("BLOCK_FAR", [cube.node_id(c, c, far)])
    deck.add("*NSET, NSET=BLOCK_NODES, ELSET=BLOCK")
    materials(deck)
    deck.add("*SHELL SECTION, ELSET=PLATE, MATERIAL=STEEL", f"{num(PLATE_THICKNESS)}, 5",
             "*SOLID SECTION, ELSET=BLOCK, MATERIAL=STEEL")
    deck.add("*INITIAL CONDITIONS, TYPE=VELOCITY", f"BLOCK_NODES, 3, {num(-side * CUBE_SPEED)}")
    deck.add("*STEP, NAME=IMPACT", "*DYNAMIC, EXPLICIT", f", {num(SHELL_BLOCK_PERIOD)}",
             "*BOUNDARY", "EDGES, 1, 3")
    general_contact(deck)
    output_requests(deck, SHELL_BLOCK_PERIOD, 30, [("CENTRE", "U3, V3"), ("BLOCK_FAR", "V3")])
    deck.add("*END STEP")
    count = n * n + cube.count()
    return deck, {"elements": count, "S4R": n * n, "C3D8R": cube.count()}


def tube_crush():
    per_side = round(TUBE_SIDE / TUBE_ELEMENT)
    around = 4 * per_side
    along = round(TUBE_LENGTH / TUBE_ELEMENT)
    half = TUBE_SIDE / 2
    amplitude = TUBE_IMPERFECTION * TUBE_THICKNESS
    base_top = -TUBE_THICKNESS / 2
    top_bottom = TUBE_LENGTH + TUBE_THICKNESS / 2 + TUBE_GAP
    crush = TUBE_SPEED * TUBE_PERIOD - TUBE_GAP
    deck = Deck("tube_crush")
    header(deck,
           f"Square tube crush: S4R steel tube {TUBE_SIDE * 1e3:g} x {TUBE_SIDE * 1e3:g} x "
           f"{TUBE_LENGTH * 1e3:g} mm, t = {TUBE_THICKNESS * 1e3:g} mm, between rigid plates, "
           "top plate at 10 m/s, ALL EXTERIOR (self contact)",
           f"Tube mid-surface |x|, |y| = {half * 1e3:g} mm, z in [0, {num(TUBE_LENGTH)}], "
           f"{around} x {along} S4R ({TUBE_ELEMENT * 1e3:g} mm), normals outward; no boundary "
           "conditions on the tube.",
           f"Imperfection: each wall bulges by {TUBE_IMPERFECTION:g} t sin(pi s/b) "
           f"sin({TUBE_HALF_WAVES} pi z/L) along its normal (s along the wall, b its width), "
           "outward on the x walls, inward on the y walls.",
           f"Base plate (rigid, fixed): 40 x 40 x 5 mm, 5 x 5 x 1 C3D8R, top face z = {num(base_top)} "
           "(the tube's lower edge minus half the wall thickness).",
           f"Top plate (rigid): bottom face z = {num(top_bottom)} ({TUBE_GAP * 1e3:g} mm above "
           f"the top edge plus half the thickness); reference node *BOUNDARY, TYPE=VELOCITY "
           f"U3 = {num(-TUBE_SPEED)} m/s, other dofs 0.",
           f"Crush by the end of the step: about {crush * 1e3:.1f} mm = "
           f"{crush / TUBE_LENGTH * 100:.0f} % of the length. Elastic material (no plasticity):"
           " the walls buckle and fold elastically;",
           "checks are qualitative: no wall passes through another (self contact), no node "
           "below the base, energy balance (ETOTAL stays small next to ALLWK).",
           "History: RF3 of BASE_REF (+ crush force) and TOP_REF (- crush force), U3 of TOP_REF.",
           "Ids: tube nodes 100000 + 1 + s + 100 iz (s around, counter-clockwise from "
           "(-b/2, -b/2)), elements the same; base plate 200000 +, top plate 300000 +; "
           "reference nodes 290001, 390001.")

    def ring_point(s):
        """Point s (0 <= s < around) of the mid-surface square, its outward normal, and the
        position along its wall as a fraction of the width."""
        wall, k = divmod(s, per_side)
        f = k / per_side
        corners = [(-half, -half), (half, -half), (half, half), (-half, half)]
        normals = [(0, -1), (1, 0), (0, 1), (-1, 0)]
        (x0, y0), (x1, y1) = corners[wall], corners[(wall + 1) % 4]
        return (x0 + f * (x1 - x0), y0 + f * (y1 - y0)), normals[wall], f

    nodes = []
    for iz in range(along + 1):
        z = TUBE_LENGTH * iz / along
        for s in range(around):
            (x, y), (nx_, ny_), f = ring_point(s)
            sign = 1.0 if nx_ != 0 else -1.0
            w = sign * amplitude * math.sin(math.pi * f) * \
                math.sin(TUBE_HALF_WAVES * math.pi * z / TUBE_LENGTH)
            nodes.append((BODY + 1 + s + 100 * iz, (x + w * nx_, y + w * ny_, z)))
    deck.nodes(nodes, "The tube.")

    def tube_node(s, iz):
        return BODY + 1 + s % around + 100 * iz

    deck.elements("S4R", "TUBE",
                  [(BODY + 1 + s + 100 * iz,
                    [tube_node(s, iz), tube_node(s + 1, iz), tube_node(s + 1, iz + 1),
                     tube_node(s, iz + 1)]) for iz in range(along) for s in range(around)])
    plate = (0.040, 0.040, 0.005)  # thick: a rigid element should not set the increment
    counts = (5, 5, 1)  # 8 mm: no plate node under a wall (|x|, |y| = 10 mm)
    base = add_hex_grid(deck, "BASE", "Base plate (rigid, fixed).", 2 * BODY,
                        (-0.020, -0.020, base_top - plate[2]), plate, counts)
    rigid_body(deck, "BASE", "BASE", 2 * BODY + REF_OFFSET, (0.0, 0.0, base_top - plate[2] / 2))
    top = add_hex_grid(deck, "TOP", "Top plate (rigid, driven).", 3 * BODY,
                       (-0.020, -0.020, top_bottom), plate, counts)
    rigid_body(deck, "TOP", "TOP", 3 * BODY + REF_OFFSET, (0.0, 0.0, top_bottom + plate[2] / 2))
    deck.add("*NSET, NSET=TOP_NODES, ELSET=TOP", "*NSET, NSET=TOP_MOVING", "TOP_NODES, TOP_REF")
    materials(deck)
    # Default section controls (S4R's physical hourglass form).
    deck.add("*SHELL SECTION, ELSET=TUBE, MATERIAL=STEEL",
             f"{num(TUBE_THICKNESS)}, 5",
             "*SOLID SECTION, ELSET=BASE, MATERIAL=STEEL",
             "*SOLID SECTION, ELSET=TOP, MATERIAL=STEEL")
    deck.add("*INITIAL CONDITIONS, TYPE=VELOCITY", f"TOP_MOVING, 3, {num(-TUBE_SPEED)}")
    deck.add("*STEP, NAME=CRUSH", "*DYNAMIC, EXPLICIT", f", {num(TUBE_PERIOD)}",
             "*BOUNDARY", "BASE_REF, 1, 6",
             "*BOUNDARY, TYPE=VELOCITY", "TOP_REF, 1, 2, 0.", f"TOP_REF, 3, 3, {num(-TUBE_SPEED)}",
             "TOP_REF, 4, 6, 0.")
    general_contact(deck)
    output_requests(deck, TUBE_PERIOD, 38,
                    [("BASE_REF", "RF3"), ("TOP_REF", "U3, RF3")])
    deck.add("*END STEP")
    shells = around * along
    return deck, {"elements": shells + base.count() + top.count(), "S4R": shells,
                  "C3D8R": base.count() + top.count(), "rigid": base.count() + top.count()}


def friction_block():
    lx, ly, lz = SLIDE_BLOCK
    mass = DENSITY * lx * ly * lz
    decel = FRICTION * GRAVITY
    stop = SLIDE_SPEED / decel
    t = FRICTION_PERIOD
    v_end = SLIDE_SPEED - decel * t
    slide = SLIDE_SPEED * t - 0.5 * decel * t * t
    h = min(l / c for l, c in zip(SLIDE_BLOCK, SLIDE_ELEMENTS))
    c_d = math.sqrt(YOUNGS_MODULUS / DENSITY)  # nu = 0
    increments = t / (0.9 * h / c_d)
    deck = Deck("friction_block")
    header(deck,
           f"Friction: C3D8R block sliding on a rigid plate at {SLIDE_SPEED:g} m/s under "
           f"gravity, mu = {FRICTION:g} (ALL EXTERIOR, *CONTACT PROPERTY ASSIGNMENT)",
           f"Block {lx * 1e3:g} x {ly * 1e3:g} x {lz * 1e3:g} mm, "
           f"{'x'.join(map(str, SLIDE_ELEMENTS))} C3D8R, nu = 0, its bottom "
           "face exactly on the plate's top face z = 0 (zero gap, no overclosure).",
           f"Initial velocity {SLIDE_SPEED:g} m/s in x; gravity {GRAVITY:g} m/s^2 in -z "
           "(*DLOAD GRAV on BLOCK, applied at t = 0: the normal force rings about m g).",
           f"Sliding: deceleration mu g = {decel:.4f} m/s^2; the block would stop at t = "
           f"v/(mu g) = {stop:.4f} s after {SLIDE_SPEED ** 2 / (2 * decel) * 1e3:.1f} mm.",
           f"The step is only {t * 1e3:g} ms: with {h * 1e3:g} mm elements the stable "
           f"increment is about {0.9 * h / c_d * 1e9:.0f} ns, so {t * 1e3:g} ms takes "
           f"~{increments:.0f} increments",
           "(xpl has no *FIXED MASS SCALING yet). Measure the deceleration as the slope of "
           "the mean V1 of BLOCK_NODES (history) against time:",
           f"at t = {t * 1e3:g} ms v = {v_end:.5f} m/s, slide {slide * 1e3:.4f} mm, frictional "
           f"dissipation ALLFD = mu m g x = {FRICTION * mass * GRAVITY * slide * 1e6:.3f} uJ "
           f"(m = {mass * 1e3:.4f} g).",
           f"Plate reaction (history of PLATE_REF): RF3 = +m g = {mass * GRAVITY * 1e3:.4f} mN "
           f"on average, RF1 = -mu m g = {-FRICTION * mass * GRAVITY * 1e3:.4f} mN while sliding.",
           "The plate is 50 x 30 x 5 mm in 2 x 1 x 1 elements, so no plate node lies under the "
           "block's path.",
           "Ids: block nodes 100000 + ix + 10 iy + 100 iz; plate 200000 +; plate reference "
           "node 290001.")
    block = add_hex_grid(deck, "BLOCK", "The block.", BODY, (0.0, 0.0, 0.0), SLIDE_BLOCK,
                         SLIDE_ELEMENTS)
    plate = add_hex_grid(deck, "PLATE", "The plate (rigid, fixed).", 2 * BODY,
                         (-0.010, -0.010, -0.005), (0.050, 0.030, 0.005), (2, 1, 1))
    rigid_body(deck, "PLATE", "PLATE", 2 * BODY + REF_OFFSET, (0.015, 0.005, -0.0025))
    deck.add("*NSET, NSET=BLOCK_NODES, ELSET=BLOCK")
    # nu = 0: a block one element thick with nu = 0.3 is unstable at the default increment
    # (the one-point hex estimate is not conservative for elements with free corners; see
    # the note on issue 4), and the friction law does not care about nu.
    materials(deck, ("STEEL_NU0",))
    deck.add("*SOLID SECTION, ELSET=BLOCK, MATERIAL=STEEL_NU0",
             "*SOLID SECTION, ELSET=PLATE, MATERIAL=STEEL_NU0")
    deck.add("*SURFACE INTERACTION, NAME=ROUGH", "*FRICTION", num(FRICTION))
    deck.add("*INITIAL CONDITIONS, TYPE=VELOCITY", f"BLOCK_NODES, 1, {num(SLIDE_SPEED)}")
    deck.add("*STEP, NAME=SLIDE", "*DYNAMIC, EXPLICIT", f", {num(t)}",
             "*BOUNDARY", "PLATE_REF, 1, 6", "*DLOAD", f"BLOCK, GRAV, {num(GRAVITY)}, 0., 0., -1.")
    general_contact(deck, properties=", , ROUGH")
    output_requests(deck, t, 20, [("BLOCK_NODES", "V1, V3"), ("PLATE_REF", "RF1, RF3")])
    deck.add("*END STEP")
    return deck, {"elements": block.count() + plate.count(),
                  "C3D8R": block.count() + plate.count(), "rigid": plate.count()}


def fold_point(s, y):
    """Point of the folded strip's mid-surface at path length s (convex fold at s = 0, concave
    fold at s = the slope's length) and width coordinate y."""
    c, sn = math.cos(math.radians(FOLD_ANGLE)), math.sin(math.radians(FOLD_ANGLE))
    slope = FOLD_PARTS[1][0]
    if s <= 0.0:
        return (s, y, 0.0)
    if s <= slope:
        return (s * c, y, -s * sn)
    return (slope * c + s - slope, y, -slope * sn)


class Puck(HexGrid):
    """A HexGrid block whose bottom face is a polygon inscribed in a cylinder of radius
    PUCK_RADIUS (axis along y): node columns at x = R sin(phi), phi = (ix - nx/2) FOLD_ANGLE, so
    its facets lie at multiples of FOLD_ANGLE and it rests on a whole facet on each straight
    part of the strip. The lift fades out linearly towards the flat top; the central facet
    lies on the block's bottom face."""

    def __init__(self, base, centre, bottom):
        nx = PUCK_ELEMENTS[0]
        length = 2 * PUCK_RADIUS * math.sin(math.radians(FOLD_ANGLE) * nx / 2)
        super().__init__(base, (centre - length / 2, -PUCK_WIDTH / 2, bottom),
                         (length, PUCK_WIDTH, PUCK_HEIGHT), PUCK_ELEMENTS)

    def point(self, ix, iy, iz):
        _, y, z = super().point(ix, iy, iz)
        phi = math.radians(FOLD_ANGLE) * (ix - self.nx / 2)
        lowest = math.cos(math.radians(FOLD_ANGLE) / 2)
        lift = PUCK_RADIUS * (lowest - math.cos(phi))
        return (self.origin[0] + self.size[0] / 2 + PUCK_RADIUS * math.sin(phi), y,
                z + (1 - iz / self.nz) * lift)

    def mass_centre_height(self):
        """Mass (kg) and height (m) of the centre of mass above the central facet."""
        mass = moment = 0.0
        for _, nodes in self.element_items():
            points = [self.point(*self.indices(n)) for n in nodes]
            volume = hex_volume(points)
            mass += DENSITY * volume
            moment += DENSITY * hex_volume(points, weight=lambda p: p[2] - self.origin[2])
        return mass, moment / mass

    def indices(self, node):
        rest = node - self.base
        return rest % self.sy, (rest % self.sz) // self.sy, rest // self.sz


def shell_slide_numbers():
    """Puck mass (kg), height of its centre of mass above its lowest facet (m), along-slope
    acceleration (m/s^2), speed at the concave fold (m/s) and step time (s)."""
    mass, height = Puck(2 * BODY, 0.0, 0.0).mass_centre_height()
    theta = math.radians(FOLD_ANGLE)
    accel = PUCK_GRAVITY * math.sin(theta)
    v_c = math.sqrt(PUCK_SPEED ** 2 + 2 * accel * FOLD_PARTS[1][0])
    # To the convex fold at v0, down the slope accelerating, then PUCK_PAST at v_c; rounded up.
    period = -PUCK_START / PUCK_SPEED + (v_c - PUCK_SPEED) / accel + PUCK_PAST / v_c
    return mass, height, accel, v_c, math.ceil(period * 1e4) / 1e4


def shell_slide():
    nw = FOLD_WIDTH_ELEMENTS
    mass, height, accel, v_c, period = shell_slide_numbers()
    theta = math.radians(FOLD_ANGLE)
    axis = PUCK_RADIUS * math.cos(theta / 2)
    (a_len, a_n), (s_len, s_n), (b_len, b_n) = FOLD_PARTS
    # Path coordinates of the strip's node columns: u + a sin(4 pi u)/(4 pi) on each part, so
    # element lengths vary by +-a and the columns at the folds stay where they are.
    columns, start = [], -a_len
    for part, (length, count) in enumerate(FOLD_PARTS):
        for k in range(0 if part == 0 else 1, count + 1):
            u = k / count
            g = u + FOLD_SPACING * math.sin(4 * math.pi * u) / (4 * math.pi)
            columns.append((start + length * g, math.sin(math.pi * u)))
        start += length
    nodes = []
    for j in range(nw + 1):
        y = FOLD_WIDTH * (j / nw - 0.5)
        for i, (s, lean) in enumerate(columns):
            nodes.append((BODY + 1 + i + 100 * j, fold_point(s + FOLD_SKEW * lean * y, y)))
    strip = [(BODY + 1 + i + 100 * j,
              [BODY + 1 + i + 100 * j, BODY + 2 + i + 100 * j, BODY + 102 + i + 100 * j,
               BODY + 101 + i + 100 * j]) for j in range(nw) for i in range(len(columns) - 1)]
    where = dict(nodes)
    edges = [math.dist(where[q[k]], where[q[k - 1]]) for _, q in strip for k in range(4)]

    def to_line(p, a, b):  # distance from p to the line through a and b
        ab = [v - u for u, v in zip(a, b)]
        ap = [v - u for u, v in zip(a, p)]
        along = sum(u * v for u, v in zip(ab, ap)) / sum(u * u for u in ab)
        return math.dist(p, [u + along * v for u, v in zip(a, ab)])

    # Each node's distance to the far side of its elements: xpl takes a shell node closer than
    # t to the face beyond its neighbour as touching that face a thickness deep (a node offset
    # sideways by less than its penetration is admissible), so keep it above t.
    across = min(to_line(where[q[k]], where[q[(k + 1) % 4]], where[q[(k + 2) % 4]])
                 for _, q in strip for k in range(4))
    assert across > 1.2 * FOLD_THICKNESS, "strip elements too narrow for the thickness"
    deck = Deck("shell_slide")
    header(deck,
           "A node sliding over a folded shell does not snag on its edges: C3D8R puck sliding "
           f"at {PUCK_SPEED:g} m/s over a fixed S4R strip with a convex and a concave fold, "
           "frictionless, ALL EXTERIOR general contact",
           f"Strip: S4R, t = {FOLD_THICKNESS * 1e3:g} mm, {FOLD_WIDTH * 1e3:g} mm wide, every "
           f"node fixed (*BOUNDARY 1-6). Flat A: x in [{-a_len * 1e3:g}, 0], z = 0; convex fold "
           f"at x = 0, down by {FOLD_ANGLE:g} deg;",
           f"slope of {s_len * 1e3:g} mm; concave fold at x = {s_len * math.cos(theta) * 1e3:.4f}"
           f" mm, z = {-s_len * math.sin(theta) * 1e3:.4f} mm, back to horizontal; flat B of "
           f"{b_len * 1e3:g} mm.",
           f"{a_n}, {s_n} and {b_n} x {nw} elements, edges {min(edges) * 1e3:.2f} to "
           f"{max(edges) * 1e3:.2f} mm (every node at least {across * 1e3:.2f} mm from the far "
           "side of its elements); the edges across the path lean by up to "
           f"{math.degrees(math.atan(FOLD_SKEW)):.1f} deg (none at the folds).",
           f"Puck: {PUCK_WIDTH * 1e3:g} mm wide (y), {PUCK_HEIGHT * 1e3:g} mm high, "
           f"{'x'.join(map(str, PUCK_ELEMENTS))} C3D8R, steel; its bottom: facets of "
           f"{FOLD_ANGLE:g} deg inscribed in a cylinder of radius R = {PUCK_RADIUS * 1e3:g} mm "
           "(axis y),",
           f"so that a whole facet lies on each straight part of the strip. Its central facet "
           f"lies on the strip's upper face, centred at x = {PUCK_START * 1e3:g} mm (zero gap). "
           f"m = {mass * 1e3:.4f} g;",
           f"centre of mass {height * 1e3:.4f} mm above the facet, {(height - axis) * 1e6:.0f} "
           f"um from the cylinder's axis: the normal forces pass close to it, the puck hardly "
           "rocks.",
           f"Velocity {PUCK_SPEED:g} m/s in x; gravity {PUCK_GRAVITY:g} m/s^2 in -z (*DLOAD GRAV,"
           f" ramped in over {PUCK_RAMP * 1e6:g} us): m g = {mass * PUCK_GRAVITY:.3f} N.",
           "Over the convex fold the puck pivots on the fold line, its axis on a circle of radius"
           f" R: v^2/R = {PUCK_SPEED ** 2 / PUCK_RADIUS:.0f} m/s^2 < g cos(theta), it stays on "
           "the strip.",
           "Frictionless: on flat A the horizontal momentum is conserved; on the slope the "
           f"speed along it grows at g sin(theta) = {accel:.1f} m/s^2 and CFN = m g cos(theta);",
           f"at the concave fold (v = {v_c:.3f} m/s) the puck meets flat B at v sin(theta) = "
           f"{v_c * math.sin(theta):.3f} m/s and bounces (elastic penalty); on flat B the "
           "horizontal momentum is conserved again.",
           f"The step ({period * 1e3:g} ms) ends about {PUCK_PAST * 1e3:g} mm past the concave "
           "fold.",
           "Ids: strip nodes 100000 + 1 + i + 100 j (i along the path, j across), elements the "
           "same; puck 200000 + ix + 10 iy + 100 iz.")
    deck.nodes(nodes, "The strip.")
    deck.elements("S4R", "STRIP", strip)
    puck = Puck(2 * BODY, PUCK_START, FOLD_THICKNESS / 2)
    puck.write(deck, "PUCK", "The puck.")
    deck.nset("STRIP_NODES", [node for node, _ in nodes])
    deck.add("*NSET, NSET=PUCK_NODES, ELSET=PUCK")
    deck.nset("PUCK_BOTTOM", puck.nodes_where(iz=0))
    # Mid-height nodes of the two central columns: their mean lies on the puck's axis.
    deck.nset("PUCK_AXIS", puck.nodes_where(ix=puck.nx // 2, iz=puck.nz // 2)
              + puck.nodes_where(ix=puck.nx // 2 + 1, iz=puck.nz // 2))
    materials(deck)
    deck.add("*SHELL SECTION, ELSET=STRIP, MATERIAL=STEEL", f"{num(FOLD_THICKNESS)}, 5",
             "*SOLID SECTION, ELSET=PUCK, MATERIAL=STEEL")
    deck.add("*AMPLITUDE, NAME=RAMP_IN, DEFINITION=TABULAR",
             f"0., 0., {num(PUCK_RAMP)}, 1., {num(period)}, 1.")
    deck.add("*INITIAL CONDITIONS, TYPE=VELOCITY", f"PUCK_NODES, 1, {num(PUCK_SPEED)}")
    deck.add("*STEP, NAME=SLIDE", "*DYNAMIC, EXPLICIT", f", {num(period)}",
             "*BOUNDARY", "STRIP_NODES, 1, 6",
             "*DLOAD, AMPLITUDE=RAMP_IN", f"PUCK, GRAV, {num(PUCK_GRAVITY)}, 0., 0., -1.")
    general_contact(deck)
    # History every microsecond (about 8 increments): the puck's momentum (V of all its nodes),
    # the positions of its bottom nodes and of its axis, CFN and the energies.
    output_requests(deck, period, 24, [("PUCK_NODES", "V1, V3"), ("PUCK_BOTTOM", "U1, U3"),
                                       ("PUCK_AXIS", "U1, U3")],
                    history_rows=round(period / 1e-6))
    deck.add("*END STEP")
    return deck, {"elements": len(strip) + puck.count(), "S4R": len(strip),
                  "C3D8R": puck.count()}

DECKS = {
    "bar_bar": lambda: bar_bar("general"),
    "bar_bar_pair": lambda: bar_bar("pair"),
    "bar_bar_oneway": lambda: bar_bar("oneway"),
    "bar_wall": bar_wall,
    "hertz": hertz,
    "shell_block": lambda: shell_block(False),
    "shell_block_below": lambda: shell_block(True),
    "tube_crush": tube_crush,
    "friction_block": friction_block,
    "shell_slide": shell_slide,
}


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("out", nargs="?", type=pathlib.Path, default=DEFAULT_OUT,
                        help="output folder; each deck goes to OUT/NAME/NAME.inp (default: the "
                             "folder of this script)")
    parser.add_argument("--only", choices=sorted(DECKS), action="append",
                        help="write only this deck (may be repeated)")
    args = parser.parse_args(argv)
    for name in args.only or DECKS:
        deck, info = DECKS[name]()
        path = args.out / name / f"{name}.inp"
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(deck.text())
        kinds = ", ".join(f"{info[k]} {k}" for k in ("C3D8R", "S4R") if k in info)
        rigid = f" ({info['rigid']} rigid)" if "rigid" in info else ""
        print(f"make_contact_decks: wrote {path} ({len(deck.coordinates)} nodes, {kinds}{rigid})")


if __name__ == "__main__":
    main()
