"""The GPU's full-resolution gather against the CPU ground truth, through the
Python API: on the Cornell box lit by a spot light, the mean indirect light
of the two agrees within 25% (the measured gap is about 9%; see
Documentation/Fidelity.md), both are finite and non-negative, the ground truth
with secondary visibility is darker than without, and the ceiling, which the
spot light cannot reach, is lit only indirectly."""
import math
import sys

import numpy as np
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkRenderingCore import vtkRenderer
from vtkmodules.vtkRenderingOpenGL2 import vtkRenderStepsPass
from vtkmodules.util.numpy_support import vtk_to_numpy

import mrgi


def check(condition, what):
    if not condition:
        print("check failed:", what, file=sys.stderr)
        sys.exit(1)


def as_array(image):
    dims = image.GetDimensions()
    return vtk_to_numpy(image.GetPointData().GetScalars()).reshape(dims[1], dims[0], -1)


def main():
    size = 64
    window = mrgi.vtkMRGIRenderWindowFactory.CreateHeadlessRenderWindow()
    window.SetSize(size, size)
    renderer = vtkRenderer()
    window.AddRenderer(renderer)
    builder = mrgi.vtkMRGISceneBuilder()
    builder.SetScene("cornell-spot")
    check(builder.Build(renderer), "scene")
    gi = mrgi.vtkMRGIPass()
    gi.SetDelegatePass(vtkRenderStepsPass())
    gi.SetNumberOfVPLs(1024)
    renderer.SetPass(gi)
    window.Render()
    buffer = vtkImageData()
    check(gi.GetIndirectBuffer(window, buffer), "GPU indirect buffer")
    gpu = as_array(buffer)

    means = {}
    for visibility in (True, False):
        reference = mrgi.vtkMRGIReferenceRenderer()
        reference.SetSecondaryVisibility(visibility)
        reference.SetTargetRelativeError(0.0)
        reference.SetMaxPasses(8)
        check(reference.Render(renderer), "ground truth: " + reference.GetLastErrorMessage())
        truth = as_array(reference.GetIndirectImage())
        check(truth.shape == gpu.shape, "same size")
        check(bool(np.isfinite(truth).all()) and bool((truth >= 0).all()), "finite, non-negative truth")
        means[visibility] = float(truth.mean())
        # Ceiling (top rows; arrays are bottom-up): no direct light, indirect light > 0.
        direct = as_array(reference.GetDirectImage())
        ceiling = (slice(size - 4, size - 1), slice(size // 2 - 4, size // 2 + 4))
        check(float(direct[ceiling].max()) == 0.0, "the spot light cannot reach the ceiling")
        check(float(truth[ceiling].mean()) > 0.0, "the ceiling is lit indirectly")
        check(float(gpu[ceiling].mean()) > 0.0, "the GPU lights the ceiling indirectly too")

    # Centre-sampled pixels: point lights' direct light is then exact, the
    # same for every seed; box-filtered pixels (jittered rays) change with it.
    box = mrgi.vtkMRGIReferenceRenderer.PixelBox
    center = mrgi.vtkMRGIReferenceRenderer.PixelCenter
    direct = {}
    for pixel in (box, center):
        for seed in (1, 2):
            reference = mrgi.vtkMRGIReferenceRenderer()
            reference.SetIndirectSamples(0)
            reference.SetMaxPasses(1)
            reference.SetPixelFilter(pixel)
            reference.SetSeed(seed)
            check(reference.Render(renderer), "ground truth: " + reference.GetLastErrorMessage())
            direct[pixel, seed] = as_array(reference.GetDirectImage()).copy()
    check(reference.GetPixelFilter() == center and "PixelFilter: Center" in str(reference),
          "the pixel filter is kept and printed")
    check(np.array_equal(direct[center, 1], direct[center, 2]), "centre samples do not depend on the seed")
    edges = int((direct[box, 1] != direct[box, 2]).any(axis=2).sum())
    check(edges > 0, "box-filtered pixels (jittered rays) depend on the seed")
    print("pixels whose box-filtered direct light changes with the seed: %d" % edges)

    gpu_mean = float(gpu.mean())
    print("mean indirect: GPU %.5f, ground truth %.5f (visibility) %.5f (no secondary visibility)"
          % (gpu_mean, means[True], means[False]))
    check(bool(np.isfinite(gpu).all()) and bool((gpu >= 0).all()), "finite, non-negative GPU indirect")
    check(means[True] < means[False], "occlusion between bounce points darkens")
    check(abs(gpu_mean / means[False] - 1.0) < 0.25, "GPU within 25% of the ground truth it models")
    renderer.SetPass(None)
    gi.ReleaseGraphicsResources(window)
    print("ok")


if __name__ == "__main__":
    main()
