/* Tests of mrgi_rsm_composite: the depth composite of RSM views across MPI
 * ranks. The operation must be a minimum over a total order (commutative and
 * associative bit for bit, as MPI's reductions require), keep the record
 * nearest the light, treat empty texels as the identity and never let a
 * NaN/Inf through. */
#include "mrgi_buffers.h"
#include "mrgi_rsm_composite.h"

#include "mrgi_test.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define F MRGI_RSM_COMPOSITE_RECORD_FLOATS

/* A small deterministic generator (xorshift64*), so failures reproduce. */
static uint64_t rng_state = 0x9E3779B97F4A7C15ull;
static double uniform(void)
{
  rng_state ^= rng_state >> 12;
  rng_state ^= rng_state << 25;
  rng_state ^= rng_state >> 27;
  return (double)((rng_state * 2685821657736338717ull) >> 11) / 9007199254740992.0;
}

static float* new_view(size_t texels)
{
  float* v = calloc(texels * F, sizeof(float));
  MRGI_CHECK(v != NULL);
  return v;
}

/* Texel i of a planar view: write a valid surface record at `p` with normal
 * +z and flux (f, f, f, area). */
static void put(float* view, size_t texels, size_t i, const float p[3], float f, float area)
{
  float* pos = view + (MRGI_RSM_POSITION * texels + i) * 4;
  float* nrm = view + (MRGI_RSM_NORMAL * texels + i) * 4;
  float* flx = view + (MRGI_RSM_FLUX * texels + i) * 4;
  pos[0] = p[0];
  pos[1] = p[1];
  pos[2] = p[2];
  pos[3] = MRGI_GBUFFER_VALID;
  nrm[0] = 0;
  nrm[1] = 0;
  nrm[2] = 1;
  nrm[3] = 0;
  flx[0] = flx[1] = flx[2] = f;
  flx[3] = area;
}

static float* channel(float* view, size_t texels, int plane, size_t i)
{
  return view + ((size_t)plane * texels + i) * 4;
}

static int record_equal(const float* a, const float* b, size_t texels, size_t i)
{
  for (int plane = 0; plane < MRGI_RSM_ATTACHMENTS; ++plane)
  {
    if (memcmp(a + ((size_t)plane * texels + i) * 4, b + ((size_t)plane * texels + i) * 4,
          4 * sizeof(float)) != 0)
    {
      return 0;
    }
  }
  return 1;
}

static int record_zero(const float* a, size_t texels, size_t i)
{
  static const float zero[F] = { 0 };
  for (int plane = 0; plane < MRGI_RSM_ATTACHMENTS; ++plane)
  {
    if (memcmp(a + ((size_t)plane * texels + i) * 4, zero, 4 * sizeof(float)) != 0)
    {
      return 0;
    }
  }
  return 1;
}

static const mrgi_rsm_view_key perspective_key = { { 0.0, 2.0, 0.0 }, { 0.0, 0.0, 0.0 }, 1 };
static const mrgi_rsm_view_key ortho_key = { { 0.0, 5.0, 0.0 }, { 0.0, -2.0, 0.0 }, 0 };

/* Random views: valid surfaces at random depths along a few shared rays
 * (ties in depth with different contents included), empty texels, and
 * texels with NaN/Inf in some float. */
static void random_view(float* v, size_t texels)
{
  memset(v, 0, texels * F * sizeof(float));
  for (size_t i = 0; i < texels; ++i)
  {
    const double u = uniform();
    if (u < 0.25)
    {
      continue; /* empty */
    }
    /* Depths from a small set so that equal depths with different records occur. */
    const float depth = (float)(1 + (int)(uniform() * 4));
    const float p[3] = { 0.0f, 2.0f - depth, 0.0f };
    put(v, texels, i, p, (float)(int)(uniform() * 3), 0.5f);
    if (u > 0.9)
    {
      const int plane = (int)(uniform() * 3);
      const int c = (int)(uniform() * 4);
      channel(v, texels, plane, i)[c] = uniform() < 0.5 ? NAN : -INFINITY;
    }
  }
}

static void composite(const float* in, float* inout, size_t texels, const mrgi_rsm_view_key* key)
{
  mrgi_error err;
  const mrgi_status status = mrgi_rsm_composite(in, inout, texels, key, &err);
  if (status != MRGI_OK)
  {
    MRGI_FAIL("mrgi_rsm_composite: %s", err.message);
  }
}

/* The nearer record wins, in both argument orders, per texel. */
static void test_nearest_wins(void)
{
  const size_t n = 3;
  float* a = new_view(n);
  float* b = new_view(n);
  const float near_p[3] = { 0.0f, 1.0f, 0.0f }; /* 1 from the light at (0, 2, 0) */
  const float far_p[3] = { 0.0f, -1.0f, 0.0f }; /* 3 from it */
  put(a, n, 0, near_p, 1.0f, 0.1f);
  put(b, n, 0, far_p, 2.0f, 0.2f);
  put(a, n, 1, far_p, 3.0f, 0.3f);
  put(b, n, 1, near_p, 4.0f, 0.4f);
  put(a, n, 2, far_p, 5.0f, 0.5f); /* b's texel 2 stays empty */
  MRGI_CHECK_NEAR(mrgi_rsm_composite_depth(a, n, 0, &perspective_key), 1.0, 1e-12);
  MRGI_CHECK_NEAR(mrgi_rsm_composite_depth(b, n, 0, &perspective_key), 3.0, 1e-12);
  MRGI_CHECK(mrgi_rsm_composite_depth(b, n, 2, &perspective_key) == INFINITY);
  float* expect = new_view(n);
  memcpy(expect, a, n * F * sizeof(float));
  put(expect, n, 1, near_p, 4.0f, 0.4f);
  composite(a, b, n, &perspective_key);
  for (size_t i = 0; i < n; ++i)
  {
    MRGI_CHECK(record_equal(b, expect, n, i));
  }
  free(a);
  free(b);
  free(expect);
}

/* Orthographic views order by the distance along the direction, not from the origin. */
static void test_orthographic(void)
{
  const size_t n = 1;
  float* a = new_view(n);
  float* b = new_view(n);
  const float pa[3] = { 100.0f, 1.0f, 0.0f }; /* far off the axis, but nearer along -y */
  const float pb[3] = { 0.0f, 0.5f, 0.0f };
  put(a, n, 0, pa, 1.0f, 1.0f);
  put(b, n, 0, pb, 2.0f, 1.0f);
  MRGI_CHECK_NEAR(mrgi_rsm_composite_depth(a, n, 0, &ortho_key), 4.0, 1e-12);
  MRGI_CHECK_NEAR(mrgi_rsm_composite_depth(b, n, 0, &ortho_key), 4.5, 1e-12);
  composite(a, b, n, &ortho_key);
  MRGI_CHECK(record_equal(a, b, n, 0));
  free(a);
  free(b);
}

/* Equal depths: the smaller bit pattern wins, whichever argument holds it. */
static void test_ties(void)
{
  const size_t n = 1;
  float* a = new_view(n);
  float* b = new_view(n);
  const float p[3] = { 0.0f, 0.0f, 0.0f };
  put(a, n, 0, p, 1.0f, 1.0f);
  put(b, n, 0, p, 2.0f, 1.0f);
  float* a2 = new_view(n);
  memcpy(a2, a, n * F * sizeof(float));
  composite(b, a2, n, &perspective_key); /* a2 = b op a */
  MRGI_CHECK(record_equal(a2, a, n, 0)); /* flux 1.0f < 2.0f as bits */
  composite(a, b, n, &perspective_key);  /* b = a op b */
  MRGI_CHECK(record_equal(b, a, n, 0));
  free(a);
  free(b);
  free(a2);
}

/* Commutative and associative bit for bit on random views, and equal to a
 * brute-force minimum (what one process's depth test keeps). */
static void test_random_algebra(void)
{
  const size_t n = 2000;
  const mrgi_rsm_view_key* keys[2] = { &perspective_key, &ortho_key };
  float* v[3];
  float* ab = new_view(n);
  float* ba = new_view(n);
  float* left = new_view(n);
  float* right = new_view(n);
  for (int k = 0; k < 3; ++k)
  {
    v[k] = new_view(n);
  }
  for (int round = 0; round < 10; ++round)
  {
    const mrgi_rsm_view_key* key = keys[round % 2];
    for (int k = 0; k < 3; ++k)
    {
      random_view(v[k], n);
    }
    /* commutativity */
    memcpy(ab, v[1], n * F * sizeof(float));
    composite(v[0], ab, n, key);
    memcpy(ba, v[0], n * F * sizeof(float));
    composite(v[1], ba, n, key);
    MRGI_CHECK(memcmp(ab, ba, n * F * sizeof(float)) == 0);
    /* associativity: (a op b) op c == a op (b op c) */
    memcpy(left, v[2], n * F * sizeof(float));
    composite(ab, left, n, key);
    memcpy(right, v[2], n * F * sizeof(float));
    composite(v[1], right, n, key);
    composite(v[0], right, n, key);
    MRGI_CHECK(memcmp(left, right, n * F * sizeof(float)) == 0);
    /* the nearest valid record of the three, or zeros */
    for (size_t i = 0; i < n; ++i)
    {
      double best = INFINITY;
      for (int k = 0; k < 3; ++k)
      {
        const double d = mrgi_rsm_composite_depth(v[k], n, i, key);
        best = d < best ? d : best;
      }
      MRGI_CHECK(mrgi_rsm_composite_depth(left, n, i, key) == best);
      if (best == INFINITY)
      {
        MRGI_CHECK(record_zero(left, n, i));
      }
      else
      {
        MRGI_CHECK(record_equal(left, v[0], n, i) || record_equal(left, v[1], n, i) ||
          record_equal(left, v[2], n, i));
      }
    }
  }
  for (int k = 0; k < 3; ++k)
  {
    free(v[k]);
  }
  free(ab);
  free(ba);
  free(left);
  free(right);
}

/* An all-zero view (a rank that sees nothing) changes no valid texel; the
 * empty and invalid ones come out as zeros, in both argument orders. */
static void test_empty_identity(void)
{
  const size_t n = 1000;
  float* x = new_view(n);
  float* empty = new_view(n);
  float* out = new_view(n);
  random_view(x, n);
  memcpy(out, x, n * F * sizeof(float));
  composite(empty, out, n, &perspective_key);
  float* out2 = new_view(n);
  composite(x, out2, n, &perspective_key); /* out2 starts all zero */
  MRGI_CHECK(memcmp(out, out2, n * F * sizeof(float)) == 0);
  size_t valid = 0;
  for (size_t i = 0; i < n; ++i)
  {
    if (mrgi_rsm_composite_depth(x, n, i, &perspective_key) < INFINITY)
    {
      ++valid;
      MRGI_CHECK(record_equal(out, x, n, i));
    }
    else
    {
      MRGI_CHECK(record_zero(out, n, i));
    }
  }
  MRGI_CHECK(valid > n / 2 && valid < n); /* the view had both kinds */
  free(x);
  free(empty);
  free(out);
  free(out2);
}

/* NaN or Inf in any float, or a NaN w, makes a texel empty: it never wins
 * against a valid one and no NaN/Inf is ever written. */
static void test_nan_inf(void)
{
  const size_t n = F * 2 + 2;
  float* bad = new_view(n);
  float* good = new_view(n);
  const float p[3] = { 0.0f, 1.9f, 0.0f }; /* nearer than the good ones */
  const float q[3] = { 0.0f, -1.0f, 0.0f };
  for (size_t i = 0; i < n; ++i)
  {
    put(bad, n, i, p, 1.0f, 1.0f);
    if (i % 2 == 0)
    {
      put(good, n, i, q, 2.0f, 1.0f); /* odd texels of `good` stay empty */
    }
  }
  for (size_t i = 0; i < 2 * F; ++i)
  {
    const int k = (int)(i % F);
    channel(bad, n, k / 4, i)[k % 4] = i < F ? NAN : INFINITY;
  }
  channel(bad, n, MRGI_RSM_POSITION, 2 * F)[3] = NAN;      /* w NaN */
  channel(bad, n, MRGI_RSM_POSITION, 2 * F + 1)[3] = 0.4f; /* w below the threshold */
  for (size_t i = 0; i < n; ++i)
  {
    MRGI_CHECK(mrgi_rsm_composite_depth(bad, n, i, &perspective_key) == INFINITY);
  }
  float* out = new_view(n);
  memcpy(out, good, n * F * sizeof(float));
  composite(bad, out, n, &perspective_key);
  for (size_t i = 0; i < n; ++i)
  {
    if (i % 2 == 0)
    {
      MRGI_CHECK(record_equal(out, good, n, i));
    }
    else
    {
      MRGI_CHECK(record_zero(out, n, i));
    }
  }
  for (size_t k = 0; k < n * F; ++k)
  {
    MRGI_CHECK(isfinite(out[k]));
  }
  /* in place: bad op bad is all zeros */
  composite(bad, bad, n, &perspective_key);
  for (size_t i = 0; i < n; ++i)
  {
    MRGI_CHECK(record_zero(bad, n, i));
  }
  free(bad);
  free(good);
  free(out);
}

static void test_bad_arguments(void)
{
  float* a = new_view(1);
  float* b = new_view(1);
  const float p[3] = { 0.0f, 0.0f, 0.0f };
  put(b, 1, 0, p, 1.0f, 1.0f);
  float* copy = new_view(1);
  memcpy(copy, b, F * sizeof(float));
  mrgi_error err;
  memset(&err, 0, sizeof err);
  MRGI_CHECK(mrgi_rsm_composite(a, b, 1, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "key") != NULL);
  MRGI_CHECK(mrgi_rsm_composite(NULL, b, 1, &perspective_key, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_rsm_composite(a, NULL, 1, &perspective_key, &err) == MRGI_ERR_INVALID_ARGUMENT);
  mrgi_rsm_view_key key = ortho_key;
  key.direction[0] = key.direction[1] = key.direction[2] = 0.0;
  MRGI_CHECK(mrgi_rsm_composite(a, b, 1, &key, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "direction") != NULL);
  key = perspective_key;
  key.origin[1] = NAN;
  MRGI_CHECK(mrgi_rsm_composite(a, b, 1, &key, &err) == MRGI_ERR_INVALID_ARGUMENT);
  key = perspective_key;
  key.perspective = 2;
  MRGI_CHECK(mrgi_rsm_composite(a, b, 1, &key, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(
    mrgi_rsm_composite(a, b, SIZE_MAX / 8, &perspective_key, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(memcmp(b, copy, F * sizeof(float)) == 0); /* untouched on failure */
  MRGI_CHECK(mrgi_rsm_composite(NULL, NULL, 0, &perspective_key, NULL) == MRGI_OK);
  free(a);
  free(b);
  free(copy);
}

int main(int argc, char** argv)
{
  static const mrgi_test_case cases[] = { MRGI_TEST_CASE(test_nearest_wins),
    MRGI_TEST_CASE(test_orthographic), MRGI_TEST_CASE(test_ties),
    MRGI_TEST_CASE(test_random_algebra), MRGI_TEST_CASE(test_empty_identity),
    MRGI_TEST_CASE(test_nan_inf), MRGI_TEST_CASE(test_bad_arguments) };
  return MRGI_TEST_MAIN(argc, argv, cases);
}
