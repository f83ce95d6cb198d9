#!/usr/bin/python3
"""Acceptance checks of the initial-overclosure pass on the decks of examples/overclosure
(issue 5, SPEC C2-C6, C11, C12).

Usage: check_overclosure.py CASE DIRECTORY

DIRECTORY holds CASE.h5, CASE.msg, CASE.sta of `xpl run` (or `xpl check` for CASE = check,
which reads blocks_adjust.*). Reference energy E_ref = the kinetic energy of the whole model
at 1 m/s; "zero" energies must stay below 1e-9 E_ref. Exits non-zero on the first failed check.
"""

import pathlib
import re
import sys

import h5py
import numpy as np

H = 1.0e-3
RHO = 7850.0
BODY = 100000


def check(condition, message):
    if not condition:
        sys.exit(f"check_overclosure.py: FAILED: {message}")
    print(f"check_overclosure.py: ok: {message}")


def frames(f):
    return [f["frames"][k] for k in sorted(f["frames"].keys())]


def rows(f, step, table):
    return int(f[f"overclosure/step_{step}/{table}"].attrs["rows"])


def node_rows(f):
    ids = f["mesh/node_ids"][:]
    return ids, {int(n): i for i, n in enumerate(ids)}


def block_pair_mass():
    return RHO * (4 * 4 * 2 + 2 * 2 * 2) * H**3


def energies_zero(h, e_ref, what):
    for name in ("ALLKE", "ALLIE", "ALLPW"):
        peak = np.abs(h["energy"][name][:]).max()
        check(peak <= 1e-9 * e_ref, f"{what}: {name} stays {peak:.3e} J <= 1e-9 E_ref ({e_ref:.3e} J)")


def adjusted_matches_u(f, frame):
    """U of `frame` is the adjustment: distance * direction on listed nodes, zero elsewhere."""
    t = f["overclosure/step_1/adjusted"]
    ids, row = node_rows(f)
    u = frame["U"][:]
    expected = np.zeros_like(u)
    for n, d, v in zip(t["node"][:], t["distance"][:], t["direction"][:]):
        expected[row[int(n)]] = d * v
    err = np.abs(u - expected).max()
    check(err <= 1e-15, f"U of frame 0 equals the reported adjustments (max difference {err:.1e} m)")


def blocks_adjust(d, name="blocks_adjust", detail=True):
    f = h5py.File(d / f"{name}.h5", "r")
    msg = (d / f"{name}.msg").read_text()
    sta = (d / f"{name}.sta").read_text()
    check(rows(f, 1, "adjusted") == 18, "18 nodes adjusted (9 of A's top face under B, 9 of B's bottom)")
    check(rows(f, 1, "offsets") == 0 and rows(f, 1, "ignored") == 0, "no offsets, nothing ignored")
    dist = f["overclosure/step_1/adjusted/distance"][:]
    check(np.abs(dist - 0.025e-3).max() < 1e-9 * H,
          "balanced views: each surface moves half of the 0.05 mm overlap (1e-9 relative)")
    fr = frames(f)
    adjusted_matches_u(f, fr[0])
    ids, row = node_rows(f)
    x = f["mesh/coordinates"][:] + fr[0]["U"][:]
    moved = [row[int(n)] for n in f["overclosure/step_1/adjusted/node"][:]]
    gap = np.abs(x[moved, 2] - 1.975e-3).max()
    check(gap < 1e-9 * H, f"adjusted nodes lie on the common surface z = 1.975 mm (|d| = {gap:.1e} m)")
    h = f["history/step_1"]
    check(len(h["time"]) > 100 and fr[-1].attrs["increment"] >= 1000,
          f"{fr[-1].attrs['increment']} increments run")
    energies_zero(h, 0.5 * block_pair_mass(), "at rest after the adjustment")
    drift = np.abs(fr[-1]["U"][:] - fr[0]["U"][:]).max()
    check(drift < 1e-15, f"nothing moves after frame 0 ({drift:.1e} m)")
    listed = len(re.findall(r"adjusted by", msg))
    check(listed == (18 if detail else 0),
          f"{'DETAIL' if detail else 'SUMMARY'}: {listed} adjusted nodes listed in the .msg file")
    check("18 node(s) adjusted, 0 offset(s), 0 ignored" in sta, "the .sta file has the summary line")


def blocks_deep(d):
    f = h5py.File(d / "blocks_deep.h5", "r")
    msg = (d / "blocks_deep.msg").read_text()
    check(rows(f, 1, "ignored") == 18 and rows(f, 1, "adjusted") == 0 and rows(f, 1, "offsets") == 0,
          "30 % overlap: 18 nodes ignored, none adjusted, no offsets")
    t = f["overclosure/step_1/ignored"]
    check(np.allclose(t["depth"][:], 0.3e-3) and np.allclose(t["limit"][:], 0.15e-3),
          "ignored at depth 0.30 mm against the limit 0.15 mm (15 % of the facet)")
    check(len(re.findall(r"deeper than the automatic limit", msg)) == 18, "each ignored node is a .msg warning")
    h = f["history/step_1"]
    ke = h["energy"]["ALLKE"][:]
    check(ke.max() > 1.0, f"the plain penalty pushes the blocks apart (ALLKE reaches {ke.max():.2f} J)")
    # The push-out's stepping loses 3.3 % of the energy (before ALLKE = ½ v(n-½)·M·v(n+½)
    # and the trapezoidal ALLVD it showed as +27 % and the watchdog failed the run): the run
    # completes, the drift past 1 % warned of in the .sta file.
    check(f.attrs["status"] == "completed", f"the push-out completes (status "
          f"{f.attrs['status']!r}, error {f.attrs['error']!r})")
    check("WARNING: energy balance" in (d / "blocks_deep.sta").read_text(),
          "the 1 % drift was warned of in the .sta file")


def blocks_bc(d):
    f = h5py.File(d / "blocks_bc.h5", "r")
    check(rows(f, 1, "offsets") == 18 and rows(f, 1, "adjusted") == 0, "held faces: 18 offsets, no adjustment")
    t = f["overclosure/step_1/offsets"]
    check(np.allclose(t["offset"][:], 0.05e-3, rtol=1e-9) and set(t["reason"][:]) == {0},
          "each offset d0 = 0.05 mm, reason BC")
    cfn = {s: f[f"history/{s}/contact/ALL_EXTERIOR/CFN"][:] for s in ("step_1", "step_2", "step_3")}
    times = {s: f[f"history/{s}/time"][:] for s in cfn}
    # Step 3: A's top face (prescribed) closes on B's fixed bottom face; both faces are
    # prescribed, so the force is k * penetration exactly, with the penetration taken from U.
    ids, row = node_rows(f)
    x0 = f["mesh/coordinates"][:]
    a_top = [i for i, n in enumerate(ids) if n // BODY == 1 and abs(x0[i, 2] - 2 * H) < 1e-12
             and H - 1e-12 <= x0[i, 0] <= 3 * H + 1e-12 and H - 1e-12 <= x0[i, 1] <= 3 * H + 1e-12]
    pen, force = [], []
    for fr in frames(f):
        if int(fr.attrs["step"]) != 3:  # 1-based, as in the deck
            continue
        z = x0[a_top, 2] + fr["U"][:][a_top, 2]
        p = z.mean() - (2 * H - 0.05e-3)
        k = np.argmin(np.abs(times["step_3"] - fr.attrs["time"]))
        if abs(times["step_3"][k] - fr.attrs["time"]) < 1e-12:
            pen.append(p)
            force.append(cfn["step_3"][k])
    pen, force = np.array(pen), np.array(force)
    closed = pen > 0.01e-3
    check(closed.sum() >= 2, f"{closed.sum()} frames of step 3 with the faces overlapping by > 0.01 mm")
    stiffness = force[closed] / pen[closed]
    spread = stiffness.max() / stiffness.min() - 1
    check(spread < 0.01, f"step 3: force = k * penetration with d0 = 0 (k constant within {spread:.1e})")
    check(np.all(force[pen < -1e-9] == 0.0), "no force while the faces are apart")
    plain = stiffness.mean() * 0.05e-3
    early = max(np.abs(cfn["step_1"]).max(), np.abs(cfn["step_2"]).max())
    check(early <= 1e-6 * plain,
          f"steps 1-2: contact force {early:.2e} N <= 1e-6 of the plain penalty force {plain:.3e} N")
    check(abs(pen.max() - 0.07e-3) < 1e-9, f"step 3 ends with the faces 0.07 mm into each other ({pen.max():.3e})")


def pinched(d):
    f = h5py.File(d / "pinched.h5", "r")
    t = f["overclosure/step_1/offsets"]
    reason, node = t["reason"][:], t["node"][:]
    # Reasons as in contact/adjustment_pass.hpp: 1 rigid, 2 pinched. The sheet (nodes 3xxxxx)
    # is pinched; the dies' nodes over the sheet (3 x 3 each) are slaves too, pressed 0.05 mm
    # into its half thickness, and cannot move (rigid bodies).
    check(np.sum((reason == 2) & (node // 100000 == 3)) == 16 and np.all(reason[reason != 1] == 2),
          "16 sheet nodes keep offsets with reason pinched")
    check(np.sum((reason == 1) & (node // 100000 != 3)) == 18 and rows(f, 1, "offsets") == 34,
          "18 die nodes over the sheet keep offsets with reason rigid")
    check(np.allclose(t["offset"][:], 0.05e-3, rtol=1e-9), "d0 = 0.05 mm")
    h = f["history/step_1"]
    check(np.abs(h["contact/ALL_EXTERIOR/CFN"][:]).max() == 0.0, "no contact force")
    check(np.abs(h["energy/ALLKE"][:]).max() == 0.0, "nothing moves")


def shells_overlap(d):
    f = h5py.File(d / "shells_overlap.h5", "r")
    ids, _ = node_rows(f)
    x = f["mesh/coordinates"][:] + frames(f)[0]["U"][:]
    for body, z, what in ((2, 1.0e-3, "UP (+0.3 mm) moves to the top face: z = +1 mm"),
                          (3, -1.0e-3, "DOWN (-0.3 mm) moves to the bottom face: z = -1 mm"),
                          (4, 1.2e-3, "FAR (beyond the thickness) stays at z = 1.2 mm")):
        zz = x[ids // BODY == body, 2]
        check(np.abs(zz - z).max() < 1e-9 * H, what)
    check(rows(f, 1, "adjusted") == 12, "12 nodes adjusted (UP and DOWN)")
    energies_zero(f["history/step_1"], 0.5 * RHO * 1e-3 * (27 + 6) * H * H, "after the adjustment")


def crossed(d, off=False):
    f = h5py.File(d / f"{'crossed_off' if off else 'crossed'}.h5", "r")
    msg = (d / f"{'crossed_off' if off else 'crossed'}.msg").read_text()
    warnings = re.findall(r"crossed surfaces: slave nodes (\d+) and (\d+)", msg)
    if off:
        check(not warnings and rows(f, 1, "crossed") == 0, "DETECT CROSSED SURFACES=OFF: no warning")
        return
    col = 2 * BODY + 1
    expected = {(col + i + 100 * j + 10000, col + i + 100 * j + 20000) for i in (0, 1) for j in (0, 1)}
    found = {tuple(sorted((int(a), int(b)))) for a, b in warnings}
    check(expected <= found, f"the column's four edges through the plate are reported: {sorted(expected)}")
    check(rows(f, 1, "crossed") == len(warnings), f"{len(warnings)} warnings = rows of /overclosure/.../crossed")


def later_step(d):
    f = h5py.File(d / "later_step.h5", "r")
    check("step_1" not in f["overclosure"], "no contact in step 1: no pass")
    t = f["overclosure/step_2/offsets"]
    check(rows(f, 2, "offsets") == 18 and set(t["reason"][:]) == {5} and rows(f, 2, "adjusted") == 0,
          "step 2: 18 offsets with reason 'later step', no node adjusted")
    umax = max(np.abs(fr["U"][:]).max() for fr in frames(f))
    check(umax == 0.0, "no node moves in any frame")
    h = f["history/step_2"]
    check(np.abs(h["contact/ALL_EXTERIOR/CFN"][:]).max() == 0.0, "no contact force in step 2")
    energies_zero(h, 0.5 * block_pair_mass(), "step 2")


def data_check(d):
    f = h5py.File(d / "blocks_adjust.h5", "r")
    check(f.attrs["status"] == "checked", "status 'checked'")
    fr = frames(f)
    check(len(fr) == 1 and fr[0].attrs["increment"] == 0, "only frame 0, before increment 1")
    adjusted_matches_u(f, fr[0])
    sta = (d / "blocks_adjust.sta").read_text()
    increments = [int(line.split()[1]) for line in sta.splitlines()
                  if re.match(r"^\s+\d+\s+\d+\s+[-\d.]+E", line)]
    check(max(increments, default=0) == 0, "no increment in the .sta file")
    check("18 node(s) adjusted" in sta, "the summary line is in the .sta file")


def lumped_masses(f):
    """Nodal masses of the C3D8R mesh (rho V / 8 per element corner), by row."""
    x = f["mesh/coordinates"][:]
    m = np.zeros(len(x))
    for conn in f["mesh/C3D8R/connectivity"][:]:
        p = x[conn]
        d = p[6] - p[0]  # the blocks are axis-aligned boxes
        m[conn] += RHO * abs(d[0] * d[1] * d[2]) / 8
    return m


def import_target(d):
    f = h5py.File(d / "import_target.h5", "r")
    t = f["overclosure/step_1/offsets"]
    check(rows(f, 1, "offsets") == 18 and set(t["reason"][:]) == {6} and rows(f, 1, "adjusted") == 0,
          "imported penetrations: 18 offsets with reason 'import', no node moves")
    check(np.allclose(t["offset"][:], 0.05e-3, rtol=1e-6), "d0 = the 0.05 mm penetration of the last frame")
    # The force a plain penalty would give at t = 0: sum over both views of w k d0 with the
    # default stiffness k = 0.5 m_eff / dt^2 (docs/theory/contact.md, C1), m_eff of the slave node and the
    # coincident node of the other block.
    sta = (d / "import_target.sta").read_text()
    dt = float(next(line.split()[4] for line in sta.splitlines()
                    if re.match(r"^\s+1\s+0\s", line)))
    ids, row = node_rows(f)
    x = f["mesh/coordinates"][:] + frames(f)[0]["U"][:]
    m = lumped_masses(f)
    plain = 0.0
    for n, d0 in zip(t["node"][:], t["offset"][:]):
        i = row[int(n)]
        other = np.where(ids // BODY != ids[i] // BODY)[0]
        j = other[np.argmin(np.linalg.norm(x[other] - x[i], axis=1))]
        m_eff = m[i] * m[j] / (m[i] + m[j])
        plain += 0.5 * 0.5 * m_eff / dt**2 * d0
    h = f["history/step_1"]
    cfn = h["contact/ALL_EXTERIOR/CFN"][:]
    check(cfn[0] == 0.0, "no contact force at the start of the imported run")
    check(cfn.max() < 0.05 * plain,
          f"no force spike: contact force stays <= {cfn.max():.1f} N, under 5 % of the "
          f"plain-penalty force {plain:.3e} N on the imported penetration")
    check(cfn[1:].max() > 0.0, "the force grows from zero as B keeps moving into A")


def adjusted_surfaces(f):
    """Slave surface names of the rows of /overclosure/step_1/adjusted."""
    t = f["overclosure/step_1/adjusted"]
    names = str(t.attrs["surface_names"]).split(",")
    return [names[int(k)] for k in t["slave_surface"][:]]


NOT_CHECKED = re.compile(r"crossed surfaces: (\d+) slave node\(s\) of node-based surfaces are not checked")


def node_block(out):
    """SPEC C13: the node_block_* decks (element-based face, node-based surface in a *CONTACT
    PAIR and in general contact) hold the same four slave nodes against the same master: the
    same adjustment and the same contact force history. OUT holds overclosure_node_block_*/."""
    cfn = {}
    for kind in ("elem", "nodes", "general"):
        name = f"node_block_{kind}"
        d = out / f"overclosure_{name}"
        f = h5py.File(d / f"{name}.h5", "r")
        msg = (d / f"{name}.msg").read_text()
        check(rows(f, 1, "adjusted") == 4 and rows(f, 1, "offsets") == 0 and rows(f, 1, "ignored") == 0,
              f"{kind}: the cube's four bottom nodes adjusted (C2), no offsets, nothing ignored")
        t = f["overclosure/step_1/adjusted"]
        check(np.abs(t["distance"][:] - 0.02e-3).max() < 1e-9 * H
              and np.abs(t["direction"][:] - [0.0, 0.0, 1.0]).max() < 1e-12,
              f"{kind}: each moved 0.02 mm up onto the base (the whole overlap: a one-sided view)")
        check(set(adjusted_surfaces(f)) == {"CUBE_BOTTOM"}, f"{kind}: listed with slave surface CUBE_BOTTOM")
        adjusted_matches_u(f, frames(f)[0])
        found = NOT_CHECKED.findall(msg)
        if kind == "elem":
            check(not found, "elem: no node-based note in the .msg")
        else:
            check(found == ["4"], f"{kind}: one .msg line says the 4 node-based slave nodes are not "
                                  "checked for crossed surfaces (C5)")
        h = f["history/step_1/contact"]
        cfn[kind] = h[list(h.keys())[0]]["CFN"][:]
    peak = np.abs(cfn["elem"]).max()
    check(peak > 1.0, f"the cube hits the base (peak CFN {peak:.3f} N)")
    for kind in ("nodes", "general"):
        diff = np.abs(cfn[kind] - cfn["elem"]).max()
        check(cfn[kind].shape == cfn["elem"].shape and diff <= 1e-12 * peak,
              f"{kind}: CFN history equals the element-based one (max difference {diff:.1e} N "
              f"<= 1e-12 of the peak)")


def node_masses(d):
    """Point masses (a node-based surface) dropped on an S4R plate (SPEC C13, C2, C4, C5)."""
    f = h5py.File(d / "node_masses.h5", "r")
    msg = (d / "node_masses.msg").read_text()
    dipped = 2 * BODY + 1
    t = f["overclosure/step_1/adjusted"]
    check(rows(f, 1, "adjusted") == 1 and int(t["node"][0]) == dipped and adjusted_surfaces(f) == ["DROPS"],
          "DIPPED (inside the plate's thickness) is the one adjusted node, of slave surface DROPS")
    check(abs(t["distance"][0] - 0.05e-3) < 1e-9 * H and abs(t["direction"][0][2] - 1.0) < 1e-12,
          "it moved 0.05 mm up, onto the plate's upper face (the nearer one, C4)")
    check(rows(f, 1, "offsets") == 0 and rows(f, 1, "ignored") == 0, "no offsets, nothing ignored")
    fr = frames(f)
    adjusted_matches_u(f, fr[0])
    check(re.search(rf"initial overclosure: node {dipped} \(slave surface DROPS\) adjusted", msg) is not None,
          "the .msg lists the adjustment with the node-based surface's name")
    check(NOT_CHECKED.findall(msg) == ["4"], "one .msg line: 4 node-based slave nodes not checked for crossed surfaces")
    ids, row = node_rows(f)
    drops = [row[2 * BODY + k] for k in (1, 2, 3, 4)]
    vz = fr[-1]["V"][:][drops, 2]
    check((vz > 0.0).all(), f"all four masses bounce off the plate (final v_z {np.round(vz, 3).tolist()} m/s)")
    z = f["mesh/coordinates"][:][drops, 2] + fr[-1]["U"][:][drops, 2]
    check((z > 0.0).all(), "none passed the plate's mid-surface")
    check(f.attrs["status"] == "completed", "the run completed (energy balanced)")


CASES = {
    "blocks_adjust": blocks_adjust,
    "node_block": node_block,
    "node_masses": node_masses,
    "blocks_summary": lambda d: blocks_adjust(d, "blocks_summary", detail=False),
    "blocks_deep": blocks_deep,
    "blocks_bc": blocks_bc,
    "pinched": pinched,
    "shells_overlap": shells_overlap,
    "crossed": crossed,
    "crossed_off": lambda d: crossed(d, off=True),
    "later_step": later_step,
    "check": data_check,
    "import_target": import_target,
}


def main():
    if len(sys.argv) != 3 or sys.argv[1] not in CASES:
        sys.exit(__doc__)
    CASES[sys.argv[1]](pathlib.Path(sys.argv[2]))


if __name__ == "__main__":
    main()
