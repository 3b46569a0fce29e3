"""Indirect shadows (issue 13): MRGI's full-resolution gather without and with
VPL visibility against the ground truth with secondary visibility.

For each scene (cornell-spot, bunny-cornell, corridor, corridor-large,
corner, u-shape), the indirect light of the full gather (`IndirectFull`,
256 grid VPLs) with `--indirect-visibility off`, `ism` and `voxel` (ism and
voxel only where vtkMRGIPass has SetIndirectVisibility; otherwise off only,
and the page says so), and on the corridors ISM with uniform points beside
the default adaptive ones, against the CPU ground truth
(vtkMRGIReferenceRenderer, secondary visibility on, relative error target
0, --passes passes; its own noise is printed and written to the page).

Where the ISM stage has SetPushPullLevels, an extra row renders ISM without
push-pull at texel bias 1 (the defaults before session 12's one-level mean
push-pull) in the same run, for a before/after ratio on one machine load.

Reports relative RMS per pixel and after 4x4 box averaging (mrgi-compare,
the C core's metric) and the median wall time of a frame. On the corridors
also the indirect shadow's region mean against the truth's (the issue's
"within 20%" target): the region is where the truth WITH secondary
visibility is below 70% of a second truth WITHOUT it (4x4 boxes, boxes
under the median of the no-visibility truth left out), i.e. the pixels
that visibility darkens; defined from the truths alone, so it does not
depend on any method's output.

    PYTHONPATH=build/lib/python3/dist-packages /usr/bin/python3 \\
        Testing/Benchmarks/indirect_shadows.py --build build --docs Documentation

With --docs the tables go between the <!-- is:SCENE --> markers of
Documentation/IndirectShadows.md and the pictures (none, ISM, voxel,
truth; one scale per scene) into Documentation/images/indirectshadows-*.png.
--quick: 64 x 64, 4 passes (a smoke test of the script, not a measurement);
--check asserts the page's structure and, where ISM exists, that ISM is
closer to the truth than off on cornell-spot.
"""
import argparse
import os
import re
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import mrgi_bench as mb  # noqa: E402
from doc_markers import replace_between_markers  # noqa: E402

import mrgi  # noqa: E402

INDIRECT_FULL = 1
NO_PUSH_PULL = "ism, no push-pull, texel bias 1"
SCENES = "cornell-spot,bunny-cornell,corridor,corridor-large,corner,u-shape"
DESCRIPTIONS = {
    "corridor": "closed 12 m corridor, statue lit only indirectly (RIHKS11 fig. 7)",
    "corridor-large": "the corridor 120 m long (RIHKS11 fig. 10c, d scale test)",
    "corner": "open corner with a spot into it (RIHKS11 fig. 5)",
    "u-shape": "closed U, light in one arm, camera in the other (RIHKS11 fig. 10)",
}


def visibility_modes(gi):
    """(label, mode, ISM point mode or None) rows this build can render."""
    if not hasattr(gi, "SetIndirectVisibility"):
        return [("off", 0, None)]
    stage = getattr(mrgi, "vtkMRGIIndirectLight", None)
    off = getattr(stage, "VisibilityOff", 0)
    ism = getattr(stage, "VisibilityISM", 1)
    voxel = getattr(stage, "VisibilityVoxels", 2)
    return [("off", off, None), ("ism", ism, None), ("voxel", voxel, None)]


def truth(renderer, visibility, passes):
    reference = mrgi.vtkMRGIReferenceRenderer()
    reference.SetSecondaryVisibility(visibility)
    reference.SetTargetRelativeError(0.0)
    reference.SetMaxPasses(passes)
    start = time.time()
    assert reference.Render(renderer), reference.GetLastErrorMessage()
    image = mb.to_numpy(reference.GetIndirectImage())[..., :3]
    return image, (reference.GetPasses(), reference.GetPixelError(), reference.GetRelativeError(),
                   time.time() - start)


def shadow_region(vis, novis):
    """4x4 boxes that secondary visibility darkens below 70% (see the file comment)."""
    a, b = mb.boxes(vis).mean(axis=2), mb.boxes(novis).mean(axis=2)
    return (b > np.median(b)) & (a < 0.7 * b)


def run_scene(scene, args, compare_tool, scratch, images):
    window, renderer = mb.make_window(args.size, args.size)
    description = mb.build_scene(renderer, scene)
    if description is None:
        print("skipping %s: its data is not in %s" % (scene, mb.SHARED_DATA))
        return None
    description = DESCRIPTIONS.get(scene, description)
    gi = mb.install_pass(renderer, IndirectMode=INDIRECT_FULL, RSMResolution=args.rsm_size,
                         StageTimingEnabled=True)
    window.Render()
    ref, (passes, pixel_noise, mean_noise, seconds) = truth(renderer, True, args.passes)
    print("%s truth: %d passes, per-pixel error (95th percentile) %.4f, error of the mean %.5f, %.1f s"
          % (scene, passes, pixel_noise, mean_noise, seconds))
    ref_path = os.path.join(scratch, "is-%s-truth.exr" % scene)
    mb.write(ref, ref_path)
    scale = 1.0 / max(1e-12, float(np.percentile(ref, 99)))
    mb.write_display(ref, os.path.join(images, "indirectshadows-%s-truth.png" % scene), scale)
    region = None
    if scene.startswith("corridor"):
        novis, _ = truth(renderer, False, args.passes)
        region = shadow_region(ref, novis)
        print("%s shadow region: %d of %d 4x4 boxes" % (scene, int(region.sum()), region.size))

    rows = []
    modes = visibility_modes(gi)
    if scene.startswith("corridor") and len(modes) > 1:
        modes.insert(2, ("ism uniform points", modes[1][1], 0))
    stage = gi.GetIndirectLightStage() if hasattr(gi, "GetIndirectLightStage") else None
    ism_stage = stage.GetImperfectShadowMaps() if stage is not None else None
    old_lookup = ism_stage is not None and hasattr(ism_stage, "SetPushPullLevels")
    if old_lookup and len(modes) > 1:
        modes.insert(2, (NO_PUSH_PULL, modes[1][1], None))
    defaults = (ism_stage.GetPushPullLevels(), stage.GetISMTexelBias()) if old_lookup else None
    for label, mode, point_mode in modes:
        if hasattr(gi, "SetIndirectVisibility"):
            gi.SetIndirectVisibility(mode)
            if hasattr(gi, "SetISMPointMode"):
                gi.SetISMPointMode(2 if point_mode is None else point_mode)
        if old_lookup:
            old = label == NO_PUSH_PULL
            ism_stage.SetPushPullLevels(0 if old else defaults[0])
            stage.SetISMTexelBias(1.0 if old else defaults[1])
        window.Render()
        buffer = mb.vtkImageData()
        assert gi.GetIndirectBuffer(window, buffer)
        image = mb.to_numpy(buffer)[..., :3]
        assert np.isfinite(image).all(), "%s %s: non-finite pixels" % (scene, label)
        tag = re.sub(r"[^a-z0-9]+", "-", label).strip("-")
        path = os.path.join(scratch, "is-%s-%s.exr" % (scene, tag))
        mb.write(image, path)
        row = {"label": label,
               "pixel": mb.compare(compare_tool, path, ref_path)["relative_rms"],
               "box": mb.box_error(compare_tool, image, ref, scratch, "is-%s-%s" % (scene, tag)),
               "frame_ms": mb.frames(window, gi, args.repeats)["frame"]}
        if region is not None and region.any():
            row["region"] = float(mb.boxes(image).mean(axis=2)[region].mean() /
                                  mb.boxes(ref).mean(axis=2)[region].mean())
        if point_mode is None and label != NO_PUSH_PULL:
            mb.write_display(image, os.path.join(images, "indirectshadows-%s-%s.png" % (scene, tag)), scale)
        rows.append(row)
        print("%-8s %-20s per pixel %.4f  4x4 %.4f  frame %.1f ms%s" % (
            scene, label, row["pixel"], row["box"], row["frame_ms"],
            "  shadow region mean / truth %.3f" % row["region"] if "region" in row else ""))

    lines = ["Scene: %s, %d x %d, RSM %d x %d, full gather, 256 grid VPLs. Ground truth with secondary "
             "visibility: %d passes; its own noise: 95th percentile of the per-pixel relative standard "
             "error %.4f, relative error of the image mean %.5f (%.0f s)."
             % (description, args.size, args.size, args.rsm_size, args.rsm_size, passes, pixel_noise,
                mean_noise, seconds)]
    if len(visibility_modes(gi)) == 1:
        lines.append("This build has no `SetIndirectVisibility`: only `off` was measured.")
    lines += ["", "| visibility | rel. RMS per pixel | rel. RMS 4x4 boxes | frame ms (median) |%s" %
              (" shadow region mean / truth |" if region is not None else ""),
              "|---|---|---|---|%s" % ("---|" if region is not None else "")]
    for r in rows:
        lines.append("| %s | %.3f | %.3f | %.1f |%s" % (
            r["label"], r["pixel"], r["box"], r["frame_ms"],
            (" %.2f |" % r["region"] if "region" in r else " - |") if region is not None else ""))
    pictures = [r["label"] for r in rows
                if "uniform" not in r["label"] and r["label"] != NO_PUSH_PULL] + ["truth"]
    lines += ["", " ".join("![%s %s](images/indirectshadows-%s-%s.png)" % (scene, p, scene, p)
                           for p in pictures)]
    window.Finalize()
    return lines, rows


def check(scene, rows):
    labels = [r["label"] for r in rows]
    assert labels[0] == "off", labels
    for r in rows:
        assert np.isfinite(r["pixel"]) and np.isfinite(r["box"]) and r["frame_ms"] > 0, r
    if scene == "cornell-spot" and "ism" in labels:
        off, ism = rows[0]["box"], rows[labels.index("ism")]["box"]
        assert ism < off, "ism %.4f is not closer to the truth than off %.4f on cornell-spot" % (ism, off)
    print("check passed: %s (%s)" % (scene, ", ".join(labels)))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default=os.path.join(mb.ROOT, "build"))
    parser.add_argument("--out", default=None, help="folder for images (default: build/indirect-shadows)")
    parser.add_argument("--docs", default=None, help="Documentation folder whose page and images to rewrite")
    parser.add_argument("--scenes", default=SCENES)
    parser.add_argument("--size", type=int, default=256)
    parser.add_argument("--rsm-size", type=int, default=256)
    parser.add_argument("--passes", type=int, default=64, help="ground-truth passes")
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--quick", action="store_true", help="64 x 64, 4 passes (smoke test)")
    parser.add_argument("--check", action="store_true", help="assert the structure (exit non-zero)")
    args = parser.parse_args()
    if args.quick:
        args.size, args.rsm_size, args.passes, args.repeats = 64, 64, 4, 1
    out = args.docs or args.out or os.path.join(args.build, "indirect-shadows")
    compare_tool, images, scratch = mb.folders(args.build, out)
    start = time.time()
    for scene in args.scenes.split(","):
        result = run_scene(scene, args, compare_tool, scratch, images)
        if result is None:
            continue
        lines, rows = result
        for line in lines:
            print(line)
        if args.check:
            check(scene, rows)
        if args.docs:
            page = os.path.join(args.docs, "IndirectShadows.md")
            replace_between_markers(page, "is:%s" % scene, lines)
            print("wrote the %s table into %s" % (scene, page))
    print("total %.0f s" % (time.time() - start))


if __name__ == "__main__":
    main()
