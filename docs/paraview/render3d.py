# Renders the last increment of a 3D asperity run of a quarter model (symmetry planes x = 0 and
# z = 0) with ParaView (pvpython) as a cut-away: the quarter mirrored into the other three
# quadrants and the modelled one left out, so the two symmetry planes show the stress inside.
#   xvfb-run -a pvpython docs/paraview/render3d.py out/shaft-fillet-3d docs/figures/paraview-shaft-fillet-3d.png
# Colours by von Mises stress from 0 to --max MPa (default 200), undeformed shape, the mesh's
# edges faint. The view looks obliquely at the shoulder from the shank's side, y running left to
# right; --from-top looks down on a part loaded on its top face y = max with y up instead
# (e.g. cases/block-3d: --from-top --max 350).
import argparse
import math
from paraview.simple import (PVDReader, Reflect, AppendDatasets, ExtractSurface, ExtractEdges,
                             Show, GetActiveViewOrCreate, ColorBy, GetColorTransferFunction,
                             SaveScreenshot, Render, GetScalarBar)

parser = argparse.ArgumentParser()
parser.add_argument("folder")
parser.add_argument("png")
parser.add_argument("--max", type=float, default=200.0)
parser.add_argument("--from-top", action="store_true")
args = parser.parse_args()

reader = PVDReader(FileName=args.folder + "/results.pvd")
last = max(reader.TimestepValues) if reader.TimestepValues else 0.0
reader.UpdatePipeline(last)

# The three mirrored quadrants: (-x, +z), (+x, -z), (-x, -z).
mx = Reflect(Input=reader, Plane="X", Center=0.0, CopyInput=0)
mz = Reflect(Input=reader, Plane="Z", Center=0.0, CopyInput=0)
mxz = Reflect(Input=mx, Plane="Z", Center=0.0, CopyInput=0)
cutaway = AppendDatasets(Input=[mx, mz, mxz])
# Faint edges: the boundary faces' straight edges between corner nodes (the quadratic cells'
# midside nodes dropped, so a face shows its own edges, not the tessellation ParaView draws it with).
linear = ExtractSurface(Input=cutaway)
linear.NonlinearSubdivisionLevel = 0
edges = ExtractEdges(Input=linear)

view = GetActiveViewOrCreate("RenderView")
view.ViewSize = [1200, 700]
view.ViewTime = last
view.OrientationAxesVisibility = 0
try:
    view.UseColorPaletteForBackground = 0
except AttributeError:
    pass
view.Background = [1.0, 1.0, 1.0]

disp = Show(cutaway, view)
disp.NonlinearSubdivisionLevel = 2      # curved faces of the 10- and 20-node cells drawn smooth
disp.Ambient = 0.2
disp.Diffuse = 0.8
ColorBy(disp, ("POINTS", "von_mises"))
lut = GetColorTransferFunction("von_mises")
lut.ApplyPreset("Turbo", True)
lut.AutomaticRescaleRangeMode = "Never"
lut.RescaleTransferFunction(0.0, args.max)
disp.SetScalarBarVisibility(view, True)
bar = GetScalarBar(lut, view)
bar.Title = "von Mises (MPa)"
bar.ComponentTitle = ""
bar.TitleColor = [0, 0, 0]
bar.LabelColor = [0, 0, 0]
bar.RangeLabelFormat = "%.0f"
bar.TitleFontSize = 18
bar.LabelFontSize = 16
bar.WindowLocation = "Any Location"
bar.Position = [0.9, 0.25]
bar.ScalarBarLength = 0.5

lines = Show(edges, view)
ColorBy(lines, None)
lines.AmbientColor = [0.0, 0.0, 0.0]
lines.DiffuseColor = [0.0, 0.0, 0.0]
lines.Opacity = 0.12

Render(view)  # the first render resets the camera; set it after
(x0, x1, y0, y1, z0, z1) = reader.GetDataInformation().GetBounds()
size = math.sqrt((2 * x1) ** 2 + (y1 - y0) ** 2 + (2 * z1) ** 2)  # the whole mirrored part
if args.from_top:
    focal, direction, up = [0.0, 0.5 * (y0 + y1), 0.0], [0.8, 0.9, 1.0], [0.0, 1.0, 0.0]
else:
    focal, direction, up = [0.0, 0.5 * (y0 + y1), 0.0], [0.5, -0.6, 1.0], [-0.5, 0.0, 1.0]
norm = math.sqrt(sum(c * c for c in direction))
view.CameraFocalPoint = focal
view.CameraPosition = [f + 2.25 * size * c / norm for f, c in zip(focal, direction)]
view.CameraViewUp = up
view.CameraParallelProjection = 0
view.CameraViewAngle = 20.0
Render(view)
SaveScreenshot(args.png, view, ImageResolution=[1200, 700])
print(args.png)
