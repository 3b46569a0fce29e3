/* Tests of mrgi_vpl: record layout, grid selection (energy, block bounds,
 * representative texel, empty blocks, cube maps) and flux importance
 * sampling (unbiasedness, concentration, determinism), degenerate RSMs and
 * bad input. */
#include "mrgi_vpl.h"
#include "mrgi_test.h"
#include "mrgi_test_rsm.h"

#include <float.h>
#include <stddef.h>
#include <string.h>

/* A valid texel whose position encodes (view, x, y) so a VPL can be traced back. */
static void set_texel(test_rsm* t, int32_t view, int32_t x, int32_t y, float r, float g, float b,
                      float area)
{
  const size_t i = test_rsm_index(t, view, x, y);
  t->position[4 * i + 0] = (float)x + 0.25f;
  t->position[4 * i + 1] = (float)y - 0.5f;
  t->position[4 * i + 2] = (float)view * 100.0f + 1.0f;
  t->position[4 * i + 3] = MRGI_GBUFFER_VALID;
  t->normal[4 * i + 0] = 0.0f;
  t->normal[4 * i + 1] = 0.6f;
  t->normal[4 * i + 2] = 0.8f;
  t->flux[4 * i + 0] = r;
  t->flux[4 * i + 1] = g;
  t->flux[4 * i + 2] = b;
  t->flux[4 * i + 3] = area;
}

/* Deterministic uniform numbers in [0, 1). */
static double next_uniform(uint32_t* state)
{
  *state = *state * 1664525u + 1013904223u;
  return (double)(*state >> 8) / 16777216.0;
}

/* Every texel of every view valid, with varied colour (so luminance is not
 * proportional to any one channel) and area. */
static void fill_random(test_rsm* t, uint32_t seed)
{
  uint32_t state = seed;
  for (int32_t v = 0; v < t->rsm.view_count; ++v)
  {
    for (int32_t y = 0; y < t->rsm.size; ++y)
    {
      for (int32_t x = 0; x < t->rsm.size; ++x)
      {
        const float r = (float)next_uniform(&state);
        const float g = (float)(next_uniform(&state) * next_uniform(&state));
        const float b = (float)(4.0 * next_uniform(&state));
        set_texel(t, v, x, y, r, g, b, (float)(0.1 + next_uniform(&state)));
      }
    }
  }
}

/* Exact per-channel flux sums (index 3: area) over usable texels. */
static void rsm_sums(const test_rsm* t, double sums[4])
{
  sums[0] = sums[1] = sums[2] = sums[3] = 0.0;
  const size_t texels = (size_t)t->rsm.view_count * (size_t)t->rsm.size * (size_t)t->rsm.size;
  for (size_t i = 0; i < texels; ++i)
  {
    if (t->position[4 * i + 3] > 0.5f && isfinite(t->position[4 * i]) && isfinite(t->flux[4 * i]))
    {
      for (int c = 0; c < 4; ++c)
      {
        sums[c] += t->flux[4 * i + c];
      }
    }
  }
}

static void vpl_sums(const mrgi_vpl* vpls, int32_t count, double sums[4])
{
  sums[0] = sums[1] = sums[2] = sums[3] = 0.0;
  for (int32_t j = 0; j < count; ++j)
  {
    for (int c = 0; c < 3; ++c)
    {
      sums[c] += vpls[j].flux[c];
    }
    sums[3] += vpls[j].area;
  }
}

static void check_all_finite(const mrgi_vpl* vpls, int32_t count)
{
  const float* data = mrgi_vpl_texture_data(vpls);
  for (size_t k = 0; k < (size_t)count * MRGI_VPL_FLOATS; ++k)
  {
    MRGI_CHECK(isfinite(data[k]));
  }
}

static void test_record_layout(void)
{
  MRGI_CHECK(sizeof(mrgi_vpl) == MRGI_VPL_TEXELS * 4 * sizeof(float));
  mrgi_vpl vpls[2];
  memset(vpls, 0, sizeof(vpls));
  vpls[1].position[2] = 3.0f;
  vpls[1].area = 4.0f;
  vpls[1].normal[1] = 5.0f;
  vpls[1].flux[0] = 6.0f;
  const float* texels = mrgi_vpl_texture_data(vpls);
  MRGI_CHECK(texels[MRGI_VPL_FLOATS + 4 * MRGI_VPL_TEXEL_POSITION + 2] == 3.0f);
  MRGI_CHECK(texels[MRGI_VPL_FLOATS + 4 * MRGI_VPL_TEXEL_POSITION + 3] == 4.0f);
  MRGI_CHECK(texels[MRGI_VPL_FLOATS + 4 * MRGI_VPL_TEXEL_NORMAL + 1] == 5.0f);
  MRGI_CHECK(texels[MRGI_VPL_FLOATS + 4 * MRGI_VPL_TEXEL_FLUX + 0] == 6.0f);
}

static void test_grid_layout(void)
{
  int32_t side = 0;
  int32_t count = 0;
  MRGI_CHECK(mrgi_vpl_grid_layout(256, 1, 256, &side, &count, NULL) == MRGI_OK);
  MRGI_CHECK(side == 16 && count == 256);
  MRGI_CHECK(mrgi_vpl_grid_layout(255, 1, 256, &side, &count, NULL) == MRGI_OK);
  MRGI_CHECK(side == 15 && count == 225);
  MRGI_CHECK(mrgi_vpl_grid_layout(4096, 1, 512, &side, &count, NULL) == MRGI_OK);
  MRGI_CHECK(side == 64 && count == 4096);
  MRGI_CHECK(mrgi_vpl_grid_layout(96, 6, 64, &side, &count, NULL) == MRGI_OK);
  MRGI_CHECK(side == 4 && count == 96);
  MRGI_CHECK(mrgi_vpl_grid_layout(95, 6, 64, &side, &count, NULL) == MRGI_OK);
  MRGI_CHECK(side == 3 && count == 54);
  /* Fewer VPLs than views: one per view. */
  MRGI_CHECK(mrgi_vpl_grid_layout(5, 6, 64, &side, &count, NULL) == MRGI_OK);
  MRGI_CHECK(side == 1 && count == 6);
  /* Grid larger than the RSM: clamped so every block keeps a texel. */
  MRGI_CHECK(mrgi_vpl_grid_layout(4096, 1, 32, &side, &count, NULL) == MRGI_OK);
  MRGI_CHECK(side == 32 && count == 1024);
  MRGI_CHECK(mrgi_vpl_grid_layout(0, 1, 32, &side, &count, NULL) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_vpl_grid_layout(4097, 1, 32, NULL, NULL, NULL) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_vpl_grid_layout(16, 7, 32, NULL, NULL, NULL) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_vpl_grid_layout(16, 1, 0, NULL, NULL, NULL) == MRGI_ERR_INVALID_ARGUMENT);
}

/* S = 10 with G = 3: blocks of 3, 3 and 4 texels per side. */
static void test_grid_energy_not_divisible(void)
{
  test_rsm t = test_rsm_make(10, 1);
  fill_random(&t, 7u);
  /* An invalid texel holding flux, and a valid one holding NaN: both ignored. */
  t.position[4 * test_rsm_index(&t, 0, 9, 9) + 3] = 0.0f;
  t.flux[4 * test_rsm_index(&t, 0, 0, 9)] = NAN;
  mrgi_vpl vpls[9];
  mrgi_vpl_selection_info info;
  MRGI_CHECK(mrgi_vpl_select_grid(&t.rsm, 9, vpls, 9, &info, NULL) == MRGI_OK);
  MRGI_CHECK(info.vpl_count == 9 && info.empty_vpl_count == 0);
  MRGI_CHECK(info.usable_texel_count == 98 && info.rejected_texel_count == 1);
  check_all_finite(vpls, 9);

  double expected[4];
  double got[4];
  rsm_sums(&t, expected);
  vpl_sums(vpls, 9, got);
  for (int c = 0; c < 4; ++c)
  {
    MRGI_CHECK(expected[c] > 0.0);
    MRGI_CHECK_NEAR(got[c] / expected[c], 1.0, 1e-5);
  }

  /* Block (i = 1, j = 2): x in [3, 6), y in [6, 10): VPL (0*3 + 2)*3 + 1 = 7. */
  double block[4] = { 0.0, 0.0, 0.0, 0.0 };
  for (int32_t y = 6; y < 10; ++y)
  {
    for (int32_t x = 3; x < 6; ++x)
    {
      for (int c = 0; c < 4; ++c)
      {
        block[c] += t.flux[4 * test_rsm_index(&t, 0, x, y) + c];
      }
    }
  }
  for (int c = 0; c < 3; ++c)
  {
    MRGI_CHECK_NEAR(vpls[7].flux[c], block[c], 1e-5 * block[c]);
  }
  MRGI_CHECK_NEAR(vpls[7].area, block[3], 1e-5 * block[3]);
  /* Its centre is (4.5, 8): texel (4, 7) and (4, 8) tie at distance 0.5; (4, 7) has the lower index. */
  MRGI_CHECK(vpls[7].position[0] == 4.25f && vpls[7].position[1] == 6.5f);
  test_rsm_free(&t);
}

static void test_grid_representative(void)
{
  test_rsm t = test_rsm_make(4, 1);
  for (int32_t y = 0; y < 4; ++y)
  {
    for (int32_t x = 0; x < 4; ++x)
    {
      set_texel(&t, 0, x, y, 1.0f, 1.0f, 1.0f, 1.0f);
    }
  }
  mrgi_vpl vpl;
  /* Centre (2, 2): texels (1,1), (2,1), (1,2), (2,2) tie; lowest index is (1, 1). */
  MRGI_CHECK(mrgi_vpl_select_grid(&t.rsm, 1, &vpl, 1, NULL, NULL) == MRGI_OK);
  MRGI_CHECK(vpl.position[0] == 1.25f && vpl.position[1] == 0.5f);
  MRGI_CHECK(vpl.normal[1] == 0.6f && vpl.normal[2] == 0.8f);
  /* Without (1, 1): (2, 1) is next in index order. */
  t.position[4 * test_rsm_index(&t, 0, 1, 1) + 3] = 0.0f;
  MRGI_CHECK(mrgi_vpl_select_grid(&t.rsm, 1, &vpl, 1, NULL, NULL) == MRGI_OK);
  MRGI_CHECK(vpl.position[0] == 2.25f && vpl.position[1] == 0.5f);
  MRGI_CHECK(vpl.flux[0] == 15.0f && vpl.area == 15.0f);
  /* A rejected (non-finite) texel is never the representative. */
  t.normal[4 * test_rsm_index(&t, 0, 2, 1) + 0] = INFINITY;
  MRGI_CHECK(mrgi_vpl_select_grid(&t.rsm, 1, &vpl, 1, NULL, NULL) == MRGI_OK);
  MRGI_CHECK(vpl.position[0] == 1.25f && vpl.position[1] == 1.5f);
  test_rsm_free(&t);

  /* Odd size: the centre (2.5, 2.5) is texel (2, 2)'s own centre. */
  test_rsm odd = test_rsm_make(5, 1);
  set_texel(&odd, 0, 0, 0, 1.0f, 1.0f, 1.0f, 1.0f);
  set_texel(&odd, 0, 2, 2, 1.0f, 1.0f, 1.0f, 1.0f);
  set_texel(&odd, 0, 4, 4, 1.0f, 1.0f, 1.0f, 1.0f);
  MRGI_CHECK(mrgi_vpl_select_grid(&odd.rsm, 1, &vpl, 1, NULL, NULL) == MRGI_OK);
  MRGI_CHECK(vpl.position[0] == 2.25f && vpl.position[1] == 1.5f);
  test_rsm_free(&odd);
}

static void test_grid_empty_blocks(void)
{
  test_rsm t = test_rsm_make(8, 1);
  set_texel(&t, 0, 1, 2, 2.0f, 3.0f, 4.0f, 0.5f);
  mrgi_vpl vpls[4];
  memset(vpls, 0xFF, sizeof(vpls)); /* NaN patterns: every field must be written */
  mrgi_vpl_selection_info info;
  MRGI_CHECK(mrgi_vpl_select_grid(&t.rsm, 4, vpls, 4, &info, NULL) == MRGI_OK);
  MRGI_CHECK(info.vpl_count == 4 && info.empty_vpl_count == 3 && info.usable_texel_count == 1);
  check_all_finite(vpls, 4);
  MRGI_CHECK(vpls[0].flux[0] == 2.0f && vpls[0].flux[2] == 4.0f && vpls[0].area == 0.5f);
  MRGI_CHECK(vpls[0].pad0 == 0.0f && vpls[0].pad1 == 0.0f);
  for (int32_t j = 1; j < 4; ++j)
  {
    const float* data = mrgi_vpl_texture_data(vpls + j);
    for (int k = 0; k < MRGI_VPL_FLOATS; ++k)
    {
      MRGI_CHECK(data[k] == 0.0f);
    }
  }
  test_rsm_free(&t);
}

static void test_grid_views(void)
{
  /* One view, one texel per block. */
  test_rsm one = test_rsm_make(64, 1);
  fill_random(&one, 3u);
  mrgi_vpl* vpls = (mrgi_vpl*)malloc(sizeof(mrgi_vpl) * MRGI_VPL_MAX_COUNT);
  MRGI_CHECK(vpls != NULL);
  mrgi_vpl_selection_info info;
  MRGI_CHECK(mrgi_vpl_select_grid(&one.rsm, MRGI_VPL_MAX_COUNT, vpls, MRGI_VPL_MAX_COUNT, &info,
                                  NULL) == MRGI_OK);
  MRGI_CHECK(info.vpl_count == 4096);
  const size_t probe = test_rsm_index(&one, 0, 37, 5);
  MRGI_CHECK(vpls[5 * 64 + 37].flux[1] == one.flux[4 * probe + 1]);
  MRGI_CHECK(vpls[5 * 64 + 37].position[0] == one.position[4 * probe]);
  test_rsm_free(&one);

  /* Six cube faces, S = 13 (not a multiple of G = 4). */
  test_rsm cube = test_rsm_make(13, 6);
  fill_random(&cube, 11u);
  MRGI_CHECK(mrgi_vpl_select_grid(&cube.rsm, 100, vpls, 100, &info, NULL) == MRGI_OK);
  MRGI_CHECK(info.vpl_count == 96 && info.usable_texel_count == 6 * 13 * 13);
  double expected[4];
  double got[4];
  rsm_sums(&cube, expected);
  vpl_sums(vpls, 96, got);
  for (int c = 0; c < 4; ++c)
  {
    MRGI_CHECK_NEAR(got[c] / expected[c], 1.0, 1e-5);
  }
  /* VPLs (v*4 + j)*4 + i come from view v (its z is 100 v + 1). */
  for (int32_t j = 0; j < 96; ++j)
  {
    MRGI_CHECK(vpls[j].position[2] == (float)(j / 16) * 100.0f + 1.0f);
  }
  /* Fewer VPLs requested than views: one per face, and the capacity must say so. */
  MRGI_CHECK(mrgi_vpl_select_grid(&cube.rsm, 5, vpls, 6, &info, NULL) == MRGI_OK);
  MRGI_CHECK(info.vpl_count == 6);
  mrgi_error err;
  MRGI_CHECK(mrgi_vpl_select_grid(&cube.rsm, 5, vpls, 5, &info, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "makes 6") != NULL);
  test_rsm_free(&cube);
  free(vpls);
}

/* Index of the texel whose position equals the VPL's (set_texel encodes view, x, y). */
static size_t traced_texel(const test_rsm* t, const mrgi_vpl* vpl)
{
  const int32_t x = (int32_t)(vpl->position[0] - 0.25f);
  const int32_t y = (int32_t)(vpl->position[1] + 0.5f);
  const int32_t view = (int32_t)((vpl->position[2] - 1.0f) / 100.0f);
  MRGI_CHECK(x >= 0 && x < t->rsm.size && y >= 0 && y < t->rsm.size && view >= 0 &&
             view < t->rsm.view_count);
  return test_rsm_index(t, view, x, y);
}

static double luminance(const float* rgb)
{
  return MRGI_LUMINANCE_R * rgb[0] + MRGI_LUMINANCE_G * rgb[1] + MRGI_LUMINANCE_B * rgb[2];
}

static void test_importance_unbiased(void)
{
  test_rsm t = test_rsm_make(16, 2);
  fill_random(&t, 5u);
  for (int32_t x = 0; x < 16; ++x)
  {
    t.position[4 * test_rsm_index(&t, 1, x, 3) + 3] = 0.0f; /* a row seeing nothing */
  }
  double exact[4];
  rsm_sums(&t, exact);
  double total_luminance = 0.0;
  for (size_t i = 0; i < 2 * 16 * 16; ++i)
  {
    total_luminance += t.position[4 * i + 3] > 0.5f ? luminance(t.flux + 4 * i) : 0.0;
  }

  enum { N = 16, SEEDS = 2000 };
  mrgi_vpl vpls[N];
  double mean[4] = { 0.0, 0.0, 0.0, 0.0 };
  double mean_square[4] = { 0.0, 0.0, 0.0, 0.0 };
  for (uint64_t seed = 0; seed < SEEDS; ++seed)
  {
    mrgi_vpl_selection_info info;
    MRGI_CHECK(mrgi_vpl_select_importance(&t.rsm, N, seed, NULL, 0, vpls, N, &info, NULL) ==
               MRGI_OK);
    MRGI_CHECK(info.vpl_count == N && info.empty_vpl_count == 0);
    MRGI_CHECK(info.usable_texel_count == 2 * 16 * 16 - 16);
    check_all_finite(vpls, N);
    double sums[4];
    vpl_sums(vpls, N, sums);
    for (int c = 0; c < 4; ++c)
    {
      mean[c] += sums[c] / SEEDS;
      mean_square[c] += sums[c] * sums[c] / SEEDS;
    }
    if (seed == 0)
    {
      /* Each VPL is its texel scaled by 1 / (N p_t): Phi_j N p_t = Phi_t, same for A. */
      for (int32_t j = 0; j < N; ++j)
      {
        const size_t i = traced_texel(&t, vpls + j);
        MRGI_CHECK(t.position[4 * i + 3] > 0.5f);
        const double n_p = N * luminance(t.flux + 4 * i) / total_luminance;
        for (int c = 0; c < 4; ++c)
        {
          const double value = c < 3 ? vpls[j].flux[c] : vpls[j].area;
          MRGI_CHECK_NEAR(value * n_p, t.flux[4 * i + c], 1e-5 * t.flux[4 * i + c] + 1e-30);
        }
      }
    }
  }
  for (int c = 0; c < 4; ++c)
  {
    const double variance = mean_square[c] - mean[c] * mean[c];
    const double standard_error = sqrt(variance > 0.0 ? variance / SEEDS : 0.0);
    /* The estimator must actually vary (colours are not proportional to luminance)... */
    MRGI_CHECK(standard_error > 1e-4 * exact[c]);
    /* ...and centre on the exact sum. */
    if (!(fabs(mean[c] - exact[c]) < 4.0 * standard_error))
    {
      fprintf(stderr, "channel %d: mean %.9g, exact %.9g, standard error %.3g\n", c, mean[c],
              exact[c], standard_error);
      MRGI_CHECK(0);
    }
  }
  test_rsm_free(&t);
}

static void test_importance_concentrated_and_deterministic(void)
{
  test_rsm t = test_rsm_make(8, 1);
  for (int32_t y = 0; y < 8; ++y)
  {
    for (int32_t x = 0; x < 8; ++x)
    {
      set_texel(&t, 0, x, y, 0.1f, 0.1f, 0.1f, 1.0f); /* luminance 0.1 each, 6.4 in all */
    }
  }
  set_texel(&t, 0, 5, 6, 1000.0f, 1000.0f, 1000.0f, 1.0f); /* 1000 of 1006.3 */
  enum { N = 200 };
  mrgi_vpl vpls[N];
  mrgi_vpl again[N];
  double scratch[64];
  MRGI_CHECK(mrgi_vpl_select_importance(&t.rsm, N, 42u, scratch, 64, vpls, N, NULL, NULL) ==
             MRGI_OK);
  int32_t on_bright = 0;
  for (int32_t j = 0; j < N; ++j)
  {
    on_bright += traced_texel(&t, vpls + j) == test_rsm_index(&t, 0, 5, 6);
  }
  /* Expected 200 * 1000 / 1006.3 = 198.7; stratification keeps it within one. */
  MRGI_CHECK(on_bright >= 197);
  /* Same seed, with or without caller scratch: identical VPLs. */
  MRGI_CHECK(mrgi_vpl_select_importance(&t.rsm, N, 42u, NULL, 0, again, N, NULL, NULL) ==
             MRGI_OK);
  MRGI_CHECK(memcmp(vpls, again, sizeof(vpls)) == 0);
  /* Another seed: other VPLs on the dim texels. */
  MRGI_CHECK(mrgi_vpl_select_importance(&t.rsm, N, 43u, NULL, 0, again, N, NULL, NULL) ==
             MRGI_OK);
  MRGI_CHECK(memcmp(vpls, again, sizeof(vpls)) != 0);
  /* Scratch too small. */
  mrgi_error err;
  MRGI_CHECK(mrgi_vpl_select_importance(&t.rsm, N, 1u, scratch, 63, vpls, N, NULL, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "64 texels") != NULL);
  MRGI_CHECK(mrgi_vpl_importance_scratch_count(&t.rsm) == 64);
  test_rsm_free(&t);
}

static void test_zero_and_extreme_rsm(void)
{
  test_rsm t = test_rsm_make(6, 1);
  mrgi_vpl vpls[9];
  mrgi_vpl_selection_info info;
  /* Nothing seen at all. */
  MRGI_CHECK(mrgi_vpl_select_grid(&t.rsm, 9, vpls, 9, &info, NULL) == MRGI_OK);
  MRGI_CHECK(info.empty_vpl_count == 9 && info.usable_texel_count == 0);
  check_all_finite(vpls, 9);
  MRGI_CHECK(mrgi_vpl_select_importance(&t.rsm, 9, 0u, NULL, 0, vpls, 9, &info, NULL) == MRGI_OK);
  MRGI_CHECK(info.empty_vpl_count == 9);
  check_all_finite(vpls, 9);
  /* Surfaces seen, all black: grid keeps positions and areas, importance gives zeros. */
  for (int32_t y = 0; y < 6; ++y)
  {
    for (int32_t x = 0; x < 6; ++x)
    {
      set_texel(&t, 0, x, y, 0.0f, 0.0f, 0.0f, 2.0f);
    }
  }
  MRGI_CHECK(mrgi_vpl_select_grid(&t.rsm, 9, vpls, 9, &info, NULL) == MRGI_OK);
  MRGI_CHECK(info.empty_vpl_count == 9 && info.usable_texel_count == 36);
  MRGI_CHECK(vpls[4].area == 8.0f && vpls[4].normal[2] == 0.8f);
  MRGI_CHECK(mrgi_vpl_select_importance(&t.rsm, 9, 0u, NULL, 0, vpls, 9, &info, NULL) == MRGI_OK);
  MRGI_CHECK(info.empty_vpl_count == 9);
  for (int32_t j = 0; j < 9; ++j)
  {
    MRGI_CHECK(vpls[j].flux[0] == 0.0f && vpls[j].area == 0.0f);
  }
  /* Intensities from 1e-6 to 1e6 side by side: finite, energy kept. */
  for (int32_t y = 0; y < 6; ++y)
  {
    for (int32_t x = 0; x < 6; ++x)
    {
      const float value = (x + y) % 2 ? 1e6f : 1e-6f;
      set_texel(&t, 0, x, y, value, 0.5f * value, value, 1e-4f);
    }
  }
  double exact[4];
  double got[4];
  rsm_sums(&t, exact);
  MRGI_CHECK(mrgi_vpl_select_grid(&t.rsm, 9, vpls, 9, &info, NULL) == MRGI_OK);
  check_all_finite(vpls, 9);
  vpl_sums(vpls, 9, got);
  MRGI_CHECK_NEAR(got[0] / exact[0], 1.0, 1e-5);
  MRGI_CHECK(mrgi_vpl_select_importance(&t.rsm, 9, 0u, NULL, 0, vpls, 9, &info, NULL) == MRGI_OK);
  check_all_finite(vpls, 9);
  /* A negative flux is rejected, not sampled. */
  t.flux[4 * test_rsm_index(&t, 0, 1, 1) + 1] = -1.0f;
  MRGI_CHECK(mrgi_vpl_select_grid(&t.rsm, 9, vpls, 9, &info, NULL) == MRGI_OK);
  MRGI_CHECK(info.rejected_texel_count == 1 && info.usable_texel_count == 35);
  test_rsm_free(&t);
}

static void test_bad_input(void)
{
  test_rsm t = test_rsm_make(4, 1);
  mrgi_vpl vpls[4];
  mrgi_error err;
  MRGI_CHECK(mrgi_vpl_select_grid(NULL, 4, vpls, 4, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "NULL") != NULL);
  MRGI_CHECK(mrgi_vpl_select_grid(&t.rsm, 4, NULL, 4, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_vpl_select_grid(&t.rsm, 0, vpls, 4, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "count 0") != NULL);
  MRGI_CHECK(mrgi_vpl_select_grid(&t.rsm, 4097, vpls, 4, NULL, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_vpl_select_grid(&t.rsm, 4, vpls, 3, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_vpl_select_importance(&t.rsm, 4, 0u, NULL, 0, vpls, 3, NULL, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_vpl_select_importance(&t.rsm, -1, 0u, NULL, 0, vpls, 4, NULL, NULL) ==
             MRGI_ERR_INVALID_ARGUMENT);
  mrgi_rsm bad = t.rsm;
  bad.size = 0;
  MRGI_CHECK(mrgi_vpl_select_grid(&bad, 4, vpls, 4, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "size 0") != NULL);
  MRGI_CHECK(mrgi_vpl_importance_scratch_count(&bad) == 0);
  bad = t.rsm;
  bad.view_count = 7;
  MRGI_CHECK(mrgi_vpl_select_importance(&bad, 4, 0u, NULL, 0, vpls, 4, NULL, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "view count 7") != NULL);
  bad = t.rsm;
  bad.flux = NULL;
  MRGI_CHECK(mrgi_rsm_validate(&bad, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "flux") != NULL);
  MRGI_CHECK(mrgi_rsm_validate(&t.rsm, NULL) == MRGI_OK);
  test_rsm_free(&t);
}

int main(int argc, char** argv)
{
  static const mrgi_test_case cases[] = {
    MRGI_TEST_CASE(test_record_layout),
    MRGI_TEST_CASE(test_grid_layout),
    MRGI_TEST_CASE(test_grid_energy_not_divisible),
    MRGI_TEST_CASE(test_grid_representative),
    MRGI_TEST_CASE(test_grid_empty_blocks),
    MRGI_TEST_CASE(test_grid_views),
    MRGI_TEST_CASE(test_importance_unbiased),
    MRGI_TEST_CASE(test_importance_concentrated_and_deterministic),
    MRGI_TEST_CASE(test_zero_and_extreme_rsm),
    MRGI_TEST_CASE(test_bad_input),
  };
  return MRGI_TEST_MAIN(argc, argv, cases);
}
