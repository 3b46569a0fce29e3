"""vtkMRGIPass never drops the indirect light silently: at a width whose
multiresolution buffer exceeds GL_MAX_TEXTURE_SIZE (levels side by side,
about twice the width) the pass reports one error, not one per frame, and
again only after the light was computed in between."""
import sys

from vtkmodules.vtkCommonCore import vtkCommand, vtkOutputWindow, vtkLogger
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkRenderingCore import vtkRenderer
from vtkmodules.vtkRenderingOpenGL2 import vtkRenderStepsPass
from vtkmodules.util.misc import calldata_type
from vtkmodules.util.vtkConstants import VTK_STRING

import mrgi


def check(condition, what):
    if not condition:
        print("check failed:", what, file=sys.stderr)
        sys.exit(1)


def main():
    # The stages' own errors are expected here: keep the log readable.
    vtkLogger.SetStderrVerbosity(vtkLogger.VERBOSITY_OFF)
    vtkOutputWindow.GetInstance().SetDisplayModeToNever()
    window = mrgi.vtkMRGIRenderWindowFactory.CreateHeadlessRenderWindow()
    renderer = vtkRenderer()
    window.AddRenderer(renderer)
    builder = mrgi.vtkMRGISceneBuilder()
    builder.SetScene("cornell-spot")
    check(builder.Build(renderer), "scene")
    gi = mrgi.vtkMRGIPass()
    gi.SetDelegatePass(vtkRenderStepsPass())
    gi.SetIndirectMode(mrgi.vtkMRGIPass.IndirectMultires)
    renderer.SetPass(gi)
    reported = []

    @calldata_type(VTK_STRING)  # the message reaches the observer
    def on_error(_caller, _event, text):
        reported.append(text)
    gi.AddObserver(vtkCommand.ErrorEvent, on_error)

    buffer = vtkImageData()
    too_wide = 9000
    window.SetSize(too_wide, 16)
    for _ in range(3):
        window.Render()
    lost = [t for t in reported if "indirect light could not be computed" in t]
    print("errors at %d wide:" % too_wide, reported)
    check(len(lost) == 1, "one error for three frames without indirect light: %s" % reported)
    check("9000 x 16" in lost[0], "the error names the size: " + lost[0])

    window.SetSize(64, 16)
    window.Render()
    check(gi.GetIndirectBuffer(window, buffer), "indirect light at 64 x 16")
    count = len([t for t in reported if "indirect light could not be computed" in t])
    check(count == 1, "no error while the light is computed")
    window.SetSize(too_wide, 16)
    window.Render()
    count = len([t for t in reported if "indirect light could not be computed" in t])
    check(count == 2, "reported again after it had worked in between")
    renderer.SetPass(None)
    gi.ReleaseGraphicsResources(window)
    print("ok")


if __name__ == "__main__":
    main()
