/* Tests of mrgi_ism_points (RGK08 3, RIHKS11 5.1-5.3): uniform density is
 * constant per unit area (chi-square; a per-triangle sampler fails it),
 * adaptive density is higher near the view, every triangle keeps p > 0, the
 * lazy update changes exactly the frame's P/8 records, points stay on a
 * deformed surface, sampling is deterministic, point clouds subsample
 * adaptively, bad input is refused. */
#include "mrgi_ism_points.h"
#include "mrgi_test.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define MAXV 512
#define MAXT 512
#define MAXP 20000

static float verts[3 * MAXV];
static int32_t tris[3 * MAXT];
static double weights[MAXT];
static double cdf[MAXT + 1];
static mrgi_ism_point pts[MAXP];
static mrgi_ism_point pts2[MAXP];
static float pos[3 * MAXP];
static float nrm[3 * MAXP];

/* A strip [0, length] x [0, 1] (z = 0) cut at the x positions `cuts`
 * (count+1 values), two triangles per cell. Returns the triangle count. */
static int32_t strip(const double* cuts, int32_t cells, int32_t* nv)
{
  for (int32_t i = 0; i <= cells; ++i)
  {
    verts[6 * i + 0] = (float)cuts[i];
    verts[6 * i + 1] = 0.0f;
    verts[6 * i + 2] = 0.0f;
    verts[6 * i + 3] = (float)cuts[i];
    verts[6 * i + 4] = 1.0f;
    verts[6 * i + 5] = 0.0f;
  }
  for (int32_t i = 0; i < cells; ++i)
  {
    const int32_t a = 2 * i, b = 2 * i + 1, c = 2 * i + 2, d = 2 * i + 3;
    const int32_t t[6] = { a, c, b, b, c, d };
    memcpy(tris + 6 * i, t, sizeof(t));
  }
  *nv = 2 * (cells + 1);
  return 2 * cells;
}

/* Cells of very different sizes on [0, 1]: 1, 3, 7 and 15 cells per quarter. */
static int32_t uneven_strip(int32_t* nv)
{
  double cuts[64];
  int32_t n = 0;
  const int32_t per[4] = { 1, 3, 7, 15 };
  cuts[n++] = 0.0;
  for (int32_t q = 0; q < 4; ++q)
    for (int32_t k = 1; k <= per[q]; ++k)
      cuts[n++] = 0.25 * q + 0.25 * k / per[q];
  return strip(cuts, n - 1, nv);
}

static void sample_all(int32_t nt, int32_t total, uint32_t seed)
{
  MRGI_CHECK(mrgi_ism_cdf_build(weights, nt, cdf, NULL) == MRGI_OK);
  MRGI_CHECK(mrgi_ism_sample(cdf, nt, seed, 0, total, 0, total, pts, NULL) == MRGI_OK);
}

/* Chi-square of the points' x over 8 equal-width bins of [0, 1]. */
static double chi2_x_bins(int32_t P)
{
  int32_t bins[8] = { 0 };
  for (int32_t i = 0; i < P; ++i)
  {
    int32_t b = (int32_t)(pos[3 * i] * 8.0f);
    bins[b < 0 ? 0 : (b > 7 ? 7 : b)]++;
  }
  double chi2 = 0.0;
  for (int32_t b = 0; b < 8; ++b)
    chi2 += (bins[b] - P / 8.0) * (bins[b] - P / 8.0) / (P / 8.0);
  return chi2;
}

/* Chi-square over 8 equal-area bins in x; 7 dof, critical value 24.32 at
 * alpha = 1e-3 (false-failure rate <= 0.1% for independent samples; the
 * stratified draw has less variance, so the rate is lower still). */
static void test_uniform_density(void)
{
  int32_t nv;
  const int32_t nt = uneven_strip(&nv);
  const int32_t P = 16000;
  double worst = 0.0;
  for (uint32_t seed = 1; seed <= 3; ++seed)
  {
    MRGI_CHECK(mrgi_ism_triangle_weights(
                 verts, nv, tris, nt, MRGI_ISM_UNIFORM, NULL, 0, 1u, weights, NULL) == MRGI_OK);
    sample_all(nt, P, seed);
    MRGI_CHECK(mrgi_ism_points_evaluate(verts, nv, tris, nt, pts, P, pos, NULL, NULL) == MRGI_OK);
    const double chi2 = chi2_x_bins(P);
    worst = chi2 > worst ? chi2 : worst;
    MRGI_CHECK(chi2 < 24.32);
  }
  printf("uniform: worst chi2 over 3 seeds %.2f (7 dof, critical 24.32)\n", worst);

  /* The statistic can fail: a broken sampler that picks every triangle
   * equally often (per triangle, not per area) on the same uneven strip. */
  for (int32_t t = 0; t < nt; ++t)
  {
    weights[t] = 1.0 / nt;
  }
  sample_all(nt, P, 1u);
  MRGI_CHECK(mrgi_ism_points_evaluate(verts, nv, tris, nt, pts, P, pos, NULL, NULL) == MRGI_OK);
  const double chi2 = chi2_x_bins(P);
  printf("broken (per-triangle) sampler: chi2 %.2f\n", chi2);
  MRGI_CHECK(chi2 > 24.32);
}

/* A 10 x 1 strip, view sample above x = 0: density per area near the view
 * (x < 1) vs far (x > 9); every triangle keeps weight >= SHARE * A / sum A. */
static void test_adaptive_density(void)
{
  double cuts[41];
  for (int32_t i = 0; i <= 40; ++i)
    cuts[i] = 0.25 * i;
  int32_t nv;
  const int32_t nt = strip(cuts, 40, &nv);
  const double views[3 * 8] = { 0.0, 0.5, 0.5 };
  double eight[3 * 8];
  for (int32_t k = 0; k < 8; ++k)
  {
    eight[3 * k] = 0.1 * k;
    eight[3 * k + 1] = 0.5;
    eight[3 * k + 2] = 0.5 + 0.05 * k;
  }
  const int32_t P = 8000;
  for (int m = 0; m < 2; ++m)
  {
    MRGI_CHECK(
      mrgi_ism_triangle_weights(verts, nv, tris, nt, m ? MRGI_ISM_ADAPTIVE_8 : MRGI_ISM_ADAPTIVE_1,
        m ? eight : views, m ? 8 : 1, 1u, weights, NULL) == MRGI_OK);
    double sum = 0.0;
    for (int32_t t = 0; t < nt; ++t)
    {
      MRGI_CHECK(weights[t] >= MRGI_ISM_UNIFORM_SHARE * 0.125 / 10.0 * (1.0 - 1e-9));
      sum += weights[t];
    }
    MRGI_CHECK_NEAR(sum, 1.0, 1e-9);
    sample_all(nt, P, 7u);
    MRGI_CHECK(mrgi_ism_points_evaluate(verts, nv, tris, nt, pts, P, pos, NULL, NULL) == MRGI_OK);
    int32_t near = 0, far = 0;
    for (int32_t i = 0; i < P; ++i)
    {
      near += pos[3 * i] < 1.0f;
      far += pos[3 * i] > 9.0f;
    }
    const double ratio = (double)near / (far > 0 ? far : 1);
    printf("adaptive (%d view samples): near %d far %d points, near/far density %.1f\n", m ? 8 : 1,
      near, far, ratio);
    MRGI_CHECK(far > 0); /* the uniform share keeps p > 0 far away */
    MRGI_CHECK(ratio > 5.0);
  }
}

/* Frame k resamples exactly [floor(jP/8), floor((j+1)P/8)); P = 1001. */
static void test_lazy_update(void)
{
  int32_t nv;
  const int32_t nt = uneven_strip(&nv);
  const int32_t P = 1001;
  MRGI_CHECK(mrgi_ism_triangle_weights(
               verts, nv, tris, nt, MRGI_ISM_UNIFORM, NULL, 0, 1u, weights, NULL) == MRGI_OK);
  sample_all(nt, P, 3u);
  int32_t covered = 0;
  for (int64_t k = 0; k < 16; ++k)
  {
    int32_t b, e;
    mrgi_ism_lazy_range(P, k, &b, &e);
    MRGI_CHECK(e - b == P / 8 || e - b == P / 8 + 1);
    if (k < 8)
      covered += e - b;
    memcpy(pts2, pts, sizeof(mrgi_ism_point) * P);
    MRGI_CHECK(
      mrgi_ism_sample(cdf, nt, 3u, mrgi_ism_lazy_generation(k), P, b, e, pts, NULL) == MRGI_OK);
    int32_t changed = 0, changed_outside = 0;
    for (int32_t i = 0; i < P; ++i)
    {
      const int diff = memcmp(&pts[i], &pts2[i], sizeof(mrgi_ism_point)) != 0;
      changed += diff;
      changed_outside += diff && (i < b || i >= e);
    }
    MRGI_CHECK(changed == e - b);
    MRGI_CHECK(changed_outside == 0);
  }
  MRGI_CHECK(covered == P);
  int32_t b, e;
  mrgi_ism_lazy_range(P, 7, &b, &e);
  MRGI_CHECK(e == P);
}

/* The general lazy cycle (lazy_frames N): frame k resamples exactly
 * [floor(jP/N), floor((j+1)P/N)), each range floor/ceil(P/N) records, N
 * frames cover every record once; N = 1 resamples all every frame; N = 8
 * is mrgi_ism_lazy_range. */
static void test_lazy_update_general(void)
{
  int32_t nv;
  const int32_t nt = uneven_strip(&nv);
  const int32_t P = 1001;
  MRGI_CHECK(mrgi_ism_triangle_weights(
               verts, nv, tris, nt, MRGI_ISM_UNIFORM, NULL, 0, 1u, weights, NULL) == MRGI_OK);
  const int32_t cycles[] = { 1, 3, 7, 8, 13 };
  for (int c = 0; c < 5; ++c)
  {
    const int32_t N = cycles[c];
    sample_all(nt, P, 3u);
    int32_t covered = 0;
    for (int64_t k = 0; k < 2 * N; ++k)
    {
      int32_t b, e;
      mrgi_ism_lazy_range_n(P, k, N, &b, &e);
      MRGI_CHECK(e - b == P / N || e - b == P / N + 1);
      if (k < N)
        covered += e - b;
      if (N == 8)
      {
        int32_t b8, e8;
        mrgi_ism_lazy_range(P, k, &b8, &e8);
        MRGI_CHECK(b8 == b && e8 == e);
        MRGI_CHECK(mrgi_ism_lazy_generation(k) == mrgi_ism_lazy_generation_n(k, 8));
      }
      memcpy(pts2, pts, sizeof(mrgi_ism_point) * P);
      MRGI_CHECK(mrgi_ism_sample(cdf, nt, 3u, mrgi_ism_lazy_generation_n(k, N), P, b, e, pts,
                   NULL) == MRGI_OK);
      int32_t changed = 0, changed_outside = 0;
      for (int32_t i = 0; i < P; ++i)
      {
        const int diff = memcmp(&pts[i], &pts2[i], sizeof(mrgi_ism_point)) != 0;
        changed += diff;
        changed_outside += diff && (i < b || i >= e);
      }
      /* A record may redraw to the same value by chance; with 1001 records
       * over 7 triangles barycentrics make that practically impossible. */
      MRGI_CHECK(changed == e - b);
      MRGI_CHECK(changed_outside == 0);
    }
    MRGI_CHECK(covered == P);
  }
  int32_t b, e;
  mrgi_ism_lazy_range_n(P, 5, 1, &b, &e);
  MRGI_CHECK(b == 0 && e == P);
  MRGI_CHECK(mrgi_ism_lazy_generation_n(5, 1) == 6u);
  mrgi_ism_lazy_range_n(P, 5, 0, &b, &e); /* N < 1 acts as 1 */
  MRGI_CHECK(b == 0 && e == P);
}

/* Move the vertices; every evaluated point satisfies its triangle's plane. */
static void test_points_follow_deformation(void)
{
  int32_t nv;
  const int32_t nt = uneven_strip(&nv);
  const int32_t P = 4000;
  MRGI_CHECK(mrgi_ism_triangle_weights(
               verts, nv, tris, nt, MRGI_ISM_UNIFORM, NULL, 0, 1u, weights, NULL) == MRGI_OK);
  sample_all(nt, P, 11u);
  for (int32_t v = 0; v < nv; ++v)
  {
    verts[3 * v + 2] = 0.3f * sinf(7.0f * verts[3 * v] + 3.0f * verts[3 * v + 1]);
    verts[3 * v + 1] += 0.1f * cosf(5.0f * verts[3 * v]);
  }
  MRGI_CHECK(mrgi_ism_points_evaluate(verts, nv, tris, nt, pts, P, pos, nrm, NULL) == MRGI_OK);
  double worst = 0.0;
  for (int32_t i = 0; i < P; ++i)
  {
    const float* a = verts + 3 * tris[3 * pts[i].index];
    double plane = 0.0, len = 0.0;
    for (int k = 0; k < 3; ++k)
    {
      plane += (double)nrm[3 * i + k] * (pos[3 * i + k] - a[k]);
      len += (double)nrm[3 * i + k] * nrm[3 * i + k];
    }
    MRGI_CHECK_NEAR(len, 1.0, 1e-5);
    worst = fabs(plane) > worst ? fabs(plane) : worst;
  }
  printf("deformed: worst plane distance %.2e\n", worst);
  MRGI_CHECK(worst < 1e-5);
}

/* Same seed -> same records; another seed -> different; clouds adapt. */
static void test_deterministic_and_clouds(void)
{
  int32_t nv;
  const int32_t nt = uneven_strip(&nv);
  MRGI_CHECK(mrgi_ism_triangle_weights(
               verts, nv, tris, nt, MRGI_ISM_UNIFORM, NULL, 0, 1u, weights, NULL) == MRGI_OK);
  sample_all(nt, 500, 5u);
  memcpy(pts2, pts, sizeof(mrgi_ism_point) * 500);
  sample_all(nt, 500, 5u);
  MRGI_CHECK(memcmp(pts, pts2, sizeof(mrgi_ism_point) * 500) == 0);
  sample_all(nt, 500, 6u);
  MRGI_CHECK(memcmp(pts, pts2, sizeof(mrgi_ism_point) * 500) != 0);
  /* A cloud of 400 points on x in [0, 10); view above x = 0. */
  for (int32_t p = 0; p < 400; ++p)
  {
    pos[3 * p] = 0.025f * p;
    pos[3 * p + 1] = 0.0f;
    pos[3 * p + 2] = 0.0f;
  }
  const double view[3] = { 0.0, 0.0, 0.5 };
  MRGI_CHECK(
    mrgi_ism_cloud_weights(pos, 400, MRGI_ISM_ADAPTIVE_1, view, 1, weights, NULL) == MRGI_OK);
  MRGI_CHECK(mrgi_ism_cdf_build(weights, 400, cdf, NULL) == MRGI_OK);
  MRGI_CHECK(mrgi_ism_sample(cdf, 400, 1u, 0, 2000, 0, 2000, pts, NULL) == MRGI_OK);
  int32_t near = 0, far = 0;
  for (int32_t i = 0; i < 2000; ++i)
  {
    MRGI_CHECK(pts[i].index >= 0 && pts[i].index < 400);
    near += pts[i].index < 40;
    far += pts[i].index >= 360;
  }
  printf("cloud: near %d far %d of 2000\n", near, far);
  MRGI_CHECK(near > 5 * far && far > 0);
}

static void test_bad_input(void)
{
  int32_t nv;
  int32_t nt = uneven_strip(&nv);
  mrgi_error err;
  const double view[3] = { 0, 0, 1 };
  MRGI_CHECK(mrgi_ism_triangle_weights(verts, nv, tris, 0, MRGI_ISM_UNIFORM, NULL, 0, 1u, weights,
               &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "empty mesh") != NULL);
  MRGI_CHECK(mrgi_ism_triangle_weights(verts, nv, tris, nt, MRGI_ISM_ADAPTIVE_1, view, 0, 1u,
               weights, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "view samples") != NULL);
  MRGI_CHECK(mrgi_ism_triangle_weights(verts, nv, tris, nt, (mrgi_ism_mode)7, view, 1, 1u, weights,
               &err) == MRGI_ERR_INVALID_ARGUMENT);
  verts[4] = NAN;
  MRGI_CHECK(mrgi_ism_triangle_weights(verts, nv, tris, nt, MRGI_ISM_UNIFORM, NULL, 0, 1u, weights,
               &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "non-finite") != NULL);
  nt = uneven_strip(&nv);
  tris[5] = nv;
  MRGI_CHECK(mrgi_ism_triangle_weights(verts, nv, tris, nt, MRGI_ISM_UNIFORM, NULL, 0, 1u, weights,
               &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "outside") != NULL);
  /* Only zero-area triangles: an error; one among good ones: weight 0, never drawn. */
  nt = uneven_strip(&nv);
  const int32_t flat[3] = { 0, 0, 1 };
  MRGI_CHECK(mrgi_ism_triangle_weights(verts, nv, flat, 1, MRGI_ISM_UNIFORM, NULL, 0, 1u, weights,
               &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "total area") != NULL);
  memcpy(tris + 3 * nt, flat, sizeof(flat));
  MRGI_CHECK(mrgi_ism_triangle_weights(verts, nv, tris, nt + 1, MRGI_ISM_ADAPTIVE_1, view, 1, 1u,
               weights, &err) == MRGI_OK);
  MRGI_CHECK(weights[nt] == 0.0);
  sample_all(nt + 1, 3000, 2u);
  for (int32_t i = 0; i < 3000; ++i)
    MRGI_CHECK(pts[i].index != nt);
  MRGI_CHECK(mrgi_ism_sample(cdf, nt, 1u, 0, 0, 0, 0, pts, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "P = 0") != NULL);
  MRGI_CHECK(
    mrgi_ism_sample(cdf, nt, 1u, 0, 1 << 30, 0, 1, pts, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_ism_sample(cdf, nt, 1u, 0, 10, 5, 11, pts, &err) == MRGI_ERR_INVALID_ARGUMENT);
  weights[0] = -1.0;
  MRGI_CHECK(mrgi_ism_cdf_build(weights, nt, cdf, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_ism_cloud_weights(pos, 0, MRGI_ISM_UNIFORM, NULL, 0, weights, &err) ==
    MRGI_ERR_INVALID_ARGUMENT);
  pts[0].index = nt + 5;
  MRGI_CHECK(mrgi_ism_points_evaluate(verts, nv, tris, nt, pts, 1, pos, NULL, &err) ==
    MRGI_ERR_INVALID_ARGUMENT);
  int32_t b = -1, e = -1;
  mrgi_ism_lazy_range(0, 3, &b, &e);
  MRGI_CHECK(b == 0 && e == 0);
}

int main(int argc, char** argv)
{
  static const mrgi_test_case cases[] = {
    MRGI_TEST_CASE(test_uniform_density),
    MRGI_TEST_CASE(test_adaptive_density),
    MRGI_TEST_CASE(test_lazy_update),
    MRGI_TEST_CASE(test_lazy_update_general),
    MRGI_TEST_CASE(test_points_follow_deformation),
    MRGI_TEST_CASE(test_deterministic_and_clouds),
    MRGI_TEST_CASE(test_bad_input),
  };
  return MRGI_TEST_MAIN(argc, argv, cases);
}
