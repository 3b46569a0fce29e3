/* The ground truth's per-pixel stopping statistic; the contract is in
 * mrgi_reference_noise.h. */
#include "mrgi_reference_noise.h"

#include <math.h>

static void noise_swap(double* a, double* b)
{
  const double t = *a;
  *a = *b;
  *b = t;
}

/* Median of values[lo], values[mid], values[hi]: a pivot that keeps sorted
 * and reverse-sorted inputs linear. */
static double noise_median3(const double* v, size_t lo, size_t hi)
{
  const size_t mid = lo + (hi - lo) / 2;
  const double a = v[lo], b = v[mid], c = v[hi];
  if (a < b)
  {
    return b < c ? b : (a < c ? c : a);
  }
  return a < c ? a : (b < c ? c : b);
}

mrgi_status mrgi_reference_quantile(double* values, size_t count, double percentile, double* out,
                                    mrgi_error* err)
{
  if (!values || !out || count == 0 || !(percentile > 0.0 && percentile <= 1.0))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "mrgi_reference_quantile: needs values, count >= 1 and a percentile in "
                          "(0, 1] (got count %zu, percentile %g)",
                          count, percentile);
  }
  double rank = ceil(percentile * (double)count);
  rank = rank < 1.0 ? 1.0 : (rank > (double)count ? (double)count : rank);
  const size_t k = (size_t)rank - 1; /* 0-based index in sorted order */
  /* Quickselect with a three-way partition (Dijkstra): runs of equal values
   * (many exact zeros in dark images) end the search at once. */
  size_t lo = 0, hi = count - 1;
  while (lo < hi)
  {
    const double pivot = noise_median3(values, lo, hi);
    size_t lt = lo, i = lo, gt = hi;
    while (i <= gt)
    {
      if (values[i] < pivot)
      {
        noise_swap(&values[lt++], &values[i++]);
      }
      else if (values[i] > pivot)
      {
        noise_swap(&values[i], &values[gt]);
        if (gt == 0)
        {
          break;
        }
        --gt;
      }
      else
      {
        ++i;
      }
    }
    /* values[lo..lt) < pivot, values[lt..gt] == pivot, values(gt..hi] > pivot */
    if (k < lt)
    {
      hi = lt - 1;
    }
    else if (k > gt)
    {
      lo = gt + 1;
    }
    else
    {
      *out = pivot;
      return MRGI_OK;
    }
  }
  *out = values[k];
  return MRGI_OK;
}

mrgi_status mrgi_reference_pixel_error(const double* mean, const double* m2, const uint8_t* mask,
                                       size_t count, int32_t passes, double percentile,
                                       double* scratch, double* error, mrgi_error* err)
{
  if (!mean || !m2 || !mask || !scratch || !error || count == 0 || passes < 1 ||
      !(percentile > 0.0 && percentile <= 1.0))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "mrgi_reference_pixel_error: needs mean, m2, mask, scratch and error, "
                          "count >= 1, passes >= 1 and a percentile in (0, 1] (got count %zu, "
                          "passes %d, percentile %g)",
                          count, (int)passes, percentile);
  }
  double sum = 0.0;
  size_t counted = 0;
  for (size_t i = 0; i < count; ++i)
  {
    if (mask[i])
    {
      sum += mean[i];
      ++counted;
    }
  }
  if (counted == 0 || !(sum > 0.0))
  {
    *error = 0.0;
    return MRGI_OK;
  }
  if (passes < 2)
  {
    *error = INFINITY;
    return MRGI_OK;
  }
  const double floor_value = MRGI_REFERENCE_NOISE_FLOOR * sum / (double)counted;
  const double to_variance = 1.0 / ((double)(passes - 1) * (double)passes);
  size_t m = 0;
  for (size_t i = 0; i < count; ++i)
  {
    if (!mask[i])
    {
      continue;
    }
    const double variance = m2[i] * to_variance;
    const double level = mean[i] > floor_value ? mean[i] : floor_value;
    scratch[m++] = sqrt(variance > 0.0 ? variance : 0.0) / level;
  }
  return mrgi_reference_quantile(scratch, m, percentile, error, err);
}
