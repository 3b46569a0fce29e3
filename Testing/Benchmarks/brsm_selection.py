"""Bidirectional RSM importance (BRSM, RIHKS11 section 4) against flux importance.

Issue 13 part 5's target: at an equal VPL count, on `corner` and `u-shape`
(RIHKS11 figures 5 and 10: the light falls mostly where the camera sees
little), BRSM's error is at least 20% lower than flux importance's. Also
the share of wasted VPLs (RIHKS11 figure 4).

Per scene (full-resolution gather, the irradiance buffer E):
- the dense reference: the VPL tree at tau = 0, every RSM texel its own VPL
  (issue 12's converged estimate of the same RSM integral: what a selection
  approximates, without the ground truth's other differences);
- grid N, flux importance N and BRSM N, the random ones over S seeds: the
  relative RMS of E against the dense reference per seed, and its mean
  (BRSM twice: each seed a first frame, and the seeds as consecutive
  frames whose pdfs the selection averages, BRSMTemporalWeight; then once
  more per --samples-per-texel K, the trade of the importance estimate's
  noise against its CPU cost);
- wasted VPLs: the VPLs (read back) whose summed irradiance at a 1-in-16
  subsample of the visible pixels (G-buffer read back, no visibility) is 0
  ("contribute nothing"), and those below 1% of the mean VPL's.

    PYTHONPATH=build/lib/python3/dist-packages /usr/bin/python3 \\
        Testing/Benchmarks/brsm_selection.py --build build --docs Documentation

writes the table into Documentation/IndirectShadows.md between its
<!-- brsm:table --> markers (the page's other sections are
indirect_shadows.py's). `--quick`: 64 x 64, 2 seeds, no page. Default 16 seeds.
"""
import argparse
import os
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(__file__))
import mrgi_bench as mb  # noqa: E402
from doc_markers import replace_between_markers  # noqa: E402

from vtkmodules.vtkCommonCore import vtkFloatArray  # noqa: E402
from vtkmodules.vtkCommonDataModel import vtkImageData  # noqa: E402
from vtkmodules.util.numpy_support import vtk_to_numpy  # noqa: E402

GRID, IMPORTANCE, TREE, BRSM = 0, 1, 3, 4
INDIRECT_FULL = 1


def irradiance(window, gi):
    window.Render()
    assert gi.GetIndirectComputed(), "no indirect light"
    image = vtkImageData()
    assert gi.GetIrradianceBuffer(window, image), "no irradiance buffer"
    e = mb.to_numpy(image)[..., :3].astype(np.float64)
    assert np.isfinite(e).all(), "non-finite irradiance"
    return e


def rel_rms(a, b):
    return float(np.sqrt(np.mean((a - b) ** 2)) / max(1e-30, np.sqrt(np.mean(b ** 2))))


def wasted(window, gi, renderer):
    """(share with zero contribution, share below 1% of the mean) of the last frame's VPLs."""
    vpls = vtkFloatArray()
    assert gi.GetVPLs(window, vpls), "no VPLs"
    v = vtk_to_numpy(vpls).reshape(-1, 12).astype(np.float64)
    position, normal, albedo = vtkImageData(), vtkImageData(), vtkImageData()
    assert gi.GetGBuffer(window, position, normal, albedo), "no G-buffer"
    p = mb.to_numpy(position).reshape(-1, 4)[::16]
    n = mb.to_numpy(normal).reshape(-1, 4)[::16, :3]
    valid = p[:, 3] > 0.5
    p, n = p[valid, :3].astype(np.float64), n[valid].astype(np.float64)
    n /= np.maximum(1e-30, np.linalg.norm(n, axis=1))[:, None]
    # Eye space -> world: the receivers meet the world-space VPLs there.
    m = renderer.GetActiveCamera().GetViewTransformMatrix()
    w2e = np.array([[m.GetElement(r, c) for c in range(4)] for r in range(4)])
    e2w = np.linalg.inv(w2e)
    P = p @ e2w[:3, :3].T + e2w[:3, 3]
    N = n @ e2w[:3, :3].T
    totals = []
    for row in v:
        pos, area, nor, flux = row[0:3], row[3], row[4:7], row[8:11]
        lum = 0.2126 * flux[0] + 0.7152 * flux[1] + 0.0722 * flux[2]
        if lum <= 0:
            totals.append(0.0)
            continue
        d = pos - P
        r2 = np.maximum(1e-30, np.sum(d * d, axis=1))
        ci = np.maximum(0.0, np.sum(N * d, axis=1))
        cj = np.maximum(0.0, -(d @ (nor / max(1e-30, np.linalg.norm(nor)))))
        totals.append(float(lum * np.sum(ci * cj / r2 / (np.pi * r2 + area))))
    totals = np.array(totals)
    mean = totals.mean() if len(totals) else 0.0
    return float(np.mean(totals == 0.0)), float(np.mean(totals < 0.01 * mean)), len(totals)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default=os.path.join(mb.ROOT, "build"))
    parser.add_argument("--docs")
    parser.add_argument("--scenes", default="corner,u-shape")
    parser.add_argument("--size", type=int, default=128)
    parser.add_argument("--rsm-size", type=int, default=128)
    parser.add_argument("--vpls", type=int, default=256)
    parser.add_argument("--seeds", type=int, default=16)
    parser.add_argument("--samples-per-texel", default="16,64",
                        help="extra BRSM rows with these view samples per texel (BRSMSamplesPerTexel; "
                             "the default row uses the class default)")
    parser.add_argument("--quick", action="store_true")
    args = parser.parse_args()
    if args.quick:
        args.size, args.seeds, args.docs = 64, 2, None
    lines = ["| scene | selection | VPLs | rel. RMS of E vs dense (mean over seeds) | min .. max | "
             "wasted: no contribution | wasted: < 1% of mean | frame ms |",
             "|---|---|---|---|---|---|---|---|"]
    verdicts = []
    for scene in args.scenes.split(","):
        window, renderer = mb.make_window(args.size, args.size)
        mb.build_scene(renderer, scene)
        gi = mb.install_pass(renderer, IndirectMode=INDIRECT_FULL, RSMResolution=args.rsm_size)
        gi.SetVPLSelectionMode(TREE)
        gi.SetTreeThreshold(0.0)
        start = time.perf_counter()
        dense = irradiance(window, gi)
        print("%s: dense reference in %.1f s" % (scene, time.perf_counter() - start))
        results = {}
        selection = gi.GetVPLSelection()
        temporal = hasattr(selection, "ResetBRSMHistory")
        # BRSM: one frame's pdf (the history restarted before each seed: the
        # seeds are independent trials); then, where the build has the
        # pdf's moving average (BRSMTemporalWeight), the same seeds as
        # consecutive frames of an unchanged view, each blending its pdf
        # into the previous ones' (the steady state of a slowly moving view).
        rows = [("grid", GRID, [1], True), ("flux importance", IMPORTANCE, range(1, args.seeds + 1), True),
                ("BRSM", BRSM, range(1, args.seeds + 1), True)]
        if temporal:
            rows.append(("BRSM, pdf averaged over the frames", BRSM, range(1, args.seeds + 1), False))
        default_k = selection.GetBRSMSamplesPerTexel() if hasattr(selection, "GetBRSMSamplesPerTexel") else None
        if default_k is not None:
            rows[2] = ("BRSM (K = %d view samples per texel)" % default_k,) + rows[2][1:]
            for k in [int(k) for k in args.samples_per_texel.split(",") if k]:
                rows.append(("BRSM, K = %d" % k, BRSM, range(1, args.seeds + 1), True, k))
        for row in rows:
            label, mode, seeds, restart = row[:4]
            if default_k is not None:
                selection.SetBRSMSamplesPerTexel(row[4] if len(row) > 4 else default_k)
            gi.SetVPLSelectionMode(mode)
            if gi.GetVPLSelectionMode() != mode:
                print("  %s: not in this build" % label)
                continue
            gi.SetNumberOfVPLs(args.vpls)
            errors, waste, waste1, times = [], [], [], []
            if temporal:
                selection.ResetBRSMHistory()
            for seed in seeds:
                if temporal and restart:
                    selection.ResetBRSMHistory()
                gi.GetVPLSelection().SetSeed(seed)
                start = time.perf_counter()
                e = irradiance(window, gi)
                times.append((time.perf_counter() - start) * 1e3)
                errors.append(rel_rms(e, dense))
                zero, low, count = wasted(window, gi, renderer)
                waste.append(zero)
                waste1.append(low)
            results[label] = float(np.mean(errors))
            print("  %-16s error %.4f (%.4f..%.4f), wasted %.1f%% / %.1f%%, %d VPLs"
                  % (label, np.mean(errors), min(errors), max(errors), 100 * np.mean(waste), 100 * np.mean(waste1),
                     count))
            lines.append("| %s | %s | %d | %.4f | %.4f .. %.4f | %.1f%% | %.1f%% | %.0f |"
                         % (scene, label, count, np.mean(errors), min(errors), max(errors), 100 * np.mean(waste),
                            100 * np.mean(waste1), float(np.median(times))))
        brsm_labels = [label for label in results if label.startswith("BRSM")]
        for brsm in brsm_labels:
            if brsm in results and "flux importance" in results:
                gain = 1.0 - results[brsm] / results["flux importance"]
                verdicts.append("| %s (%s) | error %.4f vs flux %.4f: %.0f%% %s | %s |"
                                % (scene, brsm, results[brsm], results["flux importance"], 100 * abs(gain),
                                   "lower" if gain >= 0 else "higher", "yes" if gain >= 0.2 else "no"))
        gi.ReleaseGraphicsResources(window)
        window.Finalize()
    table = lines + ["", "| target: BRSM >= 20% lower error than flux importance at equal VPLs | measured | met |",
                     "|---|---|---|"] + verdicts
    print("\n".join(table))
    if args.docs:
        page = os.path.join(args.docs, "IndirectShadows.md")
        setup = ["%d x %d, RSM %d x %d, %d VPLs, %d seeds; load average %s." % (
            args.size, args.size, args.rsm_size, args.rsm_size, args.vpls, args.seeds,
            ", ".join("%.1f" % x for x in os.getloadavg())), ""]
        replace_between_markers(page, "brsm:table", setup + table)
        print("wrote the table into", page)


if __name__ == "__main__":
    main()
