#!/usr/bin/env python3
"""Cold start: what a single image costs, whole process, multiresolution
against the full-resolution gather (issue 17 part 1).

Two measurements, each repeated and interleaved (full, multires, full, ...)
so that both modes see the same machine load:

1. whole process: the wall time of `mrgi-render SCENE --indirect-only -o
   X.exr` as a subprocess (loader, VTK start-up, EGL context, scene, one
   frame, the EXR write, exit);
2. in process: `mrgi-render ... --timings --frames N` prints the first
   frame against the median of the later ones, per stage (GPU timer
   queries) and for the frame's wall time, the time from main() to the
   render window and to the first frame, and the textures each frame
   allocated (vtkMRGIResourceStatistics).

Prints the table, writes it to build/cold_start/cold_start.csv and, with
--page, between the <!-- cold-start --> markers of
Documentation/Multiresolution.md. Times are medians over --repeats runs;
only the ratios within one run mean something on a shared machine (the
load average is printed with the table).

Usage: cold_start.py --build build [--size 1024] [--repeats 3] [--frames 4]
                     [--page Documentation/Multiresolution.md]
"""
import argparse
import csv
import os
import re
import statistics
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from doc_markers import replace_between_markers  # noqa: E402

MODES = [("full", "full"), ("multires", "multires")]


def command(args, mode, output, extra=()):
    return [os.path.join(args.build, "bin", "mrgi-render"), args.scene, "--indirect-only",
            "--gi", mode, "--size", "%dx%d" % (args.size, args.size), "-q", "-o", output] + list(extra)


def environment():
    env = dict(os.environ)
    env.pop("DISPLAY", None)  # headless EGL, as the CLI runs in CI
    return env


def whole_process(args, mode, folder):
    output = os.path.join(folder, "%s.exr" % mode)
    start = time.perf_counter()
    subprocess.run(command(args, mode, output), check=True, capture_output=True, env=environment())
    return time.perf_counter() - start


ROW = re.compile(r"^  (\S.*?)\s{2,}([-0-9.]+)(?:\s+([-0-9.]+))?$")
TEXTURES = re.compile(r"textures allocated: first frame (\d+) \(([0-9.]+) MiB\), "
                      r"later frames (\d+) \(([0-9.]+) MiB\)")


def in_process(args, mode, folder):
    """The cold-start table of one run: {row: (first, steady or None)}, textures."""
    output = os.path.join(folder, "%s-timed.exr" % mode)
    out = subprocess.run(command(args, mode, output, ["--timings", "--frames", str(args.frames)]),
                         check=True, capture_output=True, text=True, env=environment()).stdout
    rows, textures, inside = {}, None, False
    for line in out.splitlines():
        if line.startswith("cold start"):
            inside = True
            continue
        m = TEXTURES.match(line)
        if m:
            textures = (int(m[1]), float(m[2]), int(m[3]), float(m[4]))
            inside = False
            continue
        m = ROW.match(line) if inside else None
        if m:
            rows[m[1]] = (float(m[2]), float(m[3]) if m[3] else None)
    if not rows or textures is None:
        raise SystemExit("no cold-start table in the output of %s:\n%s" % (mode, out))
    return rows, textures


def median(values):
    values = [v for v in values if v is not None]
    return statistics.median(values) if values else None


def fmt(v, spec="%.0f"):
    return "-" if v is None else spec % v


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default="build")
    parser.add_argument("--scene", default="cornell-spot")
    parser.add_argument("--size", type=int, default=1024)
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--frames", type=int, default=4)
    parser.add_argument("--out", default=None, help="folder for the CSV (default BUILD/cold_start)")
    parser.add_argument("--page", default=None, help="Markdown page to write the table into")
    args = parser.parse_args()
    if args.repeats < 1 or args.frames < 2:
        raise SystemExit("--repeats must be >= 1 and --frames >= 2")
    out = args.out or os.path.join(args.build, "cold_start")
    os.makedirs(out, exist_ok=True)
    load_before = os.getloadavg()[0]

    wall = {m: [] for m, _ in MODES}
    runs = {m: [] for m, _ in MODES}
    with tempfile.TemporaryDirectory() as folder:
        for r in range(args.repeats):
            for label, mode in MODES:
                wall[label].append(whole_process(args, mode, folder))
                runs[label].append(in_process(args, mode, folder))
                print("repeat %d %s: whole process %.2f s" % (r + 1, label, wall[label][-1]),
                      file=sys.stderr)
    load_after = os.getloadavg()[0]

    # Rows in the order of the multiresolution run (it has every stage).
    order = list(runs["multires"][0][0].keys())
    for name in runs["full"][0][0]:
        if name not in order:
            order.insert(len(order) - 1, name)

    def cell(label, name, which):
        return median([rows.get(name, (None, None))[which] for rows, _ in runs[label]])

    table = ["| step | full: first ms | full: steady ms | multires: first ms | multires: steady ms |",
             "|---|---|---|---|---|"]
    csv_rows = []
    for name in order:
        cells = [cell(label, name, w) for label, _ in MODES for w in (0, 1)]
        spec = "%.0f" if name in ("start to window", "scene build", "start to first frame",
                                  "frame (wall)") else "%.1f"
        table.append("| %s | %s |" % (name, " | ".join(fmt(c, spec) for c in cells)))
        csv_rows.append([name] + cells)
    tex = {label: [median([t[i] for _, t in runs[label]]) for i in range(4)] for label, _ in MODES}
    table.append("| textures allocated (count, MiB) | %d, %.0f | %d, %.0f | %d, %.0f | %d, %.0f |" % (
        tex["full"][0], tex["full"][1], tex["full"][2], tex["full"][3],
        tex["multires"][0], tex["multires"][1], tex["multires"][2], tex["multires"][3]))

    whole = {label: median(wall[label]) for label, _ in MODES}
    lines = table + [""]
    lines.append("Whole process (`mrgi-render %s --indirect-only --size %dx%d -o X.exr`, median of %d, "
                 "interleaved): full gather %.2f s, multiresolution %.2f s: **%.2fx** (target >= 1.5x)."
                 % (args.scene, args.size, args.size, args.repeats, whole["full"], whole["multires"],
                    whole["full"] / whole["multires"]))
    for label, _ in MODES:
        first = cell(label, "frame (wall)", 0)
        steady = cell(label, "frame (wall)", 1)
        start = cell(label, "start to first frame", 0)
        lines.append("%s: first frame %.0f ms = %.2fx the steady frame (%.0f ms; target <= 1.5x); "
                     "start-up to the first frame %.0f ms; whole process %.0f ms = steady frame x %.2f "
                     "+ start-up x %.2f."
                     % (label.capitalize(), first, first / steady, steady, start, whole[label] * 1e3,
                        first / steady, (whole[label] * 1e3 - first) / start))
    lines.append("")
    lines.append("`first` is the first frame, `steady` the median of frames 2..%d of the same process; "
                 "stage rows are GPU timer queries (on llvmpipe they include the time the rasterizer "
                 "threads spend), `frame (wall)` is `vtkRenderWindow::Render()` on the CPU. Load "
                 "average %.1f before, %.1f after (2 cores, other work running)."
                 % (args.frames, load_before, load_after))
    print("\n".join(lines))

    with open(os.path.join(out, "cold_start.csv"), "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(["step", "full_first_ms", "full_steady_ms", "multires_first_ms",
                         "multires_steady_ms"])
        writer.writerows(csv_rows)
        writer.writerow(["whole_process_s", whole["full"], "", whole["multires"], ""])
    if args.page:
        replace_between_markers(args.page, "cold-start", lines)


if __name__ == "__main__":
    main()
