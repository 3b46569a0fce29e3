"""pvbatch: ParaView's representations behave in the MRGI Render View.

usage: pvbatch pvbatch_representations.py PLUGIN OUT_DIR
For each case (scalar colouring through a lookup table, points rendered as
spheres, a volume, a translucent surface, all together) renders ParaView's
own Render View and the MRGI Render View with GI off and on, writes the
PNGs to OUT_DIR and prints one line per case:
  case=NAME covered_pv=N covered_off=N covered_on=N
(covered = pixels that differ from the background). The shell script
compares the images.
"""
import os
import sys

from paraview import simple

plugin, out_dir = sys.argv[1], sys.argv[2]
simple.LoadPlugin(plugin, remote=False)
SIZE = 160


def scalars(view):
    wavelet = simple.Wavelet()
    contour = simple.Contour(Input=wavelet, ContourBy=["POINTS", "RTData"], Isosurfaces=[150.0])
    elevation = simple.Elevation(Input=contour, LowPoint=[-10, -10, -10], HighPoint=[10, 10, 10])
    display = simple.Show(elevation, view)
    simple.ColorBy(display, ("POINTS", "Elevation"))
    display.RescaleTransferFunctionToDataRange(True)
    floor = simple.Plane(Origin=[-15, -12, -15], Point1=[15, -12, -15], Point2=[-15, -12, 15])
    simple.Show(floor, view)


def spheres(view):
    sphere = simple.Sphere(ThetaResolution=12, PhiResolution=12, Radius=8)
    display = simple.Show(sphere, view)
    display.SetRepresentationType("Points")
    display.RenderPointsAsSpheres = 1
    display.PointSize = 10
    floor = simple.Plane(Origin=[-15, -10, -15], Point1=[15, -10, -15], Point2=[-15, -10, 15])
    simple.Show(floor, view)


def volume(view):
    wavelet = simple.Wavelet()
    display = simple.Show(wavelet, view)
    display.SetRepresentationType("Volume")
    simple.ColorBy(display, ("POINTS", "RTData"))


def translucent(view):
    box = simple.Box(XLength=30, YLength=2, ZLength=30, Center=[0, -10, 0])
    simple.Show(box, view)
    sphere = simple.Sphere(Radius=8, ThetaResolution=32, PhiResolution=32)
    display = simple.Show(sphere, view)
    display.Opacity = 0.5
    display.DiffuseColor = [1.0, 0.3, 0.2]


def together(view):
    scalars(view)
    spheres(view)
    translucent(view)


CASES = [("scalars", scalars), ("spheres", spheres), ("volume", volume),
         ("translucent", translucent), ("together", together)]


def covered(path):
    from vtkmodules.vtkIOImage import vtkPNGReader
    from vtkmodules.util.numpy_support import vtk_to_numpy
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    pixels = vtk_to_numpy(reader.GetOutput().GetPointData().GetScalars())[:, :3].astype(int)
    background = pixels[0]  # a corner: every case leaves it empty
    return int(((abs(pixels - background)).sum(axis=1) > 6).sum())


def render(case, build, kind, gi):
    view = simple.CreateView(kind)
    view.ViewSize = [SIZE, SIZE]
    view.OrientationAxesVisibility = 0
    view.UseFXAA = 0
    if hasattr(view, "UseColorPaletteForBackground"):
        view.UseColorPaletteForBackground = 0
    view.Background = [0.1, 0.1, 0.12]
    if kind == "MRGIRenderView":
        view.GlobalIllumination = 1 if gi else 0
    build(view)
    view.CameraPosition = [30, 25, 45]
    view.CameraFocalPoint = [0, 0, 0]
    view.CameraViewUp = [0, 1, 0]
    simple._DisableFirstRenderCameraReset()
    simple.Render(view)
    name = "%s-%s.png" % (case, "pv" if kind == "RenderView" else ("on" if gi else "off"))
    path = os.path.join(out_dir, name)
    simple.SaveScreenshot(path, view, ImageResolution=[SIZE, SIZE])
    for source in list(simple.GetSources().values()):
        simple.Delete(source)
    simple.Delete(view)
    return covered(path)


for case, build in CASES:
    pv = render(case, build, "RenderView", False)
    off = render(case, build, "MRGIRenderView", False)
    on = render(case, build, "MRGIRenderView", True)
    print("case=%s covered_pv=%d covered_off=%d covered_on=%d" % (case, pv, off, on))
