"""pvbatch: MRGI Render View properties survive a state file.

usage: pvbatch pvbatch_state.py PLUGIN save STATE.pvsm OUT.png
       pvbatch pvbatch_state.py PLUGIN load STATE.pvsm OUT.png
`save` sets non-default view properties, renders the Cornell box and
saves the state; `load` loads it in a fresh process, checks every property
came back, and renders again (the two images must be equal).
"""
import os
import sys

from paraview import simple

plugin, mode, state, out = sys.argv[1:5]
simple.LoadPlugin(plugin, remote=False)
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from mrgi_paraview_scene import show_mrgi_scene  # noqa: E402

EXPECTED = {
    "IndirectMode": 1,
    "NumberOfVPLs": 64,
    "RSMResolution": 128,
    "IndirectStrength": 1.5,
    "MRGIExposure": 0.5,
    "MultiresolutionPreset": 2,
    # Both non-default: BRSM's selection and ISM shadows must come back and
    # render the same first frame in the fresh process.
    "VPLSelectionMode": 4,
    "IndirectVisibility": 1,
    # The Area Lights group (cornell has no area light: only their return
    # is checked, the images do not depend on them).
    "AreaLightVisibility": 1,
    "AreaLightVoxelSlices": 512,
    "AreaLightVoxelSide": 96,
}

if mode == "save":
    view = simple.CreateView("MRGIRenderView")
    view.ViewSize = [128, 128]
    view.UseFXAA = 0
    for name, value in EXPECTED.items():
        setattr(view, name, value)
    show_mrgi_scene(view, "cornell")
    simple.Render(view)
    simple.SaveScreenshot(out, view, ImageResolution=[128, 128])
    simple.SaveState(state)
elif mode == "load":
    simple.LoadState(state)
    views = [v for v in simple.GetViews() if v.GetXMLName() == "MRGIRenderView"]
    if len(views) != 1:
        raise SystemExit("pvbatch_state: expected one MRGIRenderView in %s, found %d" % (state, len(views)))
    view = views[0]
    wrong = []
    for name, value in EXPECTED.items():
        got = view.SMProxy.GetProperty(name).GetElement(0)  # raw value, enums too
        if abs(float(got) - float(value)) > 1e-9:
            wrong.append("%s=%s (saved %s)" % (name, got, value))
    if wrong:
        raise SystemExit("pvbatch_state: properties not restored: " + ", ".join(wrong))
    # The state holds the camera; paraview.simple would reset it at this
    # view's first render in this process.
    simple._DisableFirstRenderCameraReset()
    view.ViewSize = [128, 128]  # a window size, not part of the scene's state
    # ParaView 5.11 comes back from LoadState with FXAA on whatever was saved
    # (measured); it is ParaView's property, not MRGI's.
    view.UseFXAA = 0
    simple.Render(view)
    simple.SaveScreenshot(out, view, ImageResolution=[128, 128])
else:
    raise SystemExit("pvbatch_state: mode must be save or load, not " + mode)
print("pvbatch_state:", mode, "ok")
