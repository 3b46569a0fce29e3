"""SSAO: VTK 9.1's vtkSSAOPass against MRGI's full-resolution SSAO
(vtkMRGIPass SetSSAO, stage vtkMRGISSAO), issue 14 part 4.

The Cornell box at each size (default 1280x720 and 1920x1080), the same
kernel sizes, radius and bias for both. For every kernel size the two
passes render alternately in one run (A B A B ..., after one warm-up frame
each, so shader compilation is not timed) and the median wall time of a
frame (Render + WaitForCompletion) is reported. Error: RMS over the pixels
of the displayed image (8-bit read-back, values in [0, 1]) against a
high-sample reference, MRGI's SSAO with the largest kernel vtkSSAOPass
accepts (1000); vtkSSAOPass's own 1000-sample image is reported too, as
the limit its half-float positions, mipmaps and 8-bit AO converge to.
Prints a table and writes CSV.

    PYTHONPATH=build/lib/python3/dist-packages /usr/bin/python3 \\
        Testing/Benchmarks/ssao_vs_vtk.py --out build/ssao-bench

On llvmpipe the absolute times are this machine's (shared, noisy); the
ratios within one run are what to compare.
"""
import argparse
import csv
import os
import statistics
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import mrgi_bench as mb  # noqa: E402

import mrgi  # noqa: E402
from vtkmodules.util.numpy_support import vtk_to_numpy  # noqa: E402
from vtkmodules.vtkRenderingCore import vtkWindowToImageFilter  # noqa: E402
from vtkmodules.vtkRenderingOpenGL2 import vtkRenderStepsPass, vtkSSAOPass  # noqa: E402

REFERENCE_SAMPLES = 1000  # vtkSSAOPass clamps KernelSize to 1..1000


def grab(window):
    """The window's displayed image as floats in [0, 1], (h, w, 3)."""
    f = vtkWindowToImageFilter()
    f.SetInput(window)
    f.SetInputBufferTypeToRGB()
    f.ReadFrontBufferOff()
    f.Update()
    image = f.GetOutput()
    dims = image.GetDimensions()
    a = vtk_to_numpy(image.GetPointData().GetScalars()).reshape(dims[1], dims[0], 3)
    return a.astype(np.float64) / 255.0


def frame_ms(window):
    start = time.perf_counter()
    window.Render()
    window.WaitForCompletion()
    return 1000.0 * (time.perf_counter() - start)


class Bench:
    def __init__(self, width, height, radius, bias):
        self.window, self.renderer = mb.make_window(width, height)
        builder = mrgi.vtkMRGISceneBuilder()
        builder.SetScene("cornell")
        assert builder.Build(self.renderer), builder.GetLastErrorMessage()
        self.builder = builder
        self.vtk = vtkSSAOPass()
        self.vtk.SetDelegatePass(vtkRenderStepsPass())
        self.vtk.SetRadius(radius)
        self.vtk.SetBias(bias)
        self.mrgi = mrgi.vtkMRGIPass()
        self.mrgi.SetDelegatePass(vtkRenderStepsPass())
        self.mrgi.SetIndirectMode(mrgi.vtkMRGIPass.IndirectOff)
        self.mrgi.SSAOOn()
        self.mrgi.SetSSAORadius(radius)
        self.mrgi.SetSSAOBias(bias)
        self.plain = vtkRenderStepsPass()

    def use(self, method, samples):
        if method == "vtkSSAOPass":
            self.vtk.SetKernelSize(samples)
            self.renderer.SetPass(self.vtk)
        elif method == "MRGI":
            self.mrgi.SetSSAOKernelSize(samples)
            self.renderer.SetPass(self.mrgi)
        else:
            self.renderer.SetPass(self.plain)

    def render(self, method, samples):
        self.use(method, samples)
        self.window.Render()
        return grab(self.window)

    def release(self):
        self.renderer.SetPass(None)
        self.vtk.ReleaseGraphicsResources(self.window)
        self.mrgi.ReleaseGraphicsResources(self.window)
        self.window.Finalize()


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--sizes", default="1280x720,1920x1080")
    parser.add_argument("--samples", default="8,16,32,64")
    parser.add_argument("--repeats", type=int, default=3, help="timed frames per method (median)")
    parser.add_argument("--radius", type=float, default=30.0,
                        help="world units (the Cornell box is 556 wide; vtkSSAOPass's default 0.5 "
                             "would occlude nothing)")
    parser.add_argument("--bias", type=float, default=0.6)
    parser.add_argument("--out", default="ssao-bench")
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)
    sizes = [tuple(int(v) for v in s.split("x")) for s in args.sizes.split(",")]
    samples = [int(n) for n in args.samples.split(",")]
    rows = []
    for width, height in sizes:
        bench = Bench(width, height, args.radius, args.bias)
        reference = bench.render("MRGI", REFERENCE_SAMPLES)
        vtk_limit = bench.render("vtkSSAOPass", REFERENCE_SAMPLES)
        plain = bench.render("none", 0)
        darkening = float(np.sqrt(np.mean((plain - reference) ** 2)))
        limit_rms = float(np.sqrt(np.mean((vtk_limit - reference) ** 2)))
        print("%dx%d: reference MRGI %d samples; RMS(no SSAO - reference) %.4f; "
              "RMS(vtkSSAOPass %d - reference) %.4f" % (width, height, REFERENCE_SAMPLES,
                                                         darkening, REFERENCE_SAMPLES, limit_rms))
        plain_times = []
        for _ in range(args.repeats):
            plain_times.append(frame_ms(bench.window))
        plain_ms = statistics.median(plain_times)
        rows.append(dict(size="%dx%d" % (width, height), method="none", samples=0,
                         ms=plain_ms, rms=darkening))
        rows.append(dict(size="%dx%d" % (width, height), method="vtkSSAOPass",
                         samples=REFERENCE_SAMPLES, ms=float("nan"), rms=limit_rms))
        for n in samples:
            errors = {}
            for method in ("vtkSSAOPass", "MRGI"):
                image = bench.render(method, n)  # warm-up: compiles the kernel size's shader
                errors[method] = float(np.sqrt(np.mean((image - reference) ** 2)))
            times = {"vtkSSAOPass": [], "MRGI": []}
            for _ in range(args.repeats):  # A B A B
                for method in ("vtkSSAOPass", "MRGI"):
                    bench.use(method, n)
                    times[method].append(frame_ms(bench.window))
            for method in ("vtkSSAOPass", "MRGI"):
                rows.append(dict(size="%dx%d" % (width, height), method=method, samples=n,
                                 ms=statistics.median(times[method]), rms=errors[method]))
        bench.release()
    path = os.path.join(args.out, "ssao_vs_vtk.csv")
    with open(path, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=["size", "method", "samples", "ms", "rms"])
        writer.writeheader()
        writer.writerows(rows)
    print()
    print("| size | method | samples | ms per frame (median of %d) | RMS vs MRGI-%d |"
          % (args.repeats, REFERENCE_SAMPLES))
    print("|---|---|---|---|---|")
    for r in rows:
        print("| %s | %s | %d | %s | %.4f |" % (r["size"], r["method"], r["samples"],
                                                "-" if r["ms"] != r["ms"] else "%.0f" % r["ms"],
                                                r["rms"]))
    print("\nwrote", path)


if __name__ == "__main__":
    main()
