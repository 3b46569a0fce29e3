/**
 * @file mrgi_finite.h
 * @brief The twins' one finite check of float arrays (kernels, matrices,
 *        G-buffer texels): header-only, inline, because SSAO and SSGI call
 *        it per sample.
 */
#ifndef MRGI_FINITE_H
#define MRGI_FINITE_H

#include <math.h>
#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/** @brief 1 when all `n` floats of `v` are finite (neither NaN nor +-infinity), else 0; n 0: 1. */
static inline int mrgi_floats_finite(const float* v, size_t n)
{
  for (size_t i = 0; i < n; ++i)
  {
    if (!isfinite(v[i]))
    {
      return 0;
    }
  }
  return 1;
}

#ifdef __cplusplus
}
#endif

#endif
