"""Render one field of a tmfdem output series with ParaView, to a PNG.

    xvfb-run -a pvbatch scripts/render_paraview.py OUTPUT/solution.pvd out.png
        [--field T] [--time 0.01] [--size 1200x900] [--cmap "Inferno (matplotlib)"]
        [--view-from X,Y,Z] [--view-up X,Y,Z] [--warp FACTOR]
        [--crop X0,X1,Y0,Y1,Z0,Z1]

Opens the .pvd (or a .vtu / .pvtu) with ParaView's own readers, goes to the
output time nearest --time (default: the last), colours by --field (point
or cell data; a vector by its magnitude; default: T, else the first array)
and saves the picture with a colour bar: seen along z as a 2D picture, or
in perspective from the direction --view-from (3D outputs), the points
moved by FACTOR times `displacement` with --warp (a discrete layer's
exploded elements then show their cracks opened), with --crop only the cells
that lie wholly inside a box (e.g. a container's walls left out to show what
it holds). pvbatch renders off screen through
an X display: on a machine without one (a server, CI), run it under
`xvfb-run -a` (Debian packages paraview, python3-paraview, xvfb).
Prints the time, the field's range there and the number of cells (and of
those shown, with --crop).
"""
import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import paraview_path  # noqa: E402,F401  (finds python3-paraview's package)
from paraview.simple import (ColorBy, CreateView, ExtractCellsByRegion,
                             GetColorTransferFunction, GetScalarBar, OpenDataFile,
                             SaveScreenshot, Show, UpdatePipeline, WarpByVector)


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("input", help=".pvd, .pvtu or .vtu file")
    ap.add_argument("output", help="PNG file to write")
    ap.add_argument("--field", default=None, help="array to colour by (default: T, else the first)")
    ap.add_argument("--time", type=float, default=None, help="output time [s] (default: the last)")
    ap.add_argument("--size", default="1200x900", help="picture size WIDTHxHEIGHT in pixels")
    ap.add_argument("--cmap", default="Inferno (matplotlib)", help="ParaView colour map preset")
    ap.add_argument("--view-from", default=None,
                    help="X,Y,Z: look at the output from this direction in perspective "
                         "(default: along z, as a 2D picture)")
    ap.add_argument("--view-up", default=None,
                    help="X,Y,Z: the picture's up direction with --view-from (default: y, or z "
                         "when looking along y)")
    ap.add_argument("--crop", default=None,
                    help="X0,X1,Y0,Y1,Z0,Z1: show only the cells wholly inside this box")
    ap.add_argument("--warp", type=float, default=None,
                    help="move the points by this factor times the point array 'displacement'")
    args = ap.parse_args(argv)

    reader = OpenDataFile(args.input)
    if reader is None:
        sys.exit(f"{args.input}: ParaView has no reader for it")
    times = list(reader.TimestepValues) if reader.TimestepValues else []
    time = 0.0
    if times:
        time = times[-1] if args.time is None else min(times, key=lambda t: abs(t - args.time))
    UpdatePipeline(time=time, proxy=reader)

    point_names, cell_names = list(reader.PointData.keys()), list(reader.CellData.keys())
    field = args.field or ("T" if "T" in point_names + cell_names else
                           (point_names + cell_names + [None])[0])
    if field is None or field not in point_names + cell_names:
        sys.exit(f"{args.input}: no field '{field}' (have: {', '.join(point_names + cell_names)})")
    association = "POINTS" if field in point_names else "CELLS"
    array = (reader.PointData if association == "POINTS" else reader.CellData)[field]
    component = -1 if array.GetNumberOfComponents() > 1 else 0
    low, high = array.GetRange(component)
    if not low <= high:  # no finite value (a crack file without cracks)
        low, high = 0.0, 1.0

    width, height = (int(v) for v in args.size.lower().split("x"))
    view = CreateView("RenderView")
    view.ViewSize = [width, height]
    view.ViewTime = time
    view.OrientationAxesVisibility = 0
    view.Background = [1, 1, 1]
    try:  # ParaView >= 5.10: the palette's background would override it
        view.UseColorPaletteForBackground = 0
    except AttributeError:
        pass
    shown = reader
    if args.warp is not None:
        if "displacement" not in point_names:
            sys.exit(f"{args.input}: --warp needs the point array 'displacement'")
        shown = WarpByVector(Input=reader, Vectors=["POINTS", "displacement"],
                             ScaleFactor=args.warp)
    if args.crop is not None:
        bounds = [float(v) for v in args.crop.split(",")]
        if len(bounds) != 6 or not all(bounds[2 * i] < bounds[2 * i + 1] for i in range(3)):
            sys.exit(f"--crop {args.crop}: give X0,X1,Y0,Y1,Z0,Z1 with X0 < X1, Y0 < Y1, Z0 < Z1")
        shown = ExtractCellsByRegion(Input=shown, IntersectWith="Box")
        shown.IntersectWith.Position = [bounds[0], bounds[2], bounds[4]]
        shown.IntersectWith.Length = [bounds[1] - bounds[0], bounds[3] - bounds[2],
                                      bounds[5] - bounds[4]]
        shown.Extractintersected = 0  # cells wholly inside
    display = Show(shown, view)
    if component == -1:
        ColorBy(display, (association, field, "Magnitude"))
    else:
        ColorBy(display, (association, field))
    lut = GetColorTransferFunction(field)
    lut.ApplyPreset(args.cmap, True)
    lut.RescaleTransferFunction(low, high)
    display.SetScalarBarVisibility(view, True)
    bar = GetScalarBar(lut, view)
    bar.TitleColor = bar.LabelColor = [0, 0, 0]
    if args.view_from is None:
        view.InteractionMode = "2D"
        view.ResetCamera()
    else:
        direction = [float(v) for v in args.view_from.split(",")]
        if len(direction) != 3 or not any(direction):
            sys.exit(f"--view-from {args.view_from}: give three numbers, not all zero")
        view.CameraPosition = direction
        view.CameraFocalPoint = [0.0, 0.0, 0.0]
        if args.view_up is not None:
            up = [float(v) for v in args.view_up.split(",")]
            if len(up) != 3 or not any(up):
                sys.exit(f"--view-up {args.view_up}: give three numbers, not all zero")
            view.CameraViewUp = up
        else:
            view.CameraViewUp = [0.0, 1.0, 0.0] if abs(direction[1]) < max(
                abs(direction[0]), abs(direction[2])) else [0.0, 0.0, 1.0]
        view.ResetCamera()
    SaveScreenshot(args.output, view, ImageResolution=[width, height])
    n_cells = reader.GetDataInformation().GetNumberOfCells()
    n_shown = shown.GetDataInformation().GetNumberOfCells()
    print(f"wrote {args.output}: {field} ({association.lower()}) at t = {time:.6g} s in "
          f"[{low:.6g}, {high:.6g}], {n_cells} cells" +
          (f", {n_shown} of them shown (--crop)" if args.crop is not None else ""))


if __name__ == "__main__":
    main(sys.argv[1:])
