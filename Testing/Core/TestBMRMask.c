/* Tests of mrgi_bmr_mask (BMR masks and inclusive stencils): a plane has no
 * edges and only level 4 stencilled; a step is caught by depth, a crease by
 * normals, shadow edges by the shadow image, each at scene scales 1e-3, 1 and
 * 1e3 with the same masks; min/max combination; inclusivity, the
 * footprint max and the separable Gaussian on random inputs; the NW09 flags
 * as mask source; 1x1 and odd sizes; presets; bad input. */
#include "mrgi_bmr_mask.h"

#include "mrgi_bmr_test.h"

/* Masks of a G-buffer; fails the case on error. */
static void build(
  const bmr_gbuffer* g, const float* shadow, const mrgi_bmr_params* params, mrgi_bmr_masks* masks)
{
  mrgi_error err;
  const mrgi_status status = mrgi_bmr_mask_build(&g->view, shadow, g->ab, params, masks, &err);
  if (status != MRGI_OK)
  {
    MRGI_FAIL("mrgi_bmr_mask_build: %s", err.message);
  }
}

static int64_t count(const uint8_t* a, int32_t w, int32_t h)
{
  int64_t n = 0;
  for (size_t t = 0; t < (size_t)w * (size_t)h; ++t)
  {
    n += a[t];
  }
  return n;
}

/* Every array of two mask sets equal (floats bit for bit). */
static int same_masks(const mrgi_bmr_masks* a, const mrgi_bmr_masks* b)
{
  for (int k = 0; k < MRGI_BMR_LEVELS; ++k)
  {
    const size_t n = (size_t)a->level_width[k] * (size_t)a->level_height[k];
    if (a->level_width[k] != b->level_width[k] || a->level_height[k] != b->level_height[k] ||
      memcmp(a->edge[k], b->edge[k], n) || memcmp(a->stencil[k], b->stencil[k], n) ||
      memcmp(a->mask[k], b->mask[k], n * sizeof(float)))
    {
      return 0;
    }
  }
  return 1;
}

static void params_only(mrgi_bmr_params* params, double depth, double normal)
{
  MRGI_CHECK(mrgi_bmr_preset_params(MRGI_BMR_EFFECT_SSAO, params, NULL) == MRGI_OK);
  params->depth_threshold = depth;
  params->normal_threshold = normal;
}

static void test_plane_has_no_edges(void)
{
  for (int kind = 0; kind < 2; ++kind)
  {
    for (int parallel = 0; parallel < 2; ++parallel)
    {
      bmr_gbuffer g;
      bmr_gbuffer_scene(&g, 64, 48, kind == 0 ? BMR_SCENE_PLANE : BMR_SCENE_TILTED, 1.0, parallel);
      mrgi_bmr_params params;
      MRGI_CHECK(mrgi_bmr_preset_params(MRGI_BMR_EFFECT_SSAO, &params, NULL) == MRGI_OK);
      mrgi_bmr_masks m;
      build(&g, NULL, &params, &m);
      for (int k = 0; k < MRGI_BMR_LEVELS - 1; ++k)
      {
        MRGI_CHECK(count(m.edge[k], m.level_width[k], m.level_height[k]) == 0);
        MRGI_CHECK(count(m.stencil[k], m.level_width[k], m.level_height[k]) == 0);
      }
      const int k = MRGI_BMR_LEVELS - 1;
      MRGI_CHECK(m.level_width[k] == 8 && m.level_height[k] == 6);
      MRGI_CHECK(count(m.stencil[k], 8, 6) == 48);
      mrgi_bmr_stats stats;
      MRGI_CHECK(mrgi_bmr_stats_compute(&m, &stats, NULL) == MRGI_OK);
      MRGI_CHECK(stats.valid_pixels == 64 * 48 && stats.finest_pixels[3] == 64 * 48);
      MRGI_CHECK_NEAR(stats.work_fraction, 48.0 / (64.0 * 48.0), 1e-12);
      mrgi_bmr_masks_destroy(&m);
      bmr_gbuffer_free(&g);
    }
  }
}

/* Columns of level 0 with an edge in row `y`. */
static void edge_columns(
  const mrgi_bmr_masks* m, int32_t y, int32_t* first, int32_t* last, int64_t* total)
{
  *first = -1;
  *last = -1;
  *total = count(m->edge[0], m->width, m->height);
  for (int32_t x = 0; x < m->width; ++x)
  {
    if (m->edge[0][(size_t)y * (size_t)m->width + (size_t)x])
    {
      if (*first < 0)
      {
        *first = x;
      }
      *last = x;
    }
  }
}

/* One scene at scales 1e-3, 1, 1e3 and both projections: the same masks;
 * edges exactly in the two middle columns, all rows. */
static void check_middle_edge(bmr_scene_kind kind, double depth, double normal)
{
  for (int parallel = 0; parallel < 2; ++parallel)
  {
    mrgi_bmr_masks ref;
    memset(&ref, 0, sizeof(ref));
    const double scales[3] = { 1.0, 1e-3, 1e3 };
    for (int s = 0; s < 3; ++s)
    {
      bmr_gbuffer g;
      bmr_gbuffer_scene(&g, 64, 40, kind, scales[s], parallel);
      mrgi_bmr_params params;
      params_only(&params, depth, normal);
      mrgi_bmr_masks m;
      build(&g, NULL, &params, &m);
      int32_t first, last;
      int64_t total;
      edge_columns(&m, 20, &first, &last, &total);
      if (first != 31 || last != 32 || total != 2 * 40)
      {
        MRGI_FAIL("kind %d parallel %d scale %g: edges in columns %d..%d, %lld in all", (int)kind,
          parallel, scales[s], (int)first, (int)last, (long long)total);
      }
      /* Stencils: level 1 around the edge, level 4 everywhere. */
      MRGI_CHECK(m.stencil[0][20 * 64 + 31] && !m.stencil[0][20 * 64 + 10]);
      MRGI_CHECK(count(m.stencil[3], m.level_width[3], m.level_height[3]) == 8 * 5);
      if (s == 0)
      {
        ref = m;
      }
      else
      {
        MRGI_CHECK(same_masks(&ref, &m));
        mrgi_bmr_masks_destroy(&m);
      }
      bmr_gbuffer_free(&g);
    }
    mrgi_bmr_masks_destroy(&ref);
  }
}

static void test_step_by_depth(void)
{
  check_middle_edge(BMR_SCENE_STEP, MRGI_BMR_DEFAULT_DEPTH_THRESHOLD, INFINITY);
  /* The normals alone do not see a step between parallel planes. */
  bmr_gbuffer g;
  bmr_gbuffer_scene(&g, 64, 40, BMR_SCENE_STEP, 1.0, 0);
  mrgi_bmr_params params;
  params_only(&params, INFINITY, MRGI_BMR_DEFAULT_NORMAL_THRESHOLD);
  mrgi_bmr_masks m;
  build(&g, NULL, &params, &m);
  MRGI_CHECK(count(m.edge[0], 64, 40) == 0);
  mrgi_bmr_masks_destroy(&m);
  bmr_gbuffer_free(&g);
}

static void test_crease_by_normals(void)
{
  check_middle_edge(BMR_SCENE_CREASE, INFINITY, MRGI_BMR_DEFAULT_NORMAL_THRESHOLD);
  /* The metric itself: n_x jumps by 1 across the ridge, so the central
   * difference is 0.5: caught at T_n = 0.49, not at 0.51. */
  bmr_gbuffer g;
  bmr_gbuffer_scene(&g, 64, 40, BMR_SCENE_CREASE, 1.0, 0);
  for (int t = 0; t < 2; ++t)
  {
    mrgi_bmr_params params;
    params_only(&params, INFINITY, t == 0 ? 0.49 : 0.51);
    mrgi_bmr_masks m;
    build(&g, NULL, &params, &m);
    MRGI_CHECK(count(m.edge[0], 64, 40) == (t == 0 ? 80 : 0));
    mrgi_bmr_masks_destroy(&m);
  }
  bmr_gbuffer_free(&g);
}

static void test_combine_min_max(void)
{
  bmr_gbuffer g;
  bmr_gbuffer_scene(&g, 64, 40, BMR_SCENE_STEP, 1.0, 0);
  mrgi_bmr_params params;
  params_only(&params, MRGI_BMR_DEFAULT_DEPTH_THRESHOLD, MRGI_BMR_DEFAULT_NORMAL_THRESHOLD);
  mrgi_bmr_masks m;
  build(&g, NULL, &params, &m);
  MRGI_CHECK(count(m.edge[0], 64, 40) == 80); /* max: the depth test suffices */
  mrgi_bmr_masks_destroy(&m);
  params.combine = MRGI_BMR_COMBINE_MIN;
  build(&g, NULL, &params, &m);
  MRGI_CHECK(count(m.edge[0], 64, 40) == 0); /* min: the normals disagree */
  mrgi_bmr_masks_destroy(&m);
  /* No test on: no edges. */
  params.depth_threshold = INFINITY;
  params.normal_threshold = INFINITY;
  build(&g, NULL, &params, &m);
  MRGI_CHECK(count(m.edge[0], 64, 40) == 0);
  mrgi_bmr_masks_destroy(&m);
  /* Threshold 0: every valid pixel. */
  params.depth_threshold = 0.0;
  build(&g, NULL, &params, &m);
  MRGI_CHECK(count(m.edge[0], 64, 40) == 64 * 40);
  MRGI_CHECK(count(m.stencil[0], 64, 40) == 64 * 40);
  mrgi_bmr_masks_destroy(&m);
  bmr_gbuffer_free(&g);
}

static void test_shadow_edges(void)
{
  bmr_gbuffer g;
  bmr_gbuffer_scene(&g, 48, 32, BMR_SCENE_PLANE, 1.0, 0);
  float* shadow = (float*)malloc(48 * 32 * sizeof(float));
  MRGI_CHECK(shadow);
  for (int32_t y = 0; y < 32; ++y)
  {
    for (int32_t x = 0; x < 48; ++x)
    {
      shadow[y * 48 + x] = y >= 20 ? 1.0f : 0.0f; /* lit above row 20 */
    }
  }
  mrgi_bmr_params params;
  MRGI_CHECK(mrgi_bmr_preset_params(MRGI_BMR_EFFECT_SSM, &params, NULL) == MRGI_OK);
  mrgi_bmr_masks m;
  build(&g, shadow, &params, &m);
  MRGI_CHECK(count(m.edge[0], 48, 32) == 2 * 48);
  for (int32_t x = 0; x < 48; ++x)
  {
    MRGI_CHECK(m.edge[0][19 * 48 + x] && m.edge[0][20 * 48 + x]);
  }
  mrgi_bmr_masks_destroy(&m);
  build(&g, NULL, &params, &m);
  MRGI_CHECK(count(m.edge[0], 48, 32) == 0);
  mrgi_bmr_masks_destroy(&m);
  free(shadow);
  bmr_gbuffer_free(&g);
}

/* The silhouette against background is an edge for either geometric test. */
static void test_silhouette(void)
{
  bmr_gbuffer g;
  bmr_gbuffer_scene(&g, 32, 32, BMR_SCENE_PLANE, 1.0, 0);
  for (int32_t y = 0; y < 32; ++y)
  {
    for (int32_t x = 16; x < 32; ++x)
    {
      g.position[4 * (y * 32 + x) + 3] = 0.0f;
    }
  }
  for (int t = 0; t < 2; ++t)
  {
    mrgi_bmr_params params;
    params_only(&params, t == 0 ? 1.0 : INFINITY, t == 0 ? INFINITY : 0.1);
    mrgi_bmr_masks m;
    build(&g, NULL, &params, &m);
    MRGI_CHECK(count(m.edge[0], 32, 32) == 32);
    MRGI_CHECK(m.edge[0][5 * 32 + 15] && !m.edge[0][5 * 32 + 16]);
    MRGI_CHECK(count(m.nonempty[0], 32, 32) == 16 * 32);
    MRGI_CHECK(count(m.stencil[3], 4, 4) == 8); /* only non-empty footprints */
    mrgi_bmr_masks_destroy(&m);
  }
  bmr_gbuffer_free(&g);
}

/* Random G-buffers and params: E and NE are footprint maxima, a is the 2D
 * Gaussian renormalised over the level, the stencils are inclusive and
 * level 4 covers exactly the non-empty texels. */
static void test_random_invariants(void)
{
  for (int trial = 0; trial < 40; ++trial)
  {
    const int32_t W = bmr_rng_int(1, 70), H = bmr_rng_int(1, 50);
    bmr_gbuffer g;
    bmr_gbuffer_random(&g, W, H);
    mrgi_bmr_params params;
    bmr_params_random(&params);
    mrgi_bmr_masks m;
    build(&g, NULL, &params, &m);
    for (int k = 0; k < MRGI_BMR_LEVELS; ++k)
    {
      const int32_t w = m.level_width[k], h = m.level_height[k], s = 1 << k;
      MRGI_CHECK(w == (W + s - 1) / s && h == (H + s - 1) / s);
      const float var = (float)params.variance[k];
      const int32_t R = var > 0.0f ? (int32_t)ceilf(3.0f * sqrtf(var)) : 0;
      for (int32_t y = 0; y < h; ++y)
      {
        for (int32_t x = 0; x < w; ++x)
        {
          const size_t t = (size_t)y * (size_t)w + (size_t)x;
          int e = 0, ne = 0;
          for (int32_t py = y * s; py < (y + 1) * s && py < H; ++py)
          {
            for (int32_t px = x * s; px < (x + 1) * s && px < W; ++px)
            {
              e |= m.edge[0][(size_t)py * (size_t)W + (size_t)px];
              ne |= m.nonempty[0][(size_t)py * (size_t)W + (size_t)px];
            }
          }
          MRGI_CHECK(m.edge[k][t] == e && m.nonempty[k][t] == ne);
          /* Brute-force 2D Gaussian over the taps inside the level. */
          double sum = 0.0, wsum = 0.0;
          for (int32_t j = -R; j <= R; ++j)
          {
            for (int32_t i = -R; i <= R; ++i)
            {
              if (x + i < 0 || x + i >= w || y + j < 0 || y + j >= h)
              {
                continue;
              }
              const double gw = R == 0
                ? 1.0
                : exp(-(double)(i * i) / (2.0 * var)) * exp(-(double)(j * j) / (2.0 * var));
              sum += gw * m.edge[k][(size_t)(y + j) * (size_t)w + (size_t)(x + i)];
              wsum += gw;
            }
          }
          const double a = params.skip[k] ? 0.0 : sum / wsum;
          MRGI_CHECK_NEAR(m.mask[k][t], a, 1e-5);
          MRGI_CHECK((m.mask[k][t] > 0.0f) == (a > 0.0));
          /* Stencils. */
          if (k == MRGI_BMR_LEVELS - 1)
          {
            MRGI_CHECK(m.stencil[k][t] == m.nonempty[k][t]);
          }
          if (m.stencil[k][t])
          {
            MRGI_CHECK(m.nonempty[k][t] && !params.skip[k]);
          }
          if (m.nonempty[k][t] && m.mask[k][t] > 0.0f && !params.skip[k])
          {
            MRGI_CHECK(m.stencil[k][t]);
          }
          if (m.stencil[k][t])
          {
            for (int j = k + 1; j < MRGI_BMR_LEVELS; ++j)
            {
              const size_t up =
                (size_t)(y >> (j - k)) * (size_t)m.level_width[j] + (size_t)(x >> (j - k));
              MRGI_CHECK(m.stencil[j][up] || params.skip[j]);
            }
          }
        }
      }
    }
    mrgi_bmr_stats stats;
    MRGI_CHECK(mrgi_bmr_stats_compute(&m, &stats, NULL) == MRGI_OK);
    int64_t finest = 0;
    for (int k = 0; k < MRGI_BMR_LEVELS; ++k)
    {
      finest += stats.finest_pixels[k];
    }
    MRGI_CHECK(finest == stats.valid_pixels);
    mrgi_bmr_masks_destroy(&m);
    bmr_gbuffer_free(&g);
  }
}

static void test_small_sizes(void)
{
  const int32_t sizes[5][2] = { { 1, 1 }, { 7, 5 }, { 1, 9 }, { 9, 1 }, { 17, 3 } };
  for (int i = 0; i < 5; ++i)
  {
    bmr_gbuffer g;
    bmr_gbuffer_scene(&g, sizes[i][0], sizes[i][1], BMR_SCENE_STEP, 1.0, 0);
    mrgi_bmr_params params;
    MRGI_CHECK(mrgi_bmr_preset_params(MRGI_BMR_EFFECT_SSAO, &params, NULL) == MRGI_OK);
    mrgi_bmr_masks m;
    build(&g, NULL, &params, &m);
    const int k = MRGI_BMR_LEVELS - 1;
    MRGI_CHECK(
      m.level_width[k] == (sizes[i][0] + 7) / 8 && m.level_height[k] == (sizes[i][1] + 7) / 8);
    MRGI_CHECK(count(m.stencil[k], m.level_width[k], m.level_height[k]) ==
      (int64_t)m.level_width[k] * m.level_height[k]);
    if (sizes[i][0] == 1 && sizes[i][1] == 1)
    {
      MRGI_CHECK(m.edge[0][0] == 0 && m.mask[0][0] == 0.0f && m.stencil[0][0] == 0);
    }
    mrgi_bmr_masks_destroy(&m);
    bmr_gbuffer_free(&g);
  }
}

/* The NW09 min-max flags as mask source. */
static void test_flags_source(void)
{
  for (int kind = 0; kind < 2; ++kind)
  {
    bmr_gbuffer g;
    bmr_gbuffer_scene(&g, 64, 40, kind == 0 ? BMR_SCENE_PLANE : BMR_SCENE_STEP, 1.0, 0);
    mrgi_multires_layout layout;
    MRGI_CHECK(mrgi_multires_layout_init(
                 &layout, 64, 40, MRGI_MULTIRES_DEFAULT_COARSEST_SIDE, NULL) == MRGI_OK);
    mrgi_multires_mipmap mipmap;
    MRGI_CHECK(mrgi_multires_mipmap_build(&layout, &g.view, g.ab, &mipmap, NULL) == MRGI_OK);
    mrgi_multires_params mp;
    mrgi_multires_params_default(&mp);
    const size_t n = (size_t)mrgi_multires_texel_count(&layout);
    uint8_t* flags = (uint8_t*)malloc(n);
    MRGI_CHECK(flags);
    MRGI_CHECK(mrgi_multires_flags_compute(&mipmap, &mp, flags, n, NULL) == MRGI_OK);
    mrgi_bmr_params params;
    MRGI_CHECK(mrgi_bmr_preset_params(MRGI_BMR_EFFECT_SSAO, &params, NULL) == MRGI_OK);
    mrgi_bmr_masks m;
    MRGI_CHECK(mrgi_bmr_mask_from_flags(&layout, flags, n, &params, &m, NULL) == MRGI_OK);
    MRGI_CHECK(layout.level_count == 3); /* 64 x 40 -> 16 x 10: level 3 comes from the max-down */
    const int64_t edges = count(m.edge[0], 64, 40);
    if (kind == 0)
    {
      MRGI_CHECK(edges == 0 && count(m.stencil[0], 64, 40) == 0);
    }
    else
    {
      MRGI_CHECK(edges > 0 && m.edge[0][20 * 64 + 31] && !m.edge[0][20 * 64 + 5]);
      MRGI_CHECK(m.stencil[0][20 * 64 + 32] && m.stencil[1][10 * 32 + 16]);
    }
    MRGI_CHECK(count(m.stencil[3], 8, 5) == 40);
    mrgi_bmr_masks_destroy(&m);
    MRGI_CHECK(mrgi_bmr_mask_from_flags(&layout, flags, n - 1, &params, &m, NULL) ==
      MRGI_ERR_INVALID_ARGUMENT);
    free(flags);
    mrgi_multires_mipmap_destroy(&mipmap);
    bmr_gbuffer_free(&g);
  }
}

static void test_presets(void)
{
  mrgi_bmr_params p;
  MRGI_CHECK(mrgi_bmr_preset_params(MRGI_BMR_EFFECT_SSAO, &p, NULL) == MRGI_OK);
  MRGI_CHECK(p.variance[0] == 0.924 && p.variance[1] == 1.848 && p.variance[2] == 3.696 &&
    p.variance[3] == 0.0);
  MRGI_CHECK(
    p.weight[0] == 100.0 && p.weight[1] == 50.0 && p.weight[2] == 20.0 && p.weight[3] == 1.0);
  MRGI_CHECK(!p.skip[0] && !p.skip[1] && !p.skip[2] && !p.skip[3]);
  MRGI_CHECK(mrgi_bmr_preset_params(MRGI_BMR_EFFECT_SSM, &p, NULL) == MRGI_OK);
  MRGI_CHECK(p.weight[0] == 1000.0 && p.weight[2] == 1000.0 && p.weight[3] == 1.0);
  MRGI_CHECK(mrgi_bmr_preset_params(MRGI_BMR_EFFECT_SSGI, &p, NULL) == MRGI_OK);
  MRGI_CHECK(p.skip[1] && p.variance[2] == 0.924 && p.weight[2] == 100.0);
  MRGI_CHECK(strcmp(mrgi_bmr_effect_name(MRGI_BMR_EFFECT_SSGI), "ssgi") == 0);
  MRGI_CHECK(mrgi_bmr_effect_name(7) == NULL);
}

static void test_bad_input(void)
{
  bmr_gbuffer g;
  bmr_gbuffer_scene(&g, 8, 8, BMR_SCENE_PLANE, 1.0, 0);
  mrgi_bmr_params p;
  mrgi_bmr_masks m;
  mrgi_error err;
  MRGI_CHECK(mrgi_bmr_preset_params(3, &p, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "unknown effect") != NULL);
  MRGI_CHECK(mrgi_bmr_preset_params(MRGI_BMR_EFFECT_SSAO, &p, NULL) == MRGI_OK);
  MRGI_CHECK(mrgi_bmr_mask_build(NULL, NULL, g.ab, &p, &m, &err) == MRGI_ERR_INVALID_ARGUMENT);
  p.depth_threshold = -1.0;
  MRGI_CHECK(mrgi_bmr_mask_build(&g.view, NULL, g.ab, &p, &m, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "depth threshold") != NULL && m.edge[0] == NULL);
  p.depth_threshold = NAN;
  MRGI_CHECK(mrgi_bmr_mask_build(&g.view, NULL, g.ab, &p, &m, &err) == MRGI_ERR_INVALID_ARGUMENT);
  p.depth_threshold = 1.0;
  p.variance[2] = 17.0;
  MRGI_CHECK(mrgi_bmr_mask_build(&g.view, NULL, g.ab, &p, &m, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "variance of level 3") != NULL);
  p.variance[2] = 1.0;
  p.skip[3] = 1;
  MRGI_CHECK(mrgi_bmr_mask_build(&g.view, NULL, g.ab, &p, &m, &err) == MRGI_ERR_INVALID_ARGUMENT);
  p.skip[3] = 0;
  p.combine = 2;
  MRGI_CHECK(mrgi_bmr_mask_build(&g.view, NULL, g.ab, &p, &m, &err) == MRGI_ERR_INVALID_ARGUMENT);
  p.combine = MRGI_BMR_COMBINE_MAX;
  const float bad_ab[2] = { 0.0f, 0.0f };
  MRGI_CHECK(mrgi_bmr_mask_build(&g.view, NULL, bad_ab, &p, &m, &err) == MRGI_ERR_INVALID_ARGUMENT);
  mrgi_gather_receivers zero = g.view;
  zero.width = 0;
  MRGI_CHECK(mrgi_bmr_mask_build(&zero, NULL, g.ab, &p, &m, &err) == MRGI_ERR_INVALID_ARGUMENT);
  /* NaN positions are invalid pixels, never edges or NaN masks. */
  g.position[4 * 9 + 2] = NAN;
  g.normal[4 * 10 + 0] = INFINITY;
  MRGI_CHECK(mrgi_bmr_mask_build(&g.view, NULL, g.ab, &p, &m, &err) == MRGI_OK);
  MRGI_CHECK(!m.nonempty[0][9] && !m.nonempty[0][10] && !m.edge[0][9]);
  for (int k = 0; k < MRGI_BMR_LEVELS; ++k)
  {
    for (size_t t = 0; t < (size_t)m.level_width[k] * (size_t)m.level_height[k]; ++t)
    {
      MRGI_CHECK(m.mask[k][t] >= 0.0f && m.mask[k][t] <= 1.0f);
    }
  }
  mrgi_bmr_masks_destroy(&m);
  mrgi_bmr_masks_destroy(&m); /* idempotent */
  mrgi_bmr_masks_destroy(NULL);
  bmr_gbuffer_free(&g);
}

int main(int argc, char** argv)
{
  static const mrgi_test_case cases[] = {
    MRGI_TEST_CASE(test_plane_has_no_edges),
    MRGI_TEST_CASE(test_step_by_depth),
    MRGI_TEST_CASE(test_crease_by_normals),
    MRGI_TEST_CASE(test_combine_min_max),
    MRGI_TEST_CASE(test_shadow_edges),
    MRGI_TEST_CASE(test_silhouette),
    MRGI_TEST_CASE(test_random_invariants),
    MRGI_TEST_CASE(test_small_sizes),
    MRGI_TEST_CASE(test_flags_source),
    MRGI_TEST_CASE(test_presets),
    MRGI_TEST_CASE(test_bad_input),
  };
  return MRGI_TEST_MAIN(argc, argv, cases);
}
