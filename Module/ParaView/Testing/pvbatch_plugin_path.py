"""pvbatch with the plugin loaded through PV_PLUGIN_PATH, no LoadPlugin().

usage: PV_PLUGIN_PATH=DIR pvbatch pvbatch_plugin_path.py OUT.png
"""
import sys

from paraview import simple
view = simple.CreateView("MRGIRenderView")
view.ViewSize = [64, 64]
simple.Show(simple.Sphere(), view)
simple.Render(view)
simple.SaveScreenshot(sys.argv[1], view, ImageResolution=[64, 64])
print("envload ok")
