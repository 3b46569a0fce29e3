"""mrgi-flicker's contract (mrgi_flicker.h through the tool the benchmarks
call): a static bar against a moving one gives sqrt(2/3) on EXR files, per
pair with --pairs; an image sequence equal to its reference gives 0; a
checkerboard that flips sign every frame is 0 only with --box 2; bad usage
exits 2 with the usage; NaN pixels and mismatched sizes exit 1 naming the
frame."""
import math
import os
import struct
import subprocess
import sys

import numpy as np
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.util.numpy_support import numpy_to_vtk

import mrgi

FLICKER = os.environ["MRGI_FLICKER"]
TMP = os.path.join(os.environ.get("MRGI_TEST_TMP", "/tmp"), "flicker_tool")


def check(condition, what):
    if not condition:
        print("check failed:", what, file=sys.stderr)
        sys.exit(1)


def write(array, name):
    """An (h, w, 3) array as TMP/name.exr; returns the path."""
    height, width, channels = array.shape
    image = vtkImageData()
    image.SetDimensions(width, height, 1)
    flat = np.ascontiguousarray(array[::-1].reshape(-1, channels), dtype=np.float32)
    image.GetPointData().SetScalars(numpy_to_vtk(flat, deep=True))
    path = os.path.join(TMP, name + ".exr")
    io = mrgi.vtkMRGIImageIO()
    check(io.Write(image, path), io.GetLastErrorMessage())
    return path


def write_raw(array, name):
    """An (h, w, 3) array as an uncompressed float EXR written here, NaN kept
    (MRGI's own writer turns NaN into 0, so it cannot make a bad file)."""
    height, width, _ = array.shape

    def attribute(key, kind, data):
        return key.encode() + b"\0" + kind.encode() + b"\0" + struct.pack("<i", len(data)) + data

    channels = b"".join(c.encode() + b"\0" + struct.pack("<iB3xii", 2, 0, 1, 1) for c in "BGR") + b"\0"
    box = struct.pack("<4i", 0, 0, width - 1, height - 1)
    header = (b"\x76\x2f\x31\x01" + struct.pack("<i", 2) + attribute("channels", "chlist", channels)
              + attribute("compression", "compression", b"\0") + attribute("dataWindow", "box2i", box)
              + attribute("displayWindow", "box2i", box) + attribute("lineOrder", "lineOrder", b"\0")
              + attribute("pixelAspectRatio", "float", struct.pack("<f", 1.0))
              + attribute("screenWindowCenter", "v2f", struct.pack("<2f", 0.0, 0.0))
              + attribute("screenWindowWidth", "float", struct.pack("<f", 1.0)) + b"\0")
    offset, offsets, lines = len(header) + 8 * height, [], []
    for y in range(height):
        data = b"".join(np.ascontiguousarray(array[y, :, c], dtype="<f4").tobytes() for c in (2, 1, 0))
        offsets.append(struct.pack("<Q", offset))
        lines.append(struct.pack("<ii", y, len(data)) + data)
        offset += len(lines[-1])
    path = os.path.join(TMP, name + ".exr")
    with open(path, "wb") as f:
        f.write(header + b"".join(offsets) + b"".join(lines))
    return path


def bar(column, size=4):
    frame = np.full((size, size, 3), 0.5, dtype=np.float32)
    frame[:, column, :] = 1.5
    return frame


def run(*args):
    p = subprocess.run([FLICKER, *args], capture_output=True, text=True, timeout=120)
    return p.returncode, p.stdout, p.stderr


def values(line):
    return {k: float(v) for k, v in (item.split("=") for item in line.split())}


def main():
    os.makedirs(TMP, exist_ok=True)
    moving = [write(bar(k), "moving-%d" % k) for k in range(4)]
    static = [write(bar(0), "static-%d" % k) for k in range(4)]

    code, out, err = run(*static, "--reference", *moving)
    check(code == 0, "static vs moving measures: " + err)
    result = values(out)
    print(out.strip())
    check(abs(result["flicker"] - math.sqrt(2.0 / 3.0)) < 1e-5, "F = sqrt(2/3): " + out)
    check(result["pairs"] == 3 and result["excluded"] == 0 and result["box"] == 1, out)

    code, out, err = run("--pairs", *static, "--reference", *moving)
    lines = out.strip().splitlines()
    check(code == 0 and len(lines) == 4, "--pairs prints 3 pairs and the total: " + out)
    for k, line in enumerate(lines[:3]):
        pair = values(line)
        check(pair["pair"] == k and abs(pair["value"] - math.sqrt(2.0 / 3.0)) < 1e-5, line)
        check(abs(pair["reference_rms"] - math.sqrt(0.75)) < 1e-5 and pair["excluded"] == 0, line)

    code, out, _ = run(*moving, "--reference", *moving)
    check(code == 0 and values(out)["flicker"] == 0.0, "I = R gives 0: " + out)

    # Checkerboard noise flipping every frame: per-pixel flicker, none in 2x2 boxes.
    checker = np.indices((4, 4)).sum(axis=0) % 2 * 2.0 - 1.0
    noisy = [write(np.ones((4, 4, 3), np.float32) + 0.1 * ((-1) ** k) * checker[..., None],
                   "noisy-%d" % k) for k in range(3)]
    flat = [write(np.ones((4, 4, 3), np.float32), "flat-%d" % k) for k in range(3)]
    code, out, _ = run(*noisy, "--reference", *flat)
    check(code == 0 and abs(values(out)["flicker"] - 0.2) < 1e-5, "per pixel 0.2: " + out)
    code, out, _ = run("--box", "2", *noisy, "--reference", *flat)
    check(code == 0 and values(out)["flicker"] < 1e-6 and "box=2" in out, "--box 2 gives 0: " + out)

    # --help: usage on stdout, exit 0.
    code, out, _ = run("--help")
    check(code == 0 and out.startswith("usage: mrgi-flicker"), "--help: " + out)
    # Bad usage: exit 2, one error line naming the problem, the usage on stderr.
    for args, expected in (([*static], "no --reference"),
                           ([static[0], "--reference", moving[0]], "at least 2"),
                           ([*static, "--reference", *moving[:3]], "4 images and 3 reference"),
                           (["--box", "0", *static, "--reference", *moving], "--box"),
                           (["--box"], "--box needs a value"),
                           (["--bogus", *static, "--reference", *moving], "unknown option '--bogus'"),
                           ([*static, "--reference", "--reference", *moving], "twice")):
        code, out, err = run(*args)
        errors = [l for l in err.splitlines() if l.startswith("mrgi-flicker: error:")]
        check(code == 2, "exit 2 for %s (got %d)" % (args, code))
        check(len(errors) == 1 and expected in errors[0], "error for %s names %r: %s" % (args, expected, err))
        check("usage: mrgi-flicker" in err and out == "", "usage printed for %s" % args)

    # Not measurable: exit 1 naming the problem.
    nan = bar(2)
    nan[1, 1, 0] = np.nan
    bad = write_raw(nan, "nan")
    code, out, err = run(static[0], write_raw(bar(0), "raw-0"), "--reference", *moving[:2])
    check(code == 0 and abs(values(out)["flicker"] - math.sqrt(2.0 / 3.0)) < 1e-5,
          "the raw EXR writer writes what it is given: " + out + err)
    small = write(bar(0, size=2), "small")
    for args, expected in (([static[0], static[1], bad, static[3], "--reference", *moving],
                            "image frame 2 holds 1 NaN"),
                           ([*static, "--reference", moving[0], small, moving[2], moving[3]],
                            "reference frame 1 is 2x2"),
                           ([*static, "--reference", *static[:3], "missing.exr"], "missing.exr"),
                           (["--box", "5", *static, "--reference", *moving], "box side 5"),
                           ([*flat[:2], "--reference", *[write(np.zeros((4, 4, 3), np.float32), "black-%d" % k)
                                                         for k in range(2)]], "black")):
        code, out, err = run(*args)
        check(code == 1 and expected in err and out == "", "exit 1 naming %r: %d %s" % (expected, code, err))
    print("ok")


if __name__ == "__main__":
    main()
