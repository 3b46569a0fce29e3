"""Indirect visibility (issue 13) through mrgi-render and the Python API:
the options are refused by name when wrong, the shadows only ever remove
light (visibility is a weight in [0, 1]), an ISM bias so large that nothing
can be nearer than the receiver gives back the unshadowed image, and the
images stay finite."""
import os
import re
import subprocess
import sys

import numpy as np
import mrgi
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.util.numpy_support import vtk_to_numpy

RENDER = os.environ["MRGI_RENDER"]
TMP = os.environ.get("MRGI_TEST_TMP", "/tmp")
SIZE = "40x40"


def check(condition, what):
    if not condition:
        print("check failed:", what, file=sys.stderr)
        sys.exit(1)


def run(*args):
    env = dict(os.environ)
    env.pop("DISPLAY", None)
    p = subprocess.run([RENDER, *args], capture_output=True, text=True, env=env, timeout=600)
    return p.returncode, p.stdout, p.stderr


def render(name, *extra):
    """Indirect light alone of cornell-spot, full-resolution gather (so that
    every pixel gathers the same VPLs in every run), as an RGB array."""
    path = os.path.join(TMP, "visibility_%s.exr" % name)
    if os.path.exists(path):
        os.remove(path)
    code, _, err = run("cornell-spot", "-o", path, "--size", SIZE, "-q", "--gi", "full",
                       "--rsm-size", "64", "--indirect-only", *extra)
    check(code == 0, "render %s: %s" % (name, err))
    image = vtkImageData()
    check(mrgi.vtkMRGIImageIO().Read(path, image), "read " + path)
    pixels = vtk_to_numpy(image.GetPointData().GetScalars())[:, :3].astype(np.float64)
    check(np.all(np.isfinite(pixels)) and pixels.min() >= 0.0, name + ": finite, non-negative")
    return pixels


def bad_options():
    target = os.path.join(TMP, "visibility_bad.png")
    for args, name in ((["--indirect-visibility", "shadows"], "--indirect-visibility"),
                       (["--ism-tile", "48"], "--ism-tile"),
                       (["--ism-tile", "2"], "--ism-tile"),
                       (["--ism-points", "0"], "--ism-points"),
                       (["--ism-bias", "-1"], "--ism-bias"),
                       (["--ism-bias", "nan"], "--ism-bias"),
                       (["--ism-lazy-frames", "0"], "--ism-lazy-frames"),
                       (["--ism-max-texel-angle", "-0.1"], "--ism-max-texel-angle"),
                       (["--ism-max-texel-angle", "nan"], "--ism-max-texel-angle"),
                       (["--ism-max-texel-angle", "5"], "--ism-max-texel-angle"),
                       (["--ism-point-mode", "random"], "--ism-point-mode")):
        if os.path.exists(target):
            os.remove(target)
        code, _, err = run("cornell-spot", "-o", target, "--size", "8x8", *args)
        check(code != 0 and name in err, "%s is refused by name: %s" % (" ".join(args), err))
        check(not os.path.exists(target), "no output after a refused option")


def python_api():
    p = mrgi.vtkMRGIPass()
    check(p.GetIndirectVisibility() == mrgi.vtkMRGIIndirectLight.VisibilityOff, "default off")
    p.SetIndirectVisibility(mrgi.vtkMRGIIndirectLight.VisibilityISM)
    check(p.GetIndirectVisibility() == 1, "ISM set")
    p.SetIndirectVisibility(7)
    check(p.GetIndirectVisibility() == mrgi.vtkMRGIIndirectLight.VisibilityVoxels, "clamped")
    p.SetISMTileSize(64)
    p.SetISMPointsPerVPL(128)
    p.SetISMLazyFrames(1)
    p.SetISMPointMode(0)
    check((p.GetISMTileSize(), p.GetISMPointsPerVPL(), p.GetISMLazyFrames(), p.GetISMPointMode())
          == (64, 128, 1, 0), "ISM knobs forwarded")
    text = str(p)
    check("Visibility: Voxels" in text and "ImperfectShadowMaps" in text, "PrintSelf shows them")


def main():
    bad_options()
    python_api()
    off = render("off")
    ism = render("ism", "--indirect-visibility", "ism")
    unbiased = render("ism_nobias", "--indirect-visibility", "ism", "--ism-bias", "16")
    every = render("ism_every_direction", "--indirect-visibility", "ism", "--ism-max-texel-angle", "0")
    voxel = render("voxel", "--indirect-visibility", "voxel")
    # --timings names the voxel buffer each light's visibility used: here the
    # VPLs' alone (cornell-spot has no area lights).
    code, out, err = run("cornell-spot", "-o", os.path.join(TMP, "visibility_timings.exr"), "--size", SIZE,
                         "-q", "--gi", "full", "--rsm-size", "64", "--indirect-only",
                         "--indirect-visibility", "voxel", "--timings")
    lines = [line for line in out.splitlines() if line.startswith(("voxels:", "voxels ("))]
    check(code == 0 and len(lines) == 1 and lines[0].startswith("voxels (VPLs): "),
          "--timings reports the VPLs' voxels only: %r %s" % (lines, err))
    # ... with the indirect stage's own slices (MRGI_VOXEL_INDIRECT_SLICES),
    # not the area lights' nor the class default.
    stage_slices = mrgi.vtkMRGIPass().GetIndirectLightStage().GetVoxelization().GetNumberOfSlices()
    used = re.search(r" x (\d+) slices", lines[0])
    check(used is not None and int(used.group(1)) == stage_slices and
          stage_slices > mrgi.vtkMRGIVoxelization().GetNumberOfSlices(),
          "the VPLs' voxels use the indirect stage's %d slices: %r" % (stage_slices, lines[0]))
    lit = off.sum(axis=1) > 0
    check(lit.mean() > 0.5, "the indirect light reaches most pixels")
    tolerance = 1e-4 * off.max()
    # Visibility weights each VPL's term by V in [0, 1]: shadows only remove light.
    for name, image in (("ism", ism), ("voxel", voxel)):
        check(np.all(image <= off + tolerance), name + " never adds light")
        removed = 1.0 - image.sum() / off.sum()
        print("%s removes %.1f%% of the indirect light" % (name, 100 * removed))
        # The two blocks of cornell-spot hide part of the walls from each other.
        check(removed > 0.01, name + " casts indirect shadows (removed %.4f)" % removed)
    # The grazing rule (mrgi_ism_visibility.h step 2b) only skips shadow tests:
    # testing every direction can only remove more light, and here it does.
    check(np.all(every <= ism + tolerance), "--ism-max-texel-angle 0 never adds light")
    restored = ism.sum() / every.sum() - 1.0
    print("the grazing rule keeps %.2f%% more of the indirect light" % (100 * restored))
    check(restored > 0.0, "the default grazing rule skips some shadow tests (%.5f)" % restored)
    # A bias of 16 distances: every receiver is nearer than its depth minus
    # the bias, so every VPL is visible and the image is the unshadowed one.
    check(np.abs(unbiased - off).max() <= tolerance,
          "--ism-bias 16 gives the unshadowed image (max difference %g)"
          % np.abs(unbiased - off).max())


if __name__ == "__main__":
    main()
