/* Temporal blend of the BRSM pdf; contract in mrgi_brsm_temporal.h. */
#include "mrgi_brsm_temporal.h"

#include <math.h>
#include <string.h>

static mrgi_status mrgi_brsm_temporal_check(const float* values, size_t count, const char* what,
                                            mrgi_error* err)
{
  for (size_t t = 0; t < count; ++t)
  {
    if (!(values[t] >= 0.0f) || !isfinite(values[t]))
    {
      return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                            "BRSM temporal blend: %s of texel %zu is negative or not finite", what, t);
    }
  }
  return MRGI_OK;
}

mrgi_status mrgi_brsm_temporal_blend(double weight, float* pdf, float* history, size_t count,
                                     int32_t has_history, mrgi_error* err)
{
  if (!pdf || !history || count == 0)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "BRSM temporal blend: %s", count == 0 ? "no texels" : "NULL array");
  }
  if (pdf == history)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "BRSM temporal blend: the pdf and the history are the same array");
  }
  if (!(weight >= MRGI_BRSM_MIN_TEMPORAL_WEIGHT && weight <= 1.0))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "BRSM temporal weight %g is outside %g..1", weight,
                          MRGI_BRSM_MIN_TEMPORAL_WEIGHT);
  }
  mrgi_status status = mrgi_brsm_temporal_check(pdf, count, "pdf", err);
  if (status == MRGI_OK && has_history)
  {
    status = mrgi_brsm_temporal_check(history, count, "history", err);
  }
  if (status != MRGI_OK)
  {
    return status;
  }
  if (has_history && weight < 1.0)
  {
    double sum = 0.0;
    for (size_t t = 0; t < count; ++t)
    {
      const double b = pdf[t] > 0.0f ? weight * pdf[t] + (1.0 - weight) * history[t] : 0.0;
      sum += b;
    }
    /* sum >= weight * sum(p) > 0 unless every p_t is 0 (left as it is). */
    if (sum > 0.0)
    {
      const double scale = 1.0 / sum;
      for (size_t t = 0; t < count; ++t)
      {
        const double b = pdf[t] > 0.0f ? weight * pdf[t] + (1.0 - weight) * history[t] : 0.0;
        pdf[t] = (float)(b * scale);
      }
    }
  }
  memcpy(history, pdf, count * sizeof(float));
  return MRGI_OK;
}
