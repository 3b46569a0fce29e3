/* Tests of mrgi_upsample: constant illumination stays constant (any
 * selection, both modes), exact tent weights, no energy from empty texels,
 * no leak across a depth step, background stays 0, threshold 0 is the
 * identity, mask-weighted mode (weight 1 = tent, larger weights favour the
 * finer level), bad input. */
#include "mrgi_upsample.h"

#include "mrgi_buffers.h"
#include "mrgi_test.h"

#include <string.h>

static uint64_t rng_state = 0x9E3779B97F4A7C15ull;
static uint32_t rng_u32(void)
{
  rng_state ^= rng_state << 13;
  rng_state ^= rng_state >> 7;
  rng_state ^= rng_state << 17;
  return (uint32_t)(rng_state >> 11);
}
static double rng_unit(void)
{
  return (double)rng_u32() / 4294967296.0;
}
static int32_t rng_int(int32_t lo, int32_t hi)
{
  return lo + (int32_t)(rng_u32() % (uint32_t)(hi - lo + 1));
}

/* A G-buffer and everything derived from it. */
typedef struct scene
{
  int32_t width;
  int32_t height;
  float* position;
  float* normal;
  int32_t* surface; /* per pixel: which surface (-1 background) */
  mrgi_multires_layout layout;
  mrgi_multires_mipmap mipmap;
  uint8_t* flags;
  uint8_t* mask;
  float* illumination; /* 4 channels per flattened texel */
  size_t texels;
} scene;

static void scene_alloc(scene* s, int32_t width, int32_t height)
{
  memset(s, 0, sizeof(*s));
  s->width = width;
  s->height = height;
  const size_t pixels = (size_t)width * (size_t)height;
  s->position = (float*)calloc(pixels * 4, sizeof(float));
  s->normal = (float*)calloc(pixels * 4, sizeof(float));
  s->surface = (int32_t*)calloc(pixels, sizeof(int32_t));
  MRGI_CHECK(s->position && s->normal && s->surface);
}

static void scene_set(scene* s, int32_t x, int32_t y, float depth, int32_t surface)
{
  const size_t p = (size_t)y * (size_t)s->width + (size_t)x;
  s->position[4 * p + 2] = -depth;
  s->position[4 * p + 3] = surface >= 0 ? MRGI_GBUFFER_VALID : 0.0f;
  s->normal[4 * p + 2] = 1.0f;
  s->surface[p] = surface;
}

/* Mipmap, flags and the (one-pass) selection; illumination zeroed except
 * that non-selected texels get junk (must be ignored). */
static void scene_select(scene* s, int32_t coarsest_side, const mrgi_multires_params* params)
{
  MRGI_CHECK(mrgi_multires_layout_init(&s->layout, s->width, s->height, coarsest_side, NULL) ==
             MRGI_OK);
  const mrgi_gather_receivers view = { s->width, s->height, s->position, s->normal };
  const float ab[2] = { 0.01f, 0.0f };
  MRGI_CHECK(mrgi_multires_mipmap_build(&s->layout, &view, ab, &s->mipmap, NULL) == MRGI_OK);
  s->texels = (size_t)mrgi_multires_texel_count(&s->layout);
  s->flags = (uint8_t*)malloc(s->texels);
  s->mask = (uint8_t*)malloc(s->texels);
  s->illumination = (float*)malloc(s->texels * 4 * sizeof(float));
  MRGI_CHECK(s->flags && s->mask && s->illumination);
  MRGI_CHECK(mrgi_multires_flags_compute(&s->mipmap, params, s->flags, s->texels, NULL) ==
             MRGI_OK);
  MRGI_CHECK(mrgi_multires_select_one_pass(&s->layout, s->flags, s->texels, params->finest_level,
                                           s->mask, s->texels, NULL) == MRGI_OK);
  for (size_t t = 0; t < s->texels * 4; ++t)
  {
    s->illumination[t] = 1e30f; /* junk where nothing was gathered */
  }
}

static void scene_free(scene* s)
{
  free(s->position);
  free(s->normal);
  free(s->surface);
  mrgi_multires_mipmap_destroy(&s->mipmap);
  free(s->flags);
  free(s->mask);
  free(s->illumination);
  memset(s, 0, sizeof(*s));
}

/* Run the upsampling; returns the image (row 0 = bottom). */
static mrgi_image scene_upsample(const scene* s, int32_t mode, float weight)
{
  mrgi_upsample_params params;
  mrgi_upsample_params_default(&params);
  params.mode = mode;
  params.mask_weight = weight;
  mrgi_image out;
  mrgi_error err;
  const mrgi_status status =
    mrgi_upsample(&s->layout, s->flags, s->texels, s->mask, s->texels, s->illumination,
                  s->texels * 4, 4, &params, &out, &err);
  if (status != MRGI_OK)
  {
    fprintf(stderr, "%s\n", err.message);
  }
  MRGI_CHECK(status == MRGI_OK);
  MRGI_CHECK(out.width == s->width && out.height == s->height && out.channels == 3);
  return out;
}

/* Random scene: planes at random depths (steps between them), holes. */
static void random_scene(scene* s)
{
  const int32_t W = rng_int(1, 80);
  const int32_t H = rng_int(1, 80);
  scene_alloc(s, W, H);
  const int32_t split_x = rng_int(0, W);
  const int32_t split_y = rng_int(0, H);
  const double depth[3] = { 2.0 + rng_unit(), 8.0 + rng_unit(), 30.0 };
  for (int32_t y = 0; y < H; ++y)
  {
    for (int32_t x = 0; x < W; ++x)
    {
      int32_t surface = x < split_x ? 0 : (y < split_y ? 1 : 2);
      if (rng_u32() % 100 < 3 || (x > W / 3 && x < W / 2 && y > H / 3 && y < H / 2))
      {
        surface = -1;
      }
      const double d = surface < 0 ? 1.0 : depth[surface] + 0.001 * (x + y);
      scene_set(s, x, y, (float)d, surface);
    }
  }
}

static void random_params(mrgi_multires_params* params, const mrgi_multires_layout* layout_hint)
{
  const double thresholds[] = { 0.0, 0.5, 4.0, INFINITY };
  mrgi_multires_params_default(params);
  params->depth_threshold = thresholds[rng_int(0, 3)];
  params->normal_threshold = INFINITY;
  params->balance = rng_int(0, 1);
  params->finest_level = layout_hint ? rng_int(0, layout_hint->level_count - 1) * rng_int(0, 1) : 0;
}

static void test_constant(void)
{
  for (int run = 0; run < 300; ++run)
  {
    scene s;
    random_scene(&s);
    const int32_t coarsest = rng_int(1, 16);
    mrgi_multires_layout hint;
    MRGI_CHECK(mrgi_multires_layout_init(&hint, s.width, s.height, coarsest, NULL) == MRGI_OK);
    mrgi_multires_params params;
    random_params(&params, &hint);
    scene_select(&s, coarsest, &params);
    const float c[3] = { 0.3f, 1.7f, 123.0f };
    for (size_t t = 0; t < s.texels; ++t)
    {
      if (s.mask[t])
      {
        memcpy(s.illumination + 4 * t, c, sizeof(c));
      }
    }
    for (int mode = 0; mode < 2; ++mode)
    {
      mrgi_image out = scene_upsample(&s, mode, mode ? 100.0f : 1.0f);
      for (int32_t y = 0; y < s.height; ++y)
      {
        for (int32_t x = 0; x < s.width; ++x)
        {
          const float* p = mrgi_image_at(&out, x, y);
          const int valid = s.surface[(size_t)y * (size_t)s.width + (size_t)x] >= 0;
          for (int k = 0; k < 3; ++k)
          {
            if (valid)
            {
              MRGI_CHECK_NEAR(p[k], c[k], 1e-6 * c[k]);
            }
            else
            {
              MRGI_CHECK(p[k] == 0.0f); /* background stays 0 */
            }
          }
        }
      }
      mrgi_image_destroy(&out);
    }
    scene_free(&s);
  }
}

/* One level (8 x 8 <= coarsest side), all continuous: tent weights by hand. */
static void test_weights_and_empty_neighbours(void)
{
  scene s;
  scene_alloc(&s, 8, 8);
  for (int32_t y = 0; y < 8; ++y)
  {
    for (int32_t x = 0; x < 8; ++x)
    {
      scene_set(&s, x, y, 5.0f, -1);
    }
  }
  scene_set(&s, 1, 1, 5.0f, 0); /* isolated pixel: all neighbours empty */
  scene_set(&s, 5, 5, 5.0f, 0); /* a pair (5,5)-(6,5) */
  scene_set(&s, 6, 5, 5.0f, 0);
  scene_set(&s, 3, 6, 5.0f, 0); /* diagonal pair (3,6)-(4,7) */
  scene_set(&s, 4, 7, 5.0f, 0);
  mrgi_multires_params params;
  mrgi_multires_params_default(&params);
  params.depth_threshold = INFINITY;
  params.normal_threshold = INFINITY;
  scene_select(&s, 8, &params);
  MRGI_CHECK(s.layout.level_count == 1);
  const float values[5][3] = { { 7, 7, 7 }, { 1, 2, 3 }, { 4, 8, 12 }, { 6, 0, 3 }, { 0, 3, 9 } };
  const int32_t where[5][2] = { { 1, 1 }, { 5, 5 }, { 6, 5 }, { 3, 6 }, { 4, 7 } };
  for (int k = 0; k < 5; ++k)
  {
    const size_t t = mrgi_multires_index(&s.layout, 0, where[k][0], where[k][1]);
    MRGI_CHECK(s.mask[t] == 1);
    memcpy(s.illumination + 4 * t, values[k], sizeof(values[k]));
  }
  mrgi_image out = scene_upsample(&s, MRGI_UPSAMPLE_TENT, 1.0f);
  for (int c = 0; c < 3; ++c)
  {
    /* next to empty texels only: keeps its value exactly */
    MRGI_CHECK(mrgi_image_at(&out, 1, 1)[c] == values[0][c]);
    /* edge neighbours: (4 v + 2 u) / 6 */
    MRGI_CHECK_NEAR(mrgi_image_at(&out, 5, 5)[c], (4 * values[1][c] + 2 * values[2][c]) / 6.0, 1e-6);
    MRGI_CHECK_NEAR(mrgi_image_at(&out, 6, 5)[c], (4 * values[2][c] + 2 * values[1][c]) / 6.0, 1e-6);
    /* corner neighbours: (4 v + u) / 5 */
    MRGI_CHECK_NEAR(mrgi_image_at(&out, 3, 6)[c], (4 * values[3][c] + values[4][c]) / 5.0, 1e-6);
    MRGI_CHECK_NEAR(mrgi_image_at(&out, 4, 7)[c], (4 * values[4][c] + values[3][c]) / 5.0, 1e-6);
    MRGI_CHECK(mrgi_image_at(&out, 0, 0)[c] == 0.0f);
    MRGI_CHECK(mrgi_image_at(&out, 2, 2)[c] == 0.0f); /* empty neighbour receives nothing */
  }
  mrgi_image_destroy(&out);
  scene_free(&s);
}

/* Two surfaces with a depth step (and a background strip) lit 1 and 5:
 * after upsampling every pixel has its own surface's value exactly. */
static void test_no_leak(void)
{
  for (int variant = 0; variant < 8; ++variant)
  {
    scene s;
    const int32_t W = 64 + 5 * variant;
    const int32_t H = 48 + 3 * variant;
    scene_alloc(&s, W, H);
    const int32_t step = 37 + variant;
    for (int32_t y = 0; y < H; ++y)
    {
      for (int32_t x = 0; x < W; ++x)
      {
        const int32_t surface = (y == 20 && x > 5) ? -1 : (x < step ? 0 : 1);
        scene_set(&s, x, y, surface == 0 ? 3.0f + 0.001f * (float)y : 9.0f, surface);
      }
    }
    mrgi_multires_params params;
    mrgi_multires_params_default(&params);
    params.balance = variant % 2;
    params.finest_level = variant / 4;
    scene_select(&s, 8, &params);
    const float lit[2] = { 1.0f, 5.0f };
    int64_t coarse = 0;
    for (int32_t i = 0; i < s.layout.level_count; ++i)
    {
      for (int32_t y = 0; y < s.layout.level_height[i]; ++y)
      {
        for (int32_t x = 0; x < s.layout.level_width[i]; ++x)
        {
          const size_t t = mrgi_multires_index(&s.layout, i, x, y);
          if (!s.mask[t])
          {
            continue;
          }
          coarse += i > 0;
          /* the value of the surface of the texel's first valid pixel; a
           * selected texel above the finest level covers one surface only */
          int32_t surface = -1;
          for (int32_t py = y << i; py < ((y + 1) << i) && py < H; ++py)
          {
            for (int32_t px = x << i; px < ((x + 1) << i) && px < W; ++px)
            {
              const int32_t here = s.surface[(size_t)py * (size_t)W + (size_t)px];
              if (here >= 0 && surface < 0)
              {
                surface = here;
              }
              if (i > params.finest_level && here >= 0)
              {
                MRGI_CHECK(here == surface);
              }
            }
          }
          MRGI_CHECK(surface >= 0);
          for (int c = 0; c < 3; ++c)
          {
            s.illumination[4 * t + (size_t)c] = lit[surface];
          }
        }
      }
    }
    MRGI_CHECK(coarse > 0); /* the test exercises upsampling */
    for (int mode = 0; mode < 2; ++mode)
    {
      mrgi_image out = scene_upsample(&s, mode, 50.0f);
      for (int32_t y = 0; y < H; ++y)
      {
        for (int32_t x = 0; x < W; ++x)
        {
          const int32_t surface = s.surface[(size_t)y * (size_t)W + (size_t)x];
          if (params.finest_level > 0 && surface >= 0)
          {
            /* a selected mixed or stepped texel at the finest level carries one value */
            continue;
          }
          const float expected = surface < 0 ? 0.0f : lit[surface];
          MRGI_CHECK(mrgi_image_at(&out, x, y)[0] == expected);
        }
      }
      mrgi_image_destroy(&out);
    }
    scene_free(&s);
  }
}

/* Threshold 0 (finest = 0): every valid pixel gathers and is DISCONTINUOUS:
 * the upsampling is the identity, in both modes. */
static void test_identity(void)
{
  for (int run = 0; run < 50; ++run)
  {
    scene s;
    random_scene(&s);
    mrgi_multires_params params;
    mrgi_multires_params_default(&params);
    params.depth_threshold = 0.0;
    params.balance = rng_int(0, 1);
    scene_select(&s, rng_int(1, 16), &params);
    for (int32_t y = 0; y < s.height; ++y)
    {
      for (int32_t x = 0; x < s.width; ++x)
      {
        const size_t t = mrgi_multires_index(&s.layout, 0, x, y);
        for (int c = 0; c < 4; ++c)
        {
          s.illumination[4 * t + (size_t)c] = (float)rng_unit() * 10.0f;
        }
      }
    }
    for (int mode = 0; mode < 2; ++mode)
    {
      mrgi_image out = scene_upsample(&s, mode, 100.0f);
      for (int32_t y = 0; y < s.height; ++y)
      {
        for (int32_t x = 0; x < s.width; ++x)
        {
          const size_t t = mrgi_multires_index(&s.layout, 0, x, y);
          const int valid = s.surface[(size_t)y * (size_t)s.width + (size_t)x] >= 0;
          MRGI_CHECK(s.mask[t] == valid);
          for (int c = 0; c < 3; ++c)
          {
            MRGI_CHECK(mrgi_image_at(&out, x, y)[c] == (valid ? s.illumination[4 * t + (size_t)c] : 0.0f));
          }
        }
      }
      mrgi_image_destroy(&out);
    }
    scene_free(&s);
  }
}

/* Mask-weighted mode: weight 1 equals the tent; heavier weights bring the
 * result closer to the finer level's own gathered values. */
static void test_mask_weighted(void)
{
  double distance_light = 0.0;
  double distance_heavy = 0.0;
  for (int run = 0; run < 100; ++run)
  {
    scene s;
    random_scene(&s);
    mrgi_multires_params params;
    mrgi_multires_params_default(&params);
    params.depth_threshold = 0.5;
    scene_select(&s, rng_int(2, 8), &params);
    for (size_t t = 0; t < s.texels; ++t)
    {
      if (s.mask[t])
      {
        for (int c = 0; c < 3; ++c)
        {
          s.illumination[4 * t + (size_t)c] = (float)rng_unit();
        }
      }
    }
    mrgi_image tent = scene_upsample(&s, MRGI_UPSAMPLE_TENT, 1.0f);
    mrgi_image one = scene_upsample(&s, MRGI_UPSAMPLE_MASK_WEIGHTED, 1.0f);
    mrgi_image heavy = scene_upsample(&s, MRGI_UPSAMPLE_MASK_WEIGHTED, 1000.0f);
    for (int32_t y = 0; y < s.height; ++y)
    {
      for (int32_t x = 0; x < s.width; ++x)
      {
        const size_t t = mrgi_multires_index(&s.layout, 0, x, y);
        for (int c = 0; c < 3; ++c)
        {
          MRGI_CHECK_NEAR(mrgi_image_at(&one, x, y)[c], mrgi_image_at(&tent, x, y)[c], 1e-5);
          if (s.mask[t])
          {
            const double own = s.illumination[4 * t + (size_t)c];
            distance_light += fabs(mrgi_image_at(&tent, x, y)[c] - own);
            distance_heavy += fabs(mrgi_image_at(&heavy, x, y)[c] - own);
          }
          /* convex combination: stays within the range of the data */
          MRGI_CHECK(mrgi_image_at(&heavy, x, y)[c] >= 0.0f && mrgi_image_at(&heavy, x, y)[c] <= 1.0f);
        }
      }
    }
    mrgi_image_destroy(&tent);
    mrgi_image_destroy(&one);
    mrgi_image_destroy(&heavy);
    scene_free(&s);
  }
  printf("mask-weighted: distance to level-0 gathered values, tent %.3f, weight 1000 %.3f\n",
         distance_light, distance_heavy);
  MRGI_CHECK(distance_heavy < distance_light);
}

static void test_bad_input(void)
{
  scene s;
  scene_alloc(&s, 9, 7);
  for (int32_t y = 0; y < 7; ++y)
  {
    for (int32_t x = 0; x < 9; ++x)
    {
      scene_set(&s, x, y, 2.0f, 0);
    }
  }
  mrgi_multires_params params;
  mrgi_multires_params_default(&params);
  scene_select(&s, 2, &params);
  mrgi_image out;
  mrgi_error err;
  mrgi_upsample_params up;
  mrgi_upsample_params_default(&up);
  MRGI_CHECK(up.mode == MRGI_UPSAMPLE_TENT && up.mask_weight == MRGI_UPSAMPLE_DEFAULT_MASK_WEIGHT);
  MRGI_CHECK(mrgi_upsample(&s.layout, s.flags, s.texels, s.mask, s.texels, s.illumination,
                           s.texels * 4, 4, NULL, &out, &err) == MRGI_OK);
  mrgi_image_destroy(&out);
  MRGI_CHECK(mrgi_upsample(&s.layout, s.flags, s.texels, s.mask, s.texels, s.illumination,
                           s.texels * 3, 3, &up, &out, &err) == MRGI_OK);
  mrgi_image_destroy(&out);
  MRGI_CHECK(mrgi_upsample(&s.layout, s.flags, s.texels, s.mask, s.texels, s.illumination,
                           s.texels * 4, 4, &up, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_upsample(NULL, s.flags, s.texels, s.mask, s.texels, s.illumination,
                           s.texels * 4, 4, &up, &out, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(out.pixels == NULL);
  MRGI_CHECK(mrgi_upsample(&s.layout, s.flags, s.texels, s.mask, s.texels, s.illumination,
                           s.texels * 4 - 1, 4, &up, &out, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "illumination") != NULL);
  MRGI_CHECK(mrgi_upsample(&s.layout, s.flags, s.texels, s.mask, s.texels, s.illumination,
                           s.texels * 4, 2, &up, &out, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "channels") != NULL);
  MRGI_CHECK(mrgi_upsample(&s.layout, s.flags, s.texels - 1, s.mask, s.texels, s.illumination,
                           s.texels * 4, 4, &up, &out, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "flags") != NULL);
  MRGI_CHECK(mrgi_upsample(&s.layout, s.flags, s.texels, NULL, s.texels, s.illumination,
                           s.texels * 4, 4, &up, &out, &err) == MRGI_ERR_INVALID_ARGUMENT);
  up.mode = 7;
  MRGI_CHECK(mrgi_upsample(&s.layout, s.flags, s.texels, s.mask, s.texels, s.illumination,
                           s.texels * 4, 4, &up, &out, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "mode") != NULL);
  up.mode = MRGI_UPSAMPLE_MASK_WEIGHTED;
  up.mask_weight = 0.5f;
  MRGI_CHECK(mrgi_upsample(&s.layout, s.flags, s.texels, s.mask, s.texels, s.illumination,
                           s.texels * 4, 4, &up, &out, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "mask weight") != NULL);
  up.mask_weight = NAN;
  MRGI_CHECK(mrgi_upsample(&s.layout, s.flags, s.texels, s.mask, s.texels, s.illumination,
                           s.texels * 4, 4, &up, &out, &err) == MRGI_ERR_INVALID_ARGUMENT);
  mrgi_multires_layout tampered = s.layout;
  tampered.level_offset[1] += 1;
  up.mask_weight = 10.0f;
  MRGI_CHECK(mrgi_upsample(&tampered, s.flags, s.texels, s.mask, s.texels, s.illumination,
                           s.texels * 4, 4, &up, &out, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "layout") != NULL);
  scene_free(&s);
}

/* nichols-wyman-2009 eq. 2: factor alpha max(V.N, 0) + 1 - alpha, never NaN. */
static void test_surface_detail(void)
{
  const float facing[3] = { 0.0f, 0.0f, 1.0f };
  const float away[3] = { 0.0f, 0.0f, -1.0f };
  const float p[3] = { 0.0f, 0.0f, -10.0f };
  const float off_axis[3] = { 10.0f, 0.0f, -10.0f };
  MRGI_CHECK(mrgi_surface_detail_factor(p, facing, 0, 0.5f) == 1.0f);
  MRGI_CHECK(mrgi_surface_detail_factor(p, away, 0, 0.5f) == 0.5f);
  MRGI_CHECK(mrgi_surface_detail_factor(p, away, 0, 0.0f) == 1.0f);
  /* 45 degrees off axis: V.N = cos 45 under perspective, 1 under parallel. */
  const float f = mrgi_surface_detail_factor(off_axis, facing, 0, 1.0f);
  MRGI_CHECK(fabsf(f - 0.70710678f) < 1e-6f);
  MRGI_CHECK(mrgi_surface_detail_factor(off_axis, facing, 1, 1.0f) == 1.0f);
  /* Unnormalised normals are normalised. */
  const float long_normal[3] = { 0.0f, 0.0f, 1e38f };
  MRGI_CHECK(mrgi_surface_detail_factor(p, long_normal, 0, 1.0f) == 1.0f);
  /* Degenerate input: the edge-on factor 1 - alpha, or V = +z at the eye. */
  const float zero[3] = { 0.0f, 0.0f, 0.0f };
  const float nan3[3] = { NAN, NAN, NAN };
  const float inf3[3] = { INFINITY, 0.0f, 0.0f };
  MRGI_CHECK(mrgi_surface_detail_factor(p, zero, 0, 0.25f) == 0.75f);
  MRGI_CHECK(mrgi_surface_detail_factor(p, nan3, 0, 0.25f) == 0.75f);
  MRGI_CHECK(mrgi_surface_detail_factor(p, inf3, 0, 0.25f) == 0.75f);
  MRGI_CHECK(mrgi_surface_detail_factor(zero, facing, 0, 0.25f) == 1.0f);
  MRGI_CHECK(mrgi_surface_detail_factor(nan3, facing, 0, 0.25f) == 1.0f);
  /* Tiny and huge scene scales give the same factor. */
  const float tiny[3] = { 1e-30f, 0.0f, -1e-30f };
  const float huge[3] = { 1e30f, 0.0f, -1e30f };
  MRGI_CHECK(fabsf(mrgi_surface_detail_factor(tiny, facing, 0, 1.0f) - f) < 1e-6f);
  MRGI_CHECK(fabsf(mrgi_surface_detail_factor(huge, facing, 0, 1.0f) - f) < 1e-6f);
}

int main(int argc, char** argv)
{
  static const mrgi_test_case cases[] = {
    MRGI_TEST_CASE(test_surface_detail),
    MRGI_TEST_CASE(test_constant),
    MRGI_TEST_CASE(test_weights_and_empty_neighbours),
    MRGI_TEST_CASE(test_no_leak),
    MRGI_TEST_CASE(test_identity),
    MRGI_TEST_CASE(test_mask_weighted),
    MRGI_TEST_CASE(test_bad_input),
  };
  return MRGI_TEST_MAIN(argc, argv, cases);
}
