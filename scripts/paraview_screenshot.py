"""Off-screen ParaView picture of an xpl result, made the way docs/user/reading-results.md tells a user to look.

Run with ParaView's Python (5.11), under a virtual X server when there is no display:

    xvfb-run -a pvpython scripts/paraview_screenshot.py JOB.xdmf OUT.png [--frame N]
        [--field NAME] [--sets] [--size WxH] [--title TEXT] [--zoom Z]

The view is what ParaView shows after *File > Open* JOB.xdmf (the Xdmf3 Reader S), *Apply*,
*Last Frame* and *Filters > Warp By Vector* (U, scale 1), *Apply*: the deformed model coloured
by the field the file makes the default (MISES_MAX on shell models, MISES on solids), or by
`--field`. Shells and solids together: the solids are drawn translucent grey (rigid plates
beside a crushed tube). The colour bar is labelled with the field's unit from JOB.h5 (MPa for
a deck that states `** xpl: UNITS=MM-T-S`), and the title names the element of the peak.
`--sets` adds a right-hand view of the deck's node and element sets, read from their 0/1
arrays (NSET_NAME, ELSET_NAME) on the undeformed mesh, one colour per set.

Printed for tests: `colour ASSOCIATION FIELD` (the colouring ParaView chose when the file was
shown), `bounds undeformed X0 X1 Y0 Y1 Z0 Z1` and `bounds deformed ...` (the reader's and the
warped model's), `peak FIELD VALUE element_id ID`, `sets NAME ...` (with --sets), `wrote
OUT.png`.

ParaView 5.11 as packaged by Debian has no EGL or OSMesa build: off-screen rendering without an
X server (`--force-offscreen-rendering`) crashes in XSync, hence xvfb-run. pvpython may abort
while it tears down after the picture is written; the script ends with os._exit(0).
"""
import argparse
import math
import os
import sys

import h5py
import paraview.simple
from paraview import servermanager
from paraview.simple import (
    ColorBy,
    CreateLayout,
    CreateRenderView,
    ExtractSelection,
    GetAnimationScene,
    GetColorTransferFunction,
    GetScalarBar,
    Hide,
    MergeBlocks,
    OpenDataFile,
    Render,
    SaveScreenshot,
    SelectionQuerySource,
    Show,
    Text,
    Threshold,
    WarpByVector,
)

# One colour per set in the sets view (RGB, 0..1), cycled.
SET_COLOURS = [
    (0.89, 0.10, 0.11),
    (0.22, 0.49, 0.72),
    (0.30, 0.69, 0.29),
    (0.60, 0.31, 0.64),
    (1.00, 0.50, 0.00),
    (0.65, 0.34, 0.16),
    (0.97, 0.51, 0.75),
    (0.40, 0.40, 0.40),
]

# What the fields mean, for the title.
MEANING = {
    "MISES_MAX": "largest Mises stress through the thickness",
    "MISES_SPOS": "Mises stress at the top surface (SPOS)",
    "MISES_SNEG": "Mises stress at the bottom surface (SNEG)",
    "MISES": "Mises stress",
    "PEEQ": "equivalent plastic strain",
}


def parse_args(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("xdmf", help="JOB.xdmf written by xpl run")
    parser.add_argument("png", help="picture to write")
    parser.add_argument("--frame", type=int, default=-1,
                        help="frame index in JOB.xdmf (default -1: the last)")
    parser.add_argument("--field", default="",
                        help="cell field to colour by (default: the file's default colouring)")
    parser.add_argument("--sets", action="store_true", help="add a view of the node and element sets")
    parser.add_argument("--size", default="", help="picture size WIDTHxHEIGHT in pixels "
                        "(default 900x700, 1600x800 with --sets)")
    parser.add_argument("--title", default="", help="first line of the title (default: the job)")
    parser.add_argument("--zoom", type=float, default=1.0, help="camera zoom of the model view")
    return parser.parse_args(argv)


def first_block(data):
    """The first vtkDataSet of a fetched (composite) data object."""
    while not data.IsA("vtkDataSet"):
        data = data.GetPiece(0) if data.IsA("vtkMultiPieceDataSet") else data.GetBlock(0)
    return data


def cell_values(source, name):
    data = first_block(servermanager.Fetch(source))
    array = data.GetCellData().GetArray(name)
    if array is None:
        sys.exit(f"paraview_screenshot.py: the reader gives no cell array {name}")
    return [array.GetValue(i) for i in range(array.GetNumberOfTuples())]


def h5_of(xdmf):
    """JOB.h5 beside JOB.xdmf."""
    return os.path.join(os.path.dirname(xdmf), os.path.splitext(os.path.basename(xdmf))[0] + ".h5")


def units_of(xdmf, field, frame_index):
    """(unit of `field`, unit of time) from JOB.h5 ('?' where it does not say)."""
    with h5py.File(h5_of(xdmf), "r") as f:
        frames = sorted(f["frames"])
        frame = f["frames"][frames[frame_index]]
        unit = frame[field].attrs.get("units", "?") if field in frame else "?"
        time_unit = "?"
        if "history" in f:
            for step in f["history"].values():
                time_unit = step["time"].attrs.get("units", "?")
                break
    text = lambda v: v.decode() if isinstance(v, bytes) else str(v)
    return text(unit), text(time_unit)


def white_view(size):
    view = CreateRenderView()
    view.ViewSize = size
    view.OrientationAxesVisibility = 1
    view.Background = [1.0, 1.0, 1.0]
    view.UseColorPaletteForBackground = 0
    return view


def aim(view, bounds, direction=(0.55, -0.75, 0.42), zoom=1.0):
    """Looks at the middle of `bounds` from `direction`, z up, fitted and zoomed."""
    centre = [(bounds[2 * i] + bounds[2 * i + 1]) / 2 for i in range(3)]
    size = max(bounds[1] - bounds[0], bounds[3] - bounds[2], bounds[5] - bounds[4])
    norm = math.sqrt(sum(d * d for d in direction))
    view.CameraFocalPoint = centre
    view.CameraPosition = [c + 3 * size * d / norm for c, d in zip(centre, direction)]
    view.CameraViewUp = [0.0, 0.0, 1.0]
    view.ResetCamera(False)
    view.GetActiveCamera().Dolly(zoom)


def model_view(xdmf, frame, field, size, title, zoom):
    view = white_view(size)
    # File > Open (ParaView picks the Xdmf3 Reader S for .xdmf), Apply.
    reader = OpenDataFile(xdmf)
    shown = Show(reader, view)
    default = list(shown.ColorArrayName)
    times = list(reader.TimestepValues)
    time = times[frame]
    view.ViewTime = time
    GetAnimationScene().AnimationTime = time
    # Filters > Warp By Vector (U, the file's first vector, is its default), Apply.
    warped = WarpByVector(registrationName="warped", Input=reader)
    if list(warped.Vectors) != ["POINTS", "U"]:
        sys.exit(f"paraview_screenshot.py: Warp By Vector offers {list(warped.Vectors)}, not U")
    warped.UpdatePipeline(time)
    Hide(reader, view)
    field = field or default[1]
    if not field:
        sys.exit("paraview_screenshot.py: the file sets no default colouring; give --field")

    mesh = MergeBlocks(registrationName="mesh", Input=warped)
    mesh.UpdatePipeline(time)
    shells, solids = mesh, None
    if "S_LOCAL" in mesh.CellData.keys():
        # Shell models: shells are the cells with a finite local-axes stress (NaN on solids).
        shells = Threshold(registrationName="shells", Input=mesh, Scalars=["CELLS", "S_LOCAL"],
                           LowerThreshold=-1e300, UpperThreshold=1e300)
        solids = Threshold(registrationName="solids", Input=mesh, Scalars=["CELLS", "S_LOCAL"],
                           LowerThreshold=-1e300, UpperThreshold=1e300, Invert=1)
        solids.UpdatePipeline(time)
        if solids.GetDataInformation().GetNumberOfCells() == 0:
            solids = None
    shells.UpdatePipeline(time)
    values = cell_values(shells, field)
    ids = cell_values(shells, "element_id")
    finite = [i for i in range(len(values)) if values[i] == values[i]]
    peak = max(finite, key=lambda i: values[i])

    shown = Show(shells, view)
    shown.SetRepresentationType("Surface With Edges")
    shown.EdgeColor = [0.25, 0.25, 0.25]
    ColorBy(shown, ("CELLS", field))
    lut = GetColorTransferFunction(field)
    lut.ApplyPreset("Jet", True)
    lut.RescaleTransferFunction(min(values[i] for i in finite), values[peak])
    lut.AutomaticRescaleRangeMode = "Never"
    unit, time_unit = units_of(xdmf, field, frame)
    shown.SetScalarBarVisibility(view, True)
    bar = GetScalarBar(lut, view)
    bar.Title = f"{field}, {unit}" if unit else field
    bar.ComponentTitle = ""
    bar.RangeLabelFormat = "%-#6.3g"
    bar.TitleColor = bar.LabelColor = [0.0, 0.0, 0.0]
    bar.HorizontalTitle = 1
    bar.TitleFontSize = 16
    bar.LabelFontSize = 15
    bar.WindowLocation = "Any Location"
    bar.Position = [0.84, 0.10]
    bar.ScalarBarLength = 0.5
    if solids is not None:
        plates = Show(solids, view)
        plates.SetRepresentationType("Surface")
        plates.ColorArrayName = ["POINTS", ""]
        plates.AmbientColor = plates.DiffuseColor = [0.7, 0.7, 0.7]
        plates.Opacity = 0.3

    name = os.path.splitext(os.path.basename(xdmf))[0]
    label = Text(registrationName="title")
    label.Text = (
        f"{title or name}: frame {frame % len(times)} of {len(times) - 1}, "
        f"t = {time:.4g} {time_unit}, warped by U (x1)\n"
        f"coloured by {field}" + (f" ({MEANING[field]})" if field in MEANING else "") + "\n"
        f"peak {values[peak]:.4g}{' ' + unit if unit else ''} in element_id {int(ids[peak])}"
        + ("; solids translucent" if solids is not None else "")
    )
    text = Show(label, view)
    text.WindowLocation = "Upper Left Corner"
    text.Justification = "Left"
    text.FontSize = 15
    text.Color = [0.0, 0.0, 0.0]
    aim(view, warped.GetDataInformation().GetBounds(), zoom=zoom)
    print(f"colour {default[0]} {default[1]}")
    print("bounds undeformed " + " ".join(repr(v) for v in reader.GetDataInformation().GetBounds()))
    print("bounds deformed " + " ".join(repr(v) for v in warped.GetDataInformation().GetBounds()))
    print(f"peak {field} {values[peak]!r} element_id {int(ids[peak])}")
    return view, reader


def set_view(reader, size):
    """The node and element sets from their 0/1 arrays, on the undeformed first frame."""
    view = white_view(size)
    time = reader.TimestepValues[0]
    mesh = MergeBlocks(registrationName="undeformed", Input=reader)
    mesh.UpdatePipeline(time)
    info = mesh.GetDataInformation()
    points, cells = list(mesh.PointData.keys()), list(mesh.CellData.keys())
    names = sorted(n for n in points if n.startswith("NSET_")) + sorted(
        n for n in cells if n.startswith("ELSET_"))
    lines = ["Sets (0/1 arrays NSET_*, ELSET_*), frame 0, undeformed:"]
    node_sets = []
    for index, name in enumerate(names):
        colour = SET_COLOURS[index % len(SET_COLOURS)]
        if name.startswith("NSET_"):
            query = SelectionQuerySource(registrationName=f"query_{name}", ElementType="Point Data",
                                         QueryString=f"{name} == 1")
            part = ExtractSelection(registrationName=name, Input=mesh, Selection=query)
            part.UpdatePipeline(time)
            count = part.GetDataInformation().GetNumberOfPoints()
            node_sets.append((count, name))
            lines.append(f"  {name}: {count} node(s)")
        else:
            part = Threshold(registrationName=name, Input=mesh, Scalars=["CELLS", name],
                             LowerThreshold=0.5, UpperThreshold=1.5)
            part.UpdatePipeline(time)
            count = part.GetDataInformation().GetNumberOfCells()
            lines.append(f"  {name}: {count} element(s)")
        shown = Show(part, view)
        shown.ColorArrayName = ["POINTS", ""]
        shown.AmbientColor = shown.DiffuseColor = list(colour)
        if name.startswith("NSET_"):
            shown.SetRepresentationType("Points")
            rank = sorted(node_sets, reverse=True).index((count, name)) if count >= 5 else 0
            # Larger sets get larger points, so that a subset drawn over them leaves a ring.
            shown.PointSize = 11 if count < 5 else max(9 - 3 * rank, 4)
            shown.RenderPointsAsSpheres = 1
        else:
            shown.SetRepresentationType("Surface")
            shown.Opacity = 0.45
        label = Text(registrationName=f"label_{name}")
        label.Text = lines[-1].strip()
        label_shown = Show(label, view)
        label_shown.WindowLocation = "Any Location"
        label_shown.Position = [0.02, 0.90 - 0.04 * index]
        label_shown.FontSize = 15
        label_shown.Bold = 1
        label_shown.Color = list(colour)
    header = Text(registrationName="set_list")
    header.Text = lines[0]
    head = Show(header, view)
    head.WindowLocation = "Upper Left Corner"
    head.Justification = "Left"
    head.FontSize = 15
    head.Color = [0.0, 0.0, 0.0]
    aim(view, info.GetBounds(), zoom=0.75)
    return view, names


def main(argv):
    args = parse_args(argv)
    # The first Render would reset the camera, and with it the zoom chosen in aim().
    paraview.simple._DisableFirstRenderCameraReset()
    width, height = (int(v) for v in (args.size or ("1600x800" if args.sets else "900x700"))
                     .split("x"))
    xdmf = os.path.abspath(args.xdmf)
    if not args.sets:
        view, _ = model_view(xdmf, args.frame, args.field, [width, height], args.title, args.zoom)
        Render(view)
        SaveScreenshot(args.png, view, ImageResolution=[width, height], CompressionLevel="9")
    else:
        half = [width // 2, height]
        left, reader = model_view(xdmf, args.frame, args.field, half, args.title, args.zoom)
        right, names = set_view(reader, half)
        layout = CreateLayout("xpl")
        layout.SplitHorizontal(0, 0.5)
        layout.AssignView(1, left)
        layout.AssignView(2, right)
        layout.SetSize(width, height)
        Render(left)
        Render(right)
        SaveScreenshot(args.png, layout, SaveAllViews=1, ImageResolution=[width, height],
                       CompressionLevel="9")
        print(f"sets {' '.join(names)}")
    print(f"wrote {args.png}")
    sys.stdout.flush()
    os._exit(0)  # pvpython 5.11 may abort in its teardown after the picture is written


if __name__ == "__main__":
    main(sys.argv[1:])
