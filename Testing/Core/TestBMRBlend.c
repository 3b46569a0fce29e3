/* Tests of mrgi_bmr_blend (BMR eq. 1, index corrected, bilinear over
 * stencilled taps): a constant effect blends to that constant whatever the
 * unstencilled texels hold; the full-resolution path (threshold 0) is the
 * identity; a linear function is reproduced; outputs stay within the
 * stencilled values; skipped levels are never read; 1x1 and odd sizes; bad
 * input. */
#include "mrgi_bmr_blend.h"

#include "mrgi_bmr_test.h"

/* Per-level effect arrays, `channels` floats per texel. */
typedef struct levels
{
  float* data[MRGI_BMR_LEVELS];
} levels;

static void levels_alloc(levels* l, const mrgi_bmr_masks* m, int32_t channels)
{
  for (int k = 0; k < MRGI_BMR_LEVELS; ++k)
  {
    l->data[k] = (float*)calloc(
      (size_t)m->level_width[k] * (size_t)m->level_height[k] * (size_t)channels, sizeof(float));
    MRGI_CHECK(l->data[k]);
  }
}

static void levels_free(levels* l)
{
  for (int k = 0; k < MRGI_BMR_LEVELS; ++k)
  {
    free(l->data[k]);
    l->data[k] = NULL;
  }
}

/* Junk at every unstencilled texel: NaN, infinities, huge values. */
static void levels_junk(levels* l, const mrgi_bmr_masks* m, int32_t channels)
{
  const float junk[4] = { NAN, INFINITY, -1e30f, 1e30f };
  for (int k = 0; k < MRGI_BMR_LEVELS; ++k)
  {
    for (size_t t = 0; t < (size_t)m->level_width[k] * (size_t)m->level_height[k]; ++t)
    {
      if (!m->stencil[k][t])
      {
        for (int32_t c = 0; c < channels; ++c)
        {
          l->data[k][t * (size_t)channels + (size_t)c] = junk[bmr_rng_int(0, 3)];
        }
      }
    }
  }
}

static void blend(
  const mrgi_bmr_masks* m, const mrgi_bmr_params* p, const levels* l, int32_t channels, float* out)
{
  mrgi_error err;
  const float* const lv[MRGI_BMR_LEVELS] = { l->data[0], l->data[1], l->data[2], l->data[3] };
  if (mrgi_bmr_blend(m, p, lv, channels, out,
        (size_t)m->width * (size_t)m->height * (size_t)channels, &err) != MRGI_OK)
  {
    MRGI_FAIL("mrgi_bmr_blend: %s", err.message);
  }
}

static void test_constant(void)
{
  for (int trial = 0; trial < 30; ++trial)
  {
    const int32_t W = trial == 0 ? 1 : bmr_rng_int(1, 60), H = trial == 0 ? 1 : bmr_rng_int(1, 45);
    bmr_gbuffer g;
    if (trial % 2)
    {
      bmr_gbuffer_random(&g, W, H);
    }
    else
    {
      bmr_gbuffer_scene(&g, W, H, (bmr_scene_kind)(trial % 4), 1.0, trial % 3 == 0);
    }
    mrgi_bmr_params p;
    bmr_params_random(&p);
    mrgi_bmr_masks m;
    MRGI_CHECK(mrgi_bmr_mask_build(&g.view, NULL, g.ab, &p, &m, NULL) == MRGI_OK);
    const int32_t C = bmr_rng_int(1, 4);
    const float value[4] = { 0.25f, 3.0f, -7.5f, 1e-3f };
    levels l;
    levels_alloc(&l, &m, C);
    for (int k = 0; k < MRGI_BMR_LEVELS; ++k)
    {
      for (size_t t = 0; t < (size_t)m.level_width[k] * (size_t)m.level_height[k]; ++t)
      {
        for (int32_t c = 0; c < C; ++c)
        {
          l.data[k][t * (size_t)C + (size_t)c] = value[c];
        }
      }
    }
    levels_junk(&l, &m, C);
    float* out = (float*)malloc((size_t)W * (size_t)H * (size_t)C * sizeof(float));
    MRGI_CHECK(out);
    blend(&m, &p, &l, C, out);
    for (size_t q = 0; q < (size_t)W * (size_t)H; ++q)
    {
      for (int32_t c = 0; c < C; ++c)
      {
        const float expected = m.nonempty[0][q] ? value[c] : 0.0f;
        /* Renormalising divides: a constant comes back to float rounding. */
        if (!(fabsf(out[q * (size_t)C + (size_t)c] - expected) <= 1e-6f * fabsf(expected)))
        {
          MRGI_FAIL("trial %d (%d x %d): pixel %zu channel %d is %.9g, expected %.9g", trial,
            (int)W, (int)H, q, (int)c, (double)out[q * (size_t)C + (size_t)c], (double)expected);
        }
      }
    }
    free(out);
    levels_free(&l);
    mrgi_bmr_masks_destroy(&m);
    bmr_gbuffer_free(&g);
  }
}

/* Threshold 0: every valid pixel at level 1, so the blend returns c_1. */
static void test_full_resolution_identity(void)
{
  for (int trial = 0; trial < 12; ++trial)
  {
    const int32_t W = bmr_rng_int(1, 50), H = bmr_rng_int(1, 40);
    bmr_gbuffer g;
    bmr_gbuffer_random(&g, W, H);
    mrgi_bmr_params p;
    MRGI_CHECK(mrgi_bmr_preset_params(trial % MRGI_BMR_EFFECT_COUNT, &p, NULL) == MRGI_OK);
    p.depth_threshold = 0.0;
    mrgi_bmr_masks m;
    MRGI_CHECK(mrgi_bmr_mask_build(&g.view, NULL, g.ab, &p, &m, NULL) == MRGI_OK);
    levels l;
    levels_alloc(&l, &m, 1);
    for (int k = 0; k < MRGI_BMR_LEVELS; ++k)
    {
      for (size_t t = 0; t < (size_t)m.level_width[k] * (size_t)m.level_height[k]; ++t)
      {
        l.data[k][t] = (float)(bmr_rng_unit() * 10.0 - 5.0);
      }
    }
    levels_junk(&l, &m, 1);
    float* out = (float*)malloc((size_t)W * (size_t)H * sizeof(float));
    MRGI_CHECK(out);
    blend(&m, &p, &l, 1, out);
    for (size_t q = 0; q < (size_t)W * (size_t)H; ++q)
    {
      MRGI_CHECK(m.nonempty[0][q] == m.stencil[0][q]);
      MRGI_CHECK(out[q] == (m.nonempty[0][q] ? l.data[0][q] : 0.0f));
    }
    free(out);
    levels_free(&l);
    mrgi_bmr_masks_destroy(&m);
    bmr_gbuffer_free(&g);
  }
}

/* Every level stencilled, any masks: c_k = f(texel centre) with f linear
 * blends to f(pixel centre) away from the border (bilinear reproduces
 * linear functions; the blend is a convex combination). */
static void test_linear_function(void)
{
  const int32_t W = 64, H = 48;
  bmr_gbuffer g;
  bmr_gbuffer_scene(&g, W, H, BMR_SCENE_PLANE, 1.0, 0);
  mrgi_bmr_params p;
  MRGI_CHECK(mrgi_bmr_preset_params(MRGI_BMR_EFFECT_SSAO, &p, NULL) == MRGI_OK);
  mrgi_bmr_masks m;
  MRGI_CHECK(mrgi_bmr_mask_build(&g.view, NULL, g.ab, &p, &m, NULL) == MRGI_OK);
  levels l;
  levels_alloc(&l, &m, 2);
  for (int k = 0; k < MRGI_BMR_LEVELS; ++k)
  {
    const double s = (double)(1 << k);
    for (int32_t y = 0; y < m.level_height[k]; ++y)
    {
      for (int32_t x = 0; x < m.level_width[k]; ++x)
      {
        const size_t t = (size_t)y * (size_t)m.level_width[k] + (size_t)x;
        m.stencil[k][t] = 1;
        m.mask[k][t] = (float)(bmr_rng_unit() * 0.05);
        const double cx = (x + 0.5) * s, cy = (y + 0.5) * s;
        l.data[k][2 * t + 0] = (float)(0.5 * cx - 0.25 * cy + 3.0);
        l.data[k][2 * t + 1] = (float)(cy);
      }
    }
  }
  float* out = (float*)malloc((size_t)W * (size_t)H * 2 * sizeof(float));
  MRGI_CHECK(out);
  blend(&m, &p, &l, 2, out);
  for (int32_t y = 8; y < H - 8; ++y)
  {
    for (int32_t x = 8; x < W - 8; ++x)
    {
      const size_t q = (size_t)y * (size_t)W + (size_t)x;
      const double cx = x + 0.5, cy = y + 0.5;
      MRGI_CHECK_NEAR(out[2 * q + 0], 0.5 * cx - 0.25 * cy + 3.0, 1e-4);
      MRGI_CHECK_NEAR(out[2 * q + 1], cy, 1e-4);
    }
  }
  /* With every mask 0, the result is level 4's bilinear alone: still linear. */
  free(out);
  levels_free(&l);
  mrgi_bmr_masks_destroy(&m);
  bmr_gbuffer_free(&g);
}

/* Random levels with junk outside the stencils: every output lies within
 * the range of the stencilled values, and the weights decide: a step edge
 * with level 1 = 1 and the other levels = 0 gives 1 on the edge, 0 far
 * from it, and in between a fall-off no wider than the blur. */
static void test_bounds_and_weights(void)
{
  for (int trial = 0; trial < 20; ++trial)
  {
    const int32_t W = bmr_rng_int(1, 60), H = bmr_rng_int(1, 45);
    bmr_gbuffer g;
    bmr_gbuffer_random(&g, W, H);
    mrgi_bmr_params p;
    bmr_params_random(&p);
    mrgi_bmr_masks m;
    MRGI_CHECK(mrgi_bmr_mask_build(&g.view, NULL, g.ab, &p, &m, NULL) == MRGI_OK);
    levels l;
    levels_alloc(&l, &m, 1);
    for (int k = 0; k < MRGI_BMR_LEVELS; ++k)
    {
      for (size_t t = 0; t < (size_t)m.level_width[k] * (size_t)m.level_height[k]; ++t)
      {
        l.data[k][t] = (float)bmr_rng_unit();
      }
    }
    levels_junk(&l, &m, 1);
    float* out = (float*)malloc((size_t)W * (size_t)H * sizeof(float));
    MRGI_CHECK(out);
    blend(&m, &p, &l, 1, out);
    for (size_t q = 0; q < (size_t)W * (size_t)H; ++q)
    {
      MRGI_CHECK(out[q] >= 0.0f && out[q] <= 1.0f);
    }
    free(out);
    levels_free(&l);
    mrgi_bmr_masks_destroy(&m);
    bmr_gbuffer_free(&g);
  }
  /* The step scene, SSAO preset. */
  const int32_t W = 64, H = 40;
  bmr_gbuffer g;
  bmr_gbuffer_scene(&g, W, H, BMR_SCENE_STEP, 1.0, 0);
  mrgi_bmr_params p;
  MRGI_CHECK(mrgi_bmr_preset_params(MRGI_BMR_EFFECT_SSAO, &p, NULL) == MRGI_OK);
  mrgi_bmr_masks m;
  MRGI_CHECK(mrgi_bmr_mask_build(&g.view, NULL, g.ab, &p, &m, NULL) == MRGI_OK);
  levels l;
  levels_alloc(&l, &m, 1);
  for (size_t t = 0; t < (size_t)W * (size_t)H; ++t)
  {
    l.data[0][t] = 1.0f;
  }
  float* out = (float*)malloc((size_t)W * (size_t)H * sizeof(float));
  MRGI_CHECK(out);
  blend(&m, &p, &l, 1, out);
  const size_t row = 20 * (size_t)W;
  MRGI_CHECK(out[row + 31] == 1.0f && out[row + 32] == 1.0f);
  MRGI_CHECK(out[row + 2] == 0.0f && out[row + 61] == 0.0f);
  /* a_1 w_1 >= 1 within the radius-3 blur of the edge columns. */
  MRGI_CHECK(out[row + 29] == 1.0f && out[row + 34] == 1.0f);
  free(out);
  levels_free(&l);
  mrgi_bmr_masks_destroy(&m);
  bmr_gbuffer_free(&g);
}

/* A skipped level is never read, even where stencilled data would be junk. */
static void test_skipped_level(void)
{
  bmr_gbuffer g;
  bmr_gbuffer_scene(&g, 40, 24, BMR_SCENE_STEP, 1.0, 0);
  mrgi_bmr_params p;
  MRGI_CHECK(mrgi_bmr_preset_params(MRGI_BMR_EFFECT_SSGI, &p, NULL) == MRGI_OK);
  mrgi_bmr_masks m;
  MRGI_CHECK(mrgi_bmr_mask_build(&g.view, NULL, g.ab, &p, &m, NULL) == MRGI_OK);
  MRGI_CHECK(m.stencil[1][0] == 0 && m.required[1][12 * 0 + 10] == 1);
  levels l;
  levels_alloc(&l, &m, 1);
  for (int k = 0; k < MRGI_BMR_LEVELS; ++k)
  {
    for (size_t t = 0; t < (size_t)m.level_width[k] * (size_t)m.level_height[k]; ++t)
    {
      l.data[k][t] = k == 1 ? NAN : 2.0f;
    }
  }
  float out[40 * 24];
  blend(&m, &p, &l, 1, out);
  for (size_t q = 0; q < 40 * 24; ++q)
  {
    MRGI_CHECK(out[q] == 2.0f);
  }
  levels_free(&l);
  mrgi_bmr_masks_destroy(&m);
  bmr_gbuffer_free(&g);
}

static void test_bad_input(void)
{
  bmr_gbuffer g;
  bmr_gbuffer_scene(&g, 8, 8, BMR_SCENE_PLANE, 1.0, 0);
  mrgi_bmr_params p;
  MRGI_CHECK(mrgi_bmr_preset_params(MRGI_BMR_EFFECT_SSAO, &p, NULL) == MRGI_OK);
  mrgi_bmr_masks m;
  MRGI_CHECK(mrgi_bmr_mask_build(&g.view, NULL, g.ab, &p, &m, NULL) == MRGI_OK);
  levels l;
  levels_alloc(&l, &m, 4);
  const float* const lv[MRGI_BMR_LEVELS] = { l.data[0], l.data[1], l.data[2], l.data[3] };
  float out[8 * 8 * 4];
  mrgi_error err;
  MRGI_CHECK(mrgi_bmr_blend(&m, &p, lv, 5, out, 8 * 8 * 4, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "channels") != NULL);
  MRGI_CHECK(mrgi_bmr_blend(&m, &p, lv, 4, out, 8 * 8 * 4 - 1, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "needs") != NULL);
  const float* const missing[MRGI_BMR_LEVELS] = { l.data[0], NULL, l.data[2], l.data[3] };
  MRGI_CHECK(mrgi_bmr_blend(&m, &p, missing, 4, out, 8 * 8 * 4, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "level 2") != NULL);
  p.weight[0] = -1.0;
  MRGI_CHECK(mrgi_bmr_blend(&m, &p, lv, 4, out, 8 * 8 * 4, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_bmr_blend(NULL, &p, lv, 4, out, 8 * 8 * 4, &err) == MRGI_ERR_INVALID_ARGUMENT);
  levels_free(&l);
  mrgi_bmr_masks_destroy(&m);
  bmr_gbuffer_free(&g);
}

int main(int argc, char** argv)
{
  static const mrgi_test_case cases[] = {
    MRGI_TEST_CASE(test_constant),
    MRGI_TEST_CASE(test_full_resolution_identity),
    MRGI_TEST_CASE(test_linear_function),
    MRGI_TEST_CASE(test_bounds_and_weights),
    MRGI_TEST_CASE(test_skipped_level),
    MRGI_TEST_CASE(test_bad_input),
  };
  return MRGI_TEST_MAIN(argc, argv, cases);
}
