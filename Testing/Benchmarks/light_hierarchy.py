"""Light-side hierarchy: error of the VPL selections against the converged
ground truth and against the dense reference, with their cost.

For each scene, the full-resolution gather's indirect light with grid VPLs,
multiresolution VPL clusters (nichols-shopf-wyman-2009 3.4) and the VPL tree
(3.5) at a sweep of thresholds tau, against

- the CPU ground truth without secondary visibility
  (vtkMRGIReferenceRenderer, relative error target 0, --passes passes; its
  own estimated relative error is printed and written to the page), and
- the dense reference: the tree at tau = 0, every RSM texel a VPL (65,536
  VPLs with a 256^2 RSM), the figure-9 reference of NSW09 (they use 1M VPLs).

Reports relative RMS per pixel and after 4x4 box averaging (both through
mrgi-compare, the C core's metric), VPLs per pixel (the tree's mean from the
gather's statistics; the VPL count for the other selections), the median GPU
gather time and its ratio to the 256-grid gather. The stenciled
multiresolution gather (vtkMRGIMultiresolution's Balanced preset, the
default) is measured with the same selections against the same references:
the "combined" light-side + eye-side error of NSW09 figure 9.

    PYTHONPATH=build/lib/python3/dist-packages /usr/bin/python3 \\
        Testing/Benchmarks/light_hierarchy.py --build build --docs Documentation

With --docs the tables go between the <!-- lh:SCENE --> markers of
Documentation/LightHierarchy.md and the difference images into
Documentation/images/lighthierarchy-*.png, and temporal_flicker.py then
regenerates the flicker page, Documentation/Temporal.md (--no-flicker skips
it; about 15 minutes in all on the 2-core llvmpipe machine of 2026-12-03); --quick runs a short sweep at
64 x 64 (a smoke test of the script, not a measurement).
"""
import argparse
import math
import os
import statistics
import subprocess
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import mrgi_bench as mb  # noqa: E402
from doc_markers import replace_between_markers  # noqa: E402

import mrgi  # noqa: E402
from vtkmodules.vtkCommonDataModel import vtkImageData  # noqa: E402

GRID, CLUSTERS, TREE = 0, 2, 3
INDIRECT_FULL, INDIRECT_MULTIRES = 1, 2
INF = math.inf

# (label, mode, VPLs asked, knobs): knobs are (depth, normal) thresholds for
# clusters, tau for the tree.
FULL_SETTINGS = [
    ("grid 256", GRID, 256, None),
    ("grid 1024", GRID, 1024, None),
    ("grid 4096", GRID, 4096, None),
    ("clusters 4 / 0.25 (default)", CLUSTERS, 256, (4.0, 0.25)),
    ("clusters 0 / 0 (every 64x64 node)", CLUSTERS, 256, (0.0, 0.0)),
    ("tree 1 (= grid 16x16)", TREE, 256, 1.0),
    ("tree 0.2", TREE, 256, 0.2),
    ("tree 0.1", TREE, 256, 0.1),
    ("tree 0.05 (default)", TREE, 256, 0.05),
    ("tree 0.02", TREE, 256, 0.02),
    ("tree 0.01", TREE, 256, 0.01),
    ("tree 0.005", TREE, 256, 0.005),
]
DENSE = ("tree 0 (dense reference)", TREE, 256, 0.0)
MULTIRES_SETTINGS = [
    ("grid 256", GRID, 256, None),
    ("clusters 4 / 0.25 (default)", CLUSTERS, 256, (4.0, 0.25)),
    ("tree 0.05 (default)", TREE, 256, 0.05),
    ("tree 0.01", TREE, 256, 0.01),
]
QUICK_TAUS = (1.0, 0.05)


def configure(gi, mode, vpls, knobs):
    gi.SetVPLSelectionMode(mode)
    gi.SetNumberOfVPLs(vpls)
    if mode == CLUSTERS:
        gi.SetClusterDepthThreshold(knobs[0])
        gi.SetClusterNormalThreshold(knobs[1])
    elif mode == TREE:
        gi.SetTreeThreshold(knobs)


def gather_ms(window, gi, repeats):
    """Median GPU ms of the "gather" stage over `repeats` frames, after one
    frame whose timings are dropped (the first frame after a settings change
    may report none)."""
    values = []
    window.Render()
    gi.FetchStageTimings(window, True)
    for _ in range(repeats):
        window.Render()
        for i in range(gi.FetchStageTimings(window, True)):
            if gi.GetStageName(i) == "gather":
                values.append(gi.GetStageTimeMilliseconds(i))
    return statistics.median(values) if values else float("nan")


def vpls_per_pixel(window, gi, mode):
    """The tree's mean VPLs per gathered texel (one frame with statistics);
    the VPL count for the flat selections."""
    if mode != TREE:
        return float(gi.GetVPLSelection().GetVPLCount())
    gather = gi.GetGather()
    gather.SetCollectStatistics(True)
    window.Render()
    mean = gather.GetMeanVPLsPerPixel() if hasattr(gather, "GetMeanVPLsPerPixel") else float("nan")
    gather.SetCollectStatistics(False)
    return mean


def indirect(window, gi, label):
    buffer = vtkImageData()
    assert gi.GetIndirectBuffer(window, buffer)
    image = mb.to_numpy(buffer)[..., :3]
    assert np.isfinite(image).all(), label + ": non-finite pixels"
    return image


def tag_of(label):
    return label.split(" (")[0].replace(" / ", "-").replace(" ", "-")


def errors(compare_tool, scratch, images, image, references, name, diff=False):
    """Relative RMS per pixel and on 4x4 boxes against each named reference."""
    path = os.path.join(scratch, "lh-%s.exr" % name)
    mb.write(image, path)
    result = {}
    for ref_name, (ref, ref_path) in references.items():
        diff_png = os.path.join(images, "lighthierarchy-%s-diff-%s.png" % (name, ref_name)) if diff else None
        result[ref_name + "_pixel"] = mb.compare(compare_tool, path, ref_path, diff_png, 4.0)["relative_rms"]
        result[ref_name + "_box"] = mb.box_error(compare_tool, image, ref, scratch, "lh-%s-%s" % (name, ref_name))
    return result


def measure(window, gi, settings, indirect_mode, references, args, compare_tool, scratch, images, scene, diff_tags,
            full_images=None):
    """One row per setting. With `full_images` (label -> full-gather image of
    the same selection), also the eye-side error: the multiresolution image
    against the full gather with the same VPLs (4x4 boxes)."""
    rows = []
    gi.SetIndirectMode(indirect_mode)
    for label, mode, vpls, knobs in settings:
        configure(gi, mode, vpls, knobs)
        window.Render()
        image = indirect(window, gi, label)
        name = "%s-%s-%s" % (scene, "full" if indirect_mode == INDIRECT_FULL else "multires", tag_of(label))
        row = {"label": label, "mode": mode}
        row.update(errors(compare_tool, scratch, images, image, references, name, diff=tag_of(label) in diff_tags))
        if full_images is None:
            row["image"] = image
        elif label in full_images:
            row["eye_box"] = mb.box_error(compare_tool, image, full_images[label], scratch, "lh-%s-eye" % name)
        repeats = 1 if (mode == TREE and knobs is not None and knobs <= 0.01) else args.repeats
        row["gather_ms"] = gather_ms(window, gi, repeats)
        row["vpls_per_pixel"] = vpls_per_pixel(window, gi, mode)
        rows.append(row)
        print("%-8s %-36s %9.1f VPL/px  truth %.4f / %.4f  dense %s  gather %.1f ms"
              % ("full" if indirect_mode == INDIRECT_FULL else "multires", label, row["vpls_per_pixel"],
                 row["truth_pixel"], row["truth_box"],
                 "%.4f / %.4f" % (row["dense_pixel"], row["dense_box"]) if "dense_pixel" in row else "-",
                 row["gather_ms"]))
    return rows


def table(rows, base_ms, dense):
    head = "| selection | VPLs / pixel | truth: rel. RMS per pixel | truth: 4x4 boxes |"
    rule = "|---|---|---|---|"
    if dense:
        head += " dense: per pixel | dense: 4x4 boxes |"
        rule += "---|---|"
    eye = any("eye_box" in r for r in rows)
    if eye:
        head += " eye side: vs full gather, 4x4 boxes |"
        rule += "---|"
    head += " gather ms | gather / grid 256 (full) |"
    rule += "---|---|"
    lines = [head, rule]
    for r in rows:
        line = "| %s | %.1f | %.3f | %.3f |" % (r["label"], r["vpls_per_pixel"], r["truth_pixel"], r["truth_box"])
        if dense:
            line += " %.3f | %.3f |" % (r["dense_pixel"], r["dense_box"])
        if eye:
            line += " %s |" % ("%.3f" % r["eye_box"] if "eye_box" in r else "-")
        line += " %.1f | %.2f |" % (r["gather_ms"], r["gather_ms"] / base_ms)
        lines.append(line)
    return lines


def run_scene(scene, args, compare_tool, scratch, images):
    window, renderer = mb.make_window(args.size, args.size)
    description = mb.build_scene(renderer, scene)
    if description is None:
        print("skipping %s: its data is not in %s" % (scene, mb.SHARED_DATA))
        return None
    gi = mb.install_pass(renderer, IndirectMode=INDIRECT_FULL, RSMResolution=args.rsm_size,
                        StageTimingEnabled=True)
    window.Render()

    reference = mrgi.vtkMRGIReferenceRenderer()
    reference.SetSecondaryVisibility(False)
    reference.SetTargetRelativeError(0.0)
    reference.SetMaxPasses(args.passes)
    start = time.time()
    assert reference.Render(renderer), reference.GetLastErrorMessage()
    truth = mb.to_numpy(reference.GetIndirectImage())[..., :3]
    truth_noise = (reference.GetPixelError(), reference.GetRelativeError())
    print("%s ground truth: %d passes, per-pixel error (95th percentile) %.4f, error of the mean %.5f, %.1f s"
          % (scene, reference.GetPasses(), truth_noise[0], truth_noise[1], time.time() - start))
    truth_path = os.path.join(scratch, "lh-%s-truth.exr" % scene)
    mb.write(truth, truth_path)
    references = {"truth": (truth, truth_path)}
    mb.write_display(truth, os.path.join(images, "lighthierarchy-%s-truth.png" % scene),
                     1.0 / max(1e-12, float(truth.max())))

    label, mode, vpls, tau = DENSE
    configure(gi, mode, vpls, tau)
    # One frame gives the image, the gather time and the VPL counts: at
    # 256^2 it takes minutes on llvmpipe.
    gi.GetGather().SetCollectStatistics(True)
    start = time.perf_counter()
    window.Render()
    wall_ms = (time.perf_counter() - start) * 1e3
    stage_ms = [gi.GetStageTimeMilliseconds(i) for i in range(gi.FetchStageTimings(window, True))
                if gi.GetStageName(i) == "gather"]
    dense_vpls = gi.GetGather().GetMeanVPLsPerPixel()
    gi.GetGather().SetCollectStatistics(False)
    dense = indirect(window, gi, label)
    dense_path = os.path.join(scratch, "lh-%s-dense.exr" % scene)
    mb.write(dense, dense_path)
    dense_row = {"label": label, "mode": TREE}
    dense_row.update(errors(compare_tool, scratch, images, dense, references, "%s-dense" % scene))
    dense_row["gather_ms"] = stage_ms[0] if stage_ms and math.isfinite(stage_ms[0]) else wall_ms
    dense_row["vpls_per_pixel"] = dense_vpls
    dense_row["dense_pixel"] = dense_row["dense_box"] = 0.0
    references["dense"] = (dense, dense_path)
    print("dense reference: truth %.4f / %.4f, %.1f VPL/px, gather %.1f ms"
          % (dense_row["truth_pixel"], dense_row["truth_box"], dense_row["vpls_per_pixel"],
             dense_row["gather_ms"]))

    full_settings = FULL_SETTINGS
    multires_settings = MULTIRES_SETTINGS
    if args.quick:
        full_settings = [s for s in FULL_SETTINGS if s[1] != TREE or s[3] in QUICK_TAUS][:2] + \
            [s for s in FULL_SETTINGS if s[1] == TREE and s[3] in QUICK_TAUS]
        multires_settings = MULTIRES_SETTINGS[:1]
    diff_tags = {"grid-256", "clusters-4-0.25", "tree-0.05", "tree-0.01"}
    full = measure(window, gi, full_settings, INDIRECT_FULL, references, args, compare_tool, scratch, images,
                   scene, diff_tags)
    if dense_row is not None:
        full.append(dense_row)
    full_images = {r["label"]: r.pop("image") for r in full if "image" in r}
    multires = measure(window, gi, multires_settings, INDIRECT_MULTIRES, references, args, compare_tool, scratch,
                       images, scene, set(), full_images)
    base_ms = full[0]["gather_ms"]
    has_dense = dense_row is not None
    lines = ["Scene: %s, %d x %d, RSM %d x %d. Ground truth: %d passes; its own noise: 95th percentile of the "
             "per-pixel relative standard error %.4f, relative error of the image mean %.5f."
             % (description, args.size, args.size, args.rsm_size, args.rsm_size, reference.GetPasses(),
                truth_noise[0], truth_noise[1]), "",
             "Full-resolution gather (`IndirectFull`):", ""]
    lines += table(full, base_ms, has_dense)
    lines += ["", "Stenciled multiresolution gather (`IndirectMultires`, Balanced preset):", ""]
    lines += table(multires, base_ms, has_dense)
    for line in lines:
        print(line)
    if args.check:
        check(full)
    window.Finalize()
    return lines


def check(full):
    """--check: the tree's invariants as the page shows them. tau = 1 gathers
    the 16 x 16 roots, i.e. grid 256 (same error against both references);
    tau = 0.05 is closer to the dense reference than grid 256."""
    rows = {r["label"].split(" (")[0]: r for r in full}
    grid, roots, tree = rows["grid 256"], rows["tree 1"], rows["tree 0.05"]
    for key in ("dense_box", "truth_box"):
        assert abs(roots[key] - grid[key]) <= 1e-3 * max(grid[key], 1e-6), \
            "tree 1 %s %.5f differs from grid 256's %.5f" % (key, roots[key], grid[key])
    assert tree["dense_box"] < 0.5 * grid["dense_box"], \
        "tree 0.05 is not closer to the dense reference: %.4f against grid 256's %.4f" % (
            tree["dense_box"], grid["dense_box"])
    print("check passed: tree 1 = grid 256 (%.4f), tree 0.05 %.4f < grid %.4f against dense"
          % (grid["dense_box"], tree["dense_box"], grid["dense_box"]))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default=os.path.join(mb.ROOT, "build"))
    parser.add_argument("--out", default=None, help="folder for images (default: build/light-hierarchy)")
    parser.add_argument("--docs", default=None, help="Documentation folder whose page and images to rewrite")
    parser.add_argument("--scenes", default="cornell-spot,bunny-cornell")
    parser.add_argument("--size", type=int, default=256)
    parser.add_argument("--rsm-size", type=int, default=256)
    parser.add_argument("--passes", type=int, default=64, help="ground-truth passes")
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--quick", action="store_true", help="64 x 64, 4 passes, a short sweep (smoke test)")
    parser.add_argument("--no-flicker", action="store_true",
                        help="with --docs, do not also run temporal_flicker.py (Temporal.md)")
    parser.add_argument("--check", action="store_true", help="assert the tree's invariants (exit non-zero)")
    args = parser.parse_args()
    if args.quick:
        args.size, args.rsm_size, args.passes, args.repeats = 64, 64, 4, 1
    out = args.docs or args.out or os.path.join(args.build, "light-hierarchy")
    compare_tool, images, scratch = mb.folders(args.build, out)
    for scene in args.scenes.split(","):
        lines = run_scene(scene, args, compare_tool, scratch, images)
        if lines is not None and args.docs:
            page = os.path.join(args.docs, "LightHierarchy.md")
            replace_between_markers(page, "lh:%s" % scene, lines)
            print("wrote the %s tables into %s" % (scene, page))
    if args.docs and not args.no_flicker:
        # The same command regenerates the flicker page (Temporal.md).
        subprocess.run([sys.executable, os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                                     "temporal_flicker.py"),
                        "--build", args.build, "--docs", args.docs], check=True)


if __name__ == "__main__":
    main()
