#!/usr/bin/python3
"""Check an impact run against the criteria of issue 32, item 7 (SPEC R3, R5, R6, C16).

Criteria, each evaluated on every run (a failed run is checked on what it wrote, and its
failure is reported with its cause):
  completed    JOB.summary.json has status "completed" (otherwise its exit_reason is given)
  drift        |ETOTAL - ETOTAL(0)| <= 1 % of the energy scale in every history row; the scale
               is the largest of ALLKE, ALLIE and |ALLWK| over the run (xpl's watchdog's)
  hourglass    ALLAE <= 10 % of ALLIE in every history row where ALLIE is not negligible:
               ALLIE >= 5 % of the energy scale (below that ALLAE is at most 0.5 % of it)
  kinetic      ALLKE >= 0 in every history row
  penetration  in the last frame's deformed coordinates, no node of the model deeper than 10 %
               of the element size inside a face of another body (or of its own body, for
               shells), and no body passed through another; penetration() has the geometry
               and the element size. A pass-through is reported with v·Δt over the target's
               thickness, which says whether the increment could resolve it (physical when a
               node crosses the whole thickness within one increment). A run that ended
               before its first output frame is "not measured" here (and failed anyway)
  threads      1 and 2 threads give bitwise the same results (`xpl compare --rtol 0 --atol 0`
               on completed runs; every dataset of the .h5 otherwise)

Usage:
  impact_check.py run XPL ID [--work DIR] [--no-threads] [--known FILE]
      write scene ID (impact_scenes.py), run it with 1 (and 2) threads, check it; prints the
      deck path first and one line per criterion; exit 0 when every criterion holds, else 1.
      With --known (tests/stress/known_failures.txt), a criterion listed there for this scene
      with its reason is reported as KNOWN and does not fail the run; every other criterion
      must hold. A listed criterion that now holds is reported so the list can shrink.
  impact_check.py check DECK_DIR [--meta SCENE.json] [--xpl XPL]
      check the runs already in DECK_DIR (JOB.h5 and JOB.summary.json; a `threads_2`
      subfolder for the threads criterion, compared by XPL compare when given)
Needs numpy and h5py (/usr/bin/python3).
"""

import argparse
import json
import math
import os
import pathlib
import subprocess
import sys
import threading

import h5py
import numpy as np

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
import impact_scenes  # noqa: E402

DRIFT_LIMIT = 0.01  # of the energy scale
HOURGLASS_LIMIT = 0.10  # of ALLIE
ALLIE_NEGLIGIBLE = 0.05  # of the energy scale: rows below are not checked for ALLAE/ALLIE
DEPTH_LIMIT = 0.10  # of the element size
SELF_EXCLUSION = 1.5  # shells: a node this many element sizes from a face as read is a partner
# v·Δt at or above this fraction of the target's thickness: a node crosses the whole target
# within one increment, which no penetration check at the increment's end can see (only a
# swept one): the test says so instead of blaming the contact search
RESOLVABLE_FRACTION = 1.0
CRITERIA = ("completed", "drift", "hourglass", "kinetic", "penetration", "threads")
HEX_FACES = ((0, 1, 2, 3), (4, 7, 6, 5), (0, 4, 5, 1), (1, 5, 6, 2), (2, 6, 7, 3), (3, 7, 4, 0))


# ---------------------------------------------------------------------------------------------
# Reading a run


def open_results(path):
    return h5py.File(path, "r")


def read_run(folder, job):
    """What the checks need from folder/JOB.h5 and JOB.summary.json."""
    folder = pathlib.Path(folder)
    run = {"h5": folder / f"{job}.h5"}
    summary_path = folder / f"{job}.summary.json"
    run["summary"] = json.loads(summary_path.read_text()) if summary_path.exists() else None
    if not run["h5"].exists():
        return run
    with open_results(run["h5"]) as f:
        run["status"] = str(f.attrs.get("status", ""))
        run["node_ids"] = f["mesh/node_ids"][()]
        run["reference"] = f["mesh/coordinates"][()]
        run["elements"] = {}
        for kind in ("C3D8R", "C3D8", "S4R"):
            if f"mesh/{kind}" in f:
                run["elements"][kind] = (f[f"mesh/{kind}/element_ids"][()],
                                         f[f"mesh/{kind}/connectivity"][()])
        run["element_sets"] = {name: f["mesh/element_sets"][name][()]
                               for name in f.get("mesh/element_sets", {})}
        frames = sorted(f["frames"]) if "frames" in f else []
        run["frames"] = len(frames)
        run["current"] = run["reference"].copy()
        run["time"] = 0.0
        if frames:
            last = f["frames"][frames[-1]]
            if "U" in last:
                run["current"] = run["reference"] + last["U"][()]
            run["time"] = float(last.attrs["time"])
        energy = {}
        steps = sorted(f.get("history", {}), key=lambda s: int(s.split("_")[1]))
        for step in steps:
            group = f["history"][step].get("energy", {})
            for name in group:
                energy.setdefault(name, []).append(group[name][()])
        run["energy"] = {k: np.concatenate(v) for k, v in energy.items()}
    return run


# ---------------------------------------------------------------------------------------------
# Geometry: faces, triangles, closest points, winding numbers


def body_faces(run, element_set):
    """Faces of one body: (kind, quads as node rows (n, 4), per-quad element size (n)).

    Solids: the exterior faces (not shared by two hexes), oriented outward in the reference
    configuration. Shells: every S4R as it is (double-sided)."""
    members = set(run["element_sets"][element_set].tolist())
    hexes, shells = [], []
    for kind, (ids, connectivity) in run["elements"].items():
        take = np.array([i in members for i in ids.tolist()], dtype=bool)
        if take.any():
            (shells if kind == "S4R" else hexes).append(connectivity[take])
    reference = run["reference"]
    if shells:
        quads = np.concatenate(shells)
        return "shell", quads
    hexes = np.concatenate(hexes)
    count = {}
    for element, nodes in enumerate(hexes):
        for face in HEX_FACES:
            quad = tuple(int(nodes[k]) for k in face)
            key = tuple(sorted(quad))
            entry = count.setdefault(key, [0, quad, element])
            entry[0] += 1
    quads = []
    for n, quad, element in count.values():
        if n != 1:
            continue
        points = reference[list(quad)]
        normal = np.cross(points[2] - points[0], points[3] - points[1])
        centre = reference[hexes[element]].mean(axis=0)
        if np.dot(normal, points.mean(axis=0) - centre) < 0.0:
            quad = quad[::-1]
        quads.append(quad)
    return "solid", np.array(quads, dtype=np.int64)


def triangles(quads, coordinates):
    """Each quad split into four triangles (corner i, corner i+1, centroid): (A, B, C) arrays
    (4n × 3), the quad of each triangle and the corner index i."""
    corners = coordinates[quads]  # n × 4 × 3
    centre = corners.mean(axis=1)
    a = corners.reshape(-1, 3)
    b = np.roll(corners, -1, axis=1).reshape(-1, 3)
    c = np.repeat(centre, 4, axis=0)
    quad_of = np.repeat(np.arange(len(quads)), 4)
    corner = np.tile(np.arange(4), len(quads))
    return a, b, c, quad_of, corner


def closest_points(p, a, b, c):
    """Closest points of points p (N × 3) on triangles (A, B, C; T × 3 each): barycentric
    weights (N × T × 3) and distances (N × T). Ericson, Real-Time Collision Detection 5.1.5,
    its tests applied in reverse order so that the first that holds wins."""
    p = p[:, None, :]
    ab, ac = (b - a)[None], (c - a)[None]
    ap, bp, cp = p - a[None], p - b[None], p - c[None]
    d1, d2 = (ab * ap).sum(-1), (ac * ap).sum(-1)
    d3, d4 = (ab * bp).sum(-1), (ac * bp).sum(-1)
    d5, d6 = (ab * cp).sum(-1), (ac * cp).sum(-1)
    va, vb, vc = d3 * d6 - d5 * d4, d5 * d2 - d1 * d6, d1 * d4 - d3 * d2
    with np.errstate(divide="ignore", invalid="ignore"):
        denominator = va + vb + vc
        v = np.where(denominator != 0.0, vb / denominator, 0.0)
        w = np.where(denominator != 0.0, vc / denominator, 0.0)
        weights = np.stack([1.0 - v - w, v, w], axis=-1)

        def put(mask, wa, wb, wc):
            weights[mask] = np.stack([wa[mask], wb[mask], wc[mask]], axis=-1)

        zero, one = np.zeros_like(d1), np.ones_like(d1)
        t = (d4 - d3) / ((d4 - d3) + (d5 - d6))
        put((va <= 0) & (d4 - d3 >= 0) & (d5 - d6 >= 0), zero, 1.0 - t, t)
        t = d2 / (d2 - d6)
        put((vb <= 0) & (d2 >= 0) & (d6 <= 0), 1.0 - t, zero, t)
        put((d6 >= 0) & (d5 <= d6), zero, zero, one)
        t = d1 / (d1 - d3)
        put((vc <= 0) & (d1 >= 0) & (d3 <= 0), 1.0 - t, t, zero)
        put((d3 >= 0) & (d4 <= d3), zero, one, zero)
        put((d1 <= 0) & (d2 <= 0), one, zero, zero)
    q = (weights[..., 0:1] * a[None] + weights[..., 1:2] * b[None] + weights[..., 2:3] * c[None])
    return weights, np.linalg.norm(p - q, axis=-1)


def winding_numbers(p, a, b, c):
    """Generalised winding number of points p (N × 3) about the closed, outward oriented
    triangle surface (A, B, C): 1 inside, 0 outside (Van Oosterom and Strackee's solid angle)."""
    ra, rb, rc = a[None] - p[:, None], b[None] - p[:, None], c[None] - p[:, None]
    la, lb, lc = (np.linalg.norm(r, axis=-1) for r in (ra, rb, rc))
    numerator = (ra * np.cross(rb, rc)).sum(-1)
    denominator = (la * lb * lc + (ra * rb).sum(-1) * lc + (ra * rc).sum(-1) * lb
                   + (rb * rc).sum(-1) * la)
    return 2.0 * np.arctan2(numerator, denominator).sum(axis=1) / (4.0 * math.pi)


def boundary_flags(quads):
    """For a shell mesh: per quad edge i (corner i to i+1) whether it is on the free perimeter,
    and per node row whether it lies on the perimeter."""
    edges = {}
    for quad in quads.tolist():
        for i in range(4):
            key = tuple(sorted((quad[i], quad[(i + 1) % 4])))
            edges[key] = edges.get(key, 0) + 1
    edge_free = np.array([[edges[tuple(sorted((q[i], q[(i + 1) % 4])))] == 1 for i in range(4)]
                          for q in quads.tolist()], dtype=bool)
    free_nodes = {n for key, count in edges.items() if count == 1 for n in key}
    return edge_free, free_nodes


def pseudo_normals(quads, coordinates, quad_of, corner):
    """Normals of a shell mesh for a side test at each triangle of triangles(): the triangle's
    own (its interior), the sum of the unit normals of the quads at its quad edge (the edge)
    and at its two quad corners (the corners). Arrays (T × 3) each."""
    corners = coordinates[quads]
    normal = np.cross(corners[:, 2] - corners[:, 0], corners[:, 3] - corners[:, 1])
    normal /= np.linalg.norm(normal, axis=1)[:, None]
    at_node = np.zeros_like(coordinates)
    at_edge = {}
    for q, quad in enumerate(quads.tolist()):
        for i in range(4):
            at_node[quad[i]] += normal[q]
            key = tuple(sorted((quad[i], quad[(i + 1) % 4])))
            at_edge[key] = at_edge.get(key, 0.0) + normal[q]
    a_rows = quads[quad_of, corner]
    b_rows = quads[quad_of, (corner + 1) % 4]
    a, b = coordinates[a_rows], coordinates[b_rows]
    c = corners.mean(axis=1)[quad_of]
    return {"face": np.cross(b - a, c - a), "a": at_node[a_rows], "b": at_node[b_rows],
            "edge": np.array([at_edge[tuple(sorted((i, j)))]
                              for i, j in zip(a_rows.tolist(), b_rows.tolist())])}


def feature_normals(normals, best, w, eps=1e-9):
    """The pseudo-normal at each closest point: weights w (N × 3) on triangles `best` (N)."""
    n = normals["face"][best].copy()
    on_edge = w[:, 2] < eps
    n[on_edge] = normals["edge"][best[on_edge]]
    at_a, at_b = w[:, 0] > 1.0 - eps, w[:, 1] > 1.0 - eps
    n[at_a] = normals["a"][best[at_a]]
    n[at_b] = normals["b"][best[at_b]]
    return n


# ---------------------------------------------------------------------------------------------
# The penetration criterion


def penetration(run, meta):
    """Deepest node inside a face at the end: list of findings (depth, limit, text), deepest
    first, and a list of pass-through texts.

    Masters are the bodies of the scene (element sets). For a solid master, a node of another
    body is inside when the winding number of the master's exterior surface about it exceeds
    1/2; its depth is its distance to that surface (plus its own half thickness if it is a shell
    node). For a shell master, a node (of another body, or of the same shell if it lay more than
    1.5 element sizes from the face as read: a fold) is inside when its distance d to the
    mid-surface is below the half thicknesses of both (depth = t_master/2 + t_node/2 - d),
    unless its closest point is on the shell's free perimeter (beside the shell, as contact
    treats it). A node of another body whose closest point is on the shell (not its perimeter)
    and that is now on the other side of it than at the start has passed through it; each side
    is taken at the node's own closest point, along the pseudo-normal of the face, edge or
    corner that point lies on (for a closed shell: inside or outside). The limit is 10 % of the
    smaller element size of the two bodies (shortest edge as read)."""
    bodies = meta["bodies"]
    reference, current = run["reference"], run["current"]
    body_rows = {}
    body_quads = {}
    for name in bodies:
        kind, quads = body_faces(run, name)
        body_quads[name] = (kind, quads)
        rows = np.unique(quads) if kind == "shell" else None
        if rows is None:
            members = set(run["element_sets"][name].tolist())
            rows = np.unique(np.concatenate([conn[[i in members for i in ids.tolist()]].ravel()
                                             for ids, conn in run["elements"].values()]))
        body_rows[name] = rows
    findings, crossings = [], []
    for master, (kind, quads) in body_quads.items():
        a, b, c, quad_of, corner = triangles(quads, current)
        a0, b0, c0, _, _ = triangles(quads, reference)
        h_master = bodies[master]["element_size"]
        t_master = bodies[master]["thickness"]
        lo = np.minimum(np.minimum(a, b), c).min(axis=0)
        hi = np.maximum(np.maximum(a, b), c).max(axis=0)
        if kind == "shell":
            edge_free, free_nodes = boundary_flags(quads)
            tri_edge_free = edge_free[quad_of, corner]
            corner_rows = quads[quad_of, corner]
            next_rows = quads[quad_of, (corner + 1) % 4]
            a_free = np.array([r in free_nodes for r in corner_rows.tolist()], dtype=bool)
            b_free = np.array([r in free_nodes for r in next_rows.tolist()], dtype=bool)
            pseudo_now = pseudo_normals(quads, current, quad_of, corner)
            pseudo_then = pseudo_normals(quads, reference, quad_of, corner)
        for slave, rows in body_rows.items():
            if slave == master and kind == "solid":
                continue  # a solid's self penetration is not measured (see the docstring)
            t_slave = bodies[slave]["thickness"]
            h = min(h_master, bodies[slave]["element_size"])
            limit = DEPTH_LIMIT * h
            margin = 0.5 * (t_master + t_slave) + h
            p_all = current[rows]
            near = np.all((p_all > lo - margin) & (p_all < hi + margin), axis=1)
            for chunk in np.array_split(np.flatnonzero(near), max(1, int(near.sum()) // 128)):
                if chunk.size == 0:
                    continue
                p = p_all[chunk]
                weights, distance = closest_points(p, a, b, c)
                if kind == "solid":
                    inside = winding_numbers(p, a, b, c) > 0.5
                    d = distance.min(axis=1)
                    depth = np.where(inside, d + 0.5 * t_slave, 0.5 * t_slave - d)
                    for k in np.flatnonzero(depth > limit):
                        node = int(run["node_ids"][rows[chunk[k]]])
                        findings.append((float(depth[k]), limit,
                                         f"node {node} ({slave}) is {depth[k] * 1e3:.3g} mm "
                                         f"inside {master} (limit {limit * 1e3:.3g} mm)"))
                    continue
                # Shell master: perimeter closest points are beside the shell.
                eps = 1e-9
                perimeter = ((weights[..., 2] < eps) & tri_edge_free[None]) | \
                            ((weights[..., 0] > 1 - eps) & a_free[None]) | \
                            ((weights[..., 1] > 1 - eps) & b_free[None])
                then = reference[rows[chunk]]
                weights0, distance0 = closest_points(then, a0, b0, c0)
                if slave == master:
                    # A fold: only faces the node was far from as read count.
                    far = distance0 > SELF_EXCLUSION * h_master
                    distance = np.where(far, distance, np.inf)
                    distance0 = np.where(far, distance0, np.inf)
                best = distance.argmin(axis=1)
                d = distance[np.arange(len(chunk)), best]
                ok = np.isfinite(d) & ~perimeter[np.arange(len(chunk)), best]
                depth = np.where(ok, 0.5 * (t_master + t_slave) - d, -np.inf)
                # The node's side of the shell now and as read, each at its own closest point,
                # along the pseudo-normal of the feature that point lies on (face, edge or
                # corner): a node outside a convex fold is not behind one of its faces, and
                # a node inside a closed shell box is inside whichever face is nearest.
                best0 = distance0.argmin(axis=1)
                side = []
                for (ta, tb, tc), points, normals, w_all, pick in (
                        ((a, b, c), p, pseudo_now, weights, best),
                        ((a0, b0, c0), then, pseudo_then, weights0, best0)):
                    w = w_all[np.arange(len(chunk)), pick]
                    q = (w[:, 0:1] * ta[pick] + w[:, 1:2] * tb[pick] + w[:, 2:3] * tc[pick])
                    n = feature_normals(normals, pick, w)
                    side.append(np.einsum("ij,ij->i", points - q, n))
                # A node of the shell itself lies on it as read, on neither side: its folds are
                # judged by the depth alone.
                crossed = ok & (side[0] * side[1] < 0.0) & (slave != master)
                for k in np.flatnonzero(crossed):
                    node = int(run["node_ids"][rows[chunk[k]]])
                    crossings.append(f"node {node} ({slave}) ended {d[k] * 1e3:.3g} mm on the "
                                     f"other side of {master}'s mid-surface than it started")
                for k in np.flatnonzero(ok & ~crossed & (depth > limit)):
                    node = int(run["node_ids"][rows[chunk[k]]])
                    findings.append((float(depth[k]), limit,
                                     f"node {node} ({slave}) is {depth[k] * 1e3:.3g} mm inside "
                                     f"{master}'s thickness (limit {limit * 1e3:.3g} mm)"))
    # A whole body beyond the other along the target's normal (meta "pair": projectile and
    # target, "normal": the target's surface normal towards the projectile): shot through.
    if meta.get("pair"):
        projectile, target = meta["pair"]
        normal = np.array(meta["normal"])
        heights_p = current[body_rows[projectile]] @ normal
        heights_t = current[body_rows[target]] @ normal
        if heights_p.max() < heights_t.min():
            crossings.append(f"{projectile} ended wholly beyond {target} along the normal")
    findings.sort(key=lambda f: -f[0] / f[1])
    return findings, crossings


# ---------------------------------------------------------------------------------------------
# The criteria


def energy_criteria(run):
    """(criterion, passed, message) for drift, hourglass and kinetic."""
    e = run.get("energy", {})
    needed = ("ALLKE", "ALLIE", "ALLAE", "ETOTAL")
    if any(k not in e or len(e[k]) == 0 for k in needed):
        return [(c, False, "no energy history") for c in ("drift", "hourglass", "kinetic")]
    ke, ie, ae, et = e["ALLKE"], e["ALLIE"], e["ALLAE"], e["ETOTAL"]
    wk = e.get("ALLWK", np.zeros_like(ke))
    energy_scale = max(float(np.abs(ke).max()), float(ie.max()), float(np.abs(wk).max()))
    out = []
    drift = np.abs(et - et[0])
    worst = int(drift.argmax())
    ratio = drift[worst] / energy_scale
    out.append(("drift", bool(ratio <= DRIFT_LIMIT),
                f"|ETOTAL drift| {100 * ratio:.3g} % of the energy scale {energy_scale:.4g} J "
                f"(row {worst}; limit {100 * DRIFT_LIMIT:g} %)"))
    rows = ie >= ALLIE_NEGLIGIBLE * energy_scale
    if rows.any():
        share = np.where(rows, ae / np.where(ie > 0, ie, 1.0), 0.0)
        worst = int(share.argmax())
        out.append(("hourglass", bool(share[worst] <= HOURGLASS_LIMIT),
                    f"ALLAE up to {100 * share[worst]:.3g} % of ALLIE (row {worst}, ALLAE "
                    f"{ae[worst]:.4g} J; at the end {100 * ae[-1] / max(ie[-1], 1e-300):.3g} %; "
                    f"limit {100 * HOURGLASS_LIMIT:g} %)"))
    else:
        out.append(("hourglass", True, f"ALLIE below {100 * ALLIE_NEGLIGIBLE:g} % of the energy "
                    "scale in every row: not checked"))
    worst = int(ke.argmin())
    out.append(("kinetic", bool(ke[worst] >= 0.0),
                f"lowest ALLKE {ke[worst]:.4g} J (row {worst}, "
                f"{100 * ke[worst] / energy_scale:.3g} % of the energy scale)"))
    return out


def threads_criterion(xpl, one, two, job):
    """1 and 2 threads bitwise: xpl compare on completed runs, every dataset otherwise."""
    h5_one, h5_two = one / f"{job}.h5", two / f"{job}.h5"
    if not h5_one.exists() or not h5_two.exists():
        return ("threads", False, "a run wrote no results")
    with open_results(h5_one) as fa, open_results(h5_two) as fb:
        statuses = (str(fa.attrs.get("status")), str(fb.attrs.get("status")))
    if statuses == ("completed", "completed") and xpl:
        r = subprocess.run([xpl, "compare", str(h5_one), str(h5_two), "--rtol", "0", "--atol",
                            "0", "--frames", "all"], capture_output=True, text=True, timeout=120)
        last = (r.stdout.strip().splitlines() or [""])[-1]
        return ("threads", r.returncode == 0, "xpl compare --rtol 0 --atol 0 --frames all: "
                + ("identical" if r.returncode == 0 else f"exit {r.returncode}: {last}"))
    differ = []
    with open_results(h5_one) as fa, open_results(h5_two) as fb:
        names = []
        fa.visit(names.append)
        for name in names:
            if isinstance(fa[name], h5py.Dataset):
                if name not in fb or fa[name][()].tobytes() != fb[name][()].tobytes():
                    differ.append(name)
        if fa.attrs.get("error", "") != fb.attrs.get("error", ""):
            differ.append("error attribute")
    return ("threads", not differ, f"statuses {statuses[0]}/{statuses[1]}: "
            + ("every dataset identical" if not differ else f"differ: {differ[:4]}"))


def check_scene(run, meta):
    """Every criterion but threads: [(criterion, passed, message)]."""
    out = []
    summary = run.get("summary")
    status = summary["status"] if summary else run.get("status", "no results")
    reason = (summary or {}).get("exit_reason", "") or ""
    out.append(("completed", status == "completed",
                f"status {status}" + (f": {reason}" if reason else "")
                + (f" (at t = {(summary or {}).get('simulated_time', 0.0) * 1e6:.4g} of "
                   f"{meta['period'] * 1e6:.4g} us)" if status != "completed" else "")))
    if "energy" not in run:
        return out + [(c, False, "no results") for c in ("drift", "hourglass", "kinetic",
                                                         "penetration")]
    out += energy_criteria(run)
    at = f" (last frame, t = {run['time'] * 1e6:.4g} us)"
    if status != "completed" and run["time"] == 0.0:
        out.append(("penetration", None, "not measured: no frame after t = 0 (the run ended "
                    "before its first output interval)"))
        return out
    findings, crossings = penetration(run, meta)
    if crossings:
        first = (summary or {}).get("first_increment")
        thickness = meta.get("target_thickness")
        why = ""
        if first and thickness:
            fraction = meta["speed"] * first / thickness
            why = (f"; v·Δt = {100 * fraction:.3g} % of the target's thickness "
                   f"({thickness * 1e3:.3g} mm) at the first increment: "
                   + ("a node crosses it within one increment, which only a swept check "
                      "can see" if fraction >= RESOLVABLE_FRACTION else
                      f"the crossing takes {1 / fraction:.3g} increments, so contact could "
                      "have stopped it"))
        out.append(("penetration", False, f"passed through{at}: {crossings[0]}"
                    + (f" (+{len(crossings) - 1} more)" if len(crossings) > 1 else "") + why))
    elif findings:
        out.append(("penetration", False, f"{findings[0][2]}"
                    + (f" (+{len(findings) - 1} more nodes)" if len(findings) > 1 else "") + at))
    else:
        out.append(("penetration", True, "no node deeper than "
                    f"{100 * DEPTH_LIMIT:g} % of the element size in a face{at}"))
    return out


# ---------------------------------------------------------------------------------------------
# Running a scene


def run_xpl(xpl, deck, out, threads, timing=None, timeout=600):
    """xpl run DECK -o OUT --threads N (stdout and stderr to OUT/xpl_run.txt); returns its exit
    code. Its own CPU time (user + system, s; os.wait4, so runs side by side in threads are
    told apart) goes to timing[f"cpu_{threads}"] when a dict is given."""
    out.mkdir(parents=True, exist_ok=True)
    with open(out / "xpl_run.txt", "w") as log:
        process = subprocess.Popen([xpl, "run", str(deck), "-o", str(out), "--threads",
                                    str(threads), "--quiet"], stdout=log, stderr=log,
                                   env={"OMP_WAIT_POLICY": "PASSIVE", "PATH": "/usr/bin:/bin"})
        timer = threading.Timer(timeout, process.kill)
        timer.start()
        try:
            _, status, usage = os.wait4(process.pid, 0)
        finally:
            timer.cancel()
    process.returncode = os.waitstatus_to_exitcode(status)
    if timing is not None:
        timing[f"cpu_{threads}"] = usage.ru_utime + usage.ru_stime
    return process.returncode


def run_deck(xpl, deck, threads=True, timing=None, reuse=False):
    """Run DECK (beside its .json metadata) with 1 (and 2) threads and check it: a list of
    (criterion, passed, message) for every criterion (threads: passed None when not run).
    timing (a dict, optional) receives the runs' CPU times, cpu_1 and cpu_2 (s). reuse: check
    the runs already beside the deck (from an earlier call) instead of running xpl again."""
    folder = deck.parent
    meta = json.loads(deck.with_suffix(".json").read_text())
    job = deck.stem
    summary = folder / f"{job}.summary.json"
    if reuse and summary.exists():
        code = None
    else:
        summary.unlink(missing_ok=True)  # a run that writes none must not find an old one
        code = run_xpl(xpl, deck, folder, 1, timing)
    if not summary.exists():
        text = (folder / "xpl_run.txt").read_text(errors="replace").strip()
        results = [("completed", False, f"xpl exited {code}: {text[-300:]}")]
        return results + [(c, False, "no results") for c in CRITERIA[1:]]
    results = check_scene(read_run(folder, job), meta)
    if threads:
        if not (reuse and (folder / "threads_2" / f"{job}.summary.json").exists()):
            run_xpl(xpl, deck, folder / "threads_2", 2, timing)
        results.append(threads_criterion(xpl, folder, folder / "threads_2", job))
    else:
        results.append(("threads", None, "not run"))
    return results


def run_scene(xpl, scene_id, work, threads=True, timing=None, reuse=False):
    """Write scene ID under WORK/scene_ID, run and check it: (deck, results)."""
    deck = impact_scenes.write_scene(scene_id, work)
    return deck, run_deck(xpl, deck, threads, timing, reuse)


def describe(scene_id):
    return impact_scenes.describe(impact_scenes.draw(scene_id)).strip()


def report(scene_id, results):
    """Lines: the scene, then each criterion; returns (lines, failed criteria)."""
    failed = [c for c, ok, _ in results if ok is False]
    lines = [f"scene {describe(scene_id)}: {'PASS' if not failed else 'FAIL ' + ','.join(failed)}"]
    for criterion, ok, message in results:
        mark = "ok  " if ok else ("--  " if ok is None else "FAIL")
        lines.append(f"  {mark} {criterion:11s} {message}")
    return lines, failed


def read_known(path, extra=()):
    """known_failures.txt: {scene id or deck name: {criterion: reason}}. Lines
    `ID-OR-NAME CRITERION REASON...`; `#` starts a comment. Unknown criteria (beyond CRITERIA and
    EXTRA) and malformed lines are errors: a typo must not excuse a failure."""
    known = {}
    allowed = CRITERIA + ("length", "wall") + tuple(extra)
    for number, line in enumerate(pathlib.Path(path).read_text().splitlines(), 1):
        line = line.split("#", 1)[0].strip()
        if not line:
            continue
        fields = line.split(None, 2)
        if len(fields) < 3 or fields[1] not in allowed:
            raise SystemExit(f"{path}:{number}: expected `ID-OR-NAME CRITERION REASON` with "
                             f"CRITERION one of {', '.join(allowed)}; got `{line}`")
        known.setdefault(fields[0], {})[fields[1]] = fields[2]
    return known


def judge(known, failed):
    """Print the known failures' state; return the failed criteria that are not known."""
    for criterion, reason in known.items():
        state = "still fails" if criterion in failed else "now HOLDS: remove it from the list"
        print(f"  KNOWN {criterion:11s} {state} ({reason})")
    unexpected = [c for c in failed if c not in known]
    if unexpected:
        print(f"  unexpected failures: {', '.join(unexpected)}")
    return unexpected


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    commands = parser.add_subparsers(dest="command", required=True)
    run = commands.add_parser("run", help="write, run and check one scene")
    run.add_argument("xpl")
    run.add_argument("id", type=int)
    run.add_argument("--work", default="impact_scenes", help="folder (default ./impact_scenes)")
    run.add_argument("--no-threads", action="store_true", help="skip the 2-thread run")
    run.add_argument("--known", help="known failures (ID CRITERION REASON per line)")
    check = commands.add_parser("check", help="check runs already made")
    check.add_argument("folder")
    check.add_argument("--meta", help="the scene's .json (default: the one in FOLDER)")
    check.add_argument("--xpl", help="xpl, for xpl compare (threads)")
    args = parser.parse_args(argv)
    if args.command == "run":
        work = pathlib.Path(args.work)
        deck = impact_scenes.write_scene(args.id, work)
        print(deck)
        sys.stdout.flush()
        timing = {}
        results = run_deck(args.xpl, deck, threads=not args.no_threads, timing=timing)
        lines, failed = report(args.id, results)
        print("\n".join(lines))
        print("  CPU time: " + ", ".join(f"{k.replace('cpu_', '')} thread(s) {v:.2f} s"
                                         for k, v in timing.items()))
        known = read_known(args.known).get(str(args.id), {}) if args.known else {}
        return 1 if judge(known, failed) else 0
    folder = pathlib.Path(args.folder)
    meta_path = pathlib.Path(args.meta) if args.meta else \
        next(p for p in sorted(folder.glob("*.json")) if not p.name.endswith(".summary.json"))
    meta = json.loads(meta_path.read_text())
    job = meta_path.stem
    results = check_scene(read_run(folder, job), meta)
    if (folder / "threads_2").exists():
        results.append(threads_criterion(args.xpl, folder, folder / "threads_2", job))
    lines, failed = report(meta["id"], results)
    print("\n".join(lines))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
