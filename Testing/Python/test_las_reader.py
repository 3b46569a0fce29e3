"""vtkMRGILASReader from Python and LAS/point-cloud files through mrgi-render.

`import mrgi` exposes the reader: the shared airborne tile (when present)
reads with its counts and classes; a LAS file written here byte by byte
reads back exactly (UTM-sized offsets, 16-bit RGB); a LAZ file is an error
naming the file. mrgi-render renders a small LAS tile and a vertex-only PLY
(EXR read back: no NaN, not black) and refuses an all-NaN cloud, a LAZ and
a truncated LAS with one line naming the file, writing nothing."""
import os
import struct
import subprocess
import sys

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkCommand

import mrgi

RENDER = os.environ["MRGI_RENDER"]
TMP = os.environ.get("MRGI_TEST_TMP", "/tmp")
SHARED = os.environ.get("MRGI_SHARED_DATA_DIR", "")
failures = []


def check(condition, what):
    if not condition:
        print("check failed:", what, file=sys.stderr)
        failures.append(what)
    return condition


def fresh(name):
    path = os.path.join(TMP, name)
    if os.path.exists(path):
        os.remove(path)
    return path


# LAS 1.2 (format 3: XYZ, intensity, returns, class, GPS time, RGB) written
# from the ASPRS specification, independently of the reader under test.
def write_las(path, points, fmt=3, offset=(500000.0, 5400000.0, 0.0), scale=0.001, compressed=False):
    record = {0: 20, 1: 28, 2: 26, 3: 34}[fmt]
    header = bytearray(227)
    header[0:4] = b"LASF"
    header[24], header[25] = 1, 2
    struct.pack_into("<HIIBHI", header, 94, 227, 227, 0, fmt | (0x80 if compressed else 0), record,
                     len(points))
    struct.pack_into("<3d3d", header, 131, scale, scale, scale, *offset)
    body = bytearray()
    for p in points:
        r = bytearray(record)
        xyz = [int(round((p["xyz"][c] - offset[c]) / scale)) for c in range(3)]
        struct.pack_into("<3iHBB", r, 0, *xyz, p.get("intensity", 0),
                         p.get("return", 1) | (p.get("returns", 1) << 3), p.get("class", 0))
        if fmt in (2, 3):
            struct.pack_into("<3H", r, 20 if fmt == 2 else 28, *p.get("rgb", (0, 0, 0)))
        body += r
    with open(path, "wb") as f:
        f.write(bytes(header) + bytes(body))


def read(path, color_by=None):
    reader = mrgi.vtkMRGILASReader()
    errors = []
    reader.AddObserver(vtkCommand.ErrorEvent, lambda o, e: errors.append(o.GetLastErrorMessage()))
    reader.SetFileName(path)
    if color_by is not None:
        reader.SetColorBy(color_by)
    reader.Update()
    return reader, reader.GetOutput(), errors


def shared_tile():
    path = os.path.join(SHARED, "file_with_both_wkt_and_geotiff_vlrs.las") if SHARED else ""
    if not path or not os.path.isfile(path):
        print("shared LAS tile not present: skipped its checks")
        return None
    reader, out, errors = read(path)
    # MANIFEST.md: LAS 1.4, point format 6, 25,408 single returns; 10,956
    # high vegetation (5), 9,808 ground (2), 3,737 building (6); z 1352.7-1404.0 ft.
    check(not errors and out.GetNumberOfPoints() == 25408, "shared tile: 25,408 points")
    check(out.GetNumberOfVerts() == 25408, "shared tile: one vertex per point")
    fd = out.GetFieldData()
    check(fd.GetAbstractArray("LASVersion").GetValue(0) == "1.4", "shared tile: LAS 1.4")
    check(fd.GetArray("LASPointFormat").GetValue(0) == 6, "shared tile: point format 6")
    pd = out.GetPointData()
    classes = vtk_to_numpy(pd.GetArray("Classification"))
    counts = np.bincount(classes, minlength=256)
    check(counts[5] == 10956 and counts[2] == 9808 and counts[6] == 3737,
          "shared tile classes: %s" % {c: int(n) for c, n in enumerate(counts) if n})
    check(np.all(vtk_to_numpy(pd.GetArray("ReturnNumber")) == 1) and
          np.all(vtk_to_numpy(pd.GetArray("NumberOfReturns")) == 1), "shared tile: single returns")
    origin = fd.GetArray("Origin").GetTuple3(0)
    z = vtk_to_numpy(out.GetPoints().GetData())[:, 2] + origin[2]
    check(abs(z.min() - 1352.7) < 0.1 and abs(z.max() - 1404.0) < 0.1,
          "shared tile z %.2f..%.2f" % (z.min(), z.max()))
    check(pd.GetScalars().GetName() == "Colors" and
          reader.GetColorByUsed() == mrgi.vtkMRGILASReader.COLOR_BY_CLASSIFICATION,
          "shared tile coloured by class")
    print("shared tile: %d points, origin %s" % (out.GetNumberOfPoints(), origin))
    return path


def written_file():
    points = []
    for j in range(30):
        for i in range(40):
            points.append({"xyz": (512345.0 + 0.5 * i, 5432109.0 + 0.5 * j, 300.0 + 0.001 * ((i * j) % 7)),
                           "intensity": 10 * i, "class": 2 if i < 20 else 6,
                           "return": 1 + (j % 2), "returns": 2,
                           "rgb": (257 * (6 * i), 257 * (8 * j), 65535)})
    path = fresh("py_las_tile.las")
    write_las(path, points)
    reader, out, errors = read(path)
    check(not errors and out.GetNumberOfPoints() == len(points), "written LAS: %s" % errors)
    origin = np.array(out.GetFieldData().GetArray("Origin").GetTuple3(0))
    xyz = vtk_to_numpy(out.GetPoints().GetData()).astype(np.float64) + origin
    expected = np.array([p["xyz"] for p in points])
    check(np.max(np.abs(xyz - expected)) < 1e-5, "written LAS positions, UTM offsets, mm exact: %g"
          % np.max(np.abs(xyz - expected)))
    pd = out.GetPointData()
    check(np.array_equal(vtk_to_numpy(pd.GetArray("Intensity")), [p["intensity"] for p in points]),
          "intensity")
    check(np.array_equal(vtk_to_numpy(pd.GetArray("Classification")), [p["class"] for p in points]),
          "classification")
    check(np.array_equal(vtk_to_numpy(pd.GetArray("ReturnNumber")), [p["return"] for p in points]),
          "return number")
    rgb = vtk_to_numpy(pd.GetArray("RGB"))
    check(pd.GetScalars().GetName() == "RGB" and rgb.shape == (len(points), 3), "RGB active")
    check(np.array_equal(rgb, [[c // 257 for c in p["rgb"]] for p in points]), "16-bit RGB to 8 bits")
    # The class palette on request, and as a lookup table.
    _, by_class, _ = read(path, mrgi.vtkMRGILASReader.COLOR_BY_CLASSIFICATION)
    colors = vtk_to_numpy(by_class.GetPointData().GetScalars())
    table = mrgi.vtkMRGILASReader.NewClassificationLookupTable()
    check(table.GetReferenceCount() == 1, "the lookup table is the caller's")
    ground = [round(255 * v) for v in table.GetTableValue(2)[:3]]
    check(list(colors[0]) == ground and list(colors[-1]) != ground, "palette colours match the table")
    check(mrgi.vtkMRGIPointCloud.IsPointCloud(out), "a LAS output is a point cloud")
    text = str(reader)  # PrintSelf
    check("FileName: " + path in text and "MaximumNumberOfPoints: 268435456" in text and
          "ColorByUsed: 1" in text, "PrintSelf: " + text)
    # LAZ: an error naming the file, an empty output.
    laz = fresh("py_las_tile.laz")
    write_las(laz, points, compressed=True)
    reader, out, errors = read(laz)
    check(len(errors) == 1 and "compressed LAZ is not supported" in errors[0] and laz in errors[0],
          "LAZ refused: %s" % errors)
    check(out.GetNumberOfPoints() == 0, "LAZ: empty output")
    return path, points


def write_ply(path, points):
    with open(path, "wb") as f:
        f.write(b"ply\nformat binary_little_endian 1.0\nelement vertex %d\n"
                b"property float x\nproperty float y\nproperty float z\n"
                b"property uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n" % len(points))
        for x, y, z in points:
            f.write(struct.pack("<3f3B", x, y, z, 230, 180, 90))


def render(scene, name, *extra):
    exr = fresh(name + ".exr")
    env = dict(os.environ)
    env.pop("DISPLAY", None)
    p = subprocess.run([RENDER, scene, "-o", exr, "--size", "160x120", *extra],
                       capture_output=True, text=True, env=env, timeout=600)
    return p.returncode, p.stderr, exr


def check_image(exr, what):
    image = __import__("vtkmodules.vtkCommonDataModel", fromlist=["vtkImageData"]).vtkImageData()
    io = mrgi.vtkMRGIImageIO()
    if not check(io.Read(exr, image), "%s: read %s: %s" % (what, exr, io.GetLastErrorMessage())):
        return
    pixels = vtk_to_numpy(image.GetPointData().GetScalars())[:, :3]
    lit = np.count_nonzero(pixels.max(axis=1) > 0.05)
    print("%s: %d of %d pixels lit, mean %.3f, max %.3f" % (what, lit, len(pixels), pixels.mean(),
                                                            pixels.max()))
    check(np.all(np.isfinite(pixels)), what + ": no NaN pixel")
    check(lit > 0.02 * len(pixels), what + ": not black (%d lit pixels)" % lit)


def cli(tile):
    code, err, exr = render(tile, "py_las_render")
    check(code == 0 and "point cloud of 1200 points" in err, "mrgi-render LAS: " + err)
    if code == 0:
        check_image(exr, "LAS tile")
    # A vertex-only PLY (a sphere of points, no faces).
    rng = np.random.default_rng(3)
    v = rng.normal(size=(4000, 3))
    v /= np.linalg.norm(v, axis=1)[:, None]
    ply = fresh("py_vertex_cloud.ply")
    write_ply(ply, v)
    code, err, exr = render(ply, "py_ply_render")
    check(code == 0 and "point cloud of 4000 points" in err, "mrgi-render vertex-only PLY: " + err)
    if code == 0:
        check_image(exr, "vertex-only PLY")
    # All NaN, LAZ, truncated: one error line naming the file, no output.
    nan_ply = fresh("py_all_nan.ply")
    write_ply(nan_ply, [(float("nan"),) * 3] * 50)
    laz = os.path.join(TMP, "py_las_tile.laz")
    truncated = fresh("py_truncated.las")
    with open(tile, "rb") as f:
        data = f.read()
    with open(truncated, "wb") as f:
        f.write(data[:len(data) // 2])
    for path, message in ((nan_ply, "none of its 50 points has finite coordinates"),
                          (laz, "compressed LAZ is not supported"), (truncated, "truncated")):
        code, err, exr = render(path, "py_bad_cloud")
        check(code == 1 and message in err and path in err and not os.path.exists(exr),
              "mrgi-render %s refused: %s" % (path, err))


def main():
    check(hasattr(mrgi, "vtkMRGILASReader") and hasattr(mrgi, "vtkMRGIPointCloud"),
          "import mrgi exposes the LAS reader")
    shared = shared_tile()
    tile, _ = written_file()
    cli(tile)
    if shared:
        code, err, exr = render(shared, "py_shared_tile")
        check(code == 0 and "point cloud of 25408 points" in err, "mrgi-render shared tile: " + err)
        if code == 0:
            check_image(exr, "shared LAS tile")
    if failures:
        print("%d checks failed" % len(failures), file=sys.stderr)
        return 1
    print("all checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
