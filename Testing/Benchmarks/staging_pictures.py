#!/usr/bin/env python3
"""The pictures and numbers of Documentation/Staging.md: each shared data
file rendered by mrgi-render without staging (--stage off, the behaviour
before it), staged with GI off, staged with the defaults (GI on), and
staged with the area key light; one PNG strip per file. Then the light
the indirect light adds, at a fixed exposure (auto exposure hides it in
the strips), and the render times.

    /usr/bin/python3 Testing/Benchmarks/staging_pictures.py [build] [out-dir]

build defaults to ./build, out-dir to Documentation/images; the data
comes from $MRGI_SHARED_DATA_DIR or ../shared/data."""
import os
import subprocess
import sys
import tempfile
import time

from vtkmodules.vtkIOImage import vtkPNGReader, vtkPNGWriter
from vtkmodules.vtkFiltersCore import vtkImageAppend
from vtkmodules.util.numpy_support import vtk_to_numpy

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
BUILD = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "build")
OUT = sys.argv[2] if len(sys.argv) > 2 else os.path.join(ROOT, "Documentation", "images")
DATA = os.environ.get("MRGI_SHARED_DATA_DIR", os.path.join(ROOT, "..", "shared", "data"))
RENDER = os.path.join(BUILD, "bin", "mrgi-render")
SIZE = "240x180"
VARIANTS = (("before", ["--stage", "off"]), ("direct", ["--gi", "off"]), ("gi", []),
            ("area", ["--key-light", "area"]))


def render(path, out, args):
    start = time.perf_counter()
    result = subprocess.run([RENDER, path, "-o", out, "--size", SIZE] + args,
                            capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit("mrgi-render %s %s failed: %s" % (path, " ".join(args), result.stderr))
    staged = [l for l in result.stderr.splitlines() if "staged:" in l]
    return time.perf_counter() - start, staged[0].split("staged: ")[1] if staged else ""


def read(path):
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    return reader.GetOutput()


def main():
    tmp = tempfile.mkdtemp(prefix="mrgi-staging-")
    print("| file | up axis (cue) | before | staged, GI off | staged, GI on | area key light | GI adds (fixed exposure) |")
    print("|---|---|---|---|---|---|---|")
    for name in ("bunny.ply", "dragon.ply", "ironProt.vtk", "teapot.obj"):
        path = os.path.join(DATA, name)
        if not os.path.exists(path):
            print("%s: not found, skipped" % path, file=sys.stderr)
            continue
        strip = vtkImageAppend()
        strip.SetAppendAxis(0)
        seconds = []
        staged = ""
        for variant, args in VARIANTS:
            png = os.path.join(tmp, "%s-%s.png" % (name, variant))
            dt, line = render(path, png, args)
            seconds.append(dt)
            staged = staged or line
            strip.AddInputData(read(png))
        strip.Update()
        writer = vtkPNGWriter()
        writer.SetFileName(os.path.join(OUT, "staging-%s.png" % os.path.splitext(name)[0]))
        writer.SetInputData(strip.GetOutput())
        writer.Write()
        sums = []
        for gi in (["--gi", "off"], []):
            png = os.path.join(tmp, "%s-fixed.png" % name)
            render(path, png, ["--exposure", "0"] + gi)
            sums.append(vtk_to_numpy(read(png).GetPointData().GetScalars()).astype(float).sum())
        print("| %s | %s | %.1f s | %.1f s | %.1f s | %.1f s | +%.1f%% |" % (
            name, staged, *seconds, 100.0 * (sums[1] / sums[0] - 1.0)))


if __name__ == "__main__":
    main()
