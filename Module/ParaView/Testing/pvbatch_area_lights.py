"""pvbatch: MRGI Area Lights in an MRGI Render View.

usage: pvbatch pvbatch_area_lights.py PLUGIN OUT_DIR [SIZE]
       pvbatch pvbatch_area_lights.py PLUGIN OUT_DIR [SIZE] --checks

Writes to OUT_DIR (PNG, SIZE x SIZE, default 256):
- area.png: the Cornell box of `mrgi-render cornell-area` (its meshes and
  its intensity-0 scene light, from the MRGIScene source) lit by an "MRGI
  Area Light" with the parameters of the scene's area light (the MRGIScene
  source's AreaLightParameters), to compare with
  `mrgi-render cornell-area --exposure 0 --aa off`; the scene's emitter
  mesh is hidden: the light's rectangle, shown self-luminous, stands for it;
- voxels.png: the view's AreaLightVoxelSlices 512 and AreaLightVoxelSide
  64 (a coarser voxel buffer than the automatic one);
- unshadowed.png: the same with AreaLightVisibility off (no shadows);
- moved.png: the light's display moved 150 down (Position): the light
  moves with its rectangle;
- hidden.png: the same with the light hidden (no area light: dark);
- textured.png: the same rectangle as an "MRGI Textured Area Light" whose
  picture is ParaView's Wavelet source (21 x 21, values divided by their
  maximum through the Intensity);
- reloaded.png: after the untextured light was shown again beside the
  textured one (two lights) and the textured one deleted (the view drops
  and re-adds lights).
Asserts the view's NumberOfAreaLights after each render, and that a render
of unchanged data does not read the light again (NumberOfAreaLightUpdates).
With --checks it checks the light's output against its contract (corners,
radiance, display colours, the field array, a 3D and an x-z picture), then
shows a light whose edges are parallel, then a textured light whose
picture has negative values, and asserts that the view uses no light for
either (the errors are expected in the log; the caller checks them).
"""
import os
import re
import sys

from paraview import simple

plugin, out_dir = sys.argv[1], sys.argv[2]
size = int(sys.argv[3]) if len(sys.argv) > 3 and sys.argv[3].isdigit() else 256
simple.LoadPlugin(plugin, remote=False)  # into paraview.simple
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from mrgi_paraview_scene import (  # noqa: E402
    scene_area_lights, show_area_light, show_mrgi_scene, view_area_light_count,
    view_area_light_updates, view_information)


def check_count(view, expected, when):
    count = view_area_light_count(view)
    if count != expected:
        raise SystemExit("pvbatch_area_lights: %s: the view used %d area lights, expected %d"
                         % (when, count, expected))
    print("pvbatch_area_lights: %s: %d area light(s)" % (when, count))


def save(view, name):
    simple.Render(view)
    path = os.path.join(out_dir, name)
    simple.SaveScreenshot(path, view, ImageResolution=[size, size])
    if not os.path.isfile(path):
        raise SystemExit("pvbatch_area_lights: no screenshot written to " + path)
    print("pvbatch_area_lights: wrote", path)


view = simple.CreateView("MRGIRenderView")
view.ViewSize = [size, size]
view.UseFXAA = 0
sources = show_mrgi_scene(view, "cornell-area")
# The light's rectangle stands for the scene's emitter mesh (the same
# rectangle): hidden, so that what the image shows of the emitter is the
# MRGI Area Light's own display.
emitters = [s for s in sources if max(s.FieldData["Emission"].GetRange(c)[1] for c in range(3)) > 0]
if len(emitters) != 1:
    raise SystemExit("pvbatch_area_lights: cornell-area has %d emitter meshes, expected 1"
                     % len(emitters))
simple.Hide(emitters[0], view)
params = scene_area_lights("cornell-area")
if len(params) != 1:
    raise SystemExit("pvbatch_area_lights: cornell-area has %d area lights, expected 1"
                     % len(params))
params = params[0]

def check_layout():
    """The light's output against its contract (vtkMRGIAreaLightSource.h)."""
    from paraview import servermanager

    def fail(why):
        raise SystemExit("pvbatch_area_lights: layout: " + why)

    # Untextured: one quad, corners -u-v, +u-v, +u+v, -u+v around the centre.
    c, u, v = [1.0, 2.0, 3.0], [2.0, 0.0, 0.0], [0.0, 0.0, -4.0]
    quad = simple.MRGIAreaLight(Center=c, EdgeU=u, EdgeV=v, Color=[1, 0.5, 0.25], Intensity=2)
    data = servermanager.Fetch(quad)
    if data.GetNumberOfCells() != 1 or data.GetNumberOfPoints() != 4:
        fail("the untextured light is not one quad")
    cell = data.GetCell(0)
    for k, (su, sv) in enumerate([(-0.5, -0.5), (0.5, -0.5), (0.5, 0.5), (-0.5, 0.5)]):
        p = data.GetPoint(cell.GetPointId(k))
        want = [c[a] + su * u[a] + sv * v[a] for a in range(3)]
        if max(abs(p[a] - want[a]) for a in range(3)) > 1e-9:
            fail("corner %d is %s, expected %s" % (k, p, want))
    radiance = [data.GetCellData().GetArray("Radiance").GetComponent(0, k) for k in range(3)]
    display = [data.GetCellData().GetArray("DisplayColors").GetComponent(0, k) for k in range(3)]
    if radiance != [2.0, 1.0, 0.5] or display != [255, 255, 128]:
        fail("radiance %s / display %s of a (1, 0.5, 0.25) x 2 light" % (radiance, display))
    mark = data.GetFieldData().GetArray("MRGIAreaLight")
    if [mark.GetComponent(0, k) for k in range(16)] != c + u + v + [1, 0.5, 0.25, 2, 0, 0, 0]:
        fail("the MRGIAreaLight field array does not hold the parameters")

    # Pictures: a 3D image gives its first z slice; an x-z slice is used whole,
    # x along EdgeU and z along EdgeV.
    for extent, axes in (([-10, 10, -10, 10, -10, 10], "xy"), ([-10, 10, 0, 0, -10, 10], "xz")):
        image_source = simple.Wavelet(WholeExtent=extent)
        image = servermanager.Fetch(image_source)
        light_data = servermanager.Fetch(simple.MRGITexturedAreaLight(Input=image_source))
        dims = image.GetDimensions()
        texture = light_data.GetCellData().GetArray("Texture")
        values = image.GetPointData().GetArray("RTData")
        if texture is None or texture.GetNumberOfTuples() != 21 * 21:
            fail("%s picture: no 21 x 21 Texture array" % axes)
        stride_v = dims[0] if axes == "xy" else dims[0] * dims[1]
        for j in range(21):
            for i in range(21):
                want = values.GetValue(i + j * stride_v)
                got = [texture.GetComponent(j * 21 + i, k) for k in range(3)]
                if max(abs(g - want) for g in got) > 1e-3 * abs(want):
                    fail("%s picture: texel (%d, %d) is %s, expected %g" % (axes, i, j, got, want))
    print("pvbatch_area_lights: layout: quad corners, radiance, display colours, mark, "
          "3D and x-z pictures as documented")


if "--checks" in sys.argv:
    check_layout()
    bad = dict(params, EdgeV=params["EdgeU"])
    light = simple.MRGIAreaLight(**bad)
    show_area_light(light, view)
    save(view, "invalid.png")
    check_count(view, 0, "parallel edges")
    simple.Delete(light)
    # A picture with negative values (this wavelet extent reaches below 0).
    negative = simple.Wavelet(WholeExtent=[0, 63, 0, 63, 0, 0])
    light = simple.MRGITexturedAreaLight(Input=negative, **params)
    show_area_light(light, view)
    save(view, "invalid-picture.png")
    check_count(view, 0, "negative picture")
    sys.exit(0)

light = simple.MRGIAreaLight(**params)
display = show_area_light(light, view)
save(view, "area.png")
check_count(view, 1, "area light shown")

# Unchanged data: another render reads nothing again; a changed property
# (new data) is read once.
updates = view_area_light_updates(view)
simple.Render(view)
if view_area_light_updates(view) != updates:
    raise SystemExit("pvbatch_area_lights: an unchanged light was read again")
light.Intensity = 2 * params["Intensity"]
simple.Render(view)
if view_area_light_updates(view) != updates + 1:
    raise SystemExit("pvbatch_area_lights: a changed light was read %d times, expected once"
                     % (view_area_light_updates(view) - updates))
light.Intensity = params["Intensity"]
print("pvbatch_area_lights: light updates: none for an unchanged light, one after a change")

# The Area Lights properties reach the pass: the defaults are the pass's
# (the depth slices' default is MRGI_VOXEL_AREA_LIGHT_SLICES, typed again
# in MRGIRenderView.xml), and the voxel knobs and shadows change what is
# drawn.
header = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..",
                      "Rendering", "Core", "Twins", "mrgi_voxel.h")
with open(header) as f:
    core_default = int(re.search(r"#define MRGI_VOXEL_AREA_LIGHT_SLICES (\d+)", f.read()).group(1))
view_slices = int(view.SMProxy.GetProperty("AreaLightVoxelSlices").GetElement(0))
last_slices = view_information(view, "LastAreaLightVoxelSlices")
if view_slices != core_default or last_slices != core_default:
    raise SystemExit("pvbatch_area_lights: the view's depth slices %d (last frame %d) are not "
                     "the pass's default %d" % (view_slices, last_slices, core_default))


def last_voxel_size():
    return (view_information(view, "LastAreaLightVoxelWidth"),
            view_information(view, "LastAreaLightVoxelHeight"))


automatic = last_voxel_size()
if min(automatic) < 16 or view.AreaLightVoxelSide != 0:
    raise SystemExit("pvbatch_area_lights: automatic voxel size %s" % (automatic,))
view.AreaLightVoxelSlices = "512"
view.AreaLightVoxelSide = 64
save(view, "voxels.png")
used = (view_information(view, "LastAreaLightVoxelSlices"),) + last_voxel_size()
if used != (512, 64, 64):
    raise SystemExit("pvbatch_area_lights: 512 slices, side 64 gave %s" % (used,))
view.AreaLightVisibility = "Off"
save(view, "unshadowed.png")
view.AreaLightVisibility = "Incremental"
view.AreaLightVoxelSlices = str(core_default)
view.AreaLightVoxelSide = 0
simple.Render(view)
if last_voxel_size() != automatic:
    raise SystemExit("pvbatch_area_lights: side 0 did not return to the automatic size")
print("pvbatch_area_lights: area-light properties: default %d slices, automatic side %s; "
      "512 slices and side 64 used" % (core_default, automatic))

# The display's transform moves the light with its rectangle (read once).
updates = view_area_light_updates(view)
display.Position = [0.0, -150.0, 0.0]
save(view, "moved.png")
if view_area_light_updates(view) != updates + 1:
    raise SystemExit("pvbatch_area_lights: a moved light was not placed again")
display.Position = [0.0, 0.0, 0.0]

simple.Hide(light, view)
save(view, "hidden.png")
check_count(view, 0, "area light hidden")

# The z = 0 slice of ParaView's default wavelet: 21 x 21 values in about
# [37, 277] (larger extents reach negative values, which a light refuses).
wavelet = simple.Wavelet(WholeExtent=[-10, 10, -10, 10, 0, 0])
wavelet.UpdatePipeline()
top = wavelet.PointData["RTData"].GetRange()[1]
textured = simple.MRGITexturedAreaLight(
    Input=wavelet, **dict(params, Intensity=params["Intensity"] / top))
show_area_light(textured, view)
save(view, "textured.png")
check_count(view, 1, "textured area light shown")

# Both at once: two lights.
simple.Show(light, view)
simple.Render(view)
check_count(view, 2, "both lights shown")

simple.Delete(textured)
save(view, "reloaded.png")
check_count(view, 1, "area light shown again")
