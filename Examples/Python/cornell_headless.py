"""Render the Cornell box headless through vtkMRGIPass and write cornell.exr
(HDR) and cornell.png, printing the GPU time of each stage.

    PYTHONPATH=build/lib/python3/dist-packages /usr/bin/python3 Examples/Python/cornell_headless.py
"""
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkRenderingCore import vtkRenderer, vtkWindowToImageFilter
from vtkmodules.vtkRenderingOpenGL2 import vtkRenderStepsPass

import mrgi


def main():
    window = mrgi.vtkMRGIRenderWindowFactory.CreateHeadlessRenderWindow()
    if window is None:
        raise SystemExit("no headless OpenGL context on this machine")
    window.SetSize(512, 512)
    renderer = vtkRenderer()
    window.AddRenderer(renderer)

    builder = mrgi.vtkMRGISceneBuilder()
    builder.SetScene("cornell")
    if not builder.Build(renderer):
        raise SystemExit(builder.GetLastErrorMessage())

    gi = mrgi.vtkMRGIPass()
    gi.SetDelegatePass(vtkRenderStepsPass())
    gi.SetStageTimingEnabled(True)
    renderer.SetPass(gi)
    window.GetRenderTimer().SetLoggingEnabled(True)
    window.Render()

    for i in range(gi.FetchStageTimings(window, True)):
        print("%-12s %8.3f ms" % (gi.GetStageName(i), gi.GetStageTimeMilliseconds(i)))

    io = mrgi.vtkMRGIImageIO()
    hdr = vtkImageData()
    if gi.GetColorBuffer(window, hdr) and io.Write(hdr, "cornell.exr"):
        print("wrote cornell.exr")
    grab = vtkWindowToImageFilter()
    grab.SetInput(window)
    grab.Update()
    if io.Write(grab.GetOutput(), "cornell.png"):
        print("wrote cornell.png")
    renderer.SetPass(None)
    gi.ReleaseGraphicsResources(window)


if __name__ == "__main__":
    main()
