#!/usr/bin/python3
"""What users see in meshio, h5py and ParaView (issue 19).

Usage: check_viz.py CASE XPL REPO OUT_DIR, CASE one of
  shear     a one-element C3D8R deck sheared in x on its top face (only S13 = S_xz nonzero):
            meshio reads S13 from JOB.xdmf (TimeSeriesReader) and JOB_last.xdmf (meshio.read)
            in column 5 of the Tensor6 attribute S, VTK's XZ; the .h5 copy says so in its
            components attribute; deck ids and sets reach meshio; the one-node history set is
            (nt, 1) with node_ids, units and components
  plate     examples/plate_pressure: MISES_SNEG / MISES_SPOS equal the Mises stress of S_SNEG /
            S_SPOS to 1e-12 relative, MISES_MAX is the largest of them and MISES, and its peak is
            the plate's peak surface stress; the global-axes XDMF copies keep the Mises stress
  live      h5py opens JOB.h5 over and over while a run of a few seconds writes frames (HDF5's
            default locking, no HDF5_USE_FILE_LOCKING): an open refused while xpl writes is
            retried; every open sees status "running" and a growing prefix of whole frames (>= 2
            distinct counts), equal to the final file's; a reader holding the file 1.5 s makes
            the run wait (noted in JOB.msg), not fail; `xpl history` works mid-run; JOB.xdmf
            lists frames mid-run, never one the .h5 lacks, and every frame at the end; the end
            "completed"
  paraview  the shear job through pvpython's XDMF reader: S's component 5 is named XZ and holds
            S13, node_id / element_id are there, the sets are 0/1 arrays and the reader gives
            one block (no set blocks); skipped (exit 77) without pvpython
  screenshot  examples/contact/tube_crush opened as README.md says (Open, Apply, Last Frame,
            Warp By Vector, Apply) by scripts/paraview_screenshot.py (xvfb-run pvpython):
            ParaView's own default colouring is MISES_MAX, the model is drawn deformed (its top
            where the .h5 puts it), most of its pixels are coloured with warm and cold cells
            (not grey), its peak MISES_MAX and that element's id are the .h5's, the sets are the
            deck's; skipped (exit 77) without pvpython or xvfb-run
"""

import ast
import os
import pathlib
import re
import shutil
import subprocess
import sys
import time

import h5py
import meshio
import numpy as np

SKIP = 77
VTK_ORDER = [0, 1, 2, 3, 5, 4]  # S11 S22 S33 S12 S23 S13 -> XX YY ZZ XY YZ XZ


def fail(message):
    sys.exit(f"check_viz.py: FAILED: {message}")


def check(condition, message):
    if not condition:
        fail(message)


def run(xpl, deck, out, *extra):
    result = subprocess.run([xpl, "run", str(deck), "-o", str(out), "--threads", "1", "--quiet",
                             *extra], capture_output=True, text=True, timeout=60,
                            env=clean_env())
    check(result.returncode == 0, f"xpl run {deck}: exit {result.returncode}: {result.stderr}")


def clean_env():
    """The environment without HDF5_USE_FILE_LOCKING: live reading must not need it."""
    env = dict(os.environ)
    env.pop("HDF5_USE_FILE_LOCKING", None)
    return env


SHEAR_DECK = """*HEADING
One C3D8R cube, 1 m, top face moved in x: simple shear, only S13 (= S_xz)
*NODE
1, 0, 0, 0
2, 1, 0, 0
3, 1, 1, 0
4, 0, 1, 0
5, 0, 0, 1
6, 1, 0, 1
7, 1, 1, 1
8, 0, 1, 1
*ELEMENT, TYPE=C3D8R, ELSET=CUBE
17, 1, 2, 3, 4, 5, 6, 7, 8
*NSET, NSET=BOTTOM
1, 2, 3, 4
*NSET, NSET=TOP
5, 6, 7, 8
*NSET, NSET=CORNER
7
*MATERIAL, NAME=STEEL
*DENSITY
7800.0
*ELASTIC
2.0e11, 0.3
*SOLID SECTION, ELSET=CUBE, MATERIAL=STEEL
*STEP, NAME=SHEAR
*DYNAMIC, EXPLICIT
, 1e-5
*BOUNDARY
BOTTOM, 1, 3
TOP, 2, 3
*BOUNDARY, TYPE=VELOCITY
TOP, 1, 1, 1e-3
*OUTPUT, FIELD, NUMBER INTERVAL=2
*NODE OUTPUT
U
*ELEMENT OUTPUT
S
*OUTPUT, HISTORY, NUMBER INTERVAL=10
*NODE OUTPUT, NSET=CORNER
U1
*ENERGY OUTPUT
*END STEP
"""


def shear_job(out):
    deck = out / "shear.inp"
    out.mkdir(parents=True, exist_ok=True)
    deck.write_text(SHEAR_DECK)
    return deck


def case_shear(xpl, repo, out):
    deck = shear_job(out)
    results = out / "results"
    run(xpl, deck, results)
    with h5py.File(results / "shear.h5", "r") as f:
        last = sorted(f["frames"])[-1]
        s = f["frames"][last]["S"][()]
        check(f["frames"][last]["S"].attrs["components"] == "S11,S22,S33,S12,S13,S23",
              "components of /frames/NNNNNN/S")
        check(f["frames"][last]["S"].attrs["units"] == "Pa", "units of S")
        copy = f["xdmf"][last]["S"]
        check(copy.attrs["components"] == "XX,YY,ZZ,XY,YZ,XZ", "components of /xdmf/NNNNNN/S")
        history = f["history/step_1/node/CORNER/U1"]
        check(history.ndim == 2 and history.shape[1] == 1, f"one-node history {history.shape}")
        check(list(history.attrs["node_ids"]) == [7], "history node_ids")
        check(history.attrs["units"] == "m" and history.attrs["components"] == "U1",
              "history units / components")
        check(f["history/step_1/energy/ALLKE"].attrs["units"] == "J", "energy units")
        n_frames = len(f["frames"])
    s13 = s[0, 4]
    # Simple shear of 1e-8: S13 = G γ ≈ 0.8 kPa; the other components are second order in γ
    # (rotation of the stress), below 1e-6 of S13.
    check(abs(s13) > 100.0, f"S13 = {s13} Pa: the deck does not shear")
    others = np.delete(s[0], 4)
    check(np.all(np.abs(others) < 1e-6 * abs(s13)), f"not simple shear: S = {s[0]}")

    mesh = meshio.read(results / "shear_last.xdmf")
    xdmf_s = mesh.cell_data["S"][0]
    check(xdmf_s.shape == (1, 6), f"meshio S shape {xdmf_s.shape}")
    check(np.argmax(np.abs(xdmf_s[0])) == 5, f"S13 not in column 5 (XZ): {xdmf_s[0]}")
    check(xdmf_s[0, 5] == s13, "XZ differs from S13")
    check(np.array_equal(xdmf_s[0], s[0][VTK_ORDER]), "meshio S is not S in VTK order")
    check(list(mesh.cell_data["element_id"][0]) == [17], "element_id")
    check(list(mesh.point_data["node_id"]) == list(range(1, 9)), "node_id")
    check(list(mesh.point_data["NSET_TOP"]) == [0, 0, 0, 0, 1, 1, 1, 1], "NSET_TOP")
    check(list(mesh.cell_data["ELSET_CUBE"][0]) == [1], "ELSET_CUBE")
    check("HGSTATE" not in mesh.cell_data, "HGSTATE in the XDMF")
    text = (results / "shear.xdmf").read_text()
    check('<Attribute Name="S" AttributeType="Tensor6" Center="Cell">' in text, "S Tensor6")
    check("HGSTATE" not in text, "HGSTATE in JOB.xdmf")
    # Issue 34: sets are 0/1 arrays, not XDMF Set elements (which ParaView's Xdmf3 reader
    # draws as grey blocks over the mesh); deck ids are global ids; the one "Scalar" of a frame
    # is the field ParaView colours by (MISES here).
    check('<Attribute Name="NSET_TOP" AttributeType="None" Center="Node">' in text,
          "NSET_TOP 0/1 attribute in JOB.xdmf")
    check("<Set " not in text, "a Set element in JOB.xdmf")
    check('<Attribute Name="node_id" AttributeType="GlobalId" Center="Node">' in text,
          "node_id as GlobalId")
    scalars = re.findall(r'<Attribute Name="(\w+)" AttributeType="Scalar"', text)
    check(scalars and set(scalars) == {"MISES"}, f"Scalar attributes {sorted(set(scalars))}")
    check('<Information Name="step_name" Value="SHEAR"/>' in text, "step name information")
    with meshio.xdmf.TimeSeriesReader(results / "shear.xdmf") as reader:
        reader.read_points_cells()
        check(reader.num_steps == n_frames, "TimeSeriesReader steps")
        _, _, cell_data = reader.read_data(reader.num_steps - 1)
        check(cell_data["S"][0][0, 5] == s13, "TimeSeriesReader: XZ differs from S13")
    # The meshio command line (`meshio convert`; Debian's python3-meshio installs no `meshio`
    # script, so its entry point is called) reads the last-frame file too.
    converted = out / "shear.vtu"
    cli = "import sys, meshio._cli; sys.exit(meshio._cli.main())"
    result = subprocess.run([sys.executable, "-c", cli, "convert",
                             str(results / "shear_last.xdmf"), str(converted)],
                            capture_output=True, text=True, timeout=60)
    check(result.returncode == 0 and converted.exists(), f"meshio convert: {result.stderr}")
    # Issue 19, item 6: U at every 4th interval, S at every 3rd: the S-only frames get U too.
    two = out / "two_requests.inp"
    two.write_text(SHEAR_DECK.replace(", 1e-5\n", ", 2e-3\n")
                   .replace("*OUTPUT, FIELD, NUMBER INTERVAL=2",
                            "*OUTPUT, FIELD, NUMBER INTERVAL=4")
                   .replace("*ELEMENT OUTPUT\nS\n", "")
                   .replace("*OUTPUT, HISTORY", "*OUTPUT, FIELD, NUMBER INTERVAL=3\n"
                            "*ELEMENT OUTPUT\nS\n*OUTPUT, HISTORY"))
    run(xpl, two, out / "two")
    with h5py.File(out / "two" / "two_requests.h5", "r") as f:
        frames = [f["frames"][n] for n in sorted(f["frames"])]
        check(len(frames) == 7, f"{len(frames)} frames of two requests")
        check(sum("S" in g and len(g) > 1 for g in frames) >= 3, "frames with S")
        check(all("U" in g for g in frames), "a frame without U")
    print(f"shear: S13 = {s13:.6g} Pa in column 5 (XZ) of meshio's S; ids, sets, "
          f"(nt, 1) history OK")


def mises(s):
    d1, d2, d3 = s[:, 0] - s[:, 1], s[:, 1] - s[:, 2], s[:, 2] - s[:, 0]
    return np.sqrt(0.5 * (d1 * d1 + d2 * d2 + d3 * d3) + 3.0 * (s[:, 3:] ** 2).sum(axis=1))


def case_plate(xpl, repo, out):
    results = out / "results"
    run(xpl, repo / "examples" / "plate_pressure" / "plate_pressure.inp", results)
    peak_surface, peak_max, peak_mid = 0.0, 0.0, 0.0
    with h5py.File(results / "plate_pressure.h5", "r") as f:
        for name in f["frames"]:
            frame = f["frames"][name]
            if "S" not in frame:
                continue
            surfaces = []
            for side in ("SNEG", "SPOS"):
                expected = mises(frame["S_" + side][()])
                got = frame["MISES_" + side][()]
                # Same formula, other summation order: rounding only, 1e-12 relative.
                scale = np.maximum(np.abs(expected), 1e-300)
                check(np.all(np.abs(got - expected) <= 1e-12 * scale),
                      f"{name}: MISES_{side} differs from the Mises stress of S_{side}")
                # The global-axes copy shown by the XDMF file is a rotation: same Mises stress
                # (1e-12 relative, rounding of the rotation).
                glob = f["xdmf"][name]["S_" + side][()][:, [0, 1, 2, 3, 5, 4]]
                check(np.all(np.abs(mises(glob) - expected) <= 1e-12 * scale + 1e-300),
                      f"{name}: the global copy of S_{side} has another Mises stress")
                surfaces.append(got)
            mid = frame["MISES"][()]
            biggest = np.maximum(np.maximum(surfaces[0], surfaces[1]), mid)
            check(np.array_equal(frame["MISES_MAX"][()], biggest), f"{name}: MISES_MAX")
            peak_surface = max(peak_surface, float(np.max(surfaces)))
            peak_max = max(peak_max, float(frame["MISES_MAX"][()].max()))
            peak_mid = max(peak_mid, float(mid.max()))
    check(peak_max == peak_surface, f"peak MISES_MAX {peak_max} != peak surface {peak_surface}")
    # Bending: the surfaces carry far more than the middle surface (issue 19: 15x).
    check(peak_surface > 5.0 * peak_mid, f"surface {peak_surface} vs middle {peak_mid}")
    mesh = meshio.read(results / "plate_pressure_last.xdmf")
    for name in ("MISES_MAX", "MISES_SPOS", "MISES_SNEG", "S_LOCAL", "element_id", "NSET_EDGES"):
        check(name in mesh.cell_data or name in mesh.point_data, f"meshio: {name} missing")
    print(f"plate: peak surface Mises {peak_surface / 1e6:.3f} MPa = peak MISES_MAX; middle "
          f"{peak_mid / 1e6:.3f} MPa")


def open_when_free(h5_path, counts, deadline):
    """h5py.File(h5_path) with HDF5's default locking, retried while the writer holds the file
    (docs/user/reading-results.md: an open fails while xpl writes; retry), until time.monotonic()
    passes `deadline`. counts["busy"] counts the refused opens."""
    while True:
        try:
            return h5py.File(h5_path, "r")
        except OSError as error:
            counts["busy"] += 1
            check(time.monotonic() < deadline, f"JOB.h5 stayed locked: {error}")
            time.sleep(0.005)


def case_live(xpl, repo, out):
    deck = out / "deck" / "block.inp"
    deck.parent.mkdir(parents=True)
    # About 3 s at one thread (9 s for 40000 increments measured), a frame every ~140
    # increments: some 85 frames while the reader polls.
    subprocess.run([sys.executable, str(repo / "benchmarks" / "make_block.py"), "-n", "10",
                    "--increments", "12000", "--out", str(deck)], check=True,
                   capture_output=True)
    text = deck.read_text().replace(
        "** No output requests: the benchmark times the element loop.",
        "*OUTPUT, FIELD, TIME INTERVAL=0.0002\n*NODE OUTPUT\nU, V\n*ELEMENT OUTPUT\nS\n"
        "*OUTPUT, HISTORY, TIME INTERVAL=0.0001\n*ENERGY OUTPUT")
    deck.write_text(text)
    results = out / "results"
    h5_path = results / "block.h5"
    process = subprocess.Popen([xpl, "run", str(deck), "-o", str(results), "--threads", "1",
                                "--quiet"], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                               text=True, env=clean_env())
    counts = {"busy": 0}
    opens, counts_seen, frames_read, held, xdmf_seen = 0, [], {}, False, 0
    history_rows, history_csv = 0, None
    t0 = time.monotonic()
    while process.poll() is None and time.monotonic() - t0 < 60:
        if not h5_path.exists():
            time.sleep(0.005)
            continue
        # JOB.xdmf, read before the .h5: it may lag the .h5 (rewritten at most once a
        # second) but never names a frame the .h5 does not hold yet.
        xdmf_path = results / "block.xdmf"
        listed = sorted(set(re.findall(r"/frames/(\d{6})/", xdmf_path.read_text()))) \
            if xdmf_path.exists() else []
        f = open_when_free(h5_path, counts, t0 + 60)
        # Once the file is open nothing may fail: every read below is of a closed, complete
        # file (no exception is caught here).
        with f:
            running = process.poll() is None
            status = f.attrs["status"]
            names = sorted(f["frames"]) if "frames" in f else []
            # A consistent prefix: frames 0..n-1, each whole (U, V, S of the model's size)
            # with a time after the last one's.
            check(names == [f"{k:06d}" for k in range(len(names))], f"frames {names}")
            check(len(names) >= (counts_seen[-1] if counts_seen else 0), "frames disappeared")
            check(set(listed) <= set(names), f"JOB.xdmf lists frames {sorted(set(listed) - set(names))} "
                  "the .h5 does not hold")
            if running and listed:
                xdmf_seen = max(xdmf_seen, len(listed))
            for name in names:
                if name in frames_read:
                    continue
                g = f["frames"][name]
                check(set(g) == {"U", "V", "S", "MISES", "HGSTATE"},
                      f"frame {name} holds {sorted(g)}")
                u, s = g["U"][()], g["S"][()]
                check(u.shape == (1331, 3) and g["V"].shape == (1331, 3) and s.shape == (1000, 6),
                      f"frame {name}: U {u.shape}, S {s.shape}")
                t = float(g.attrs["time"])
                check(not frames_read or t > max(v[0] for v in frames_read.values()),
                      f"frame {name} at t = {t}: not after the frames before it")
                frames_read[name] = (t, u, s)
            if "history" in f:
                rows = f["history/step_1/time"].shape[0]
                check(f["history/step_1/energy/ALLKE"].shape == (rows,), "history rows differ")
                check(rows >= history_rows, "history rows disappeared")
                history_rows = rows
            if running:
                check(status in ("running", "completed"), f"status {status} during the run")
            if running and len(names) >= 10 and not held:
                # Keep the file open for 1.5 s once: the writer must wait for the reader (and
                # say so in JOB.msg), not fail or write under it.
                held = True
                time.sleep(1.5)
        counts_seen.append(len(names))
        opens += 1
        if held and history_csv is None and process.poll() is None:
            # xpl's own reader retries an open refused while the run writes (h5_reader.cpp).
            history_csv = subprocess.run([xpl, "history", str(h5_path)], capture_output=True,
                                         text=True, timeout=30)
        time.sleep(0.01)
    code = process.wait(timeout=60)
    check(code == 0, f"run: exit {code}: {process.communicate()}")
    with h5py.File(h5_path, "r") as f:
        check(f.attrs["status"] == "completed", f"final status {f.attrs['status']}")
        total = len(f["frames"])
        # Whatever a reader read during the run is what the finished file holds, bit for bit.
        for name, (t, u, s) in frames_read.items():
            frame = f["frames"][name]
            check(frame.attrs["time"] == t and np.array_equal(frame["U"][()], u)
                  and np.array_equal(frame["S"][()], s), f"frame {name} read during the run")
    check(xdmf_seen > 0, "JOB.xdmf listed no frame while the run wrote them")
    listed = set(re.findall(r"/frames/(\d{6})/", (results / "block.xdmf").read_text()))
    check(len(listed) == total, f"the final JOB.xdmf lists {len(listed)} of {total} frames")
    distinct = sorted(set(counts_seen))
    check(len(distinct) >= 2, f"the reader saw only the frame counts {distinct}")
    check(held, "the run ended before the reader could hold the file")
    check(0 < len(frames_read) <= total, f"read {len(frames_read)} of {total} frames")
    check(history_csv is not None, "xpl history was not run during the run")
    check(history_csv.returncode == 0, f"xpl history during the run: {history_csv.stderr}")
    csv_lines = history_csv.stdout.splitlines()
    check(csv_lines[0].startswith("time,") and len(csv_lines) > 1,
          f"xpl history during the run: {csv_lines[:2]}")
    msg = (results / "block.msg").read_text()
    check("waited" in msg and "to close" in msg, "JOB.msg does not say the run waited for a reader")
    print(f"live: {opens} reads during the run ({counts['busy']} opens refused while xpl wrote, "
          f"retried), {len(distinct)} distinct frame counts up to {distinct[-1]} of {total}; "
          f"{len(frames_read)} frames read during the run equal the final file's; the run "
          f"waited for a reader that held the file 1.5 s; JOB.xdmf listed up to {xdmf_seen} "
          f"frames mid-run, all of them in the .h5; xpl history read "
          f"{len(csv_lines) - 1} rows mid-run; final status completed")


PV_SCRIPT = """
import sys
from paraview.simple import *
from paraview import servermanager
# The reader docs/user/reading-results.md names: ParaView's legacy "XDMF Reader" (XDMF 2) reads a Tensor6 as
# xx xy xz yy yz zz and expands it to 9 components, which puts S13 under ZZ.
reader = Xdmf3ReaderS(FileName=sys.argv[1])
reader.UpdatePipeline(reader.TimestepValues[-1])
info = reader.GetCellDataInformation().GetArray("S")
print("components", repr([info.GetComponentName(c) for c in range(info.GetNumberOfComponents())]))
data = servermanager.Fetch(reader)
while not data.IsA("vtkDataSet"):
    data = data.GetPiece(0) if data.IsA("vtkMultiPieceDataSet") else data.GetBlock(0)
cells, points = data.GetCellData(), data.GetPointData()
s = cells.GetArray("S")
print("values", repr([s.GetComponent(0, c) for c in range(s.GetNumberOfComponents())]))
print("element_id", cells.GetArray("element_id").GetValue(0))
print("node_id", points.GetArray("node_id").GetValue(0))
# Sets are 0/1 arrays (issue 34): no Set blocks, the reader lists them with the fields.
print("sets", repr([n for n in reader.PointData.keys() + reader.CellData.keys()
                    if n.startswith(("NSET_", "ELSET_"))]))
print("blocks", data.GetNumberOfCells(), servermanager.Fetch(reader).GetNumberOfBlocks()
      if servermanager.Fetch(reader).IsA("vtkMultiBlockDataSet") else 1)
sys.stdout.flush()
import os
os._exit(0)  # pvpython 5.11 may abort in its teardown
"""


def case_paraview(xpl, repo, out):
    pvpython = shutil.which("pvpython")
    if pvpython is None:
        print("pvpython not installed: skipped")
        sys.exit(SKIP)
    deck = shear_job(out)
    results = out / "results"
    run(xpl, deck, results)
    with h5py.File(results / "shear.h5", "r") as f:
        s13 = f["frames"][sorted(f["frames"])[-1]]["S"][0, 4]
    script = out / "pv_shear.py"
    script.write_text(PV_SCRIPT)
    command = [pvpython, "--force-offscreen-rendering", str(script), str(results / "shear.xdmf")]
    result = subprocess.run(command, capture_output=True, text=True, timeout=120)
    check(result.returncode == 0, f"pvpython: {result.returncode}: {result.stderr[-2000:]}")
    lines = dict(line.split(" ", 1) for line in result.stdout.splitlines() if " " in line)
    components = ast.literal_eval(lines["components"])
    values = ast.literal_eval(lines["values"])
    check(components == ["XX", "YY", "ZZ", "XY", "YZ", "XZ"], f"ParaView components {components}")
    check(values[5] == s13 and values[4] == 0.0, f"ParaView S {values}, S13 {s13}")
    check(int(float(lines["element_id"])) == 17, "ParaView element_id")
    check(int(float(lines["node_id"])) == 1, "ParaView node_id")
    sets = ast.literal_eval(lines["sets"])
    check(sorted(sets) == ["ELSET_CUBE", "NSET_BOTTOM", "NSET_CORNER", "NSET_TOP"],
          f"sets {sets}")
    cells, blocks = (int(v) for v in lines["blocks"].split())
    check(cells == 1 and blocks == 1, f"ParaView reads {blocks} block(s), {cells} cell(s): "
          "set blocks beside the mesh")
    print(f"paraview: S13 = {s13:.6g} under {components[5]}; node_id, element_id and sets "
          f"{sets} present")


def pvpython_picture(command):
    """Runs a pvpython picture command (a list); retries once when the virtual X server was not
    ready (ParaView 5.11 then aborts with "bad X server connection")."""
    for attempt in range(2):
        result = subprocess.run(command, capture_output=True, text=True, timeout=180)
        if "bad X server connection" not in result.stderr or attempt == 1:
            return result
        time.sleep(1.0)
    return result


def case_screenshot(xpl, repo, out):
    """ParaView as docs/user/reading-results.md says to open a result (issue 34): Open, Apply, Last Frame, Warp By
    Vector, Apply, with nothing else chosen, shows the deformed model in colour: the default
    colouring is MISES_MAX (not node_id, not grey set blocks), the picture is mostly coloured,
    and the model is drawn deformed."""
    pvpython, xvfb = shutil.which("pvpython"), shutil.which("xvfb-run")
    if pvpython is None or xvfb is None:
        print("pvpython or xvfb-run not installed: skipped")
        sys.exit(SKIP)
    import matplotlib.image

    results = out / "results"
    run(xpl, repo / "examples/contact/tube_crush/tube_crush.inp", results)
    png = out / "tube_crush_mises.png"
    command = [xvfb, "-a", pvpython, str(repo / "scripts/paraview_screenshot.py"),
               str(results / "tube_crush.xdmf"), str(png), "--sets"]
    result = pvpython_picture(command)
    check(result.returncode == 0 and png.exists(),
          f"screenshot: {result.returncode}: {result.stderr[-2000:]}")
    lines = dict(line.split(" ", 1) for line in result.stdout.splitlines() if " " in line)
    check(lines.get("colour") == "CELLS MISES_MAX",
          f"ParaView colours the opened file by {lines.get('colour')!r}, not MISES_MAX")
    bounds = {line.split()[1]: [float(v) for v in line.split()[2:]]
              for line in result.stdout.splitlines() if line.startswith("bounds ")}
    top_before, top_after = bounds["undeformed"][5], bounds["deformed"][5]
    with h5py.File(results / "tube_crush.h5", "r") as f:
        last = f["frames"][sorted(f["frames"])[-1]]
        mises_max = last["MISES_MAX"][:]
        peak = int(np.nanargmax(mises_max))
        element_id = int(f["mesh/element_ids"][peak])
        sets = sorted(["NSET_" + n for n in f["mesh/node_sets"]]
                      + ["ELSET_" + n for n in f["mesh/element_sets"]])
        coordinates = f["mesh/coordinates"][()]
        moved = coordinates + last["U"][()]
    check(np.isclose(top_before, coordinates[:, 2].max()) and np.isclose(top_after, moved[:, 2].max()),
          f"picture's top z {top_before} -> {top_after}; .h5 {coordinates[:, 2].max()} -> "
          f"{moved[:, 2].max()}")
    check(top_before - top_after > 0.01, f"the picture is not deformed: top {top_before} -> {top_after}")
    field, value, _, shown_id = lines["peak"].split()
    check(field == "MISES_MAX" and float(value) == mises_max[peak],
          f"picture's peak {lines['peak']}, .h5 {mises_max[peak]!r}")
    check(int(shown_id) == element_id, f"picture's peak element {shown_id}, .h5 {element_id}")
    check(sorted(lines["sets"].split()) == sets, f"picture's sets {lines['sets']}, .h5 {sets}")
    check(png.stat().st_size < 300_000, f"picture of {png.stat().st_size} bytes")
    image = matplotlib.image.imread(png)[:, :, :3]
    height, width = image.shape[:2]
    # The tube stands in the middle of the left half, between the translucent grey plates (at
    # the top and bottom of the view) on a white background. Coloured by MISES_MAX with the Jet
    # map its cells are saturated colours, warm (red to yellow) and cold (blue); grey shells
    # (set blocks drawn over them, or no colouring) have neither.
    view = image[int(0.30 * height) : int(0.75 * height), int(0.16 * width) : int(0.33 * width)]
    red, green, blue = view[:, :, 0], view[:, :, 1], view[:, :, 2]
    saturation = view.max(axis=2) - view.min(axis=2)
    model = view.min(axis=2) < 0.95  # not the white background
    coloured = float(np.mean(saturation[model] > 0.3))
    warm = float(np.mean((red > 0.6) & (blue < 0.35) & (red - blue > 0.4)))
    cold = float(np.mean((blue > 0.5) & (red < 0.35) & (blue - red > 0.4)))
    # (cell edges are drawn dark grey: a quarter of the pixels)
    check(model.mean() > 0.5 and coloured > 0.6 and warm > 0.01 and cold > 0.1,
          f"model part of the picture: {coloured:.1%} of its pixels coloured, {warm:.1%} warm, "
          f"{cold:.1%} cold")
    print(f"screenshot: {width}x{height}, {png.stat().st_size} bytes; opened as documented, "
          f"ParaView colours by {lines['colour']}; {coloured:.1%} of the model's pixels coloured "
          f"({warm:.1%} warm, {cold:.1%} cold of the view); top {top_before:.4f} -> "
          f"{top_after:.4f} m deformed; peak MISES_MAX {mises_max[peak]:.4g} Pa in element "
          f"{element_id}")


def main():
    if len(sys.argv) != 5:
        sys.exit(__doc__)
    case, xpl = sys.argv[1], sys.argv[2]
    repo, out = pathlib.Path(sys.argv[3]), pathlib.Path(sys.argv[4])
    shutil.rmtree(out, ignore_errors=True)
    out.mkdir(parents=True)
    cases = {"shear": case_shear, "plate": case_plate, "live": case_live,
             "paraview": case_paraview, "screenshot": case_screenshot}
    if case not in cases:
        sys.exit(__doc__)
    cases[case](xpl, repo, out)


if __name__ == "__main__":
    main()
