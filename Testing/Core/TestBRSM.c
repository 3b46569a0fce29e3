/* Tests of the BRSM stages (RIHKS11 4, 4.1, 4.2, 6.5): importance (exact and
 * guided estimates), flux mix, geometry-aware blur, 2-D CDF inversion on
 * hand cases, an unbiasedness test of the VPL estimator that a sampler
 * forgetting 1/p fails, inter-texel VPLs that never cross a depth step, and
 * the float twin of the GPU inversion against the double one, and the
 * temporal blend of the pdf (exact rule, unbiased with a stale history that
 * a blend keeping zero-weight lit texels fails). */
#include "mrgi_brsm_blur.h"
#include "mrgi_brsm_cdf_float.h"
#include "mrgi_brsm_importance.h"
#include "mrgi_brsm_sample.h"
#include "mrgi_brsm_temporal.h"
#include "mrgi_gather_term.h"
#include "mrgi_test.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define S_MAX 16
static float g_position[4 * S_MAX * S_MAX], g_normal[4 * S_MAX * S_MAX], g_flux[4 * S_MAX * S_MAX];

static uint32_t rng_state = 777u;
static double rnd(void)
{
  rng_state = rng_state * 1664525u + 1013904223u;
  return (rng_state >> 8) * (1.0 / 16777216.0);
}

/* S x S texels on the unit square facing +z; right half at z = step (a depth
 * step when step != 0); random flux (some zero); area = texel area. */
static mrgi_rsm make_rsm(int32_t S, double step)
{
  const double h = 1.0 / S;
  for (int32_t y = 0; y < S; ++y)
  {
    for (int32_t x = 0; x < S; ++x)
    {
      const int32_t t = y * S + x;
      g_position[4 * t] = (float)((x + 0.5) * h);
      g_position[4 * t + 1] = (float)((y + 0.5) * h);
      g_position[4 * t + 2] = (float)(x >= S / 2 ? step : 0.0);
      g_position[4 * t + 3] = 1.0f;
      g_normal[4 * t] = 0.0f;
      g_normal[4 * t + 1] = 0.0f;
      g_normal[4 * t + 2] = 1.0f;
      g_normal[4 * t + 3] = 0.0f;
      const double f = rnd() < 0.2 ? 0.0 : rnd();
      g_flux[4 * t] = (float)f;
      g_flux[4 * t + 1] = (float)(f * rnd()); /* colour varies per texel */
      g_flux[4 * t + 2] = (float)(f * rnd());
      g_flux[4 * t + 3] = (float)(h * h);
    }
  }
  const mrgi_rsm rsm = { S, 1, g_position, g_normal, g_flux };
  return rsm;
}

/* Column CDFs and the column-sum CDF, inverted on a 2 x 2 hand case. */
static void test_cdf_hand(void)
{
  const mrgi_rsm rsm = make_rsm(2, 0.0);
  const float w[4] = { 1.0f, 3.0f, 0.0f, 4.0f }; /* (0,0)=1 (1,0)=3 (0,1)=0 (1,1)=4 */
  double cdf[6], total = 0.0;
  MRGI_CHECK(mrgi_brsm_cdf_count(&rsm) == 6);
  MRGI_CHECK(mrgi_brsm_cdf_build(&rsm, w, 4, cdf, 6, &total, NULL) == MRGI_OK);
  MRGI_CHECK(total == 8.0);
  MRGI_CHECK(cdf[0] == 1.0 && cdf[1] == 1.0 && cdf[2] == 3.0 && cdf[3] == 7.0);
  MRGI_CHECK(cdf[4] == 1.0 && cdf[5] == 8.0);
  mrgi_brsm_pick p;
  MRGI_CHECK(mrgi_brsm_cdf_invert(&rsm, cdf, 0.0625, 0.5, &p));
  MRGI_CHECK(p.view == 0 && p.x == 0 && p.y == 0 && p.fx == 0.5f && p.fy == 0.5f);
  MRGI_CHECK(p.pdf == 0.125f);
  MRGI_CHECK(mrgi_brsm_cdf_invert(&rsm, cdf, 0.5, 0.5, &p));
  MRGI_CHECK(p.x == 1 && p.y == 1 && p.fx == (float)(3.0 / 7.0) && p.fy == 0.125f);
  MRGI_CHECK(p.pdf == 0.5f);
  MRGI_CHECK(mrgi_brsm_cdf_invert(&rsm, cdf, 0.125, 0.999, &p)); /* boundary: next column */
  MRGI_CHECK(p.x == 1 && p.y == 1 && p.fx == 0.0f);
  /* The zero-weight texel (0, 1) is never picked, whatever u. */
  for (int i = 0; i < 1000; ++i)
  {
    MRGI_CHECK(mrgi_brsm_cdf_invert(&rsm, cdf, rnd(), rnd(), &p));
    MRGI_CHECK(!(p.x == 0 && p.y == 1));
  }
  const float zero[4] = { 0, 0, 0, 0 };
  MRGI_CHECK(mrgi_brsm_cdf_build(&rsm, zero, 4, cdf, 6, &total, NULL) == MRGI_OK);
  MRGI_CHECK(!mrgi_brsm_cdf_invert(&rsm, cdf, 0.3, 0.3, &p));
}

/* Mean and standard error over seeds of sum_k Phi_k.r. `broken` 1 forgets
 * 1/p (Phi_k = Phi_t / N); 2 divides by the wrong pdf (flux importance's
 * lum(Phi_t) / sum lum(Phi) while sampling the mixed pdf). Bugs the test must catch. */
static void estimate(const mrgi_rsm* rsm, const double* cdf, int32_t N, int inter_texel,
                     int broken, int runs, double* mean, double* stderr_out)
{
  mrgi_vpl vpls[64];
  mrgi_brsm_pick picks[64];
  double sum = 0.0, sum2 = 0.0;
  for (int s = 0; s < runs; ++s)
  {
    const mrgi_brsm_sampling sampling = { N, (uint64_t)s * 7919u + 1u, inter_texel, NULL };
    MRGI_CHECK(mrgi_brsm_sample_vpls(rsm, cdf, mrgi_brsm_cdf_count(rsm), &sampling, picks, vpls,
                                     64, NULL, NULL) == MRGI_OK);
    double e = 0.0;
    for (int32_t k = 0; k < N; ++k)
    {
      const int32_t t = picks[k].y * rsm->size + picks[k].x;
      if (broken == 1)
      {
        e += rsm->flux[4 * t] / (double)N;
      }
      else if (broken == 2)
      {
        double total_lum = 0.0;
        for (int32_t i = 0; i < rsm->size * rsm->size; ++i)
        {
          total_lum += 0.2126 * rsm->flux[4 * i] + 0.7152 * rsm->flux[4 * i + 1] +
                       0.0722 * rsm->flux[4 * i + 2];
        }
        const double lum = 0.2126 * rsm->flux[4 * t] + 0.7152 * rsm->flux[4 * t + 1] +
                           0.0722 * rsm->flux[4 * t + 2];
        e += rsm->flux[4 * t] * total_lum / ((double)N * lum);
      }
      else
      {
        e += vpls[k].flux[0];
      }
    }
    sum += e;
    sum2 += e * e;
  }
  *mean = sum / runs;
  const double var = sum2 / runs - *mean * *mean;
  *stderr_out = sqrt((var > 0.0 ? var : 0.0) / runs);
}

static int close_to(double mean, double se, double truth)
{
  return fabs(mean - truth) <= 4.0 * se + 1e-6 * truth;
}

/* E[sum Phi_k] = sum Phi_t for texels with p > 0; a sampler without 1/p fails. */
static void test_unbiased(void)
{
  const int32_t S = 8;
  const mrgi_rsm rsm = make_rsm(S, 0.0);
  float w[S_MAX * S_MAX];
  double truth = 0.0;
  for (int32_t t = 0; t < S * S; ++t)
  {
    w[t] = rnd() < 0.3 ? 0.0f : (float)rnd(); /* a view importance unrelated to flux */
    truth += g_flux[4 * t];
  }
  MRGI_CHECK(mrgi_brsm_mix(&rsm, MRGI_BRSM_DEFAULT_FLUX_SHARE, w, (size_t)(S * S), NULL) == MRGI_OK);
  for (int32_t t = 0; t < S * S; ++t)
  {
    MRGI_CHECK((w[t] > 0.0f) == (g_flux[4 * t] > 0.0f)); /* p > 0 exactly where flux > 0 */
  }
  double cdf[S_MAX * S_MAX + S_MAX];
  MRGI_CHECK(mrgi_brsm_cdf_build(&rsm, w, (size_t)(S * S), cdf, sizeof cdf / sizeof cdf[0], NULL,
                                 NULL) == MRGI_OK);
  const int32_t counts[3] = { 1, 7, 16 };
  for (int i = 0; i < 3; ++i)
  {
    double mean, se;
    estimate(&rsm, cdf, counts[i], 0, 0, 4000, &mean, &se);
    printf("N=%d: mean %.6f +- %.6f, truth %.6f\n", counts[i], mean, se, truth);
    MRGI_CHECK(close_to(mean, se, truth));
    estimate(&rsm, cdf, counts[i], 0, 1, 4000, &mean, &se);
    printf("N=%d without 1/p: mean %.6f +- %.6f\n", counts[i], mean, se);
    MRGI_CHECK(!close_to(mean, se, truth)); /* the test detects the broken sampler */
    estimate(&rsm, cdf, counts[i], 0, 2, 4000, &mean, &se);
    printf("N=%d with the flux pdf: mean %.6f +- %.6f\n", counts[i], mean, se);
    MRGI_CHECK(!close_to(mean, se, truth));
  }
}

/* A texel with flux but zero view importance is still picked after the mix. */
static void test_zero_view_importance_picked(void)
{
  const int32_t S = 4;
  const mrgi_rsm rsm = make_rsm(S, 0.0);
  g_flux[4 * 5] = 1.0f;
  float w[16], w0[16];
  for (int t = 0; t < 16; ++t)
  {
    w[t] = t == 0 ? 1.0f : 0.0f; /* the view only "sees" texel 0 */
    g_flux[4 * t] = g_flux[4 * t] > 0.0f ? g_flux[4 * t] : 0.5f;
    w0[t] = w[t];
  }
  MRGI_CHECK(mrgi_brsm_mix(&rsm, 0.1, w, 16, NULL) == MRGI_OK);
  MRGI_CHECK(mrgi_brsm_mix(&rsm, 0.0, w0, 16, NULL) == MRGI_OK);
  MRGI_CHECK(w[5] > 0.0f && w0[5] == 0.0f);
  double cdf[20], cdf0[20];
  MRGI_CHECK(mrgi_brsm_cdf_build(&rsm, w, 16, cdf, 20, NULL, NULL) == MRGI_OK);
  MRGI_CHECK(mrgi_brsm_cdf_build(&rsm, w0, 16, cdf0, 20, NULL, NULL) == MRGI_OK);
  int hits = 0, hits0 = 0;
  mrgi_vpl vpls[8];
  mrgi_brsm_pick picks[8];
  for (int s = 0; s < 400; ++s)
  {
    const mrgi_brsm_sampling sampling = { 8, (uint64_t)s, 0, NULL };
    MRGI_CHECK(mrgi_brsm_sample_vpls(&rsm, cdf, 20, &sampling, picks, vpls, 8, NULL, NULL) == MRGI_OK);
    for (int k = 0; k < 8; ++k)
    {
      hits += picks[k].y * S + picks[k].x == 5;
    }
    MRGI_CHECK(mrgi_brsm_sample_vpls(&rsm, cdf0, 20, &sampling, picks, vpls, 8, NULL, NULL) == MRGI_OK);
    for (int k = 0; k < 8; ++k)
    {
      hits0 += picks[k].y * S + picks[k].x == 5;
    }
  }
  printf("texel with flux, no view importance: picked %d times (beta 0.1), %d (beta 0)\n", hits,
         hits0);
  MRGI_CHECK(hits > 0 && hits0 == 0);
}

/* Blur keeps importance >= 0 and finite, never mixes across a depth step. */
static void test_blur(void)
{
  const int32_t S = 16; /* radius 1 */
  const mrgi_rsm rsm = make_rsm(S, 1.0);
  float in[S_MAX * S_MAX], out[S_MAX * S_MAX];
  for (int32_t t = 0; t < S * S; ++t)
  {
    in[t] = (t % S) < S / 2 ? (float)(rnd() < 0.1 ? 3e38 : rnd()) : 0.0f;
  }
  g_position[4 * 17 + 3] = 0.0f; /* an invalid texel */
  MRGI_CHECK(mrgi_brsm_blur_radius(S) == 1 && mrgi_brsm_blur_radius(256) == 3);
  MRGI_CHECK(mrgi_brsm_blur(&rsm, in, out, (size_t)(S * S), NULL) == MRGI_OK);
  int smoothed = 0;
  for (int32_t t = 0; t < S * S; ++t)
  {
    MRGI_CHECK(out[t] >= 0.0f && isfinite(out[t]));
    if ((t % S) >= S / 2)
    {
      MRGI_CHECK(out[t] == 0.0f); /* the far plane got nothing from the near one */
    }
    smoothed += out[t] != in[t];
  }
  MRGI_CHECK(out[17] == 0.0f && smoothed > 0);
  in[3] = -1.0f;
  MRGI_CHECK(mrgi_brsm_blur(&rsm, in, out, (size_t)(S * S), NULL) == MRGI_ERR_INVALID_ARGUMENT);
  in[3] = NAN;
  MRGI_CHECK(mrgi_brsm_blur(&rsm, in, out, (size_t)(S * S), NULL) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_brsm_blur(&rsm, in, in, (size_t)(S * S), NULL) == MRGI_ERR_INVALID_ARGUMENT);
}

/* Luminance of what texel vpl gives view sample s (mrgi_brsm_importance.h's E_tm). */
static double test_contribution(const mrgi_gather_vpl* vpl, const float* s)
{
  if (!(s[11] > MRGI_VALID_THRESHOLD))
  {
    return 0.0;
  }
  const double position[3] = { s[0], s[1], s[2] }, normal[3] = { s[4], s[5], s[6] };
  const double transfer = mrgi_gather_transfer(position, normal, vpl);
  return (MRGI_LUMINANCE_R * s[8] * vpl->flux[0] + MRGI_LUMINANCE_G * s[9] * vpl->flux[1] +
          MRGI_LUMINANCE_B * s[10] * vpl->flux[2]) *
         transfer;
}

/*
 * Importance: the exact RMS contribution without guide (checked against a
 * direct sum of squares); guided and random estimates of its square are
 * unbiased; the RMS, not the mean, ranks a concentrated texel higher.
 */
static void test_importance(void)
{
  const int32_t S = 4, M = 24;
  const mrgi_rsm rsm = make_rsm(S, 0.0);
  float samples[M * MRGI_BRSM_VIEW_SAMPLE_FLOATS];
  for (int m = 0; m < M; ++m)
  {
    float* s = samples + m * MRGI_BRSM_VIEW_SAMPLE_FLOATS;
    s[0] = (float)(2.0 * rnd() - 0.5); /* receivers above the plane, facing down */
    s[1] = (float)(2.0 * rnd() - 0.5);
    s[2] = (float)(0.2 + rnd());
    s[3] = (float)(64.0 * rnd());
    s[4] = 0.0f;
    s[5] = 0.0f;
    s[6] = -1.0f;
    s[7] = (float)(64.0 * rnd());
    s[8] = s[9] = s[10] = 0.8f;
    s[11] = m == 3 ? 0.0f : 1.0f; /* one invalid sample */
  }
  /* Orthographic camera: world xy in [0, 1] -> NDC [-1, 1], viewport 64 x 64. */
  const float world_to_clip[16] = { 2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 1, 0, -1, -1, 0, 1 };
  float exact[16], estimate_sum[16] = { 0 }, one[16];
  mrgi_brsm_view view = { samples, M, NULL, 0, 0, M, 0 };
  MRGI_CHECK(mrgi_brsm_importance(&rsm, &view, 1u, exact, 16, NULL) == MRGI_OK);
  mrgi_gather_vpl vpl;
  for (int t = 0; t < 16; ++t)
  {
    MRGI_CHECK(exact[t] >= 0.0f && isfinite(exact[t]));
    MRGI_CHECK((exact[t] > 0.0f) == (g_flux[4 * t] > 0.0f));
    /* The RMS over the M samples, from the gather's own transfer. */
    const mrgi_vpl record = { { rsm.position[4 * t], rsm.position[4 * t + 1], rsm.position[4 * t + 2] },
                              rsm.flux[4 * t + 3],
                              { rsm.normal[4 * t], rsm.normal[4 * t + 1], rsm.normal[4 * t + 2] },
                              0.0f,
                              { rsm.flux[4 * t], rsm.flux[4 * t + 1], rsm.flux[4 * t + 2] },
                              0.0f };
    if (mrgi_gather_vpl_prepare(&record, NULL, &vpl) != MRGI_GATHER_VPL_USABLE)
    {
      MRGI_CHECK(exact[t] == 0.0f);
      continue;
    }
    double squares = 0.0, mean = 0.0;
    for (int m = 0; m < M; ++m)
    {
      const double e = test_contribution(&vpl, samples + m * MRGI_BRSM_VIEW_SAMPLE_FLOATS);
      squares += e * e / M;
      mean += e / M;
    }
    MRGI_CHECK(fabs(exact[t] - sqrt(squares)) <= 1e-5 * sqrt(squares) + 1e-30);
    MRGI_CHECK(exact[t] >= (float)mean * (1.0f - 1e-5f)); /* RMS >= mean */
  }
  for (int guided = 0; guided < 2; ++guided)
  {
    mrgi_brsm_view v = { samples, M, world_to_clip, 64, 64, 4, guided };
    const int runs = 4000;
    double sum2[16] = { 0 };
    memset(estimate_sum, 0, sizeof estimate_sum);
    for (int s = 0; s < runs; ++s)
    {
      MRGI_CHECK(mrgi_brsm_importance(&rsm, &v, (uint64_t)s + 100u, one, 16, NULL) == MRGI_OK);
      for (int t = 0; t < 16; ++t)
      {
        /* The square is the unbiased part (the root only shapes the pdf). */
        const double square = (double)one[t] * one[t];
        estimate_sum[t] += (float)(square / runs);
        sum2[t] += square * square / runs;
      }
    }
    /* Each texel's mean square over seeds is within 4.5 standard errors of the exact one. */
    double worst = 0.0;
    for (int t = 0; t < 16; ++t)
    {
      const double var = sum2[t] - (double)estimate_sum[t] * estimate_sum[t];
      const double se = sqrt((var > 0.0 ? var : 0.0) / runs) + 1e-12;
      const double z = fabs(estimate_sum[t] - (double)exact[t] * exact[t]) / se;
      worst = z > worst ? z : worst;
    }
    printf("importance K=4 of M=%d, guided=%d: worst |mean - exact| = %.2f standard errors\n", M,
           guided, worst);
    MRGI_CHECK(worst < 4.5);
  }
  view.sample_count = 0;
  MRGI_CHECK(mrgi_brsm_importance(&rsm, &view, 1u, exact, 16, NULL) == MRGI_ERR_INVALID_ARGUMENT);
  view.sample_count = M;
  MRGI_CHECK(mrgi_brsm_importance(&rsm, &view, 1u, exact, 15, NULL) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_brsm_mix(&rsm, 1.5, exact, 16, NULL) == MRGI_ERR_INVALID_ARGUMENT);
}

/*
 * The guided draw's forward walk over block sums (mrgi_brsm_importance.c)
 * against the plain algorithm of the header: the weights c_m, the full
 * prefix of q_m, and a binary search for each stratified target. Sample
 * counts around the block size (1, 3, 31, 32, 33, 100, 1024), K above and
 * below M, samples at the texel's projection and far away, and non-finite
 * pixel coordinates; the estimates must agree to rounding.
 */
static double reference_guided(const mrgi_rsm* rsm, int32_t t, const float* samples, int32_t M,
  int32_t K, const float* world_to_clip, int32_t width, int32_t height, uint64_t seed)
{
  const mrgi_vpl record = { { rsm->position[4 * t], rsm->position[4 * t + 1], rsm->position[4 * t + 2] },
                            rsm->flux[4 * t + 3],
                            { rsm->normal[4 * t], rsm->normal[4 * t + 1], rsm->normal[4 * t + 2] },
                            0.0f,
                            { rsm->flux[4 * t], rsm->flux[4 * t + 1], rsm->flux[4 * t + 2] },
                            0.0f };
  mrgi_gather_vpl vpl;
  if (mrgi_gather_vpl_prepare(&record, NULL, &vpl) != MRGI_GATHER_VPL_USABLE)
  {
    return 0.0;
  }
  double clip[4];
  for (int row = 0; row < 4; ++row)
  {
    clip[row] = (double)world_to_clip[row] * vpl.position[0] + (double)world_to_clip[4 + row] * vpl.position[1] +
                (double)world_to_clip[8 + row] * vpl.position[2] + (double)world_to_clip[12 + row];
  }
  const float cx = (float)((clip[0] / clip[3] * 0.5 + 0.5) * width);
  const float cy = (float)((clip[1] / clip[3] * 0.5 + 0.5) * height);
  const float r2 = (float)(MRGI_BRSM_GUIDE_RADIUS * MRGI_BRSM_GUIDE_RADIUS);
  static double weight[MRGI_BRSM_MAX_VIEW_SAMPLES], cdf[MRGI_BRSM_MAX_VIEW_SAMPLES];
  double total = 0.0;
  for (int32_t m = 0; m < M; ++m)
  {
    const float* s = samples + m * MRGI_BRSM_VIEW_SAMPLE_FLOATS;
    const int finite = isfinite(s[3]) && isfinite(s[7]);
    const float dx = (finite ? s[3] : 1e30f) - cx, dy = (finite ? s[7] : 1e30f) - cy;
    const float x2 = dx * dx + dy * dy;
    const float c = r2 / (x2 > r2 ? x2 : r2);
    weight[m] = c > 1e-30f ? c : 1e-30f;
    total += weight[m];
  }
  const double a = MRGI_BRSM_GUIDE_UNIFORM_SHARE;
  double running = 0.0;
  for (int32_t m = 0; m < M; ++m)
  {
    running += (1.0 - a) * weight[m] / total + a / M;
    cdf[m] = running;
  }
  const double h = mrgi_brsm_hash01(seed, (uint64_t)t);
  double sum = 0.0;
  for (int32_t k = 0; k < K; ++k)
  {
    const double target = ((double)k + h) / (double)K;
    int32_t low = 0, high = M - 1; /* the first m with cdf[m] > target */
    while (low < high)
    {
      const int32_t middle = low + (high - low) / 2;
      if (cdf[middle] > target)
      {
        high = middle;
      }
      else
      {
        low = middle + 1;
      }
    }
    const double q = (1.0 - a) * weight[low] / total + a / M;
    const double e = test_contribution(&vpl, samples + low * MRGI_BRSM_VIEW_SAMPLE_FLOATS);
    sum += e * e / ((double)M * q);
  }
  return sqrt(sum / K);
}

static void test_guided_walk(void)
{
  enum { S = 8 };
  const mrgi_rsm rsm = make_rsm(S, 0.0);
  static float samples[MRGI_BRSM_MAX_VIEW_SAMPLES * MRGI_BRSM_VIEW_SAMPLE_FLOATS];
  const float world_to_clip[16] = { 2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 1, 0, -1, -1, 0, 1 };
  const int32_t counts[] = { 1, 3, 31, 32, 33, 100, 1024 };
  int compared = 0;
  double worst = 0.0;
  for (size_t c = 0; c < sizeof(counts) / sizeof(counts[0]); ++c)
  {
    const int32_t M = counts[c];
    for (int32_t m = 0; m < M; ++m)
    {
      float* s = samples + m * MRGI_BRSM_VIEW_SAMPLE_FLOATS;
      s[0] = (float)rnd();
      s[1] = (float)rnd();
      s[2] = (float)(0.05 + rnd());
      /* Pixel positions near the texels' projections (64 x 64 viewport) or
       * far off; one in 17 not finite. */
      s[3] = m % 17 == 5 ? NAN : (float)(m % 3 == 0 ? 64.0 * rnd() : 1e6 * rnd());
      s[7] = (float)(64.0 * rnd());
      s[4] = 0.0f;
      s[5] = 0.0f;
      s[6] = -1.0f;
      s[8] = s[9] = s[10] = 0.5f;
      s[11] = 1.0f;
    }
    const int32_t ks[] = { 1, 7, 32, 2 * M + 1 };
    for (size_t k = 0; k < sizeof(ks) / sizeof(ks[0]); ++k)
    {
      const int32_t K = ks[k] < MRGI_BRSM_MAX_VIEW_SAMPLES ? ks[k] : MRGI_BRSM_MAX_VIEW_SAMPLES;
      const mrgi_brsm_view view = { samples, M, world_to_clip, 64, 64, K, 1 };
      float out[S * S];
      MRGI_CHECK(mrgi_brsm_importance(&rsm, &view, 99u + (uint64_t)k, out, S * S, NULL) == MRGI_OK);
      for (int32_t t = 0; t < S * S; ++t)
      {
        const double expected =
          reference_guided(&rsm, t, samples, M, K, world_to_clip, 64, 64, 99u + (uint64_t)k);
        const double d = fabs(out[t] - expected) / (expected > 0.0 ? expected : 1.0);
        worst = d > worst ? d : worst;
        compared++;
      }
    }
  }
  printf("guided walk against a binary search: %d texel estimates, worst relative difference %.2g\n",
         compared, worst);
  MRGI_CHECK(worst < 1e-5);
}

/* Inter-texel VPLs stay on T_0's plane; a one-texel distribution gives that texel. */
static void test_inter_texel(void)
{
  const int32_t S = 8;
  const mrgi_rsm rsm = make_rsm(S, 1.0);
  float w[S_MAX * S_MAX];
  for (int32_t t = 0; t < S * S; ++t)
  {
    g_flux[4 * t] = g_flux[4 * t + 1] = g_flux[4 * t + 2] = 0.5f;
    w[t] = 1.0f;
  }
  double cdf[S_MAX * S_MAX + S_MAX];
  MRGI_CHECK(mrgi_brsm_cdf_build(&rsm, w, (size_t)(S * S), cdf, sizeof cdf / sizeof cdf[0], NULL,
                                 NULL) == MRGI_OK);
  mrgi_vpl vpls[64];
  mrgi_brsm_pick picks[64];
  int moved = 0;
  for (int s = 0; s < 50; ++s)
  {
    const mrgi_brsm_sampling sampling = { 64, (uint64_t)s, 1, NULL };
    MRGI_CHECK(mrgi_brsm_sample_vpls(&rsm, cdf, sizeof cdf / sizeof cdf[0], &sampling, picks, vpls,
                                     64, NULL, NULL) == MRGI_OK);
    for (int k = 0; k < 64; ++k)
    {
      const float plane = picks[k].x >= S / 2 ? 1.0f : 0.0f;
      MRGI_CHECK(vpls[k].position[2] == plane); /* never between the planes */
      const int32_t t = picks[k].y * S + picks[k].x;
      moved += vpls[k].position[0] != g_position[4 * t] || vpls[k].position[1] != g_position[4 * t + 1];
      /* Uniform flux and pdf: Phi_k = Phi_t / (N p) exactly as a texel VPL. */
      MRGI_CHECK(fabsf(vpls[k].flux[0] - 0.5f * (S * S) / 64.0f) < 1e-5f);
    }
  }
  MRGI_CHECK(moved > 0); /* VPLs do slide between texels on one plane */
  for (int32_t t = 0; t < S * S; ++t)
  {
    w[t] = t == 27 ? 1.0f : 0.0f;
  }
  MRGI_CHECK(mrgi_brsm_cdf_build(&rsm, w, (size_t)(S * S), cdf, sizeof cdf / sizeof cdf[0], NULL,
                                 NULL) == MRGI_OK);
  const mrgi_brsm_sampling sampling = { 5, 3u, 1, NULL };
  MRGI_CHECK(mrgi_brsm_sample_vpls(&rsm, cdf, sizeof cdf / sizeof cdf[0], &sampling, picks, vpls,
                                   64, NULL, NULL) == MRGI_OK);
  for (int k = 0; k < 5; ++k)
  {
    MRGI_CHECK(picks[k].y * S + picks[k].x == 27);
    for (int c = 0; c < 3; ++c)
    {
      MRGI_CHECK(vpls[k].position[c] == g_position[4 * 27 + c]);
      MRGI_CHECK(vpls[k].normal[c] == g_normal[4 * 27 + c]);
    }
    MRGI_CHECK(fabsf(vpls[k].flux[0] - 0.5f / 5.0f) < 1e-7f);
    MRGI_CHECK(fabsf(vpls[k].area - g_flux[4 * 27 + 3] / 5.0f) < 1e-9f);
  }
  MRGI_CHECK(mrgi_brsm_sample_vpls(&rsm, cdf, 3, &sampling, picks, vpls, 64, NULL, NULL) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_brsm_sample_vpls(&rsm, cdf, sizeof cdf / sizeof cdf[0], &sampling, picks, vpls,
                                   4, NULL, NULL) == MRGI_ERR_INVALID_ARGUMENT);
}

/* The float twin (mrgi_brsm_cdf_float.h, the GPU's): layout, and the same
 * picks and texel records as the double sampler up to float rounding. */
static void test_float_twin(void)
{
  const int32_t S = 16, N = 200;
  const mrgi_rsm rsm = make_rsm(S, 0.0);
  float w[S_MAX * S_MAX];
  for (int32_t t = 0; t < S * S; ++t)
  {
    w[t] = rnd() < 0.3 ? 0.0f : (float)rnd();
  }
  double cdf[S_MAX * S_MAX + S_MAX];
  float fcdf[S_MAX * (S_MAX + 1)], u[2 * N];
  MRGI_CHECK(mrgi_brsm_cdf_float_count(&rsm) == (size_t)(S * (S + 1)));
  MRGI_CHECK(mrgi_brsm_cdf_build(&rsm, w, (size_t)(S * S), cdf, (size_t)(S * S + S), NULL, NULL) ==
             MRGI_OK);
  MRGI_CHECK(mrgi_brsm_cdf_to_float(&rsm, cdf, (size_t)(S * S + S), fcdf, (size_t)(S * (S + 1)),
                                    NULL) == MRGI_OK);
  for (int32_t i = 0; i < S * S + S; ++i)
  {
    MRGI_CHECK(fcdf[i] == (float)cdf[i]); /* row S = the column sums */
  }
  MRGI_CHECK(mrgi_brsm_sample_values(N, 42u, u, 2 * N, NULL) == MRGI_OK);
  mrgi_brsm_pick picks[N];
  mrgi_vpl vpls[N];
  const mrgi_brsm_sampling sampling = { N, 42u, 0, NULL };
  MRGI_CHECK(mrgi_brsm_sample_vpls(&rsm, cdf, (size_t)(S * S + S), &sampling, picks, vpls, N, NULL,
                                   NULL) == MRGI_OK);
  int same = 0;
  for (int32_t k = 0; k < N; ++k)
  {
    mrgi_brsm_pick p;
    mrgi_vpl v;
    MRGI_CHECK(mrgi_brsm_cdf_float_invert(&rsm, fcdf, u[2 * k], u[2 * k + 1], &p) == 1);
    if (p.x != picks[k].x || p.y != picks[k].y)
    {
      continue; /* a float rounding moved a boundary: counted below */
    }
    ++same;
    MRGI_CHECK(fabsf(p.fx - picks[k].fx) < 1e-4f && fabsf(p.fy - picks[k].fy) < 1e-4f);
    mrgi_brsm_float_vpl(&rsm, &p, N, &v);
    for (int c = 0; c < 3; ++c)
    {
      MRGI_CHECK(v.position[c] == vpls[k].position[c]);
      MRGI_CHECK(fabsf(v.flux[c] - vpls[k].flux[c]) <= 1e-5f * vpls[k].flux[c] + 1e-30f);
    }
    MRGI_CHECK(fabsf(v.area - vpls[k].area) <= 1e-5f * vpls[k].area);
  }
  MRGI_CHECK(same >= N - 2);
  /* W = 0: nothing picked; bad arguments named. */
  float zero[S_MAX * (S_MAX + 1)] = { 0 };
  mrgi_brsm_pick p;
  MRGI_CHECK(mrgi_brsm_cdf_float_invert(&rsm, zero, 0.5f, 0.5f, &p) == 0);
  mrgi_error err;
  MRGI_CHECK(mrgi_brsm_cdf_to_float(&rsm, cdf, (size_t)(S * S + S), fcdf, 3, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "float CDF") != NULL);
  MRGI_CHECK(mrgi_brsm_sample_values(N, 1u, u, 3, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_brsm_sample_values(0, 1u, u, 2 * N, &err) == MRGI_ERR_INVALID_ARGUMENT);
}

/* mrgi_brsm_temporal_blend: the rule on a hand case, the first frame, the
 * errors; then an unbiasedness test with a history that has nothing to do
 * with this frame's flux, which the estimator must survive, and a broken
 * blend (pdf = history alone, a = 0) that leaves lit texels at p = 0 and
 * must fail it. */
static void test_temporal_blend(void)
{
  float pdf[4] = { 0.5f, 0.25f, 0.25f, 0.0f };
  float history[4] = { 0.25f, 0.0f, 0.5f, 0.25f };
  /* Overlap min(.5,.25) + min(.25,0) + min(.25,.5) + 0 = 0.5: kept.
   * b = (0.375, 0.125, 0.375, 0) (texel 3 has p = 0), sum 0.875. */
  MRGI_CHECK(fabs(mrgi_brsm_temporal_overlap(pdf, history, 4) - 0.5) <= 1e-12);
  MRGI_CHECK(mrgi_brsm_temporal_blend(0.5, pdf, history, 4, 1, NULL) == MRGI_OK);
  const float want[4] = { 0.375f / 0.875f, 0.125f / 0.875f, 0.375f / 0.875f, 0.0f };
  for (int t = 0; t < 4; ++t)
  {
    MRGI_CHECK(fabsf(pdf[t] - want[t]) <= 1e-7f && history[t] == pdf[t]);
  }
  /* A stale history (overlap under MRGI_BRSM_HISTORY_MIN_OVERLAP: a cut) is
   * dropped: this frame's pdf as it is. Unnormalised inputs count by share. */
  float cut[4] = { 2.0f, 2.0f, 0.0f, 0.0f }, old_view[4] = { 0.0f, 1.0f, 3.0f, 4.0f };
  MRGI_CHECK(fabs(mrgi_brsm_temporal_overlap(cut, old_view, 4) - 0.125) <= 1e-12);
  MRGI_CHECK(mrgi_brsm_temporal_blend(0.5, cut, old_view, 4, 1, NULL) == MRGI_OK);
  MRGI_CHECK(cut[0] == 2.0f && cut[1] == 2.0f && memcmp(cut, old_view, sizeof cut) == 0);
  MRGI_CHECK(mrgi_brsm_temporal_overlap(cut, NULL, 4) == 0.0);
  const float zero[2] = { 0.0f, 0.0f }, one[2] = { 1.0f, 0.0f };
  MRGI_CHECK(mrgi_brsm_temporal_overlap(zero, one, 2) == 0.0);
  MRGI_CHECK(mrgi_brsm_temporal_overlap(one, one, 2) == 1.0);
  /* First frame, and weight 1: the pdf unchanged, copied to the history. */
  float first[3] = { 0.2f, 0.3f, 0.5f }, h[3] = { 7.0f, -1.0f, NAN };
  MRGI_CHECK(mrgi_brsm_temporal_blend(0.1, first, h, 3, 0, NULL) == MRGI_OK);
  MRGI_CHECK(first[0] == 0.2f && first[1] == 0.3f && first[2] == 0.5f && memcmp(first, h, sizeof h) == 0);
  float same[3] = { 0.6f, 0.4f, 0.0f }, other[3] = { 0.0f, 0.0f, 1.0f };
  MRGI_CHECK(mrgi_brsm_temporal_blend(1.0, same, other, 3, 1, NULL) == MRGI_OK);
  MRGI_CHECK(same[0] == 0.6f && same[1] == 0.4f && other[2] == 0.0f);
  /* Errors name the problem and write nothing. */
  mrgi_error err;
  float keep[2] = { 0.5f, 0.5f }, bad[2] = { 0.5f, -0.1f };
  MRGI_CHECK(mrgi_brsm_temporal_blend(0.0, keep, history, 2, 1, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "weight") != NULL);
  MRGI_CHECK(mrgi_brsm_temporal_blend(NAN, keep, history, 2, 1, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_brsm_temporal_blend(1.5, keep, history, 2, 1, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_brsm_temporal_blend(0.5, keep, keep, 2, 1, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_brsm_temporal_blend(0.5, NULL, history, 2, 1, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_brsm_temporal_blend(0.5, keep, history, 0, 1, &err) == MRGI_ERR_INVALID_ARGUMENT);
  float copy[2] = { 0.25f, 0.75f };
  MRGI_CHECK(mrgi_brsm_temporal_blend(0.5, keep, bad, 2, 1, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "history of texel 1") != NULL);
  MRGI_CHECK(mrgi_brsm_temporal_blend(0.5, bad, copy, 2, 1, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "pdf of texel 1") != NULL);
  MRGI_CHECK(keep[0] == 0.5f && keep[1] == 0.5f && copy[0] == 0.25f && copy[1] == 0.75f);

  /* Unbiased with a stale history: the history piles its mass on the
   * texels this frame's flux ignores (and on texels without flux now). */
  const int32_t S = 8, T = S * S;
  const mrgi_rsm rsm = make_rsm(S, 0.0);
  float w[S_MAX * S_MAX], stale[S_MAX * S_MAX], frozen[S_MAX * S_MAX];
  double truth = 0.0;
  for (int32_t t = 0; t < T; ++t)
  {
    w[t] = (float)rnd();
    truth += g_flux[4 * t];
  }
  MRGI_CHECK(mrgi_brsm_mix(&rsm, MRGI_BRSM_DEFAULT_FLUX_SHARE, w, (size_t)T, NULL) == MRGI_OK);
  memcpy(frozen, w, sizeof(float) * (size_t)T);
  /* Stale but kept: 60% this frame's shape, 40% piled on 13 texels of 64. */
  double mass = 0.0;
  for (int32_t t = 0; t < T; ++t)
  {
    mass += frozen[t];
  }
  for (int32_t t = 0; t < T; ++t)
  {
    stale[t] = (float)(0.6 * frozen[t] / mass + (t % 5 == 0 ? 0.4 / 13.0 : 0.0));
  }
  MRGI_CHECK(mrgi_brsm_temporal_overlap(frozen, stale, (size_t)T) >= MRGI_BRSM_HISTORY_MIN_OVERLAP);
  MRGI_CHECK(mrgi_brsm_temporal_blend(MRGI_BRSM_DEFAULT_TEMPORAL_WEIGHT, w, stale, (size_t)T, 1,
                                      NULL) == MRGI_OK);
  int lit_below_a = 0;
  for (int32_t t = 0; t < T; ++t)
  {
    /* p_t >= a p_t(this frame) / sum b, and sum b <= 1. */
    lit_below_a += frozen[t] > 0.0f && !(w[t] >= (float)MRGI_BRSM_DEFAULT_TEMPORAL_WEIGHT * frozen[t] * 0.999f);
    MRGI_CHECK((w[t] > 0.0f) == (g_flux[4 * t] > 0.0f));
  }
  MRGI_CHECK(lit_below_a == 0);
  double cdf[S_MAX * S_MAX + S_MAX];
  MRGI_CHECK(mrgi_brsm_cdf_build(&rsm, w, (size_t)T, cdf, sizeof cdf / sizeof cdf[0], NULL, NULL) ==
             MRGI_OK);
  double mean, se;
  estimate(&rsm, cdf, 16, 0, 0, 4000, &mean, &se);
  printf("temporal blend, stale history: mean %.6f +- %.6f, truth %.6f\n", mean, se, truth);
  MRGI_CHECK(close_to(mean, se, truth));
  /* Broken: the history alone (weight 0 bypassed), zero on most lit texels. */
  float history_only[S_MAX * S_MAX];
  for (int32_t t = 0; t < T; ++t)
  {
    history_only[t] = g_flux[4 * t] > 0.0f && t % 5 == 0 ? 1.0f : 0.0f;
  }
  MRGI_CHECK(mrgi_brsm_cdf_build(&rsm, history_only, (size_t)T, cdf, sizeof cdf / sizeof cdf[0], NULL,
                                 NULL) == MRGI_OK);
  estimate(&rsm, cdf, 16, 0, 0, 4000, &mean, &se);
  printf("history alone (broken): mean %.6f +- %.6f\n", mean, se);
  MRGI_CHECK(!close_to(mean, se, truth));
}

int main(int argc, char** argv)
{
  static const mrgi_test_case cases[] = { MRGI_TEST_CASE(test_cdf_hand),
                                          MRGI_TEST_CASE(test_unbiased),
                                          MRGI_TEST_CASE(test_zero_view_importance_picked),
                                          MRGI_TEST_CASE(test_blur),
                                          MRGI_TEST_CASE(test_importance),
    MRGI_TEST_CASE(test_guided_walk),
                                          MRGI_TEST_CASE(test_inter_texel),
                                          MRGI_TEST_CASE(test_float_twin),
                                          MRGI_TEST_CASE(test_temporal_blend) };
  return MRGI_TEST_MAIN(argc, argv, cases);
}
