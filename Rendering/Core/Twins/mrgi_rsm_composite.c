#include "mrgi_rsm_composite.h"

#include "mrgi_buffers.h"

#include <math.h>
#include <stdint.h>
#include <string.h>

/* The 12 floats of texel i, in plane order. */
static void gather_record(const float* view, size_t texels, size_t i, float record[12])
{
  for (int plane = 0; plane < MRGI_RSM_ATTACHMENTS; ++plane)
  {
    memcpy(record + 4 * plane, view + ((size_t)plane * texels + i) * 4, 4 * sizeof(float));
  }
}

static void scatter_record(float* view, size_t texels, size_t i, const float record[12])
{
  for (int plane = 0; plane < MRGI_RSM_ATTACHMENTS; ++plane)
  {
    memcpy(view + ((size_t)plane * texels + i) * 4, record + 4 * plane, 4 * sizeof(float));
  }
}

static int record_valid(const float record[12])
{
  /* NaN fails the comparison: a NaN w is empty too. */
  if (!(record[4 * MRGI_RSM_POSITION + 3] > MRGI_GBUFFER_VALID_THRESHOLD))
  {
    return 0;
  }
  for (int k = 0; k < MRGI_RSM_COMPOSITE_RECORD_FLOATS; ++k)
  {
    if (!isfinite(record[k]))
    {
      return 0;
    }
  }
  return 1;
}

static double record_depth(const float record[12], const mrgi_rsm_view_key* key)
{
  if (!record_valid(record))
  {
    return INFINITY;
  }
  const float* p = record + 4 * MRGI_RSM_POSITION;
  const double d[3] = { (double)p[0] - key->origin[0], (double)p[1] - key->origin[1],
    (double)p[2] - key->origin[2] };
  if (key->perspective)
  {
    return sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  }
  const double* v = key->direction;
  return (d[0] * v[0] + d[1] * v[1] + d[2] * v[2]) / sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

/* -1 when a's bits are lexicographically smaller than b's, 0 equal, 1 larger. */
static int compare_bits(const float a[12], const float b[12])
{
  for (int k = 0; k < MRGI_RSM_COMPOSITE_RECORD_FLOATS; ++k)
  {
    uint32_t ua, ub;
    memcpy(&ua, a + k, sizeof ua);
    memcpy(&ub, b + k, sizeof ub);
    if (ua != ub)
    {
      return ua < ub ? -1 : 1;
    }
  }
  return 0;
}

double mrgi_rsm_composite_depth(
  const float* view, size_t texels, size_t i, const mrgi_rsm_view_key* key)
{
  float record[MRGI_RSM_COMPOSITE_RECORD_FLOATS];
  gather_record(view, texels, i, record);
  return record_depth(record, key);
}

mrgi_status mrgi_rsm_composite(
  const float* in, float* inout, size_t texels, const mrgi_rsm_view_key* key, mrgi_error* err)
{
  if (!key)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "RSM composite: no view key");
  }
  if (key->perspective != 0 && key->perspective != 1)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "RSM composite: perspective is %d, must be 0 or 1", (int)key->perspective);
  }
  if (!isfinite(key->origin[0]) || !isfinite(key->origin[1]) || !isfinite(key->origin[2]))
  {
    return mrgi_error_set(
      err, MRGI_ERR_INVALID_ARGUMENT, "RSM composite: the view origin is not finite");
  }
  if (!key->perspective)
  {
    const double* v = key->direction;
    const double n2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
    if (!isfinite(n2) || !(n2 > 0))
    {
      return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
        "RSM composite: an orthographic view needs a finite, non-zero direction");
    }
  }
  if (texels == 0)
  {
    return MRGI_OK;
  }
  if (!in || !inout)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "RSM composite: NULL view");
  }
  if (texels > SIZE_MAX / (sizeof(float) * MRGI_RSM_COMPOSITE_RECORD_FLOATS))
  {
    return mrgi_error_set(
      err, MRGI_ERR_INVALID_ARGUMENT, "RSM composite: %zu texels overflow", texels);
  }

  static const float zero[MRGI_RSM_COMPOSITE_RECORD_FLOATS] = { 0 };
  for (size_t i = 0; i < texels; ++i)
  {
    float a[MRGI_RSM_COMPOSITE_RECORD_FLOATS], b[MRGI_RSM_COMPOSITE_RECORD_FLOATS];
    gather_record(in, texels, i, a);
    gather_record(inout, texels, i, b);
    const double da = record_depth(a, key);
    const double db = record_depth(b, key);
    const float* keep;
    if (da == INFINITY && db == INFINITY)
    {
      keep = zero; /* both empty: the cleared texel, whatever they held */
    }
    else if (da != db)
    {
      keep = da < db ? a : b;
    }
    else
    {
      keep = compare_bits(a, b) <= 0 ? a : b;
    }
    scatter_record(inout, texels, i, keep);
  }
  return MRGI_OK;
}
