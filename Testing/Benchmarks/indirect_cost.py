"""Where the GPU frame goes with indirect shadows, next to RIHKS11's breakdown.

Issue 13's cost target: ISM creation, importance (the VPL selection, BRSM
included), gather and blur in the GPU frame. RIHKS11 section 7 (GTX 480,
1600 x 800, its figure 8 scenes): 37% indirect lighting, 15% direct
lighting, 12% ISM creation including blocker adaptation, 12% reflective
shadow maps including bidirectional sampling, 9% geometry-aware blur (the
rest unaccounted for there).

Per configuration, the median over `--frames` frames (after one warm-up
frame) of each stage's GPU time from vtkMRGIPass's stage timers, as a share
of the stages' sum and in ms, plus the median wall time per frame. The
light moves a little every frame so that the VPLs, their ISMs and the
importance are rebuilt each frame, as in an interactive session with a
moving light (a static light would reuse them).

    PYTHONPATH=build/lib/python3/dist-packages /usr/bin/python3 \\
        Testing/Benchmarks/indirect_cost.py --build build --docs Documentation

writes the table into Documentation/IndirectShadows.md between its
<!-- cost:table --> markers. `--quick`: 64 x 64, 2 frames, no page.
"""
import argparse
import os
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(__file__))
import mrgi_bench as mb  # noqa: E402
from doc_markers import replace_between_markers  # noqa: E402

# Stage names of vtkMRGIPass's timers, grouped as the paper groups its costs.
GROUPS = [
    ("direct light (scene, shadows)", ("scene", "shadows")),
    ("reflective shadow maps", ("rsm",)),
    ("VPL selection (importance)", ("vpl",)),
    ("ISM creation", ("ism",)),
    ("voxelization", ("voxels",)),
    ("gather (indirect lighting)", ("select", "gather")),
    ("upsampling (the geometry-aware blur)", ("upsample",)),
    ("add, output", ("add", "forward", "output")),
]
PAPER = {"direct light (scene, shadows)": "15%", "reflective shadow maps": "12% (with bidirectional sampling)",
         "VPL selection (importance)": "(in the 12% above)", "ISM creation": "12%",
         "gather (indirect lighting)": "37%", "upsampling (the geometry-aware blur)": "9%"}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default=os.path.join(mb.ROOT, "build"))
    parser.add_argument("--docs")
    parser.add_argument("--scene", default="cornell-spot")
    parser.add_argument("--size", type=int, default=256)
    parser.add_argument("--frames", type=int, default=5)
    parser.add_argument("--quick", action="store_true")
    args = parser.parse_args()
    if args.quick:
        args.size, args.frames, args.docs = 64, 2, None
    configs = [("grid 256, no visibility", dict(VPLSelectionMode=0, IndirectVisibility=0)),
               ("grid 256 + ISM", dict(VPLSelectionMode=0, IndirectVisibility=1)),
               ("BRSM 256 + ISM", dict(VPLSelectionMode=4, IndirectVisibility=1)),
               ("grid 256 + voxels", dict(VPLSelectionMode=0, IndirectVisibility=2))]
    window, renderer = mb.make_window(args.size, args.size)
    mb.build_scene(renderer, args.scene)
    gi = mb.install_pass(renderer, StageTimingEnabled=True)
    window.GetRenderTimer().SetLoggingEnabled(True)
    lights = renderer.GetLights()
    lights.InitTraversal()
    light = lights.GetNextItem()
    start_position = light.GetPosition()
    columns, rows = [], {}
    for label, settings in configs:
        for key, value in settings.items():
            getattr(gi, "Set" + key)(value)
        if gi.GetVPLSelectionMode() != settings["VPLSelectionMode"]:
            print("%s: not in this build" % label)
            continue
        stages, walls = {}, []
        for frame in range(args.frames + 1):
            light.SetPosition(start_position[0] + 0.5 * frame, start_position[1], start_position[2])
            start = time.perf_counter()
            window.Render()
            n = gi.FetchStageTimings(window, True)
            if frame == 0:
                continue  # warm-up: programs and buffers
            walls.append((time.perf_counter() - start) * 1e3)
            for s in range(n):
                stages.setdefault(gi.GetStageName(s), []).append(gi.GetStageTimeMilliseconds(s))
        medians = {k: float(np.median(v)) for k, v in stages.items() if "." not in k}
        total = sum(medians.values())
        columns.append(label)
        for group, names in GROUPS:
            ms = sum(medians.get(name, 0.0) for name in names)
            rows.setdefault(group, []).append((ms, ms / total if total > 0 else 0.0))
        rows.setdefault("frame (wall, median)", []).append((float(np.median(walls)), None))
        print("%s: %s; wall %.0f ms" % (label, ", ".join("%s %.1f" % kv for kv in sorted(medians.items())),
                                         np.median(walls)))
    head = "| stage | " + " | ".join(columns) + " | RIHKS11 (GTX 480) |"
    lines = [head, "|---" * (len(columns) + 2) + "|"]
    for group, values in rows.items():
        cells = ["%.1f ms" % ms if share is None else "%.1f ms (%.0f%%)" % (ms, 100 * share) for ms, share in values]
        lines.append("| %s | %s | %s |" % (group, " | ".join(cells), PAPER.get(group, "")))
    print("\n".join(lines))
    if args.docs:
        page = os.path.join(args.docs, "IndirectShadows.md")
        setup = ["`%s`, %d x %d, multiresolution gather (Balanced), light moving every frame; median of %d frames "
                 "after a warm-up; GPU stage timers on llvmpipe (2 cores); load average %s." % (
                     args.scene, args.size, args.size, args.frames,
                     ", ".join("%.1f" % x for x in os.getloadavg())), ""]
        replace_between_markers(page, "cost:table", setup + lines)
        print("wrote the table into", page)


if __name__ == "__main__":
    main()
