/*
 * mrgi-compare: compare an image with a reference (EXR or PNG) with MRGI's
 * metrics: relative RMS error, RMS, max error, PSNR and SSIM, over the pixels
 * where the reference or the image is non-zero (or all pixels with --all),
 * and optionally write the difference image.
 *
 *   mrgi-compare IMAGE REFERENCE [--all] [--peak P] [--diff OUT.exr|OUT.png] [--diff-scale S]
 *
 * Prints one line: `relative_rms=... rms=... max=... psnr_db=... ssim=... pixels=... channels=N`
 * (every value a number). An RGBA image (the GPU's EXR) and an RGB one (the
 * ground truth's) are compared on RGB, alpha ignored (channels=3, with a
 * note on stderr); alpha counts only when both images have it.
 * Exit status: 0 compared, 1 the images cannot be compared (unreadable,
 * sizes differ), 2 bad usage (the usage is printed), 0 after --help.
 */
#include "mrgi_error.h"
#include "mrgi_exr.h"
#include "mrgi_image.h"
#include "mrgi_image_file.h"
#include "mrgi_metrics.h"
#include "mrgi_parse.h"
#include "mrgi_png.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char* const usage =
  "usage: mrgi-compare IMAGE REFERENCE [--all] [--peak P] [--diff OUT.exr|OUT.png]\n"
  "                    [--diff-scale S]\n"
  "\n"
  "Compares IMAGE with REFERENCE (each .exr or .png, same size) and prints\n"
  "  relative_rms=... rms=... max=... psnr_db=... ssim=... pixels=... channels=N\n"
  "\n"
  "  --all             compare every pixel (default: skip pixels black in both)\n"
  "  --peak P          largest meaningful value, > 0, for PSNR and SSIM (default 1)\n"
  "  --diff OUT        write |IMAGE - REFERENCE| (.exr or .png)\n"
  "  --diff-scale S    multiply the difference image by S, > 0 (default 1)\n"
  "  -h, --help        this text\n"
  "\n"
  "RGB and RGBA images are compared on RGB (alpha ignored, said on stderr);\n"
  "alpha counts when both have it. Exit: 0 compared, 1 not comparable, 2 bad usage.\n";

static int fail(const char* message)
{
  fprintf(stderr, "mrgi-compare: error: %s\n", message);
  return 1;
}

/* Bad usage: the message, then the usage, exit status 2. */
static int usage_error(const char* message, const char* value)
{
  fprintf(stderr, "mrgi-compare: error: %s%s%s%s\n", message, value ? " '" : "", value ? value : "",
    value ? "'" : "");
  fputs(usage, stderr);
  return 2;
}

/* Keeps the first `channels` values of each pixel, in place. */
static void keep_channels(mrgi_image* img, int32_t channels)
{
  const int64_t n = mrgi_image_pixel_count(img);
  for (int64_t p = 0; p < n; ++p)
  {
    for (int32_t c = 0; c < channels; ++c)
    {
      img->pixels[p * channels + c] = img->pixels[p * img->channels + c];
    }
  }
  img->channels = channels;
}

int main(int argc, char** argv)
{
  const char* paths[2] = { NULL, NULL };
  const char* diff_path = NULL;
  double peak = 1.0, diff_scale = 1.0;
  int all = 0, count = 0;
  mrgi_error err;
  for (int i = 1; i < argc; ++i)
  {
    const int has_value = i + 1 < argc;
    if (strcmp(argv[i], "-h") == 0 || strcmp(argv[i], "--help") == 0)
    {
      fputs(usage, stdout);
      return 0;
    }
    if (strcmp(argv[i], "--all") == 0)
      all = 1;
    else if (strcmp(argv[i], "--peak") == 0 || strcmp(argv[i], "--diff-scale") == 0)
    {
      const char* option = argv[i];
      double* target = strcmp(option, "--peak") == 0 ? &peak : &diff_scale;
      double value = 0.0;
      if (!has_value)
        return usage_error(
          strcmp(option, "--peak") == 0 ? "--peak needs a value" : "--diff-scale needs a value",
          NULL);
      if (mrgi_parse_double(argv[++i], &value, &err) != MRGI_OK || !(value > 0) ||
        !(value <= 3.4e38))
        return usage_error(strcmp(option, "--peak") == 0 ? "--peak needs a number > 0, not"
                                                         : "--diff-scale needs a number > 0, not",
          argv[i]);
      *target = value;
    }
    else if (strcmp(argv[i], "--diff") == 0)
    {
      if (!has_value)
        return usage_error("--diff needs a file name", NULL);
      diff_path = argv[++i];
      if (!mrgi_image_file_has_extension(diff_path, ".exr") && !mrgi_image_file_has_extension(diff_path, ".png"))
        return usage_error("--diff: the file name must end in .exr or .png, not", diff_path);
    }
    else if (argv[i][0] == '-' && argv[i][1] != '\0')
      return usage_error("unknown option", argv[i]);
    else if (count < 2)
      paths[count++] = argv[i];
    else
      return usage_error("more than two images given; the third is", argv[i]);
  }
  if (count != 2)
  {
    return usage_error(count == 0 ? "no images given" : "only one image given", NULL);
  }
  mrgi_image image = { 0 }, reference = { 0 }, diff = { 0 };
  int code = 0;
  uint8_t* mask = NULL;
  if (mrgi_image_file_read(paths[0], &image, &err) != MRGI_OK || mrgi_image_file_read(paths[1], &reference, &err) != MRGI_OK)
  {
    code = fail(err.message);
    goto done;
  }
  if (image.width != reference.width || image.height != reference.height)
  {
    char message[1024];
    snprintf(message, sizeof message, "the images differ in size: '%s' is %d x %d, '%s' is %d x %d",
      paths[0], image.width, image.height, paths[1], reference.width, reference.height);
    code = fail(message);
    goto done;
  }
  if (image.channels != reference.channels)
  {
    /* RGB against RGBA: the colour is what both have; alpha is ignored. */
    if (image.channels < 3 || reference.channels < 3)
    {
      char message[1024];
      snprintf(message, sizeof message,
        "the images differ in channels: '%s' has %d, '%s' has %d (RGB and RGBA mix, "
        "others do not)",
        paths[0], image.channels, paths[1], reference.channels);
      code = fail(message);
      goto done;
    }
    fprintf(stderr,
      "mrgi-compare: note: '%s' has %d channels, '%s' %d: comparing RGB, alpha ignored\n", paths[0],
      image.channels, paths[1], reference.channels);
    keep_channels(&image, 3);
    keep_channels(&reference, 3);
  }
  if (!all)
  {
    /* Ignore pixels where both images are black (background, unlit). */
    const int64_t n = mrgi_image_pixel_count(&reference);
    mask = (uint8_t*)calloc((size_t)n, 1);
    if (!mask)
    {
      code = fail("out of memory");
      goto done;
    }
    for (int64_t p = 0; p < n; ++p)
    {
      int zero = 1;
      for (int32_t c = 0; c < reference.channels; ++c)
      {
        zero &= reference.pixels[p * reference.channels + c] == 0.0f &&
          image.pixels[p * image.channels + c] == 0.0f;
      }
      mask[p] = (uint8_t)zero;
    }
  }
  mrgi_metrics m;
  if (mrgi_metrics_compare(&image, &reference, mask, peak, &m, &err) != MRGI_OK)
  {
    code = fail(err.message);
    goto done;
  }
  printf("relative_rms=%.6f rms=%.6g max=%.6g psnr_db=%.3f ssim=%.5f pixels=%lld channels=%d\n",
    m.relative_rms, m.rms, m.max_abs_error, m.psnr_db, m.ssim, (long long)m.compared_pixels,
    (int)reference.channels);
  if (diff_path)
  {
    if (mrgi_metrics_difference_image(&image, &reference, mask, &diff, &err) != MRGI_OK)
    {
      code = fail(err.message);
      goto done;
    }
    for (size_t i = 0; i < mrgi_image_value_count(&diff); ++i)
    {
      diff.pixels[i] *= (float)diff_scale;
    }
    const mrgi_status status = mrgi_image_file_has_extension(diff_path, ".exr")
      ? mrgi_exr_write(diff_path, &diff, NULL, MRGI_EXR_FLOAT, &err)
      : mrgi_png_write_image(diff_path, &diff, 0, 1.0f, &err);
    if (status != MRGI_OK)
    {
      code = fail(err.message);
    }
  }
done:
  free(mask);
  mrgi_image_destroy(&image);
  mrgi_image_destroy(&reference);
  mrgi_image_destroy(&diff);
  return code;
}
