/* Tests of mrgi_ism_visibility (RGK08 3.3, RIHKS11 6.1) and of the gathers
 * with visibility (mrgi_gather_full_visibility, mrgi_vpl_tree_gather_visibility):
 * a plane occluder between a VPL and a receiver plane shadows; 2x2 PCF gives
 * fractions at the shadow edge and never reads a neighbour tile; at the
 * default bias a receiver on the point-sampled surface that made the ISM is
 * not self-shadowed (and without bias it is); bad parameters give errors;
 * the gathers with NONE equal the old ones bit for bit, the tree's roots use
 * the roots' tiles, voxels with an empty buffer change nothing. */
#include "mrgi_gather.h"
#include "mrgi_ism_atlas.h"
#include "mrgi_ism_visibility.h"
#include "mrgi_test.h"
#include "mrgi_test_rsm.h"
#include "mrgi_voxel_march.h"
#include "mrgi_vpl_tree_gather.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

enum
{
  TILE = 64
};

/* Scatter `count` points of the rectangle z = z0, x in [x0, x1], y in [y0, y1]
 * into VPL 0's tile (nearest depth wins), then push-pull. */
static void scatter_rect(const mrgi_ism_atlas_layout* L, float* depth, const double vpl[3],
  const double n[3], double z0, double x0, double x1, double y0, double y1, int count,
  uint32_t* seed)
{
  for (int i = 0; i < count; ++i)
  {
    const double p[3] = { x0 + (x1 - x0) * test_uniform(seed), y0 + (y1 - y0) * test_uniform(seed),
      z0 };
    int64_t texel;
    float z;
    if (mrgi_ism_point_texel(L, 0, vpl, n, p, &texel, &z) && z < depth[texel])
      depth[texel] = z;
  }
}

static float* atlas_new(const mrgi_ism_atlas_layout* L, float value)
{
  float* depth = (float*)malloc(sizeof(float) * (size_t)L->width * (size_t)L->height);
  MRGI_CHECK(depth);
  for (int64_t i = 0; i < (int64_t)L->width * L->height; ++i)
    depth[i] = value;
  return depth;
}

/* Push-pull over `levels` levels (0: none). */
static void push_pull_levels(const mrgi_ism_atlas_layout* L, float* depth, int levels)
{
  if (levels == 0)
    return;
  const size_t n = mrgi_ism_push_pull_scratch_size(L);
  float* scratch = (float*)malloc(sizeof(float) * n);
  MRGI_CHECK(scratch);
  MRGI_CHECK(mrgi_ism_push_pull(L, depth, levels, scratch, n, NULL) == MRGI_OK);
  free(scratch);
}

/* Push-pull over the whole tile (dense tiles). */
static void push_pull(const mrgi_ism_atlas_layout* L, float* depth)
{
  push_pull_levels(L, depth, MRGI_ISM_MAX_PUSH_PULL_LEVELS);
}

/* VPL at the origin facing +z; receiver plane z = 2 (|x|, |y| <= 4) and an
 * occluder square z = 1, |x|, |y| <= 0.5: its shadow is |x|, |y| <= 1 at z = 2. */
static float* occluder_atlas(mrgi_ism_atlas_layout* L, int with_occluder)
{
  MRGI_CHECK(mrgi_ism_atlas_layout_make(1, TILE, L, NULL) == MRGI_OK);
  float* depth = atlas_new(L, MRGI_ISM_EMPTY_DEPTH);
  const double vpl[3] = { 0, 0, 0 }, n[3] = { 0, 0, 1 };
  uint32_t seed = 99u;
  scatter_rect(L, depth, vpl, n, 2.0, -4.0, 4.0, -4.0, 4.0, 40000, &seed);
  if (with_occluder)
    scatter_rect(L, depth, vpl, n, 1.0, -0.5, 0.5, -0.5, 0.5, 4000, &seed);
  push_pull(L, depth);
  return depth;
}

static void test_plane_occluder(void)
{
  mrgi_ism_atlas_layout L;
  float* depth = occluder_atlas(&L, 1);
  const float vpl[3] = { 0, 0, 0 }, n[3] = { 0, 0, 1 };
  mrgi_ism_lookup_params p;
  mrgi_ism_lookup_params_default(&p);
  MRGI_CHECK(mrgi_ism_lookup_params_validate(&p, NULL) == MRGI_OK);
  /* Deep in the shadow and well outside it, PCF on and off. */
  for (int pcf = 0; pcf < 2; ++pcf)
  {
    p.pcf = pcf;
    for (int i = 0; i < 50; ++i)
    {
      const float a = -0.7f + 1.4f * (float)i / 49.0f;
      const float in[3] = { a, -a * 0.5f, 2.0f };
      MRGI_CHECK(mrgi_ism_visibility(&L, depth, 0, vpl, n, in, &p) == 0.0f);
      const float out[3] = { 1.3f + fabsf(a), a, 2.0f };
      MRGI_CHECK(mrgi_ism_visibility(&L, depth, 0, vpl, n, out, &p) == 1.0f);
    }
  }
  /* The edge x = 1: PCF gives fractions there, monotone in x; one texel gives 0 or 1. */
  p.pcf = 1;
  int fractions = 0;
  float last = 0.0f;
  for (int i = 0; i <= 200; ++i)
  {
    const float x[3] = { 0.8f + 0.4f * (float)i / 200.0f, 0.0f, 2.0f };
    const float v = mrgi_ism_visibility(&L, depth, 0, vpl, n, x, &p);
    MRGI_CHECK(v >= 0.0f && v <= 1.0f);
    MRGI_CHECK(v >= last - 1e-6f);
    last = v;
    fractions += v > 0.0f && v < 1.0f;
    p.pcf = 0;
    const float hard = mrgi_ism_visibility(&L, depth, 0, vpl, n, x, &p);
    MRGI_CHECK(hard == 0.0f || hard == 1.0f);
    p.pcf = 1;
  }
  MRGI_CHECK(fractions >= 3);
  MRGI_CHECK(last == 1.0f);
  /* Behind the VPL and coincident with it: visible (the term is 0 there). */
  const float behind[3] = { 0, 0, -1 };
  MRGI_CHECK(mrgi_ism_visibility(&L, depth, 0, vpl, n, behind, &p) == 1.0f);
  MRGI_CHECK(mrgi_ism_visibility(&L, depth, 0, vpl, n, vpl, &p) == 1.0f);
  /* Out-of-range VPL index: 1. */
  MRGI_CHECK(mrgi_ism_visibility(&L, depth, 1, vpl, n, behind, &p) == 1.0f);
  free(depth);
}

/* Receivers on the point-sampled surface that made the ISM (not the sample
 * points themselves): on this DENSE, push-pulled tile (about 10 points per
 * texel) never self-shadowed at texel bias 3 (what the header advises for
 * dense tiles; the default is tuned to the stage's sparse tiles), PCF on or
 * off; without any bias a good part is. Plane z = 2 within 63 degrees of
 * the VPL normal (|x|, |y| <= 4), and a wall x = 1.5 seen at grazing angles. */
static void test_bias_no_self_shadow(void)
{
  for (int wall = 0; wall < 2; ++wall)
  {
    mrgi_ism_atlas_layout L;
    MRGI_CHECK(mrgi_ism_atlas_layout_make(1, TILE, &L, NULL) == MRGI_OK);
    float* depth = atlas_new(&L, MRGI_ISM_EMPTY_DEPTH);
    const double vpld[3] = { 0, 0, 0 }, nd[3] = { 0, 0, 1 };
    uint32_t seed = 5u;
    for (int i = 0; i < 40000; ++i)
    {
      const double a = -4.0 + 8.0 * test_uniform(&seed), b = -4.0 + 8.0 * test_uniform(&seed);
      const double q[3] = { wall ? 1.5 : a, b, wall ? 0.05 + (a + 4.0) * 0.5 : 2.0 };
      int64_t texel;
      float z;
      if (mrgi_ism_point_texel(&L, 0, vpld, nd, q, &texel, &z) && z < depth[texel])
        depth[texel] = z;
    }
    push_pull(&L, depth);
    const float vpl[3] = { 0, 0, 0 }, n[3] = { 0, 0, 1 };
    mrgi_ism_lookup_params p;
    mrgi_ism_lookup_params_default(&p);
    p.texel_bias = 3.0f;
    mrgi_ism_lookup_params none = { 0.0f, 0.0f, 0, 0.0f };
    int shadowed = 0, shadowed_unbiased = 0, tested = 0;
    for (int i = 0; i < 4000; ++i)
    {
      const float a = (float)(-3.5 + 7.0 * test_uniform(&seed));
      const float b = (float)(-3.5 + 7.0 * test_uniform(&seed));
      const float x[3] = { wall ? 1.5f : a, b, wall ? 0.05f + (a + 3.5f) * 0.5f : 2.0f };
      ++tested;
      for (int pcf = 0; pcf < 2; ++pcf)
      {
        p.pcf = pcf;
        shadowed += mrgi_ism_visibility(&L, depth, 0, vpl, n, x, &p) < 1.0f;
      }
      shadowed_unbiased += mrgi_ism_visibility(&L, depth, 0, vpl, n, x, &none) < 1.0f;
    }
    printf("%s: %d of %d receivers self-shadowed at texel bias 3, %d without bias\n",
      wall ? "wall x = 1.5" : "plane z = 2", shadowed, 2 * tested, shadowed_unbiased);
    MRGI_CHECK(shadowed == 0);
    MRGI_CHECK(shadowed_unbiased > tested / 20);
    free(depth);
  }
}

/* The stage's defaults (32^2 tile, no push-pull, default bias; corridor
 * issue 13): (1) an occluder close to its receiver shadows it: VPL at the
 * origin facing +z, occluder square z = 1.7, |x|, |y| <= 0.3, receivers at
 * z = 2, |x|, |y| <= 0.15 (0.3 behind it, 15% of the distance). At the old
 * default texel bias 3 the bias, 2 (0.02 + 6 / 32) = 0.415, exceeded the gap
 * and they stayed lit. (2) A sparse open scene gets no false shadows: 256
 * points on the plane z = 2 and 16 on a small square z = 0.5 near x = 1.6;
 * receivers on the plane away from the square's shadow (|x| <= 1) stay
 * visible with the default push-pull levels; push-pull over the whole tile
 * spreads the square's depth into the plane's holes and shadows many of them. */
static void test_sparse_defaults(void)
{
  mrgi_ism_atlas_layout L;
  MRGI_CHECK(mrgi_ism_atlas_layout_make(1, 32, &L, NULL) == MRGI_OK);
  const double vpld[3] = { 0, 0, 0 }, nd[3] = { 0, 0, 1 };
  const float vpl[3] = { 0, 0, 0 }, n[3] = { 0, 0, 1 };
  mrgi_ism_lookup_params p;
  mrgi_ism_lookup_params_default(&p);
  uint32_t seed = 21u;
  float* depth = atlas_new(&L, MRGI_ISM_EMPTY_DEPTH);
  scatter_rect(&L, depth, vpld, nd, 1.7, -0.3, 0.3, -0.3, 0.3, 2000, &seed);
  push_pull_levels(&L, depth, MRGI_ISM_DEFAULT_PUSH_PULL_LEVELS);
  int lit = 0;
  for (int i = 0; i < 200; ++i)
  {
    const float x[3] = { (float)(-0.15 + 0.3 * test_uniform(&seed)),
      (float)(-0.15 + 0.3 * test_uniform(&seed)), 2.0f };
    lit += mrgi_ism_visibility(&L, depth, 0, vpl, n, x, &p) > 0.0f;
  }
  printf("occluder 0.3 in front of its receivers: %d of 200 receivers lit\n", lit);
  MRGI_CHECK(lit == 0);
  free(depth);

  /* No push-pull, the default levels, the whole tile. */
  const int variants[3] = { 0, MRGI_ISM_DEFAULT_PUSH_PULL_LEVELS, MRGI_ISM_MAX_PUSH_PULL_LEVELS };
  int shadowed[3] = { 0, 0, 0 };
  for (int v = 0; v < 3; ++v)
  {
    depth = atlas_new(&L, MRGI_ISM_EMPTY_DEPTH);
    seed = 22u;
    scatter_rect(&L, depth, vpld, nd, 2.0, -4.0, 4.0, -4.0, 4.0, 256, &seed);
    scatter_rect(&L, depth, vpld, nd, 0.5, 1.5, 1.7, -0.1, 0.1, 16, &seed);
    push_pull_levels(&L, depth, variants[v]);
    for (int i = 0; i < 1000; ++i)
    {
      const float x[3] = { (float)(-1.0 + 2.0 * test_uniform(&seed)),
        (float)(-3.0 + 6.0 * test_uniform(&seed)), 2.0f };
      shadowed[v] += mrgi_ism_visibility(&L, depth, 0, vpl, n, x, &p) < 1.0f;
    }
    free(depth);
  }
  printf("sparse open scene: of 1000 unoccluded receivers %d shadowed without push-pull, %d with "
         "the default %d level(s), %d over the whole tile\n",
    shadowed[0], shadowed[1], MRGI_ISM_DEFAULT_PUSH_PULL_LEVELS, shadowed[2]);
  MRGI_CHECK(shadowed[0] <= 20 && shadowed[1] <= 20);
  MRGI_CHECK(shadowed[2] > shadowed[1]); /* why few levels: the square's depth spreads */
}

/* PCF at the tile border clamps to the tile: tile 0 empty (visible), its
 * neighbours all depth 0 (shadow). Directions near the disk's rim land in
 * border texels of tile 0. */
static void test_pcf_stays_in_tile(void)
{
  mrgi_ism_atlas_layout L;
  MRGI_CHECK(mrgi_ism_atlas_layout_make(4, 32, &L, NULL) == MRGI_OK);
  float* depth = atlas_new(&L, 0.0f);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x)
      depth[y * L.width + x] = MRGI_ISM_EMPTY_DEPTH;
  const float vpl[3] = { 1, 2, 3 };
  mrgi_ism_lookup_params p;
  mrgi_ism_lookup_params_default(&p);
  const mrgi_ism_lookup_params unbiased = { 0.0f, 0.0f, 1, 0.0f };
  uint32_t seed = 3u;
  for (int i = 0; i < 5000; ++i)
  {
    float n[3] = { (float)test_uniform(&seed) - 0.5f, (float)test_uniform(&seed) - 0.5f,
      (float)test_uniform(&seed) - 0.5f };
    const double phi = 6.283185307179586 * test_uniform(&seed);
    const double nn[3] = { n[0], n[1], n[2] };
    const double len = sqrt(nn[0] * nn[0] + nn[1] * nn[1] + nn[2] * nn[2]);
    const double un[3] = { nn[0] / len, nn[1] / len, nn[2] / len };
    double t[3], b[3];
    mrgi_ism_vpl_frame(un, t, b);
    const double e = 0.02 + 0.2 * test_uniform(&seed); /* elevation: near the rim */
    float x[3];
    for (int k = 0; k < 3; ++k)
      x[k] = vpl[k] +
        (float)(3.0 * (cos(e) * (cos(phi) * t[k] + sin(phi) * b[k]) + sin(e) * un[k]));
    MRGI_CHECK(mrgi_ism_visibility(&L, depth, 0, vpl, n, x, &p) == 1.0f);
    MRGI_CHECK(mrgi_ism_visibility(&L, depth, 0, vpl, n, x, &unbiased) == 1.0f);
    /* Tile 3 shadows (without bias: the default's texel term exceeds the
     * distance at these grazing angles of a 32^2 tile). */
    MRGI_CHECK(mrgi_ism_visibility(&L, depth, 3, vpl, n, x, &unbiased) == 0.0f);
  }
  free(depth);
}

/* Step 2b: over an all-occluded tile (every texel at depth 0) and without
 * bias, a receiver is visible exactly where its direction's texel is wider
 * than max_texel_angle (2 / (T c) > angle), and everywhere shadowed with the
 * rule off. Directions in the x-z plane from the VPL normal (c = 1) to the
 * horizon. */
static void test_grazing_rule(void)
{
  mrgi_ism_atlas_layout L;
  MRGI_CHECK(mrgi_ism_atlas_layout_make(1, 32, &L, NULL) == MRGI_OK);
  float* depth = atlas_new(&L, 0.0f);
  const float vpl[3] = { 0, 0, 0 }, n[3] = { 0, 0, 1 };
  mrgi_ism_lookup_params p;
  mrgi_ism_lookup_params_default(&p);
  MRGI_CHECK(p.max_texel_angle == MRGI_ISM_DEFAULT_MAX_TEXEL_ANGLE);
  p.relative_bias = 0.0f;
  p.texel_bias = 0.0f;
  const float T = (float)L.tile_size;
  int visible = 0, shadowed = 0;
  for (int i = 1; i < 200; ++i)
  {
    const float c = (float)i / 200.0f;
    const float x[3] = { 3.0f * sqrtf(1.0f - c * c), 0.0f, 3.0f * c };
    /* The twin's own c (float rounding of d . n) decides; skip the few
     * receivers within rounding of the boundary. */
    const float expected_c = x[2] / sqrtf(x[0] * x[0] + x[2] * x[2]);
    const float width = 2.0f / (T * expected_c);
    if (fabsf(width - p.max_texel_angle) < 1e-4f)
      continue;
    const float v = mrgi_ism_visibility(&L, depth, 0, vpl, n, x, &p);
    MRGI_CHECK(v == (width > p.max_texel_angle ? 1.0f : 0.0f));
    visible += v == 1.0f;
    shadowed += v == 0.0f;
    p.max_texel_angle = 0.0f; /* off: the tile decides everywhere */
    MRGI_CHECK(mrgi_ism_visibility(&L, depth, 0, vpl, n, x, &p) == 0.0f);
    p.max_texel_angle = MRGI_ISM_DEFAULT_MAX_TEXEL_ANGLE;
  }
  printf("grazing rule at T = 32: %d of %d directions skipped (c < %.3f)\n", visible,
    visible + shadowed, 2.0 / (32.0 * MRGI_ISM_DEFAULT_MAX_TEXEL_ANGLE));
  MRGI_CHECK(visible > 0 && shadowed > 0);
  free(depth);
}

static void test_bad_params(void)
{
  mrgi_error err;
  mrgi_ism_lookup_params p;
  mrgi_ism_lookup_params_default(&p);
  MRGI_CHECK(p.pcf == 1 && p.relative_bias == MRGI_ISM_DEFAULT_RELATIVE_BIAS);
  MRGI_CHECK(mrgi_ism_lookup_params_validate(NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  p.relative_bias = -0.1f;
  MRGI_CHECK(mrgi_ism_lookup_params_validate(&p, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "relative bias"));
  p.relative_bias = NAN;
  MRGI_CHECK(mrgi_ism_lookup_params_validate(&p, &err) == MRGI_ERR_INVALID_ARGUMENT);
  mrgi_ism_lookup_params_default(&p);
  p.texel_bias = MRGI_ISM_MAX_BIAS * 2.0f;
  MRGI_CHECK(mrgi_ism_lookup_params_validate(&p, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "texel bias"));
  mrgi_ism_lookup_params_default(&p);
  p.pcf = 2;
  MRGI_CHECK(mrgi_ism_lookup_params_validate(&p, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "pcf"));
  const float angles[3] = { -0.1f, NAN, MRGI_ISM_MAX_TEXEL_ANGLE_LIMIT * 2.0f };
  for (int i = 0; i < 3; ++i)
  {
    mrgi_ism_lookup_params_default(&p);
    p.max_texel_angle = angles[i];
    MRGI_CHECK(mrgi_ism_lookup_params_validate(&p, &err) == MRGI_ERR_INVALID_ARGUMENT);
    MRGI_CHECK(strstr(err.message, "max texel angle"));
  }
  /* NULL pointers: visible, no crash. */
  const float v[3] = { 0, 0, 0 }, x[3] = { 0, 0, 1 };
  mrgi_ism_lookup_params_default(&p);
  MRGI_CHECK(mrgi_ism_visibility(NULL, NULL, 0, v, v, x, &p) == 1.0f);
}

/* ---- the gathers ---------------------------------------------------- */

typedef struct receivers
{
  float* position;
  float* normal;
  mrgi_gather_receivers r;
} receivers;

/* W x H receivers near the VPLs of the tree map (world space). */
static receivers make_receivers(uint32_t seed, int32_t w, int32_t h)
{
  receivers out;
  out.position = (float*)calloc(4 * (size_t)w * h, sizeof(float));
  out.normal = (float*)calloc(4 * (size_t)w * h, sizeof(float));
  MRGI_CHECK(out.position && out.normal);
  for (int32_t i = 0; i < w * h; ++i)
  {
    for (int k = 0; k < 3; ++k)
    {
      out.position[4 * i + k] = (float)(-3.0 + 6.0 * test_uniform(&seed));
      out.normal[4 * i + k] = (float)(test_uniform(&seed) - 0.5);
    }
    out.position[4 * i + 3] = i % 13 == 5 ? 0.0f : 1.0f;
  }
  out.r.width = w;
  out.r.height = h;
  out.r.position = out.position;
  out.r.normal = out.normal;
  return out;
}

static int images_equal(const mrgi_image* a, const mrgi_image* b)
{
  return a->width == b->width && a->height == b->height && a->channels == b->channels &&
    memcmp(a->pixels, b->pixels, sizeof(float) * (size_t)a->width * a->height * a->channels) == 0;
}

static double image_sum(const mrgi_image* a)
{
  double s = 0.0;
  for (size_t i = 0; i < (size_t)a->width * a->height * a->channels; ++i)
    s += a->pixels[i];
  return s;
}

static void test_gathers(void)
{
  test_rsm map = test_rsm_make(32, 1);
  const double where[3] = { 0.3, -0.2, 0.5 };
  test_camera(&map.cameras[0], 0.4, where, 0, 70.0);
  test_rsm_fill_random(&map, 7u, 0.8);
  mrgi_vpl_tree tree;
  MRGI_CHECK(mrgi_vpl_tree_build(&map.rsm, map.cameras, &tree, NULL) == MRGI_OK);
  const int32_t roots = mrgi_vpl_tree_root_count(&tree);
  MRGI_CHECK(roots == 256);
  const mrgi_vpl* vpls = tree.nodes; /* the roots, level L first: the cache in Tree mode */
  receivers rec = make_receivers(17u, 24, 16);

  mrgi_ism_atlas_layout L;
  MRGI_CHECK(mrgi_ism_atlas_layout_make(roots, 16, &L, NULL) == MRGI_OK);
  float* far_atlas = atlas_new(&L, MRGI_ISM_EMPTY_DEPTH);
  float* zero_atlas = atlas_new(&L, 0.0f);
  /* A random atlas: tiles partly shadowing. */
  float* random_atlas = atlas_new(&L, 0.0f);
  uint32_t seed = 77u;
  for (int64_t i = 0; i < (int64_t)L.width * L.height; ++i)
    random_atlas[i] = (float)(6.0 * test_uniform(&seed));

  mrgi_gather_visibility vis;
  memset(&vis, 0, sizeof(vis));
  mrgi_image plain, with, tree_plain, tree_with;
  mrgi_error err;
  /* NONE (and NULL) equal the old gathers bit for bit. */
  MRGI_CHECK(mrgi_gather_full(&rec.r, vpls, roots, NULL, &plain, NULL, NULL) == MRGI_OK);
  MRGI_CHECK(mrgi_gather_full_visibility(&rec.r, vpls, roots, NULL, &vis, &with, NULL, NULL) ==
    MRGI_OK);
  MRGI_CHECK(images_equal(&plain, &with));
  MRGI_CHECK(image_sum(&plain) > 0.0);
  mrgi_image_destroy(&with);
  MRGI_CHECK(mrgi_vpl_tree_gather(&rec.r, &tree, 0.05, NULL, &tree_plain, NULL, NULL, NULL) ==
    MRGI_OK);
  MRGI_CHECK(mrgi_vpl_tree_gather_visibility(&rec.r, &tree, 0.05, NULL, &vis, &tree_with, NULL,
               NULL, NULL) == MRGI_OK);
  MRGI_CHECK(images_equal(&tree_plain, &tree_with));
  mrgi_image_destroy(&tree_with);

  /* ISM with an empty atlas: no shadow, the same image; an all-zero atlas: all dark. */
  vis.mode = MRGI_GATHER_VISIBILITY_ISM;
  vis.ism_layout = &L;
  vis.ism_depth = far_atlas;
  mrgi_ism_lookup_params_default(&vis.ism_lookup);
  MRGI_CHECK(mrgi_gather_full_visibility(&rec.r, vpls, roots, NULL, &vis, &with, NULL, NULL) ==
    MRGI_OK);
  MRGI_CHECK(images_equal(&plain, &with));
  mrgi_image_destroy(&with);
  MRGI_CHECK(mrgi_vpl_tree_gather_visibility(&rec.r, &tree, 0.05, NULL, &vis, &tree_with, NULL,
               NULL, NULL) == MRGI_OK);
  MRGI_CHECK(images_equal(&tree_plain, &tree_with));
  mrgi_image_destroy(&tree_with);
  vis.ism_depth = zero_atlas; /* without bias: grazing directions' bias exceeds the distance */
  vis.ism_lookup.relative_bias = 0.0f;
  vis.ism_lookup.texel_bias = 0.0f;
  vis.ism_lookup.max_texel_angle = 0.0f; /* and every direction tested (step 2b off) */
  MRGI_CHECK(mrgi_gather_full_visibility(&rec.r, vpls, roots, NULL, &vis, &with, NULL, NULL) ==
    MRGI_OK);
  MRGI_CHECK(image_sum(&with) == 0.0);
  mrgi_image_destroy(&with);
  MRGI_CHECK(mrgi_vpl_tree_gather_visibility(&rec.r, &tree, 0.05, NULL, &vis, &tree_with, NULL,
               NULL, NULL) == MRGI_OK);
  /* Not exactly 0: a node may face a receiver that lies behind its root's
   * plane, where the root's tile says visible (the approximation of
   * mrgi_vpl_tree_gather.h section 4). */
  printf("tree, all-shadow atlas: %.3g of the unshadowed sum\n",
    image_sum(&tree_with) / image_sum(&tree_plain));
  MRGI_CHECK(image_sum(&tree_with) < 0.5 * image_sum(&tree_plain)); /* random RSM normals: roots and nodes disagree */
  mrgi_image_destroy(&tree_with);

  /* Random atlas: darker, and the tree at tau = +inf (roots only) is the flat
   * gather over the roots with the same tiles, bit for bit. */
  vis.ism_depth = random_atlas;
  mrgi_ism_lookup_params_default(&vis.ism_lookup);
  MRGI_CHECK(mrgi_gather_full_visibility(&rec.r, vpls, roots, NULL, &vis, &with, NULL, NULL) ==
    MRGI_OK);
  MRGI_CHECK(image_sum(&with) > 0.0 && image_sum(&with) < image_sum(&plain));
  MRGI_CHECK(mrgi_vpl_tree_gather_visibility(&rec.r, &tree, INFINITY, NULL, &vis, &tree_with,
               NULL, NULL, NULL) == MRGI_OK);
  MRGI_CHECK(images_equal(&with, &tree_with));
  mrgi_image_destroy(&tree_with);
  mrgi_image_destroy(&with);

  /* Errors name the problem. */
  MRGI_CHECK(mrgi_gather_full_visibility(&rec.r, vpls, roots - 1, NULL, &vis, &with, NULL, &err) ==
    MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "tiles"));
  vis.ism_depth = NULL;
  MRGI_CHECK(mrgi_vpl_tree_gather_visibility(&rec.r, &tree, 0.05, NULL, &vis, &tree_with, NULL,
               NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "missing"));
  vis.ism_depth = far_atlas;
  vis.ism_lookup.pcf = 7;
  MRGI_CHECK(mrgi_gather_full_visibility(&rec.r, vpls, roots, NULL, &vis, &with, NULL, &err) ==
    MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "pcf"));
  vis.mode = 9;
  MRGI_CHECK(mrgi_gather_full_visibility(&rec.r, vpls, roots, NULL, &vis, &with, NULL, &err) ==
    MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "mode 9"));
  vis.mode = MRGI_GATHER_VISIBILITY_VOXELS;
  vis.voxels = NULL;
  MRGI_CHECK(mrgi_gather_full_visibility(&rec.r, vpls, roots, NULL, &vis, &with, NULL, &err) ==
    MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "voxel"));

  /* Voxels: receivers in eye space in front of a camera at the origin
   * looking down -z. An empty buffer shadows nothing (the horizon tests
   * agree with the term's cosines up to float rounding); a full buffer
   * shadows all but contact rays. */
  mrgi_voxel_view view;
  memset(&view, 0, sizeof(view));
  MRGI_CHECK(mrgi_voxel_grid_init(&view.grid, 24, 16, MRGI_VOXEL_DEFAULT_SLICES, 0.5, 20.0, NULL) ==
    MRGI_OK);
  mrgi_multires_projection cam;
  memset(&cam, 0, sizeof(cam));
  cam.parallel = 0;
  cam.view_angle_deg = 60.0;
  MRGI_CHECK(mrgi_voxel_projection_from_camera(&view.projection, &cam, 1.5, NULL) == MRGI_OK);
  mrgi_voxel_march_params_default(&view.params);
  const size_t words = mrgi_voxel_buffer_words(&view.grid);
  uint32_t* voxels = (uint32_t*)calloc(words, sizeof(uint32_t));
  MRGI_CHECK(voxels);
  view.voxels = voxels;
  view.voxel_words = words;
  MRGI_CHECK(mrgi_voxel_view_check(&view, NULL) == MRGI_OK);
  /* Eye space: shift the scene 8 units down -z (a rigid matrix). */
  const float to_eye[16] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, -8, 1 };
  for (int32_t i = 0; i < 24 * 16; ++i)
    rec.position[4 * i + 2] -= 8.0f;
  vis.voxels = &view;
  mrgi_image eye_plain;
  MRGI_CHECK(mrgi_gather_full(&rec.r, vpls, roots, to_eye, &eye_plain, NULL, NULL) == MRGI_OK);
  MRGI_CHECK(mrgi_gather_full_visibility(&rec.r, vpls, roots, to_eye, &vis, &with, NULL, &err) ==
    MRGI_OK);
  const double ratio = image_sum(&with) / image_sum(&eye_plain);
  MRGI_CHECK(ratio > 0.999 && ratio <= 1.0);
  mrgi_image_destroy(&with);
  memset(voxels, 0xff, sizeof(uint32_t) * words);
  MRGI_CHECK(mrgi_gather_full_visibility(&rec.r, vpls, roots, to_eye, &vis, &with, NULL, &err) ==
    MRGI_OK);
  MRGI_CHECK(image_sum(&with) < 0.5 * image_sum(&eye_plain));
  mrgi_image_destroy(&with);
  /* The tree at tau = +inf with voxels is the flat voxel gather over the roots. */
  MRGI_CHECK(mrgi_gather_full_visibility(&rec.r, vpls, roots, to_eye, &vis, &with, NULL, &err) ==
    MRGI_OK);
  MRGI_CHECK(mrgi_vpl_tree_gather_visibility(&rec.r, &tree, INFINITY, to_eye, &vis, &tree_with,
               NULL, NULL, &err) == MRGI_OK);
  MRGI_CHECK(images_equal(&with, &tree_with));
  mrgi_image_destroy(&with);
  mrgi_image_destroy(&tree_with);
  mrgi_image_destroy(&eye_plain);

  free(voxels);
  mrgi_image_destroy(&plain);
  mrgi_image_destroy(&tree_plain);
  free(far_atlas);
  free(zero_atlas);
  free(random_atlas);
  free(rec.position);
  free(rec.normal);
  mrgi_vpl_tree_destroy(&tree);
  test_rsm_free(&map);
}

int main(int argc, char** argv)
{
  static const mrgi_test_case cases[] = { MRGI_TEST_CASE(test_plane_occluder),
    MRGI_TEST_CASE(test_bias_no_self_shadow), MRGI_TEST_CASE(test_sparse_defaults),
    MRGI_TEST_CASE(test_pcf_stays_in_tile), MRGI_TEST_CASE(test_grazing_rule),
    MRGI_TEST_CASE(test_bad_params), MRGI_TEST_CASE(test_gathers) };
  return MRGI_TEST_MAIN(argc, argv, cases);
}
