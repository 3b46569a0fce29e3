"""Still-render times of the Cornell box through vtkMRGIPass in a plain VTK window.

The counterpart of paraview_gui_cornell.py's timing (issue 16's target: the
GUI's frame time within 1.2x of this): the same scene from the same
vtkMRGISceneBuilder, 512 x 512, fixed exposure 0 EV, no FXAA, and the same
loop: a 2-degree azimuth change, alternating, then Render() and a wait until
the GL has drawn the frame. Prints the wall and CPU time of each frame (ms),
then their medians.

    PYTHONPATH=build/lib/python3/dist-packages /usr/bin/python3 \\
        Module/ParaView/Testing/vtk_cornell_frames.py [--frames N] [--window x|headless] [--gi off]

--window x (default) opens VTK's own X window (run it under xvfb-run, as the
GUI); headless uses MRGI's EGL window (no X server needed). --gi off renders
without vtkMRGIPass (VTK's own passes: the counterpart of the view with
Global Illumination off).
"""
import argparse
import time

from vtkmodules.vtkRenderingCore import vtkRenderer, vtkRenderWindow
from vtkmodules.vtkRenderingOpenGL2 import vtkRenderStepsPass

import mrgi


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--frames", type=int, default=20)
    parser.add_argument("--size", type=int, default=512)
    parser.add_argument("--window", choices=("x", "headless"), default="x")
    parser.add_argument("--gi", choices=("on", "off"), default="on")
    args = parser.parse_args()
    if args.frames < 1:
        parser.error("--frames must be at least 1")

    if args.window == "headless":
        window = mrgi.vtkMRGIRenderWindowFactory.CreateHeadlessRenderWindow()
        if window is None:
            raise SystemExit("vtk_cornell_frames: no headless OpenGL context on this machine")
    else:
        window = vtkRenderWindow()
    window.SetSize(args.size, args.size)
    window.SetMultiSamples(0)  # MRGI's buffers are single-sample (as ParaView's views)
    renderer = vtkRenderer()
    window.AddRenderer(renderer)
    builder = mrgi.vtkMRGISceneBuilder()
    builder.SetScene("cornell")
    if not builder.Build(renderer):
        raise SystemExit("vtk_cornell_frames: " + builder.GetLastErrorMessage())
    gi = mrgi.vtkMRGIPass()
    gi.SetDelegatePass(vtkRenderStepsPass())
    gi.SetAutoExposure(False)
    gi.SetExposure(0.0)
    if args.gi == "on":
        renderer.SetPass(gi)

    def render_finished():
        window.Render()
        window.WaitForCompletion()

    render_finished()  # first frame: buffers and shaders
    camera = renderer.GetActiveCamera()
    # Wall time, and the CPU time of the whole process (llvmpipe's threads
    # included), as paraview_gui_cornell.py measures them.
    wall, cpu = [], []
    for i in range(args.frames):
        camera.Azimuth(2.0 if i % 2 == 0 else -2.0)
        start, start_cpu = time.perf_counter(), time.process_time()
        render_finished()
        wall.append((time.perf_counter() - start) * 1e3)
        cpu.append((time.process_time() - start_cpu) * 1e3)
    print("# wall_ms cpu_ms, %dx%d, %s" % (args.size, args.size, window.GetClassName()))
    for pair in zip(wall, cpu):
        print("%.3f %.3f" % pair)
    half = args.frames // 2
    print("median %.3f ms wall, %.3f ms CPU" % (sorted(wall)[half], sorted(cpu)[half]))
    renderer.SetPass(None)
    gi.ReleaseGraphicsResources(window)


if __name__ == "__main__":
    main()
