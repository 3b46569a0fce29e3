"""Is the default ground truth converged, and how far is the gather from it?

1. The CLI's default ground truth (`mrgi-render cornell-spot --reference
   --indirect-only`, per-pixel stopping rule, mrgi_reference_noise.h) with
   two seeds, and a 256-pass render with a third: relative RMS between them
   per pixel and on 4x4-pixel box averages (C core metrics, mrgi-compare).
   Two independent renders with the same noise differ by sqrt(2) times each
   one's noise, so a render's own noise is their difference / sqrt(2).
2. The full-resolution gather with 256, 1024 and 4096 grid VPLs against the
   default ground truth (seed 1), per pixel and on 4x4 boxes.

All without secondary visibility (`--reference-visibility off`, what
reflective shadow maps assume; issue 12 part 4), 256x256. Renders are kept
in --scratch and reused when present (the ground truths take minutes).

    Testing/Benchmarks/reference_convergence.py --build build
"""
import argparse
import os
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(__file__))
import mrgi_bench as mb  # noqa: E402


def read_exr(path):
    """An EXR as an (height, width, 3) float array, rows top-down (the project's reader)."""
    image = mb.vtkImageData()
    io = mb.mrgi.vtkMRGIImageIO()
    assert io.Read(path, image), io.GetLastErrorMessage()
    return mb.to_numpy(image)[..., :3]


def errors(compare_tool, scratch, image_path, reference_path, tag):
    """Relative RMS per pixel and on 4x4 boxes."""
    per_pixel = mb.compare(compare_tool, image_path, reference_path)["relative_rms"]
    boxed = mb.box_error(compare_tool, read_exr(image_path), read_exr(reference_path), scratch,
                         "convergence-%s-boxes" % tag)
    return per_pixel, boxed


def render(tool, path, args):
    """Run mrgi-render unless `path` exists; returns (seconds, last summary line)."""
    log = path + ".log"
    if not os.path.exists(path):
        start = time.time()
        p = subprocess.run([tool, "cornell-spot", "--size", "256x256", "-o", path] + args,
                           capture_output=True, text=True, check=True)
        with open(log, "w") as f:
            f.write(p.stderr)
            f.write("wall seconds %.1f\n" % (time.time() - start))
    with open(log) as f:
        text = f.read()
    summary = [line for line in text.splitlines() if "ground truth:" in line and "passes" in line]
    wall = [line for line in text.splitlines() if line.startswith("wall seconds")]
    return (wall[-1] if wall else ""), (summary[-1] if summary else "")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default=os.path.join(mb.ROOT, "build"))
    parser.add_argument("--scratch", default=None, help="where renders go (default build/Testing/Temporary)")
    args = parser.parse_args()
    tool = os.path.join(args.build, "bin", "mrgi-render")
    compare_tool = os.path.join(args.build, "bin", "mrgi-compare")
    scratch = args.scratch or os.path.join(args.build, "Testing", "Temporary")
    os.makedirs(scratch, exist_ok=True)
    truth = ["--reference", "--indirect-only", "--reference-visibility", "off"]

    paths = {}
    for name, extra in (("default-s1", ["--seed", "1"]), ("default-s2", ["--seed", "2"]),
                        ("passes256-s3", ["--seed", "3", "--reference-error", "0",
                                          "--reference-passes", "256"])):
        paths[name] = os.path.join(scratch, "convergence-%s.exr" % name)
        wall, summary = render(tool, paths[name], truth + extra)
        print("%s: %s (%s)" % (name, summary, wall))
    for vpls in (256, 1024, 4096):
        name = "gpu-%d" % vpls
        paths[name] = os.path.join(scratch, "convergence-%s.exr" % name)
        render(tool, paths[name], ["--gi", "full", "--vpls", str(vpls), "--indirect-only"])

    print()
    print("| compared | rel. RMS per pixel | rel. RMS on 4x4 boxes |")
    print("|---|---|---|")
    for a, b, label in (("default-s2", "default-s1", "default truth, seed 2 vs seed 1"),
                        ("passes256-s3", "default-s1", "256-pass render (seed 3) vs default truth (seed 1)")):
        pixel, box = errors(compare_tool, scratch, paths[a], paths[b], a + "-" + b)
        print("| %s | %.4f | %.4f |" % (label, pixel, box))
    print()
    print("| grid VPLs | rel. RMS per pixel | rel. RMS on 4x4 boxes |")
    print("|---|---|---|")
    for vpls in (256, 1024, 4096):
        pixel, box = errors(compare_tool, scratch, paths["gpu-%d" % vpls], paths["default-s1"],
                            "gpu-%d" % vpls)
        print("| %d | %.4f | %.4f |" % (vpls, pixel, box))


if __name__ == "__main__":
    main()
