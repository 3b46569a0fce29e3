"""Light-side hierarchy: error of the VPL selections against a dense ground truth.

The full-resolution gather's indirect light with grid VPLs and with
multiresolution VPL clusters (nichols-shopf-wyman-2009 3.4) at several
thresholds, against the CPU ground truth without secondary visibility
(vtkMRGIReferenceRenderer, relative error target 0, a fixed number of
passes). Reports relative RMS per pixel and after 4x4 box averaging (both
through mrgi-compare, the C core's metric), VPL counts, the median GPU gather
time and the median wall time of a frame that reselects the VPLs, and writes
the table and difference images for Documentation/LightHierarchy.md.

    PYTHONPATH=build/lib/python3/dist-packages /usr/bin/python3 \\
        Testing/Benchmarks/light_hierarchy.py --build build --out Documentation
"""
import argparse
import math
import os
import statistics
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(__file__))
import mrgi_bench as mb  # noqa: E402

import mrgi  # noqa: E402
from vtkmodules.vtkCommonDataModel import vtkImageData  # noqa: E402

GRID, CLUSTERS = 0, 2
INF = math.inf

# (label, mode, VPLs asked, depth threshold, normal threshold)
SETTINGS = [
    ("grid 256", GRID, 256, None, None),
    ("grid 1024", GRID, 1024, None, None),
    ("grid 4096", GRID, 4096, None, None),
    ("clusters inf / inf (= grid 16x16)", CLUSTERS, 256, INF, INF),
    ("clusters 4 / 0.25 (default)", CLUSTERS, 256, 4.0, 0.25),
    ("clusters 1 / 0.1", CLUSTERS, 256, 1.0, 0.1),
    ("clusters 0 / 0 (every 64x64 node)", CLUSTERS, 256, 0.0, 0.0),
]


def box4(array):
    """4x4 box average of an (h, w, c) array (h, w multiples of 4)."""
    h, w, c = array.shape
    return array[: h - h % 4, : w - w % 4].reshape(h // 4, 4, w // 4, 4, c).mean(axis=(1, 3))


def gather_ms(window, gi, repeats):
    values = []
    for _ in range(repeats):
        window.Render()
        for i in range(gi.FetchStageTimings(window, True)):
            if gi.GetStageName(i) == "gather":
                values.append(gi.GetStageTimeMilliseconds(i))
    return statistics.median(values) if values else float("nan")


def reselect_ms(window, gi, repeats):
    """Median wall ms of a frame whose VPL selection is redone (settings touched)."""
    values = []
    for _ in range(repeats):
        gi.GetVPLSelection().Modified()
        start = time.perf_counter()
        window.Render()
        values.append((time.perf_counter() - start) * 1e3)
    return statistics.median(values)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default=os.path.join(mb.ROOT, "build"))
    parser.add_argument("--out", default=os.path.join(mb.ROOT, "Documentation"))
    parser.add_argument("--scene", default="cornell-spot")
    parser.add_argument("--size", type=int, default=256)
    parser.add_argument("--rsm-size", type=int, default=256)
    parser.add_argument("--passes", type=int, default=64, help="ground-truth passes")
    parser.add_argument("--repeats", type=int, default=5)
    args = parser.parse_args()
    compare_tool = os.path.join(args.build, "bin", "mrgi-compare")
    images = os.path.join(args.out, "images")
    os.makedirs(images, exist_ok=True)
    scratch = os.path.join(args.build, "Testing", "Temporary")
    os.makedirs(scratch, exist_ok=True)

    window, renderer = mb.make_window(args.size, args.size)
    mb.build_scene(renderer, args.scene)
    gi = mb.install_pass(renderer, IndirectMode=1, RSMResolution=args.rsm_size, StageTimingEnabled=True)
    window.Render()

    reference = mrgi.vtkMRGIReferenceRenderer()
    reference.SetSecondaryVisibility(False)
    reference.SetTargetRelativeError(0.0)
    reference.SetMaxPasses(args.passes)
    start = time.time()
    assert reference.Render(renderer), reference.GetLastErrorMessage()
    ref = mb.to_numpy(reference.GetIndirectImage())[..., :3]
    print("ground truth: %d passes, relative error %.5f, %.1f s"
          % (reference.GetPasses(), reference.GetRelativeError(), time.time() - start))
    ref_path = os.path.join(scratch, "lh-ref.exr")
    ref_box_path = os.path.join(scratch, "lh-ref-box.exr")
    mb.write(ref, ref_path)
    mb.write(box4(ref), ref_box_path)

    rows = []
    for label, mode, vpls, depth, normal in SETTINGS:
        gi.SetVPLSelectionMode(mode)
        gi.SetNumberOfVPLs(vpls)
        if depth is not None:
            gi.SetClusterDepthThreshold(depth)
            gi.SetClusterNormalThreshold(normal)
        window.Render()
        buffer = vtkImageData()
        assert gi.GetIndirectBuffer(window, buffer)
        image = mb.to_numpy(buffer)[..., :3]
        assert np.isfinite(image).all(), label + ": non-finite pixels"
        tag = label.split(" (")[0].replace(" / ", "-").replace(" ", "-")
        path = os.path.join(scratch, "lh-%s.exr" % tag)
        box_path = os.path.join(scratch, "lh-%s-box.exr" % tag)
        mb.write(image, path)
        mb.write(box4(image), box_path)
        diff_png = os.path.join(images, "lighthierarchy-%s-diff.png" % tag)
        pixel = mb.compare(compare_tool, path, ref_path, diff_png, diff_scale=4.0)["relative_rms"]
        box = mb.compare(compare_tool, box_path, ref_box_path)["relative_rms"]
        row = {
            "label": label,
            "vpls": gi.GetVPLSelection().GetVPLCount(),
            "flux_ratio": float(image.sum() / max(1e-30, ref.sum())),
            "pixel": pixel,
            "box": box,
            "gather_ms": gather_ms(window, gi, args.repeats),
            "reselect_ms": reselect_ms(window, gi, args.repeats),
        }
        rows.append(row)
        print("%-36s %5d VPLs  rel. RMS %.4f per pixel, %.4f 4x4 boxes  gather %.1f ms  "
              "frame with reselection %.1f ms" % (label, row["vpls"], pixel, box, row["gather_ms"],
                                                   row["reselect_ms"]))
    scale = 1.0 / max(1e-12, float(ref.max()))
    mb.write_display(ref, os.path.join(images, "lighthierarchy-ref.png"), scale)

    grid = rows[0]
    print()
    print("| selection | VPLs | rel. RMS per pixel | rel. RMS 4x4 boxes | gather ms | gather / grid 256 | "
          "frame with reselection ms |")
    print("|---|---|---|---|---|---|---|")
    for r in rows:
        print("| %s | %d | %.3f | %.3f | %.1f | %.2f | %.1f |"
              % (r["label"], r["vpls"], r["pixel"], r["box"], r["gather_ms"],
                 r["gather_ms"] / grid["gather_ms"], r["reselect_ms"]))


if __name__ == "__main__":
    main()
