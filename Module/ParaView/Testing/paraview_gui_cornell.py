"""ParaView GUI script: the Cornell box in an MRGI Render View (issue 16, part 6).

Run by scripts/check-paraview-gui.sh as `paraview --script=THIS_FILE`, with
the plugin loaded on the command line (`--plugin-search-paths=DIR
--plugins=MRGIRenderView`).
`paraview --script` passes no arguments, so the settings come from the
environment:

  MRGI_GUI_OUT         folder for the results (required)
  MRGI_GUI_SCRIPT_DIR  this file's folder (mrgi_paraview_scene.py)
  MRGI_GUI_SIZE        side of the compared screenshots, pixels (default 256)
  MRGI_GUI_FRAMES      still renders to time (default 20; 0: none)
  MRGI_GUI_TIMING_SIZE their size, side in pixels (default 512)
  MRGI_GUI_TIMING_GI   on (default) or off: time with Global Illumination off
  MRGI_GUI_GRAB        file name: at the end, copy Xvfb's screen (MRGI_GUI_XWD,
                       the -fbdir file) into it once Qt has painted the
                       window (the docs' screenshots)

Replaces the layout's render view by an MRGI Render View, shows the Cornell
box as mrgi-render draws it (mrgi_paraview_scene.show_mrgi_scene), and writes

  gui-gi-on.png, gui-gi-off.png  the view at SIZE x SIZE, GI on and off
  gui-frames.txt                 per still render: wall and CPU time, ms
  gui-status.txt                 "ok", or "error" and the traceback

The shell script reads gui-status.txt: an exception inside `paraview
--script` is printed but does not change paraview's exit status.
"""
import os
import sys
import time
import traceback

OUT = os.environ.get("MRGI_GUI_OUT", "")
STATUS = os.path.join(OUT, "gui-status.txt")


def log(message):
    # The GUI's stdout goes to the shell script's log: flush each line, so
    # that a hang shows how far the script came.
    print("paraview_gui_cornell: " + message, flush=True)


def qt_process_events(seconds):
    """Runs Qt's event loop for `seconds`: layout changes and painting.

    `paraview --script` runs the script from one Qt event, and ParaView's
    Python has no Qt binding: a layout change (preview mode) would reach
    the widgets only after the script. QCoreApplication::processEvents(flags,
    maxtime) is a static function of the Qt 5 the GUI already loaded;
    ctypes calls it (QFlags is passed as its int).
    """
    import ctypes

    try:
        qt = ctypes.CDLL("libQt5Core.so.5")
        process = qt._ZN16QCoreApplication13processEventsE6QFlagsIN10QEventLoop17ProcessEventsFlagEEi
    except (OSError, AttributeError) as error:
        raise RuntimeError("cannot reach Qt 5's processEvents (%s): "
                           "is this ParaView built with Qt 5?" % error)
    process.argtypes = [ctypes.c_int, ctypes.c_int]
    process.restype = None
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        process(0, 50)  # QEventLoop::AllEvents, at most 50 ms
        time.sleep(0.01)


def set_view_size(view, layout, size, simple):
    """Gives the view widget size x size pixels (preview mode) and checks it."""
    layout.PreviewMode = [size, size]
    qt_process_events(1.0)
    simple.Render(view)
    actual = list(view.GetRenderWindow().GetSize())
    if actual != [size, size]:
        raise RuntimeError("the view is %dx%d, not %dx%d: the GUI's layout has no room "
                           "for it (ask for a smaller size)" % (actual[0], actual[1], size, size))


def render_finished(view, simple):
    """Renders `view` and waits until the GL has drawn the frame."""
    simple.Render(view)
    window = view.GetRenderWindow()
    # llvmpipe (and a GPU) queue the frame's commands; without the wait a
    # frame's time would be only the time to submit it.
    window.MakeCurrent()
    window.WaitForCompletion()


def run():
    from paraview import simple

    if not hasattr(simple, "MRGIScene"):
        raise RuntimeError("the MRGI plugin is not loaded "
                           "(paraview --plugin-search-paths=DIR --plugins=MRGIRenderView)")
    # `paraview --script` defines no __file__: the shell script names the folder.
    sys.path.insert(0, os.environ.get("MRGI_GUI_SCRIPT_DIR", "."))
    from mrgi_paraview_scene import show_mrgi_scene

    size = int(os.environ.get("MRGI_GUI_SIZE", "256"))
    frames = int(os.environ.get("MRGI_GUI_FRAMES", "20"))
    timing_size = int(os.environ.get("MRGI_GUI_TIMING_SIZE", "512"))

    # The GUI starts with one layout holding a render view: put an MRGI
    # Render View in its place, as View > "MRGI Render View" would.
    layout = simple.GetLayout()
    old = simple.GetActiveView()
    if old is not None:
        simple.Delete(old)
    view = simple.CreateView("MRGIRenderView")
    simple.AssignViewToLayout(view=view, layout=layout, hint=0)
    simple.SetActiveView(view)
    if view.GetXMLName() != "MRGIRenderView":
        raise RuntimeError("CreateView made a %s, not an MRGIRenderView" % view.GetXMLName())
    view.UseFXAA = 0  # as `mrgi-render --aa off`
    show_mrgi_scene(view, "cornell")
    log("MRGI Render View with the Cornell box")

    # Preview mode gives the view widget exactly this size, so that the
    # screenshot is the view's own pixels, not a resized copy.
    set_view_size(view, layout, size, simple)
    for gi, name in ((1, "gui-gi-on.png"), (0, "gui-gi-off.png")):
        view.GlobalIllumination = gi
        simple.Render(view)
        path = os.path.join(OUT, name)
        simple.SaveScreenshot(path, view, ImageResolution=[size, size])
        if not os.path.isfile(path):
            raise RuntimeError("SaveScreenshot wrote no " + path)
        log("wrote " + path)
    view.GlobalIllumination = 0 if os.environ.get("MRGI_GUI_TIMING_GI", "on") == "off" else 1

    if frames > 0:
        # Still renders at TIMING_SIZE: each after a camera change (a small
        # azimuth, alternating, so the box stays in view), so that every
        # frame is really drawn again. Times only; nothing asserts them.
        set_view_size(view, layout, timing_size, simple)
        render_finished(view, simple)  # first frame: buffers and shaders
        camera = simple.GetActiveCamera()
        # Wall time, and the CPU time of the whole process (llvmpipe's
        # threads included): on a shared machine the wall time depends on
        # the other jobs, the CPU time much less.
        wall, cpu = [], []
        for i in range(frames):
            camera.Azimuth(2.0 if i % 2 == 0 else -2.0)
            start, start_cpu = time.perf_counter(), time.process_time()
            render_finished(view, simple)
            wall.append((time.perf_counter() - start) * 1e3)
            cpu.append((time.process_time() - start_cpu) * 1e3)
        with open(os.path.join(OUT, "gui-frames.txt"), "w") as f:
            f.write("# wall_ms cpu_ms, %dx%d\n" % (timing_size, timing_size))
            f.write("".join("%.3f %.3f\n" % pair for pair in zip(wall, cpu)))
        log("%d still renders at %dx%d, median %.1f ms wall, %.1f ms CPU" % (
            frames, timing_size, timing_size, sorted(wall)[frames // 2], sorted(cpu)[frames // 2]))

    layout.PreviewMode = [0, 0]
    # With no source selected the properties panel shows only the view's
    # section (ParaView's properties, then the "Global Illumination" group).
    simple.SetActiveSource(None)
    simple.Render(view)

    grab = os.environ.get("MRGI_GUI_GRAB", "")
    if grab:
        # Xvfb keeps its screen in a file (-fbdir): copy it once Qt has laid
        # out and painted the window as the script left it.
        import shutil

        qt_process_events(2.0)
        simple.Render(view)
        qt_process_events(1.0)
        shutil.copyfile(os.environ.get("MRGI_GUI_XWD", ""), grab)
        log("copied the screen to " + grab)


def main():
    if not OUT or not os.path.isdir(OUT):
        log("MRGI_GUI_OUT must name an existing folder (got %r)" % OUT)
        return
    try:
        run()
        with open(STATUS, "w") as f:
            f.write("ok\n")
    except Exception:  # noqa: BLE001 -- every failure must reach the status file
        text = traceback.format_exc()
        log(text)
        with open(STATUS, "w") as f:
            f.write("error\n" + text)


main()
