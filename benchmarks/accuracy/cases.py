"""The cases of the error-against-time fronts (issue 16, item 1): decks and error measures.

Every deck is written once per solver from the same model text (nodes, elements, sets,
material, initial conditions, boundary conditions); only what a solver needs differently
is written per solver:

  output   xpl: *OUTPUT, HISTORY at every increment (an interval below the increment) of
           the series the measure needs, *ENERGY OUTPUT, a field frame at the end where
           velocities are needed; CalculiX: *NODE PRINT / *EL PRINT / *CONTACT PRINT to the
           .dat file at every increment (FREQUENCY=1), totals where a sum is needed
  contact  the same one-way node-to-surface *CONTACT PAIR in both; xpl with its default
           penalty (PRESSURE-OVERCLOSURE=HARD), CalculiX with the LINEAR slope it needs
           (it has no default for node-to-surface penalty contact): E/h of the elements at
           the contact, the element's own axial stiffness per unit area
  step     CalculiX: *STEP, INC= large (its default stops at 100 increments); both solvers
           pick their own stable increment (CalculiX overrides the data line's first value
           with its Courant increment)

Ids are consecutive: CalculiX sizes its arrays by the largest id (a two-bar deck with ids
up to 200000 took 1.35 GB and 4 s per increment; renumbered, 50 MB), so the sparse-id
generators of examples/ are used for their geometry (examples/contact's sphere mesh,
examples/plasticity's Taylor bar section) and written here with compact ids.

Units m, kg, s, N, Pa. Each case returns (deck text, reference dict) from deck(level,
solver) and the errors of one run from measure(run, reference).
"""
import math
import pathlib
import sys

import numpy as np

import solvers

REPO = pathlib.Path(__file__).resolve().parents[2]

E_STEEL = 200.0e9
RHO_STEEL = 7850.0


def lines_of(values, per_line=8):
    values = list(values)
    return [", ".join(str(v) for v in values[i:i + per_line])
            for i in range(0, len(values), per_line)]


def fmt(value):
    return f"{value:.10g}"


class Box:
    """Structured nx x ny x nz C3D8R box with consecutive ids from first_node/first_element.

    Node order: Abaqus C3D8R, 1-4 counter-clockwise at the lower z, 5-8 above; face S4 is
    the x = max face of an element, S6 the x = min face.
    """

    def __init__(self, first_node, first_element, origin, size, counts):
        self.n0, self.e0 = first_node, first_element
        self.origin, self.size = origin, size
        self.nx, self.ny, self.nz = counts

    def node(self, ix, iy, iz):
        return self.n0 + ix + (self.nx + 1) * (iy + (self.ny + 1) * iz)

    def element(self, ex, ey, ez):
        return self.e0 + ex + self.nx * (ey + self.ny * ez)

    def point(self, ix, iy, iz):
        (x0, y0, z0), (lx, ly, lz) = self.origin, self.size
        return (x0 + lx * ix / self.nx, y0 + ly * iy / self.ny, z0 + lz * iz / self.nz)

    def node_lines(self):
        return [f"{self.node(i, j, k)}, " + ", ".join(fmt(c) for c in self.point(i, j, k))
                for k in range(self.nz + 1) for j in range(self.ny + 1)
                for i in range(self.nx + 1)]

    def element_lines(self):
        n = self.node
        out = []
        for k in range(self.nz):
            for j in range(self.ny):
                for i in range(self.nx):
                    ids = [n(i, j, k), n(i + 1, j, k), n(i + 1, j + 1, k), n(i, j + 1, k),
                           n(i, j, k + 1), n(i + 1, j, k + 1), n(i + 1, j + 1, k + 1),
                           n(i, j + 1, k + 1)]
                    out.append(f"{self.element(i, j, k)}, " + ", ".join(map(str, ids)))
        return out

    def nodes_where(self, ix=None, iy=None, iz=None):
        return [self.node(i, j, k) for k in range(self.nz + 1) for j in range(self.ny + 1)
                for i in range(self.nx + 1)
                if (ix is None or i == ix) and (iy is None or j == iy) and (iz is None or k == iz)]

    def elements_where(self, ex=None, ey=None, ez=None):
        return [self.element(i, j, k) for k in range(self.nz) for j in range(self.ny)
                for i in range(self.nx)
                if (ex is None or i == ex) and (ey is None or j == ey) and (ez is None or k == ez)]

    def all_nodes(self):
        return self.nodes_where()

    def count(self):
        return self.nx * self.ny * self.nz

    def last_node(self):
        return self.node(self.nx, self.ny, self.nz)

    def last_element(self):
        return self.element(self.nx - 1, self.ny - 1, self.nz - 1)


def nset(name, ids):
    return [f"*NSET, NSET={name}"] + lines_of(ids)


def elset(name, ids):
    return [f"*ELSET, ELSET={name}"] + lines_of(ids)


def material(name, e, nu, rho):
    return [f"*MATERIAL, NAME={name}", "*DENSITY", fmt(rho), "*ELASTIC", f"{fmt(e)}, {fmt(nu)}"]


def step_header(solver, period):
    if solver == "calculix":
        return ["*STEP, INC=100000000", "*DYNAMIC, EXPLICIT", f"1e-9, {fmt(period)}"]
    return ["*STEP, NAME=RUN", "*DYNAMIC, EXPLICIT", f", {fmt(period)}"]


def xpl_history(node_requests, energy=True):
    """History at every increment (an interval below any stable increment)."""
    out = ["*OUTPUT, HISTORY, TIME INTERVAL=1e-12"]
    for name, variables in node_requests:
        out += [f"*NODE OUTPUT, NSET={name}", variables]
    if energy:
        out.append("*ENERGY OUTPUT")
    return out


def ccx_prints(node_totals, elsets_energy, node_values=(), contact=None):
    out = []
    for name, variables in node_totals:
        out += [f"*NODE PRINT, NSET={name}, TOTALS=ONLY, FREQUENCY=1", variables]
    for name, variables in node_values:
        out += [f"*NODE PRINT, NSET={name}, FREQUENCY=1", variables]
    for name in elsets_energy:
        out += [f"*EL PRINT, ELSET={name}, TOTALS=ONLY, FREQUENCY=1", "ELSE, ELKE"]
    if contact:
        slave, master = contact
        # CF totals print as zero in CalculiX 2.20's explicit runs; the slave nodes'
        # pressures (CSTR) times their tributary areas give the force.
        out += [f"*CONTACT PRINT, SLAVE={slave}, MASTER={master}, FREQUENCY=1", "CSTR"]
    return out


# ---------------------------------------------------------------------------------------------
# Time-series helpers


def crossing_up(t, y, level, start=0):
    """First time after index start where y rises through level (linear interpolation)."""
    for i in range(max(start, 1), len(y)):
        if y[i - 1] < level <= y[i]:
            return t[i - 1] + (level - y[i - 1]) / (y[i] - y[i - 1]) * (t[i] - t[i - 1])
    return math.nan


def crossing_down_last(t, y, level):
    """Last time y falls through level (linear interpolation)."""
    for i in range(len(y) - 1, 0, -1):
        if y[i - 1] > level >= y[i]:
            return t[i - 1] + (y[i - 1] - level) / (y[i - 1] - y[i]) * (t[i] - t[i - 1])
    return math.nan


def crossing_down(t, y, level, start=0):
    for i in range(max(start, 1), len(y)):
        if y[i - 1] > level >= y[i]:
            return t[i - 1] + (y[i - 1] - level) / (y[i - 1] - y[i]) * (t[i] - t[i - 1])
    return math.nan


def relative(value, reference):
    return abs(value - reference) / abs(reference)


def energy_error_ccx(dat, elsets, e0, final=False):
    """|ELSE + ELKE - E0| / E0 of the elements: CalculiX books neither the dissipation of its
    alpha method nor (in ELSE) the energy in its contact springs, so for contact cases
    (final=True) the value after separation is taken, otherwise the largest over the run."""
    total = None
    for name in elsets:
        _, se = dat[("total internal energy", name)]
        _, ke = dat[("total kinetic energy", name)]
        series = se.reshape(len(se), -1)[:, 0] + ke.reshape(len(ke), -1)[:, 0]
        total = series if total is None else total + series
    if final:
        return float(abs(total[-1] - e0) / e0)
    return float(np.max(np.abs(total - e0)) / e0)


def energy_error_xpl(run):
    return float(run["summary"]["energy_balance"]["relative_error"])


# ---------------------------------------------------------------------------------------------
# Bars (nu = 0: one-dimensional waves)

BAR_L = 0.100
BAR_SIDE = 0.010
BAR_V = 10.0
BAR_SECTION = 2  # elements across the 10 mm side at every level: the wave is 1D (nu = 0)


def bar_numbers():
    c0 = math.sqrt(E_STEEL / RHO_STEEL)
    area = BAR_SIDE ** 2
    return {"c0": c0, "T": 2 * BAR_L / c0, "force": RHO_STEEL * c0 * BAR_V * area,
            "e0": 0.5 * RHO_STEEL * BAR_L * area * BAR_V ** 2}


class BarWall:
    """Bar impact on a fixed end: every node off x = 0 starts at -v, x = 0 held.

    Exact (1D, nu = 0): the wall reaction is a square wave of +rho c0 v A for 0 < t < 2L/c0,
    then -rho c0 v A (the end stays held: the bar pulls). Errors: plateau = mean reaction
    over the middle 80 % of the first half period against rho c0 v A; return time = the
    reaction's first down-crossing of zero against 2L/c0.
    """
    name = "bar_wall"
    level_name = "elements along the bar"
    title = "Bar impact on a fixed end"
    errors = ("plateau", "return_time")
    levels = (10, 20, 40, 80, 160)

    def mesh_size(self, nx):
        return BAR_L / nx

    def deck(self, nx, solver):
        ref = bar_numbers()
        box = Box(1, 1, (0.0, 0.0, 0.0), (BAR_L, BAR_SIDE, BAR_SIDE),
                  (nx, BAR_SECTION, BAR_SECTION))
        out = ["*HEADING", f"Bar {nx}x{BAR_SECTION}x{BAR_SECTION} C3D8R on a fixed end at "
               f"{BAR_V:g} m/s (benchmarks/accuracy)", "*NODE"]
        out += box.node_lines()
        out += ["*ELEMENT, TYPE=C3D8R, ELSET=BAR"] + box.element_lines()
        out += nset("FIXED", box.nodes_where(ix=0))
        out += nset("MOVING", [n for i in range(1, nx + 1) for n in box.nodes_where(ix=i)])
        out += material("STEEL", E_STEEL, 0.0, RHO_STEEL)
        out += ["*SOLID SECTION, ELSET=BAR, MATERIAL=STEEL"]
        out += ["*INITIAL CONDITIONS, TYPE=VELOCITY", f"MOVING, 1, {fmt(-BAR_V)}"]
        out += step_header(solver, 1.25 * ref["T"])
        out += ["*BOUNDARY", "FIXED, 1, 3"]
        if solver == "xpl":
            out += xpl_history([("FIXED", "RF1")])
        else:
            out += ccx_prints([("FIXED", "RF")], ["BAR"])
        out.append("*END STEP")
        return "\n".join(out) + "\n", {**ref, "elements": box.count()}

    def measure(self, run, ref):
        if run["solver"] == "xpl":
            h = solvers.xpl_history(run["h5"])
            t, force = h["time"], h["node/FIXED/RF1"].sum(axis=1)
            energy = energy_error_xpl(run)
        else:
            t, values = run["dat"][("total force (fx,fy,fz)", "FIXED")]
            force = values.reshape(len(t), -1)[:, 0]
            energy = energy_error_ccx(run["dat"], ["BAR"], ref["e0"])
        # The wall pushes the bar in +x: RF1 > 0 while the bar is pressed on it.
        period = ref["T"]
        window = (t > 0.1 * period) & (t < 0.9 * period)
        plateau = float(np.mean(force[window]))
        start = int(np.searchsorted(t, 0.5 * period))
        back = crossing_down(t, force, 0.0, start)
        return {"plateau": relative(plateau, ref["force"]),
                "return_time": relative(back, period), "energy": energy,
                "plateau_value": plateau, "return_time_value": back}


class BarBar:
    """Bar on bar through contact: A (x in [0, L]) at +v onto B at rest across a small gap,
    one-way node-to-surface *CONTACT PAIR (slave A's end face, master B's).

    Exact: interface force rho c0 v A / 2 for 2L/c0, then A at rest and B at v. Errors:
    force = median contact force between the half-plateau crossings, against rho c0 v A / 2
    (xpl: CFN of the pair's history; CalculiX: the slave nodes' CSTR pressures times their
    tributary areas);
    duration from the first to the last sample of nonzero force (above 1e-3 of the
    peak; quantised to the increment) and at half the plateau (crossings interpolated),
    against 2L/c0; velocities after: mean V1 of each bar at the end of the step (of a node
    line along it), |v_A|/v and |v_B - v|/v (their sum is the error column 'velocity').
    """
    name = "bar_bar"
    level_name = "elements along each bar"
    title = "Bar on bar through contact"
    errors = ("force", "duration_nonzero", "duration_half", "velocity")
    levels = (10, 20, 40, 80, 160)
    gap = 0.05e-3

    def mesh_size(self, nx):
        return BAR_L / nx

    def deck(self, nx, solver):
        ref = bar_numbers()
        ref = {**ref, "force": ref["force"] / 2, "impact": self.gap / BAR_V}
        a = Box(1, 1, (0.0, 0.0, 0.0), (BAR_L, BAR_SIDE, BAR_SIDE), (nx, BAR_SECTION, BAR_SECTION))
        b = Box(a.last_node() + 1, a.last_element() + 1, (BAR_L + self.gap, 0.0, 0.0),
                (BAR_L, BAR_SIDE, BAR_SIDE), (nx, BAR_SECTION, BAR_SECTION))
        out = ["*HEADING", f"Bar on bar, {nx}x{BAR_SECTION}x{BAR_SECTION} C3D8R each, "
               f"{BAR_V:g} m/s, node-to-surface contact pair (benchmarks/accuracy)", "*NODE"]
        out += a.node_lines() + b.node_lines()
        out += ["*ELEMENT, TYPE=C3D8R, ELSET=A"] + a.element_lines()
        out += ["*ELEMENT, TYPE=C3D8R, ELSET=B"] + b.element_lines()
        out += nset("A_NODES", a.all_nodes()) + nset("B_NODES", b.all_nodes())
        # One line of nodes along each bar: with nu = 0 every section moves as a whole, so
        # the bar's mean velocity is the line's mean (end nodes weighted 1/2).
        out += nset("A_LINE", a.nodes_where(iy=0, iz=0)) + nset("B_LINE", b.nodes_where(iy=0, iz=0))
        out += elset("A_END_LAYER", a.elements_where(ex=nx - 1))
        out += elset("B_END_LAYER", b.elements_where(ex=0))
        out += ["*SURFACE, TYPE=ELEMENT, NAME=A_END", "A_END_LAYER, S4",
                "*SURFACE, TYPE=ELEMENT, NAME=B_END", "B_END_LAYER, S6"]
        out += material("STEEL", E_STEEL, 0.0, RHO_STEEL)
        out += ["*SOLID SECTION, ELSET=A, MATERIAL=STEEL",
                "*SOLID SECTION, ELSET=B, MATERIAL=STEEL"]
        out += ["*SURFACE INTERACTION, NAME=CONTACT"]
        if solver == "xpl":
            out += ["*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=HARD"]
        else:
            out += ["*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR",
                    fmt(E_STEEL / self.mesh_size(nx))]
        out += ["*CONTACT PAIR, INTERACTION=CONTACT, TYPE=NODE TO SURFACE", "A_END, B_END"]
        out += ["*INITIAL CONDITIONS, TYPE=VELOCITY", f"A_NODES, 1, {fmt(BAR_V)}"]
        period = ref["impact"] + ref["T"] + 0.5 * ref["T"]
        out += step_header(solver, period)
        if solver == "xpl":
            out += xpl_history([("A_LINE", "V1"), ("B_LINE", "V1")])
        else:
            out += ccx_prints([], ["A", "B"], node_values=[("A_LINE", "V"), ("B_LINE", "V")],
                              contact=("A_END", "B_END"))
        out.append("*END STEP")
        hy, hz = BAR_SIDE / BAR_SECTION, BAR_SIDE / BAR_SECTION
        areas = {}
        for j in range(BAR_SECTION + 1):
            for k in range(BAR_SECTION + 1):
                wy = 0.5 if j in (0, BAR_SECTION) else 1.0
                wz = 0.5 if k in (0, BAR_SECTION) else 1.0
                areas[a.node(nx, j, k)] = wy * wz * hy * hz
        return "\n".join(out) + "\n", {**ref, "elements": a.count() + b.count(),
                                       "slave_areas": areas}

    def measure(self, run, ref):
        if run["solver"] == "xpl":
            h = solvers.xpl_history(run["h5"])
            t = h["time"]
            key = [k for k in h if k.startswith("contact/") and k.endswith("/CFN")]
            force = np.abs(np.sum([h[k] for k in key], axis=0))
            lines = {name: h[f"node/{name}_LINE/V1"][-1] for name in ("A", "B")}
            energy = energy_error_xpl(run)
        else:
            t, pressures = run["dat"][("contact stress", "all")]
            force = np.array([sum(p * ref["slave_areas"][n] for n, p in step.items())
                              for step in pressures])
            lines = {name: run["dat"][("velocities (vx,vy,vz)", f"{name}_LINE")][1][-1][:, 0]
                     for name in ("A", "B")}
            energy = energy_error_ccx(run["dat"], ["A", "B"], ref["e0"], final=True)
        peak = float(np.max(force))
        on = np.where(force > 1e-3 * peak)[0]
        duration_nonzero = t[on[-1]] - t[on[0]]
        # Half the plateau: the plateau is first taken as the median force over the nonzero
        # samples (robust to the overshoot at the front and to contact chatter); the pulse
        # runs from the first up- to the last down-crossing of half of it.
        half = 0.5 * float(np.median(force[on]))
        up = crossing_up(t, force, half)
        down = crossing_down_last(t, force, half)
        inside = (t >= up) & (t <= down)
        plateau = float(np.median(force[inside]))
        means = {}
        for name, v in lines.items():
            w = np.ones(len(v))
            w[0] = w[-1] = 0.5
            means[name] = float(np.sum(w * v) / np.sum(w))
        return {"force": relative(plateau, ref["force"]),
                "duration_nonzero": relative(duration_nonzero, ref["T"]),
                "duration_half": relative(down - up, ref["T"]),
                "velocity": abs(means["A"]) / BAR_V + abs(means["B"] - BAR_V) / BAR_V,
                "energy": energy, "force_value": plateau,
                "duration_nonzero_value": duration_nonzero, "duration_half_value": down - up,
                "vA": means["A"], "vB": means["B"]}


CASES = {c.name: c for c in (BarWall(), BarBar())}


# ---------------------------------------------------------------------------------------------
# Hertz: elastic sphere on a rigid plane (quarter model)

FACES = {1: (0, 1, 2, 3), 2: (4, 7, 6, 5), 3: (0, 4, 5, 1), 4: (1, 5, 6, 2), 5: (2, 6, 7, 3),
         6: (3, 7, 4, 0)}  # Abaqus C3D8R faces S1..S6, zero-based corners


class Hertz:
    """Hertz impact: elastic steel sphere (R = 10 mm, nu = 0.3) at 5 m/s on a rigid plane,
    quarter model (examples/contact's cubed-sphere mesh, refined at the pole).

    The plane is a 6 x 6 x 1 mm C3D8R block with every node held (rigid without *RIGID
    BODY, which both solvers then treat alike); the contact is a one-way node-to-surface
    *CONTACT PAIR, slave the sphere's faces within 2 mm of the pole, master the plane's top.
    Exact (Hertz, quasi-static): peak force 4/3 E* sqrt(R) delta^1.5 (a quarter of it in
    this model), contact time 2.943 delta/v. Errors: peak = the largest plane reaction
    (sum of RF3) against F/4; duration = first to last sample of nonzero force (above 1e-3 of
    the peak) of the first contact against t_c. Levels: elements along half a cube face of
    the sphere mesh (12 is the example deck's mesh); the radial layers, the surface layer
    and the pole edge scale with it.
    """
    name = "hertz"
    title = "Hertz sphere on a rigid plane"
    level_name = "elements per half cube face"
    errors = ("peak", "duration")
    levels = (3, 4, 5, 6, 8, 12)
    ccx_max_level = 6  # CalculiX takes about 10 us per element and increment: 8 would cost ~100 s
    gap = 0.01e-3

    def mesh_size(self, n):
        return 0.23e-3 * 12 / n

    def _mesh(self, n):
        sys.path.insert(0, str(REPO / "examples" / "contact"))
        import make_contact_decks as decks
        saved = (decks.SPHERE_HALF_FACE, decks.SPHERE_LAYERS, decks.SPHERE_SURFACE_LAYER,
                 decks.SPHERE_POLE_EDGE)
        decks.SPHERE_HALF_FACE = n
        decks.SPHERE_LAYERS = max(3, round(n * 10 / 12))
        decks.SPHERE_SURFACE_LAYER = 0.25e-3 * 12 / n
        decks.SPHERE_POLE_EDGE = self.mesh_size(n)
        try:
            points, hexes, info = decks.quarter_sphere_mesh()
            numbers = decks.hertz_numbers()
        finally:
            (decks.SPHERE_HALF_FACE, decks.SPHERE_LAYERS, decks.SPHERE_SURFACE_LAYER,
             decks.SPHERE_POLE_EDGE) = saved
        return points, hexes, info, numbers, decks

    def deck(self, n, solver):
        points, hexes, info, h, decks = self._mesh(n)
        radius, speed = decks.SPHERE_RADIUS, decks.SPHERE_SPEED
        keys = sorted(points)
        node_of = {key: i + 1 for i, key in enumerate(keys)}
        plane_top = -radius - self.gap
        plane = Box(len(keys) + 1, len(hexes) + 1, (-0.001, -0.001, plane_top - 0.001),
                    (0.006, 0.006, 0.001), (3, 3, 1))
        out = ["*HEADING", f"Hertz sphere, quarter model, {len(hexes)} C3D8R, on a fixed plane "
               "(benchmarks/accuracy)", "*NODE"]
        out += [f"{node_of[k]}, " + ", ".join(fmt(c) for c in points[k]) for k in keys]
        out += plane.node_lines()
        out.append("*ELEMENT, TYPE=C3D8R, ELSET=SPHERE")
        out += [f"{i + 1}, " + ", ".join(str(node_of[k]) for k in hexa)
                for i, hexa in enumerate(hexes)]
        out += ["*ELEMENT, TYPE=C3D8R, ELSET=PLANE"] + plane.element_lines()
        slave = []
        for i, hexa in enumerate(hexes):
            for label, corners in FACES.items():
                xyz = [points[hexa[c]] for c in corners]
                if all(abs(math.dist(p, (0, 0, 0)) - radius) < 1e-9 for p in xyz) and \
                        max(p[2] for p in xyz) < -radius + 2e-3:
                    slave.append(f"{i + 1}, S{label}")
        out += ["*SURFACE, TYPE=ELEMENT, NAME=POLE_CAP"] + slave
        out += elset("PLANE_TOP", plane.elements_where(ez=0))
        out += ["*SURFACE, TYPE=ELEMENT, NAME=PLANE_FACE", "PLANE_TOP, S2"]
        out += nset("SPHERE_NODES", [node_of[k] for k in keys])
        out += nset("XSYM", [node_of[k] for k in keys if points[k][0] == 0.0])
        out += nset("YSYM", [node_of[k] for k in keys if points[k][1] == 0.0])
        out += nset("PLANE_NODES", plane.all_nodes())
        out += material("STEEL", E_STEEL, 0.3, RHO_STEEL)
        out += ["*SOLID SECTION, ELSET=SPHERE, MATERIAL=STEEL",
                "*SOLID SECTION, ELSET=PLANE, MATERIAL=STEEL"]
        out += ["*SURFACE INTERACTION, NAME=CONTACT"]
        if solver == "xpl":
            out += ["*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=HARD"]
        else:
            out += ["*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR",
                    fmt(E_STEEL / self.mesh_size(n))]
        out += ["*CONTACT PAIR, INTERACTION=CONTACT, TYPE=NODE TO SURFACE",
                "POLE_CAP, PLANE_FACE"]
        out += ["*INITIAL CONDITIONS, TYPE=VELOCITY", f"SPHERE_NODES, 3, {fmt(-speed)}"]
        period = self.gap / speed + 1.5 * h["duration"]
        out += step_header(solver, period)
        out += ["*BOUNDARY", "XSYM, 1, 1", "YSYM, 2, 2", "PLANE_NODES, 1, 3"]
        if solver == "xpl":
            out += xpl_history([("PLANE_NODES", "RF3")])
        else:
            out += ccx_prints([("PLANE_NODES", "RF")], ["SPHERE"])
        out.append("*END STEP")
        e0 = 0.5 * info["volume"] * RHO_STEEL * speed ** 2
        return "\n".join(out) + "\n", {"force": h["force"] / 4, "T": h["duration"],
                                       "elements": len(hexes) + plane.count(), "e0": e0}

    def measure(self, run, ref):
        if run["solver"] == "xpl":
            hist = solvers.xpl_history(run["h5"])
            t, force = hist["time"], hist["node/PLANE_NODES/RF3"].sum(axis=1)
            energy = energy_error_xpl(run)
        else:
            t, values = run["dat"][("total force (fx,fy,fz)", "PLANE_NODES")]
            force = values.reshape(len(t), -1)[:, 2]
            energy = energy_error_ccx(run["dat"], ["SPHERE"], ref["e0"], final=True)
        force = np.abs(force)
        peak = float(np.max(force))
        on = np.where(force > 1e-3 * peak)[0]
        # The first contact only: from the first nonzero sample to the last one before the
        # force first falls back to zero after its peak (the ringing sphere may touch again).
        top = int(np.argmax(force))
        off = np.where(force[top:] <= 1e-3 * peak)[0]
        if len(off) == 0:
            raise ValueError("the sphere is still in contact at the end of the step")
        duration = t[top + off[0] - 1] - t[on[0]]
        return {"peak": relative(peak, ref["force"]), "duration": relative(duration, ref["T"]),
                "energy": energy, "peak_value": peak, "duration_value": duration}


CASES["hertz"] = Hertz()


# ---------------------------------------------------------------------------------------------
# Simply supported plate under a step pressure (S4R; xpl only)


def navier_centre(t, side, thickness, e, nu, rho, q, terms=99):
    """Centre deflection (m, along the load) of the undamped simply supported Kirchhoff
    plate under a pressure q applied at t = 0: sum over odd m, n of the static modal
    deflections times (1 - cos(omega_mn t))."""
    d = e * thickness ** 3 / (12.0 * (1.0 - nu * nu))
    t = np.asarray(t, dtype=float)
    w = np.zeros_like(t)
    for m in range(1, terms + 1, 2):
        for n in range(1, terms + 1, 2):
            k2 = (m * m + n * n) * (math.pi / side) ** 2
            static = 16.0 * q / (math.pi ** 2 * m * n * d * k2 * k2)
            omega = k2 * math.sqrt(d / (rho * thickness))
            sign = (-1) ** ((m - 1) // 2 + (n - 1) // 2)
            w += sign * static * (1.0 - np.cos(omega * t))
    return w


class Plate:
    """Simply supported square plate under a step pressure (examples/make_plate.py: 1 m,
    t = 10 mm steel, 1 kPa, n x n S4R), centre deflection against Navier's series.

    Errors: peak = the first peak of the centre deflection against Navier's (0.4436 mm at
    10.42 ms); history = the largest |w - w_Navier| over the 12 ms step / Navier's peak.
    xpl only. CalculiX 2.20 expands each S4R into a 20-node solid (C3D20R) and runs the deck
    explicitly, but on the 4 x 4 mesh (18 328 increments, 67 s of CPU: its increment is set
    by the 10 mm thickness) the centre moved 4.2e-7 m, 0.1 % of Navier's 0.44 mm: no usable
    CalculiX front without work on that deck, which was not done.
    """
    name = "plate"
    title = "Simply supported plate under a step pressure"
    level_name = "S4R per side"
    errors = ("peak", "history")
    levels = (8, 16, 32, 64)
    solvers = ("xpl",)
    period = 0.012

    def mesh_size(self, n):
        return 1.0 / n

    def deck(self, n, solver):
        sys.path.insert(0, str(REPO / "examples"))
        import make_plate
        text = make_plate.build(n, 1000.0, self.period, False)
        head = text[:text.index("*OUTPUT, FIELD")]
        out = head.splitlines() + xpl_history([("CENTER", "U3")]) + ["*END STEP"]
        ref = {"side": make_plate.SIDE, "thickness": make_plate.THICKNESS,
               "e": make_plate.YOUNGS_MODULUS, "nu": make_plate.POISSONS_RATIO,
               "rho": make_plate.DENSITY, "q": 1000.0, "elements": n * n}
        return "\n".join(out) + "\n", ref

    def measure(self, run, ref):
        hist = solvers.xpl_history(run["h5"])
        t = hist["time"]
        w = -hist["node/CENTER/U3"].reshape(len(t), -1)[:, 0]
        exact = navier_centre(t, ref["side"], ref["thickness"], ref["e"], ref["nu"], ref["rho"],
                              ref["q"])
        fine = np.linspace(0.0, self.period, 4001)
        peak_exact = float(np.max(navier_centre(fine, ref["side"], ref["thickness"], ref["e"],
                                                ref["nu"], ref["rho"], ref["q"])))
        return {"peak": relative(float(np.max(w)), peak_exact),
                "history": float(np.max(np.abs(w - exact)) / peak_exact),
                "energy": energy_error_xpl(run), "peak_value": float(np.max(w))}


CASES["plate"] = Plate()


# ---------------------------------------------------------------------------------------------
# Cantilever strip, first bending frequency

BETA1 = 1.8751040687119611  # first root of cos(b) cosh(b) = -1


class Cantilever:
    """Cantilever strip, first bending frequency: a steel strip 40 x 2 x 2 mm (nu = 0), the
    end x = 0 held, every node started with the first mode's velocity shape (tip 0.128 m/s,
    tip amplitude about 20 um: linear), C3D8R, nx = 10 nz along, nz through the thickness,
    one across.

    Reference: Euler-Bernoulli f1 = beta1^2 / (2 pi L^2) sqrt(E I / (rho A)) = 1019.3 Hz
    with a first-order correction for rotary inertia and shear (kappa = 5/6):
    f1 (1 - 1/2 beta1^2 (r/L)^2 (1 + E/(kappa G))), -0.12 %, known to about half of itself,
    so errors below about 0.06 % are not resolved. Error: frequency = 1 / (2 x the half
    period), the half period being the tip's mean U3 first falling back through zero,
    against f1 (CalculiX takes about 2 ms per increment whatever the mesh, so the step is
    0.62 periods, not several).
    """
    name = "cantilever"
    title = "Cantilever strip, first frequency"
    level_name = "elements through the thickness"
    errors = ("frequency",)
    levels = (2, 3, 4, 6, 8)
    ccx_max_level = 4  # CalculiX: about 45 s of CPU at 4, 6 would take about 150 s
    length, thickness, width = 0.040, 0.002, 0.002
    tip_speed = 0.128

    def mesh_size(self, nz):
        return self.thickness / nz

    def reference(self):
        area = self.width * self.thickness
        inertia = self.width * self.thickness ** 3 / 12.0
        f_eb = BETA1 ** 2 / (2 * math.pi * self.length ** 2) * math.sqrt(
            E_STEEL * inertia / (RHO_STEEL * area))
        r2 = inertia / area
        shear_modulus = E_STEEL / 2.0  # nu = 0
        correction = 0.5 * BETA1 ** 2 * r2 / self.length ** 2 * (
            1.0 + E_STEEL / (5.0 / 6.0 * shear_modulus))
        return f_eb * (1.0 - correction), f_eb, correction

    def mode(self, x):
        b = BETA1 / self.length
        s = (math.cosh(BETA1) + math.cos(BETA1)) / (math.sinh(BETA1) + math.sin(BETA1))
        return math.cosh(b * x) - math.cos(b * x) - s * (math.sinh(b * x) - math.sin(b * x))

    def deck(self, nz, solver):
        nx = 10 * nz
        f1, f_eb, correction = self.reference()
        box = Box(1, 1, (0.0, 0.0, -self.thickness / 2), (self.length, self.width, self.thickness),
                  (nx, 1, nz))
        out = ["*HEADING", f"Cantilever strip {nx}x1x{nz} C3D8R, first mode (benchmarks/accuracy)",
               "*NODE"]
        out += box.node_lines()
        out += ["*ELEMENT, TYPE=C3D8R, ELSET=STRIP"] + box.element_lines()
        out += nset("CLAMPED", box.nodes_where(ix=0))
        out += nset("TIP", box.nodes_where(ix=nx))
        out += material("STEEL", E_STEEL, 0.0, RHO_STEEL)
        out += ["*SOLID SECTION, ELSET=STRIP, MATERIAL=STEEL"]
        out += ["*INITIAL CONDITIONS, TYPE=VELOCITY"]
        tip = self.mode(self.length)
        for i in range(1, nx + 1):
            v = self.tip_speed * self.mode(self.length * i / nx) / tip
            for node in box.nodes_where(ix=i):
                out.append(f"{node}, 3, {fmt(v)}")
        out += step_header(solver, 0.62 / f1)
        out += ["*BOUNDARY", "CLAMPED, 1, 3"]
        if solver == "xpl":
            out += xpl_history([("TIP", "U3")])
        else:
            out += ccx_prints([], ["STRIP"], node_values=[("TIP", "U")])
        out.append("*END STEP")
        e0 = 0.0
        for i in range(nx + 1):
            v = self.tip_speed * self.mode(self.length * i / nx) / tip
            weight = 0.5 if i in (0, nx) else 1.0
            e0 += 0.5 * RHO_STEEL * self.width * self.thickness * self.length / nx * weight * v * v
        return "\n".join(out) + "\n", {"f": f1, "elements": box.count(), "e0": e0}

    def measure(self, run, ref):
        if run["solver"] == "xpl":
            hist = solvers.xpl_history(run["h5"])
            t = hist["time"]
            w = hist["node/TIP/U3"].reshape(len(t), -1).mean(axis=1)
            energy = energy_error_xpl(run)
        else:
            t, values = run["dat"][("displacements (vx,vy,vz)", "TIP")]
            w = values[:, :, 2].mean(axis=1)
            energy = energy_error_ccx(run["dat"], ["STRIP"], ref["e0"])
        period = 1.0 / ref["f"]
        start = int(np.searchsorted(t, 0.25 * period))
        half = crossing_down(t, w, 0.0, start)
        return {"frequency": relative(0.5 / half, ref["f"]), "energy": energy,
                "frequency_value": 0.5 / half}


CASES["cantilever"] = Cantilever()


# ---------------------------------------------------------------------------------------------
# Taylor bar (plasticity)


class Taylor:
    """Taylor bar: Wilkins and Guinan's copper bar (L0 = 32.4 mm, R0 = 3.2 mm, 227 m/s,
    E = 117 GPa, nu = 0.35, yield 400 MPa, linear hardening 100 MPa) on a rigid frictionless
    wall (U3 = 0 on the impact face), quarter model, examples/plasticity/make_taylor_bar.py
    (O-grid of n x n and 2n x m per section, nz along), 80 us, finite strain (CalculiX:
    *STEP, NLGEOM; xpl always).

    No closed form: the reference is the Richardson extrapolation of xpl's three finest
    meshes (h = 1/n; the order fitted), so xpl's own finest errors are not independent of it;
    the experiment (21.45 mm, 7.15 mm) is quoted beside it. Errors: length = final length
    (L0 + mean U3 of the far end), radius = the impact face's largest radius at the end.
    Hourglass control: xpl runs the example's, the solver's default (no *SECTION CONTROLS:
    C3D8R's enhanced assumed-strain form since issue 32; the viscous form up to the run of
    2026-12-02), CalculiX its own C3D8R control.
    """
    name = "taylor"
    title = "Taylor bar"
    level_name = "inner-square divisions n"
    errors = ("length", "radius")
    levels = (2, 3, 4, 6)
    meshes = {2: (2, 1, 20), 3: (3, 2, 40), 4: (4, 3, 60), 6: (6, 4, 80)}
    ccx_max_level = 4  # CalculiX: about 70 s of CPU at 4, several minutes at 6

    def mesh_size(self, n):
        return 3.2e-3 / n

    def deck(self, level, solver):
        import argparse
        sys.path.insert(0, str(REPO / "examples" / "plasticity"))
        import make_taylor_bar as tb
        n, m, nz = self.meshes[level]
        args = argparse.Namespace(n=n, m=m, nz=nz, end_time=tb.END_TIME, frames=1,
                                  hourglass=None, rigid_plate=False)
        text = tb.build_deck(args)
        head = text[:text.index("*OUTPUT, FIELD")]
        if solver == "calculix":
            head = head.replace("*STEP, NAME=IMPACT\n*DYNAMIC, EXPLICIT\n, ",
                                "*STEP, INC=100000000, NLGEOM\n*DYNAMIC, EXPLICIT\n1e-9, ")
            # Prints at the end only (the .dat prints share one FREQUENCY).
            out = head + ("*NODE PRINT, NSET=TOP, FREQUENCY=100000000\nU\n"
                          "*NODE PRINT, NSET=WALL, FREQUENCY=100000000\nU\n"
                          "*EL PRINT, ELSET=BAR, TOTALS=ONLY, FREQUENCY=100000000\nELSE, ELKE\n"
                          "*END STEP\n")
        else:
            out = head + ("*OUTPUT, FIELD, NUMBER INTERVAL=1\n*NODE OUTPUT\nU\n"
                          "*OUTPUT, HISTORY, TIME INTERVAL=1e-6\n*ENERGY OUTPUT\n*END STEP\n")
        coords = {}
        for line in text.split("*NODE\n", 1)[1].split("*ELEMENT", 1)[0].splitlines():
            if line and line[0].isdigit():
                fields = line.split(",")
                coords[int(fields[0])] = tuple(float(v) for v in fields[1:4])
        per_layer = len(coords) // (nz + 1)
        volume = math.pi * tb.RADIUS ** 2 * tb.LENGTH / 4
        return out, {"elements": len(tb.section_points(n, m)[1]) * nz,
                     "wall": list(range(1, per_layer + 1)), "coords": coords,
                     "top": list(range(1 + per_layer * nz, 1 + per_layer * (nz + 1))),
                     "L0": tb.LENGTH, "e0": 0.5 * tb.DENSITY * volume * tb.VELOCITY ** 2,
                     "end_time": tb.END_TIME}

    def final_shape(self, run, ref):
        if run["solver"] == "xpl":
            ids, u = solvers.xpl_last_frame(run["h5"], "U")
            disp = dict(zip(ids.tolist(), map(tuple, u.tolist())))
        else:
            disp = {}
            for name in ("TOP", "WALL"):
                _, values = run["dat"][("displacements (vx,vy,vz)", name)]
                ids = run["dat"][("displacements (vx,vy,vz)", name, "ids")]
                disp.update(zip(ids, map(tuple, values[-1].tolist())))
        length = ref["L0"] + float(np.mean([disp[n][2] for n in ref["top"]]))
        radius = max(math.hypot(ref["coords"][n][0] + disp[n][0], ref["coords"][n][1] + disp[n][1])
                     for n in ref["wall"])
        return length, radius

    def measure(self, run, ref):
        length, radius = self.final_shape(run, ref)
        if run["solver"] == "xpl":
            energy = energy_error_xpl(run)
        else:
            energy = energy_error_ccx(run["dat"], ["BAR"], ref["e0"], final=True)
        if run["solver"] == "calculix":  # prints at the end only: count from the increment
            run["increments"] = math.ceil(ref["end_time"] / run["dt"] - 1e-9)
        return {"energy": energy, "length_value": length, "radius_value": radius}

    def finish(self, rows):
        """The errors against the Richardson reference of xpl's three finest meshes (1
        thread); returns the reference as a line for the run's notes."""
        xpl = sorted((r for r in rows if r["solver"] == "xpl" and r["threads"] == 1),
                     key=lambda r: r["level"])[-3:]
        if len(xpl) < 3:
            raise ValueError("the Taylor reference needs xpl runs on the three finest meshes")
        notes = []
        for name in ("length", "radius"):
            value, order = richardson([r["mesh_size"] for r in xpl],
                                      [r[f"{name}_value"] for r in xpl])
            if value is None:
                value, order = xpl[-1][f"{name}_value"], math.nan
                notes.append(f"{name}: not monotone on xpl's finest meshes, reference = the "
                             f"finest value {value * 1e3:.4f} mm")
            else:
                levels = ", ".join(str(r["level"]) for r in xpl)
                notes.append(f"{name}: Richardson reference {value * 1e3:.4f} mm (order "
                             f"{order:.2f}, from xpl levels {levels})")
            for r in rows:
                r[name] = relative(r[f"{name}_value"], value)
        return "; ".join(notes)


def richardson(h, f):
    """Extrapolated f(0) from three (h, f) with f = f0 + C h^p (p fitted by bisection);
    None when the three are not monotone (no consistent order)."""
    (h1, f1), (h2, f2), (h3, f3) = sorted(zip(h, f))  # h1 finest
    if (f2 - f1) * (f3 - f2) <= 0:
        return None, None

    def residual(p):
        return (f3 - f2) / (f2 - f1) - (h3 ** p - h2 ** p) / (h2 ** p - h1 ** p)
    lo, hi = 0.05, 8.0
    if residual(lo) * residual(hi) > 0:
        return None, None
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if residual(lo) * residual(mid) > 0 else (lo, mid)
    p = 0.5 * (lo + hi)
    c = (f2 - f1) / (h2 ** p - h1 ** p)
    return f1 - c * h1 ** p, p


CASES["taylor"] = Taylor()
