#include "mrgi_flicker.h"

#include <math.h>
#include <stddef.h>
#include <stdio.h>

/* The channels both sequences are compared on (see the header), or 0 with
 * the error set. */
static int32_t mrgi_flicker_channels(const mrgi_image* image, const mrgi_image* ref, mrgi_error* err)
{
  if (image->channels >= 3 && ref->channels >= 3)
  {
    return 3;
  }
  if (image->channels != ref->channels)
  {
    mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                   "the images have %d channels but the references %d (only RGB and RGBA mix)",
                   image->channels, ref->channels);
    return 0;
  }
  return image->channels;
}

/* One frame valid, of the first frame's size and channels, finite. */
static mrgi_status mrgi_flicker_check_frame(const mrgi_image* frame, const mrgi_image* first,
                                            const char* sequence, int64_t index, mrgi_error* err)
{
  if (!frame)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "%s frame %lld is NULL", sequence,
                          (long long)index);
  }
  mrgi_status status = mrgi_image_validate(frame, err);
  if (status != MRGI_OK)
  {
    char prefix[96];
    snprintf(prefix, sizeof prefix, "%s frame %lld: ", sequence, (long long)index);
    mrgi_error_prefix(err, prefix);
    return status;
  }
  if (frame->width != first->width || frame->height != first->height ||
      frame->channels != first->channels)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "%s frame %lld is %dx%d with %d channels but the first image is %dx%d "
                          "with %d channels",
                          sequence, (long long)index, frame->width, frame->height,
                          frame->channels, first->width, first->height, first->channels);
  }
  int64_t nonfinite = 0;
  status = mrgi_image_count_nonfinite(frame, &nonfinite, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  if (nonfinite > 0)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "%s frame %lld holds %lld NaN or infinite values", sequence,
                          (long long)index, (long long)nonfinite);
  }
  return MRGI_OK;
}

/* Mean of channel c over the box x0..x0+n-1, y0..y0+n-1 (n = 1: the value). */
static double mrgi_flicker_box_mean(const mrgi_image* img, int32_t x0, int32_t y0, int32_t n,
                                    int32_t c)
{
  double sum = 0.0;
  for (int32_t y = y0; y < y0 + n; ++y)
  {
    for (int32_t x = x0; x < x0 + n; ++x)
    {
      sum += (double)mrgi_image_at(img, x, y)[c];
    }
  }
  return sum / ((double)n * (double)n);
}

mrgi_status mrgi_flicker_compute_pair(const mrgi_image* image0, const mrgi_image* image1,
                                      const mrgi_image* ref0, const mrgi_image* ref1, int32_t box,
                                      mrgi_flicker_pair* out, mrgi_error* err)
{
  if (!image0 || !image1 || !ref0 || !ref1 || !out)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "NULL argument (images, references and the result are required)");
  }
  const mrgi_image* frames[4] = { image0, image1, ref0, ref1 };
  static const char* const names[4] = { "image", "image", "reference", "reference" };
  mrgi_status status = mrgi_flicker_check_frame(image0, image0, "image", 0, err);
  for (int i = 1; i < 4 && status == MRGI_OK; ++i)
  {
    /* References are checked against the first reference, then sizes across. */
    status = mrgi_flicker_check_frame(frames[i], i < 2 ? image0 : ref0, names[i], i % 2, err);
  }
  if (status != MRGI_OK)
  {
    return status;
  }
  if (ref0->width != image0->width || ref0->height != image0->height)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "the images are %dx%d but the references %dx%d", image0->width,
                          image0->height, ref0->width, ref0->height);
  }
  const int32_t channels = mrgi_flicker_channels(image0, ref0, err);
  if (channels == 0)
  {
    return MRGI_ERR_INVALID_ARGUMENT;
  }
  if (box < 1 || box > image0->width || box > image0->height)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "box side %d must be >= 1 and at most the frame's %dx%d", box,
                          image0->width, image0->height);
  }
  const int32_t bx = image0->width / box, by = image0->height / box;
  double change2 = 0.0, ref2 = 0.0;
  for (int32_t y = 0; y < by; ++y)
  {
    for (int32_t x = 0; x < bx; ++x)
    {
      for (int32_t c = 0; c < channels; ++c)
      {
        const double i0 = mrgi_flicker_box_mean(image0, x * box, y * box, box, c);
        const double i1 = mrgi_flicker_box_mean(image1, x * box, y * box, box, c);
        const double r0 = mrgi_flicker_box_mean(ref0, x * box, y * box, box, c);
        const double r1 = mrgi_flicker_box_mean(ref1, x * box, y * box, box, c);
        const double d = (i1 - i0) - (r1 - r0);
        change2 += d * d;
        ref2 += r0 * r0;
      }
    }
  }
  const double values = (double)bx * (double)by * (double)channels;
  mrgi_flicker_pair pair;
  pair.change_rms = sqrt(change2 / values);
  pair.reference_rms = sqrt(ref2 / values);
  pair.excluded = !(pair.reference_rms > 0.0);
  pair.value = pair.excluded ? 0.0 : pair.change_rms / pair.reference_rms;
  *out = pair;
  return MRGI_OK;
}

mrgi_status mrgi_flicker_sequence(const mrgi_image* images, const mrgi_image* references,
                                  int32_t count, int32_t box, mrgi_flicker_pair* pairs,
                                  mrgi_flicker_result* out, mrgi_error* err)
{
  if (!images || !references || !out)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "NULL argument (images, references and the result are required)");
  }
  if (count < 2)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "flicker needs at least 2 frames, got %d", count);
  }
  /* Every frame against the first of its sequence, so that a bad frame is
   * named by its index in the sequence. */
  for (int32_t k = 0; k < count; ++k)
  {
    mrgi_status status = mrgi_flicker_check_frame(&images[k], &images[0], "image", k, err);
    if (status == MRGI_OK)
    {
      status = mrgi_flicker_check_frame(&references[k], &references[0], "reference", k, err);
    }
    if (status != MRGI_OK)
    {
      return status;
    }
  }
  mrgi_flicker_result result = { 0.0, 0.0, 0, 0 };
  double sum = 0.0;
  for (int32_t k = 0; k + 1 < count; ++k)
  {
    mrgi_flicker_pair pair;
    const mrgi_status status = mrgi_flicker_compute_pair(&images[k], &images[k + 1],
                                                         &references[k], &references[k + 1], box,
                                                         &pair, err);
    if (status != MRGI_OK)
    {
      return status;
    }
    if (pairs)
    {
      pairs[k] = pair;
    }
    if (pair.excluded)
    {
      ++result.pairs_excluded;
      continue;
    }
    ++result.pairs_counted;
    sum += pair.value;
    result.max_pair = fmax(result.max_pair, pair.value);
  }
  if (result.pairs_counted == 0)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "every reference frame R_0..R_%d is black (rms 0); flicker is undefined",
                          count - 2);
  }
  result.flicker = sum / result.pairs_counted;
  *out = result;
  return MRGI_OK;
}
