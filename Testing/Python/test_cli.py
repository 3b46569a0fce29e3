"""mrgi-render's command-line contract: it renders PNG and EXR with stage
timings, and for bad input it prints a one-line error naming the problem,
exits non-zero and leaves no output file behind."""
import os
import re
import signal
import struct
import subprocess
import sys
import time
import zlib

RENDER = os.environ["MRGI_RENDER"]
TMP = os.environ.get("MRGI_TEST_TMP", "/tmp")


def check(condition, what):
    if not condition:
        print("check failed:", what, file=sys.stderr)
        sys.exit(1)


def run(*args, extra_env=None):
    env = dict(os.environ)
    env.pop("DISPLAY", None)
    env.update(extra_env or {})
    p = subprocess.run([RENDER, *args], capture_output=True, text=True, env=env, timeout=600)
    return p.returncode, p.stdout, p.stderr


def png_size(path):
    with open(path, "rb") as f:
        data = f.read()
    check(data[:8] == b"\x89PNG\r\n\x1a\n", "PNG signature in " + path)
    return struct.unpack(">II", data[16:24])


def fresh(name):
    path = os.path.join(TMP, name)
    if os.path.exists(path):
        os.remove(path)
    return path


def main():
    # --help and --version.
    code, out, _ = run("--help")
    check(code == 0 and "usage: mrgi-render SCENE" in out, "--help")
    for option in ("--size", "--timings", "--light", "--camera-position", "--half"):
        check(option in out, option + " documented in --help")
    # The usage text and the parser come from one table: every option the
    # text lists is accepted (alone, one that takes a value says it needs
    # one; a switch leaves only "no scene given"; --help and --version exit 0).
    documented = set()
    for line in out.splitlines():
        m = re.match(r"  (-[\w-]+)(?:, (--[\w-]+))?", line)
        if m:
            documented.update(n for n in m.groups() if n)
    check(len(documented) > 50, "options found in --help: %d" % len(documented))
    for option in sorted(documented):
        code, _, err = run(option)
        check("unknown option" not in err, option + " (in --help) is accepted: " + err)
        check(code == 0 or "mrgi-render: error:" in err, option + " alone: " + err)

    # The main job: PNG + EXR of the Cornell box with stage timings.
    png, exr = fresh("cli_cornell.png"), fresh("cli_cornell.exr")
    code, out, err = run("cornell", "-o", png, "-o", exr, "--size", "96x64", "--timings")
    print(out, err)
    check(code == 0, "cornell renders")
    check(png_size(png) == (96, 64), "PNG size")
    with open(exr, "rb") as f:
        check(f.read(4) == b"\x76\x2f\x31\x01", "EXR magic")
    check("scene" in out and "gather" in out and "output" in out and "total (GPU)" in out, "stage table")

    # Render window backends: the progress names the one used and its GL; a
    # named backend is used or is an error (never another one), as is an
    # unknown name from --backend or MRGI_BACKEND.
    for backend, platform in (("egl", "egl ("), ("osmesa", "osmesa (OSMesa, OpenGL")):
        path = fresh("cli_backend_%s.png" % backend)
        code, _, err = run("cornell", "-o", path, "--size", "32x24", "--backend", backend)
        check(code == 0 and png_size(path) == (32, 24), "--backend %s: %s" % (backend, err))
        check("render window: " + platform in err, "--backend %s in the progress: %s" % (backend, err))
        code, _, err = run("cornell", "-o", path, "--size", "32x24", extra_env={"MRGI_BACKEND": backend})
        check(code == 0 and "render window: " + platform in err, "MRGI_BACKEND=%s: %s" % (backend, err))
    bad = fresh("cli_backend_bad.png")
    for args, env, message in (
            (("--backend", "vulkan"), None, "--backend 'vulkan': expected auto, egl, osmesa or x"),
            ((), {"MRGI_BACKEND": "vulkan"}, "MRGI_BACKEND='vulkan' is not one of auto, egl, osmesa, x"),
            (("--backend", "x"), None, "DISPLAY is not set"),
            (("--backend", "osmesa"), {"MRGI_OSMESA_LIBRARY": "/nonexistent/libOSMesa.so"},
             "/nonexistent/libOSMesa.so")):
        code, _, err = run("cornell", "-o", bad, "--size", "32x24", *args, extra_env=env)
        check(code != 0 and message in err and not os.path.exists(bad),
              "%s %s refused: %s" % (" ".join(args), env, err))

    # Indirect light options: --gi off gives VTK's direct image, darker than
    # with GI; --indirect-only writes the indirect buffer; the ground truth runs.
    on_png, off_png, ind_exr, ref_exr = (fresh("cli_gi_on.png"), fresh("cli_gi_off.png"),
                                         fresh("cli_indirect.exr"), fresh("cli_reference.exr"))
    code, _, err = run("cornell-spot", "-o", on_png, "--size", "48x48", "-q", "--vpls", "64",
                       "--rsm-size", "64", "--vpl-selection", "importance")
    check(code == 0, "GI render: " + err)
    code, _, err = run("cornell-spot", "-o", off_png, "--size", "48x48", "-q", "--gi", "off")
    check(code == 0, "direct-only render: " + err)
    # Multiresolution VPL clusters, with and without thresholds; +inf for both
    # is the 16x16 grid, so its image differs from the split one.
    split_exr, grid_exr = fresh("cli_clusters.exr"), fresh("cli_clusters_inf.exr")
    code, _, err = run("cornell-spot", "-o", split_exr, "--size", "48x48", "-q", "--rsm-size",
                       "64", "--indirect-only", "--vpl-selection", "clusters",
                       "--cluster-depth-threshold", "1", "--cluster-normal-threshold", "0.1")
    check(code == 0, "clusters render: " + err)
    code, _, err = run("cornell-spot", "-o", grid_exr, "--size", "48x48", "-q", "--rsm-size",
                       "64", "--indirect-only", "--vpl-selection", "clusters",
                       "--cluster-depth-threshold", "inf", "--cluster-normal-threshold", "inf")
    check(code == 0, "clusters render, thresholds inf: " + err)
    check(open(split_exr, "rb").read() != open(grid_exr, "rb").read(),
          "cluster thresholds change the indirect light")
    # The VPL tree (NSW09 3.5): its threshold changes the indirect light (inf
    # gathers the 16x16 roots only); --timings reports the VPLs per pixel.
    tree_exr, roots_exr = fresh("cli_tree.exr"), fresh("cli_tree_inf.exr")
    code, out, err = run("cornell-spot", "-o", tree_exr, "--size", "48x48", "-q", "--rsm-size",
                         "64", "--indirect-only", "--vpl-selection", "tree", "--tree-threshold",
                         "0.02", "--timings")
    check(code == 0, "tree render: " + err)
    check("VPLs per pixel (tree)" in out, "--timings prints the tree's VPLs per pixel: " + out)
    code, _, err = run("cornell-spot", "-o", roots_exr, "--size", "48x48", "-q", "--rsm-size",
                       "64", "--indirect-only", "--vpl-selection", "tree", "--tree-threshold",
                       "inf")
    check(code == 0, "tree render, threshold inf: " + err)
    check(open(tree_exr, "rb").read() != open(roots_exr, "rb").read(),
          "the tree threshold changes the indirect light")
    # Bidirectional RSM importance (RIHKS11 4): the view changes which VPLs
    # are drawn, so its indirect light differs from flux importance's.
    brsm_exr, flux_exr = fresh("cli_brsm.exr"), fresh("cli_flux.exr")
    code, _, err = run("cornell-spot", "-o", brsm_exr, "--size", "48x48", "-q", "--rsm-size",
                       "64", "--vpls", "64", "--indirect-only", "--vpl-selection", "brsm")
    check(code == 0, "brsm render: " + err)
    code, _, err = run("cornell-spot", "-o", flux_exr, "--size", "48x48", "-q", "--rsm-size",
                       "64", "--vpls", "64", "--indirect-only", "--vpl-selection", "importance")
    check(code == 0, "importance render: " + err)
    check(open(brsm_exr, "rb").read() != open(flux_exr, "rb").read(),
          "brsm and flux importance select different VPLs")
    check(os.path.getsize(on_png) != os.path.getsize(off_png) or
          open(on_png, "rb").read() != open(off_png, "rb").read(), "--gi off changes the image")
    # --ssao darkens the direct light (corners and contacts), with the
    # scene-scaled default radius and with every knob given; the stage is timed.
    ao_exr, noao_exr = fresh("cli_ssao_on.exr"), fresh("cli_ssao_off.exr")
    code, out, err = run("cornell", "-o", ao_exr, "--size", "48x40", "-q", "--gi", "off",
                         "--ssao", "on", "--timings")
    check(code == 0 and "ssao.ao" in out, "--ssao on renders and times its stage: " + err)
    code, _, err = run("cornell", "-o", noao_exr, "--size", "48x40", "-q", "--gi", "off")
    check(code == 0, "--ssao off render: " + err)
    check(open(ao_exr, "rb").read() != open(noao_exr, "rb").read(), "--ssao on changes the image")
    code, _, err = run("cornell", "-o", fresh("cli_ssao_knobs.png"), "--size", "40x48", "-q",
                       "--ssao", "on", "--ssao-samples", "8", "--ssao-radius", "20",
                       "--ssao-bias", "0.5", "--ssao-blur", "on")
    check(code == 0, "--ssao with every knob: " + err)
    # --ssgi adds a bounce to the direct light; the stage is timed.
    gi_exr = fresh("cli_ssgi_on.exr")
    code, out, err = run("cornell", "-o", gi_exr, "--size", "48x40", "-q", "--gi", "off",
                         "--ssgi", "on", "--ssgi-samples", "16", "--ssgi-radius", "80", "--timings")
    check(code == 0 and "ssgi" in out, "--ssgi on renders and times its stage: " + err)
    check(open(gi_exr, "rb").read() != open(noao_exr, "rb").read(), "--ssgi on changes the image")
    # --ssao-resolution multires: BMR's masks and blend run and are timed.
    code, out, err = run("cornell", "-o", fresh("cli_ssao_multires.png"), "--size", "40x48", "-q",
                         "--ssao", "on", "--ssao-resolution", "multires", "--timings")
    check(code == 0 and "bmr.mask" in out and "bmr.blend" in out,
          "--ssao-resolution multires renders and times the masks and blend: " + err)
    # --ssgi-resolution multires: the same masks and blend for SSGI.
    code, out, err = run("cornell", "-o", fresh("cli_ssgi_multires.png"), "--size", "40x48", "-q",
                         "--gi", "off", "--ssgi", "on", "--ssgi-samples", "16",
                         "--ssgi-resolution", "multires", "--timings")
    check(code == 0 and "ssgi" in out and "bmr.mask" in out and "bmr.blend" in out,
          "--ssgi-resolution multires renders and times the masks and blend: " + err)
    code, out, err = run("cornell-spot", "-o", fresh("cli_shadow_multires.png"), "--size", "40x48",
                         "-q", "--shadow-resolution", "multires", "--timings")
    check(code == 0 and "shadows.factors.invert" in out,
          "--shadow-resolution multires renders and times its steps: " + err)
    mr_exr = fresh("cli_multires.exr")
    code, out, err = run("cornell-spot", "-o", mr_exr, "--size", "48x48", "-q", "--gi", "multires",
                         "--depth-threshold", "8", "--normal-threshold", "inf", "--upsample", "mask",
                         "--refinement", "geometry", "--timings")
    check(code == 0 and os.path.getsize(mr_exr) > 0, "--gi multires: " + err)
    check("select" in out and "upsample" in out, "multires stages in the timing table")
    splat_exr = fresh("cli_splat.exr")
    code, out, err = run("cornell-spot", "-o", splat_exr, "--size", "48x48", "-q", "--gi", "multires",
                         "--depth-threshold", "8", "--normal-threshold", "inf", "--upsample", "mask",
                         "--gather", "splat", "--timings")
    check(code == 0 and "gather.subsplats" in out, "--gather splat times its subsplat list: " + err)
    check(open(splat_exr, "rb").read() == open(mr_exr, "rb").read(),
          "--gather splat writes the stenciled gather's image (splatting refines by geometry)")
    code, out, err = run("cornell-spot", "-o", fresh("cli_splat_lit.exr"), "--size", "48x48", "-q",
                         "--gather", "splat", "--refinement", "illumination")
    check(code != 0 and "--gather splat" in err and "illumination" in err,
          "--gather splat refuses --refinement illumination by name: " + err)
    # Area lights: cornell-area is lit by its emitter alone (with and without
    # voxel shadows), a command-line rectangle lights any scene.
    area = {}
    for visibility in ("off", "naive"):
        area[visibility] = fresh("cli_area_%s.exr" % visibility)
        code, out, err = run("cornell-area", "-o", area[visibility], "--size", "48x48", "-q",
                             "--area-light-samples", "16", "--area-light-visibility", visibility,
                             "--voxel-size", "64", "--timings")
        check(code == 0 and "area" in out, "cornell-area, visibility %s: %s" % (visibility, err))
        check(("voxels: 64x64 (fixed)" in out) == (visibility == "naive"),
              "--timings reports the fixed voxel size only where voxels were used: %s" % out[-400:])
    # Without --voxel-size the voxel buffer is sized automatically: the Cornell
    # box is shallow, so its voxel pixels are finer than NPW10's 128^2.
    code, out, err = run("cornell-area", "-o", fresh("cli_area_auto.exr"), "--size", "48x48", "-q",
                         "--area-light-samples", "16", "--area-light-visibility", "naive", "--timings")
    auto = [line for line in out.splitlines() if line.startswith("voxels: ")]
    check(code == 0 and len(auto) == 1 and "(automatic)" in auto[0], "automatic voxel size reported: %s" % err)
    if auto:
        side = int(auto[0].split()[1].split("x")[0])
        check(128 < side <= 512, "cornell-area's automatic voxel side %d is finer than 128" % side)
    # Incremental visibility with and without the incremental stencil
    # (NPW10 3.4): it gathers the penumbrae at finer levels, so the images differ.
    for stencil in ("on", "off"):
        area["stencil-" + stencil] = fresh("cli_area_stencil_%s.exr" % stencil)
        code, out, err = run("cornell-area", "-o", area["stencil-" + stencil], "--size", "48x48", "-q",
                             "--area-light-samples", "64", "--area-light-visibility", "incremental",
                             "--voxel-size", "64", "--incremental-stencil", stencil, "--timings")
        check(code == 0, "--incremental-stencil %s: %s" % (stencil, err))
        check(("select.incremental" in out) == (stencil == "on"),
              "--incremental-stencil %s times its stencil pass only when on" % stencil)
    check(open(area["stencil-on"], "rb").read() != open(area["stencil-off"], "rb").read(),
          "--incremental-stencil changes the image")
    # Area-light highlights gathered at full resolution or at the
    # multiresolution texels (NPW10 3.2.1): only multires times the specular
    # stencil; the images differ.
    for resolution in ("full", "multires"):
        area["specular-" + resolution] = fresh("cli_area_specular_%s.exr" % resolution)
        code, out, err = run("cornell-area", "-o", area["specular-" + resolution], "--size", "48x48",
                             "-q", "--area-light-samples", "16", "--area-light-visibility", "off",
                             "--specular", "0.5:40", "--area-light-specular-resolution", resolution,
                             "--timings")
        check(code == 0, "--area-light-specular-resolution %s: %s" % (resolution, err))
        check(("select.specular" in out) == (resolution == "multires"),
              "--area-light-specular-resolution %s times the specular stencil only when multires"
              % resolution)
    check(open(area["specular-full"], "rb").read() != open(area["specular-multires"], "rb").read(),
          "--area-light-specular-resolution changes the image")
    # More samples than the incremental masks hold: naive visibility for
    # that light, said once (not once per frame); none at the limit.
    many = fresh("cli_area_many.exr")
    for samples, warned in (("1024", True), ("512", False)):
        code, _, err = run("cornell-area", "-o", many, "--size", "24x24", "--frames", "3",
                           "--area-light-samples", samples, "--voxel-size", "32")
        check(code == 0 and err.count("use naive visibility") == (1 if warned else 0),
              "--area-light-samples %s: naive fallback said %s: %s" % (samples, "once" if warned else "never", err))
    dark = fresh("cli_area_dark.exr")
    code, _, err = run("cornell-area", "-o", dark, "--size", "48x48", "-q", "--area-lights", "off")
    check(code == 0, "--area-lights off: " + err)
    sizes = [os.path.getsize(p) for p in (area["off"], area["naive"], dark)]
    check(open(area["off"], "rb").read() != open(area["naive"], "rb").read(), "voxel shadows change the image")
    check(open(area["off"], "rb").read() != open(dark, "rb").read(), "the area light lights the box")
    # The area light bounces (mrgi_area_light_rsm.h) and --gi off removes that.
    flat = fresh("cli_area_gi_off.exr")
    code, _, err = run("cornell-area", "-o", flat, "--size", "48x48", "-q", "--area-light-samples",
                       "16", "--area-light-visibility", "off", "--voxel-size", "64", "--gi", "off")
    check(code == 0, "cornell-area --gi off: " + err)
    check(open(area["off"], "rb").read() != open(flat, "rb").read(),
          "the area light's bounce is in the image with --gi on only")
    check(min(sizes) > 0, "area-light outputs written")
    lit = fresh("cli_area_rect.png")
    code, _, err = run("cornell-spot", "-o", lit, "--size", "32x32", "-q", "--gi", "off",
                       "--area-light", "278,540,280:100,0,0:0,0,-80:1,1,1:5", "--area-light-two-sided")
    check(code == 0 and os.path.exists(lit), "--area-light on cornell-spot: " + err)
    tm_png = fresh("cli_tone_mapping.png")
    code, _, err = run("cornell-spot", "-o", tm_png, "--size", "48x48", "-q", "--tone-mapping")
    check(code == 0 and os.path.exists(tm_png), "--tone-mapping: " + err)
    check("ERR" not in err and "error" not in err.lower(), "--tone-mapping leaves no errors: " + err)
    code, _, err = run("cornell-spot", "-o", ind_exr, "--size", "48x48", "-q", "--indirect-only")
    check(code == 0 and os.path.getsize(ind_exr) > 0, "--indirect-only: " + err)
    code, _, err = run("cornell-spot", "-o", ref_exr, "--size", "32x32", "--reference",
                       "--reference-passes", "2", "--reference-error", "0")
    check(code == 0 and os.path.getsize(ref_exr) > 0, "--reference: " + err)
    check(re.search(r"ground truth: 2 passes, per-pixel error [0-9.]+ at the 0.95 quantile", err),
          "--reference reports passes and the per-pixel error: " + err)
    code, _, err = run("cornell-spot", "-o", ref_exr, "--size", "32x32", "--reference",
                       "--reference-passes", "1", "--reference-pixel", "center", "-q")
    check(code == 0 and os.path.getsize(ref_exr) > 0, "--reference-pixel center: " + err)
    code, _, err = run("cornell-spot", "-o", ref_exr, "--size", "32x32", "--reference",
                       "--reference-pixel", "middle", "-q")
    check(code != 0 and "--reference-pixel" in err and "box or center" in err,
          "--reference-pixel refuses other values by name: " + err)
    code, _, err = run("cornell-area", "-o", ref_exr, "--size", "24x24", "--voxel-offset", "both", "-q")
    check(code == 0 and os.path.getsize(ref_exr) > 0, "--voxel-offset both: " + err)
    code, _, err = run("cornell-area", "-o", ref_exr, "--size", "24x24", "--voxel-offset", "sideways", "-q")
    check(code != 0 and "--voxel-offset" in err and "normals, receiver or both" in err,
          "--voxel-offset refuses other values by name: " + err)
    code, out, err = run("cornell-area", "-o", ref_exr, "--size", "24x24", "--voxel-slices", "256", "--timings")
    check(code == 0 and "x 256 slices" in out, "--voxel-slices 256 reaches the voxels: " + out + err)
    code, _, err = run("cornell-area", "-o", ref_exr, "--size", "24x24", "--voxel-slices", "200", "-q")
    check(code != 0 and "--voxel-slices" in err and "128, 256, 384 or 512" in err,
          "--voxel-slices refuses other counts by name: " + err)
    # stderr is a pipe here, no terminal: no per-pass lines unless --progress
    check("ground truth: pass" not in err, "no progress lines into a pipe without --progress: " + err)
    code, _, err = run("cornell-spot", "-o", ref_exr, "--size", "32x32", "--reference",
                       "--reference-passes", "2", "--reference-error", "0", "--progress",
                       "--reference-percentile", "0.5")
    check(code == 0, "--progress --reference-percentile 0.5: " + err)
    check(re.search(r"ground truth: pass 1, \d+%, per-pixel error unknown", err) and
          re.search(r"ground truth: pass 2, 100%, per-pixel error [0-9.]+ \(target 0 at the 0.5 "
                    r"quantile\), about [0-9]+ s left", err),
          "--progress prints a line per pass here: " + err)

    # Scaling scene and a file scene.
    out_png = fresh("cli_scaling.png")
    code, _, err = run("scaling", "--triangles", "5000", "--objects", "4", "-o", out_png,
                       "--size", "64x64", "-q")
    check(code == 0 and os.path.exists(out_png), "scaling renders: " + err)
    check(err == "", "--quiet prints nothing")

    parallel_framing()
    display_steps()
    staging()
    bad_input()
    quiet_and_plain(corrupt_stl())
    signal_during_write()
    print("ok")


def display_steps():
    """Exposure, tone mapping and FXAA shape the display image only: with EXR
    outputs alone they do not run, and the EXR is the same file as when a
    PNG beside it needs them. The emptiness check holds either way."""
    alone, both_exr, both_png = fresh("cli_hdr_alone.exr"), fresh("cli_hdr_both.exr"), fresh("cli_hdr_both.png")
    code, _, err = run("cornell-spot", "-o", alone, "--size", "40x32", "--tone-mapping")
    check(code == 0 and "no display image" in err and "(auto)" not in err, "EXR alone: " + err)
    code, _, err = run("cornell-spot", "-o", both_exr, "-o", both_png, "--size", "40x32", "--tone-mapping")
    check(code == 0 and "exposure" in err and "(auto), tone mapped, FXAA" in err, "EXR and PNG: " + err)
    with open(alone, "rb") as a, open(both_exr, "rb") as b:
        check(a.read() == b.read(), "the EXR does not depend on the display steps")
    # A camera looking away: the background alone fails the run, whichever
    # image the check reads (the window's for PNG, the HDR colour for EXR,
    # also with --indirect-only), unless --allow-empty.
    away = ("cornell-spot", "--size", "24x24", "--camera-position", "0,0,-5000",
            "--camera-focal-point", "0,0,-10000", "--background", "0.2,0.3,0.4")
    for outputs in (["x.png"], ["x.exr"], ["x.exr", "--indirect-only"]):
        path = fresh("cli_away_" + outputs[0])
        code, _, err = run(*away, "-o", path, *outputs[1:])
        check(code == 1 and "renders an empty image (background only)" in err and not os.path.exists(path),
              "%s of the background alone fails: %s" % (outputs, err))
        code, _, err = run(*away, "-o", path, *outputs[1:], "--allow-empty")
        check(code == 0 and os.path.exists(path), "%s with --allow-empty: %s" % (outputs, err))


def parallel_framing():
    """--parallel frames what the perspective view shows: VTK's parallel
    scale defaults to 1 world unit, which in the millimetre Cornell box
    showed one uniform patch of wall."""
    import numpy as np
    import mrgi
    from vtkmodules.vtkCommonDataModel import vtkImageData
    from vtkmodules.util.numpy_support import vtk_to_numpy
    means = {}
    for name, extra in (("persp", ()), ("parallel", ("--parallel",))):
        path = fresh("cli_%s.exr" % name)
        code, _, err = run("cornell-spot", "-o", path, "--size", "48x48", "--gi", "off", *extra)
        check(code == 0, "cornell-spot %s renders: %s" % (name, err))
        image = vtkImageData()
        check(mrgi.vtkMRGIImageIO().Read(path, image), "read " + path)
        pixels = vtk_to_numpy(image.GetPointData().GetScalars())[:, :3]
        means[name] = (float(pixels.mean()), float(pixels.std()))
    code, _, err = run("cornell-spot", "-o", fresh("cli_ssgi.exr"), "--size", "16x16", "--ssgi", "on",
                       "--indirect-only")
    check(code != 0 and "--ssgi on" in err and "--indirect-only" in err,
          "--indirect-only with --ssgi on is refused by name: " + err)
    mean, spread = means["parallel"]
    # The perspective view's own spread is about its mean; a uniform wall's is ~0.
    check(spread > 0.3 * mean and spread > 0.3 * means["persp"][1],
          "--parallel shows the box, not one patch of wall: mean %.4f, spread %.4f (perspective %s)"
          % (mean, spread, means["persp"]))


def staging():
    """Data files are staged (Documentation/Staging.md): the up axis of a
    z-up pedestal, the options, a volume as an iso-surface; built-in scenes
    and --stage off are not."""
    # A z-up pedestal: a wide flat slab with a tall block on it.
    obj = os.path.join(TMP, "cli_pedestal.obj")
    with open(obj, "w") as f:
        for n, (x0, x1, y0, y1, z0, z1) in enumerate(((-1, 1, -1, 1, 0, 0.1), (-0.2, 0.2, -0.2, 0.2, 0.1, 2))):
            for z in (z0, z1):
                for y in (y0, y1):
                    for x in (x0, x1):
                        f.write("v %g %g %g\n" % (x, y, z))
            o = 8 * n + 1
            for a, b, c, d in ((0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)):
                f.write("f %d %d %d %d\n" % (o + a, o + b, o + c, o + d))
    images = {}
    for name, args, line in (
            ("default", [], "staged: up +z (flat base)"),
            ("up_y", ["--up", "y"], "staged: up +y (set)"),
            ("area", ["--key-light", "area", "--ground", "off", "--fill", "0.5"], "staged: up +z"),
            ("none", ["--key-light", "none"], "staged: up +z"),
            ("off", ["--stage", "off"], None)):
        images[name] = fresh("cli_stage_%s.png" % name)
        code, _, err = run(obj, "-o", images[name], "--size", "48x36", "--vpls", "16", *args)
        check(code == 0 and png_size(images[name]) == (48, 36), "staging %s: %s" % (name, err))
        check((line in err) if line else ("staged:" not in err), "staging %s progress: %s" % (name, err))
    contents = [open(images[n], "rb").read() for n in sorted(images)]
    check(len(set(contents)) == len(contents), "each staging option changes the image")
    code, _, err = run("cornell", "-o", fresh("cli_stage_cornell.png"), "--size", "16x16", "--up", "z",
                       "--fill", "0.5")
    check(code == 0 and "staged:" not in err, "built-in scenes are not staged: " + err)
    check("note: --up --fill ignored: built-in scenes are not staged" in err,
          "staging options on a built-in scene are noted: " + err)
    code, _, err = run(obj, "-o", fresh("cli_stage_off.png"), "--size", "16x16", "--stage", "off",
                       "--ground", "off")
    check(code == 0 and "note: --ground ignored: --stage off" in err, "--stage off notes: " + err)

    # A volume: a ball of 1s in 0s, shown as the iso-surface (Otsu: 0.5)
    # or at --iso; a value outside the range is an error naming the file.
    vol = os.path.join(TMP, "cli_ball.vtk")
    with open(vol, "w") as f:
        f.write("# vtk DataFile Version 3.0\nball\nASCII\nDATASET STRUCTURED_POINTS\n"
                "DIMENSIONS 12 12 12\nORIGIN 0 0 0\nSPACING 1 1 1\nPOINT_DATA 1728\n"
                "SCALARS density float 1\nLOOKUP_TABLE default\n")
        for z in range(12):
            for y in range(12):
                f.write(" ".join("1" if (x - 5.5) ** 2 + (y - 5.5) ** 2 + (z - 5.5) ** 2 < 16 else "0"
                                 for x in range(12)) + "\n")
    ball = fresh("cli_stage_ball.png")
    code, _, err = run(vol, "-o", ball, "--size", "32x32", "--gi", "off")
    check(code == 0 and "volume as the iso-surface at 0.5" in err, "a volume's iso-surface: " + err)
    code, _, err = run(vol, "-o", ball, "--size", "32x32", "--gi", "off", "--iso", "0.25")
    check(code == 0 and "iso-surface at 0.25" in err, "--iso: " + err)
    os.remove(ball)
    code, _, err = run(vol, "-o", ball, "--size", "32x32", "--iso", "7")
    check(code != 0 and "cli_ball.vtk" in err and "is empty" in err and not os.path.exists(ball),
          "--iso outside the range: " + err)


def corrupt_stl():
    """An STL file VTK's reader complains about (and the CLI refuses)."""
    path = os.path.join(TMP, "corrupt.stl")
    with open(path, "wb") as f:
        f.write(b"solid x\n facet normal 0 0 1\n outer loop\n vertex 0 0\n")
    return path


def bad_input():
    """Bad input: one-line error, non-zero exit, no output file. Also run
    alone (--bad-input) against the sanitized build (sanitize.CLI)."""
    target = fresh("cli_bad.png")
    bad_cases = [
        (["cornell", "-o", target, "--size", "0x64"], "width"),
        (["cornell", "-o", target, "--size", "nanx64"], "size"),
        (["cornell", "-o", target, "--size", "64"], "size"),
        (["cornell", "-o", target, "--bogus"], "unknown option"),
        ([os.path.join(TMP, "does-not-exist.ply"), "-o", target], "cannot open"),
        (["cornell", "-o", os.path.join(TMP, "x.jpg")], ".png or .exr"),
        (["cornell"], "no output"),
        (["cornell", "-o", target, "--light", "spot:1,2,3"], "--light"),
        (["cornell", "-o", target, "--light-intensity", "nan"], "--light-intensity"),
        (["cornell", "-o", target, "--camera-position", "1,2"], "--camera-position"),
        (["cornell", "-o", target, "--frames", "0"], "--frames"),
        (["cornell", "-o", target, "--gi", "half"], "--gi"),
        (["cornell", "-o", target, "--depth-threshold", "-3"], "--depth-threshold"),
        (["cornell", "-o", target, "--finest-level", "40"], "--finest-level"),
        (["cornell", "-o", target, "--upsample", "cubic"], "--upsample"),
        (["cornell", "-o", target, "--gather", "scatter"], "--gather"),
        (["cornell", "-o", target, "--area-light", "0,0,0:1,0,0"], "--area-light"),
        (["cornell", "-o", target, "--area-light", "0,0,0:1,0,0:1,1,0"], "perpendicular"),
        (["cornell", "-o", target, "--area-light", "0,0,0:1,0,0:0,1,0:1,1,1:-2"], "intensity"),
        (["cornell", "-o", target, "--area-light", "0,0,0:1,0,0:0,1,0:-1,1,1"], "colour"),
        (["cornell", "-o", target, "--area-light-samples", "0"], "--area-light-samples"),
        (["cornell", "-o", target, "--area-light-visibility", "exact"], "--area-light-visibility"),
        (["cornell", "-o", target, "--direct-shadows", "maybe"], "--direct-shadows"),
        (["cornell", "-o", target, "--direct-shadows", ""], "--direct-shadows"),
        (["cornell", "-o", target, "--shadow-kernel", "15"], "--shadow-kernel"),
        (["cornell", "-o", target, "--shadow-kernel", "0"], "--shadow-kernel"),
        (["cornell", "-o", target, "--shadow-light-radius", "0"], "--shadow-light-radius"),
        (["cornell", "-o", target, "--shadow-light-radius", "nan"], "--shadow-light-radius"),
        (["cornell", "-o", target, "--voxel-size", "0"], "--voxel-size"),
        (["cornell", "-o", target, "--incremental-stencil", "yes"], "--incremental-stencil"),
        (["cornell", "-o", target, "--area-light-specular-resolution", "half"],
         "--area-light-specular-resolution"),
        (["cornell", "-o", target, "--area-lights", "maybe"], "--area-lights"),
        (["cornell", "-o", target, "--vpls", "5000"], "--vpls"),
        (["cornell", "-o", target, "--vpls", "-1"], "--vpls"),
        (["cornell", "-o", target, "--rsm-size", "8"], "--rsm-size"),
        (["cornell", "-o", target, "--vpl-selection", "random"], "--vpl-selection"),
        (["cornell", "-o", target, "--vpl-selection", "BRSM4"], "--vpl-selection"),
        (["cornell", "-o", target, "--cluster-depth-threshold", "-1"], "--cluster-depth-threshold"),
        (["cornell", "-o", target, "--cluster-normal-threshold", "nan"],
         "--cluster-normal-threshold"),
        (["cornell", "-o", target, "--tree-threshold", "-1"], "--tree-threshold"),
        (["cornell", "-o", target, "--tree-threshold", "nan"], "--tree-threshold"),
        (["cornell", "-o", target, "--vpl-selection", "tree", "--rsm-size", "2048"],
         "--rsm-size"),
        (["cornell", "-o", target, "--indirect-strength", "nan"], "--indirect-strength"),
        (["cornell", "-o", target, "--gi", "off", "--indirect-only"], "--indirect-only"),
        (["cornell", "-o", target, "--reference-visibility", "maybe"], "--reference-visibility"),
        (["cornell", "-o", target, "--ssao", "yes"], "--ssao"),
        (["cornell", "-o", target, "--ssao-samples", "0"], "--ssao-samples"),
        (["cornell", "-o", target, "--ssao-samples", "1001"], "--ssao-samples"),
        (["cornell", "-o", target, "--ssao-samples", "3x"], "--ssao-samples"),
        (["cornell", "-o", target, "--ssao-radius", "0"], "--ssao-radius"),
        (["cornell", "-o", target, "--ssao-radius", "-1"], "--ssao-radius"),
        (["cornell", "-o", target, "--ssao-radius", "nan"], "--ssao-radius"),
        (["cornell", "-o", target, "--ssao-radius", "1e39"], "--ssao-radius"),
        (["cornell", "-o", target, "--ssao-bias", "inf"], "--ssao-bias"),
        (["cornell", "-o", target, "--ssao-bias", "0.1.2"], "--ssao-bias"),
        (["cornell", "-o", target, "--ssao-resolution", "half"], "--ssao-resolution"),
        (["cornell", "-o", target, "--shadow-resolution", "multi"], "--shadow-resolution"),
        (["cornell", "-o", target, "--ssao-resolution", ""], "--ssao-resolution"),
        (["cornell", "-o", target, "--ssao-blur", "maybe"], "--ssao-blur"),
        (["cornell", "-o", target, "--ssgi", "yes"], "--ssgi"),
        (["cornell", "-o", target, "--ssgi-samples", "0"], "--ssgi-samples"),
        (["cornell", "-o", target, "--ssgi-samples", "513"], "--ssgi-samples"),
        (["cornell", "-o", target, "--ssgi-radius", "0"], "--ssgi-radius"),
        (["cornell", "-o", target, "--ssgi-radius", "nan"], "--ssgi-radius"),
        (["cornell", "-o", target, "--ssgi-radius", "1e39"], "--ssgi-radius"),
        (["cornell", "-o", target, "--ssgi-resolution", "half"], "--ssgi-resolution"),
        (["cornell", "-o", "/nonexistent-dir/out.png", "--size", "8x8"], "nonexistent-dir"),
        # Every value outside its documented range is refused, naming the option.
        (["cornell", "-o", target, "--voxel-size", "16384"], "[1, 4096]"),
        (["cornell", "-o", target, "--area-light", "0,0,0:1e39,0,0:0,1,0"], "float range"),
        (["cornell", "-o", target, "--area-light", "0,0,0:1e20,0,0:0,1e20,0"], "float range"),
        (["cornell", "-o", target, "--area-light", "0,0,0:1,0,0:0,1,0:1,1,1:1e7"], "intensity"),
        (["cornell", "-o", target, "--light-intensity", "1e300"], "--light-intensity"),
        (["cornell", "-o", target, "--light", "positional:1e39,0,0"], "float range"),
        (["cornell", "-o", target, "--background", "-1,0,0"], "--background"),
        (["cornell", "-o", target, "--camera-position", "1e39,0,0"], "--camera-position"),
        (["cornell", "-o", target, "--camera-view-up", "0,0,0"], "--camera-view-up"),
        (["cornell", "-o", target, "--camera-position", "1,2,3", "--camera-focal-point", "1,2,3"],
         "coincide"),
        (["cornell", "-o", target, "--size", "64x64junk"], "--size"),
        (["cornell", "-o", target, "--frames", "3x"], "--frames"),
        (["cornell", "-o", target, "--vpls", "1e3"], "--vpls"),
        (["cornell", "-o", target, "--triangles", "99999999999999999999"], "--triangles"),
        (["cornell", "-o", target, "--seed", "-1"], "--seed"),
        (["cornell", "-o", target, "--depth-threshold", "1e300"], "--depth-threshold"),
        (["cornell", "-o", target, "--normal-threshold", "inff"], "--normal-threshold"),
        (["cornell", "-o", target, "--camera-view-angle", "180"], "--camera-view-angle"),
        (["cornell", "-o", target, "--specular", "0.5:nan"], "--specular"),
        (["cornell", "-o", target, "--reference-error", "1.5"], "--reference-error"),
        (["cornell", "-o", target, "--reference-percentile", "0"], "--reference-percentile"),
        (["cornell", "-o", target, "--reference-percentile", "1.5"], "--reference-percentile"),
        (["cornell", "-o", target, "--finest-level", "24"], "--finest-level"),
        (["cornell", "-o", target, "--stage", "yes"], "--stage"),
        (["cornell", "-o", target, "--up", "w"], "--up 'w': expected auto, x, y, z, -x, -y or -z"),
        (["cornell", "-o", target, "--up", "+y"], "--up"),
        (["cornell", "-o", target, "--ground", "1"], "--ground"),
        (["cornell", "-o", target, "--key-light", "laser"], "--key-light"),
        (["cornell", "-o", target, "--fill", "0"], "--fill"),
        (["cornell", "-o", target, "--fill", "1.5"], "--fill"),
        (["cornell", "-o", target, "--fill", "nan"], "--fill"),
        (["cornell", "-o", target, "--iso", "nan"], "--iso"),
        (["cornell", "-o", target, "--iso", "1e39"], "--iso"),
        (["cornell", "-o", target, "--iso", "3junk"], "--iso"),
        # Outputs are checked before rendering: a bad second output leaves
        # no first one; an output given twice; a directory as output.
        (["cornell", "-o", target, "-o", "/nonexistent-dir/second.exr", "--size", "8x8"],
         "second.exr"),
        (["cornell", "-o", target, "-o", target, "--size", "8x8"], "given twice"),
        (["cornell", "-o", os.path.join(TMP, "cli_dir.png"), "--size", "8x8"], "is a directory"),
        # Sizes this OpenGL cannot hold are refused before rendering, never
        # rendered without indirect light: the multiresolution buffer is about
        # twice the width (llvmpipe: GL_MAX_TEXTURE_SIZE 16384).
        (["cornell", "-o", target, "--size", "9000x16"], "GL_MAX_TEXTURE_SIZE"),
    ]
    os.makedirs(os.path.join(TMP, "cli_dir.png"), exist_ok=True)
    unreadable = corrupt_stl()
    bad_cases.append(([unreadable, "-o", target], "corrupt.stl"))
    for args, expected in bad_cases:
        code, out, err = run(*args)
        lines = [l for l in err.splitlines() if l.startswith("mrgi-render: error:")]
        print(args, "->", code, err.strip())
        check(code != 0, "non-zero exit for %s" % args)
        check(len(lines) == 1, "exactly one error line for %s" % args)
        check(expected in lines[0], "error for %s names %r" % (args, expected))
        check(not os.path.exists(target), "no output left for %s" % args)
    leftovers = [n for n in os.listdir(TMP) if n.startswith("cli_bad.png.tmp")]
    check(not leftovers, "no temporary files left: %s" % leftovers)


def quiet_and_plain(unreadable):
    """-q leaves only the CLI's one error line, even when VTK complains; without
    -q, VTK's messages come as plain lines (no colour codes, no file:line)."""
    target = fresh("cli_quiet.png")
    code, out, err = run(unreadable, "-o", target, "-q")
    print("-q:", repr(err))
    check(code != 0, "-q: a corrupt file fails")
    check(len(err.splitlines()) == 1 and err.startswith("mrgi-render: error:"),
          "-q: exactly the one error line: %r" % err)
    code, out, err = run(unreadable, "-o", target)
    check(code != 0 and "\x1b" not in err, "no colour codes without -q: %r" % err)
    vtk_lines = [l for l in err.splitlines() if l.startswith("mrgi-render: VTK error:")]
    check(vtk_lines, "VTK's complaint is shown without -q: %r" % err)
    check(all(l.startswith("mrgi-render: ") for l in err.splitlines()),
          "every line is the CLI's: %r" % err)
    check(not any(re.search(r"\.cxx[:,]|line \d+\n|0x[0-9a-f]{6,}", l) for l in vtk_lines),
          "plain VTK lines (no source file, line or address): %r" % vtk_lines)
    check(not os.path.exists(target), "no output after VTK's error")


def signal_during_write():
    """SIGTERM while the outputs are being written: exit 128 + 15, and neither
    the outputs nor any temporary file is left."""
    env = dict(os.environ)
    env.pop("DISPLAY", None)
    prefix = "cli_signal"
    for attempt, size in enumerate(("1024x1024", "2048x2048", "4096x2048")):
        outputs = [fresh(prefix + ".exr"), fresh(prefix + ".png")]
        p = subprocess.Popen([RENDER, "cornell", "--gi", "off", "--size", size, "-q",
                              "-o", outputs[0], "-o", outputs[1]],
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=env)
        caught = False
        while p.poll() is None:
            # The first staging or writer temporary file of THIS process
            # (".tmp-PID"): the write has begun. A stale temporary of an
            # earlier, killed run must not trigger the signal before the
            # handlers exist.
            mine = ".tmp-%d" % p.pid
            if any(n.startswith(prefix) and mine in n for n in os.listdir(TMP)):
                p.send_signal(signal.SIGTERM)
                caught = True
                break
            time.sleep(0.001)
        _, err = p.communicate(timeout=600)
        left = sorted(n for n in os.listdir(TMP) if n.startswith(prefix) and
                      (".tmp-" not in n or (".tmp-%d" % p.pid) in n))
        print("SIGTERM at", size, "caught:", caught, "exit:", p.returncode, "left:", left)
        if not caught:
            check(p.returncode == 0, "the render itself succeeds: %s" % err)
            continue  # the write was too quick to catch: a bigger image
        check(p.returncode == 128 + signal.SIGTERM, "exit 143 after SIGTERM, got %d" % p.returncode)
        if sorted(left) == sorted(os.path.basename(o) for o in outputs):
            # The signal landed just after the last rename: the run was
            # complete. Not what is tested here: a bigger image.
            continue
        check(not left, "nothing left after SIGTERM during the write: %s" % left)
        return
    check(False, "never caught the write in progress")


if __name__ == "__main__":
    if sys.argv[1:] == ["--bad-input"]:
        bad_input()
        print("ok")
    else:
        main()
