"""ParaView GUI script: the Cornell box in an MRGI Render View (issue 16, part 6).

Run by scripts/check-paraview-gui.sh as `paraview --script=THIS_FILE`, with
the plugin loaded on the command line (`--plugin-search-paths=DIR
--plugins=MRGIRenderView`).
`paraview --script` passes no arguments, so the settings come from the
environment:

  MRGI_GUI_OUT         folder for the results (required)
  MRGI_GUI_SCRIPT_DIR  this file's folder (mrgi_paraview_scene.py)
  MRGI_GUI_SIZE        side of the compared screenshots, pixels (default 256)
  MRGI_GUI_FRAMES      still renders timed at 512 x 512 (default 20; 0: none)
  MRGI_GUI_GRAB        file name: keep the GUI open, copy Xvfb's screen
                       (MRGI_GUI_XWD, the -fbdir file) into it once Qt has
                       painted the window, then exit (the docs' screenshots)

Replaces the layout's render view by an MRGI Render View, shows the Cornell
box as mrgi-render draws it (mrgi_paraview_scene.show_mrgi_scene), and writes

  gui-gi-on.png, gui-gi-off.png  the view at SIZE x SIZE, GI on and off
  gui-frames.txt                 one still-render time per line, ms
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
    # The GUI's stdout is a pipe to the shell script: flush each line, so
    # that a hang shows how far the script came.
    print("paraview_gui_cornell: " + message, flush=True)


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
        raise RuntimeError("the MRGI plugin is not loaded (paraview --plugin-search-paths=DIR --plugins=MRGIRenderView)")
    # `paraview --script` defines no __file__: the shell script names the folder.
    sys.path.insert(0, os.environ.get("MRGI_GUI_SCRIPT_DIR", "."))
    from mrgi_paraview_scene import show_mrgi_scene

    size = int(os.environ.get("MRGI_GUI_SIZE", "256"))
    frames = int(os.environ.get("MRGI_GUI_FRAMES", "20"))

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
    layout.PreviewMode = [size, size]
    simple.Render(view)
    for gi, name in ((1, "gui-gi-on.png"), (0, "gui-gi-off.png")):
        view.GlobalIllumination = gi
        simple.Render(view)
        path = os.path.join(OUT, name)
        simple.SaveScreenshot(path, view, ImageResolution=[size, size])
        if not os.path.isfile(path):
            raise RuntimeError("SaveScreenshot wrote no " + path)
        log("wrote " + path)
    view.GlobalIllumination = 1

    if frames > 0:
        # Still renders at 512 x 512: each after a camera change (a small
        # azimuth, alternating, so the box stays in view), so that every
        # frame is really drawn again. Times only; nothing asserts them.
        layout.PreviewMode = [512, 512]
        render_finished(view, simple)  # first frame: buffers and shaders
        camera = simple.GetActiveCamera()
        times = []
        for i in range(frames):
            camera.Azimuth(2.0 if i % 2 == 0 else -2.0)
            start = time.perf_counter()
            render_finished(view, simple)
            times.append((time.perf_counter() - start) * 1e3)
        with open(os.path.join(OUT, "gui-frames.txt"), "w") as f:
            f.write("".join("%.3f\n" % t for t in times))
        times.sort()
        log("%d still renders at 512x512, median %.1f ms" % (frames, times[len(times) // 2]))

    layout.PreviewMode = [0, 0]
    # The properties panel shows the view's properties (the "Global
    # Illumination" group) when no source is selected.
    simple.SetActiveSource(None)
    simple.Render(view)
    return view


def grab_when_painted(view, target):
    """Copies Xvfb's screen to `target` once Qt has painted, then exits."""
    import shutil

    xwd = os.environ.get("MRGI_GUI_XWD", "")
    interactor = view.GetInteractor()
    ticks = {"count": 0}

    def tick(caller, event):
        ticks["count"] += 1
        # A few rounds of the event loop (0.5 s each) lay out and paint
        # the panels that the script changed.
        if ticks["count"] < 4:
            return
        try:
            shutil.copyfile(xwd, target)
            log("copied the screen to " + target)
        except OSError as error:
            log("no screen grab: %s" % error)
        # No Qt binding in ParaView's Python to quit the application: end
        # the process (only the screenshot tool does this; the test exits
        # through `paraview --exit`).
        sys.stdout.flush()
        os._exit(0)

    interactor.AddObserver("TimerEvent", tick)
    interactor.CreateRepeatingTimer(500)


def main():
    if not OUT or not os.path.isdir(OUT):
        log("MRGI_GUI_OUT must name an existing folder (got %r)" % OUT)
        return
    try:
        view = run()
        with open(STATUS, "w") as f:
            f.write("ok\n")
        grab = os.environ.get("MRGI_GUI_GRAB", "")
        if grab:
            grab_when_painted(view, grab)
    except Exception:  # noqa: BLE001 -- every failure must reach the status file
        text = traceback.format_exc()
        log(text)
        with open(STATUS, "w") as f:
            f.write("error\n" + text)


main()
