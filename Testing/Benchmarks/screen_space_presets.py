"""The screen-space presets (mrgi_screen_space_preset.h) measured: for each
of fast, balanced and accurate, mrgi-render renders the Cornell box with
soft shadows, SSAO and SSGI on (--gi off: SSGI and the VPL gather are
exclusive) through `--screen-space-preset`, and reports the stage times
that `--timings` prints for the last of --frames frames (GPU timer, ms) and
the image's error against accurate's (mrgi-compare: absolute and relative
RMS, EXR radiance).

    /usr/bin/python3 Testing/Benchmarks/screen_space_presets.py --build build \
        --out build/presets [--size 640x480 --frames 5]

Prints a Markdown table for Documentation/ScreenSpaceEffects.md ("Presets").
"""
import argparse
import os
import re
import subprocess
import sys


def render(args, preset, path):
    command = [os.path.join(args.build, "bin", "mrgi-render"), "cornell", "-o", path,
               "--size", args.size, "-q", "--gi", "off", "--direct-shadows", "soft",
               "--ssao", "on", "--ssgi", "on", "--screen-space-preset", preset,
               "--frames", str(args.frames), "--timings"]
    env = dict(os.environ)
    env.pop("DISPLAY", None)
    out = subprocess.run(command, check=True, capture_output=True, text=True, env=env).stdout
    times = {}
    for line in out.splitlines():
        m = re.match(r"(\S.*?)\s{2,}(\S+)$", line.strip())
        if m:
            try:
                times[m[1]] = float(m[2])
            except ValueError:
                pass
    return times


def compare(args, image, reference):
    out = subprocess.run([os.path.join(args.build, "bin", "mrgi-compare"), image, reference],
                         check=True, capture_output=True, text=True).stdout
    return {k: float(v) for k, v in (item.split("=") for item in out.split())}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default="build")
    parser.add_argument("--out", default="build/presets")
    parser.add_argument("--size", default="640x480")
    parser.add_argument("--frames", type=int, default=5)
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)
    presets = ["fast", "balanced", "accurate"]
    times, paths = {}, {}
    for p in presets:
        paths[p] = os.path.join(args.out, "preset-%s.exr" % p)
        times[p] = render(args, p, paths[p])
    table = ["| preset | shadows ms | SSAO ms | SSGI ms | frame (wall) ms | abs RMS vs accurate | "
             "rel RMS vs accurate |", "|---|---|---|---|---|---|---|"]
    for p in presets:
        c = compare(args, paths[p], paths["accurate"])
        t = times[p]
        table.append("| %s | %.0f | %.0f | %.0f | %.0f | %.5f | %.4f |" % (
            p, t.get("shadows", float("nan")), t.get("ssao", float("nan")),
            t.get("ssgi", float("nan")), t.get("frame (wall)", float("nan")), c["rms"],
            c["relative_rms"]))
    print("\n".join(table))


if __name__ == "__main__":
    sys.exit(main())
