/*
 * area_bounce_error: the area lights' one bounce of the GPU against the
 * ground truth (Documentation/IndirectLight.md, "Area lights bounce").
 *
 *   area_bounce_error ON.exr OFF.exr TRUTH.exr [PREFIX EV]
 *
 * ON and OFF: `mrgi-render SCENE` with --gi on and off (EXR: HDR radiance);
 * their difference is the GPU's indirect part. TRUTH: `mrgi-render SCENE
 * --reference --indirect-only` (the truth's one bounce, which includes the
 * area lights', mrgi_reference.h). Prints the mean indirect of both, and
 * the relative RMS, sqrt(sum (g - t)^2 / sum t^2) over all pixels and RGB,
 * per pixel and after 4 x 4 box averaging (mrgi_box_downsample). With
 * PREFIX, writes PREFIX-gpu.png, PREFIX-truth.png (both scaled by 2^EV)
 * and PREFIX-diff.png (|g - t| scaled by 4 * 2^EV). Sizes must be
 * multiples of 4. Run by Testing/Benchmarks/area_bounce.sh.
 */
#include "mrgi_box_filter.h"
#include "mrgi_exr.h"
#include "mrgi_image.h"
#include "mrgi_png.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

static double relative_rms(const mrgi_image* test, const mrgi_image* truth)
{
  double num = 0.0, den = 0.0;
  for (int64_t i = 0; i < test->width * test->height; ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      const double g = test->pixels[i * test->channels + c];
      const double t = truth->pixels[i * truth->channels + c];
      num += (g - t) * (g - t);
      den += t * t;
    }
  }
  return den > 0.0 ? sqrt(num / den) : INFINITY;
}

static int fail(const mrgi_error* err)
{
  fprintf(stderr, "area_bounce_error: %s\n", err->message);
  return 1;
}

int main(int argc, char** argv)
{
  if (argc != 4 && argc != 6)
  {
    fprintf(stderr, "usage: area_bounce_error ON.exr OFF.exr TRUTH.exr [PREFIX EV]\n");
    return 2;
  }
  mrgi_image on, off, truth, diff, box_gpu, box_truth;
  mrgi_error err;
  if (mrgi_exr_read(argv[1], &on, &err) || mrgi_exr_read(argv[2], &off, &err) ||
      mrgi_exr_read(argv[3], &truth, &err))
  {
    return fail(&err);
  }
  if (on.width != off.width || on.height != off.height || on.width != truth.width ||
      on.height != truth.height || on.channels < 3 || off.channels != on.channels ||
      truth.channels < 3)
  {
    fprintf(stderr, "area_bounce_error: the three images differ in size or have < 3 channels\n");
    return 1;
  }
  double sum_gpu = 0.0, sum_truth = 0.0;
  for (int64_t i = 0; i < on.width * on.height; ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      on.pixels[i * on.channels + c] -= off.pixels[i * off.channels + c];
    }
    for (int c = 0; c < 3; ++c)
    {
      sum_gpu += on.pixels[i * on.channels + c];
      sum_truth += truth.pixels[i * truth.channels + c];
    }
  }
  const double n = 3.0 * (double)(on.width * on.height);
  printf("mean indirect: GPU %.6g, truth %.6g (ratio %.4f)\n", sum_gpu / n, sum_truth / n,
         sum_gpu / sum_truth);
  printf("relative RMS per pixel: %.4f\n", relative_rms(&on, &truth));
  if (mrgi_box_downsample(&on, 4, &box_gpu, &err) ||
      mrgi_box_downsample(&truth, 4, &box_truth, &err))
  {
    return fail(&err);
  }
  printf("relative RMS on 4x4 boxes: %.4f\n", relative_rms(&box_gpu, &box_truth));
  if (argc == 6)
  {
    const float scale = exp2f((float)atof(argv[5]));
    char path[4096];
    if (mrgi_image_copy(&diff, &on, &err))
    {
      return fail(&err);
    }
    for (int64_t i = 0; i < on.width * on.height; ++i)
    {
      for (int c = 0; c < 3; ++c)
      {
        diff.pixels[i * diff.channels + c] =
          fabsf(on.pixels[i * on.channels + c] - truth.pixels[i * truth.channels + c]);
      }
    }
    snprintf(path, sizeof(path), "%s-gpu.png", argv[4]);
    if (mrgi_png_write_image(path, &on, 1, scale, &err))
      return fail(&err);
    snprintf(path, sizeof(path), "%s-truth.png", argv[4]);
    if (mrgi_png_write_image(path, &truth, 1, scale, &err))
      return fail(&err);
    snprintf(path, sizeof(path), "%s-diff.png", argv[4]);
    if (mrgi_png_write_image(path, &diff, 1, 4.0f * scale, &err))
      return fail(&err);
    mrgi_image_destroy(&diff);
  }
  mrgi_image_destroy(&on);
  mrgi_image_destroy(&off);
  mrgi_image_destroy(&truth);
  mrgi_image_destroy(&box_gpu);
  mrgi_image_destroy(&box_truth);
  return 0;
}
