/* Tests of mrgi_multires: layout numbers (NPOT, 1x1), min-max mipmaps by
 * hand, thresholds 0 and +inf, iterative == one-pass selection on random
 * G-buffers with and without the balance rule, the balance property,
 * coverage (each valid pixel in exactly one selected texel), scale and
 * projection invariance, statistics and bad input. */
#include "mrgi_multires.h"

#include "mrgi_test.h"

#include <float.h>
#include <math.h>
#include <string.h>

/* ---- small deterministic random numbers ---- */
static uint64_t rng_state = 88172645463325252ull;
static uint32_t rng_u32(void)
{
  rng_state ^= rng_state << 13;
  rng_state ^= rng_state >> 7;
  rng_state ^= rng_state << 17;
  return (uint32_t)(rng_state >> 11);
}
static double rng_unit(void) /* [0, 1) */
{
  return (double)rng_u32() / 4294967296.0;
}
static int32_t rng_int(int32_t lo, int32_t hi) /* [lo, hi] */
{
  return lo + (int32_t)(rng_u32() % (uint32_t)(hi - lo + 1));
}

/* ---- G-buffers ---- */
typedef struct gbuffer
{
  int32_t width;
  int32_t height;
  float* position;
  float* normal;
} gbuffer;

static gbuffer gbuffer_make(int32_t width, int32_t height)
{
  gbuffer g = { width, height, NULL, NULL };
  g.position = (float*)calloc((size_t)width * (size_t)height * 4, sizeof(float));
  g.normal = (float*)calloc((size_t)width * (size_t)height * 4, sizeof(float));
  MRGI_CHECK(g.position && g.normal);
  return g;
}

static void gbuffer_free(gbuffer* g)
{
  free(g->position);
  free(g->normal);
  g->position = g->normal = NULL;
}

static void gbuffer_set(gbuffer* g, int32_t x, int32_t y, float depth, const float n[3], int valid)
{
  float* p = g->position + 4 * ((size_t)y * (size_t)g->width + (size_t)x);
  float* q = g->normal + 4 * ((size_t)y * (size_t)g->width + (size_t)x);
  p[0] = (float)x * 0.01f * depth;
  p[1] = (float)y * 0.01f * depth;
  p[2] = -depth;
  p[3] = valid ? MRGI_GBUFFER_VALID : 0.0f;
  q[0] = n[0];
  q[1] = n[1];
  q[2] = n[2];
  q[3] = 0.0f;
}

static mrgi_gather_receivers gbuffer_view(const gbuffer* g)
{
  mrgi_gather_receivers r = { g->width, g->height, g->position, g->normal };
  return r;
}

/* Random scene: a few regions split by random lines, each a tilted plane
 * of depth with its own normal; background holes; one-pixel features;
 * far-plane pixels. Depths in units of `scale`. */
static void random_scene(gbuffer* g, double scale, int perspective)
{
  const int regions = rng_int(1, 4);
  double base[4], gx[4], gy[4];
  float normal[4][3];
  for (int r = 0; r < regions; ++r)
  {
    base[r] = (perspective ? 2.0 + 20.0 * rng_unit() : -5.0 + 20.0 * rng_unit());
    gx[r] = (rng_unit() - 0.5) * 0.2;
    gy[r] = (rng_unit() - 0.5) * 0.2;
    double n[3] = { rng_unit() - 0.5, rng_unit() - 0.5, 0.3 + rng_unit() };
    const double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int c = 0; c < 3; ++c)
    {
      normal[r][c] = (float)(n[c] / len);
    }
  }
  /* splitting lines a x + b y < c */
  double la[3], lb[3], lc[3];
  for (int k = 0; k < 3; ++k)
  {
    la[k] = rng_unit() - 0.5;
    lb[k] = rng_unit() - 0.5;
    lc[k] = (rng_unit() - 0.5) * 0.3 * (g->width + g->height) +
            la[k] * g->width * 0.5 + lb[k] * g->height * 0.5;
  }
  const int holes = rng_int(0, 2);
  int32_t hx0[2], hy0[2], hx1[2], hy1[2];
  for (int k = 0; k < holes; ++k)
  {
    hx0[k] = rng_int(0, g->width - 1);
    hy0[k] = rng_int(0, g->height - 1);
    hx1[k] = hx0[k] + rng_int(0, g->width / 2);
    hy1[k] = hy0[k] + rng_int(0, g->height / 2);
  }
  const int all_background = rng_int(0, 30) == 0;
  for (int32_t y = 0; y < g->height; ++y)
  {
    for (int32_t x = 0; x < g->width; ++x)
    {
      int r = 0;
      for (int k = 0; k < 3; ++k)
      {
        if (la[k] * x + lb[k] * y < lc[k])
        {
          r = (r + k + 1) % regions;
        }
      }
      double d = base[r] + gx[r] * x + gy[r] * y;
      int valid = !all_background;
      for (int k = 0; k < holes; ++k)
      {
        if (x >= hx0[k] && x <= hx1[k] && y >= hy0[k] && y <= hy1[k])
        {
          valid = 0;
        }
      }
      const uint32_t roll = rng_u32() % 100;
      if (roll < 2)
      {
        valid = 0; /* scattered background pixel */
      }
      else if (roll < 4)
      {
        d *= 3.0; /* one-pixel feature */
      }
      else if (roll < 5)
      {
        d = perspective ? 1000.0 : 1000.0; /* far plane */
      }
      float n[3] = { normal[r][0], normal[r][1], normal[r][2] };
      if (roll >= 5 && roll < 7)
      {
        n[0] = -n[0]; /* one-pixel normal feature */
      }
      gbuffer_set(g, x, y, (float)(d * scale), n, valid);
    }
  }
}

/* ---- pipeline helper ---- */
typedef struct selection_run
{
  mrgi_multires_layout layout;
  mrgi_multires_mipmap mipmap;
  uint8_t* flags;
  uint8_t* mask_one_pass;
  uint8_t* mask_iterative;
  size_t texels;
} selection_run;

static void run_selection(selection_run* run, const gbuffer* g, int32_t coarsest_side,
                          const float ab[2], const mrgi_multires_params* params)
{
  mrgi_error err;
  MRGI_CHECK(mrgi_multires_layout_init(&run->layout, g->width, g->height, coarsest_side, &err) ==
             MRGI_OK);
  const mrgi_gather_receivers view = gbuffer_view(g);
  MRGI_CHECK(mrgi_multires_mipmap_build(&run->layout, &view, ab, &run->mipmap, &err) == MRGI_OK);
  run->texels = (size_t)mrgi_multires_texel_count(&run->layout);
  run->flags = (uint8_t*)malloc(run->texels);
  run->mask_one_pass = (uint8_t*)malloc(run->texels);
  run->mask_iterative = (uint8_t*)malloc(run->texels);
  MRGI_CHECK(run->flags && run->mask_one_pass && run->mask_iterative);
  MRGI_CHECK(mrgi_multires_flags_compute(&run->mipmap, params, run->flags, run->texels, &err) ==
             MRGI_OK);
  MRGI_CHECK(mrgi_multires_select_one_pass(&run->layout, run->flags, run->texels,
                                           params->finest_level, run->mask_one_pass, run->texels,
                                           &err) == MRGI_OK);
  MRGI_CHECK(mrgi_multires_select_iterative(&run->layout, run->flags, run->texels,
                                            params->finest_level, run->mask_iterative,
                                            run->texels, &err) == MRGI_OK);
}

static void free_selection(selection_run* run)
{
  mrgi_multires_mipmap_destroy(&run->mipmap);
  free(run->flags);
  free(run->mask_one_pass);
  free(run->mask_iterative);
}

/* Fill `levels` (W*H) with the level of the selected texel covering each
 * pixel (-1: none); checks that no pixel is covered twice, that every valid
 * pixel is covered and that nothing below finest is selected. */
static void coverage(const selection_run* run, const uint8_t* mask, int32_t finest, int32_t* levels)
{
  const mrgi_multires_layout* L = &run->layout;
  for (size_t p = 0; p < (size_t)L->width * (size_t)L->height; ++p)
  {
    levels[p] = -1;
  }
  for (int32_t i = 0; i < L->level_count; ++i)
  {
    for (int32_t y = 0; y < L->level_height[i]; ++y)
    {
      for (int32_t x = 0; x < L->level_width[i]; ++x)
      {
        const size_t t = mrgi_multires_index(L, i, x, y);
        if (!mask[t])
        {
          continue;
        }
        MRGI_CHECK(mask[t] == 1);
        MRGI_CHECK(i >= finest);
        MRGI_CHECK(run->flags[t] & MRGI_MULTIRES_FLAG_NONEMPTY);
        const int32_t x1 = ((x + 1) << i) < L->width ? ((x + 1) << i) : L->width;
        const int32_t y1 = ((y + 1) << i) < L->height ? ((y + 1) << i) : L->height;
        for (int32_t py = y << i; py < y1; ++py)
        {
          for (int32_t px = x << i; px < x1; ++px)
          {
            MRGI_CHECK(levels[(size_t)py * (size_t)L->width + (size_t)px] == -1);
            levels[(size_t)py * (size_t)L->width + (size_t)px] = i;
          }
        }
      }
    }
  }
  for (int32_t y = 0; y < L->height; ++y)
  {
    for (int32_t x = 0; x < L->width; ++x)
    {
      const int valid = (run->flags[mrgi_multires_index(L, 0, x, y)] &
                         MRGI_MULTIRES_FLAG_NONEMPTY) != 0;
      if (valid)
      {
        MRGI_CHECK(levels[(size_t)y * (size_t)L->width + (size_t)x] >= 0);
      }
    }
  }
  /* Texels outside the levels are never selected. */
  for (int32_t Y = 0; Y < L->total_height; ++Y)
  {
    for (int32_t X = 0; X < L->total_width; ++X)
    {
      if (!mrgi_multires_locate(L, X, Y, NULL, NULL, NULL))
      {
        MRGI_CHECK(mask[(size_t)Y * (size_t)L->total_width + (size_t)X] == 0);
        MRGI_CHECK(run->flags[(size_t)Y * (size_t)L->total_width + (size_t)X] == 0);
      }
    }
  }
}

/* Largest level difference between 8-adjacent covered pixels. */
static int32_t max_level_jump(const mrgi_multires_layout* L, const int32_t* levels)
{
  int32_t jump = 0;
  for (int32_t y = 0; y < L->height; ++y)
  {
    for (int32_t x = 0; x < L->width; ++x)
    {
      const int32_t a = levels[(size_t)y * (size_t)L->width + (size_t)x];
      if (a < 0)
      {
        continue;
      }
      for (int32_t dy = -1; dy <= 1; ++dy)
      {
        for (int32_t dx = -1; dx <= 1; ++dx)
        {
          const int32_t qx = x + dx;
          const int32_t qy = y + dy;
          if (qx < 0 || qy < 0 || qx >= L->width || qy >= L->height)
          {
            continue;
          }
          const int32_t b = levels[(size_t)qy * (size_t)L->width + (size_t)qx];
          if (b >= 0 && abs(a - b) > jump)
          {
            jump = abs(a - b);
          }
        }
      }
    }
  }
  return jump;
}

/* ---- tests ---- */
static void test_layout(void)
{
  mrgi_multires_layout L;
  mrgi_error err;
  MRGI_CHECK(mrgi_multires_layout_init(&L, 97, 61, 16, &err) == MRGI_OK);
  MRGI_CHECK(L.level_count == 4);
  const int32_t w[4] = { 97, 49, 25, 13 };
  const int32_t h[4] = { 61, 31, 16, 8 };
  const int32_t o[4] = { 0, 97, 146, 171 };
  for (int i = 0; i < 4; ++i)
  {
    MRGI_CHECK(L.level_width[i] == w[i] && L.level_height[i] == h[i] && L.level_offset[i] == o[i]);
  }
  MRGI_CHECK(L.level_width[4] == 0);
  MRGI_CHECK(L.total_width == 184 && L.total_height == 61);
  MRGI_CHECK(mrgi_multires_texel_count(&L) == 184 * 61);
  MRGI_CHECK(mrgi_multires_index(&L, 2, 3, 4) == (size_t)4 * 184 + 146 + 3);
  int32_t level = -1, x = -1, y = -1;
  MRGI_CHECK(mrgi_multires_locate(&L, 150, 15, &level, &x, &y) == 1);
  MRGI_CHECK(level == 2 && x == 4 && y == 15);
  MRGI_CHECK(mrgi_multires_locate(&L, 150, 16, &level, &x, &y) == 0); /* above level 2 */
  MRGI_CHECK(mrgi_multires_locate(&L, 183, 7, &level, &x, &y) == 1 && level == 3 && x == 12);
  MRGI_CHECK(mrgi_multires_locate(&L, 184, 0, NULL, NULL, NULL) == 0);
  MRGI_CHECK(mrgi_multires_locate(&L, -1, 0, NULL, NULL, NULL) == 0);
  MRGI_CHECK(mrgi_multires_locate(&L, 96, 60, &level, NULL, NULL) == 1 && level == 0);

  MRGI_CHECK(mrgi_multires_layout_init(&L, 1, 1, 16, &err) == MRGI_OK);
  MRGI_CHECK(L.level_count == 1 && L.total_width == 1 && L.total_height == 1);
  MRGI_CHECK(mrgi_multires_layout_init(&L, 1, 1, 1, &err) == MRGI_OK && L.level_count == 1);
  MRGI_CHECK(mrgi_multires_layout_init(&L, 16, 16, 16, &err) == MRGI_OK && L.level_count == 1);
  MRGI_CHECK(mrgi_multires_layout_init(&L, 17, 16, 16, &err) == MRGI_OK && L.level_count == 2);
  MRGI_CHECK(L.level_width[1] == 9 && L.level_height[1] == 8 && L.total_width == 26);
  MRGI_CHECK(mrgi_multires_layout_init(&L, 1024, 1024, 16, &err) == MRGI_OK);
  MRGI_CHECK(L.level_count == 7 && L.total_width == 2032 && L.level_width[6] == 16);
  MRGI_CHECK(mrgi_multires_layout_init(&L, 1, 1000, 16, &err) == MRGI_OK);
  MRGI_CHECK(L.level_count == 7 && L.level_height[6] == 16 && L.total_width == 7);
  MRGI_CHECK(mrgi_multires_layout_init(&L, MRGI_IMAGE_MAX_DIMENSION, 3, 1, &err) == MRGI_OK);
  MRGI_CHECK(L.level_count == 21 && L.level_width[20] == 1 && L.level_height[20] == 1);
  /* ceil at every level, nested: w_{i+1} = ceil(w_i / 2) = ceil(W / 2^(i+1)) */
  for (int32_t W = 1; W < 300; W += 7)
  {
    MRGI_CHECK(mrgi_multires_layout_init(&L, W, 300 - W, 2, &err) == MRGI_OK);
    int32_t offset = 0;
    for (int32_t i = 0; i < L.level_count; ++i)
    {
      MRGI_CHECK(L.level_width[i] == (W + (1 << i) - 1) >> i);
      MRGI_CHECK(L.level_height[i] == (300 - W + (1 << i) - 1) >> i);
      MRGI_CHECK(L.level_offset[i] == offset);
      offset += L.level_width[i];
    }
    MRGI_CHECK(L.total_width == offset);
    const int32_t last = L.level_count - 1;
    MRGI_CHECK(L.level_width[last] <= 2 && L.level_height[last] <= 2);
    MRGI_CHECK(last == 0 || L.level_width[last - 1] > 2 || L.level_height[last - 1] > 2);
  }
  /* bad input */
  MRGI_CHECK(mrgi_multires_layout_init(&L, 0, 5, 16, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "0 x 5") != NULL);
  MRGI_CHECK(L.level_count == 0);
  MRGI_CHECK(mrgi_multires_layout_init(&L, 5, MRGI_IMAGE_MAX_DIMENSION + 1, 16, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_multires_layout_init(&L, 5, 5, 0, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "coarsest") != NULL);
  MRGI_CHECK(mrgi_multires_layout_init(NULL, 5, 5, 16, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_multires_texel_count(NULL) == 0);
}

static void test_pixel_size(void)
{
  mrgi_error err;
  float ab[2];
  mrgi_multires_projection proj = { 0, 90.0, 1.0 };
  MRGI_CHECK(mrgi_multires_pixel_size_coefficients(&proj, 100, ab, &err) == MRGI_OK);
  MRGI_CHECK_NEAR(ab[0], 0.02, 1e-7);
  MRGI_CHECK(ab[1] == 0.0f);
  proj.parallel = 1;
  proj.parallel_scale = 5.0;
  MRGI_CHECK(mrgi_multires_pixel_size_coefficients(&proj, 100, ab, &err) == MRGI_OK);
  MRGI_CHECK(ab[0] == 0.0f && ab[1] == 0.1f);
  proj.parallel_scale = 0.0;
  MRGI_CHECK(mrgi_multires_pixel_size_coefficients(&proj, 100, ab, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "parallel scale") != NULL);
  proj.parallel_scale = INFINITY;
  MRGI_CHECK(mrgi_multires_pixel_size_coefficients(&proj, 100, ab, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  proj.parallel = 0;
  proj.view_angle_deg = 180.0;
  MRGI_CHECK(mrgi_multires_pixel_size_coefficients(&proj, 100, ab, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "view angle") != NULL);
  proj.view_angle_deg = NAN;
  MRGI_CHECK(mrgi_multires_pixel_size_coefficients(&proj, 100, ab, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  proj.view_angle_deg = 30.0;
  MRGI_CHECK(mrgi_multires_pixel_size_coefficients(&proj, 0, ab, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_multires_pixel_size_coefficients(NULL, 10, ab, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_multires_pixel_size_coefficients(&proj, 10, NULL, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);

  MRGI_CHECK(mrgi_multires_threshold_uniform(2.5) == 2.5f);
  MRGI_CHECK(mrgi_multires_threshold_uniform(0.0) == 0.0f);
  MRGI_CHECK(mrgi_multires_threshold_uniform(INFINITY) == MRGI_MULTIRES_THRESHOLD_OFF);
  MRGI_CHECK(mrgi_multires_threshold_uniform(1e300) == MRGI_MULTIRES_THRESHOLD_OFF);
  MRGI_CHECK(MRGI_MULTIRES_FLT_MAX == FLT_MAX && MRGI_MULTIRES_MIN_PIXEL_SIZE == FLT_MIN);
}

/* 3 x 3 image, parallel projection with pixel size 1 (a = 0, b = 1):
 *   row 2 (top):    d = 5  5  .       ('.' = background)
 *   row 1:          d = 4  4  9
 *   row 0 (bottom): d = 1  2  3
 * levels: 3x3, 2x2, 1x1 (coarsest side 1). */
static void test_mipmap_by_hand(void)
{
  gbuffer g = gbuffer_make(3, 3);
  const float depth[3][3] = { { 1, 2, 3 }, { 4, 4, 9 }, { 5, 5, 0 } };
  const float up[3] = { 0, 0, 2 }; /* not unit: normalised to (0,0,1) */
  const float tilted[3] = { 0.6f, 0, 0.8f };
  for (int32_t y = 0; y < 3; ++y)
  {
    for (int32_t x = 0; x < 3; ++x)
    {
      gbuffer_set(&g, x, y, depth[y][x], (x == 2 && y == 1) ? tilted : up, !(x == 2 && y == 2));
    }
  }
  mrgi_multires_layout L;
  MRGI_CHECK(mrgi_multires_layout_init(&L, 3, 3, 1, NULL) == MRGI_OK);
  MRGI_CHECK(L.level_count == 3 && L.total_width == 6);
  const float ab[2] = { 0.0f, 1.0f };
  mrgi_multires_mipmap m;
  const mrgi_gather_receivers view = gbuffer_view(&g);
  mrgi_error err;
  MRGI_CHECK(mrgi_multires_mipmap_build(&L, &view, ab, &m, &err) == MRGI_OK);
  const float* A = m.texture[MRGI_MULTIRES_TEX_DEPTH];
  const float* NMIN = m.texture[MRGI_MULTIRES_TEX_NORMAL_MIN];
  const float* NMAX = m.texture[MRGI_MULTIRES_TEX_NORMAL_MAX];
#define TEX(arr, i, x, y, c) (arr)[4 * mrgi_multires_index(&L, (i), (x), (y)) + (c)]
  /* level 0: depth, derivative g = max |d_q - d_p| over valid 8-neighbours */
  MRGI_CHECK(TEX(A, 0, 0, 0, 0) == 1.0f && TEX(A, 0, 0, 0, 1) == 1.0f);
  MRGI_CHECK(TEX(A, 0, 0, 0, 2) == 3.0f);  /* neighbours 2, 4, 4 */
  MRGI_CHECK(TEX(A, 0, 1, 1, 2) == 5.0f);  /* 4 vs 1,2,3,4,9,5,5 */
  MRGI_CHECK(TEX(A, 0, 2, 1, 2) == 7.0f);  /* 9 vs 2,3,4,5 (top-right is background) */
  MRGI_CHECK(TEX(A, 0, 1, 2, 2) == 4.0f);  /* 5 vs 4,4,9,5 */
  MRGI_CHECK(TEX(A, 0, 0, 0, 3) == (float)MRGI_MULTIRES_VALID_BIT);
  MRGI_CHECK(TEX(A, 0, 2, 2, 3) == (float)MRGI_MULTIRES_INVALID_BIT);
  MRGI_CHECK(TEX(A, 0, 2, 2, 0) == FLT_MAX && TEX(A, 0, 2, 2, 1) == -FLT_MAX);
  MRGI_CHECK(TEX(A, 0, 2, 2, 2) == 0.0f);
  MRGI_CHECK(TEX(NMIN, 0, 0, 0, 2) == 1.0f && TEX(NMAX, 0, 0, 0, 2) == 1.0f);
  MRGI_CHECK_NEAR(TEX(NMIN, 0, 2, 1, 0), 0.6, 1e-6);
  MRGI_CHECK(TEX(NMIN, 0, 2, 2, 0) == FLT_MAX && TEX(NMAX, 0, 2, 2, 1) == -FLT_MAX);
  /* level 1 (2x2): (0,0) covers d 1,2,4,4; (1,0) covers 3,9; (0,1) 5,5; (1,1) background only */
  MRGI_CHECK(TEX(A, 1, 0, 0, 0) == 1.0f && TEX(A, 1, 0, 0, 1) == 4.0f);
  MRGI_CHECK(TEX(A, 1, 0, 0, 2) == 7.0f);
  MRGI_CHECK(TEX(A, 1, 1, 0, 0) == 3.0f && TEX(A, 1, 1, 0, 1) == 9.0f);
  MRGI_CHECK(TEX(A, 1, 0, 1, 0) == 5.0f && TEX(A, 1, 0, 1, 1) == 5.0f);
  MRGI_CHECK(TEX(A, 1, 0, 1, 2) == 4.0f);
  MRGI_CHECK(TEX(A, 1, 1, 1, 3) == (float)MRGI_MULTIRES_INVALID_BIT);
  MRGI_CHECK(TEX(A, 1, 1, 0, 3) == (float)MRGI_MULTIRES_VALID_BIT);
  MRGI_CHECK_NEAR(TEX(NMIN, 1, 1, 0, 0), 0.0, 0);
  MRGI_CHECK_NEAR(TEX(NMAX, 1, 1, 0, 0), 0.6, 1e-6);
  MRGI_CHECK_NEAR(TEX(NMIN, 1, 1, 0, 2), 0.8, 1e-6);
  /* level 2 (1x1): everything */
  MRGI_CHECK(TEX(A, 2, 0, 0, 0) == 1.0f && TEX(A, 2, 0, 0, 1) == 9.0f);
  MRGI_CHECK(TEX(A, 2, 0, 0, 3) == (float)(MRGI_MULTIRES_VALID_BIT | MRGI_MULTIRES_INVALID_BIT));
  /* texels outside the levels are 0 */
  MRGI_CHECK(A[4 * (size_t)(2 * L.total_width + 4) + 0] == 0.0f); /* level 1 has 2 rows */

  /* Flags, normals off. g reaches 7 at (1,0) and (2,1) only. */
  uint8_t flags[18];
  mrgi_multires_params params;
  mrgi_multires_params_default(&params);
  params.depth_threshold = 7.5;
  params.normal_threshold = INFINITY;
  params.balance = 0;
  MRGI_CHECK(mrgi_multires_flags_compute(&m, &params, flags, sizeof(flags), &err) == MRGI_OK);
  /* no g reaches 7.5: only MIXED texels are discontinuous */
  for (int32_t i = 0; i < 3; ++i)
  {
    for (int32_t y = 0; y < L.level_height[i]; ++y)
    {
      for (int32_t x = 0; x < L.level_width[i]; ++x)
      {
        const uint8_t f = flags[mrgi_multires_index(&L, i, x, y)];
        const int mixed = i == 2;
        const int empty = (i == 0 && x == 2 && y == 2) || (i == 1 && x == 1 && y == 1);
        MRGI_CHECK(((f & MRGI_MULTIRES_FLAG_NONEMPTY) != 0) == !empty);
        MRGI_CHECK(((f & MRGI_MULTIRES_FLAG_MIXED) != 0) == mixed);
        MRGI_CHECK(((f & MRGI_MULTIRES_FLAG_DISCONTINUOUS) != 0) == mixed);
      }
    }
  }
  /* the top texel refines because of the children/mixing; level 1 texels don't */
  MRGI_CHECK(flags[mrgi_multires_index(&L, 2, 0, 0)] & MRGI_MULTIRES_FLAG_REFINE);
  MRGI_CHECK(!(flags[mrgi_multires_index(&L, 1, 0, 0)] & MRGI_MULTIRES_FLAG_REFINE));
  uint8_t mask[18];
  MRGI_CHECK(mrgi_multires_select_one_pass(&L, flags, 18, 0, mask, 18, &err) == MRGI_OK);
  int selected = 0;
  for (int k = 0; k < 18; ++k)
  {
    selected += mask[k];
  }
  MRGI_CHECK(selected == 3); /* the three non-empty level 1 texels */
  MRGI_CHECK(mask[mrgi_multires_index(&L, 1, 0, 0)] && mask[mrgi_multires_index(&L, 1, 1, 0)] &&
             mask[mrgi_multires_index(&L, 1, 0, 1)]);
  /* depth threshold 7: g = 7 hits (>=): every window containing (1,1) or (2,1) */
  params.depth_threshold = 7.0;
  MRGI_CHECK(mrgi_multires_flags_compute(&m, &params, flags, sizeof(flags), &err) == MRGI_OK);
  MRGI_CHECK(flags[mrgi_multires_index(&L, 0, 0, 1)] & MRGI_MULTIRES_FLAG_DISCONTINUOUS);
  MRGI_CHECK(!(flags[mrgi_multires_index(&L, 0, 0, 2)] & MRGI_MULTIRES_FLAG_DISCONTINUOUS));
  MRGI_CHECK(flags[mrgi_multires_index(&L, 1, 0, 1)] & MRGI_MULTIRES_FLAG_DISCONTINUOUS);
  /* normal threshold 0.5: the tilted pixel's x spread is 0.6; the level 0
   * windows that contain (2,1) are those of every pixel with x >= 1 */
  params.depth_threshold = INFINITY;
  params.normal_threshold = 0.5;
  MRGI_CHECK(mrgi_multires_flags_compute(&m, &params, flags, sizeof(flags), &err) == MRGI_OK);
  for (int32_t y = 0; y < 3; ++y)
  {
    for (int32_t x = 0; x < 3; ++x)
    {
      const uint8_t f = flags[mrgi_multires_index(&L, 0, x, y)];
      const int expected = x >= 1 && !(x == 2 && y == 2);
      MRGI_CHECK(((f & MRGI_MULTIRES_FLAG_DISCONTINUOUS) != 0) == expected);
    }
  }
  /* with the depth test off, the MIXED top texel is not discontinuous by itself */
  MRGI_CHECK(flags[mrgi_multires_index(&L, 2, 0, 0)] & MRGI_MULTIRES_FLAG_DISCONTINUOUS); /* normals */
  params.normal_threshold = INFINITY;
  MRGI_CHECK(mrgi_multires_flags_compute(&m, &params, flags, sizeof(flags), &err) == MRGI_OK);
  MRGI_CHECK(!(flags[mrgi_multires_index(&L, 2, 0, 0)] & MRGI_MULTIRES_FLAG_DISCONTINUOUS));
  MRGI_CHECK(!(flags[mrgi_multires_index(&L, 2, 0, 0)] & MRGI_MULTIRES_FLAG_REFINE));
#undef TEX
  mrgi_multires_mipmap_destroy(&m);
  mrgi_multires_mipmap_destroy(&m); /* idempotent */
  mrgi_multires_mipmap_destroy(NULL);
  gbuffer_free(&g);
}

/* Thresholds 0 and +inf on random scenes. */
static void test_threshold_extremes(void)
{
  for (int run_index = 0; run_index < 40; ++run_index)
  {
    gbuffer g = gbuffer_make(rng_int(1, 70), rng_int(1, 70));
    random_scene(&g, 1.0, 1);
    const float ab[2] = { 0.01f, 0.0f };
    mrgi_multires_params params;
    mrgi_multires_params_default(&params);
    params.balance = rng_int(0, 1);
    mrgi_multires_layout L;
    MRGI_CHECK(mrgi_multires_layout_init(&L, g.width, g.height, 4, NULL) == MRGI_OK);
    params.finest_level = rng_int(0, L.level_count - 1);

    /* 0: every non-empty texel of the finest level, nothing else */
    params.depth_threshold = 0.0;
    params.normal_threshold = run_index % 2 ? 0.0 : INFINITY;
    if (run_index % 2)
    {
      params.depth_threshold = INFINITY; /* normal threshold 0 alone does it too */
    }
    selection_run run;
    run_selection(&run, &g, 4, ab, &params);
    for (int32_t i = 0; i < L.level_count; ++i)
    {
      for (int32_t y = 0; y < L.level_height[i]; ++y)
      {
        for (int32_t x = 0; x < L.level_width[i]; ++x)
        {
          const size_t t = mrgi_multires_index(&L, i, x, y);
          const int nonempty = (run.flags[t] & MRGI_MULTIRES_FLAG_NONEMPTY) != 0;
          MRGI_CHECK(run.mask_one_pass[t] == (i == params.finest_level && nonempty));
          MRGI_CHECK(run.mask_iterative[t] == run.mask_one_pass[t]);
        }
      }
    }
    mrgi_multires_stats stats;
    MRGI_CHECK(mrgi_multires_stats_compute(&run.layout, run.flags, run.texels, run.mask_one_pass,
                                           run.texels, &stats, NULL) == MRGI_OK);
    if (params.finest_level == 0)
    {
      MRGI_CHECK(stats.selected_total == stats.valid_pixels);
      MRGI_CHECK(stats.valid_pixels == 0 || stats.work_fraction == 1.0);
    }
    free_selection(&run);

    /* +inf for both: the coarsest level everywhere */
    params.depth_threshold = INFINITY;
    params.normal_threshold = INFINITY;
    run_selection(&run, &g, 4, ab, &params);
    const int32_t c = L.level_count - 1;
    int64_t coarse_nonempty = 0;
    for (int32_t i = 0; i < L.level_count; ++i)
    {
      for (int32_t y = 0; y < L.level_height[i]; ++y)
      {
        for (int32_t x = 0; x < L.level_width[i]; ++x)
        {
          const size_t t = mrgi_multires_index(&L, i, x, y);
          const int nonempty = (run.flags[t] & MRGI_MULTIRES_FLAG_NONEMPTY) != 0;
          MRGI_CHECK(run.mask_one_pass[t] == (i == c && nonempty));
          MRGI_CHECK(run.mask_iterative[t] == run.mask_one_pass[t]);
          MRGI_CHECK(!(run.flags[t] & MRGI_MULTIRES_FLAG_DISCONTINUOUS));
          coarse_nonempty += i == c && nonempty;
        }
      }
    }
    MRGI_CHECK(mrgi_multires_stats_compute(&run.layout, run.flags, run.texels, run.mask_one_pass,
                                           run.texels, &stats, NULL) == MRGI_OK);
    MRGI_CHECK(stats.selected[c] == coarse_nonempty && stats.selected_total == coarse_nonempty);
    if (stats.valid_pixels > 0)
    {
      MRGI_CHECK_NEAR(stats.work_fraction, (double)coarse_nonempty / (double)stats.valid_pixels,
                      1e-15);
    }
    free_selection(&run);
    gbuffer_free(&g);
  }
}

/* Iterative == one pass, coverage, monotone flags, balance. */
static void test_selection_random(void)
{
  const double depth_thresholds[] = { 0.0, 0.05, 0.5, 2.0, 8.0, INFINITY };
  const double normal_thresholds[] = { 0.0, 0.1, 0.5, INFINITY };
  int64_t unbalanced_runs = 0; /* balance off: jumps > 1 must occur somewhere */
  int64_t multi_level_runs = 0;
  for (int run_index = 0; run_index < 600; ++run_index)
  {
    int32_t W = rng_int(1, 90);
    int32_t H = rng_int(1, 90);
    if (run_index % 50 == 0)
    {
      W = 1;
      H = 1;
    }
    gbuffer g = gbuffer_make(W, H);
    const int perspective = rng_int(0, 1);
    random_scene(&g, 1.0, perspective);
    const float ab[2] = { perspective ? 0.004f : 0.0f, perspective ? 0.0f : 0.05f };
    const int32_t coarsest_side = rng_int(1, 8);
    mrgi_multires_layout L;
    MRGI_CHECK(mrgi_multires_layout_init(&L, W, H, coarsest_side, NULL) == MRGI_OK);
    mrgi_multires_params params;
    params.depth_threshold = depth_thresholds[rng_int(0, 5)];
    params.normal_threshold = normal_thresholds[rng_int(0, 3)];
    params.finest_level = rng_int(0, L.level_count - 1) * rng_int(0, 1);
    int32_t* levels = (int32_t*)malloc(sizeof(int32_t) * (size_t)W * (size_t)H);
    MRGI_CHECK(levels != NULL);
    for (int balance = 0; balance <= 1; ++balance)
    {
      params.balance = balance;
      selection_run run;
      run_selection(&run, &g, coarsest_side, ab, &params);
      MRGI_CHECK(memcmp(run.mask_one_pass, run.mask_iterative, run.texels) == 0);
      coverage(&run, run.mask_one_pass, params.finest_level, levels);
      const int32_t jump = max_level_jump(&L, levels);
      if (balance)
      {
        MRGI_CHECK(jump <= 1);
      }
      else
      {
        unbalanced_runs += jump > 1;
      }
      multi_level_runs += jump > 0;
      /* monotone: D child => D parent; REFINE child => REFINE parent (levels >= finest) */
      for (int32_t i = 0; i + 1 < L.level_count; ++i)
      {
        for (int32_t y = 0; y < L.level_height[i]; ++y)
        {
          for (int32_t x = 0; x < L.level_width[i]; ++x)
          {
            const uint8_t child = run.flags[mrgi_multires_index(&L, i, x, y)];
            const uint8_t parent = run.flags[mrgi_multires_index(&L, i + 1, x / 2, y / 2)];
            if (child & MRGI_MULTIRES_FLAG_NONEMPTY)
            {
              MRGI_CHECK(parent & MRGI_MULTIRES_FLAG_NONEMPTY);
            }
            if (child & MRGI_MULTIRES_FLAG_DISCONTINUOUS)
            {
              MRGI_CHECK(parent & MRGI_MULTIRES_FLAG_DISCONTINUOUS);
            }
            if (i >= params.finest_level && (child & MRGI_MULTIRES_FLAG_REFINE))
            {
              MRGI_CHECK(parent & MRGI_MULTIRES_FLAG_REFINE);
            }
            if (i < params.finest_level)
            {
              MRGI_CHECK(!(child & MRGI_MULTIRES_FLAG_REFINE));
            }
            if (child & MRGI_MULTIRES_FLAG_DISCONTINUOUS)
            {
              MRGI_CHECK(child & MRGI_MULTIRES_FLAG_NONEMPTY);
            }
          }
        }
      }
      free_selection(&run);
    }
    free(levels);
    gbuffer_free(&g);
  }
  printf("random selections: %lld multi-level, %lld unbalanced without the balance rule\n",
         (long long)multi_level_runs, (long long)unbalanced_runs);
  MRGI_CHECK(multi_level_runs > 100);
  MRGI_CHECK(unbalanced_runs > 0); /* the balance check can fail, and the rule matters */
}

/* The same scene at scales 2^-14 and 2^17 (exact in float) and at 1e-4 and
 * 1e5 (a scene whose metrics are far from the thresholds), perspective and
 * parallel: the same flags and selection. */
static void test_scale_invariance(void)
{
  for (int projection = 0; projection < 2; ++projection)
  {
    /* exact scales on random scenes */
    for (int run_index = 0; run_index < 30; ++run_index)
    {
      const int32_t W = rng_int(8, 80);
      const int32_t H = rng_int(8, 80);
      const uint64_t seed = rng_state;
      const double scales[3] = { 1.0, ldexp(1.0, -14), ldexp(1.0, 17) };
      uint8_t* reference = NULL;
      size_t texels = 0;
      mrgi_multires_params params;
      mrgi_multires_params_default(&params);
      params.depth_threshold = 0.5;
      params.normal_threshold = 0.2;
      for (int s = 0; s < 3; ++s)
      {
        rng_state = seed;
        gbuffer g = gbuffer_make(W, H);
        random_scene(&g, scales[s], projection == 0);
        mrgi_multires_projection proj = { projection, 30.0, 20.0 * scales[s] };
        float ab[2];
        MRGI_CHECK(mrgi_multires_pixel_size_coefficients(&proj, H, ab, NULL) == MRGI_OK);
        selection_run run;
        run_selection(&run, &g, 4, ab, &params);
        if (!reference)
        {
          texels = run.texels;
          reference = (uint8_t*)malloc(2 * texels);
          MRGI_CHECK(reference != NULL);
          memcpy(reference, run.flags, texels);
          memcpy(reference + texels, run.mask_one_pass, texels);
        }
        else
        {
          MRGI_CHECK(memcmp(reference, run.flags, texels) == 0);
          MRGI_CHECK(memcmp(reference + texels, run.mask_one_pass, texels) == 0);
        }
        free_selection(&run);
        gbuffer_free(&g);
      }
      free(reference);
    }
    /* 1e-4 and 1e5: a plane tilted at tan = 0.25, a step of 40 pixel
     * widths, a 90-degree crease, a background corner; thresholds 1 (depth)
     * and 0.3 (normal): every metric is far from its threshold */
    const double scales[3] = { 1.0, 1e-4, 1e5 };
    uint8_t* reference = NULL;
    size_t texels = 0;
    for (int s = 0; s < 3; ++s)
    {
      const int32_t W = 256;
      const int32_t H = 128;
      mrgi_multires_projection proj = { projection, 40.0, 10.0 * scales[s] };
      float ab[2];
      MRGI_CHECK(mrgi_multires_pixel_size_coefficients(&proj, H, ab, NULL) == MRGI_OK);
      /* world width of a pixel at depth 5 */
      const double pixel = projection ? 2.0 * 10.0 / H : 5.0 * 2.0 * tan(20.0 * MRGI_PI / 180.0) / H;
      gbuffer g = gbuffer_make(W, H);
      const float facing[3] = { 0, 0, 1 };
      const float side[3] = { 1, 0, 0 };
      for (int32_t y = 0; y < H; ++y)
      {
        for (int32_t x = 0; x < W; ++x)
        {
          double d = 5.0;
          const float* n = facing;
          if (x < 100)
          {
            d = 5.0 + 0.25 * pixel * y;
          }
          else if (x < 200)
          {
            d = 5.0 + 40.0 * pixel;
            n = y > 100 ? side : facing;
          }
          gbuffer_set(&g, x, y, (float)(d * scales[s]), n, !(x > 240 && y < 5));
        }
      }
      mrgi_multires_params params;
      mrgi_multires_params_default(&params);
      params.depth_threshold = 1.0;
      params.normal_threshold = 0.3;
      selection_run run;
      run_selection(&run, &g, 16, ab, &params);
      if (!reference)
      {
        texels = run.texels;
        reference = (uint8_t*)malloc(2 * texels);
        MRGI_CHECK(reference != NULL);
        memcpy(reference, run.flags, texels);
        memcpy(reference + texels, run.mask_one_pass, texels);
        mrgi_multires_stats stats;
        MRGI_CHECK(mrgi_multires_stats_compute(&run.layout, run.flags, run.texels,
                                               run.mask_one_pass, run.texels, &stats,
                                               NULL) == MRGI_OK);
        /* a few levels are in use and the work is well below the full gather */
        MRGI_CHECK(stats.selected[0] > 0 && stats.selected[run.layout.level_count - 1] > 0);
        MRGI_CHECK(stats.work_fraction > 0.005 && stats.work_fraction < 0.5);
        printf("scale scene (%s): work fraction %.3f, per level", projection ? "parallel" : "perspective",
               stats.work_fraction);
        for (int32_t i = 0; i < run.layout.level_count; ++i)
        {
          printf(" %lld", (long long)stats.selected[i]);
        }
        printf("\n");
      }
      else
      {
        MRGI_CHECK(memcmp(reference, run.flags, texels) == 0);
        MRGI_CHECK(memcmp(reference + texels, run.mask_one_pass, texels) == 0);
      }
      free_selection(&run);
      gbuffer_free(&g);
    }
    free(reference);
  }
}

/* Extremes: all background, 1x1, a far plane with a near object. */
static void test_edge_cases(void)
{
  const float ab[2] = { 0.01f, 0.0f };
  const float n[3] = { 0, 0, 1 };
  mrgi_multires_params params;
  mrgi_multires_params_default(&params);
  /* all background */
  gbuffer g = gbuffer_make(37, 21);
  for (int32_t y = 0; y < 21; ++y)
  {
    for (int32_t x = 0; x < 37; ++x)
    {
      gbuffer_set(&g, x, y, 10.0f, n, 0);
    }
  }
  selection_run run;
  run_selection(&run, &g, 16, ab, &params);
  for (size_t t = 0; t < run.texels; ++t)
  {
    MRGI_CHECK(run.flags[t] == 0 && run.mask_one_pass[t] == 0 && run.mask_iterative[t] == 0);
  }
  mrgi_multires_stats stats;
  MRGI_CHECK(mrgi_multires_stats_compute(&run.layout, run.flags, run.texels, run.mask_one_pass,
                                         run.texels, &stats, NULL) == MRGI_OK);
  MRGI_CHECK(stats.valid_pixels == 0 && stats.selected_total == 0 && stats.work_fraction == 0.0);
  free_selection(&run);
  gbuffer_free(&g);
  /* 1x1 valid and invalid */
  for (int valid = 0; valid <= 1; ++valid)
  {
    g = gbuffer_make(1, 1);
    gbuffer_set(&g, 0, 0, 3.0f, n, valid);
    run_selection(&run, &g, 16, ab, &params);
    MRGI_CHECK(run.texels == 1 && run.mask_one_pass[0] == valid && run.mask_iterative[0] == valid);
    free_selection(&run);
    gbuffer_free(&g);
  }
  /* a single valid pixel in a background image, non-finite junk in invalid
   * pixels and a valid pixel with a NaN depth (treated as background) */
  g = gbuffer_make(40, 40);
  for (int32_t y = 0; y < 40; ++y)
  {
    for (int32_t x = 0; x < 40; ++x)
    {
      gbuffer_set(&g, x, y, (x + y) % 3 ? INFINITY : NAN, n, 0);
    }
  }
  gbuffer_set(&g, 17, 23, 1e-6f, n, 1);
  gbuffer_set(&g, 2, 2, NAN, n, 1);
  run_selection(&run, &g, 16, ab, &params);
  MRGI_CHECK(memcmp(run.mask_one_pass, run.mask_iterative, run.texels) == 0);
  MRGI_CHECK(run.mask_one_pass[mrgi_multires_index(&run.layout, 0, 17, 23)] == 1);
  MRGI_CHECK(!(run.flags[mrgi_multires_index(&run.layout, 0, 2, 2)] & MRGI_MULTIRES_FLAG_NONEMPTY));
  MRGI_CHECK(mrgi_multires_stats_compute(&run.layout, run.flags, run.texels, run.mask_one_pass,
                                         run.texels, &stats, NULL) == MRGI_OK);
  MRGI_CHECK(stats.valid_pixels == 1);
  /* the mixed texels above it refine down to level 0 (balance keeps the neighbours within 1) */
  MRGI_CHECK(stats.selected[0] == 1 && stats.selected_total == 1);
  for (size_t k = 0; k < 4 * run.texels; ++k)
  {
    MRGI_CHECK(!isnan(run.mipmap.texture[0][k]) && !isnan(run.mipmap.texture[1][k]) &&
               !isnan(run.mipmap.texture[2][k]));
  }
  free_selection(&run);
  gbuffer_free(&g);
  /* depth 0 and huge depth next to each other (perspective): g saturates at FLT_MAX */
  g = gbuffer_make(2, 1);
  gbuffer_set(&g, 0, 0, 0.0f, n, 1);
  gbuffer_set(&g, 1, 0, 3e38f, n, 1);
  params.depth_threshold = 1e30;
  run_selection(&run, &g, 16, ab, &params);
  MRGI_CHECK(run.mipmap.texture[0][2] == FLT_MAX);
  MRGI_CHECK(run.flags[0] & MRGI_MULTIRES_FLAG_DISCONTINUOUS);
  free_selection(&run);
  gbuffer_free(&g);
}

static void test_bad_input(void)
{
  mrgi_error err;
  gbuffer g = gbuffer_make(10, 8);
  const mrgi_gather_receivers view = gbuffer_view(&g);
  mrgi_multires_layout L;
  MRGI_CHECK(mrgi_multires_layout_init(&L, 10, 8, 2, NULL) == MRGI_OK);
  const float ab[2] = { 0.01f, 0.0f };
  mrgi_multires_mipmap m;
  MRGI_CHECK(mrgi_multires_mipmap_build(&L, &view, ab, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_multires_mipmap_build(NULL, &view, ab, &m, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(m.texture[0] == NULL);
  MRGI_CHECK(mrgi_multires_mipmap_build(&L, NULL, ab, &m, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_multires_mipmap_build(&L, &view, NULL, &m, &err) == MRGI_ERR_INVALID_ARGUMENT);
  mrgi_gather_receivers wrong = view;
  wrong.width = 11;
  MRGI_CHECK(mrgi_multires_mipmap_build(&L, &wrong, ab, &m, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "11 x 8") != NULL);
  wrong = view;
  wrong.normal = NULL;
  MRGI_CHECK(mrgi_multires_mipmap_build(&L, &wrong, ab, &m, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "normal") != NULL);
  const float bad_ab[3][2] = { { 0.0f, 0.0f }, { -1.0f, 0.0f }, { NAN, 0.0f } };
  for (int k = 0; k < 3; ++k)
  {
    MRGI_CHECK(mrgi_multires_mipmap_build(&L, &view, bad_ab[k], &m, &err) ==
               MRGI_ERR_INVALID_ARGUMENT);
    MRGI_CHECK(strstr(err.message, "coefficients") != NULL);
  }
  mrgi_multires_layout tampered = L;
  tampered.total_width += 1;
  MRGI_CHECK(mrgi_multires_mipmap_build(&tampered, &view, ab, &m, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "layout") != NULL);
  MRGI_CHECK(mrgi_multires_mipmap_build(&L, &view, ab, &m, &err) == MRGI_OK);

  const size_t texels = (size_t)mrgi_multires_texel_count(&L);
  uint8_t* flags = (uint8_t*)malloc(texels);
  uint8_t* mask = (uint8_t*)malloc(texels);
  MRGI_CHECK(flags && mask);
  mrgi_multires_params params;
  mrgi_multires_params_default(&params);
  MRGI_CHECK(params.balance == 1 && params.finest_level == 0);
  MRGI_CHECK(mrgi_multires_flags_compute(&m, &params, flags, texels - 1, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "needs") != NULL);
  MRGI_CHECK(mrgi_multires_flags_compute(&m, &params, NULL, texels, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_multires_flags_compute(NULL, &params, flags, texels, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_multires_flags_compute(&m, NULL, flags, texels, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  params.depth_threshold = -1.0;
  MRGI_CHECK(mrgi_multires_flags_compute(&m, &params, flags, texels, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "depth threshold") != NULL);
  params.depth_threshold = NAN;
  MRGI_CHECK(mrgi_multires_flags_compute(&m, &params, flags, texels, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  params.depth_threshold = 1.0;
  params.normal_threshold = NAN;
  MRGI_CHECK(mrgi_multires_flags_compute(&m, &params, flags, texels, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "normal threshold") != NULL);
  params.normal_threshold = 0.2;
  params.finest_level = L.level_count;
  MRGI_CHECK(mrgi_multires_flags_compute(&m, &params, flags, texels, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "finest level") != NULL);
  params.finest_level = -1;
  MRGI_CHECK(mrgi_multires_flags_compute(&m, &params, flags, texels, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  params.finest_level = 0;
  params.balance = 2;
  MRGI_CHECK(mrgi_multires_flags_compute(&m, &params, flags, texels, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "balance") != NULL);
  params.balance = 1;
  MRGI_CHECK(mrgi_multires_flags_compute(&m, &params, flags, texels, &err) == MRGI_OK);
  MRGI_CHECK(mrgi_multires_select_one_pass(&L, flags, texels, 0, mask, texels - 1, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "selection mask") != NULL);
  MRGI_CHECK(mrgi_multires_select_iterative(&L, flags, texels, L.level_count, mask, texels,
                                            &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_multires_select_iterative(&L, NULL, texels, 0, mask, texels, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_multires_select_one_pass(NULL, flags, texels, 0, mask, texels, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  mrgi_multires_stats stats;
  MRGI_CHECK(mrgi_multires_stats_compute(&L, flags, texels, mask, texels, NULL, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_multires_stats_compute(&L, flags, 3, mask, texels, &stats, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  mrgi_multires_mipmap_destroy(&m);
  MRGI_CHECK(mrgi_multires_flags_compute(&m, &params, flags, texels, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  free(flags);
  free(mask);
  gbuffer_free(&g);
}

/* Presets: every preset has valid geometric settings and an illumination
 * threshold that is +inf (geometry alone) or in the illumination rule's
 * range; the more accurate preset never refines less; unknown presets and
 * NULL outputs are refused without writing. */
static void test_presets(void)
{
  mrgi_multires_layout L;
  MRGI_CHECK(mrgi_multires_layout_init(&L, 1024, 1024, MRGI_MULTIRES_DEFAULT_COARSEST_SIDE, NULL) ==
    MRGI_OK);
  mrgi_error err;
  double previous = INFINITY;
  for (int32_t p = 0; p < MRGI_MULTIRES_PRESET_COUNT; ++p)
  {
    mrgi_multires_params params;
    double t = -1.0;
    MRGI_CHECK(mrgi_multires_preset_params(p, &params, NULL) == MRGI_OK);
    MRGI_CHECK(mrgi_multires_params_validate(&params, &L, NULL) == MRGI_OK);
    MRGI_CHECK(mrgi_multires_preset_illumination_threshold(p, &t, NULL) == MRGI_OK);
    MRGI_CHECK(isinf(t) || (t >= 0.0 && t <= 1.0));
    MRGI_CHECK(t <= previous); /* fast, balanced, accurate: ever finer */
    previous = t;
    MRGI_CHECK(mrgi_multires_preset_name(p) != NULL);
    /* The area lights' settings: same finest level and balance, their own thresholds. */
    mrgi_multires_params area;
    MRGI_CHECK(mrgi_multires_preset_area_light_params(p, &area, NULL) == MRGI_OK);
    MRGI_CHECK(mrgi_multires_params_validate(&area, &L, NULL) == MRGI_OK);
    MRGI_CHECK(area.finest_level == params.finest_level && area.balance == params.balance);
    /* Where the light refines the indirect gather, the area lights keep a
     * depth test at least as strict as the indirect gather's. */
    MRGI_CHECK(isinf(t) || area.depth_threshold <= params.depth_threshold);
  }
  MRGI_CHECK(mrgi_multires_preset_area_light_params(-1, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  double t = 42.0;
  MRGI_CHECK(mrgi_multires_preset_illumination_threshold(MRGI_MULTIRES_PRESET_COUNT, &t, &err) ==
    MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "unknown preset") != NULL && t == 42.0);
  MRGI_CHECK(
    mrgi_multires_preset_illumination_threshold(-1, &t, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(
    mrgi_multires_preset_illumination_threshold(0, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "threshold is NULL") != NULL);
  MRGI_CHECK(mrgi_multires_preset_params(0, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_multires_preset_name(MRGI_MULTIRES_PRESET_COUNT) == NULL);
}

int main(int argc, char** argv)
{
  static const mrgi_test_case cases[] = {
    MRGI_TEST_CASE(test_layout),
    MRGI_TEST_CASE(test_pixel_size),
    MRGI_TEST_CASE(test_mipmap_by_hand),
    MRGI_TEST_CASE(test_threshold_extremes),
    MRGI_TEST_CASE(test_selection_random),
    MRGI_TEST_CASE(test_scale_invariance),
    MRGI_TEST_CASE(test_edge_cases),
    MRGI_TEST_CASE(test_bad_input),
    MRGI_TEST_CASE(test_presets),
  };
  return MRGI_TEST_MAIN(argc, argv, cases);
}
