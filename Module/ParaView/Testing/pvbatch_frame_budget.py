"""pvbatch: the MRGI Render View's frame budget.

usage: pvbatch pvbatch_frame_budget.py PLUGIN OUT_DIR
(with XDG_CACHE_HOME set: the calibration is written under it.)

Renders the Cornell box at 128 x 128 with the view's own settings (64 VPLs,
RSM 128): before.png. Calibrate Frame Budget must write the calibration
file and give the view its settings back (calibrated.png); a generous Frame
Budget must hand the settings to the tuner, which reports a measured
calibration and another VPL count (budget.png); Frame Budget 0 must bring
the view's settings back (after.png); an Error Budget must do the same.
scripts/check-paraview-plugin.sh compares the images.
"""
import os
import re
import sys

from paraview import simple

plugin, out = sys.argv[1:3]
simple.LoadPlugin(plugin, remote=False)
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from mrgi_paraview_scene import show_mrgi_scene  # noqa: E402

VPLS = 64


def fail(why):
    raise SystemExit("pvbatch_frame_budget: " + why)


def setting(view):
    view.UpdatePropertyInformation()
    return view.SMProxy.GetProperty("FrameBudgetSetting").GetElement(0)


def save(view, name, frames=1):
    for _ in range(frames):
        simple.Render(view)
    simple.SaveScreenshot(os.path.join(out, name), view, ImageResolution=[128, 128])


view = simple.CreateView("MRGIRenderView")
view.ViewSize = [128, 128]
view.UseFXAA = 0
view.NumberOfVPLs = VPLS
view.RSMResolution = 128
show_mrgi_scene(view, "cornell")
save(view, "before.png")
if setting(view) != "off":
    fail("without a budget the setting reads %r, not 'off'" % setting(view))

cache = os.path.join(os.environ["XDG_CACHE_HOME"], "mrgi")
view.SMProxy.InvokeCommand("CalibrateFrameBudget")
written = [f for f in os.listdir(cache) if f.startswith("frame-budget-")] if os.path.isdir(cache) else []
if len(written) != 1:
    fail("calibration files in %s: %s (expected one)" % (cache, written))
save(view, "calibrated.png")

view.FrameBudget = 10000.0
save(view, "budget.png", frames=4)
chosen = setting(view)
print("pvbatch_frame_budget: budget 10 s:", chosen)
match = re.search(r"vpls (\d+)", chosen)
if not match or "calibration: measured" not in chosen:
    fail("the tuner's setting %r names no VPL count or no measured calibration" % chosen)
if int(match.group(1)) == VPLS:
    fail("a 10 s budget kept the view's %d VPLs" % VPLS)

view.FrameBudget = 0.0
save(view, "after.png")
if setting(view) != "off":
    fail("budget 0 still reads %r" % setting(view))

view.ErrorBudget = 0.5
save(view, "error-budget.png", frames=2)
chosen = setting(view)
print("pvbatch_frame_budget: error budget 0.5:", chosen)
if "frame budget: error 0.5" not in chosen:
    fail("the error budget's setting reads %r" % chosen)
view.ErrorBudget = 0.0
save(view, "error-after.png")
print("pvbatch_frame_budget: ok")
