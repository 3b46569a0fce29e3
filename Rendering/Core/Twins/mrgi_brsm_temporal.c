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

double mrgi_brsm_temporal_overlap(const float* pdf, const float* history, size_t count)
{
  if (!pdf || !history)
  {
    return 0.0;
  }
  double sp = 0.0, sh = 0.0;
  for (size_t t = 0; t < count; ++t)
  {
    sp += pdf[t] > 0.0f ? pdf[t] : 0.0f;
    sh += history[t] > 0.0f ? history[t] : 0.0f;
  }
  if (!(sp > 0.0 && sh > 0.0) || !isfinite(sp) || !isfinite(sh))
  {
    return 0.0;
  }
  double overlap = 0.0;
  for (size_t t = 0; t < count; ++t)
  {
    const double p = pdf[t] > 0.0f ? pdf[t] / sp : 0.0;
    const double h = history[t] > 0.0f ? history[t] / sh : 0.0;
    overlap += p < h ? p : h;
  }
  return overlap;
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
  if (has_history && weight < 1.0 && mrgi_brsm_temporal_overlap(pdf, history, count) >=
                                          MRGI_BRSM_HISTORY_MIN_OVERLAP)
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
