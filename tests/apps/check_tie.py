#!/usr/bin/python3
"""*TIE (issue 18 item 1, SPEC S6): node-to-face kinematic ties, each case a deck written here.

Usage: check_tie.py XPL OUT_DIR [CASE]   (CASE: one of deck_errors, patch, wave, plate,
       shells, threads, overclosure, example; default all)

Cases (units m, kg, s; steel E = 200 GPa, rho = 7850, nu as stated):
- deck_errors: four node conflicts (a slave of two ties, a slave on another tie's master, a
  slave with a BC on DOFs 1-3, a slave in a rigid body): one file:line error each, exit 1.
- patch: block B (5 x 5 x 2 C3D8R) on block A (4 x 4 x 2), B's bottom (36 nodes) tied to A's
  top, stretched across the tie (v3 = 100 z /s): with every non-slave DOF driven by the field,
  S is uniform to 1e-6 of S33 and S33 = (lambda + 2 mu) ln(1 + rate t); the same with a free
  interior is run and its spread printed (not asserted).
- wave: a bar in two tied halves (2 x 2 | 3 x 3 elements across, nu = 0), the left end at
  1 m/s: the mean S11 over 55-70 mm within 2 % of rho c0 v, the left half within 2 % of
  rho c0 v of the same bar in one piece (the tie's reflection), ETOTAL within 1 %.
- plate: an S4R plate (5 x 5) tied to the top of a 4 x 4 x 2 block, pressure on the plate:
  ETOTAL within 1 % of ALLWK, plate nodes on the block face to 1e-9 m, 1 and 2 threads bit for
  bit; continued from half time with --import: end U within 2e-3 of the largest U.
- shells: a lap joint of two S4R plates (rotations tied): U and UR of the tied nodes follow
  the master, the nodes off the master listed untied in .msg, ETOTAL within 1 %.
- threads: a 6570-node tied model at 1 and 2 threads, bit for bit.
- overclosure: B's bottom 0.01 mm inside A's top with general contact: ADJUST=NO holds the 18
  tied nodes, offsets with reason 7 (tie); ADJUST=YES moves the slaves onto A first.
- example: examples/tie/glued_drop.inp runs, ETOTAL balanced, both blocks rebound.
"""

import pathlib
import re
import shutil
import subprocess
import sys

import h5py
import numpy as np

E, NU_STEEL, RHO = 200e9, 0.3, 7850.0
C0 = (E / RHO) ** 0.5  # bar wave speed at nu = 0, m/s


def check(condition, message):
    if not condition:
        sys.exit(f"check_tie.py: FAILED: {message}")


def xpl(binary, *args):
    r = subprocess.run([binary, *args], capture_output=True, text=True, timeout=300)
    return r.returncode, r.stdout + r.stderr


class Mesh:
    def __init__(self):
        self.nodes, self.elements, self.lines = {}, [], []
        self.next_node, self.next_element = 1, 1

    def block(self, origin, size, counts, etype="C3D8R", elset="A"):
        """Regular hex block; returns ids[i][j][k]."""
        nx, ny, nz = counts
        ids = [[[0] * (nz + 1) for _ in range(ny + 1)] for _ in range(nx + 1)]
        for k in range(nz + 1):
            for j in range(ny + 1):
                for i in range(nx + 1):
                    x = (origin[0] + size[0] * i / nx, origin[1] + size[1] * j / ny,
                         origin[2] + size[2] * k / nz)
                    ids[i][j][k] = self.next_node
                    self.nodes[self.next_node] = x
                    self.next_node += 1
        rows = []
        for k in range(nz):
            for j in range(ny):
                for i in range(nx):
                    c = [ids[i][j][k], ids[i + 1][j][k], ids[i + 1][j + 1][k], ids[i][j + 1][k],
                         ids[i][j][k + 1], ids[i + 1][j][k + 1], ids[i + 1][j + 1][k + 1],
                         ids[i][j + 1][k + 1]]
                    rows.append(f"{self.next_element}, " + ", ".join(map(str, c)))
                    self.next_element += 1
        self.elements.append((etype, elset, rows))
        return ids

    def plate(self, origin, size, counts, elset):
        nx, ny = counts
        ids = [[0] * (ny + 1) for _ in range(nx + 1)]
        for j in range(ny + 1):
            for i in range(nx + 1):
                ids[i][j] = self.next_node
                self.nodes[self.next_node] = (origin[0] + size[0] * i / nx,
                                              origin[1] + size[1] * j / ny, origin[2])
                self.next_node += 1
        rows = []
        for j in range(ny):
            for i in range(nx):
                c = [ids[i][j], ids[i + 1][j], ids[i + 1][j + 1], ids[i][j + 1]]
                rows.append(f"{self.next_element}, " + ", ".join(map(str, c)))
                self.next_element += 1
        self.elements.append(("S4R", elset, rows))
        return ids

    def text(self, title):
        out = ["*HEADING", title, "*NODE"]
        out += [f"{n}, {x[0]!r}, {x[1]!r}, {x[2]!r}" for n, x in self.nodes.items()]
        for etype, elset, rows in self.elements:
            out.append(f"*ELEMENT, TYPE={etype}, ELSET={elset}")
            out += rows
        return "\n".join(out + self.lines) + "\n"


def nset(name, ids):
    ids = sorted(set(ids))
    out = [f"*NSET, NSET={name}"]
    for k in range(0, len(ids), 8):
        out.append(", ".join(map(str, ids[k:k + 8])))
    return out


def flat(ids3, pick):
    return [ids3[i][j][k] for i in range(len(ids3)) for j in range(len(ids3[0]))
            for k in range(len(ids3[0][0])) if pick(i, j, k)]


def material(nu):
    return ["*MATERIAL, NAME=STEEL", "*DENSITY", f"{RHO}", "*ELASTIC", f"{E}, {nu}"]


def read_msg(d, job):
    return (d / f"{job}.msg").read_text()


# --- patch ------------------------------------------------------------------------------------
def patch(binary, out, driven=True):
    """Block B (5 x 5 x 2) on block A (4 x 4 x 2), B's bottom tied to A's top, stretched across
    the tie by v3 = RATE z (v1 = v2 = 0). driven: every DOF of every non-slave node follows the
    field (asserted: uniform S to 1e-6 of S33); else only z = 0 and z = 2T are driven in z and
    the rest of the interior moves freely in z (the spread measured and printed, not asserted:
    the one-pass node-to-face force transfer does not pass this patch test exactly)."""
    L, T, RATE = 0.01, 0.005, 100.0
    m = Mesh()
    m.block((0, 0, 0), (L, L, T), (4, 4, 2), elset="A")
    b = m.block((0, 0, T), (L, L, T), (5, 5, 2), elset="B")
    slaves = set(flat(b, lambda i, j, k: k == 0))
    others = [n for n in m.nodes if n not in slaves]
    z0 = [n for n in others if abs(m.nodes[n][2]) < 1e-12]
    z1 = [n for n in others if abs(m.nodes[n][2] - 2 * T) < 1e-12]
    m.lines += nset("OTHERS", others) + nset("Z0", z0) + nset("Z1", z1)
    m.lines += ["*SURFACE, NAME=A_TOP, TYPE=ELEMENT"] + [
        f"{e}, S2" for e in range(1 + 16, 1 + 32)]  # A's upper layer, faces S2 (z max)
    m.lines += ["*SURFACE, NAME=B_BOTTOM, TYPE=ELEMENT"] + [f"{e}, S1" for e in range(33, 33 + 25)]
    m.lines += ["*TIE, NAME=GLUE", "B_BOTTOM, A_TOP"]
    m.lines += material(NU_STEEL) + ["*SOLID SECTION, ELSET=A, MATERIAL=STEEL",
                                     "*SOLID SECTION, ELSET=B, MATERIAL=STEEL"]
    # The slave nodes get no initial velocity: the tie gives them theirs.
    m.lines += ["*INITIAL CONDITIONS, TYPE=VELOCITY"] + [f"{n}, 3, {RATE * m.nodes[n][2]!r}"
                                                         for n in others]
    z_lines = ([f"{n}, 3, 3, {RATE * m.nodes[n][2]!r}" for n in others] if driven else
               ["Z0, 3, 3, 0.", f"Z1, 3, 3, {RATE * 2 * T!r}"])
    m.lines += ["*BOUNDARY, TYPE=VELOCITY", "OTHERS, 1, 2, 0.", *z_lines,
                "*STEP", "*DYNAMIC, EXPLICIT", ", 5e-5",
                "*OUTPUT, FIELD, NUMBER INTERVAL=50", "*NODE OUTPUT", "U", "*ELEMENT OUTPUT", "S",
                "*OUTPUT, HISTORY, NUMBER INTERVAL=1", "*ENERGY OUTPUT", "*END STEP"]
    d = out / ("patch" if driven else "patch_free")
    d.mkdir()
    (d / "patch.inp").write_text(m.text("tie patch test"))
    code, text = xpl(binary, "run", str(d / "patch.inp"), "-o", str(d), "--quiet")
    check(code == 0, f"patch: xpl exited {code}\n{text}")
    msg = read_msg(d, "patch")
    check(re.search(r"tie GLUE: 36 slave node\(s\) tied", msg), "patch: 36 tied slave nodes")
    with h5py.File(d / "patch.h5", "r") as f:
        fr = last_frame(f)
        incs = int(fr.attrs["increment"])
        t = float(fr.attrs["time"])
        stress = fr["S"][:]
        h = f["history/step_1/energy"]
        drift = np.abs(h["ETOTAL"][:] - h["ETOTAL"][0]).max() / np.abs(h["ALLWK"][:]).max()
    check(incs >= 100, f"patch: only {incs} increments")
    s33 = stress[:, 2].mean()
    spread = np.abs(stress - stress.mean(axis=0)).max() / abs(s33)
    lam, mu = E * NU_STEEL / ((1 + NU_STEEL) * (1 - 2 * NU_STEEL)), E / (2 * (1 + NU_STEEL))
    # Hypoelastic: the rate of deformation RATE / (1 + RATE t) integrates to ln(1 + RATE t).
    expected = (lam + 2 * mu) * np.log1p(RATE * t)
    if not driven:
        print(f"check_tie.py: patch with a free interior (measured, not asserted): S spread "
              f"{spread:.2e} of S33, mean S33/analytic - 1 = {s33 / expected - 1:.1e}, ETOTAL "
              f"drift {drift:.1e} of ALLWK")
        return
    check(spread < 1e-6, f"patch: S spread {spread:.2e} of S33 (limit 1e-6)")
    check(abs(s33 / expected - 1) < 1e-3,
          f"patch: mean S33 {s33:.6e} Pa vs (lambda+2mu) ln(1 + RATE t) = {expected:.6e} Pa")
    check(drift < 0.01, f"patch: ETOTAL drift {drift:.2%} of ALLWK (limit 1 %)")
    print(f"check_tie.py: patch: {len(stress)} elements after {incs} increments, S spread "
          f"{spread:.1e} of S33, mean S33/analytic - 1 = {s33 / expected - 1:.1e}, ETOTAL drift "
          f"{drift:.1e} of ALLWK")


# --- wave -------------------------------------------------------------------------------------
def wave_run(binary, out, tied):
    """The bar, tied (2 x 2 | 3 x 3 elements across) or in one piece (2 x 2 throughout);
    returns the cross-section mean -S11 per 1 mm along x (100 values) at the end."""
    W, HALF, V = 0.003, 0.05, 1.0
    m = Mesh()
    if tied:
        a = m.block((0, 0, 0), (HALF, W, W), (50, 2, 2), elset="LEFT")
        m.block((HALF, 0, 0), (HALF, W, W), (50, 3, 3), elset="RIGHT")
        m.lines += ["*SURFACE, NAME=CUT_A, TYPE=ELEMENT"] + [
            f"{1 + 49 + 50 * (j + 2 * k)}, S4" for k in range(2) for j in range(2)]
        m.lines += ["*SURFACE, NAME=CUT_B, TYPE=ELEMENT"] + [
            f"{200 + 1 + 50 * (j + 3 * k)}, S6" for k in range(3) for j in range(3)]
        m.lines += ["*TIE, NAME=CUT, POSITION TOLERANCE=1e-6", "CUT_B, CUT_A"]
        sections = ["*SOLID SECTION, ELSET=LEFT, MATERIAL=STEEL",
                    "*SOLID SECTION, ELSET=RIGHT, MATERIAL=STEEL"]
    else:
        a = m.block((0, 0, 0), (2 * HALF, W, W), (100, 2, 2), elset="BAR")
        sections = ["*SOLID SECTION, ELSET=BAR, MATERIAL=STEEL"]
    m.lines += nset("END", flat(a, lambda i, j, k: i == 0))
    m.lines += material(0.0) + sections
    period = 0.075 / C0  # the front at 75 mm; the far end's reflection not yet back
    m.lines += ["*BOUNDARY, TYPE=VELOCITY", f"END, 1, 1, {V}",
                "*STEP", "*DYNAMIC, EXPLICIT", f", {period!r}",
                "*OUTPUT, FIELD, NUMBER INTERVAL=1000", "*ELEMENT OUTPUT", "S",
                "*OUTPUT, HISTORY, NUMBER INTERVAL=1", "*ENERGY OUTPUT", "*END STEP"]
    name = "tied" if tied else "whole"
    d = out / "wave" / name
    d.mkdir(parents=True)
    (d / f"{name}.inp").write_text(m.text("tied bar wave" if tied else "bar in one piece"))
    code, text = xpl(binary, "run", str(d / f"{name}.inp"), "-o", str(d), "--quiet")
    check(code == 0, f"wave: xpl exited {code}\n{text}")
    with h5py.File(d / f"{name}.h5", "r") as f:
        s11 = -last_frame(f)["S"][:, 0]
        h = f["history/step_1/energy"]
        drift = np.abs(h["ETOTAL"][:] - h["ETOTAL"][0]).max() / np.abs(h["ALLWK"][:]).max()
    if tied:
        profile = np.concatenate([s11[:200].reshape(4, 50).mean(axis=0),
                                  s11[200:].reshape(9, 50).mean(axis=0)])
    else:
        profile = s11.reshape(4, 100).mean(axis=0)
    return profile, drift


def wave(binary, out):
    V = 1.0
    sigma = RHO * C0 * V
    tied, drift = wave_run(binary, out, True)
    whole, _ = wave_run(binary, out, False)
    # Plateau past the tie: the mean over x = 55..70 mm (front at 75 mm; the ringing behind a
    # stepped front, +-2 % on either mesh, averages out over the window).
    err = abs(tied[55:70].mean() / sigma - 1)
    # Reflection: what the tie sends back shows in the left half (the reflected front would be
    # back at 25 mm): the difference to the bar in one piece there, element by element.
    refl = np.abs(tied[:50] - whole[:50]).max() / sigma
    check(err < 0.02, f"wave: plateau past the tie off by {err:.2%} of rho c0 v (limit 2 %)")
    check(refl < 0.02, f"wave: reflection {refl:.2%} of rho c0 v (limit 2 %)")
    check(drift < 0.01, f"wave: ETOTAL drift {drift:.2%} of ALLWK (limit 1 %)")
    print(f"check_tie.py: wave: plateau past the tie within {err:.2%} of rho c0 v = {sigma:.4e} "
          f"Pa, reflection at most {refl:.2%} (vs the bar in one piece), ETOTAL drift "
          f"{drift:.2e} of ALLWK")


# --- plate --------------------------------------------------------------------------------------
def plate_deck(period, output_interval):
    L, T = 0.01, 0.005
    m = Mesh()
    a = m.block((0, 0, 0), (L, L, T), (4, 4, 2), elset="BLOCK")
    p = m.plate((0, 0, T), (L, L), (5, 5), "PLATE")
    m.lines += nset("BASE", flat(a, lambda i, j, k: k == 0))
    m.lines += ["*SURFACE, NAME=TOP, TYPE=ELEMENT"] + [f"{e}, S2" for e in range(17, 33)]
    m.lines += ["*SURFACE, NAME=SHEET, TYPE=ELEMENT", "PLATE, SNEG"]
    m.lines += ["*TIE, NAME=SKIN, ADJUST=YES", "SHEET, TOP"]
    m.lines += material(NU_STEEL) + ["*SOLID SECTION, ELSET=BLOCK, MATERIAL=STEEL",
                                     "*SHELL SECTION, ELSET=PLATE, MATERIAL=STEEL", "0.0005"]
    m.lines += ["*AMPLITUDE, NAME=RAMP", f"0., 0., {2e-6!r}, 1., 1., 1."]
    m.lines += ["*BOUNDARY", "BASE, 1, 3",
                "*STEP", "*DYNAMIC, EXPLICIT", f", {period!r}",
                "*DLOAD, AMPLITUDE=RAMP", "PLATE, P, 2e8",
                f"*OUTPUT, FIELD, TIME INTERVAL={output_interval!r}", "*NODE OUTPUT", "U, V",
                "*ELEMENT OUTPUT", "S",
                "*OUTPUT, HISTORY, TIME INTERVAL=1e-7", "*ENERGY OUTPUT", "*END STEP"]
    return m, a, p


def last_frame(f):
    return f["frames"][sorted(f["frames"], key=lambda s: int(s.split("_")[-1]))[-1]]


def plate(binary, out):
    period = 6e-6
    m, a, p = plate_deck(period, period / 4)
    d = out / "plate"
    d.mkdir()
    (d / "plate.inp").write_text(m.text("shell plate tied to a block"))
    results = []
    for threads in (1, 2):
        r = d / f"t{threads}"
        code, text = xpl(binary, "run", str(d / "plate.inp"), "-o", str(r), "--threads",
                         str(threads), "--quiet")
        check(code == 0, f"plate: xpl exited {code} with {threads} threads\n{text}")
        results.append(r / "plate.h5")
    msg = read_msg(d / "t1", "plate")
    check(re.search(r"tie SKIN: 36 slave node\(s\) tied", msg), "plate: 36 tied nodes in .msg")
    same_results(results[0], results[1], "plate")
    with h5py.File(results[0], "r") as f:
        h = f["history/step_1/energy"]
        wk = h["ALLWK"][:]
        drift = np.abs(h["ETOTAL"][:] - h["ETOTAL"][0]).max() / max(np.abs(wk).max(), 1e-30)
        check(wk.max() > 0, "plate: the pressure does work")
        check(drift < 0.01, f"plate: ETOTAL drift {drift:.2%} of ALLWK (limit 1 %)")
        ids = list(f["mesh/node_ids"][:])
        row = {n: k for k, n in enumerate(ids)}
        x0 = f["mesh/coordinates"][:]
        u = last_frame(f)["U"][:]
        x = x0 + u
        umax = np.abs(u).max()
        worst = 0.0
        for i in range(6):
            for j in range(6):
                px, py = 0.01 * i / 5, 0.01 * j / 5
                ei, ej = min(int(px / 0.0025), 3), min(int(py / 0.0025), 3)
                xi, eta = px / 0.0025 - ei, py / 0.0025 - ej
                c = [a[ei][ej][2], a[ei + 1][ej][2], a[ei + 1][ej + 1][2], a[ei][ej + 1][2]]
                w = [(1 - xi) * (1 - eta), xi * (1 - eta), xi * eta, (1 - xi) * eta]
                target = sum(wk_ * x[row[n]] for wk_, n in zip(w, c))
                worst = max(worst, np.abs(x[row[p[i][j]]] - target).max())
        check(umax > 1e-7, f"plate: the block deforms (largest U {umax:.2e} m)")
        # Round-off of the interpolation only: relative 1e-9 of the motion.
        check(worst < 1e-9 * umax, f"plate: a plate node is {worst:.2e} m off the block's face")
    print(f"check_tie.py: plate: ETOTAL drift {drift:.2e} of ALLWK, plate nodes on the block face "
          f"to {worst:.1e} m (largest U {umax:.2e} m), 1 and 2 threads identical")
    return results[0], umax


# --- import ---------------------------------------------------------------------------------------
def import_case(binary, out, full, umax):
    period = 6e-6
    d = out / "import"
    d.mkdir()
    first, _, _ = plate_deck(period / 2, period / 4)
    (d / "first.inp").write_text(first.text("first half"))
    code, text = xpl(binary, "run", str(d / "first.inp"), "-o", str(d), "--quiet")
    check(code == 0, f"import: first half exited {code}\n{text}")
    second, _, _ = plate_deck(period / 2, period / 4)
    # The second half starts with the pressure at its full value (the ramp is over).
    text2 = second.text("second half").replace(f"0., 0., {2e-6!r}, 1., 1., 1.", "0., 1., 1., 1.")
    (d / "second.inp").write_text(text2)
    code, text = xpl(binary, "run", str(d / "second.inp"), "-o", str(d), "--import",
                     str(d / "first.h5"), "--quiet")
    check(code == 0, f"import: second half exited {code}\n{text}")
    with h5py.File(full, "r") as f, h5py.File(d / "second.h5", "r") as g:
        diff = np.abs(last_frame(f)["U"][:] - last_frame(g)["U"][:]).max()
    check(diff < 2e-3 * umax, f"import: end U differs by {diff:.2e} m = {diff / umax:.2e} of the "
          f"largest U (limit 2e-3)")
    print(f"check_tie.py: import: end U within {diff:.2e} m ({diff / umax:.1e} of the largest U) "
          f"of the uninterrupted run")


# --- overclosure ----------------------------------------------------------------------------------
def overclosure_run(binary, out, adjust):
    """Block B's bottom 0.01 mm inside block A's top, tied (POSITION TOLERANCE 0.1 mm), general
    contact over all exterior faces; returns the offsets' reasons, the nodes the contact pass
    moved, U of frame 0 of B's bottom nodes, and the .msg."""
    L, T, DEPTH = 0.004, 0.002, 1e-5
    m = Mesh()
    m.block((0, 0, 0), (L, L, T), (2, 2, 2), elset="A")
    b = m.block((0, 0, T - DEPTH), (L, L, T), (2, 2, 2), elset="B")
    m.lines += ["*SURFACE, NAME=A_TOP, TYPE=ELEMENT"] + [f"{e}, S2" for e in range(5, 9)]
    m.lines += ["*SURFACE, NAME=B_BOTTOM, TYPE=ELEMENT"] + [f"{e}, S1" for e in range(9, 13)]
    m.lines += [f"*TIE, NAME=GLUE, ADJUST={'YES' if adjust else 'NO'}, POSITION TOLERANCE=1e-4",
                "B_BOTTOM, A_TOP"]
    m.lines += material(NU_STEEL) + ["*SOLID SECTION, ELSET=A, MATERIAL=STEEL",
                                     "*SOLID SECTION, ELSET=B, MATERIAL=STEEL"]
    m.lines += ["*STEP", "*DYNAMIC, EXPLICIT", ", 1e-7", "*CONTACT",
                "*CONTACT INCLUSIONS, ALL EXTERIOR", "*OUTPUT, FIELD, NUMBER INTERVAL=1",
                "*NODE OUTPUT", "U", "*END STEP"]
    name = "adjust" if adjust else "held"
    d = out / "overclosure" / name
    d.mkdir(parents=True)
    (d / f"{name}.inp").write_text(m.text("tied nodes penetrating at t = 0"))
    code, text = xpl(binary, "run", str(d / f"{name}.inp"), "-o", str(d), "--quiet")
    check(code == 0, f"overclosure: exited {code}\n{text}")
    bottom = flat(b, lambda i, j, k: k == 0)
    with h5py.File(d / f"{name}.h5", "r") as f:
        t = f["overclosure/step_1/offsets"]
        reasons = [int(r) for r in t["reason"][:]] if int(t.attrs["rows"]) > 0 else []
        adjusted = int(f["overclosure/step_1/adjusted"].attrs["rows"])
        row = {n: k for k, n in enumerate(f["mesh/node_ids"][:])}
        u0 = f["frames"][sorted(f["frames"])[0]]["U"][:][[row[n] for n in bottom]]
    return reasons, adjusted, u0, read_msg(d, name), DEPTH


def overclosure(binary, out):
    # ADJUST=NO: the 9 slave nodes of B's bottom and the 9 master corners of A's top (inside
    # B's bottom faces) penetrate; all are held, their penetration an offset with reason tie.
    reasons, adjusted, u0, msg, depth = overclosure_run(binary, out, False)
    check(len(reasons) == 18 and set(reasons) == {7},
          f"overclosure: offsets {len(reasons)}, reasons {set(reasons)} (expected 18, all 7 tie)")
    check(adjusted == 0, f"overclosure: {adjusted} tied nodes were moved")
    check(np.abs(u0).max() == 0.0, "overclosure: ADJUST=NO moved a slave node")
    check("reason: tie" in msg, "overclosure: the .msg names reason tie")
    # ADJUST=YES: the tie moves the slave nodes onto A's top first (U3 = DEPTH at frame 0,
    # strain free); nothing penetrates any more, no offset.
    reasons_a, adjusted_a, u0_a, msg_a, _ = overclosure_run(binary, out, True)
    err = np.abs(u0_a[:, 2] - depth).max()
    check(err < 1e-12 and np.abs(u0_a[:, :2]).max() < 1e-12,
          f"overclosure: ADJUST=YES moved the slave nodes by {u0_a[:, 2].min():.3e}.."
          f"{u0_a[:, 2].max():.3e} m in z (expected {depth:.1e})")
    check(not reasons_a and adjusted_a == 0,
          f"overclosure: ADJUST=YES left {len(reasons_a)} offsets, {adjusted_a} contact moves")
    check("removed by ADJUST=YES" in msg_a, "overclosure: .msg names the ADJUST=YES move")
    print(f"check_tie.py: overclosure: ADJUST=NO 18 offsets, all reason tie, none moved; "
          f"ADJUST=YES slaves moved by {depth:.0e} m to {err:.1e}, no offset")


# --- deck errors ----------------------------------------------------------------------------------
def deck_errors(binary, out):
    """Four node conflicts in one deck: each one file:line error, all reported, exit code 1."""
    L, T = 0.004, 0.002
    m = Mesh()
    for k, name in enumerate("ABCD"):
        m.block((0, 0, k * T), (L, L, T), (2, 2, 1), elset=name)
    # Elements 1-4 A, 5-8 B, 9-12 C, 13-16 D; S1 bottom, S2 top.
    for name, first in (("A", 1), ("B", 5), ("C", 9), ("D", 13)):
        m.lines += [f"*SURFACE, NAME={name}_TOP, TYPE=ELEMENT"] + [
            f"{e}, S2" for e in range(first, first + 4)]
        m.lines += [f"*SURFACE, NAME={name}_BOTTOM, TYPE=ELEMENT"] + [
            f"{e}, S1" for e in range(first, first + 4)]
    m.lines += material(NU_STEEL) + ["*SOLID SECTION, ELSET=A, MATERIAL=STEEL",
                                     "*SOLID SECTION, ELSET=B, MATERIAL=STEEL",
                                     "*SOLID SECTION, ELSET=C, MATERIAL=STEEL",
                                     "*SOLID SECTION, ELSET=D, MATERIAL=STEEL"]
    m.nodes[999] = (0.0, 0.0, 0.02)
    m.lines += ["*RIGID BODY, REF NODE=999, ELSET=D"]
    b_bottom_node = 19  # block B's first node: on B's bottom face
    ties = {
        "T1": ("*TIE, NAME=T1", "B_BOTTOM, A_TOP",
               "has a boundary condition on a translational DOF"),
        "T2": ("*TIE, NAME=T2", "B_BOTTOM, C_BOTTOM", "is also a slave of tie T1"),
        "T3": ("*TIE, NAME=T3", "A_TOP, C_TOP", "is also a master node of tie T1"),
        "T4": ("*TIE, NAME=T4", "D_BOTTOM, C_TOP", "belongs to a rigid body"),
    }
    for keyword, data, _ in ties.values():
        m.lines += [keyword, data]
    m.lines += ["*STEP", "*DYNAMIC, EXPLICIT", ", 1e-7", "*BOUNDARY", f"{b_bottom_node}, 3, 3",
                "*END STEP"]
    d = out / "deck_errors"
    d.mkdir()
    text = m.text("tie conflicts")
    (d / "bad.inp").write_text(text)
    lines = text.splitlines()
    code, output = xpl(binary, "run", str(d / "bad.inp"), "-o", str(d / "out"))
    check(code == 1, f"deck errors: exit code {code} (expected 1)\n{output}")
    found = [l for l in output.splitlines() if "*TIE:" in l]
    check(len(found) == len(ties), f"deck errors: {len(found)} *TIE errors (expected "
          f"{len(ties)}):\n{output}")
    for name, (keyword, _, what) in ties.items():
        line = lines.index(keyword) + 1
        hits = [l for l in found if l.startswith(f"{d / 'bad.inp'}:{line}: *TIE:") or
                l.startswith(f"bad.inp:{line}: *TIE:")]
        check(len(hits) == 1 and what in hits[0],
              f"deck errors: tie {name} (line {line}): expected one error with {what!r}, got "
              f"{hits}\n{output}")
    check(not (d / "out" / "bad.h5").exists(), "deck errors: a result file was written")
    print(f"check_tie.py: deck errors: {len(ties)} conflicts, one file:line error each, exit 1")


# --- shells -------------------------------------------------------------------------------------
def shells(binary, out):
    """Lap joint of two S4R plates in one plane: MASTER (4 x 4, x 0..10 mm, clamped at x = 0)
    and SLAVE (5 x 5, x 6..16 mm) overlapping over 6..10 mm; a pressure on SLAVE bends the
    joint. The slave nodes over the master (x <= 10 mm, 18) are tied with their rotations, the
    others (x >= 12 mm, 18) are listed untied in the .msg. Checked: UR and U of every tied
    slave node equal the bilinear interpolation of its master corners (the tie passes
    rotations, else the joint would be a hinge), ETOTAL within 1 % of ALLWK."""
    W = 0.01
    m = Mesh()
    mp = m.plate((0, 0, 0), (W, W), (4, 4), "MASTER")
    sp = m.plate((0.006, 0, 0), (W, W), (5, 5), "SLAVE")
    m.lines += nset("CLAMP", [mp[0][j] for j in range(5)])
    m.lines += ["*SURFACE, NAME=M_SURF, TYPE=ELEMENT", "MASTER, SPOS",
                "*SURFACE, NAME=S_SURF, TYPE=ELEMENT", "SLAVE, SNEG",
                "*TIE, NAME=LAP", "S_SURF, M_SURF"]
    m.lines += material(NU_STEEL) + ["*SHELL SECTION, ELSET=MASTER, MATERIAL=STEEL", "0.0005",
                                     "*SHELL SECTION, ELSET=SLAVE, MATERIAL=STEEL", "0.0005"]
    m.lines += ["*AMPLITUDE, NAME=RAMP", f"0., 0., {2e-5!r}, 1., 1., 1.",
                "*BOUNDARY", "CLAMP, 1, 6",
                "*STEP", "*DYNAMIC, EXPLICIT", ", 3e-5",
                "*DLOAD, AMPLITUDE=RAMP", "SLAVE, P, 1e5",
                "*OUTPUT, FIELD, TIME INTERVAL=1e-5", "*NODE OUTPUT", "U, UR",
                "*OUTPUT, HISTORY, TIME INTERVAL=1e-7", "*ENERGY OUTPUT", "*END STEP"]
    d = out / "shells"
    d.mkdir()
    (d / "lap.inp").write_text(m.text("lap joint of two tied shell plates"))
    code, text = xpl(binary, "run", str(d / "lap.inp"), "-o", str(d), "--quiet")
    check(code == 0, f"shells: xpl exited {code}\n{text}")
    msg = read_msg(d, "lap")
    check(re.search(r"tie LAP: 18 slave node\(s\) tied", msg), "shells: 18 tied slave nodes")
    check(re.search(r"18 slave node\(s\) farther than the tolerance stay free: \d+", msg),
          "shells: the 18 untied slave nodes listed in .msg")
    with h5py.File(d / "lap.h5", "r") as f:
        check(f.attrs["status"] == "completed", f"shells: status {f.attrs['status']!r}")
        ids = list(f["mesh/node_ids"][:])
        row = {n: k for k, n in enumerate(ids)}
        fr = last_frame(f)
        u, ur = fr["U"][:], fr["UR"][:]
        h = f["history/step_1/energy"]
        drift = np.abs(h["ETOTAL"][:] - h["ETOTAL"][0]).max() / np.abs(h["ALLWK"][:]).max()
    worst_u = worst_r = 0.0
    for i in range(3):  # slave columns at x = 6, 8, 10 mm
        for j in range(6):
            px, py = 0.006 + 0.002 * i, W * j / 5
            ei, ej = min(int(px / 0.0025), 3), min(int(py / 0.0025), 3)
            xi, eta = px / 0.0025 - ei, py / 0.0025 - ej
            c = [mp[ei][ej], mp[ei + 1][ej], mp[ei + 1][ej + 1], mp[ei][ej + 1]]
            w = [(1 - xi) * (1 - eta), xi * (1 - eta), xi * eta, (1 - xi) * eta]
            s_row = row[sp[i][j]]
            u_tie = sum(a * u[row[n]] for a, n in zip(w, c))
            ur_tie = sum(a * ur[row[n]] for a, n in zip(w, c))
            worst_u = max(worst_u, np.abs(u[s_row] - u_tie).max())
            worst_r = max(worst_r, np.abs(ur[s_row] - ur_tie).max())
    umax, rmax = np.abs(u).max(), np.abs(ur).max()
    check(umax > 1e-6 and rmax > 1e-4, f"shells: the joint bends (U {umax:.2e} m, UR {rmax:.2e})")
    # U: exact up to round-off; UR: each rotation vector is integrated incrementally from the
    # tied angular velocity, which matches the interpolation to second order in the rotation.
    check(worst_u < 1e-9 * umax, f"shells: tied U off by {worst_u:.2e} m (largest U {umax:.2e})")
    check(worst_r < 1e-3 * rmax, f"shells: tied UR off by {worst_r:.2e} (largest UR {rmax:.2e})")
    check(drift < 0.01, f"shells: ETOTAL drift {drift:.2%} of ALLWK (limit 1 %)")
    print(f"check_tie.py: shells: tied U to {worst_u / umax:.1e}, UR to {worst_r / rmax:.1e} of "
          f"the largest, ETOTAL drift {drift:.1e} of ALLWK")
    # The tie sets the rotations of these slaves: a rotational BC on one would be overwritten,
    # so the deck is refused (one error at the *TIE line).
    text = m.text("lap joint with a rotational BC on a tied slave").replace(
        "*BOUNDARY\nCLAMP, 1, 6", f"*BOUNDARY\nCLAMP, 1, 6\n{sp[0][0]}, 4, 6")
    check(f"{sp[0][0]}, 4, 6" in text, "shells: rotational BC added to the deck")
    (d / "rot.inp").write_text(text)
    code, output = xpl(binary, "check", str(d / "rot.inp"))
    line = text.splitlines().index("*TIE, NAME=LAP") + 1
    hits = [l for l in output.splitlines() if "*TIE:" in l]
    check(code == 1 and len(hits) == 1 and f"rot.inp:{line}: *TIE:" in hits[0] and
          "rotational DOF" in hits[0], f"shells: rotational BC on a tied slave: exit {code}, "
          f"errors {hits}\n{output}")


# --- threads ------------------------------------------------------------------------------------
def same_results(a, b, what):
    """Every frame field and history series of two result files, bit for bit."""
    with h5py.File(a, "r") as f, h5py.File(b, "r") as g:
        check(f.attrs["status"] == "completed", f"{what}: status {f.attrs['status']!r}")
        check(sorted(f["frames"]) == sorted(g["frames"]), f"{what}: different frames")
        for name in f["frames"]:
            for field in f["frames"][name]:
                check(f["frames"][name][field][()].tobytes() ==
                      g["frames"][name][field][()].tobytes(),
                      f"{what}: frame {name} {field} differs between 1 and 2 threads")

        def same(name, obj):
            if isinstance(obj, h5py.Dataset):
                check(obj[()].tobytes() == g["history"][name][()].tobytes(),
                      f"{what}: history {name} differs between 1 and 2 threads")

        f["history"].visititems(same)


def threads(binary, out):
    """A tied model large enough (6570 nodes) that the nodal update and the loads pass split
    into chunks across threads: 1 and 2 threads bit for bit."""
    L, T = 0.04, 0.01
    m = Mesh()
    a = m.block((0, 0, 0), (L, L, T), (16, 16, 8), elset="A")
    m.block((0, 0, T), (L, L, T), (20, 20, 8), elset="B")
    first_b = 1 + 16 * 16 * 8
    m.lines += nset("BASE", flat(a, lambda i, j, k: k == 0))
    m.lines += ["*SURFACE, NAME=A_TOP, TYPE=ELEMENT"] + [
        f"{e}, S2" for e in range(first_b - 256, first_b)]
    m.lines += ["*SURFACE, NAME=B_BOTTOM, TYPE=ELEMENT"] + [
        f"{e}, S1" for e in range(first_b, first_b + 400)]
    m.lines += ["*TIE, NAME=GLUE", "B_BOTTOM, A_TOP"]
    m.lines += material(NU_STEEL) + ["*SOLID SECTION, ELSET=A, MATERIAL=STEEL",
                                     "*SOLID SECTION, ELSET=B, MATERIAL=STEEL"]
    m.lines += ["*INITIAL CONDITIONS, TYPE=VELOCITY"] + [
        f"{n}, 3, {-5.0 * x[0] / L!r}" for n, x in m.nodes.items() if x[2] > T + 1e-9]
    m.lines += ["*BOUNDARY", "BASE, 1, 3", "*STEP", "*DYNAMIC, EXPLICIT", ", 2e-5",
                "*DLOAD", "B, GRAV, 9.81, 0, 0, -1",
                "*OUTPUT, FIELD, NUMBER INTERVAL=20", "*NODE OUTPUT", "U, V, A",
                "*ELEMENT OUTPUT", "S",
                "*OUTPUT, HISTORY, NUMBER INTERVAL=1", "*ENERGY OUTPUT", "*END STEP"]
    d = out / "threads"
    d.mkdir()
    (d / "big.inp").write_text(m.text("tied blocks, 6570 nodes"))
    results = []
    for n_threads in (1, 2):
        r = d / f"t{n_threads}"
        code, text = xpl(binary, "run", str(d / "big.inp"), "-o", str(r), "--threads",
                         str(n_threads), "--quiet")
        check(code == 0, f"threads: xpl exited {code} with {n_threads} threads\n{text}")
        results.append(r / "big.h5")
    same_results(results[0], results[1], "threads")
    with h5py.File(results[0], "r") as f:
        h = f["history/step_1/energy"]
        scale = max(np.abs(h["ALLKE"][:]).max(), np.abs(h["ALLWK"][:]).max())
        drift = np.abs(h["ETOTAL"][:] - h["ETOTAL"][0]).max() / scale
        n_nodes = len(f["mesh/node_ids"])
    check(n_nodes > 2 * 2048, f"threads: {n_nodes} nodes, fewer than two node chunks")
    check(drift < 0.01, f"threads: ETOTAL drift {drift:.2%} (limit 1 %)")
    print(f"check_tie.py: threads: {n_nodes} nodes, 1 and 2 threads identical, ETOTAL drift "
          f"{drift:.1e}")


# --- example ------------------------------------------------------------------------------------
def example(binary, out):
    """examples/tie/glued_drop.inp: runs, all 36 slave nodes tied, ETOTAL balanced, the glued
    blocks rebound from the wall together (the upper block's mean V3 turns positive)."""
    deck = pathlib.Path(__file__).resolve().parents[2] / "examples" / "tie" / "glued_drop.inp"
    d = out / "example"
    code, text = xpl(binary, "run", str(deck), "-o", str(d), "--quiet")
    check(code == 0, f"example: xpl exited {code}\n{text}")
    msg = read_msg(d, "glued_drop")
    check(re.search(r"tie GLUE: 36 slave node\(s\) tied", msg), "example: 36 tied slave nodes")
    check("no slave node outside the tolerance" in msg, "example: every slave node tied")
    with h5py.File(d / "glued_drop.h5", "r") as f:
        check(f.attrs["status"] == "completed", f"example: status {f.attrs['status']!r}")
        h = f["history/step_1/energy"]
        ke = h["ALLKE"][:]
        drift = np.abs(h["ETOTAL"][:] - h["ETOTAL"][0]).max() / ke[0]
        ids = list(f["mesh/node_ids"][:])
        upper = [k for k, n in enumerate(ids) if 1001 <= n < 2000]
        lower = [k for k, n in enumerate(ids) if n < 1000]
        v = last_frame(f)["V"][:]
    check(drift < 0.01, f"example: ETOTAL drift {drift:.2%} of the initial ALLKE (limit 1 %)")
    vu, vl = v[upper, 2].mean(), v[lower, 2].mean()
    check(vu > 0 and vl > 0, f"example: mean V3 after the impact upper {vu:.3f}, lower "
          f"{vl:.3f} m/s (expected both rebounding, > 0)")
    print(f"check_tie.py: example: ETOTAL drift {drift:.2e} of ALLKE, rebound V3 upper {vu:.3f}, "
          f"lower {vl:.3f} m/s")


CASES = ("deck_errors", "patch", "wave", "plate", "shells", "threads", "overclosure",
         "example")


def main():
    if len(sys.argv) not in (3, 4) or (len(sys.argv) == 4 and sys.argv[3] not in CASES):
        sys.exit(__doc__)
    binary, out = sys.argv[1], pathlib.Path(sys.argv[2])
    cases = [sys.argv[3]] if len(sys.argv) == 4 else list(CASES)
    shutil.rmtree(out, ignore_errors=True)
    out.mkdir(parents=True)
    for case in cases:
        if case == "deck_errors":
            deck_errors(binary, out)
        elif case == "patch":
            patch(binary, out)
            patch(binary, out, driven=False)
        elif case == "wave":
            wave(binary, out)
        elif case == "plate":
            full, umax = plate(binary, out)
            import_case(binary, out, full, umax)
        elif case == "shells":
            shells(binary, out)
        elif case == "threads":
            threads(binary, out)
        elif case == "overclosure":
            overclosure(binary, out)
        elif case == "example":
            example(binary, out)
    print(f"check_tie.py: {', '.join(cases)} passed")


if __name__ == "__main__":
    main()
