"""What one-bounce indirect light costs on this machine, measured in one run.

Prints (and writes as CSV) for each window size: the median frame time with
GI off and with the full-resolution gather (A B A B over the repeats, so the
machine's load affects both alike), their ratio, the gather stage's GPU time
and the cost of one pixel-VPL pair = gather time / (lit pixels x VPLs).

    PYTHONPATH=build/lib/python3/dist-packages /usr/bin/python3 \
        Testing/Benchmarks/gi_cost.py --sizes 512,1024 --repeats 5
"""
import argparse
import csv
import os
import statistics
import sys
import time

sys.path.insert(0, os.path.dirname(__file__))
import mrgi_bench as mb  # noqa: E402

from vtkmodules.vtkCommonDataModel import vtkImageData  # noqa: E402


def frame_seconds(window):
    """Wall time of one frame, GPU work included (the pixels are read back)."""
    start = time.perf_counter()
    window.Render()
    window.GetPixelData(0, 0, 0, 0, 0, 0)  # a read-back waits for the frame, as a present would
    return time.perf_counter() - start


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--scene", default="cornell-spot")
    parser.add_argument("--sizes", default="512,1024")
    parser.add_argument("--vpls", type=int, default=256)
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--csv", default=os.path.join(mb.ROOT, "build", "Testing", "Temporary", "gi_cost.csv"))
    args = parser.parse_args()
    rows = []
    for size in (int(s) for s in args.sizes.split(",")):
        window, renderer = mb.make_window(size, size)
        mb.build_scene(renderer, args.scene)
        gi = mb.install_pass(renderer, NumberOfVPLs=args.vpls, StageTimingEnabled=True)
        window.GetRenderTimer().SetLoggingEnabled(True)
        # Warm up both modes (shader compilation, first RSM).
        for mode in (1, 0, 1):
            gi.SetIndirectMode(mode)
            window.Render()
        off, on, gather = [], [], []
        for _ in range(args.repeats):
            for mode in (0, 1):  # A B A B
                gi.SetIndirectMode(mode)
                seconds = frame_seconds(window)
                (on if mode else off).append(seconds)
                if mode:
                    for i in range(gi.FetchStageTimings(window, True)):
                        if gi.GetStageName(i) == "gather":
                            gather.append(gi.GetStageTimeMilliseconds(i) * 1e-3)
        position = vtkImageData()
        normal = vtkImageData()
        albedo = vtkImageData()
        gi.GetGBuffer(window, position, normal, albedo)
        lit = int((mb.to_numpy(position)[..., 3] > 0.5).sum())
        vpls = gi.GetVPLSelection().GetVPLCount()
        t_off, t_on = statistics.median(off), statistics.median(on)
        t_gather = statistics.median(gather) if gather else float("nan")
        row = {
            "size": size, "vpls": vpls, "lit_pixels": lit,
            "frame_ms_gi_off": 1e3 * t_off, "frame_ms_gi_full": 1e3 * t_on, "ratio": t_on / t_off,
            "gather_ms": 1e3 * t_gather, "ns_per_pixel_vpl": 1e9 * t_gather / max(1, lit * vpls),
        }
        rows.append(row)
        renderer.SetPass(None)
        gi.ReleaseGraphicsResources(window)
    print("%-6s %6s %10s %12s %12s %7s %11s %16s" % ("size", "VPLs", "lit px", "off ms", "full ms", "ratio",
                                                  "gather ms", "ns / pixel-VPL"))
    for r in rows:
        print("%-6d %6d %10d %12.1f %12.1f %7.2f %11.1f %16.3f" % (
            r["size"], r["vpls"], r["lit_pixels"], r["frame_ms_gi_off"], r["frame_ms_gi_full"], r["ratio"],
            r["gather_ms"], r["ns_per_pixel_vpl"]))
    os.makedirs(os.path.dirname(args.csv), exist_ok=True)
    with open(args.csv, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        writer.writeheader()
        writer.writerows(rows)
    print("wrote %s (medians of %d frames each, GI off and full alternating)" % (args.csv, args.repeats))


if __name__ == "__main__":
    main()
