"""Off-screen ParaView picture of an xpl result: shells coloured by MISES_MAX, plus the sets.

Run with ParaView's Python (5.11), under a virtual X server when there is no display:

    xvfb-run -a pvpython scripts/paraview_screenshot.py JOB.xdmf OUT.png [--frame N]

Left view: the frame (default: the last) read with the Xdmf3 Reader S, warped by U (scale 1),
the S4R shells coloured by the cell field MISES_MAX (largest Mises stress through the
thickness), the other elements (rigid plates) translucent grey; the title names the
element id of the peak cell (element_id cell data). Right view: the node and element sets
the way ParaView's readers expose them, drawn on the undeformed mesh, one colour per set, and
listed with their sizes.

Why it is done this way (ParaView 5.11 as packaged by Debian, under xvfb):
* The Xdmf3 reader turns every XDMF `Set` on by default and adds it as a block without any
  cell data; those blocks lie on top of the mesh and are drawn in the solid colour, which is
  what made an earlier attempt show grey surfaces under a correct scalar bar. Here its `Sets`
  list is emptied, so the only block is the mesh with its fields.
* The sets are read with the legacy XDMF Reader, whose `SetStatus` lists each set once and
  names its blocks after the sets. The Xdmf3 reader lists every set once per frame
  (`NAME`, `NAME[1]` ... `NAME[N]`), because each frame of JOB.xdmf repeats the `Set`
  elements; the count of that list is printed in the picture too.
"""
import argparse
import os
import re
import sys

from paraview import servermanager
from paraview.simple import (
    ColorBy,
    CreateLayout,
    CreateRenderView,
    ExtractBlock,
    GetColorTransferFunction,
    GetScalarBar,
    MergeBlocks,
    Render,
    SaveScreenshot,
    Show,
    Text,
    Threshold,
    WarpByVector,
    XDMFReader,
    Xdmf3ReaderS,
)

# One colour per set in the right view (RGB, 0..1), cycled.
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

# What the shell fields mean, for the title.
MEANING = {
    "MISES_MAX": " (largest Mises through the thickness)",
    "MISES_SPOS": " (Mises at the top surface, SPOS)",
    "MISES_SNEG": " (Mises at the bottom surface, SNEG)",
    "MISES": " (Mises at the middle section point)",
}


def parse_args(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("xdmf", help="JOB.xdmf written by xpl run")
    parser.add_argument("png", help="picture to write")
    parser.add_argument("--frame", type=int, default=-1,
                        help="frame index in JOB.xdmf (default -1: the last)")
    parser.add_argument("--field", default="MISES_MAX", help="cell field to colour the shells by")
    parser.add_argument("--size", default="1600x800", help="picture size WIDTHxHEIGHT in pixels")
    return parser.parse_args(argv)


def blocks(data):
    """(name, block) of every leaf of a fetched composite data set, in order."""
    out = []
    it = data.NewIterator()
    it.InitTraversal()
    while not it.IsDoneWithTraversal():
        meta = it.GetCurrentMetaData()
        name = meta.Get(data.NAME()) if meta is not None and meta.Has(data.NAME()) else ""
        out.append((name, it.GetCurrentDataObject()))
        it.GoToNextItem()
    return out


def cell_array(block, name):
    array = block.GetCellData().GetArray(name)
    if array is None:
        sys.exit(f"paraview_screenshot.py: the reader gives no cell array {name}")
    return [array.GetValue(i) for i in range(array.GetNumberOfTuples())]


def stress_view(xdmf, frame, field, size):
    reader = Xdmf3ReaderS(registrationName="xdmf3", FileName=[xdmf])
    reader.UpdatePipelineInformation()
    times = list(reader.TimestepValues)
    time = times[frame]
    set_entries = list(reader.Sets)
    reader.Sets = []  # set blocks carry no fields and would be drawn grey over the mesh
    if field not in reader.CellArrays:
        sys.exit(f"paraview_screenshot.py: {xdmf} has no cell field {field}")
    reader.UpdatePipeline(time)

    mesh = MergeBlocks(registrationName="mesh", Input=reader)
    warped = WarpByVector(registrationName="warped", Input=mesh)
    warped.Vectors = ["POINTS", "U"]
    warped.ScaleFactor = 1.0
    tube = Threshold(registrationName="shells", Input=warped)
    # Shells are the cells with a finite local-axes stress (S_LOCAL is NaN on solids).
    tube.Scalars = ["CELLS", "S_LOCAL"]
    tube.LowerThreshold = -1e300
    tube.UpperThreshold = 1e300
    rest = Threshold(registrationName="solids", Input=warped)
    rest.Scalars = ["CELLS", "S_LOCAL"]
    rest.LowerThreshold = -1e300
    rest.UpperThreshold = 1e300
    rest.Invert = 1
    for source in (tube, rest):
        source.UpdatePipeline(time)

    # Peak of the field over the shells, and the deck id of its element.
    shells = servermanager.Fetch(tube)
    values = cell_array(shells, field)
    ids = cell_array(shells, "element_id")
    peak = max(range(len(values)), key=lambda i: values[i])

    view = CreateRenderView()
    view.ViewSize = size
    view.ViewTime = time
    view.OrientationAxesVisibility = 1
    view.Background = [1.0, 1.0, 1.0]
    view.UseColorPaletteForBackground = 0

    shown = Show(tube, view)
    shown.SetRepresentationType("Surface With Edges")
    shown.EdgeColor = [0.25, 0.25, 0.25]
    ColorBy(shown, ("CELLS", field))
    lut = GetColorTransferFunction(field)
    lut.ApplyPreset("Jet", True)
    lut.RescaleTransferFunction(0.0, values[peak])
    lut.AutomaticRescaleRangeMode = "Never"
    shown.SetScalarBarVisibility(view, True)
    bar = GetScalarBar(lut, view)
    bar.Title = f"{field}, Pa (cell data)"
    bar.ComponentTitle = ""
    bar.RangeLabelFormat = "%-#6.2e"
    bar.TitleColor = bar.LabelColor = [0.0, 0.0, 0.0]
    bar.HorizontalTitle = 1
    bar.TitleFontSize = 15
    bar.LabelFontSize = 14
    bar.WindowLocation = "Any Location"
    bar.Position = [0.80, 0.12]
    bar.ScalarBarLength = 0.6

    plates = Show(rest, view)
    plates.SetRepresentationType("Surface")
    plates.ColorArrayName = ["POINTS", ""]
    plates.AmbientColor = plates.DiffuseColor = [0.7, 0.7, 0.7]
    plates.Opacity = 0.3

    name = os.path.splitext(os.path.basename(xdmf))[0]
    title = Text(registrationName="title")
    title.Text = (
        f"{name}: frame {frame % len(times)} of {len(times) - 1}, t = {time * 1e3:.3f} ms, "
        f"warped by U (x1)\n"
        f"S4R shells coloured by {field}{MEANING.get(field, '')};\n"
        f"peak {values[peak]:.3e} Pa in element_id {int(ids[peak])}; rigid plates translucent\n"
        f"reader: Xdmf3ReaderS, Sets off ({len(set_entries)} set entries listed)"
    )
    text = Show(title, view)
    text.WindowLocation = "Upper Left Corner"
    text.Justification = "Left"
    text.FontSize = 15
    text.Color = [0.0, 0.0, 0.0]

    view.CameraPosition = [0.11, -0.13, 0.085]
    view.CameraFocalPoint = [0.0, 0.0, 0.022]
    view.CameraViewUp = [0.0, 0.0, 1.0]
    view.ResetCamera(False)
    view.CameraParallelScale = 0.03
    print(f"peak {field} {values[peak]!r} element_id {int(ids[peak])}")
    return view, set_entries


def set_view(xdmf, set_entries, size):
    reader = XDMFReader(registrationName="xdmf_legacy", FileNames=[xdmf])
    reader.UpdatePipelineInformation()
    names = list(reader.SetStatus)
    reader.SetStatus = names
    reader.PointArrayStatus = []
    reader.CellArrayStatus = []
    reader.UpdatePipeline(reader.TimestepValues[0])
    data = servermanager.Fetch(reader)
    found = {name: block for name, block in blocks(data) if name in names}

    view = CreateRenderView()
    view.ViewSize = size
    view.OrientationAxesVisibility = 1
    view.Background = [1.0, 1.0, 1.0]
    view.UseColorPaletteForBackground = 0

    node_sets = sorted((n for n in names if n.startswith("NSET_") and n in found),
                       key=lambda n: -found[n].GetNumberOfPoints())
    sizes = {n: max(9 - 3 * rank, 4) for rank, n in enumerate(node_sets)}
    lines = ["Sets in ParaView (XDMF Reader, SetStatus), frame 0, undeformed:"]
    for index, name in enumerate(names):
        block = found.get(name)
        colour = SET_COLOURS[index % len(SET_COLOURS)]
        part = ExtractBlock(registrationName=name, Input=reader)
        part.Selectors = [f"/Root/{name}"]
        shown = Show(part, view)
        shown.ColorArrayName = ["POINTS", ""]
        shown.AmbientColor = shown.DiffuseColor = list(colour)
        if name.startswith("NSET_"):
            count = block.GetNumberOfPoints() if block is not None else 0
            shown.SetRepresentationType("Points")
            # Larger sets get larger points, so that a subset drawn over them leaves a ring.
            shown.PointSize = 11 if count < 5 else sizes.get(name, 5)
            shown.RenderPointsAsSpheres = 1
            lines.append(f"  {name}: {count} node(s)")
        else:
            count = block.GetNumberOfCells() if block is not None else 0
            shown.SetRepresentationType("Surface")
            shown.Opacity = 0.35 if name != "ELSET_TUBE" else 0.6
            lines.append(f"  {name}: {count} element(s)")
        label = Text(registrationName=f"label_{name}")
        label.Text = lines[-1].strip()
        label_shown = Show(label, view)
        label_shown.WindowLocation = "Any Location"
        label_shown.Position = [0.02, 0.78 - 0.045 * index]
        label_shown.FontSize = 15
        label_shown.Bold = 1
        label_shown.Color = list(colour)
    distinct = sorted({re.sub(r"\[\d+\]$", "", entry) for entry in set_entries})
    same = "these" if distinct == sorted(names) else "other"
    header = Text(registrationName="set_list")
    header.Text = (
        lines[0]
        + f"\nXdmf3ReaderS Sets: {len(set_entries)} entries, {same} {len(distinct)} names"
        + " once per frame (NAME, NAME[1], ...)"
    )
    head = Show(header, view)
    head.WindowLocation = "Upper Left Corner"
    head.Justification = "Left"
    head.FontSize = 15
    head.Color = [0.0, 0.0, 0.0]

    view.CameraPosition = [0.11, -0.13, 0.10]
    view.CameraFocalPoint = [0.0, 0.0, 0.03]
    view.CameraViewUp = [0.0, 0.0, 1.0]
    view.ResetCamera(False)
    view.GetActiveCamera().Dolly(0.9)
    return view, names


def main(argv):
    args = parse_args(argv)
    width, height = (int(v) for v in args.size.split("x"))
    half = [width // 2, height]
    xdmf = os.path.abspath(args.xdmf)
    left, set_entries = stress_view(xdmf, args.frame, args.field, half)
    right, names = set_view(xdmf, set_entries, half)
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


if __name__ == "__main__":
    main(sys.argv[1:])
