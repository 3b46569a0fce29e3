/*
 * mrgi-compare: compare an image with a reference (EXR or PNG) with MRGI's
 * metrics: relative RMS error, RMS, max error, PSNR and SSIM, over the pixels
 * where the reference or the image is non-zero (or all pixels with --all),
 * and optionally write the difference image.
 *
 *   mrgi-compare IMAGE REFERENCE [--all] [--peak P] [--diff OUT.exr|OUT.png] [--diff-scale S]
 *
 * Prints one line: `relative_rms=... rms=... max=... psnr_db=... ssim=... pixels=...`.
 */
#include "mrgi_error.h"
#include "mrgi_exr.h"
#include "mrgi_image.h"
#include "mrgi_metrics.h"
#include "mrgi_parse.h"
#include "mrgi_png.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

static int ends_with(const char* s, const char* ext)
{
  const size_t n = strlen(s), e = strlen(ext);
  return n > e && strcasecmp(s + n - e, ext) == 0;
}

static mrgi_status read_image(const char* path, mrgi_image* out, mrgi_error* err)
{
  if (ends_with(path, ".exr"))
  {
    return mrgi_exr_read(path, out, err);
  }
  if (ends_with(path, ".png"))
  {
    return mrgi_png_read(path, out, err);
  }
  return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "'%s': the file name must end in .exr or .png", path);
}

static int fail(const char* message)
{
  fprintf(stderr, "mrgi-compare: error: %s\n", message);
  return 2;
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
    if (strcmp(argv[i], "--all") == 0)
      all = 1;
    else if ((strcmp(argv[i], "--peak") == 0 || strcmp(argv[i], "--diff-scale") == 0) && i + 1 < argc)
    {
      double* target = strcmp(argv[i], "--peak") == 0 ? &peak : &diff_scale;
      if (mrgi_parse_double(argv[++i], target, &err) != MRGI_OK || *target <= 0)
        return fail("--peak and --diff-scale need a number > 0");
    }
    else if (strcmp(argv[i], "--diff") == 0 && i + 1 < argc)
      diff_path = argv[++i];
    else if (argv[i][0] == '-')
    {
      fprintf(stderr, "mrgi-compare: error: unknown option '%s'\n", argv[i]);
      return 2;
    }
    else if (count < 2)
      paths[count++] = argv[i];
    else
      return fail("more than two images given");
  }
  if (count != 2)
  {
    fprintf(stderr, "usage: mrgi-compare IMAGE REFERENCE [--all] [--peak P] [--diff OUT] [--diff-scale S]\n");
    return 2;
  }
  mrgi_image image = { 0 }, reference = { 0 }, diff = { 0 };
  int code = 0;
  uint8_t* mask = NULL;
  if (read_image(paths[0], &image, &err) != MRGI_OK || read_image(paths[1], &reference, &err) != MRGI_OK)
  {
    code = fail(err.message);
    goto done;
  }
  if (!all)
  {
    /* Ignore pixels where both images are black (background, unlit). */
    const int64_t n = mrgi_image_pixel_count(&reference);
    mask = (uint8_t*)calloc((size_t)n, 1);
    if (!mask || image.width != reference.width || image.height != reference.height ||
        image.channels != reference.channels)
    {
      code = fail(mask ? "the images differ in size or channels" : "out of memory");
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
  printf("relative_rms=%.6f rms=%.6g max=%.6g psnr_db=%.3f ssim=%.5f pixels=%lld\n", m.relative_rms,
    m.rms, m.max_abs_error, m.psnr_db, m.ssim, (long long)m.compared_pixels);
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
    const mrgi_status status = ends_with(diff_path, ".exr")
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
