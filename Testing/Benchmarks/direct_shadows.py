"""Direct light with shadows against the ground truth, and the cost of the shadows.

For each scene: VTK's direct light through vtkMRGIPass (indirect light off)
with DirectShadows Off, Hard and Soft, against the CPU ground truth's
direct light (vtkMRGIReferenceRenderer, Shadows on and off). Errors are
relative RMS over 4x4-pixel box averages (C core metric, mrgi-compare), on
pixels lit in either image. The ground truth's own noise (pixel jitter
only: point lights have no sampling noise) is the same metric between two
ground truths with different seeds. Cost: GPU ms of the "shadows" stage and
wall ms per frame, medians over --frames frames after one warm-up, the
modes measured A B A B in one run.

    PYTHONPATH=build/lib/python3/dist-packages /usr/bin/python3 \
        Testing/Benchmarks/direct_shadows.py --build build --out Documentation
"""
import argparse
import csv
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(__file__))
import mrgi_bench as mb  # noqa: E402

import mrgi  # noqa: E402
from vtkmodules.vtkCommonDataModel import vtkImageData  # noqa: E402

MODES = (("off", 0), ("hard", 1), ("soft", 2))


def box_error(compare_tool, image, reference, scratch, tag, diff_png=None):
    return mb.box_error(compare_tool, image, reference, scratch, "direct-shadows-" + tag, diff_png)


def ground_truth(renderer, shadows, seed, passes):
    reference = mrgi.vtkMRGIReferenceRenderer()
    reference.SetShadows(shadows)
    reference.SetIndirectSamples(0)
    reference.SetTargetRelativeError(0.0)
    reference.SetMaxPasses(passes)
    reference.SetSeed(seed)
    assert reference.Render(renderer), reference.GetLastErrorMessage()
    return mb.to_numpy(reference.GetDirectImage())[..., :3]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default=os.path.join(mb.ROOT, "build"))
    parser.add_argument("--out", default=os.path.join(mb.ROOT, "Documentation"))
    parser.add_argument("--size", type=int, default=256)
    parser.add_argument("--passes", type=int, default=16, help="ground-truth passes (pixel jitter)")
    parser.add_argument("--frames", type=int, default=5)
    parser.add_argument("--scenes", default="cornell-spot,cornell")
    args = parser.parse_args()
    compare_tool, images, scratch = mb.folders(args.build, args.out)

    rows = []
    for name in args.scenes.split(","):
        window, renderer = mb.make_window(args.size, args.size)
        mb.build_scene(renderer, name)
        gi = mb.install_pass(renderer, IndirectMode=0, StageTimingEnabled=True)
        truth = ground_truth(renderer, True, 1, args.passes)
        truth2 = ground_truth(renderer, True, 2, args.passes)
        unshadowed_truth = ground_truth(renderer, False, 1, args.passes)
        noise = box_error(compare_tool, truth2, truth, scratch, name + "-noise")
        scale = 1.0 / max(1e-12, float(np.percentile(truth, 99.5)))
        mb.write_display(truth, os.path.join(images, "direct-shadows-%s-truth.png" % name), scale)
        images_by_mode = {}
        for label, mode in MODES:
            gi.SetDirectShadows(mode)
            window.Render()
            color = vtkImageData()
            assert gi.GetColorBuffer(window, color)
            images_by_mode[label] = mb.to_numpy(color)[..., :3]
            mb.write_display(images_by_mode[label],
                             os.path.join(images, "direct-shadows-%s-%s.png" % (name, label)), scale)
        # Cost, A B A B: every mode once per round, medians over the rounds.
        timings = {label: {"shadows": [], "frame": []} for label, _ in MODES}
        for _ in range(args.frames):
            for label, mode in MODES:
                gi.SetDirectShadows(mode)
                window.Render()  # the mode's first frame (programs, buffers) is not timed
                gi.FetchStageTimings(window, True)
                result = mb.frames(window, gi, 1)
                timings[label]["shadows"].append(result.get("shadows", 0.0))
                timings[label]["frame"].append(result["frame"])
        for label, _ in MODES:
            diff_png = os.path.join(images, "direct-shadows-%s-%s-diff.png" % (name, label))
            row = {
                "scene": name,
                "mode": label,
                "size": args.size,
                "rel_rms_vs_truth_shadowed": box_error(compare_tool, images_by_mode[label], truth, scratch,
                                                       "%s-%s" % (name, label), diff_png),
                "rel_rms_vs_truth_unshadowed": box_error(compare_tool, images_by_mode[label],
                                                         unshadowed_truth, scratch, "%s-%s-u" % (name, label)),
                "truth_noise": noise,
                "shadows_gpu_ms": float(np.median(timings[label]["shadows"])),
                "frame_ms": float(np.median(timings[label]["frame"])),
            }
            rows.append(row)
            print("%-12s %-4s vs truth with shadows %.4f, without %.4f (truth noise %.4f); shadows %.2f ms GPU, "
                  "frame %.1f ms" % (name, label, row["rel_rms_vs_truth_shadowed"],
                                     row["rel_rms_vs_truth_unshadowed"], noise, row["shadows_gpu_ms"],
                                     row["frame_ms"]))
        renderer.SetPass(None)
        gi.ReleaseGraphicsResources(window)
    path = os.path.join(scratch, "direct_shadows.csv")
    with open(path, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        writer.writeheader()
        writer.writerows(rows)
    print("wrote", path)


if __name__ == "__main__":
    main()
