# Renders the last increment of an asperity run with ParaView (pvpython):
#   xvfb-run -a pvpython docs/paraview/render.py out/punch-plane-stress docs/figures/paraview-von-mises.png
# Warps by the displacement (x20) and colours by von Mises stress.
import sys
from paraview.simple import (PVDReader, WarpByVector, Show, GetActiveViewOrCreate,
                             ColorBy, GetColorTransferFunction, ResetCamera, SaveScreenshot,
                             Render, GetScalarBar)

folder, png = sys.argv[1], sys.argv[2]
reader = PVDReader(FileName=folder + "/results.pvd")
reader.UpdatePipeline(max(reader.TimestepValues) if reader.TimestepValues else 0.0)
warp = WarpByVector(Input=reader)
warp.Vectors = ["POINTS", "displacement"]
warp.ScaleFactor = 20.0
view = GetActiveViewOrCreate("RenderView")
view.ViewSize = [1200, 640]
view.ViewTime = max(reader.TimestepValues) if reader.TimestepValues else 0.0
view.OrientationAxesVisibility = 0
try:
    view.UseColorPaletteForBackground = 0
except AttributeError:
    pass
view.Background = [1.0, 1.0, 1.0]
disp = Show(warp, view)
ColorBy(disp, ("POINTS", "von_mises"))
lut = GetColorTransferFunction("von_mises")
lut.ApplyPreset("Turbo", True)
lut.RescaleTransferFunction(0.0, 300.0)
disp.SetScalarBarVisibility(view, True)
bar = GetScalarBar(lut, view)
bar.Title = "von Mises (MPa)"
bar.ComponentTitle = ""
bar.TitleColor = [0, 0, 0]
bar.LabelColor = [0, 0, 0]
view.CameraPosition = [30.0, -20.0, 200.0]
view.CameraFocalPoint = [30.0, -20.0, 0.0]
view.CameraViewUp = [0.0, 1.0, 0.0]
view.CameraParallelProjection = 1
view.CameraParallelScale = 42.0
Render(view)
SaveScreenshot(png, view, ImageResolution=[1200, 640])
print(png)
