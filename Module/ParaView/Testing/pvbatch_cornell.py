"""pvbatch: the Cornell box in an MRGI Render View, saved as a PNG.

usage: pvbatch pvbatch_cornell.py PLUGIN OUT.png [SIZE] [--gi off]
PLUGIN is MRGIRenderView.so. Works without an X server (the plugin then
supplies MRGI's EGL window). The settings match
`mrgi-render cornell --exposure 0 --aa off` (ParaView's view: fixed
exposure 0 EV, no FXAA).
"""
import os
import sys

from paraview.simple import CreateView, LoadPlugin, Render, SaveScreenshot

plugin, out = sys.argv[1], sys.argv[2]
size = int(sys.argv[3]) if len(sys.argv) > 3 and sys.argv[3].isdigit() else 256
LoadPlugin(plugin, remote=False)  # into paraview.simple
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from mrgi_paraview_scene import show_mrgi_scene  # noqa: E402

view = CreateView("MRGIRenderView")
view.ViewSize = [size, size]
view.UseFXAA = 0
if "--gi" in sys.argv and sys.argv[sys.argv.index("--gi") + 1] == "off":
    view.GlobalIllumination = 0
show_mrgi_scene(view, "cornell")
Render(view)
SaveScreenshot(out, view, ImageResolution=[size, size])
if not os.path.isfile(out):
    raise SystemExit("pvbatch_cornell: no screenshot written to " + out)
print("pvbatch_cornell: wrote", out)
