"""pvbatch: a LAS point cloud lit in the MRGI Render View.

usage: pvbatch pvbatch_point_clouds.py PLUGIN OUT_DIR [SIZE] [LAS]
       pvbatch pvbatch_point_clouds.py PLUGIN OUT_DIR SIZE --bad

Without LAS, writes OUT_DIR/valley.las (LAS 1.2, point format 2, UTM-sized
offsets): two facing slopes of a V-shaped valley, one red and one white,
so that light bounces from each slope onto the other. Then, as a ParaView
user would:
- OpenDataFile() must pick the plugin's "MRGI LAS Reader" for the .las;
- "MRGI Point Cloud Normals" (Up 0 0 1) and "MRGI Surfels" (squares, then
  hexagons): the surfels must have 4 (6) points per input point, as many
  polygons as points, each polygon 4 (6) corners, finite points and normals
  of unit length;
- shows the surfels coloured by the file's RGB in an MRGI Render View with
  Global Illumination off and on (OUT_DIR/off.png, on.png, SIZE x SIZE).
Asserts that the cloud covers a good part of the image, that no covered
pixel is black (where NaNs would land: an 8-bit PNG cannot hold one), that
GI on differs from GI off and is brighter (indirect light added). With a
LAS path (e.g. the shared tile), uses it instead of the valley and checks
the same, with Up 0 0 1; the valley's geometry checks are skipped.
With --bad, opens a truncated LAS file instead, then gives the surfels a
cloud without normals and the normals a RadiusScale of 0: empty outputs,
and each error in the log (the caller checks them).
Prints one line per check; exits non-zero on the first failed one.
"""
import os
import struct
import sys

from paraview import servermanager, simple

plugin, out_dir = sys.argv[1], sys.argv[2]
size = int(sys.argv[3]) if len(sys.argv) > 3 else 256
las_path = sys.argv[4] if len(sys.argv) > 4 else None
simple.LoadPlugin(plugin, remote=False)

import numpy as np  # noqa: E402
from vtkmodules.util.numpy_support import vtk_to_numpy  # noqa: E402
from vtkmodules.vtkIOImage import vtkPNGReader  # noqa: E402


def check(condition, what):
    if not condition:
        raise SystemExit("pvbatch_point_clouds: FAIL: " + what)
    print("pvbatch_point_clouds: ok:", what)


def write_valley(path, n=48):
    """LAS 1.2, point format 2 (XYZ, intensity, returns, class, RGB), from
    the ASPRS specification: an n x n grid over x in [-1, 1], y in [-1, 1]
    with z = |x| (two 45-degree slopes), x < 0 red, x >= 0 white."""
    offset, scale = (512000.0, 5403000.0, 300.0), 0.0001
    header = bytearray(227)
    header[0:4] = b"LASF"
    header[24], header[25] = 1, 2
    struct.pack_into("<HIIBHI", header, 94, 227, 227, 0, 2, 26, n * n)
    struct.pack_into("<3d3d", header, 131, scale, scale, scale, *offset)
    body = bytearray()
    for j in range(n):
        for i in range(n):
            x = -1.0 + 2.0 * (i + 0.5) / n
            y = -1.0 + 2.0 * (j + 0.5) / n
            xyz = (offset[0] + x, offset[1] + y, offset[2] + abs(x))
            rgb = (65535, 9000, 6000) if x < 0 else (60000, 60000, 60000)
            record = bytearray(26)
            struct.pack_into("<3iHBB", record, 0,
                             *[int(round((xyz[c] - offset[c]) / scale)) for c in range(3)],
                             100, 1 | (1 << 3), 2)
            struct.pack_into("<3H", record, 20, *rgb)
            body += record
    with open(path, "wb") as f:
        f.write(bytes(header) + bytes(body))
    return n * n


def pixels_of(path):
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    check(image.GetNumberOfPoints() == size * size, "%s is %d x %d" % (path, size, size))
    return vtk_to_numpy(image.GetPointData().GetScalars())[:, :3].astype(float)


if las_path == "--bad":
    # A LAS file cut in its point data: the reader's error (the caller
    # checks the log for it), an empty output, no crash; then the surfels
    # of that empty cloud are empty too.
    bad = os.path.join(out_dir, "truncated.las")
    write_valley(bad)
    with open(bad, "r+b") as f:
        f.truncate(227 + 26 * 10 + 7)
    reader = simple.OpenDataFile(bad)
    check(reader is not None and reader.GetXMLName() == "MRGILASReader", "truncated: MRGI LAS Reader")
    check(servermanager.Fetch(reader).GetNumberOfPoints() == 0, "truncated: empty output")
    surfels = simple.MRGISurfels(Input=simple.MRGIPointCloudNormals(Input=reader))
    check(servermanager.Fetch(surfels).GetNumberOfPoints() == 0, "truncated: no surfels")
    # A good cloud with bad filter settings: surfels without normals, a
    # radius scale of 0. Each must give its filter's error (the caller
    # checks the log) and an empty output.
    good = os.path.join(out_dir, "valley.las")
    write_valley(good)
    cloud = simple.OpenDataFile(good)
    check(servermanager.Fetch(simple.MRGISurfels(Input=cloud)).GetNumberOfPoints() == 0,
          "surfels without normals: empty output")
    check(servermanager.Fetch(simple.MRGIPointCloudNormals(Input=cloud, RadiusScale=0.0))
          .GetNumberOfPoints() == 0, "normals with RadiusScale 0: empty output")
    print("pvbatch_point_clouds: bad input checks done")
    sys.exit(0)

written = las_path is None
if written:
    las_path = os.path.join(out_dir, "valley.las")
    count = write_valley(las_path)

# 1. File > Open's choice: the plugin's reader, by the extension.
reader = simple.OpenDataFile(las_path)
check(reader is not None and reader.GetXMLName() == "MRGILASReader",
      "OpenDataFile picks the MRGI LAS Reader (got %s)"
      % (reader.GetXMLName() if reader is not None else None))
cloud = servermanager.Fetch(reader)
if not written:
    count = cloud.GetNumberOfPoints()
check(cloud.GetNumberOfPoints() == count and cloud.GetNumberOfVerts() == count,
      "the reader gives %d points, one vertex each" % count)
check(cloud.GetPointData().GetArray("RGB") is not None or not written, "RGB read")

# 2. Normals and surfels.
normals = simple.MRGIPointCloudNormals(Input=reader)
normals.Up = [0, 0, 1]
surfels = simple.MRGISurfels(Input=normals)
for shape, corners in ((6, 6), (4, 4)):
    surfels.Shape = shape
    out = servermanager.Fetch(surfels)
    n_surfels = out.GetNumberOfPolys()
    surfels.UpdatePropertyInformation()
    skipped = surfels.GetPropertyValue("NumberOfSkippedPoints")
    check(n_surfels + skipped == count and n_surfels > 0,
          "shape %d: %d surfels + %d skipped = %d points" % (shape, n_surfels, skipped, count))
    if written:
        check(skipped == 0, "no valley point skipped")
    check(out.GetNumberOfPoints() == corners * n_surfels,
          "shape %d: %d points = %d x %d surfels" % (shape, out.GetNumberOfPoints(), corners,
                                                     n_surfels))
    offsets = vtk_to_numpy(out.GetPolys().GetOffsetsArray())
    check(bool(np.all(np.diff(offsets) == corners)), "every polygon has %d corners" % corners)
    xyz = vtk_to_numpy(out.GetPoints().GetData())
    nrm = vtk_to_numpy(out.GetPointData().GetNormals())
    check(bool(np.isfinite(xyz).all() and np.isfinite(nrm).all()), "finite points and normals")
    check(bool(np.all(np.abs(np.linalg.norm(nrm, axis=1) - 1.0) < 1e-3)), "unit normals")
    if written:
        # The slopes' normals are (-+1, 0, 1) / sqrt(2): up, facing each other.
        up = nrm[:, 2]
        check(bool(np.all(up > 0.6)), "normals point up (min z %.3f)" % up.min())
        across = nrm[:, 0] * np.sign(xyz[:, 0] + 1e-9)
        check(float(np.median(across)) < -0.6, "each slope faces the other")

# 3. The MRGI Render View, GI off then on.
view = simple.CreateView("MRGIRenderView")
view.ViewSize = [size, size]
view.OrientationAxesVisibility = 0
view.UseFXAA = 0
if hasattr(view, "UseColorPaletteForBackground"):
    view.UseColorPaletteForBackground = 0
view.Background = [0.0, 0.0, 0.0]
display = simple.Show(surfels, view)
colors = "RGB" if out.GetPointData().GetArray("RGB") is not None else "Colors"
simple.ColorBy(display, ("POINTS", colors))
display.MapScalars = 0
bounds = out.GetBounds()
center = [(bounds[2 * c] + bounds[2 * c + 1]) / 2 for c in range(3)]
extent = max(bounds[1] - bounds[0], bounds[3] - bounds[2], bounds[5] - bounds[4])
# Looking down the valley, from above and in front.
view.CameraFocalPoint = center
view.CameraPosition = [center[0], center[1] - 2.0 * extent, center[2] + 1.2 * extent]
view.CameraViewUp = [0, 0, 1]
simple._DisableFirstRenderCameraReset()
# GI off and on without direct shadows (this test is about the surfels:
# a hole shows as a black pixel), then on with the view's default soft
# shadows, which may darken but must not open holes in the light kit's fill.
images = {}
for gi, shadows, name in ((0, 0, "off.png"), (1, 0, "on.png"), (1, 2, "on-shadows.png")):
    view.GlobalIllumination = gi
    view.DirectShadows = shadows
    simple.Render(view)
    path = os.path.join(out_dir, name)
    simple.SaveScreenshot(path, view, ImageResolution=[size, size])
    images[(gi, shadows)] = pixels_of(path)

off, on, shadowed = images[(0, 0)], images[(1, 0)], images[(1, 2)]
covered = off.sum(axis=1) > 0  # the background is black
fraction = covered.mean()
print("pvbatch_point_clouds: covered fraction %.3f" % fraction)
check(fraction > 0.15, "the cloud covers %.1f%% of the image (> 15%%)" % (100 * fraction))
check(bool(np.all(on[covered].sum(axis=1) > 0)),
      "no black pixel inside the cloud with GI on (%d black)"
      % int((on[covered].sum(axis=1) == 0).sum()))
rms = float(np.sqrt(np.mean((on - off) ** 2)) / np.sqrt(np.mean(off ** 2)))
gain = float(on[covered].mean() / off[covered].mean())
print("pvbatch_point_clouds: GI on vs off: relative RMS %.4f, mean covered brightness x%.3f"
      % (rms, gain))
check(rms > 0.02, "GI changes the image (relative RMS %.4f > 0.02)" % rms)
check(gain > 1.01, "GI adds light (covered pixels x%.3f)" % gain)
dark = float(shadowed[covered].mean() / on[covered].mean())
black = int((shadowed[covered].sum(axis=1) == 0).sum())
print("pvbatch_point_clouds: soft shadows: mean covered brightness x%.3f, %d black pixels" % (dark, black))
check(dark <= 1.0 + 1e-3, "shadows only take light away (x%.3f)" % dark)
check(black <= 0.01 * int(covered.sum()), "under 1%% of the cloud black with shadows (%d)" % black)
if written:
    # Colour bleeding: the red slope (left half of the image) tints the
    # white one (right half) only through the indirect light.
    right = covered.reshape(size, size).copy()
    right[:, : size // 2 + 4] = False
    right = right.reshape(-1)
    bleed = {gi: float(np.mean(images[(gi, 0)][right, 0] - images[(gi, 0)][right, 1]))
             for gi in (0, 1)}
    print("pvbatch_point_clouds: white slope, mean red - green: GI off %.2f, on %.2f"
          % (bleed[0], bleed[1]))
    check(bleed[1] > bleed[0] + 2.0, "the red slope bleeds onto the white one")
print("pvbatch_point_clouds: all checks passed")
