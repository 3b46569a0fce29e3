"""The `mrgi` Python package: import it beside Debian's vtkmodules, render the
Cornell box headless through vtkMRGIPass, check pixels, stage timings, the HDR
buffer and the EXR writer."""
import math
import os
import sys

from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkRenderingCore import vtkRenderer
from vtkmodules.vtkRenderingOpenGL2 import vtkRenderStepsPass
from vtkmodules.util.numpy_support import vtk_to_numpy

import mrgi


def check(condition, what):
    if not condition:
        print("check failed:", what, file=sys.stderr)
        sys.exit(1)


def main():
    check("DISPLAY" not in os.environ or not os.environ["DISPLAY"], "DISPLAY is unset")
    window = mrgi.vtkMRGIRenderWindowFactory.CreateHeadlessRenderWindow()
    check(window is not None, "a headless window")
    window.SetSize(200, 150)
    renderer = vtkRenderer()
    window.AddRenderer(renderer)

    builder = mrgi.vtkMRGISceneBuilder()
    builder.SetScene("cornell")
    check(builder.Build(renderer), "the Cornell box builds")

    steps = vtkRenderStepsPass()
    gi = mrgi.vtkMRGIPass()
    gi.SetDelegatePass(steps)
    gi.SetStageTimingEnabled(True)
    gi.SetIndirectMode(mrgi.vtkMRGIPass.IndirectFull)  # its stages are checked below
    renderer.SetPass(gi)
    window.GetRenderTimer().SetLoggingEnabled(True)  # time from the first frame on
    window.Render()

    stages = gi.FetchStageTimings(window, True)
    names = [gi.GetStageName(i) for i in range(stages)]
    times = [gi.GetStageTimeMilliseconds(i) for i in range(stages)]
    print("stages:", list(zip(names, times)))
    # Top-level stages in order; "stage.step" parts follow their stage.
    top = [n for n in names if "." not in n]
    check(top == ["scene", "rsm", "shadows", "vpl", "gather", "add", "forward", "output"],
          "stage names, got %s" % top)
    check(all(n.split(".")[0] in top for n in names), "every step belongs to a stage")
    check(gi.GetIndirectComputed(), "indirect light computed")
    indirect = vtkImageData()
    check(gi.GetIndirectBuffer(window, indirect), "indirect buffer read back")
    ind = vtk_to_numpy(indirect.GetPointData().GetScalars()).reshape(150, 200, 3)
    check(float(ind.max()) > 0.0 and bool((ind >= 0).all()), "indirect light is positive somewhere, never negative")
    check(all(math.isfinite(t) and t >= 0 for t in times), "finite stage times")

    hdr = vtkImageData()
    check(gi.GetColorBuffer(window, hdr), "HDR buffer read back")
    pixels = vtk_to_numpy(hdr.GetPointData().GetScalars()).reshape(150, 200, 4)
    check(pixels.dtype.kind == "f", "float pixels")
    check(bool((pixels == pixels).all()), "no NaN")
    red_wall = pixels[60:100, 30:40, :3].mean(axis=(0, 1))
    green_wall = pixels[60:100, 160:170, :3].mean(axis=(0, 1))
    print("red wall", red_wall, "green wall", green_wall)
    check(red_wall[0] > 2 * red_wall[1], "red wall is red")
    check(green_wall[1] > 2 * green_wall[0], "green wall is green")

    io = mrgi.vtkMRGIImageIO()
    path = os.path.join(os.environ.get("MRGI_TEST_TMP", "/tmp"), "python_cornell.exr")
    if os.path.exists(path):
        os.remove(path)
    check(io.Write(hdr, path), "EXR written: " + io.GetLastErrorMessage())
    back = vtkImageData()
    check(io.Read(path, back), "EXR read back")
    again = vtk_to_numpy(back.GetPointData().GetScalars()).reshape(150, 200, 4)
    check(float(abs(again - pixels).max()) == 0.0, "float EXR round trip is exact")
    check(not io.Write(hdr, "/nonexistent-dir/x.exr"), "unwritable path fails")
    check("nonexistent" in io.GetLastErrorMessage() or len(io.GetLastErrorMessage()) > 10,
          "error names the problem")

    renderer.SetPass(None)
    gi.ReleaseGraphicsResources(window)

    # The OSMesa backend from Python: the factory by name, the wrapped window,
    # the same Cornell box through vtkMRGIPass, the same HDR pixels as above.
    factory = mrgi.vtkMRGIRenderWindowFactory
    osmesa = factory.NewRenderWindow(factory.Headless, "osmesa")
    check(isinstance(osmesa, mrgi.vtkMRGIOSMesaRenderWindow), "an OSMesa window by name")
    line = factory.DescribeRenderWindow(osmesa)
    print("backend:", line)
    check(line.startswith("osmesa (OSMesa, OpenGL"), "the backend line names OSMesa")
    check(osmesa.GetContextVersion() >= 32, "an OpenGL 3.2+ core context")
    osmesa.SetSize(200, 150)
    osmesa_renderer = vtkRenderer()
    osmesa.AddRenderer(osmesa_renderer)
    builder.Build(osmesa_renderer)
    osmesa_gi = mrgi.vtkMRGIPass()
    osmesa_gi.SetDelegatePass(vtkRenderStepsPass())
    osmesa_gi.SetIndirectMode(mrgi.vtkMRGIPass.IndirectFull)
    osmesa_renderer.SetPass(osmesa_gi)
    osmesa.Render()
    osmesa_hdr = vtkImageData()
    check(osmesa_gi.GetColorBuffer(osmesa, osmesa_hdr), "OSMesa HDR buffer read back")
    osmesa_pixels = vtk_to_numpy(osmesa_hdr.GetPointData().GetScalars()).reshape(150, 200, 4)
    difference = float(abs(osmesa_pixels - pixels).max())
    print("OSMesa vs EGL HDR max difference:", difference)
    check(bool((osmesa_pixels == osmesa_pixels).all()), "no NaN on OSMesa")
    check(difference < 0.05, "OSMesa and EGL agree (max difference %g)" % difference)
    osmesa_renderer.SetPass(None)
    osmesa_gi.ReleaseGraphicsResources(osmesa)
    check_rsm_resolution_change()
    print("ok")


def check_rsm_resolution_change():
    """The maps follow SetRSMResolution after the first frame: the indirect
    light after growing 256 -> 1024 equals a fresh pass's at 1024 (their
    depth buffer once kept its first size, so larger maps were drawn in a
    corner only and the light dropped about fourfold)."""
    def render(resolutions):
        window = mrgi.vtkMRGIRenderWindowFactory.CreateHeadlessRenderWindow()
        window.SetSize(64, 64)
        window.SetMultiSamples(0)
        renderer = vtkRenderer()
        window.AddRenderer(renderer)
        builder = mrgi.vtkMRGISceneBuilder()
        builder.SetScene("cornell-spot")
        check(builder.Build(renderer), "cornell-spot builds")
        gi = mrgi.vtkMRGIPass()
        gi.SetDelegatePass(vtkRenderStepsPass())
        gi.SetIndirectMode(mrgi.vtkMRGIPass.IndirectFull)
        renderer.SetPass(gi)
        for r in resolutions:
            gi.SetRSMResolution(r)
            window.Render()
        image = vtkImageData()
        check(gi.GetIndirectBuffer(window, image), "indirect buffer read back")
        mean = float(vtk_to_numpy(image.GetPointData().GetScalars()).mean())
        renderer.SetPass(None)
        gi.ReleaseGraphicsResources(window)
        return mean

    fresh = render([1024])
    grown = render([256, 1024])
    print("indirect mean, RSM 1024 fresh %.6g, after 256: %.6g" % (fresh, grown))
    check(fresh > 0 and abs(grown - fresh) <= 1e-3 * fresh,
          "RSM 256 -> 1024 gives the light of a fresh 1024 pass (%g vs %g)" % (grown, fresh))

if __name__ == "__main__":
    main()
