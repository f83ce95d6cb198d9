#!/usr/bin/python3
"""C6 after an import, exactly (issue 35 item 4): a body driven into another without contact
and stopped at rest, then continued with `--import` in a deck that turns general contact on,
stays at rest: the penetrations become offsets (reason "import") that make no force.

Usage: check_import_rest.py XPL OUT_DIR [CASE...]

For every case (all when none is named) two decks are written and run:
- CASE_source.inp: no contact; every node of the moving body B has a prescribed velocity (a
  trapezoid in time, 10 us ramps at 1 m/s, the ramp down ending with the step), so B travels
  rigidly (strain free) from 0.05 mm clear of block A to 0.05 mm into it and stops; A is never
  touched. Its last frame must be at rest: V exactly 0. (Before issue 35 the V of a prescribed
  velocity at t_n was the mean of the half-step velocities, and at the end of the ramp that is
  slope * dt / 4: V = 2.8e-3 m/s on B, and the continued run of "blocks" started with ALLKE
  2.4e-10 J and pressed B into A with up to 0.25 N: the symptom of issue 35 item 4.)
- CASE_target.inp: the same mesh, no boundary condition, *CONTACT with ALL EXTERIOR (both
  views of every pair), run with --import CASE_source.h5 for 0.1 ms (about 700 increments).

Checks of the continued run: it completed; /overclosure/step_1/offsets lists the penetrating
slave nodes with reason 6 (import) and none are adjusted; over the step the total contact force
CFN stays below 1e-6 N and ALLKE below 1e-15 J (the acceptance of issue 35; a plain penalty on
the 0.05 mm penetrations gives about 1e4 N); no node moves by more than 1e-15 m (round-off of
the coordinates).

Cases (H = 1 mm; A is 4 x 4 x 2 C3D8R of H from the origin, its top face at z = 2H):
- blocks:   the issue's deck: B 2 x 2 x 2 C3D8R of H over A's centre, matching meshes (every node
            of B's bottom sits on a node of A's top and the reverse: both views, nodes at the
            shared corners of four faces).
- shell:    B an S4R plate (3 x 3 of H, t = 0.5 mm) driven 0.05 mm into A's top with its lower
            skin: a shell slave node (contact surface at -t/2) and A's nodes against a shell face.
- offset:   B 4 x 4 x 2 C3D8R of 0.75 H x 0.75 H x H whose nodes sit 0.1 um beside A's face edges
            (x = 0.9999 H + 0.75 H i, y = 1.0001 H + 0.75 H j): non-matching meshes, the last row
            of B's nodes 0.1 um beyond A's perimeter edge and A's edge nodes 0.1 um inside B's.
- corner:   B 2 x 2 x 2 C3D8R of H over A's corner (from x = y = 3.5 H): A's corner node under B's
            bottom, B's bottom edges across A's top edges.
- edge:     B 2 x 2 x 2 C3D8R of H driven diagonally (down and towards A) into A's top edge along
            y: it ends 0.05 mm into A's top face and 0.05 mm into its side face x = 4H, so the
            nodes at the edges lie equally deep below two faces (their nearest face is a tie).
"""

import pathlib
import shutil
import subprocess
import sys

import h5py
import numpy as np

H = 1.0e-3  # element size of A, m
OVERLAP = 0.05e-3  # penetration at rest, m
SPEED = 1.0  # m/s
RAMP = 10e-6  # s
CONTINUE = 0.1e-3  # s
BODY = 100000
IMPORT_REASON = 6  # OffsetReason::Import in /overclosure/step_1/offsets

CFN_LIMIT = 1e-6  # N
ALLKE_LIMIT = 1e-15  # J
MOVE_LIMIT = 1e-15  # m


def check(condition, message):
    if not condition:
        sys.exit(f"check_import_rest.py: FAILED: {message}")
    print(f"check_import_rest.py: ok: {message}")


def fmt(v):
    return repr(float(v))


def nset(lines, name, ids):
    lines.append(f"*NSET, NSET={name}")
    for k in range(0, len(ids), 12):
        lines.append(", ".join(str(v) for v in ids[k:k + 12]))


def hex_block(lines, body, name, origin, counts, size):
    """C3D8R block; returns its node ids."""
    nx, ny, nz = counts
    dx, dy, dz = size

    def nid(i, j, k):
        return body * BODY + 1 + i + 100 * j + 10000 * k

    lines.append("*NODE")
    ids = []
    for k in range(nz + 1):
        for j in range(ny + 1):
            for i in range(nx + 1):
                ids.append(nid(i, j, k))
                lines.append(f"{nid(i, j, k)}, {fmt(origin[0] + i * dx)}, "
                             f"{fmt(origin[1] + j * dy)}, {fmt(origin[2] + k * dz)}")
    lines.append(f"*ELEMENT, TYPE=C3D8R, ELSET={name}")
    e = body * BODY + 1
    for k in range(nz):
        for j in range(ny):
            for i in range(nx):
                n = [nid(i, j, k), nid(i + 1, j, k), nid(i + 1, j + 1, k), nid(i, j + 1, k),
                     nid(i, j, k + 1), nid(i + 1, j, k + 1), nid(i + 1, j + 1, k + 1),
                     nid(i, j + 1, k + 1)]
                lines.append(f"{e}, " + ", ".join(str(v) for v in n))
                e += 1
    return ids


def shell_plate(lines, body, name, origin, counts, size):
    nx, ny = counts

    def nid(i, j):
        return body * BODY + 1 + i + 100 * j

    lines.append("*NODE")
    ids = []
    for j in range(ny + 1):
        for i in range(nx + 1):
            ids.append(nid(i, j))
            lines.append(f"{nid(i, j)}, {fmt(origin[0] + i * size)}, {fmt(origin[1] + j * size)}, "
                         f"{fmt(origin[2])}")
    lines.append(f"*ELEMENT, TYPE=S4R, ELSET={name}")
    e = body * BODY + 1
    for j in range(ny):
        for i in range(nx):
            lines.append(f"{e}, {nid(i, j)}, {nid(i + 1, j)}, {nid(i + 1, j + 1)}, {nid(i, j + 1)}")
            e += 1
    return ids


SHELL_T = 0.5e-3

# Per case: B's start (before the approach) and the unit direction of its travel. B travels
# 2 * OVERLAP / (direction's component into A): from OVERLAP clear to OVERLAP in.
CASES = {
    "blocks": {"b": "hex", "origin": (1.0 * H, 1.0 * H, 2.0 * H + OVERLAP), "counts": (2, 2, 2),
               "size": (H, H, H), "direction": (0.0, 0.0, -1.0)},
    "shell": {"b": "shell", "origin": (0.5 * H, 0.5 * H, 2.0 * H + 0.5 * SHELL_T + OVERLAP),
              "counts": (3, 3), "size": H, "direction": (0.0, 0.0, -1.0)},
    "offset": {"b": "hex", "origin": (0.9999 * H, 1.0001 * H, 2.0 * H + OVERLAP),
               "counts": (4, 4, 2), "size": (0.75 * H, 0.75 * H, H),
               "direction": (0.0, 0.0, -1.0)},
    "corner": {"b": "hex", "origin": (3.5 * H, 3.5 * H, 2.0 * H + OVERLAP), "counts": (2, 2, 2),
               "size": (H, H, H), "direction": (0.0, 0.0, -1.0)},
    "edge": {"b": "hex", "origin": (4.0 * H + OVERLAP, 1.0 * H, 2.0 * H + OVERLAP),
             "counts": (2, 2, 2), "size": (H, H, H), "direction": (-1.0, 0.0, -1.0)},
}


def deck_text(case, source):
    c = CASES[case]
    lines = ["*HEADING", f"Import at rest ({case}): " + ("source, no contact" if source else
                                                            "target, general contact")]
    hex_block(lines, 1, "A", (0.0, 0.0, 0.0), (4, 4, 2), (H, H, H))
    if c["b"] == "hex":
        b_nodes = hex_block(lines, 2, "B", c["origin"], c["counts"], c["size"])
    else:
        b_nodes = shell_plate(lines, 2, "B", c["origin"], c["counts"], c["size"])
    nset(lines, "B_ALL", b_nodes)
    lines += ["*MATERIAL, NAME=STEEL", "*DENSITY", "7850.", "*ELASTIC", "2.0e11, 0.3",
              "*SOLID SECTION, ELSET=A, MATERIAL=STEEL"]
    if c["b"] == "hex":
        lines.append("*SOLID SECTION, ELSET=B, MATERIAL=STEEL")
    else:
        lines += ["*SHELL SECTION, ELSET=B, MATERIAL=STEEL", f"{fmt(SHELL_T)}, 5"]
    direction = np.array(c["direction"])
    # Each component into A travels 2 * OVERLAP at SPEED along its axis.
    travel = 2.0 * OVERLAP
    period = travel / SPEED + RAMP
    if source:
        # The ramp down ends with the step: B stops at the last frame.
        lines += ["*AMPLITUDE, NAME=APPROACH",
                  f"0., 0., {fmt(RAMP)}, 1., {fmt(period - RAMP)}, 1., {fmt(period)}, 0."]
        lines += ["*STEP, NAME=APPROACH", "*DYNAMIC, EXPLICIT", f", {fmt(period)}",
                  "*BOUNDARY, TYPE=VELOCITY, AMPLITUDE=APPROACH"]
        for d in range(3):
            lines.append(f"B_ALL, {d + 1}, {d + 1}, {fmt(SPEED * direction[d])}")
        if c["b"] == "shell":
            lines.append("*BOUNDARY, TYPE=VELOCITY")
            lines += [f"B_ALL, {d}, {d}, 0." for d in (4, 5, 6)]
        lines += ["*OUTPUT, FIELD, NUMBER INTERVAL=2", "*NODE OUTPUT", "U, V",
                  "*OUTPUT, HISTORY, TIME INTERVAL=1e-06", "*ENERGY OUTPUT", "*END STEP"]
    else:
        lines += ["*STEP, NAME=CONTINUE", "*DYNAMIC, EXPLICIT", f", {fmt(CONTINUE)}",
                  "*CONTACT", "*CONTACT INCLUSIONS, ALL EXTERIOR",
                  "*OUTPUT, FIELD, NUMBER INTERVAL=4", "*NODE OUTPUT", "U, V",
                  "*CONTACT OUTPUT", "CSTRESS, CSTATUS, CFORCE",
                  # Every increment (the stable increment is about 0.1 us).
                  "*OUTPUT, HISTORY, TIME INTERVAL=1e-08", "*ENERGY OUTPUT", "*END STEP"]
    return "\n".join(lines) + "\n"


def run(xpl, deck, out, *extra):
    result = subprocess.run([xpl, "run", str(deck), "-o", str(out), "--quiet", *extra],
                            capture_output=True, text=True, timeout=300)
    check(result.returncode == 0,
          f"xpl run {deck.name} {' '.join(extra)} exited {result.returncode}")
    if result.returncode != 0:
        sys.stdout.write(result.stdout + result.stderr)
    return out / (deck.stem + ".h5")


def last_frame(f):
    return f["frames"][sorted(f["frames"])[-1]]


def run_case(xpl, out, case):
    d = out / case
    d.mkdir(parents=True)
    source = d / f"{case}_source.inp"
    source.write_text(deck_text(case, True))
    source_h5 = run(xpl, source, d / "source")
    with h5py.File(source_h5, "r") as f:
        frame = last_frame(f)
        v_end = np.abs(frame["V"][:]).max()
        u_end = frame["U"][:]
    check(v_end == 0.0, f"{case}: the source run ends at rest (max |V| {v_end:.1e} m/s)")
    target = d / f"{case}_target.inp"
    target.write_text(deck_text(case, False))
    target_h5 = run(xpl, target, d / "target", "--import", str(source_h5))
    with h5py.File(target_h5, "r") as f:
        check(f.attrs["status"] == "completed", f"{case}: the continued run completed")
        oc = f["overclosure/step_1"]
        offsets = int(oc["offsets"].attrs["rows"])
        reasons = set(oc["offsets"]["reason"][:]) if offsets else set()
        deepest = float(oc["offsets"]["offset"][:].max()) if offsets else 0.0
        check(offsets > 0 and reasons == {IMPORT_REASON} and int(oc["adjusted"].attrs["rows"]) == 0,
              f"{case}: {offsets} penetrations stored as offsets with reason 'import' "
              f"(deepest {deepest:.4e} m), no node adjusted")
        h = f["history/step_1"]
        cfn = max(np.abs(h["contact"][p]["CFN"][:]).max() for p in h["contact"])
        allke = np.abs(h["energy"]["ALLKE"][:]).max()
        rows = len(h["energy"]["ALLKE"][:])
        u = last_frame(f)["U"][:]
    moved = np.abs(u - u_end).max()
    print(f"check_import_rest.py: {case}: over {rows} history rows max CFN {cfn:.3e} N, "
          f"max ALLKE {allke:.3e} J, largest move {moved:.3e} m")
    check(cfn < CFN_LIMIT, f"{case}: max CFN {cfn:.3e} N < {CFN_LIMIT:g} N over the continued step")
    check(allke < ALLKE_LIMIT, f"{case}: max ALLKE {allke:.3e} J < {ALLKE_LIMIT:g} J")
    check(moved < MOVE_LIMIT, f"{case}: no node moves ({moved:.3e} m < {MOVE_LIMIT:g} m)")


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    xpl = sys.argv[1]
    out = pathlib.Path(sys.argv[2])
    cases = sys.argv[3:] or list(CASES)
    for case in cases:
        if case not in CASES:
            sys.exit(f"check_import_rest.py: unknown case {case}; expected one of {list(CASES)}")
    shutil.rmtree(out, ignore_errors=True)
    out.mkdir(parents=True)
    for case in cases:
        run_case(xpl, out, case)


if __name__ == "__main__":
    main()
