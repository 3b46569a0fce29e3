"""SSGI against the ground truth's indirect light, and its cost.

On cornell-spot (256x256): the indirect light of SSGI alone (the colour with
SSGI minus the colour without, VPL gather off), of the full-resolution VPL
gather (GetIndirectBuffer, SSGI off) and of neither (zero), each against the
ground truth's indirect light (vtkMRGIReferenceRenderer, secondary
visibility on, shadowed direct light): relative RMS over 4x4-pixel box
averages (C core metric, mrgi-compare), as fidelity.py and
direct_shadows.py do. The ground truth's own noise is the same metric
between two ground truths with different seeds. Cost: GPU ms of the "ssgi"
stage (stage timer), medians over --frames frames after one warm-up, at
256x256 and 1280x720. Writes Documentation/images/ssgi-cornell-spot.png
(ground truth | VPL gather | SSGI, same scale) and a CSV next to it.

    PYTHONPATH=build/lib/python3/dist-packages /usr/bin/python3 \
        Testing/Benchmarks/ssgi.py --build build --out Documentation
"""
import argparse
import csv
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(__file__))
import mrgi_bench as mb  # noqa: E402

import mrgi  # noqa: E402
from vtkmodules.vtkCommonDataModel import vtkImageData  # noqa: E402


def box_error(compare_tool, image, reference, scratch, tag):
    return mb.box_error(compare_tool, image, reference, scratch, "ssgi-" + tag)


def ground_truth(renderer, seed, passes):
    reference = mrgi.vtkMRGIReferenceRenderer()
    reference.SetSecondaryVisibility(True)
    reference.SetTargetRelativeError(0.0)
    reference.SetMaxPasses(passes)
    reference.SetSeed(seed)
    assert reference.Render(renderer), reference.GetLastErrorMessage()
    return mb.to_numpy(reference.GetIndirectImage())[..., :3]


def colour(window, gi):
    window.Render()
    image = vtkImageData()
    assert gi.GetColorBuffer(window, image)
    return mb.to_numpy(image)[..., :3]


def diagonal(renderer):
    b = renderer.ComputeVisiblePropBounds()
    return math.sqrt((b[1] - b[0]) ** 2 + (b[3] - b[2]) ** 2 + (b[5] - b[4]) ** 2)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default=os.path.join(mb.ROOT, "build"))
    parser.add_argument("--out", default=os.path.join(mb.ROOT, "Documentation"))
    parser.add_argument("--scene", default="cornell-spot")
    parser.add_argument("--size", type=int, default=256)
    parser.add_argument("--passes", type=int, default=16, help="ground-truth passes (16 bounce rays each)")
    parser.add_argument("--frames", type=int, default=3)
    parser.add_argument("--samples", default="64,228")
    parser.add_argument("--radius", type=float, default=0.1, help="R as a fraction of the scene's diagonal")
    parser.add_argument("--no-cost", action="store_true", help="skip the cost measurement (and the CSV)")
    args = parser.parse_args()
    compare_tool, images, scratch = mb.folders(args.build, args.out)
    samples = [int(s) for s in args.samples.split(",")]

    window, renderer = mb.make_window(args.size, args.size)
    mb.build_scene(renderer, args.scene)
    gi = mb.install_pass(renderer, IndirectMode=0, StageTimingEnabled=True)
    radius = args.radius * diagonal(renderer)
    gi.SetSSGIRadius(radius)
    gi.SetSSGIBias(radius / 50.0)
    truth = ground_truth(renderer, 1, args.passes)
    truth2 = ground_truth(renderer, 2, args.passes)
    noise = box_error(compare_tool, truth2, truth, scratch, "noise")
    print("%s %dx%d: R = %.1f (%.2f x diagonal); ground truth %d passes, its noise (seed 1 vs 2) %.4f"
          % (args.scene, args.size, args.size, radius, args.radius, args.passes, noise))

    rows = []
    direct = colour(window, gi)
    rows.append({"method": "neither", "samples": 0,
                 "rel_rms": box_error(compare_tool, np.zeros_like(truth), truth, scratch, "neither")})
    ssgi_images = {}
    for n in samples:
        gi.SetSSGI(True)
        gi.SetSSGISamples(n)
        with_ssgi = colour(window, gi)
        gi.SetSSGI(False)
        ssgi_images[n] = with_ssgi - direct
        rows.append({"method": "ssgi", "samples": n,
                     "rel_rms": box_error(compare_tool, ssgi_images[n], truth, scratch, "ssgi%d" % n)})
    gi.SetIndirectMode(1)  # the full-resolution VPL gather
    window.Render()
    buffer = vtkImageData()
    assert gi.GetIndirectBuffer(window, buffer)
    gather = mb.to_numpy(buffer)[..., :3]
    rows.append({"method": "vpl-gather", "samples": gi.GetNumberOfVPLs(),
                 "rel_rms": box_error(compare_tool, gather, truth, scratch, "gather")})
    gi.SetIndirectMode(0)
    for row in rows:
        row["truth_noise"] = noise
        print("indirect light vs ground truth, 4x4 boxes: %-10s %4d  relative RMS %.4f"
              % (row["method"], row["samples"], row["rel_rms"]))

    scale = 1.0 / max(1e-12, float(np.percentile(truth, 99.5)))
    picture = np.concatenate([truth, gather, ssgi_images[samples[-1]]], axis=1)
    if not args.no_cost:
        mb.write_display(picture, os.path.join(images, "ssgi-%s.png" % args.scene), scale)

    if args.no_cost:
        return
    # Cost: the "ssgi" stage at two sizes.
    costs = []
    for width, height in ((args.size, args.size), (1280, 720)):
        window.SetSize(width, height)
        gi.SetSSGI(True)
        for n in samples:
            gi.SetSSGISamples(n)
            window.Render()  # warm-up: shader build
            gi.FetchStageTimings(window, True)
            t = mb.frames(window, gi, args.frames)
            costs.append({"size": "%dx%d" % (width, height), "samples": n, "ssgi_gpu_ms": t.get("ssgi", float("nan")),
                          "frame_ms": t["frame"]})
            print("cost %dx%d, %d samples: ssgi %.1f ms (stage timer), frame %.1f ms wall"
                  % (width, height, n, costs[-1]["ssgi_gpu_ms"], costs[-1]["frame_ms"]))
        gi.SetSSGI(False)

    with open(os.path.join(images, "ssgi-%s.csv" % args.scene), "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(["kind", "method_or_size", "samples", "value", "truth_noise"])
        for row in rows:
            writer.writerow(["rel_rms", row["method"], row["samples"], "%.5f" % row["rel_rms"], "%.5f" % noise])
        for c in costs:
            writer.writerow(["ssgi_gpu_ms", c["size"], c["samples"], "%.2f" % c["ssgi_gpu_ms"], ""])
    renderer.SetPass(None)
    gi.ReleaseGraphicsResources(window)


if __name__ == "__main__":
    main()
