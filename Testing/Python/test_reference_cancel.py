"""vtkMRGIReferenceRenderer reports progress and can be cancelled from Python:
ProgressEvent fires after each pass with a fraction in (0, 1] that grows,
and an observer that sets AbortRender stops the render after that pass,
leaving finite images of exactly the passes done (the same as a render of
that many passes) and GetCancelled() true. A later render runs in full."""
import sys

import numpy as np
from vtkmodules.vtkCommonCore import vtkCommand
from vtkmodules.vtkRenderingCore import vtkRenderer
from vtkmodules.util.numpy_support import vtk_to_numpy

import mrgi


def check(condition, what):
    if not condition:
        print("check failed:", what, file=sys.stderr)
        sys.exit(1)


def as_array(image):
    dims = image.GetDimensions()
    return vtk_to_numpy(image.GetPointData().GetScalars()).reshape(dims[1], dims[0], -1).copy()


def main():
    window = mrgi.vtkMRGIRenderWindowFactory.CreateHeadlessRenderWindow()
    window.SetSize(32, 24)
    renderer = vtkRenderer()
    window.AddRenderer(renderer)
    builder = mrgi.vtkMRGISceneBuilder()
    builder.SetScene("cornell-spot")
    check(builder.Build(renderer), "scene")
    window.Render()  # places the lights as the GPU frame does

    reference = mrgi.vtkMRGIReferenceRenderer()
    reference.SetTargetRelativeError(0.0)  # only MaxPasses or a cancel stop it
    reference.SetMaxPasses(40)
    reference.SetIndirectSamples(4)
    events = []

    def on_progress(caller, _event):
        events.append((caller.GetProgressPasses(), caller.GetProgress(),
                       caller.GetProgressRelativeError(), caller.GetProgressSecondsLeft(),
                       caller.GetProgressPixelError()))
        if caller.GetProgressPasses() >= 3:
            caller.AbortRenderOn()

    tag = reference.AddObserver(vtkCommand.ProgressEvent, on_progress)
    started = []
    reference.AddObserver(vtkCommand.StartEvent, lambda *_: started.append(1))
    check(reference.Render(renderer), "a cancelled render is not an error: " +
          reference.GetLastErrorMessage())
    print("progress events:", events)
    check(started == [1], "StartEvent once")
    check(reference.GetCancelled(), "GetCancelled() after AbortRender")
    check(reference.GetPasses() == 3, "stopped after pass 3, ran %d" % reference.GetPasses())
    check([e[0] for e in events] == [1, 2, 3], "one ProgressEvent per pass: %s" % events)
    fractions = [e[1] for e in events]
    check(all(0 < f <= 1 for f in fractions) and fractions == sorted(fractions),
          "fractions in (0, 1], growing: %s" % fractions)
    check(abs(fractions[-1] - 3 / 40) < 1e-9, "3 of 40 passes: %s" % fractions[-1])
    check(np.isinf(events[0][2]) and np.isfinite(events[1][2]), "error unknown after one pass only")
    # the stopping statistic: per pixel, unknown after one pass, then finite
    # and (sqrt(N) times, N = 768 pixels) larger than the image mean's error
    check(np.isinf(events[0][4]) and np.isfinite(events[1][4]) and events[2][4] > 0,
          "per-pixel error unknown after one pass only: %s" % events)
    check(events[2][4] > 5 * events[2][2], "per-pixel error well above the image mean's: %s" % events)
    check(reference.GetTargetPercentile() == 0.95, "default percentile 0.95")
    check(reference.GetPixelError() == events[2][4], "GetPixelError() is the last pass's statistic")
    check(all(e[3] >= 0 for e in events), "seconds left >= 0")
    cancelled = {"direct": as_array(reference.GetDirectImage()),
                 "indirect": as_array(reference.GetIndirectImage())}
    for name, image in cancelled.items():
        check(image.shape == (24, 32, 3), name + " image size")
        check(bool(np.isfinite(image).all()), name + " image finite")
    check(float(cancelled["indirect"].mean()) > 0, "the passes done are in the image")

    # The same three passes uncancelled: the partial image is that image.
    reference.RemoveObserver(tag)
    reference.SetMaxPasses(3)
    check(reference.Render(renderer), "three passes")
    check(not reference.GetCancelled() and not reference.GetAbortRender(),
          "Render() clears AbortRender; not cancelled")
    check(np.array_equal(as_array(reference.GetIndirectImage()), cancelled["indirect"]),
          "the cancelled image equals a 3-pass render")
    check(abs(reference.GetProgress() - 1.0) < 1e-12, "progress ends at 1")
    check(reference.GetPixelError() == events[2][4], "the same three passes, the same statistic")
    # a lower percentile is a smaller statistic on the same passes
    reference.SetTargetPercentile(0.5)
    check(reference.Render(renderer), "three passes at the median")
    check(reference.GetPixelError() < events[2][4],
          "median %g below the 95th percentile %g" % (reference.GetPixelError(), events[2][4]))
    reference.SetTargetPercentile(0.0)
    check(reference.GetTargetPercentile() > 0, "the percentile is clamped into (0, 1]")
    print("ok")


if __name__ == "__main__":
    main()
