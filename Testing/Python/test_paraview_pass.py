"""MRGI's pass on a ParaView render view, from a pvbatch script
(Documentation/ParaView-Python.md).

Run by /usr/bin/python3 (ctest), this starts `xvfb-run -a pvbatch` on itself
with PYTHONPATH = ParaView's unpacked python3-paraview, then the `mrgi`
package built against ParaView's VTK (build/paraview-vtk). In pvbatch it
builds a box of five walls (red left, green right) and a block with
paraview.simple, lit by one ParaView spot light pointing down (the ceiling
gets no direct light), and saves three screenshots of the same view:

  plain  ParaView's own rendering;
  off    vtkMRGIPass on view.GetClientSideObject().GetRenderer(), IndirectOff;
  gi     the same pass with its default multiresolution indirect light.

Checks: the mrgi imported is the ParaView-side one; `off` equals `plain`
(the pass draws ParaView's scene, direct light unchanged); `gi` differs from
`off` measurably; the ceiling, black without indirect light, is lit, reddish
next to the red wall and greenish next to the green wall; the indirect light
only adds. Exit status 77 (skipped) only when pvbatch or xvfb-run is absent.

Environment (from ctest): MRGI_PARAVIEW_SITE (python3-paraview's
dist-packages), MRGI_PARAVIEW_MRGI (the folder holding the ParaView-side
mrgi), MRGI_TEST_TMP (where the screenshots go).
"""
import os
import shutil
import subprocess
import sys

SIZE = 200
failures = []


def check(condition, what):
    print(("ok: " if condition else "FAILED: ") + what)
    if not condition:
        failures.append(what)


def driver():
    """ctest's side: run this file in pvbatch under Xvfb."""
    for program in ("pvbatch", "xvfb-run"):
        if shutil.which(program) is None:
            print("skip: %s is not installed (scripts/install-deps.sh installs paraview, xvfb)"
                  % program)
            return 77
    site = os.environ["MRGI_PARAVIEW_SITE"]
    package = os.environ["MRGI_PARAVIEW_MRGI"]
    for path in (os.path.join(site, "paraview", "simple.py"),
                 os.path.join(package, "mrgi", "__init__.py")):
        if not os.path.isfile(path):
            print("FAILED: %s is missing (scripts/check-paraview-vtk.sh, i.e. "
                  "compat.ParaViewVTK, fetches and builds it)" % path)
            return 1
    env = dict(os.environ, PYTHONPATH=site + os.pathsep + package)
    env.pop("DISPLAY", None)
    # pvbatch needs an X server to render (Debian's aborts without one).
    # xvfb-run -a probes for a free display from -n on; parallel tests that
    # all start at its default 99 can pick the same one, and pvbatch then
    # aborts on a display that goes away: start the search at a number
    # derived from the process id, and retry once on that failure only.
    for attempt in (1, 2):
        display = 1000 + (os.getpid() * 7 + attempt) % 4000
        argv = ["xvfb-run", "-a", "-n", str(display), "pvbatch", os.path.abspath(__file__),
                "--in-pvbatch"]
        proc = subprocess.run(argv, env=env, timeout=600, check=False,
                              stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
        out = proc.stdout.decode("utf-8", "replace")
        print(out)
        print("pvbatch exit status %d" % proc.returncode)
        if proc.returncode == 0:
            return 0
        if "bad X server connection" not in out or attempt == 2:
            return 1
        print("the X server went away under pvbatch; once more on another display")
    return 1


def read_png(path):
    from vtkmodules.vtkIOImage import vtkPNGReader
    from vtkmodules.util.numpy_support import vtk_to_numpy
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    w, h, _ = image.GetDimensions()
    pixels = vtk_to_numpy(image.GetPointData().GetScalars()).reshape(h, w, -1)
    return pixels[::-1, :, :3].astype(float)  # row 0 at the top


def region(image, rows, cols):
    """Mean RGB (0-255) of a block given in fractions of the image size."""
    h, w, _ = image.shape
    block = image[int(rows[0] * h):int(rows[1] * h), int(cols[0] * w):int(cols[1] * w)]
    return block.mean(axis=(0, 1))


def in_pvbatch():
    from paraview import simple as pv
    from vtkmodules.vtkRenderingOpenGL2 import vtkRenderStepsPass
    import mrgi

    package = os.path.realpath(os.environ["MRGI_PARAVIEW_MRGI"])
    check(os.path.realpath(mrgi.__file__).startswith(package + os.sep),
          "the ParaView-side mrgi is imported: %s" % mrgi.__file__)
    check(mrgi._build_info.PARAVIEW_VERSION != "",
          "it was built against ParaView's VTK %s" % mrgi._build_info.VTK_VERSION)

    view = pv.CreateView("RenderView")
    view.ViewSize = [SIZE, SIZE]
    view.OrientationAxesVisibility = 0
    view.UseColorPaletteForBackground = 0
    view.Background = [0, 0, 0]

    def show(source, color):
        display = pv.Show(source, view)
        display.ColorArrayName = ["POINTS", ""]
        display.AmbientColor = color
        display.DiffuseColor = color

    white, red, green = [0.75, 0.75, 0.75], [0.75, 0.1, 0.1], [0.1, 0.75, 0.1]
    walls = [([0, 0, 0], [1, 0, 0], [0, 0, 1], white),  # floor, y = 0
             ([0, 1, 0], [0, 1, 1], [1, 1, 0], white),  # ceiling, y = 1
             ([0, 0, 0], [0, 1, 0], [1, 0, 0], white),  # back, z = 0
             ([0, 0, 0], [0, 0, 1], [0, 1, 0], red),    # left, x = 0
             ([1, 0, 0], [1, 1, 0], [1, 0, 1], green)]  # right, x = 1
    for origin, p1, p2, color in walls:
        show(pv.Plane(Origin=origin, Point1=p1, Point2=p2), color)
    show(pv.Box(Center=[0.5, 0.25, 0.45], XLength=0.3, YLength=0.5, ZLength=0.3), white)
    view.CameraPosition = [0.5, 0.5, 2.6]
    view.CameraFocalPoint = [0.5, 0.5, 0.0]
    view.CameraViewUp = [0, 1, 0]
    view.CameraViewAngle = 30
    # One spot light under the ceiling, pointing down; no light kit.
    view.UseLight = 0
    light = pv.AddLight(view=view)
    light.Coords = "Scene"
    light.Type = "Positional"
    light.Position = [0.5, 0.95, 0.5]
    light.FocalPoint = [0.5, 0.0, 0.5]
    light.ConeAngle = 80

    out = os.environ.get("MRGI_TEST_TMP", ".")
    os.makedirs(out, exist_ok=True)

    def shot(name):
        path = os.path.join(out, "paraview-python-%s.png" % name)
        pv.Render(view)
        pv.SaveScreenshot(path, view, ImageResolution=[SIZE, SIZE])
        print("wrote", path)
        return read_png(path)

    plain = shot("plain")
    renderer = view.GetClientSideObject().GetRenderer()
    gi = mrgi.vtkMRGIPass()
    gi.SetDelegatePass(vtkRenderStepsPass())
    gi.SetIndirectMode(mrgi.vtkMRGIPass.IndirectOff)
    # VTK's direct light as ParaView draws it: the checks below compare the
    # indirect light alone (direct shadows are on by default).
    gi.SetDirectShadowsToOff()
    renderer.SetPass(gi)
    off = shot("off")
    gi.SetIndirectMode(mrgi.vtkMRGIPass.IndirectMultires)
    lit = shot("gi")
    check(renderer.GetPass() is gi, "ParaView kept the pass through SaveScreenshot")

    d_plain = abs(off - plain).mean()
    d_gi = abs(lit - off).mean()
    print("mean |off - plain| = %.3f, mean |gi - off| = %.3f (0-255)" % (d_plain, d_gi))
    print("mean RGB: plain %s, off %s, gi %s" % tuple(
        str(i.mean(axis=(0, 1)).round(2)) for i in (plain, off, lit)))
    check(d_plain < 1.0, "IndirectOff draws ParaView's image (mean |diff| < 1)")
    check(d_gi > 2.0, "the indirect light changes the image (mean |diff| > 2)")

    ceiling_rows = (0.16, 0.25)
    left, right = (0.22, 0.47), (0.53, 0.78)
    off_l, off_r = region(off, ceiling_rows, left), region(off, ceiling_rows, right)
    gi_l, gi_r = region(lit, ceiling_rows, left), region(lit, ceiling_rows, right)
    print("ceiling left: off %s, gi %s; right: off %s, gi %s" % tuple(
        str(v.round(1)) for v in (off_l, gi_l, off_r, gi_r)))
    check(max(off_l.max(), off_r.max()) < 2, "the ceiling gets no direct light")
    check(min(gi_l.mean(), gi_r.mean()) > 10, "the indirect light reaches the ceiling")
    check(gi_l[0] - gi_l[1] > 1, "red bleeds onto the ceiling next to the red wall")
    check(gi_r[1] - gi_r[0] > 1, "green bleeds onto the ceiling next to the green wall")
    back_rows = (0.35, 0.6)
    for cols in ((0.27, 0.4), (0.6, 0.72)):
        before, after = region(off, back_rows, cols), region(lit, back_rows, cols)
        check(bool((after >= before - 0.5).all()),
              "the indirect light only adds on the back wall %s: %s -> %s"
              % (cols, before.round(1), after.round(1)))
    if failures:
        print("%d check(s) failed" % len(failures))
        sys.exit(1)
    print("all checks passed")


if __name__ == "__main__":
    if "--in-pvbatch" in sys.argv:
        in_pvbatch()
    else:
        sys.exit(driver())
