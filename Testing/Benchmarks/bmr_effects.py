"""BMR multiresolution screen-space effects on this machine (issue 14;
besenthal-maisch-ropinski figures 6 and 10): the speed-up of the
multiresolution path over full resolution, its absolute RMS error, the
difference images and the fraction of pixels per level.

Runs the Benchmark case of cxx.TestMRGISSAOMultires (Cornell box, radius
30, bias 0.6; at 1280x720 and 1920x1080, for every kernel size full and
multiresolution AO alternate in one run, A B A B, one warm-up each, median
wall time of the stage + WaitForCompletion), then writes into --out:
bmr_effects.csv, speedup_vs_samples.png, rms_vs_samples.png and
ssao_diff_<size>.png (|multires - full| AO around the mask borders, x10),
and prints a Markdown table for Documentation/ScreenSpaceEffects-Benchmark.md.

    /usr/bin/python3 Testing/Benchmarks/bmr_effects.py --build build --out build/bmr-bench \
        --docs Documentation   # also rewrites the page's tables, PNGs and CSVs

Soft shadows: the Benchmark case of cxx.TestMRGIShadowsMultires
(`cornell-spot`, PCSS at 36, 100 and 196 taps): whole frames through
vtkMRGIPass with ShadowResolution full and multires, A B A B, medians; the
absolute RMS of the factors (slot 0).

SSGI: the Benchmark case of cxx.TestMRGISSGIMultires (Cornell box, radius
60, bias 0.6, the direct light as senders; --ssgi-samples, default 228 as
BMR figure 6): vtkMRGISSGI::Compute level 0 against ComputeMultiresolution
(masks, levels, blend), A B A B, medians; the absolute RMS of the bounce.
--effects picks the effects (e.g. `--effects ssgi` runs and rewrites the
SSGI table only, leaving the others as they are).
"""
import argparse
import csv
import os
import re
import subprocess
import sys

import numpy as np


def difference_images(out, sizes):
    """|multires - full| AO as 4 x 4 block means x 20 (quarter size PNG): the
    noise of both paths is everywhere; mask borders show as lines."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    for size in sizes:
        w, h = (int(v) for v in size.split("x"))
        path = os.path.join(out, "ssao_diff_%s.f32" % size)
        if not os.path.exists(path):
            continue
        d = np.abs(np.fromfile(path, dtype=np.float32).reshape(h, w)[::-1])
        d = d[:h - h % 4, :w - w % 4].reshape(h // 4, 4, w // 4, 4).mean(axis=(1, 3))
        plt.imsave(os.path.join(out, "ssao_diff_%s.png" % size), np.clip(d * 20.0, 0, 1),
                   cmap="magma", vmin=0, vmax=1)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default="build")
    parser.add_argument("--out", default="build/bmr-bench")
    parser.add_argument("--kernels", default="16,32,64,128",
                        help="SSAO sample counts; the last one's difference image is written")
    parser.add_argument("--repeats", type=int, default=3, help="timed A B pairs per row")
    parser.add_argument("--ssgi-samples", default="228", help="SSGI sample counts (BMR fig. 6: 228)")
    parser.add_argument("--effects", default="ssao,shadows,ssgi")
    parser.add_argument("--docs", default="",
                        help="a Documentation folder: copy the PNGs and CSVs there and rewrite the "
                             "tables between the <!-- bmr:NAME --> markers of "
                             "ScreenSpaceEffects-Benchmark.md")
    args = parser.parse_args()
    effects = args.effects.split(",")
    os.makedirs(args.out, exist_ok=True)
    exe = os.path.join(args.build, "Testing", "Cxx", "TestMRGISSAOMultires")
    if not os.access(exe, os.X_OK):
        sys.exit("bmr_effects.py: %s is not built (cmake --build %s --target "
                 "TestMRGISSAOMultires)" % (exe, args.build))
    env = dict(os.environ, MRGI_BMR_BENCHMARK="1", MRGI_BMR_KERNELS=args.kernels,
               MRGI_BMR_REPEATS=str(args.repeats), MRGI_BMR_OUT=os.path.abspath(args.out),
               MRGI_BMR_SSGI_SAMPLES=args.ssgi_samples)
    env.pop("DISPLAY", None)
    stdout = ""
    for effect, program in (("ssao", exe),
                            ("shadows", exe.replace("TestMRGISSAOMultires",
                                                    "TestMRGIShadowsMultires")),
                            ("ssgi", exe.replace("TestMRGISSAOMultires", "TestMRGISSGIMultires"))):
        if effect not in effects:
            continue
        run = subprocess.run([program, "--case", "Benchmark"], env=env, capture_output=True,
                             text=True)
        if run.returncode != 0:
            sys.stderr.write(run.stdout + run.stderr)
            sys.exit("bmr_effects.py: the %s benchmark failed" % effect)
        stdout += run.stdout
    rows, levels, overhead, shadows, ssgi = [], {}, {}, [], []
    for line in stdout.splitlines():
        m = re.match(r"BENCH ssgi (\d+) (\d+) samples (\d+) full_ms (\S+) multires_ms (\S+) "
                     r"speedup (\S+) rms (\S+) max (\S+) largest (\S+)", line)
        if m:
            ssgi.append(dict(size="%sx%s" % (m[1], m[2]), samples=int(m[3]),
                             full_ms=float(m[4]), multires_ms=float(m[5]),
                             speedup=float(m[6]), rms=float(m[7]), max=float(m[8]),
                             largest=float(m[9])))
        m = re.match(r"BENCH shadows (\d+) (\d+) taps (\d+) full_frame_ms (\S+) "
                     r"multires_frame_ms (\S+) speedup (\S+) rms (\S+)", line)
        if m:
            shadows.append(dict(size="%sx%s" % (m[1], m[2]), taps=int(m[3]),
                                full_ms=float(m[4]), multires_ms=float(m[5]),
                                speedup=float(m[6]), rms=float(m[7])))
        m = re.match(r"BENCH ssao (\d+) (\d+) kernel (\d+) full_ms (\S+) multires_ms (\S+) "
                     r"speedup (\S+) rms (\S+) blurred_rms (\S+)", line)
        if m:
            w, h, k = int(m[1]), int(m[2]), int(m[3])
            rows.append(dict(effect="ssao", size="%dx%d" % (w, h), samples=k,
                             full_ms=float(m[4]), multires_ms=float(m[5]),
                             speedup=float(m[6]), rms=float(m[7]), blurred_rms=float(m[8])))
        m = re.match(r"BENCH levels ssao (\d+) (\d+) finest (\S+) (\S+) (\S+) (\S+) work (\S+)",
                     line)
        if m:
            levels["%sx%s" % (m[1], m[2])] = [float(m[i]) for i in range(3, 8)]
        m = re.match(r"BENCH overhead ssao (\d+) (\d+) mask_ms (\S+) blend_ms (\S+)", line)
        if m:
            overhead["%sx%s" % (m[1], m[2])] = (float(m[3]), float(m[4]))
    if shadows:
        with open(os.path.join(args.out, "bmr_shadows.csv"), "w", newline="") as f:
            writer = csv.DictWriter(f, fieldnames=list(shadows[0].keys()))
            writer.writeheader()
            writer.writerows(shadows)
        table = ["| size | taps | full frame ms | multires frame ms | speed-up | abs RMS of factors |",
                 "|---|---|---|---|---|---|"]
        for r in shadows:
            table.append("| %s | %d | %.0f | %.0f | %.2f | %.5f |" % (
                r["size"], r["taps"], r["full_ms"], r["multires_ms"], r["speedup"], r["rms"]))
        print("\n".join(table) + "\n")
        publish(args, "shadows-table", table, {"bmr_shadows.csv": "data/bmr_shadows.csv"})
    if ssgi:
        with open(os.path.join(args.out, "bmr_ssgi.csv"), "w", newline="") as f:
            writer = csv.DictWriter(f, fieldnames=list(ssgi[0].keys()))
            writer.writeheader()
            writer.writerows(ssgi)
        table = ["| size | samples | full ms | multires ms | speed-up | abs RMS of the bounce | "
                 "max abs | largest bounce |",
                 "|---|---|---|---|---|---|---|---|"]
        for r in ssgi:
            table.append("| %s | %d | %.0f | %.0f | %.2f | %.5f | %.4f | %.4f |" % (
                r["size"], r["samples"], r["full_ms"], r["multires_ms"], r["speedup"], r["rms"],
                r["max"], r["largest"]))
        print("\n".join(table) + "\n")
        publish(args, "ssgi-table", table, {"bmr_ssgi.csv": "data/bmr_ssgi.csv"})
    if not rows:
        return
    with open(os.path.join(args.out, "bmr_effects.csv"), "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        writer.writeheader()
        writer.writerows(rows)

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    for key, label, name in (("speedup", "speed-up (full / multires)", "speedup_vs_samples.png"),
                             ("rms", "absolute RMS of AO vs full", "rms_vs_samples.png")):
        fig, ax = plt.subplots(figsize=(4.5, 3.2), dpi=100)
        for size in sorted({r["size"] for r in rows}):
            pts = [(r["samples"], r[key]) for r in rows if r["size"] == size]
            ax.plot([p[0] for p in pts], [p[1] for p in pts], "o-", label="SSAO " + size)
        ax.axhline(1.3 if key == "speedup" else 0.01, color="grey", ls="--", lw=1,
                   label="BMR target")
        ax.set_xscale("log", base=2)
        ax.set_xlabel("SSAO samples")
        ax.set_ylabel(label)
        ax.legend(fontsize=7)
        fig.tight_layout()
        fig.savefig(os.path.join(args.out, name))
        plt.close(fig)
    difference_images(args.out, levels)

    table = ["| size | samples | full ms | multires ms | speed-up | abs RMS | abs RMS, both blurred |",
             "|---|---|---|---|---|---|---|"]
    for r in rows:
        table.append("| %s | %d | %.0f | %.0f | %.2f | %.4f | %.4f |" % (
            r["size"], r["samples"], r["full_ms"], r["multires_ms"], r["speedup"], r["rms"],
            r["blurred_rms"]))
    print("\n".join(table) + "\n")
    level_table = ["| size | finest level 1 | 2 | 3 | 4 | work | mask ms | blend ms |",
                   "|---|---|---|---|---|---|---|---|"]
    for size, v in levels.items():
        mask, blend = overhead.get(size, (float("nan"), float("nan")))
        level_table.append("| %s | %.3f | %.3f | %.3f | %.3f | %.3f | %.0f | %.0f |" % (
            size, v[0], v[1], v[2], v[3], v[4], mask, blend))
    print("\n".join(level_table))
    files = {"bmr_effects.csv": "data/bmr_effects.csv",
             "speedup_vs_samples.png": "images/bmr-ssao-speedup.png",
             "rms_vs_samples.png": "images/bmr-ssao-rms.png"}
    for size in levels:
        files["ssao_diff_%s.png" % size] = "images/bmr-ssao-diff-%s.png" % size
    publish(args, "ssao-table", table, files)
    publish(args, "levels-table", level_table, {})


def publish(args, marker, table, files):
    """With --docs: copy `files` (name in --out -> path under --docs) and put
    `table` between <!-- bmr:marker --> and <!-- /bmr:marker --> of the page."""
    if not args.docs:
        return
    import shutil
    for name, target in files.items():
        source = os.path.join(args.out, name)
        if os.path.isfile(source):
            shutil.copyfile(source, os.path.join(args.docs, target))
    page = os.path.join(args.docs, "ScreenSpaceEffects-Benchmark.md")
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    from doc_markers import replace_between_markers
    replace_between_markers(page, "bmr:%s" % marker, table)
    print("wrote the %s table into %s" % (marker, page))


if __name__ == "__main__":
    main()
