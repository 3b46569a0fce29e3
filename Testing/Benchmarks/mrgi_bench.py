"""Shared pieces of MRGI's benchmark scripts: scenes, headless windows,
buffers as numpy arrays, EXR/PNG writing, and the core's image metrics
(through the mrgi-compare tool, so that reported numbers come from the same
C code the tests check)."""
import os
import subprocess
import time

import numpy as np
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkIOPLY import vtkPLYReader
from vtkmodules.vtkRenderingCore import vtkActor, vtkPolyDataMapper, vtkRenderer
from vtkmodules.vtkRenderingOpenGL2 import vtkRenderStepsPass
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy

import mrgi

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
SHARED_DATA = os.environ.get("MRGI_SHARED_DATA_DIR", os.path.join(ROOT, "..", "shared", "data"))


def build_scene(renderer, name):
    """Fill `renderer` with a named benchmark scene; returns a description or None."""
    builder = mrgi.vtkMRGISceneBuilder()
    if name == "bunny-cornell":
        path = os.path.join(SHARED_DATA, "bunny.ply")
        if not os.path.exists(path):
            return None
        builder.SetScene("cornell-spot")
        assert builder.Build(renderer), builder.GetLastErrorMessage()
        reader = vtkPLYReader()
        reader.SetFileName(path)
        reader.Update()
        bounds = reader.GetOutput().GetBounds()
        mapper = vtkPolyDataMapper()
        mapper.SetInputConnection(reader.GetOutputPort())
        mapper.ScalarVisibilityOff()
        bunny = vtkActor()
        bunny.SetMapper(mapper)
        # Metres to the box's millimetres, standing on the floor in front of the tall block.
        bunny.SetScale(1000.0)
        bunny.SetPosition(430.0 - 1000.0 * 0.5 * (bounds[0] + bounds[1]), -1000.0 * bounds[2],
                          130.0 - 1000.0 * 0.5 * (bounds[4] + bounds[5]))
        bunny.GetProperty().SetColor(0.725, 0.71, 0.68)
        bunny.GetProperty().SetAmbient(0.0)
        bunny.GetProperty().SetDiffuse(1.0)
        bunny.GetProperty().SetSpecular(0.0)
        renderer.AddActor(bunny)
        return "Cornell box (spot) with the Stanford bunny (69,451 triangles, shared/data/bunny.ply)"
    builder.SetScene(name)
    assert builder.Build(renderer), builder.GetLastErrorMessage()
    return {"cornell-spot": "Cornell box lit by a spot light (65 degree half-angle)"}.get(name, name)


def frames(window, gi, count):
    """Render `count` frames; median GPU ms per stage of the MRGI pass `gi` and wall ms per frame ("frame")."""
    times, walls = {}, []
    if hasattr(gi, "SetAreaLightReuse"):
        gi.SetAreaLightReuse(False)  # measure the area lights' computation, not its reuse
    for _ in range(count):
        start = time.perf_counter()
        window.Render()
        n = gi.FetchStageTimings(window, True)
        walls.append((time.perf_counter() - start) * 1e3)
        for s in range(n):
            times.setdefault(gi.GetStageName(s), []).append(gi.GetStageTimeMilliseconds(s))
    result = {k: float(np.median(v)) for k, v in times.items()}
    result["frame"] = float(np.median(walls))
    return result


def make_window(width, height):
    window = mrgi.vtkMRGIRenderWindowFactory.CreateHeadlessRenderWindow()
    assert window is not None, "no headless OpenGL context"
    window.SetSize(width, height)
    window.SetMultiSamples(0)
    renderer = vtkRenderer()
    window.AddRenderer(renderer)
    return window, renderer


def install_pass(renderer, **settings):
    gi = mrgi.vtkMRGIPass()
    gi.SetDelegatePass(vtkRenderStepsPass())
    for key, value in settings.items():
        getattr(gi, "Set" + key)(value)
    renderer.SetPass(gi)
    return gi


def to_numpy(image):
    """A vtkImageData as an (height, width, components) array, rows top-down."""
    dims = image.GetDimensions()
    array = vtk_to_numpy(image.GetPointData().GetScalars())
    return array.reshape(dims[1], dims[0], -1)[::-1].copy()


def from_numpy(array):
    """An (height, width, components) top-down array as a float vtkImageData."""
    height, width, components = array.shape
    image = vtkImageData()
    image.SetDimensions(width, height, 1)
    flat = np.ascontiguousarray(array[::-1].reshape(-1, components), dtype=np.float32)
    scalars = numpy_to_vtk(flat, deep=True)
    image.GetPointData().SetScalars(scalars)
    return image


def write(array, path):
    io = mrgi.vtkMRGIImageIO()
    assert io.Write(from_numpy(array), path), io.GetLastErrorMessage()


def write_display(array, path, scale):
    """PNG for a person: linear values times `scale`, clamped."""
    write(np.clip(array[..., :3] * scale, 0.0, 1.0), path)


def folders(build, out):
    """What a fidelity benchmark writes with: the path of BUILD's
    mrgi-compare, OUT/images (the page's pictures) and BUILD's scratch
    folder Testing/Temporary, both created."""
    images = os.path.join(out, "images")
    scratch = os.path.join(build, "Testing", "Temporary")
    os.makedirs(images, exist_ok=True)
    os.makedirs(scratch, exist_ok=True)
    return os.path.join(build, "bin", "mrgi-compare"), images, scratch


def boxes(array, n=4):
    """Means of n x n pixel boxes of an H x W (x C) array: the 4 x 4 box
    averages the issues' relative RMS is taken over. Rows and columns past
    the last whole box are dropped."""
    h, w = array.shape[:2]
    cropped = array[: h - h % n, : w - w % n]
    return cropped.reshape((h // n, n, w // n, n) + array.shape[2:]).mean(axis=(1, 3))


def box_error(compare_tool, image, reference, scratch, name, diff_png=None):
    """Relative RMS (mrgi-compare) of the box averages of two H x W x 3+
    images, written as NAME-image.exr and NAME-ref.exr into `scratch`."""
    a = os.path.join(scratch, "%s-image.exr" % name)
    b = os.path.join(scratch, "%s-ref.exr" % name)
    write(boxes(image[..., :3]), a)
    write(boxes(reference[..., :3]), b)
    return compare(compare_tool, a, b, diff_png)["relative_rms"]


def compare(compare_tool, image_path, reference_path, diff_path=None, diff_scale=4.0):
    """Metrics from the C core (mrgi-compare): dict of floats."""
    command = [compare_tool, image_path, reference_path]
    if diff_path:
        command += ["--diff", diff_path, "--diff-scale", str(diff_scale)]
    out = subprocess.run(command, check=True, capture_output=True, text=True).stdout
    return {k: float(v) for k, v in (item.split("=") for item in out.split())}
