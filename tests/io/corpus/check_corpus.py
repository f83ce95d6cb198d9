#!/usr/bin/python3
"""The corpus of decks as users have them (tests/data/decks, issue 34 item 5, SPEC I5): each
case reads its deck with `xpl check` (the model: counts, sets, a few coordinates), runs it and
checks what the run must show.

Usage: check_corpus.py XPL DECKS OUT CASE
  XPL    the xpl program; DECKS tests/data/decks; OUT a scratch directory (emptied)
  CASE   cae_assembly | gmsh_block | gmsh_plate | meshio_block | calculix_massless |
         calculix_clearance | calculix_refused

Exits non-zero on the first failed check. Each case runs xpl two to four times on models of
at most 54 nodes (a few seconds in all).
"""

import pathlib
import re
import shutil
import subprocess
import sys

import h5py
import numpy as np


def check(condition, message):
    if not condition:
        sys.exit(f"check_corpus.py: FAILED: {message}")
    print(f"check_corpus.py: ok: {message}")


def xpl(binary, *args, expect=0):
    result = subprocess.run([str(binary), *map(str, args)], capture_output=True, text=True,
                            timeout=300)
    if result.returncode != expect:
        sys.stdout.write(result.stdout)
        sys.stderr.write(result.stderr)
        sys.exit(f"check_corpus.py: FAILED: xpl {' '.join(map(str, args))} exited with "
                 f"{result.returncode}, expected {expect}")
    return result


def run(binary, deck, out, command="run"):
    """xpl check|run DECK -o OUT; the results file."""
    out.mkdir(parents=True, exist_ok=True)
    quiet = ["--quiet"] if command == "run" else []
    xpl(binary, command, deck, "-o", out, *quiet)
    return out / (pathlib.Path(deck).stem + ".h5")


def node_set(f, name):
    return sorted(int(i) for i in f[f"mesh/node_sets/{name}"][:])


def coordinates(f, node_id):
    ids = list(f["mesh/node_ids"][:])
    return f["mesh/coordinates"][ids.index(node_id)]


def history(f, path, step=1):
    return f[f"history/step_{step}/{path}"][:]


def msg(out, job):
    return (out / f"{job}.msg").read_text()


def cae_assembly(binary, decks, out):
    folder = decks / "cae_assembly"
    cae, flat = folder / "two_blocks_cae.inp", folder / "two_blocks_flat.inp"
    with h5py.File(run(binary, cae, out / "check", "check"), "r") as f:
        check(len(f["mesh/node_ids"]) == 54 and len(f["mesh/element_ids"]) == 16,
              "two instances of a 27-node, 8-element part: 54 nodes, 16 elements")
        check(list(f["mesh/node_ids"][:27]) == list(range(1, 28))
              and list(f["mesh/node_ids"][27:]) == list(range(101, 128)),
              "model ids: Block-1 keeps the part's, Block-2 has 100 + the part's")
        check(f["mesh"].attrs["instances"] == "BLOCK-1,BLOCK-2"
              and f["mesh"].attrs["instance_parts"] == "BLOCK,BLOCK", "instance names and parts")
        check(list(f["mesh/node_instance"][:]) == [0] * 27 + [1] * 27
              and list(f["mesh/node_local_ids"][27:]) == list(range(1, 28))
              and list(f["mesh/element_local_ids"][8:]) == list(range(1, 9)),
              "each node and element keeps its instance and part id")
        check(node_set(f, "BLOCK-1.BOTTOM") == list(range(1, 10)), "part-level set, qualified")
        check(node_set(f, "BLOCK-2.PROBE") == [127], "instance-level set")
        check(node_set(f, "MOVING") == list(range(101, 128)),
              "assembly-level set with INSTANCE= and GENERATE")
        check(sorted(f["mesh/element_sets/_UNDER_S1"][:]) == [101, 102, 103, 104],
              "assembly-level internal element set")
        # Block-2's node 1 (0, 0, 0): up by 10.2 mm, then 30 degrees about the vertical axis
        # through (4.7, 5.3) mm.
        c, s = np.cos(np.radians(30.0)), np.sin(np.radians(30.0))
        a = np.array([0.0047, 0.0053, 0.0])
        d = np.array([0.0, 0.0, 0.0102]) - a
        expected = a + np.array([c * d[0] - s * d[1], s * d[0] + c * d[1], d[2]])
        check(np.allclose(coordinates(f, 101), expected, rtol=0, atol=1e-17),
              f"Block-2's node 1 translated then rotated: {coordinates(f, 101)}")
        check(np.array_equal(coordinates(f, 27), [0.01, 0.01, 0.01]), "Block-1 in place")
    text = msg(out / "check", "two_blocks_cae")
    check("instance BLOCK-2 of part BLOCK: 27 nodes, 8 elements, translated by (0, 0, 0.0102), "
          "then rotated by 30 degrees" in text, ".msg lists the instances")
    check("*RESTART: no restart file is written" in text, "*RESTART accepted with a note")
    xdmf = (out / "check" / "two_blocks_cae.xdmf").read_text()
    check('Name="node_local_id"' in xdmf and 'Name="element_instance"' in xdmf
          and 'Name="instances" Value="BLOCK-1,BLOCK-2"' in xdmf, "XDMF attributes")

    h5_cae = run(binary, cae, out / "cae")
    h5_flat = run(binary, flat, out / "flat")
    with h5py.File(h5_cae, "r") as f:
        check(f.attrs["status"] == "completed", "the CAE deck runs")
        v3 = history(f, "node/BLOCK-2.PROBE/V3")[:, 0]
        u3 = history(f, "node/BLOCK-2.PROBE/U3")[:, 0]
        check(v3[0] == -10.0 and v3[-1] > 5.0,
              f"Block-2 bounces off Block-1: V3 {v3[0]:.3g} -> {v3[-1]:.3g} m/s")
        check(u3.min() > -0.0003, f"contact holds Block-2 above Block-1 (U3 >= {u3.min():.3g} m)")
    result = xpl(binary, "compare", h5_flat, h5_cae, "--history", "--rtol", "1e-9")
    check(result.returncode == 0, "the same history as the model written flat (rtol 1e-9)")


def gmsh_block(binary, decks, out, deck=None):
    deck = deck or decks / "gmsh_block" / "block.inp"
    with h5py.File(run(binary, deck, out / "check", "check"), "r") as f:
        check(len(f["mesh/node_ids"]) == 45, "45 nodes (5 x 3 x 3)")
        check(len(f["mesh/element_ids"]) == 16 and "C3D8" in f["mesh"],
              "16 hexahedra; the CPS4 faces are geometry")
        check(node_set(f, "CORNER") == [1], "the physical point as a node set")
        check(len(node_set(f, "BOTTOM")) == 15 and len(node_set(f, "TOP")) == 15,
              "node sets of the physical surfaces")
        check(np.array_equal(coordinates(f, 2), [0.02, 0.0, 0.0]), "node 2 at (20, 0, 0) mm")
    text = msg(out / "check", deck.stem)
    check(len(re.findall(r"\*ELEMENT: 8 CPS4 elements (\(ELSET=SURFACE\d+\) )?carry no section: "
                         r"read as geometry", text)) == 2, ".msg: the CPS4 blocks are geometry")
    h5 = run(binary, deck, out / "run")
    with h5py.File(h5, "r") as f:
        check(f.attrs["status"] == "completed", "the gmsh block runs")
        u3 = history(f, "node/TOP/U3")[-1]
        # 1e8 Pa on 10 mm of steel: p H / E = 4.8e-6 m statically, up to twice that dynamically.
        check(np.all(u3 < -1e-6) and np.all(u3 > -2e-5),
              f"the pressure on the CPS4 top face compresses the block: U3 {u3.min():.3g} .. "
              f"{u3.max():.3g} m")
        return h5


def gmsh_plate(binary, decks, out):
    folder = decks / "gmsh_plate"
    deck = folder / "plate.inp"
    with h5py.File(run(binary, deck, out / "check", "check"), "r") as f:
        check(len(f["mesh/node_ids"]) == 45 and list(f["mesh"].keys()).count("S4R") == 1
              and len(f["mesh/S4R/element_ids"]) == 32, "45 nodes, 32 CPS4 run as S4R")
        check(node_set(f, "CLAMPED") == [1, 4, 22, 23, 24], "node set of the T3D2 edge clamped")
        check(len(node_set(f, "FREE_EDGE")) == 5, "node set of the free edge")
        check(np.array_equal(coordinates(f, 3), [0.1, 0.05, 0.0]), "node 3 at (100, 50, 0) mm")
    text = msg(out / "check", "plate")
    check("32 CPS4 elements (ELSET=SURFACE1) are under a *SHELL SECTION: run as S4R" in text,
          ".msg: CPS4 run as S4R")
    h5 = run(binary, deck, out / "run")
    with h5py.File(h5, "r") as f:
        check(f.attrs["status"] == "completed", "the gmsh plate runs")
        u3 = history(f, "node/FREE_EDGE/U3")[-1]
        check(np.all(np.abs(u3) > 1e-6) and (np.all(u3 > 0) or np.all(u3 < 0)),
              f"the pressure bends the free edge one way: U3 {u3.min():.3g} .. {u3.max():.3g} m")
    # The same plate with the quads named S4R: bitwise the same results.
    renamed = out / "renamed"
    renamed.mkdir(parents=True, exist_ok=True)
    shutil.copy(deck, renamed / "plate.inp")
    (renamed / "plate_mesh.inp").write_text(
        (folder / "plate_mesh.inp").read_text().replace("type=CPS4", "type=S4R"))
    h5_s4r = run(binary, renamed / "plate.inp", out / "run_s4r")
    result = xpl(binary, "compare", h5_s4r, h5, "--rtol", "0", "--atol", "0", "--frames", "all")
    check(result.returncode == 0, "CPS4 under a *SHELL SECTION = S4R, bitwise")


def meshio_block(binary, decks, out):
    folder = decks / "meshio_block"
    result = xpl(binary, "check", folder / "block.inp", "-o", out / "refused", expect=1)
    errors = [line for line in result.stderr.splitlines() if "block_meshio.inp:" in line]
    check(len(errors) == 2, f"one error per foreign type: {errors}")
    check(any("element type CAX4P is not supported; nearest supported: S4R" in e for e in errors)
          and any("element type C3D8RH is not supported; nearest supported: C3D8R" in e
                  for e in errors), "each names the nearest supported type")
    # With the names changed as the errors say (C3D8 as gmsh wrote it; CPS4 for the faces),
    # meshio's export runs as gmsh's.
    edited = out / "edited"
    edited.mkdir(parents=True, exist_ok=True)
    shutil.copy(folder / "block.inp", edited / "block.inp")
    (edited / "block_meshio.inp").write_text(
        (folder / "block_meshio.inp").read_text().replace("TYPE=C3D8RH", "TYPE=C3D8")
        .replace("TYPE=CAX4P", "TYPE=CPS4"))
    h5 = gmsh_block(binary, decks, out / "edited_run", edited / "block.inp")
    h5_gmsh = gmsh_block(binary, decks, out / "gmsh_run")
    with h5py.File(h5, "r") as a, h5py.File(h5_gmsh, "r") as b:
        same = all(np.array_equal(history(a, f"energy/{e}"), history(b, f"energy/{e}"))
                   for e in ("ALLKE", "ALLIE", "ALLWK"))
        check(same and np.array_equal(history(a, "node/TOP/U3"), history(b, "node/TOP/U3")),
              "meshio's export, renamed, gives gmsh's history bitwise")


def calculix_massless(binary, decks, out):
    deck = decks / "calculix" / "massless_cubes.inp"
    with h5py.File(run(binary, deck, out / "check", "check"), "r") as f:
        check(len(f["mesh/node_ids"]) == 54 and len(f["mesh/element_ids"]) == 16,
              "two cubes: 54 nodes, 16 elements")
        check(len(node_set(f, "NFIX")) == 9 and node_set(f, "N1") == [127], "node sets")
        check(np.allclose(coordinates(f, 101), [0.0, 0.0, 10.01], rtol=0, atol=1e-12),
              "the upper cube 0.01 mm above the lower")
    text = msg(out / "check", "massless_cubes")
    check("TYPE=MASSLESS (CalculiX's explicit contact" in text, ".msg: MASSLESS runs as penalty")
    check("ALPHA=-0.05 ignored" in text, ".msg: ALPHA= ignored")
    with h5py.File(run(binary, deck, out / "run"), "r") as f:
        check(f.attrs["status"] == "completed", "the MASSLESS deck runs")
        u3 = history(f, "node/N1/U3")[:, 0]
        # Free flight for 2e-5 s would move the cube 0.02 mm, through the 0.01 mm gap; with
        # contact its top corner comes down by the gap and both cubes' compression, 2 x 2.2 um
        # (a stress wave of rho c v = 46 MPa in steel at 1 m/s).
        check(-0.0155 < u3.min() < -0.0120,
              f"contact stops the upper cube (U3 min {u3.min():.4g} mm)")
        check(u3[-1] > u3.min() + 1e-3, f"and it bounces back (U3 {u3.min():.4g} -> "
              f"{u3[-1]:.4g} mm)")


def calculix_clearance(binary, decks, out):
    deck = decks / "calculix" / "clearance_cubes.inp"
    text = ""
    with h5py.File(run(binary, deck, out / "run"), "r") as f:
        check(f.attrs["status"] == "completed", "the *CLEARANCE deck runs")
        t = history(f, "time")
        u3 = history(f, "node/N1/U3")[:, 0]
        free = -1000.0 * t  # mm: the cube's free flight
        touched = t[np.argmax(np.abs(u3 - free) > 1e-4)]
        check(1.5e-5 < touched < 3.5e-5,
              f"contact starts once the cube has closed the 0.02 mm clearance (20 us; the mesh's "
              f"gap of 0.1 mm would take 100 us): at {touched * 1e6:.1f} us")
        text = msg(out / "run", "clearance_cubes")
    check("*CLEARANCE: VALUE=0.02 runs as xpl's contact clearance with ADJUST=NO" in text,
          ".msg: the clearance note")


def calculix_refused(binary, decks, out):
    result = xpl(binary, "check", decks / "calculix" / "refused.inp", "-o", out, expect=1)
    errors = [line for line in result.stderr.splitlines() if "refused.inp:" in line]
    check(len(errors) == 3, f"three errors: {errors}")
    for keyword, text in (("*ELEMENT", "element type C3D20 is not supported"),
                          ("*EQUATION", "linear constraint equations are not supported"),
                          ("*STATIC", "static analysis is not supported")):
        check(any(f"{keyword}: {text}" in e for e in errors), f"{keyword}: {text}")


CASES = {f.__name__: f for f in (cae_assembly, gmsh_block, gmsh_plate, meshio_block,
                                 calculix_massless, calculix_clearance, calculix_refused)}


def main():
    if len(sys.argv) != 5 or sys.argv[4] not in CASES:
        sys.exit(__doc__)
    binary, decks, out = (pathlib.Path(a) for a in sys.argv[1:4])
    shutil.rmtree(out, ignore_errors=True)
    out.mkdir(parents=True)
    CASES[sys.argv[4]](binary, decks, out)


if __name__ == "__main__":
    main()
