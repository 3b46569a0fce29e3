"""Temporal flicker of the VPL selections along a light path and a camera orbit.

Issue 12 part 6. On `cornell-spot` (full-resolution gather, the indirect
buffer) two paths of K frames each (default 60):

- light path: the spot light's position moves 0.2% of the scene's
  bounding-box diagonal per frame sideways (+x), its focal point kept;
- camera orbit: the camera turns 0.5 degree per frame about the scene's
  vertical axis (the view-up through the focal point), from -K/4 to +K/4
  degrees so that the box stays centred.

Every selection row renders I_0..I_K-1 and the reference R_0..R_K-1 along the
same path; the flicker

    F = mean over k of rms((I_k+1 - I_k) - (R_k+1 - R_k)) / rms(R_k)

comes from the C core (mrgi_flicker.h through the mrgi-flicker tool), per
pixel and on 4x4 boxes; the per-frame relative RMS error against R from
mrgi-compare; the frame time is the median wall time of window.Render() along
the path (the light path reselects the VPLs every frame; tree rows run with
the gather's statistics on, which their VPLs-per-pixel count needs).

The reference is the dense one of issue 12 part 4, the VPL tree at tau = 0
(`--reference tree:0`, vtkMRGIPass::SetTreeThreshold); `grid:N` is accepted
too. The defaults (128 x 128, RSM 128) keep a dense frame near 2 s on
llvmpipe; at 256 x 256 with RSM 256 it is about 30 s.

"Equal average VPLs per pixel": in the full gather every pixel gathers every
VPL, so grid, importance and clusters have VPLs/pixel = their VPL count (the
clusters' count varies per frame: mean). The tree's is
GetGather().GetMeanVPLsPerPixel(); `tree:auto` picks tau from a small list by
rendering frame 0 of the path and keeping the tau whose mean VPLs per pixel is
closest to the 256 of the grid row (the budget of the issue's target).

    PYTHONPATH=build/lib/python3/dist-packages /usr/bin/python3 \\
        Testing/Benchmarks/temporal_flicker.py --build build --docs Documentation

writes Documentation/Temporal.md (between its <!-- temporal:NAME --> markers),
Documentation/data/temporal.csv and Documentation/images/temporal-*.png.
`--quick` (4 frames at 64 x 64, no page) is the smoke test.
"""
import argparse
import math
import os
import statistics
import subprocess
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(__file__))
import mrgi_bench as mb  # noqa: E402
from doc_markers import replace_between_markers  # noqa: E402

from vtkmodules.vtkCommonDataModel import vtkImageData  # noqa: E402

GRID, IMPORTANCE, CLUSTERS, TREE, BRSM = 0, 1, 2, 3, 4
ISM = 100  # not a selection: grid 256 with imperfect shadow maps (issue 13), `number` = lazy frames
DEFAULT_ROWS = ["grid:256", "importance:256:fixed", "importance:256:per-frame", "clusters", "tree:auto",
                "brsm:256", "brsm:256:1", "ism:8", "ism:1"]
TREE_TAUS = [1.0, 0.5, 0.2, 0.1, 0.05, 0.02, 0.01, 0.005, 0.002]
LIGHT_STEP = 0.002  # of the bounding-box diagonal per frame
ORBIT_STEP = 0.5  # degrees per frame


def parse_spec(spec):
    """'grid:256' -> (label, kind, number, seed rule); raises on nonsense."""
    parts = spec.split(":")
    kind = parts[0]
    if kind == "grid" and len(parts) == 2:
        return "grid %s" % parts[1], GRID, int(parts[1]), None
    if kind == "importance" and len(parts) in (2, 3):
        rule = parts[2] if len(parts) == 3 else "fixed"
        if rule not in ("fixed", "per-frame"):
            raise SystemExit("importance seed rule must be fixed or per-frame: " + spec)
        return "importance %s (%s seed)" % (parts[1], rule), IMPORTANCE, int(parts[1]), rule
    if kind == "clusters" and len(parts) == 1:
        return "clusters (default 4 / 0.25)", CLUSTERS, 256, None
    if kind == "brsm" and len(parts) in (2, 3):
        # brsm:N[:W]: W, the weight of this frame's pdf in its moving average
        # (BRSMTemporalWeight; 1 = re-estimated every frame, RIHKS11's rule).
        weight = float(parts[2]) if len(parts) == 3 else None
        label = "brsm %s" % parts[1] + ("" if weight is None else
                                        (" (pdf per frame)" if weight == 1.0 else " (pdf weight %g)" % weight))
        return label, BRSM, int(parts[1]), weight
    if kind == "ism" and len(parts) == 2:
        lazy = int(parts[1])
        return ("grid 256 + ISM, lazy over %d frames" % lazy if lazy > 1 else "grid 256 + ISM, full resampling"), \
            ISM, lazy, None
    if kind == "tree" and len(parts) == 2:
        tau = parts[1]
        return "tree tau %s" % tau, TREE, (None if tau == "auto" else float(tau)), None
    raise SystemExit("unknown selection %r (grid:N, importance:N[:fixed|per-frame], clusters, "
                     "tree:T, tree:auto, brsm:N[:W], ism:LAZY)" % spec)


def supported(gi, kind):
    """Whether this build has the row's machinery (older builds lack ISM and BRSM)."""
    if kind == ISM:
        return hasattr(gi, "SetIndirectVisibility")
    if kind == BRSM:
        gi.SetVPLSelectionMode(BRSM)
        ok = gi.GetVPLSelectionMode() == BRSM
        gi.SetVPLSelectionMode(GRID)
        return ok
    return True


def apply(gi, kind, number, seed_rule, frame):
    """Put the pass into a row's selection for frame `frame`."""
    if hasattr(gi, "SetIndirectVisibility"):
        gi.SetIndirectVisibility(1 if kind == ISM else 0)
    if kind == ISM:
        # The lazy update (RIHKS11 5.3) against resampling every point every frame.
        gi.SetISMLazyFrames(number)
        kind, number = GRID, 256
    gi.SetVPLSelectionMode(kind)
    if hasattr(gi.GetGather(), "SetCollectStatistics"):
        # The tree's VPLs per pixel is counted only with the gather's statistics on.
        gi.GetGather().SetCollectStatistics(kind == TREE)
    if kind == TREE:
        gi.SetTreeThreshold(number)
        gi.SetNumberOfVPLs(256)
        return
    gi.SetNumberOfVPLs(number)
    if kind == CLUSTERS:
        gi.SetClusterDepthThreshold(4.0)
        gi.SetClusterNormalThreshold(0.25)
    if kind == IMPORTANCE:
        gi.GetVPLSelection().SetSeed(1 + (frame if seed_rule == "per-frame" else 0))
    if kind == BRSM and hasattr(gi.GetVPLSelection(), "SetBRSMTemporalWeight"):
        selection = gi.GetVPLSelection()
        # seed_rule carries brsm:N:W's weight (None: the default).
        if not hasattr(apply, "default_weight"):
            apply.default_weight = selection.GetBRSMTemporalWeight()  # the pass's default, read once
        selection.SetBRSMTemporalWeight(seed_rule if seed_rule is not None else apply.default_weight)
        if frame == 0:
            selection.ResetBRSMHistory()  # every path starts without a history


def vpls_per_pixel(gi, kind):
    if kind == TREE:
        value = gi.GetGather().GetMeanVPLsPerPixel() if hasattr(gi.GetGather(), "GetMeanVPLsPerPixel") else -1
        if value < 0:
            raise SystemExit("the tree gather did not count its VPLs per pixel (GetMeanVPLsPerPixel %s)" % value)
        return float(value)
    return float(gi.GetVPLSelection().GetVPLCount())  # full gather: every pixel, every VPL


class Paths:
    """The two paths: set_pose(name, k) puts light and camera at frame k."""

    def __init__(self, renderer):
        self.renderer = renderer
        lights = renderer.GetLights()
        lights.InitTraversal()
        self.light = lights.GetNextItem()
        self.light_position = self.light.GetPosition()
        self.light_focal = self.light.GetFocalPoint()
        b = renderer.ComputeVisiblePropBounds()
        self.diagonal = math.sqrt((b[1] - b[0]) ** 2 + (b[3] - b[2]) ** 2 + (b[5] - b[4]) ** 2)
        camera = renderer.GetActiveCamera()
        self.camera = (camera.GetPosition(), camera.GetFocalPoint(), camera.GetViewUp())

    def set_pose(self, path, k, frames):
        p = self.light_position
        shift = LIGHT_STEP * self.diagonal * k if path == "light" else 0.0
        self.light.SetPosition(p[0] + shift, p[1], p[2])
        self.light.SetFocalPoint(*self.light_focal)
        camera = self.renderer.GetActiveCamera()
        camera.SetPosition(*self.camera[0])
        camera.SetFocalPoint(*self.camera[1])
        camera.SetViewUp(*self.camera[2])
        if path == "orbit":
            camera.Azimuth(ORBIT_STEP * (k - (frames - 1) / 2.0))
        self.renderer.ResetCameraClippingRange()


def render_sequence(window, gi, paths, path, frames, kind, number, seed_rule, folder, tag):
    """Render the path; returns (list of EXR paths, frames as arrays, ms, VPLs/pixel)."""
    files, images, walls, per_pixel = [], [], [], []
    apply(gi, kind, number, seed_rule, 0)
    paths.set_pose(path, 0, frames)
    window.Render()  # warm-up: shaders and resources of this selection
    for k in range(frames):
        apply(gi, kind, number, seed_rule, k)
        paths.set_pose(path, k, frames)
        start = time.perf_counter()
        window.Render()
        walls.append((time.perf_counter() - start) * 1e3)
        buffer = vtkImageData()
        assert gi.GetIndirectBuffer(window, buffer), "no indirect buffer"
        image = mb.to_numpy(buffer)[..., :3]
        if not np.isfinite(image).all():
            raise SystemExit("%s, %s path frame %d: non-finite pixels" % (tag, path, k))
        name = os.path.join(folder, "%s-%s-%03d.exr" % (path, tag, k))
        mb.write(image, name)
        files.append(name)
        images.append(image)
        per_pixel.append(vpls_per_pixel(gi, kind))
    return files, images, statistics.median(walls), float(np.mean(per_pixel))


def flicker(tool, files, reference_files, box):
    """(F, per-pair values) from mrgi-flicker."""
    out = subprocess.run([tool, "--pairs", "--box", str(box), *files, "--reference", *reference_files],
                         check=True, capture_output=True, text=True).stdout
    lines = [dict(item.split("=") for item in line.split()) for line in out.strip().splitlines()]
    return float(lines[-1]["flicker"]), [float(line["value"]) for line in lines[:-1]]


def choose_tau(window, gi, paths, path, frames, target):
    """tau from TREE_TAUS whose mean VPLs/pixel at frame 0 is closest to `target`."""
    paths.set_pose(path, 0, frames)
    best = None
    for tau in TREE_TAUS:
        apply(gi, TREE, tau, None, 0)
        window.Render()
        v = vpls_per_pixel(gi, TREE)
        print("  tree tau %g: %.1f VPLs per pixel" % (tau, v))
        if best is None or abs(v - target) < abs(best[1] - target):
            best = (tau, v)
    return best[0]


def strip(reference, rows, k, scale):
    """One picture: R_k, then |(I_k+1 - I_k) - (R_k+1 - R_k)| of each row, times `scale`."""
    dr = reference[k + 1] - reference[k]
    tiles = [reference[k] / max(1e-12, float(reference[k].max()))]
    tiles += [np.abs((images[k + 1] - images[k]) - dr) * scale for images in rows]
    gap = np.ones((reference[k].shape[0], 4, 3), np.float32)
    out = []
    for t in tiles:
        out += [t, gap]
    return np.concatenate(out[:-1], axis=1)


def plot(results, frames, path_png):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("no matplotlib: no plot")
        return
    fig, axes = plt.subplots(1, 2, figsize=(10, 3.4), sharey=True)
    for ax, path in zip(axes, ("light", "orbit")):
        for r in (r for r in results if r["path"] == path):
            ax.plot(range(len(r["pairs"])), r["pairs"], label=r["label"], lw=1)
        ax.set_title("%s path, per-pair flicker (per pixel)" % path)
        ax.set_xlabel("pair k")
        ax.set_yscale("log")
    axes[0].set_ylabel("rms(dI - dR) / rms(R_k)")
    axes[1].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path_png, dpi=80)
    print("wrote", path_png)


def publish(page, marker, lines):
    replace_between_markers(page, "temporal:%s" % marker, lines)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default=os.path.join(mb.ROOT, "build"))
    parser.add_argument("--docs", help="Documentation folder to write the page, CSV and images into")
    parser.add_argument("--scene", default="cornell-spot")
    parser.add_argument("--size", type=int, default=128)
    parser.add_argument("--frames", type=int, default=60)
    parser.add_argument("--rsm-size", type=int, default=128)
    parser.add_argument("--reference", default="tree:0", help="tree:0 (default) or grid:N")
    parser.add_argument("--rows", default=",".join(DEFAULT_ROWS),
                        help="comma-separated selections: grid:N, importance:N[:fixed|per-frame], "
                             "clusters, tree:T, tree:auto")
    parser.add_argument("--paths", default="light,orbit")
    parser.add_argument("--quick", action="store_true", help="4 frames at 64 x 64, no page (smoke test)")
    args = parser.parse_args()
    if args.quick:
        args.frames, args.size, args.docs = 4, 64, None
    if args.frames < 2:
        raise SystemExit("--frames must be at least 2")
    tool = os.path.join(args.build, "bin", "mrgi-flicker")
    compare_tool = os.path.join(args.build, "bin", "mrgi-compare")
    for t in (tool, compare_tool):
        if not os.access(t, os.X_OK):
            raise SystemExit("%s is not built" % t)
    scratch = os.path.join(args.build, "Testing", "Temporary", "temporal")
    os.makedirs(scratch, exist_ok=True)

    window, renderer = mb.make_window(args.size, args.size)
    description = mb.build_scene(renderer, args.scene)
    gi = mb.install_pass(renderer, IndirectMode=1, RSMResolution=args.rsm_size)
    window.Render()
    paths = Paths(renderer)
    print("%s, %d x %d, %d frames; light type %d, diagonal %.1f, light step %.2f per frame"
          % (description, args.size, args.size, args.frames, paths.light.GetLightType(), paths.diagonal,
             LIGHT_STEP * paths.diagonal))

    reference = args.reference
    ref_label, ref_kind, ref_number, _ = parse_spec(reference)
    rows = [parse_spec(spec.strip()) for spec in args.rows.split(",")]
    for row in [r for r in rows if not supported(gi, r[1])]:
        print("skipping %s: not in this build" % row[0])
        rows.remove(row)

    results = []
    strips = {}
    for path in args.paths.split(","):
        print("%s path: reference %s" % (path, ref_label))
        ref_files, ref_images, ref_ms, ref_vpp = render_sequence(
            window, gi, paths, path, args.frames, ref_kind, ref_number, None, scratch, "reference")
        row_images = []
        for label, kind, number, seed_rule in rows:
            if kind == TREE and number is None:
                grid_vpp = next((r["vpls_per_pixel"] for r in results
                                 if r["path"] == path and r["kind"] == GRID), 256.0)
                number = choose_tau(window, gi, paths, path, args.frames, grid_vpp)
                label = "tree tau %g (auto)" % number
            tag = "".join(c if c.isalnum() or c in "-." else "-" for c in label.split(" (")[0])
            files, images, ms, vpp = render_sequence(window, gi, paths, path, args.frames, kind, number,
                                                     seed_rule, scratch, tag)
            f_pixel, pairs = flicker(tool, files, ref_files, 1)
            f_box, _ = flicker(tool, files, ref_files, 4) if args.size >= 4 else (float("nan"), [])
            errors = [mb.compare(compare_tool, a, b)["relative_rms"] for a, b in zip(files, ref_files)]
            result = dict(path=path, label=label, kind=kind, vpls_per_pixel=vpp, flicker=f_pixel,
                          flicker_box=f_box, rel_rms=float(np.mean(errors)), frame_ms=ms,
                          reference_ms=ref_ms, pairs=pairs)
            results.append(result)
            row_images.append(images)
            print("  %-34s %7.1f VPLs/px  F %.4f (4x4 %.4f)  rel. RMS %.4f  frame %.0f ms (reference %.0f)"
                  % (label, vpp, f_pixel, f_box, result["rel_rms"], ms, ref_ms))
        if row_images:
            strips[path] = strip(ref_images, row_images, args.frames // 2 - 1 if args.frames > 2 else 0,
                                 8.0 / max(1e-12, float(ref_images[0].max())))
        del ref_images, row_images

    table = ["| path | selection | VPLs / pixel | flicker F per pixel | F 4x4 boxes | F / grid 256 | "
             "rel. RMS vs reference | median frame ms |",
             "|---|---|---|---|---|---|---|---|"]
    for r in results:
        grid = next((g for g in results if g["path"] == r["path"] and g["label"] == "grid 256"), None)
        ratio = "%.2f" % (r["flicker"] / grid["flicker"]) if grid and grid["flicker"] > 0 else "-"
        table.append("| %s | %s | %.0f | %.4f | %.4f | %s | %.4f | %.0f |"
                     % (r["path"], r["label"], r["vpls_per_pixel"], r["flicker"], r["flicker_box"], ratio,
                        r["rel_rms"], r["frame_ms"]))
    target = target_lines(results)
    print()
    print("\n".join(table))
    print()
    print("\n".join(target))
    if not args.docs:
        return
    images_dir = os.path.join(args.docs, "images")
    data_dir = os.path.join(args.docs, "data")
    os.makedirs(images_dir, exist_ok=True)
    os.makedirs(data_dir, exist_ok=True)
    for path, picture in strips.items():
        name = os.path.join(images_dir, "temporal-%s-strip.png" % path)
        mb.write(np.clip(picture, 0.0, 1.0), name)
        print("wrote", name)
    plot(results, args.frames, os.path.join(images_dir, "temporal-pairs.png"))
    csv = os.path.join(data_dir, "temporal.csv")
    with open(csv, "w") as f:
        f.write("path,selection,reference,frames,size,vpls_per_pixel,flicker,flicker_box4,rel_rms,"
                "frame_ms,reference_frame_ms\n")
        for r in results:
            f.write("%s,%s,%s,%d,%d,%.2f,%.6f,%.6f,%.6f,%.1f,%.1f\n"
                    % (r["path"], r["label"], ref_label, args.frames, args.size, r["vpls_per_pixel"],
                       r["flicker"], r["flicker_box"], r["rel_rms"], r["frame_ms"], r["reference_ms"]))
    print("wrote", csv)
    page = os.path.join(args.docs, "Temporal.md")
    setup = ["`%s`, %d x %d, RSM %d x %d, %d frames per path, full-resolution gather; reference: %s."
             % (args.scene, args.size, args.size, args.rsm_size, args.rsm_size, args.frames, ref_label)]
    setup += ["", "Load average when the run ended: %s." % ", ".join("%.1f" % x for x in os.getloadavg())]
    publish(page, "setup", setup)
    publish(page, "table", table)
    publish(page, "target", target)
    print("wrote the tables into", page)


def target_lines(results):
    """The issue's flicker target on the light path, measured against it."""
    light = {r["label"]: r for r in results if r["path"] == "light"}
    grid = light.get("grid 256")
    lines = ["| target (light path) | measured | met |", "|---|---|---|"]
    if not grid:
        return lines + ["| - | no grid 256 row | - |"]
    tree = next((r for r in light.values() if r["kind"] == TREE), None)
    if tree:
        lines.append("| tree <= 0.5 x grid 256 | %s: F %.4f = %.2f x grid's %.4f | %s |"
                     % (tree["label"], tree["flicker"], tree["flicker"] / grid["flicker"], grid["flicker"],
                        "yes" if tree["flicker"] <= 0.5 * grid["flicker"] else "no"))
    else:
        lines.append("| tree <= 0.5 x grid 256 | not measured (no VPL tree in this build) | - |")
    for path in ("light", "orbit"):
        rows = {r["label"]: r for r in results if r["path"] == path}
        lazy = next((r for r in rows.values() if r["kind"] == ISM and "lazy" in r["label"]), None)
        full = next((r for r in rows.values() if r["kind"] == ISM and "full" in r["label"]), None)
        if lazy and full:
            lines.append("| ISM lazy update below full resampling (%s path) | F %.4f against %.4f (%.2f x) | %s |"
                         % (path, lazy["flicker"], full["flicker"], lazy["flicker"] / max(1e-30, full["flicker"]),
                            "yes" if lazy["flicker"] < full["flicker"] else "no"))
        brsm = next((r for r in rows.values() if r["kind"] == BRSM), None)
        grid_row = rows.get("grid 256")
        if brsm and grid_row:
            lines.append("| BRSM no worse than grid 256 (%s path) | F %.4f against %.4f (%.2f x) | %s |"
                         % (path, brsm["flicker"], grid_row["flicker"],
                            brsm["flicker"] / max(1e-30, grid_row["flicker"]),
                            "yes" if brsm["flicker"] <= grid_row["flicker"] else "no"))
    clusters = next((r for r in light.values() if r["kind"] == CLUSTERS), None)
    if clusters:
        lines.append("| clusters < grid 256 | F %.4f = %.2f x grid's %.4f (%.0f VPLs/pixel against 256) | %s |"
                     % (clusters["flicker"], clusters["flicker"] / grid["flicker"], grid["flicker"],
                        clusters["vpls_per_pixel"], "yes" if clusters["flicker"] < grid["flicker"] else "no"))
    return lines


if __name__ == "__main__":
    main()
