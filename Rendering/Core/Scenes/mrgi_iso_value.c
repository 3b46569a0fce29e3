#include "mrgi_iso_value.h"

#include <math.h>
#include <stddef.h>

mrgi_status mrgi_iso_value_otsu(const double* counts, int bins, double lo, double hi,
  double* threshold, int* otsu, mrgi_error* err)
{
  if (!counts || !threshold)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "mrgi_iso_value_otsu: NULL argument");
  }
  if (bins < 2)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "mrgi_iso_value_otsu: bins must be >= 2");
  }
  if (!isfinite(lo) || !isfinite(hi) || !(lo < hi))
  {
    return mrgi_error_set(
      err, MRGI_ERR_INVALID_ARGUMENT, "mrgi_iso_value_otsu: the range must be finite with lo < hi");
  }
  double total = 0.0, moment = 0.0;
  const double width = (hi - lo) / bins;
  for (int i = 0; i < bins; ++i)
  {
    if (!(counts[i] >= 0.0) || !isfinite(counts[i]))
    {
      return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
        "mrgi_iso_value_otsu: count %d is negative or not finite", i);
    }
    total += counts[i];
    moment += counts[i] * (lo + (i + 0.5) * width);
  }
  if (!(total > 0.0))
  {
    return mrgi_error_set(
      err, MRGI_ERR_INVALID_ARGUMENT, "mrgi_iso_value_otsu: the histogram is empty");
  }
  double best = -1.0;
  int best_t = 0, last_t = 0;
  double below = 0.0, below_moment = 0.0;
  for (int t = 1; t < bins; ++t)
  {
    below += counts[t - 1];
    below_moment += counts[t - 1] * (lo + (t - 0.5) * width);
    const double above = total - below;
    if (!(below > 0.0) || !(above > 0.0))
    {
      continue;
    }
    const double m0 = below_moment / below;
    const double m1 = (moment - below_moment) / above;
    const double between = (below / total) * (above / total) * (m0 - m1) * (m0 - m1);
    if (between > best * (1.0 + 1e-12))
    {
      best = between;
      best_t = t;
      last_t = t;
    }
    else if (between >= best * (1.0 - 1e-12))
    {
      last_t = t; /* a tie: empty bins between the populations */
    }
  }
  if (best_t == 0)
  {
    *threshold = 0.5 * (lo + hi);
    if (otsu)
    {
      *otsu = 0;
    }
    return MRGI_OK;
  }
  *threshold = lo + 0.5 * (best_t + last_t) * width;
  if (otsu)
  {
    *otsu = 1;
  }
  return MRGI_OK;
}
