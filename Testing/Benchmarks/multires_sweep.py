"""The multiresolution speed/accuracy trade, measured (issue: multiresolution, part 9).

Sweeps depth threshold x normal threshold x finest level x VPL count on the
Cornell box (spot), the scaling scene and the real meshes in ../shared/data
when present. For every setting: GPU time per stage (medians over
--repeats frames, vtkRenderTimerLog), frame time, the share of the
full-resolution work gathered, relative RMS and maximum error against the
full-resolution gather and against the ground truth (C core metrics through
mrgi-compare), and the temporal flicker: the change of the error between two
frames with a slightly moved light (and, for the balance rule, a slightly
moved camera). Writes CSV, a PNG plot of error against time with the Pareto
frontier, images of the levels and difference images, and regenerates
Documentation/Multiresolution.md.

    bash scripts/install-deps.sh --benchmarks   # matplotlib, for the plots
    PYTHONPATH=build/lib/python3/dist-packages /usr/bin/python3 \\
        Testing/Benchmarks/multires_sweep.py --build build

Speed is reported as ratios within one run (the machine is shared and noisy).
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
from vtkmodules.vtkCommonCore import vtkFloatArray, vtkUnsignedCharArray  # noqa: E402
from vtkmodules.vtkCommonDataModel import vtkImageData  # noqa: E402
from vtkmodules.util.numpy_support import vtk_to_numpy  # noqa: E402

INDIRECT_STAGES = ("select", "gather", "upsample")
LEVEL_COLOURS = np.array([[0.85, 0.1, 0.1], [1.0, 0.55, 0.0], [0.95, 0.9, 0.1], [0.2, 0.75, 0.2],
                          [0.1, 0.75, 0.85], [0.15, 0.3, 0.9], [0.65, 0.2, 0.85], [1.0, 1.0, 1.0]])


def parse_list(text, kind=float):
    return [kind(v) if v != "inf" else math.inf for v in text.split(",")]


class Bench:
    """One scene in one window, with the MRGI pass and its timer."""

    def __init__(self, args, scene, triangles=None):
        self.args = args
        self.window, self.renderer = mb.make_window(args.size, args.size)
        if triangles is not None:
            builder = mrgi.vtkMRGISceneBuilder()
            builder.SetScene("scaling")
            builder.SetTriangleCount(triangles)
            assert builder.Build(self.renderer), builder.GetLastErrorMessage()
            self.description = "scaling scene, %d triangles" % triangles
        else:
            self.description = mb.build_scene(self.renderer, scene)
        if self.description is None:
            return
        self.gi = mb.install_pass(self.renderer)
        self.gi.SetStageTimingEnabled(True)
        self.window.GetRenderTimer().SetLoggingEnabled(True)
        self.mr = self.gi.GetMultiresolution()
        self.gather = self.gi.GetGather()
        self.light = self.renderer.GetLights().GetItemAsObject(0)
        self.camera = self.renderer.GetActiveCamera()

    def frames(self, count):
        """Render `count` frames; median GPU ms per stage and wall ms per frame."""
        return mb.frames(self.window, self.gi, count)

    def indirect(self):
        image = vtkImageData()
        assert self.gi.GetIndirectBuffer(self.window, image)
        return mb.to_numpy(image)[..., :3]

    def move_light(self, sign):
        """Nudge the light by 0.2% of the scene's size (sign +1 / -1 undoes it)."""
        b = self.renderer.ComputeVisiblePropBounds()
        step = 0.002 * max(b[1] - b[0], b[3] - b[2], b[5] - b[4])
        p = self.light.GetPosition()
        f = self.light.GetFocalPoint()
        self.light.SetPosition(p[0] + sign * step, p[1], p[2])
        self.light.SetFocalPoint(f[0] + sign * step, f[1], f[2])

    def move_camera(self, sign):
        self.camera.Azimuth(sign * 0.25)

    def release(self):
        self.renderer.SetPass(None)
        self.gi.ReleaseGraphicsResources(self.window)


def configure(bench, mode, depth=4.0, normal=0.25, finest=0, vpls=256, balance=True, illumination=None):
    """illumination: None for the geometric refinement, else the illumination threshold T."""
    bench.gi.SetIndirectMode(mode)
    bench.gi.SetRefinement(0 if illumination is None else 1)  # at any window size
    if illumination is not None:
        # "cT": the curvature metric at threshold T; "T": the difference metric
        curvature = str(illumination).startswith("c")
        bench.gi.GetIndirectLightStage().GetIlluminationStencil().SetIlluminationMetric(1 if curvature else 0)
        bench.gi.SetIlluminationThreshold(float(str(illumination).lstrip("c")))
    bench.gi.SetNumberOfVPLs(vpls)
    bench.mr.SetDepthThreshold(-1.0 if math.isinf(depth) else depth)
    bench.mr.SetNormalThreshold(-1.0 if math.isinf(normal) else normal)
    bench.mr.SetFinestLevel(finest)
    bench.mr.SetBalance(balance)


def save(array, path):
    mb.write(np.asarray(array, dtype=np.float32), path)
    return path


def metrics(compare_tool, image_path, reference_path, peak):
    m = mb.compare(compare_tool, image_path, reference_path)
    return m["relative_rms"], m["max"] / max(peak, 1e-30)


def flicker(bench, first, reference_first, reference_second, move):
    """Change of the error between two frames: rms((M2 - M1) - (F2 - F1)) / rms(F1)."""
    move(+1)
    bench.window.Render()
    second = bench.indirect()
    move(-1)
    change = (second - first) - (reference_second - reference_first)
    return float(np.sqrt(np.mean(change ** 2)) / max(np.sqrt(np.mean(reference_first ** 2)), 1e-30))


def level_image(bench):
    """Colour per pixel: the level whose texel gathered it (as NW09 figure 3 shows them)."""
    mask = vtkUnsignedCharArray()
    assert bench.mr.ReadSelection(bench.window, mask, True)
    flat_w = bench.mr.GetFlattenedWidth()
    flat = vtk_to_numpy(mask).reshape(bench.mr.GetFlattenedHeight(), flat_w)
    W = H = bench.args.size
    image = np.zeros((H, W, 3), dtype=np.float32)
    offset = 0
    for level in range(bench.mr.GetNumberOfLevels()):
        size = [0, 0]
        bench.mr.GetLevelSize(level, size)
        w, h = size
        selected = flat[:h, offset:offset + w]
        up = np.kron(selected, np.ones((1 << level, 1 << level), dtype=np.uint8))[:H, :W]
        image[up > 0] = LEVEL_COLOURS[min(level, len(LEVEL_COLOURS) - 1)]
        offset += w
    return image[::-1]  # rows top-down for the PNG


def pareto(rows, x, y):
    """Rows not dominated in (x, y), both lower-is-better, sorted by x."""
    front = []
    for r in sorted(rows, key=lambda r: (r[x], r[y])):
        if not front or r[y] < front[-1][y]:
            front.append(r)
    return front


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default=os.path.join(mb.ROOT, "build"))
    parser.add_argument("--doc", default=os.path.join(mb.ROOT, "Documentation"))
    parser.add_argument("--size", type=int, default=1024)
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--depth", default="4,8,16,64,inf")
    parser.add_argument("--normal", default="0.25,0.5,1,inf")
    parser.add_argument("--finest", default="0,1")
    parser.add_argument("--illumination", default="none,0.05,0.1,0.2",
                        help="refinement per setting: none (geometry), illumination thresholds T "
                             "(difference metric) or cT (curvature metric)")
    parser.add_argument("--vpls", default="64,256,1024")
    parser.add_argument("--grid-vpls", default="256",
                        help="VPL counts at which the whole threshold grid runs; at the other counts of --vpls, "
                             "only the presets")
    parser.add_argument("--scenes", default="cornell-spot,bunny-cornell")
    parser.add_argument("--scaling", default="10000,1000000", help="triangle counts of the scaling scene")
    parser.add_argument("--truth-passes", type=int, default=16, help="ground-truth passes (16 rays each)")
    parser.add_argument("--no-doc", action="store_true", help="do not rewrite Documentation/Multiresolution.md")
    parser.add_argument("--splat-vpls", default="64,256",
                        help="VPL counts of the stenciled gather vs multiresolution splatting comparison "
                             "(empty: skip it)")
    parser.add_argument("--skip-sweep", action="store_true",
                        help="measure only the splatting comparison; with --previous, the page keeps the "
                             "earlier sweep")
    parser.add_argument("--previous", help="CSV of an earlier run: its settings not measured again are kept "
                                           "(the page and the plot then combine both runs)")
    args = parser.parse_args()
    compare_tool = os.path.join(args.build, "bin", "mrgi-compare")
    scratch = os.path.join(args.build, "Testing", "Temporary", "sweep")
    images = os.path.join(args.doc, "images")
    os.makedirs(scratch, exist_ok=True)
    os.makedirs(images, exist_ok=True)
    presets = {}
    for index in range(3):
        settings = [0.0, 0.0, 0.0]
        assert mrgi.vtkMRGIMultiresolution.GetPresetSettings(index, settings)
        # settings[3]: the illumination threshold, -1 for geometry alone
        settings.append(mrgi.vtkMRGIMultiresolution.GetPresetIlluminationThreshold(index))
        presets[mrgi.vtkMRGIMultiresolution.GetPresetName(index)] = settings

    rows = []
    splats = []
    notes = {}
    for scene in args.scenes.split(","):
        bench = Bench(args, scene)
        if bench.description is None:
            print("skipping %s: its data is not in %s" % (scene, mb.SHARED_DATA))
            continue
        notes[scene] = bench.description
        for vpls in (parse_list(args.splat_vpls, int) if args.splat_vpls else []):
            splats += splat_compare(bench, scene, vpls, presets, args.repeats)
        for vpls in ([] if args.skip_sweep else parse_list(args.vpls, int)):
            # The full-resolution gather: the reference for speed and error.
            configure(bench, mrgi.vtkMRGIPass.IndirectFull, vpls=vpls)
            full_t = bench.frames(args.repeats)
            full = bench.indirect()
            full_path = save(full, os.path.join(scratch, "%s-%d-full.exr" % (scene, vpls)))
            peak = float(full.max())
            bench.move_light(+1)
            bench.window.Render()
            full_light = (full, bench.indirect())
            bench.move_light(-1)
            bench.move_camera(+1)
            bench.window.Render()
            full_camera = bench.indirect()
            bench.move_camera(-1)
            configure(bench, mrgi.vtkMRGIPass.IndirectOff)
            off_t = bench.frames(args.repeats)
            # Ground truth (CPU), once per scene and VPL count.
            truth_path = None
            if args.truth_passes > 0:
                reference = mrgi.vtkMRGIReferenceRenderer()
                reference.SetTargetRelativeError(0.0)
                reference.SetMaxPasses(args.truth_passes)
                reference.SetWidth(args.size)
                reference.SetHeight(args.size)
                assert reference.Render(bench.renderer), reference.GetLastErrorMessage()
                truth = mb.to_numpy(reference.GetIndirectImage())[..., :3]
                truth_path = save(truth, os.path.join(scratch, "%s-truth.exr" % scene))
                truth_peak = float(truth.max())
                full_truth = metrics(compare_tool, full_path, truth_path, truth_peak)
            print("%s, %d VPLs: full gather %.1f ms GPU, frame %.1f ms (GI off: %.1f ms)"
                  % (scene, vpls, full_t.get("gather", 0.0), full_t["frame"], off_t["frame"]))
            rows.append(dict(scene=scene, vpls=vpls, mode="full", depth="", normal="", finest="", illumination="",
                             balance="", select=0.0, gather=full_t.get("gather", 0.0), upsample=0.0,
                             indirect=full_t.get("gather", 0.0), frame=full_t["frame"], work=1.0,
                             rel_rms_full=0.0, rel_max_full=0.0,
                             rel_rms_truth=full_truth[0] if truth_path else "",
                             rel_max_truth=full_truth[1] if truth_path else "",
                             flicker_light=0.0, flicker_camera=0.0, gather_speedup=1.0, indirect_speedup=1.0))
            grid = vpls in parse_list(args.grid_vpls, int)
            lights = [None if v == "none" else illumination_key(v) for v in args.illumination.split(",")]
            settings = [(d, n, f, True, il) for d in parse_list(args.depth) for n in parse_list(args.normal)
                        for f in parse_list(args.finest, int) for il in lights] if grid else []
            for name, p in presets.items():
                pd, pn = (p[0] if p[0] >= 0 else math.inf), (p[1] if p[1] >= 0 else math.inf)
                pl = None if len(p) < 4 or p[3] < 0 else float(p[3])
                settings.append((pd, pn, int(p[2]), True, pl))
                settings.append((pd, pn, int(p[2]), False, pl))
            seen = set()
            for depth, normal, finest, balance, illumination in settings:
                if (depth, normal, finest, balance, illumination) in seen:
                    continue
                seen.add((depth, normal, finest, balance, illumination))
                configure(bench, mrgi.vtkMRGIPass.IndirectMultires, depth, normal, finest, vpls, balance,
                          illumination)
                t = bench.frames(args.repeats)
                bench.gather.SetCollectStatistics(True)
                bench.window.Render()
                work = bench.gather.GetGatherWorkFraction()
                bench.gather.SetCollectStatistics(False)
                image = bench.indirect()
                path = save(image, os.path.join(scratch, "%s-%d-mr.exr" % (scene, vpls)))
                vs_full = metrics(compare_tool, path, full_path, peak)
                vs_truth = metrics(compare_tool, path, truth_path, truth_peak) if truth_path else ("", "")
                flick_light = flicker(bench, image, full_light[0], full_light[1], bench.move_light)
                flick_camera = flicker(bench, image, full, full_camera, bench.move_camera)
                indirect_ms = sum(t.get(s, 0.0) for s in INDIRECT_STAGES)
                row = dict(scene=scene, vpls=vpls, mode="multires", depth=depth, normal=normal, finest=finest,
                           balance=int(balance), illumination="" if illumination is None else illumination, select=t.get("select", 0.0), gather=t.get("gather", 0.0),
                           upsample=t.get("upsample", 0.0), indirect=indirect_ms, frame=t["frame"], work=work,
                           rel_rms_full=vs_full[0], rel_max_full=vs_full[1], rel_rms_truth=vs_truth[0],
                           rel_max_truth=vs_truth[1], flicker_light=flick_light, flicker_camera=flick_camera,
                           gather_speedup=full_t.get("gather", 0.0) / max(t.get("gather", 0.0), 1e-9),
                           indirect_speedup=full_t.get("gather", 0.0) / max(indirect_ms, 1e-9))
                for step in ("select.mipmap0", "select.mipmaps", "select.flags0", "select.flags",
                             "select.stencil", "gather.receivers", "gather.vpls", "upsample.levels",
                             "upsample.resolve"):
                    row[step] = t.get(step, 0.0)
                rows.append(row)
                print("  illumination %-5s depth %-5s normal %-5s finest %d balance %d: select %.1f gather %.1f upsample %.1f ms, "
                      "work %.3f, gather x%.1f, indirect x%.1f, rel. RMS %.4f (max %.3f), flicker %.4f / %.4f"
                      % (row["illumination"] if illumination is not None else "-", depth, normal, finest, balance,
                         row["select"], row["gather"], row["upsample"], work,
                         row["gather_speedup"], row["indirect_speedup"], vs_full[0], vs_full[1], flick_light,
                         flick_camera))
                # Pictures for the page: levels and differences at each preset.
                for pname, p in presets.items():
                    pd = p[0] if p[0] >= 0 else math.inf
                    pn = p[1] if p[1] >= 0 else math.inf
                    pl = None if len(p) < 4 or p[3] < 0 else float(p[3])
                    if (pd, pn, int(p[2]), True, pl) == (depth, normal, finest, balance, illumination) \
                            and scene == "cornell-spot":
                        mb.write(level_image(bench), os.path.join(images, "multires-levels-%s.png" % pname))
                        mb.compare(compare_tool, path, full_path,
                                   os.path.join(images, "multires-diff-%s.png" % pname), diff_scale=8.0)
                        scale = 1.0 / max(peak, 1e-12)
                        mb.write_display(image, os.path.join(images, "multires-indirect-%s.png" % pname), scale)
                        if pname == "balanced":
                            mb.write_display(full, os.path.join(images, "multires-indirect-full.png"), scale)
        bench.release()

    # Cost against triangles (fixed screen coverage), Balanced preset.
    scaling = []
    for triangles in (parse_list(args.scaling, int) if args.scaling else []):
        bench = Bench(args, "scaling", triangles)
        p = presets["balanced"]
        results = {}
        for label, mode in (("off", mrgi.vtkMRGIPass.IndirectOff), ("gi", mrgi.vtkMRGIPass.IndirectMultires)):
            configure(bench, mode, p[0] if p[0] >= 0 else math.inf, p[1] if p[1] >= 0 else math.inf, int(p[2]),
                      illumination=p[3] if p[3] >= 0 else None)
            bench.frames(1)
            static = bench.frames(args.repeats)
            # A light that moves every frame re-renders the RSM each time.
            moving = []
            for i in range(args.repeats):
                bench.move_light(+1 if i % 2 == 0 else -1)
                moving.append(bench.frames(1))
            results[label] = (static, {k: float(np.median([m.get(k, 0.0) for m in moving])) for k in moving[0]})
        overhead_static = results["gi"][0]["frame"] - results["off"][0]["frame"]
        overhead_moving = results["gi"][1]["frame"] - results["off"][1]["frame"]
        gpu_overhead = sum(results["gi"][1].get(s, 0.0) for s in ("rsm", "vpl", "select", "gather", "upsample", "add"))
        scaling.append(dict(triangles=triangles, frame_off=results["off"][0]["frame"],
                            frame_gi=results["gi"][0]["frame"], overhead_static=overhead_static,
                            overhead_moving=overhead_moving, gpu_overhead_moving=gpu_overhead,
                            rsm=results["gi"][1].get("rsm", 0.0)))
        print("scaling %d triangles: frame off %.1f, GI %.1f ms; GI overhead %.1f ms (static light), %.1f ms "
              "(moving light; GPU %.1f ms, RSM %.1f ms)" % (triangles, results["off"][0]["frame"],
                                                          results["gi"][0]["frame"], overhead_static,
                                                          overhead_moving, gpu_overhead,
                                                          results["gi"][1].get("rsm", 0.0)))
        bench.release()

    splat_csv = os.path.join(args.doc, "data", "multires-splatting.csv")
    if splats:
        os.makedirs(os.path.dirname(splat_csv), exist_ok=True)
        with open(splat_csv, "w", newline="") as f:
            writer = csv.DictWriter(f, fieldnames=list(splats[0].keys()))
            writer.writeheader()
            writer.writerows(splats)
    elif os.path.exists(splat_csv):
        with open(splat_csv, newline="") as f:
            splats = [{k: (v if k in ("scene", "preset") else float(v)) for k, v in r.items()}
                      for r in csv.DictReader(f)]
    if args.previous:
        def key(r):
            return tuple(str(r.get(k, "")) for k in ("scene", "vpls", "mode", "depth", "normal", "finest",
                                                        "balance")) + (illumination_key(r.get("illumination", "")),)
        measured = {key(r) for r in rows}
        with open(args.previous, newline="") as f:
            for r in csv.DictReader(f):
                for k, v in r.items():
                    if k in ("scene", "mode") or v == "":
                        continue
                    r[k] = int(v) if k in ("vpls", "finest", "balance") else float(v)
                if key(r) not in measured:
                    rows.append(r)
        if not scaling:
            previous_scaling = os.path.join(os.path.dirname(args.previous), "multires-scaling.csv")
            if os.path.exists(previous_scaling):
                with open(previous_scaling, newline="") as f:
                    scaling = [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]
                for r in scaling:
                    r["triangles"] = int(r["triangles"])
    csv_path = os.path.join(scratch, "multires-sweep.csv")
    keys = []
    for r in rows:
        keys += [k for k in r if k not in keys]
    with open(csv_path, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=keys)
        writer.writeheader()
        writer.writerows(rows)
    doc_csv = os.path.join(args.doc, "data")
    os.makedirs(doc_csv, exist_ok=True)
    with open(os.path.join(doc_csv, "multires-sweep.csv"), "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=keys)
        writer.writeheader()
        writer.writerows(rows)
    if scaling:
        with open(os.path.join(doc_csv, "multires-scaling.csv"), "w", newline="") as f:
            writer = csv.DictWriter(f, fieldnames=list(scaling[0].keys()))
            writer.writeheader()
            writer.writerows(scaling)
    print("wrote %s" % csv_path)

    plot(rows, presets, os.path.join(images, "multires-tradeoff.png"))
    if not args.no_doc:
        write_page(args, rows, scaling, splats, presets, notes, os.path.join(args.doc, "Multiresolution.md"))


def splat_compare(bench, scene, vpls, presets, repeats):
    """Stenciled gather against multiresolution splatting at each preset: the same texels, the same numbers
    (checked), GPU time of the gathering step ("gather.vpls") in both, frames interleaved so that load on
    the machine hits both alike."""
    out = []
    stenciled, splatting = mrgi.vtkMRGIGather.GatherStenciled, mrgi.vtkMRGIGather.GatherSplatting
    # Splatting has no illumination rule: both gather each preset's geometric selection.
    for name, p in presets.items():
        configure(bench, mrgi.vtkMRGIPass.IndirectMultires, p[0] if p[0] >= 0 else math.inf,
                  p[1] if p[1] >= 0 else math.inf, int(p[2]), vpls)
        flat = {}
        for mode in (stenciled, splatting):  # warm-up (shader builds) and the outputs
            bench.gather.SetGatherMode(mode)
            bench.gather.SetCollectStatistics(True)
            bench.window.Render()
            bench.gather.SetCollectStatistics(False)
            array = vtkFloatArray()
            assert bench.gather.ReadIrradiance(bench.window, array)
            flat[mode] = vtk_to_numpy(array).copy()
        work = bench.gather.GetGatherWorkFraction()
        peak = float(np.abs(flat[stenciled][:, :3]).max())
        difference = float(np.abs(flat[splatting] - flat[stenciled]).max()) / max(peak, 1e-30)
        times = {stenciled: [], splatting: []}
        lists = []
        for _ in range(repeats):
            for mode in (stenciled, splatting):
                bench.gather.SetGatherMode(mode)
                t = bench.frames(1)
                times[mode].append(t.get("gather.vpls", 0.0))
                if mode == splatting:
                    lists.append(t.get("gather.subsplats", 0.0))
        bench.gather.SetGatherMode(stenciled)
        a, b = float(np.median(times[stenciled])), float(np.median(times[splatting]))
        row = dict(scene=scene, vpls=vpls, preset=name, work=work, stenciled_ms=a, splatting_ms=b,
                   speedup=b / max(a, 1e-9), subsplat_list_ms=float(np.median(lists)),
                   max_difference=difference)
        print("  %s, %d VPLs, %s: stenciled gather %.1f ms, splatting %.1f ms (x%.1f; list %.1f ms), "
              "max |difference| %.2g of the peak" % (scene, vpls, name, a, b, row["speedup"],
                                                     row["subsplat_list_ms"], difference))
        out.append(row)
    return out


def illumination_key(value):
    """A row's refinement: None (geometry), a threshold, or "cT" (curvature metric)."""
    if value in ("", None):
        return None
    return str(value) if str(value).startswith("c") else float(value)


def matches(row, preset, balance=1):
    d = preset[0] if preset[0] >= 0 else math.inf
    n = preset[1] if preset[1] >= 0 else math.inf
    il = None if len(preset) < 4 or preset[3] < 0 else float(preset[3])
    return (row["mode"] == "multires" and row["depth"] == d and row["normal"] == n
            and row["finest"] == int(preset[2]) and row["balance"] == balance
            and illumination_key(row.get("illumination", "")) == il)


def plot(rows, presets, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    scenes = sorted({r["scene"] for r in rows}, key=lambda s: s != "cornell-spot")
    fig, axes = plt.subplots(1, len(scenes), figsize=(6.5 * len(scenes), 5), squeeze=False)
    for ax, scene in zip(axes[0], scenes):
        mine = [r for r in rows if r["scene"] == scene and r["mode"] == "multires" and r["balance"] == 1]
        full = [r for r in rows if r["scene"] == scene and r["mode"] == "full"]
        for vpls in sorted({r["vpls"] for r in mine}):
            sel = [r for r in mine if r["vpls"] == vpls]
            ax.scatter([r["indirect"] for r in sel], [100 * r["rel_rms_full"] for r in sel], s=14,
                       label="settings, %d VPLs" % vpls)
            front = pareto(sel, "indirect", "rel_rms_full")
            ax.plot([r["indirect"] for r in front], [100 * r["rel_rms_full"] for r in front], "k-", lw=1,
                    label="Pareto frontier" if vpls == min(r["vpls"] for r in mine) else None)
        for name, p in presets.items():
            for r in mine:
                if matches(r, p):
                    ax.annotate(name, (r["indirect"], 100 * r["rel_rms_full"]), textcoords="offset points",
                                xytext=(6, 6), fontsize=9, weight="bold")
        for r in full:
            ax.axvline(r["gather"], color="grey", ls="--", lw=1)
            ax.text(r["gather"], ax.get_ylim()[1] * 0.9 if ax.get_ylim()[1] > 0 else 1, " full gather",
                    color="grey", fontsize=8)
        ax.axhline(3.0, color="red", ls=":", lw=1)
        ax.set_xscale("log")
        ax.set_xlabel("indirect light, GPU ms per frame (select + gather + upsample)")
        ax.set_ylabel("relative RMS error vs full-resolution gather (%)")
        ax.set_title(scene)
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)
    print("wrote %s" % path)


def fmt(v, spec=".3f"):
    return format(v, spec) if isinstance(v, float) else str(v)


def write_page(args, rows, scaling, splats, presets, notes, path):
    lines = ["# Multiresolution gather: the speed/accuracy trade", "",
             "Generated by `Testing/Benchmarks/multires_sweep.py` (%dx%d, medians of %d frames, "
             "Mesa llvmpipe on this project's 2-core machines; speed as ratios within one run). "
             "Do not edit by hand: rerun the script." % (args.size, args.size, args.repeats), "",
             "Papers: nichols-wyman-2009 (multiresolution splatting, 3.2-3.5, eq. 2), "
             "nichols-shopf-wyman-2009 (stencil refinement 3.2.1, table 1), nichols-penmatsa-wyman-2010 "
             "(depth-derivative metric 3.2), Besenthal et al. (mask-weighted upsampling).", "",
             "Scenes: " + "; ".join("`%s`: %s" % kv for kv in notes.items()), "",
             "![error against time](images/multires-tradeoff.png)", "",
             "Each point is one setting (depth threshold, normal threshold, finest level, refinement: geometry "
             "alone or the illumination rule at threshold T, IlluminationRefinement.md); the black line "
             "is the Pareto frontier (no other setting is both faster and more accurate); the dashed line "
             "is the full-resolution gather, the dotted line the 3% error target.", ""]
    lines += ["## Presets", "",
              "| preset | depth threshold | normal threshold | finest level | refinement | scene | indirect ms | "
              "gather x | indirect x | work | rel. RMS vs full | rel. max vs full | rel. RMS vs truth |",
              "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for name, p in presets.items():
        for r in rows:
            if matches(r, p):
                lines.append("| %s | %s | %s | %d | %s | %s (%d VPLs) | %.0f | %.1f | %.1f | %.3f | %.4f | %.3f | %s |"
                             % (name, fmt(r["depth"], "g"), fmt(r["normal"], "g"), r["finest"],
                                "geometry" if p[3] < 0 else "illumination T %g" % p[3], r["scene"],
                                r["vpls"], r["indirect"], r["gather_speedup"], r["indirect_speedup"], r["work"],
                                r["rel_rms_full"], r["rel_max_full"], fmt(r["rel_rms_truth"], ".4f")))
    lines += ["", "Full-resolution gather for comparison:", "",
              "| scene | VPLs | gather ms | frame ms | rel. RMS vs truth |", "|---|---|---|---|---|"]
    for r in rows:
        if r["mode"] == "full":
            lines.append("| %s | %d | %.0f | %.0f | %s |" % (r["scene"], r["vpls"], r["gather"], r["frame"],
                                                            fmt(r["rel_rms_truth"], ".4f")))
    lines += ["", "## Targets", ""]
    for r in rows:
        if r["scene"] == "cornell-spot" and matches(r, presets["balanced"]) and r["vpls"] == 256:
            lines.append("- Balanced, %dx%d Cornell box, 256 VPLs: gather **%.1fx** faster (target 10x), whole "
                         "indirect computation **%.1fx** faster (target 5x), relative RMS **%.2f%%** against the "
                         "full gather (target <= 3%%). %s"
                         % (args.size, args.size, r["gather_speedup"], r["indirect_speedup"],
                            100 * r["rel_rms_full"],
                            "Met." if r["gather_speedup"] >= 10 and r["indirect_speedup"] >= 5
                            and r["rel_rms_full"] <= 0.03 else
                            "**Not met**: the gather's share of the work is %.1f%% (at most ~%.0fx at that share), "
                            "and the selection and upsampling cost %.0f ms here against %.0f ms for the full "
                            "gather (steps below); no measured setting within 3%% of the full gather gathers less "
                            "than %.1f%% of the pixels."
                            % (100 * r["work"], 1.0 / max(r["work"], 1e-9), r["select"] + r["upsample"],
                               r["indirect"] * r["indirect_speedup"],
                               100 * min([q["work"] for q in rows if q["scene"] == r["scene"] and q["mode"] ==
                                          "multires" and q["vpls"] == 256 and q["rel_rms_full"] <= 0.03]
                                         or [r["work"]]))))
    if len(scaling) >= 2:
        a, b = scaling[0], scaling[-1]
        lines.append("- Scaling scene, %d -> %d triangles at fixed coverage, Balanced: GI overhead %.1f -> %.1f ms "
                     "with a static light (**%.2fx**), %.1f -> %.1f ms with a light moving every frame "
                     "(RSM re-rendered; **%.2fx**; target <= 1.5x)."
                     % (a["triangles"], b["triangles"], a["overhead_static"], b["overhead_static"],
                        b["overhead_static"] / max(a["overhead_static"], 1e-9), a["overhead_moving"],
                        b["overhead_moving"], b["overhead_moving"] / max(a["overhead_moving"], 1e-9)))
    for r in splats:
        if r["scene"] == "cornell-spot" and r["preset"] == "balanced" and int(r["vpls"]) == 256:
            lines.append("- Stenciled gather against multiresolution splatting, Balanced's geometric selection, 256 "
                         "VPLs, same texels and "
                         "the same output (largest difference %.1g of the peak): **%.1fx** faster (target 4x; "
                         "nichols-shopf-wyman-2009 measured 6.4x). %s"
                         % (r["max_difference"], r["speedup"], "Met." if r["speedup"] >= 4 else "**Not met.**"))
    if splats:
        lines += ["", "## Stenciled gather against multiresolution splatting", "",
                  "`--gather splat` (vtkMRGIGather::GatherSplatting) draws, per VPL, one point per selected "
                  "texel with additive blending (nichols-wyman-2009 3.4); the stenciled gather draws one quad per "
                  "level and lets early stencil culling skip the unselected texels (nichols-shopf-wyman-2009 "
                  "3.2.2). Splatting has no step between its levels for the illumination rule, so both gather "
                  "each preset's geometric selection here. "
                  "Both compute the same numbers (shared GLSL, vtkMRGIVPLIrradiance.glsl); the table "
                  "gives the GPU time of the gathering step alone, medians of %d interleaved frames. Splatting's "
                  "subsplat list is read back from the selection here (the paper streams it out on the GPU); "
                  "its time is listed apart and not counted." % args.repeats, "",
                  "| scene | VPLs | preset | work | stenciled gather ms | splatting ms | stenciled faster | "
                  "subsplat list ms | max difference / peak |", "|---|---|---|---|---|---|---|---|---|"]
        for r in splats:
            lines.append("| %s | %d | %s | %.3f | %.1f | %.1f | **%.1fx** | %.1f | %.1g |" % (
                r["scene"], int(r["vpls"]), r["preset"], r["work"], r["stenciled_ms"], r["splatting_ms"],
                r["speedup"], r["subsplat_list_ms"], r["max_difference"]))
        lines += ["", "CSV: [data/multires-splatting.csv](data/multires-splatting.csv).", ""]
    lines += ["", "## Flicker and the balance rule", "",
              "Flicker: rms((M2 - M1) - (F2 - F1)) / rms(F1), the change of the multiresolution error between "
              "two frames (M: multiresolution, F: full gather), with the light moved by 0.2% of the scene or "
              "the camera turned by 0.25 degrees. 0 means the error does not move.", "",
              "| preset | balance | rel. RMS vs full | flicker (light) | flicker (camera) | indirect ms |",
              "|---|---|---|---|---|---|"]
    for name, p in presets.items():
        for balance in (1, 0):
            for r in rows:
                if r["scene"] == "cornell-spot" and r["vpls"] == 256 and matches(r, p, balance):
                    lines.append("| %s | %s | %.4f | %.4f | %.4f | %.0f |" % (
                        name, "on" if balance else "off", r["rel_rms_full"], r["flicker_light"],
                        r["flicker_camera"], r["indirect"]))
    lines += ["", "## Levels and differences (Cornell box)", "",
              "Level that gathered each pixel (red: full resolution, orange: 1/2, yellow: 1/4, green: 1/8, "
              "cyan: 1/16, blue: 1/32, violet: 1/64), as nichols-wyman-2009 figure 3 shows them; the indirect "
              "light; |multires - full| x 8.", "",
              "| preset | levels | indirect | difference x8 |", "|---|---|---|---|"]
    for name in presets:
        lines.append("| %s | ![](images/multires-levels-%s.png) | ![](images/multires-indirect-%s.png) | "
                     "![](images/multires-diff-%s.png) |" % (name, name, name, name))
    lines += ["", "Full-resolution gather: ![](images/multires-indirect-full.png)", "",
              "## GPU time per step (Cornell box, 256 VPLs)", "",
              "As nichols-shopf-wyman-2009 table 1: the selection's cost is fixed, the gather's follows the "
              "texels selected.", "",
              "| preset | mipmap0 | mipmaps | flags0 | flags | stencil | receivers | VPLs | upsample | resolve |",
              "|---|---|---|---|---|---|---|---|---|---|"]
    for name, p in presets.items():
        for r in rows:
            if r["scene"] == "cornell-spot" and r["vpls"] == 256 and matches(r, p):
                lines.append("| %s | %s |" % (name, " | ".join("%.1f" % r[k] for k in (
                    "select.mipmap0", "select.mipmaps", "select.flags0", "select.flags", "select.stencil",
                    "gather.receivers", "gather.vpls", "upsample.levels", "upsample.resolve"))))
    lines += ["", "## Scaling scene", "", "| triangles | frame, GI off | frame, GI | overhead (static light) | "
              "overhead (moving light) | of which RSM |", "|---|---|---|---|---|---|"]
    for s in scaling:
        lines.append("| %d | %.1f | %.1f | %.1f | %.1f | %.1f |" % (s["triangles"], s["frame_off"], s["frame_gi"],
                                                                   s["overhead_static"], s["overhead_moving"],
                                                                   s["rsm"]))
    lines += ["", "## Every setting", "", "CSV: [data/multires-sweep.csv](data/multires-sweep.csv).", ""]
    # The cold-start section is cold_start.py's (between its markers): kept.
    if os.path.exists(path):
        with open(path) as f:
            old = f.read()
        begin, end = old.find("## Cold start"), old.find("<!-- /cold-start -->")
        if 0 <= begin < end:
            lines += [old[begin:end + len("<!-- /cold-start -->")], ""]
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    print("wrote %s" % path)


if __name__ == "__main__":
    main()
