"""mrgi-render's exposure, tone mapping and anti-aliasing (--exposure,
--tone-mapping, --aa): the default (automatic exposure) lifts the
under-exposed area-light scene; a fixed EV scales; tone mapping keeps every
value up to 0.5 and never brightens; FXAA and SSAA add intermediate values
along edges and leave flat areas alone, SSAA 4x4 comes closer to an SSAA
8x8 reference; bad values are refused naming the option."""
import os
import subprocess
import sys

from vtkmodules.vtkIOImage import vtkPNGReader

RENDER = os.environ["MRGI_RENDER"]
TMP = os.environ.get("MRGI_TEST_TMP", "/tmp")


def check(condition, what):
    if not condition:
        print("check failed:", what, file=sys.stderr)
        sys.exit(1)


def run(*args):
    env = dict(os.environ)
    env.pop("DISPLAY", None)
    p = subprocess.run([RENDER, *args], capture_output=True, text=True, env=env, timeout=600)
    return p.returncode, p.stdout, p.stderr


def render(name, *args):
    """Renders to TMP/name.png and returns (width, height, [(r, g, b)], stderr)."""
    path = os.path.join(TMP, "cli_xa_" + name + ".png")
    if os.path.exists(path):
        os.remove(path)
    code, _, err = run(*args, "-o", path)
    check(code == 0 and os.path.exists(path), name + ": " + err)
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    w, h, _ = image.GetDimensions()
    s = image.GetPointData().GetScalars()
    pixels = [s.GetTuple(i)[:3] for i in range(s.GetNumberOfTuples())]
    return w, h, pixels, err


def luminance(p):
    return (0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]) / 255.0


def mean_luminance(pixels):
    return sum(luminance(p) for p in pixels) / len(pixels)


def spread(pixels, w, h, x, y, r=2):
    """Largest channel difference between (x, y) and its (2r+1)^2 neighbourhood."""
    c = pixels[y * w + x]
    worst = 0
    for dy in range(-r, r + 1):
        for dx in range(-r, r + 1):
            q = pixels[(y + dy) * w + x + dx]
            worst = max(worst, max(abs(q[k] - c[k]) for k in range(3)))
    return worst


def main():
    # Exposure: the default is automatic; cornell-area was measured at a
    # mean luminance of 0.037 with EV 0 (Documentation/reliability/composition.md).
    _, _, fixed, _ = render("area_ev0", "cornell-area", "--size", "48x48", "--exposure", "0")
    _, _, auto, err = render("area_auto", "cornell-area", "--size", "48x48")
    print("cornell-area mean luminance: EV 0 %.4f, default %.4f" % (mean_luminance(fixed),
                                                                     mean_luminance(auto)))
    check("(auto)" in err, "the default exposure is automatic: " + err)
    check(mean_luminance(fixed) < 0.08, "cornell-area at EV 0 is dark (the issue)")
    check(mean_luminance(auto) > 2.0 * mean_luminance(fixed) and mean_luminance(auto) > 0.12,
          "automatic exposure lifts cornell-area")

    # A fixed EV scales: +1 doubles every unclipped value (within rounding).
    base = ("cornell", "--size", "48x48", "--gi", "off", "--aa", "off")
    _, _, ev0, _ = render("ev0", *base, "--exposure", "0")
    _, _, ev1, err = render("ev1", *base, "--exposure", "1")
    check("+1.00 EV (fixed)" in err, "--exposure 1 is reported: " + err)
    doubled = [(a, b) for a, b in zip(ev0, ev1) if 10 < max(a) < 110]
    check(len(doubled) > 200, "enough mid-tone pixels: %d" % len(doubled))
    check(all(abs(2 * a[k] - b[k]) <= 2.5 for a, b in doubled for k in range(3)),
          "+1 EV doubles the mid-tones")

    # Tone mapping at +1.5 EV: values up to 0.5 kept, highlights rolled off, never brighter.
    _, _, plain15, _ = render("ev15", *base, "--exposure", "1.5")
    _, _, tone15, _ = render("ev15_tone", *base, "--exposure", "1.5", "--tone-mapping")
    kept = [(a, b) for a, b in zip(plain15, tone15) if max(a) <= 126]
    check(len(kept) > 200 and all(abs(a[k] - b[k]) <= 1 for a, b in kept for k in range(3)),
          "--tone-mapping keeps values up to 0.5")
    check(all(b[k] <= a[k] + 1 for a, b in zip(plain15, tone15) for k in range(3)),
          "--tone-mapping never brightens")
    clipped_plain = sum(1 for p in plain15 if max(p) >= 255)
    clipped_tone = sum(1 for p in tone15 if max(p) >= 255)
    check(clipped_plain > 20 and clipped_tone < clipped_plain / 4,
          "--tone-mapping rolls off the clipped highlights (%d -> %d)" % (clipped_plain,
                                                                          clipped_tone))

    # Anti-aliasing on the direct light (no multiresolution noise): edges get
    # intermediate values, the image comes closer to SSAA 8x8, flat areas stay.
    aa = ("cornell", "--size", "64x64", "--gi", "off", "--exposure", "0")
    w, h, off, _ = render("aa_off", *aa, "--aa", "off")
    _, _, fxaa, _ = render("aa_fxaa", *aa)  # the default
    _, _, ssaa4, _ = render("aa_ssaa4", *aa, "--aa", "ssaa:4")
    w8, h8, ssaa8, _ = render("aa_ssaa8", *aa, "--aa", "ssaa:8")
    check((w, h) == (64, 64) and (w8, h8) == (64, 64), "SSAA writes the asked size")

    def distance(a, b):
        return sum(abs(p[k] - q[k]) for p, q in zip(a, b) for k in range(3)) / (3.0 * len(a))

    edges = [(x, y) for y in range(2, h - 2) for x in range(2, w - 2)
             if spread(off, w, h, x, y, 1) > 40]
    flat = [(x, y) for y in range(2, h - 2) for x in range(2, w - 2)
            if spread(off, w, h, x, y, 2) == 0]
    check(len(edges) > 50 and len(flat) > 200, "edges %d, flat %d" % (len(edges), len(flat)))
    for name, image in (("fxaa", fxaa), ("ssaa:4", ssaa4)):
        values_off = len(set(off[y * w + x] for x, y in edges))
        values_aa = len(set(image[y * w + x] for x, y in edges))
        d_off, d_aa = distance(off, ssaa8), distance(image, ssaa8)
        flat_worst = max(max(abs(image[y * w + x][k] - off[y * w + x][k]) for k in range(3))
                         for x, y in flat)
        print("%-7s distinct edge colours %d -> %d, mean distance to SSAA 8x8 %.3f -> %.3f, "
              "flat areas change by at most %d / 255" % (name, values_off, values_aa, d_off,
                                                          d_aa, flat_worst))
        check(values_aa > values_off, name + " adds intermediate edge values")
        if name != "fxaa":
            # FXAA guesses edges from one sample per pixel: measured, it does
            # not come closer to SSAA 8x8 on average (it softens edges the
            # reference keeps sharp); supersampling does.
            check(d_aa < 0.8 * d_off, name + " comes closer to SSAA 8x8")
        check(flat_worst <= (0 if name == "fxaa" else 1), name + " leaves flat areas alone")

    # Bad values name the option and the range.
    for args, fragment in ((["--aa", "ssaa:9"], "--aa"), (["--aa", "msaa"], "--aa"),
                           (["--aa", "ssaa:"], "--aa"), (["--exposure", "30"], "--exposure"),
                           (["--exposure", "auto:0"], "--exposure"),
                           (["--exposure", "nan"], "--exposure"),
                           (["--size", "4000x100", "--aa", "ssaa:8"], "16384")):
        code, _, err = run("cornell", "-o", os.path.join(TMP, "cli_xa_bad.png"), *args)
        check(code == 2 and fragment in err and err.count("\n") == 1,
              " ".join(args) + " is refused naming " + fragment + ": " + err)
    print("test_cli_exposure_aa: all checks passed")


if __name__ == "__main__":
    main()
