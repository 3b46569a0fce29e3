"""A "TV" showing a moving picture lights a room: a vtkMRGIAreaLight whose
texture is a vtkImageData updated every frame (as a video player would), in
the built-in living room, rendered headless through vtkMRGIPass. The TV's
screen shows each frame (the scene's screen actor shares the light's
emitter actor) and lights the room. Writes tv-0.png .. tv-2.png and prints
how much light reached the room per frame.

    PYTHONPATH=build/lib/python3/dist-packages /usr/bin/python3 Examples/Python/area_light_video.py
"""
import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkRenderingCore import vtkRenderer, vtkWindowToImageFilter
from vtkmodules.vtkRenderingOpenGL2 import vtkRenderStepsPass

import mrgi

WIDTH, HEIGHT = 64, 36  # the picture's pixels


def frame(t):
    """Frame t of a synthetic video: a colour wave drifting across the screen (rows bottom-up, RGB bytes)."""
    x = np.linspace(0.0, 1.0, WIDTH)[None, :]
    y = np.linspace(0.0, 1.0, HEIGHT)[:, None]
    phase = 2.0 * np.pi * (x + 0.35 * t) + 0.0 * y  # (HEIGHT, WIDTH)
    rgb = np.stack([0.5 + 0.5 * np.sin(phase), (0.5 + 0.5 * np.sin(phase + 2.1)) * (0.3 + 0.7 * y),
                    0.5 + 0.5 * np.cos(phase)], axis=-1)
    return (255.0 * np.clip(rgb, 0.0, 1.0)).astype(np.uint8).reshape(-1, 3)


def main():
    window = mrgi.vtkMRGIRenderWindowFactory.CreateHeadlessRenderWindow()
    if window is None:
        raise SystemExit("no headless OpenGL context on this machine")
    window.SetSize(480, 320)
    renderer = vtkRenderer()
    window.AddRenderer(renderer)
    builder = mrgi.vtkMRGISceneBuilder()
    builder.SetScene("living-room")
    if not builder.Build(renderer):
        raise SystemExit(builder.GetLastErrorMessage())

    # The scene's screen light, given our own picture instead of its test card.
    tv = builder.GetAreaLight(0)
    picture = vtkImageData()
    picture.SetDimensions(WIDTH, HEIGHT, 1)
    picture.GetPointData().SetScalars(numpy_to_vtk(frame(0), deep=True))
    tv.SetTextureData(picture)

    gi = mrgi.vtkMRGIPass()
    gi.SetDelegatePass(vtkRenderStepsPass())
    gi.AddAreaLight(tv)
    renderer.SetPass(gi)

    grab = vtkWindowToImageFilter()
    grab.SetInput(window)
    io = mrgi.vtkMRGIImageIO()
    for t in range(3):
        # A new frame: overwrite the pixels and mark the image modified; the
        # light rebuilds its samples and the screen's picture on the next
        # render, nothing else.
        scalars = picture.GetPointData().GetScalars()
        vtk_to_numpy(scalars)[:] = frame(t)
        scalars.Modified()
        picture.Modified()
        window.Render()
        light = vtkImageData()
        gi.GetAreaLightBuffer(window, light)
        mean = vtk_to_numpy(light.GetPointData().GetScalars()).reshape(-1, 3).mean(axis=0)
        grab.Modified()
        grab.Update()
        name = "tv-%d.png" % t
        if io.Write(grab.GetOutput(), name):
            print("frame %d: mean light (%.4f, %.4f, %.4f), sample builds %d; wrote %s"
                  % (t, mean[0], mean[1], mean[2], tv.GetNumberOfSampleBuilds(), name))


if __name__ == "__main__":
    main()
