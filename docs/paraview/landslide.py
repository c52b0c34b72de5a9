# Renders a run's ParaView files (docs/formats.md, section 7) as ParaView itself shows them: the
# particles as spheres coloured by fragment, the bonds coloured by state, over the terrain. Made
# docs/paraview/landslide.png from the landslide case:
#   build/dem run cases/landslide/spec.json --out runs/landslide
#   xvfb-run -a pvbatch docs/paraview/landslide.py runs/landslide docs/paraview/landslide.png 1.5
# (Debian's paraview and xvfb). The same steps in ParaView's window: open particles.pvd, Glyph
# (Sphere, Scale Array radius, Scale Factor 2), open walls.vtp and bonds.pvd, play.
import sys

from paraview.simple import (
    ColorBy, GetActiveViewOrCreate, GetAnimationScene, GetColorTransferFunction, GetScalarBar, Glyph,
    PVDReader,
    SaveScreenshot, Show, Threshold, XMLPolyDataReader)

run, png = sys.argv[1], sys.argv[2]
at_time = float(sys.argv[3]) if len(sys.argv) > 3 else None

particles = PVDReader(FileName=run + "/particles.pvd")
# the bonds that hold: a broken bond is a line too (state 1 or 2), between pieces that fly apart
bonds = Threshold(Input=PVDReader(FileName=run + "/bonds.pvd"), Scalars=["CELLS", "state"],
                  LowerThreshold=0, UpperThreshold=0)
terrain = XMLPolyDataReader(FileName=[run + "/walls.vtp"])

spheres = Glyph(Input=particles, GlyphType="Sphere")
spheres.ScaleArray = ["POINTS", "radius"]
spheres.ScaleFactor = 2.0  # the glyph sphere's own radius is 0.5
spheres.GlyphMode = "All Points"
spheres.GlyphType.ThetaResolution = 16
spheres.GlyphType.PhiResolution = 12

view = GetActiveViewOrCreate("RenderView")
view.ViewSize = [1600, 700]
view.UseColorPaletteForBackground = 0
view.Background = [1, 1, 1]
view.OrientationAxesVisibility = 1

ground = Show(terrain, view)
ground.DiffuseColor = [0.75, 0.72, 0.66]
ground.Opacity = 0.9

shown = Show(spheres, view)
ColorBy(shown, ("POINTS", "fragment"))
fragments = GetColorTransferFunction("fragment")
fragments.ApplyPreset("Rainbow Uniform", True)
shown.SetScalarBarVisibility(view, True)
bar = GetScalarBar(fragments, view)
bar.Title = "fragment"
bar.ComponentTitle = ""
bar.TitleColor = bar.LabelColor = [0.1, 0.1, 0.1]

links = Show(bonds, view)
links.ColorArrayName = [None, ""]
links.DiffuseColor = [0.95, 0.95, 0.95]
links.AmbientColor = [0.95, 0.95, 0.95]
links.LineWidth = 1.0
links.Opacity = 0.5

scene = GetAnimationScene()
scene.UpdateAnimationUsingDataTimeSteps()
if at_time is not None:
    scene.AnimationTime = at_time
    view.ViewTime = at_time
    for source in (spheres, bonds):
        source.UpdatePipeline(at_time)
print("spheres' bounds:", spheres.GetDataInformation().GetBounds())
fragments.RescaleTransferFunction(1.0, 12.0)

view.CameraPosition = [7.0, -13.0, 9.0]
view.CameraFocalPoint = [7.0, 0.0, 2.5]
view.CameraViewUp = [0.0, 0.45, 1.0]
view.CameraParallelProjection = 0
SaveScreenshot(png, view, ImageResolution=[1600, 700])
print("wrote", png, "at t =", scene.AnimationTime, "s")
