"""vtkMRGIAreaLight from Python: a numpy-made vtkImageData as the texture,
samples as a float array (3 RGBA texels per sample), the cache, the next
video frame, bad input reported (no exception, False, a message), the
emitter actor (textured with the light's picture, shareable)."""
import math
import sys

import numpy as np
from vtkmodules.vtkCommonCore import vtkCommand, vtkFloatArray
from vtkmodules.vtkCommonDataModel import vtkImageData, vtkPolyData
from vtkmodules.vtkRenderingCore import vtkActor, vtkRenderer, vtkTexture
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy

import mrgi


def check(condition, what):
    if not condition:
        print("check failed:", what, file=sys.stderr)
        sys.exit(1)


def image_from_numpy(pixels):
    """A vtkImageData of an (H, W, C) array whose row 0 is the picture's
    bottom (VTK's row order)."""
    height, width, components = pixels.shape
    image = vtkImageData()
    image.SetDimensions(width, height, 1)
    scalars = numpy_to_vtk(np.ascontiguousarray(pixels).reshape(-1, components), deep=True)
    scalars.SetName("pixels")
    image.GetPointData().SetScalars(scalars)
    return image


def samples_of(light):
    array = vtkFloatArray()
    check(light.GetSamples(array), "samples: " + light.GetLastErrorMessage())
    check(array.GetNumberOfComponents() == 4, "RGBA texels")
    records = vtk_to_numpy(array).reshape(-1, 3, 4).copy()  # sample, texel, rgba
    check(bool(np.isfinite(records).all()), "finite samples")
    return records


def main():
    light = mrgi.vtkMRGIAreaLight()
    check(light.GetNumberOfSamples() == 256, "256 samples by default")
    light.SetCenter(0.0, 1.0, 0.0)
    light.SetEdgeU(2.0, 0.0, 0.0)
    light.SetEdgeV(0.0, 0.0, 2.0)  # u x v = -y: a ceiling light shining down
    light.SetColor(1.0, 0.9, 0.8)
    light.SetIntensity(2.0)

    records = samples_of(light)
    check(records.shape == (256, 3, 4), "a 16 x 16 grid, got %s" % (records.shape,))
    check(np.allclose(records[:, 1, :3], [0.0, -1.0, 0.0]), "normal is u x v")
    check(abs(records[:, 0, 3].sum() - 4.0) < 1e-4, "cell areas sum to the light's area")
    check(np.allclose(records[:, 2, :3], [2.0, 1.8, 1.6]), "radiance = Intensity * Color")
    check(np.allclose(records[:, 0, 1], 1.0), "samples lie in the light's plane")

    # A numpy texture: left half red, right half blue (VTK rows, bottom first).
    pixels = np.zeros((32, 64, 3), dtype=np.uint8)
    pixels[:, :32, 0] = 255
    pixels[:, 32:, 2] = 255
    image = image_from_numpy(pixels)
    light.SetTextureData(image)
    light.SetColor(1.0, 1.0, 1.0)
    light.SetIntensity(1.0)
    textured = samples_of(light)
    left = textured[:, 0, 0] < -0.5  # s < 1/4: well inside the red half
    right = textured[:, 0, 0] > 0.5
    check(np.allclose(textured[left, 2, :3], [1.0, 0.0, 0.0], atol=1e-6), "red on the left")
    check(np.allclose(textured[right, 2, :3], [0.0, 0.0, 1.0], atol=1e-6), "blue on the right")
    builds = (light.GetNumberOfTextureBuilds(), light.GetNumberOfSampleBuilds())
    check(builds[0] == 1, "one pyramid build")

    # Unchanged: from the cache.
    samples_of(light)
    check((light.GetNumberOfTextureBuilds(), light.GetNumberOfSampleBuilds()) == builds,
          "unchanged inputs reuse the cache")

    # The next video frame: a new picture in the same image, Modified().
    frame = vtk_to_numpy(image.GetPointData().GetScalars())
    frame[:] = 0
    frame[:, 1] = 255  # all green
    image.Modified()
    green = samples_of(light)
    check(np.allclose(green[:, 2, :3], [0.0, 1.0, 0.0], atol=1e-6), "the next frame is green")
    check(light.GetNumberOfTextureBuilds() == builds[0] + 1, "pyramid rebuilt once")
    check(light.GetNumberOfSampleBuilds() == builds[1] + 1, "samples rebuilt once")

    # An HDR float texture through a vtkTexture.
    hdr = image_from_numpy(np.full((4, 4, 3), 5.0, dtype=np.float32))
    texture = vtkTexture()
    texture.SetInputData(hdr)
    light.SetTexture(texture)
    check(light.GetTextureData() is None, "the last texture set wins")
    check(np.allclose(samples_of(light)[:, 2, :3], 5.0), "float texels are radiance")

    # Bad input: an error event, False, the array left alone, a message.
    errors = []
    light.AddObserver(vtkCommand.ErrorEvent, lambda obj, event: errors.append(event))
    light.SetTextureData(image_from_numpy(np.zeros((4, 4, 3), dtype=np.float64)))
    array = vtkFloatArray()
    check(not light.GetSamples(array), "a double texture is refused")
    check(array.GetNumberOfTuples() == 0, "output untouched")
    check("double" in light.GetLastErrorMessage(), "the message names the type")
    check(len(errors) == 1, "one error event")
    light.SetTextureData(None)
    light.SetEdgeV(float("nan"), 0.0, 0.0)
    check(not light.GetSamples(array), "a NaN edge is refused")
    check("EdgeV" in light.GetLastErrorMessage(), "the message names EdgeV")
    light.SetEdgeV(0.0, 0.0, 2.0)
    light.SetIntensity(-1.0)
    check(not light.GetSamples(array), "a negative intensity is refused")
    check("Intensity" in light.GetLastErrorMessage(), "the message names Intensity")
    light.SetIntensity(1.0)
    check(light.GetSamples(array), "fixed input works again")
    check(all(math.isfinite(v) for v in vtk_to_numpy(array).ravel()), "no NaN")

    # The emitter geometry.
    quad = vtkPolyData()
    check(light.MakeGeometry(quad), "geometry")
    check(quad.GetNumberOfPoints() == 4 and quad.GetNumberOfPolys() == 1, "one quad")
    actor = light.GetGeometryActor()
    check(actor is not None and actor.GetVisibility() == 1, "a visible actor")
    check(actor.GetTexture() is None, "untextured: a plain colour")
    check(actor.GetProperty().GetLighting() == 0, "the emitter is unlit")
    light.SetTextureData(image)
    check(actor.GetTexture() is not None, "textured: the light's picture")
    view = vtkActor()
    light.ShareGeometryActor(view)
    check(view.GetMapper() is not None and view.GetProperty() is actor.GetProperty()
          and view.GetTexture() is actor.GetTexture(),
          "a shared view draws the same quad and picture")
    light.VisibleOff()
    check(actor.GetVisibility() == 0, "Visible drives the actor")
    check(view.GetVisibility() == 1, "a shared view keeps its own visibility")
    light.SetTextureData(None)
    check(actor.GetTexture() is None and view.GetTexture() is None, "the view follows the light")

    # The living room's screen (the scene's own emitter actor) shows its
    # light's picture: it shares the light's emitter actor, while the
    # light's own actor stays hidden (Visible off).
    renderer = vtkRenderer()
    builder = mrgi.vtkMRGISceneBuilder()
    builder.SetScene("living-room")
    check(builder.Build(renderer), builder.GetLastErrorMessage())
    tv = builder.GetAreaLight(0)
    emitter = tv.GetGeometryActor()
    actors = renderer.GetActors()
    actors.InitTraversal()
    screens = [a for a in (actors.GetNextActor() for _ in range(actors.GetNumberOfItems()))
               if a.GetProperty() is emitter.GetProperty()]
    check(len(screens) == 1, "one scene actor draws the TV's emitter, got %d" % len(screens))
    check(screens[0].GetTexture() is not None and screens[0].GetTexture() is emitter.GetTexture(),
          "the screen shows the light's picture")
    check(screens[0].GetVisibility() == 1 and not tv.GetVisible(), "the screen is drawn once")
    del builder, tv, emitter  # the screen keeps its light (and picture) alive
    screens[0].GetMapper().Update()
    check(screens[0].GetMapper().GetInput().GetNumberOfPolys() == 1,
          "the screen outlives the builder")
    print("area light from Python: ok")


if __name__ == "__main__":
    main()
