"""mrgi-compare's contract: an RGBA GPU image against an RGB ground truth is
compared on RGB (and says so), --help prints the usage, bad usage exits 2
with the usage, images of different sizes exit 1 naming both sizes."""
import os
import subprocess
import sys

RENDER = os.environ["MRGI_RENDER"]
COMPARE = os.environ["MRGI_COMPARE"]
TMP = os.environ.get("MRGI_TEST_TMP", "/tmp")


def check(condition, what):
    if not condition:
        print("check failed:", what, file=sys.stderr)
        sys.exit(1)


def run(program, *args):
    env = dict(os.environ)
    env.pop("DISPLAY", None)
    p = subprocess.run([program, *args], capture_output=True, text=True, env=env, timeout=600)
    return p.returncode, p.stdout, p.stderr


def exr_channels(path):
    """Channel names in an OpenEXR header (the 'channels' attribute)."""
    with open(path, "rb") as f:
        data = f.read(4096)
    start = data.index(b"channels\0chlist\0") + len(b"channels\0chlist\0") + 4
    names = []
    while data[start] != 0:
        end = data.index(b"\0", start)
        names.append(data[start:end].decode())
        start = end + 1 + 16
    return sorted(names)


def main():
    gpu = os.path.join(TMP, "compare_gpu.exr")
    truth = os.path.join(TMP, "compare_truth.exr")
    small = os.path.join(TMP, "compare_small.exr")
    for args in (["-o", gpu, "--size", "24x16"],
                 ["-o", truth, "--size", "24x16", "--reference", "--reference-passes", "1"],
                 ["-o", small, "--size", "16x16", "--gi", "off"]):
        code, _, err = run(RENDER, "cornell", "-q", *args)
        check(code == 0, "render %s: %s" % (args, err))
    check(exr_channels(gpu) == ["A", "B", "G", "R"], "the GPU EXR is RGBA: %s" % exr_channels(gpu))
    check(exr_channels(truth) == ["B", "G", "R"], "the ground truth is RGB: %s" % exr_channels(truth))

    # RGBA against RGB: compared on RGB, said on stderr and in the line.
    code, out, err = run(COMPARE, gpu, truth)
    print(out, err)
    check(code == 0, "RGBA vs RGB compares: " + err)
    metrics = {k: float(v) for k, v in (item.split("=") for item in out.split())}
    check(metrics["channels"] == 3, "compared on RGB: " + out)
    check(metrics["pixels"] > 0 and metrics["relative_rms"] > 0, "a real comparison: " + out)
    check("alpha ignored" in err, "says alpha is ignored: " + err)
    # Both RGBA: alpha counts, no note.
    code, out, err = run(COMPARE, gpu, gpu)
    check(code == 0 and "channels=4" in out and "alpha ignored" not in err, "RGBA vs RGBA: " + out + err)
    check("relative_rms=0.000000" in out, "an image equals itself: " + out)

    # --help / -h: usage on stdout, exit 0.
    for flag in ("--help", "-h"):
        code, out, _ = run(COMPARE, flag)
        check(code == 0 and out.startswith("usage: mrgi-compare"), flag + ": " + out)
    # Bad usage: exit 2, one error line and the usage on stderr.
    for args, expected in ((["--bogus", gpu, truth], "unknown option '--bogus'"),
                           ([gpu], "only one image"),
                           ([], "no images"),
                           ([gpu, truth, gpu], "more than two images"),
                           ([gpu, truth, "--peak", "0"], "--peak"),
                           ([gpu, truth, "--peak"], "--peak needs a value"),
                           ([gpu, truth, "--diff", "x.jpg"], "--diff")):
        code, out, err = run(COMPARE, *args)
        errors = [l for l in err.splitlines() if l.startswith("mrgi-compare: error:")]
        check(code == 2, "exit 2 for %s (got %d)" % (args, code))
        check(len(errors) == 1 and expected in errors[0], "error for %s names %r: %s" % (args, expected, err))
        check("usage: mrgi-compare" in err and out == "", "usage printed for %s" % args)
    # An input that is neither EXR nor PNG: refused by name (exit 1), nothing read.
    code, _, err = run(COMPARE, gpu, "frame.jpg")
    check(code != 0 and "'frame.jpg': the file name must end in .exr or .png" in err,
          "a .jpg input is refused by name: " + err)
    # Different sizes: exit 1, both sizes named.
    code, _, err = run(COMPARE, gpu, small)
    check(code == 1 and "24 x 16" in err and "16 x 16" in err, "size mismatch named: " + err)
    print("ok")


if __name__ == "__main__":
    main()
