#!/usr/bin/python3
"""The geometry of impact_check.py's penetration criterion, on made-up meshes (no xpl run):
closest points on triangles against dense sampling, winding numbers inside and outside a
block, a node pushed into a block found at its depth (and one within the limit not), a node
moved through a shell plate reported as passed through, a node beside the plate's edge not
counted, a whole body beyond the other reported as shot through, a node outside a closed shell
box beside its edge not taken as behind a face (and one through its bottom reported), the
energy criteria failing and holding at their limits.

Usage: check_impact_geometry.py   (exit 0 when every check holds)
"""

import pathlib
import sys

import numpy as np

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import impact_check as ic  # noqa: E402
import impact_scenes as scenes  # noqa: E402

failures = []


def check(condition, message):
    print(("ok   " if condition else "FAIL ") + message)
    if not condition:
        failures.append(message)


def closest_points_against_sampling():
    rng = np.random.default_rng(1)
    a, b, c = (rng.normal(size=(20, 3)) for _ in range(3))
    p = rng.normal(size=(30, 3)) * 2.0
    _, distance = ic.closest_points(p, a, b, c)
    u, v = np.meshgrid(np.linspace(0, 1, 201), np.linspace(0, 1, 201))
    keep = u + v <= 1.0
    u, v = u[keep], v[keep]
    worst = 0.0
    for t in range(len(a)):
        samples = a[t] + u[:, None] * (b[t] - a[t]) + v[:, None] * (c[t] - a[t])
        sampled = np.linalg.norm(p[:, None, :] - samples[None], axis=-1).min(axis=1)
        if np.any(distance[:, t] > sampled + 1e-12):
            worst = np.inf
        edge = max(np.linalg.norm(b[t] - a[t]), np.linalg.norm(c[t] - a[t]))
        worst = max(worst, float(((sampled - distance[:, t]) / edge).max()))
    # The sampling grid's spacing is 1/200 of an edge: the exact distance is never above a
    # sampled one and at most that spacing below it.
    check(worst <= 1.0 / 200.0, f"closest points: exact distances within {worst:.2e} edge "
          "lengths of the sampled ones, never above")


def block_run(blocks):
    """A fake run of hex blocks: blocks = [(name, Body)], with the fields impact_check reads."""
    ids, points, elements, sets = [], [], {"C3D8R": ([], [])}, {}
    element_id = 1
    for name, body in blocks:
        base = len(points)
        for i, p in enumerate(body.points):
            ids.append(len(ids) + 1)
            points.append(p)
        members = []
        for kind, nodes in body.elements:
            elements.setdefault(kind, ([], []))
            elements[kind][0].append(element_id)
            elements[kind][1].append([base + n for n in nodes])
            members.append(element_id)
            element_id += 1
        sets[name] = np.array(members)
    run = {"node_ids": np.array(ids), "reference": np.array(points, dtype=float),
           "elements": {k: (np.array(v[0]), np.array(v[1])) for k, v in elements.items() if v[0]},
           "element_sets": sets}
    run["current"] = run["reference"].copy()
    return run


def meta_of(blocks, normal=(0.0, 0.0, 1.0)):
    return {"bodies": {name: {"kind": body.kind, "thickness": body.thickness,
                              "element_size": body.element_size()} for name, body in blocks},
            "normal": list(normal), "pair": ["PROJECTILE", "TARGET"]}


def winding_numbers_of_a_block():
    body = scenes.solid_block("B", (2.0, 2.0, 2.0), (2, 2, 2), "C3D8R")
    run = block_run([("B", body)])
    _, quads = ic.body_faces(run, "B")
    a, b, c, _, _ = ic.triangles(quads, run["reference"])
    inside = np.array([[0.0, 0.0, 0.0], [0.9, -0.9, 0.5], [0.2, 0.3, -0.99]])
    outside = np.array([[1.01, 0.0, 0.0], [3.0, 3.0, 3.0], [0.0, 0.0, -1.2]])
    w_in, w_out = ic.winding_numbers(inside, a, b, c), ic.winding_numbers(outside, a, b, c)
    check(np.allclose(w_in, 1.0) and np.allclose(w_out, 0.0, atol=1e-12),
          f"winding numbers: inside {np.round(w_in, 12)}, outside {np.round(w_out, 12)}")


def two_blocks(depth):
    """Block P (h = 0.5) resting on block T (h = 2/3, no node under P's centre), P's bottom
    centre node pushed `depth` into T."""
    lower = scenes.solid_block("TARGET", (2.0, 2.0, 1.0), (3, 3, 2), "C3D8R")
    lower.moved(shift=(0.0, 0.0, -0.5))
    upper = scenes.solid_block("PROJECTILE", (1.0, 1.0, 1.0), (2, 2, 2), "C3D8R")
    upper.moved(shift=(0.0, 0.0, 0.5 + 1e-9))
    blocks = [("PROJECTILE", upper), ("TARGET", lower)]
    run = block_run(blocks)
    centre = int(np.flatnonzero(np.all(np.isclose(run["reference"], [0.0, 0.0, 1e-9]),
                                       axis=1))[0])
    run["current"][centre, 2] -= depth
    return run, meta_of(blocks), int(run["node_ids"][centre])


def solid_penetration():
    h = 0.5
    run, meta, node = two_blocks(0.2 * h)
    findings, crossings = ic.penetration(run, meta)
    check(len(findings) == 1 and f"node {node} " in findings[0][2]
          and abs(findings[0][0] - 0.2 * h) < 1e-6 and not crossings,
          f"a node 0.2 h inside a block is found at its depth: {[f[2] for f in findings]}")
    run, meta, node = two_blocks(0.05 * h)
    findings, crossings = ic.penetration(run, meta)
    check(not findings and not crossings, "a node 0.05 h inside a block is within the limit")


def plate_and_block(move):
    plate = scenes.shell_plate("TARGET", (4.0, 4.0), (4, 4), 0.4)
    block = scenes.solid_block("PROJECTILE", (1.0, 1.0, 1.0), (2, 2, 2), "C3D8R")
    block.moved(shift=(0.0, 0.0, 0.7 + 1e-6))
    blocks = [("PROJECTILE", block), ("TARGET", plate)]
    run = block_run(blocks)
    run["elements"] = {"C3D8R": run["elements"]["C3D8R"], "S4R": run["elements"]["S4R"]}
    move(run)
    return run, meta_of(blocks)


def shell_crossing():
    def through(run):  # the block's bottom centre node 0.3 below the plate's mid-surface
        centre = np.flatnonzero(np.all(np.isclose(run["reference"], [0, 0, 0.2 + 1e-6]), axis=1))
        run["current"][centre, 2] = -0.3
    findings, crossings = ic.penetration(*plate_and_block(through))
    check(len(crossings) == 1 and "other side" in crossings[0],
          f"a node moved through a plate is reported: {crossings}")

    def into(run):  # the whole bottom face 0.06 into the plate's upper half thickness
        bottom = np.isclose(run["reference"][:, 2], 0.2 + 1e-6)
        run["current"][bottom, 2] -= 0.06 + 1e-6
    findings, crossings = ic.penetration(*plate_and_block(into))
    # 9 nodes of the block's bottom face, and the plate's node under them the other way round
    check(len(findings) == 10 and not crossings and abs(findings[0][0] - 0.06) < 1e-9,
          f"nodes 0.06 into a plate's thickness, limit 0.05: "
          f"{len(findings)} found, depth {findings[0][0] if findings else None}")

    def beside(run):  # the block moved beside the plate's edge, level with it, 0.3 away
        above = run["reference"][:, 2] > 0.01
        run["current"][above, 0] += 2.8
        run["current"][above, 2] -= 0.7
    findings, crossings = ic.penetration(*plate_and_block(beside))
    check(not findings and not crossings, f"nodes beside a plate's edge are not inside it: "
          f"{[f[2] for f in findings[:2]]} {crossings[:2]}")

    def shot(run):  # the whole block below the plate
        above = run["reference"][:, 2] > 0.01
        run["current"][above, 2] -= 3.0
    findings, crossings = ic.penetration(*plate_and_block(shot))
    check(any("wholly beyond" in c for c in crossings),
          f"a block below the plate is shot through: {crossings[-1:]}")


def shell_box_edge():
    """A node outside a closed shell box near its edge is not behind the box's faces; a node
    moved through the box's bottom is."""
    box = scenes.shell_box("TARGET", (2.0, 2.0, 2.0), (2, 2, 2), 0.1)
    block = scenes.solid_block("PROJECTILE", (1.0, 1.0, 1.0), (1, 1, 1), "C3D8R")
    block.moved(shift=(0.0, 0.0, -3.0))
    blocks = [("PROJECTILE", block), ("TARGET", box)]
    run = block_run(blocks)
    meta = meta_of(blocks)
    meta["pair"] = None
    corner = int(np.flatnonzero(np.all(np.isclose(run["reference"], [0.5, 0.5, -2.5]),
                                       axis=1))[0])
    other = int(np.flatnonzero(np.all(np.isclose(run["reference"], [-0.5, 0.5, -2.5]),
                                      axis=1))[0])
    # Each beside the edge x = 1, z = -1, in the plane of one of its faces (1e-9 on the inner
    # side of it): the closest point is on the edge, where the two faces tie; whichever wins,
    # one node is behind its face's plane, so a test along face normals reports a crossing.
    run["current"][corner] = [1.3, 0.0, -1.0 + 1e-9]
    run["current"][other] = [1.0 - 1e-9, 0.0, -1.3]
    findings, crossings = ic.penetration(run, meta)
    check(not findings and not crossings,
          f"nodes outside a shell box beside its edge are not behind its faces: {crossings}")
    run["current"][other] = run["reference"][other]
    run["current"][corner] = [0.2, 0.1, -0.8]  # 0.2 inside the box's bottom
    findings, crossings = ic.penetration(run, meta)
    check(len(crossings) == 1, f"a node through a shell box's bottom is reported: {crossings}")


def energy_checks():
    run = {"energy": {"ALLKE": np.array([10.0, 5.0, -0.1]), "ALLIE": np.array([0.0, 5.0, 9.0]),
                      "ALLAE": np.array([0.0, 0.2, 1.0]), "ETOTAL": np.array([10.0, 10.0, 9.85]),
                      "ALLWK": np.zeros(3)}}
    results = {c: ok for c, ok, _ in ic.energy_criteria(run)}
    check(all(results[c] is False for c in ("drift", "hourglass", "kinetic")),
          f"energy criteria fail as they should: {results}")
    run["energy"]["ALLKE"][2] = 0.1
    run["energy"]["ALLAE"][2] = 0.9
    run["energy"]["ETOTAL"][2] = 9.95
    results = {c: ok for c, ok, _ in ic.energy_criteria(run)}
    check(all(results[c] is True for c in ("drift", "hourglass", "kinetic")),
          f"and hold at their limits: {results}")


def main():
    closest_points_against_sampling()
    winding_numbers_of_a_block()
    solid_penetration()
    shell_crossing()
    shell_box_edge()
    energy_checks()
    if failures:
        print(f"check_impact_geometry.py: {len(failures)} FAILED")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
