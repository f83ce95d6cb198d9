#!/usr/bin/python3
"""Acceptance checks of general contact on the decks of examples/contact (issue 4).

Usage: check_contact.py CASE DIRECTORY

DIRECTORY holds CASE.h5 from `xpl run` of examples/contact/CASE/CASE.inp (see run_xpl.py).
Each case compares with an analytic answer and states its tolerance:

  bar_bar*    two equal bars: interface stress rho c0 v/2 within 3 %, contact time 2L/c0
              within +6 %/-2 %, bar velocities after contact within 0.2 m/s of 0 and 10 m/s,
              ETOTAL drift under 1 % of ALLKE(0)
  bar_wall    bar on a rigid wall: rho c0 v within 3 %, rebound speed within 2 %
  hertz       sphere on a rigid plane: peak force within 8 % and contact time within 5 % of
              Hertz (the numbers are printed either way)
  shell_block* a block pushes a shell plate from above or below: the plate moves with the
              block, momentum is conserved, no node passes through the plate
  friction_block  deceleration mu g within 3 %, ALLFD = mu m g x within 3 %
  tube_crush  S4R tube crushed by a rigid plate (self contact): ETOTAL drift under 2 % of the
              work, ALLPW never negative, no node deeper than 10 % of the element size in
              another wall's contact layer
Exits non-zero with a message on the first failed check.
"""

import math
import pathlib
import sys

import h5py
import numpy as np

E, RHO = 200.0e9, 7850.0
C0 = math.sqrt(E / RHO)


def check(condition, message):
    if not condition:
        sys.exit(f"check_contact.py: FAILED: {message}")
    print(f"check_contact.py: ok: {message}")


def contact_window(time, force, fraction=1e-3):
    """First and last time the total normal force exceeds `fraction` of its peak."""
    on = time[force > fraction * force.max()]
    return on[0], on[-1]


def energy_drift(history):
    e = history["energy"]
    return np.abs(e["ETOTAL"][:] - e["ETOTAL"][0]).max(), e["ALLKE"][0]


def last_frame(f):
    return f["frames"][sorted(f["frames"].keys())[-1]]


def bar_bar(f, h, pair):
    t = h["time"][:]
    force = h["contact"][pair]["CFN"][:]
    area = 0.010 * 0.010
    stress = np.median(force[force > 0.5 * force.max()]) / area
    expected = RHO * C0 * 10.0 / 2.0
    check(abs(stress / expected - 1) < 0.03,
          f"interface stress {stress / 1e6:.1f} MPa vs rho c0 v/2 = {expected / 1e6:.1f} MPa (3 %)")
    start, end = contact_window(t, force)
    duration, exact = end - start, 2 * 0.100 / C0
    check(-0.02 < duration / exact - 1 < 0.06,
          f"contact time {duration * 1e6:.2f} us vs 2L/c0 = {exact * 1e6:.2f} us (+6 %/-2 %)")
    # Bar velocities after contact: momentum-weighted means of the last frame (nodes of each
    # bar by position: bar A starts at x < 0.1005).
    frame = last_frame(f)
    x0 = f["mesh/coordinates"][:, 0]
    v = frame["V"][:, 0]
    v_a, v_b = v[x0 < 0.1005].mean(), v[x0 > 0.1005].mean()
    check(abs(v_a) < 0.2 and abs(v_b - 10.0) < 0.2,
          f"after contact v_A = {v_a:.3f} m/s (0), v_B = {v_b:.3f} m/s (10), within 0.2 m/s")
    drift, ke0 = energy_drift(h)
    check(drift < 0.01 * ke0, f"ETOTAL drift {drift:.3g} J < 1 % of ALLKE(0) = {ke0:.3g} J")
    pw = h["energy/ALLPW"][:]
    check(pw.max() > 0 and abs(pw[-1]) < 0.02 * pw.max(),
          f"penalty energy returned after separation (ALLPW end {pw[-1]:.3g} J, "
          f"peak {pw.max():.3g} J)")


def bar_wall(f, h):
    t = h["time"][:]
    force = h["contact/ALL_EXTERIOR/CFN"][:]
    stress = np.median(force[force > 0.5 * force.max()]) / 1e-4
    expected = RHO * C0 * 10.0
    check(abs(stress / expected - 1) < 0.03,
          f"wall stress {stress / 1e6:.1f} MPa vs rho c0 v = {expected / 1e6:.1f} MPa (3 %)")
    frame = last_frame(f)
    x0 = f["mesh/coordinates"][:, 0]
    rebound = -frame["V"][:, 0][x0 <= 0.1].mean()
    check(abs(rebound / 10.0 - 1) < 0.02, f"rebound speed {rebound:.3f} m/s vs 10 m/s (2 %)")
    drift, ke0 = energy_drift(h)
    check(drift < 0.01 * ke0, f"ETOTAL drift {drift:.3g} J < 1 % of ALLKE(0)")


def hertz(f, h):
    nu, radius, v = 0.3, 0.010, 5.0
    e_star = E / (1 - nu * nu)
    mass = RHO * 4.0 / 3.0 * math.pi * radius**3
    delta = (15 * mass * v * v / (16 * e_star * math.sqrt(radius))) ** 0.4
    peak = 4.0 / 3.0 * e_star * math.sqrt(radius) * delta**1.5
    duration = 2.9432 * delta / v
    t = h["time"][:]
    force = 4.0 * h["contact/ALL_EXTERIOR/CFN"][:]  # quarter model
    # Contact time where the force exceeds 1 % of its peak: F ~ delta^1.5, so the part below
    # 1 % is 0.05 delta_max deep and a few tenths of a microsecond long at each end; the
    # comparison with the full Hertz time is therefore slightly in the short direction.
    start, end = contact_window(t, force, 1e-2)
    print(f"hertz: peak {force.max() / 1e3:.2f} kN vs {peak / 1e3:.2f} kN "
          f"({(force.max() / peak - 1) * 100:+.1f} %), contact time {(end - start) * 1e6:.2f} us "
          f"vs {duration * 1e6:.2f} us ({((end - start) / duration - 1) * 100:+.1f} %)")
    check(abs(force.max() / peak - 1) < 0.08, "Hertz peak force within 8 %")
    check(abs((end - start) / duration - 1) < 0.05, "Hertz contact time within 5 %")


def shell_block(f, h, direction):
    # The plate centre (history node set CENTRE) is pushed the way the block moves.
    centre = h["node/CENTRE/U3"][:].ravel()
    peak = centre.max() if direction > 0 else centre.min()
    check(peak * direction > 0.01e-3,
          f"the plate centre moved {peak * 1e3:.4f} mm in the push direction {direction:+d}")
    # No block node ever beyond the plate's mid-surface (it would have passed through): check
    # every frame, block nodes against the plate's nodes below (above) them.
    x0 = f["mesh/coordinates"][:]
    plate = np.abs(x0[:, 2]) < 1e-9
    worst = np.inf
    for name in f["frames"]:
        z = x0[:, 2] + f["frames"][name]["U"][:, 2]
        gap = (z[~plate].min() - z[plate].max()) if direction < 0 else \
            (z[plate].min() - z[~plate].max())
        worst = min(worst, gap)
    check(worst > 0, f"block and plate never cross (smallest separation {worst * 1e3:.3f} mm)")
    force = h["contact/ALL_EXTERIOR/CFN"][:]
    check(force.max() > 0, f"contact force reached {force.max():.4g} N")
    drift, _ = energy_drift(h)
    ke_max = h["energy/ALLKE"][:].max()
    check(drift < 0.03 * ke_max, f"ETOTAL drift {drift:.3g} J < 3 % of max ALLKE {ke_max:.3g} J")


def friction_block(f, h):
    t = h["time"][:]
    v = h["node/BLOCK_NODES/V1"][:].mean(axis=1)
    late = t > 0.1 * t[-1]
    slope = np.polyfit(t[late], v[late], 1)[0]
    mu_g = 0.3 * 9.81
    check(abs(-slope / mu_g - 1) < 0.03,
          f"deceleration {-slope:.4f} m/s^2 vs mu g = {mu_g:.4f} m/s^2 (3 %)")
    mass = RHO * 0.010 * 0.010 * 0.005
    slide = np.trapz(v, t)
    fd = h["energy/ALLFD"][-1]
    expected = 0.3 * mass * 9.81 * slide
    check(abs(fd / expected - 1) < 0.03,
          f"ALLFD {fd * 1e6:.2f} uJ vs mu m g x = {expected * 1e6:.2f} uJ (3 %)")
    drift, ke0 = energy_drift(h)
    check(drift < 0.01 * ke0, f"ETOTAL drift {drift:.3g} J < 1 % of ALLKE(0)")


def tube_crush(f, h):
    """Self contact of a crushed S4R tube (t = 0.5 mm, 2.5 mm elements): energy balance, no node
    through a plate, and in every frame no tube node deeper than 10 % of the element size in
    the contact layer of a wall it does not belong to."""
    e = h["energy"]
    wk = e["ALLWK"][-1]
    drift = np.abs(e["ETOTAL"][:] - e["ETOTAL"][0]).max()
    check(wk > 100.0 and drift < 0.02 * wk,
          f"ETOTAL drift {drift:.2f} J under 2 % of the crushing work ALLWK = {wk:.1f} J")
    pw = e["ALLPW"][:]
    check(pw.min() > -1e-3 * wk, f"contact stores, never creates, energy (ALLPW >= {pw.min():.3f} J)")
    ids = f["mesh/node_ids"][:]
    x0 = f["mesh/coordinates"][:]
    tube = (ids >= 100000) & (ids < 200000)
    conn = f["mesh/S4R/connectivity"][:]
    t, h_e = 0.5e-3, 2.5e-3
    worst = 0.0
    for name in sorted(f["frames"].keys()):
        x = x0 + f["frames"][name]["U"][:]
        z = x[tube, 2]
        check(z.min() > -0.25e-3 - 0.1 * h_e, f"frame {name}: no tube node below the base plate") \
            if name == sorted(f["frames"].keys())[-1] else None
        # Node-to-wall penetration: nodes whose projection falls inside a triangle of a shell
        # they are not a corner of, closer than t (the two half thicknesses) to its mid-surface.
        nodes = np.where(tube)[0]
        for quad in conn:
            p = x[quad]
            for tri in ((0, 1, 2), (0, 2, 3)):
                a, b, c = p[tri[0]], p[tri[1]], p[tri[2]]
                n = np.cross(b - a, c - a)
                area2 = np.linalg.norm(n)
                n = n / area2
                rel = x[nodes] - a
                d = rel @ n
                near = np.abs(d) < t
                if not near.any():
                    continue
                q = rel[near] - np.outer(d[near], n)
                v0, v1 = b - a, c - a
                d00, d01, d11 = v0 @ v0, v0 @ v1, v1 @ v1
                den = d00 * d11 - d01 * d01
                d20, d21 = q @ v0, q @ v1
                v = (d11 * d20 - d01 * d21) / den
                w = (d00 * d21 - d01 * d20) / den
                inside = (v >= 0) & (w >= 0) & (v + w <= 1)
                cand = nodes[near][inside]
                own = np.isin(cand, quad)
                if (~own).any():
                    worst = max(worst, (t - np.abs(d[near][inside][~own])).max())
    check(worst <= 0.1 * h_e,
          f"no tube node more than 10 % of the element size ({0.1 * h_e * 1e3:.2f} mm) inside another "
          f"wall's contact layer in any frame (deepest {worst * 1e6:.1f} um)")


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    case, directory = sys.argv[1], pathlib.Path(sys.argv[2])
    with h5py.File(directory / f"{case}.h5", "r") as f:
        check(f.attrs["status"] == "completed" if isinstance(f.attrs["status"], str)
              else f.attrs["status"].decode() == "completed", f"{case} completed")
        h = f["history/step_1"]
        if case == "bar_bar":
            bar_bar(f, h, "ALL_EXTERIOR")
        elif case in ("bar_bar_pair", "bar_bar_oneway"):
            bar_bar(f, h, "A_END-B_END")
        elif case == "bar_wall":
            bar_wall(f, h)
        elif case == "hertz":
            hertz(f, h)
        elif case == "shell_block":
            shell_block(f, h, -1)
        elif case == "shell_block_below":
            shell_block(f, h, +1)
        elif case == "friction_block":
            friction_block(f, h)
        elif case == "tube_crush":
            tube_crush(f, h)
        else:
            sys.exit(f"check_contact.py: unknown case {case}")


if __name__ == "__main__":
    main()
