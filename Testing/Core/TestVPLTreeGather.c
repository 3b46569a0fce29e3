/* Tests of mrgi_vpl_tree_gather (NSW09 3.5, the HISR VPL tree): tau >= 1 is
 * the 16 x 16 grid gather and tau = 0 the gather over every usable texel,
 * on spot, cube-face, orthographic and non-power-of-two maps, in world and
 * light-view receiver spaces; the error against tau = 0 does not grow and
 * the VPL count does not shrink as tau falls; the refinement bound is
 * conservative and in [0, 1]; the cull is exact; the statistics, stack
 * depth and GPU batch sizes; bad arguments, bad receivers, black maps. */
#include "mrgi_gather.h"
#include "mrgi_test_rsm.h"
#include "mrgi_vpl.h"
#include "mrgi_vpl_tree.h"
#include "mrgi_vpl_tree_gather.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

/* ---- maps and receivers ------------------------------------------------ */

enum
{
  MAP_SPOT,      /* 64^2, corner over random texels, perspective */
  MAP_CUBE,      /* 32^2 x 6 cube faces, random texels */
  MAP_ORTHO,     /* 64^2, corner, orthographic */
  MAP_CUBE_NPOT, /* 40^2 x 6 cube faces, corners: T = 64, padding */
  MAP_SPOT_NPOT, /* 24^2, corner over random texels: T = 32, padding */
  MAP_COUNT
};

static test_rsm make_map(int which)
{
  const double where[3] = { 0.3, -0.2, 0.5 };
  test_rsm t;
  switch (which)
  {
    case MAP_SPOT:
      t = test_rsm_make(64, 1);
      test_camera(&t.cameras[0], 0.4, where, 0, 70.0);
      test_rsm_fill_random(&t, 7u, 0.8);
      test_rsm_fill_corner(&t, 0);
      break;
    case MAP_CUBE:
      t = test_rsm_make(32, 6);
      for (int32_t v = 0; v < 6; ++v)
      {
        test_camera(&t.cameras[v], 1.0471975511965976 * v, where, 0, 90.0);
      }
      test_rsm_fill_random(&t, 11u, 0.6);
      break;
    case MAP_ORTHO:
      t = test_rsm_make(64, 1);
      test_camera(&t.cameras[0], -0.3, where, 1, 4.0);
      test_rsm_fill_corner(&t, 0);
      break;
    case MAP_CUBE_NPOT:
      t = test_rsm_make(40, 6);
      for (int32_t v = 0; v < 6; ++v)
      {
        test_camera(&t.cameras[v], 1.0471975511965976 * v, where, 0, 90.0);
        test_rsm_fill_corner(&t, v);
      }
      break;
    default:
      t = test_rsm_make(24, 1);
      test_camera(&t.cameras[0], 0.9, where, 0, 60.0);
      test_rsm_fill_random(&t, 17u, 0.9);
      test_rsm_fill_corner(&t, 0);
      break;
  }
  return t;
}

typedef struct test_receivers
{
  float* position;
  float* normal;
  mrgi_gather_receivers r;
  int has_matrix; /* 0: world space */
  float matrix[16];
} test_receivers;

/* The world -> receiver matrix (NULL for world-space receivers). */
static const float* receiver_matrix(const test_receivers* t)
{
  return t->has_matrix ? t->matrix : NULL;
}

static void receivers_alloc(test_receivers* out, int32_t w, int32_t h)
{
  memset(out, 0, sizeof(*out));
  out->position = (float*)calloc(4 * (size_t)w * (size_t)h, sizeof(float));
  out->normal = (float*)calloc(4 * (size_t)w * (size_t)h, sizeof(float));
  MRGI_CHECK(out->position && out->normal);
  out->r.width = w;
  out->r.height = h;
  out->r.position = out->position;
  out->r.normal = out->normal;
}

static void receivers_free(test_receivers* t)
{
  free(t->position);
  free(t->normal);
}

/* W x H world-space receivers in [-6, 6]^3 with random unit normals; one in
 * ten invalid. */
static test_receivers random_receivers(uint32_t seed, int32_t w, int32_t h)
{
  test_receivers t;
  receivers_alloc(&t, w, h);
  uint32_t state = seed;
  for (size_t i = 0; i < (size_t)w * (size_t)h; ++i)
  {
    double n[3] = { test_uniform(&state) - 0.5, test_uniform(&state) - 0.5,
                    test_uniform(&state) - 0.5 };
    const double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]) + 1e-9;
    for (int c = 0; c < 3; ++c)
    {
      t.position[4 * i + c] = (float)(12.0 * test_uniform(&state) - 6.0);
      t.normal[4 * i + c] = (float)(n[c] / len);
    }
    t.position[4 * i + 3] = test_uniform(&state) < 0.1 ? 0.0f : MRGI_GBUFFER_VALID;
  }
  return t;
}

/* The map's view 0 as a G-buffer in the light's view space (the receivers
 * sit on the VPLs' own surfaces), with its world -> view matrix. */
static test_receivers light_view_receivers(const test_rsm* map)
{
  test_receivers t;
  const int32_t side = mrgi_vpl_tree_side(map->rsm.size);
  receivers_alloc(&t, side, side);
  MRGI_CHECK(mrgi_rsm_view_receivers(&map->rsm, 0, &map->cameras[0], t.position, t.normal,
                                     4 * (size_t)side * (size_t)side, &t.r, NULL) == MRGI_OK);
  memcpy(t.matrix, map->cameras[0].world_to_view, sizeof(t.matrix));
  t.has_matrix = 1;
  return t;
}

/* ---- references ------------------------------------------------------- */

/* mrgi_gather_full() over `vpls` (any count: chunks of MRGI_VPL_MAX_COUNT,
 * summed in double into `sum`, W*H*3). */
static void gather_chunks(const test_receivers* rec, const mrgi_vpl* vpls, int64_t count,
                          double* sum)
{
  const size_t values = 3 * (size_t)rec->r.width * (size_t)rec->r.height;
  memset(sum, 0, sizeof(double) * values);
  for (int64_t first = 0; first < count; first += MRGI_VPL_MAX_COUNT)
  {
    const int64_t left = count - first;
    const int32_t n = (int32_t)(left < MRGI_VPL_MAX_COUNT ? left : MRGI_VPL_MAX_COUNT);
    mrgi_image image;
    mrgi_error err;
    if (mrgi_gather_full(&rec->r, vpls + first, n, receiver_matrix(rec), &image, NULL, &err) !=
        MRGI_OK)
    {
      MRGI_FAIL("reference gather: %s", err.message);
    }
    for (size_t k = 0; k < values; ++k)
    {
      sum[k] += image.pixels[k];
    }
    mrgi_image_destroy(&image);
  }
}

/* Every usable texel of the map as its own VPL (position, normal, flux, area). */
static mrgi_vpl* texel_vpls(const test_rsm* map, int64_t* out_count)
{
  const int64_t texels = (int64_t)map->rsm.view_count * map->rsm.size * map->rsm.size;
  mrgi_vpl* vpls = (mrgi_vpl*)calloc((size_t)texels, sizeof(mrgi_vpl));
  MRGI_CHECK(vpls);
  int64_t count = 0;
  for (int64_t i = 0; i < texels; ++i)
  {
    if (!mrgi_rsm_texel_usable(&map->rsm, i))
    {
      continue;
    }
    mrgi_vpl* v = vpls + count++;
    for (int c = 0; c < 3; ++c)
    {
      v->position[c] = map->position[4 * i + c];
      v->normal[c] = map->normal[4 * i + c];
      v->flux[c] = map->flux[4 * i + c];
    }
    v->area = map->flux[4 * i + 3];
  }
  *out_count = count;
  return vpls;
}

/* Per value: |a - b| <= tol * max(|a|, |b|) (all values are >= 0: sums of
 * non-negative terms, so a relative check per pixel is meaningful). */
static void check_close(const float* a, const double* b, size_t values, double tol,
                        const char* what)
{
  double worst = 0.0;
  for (size_t k = 0; k < values; ++k)
  {
    MRGI_CHECK(isfinite(a[k]) && a[k] >= 0.0f);
    const double scale = fmax(fabs((double)a[k]), fabs(b[k]));
    const double diff = fabs((double)a[k] - b[k]);
    if (diff > tol * scale)
    {
      MRGI_FAIL("%s: value %zu is %.9g, expected %.9g (relative %.3g > %.3g)", what, k,
                (double)a[k], b[k], diff / scale, tol);
    }
    worst = scale > 0.0 && diff / scale > worst ? diff / scale : worst;
  }
  printf("  %s: largest relative difference %.3g over %zu values\n", what, worst, values);
}

/* sum(out - ref)^2 / sum(ref)^2, square-rooted. */
static double relative_rms(const float* out, const float* ref, size_t values)
{
  double num = 0.0;
  double den = 0.0;
  for (size_t k = 0; k < values; ++k)
  {
    const double d = (double)out[k] - ref[k];
    num += d * d;
    den += (double)ref[k] * ref[k];
  }
  return den > 0.0 ? sqrt(num / den) : 0.0;
}

static void tree_gather(const test_receivers* rec, const mrgi_vpl_tree* tree, double tau,
                        mrgi_image* image, mrgi_image* vpls, mrgi_vpl_tree_gather_info* info)
{
  mrgi_error err;
  const mrgi_status status =
    mrgi_vpl_tree_gather(&rec->r, tree, tau, receiver_matrix(rec), image, vpls, info, &err);
  if (status != MRGI_OK)
  {
    MRGI_FAIL("tree gather at tau %g: %s", tau, err.message);
  }
}

/* ---- tau >= 1: the grid ---------------------------------------------- */

/* tau = 1 and +inf give exactly mrgi_gather_full() over the roots: the 16 x 16
 * grid for a power-of-two S (mrgi_vpl_tree.h: level-L nodes are the grid,
 * bit for bit), the level-L records for any S. The sums are the same terms
 * in the same order, so the images are bit-equal, not only close. */
static void test_threshold_one_is_the_grid(void)
{
  for (int which = 0; which < MAP_COUNT; ++which)
  {
    test_rsm map = make_map(which);
    mrgi_vpl_tree tree;
    MRGI_CHECK(mrgi_vpl_tree_build(&map.rsm, map.cameras, &tree, NULL) == MRGI_OK);
    const int32_t roots = mrgi_vpl_tree_root_count(&tree);
    MRGI_CHECK(roots == map.rsm.view_count * 256);
    mrgi_vpl* reference = (mrgi_vpl*)calloc((size_t)roots, sizeof(mrgi_vpl));
    MRGI_CHECK(reference);
    const int pot = tree.side == map.rsm.size;
    if (pot)
    {
      mrgi_vpl_selection_info sel;
      MRGI_CHECK(mrgi_vpl_select_grid(&map.rsm, roots, reference, roots, &sel, NULL) == MRGI_OK);
      MRGI_CHECK(sel.vpl_count == roots); /* G = 16 */
    }
    else
    {
      memcpy(reference, tree.nodes, sizeof(mrgi_vpl) * (size_t)roots); /* level L first */
    }
    test_receivers sets[2] = { light_view_receivers(&map),
                                random_receivers(31u + (uint32_t)which, 32, 24) };
    for (int s = 0; s < 2; ++s)
    {
      mrgi_image grid;
      MRGI_CHECK(mrgi_gather_full(&sets[s].r, reference, roots, receiver_matrix(&sets[s]), &grid,
                                  NULL, NULL) == MRGI_OK);
      const double taus[2] = { 1.0, INFINITY };
      for (int k = 0; k < 2; ++k)
      {
        mrgi_image image;
        mrgi_vpl_tree_gather_info info;
        tree_gather(&sets[s], &tree, taus[k], &image, NULL, &info);
        const size_t values = 3 * (size_t)image.width * (size_t)image.height;
        if (memcmp(image.pixels, grid.pixels, sizeof(float) * values) != 0)
        {
          MRGI_FAIL("map %d receivers %d tau %g: tree gather differs from the %s gather", which,
                    s, taus[k], pot ? "16x16 grid" : "root records");
        }
        MRGI_CHECK(info.nodes_visited == info.receivers_gathered * roots); /* roots only */
        MRGI_CHECK(info.max_stack_depth == 1);
        MRGI_CHECK(info.max_vpls_per_pixel <= roots);
        mrgi_image_destroy(&image);
      }
      double energy = 0.0;
      for (size_t k = 0; k < 3 * (size_t)grid.width * (size_t)grid.height; ++k)
      {
        energy += grid.pixels[k];
      }
      /* Random receivers see light on every map (the ortho corner's walls all
       * face +z and light none of each other: its own view is black). */
      if (s == 1 && !(energy > 0.0))
      {
        MRGI_FAIL("map %d receivers %d: the grid image is black", which, s);
      }
      mrgi_image_destroy(&grid);
      receivers_free(&sets[s]);
    }
    free(reference);
    mrgi_vpl_tree_destroy(&tree);
    test_rsm_free(&map);
  }
}

/* ---- tau = 0: every texel --------------------------------------------- */

static void test_threshold_zero_is_every_texel(void)
{
  for (int which = 0; which < MAP_COUNT; ++which)
  {
    test_rsm map = make_map(which);
    mrgi_vpl_tree tree;
    MRGI_CHECK(mrgi_vpl_tree_build(&map.rsm, map.cameras, &tree, NULL) == MRGI_OK);
    int64_t count = 0;
    mrgi_vpl* texels = texel_vpls(&map, &count);
    MRGI_CHECK(count == tree.usable_texel_count && count > 0);
    test_receivers sets[2] = { light_view_receivers(&map),
                                random_receivers(41u + (uint32_t)which, 32, 32) };
    for (int s = 0; s < 2; ++s)
    {
      const size_t pixels = (size_t)sets[s].r.width * (size_t)sets[s].r.height;
      double* reference = (double*)malloc(sizeof(double) * 3 * pixels);
      MRGI_CHECK(reference);
      gather_chunks(&sets[s], texels, count, reference);
      mrgi_image image;
      mrgi_image vpls;
      mrgi_vpl_tree_gather_info info;
      tree_gather(&sets[s], &tree, 0.0, &image, &vpls, &info);
      char what[96];
      snprintf(what, sizeof(what), "map %d (S %d, %d views) receivers %d, tau 0 vs %lld texels",
               which, map.rsm.size, map.rsm.view_count, s, (long long)count);
      check_close(image.pixels, reference, 3 * pixels, 1e-6, what);
      /* A receiver uses at most every usable texel once (culled ones not at all). */
      MRGI_CHECK(info.max_vpls_per_pixel <= count);
      MRGI_CHECK(info.vpls_used > 0);
      mrgi_image_destroy(&image);
      mrgi_image_destroy(&vpls);
      free(reference);
      receivers_free(&sets[s]);
    }
    free(texels);
    mrgi_vpl_tree_destroy(&tree);
    test_rsm_free(&map);
  }
}

/* ---- the error falls with tau ------------------------------------------ */

/* The corner lit by a 128^2 spot RSM (3 levels below the roots), seen by an
 * "eye" 32^2 G-buffer of the same corner (receivers on the VPLs' surfaces,
 * where refinement matters). As tau falls, every receiver's visited nodes
 * only grow (a node is visited iff all its ancestors' bounds exceed tau), but
 * a finer cut need not be closer to tau = 0 for every receiver; summed over
 * the image it is. The check allows no increase beyond 1e-9 relative (float
 * rounding of identical images) and prints the table. */
static void test_error_falls_with_threshold(void)
{
  const double where[3] = { 0.3, -0.2, 0.5 };
  test_rsm map = test_rsm_make(128, 1);
  test_camera(&map.cameras[0], 0.4, where, 0, 70.0);
  test_rsm_fill_corner(&map, 0);
  test_rsm eye = test_rsm_make(32, 1);
  test_camera(&eye.cameras[0], 0.4, where, 0, 55.0);
  test_rsm_fill_corner(&eye, 0);
  test_receivers rec;
  memset(&rec, 0, sizeof(rec));
  rec.r.width = 32;
  rec.r.height = 32;
  rec.r.position = eye.position; /* an RSM's world arrays are a G-buffer's layout */
  rec.r.normal = eye.normal;
  mrgi_vpl_tree tree;
  MRGI_CHECK(mrgi_vpl_tree_build(&map.rsm, map.cameras, &tree, NULL) == MRGI_OK);
  MRGI_CHECK(tree.layout.level_count == 4);
  mrgi_image reference;
  mrgi_vpl_tree_gather_info info0;
  tree_gather(&rec, &tree, 0.0, &reference, NULL, &info0);
  const size_t values = 3 * 32 * 32;
  const double taus[] = { 1.0, 0.5, 0.2, 0.1, 0.05, 0.02, 0.01, 0.005, 0.0 };
  double previous_error = INFINITY;
  double previous_mean = 0.0;
  double first_error = 0.0;
  printf("  tau      rel. RMS vs tau=0   mean VPLs/pixel\n");
  for (size_t k = 0; k < sizeof(taus) / sizeof(taus[0]); ++k)
  {
    mrgi_image image;
    mrgi_vpl_tree_gather_info info;
    tree_gather(&rec, &tree, taus[k], &image, NULL, &info);
    const double error = relative_rms(image.pixels, reference.pixels, values);
    printf("  %-8g %-19.6g %.2f\n", taus[k], error, info.mean_vpls_per_pixel);
    if (k == 0)
    {
      first_error = error;
    }
    if (!(error <= previous_error * (1.0 + 1e-9)))
    {
      MRGI_FAIL("error at tau %g (%g) exceeds the error at the larger tau (%g)", taus[k], error,
                previous_error);
    }
    if (!(info.mean_vpls_per_pixel >= previous_mean))
    {
      MRGI_FAIL("mean VPLs per pixel fell from %g to %g at tau %g", previous_mean,
                info.mean_vpls_per_pixel, taus[k]);
    }
    previous_error = error;
    previous_mean = info.mean_vpls_per_pixel;
    mrgi_image_destroy(&image);
  }
  MRGI_CHECK(previous_error == 0.0);   /* tau = 0 is the reference */
  MRGI_CHECK(first_error > 1e-3);      /* the grid is really approximate here */
  MRGI_CHECK(previous_mean == info0.mean_vpls_per_pixel);
  mrgi_image_destroy(&reference);
  mrgi_vpl_tree_destroy(&tree);
  test_rsm_free(&eye);
  test_rsm_free(&map);
}

/* ---- the bound ---------------------------------------------------------- */

/* For nodes of every level and random receivers (near and far), B_P is in
 * [0, 1] and bounds every usable texel's form factor even without its
 * cosines, A_t / (pi d_t^2 + A_t), and the node's own F_P. */
static void check_bounds(const test_rsm* map, uint32_t seed)
{
  mrgi_vpl_tree tree;
  MRGI_CHECK(mrgi_vpl_tree_build(&map->rsm, map->cameras, &tree, NULL) == MRGI_OK);
  uint32_t state = seed;
  int64_t checked = 0;
  int64_t tight = 0; /* pairs with B_P > 0.5: the check is not only about far receivers */
  const int32_t s = map->rsm.size;
  for (int32_t level = 0; level < tree.layout.level_count; ++level)
  {
    const int32_t w = tree.layout.level_width[level];
    const int32_t span = tree.side / w;
    for (int32_t view = 0; view < tree.view_count; ++view)
    {
      for (int32_t y = 0; y < w; y += 3)
      {
        for (int32_t x = 0; x < w; x += 3)
        {
          const mrgi_vpl* node = tree.nodes + mrgi_vpl_tree_index(&tree, level, view, x, y);
          if (!(node->area > 0.0f))
          {
            const double any[3] = { 0.0, 0.0, 0.0 };
            MRGI_CHECK(mrgi_vpl_tree_refinement_bound(node, any) == 0.0);
            continue;
          }
          for (int trial = 0; trial < 6; ++trial)
          {
            double rx[3];
            /* Half the receivers within 2 R_P of the representative. */
            const double reach = trial % 2 ? 2.0 * node->pad0 + 0.05 : 12.0;
            for (int c = 0; c < 3; ++c)
            {
              rx[c] = (trial % 2 ? node->position[c] : 0.0) + reach * (test_uniform(&state) - 0.5);
            }
            if (trial == 0)
            {
              rx[0] = node->position[0]; /* at the representative: B_P = 1 */
              rx[1] = node->position[1];
              rx[2] = node->position[2];
            }
            const double bound = mrgi_vpl_tree_refinement_bound(node, rx);
            MRGI_CHECK(bound >= 0.0 && bound <= 1.0);
            if (trial == 0)
            {
              MRGI_CHECK(bound == 1.0);
            }
            tight += bound > 0.5;
            const double limit = bound * (1.0 + 1e-12);
            const double dc[3] = { node->position[0] - rx[0], node->position[1] - rx[1],
                                   node->position[2] - rx[2] };
            const double dc2 = dc[0] * dc[0] + dc[1] * dc[1] + dc[2] * dc[2];
            MRGI_CHECK(node->area / (MRGI_PI * dc2 + node->area) <= limit);
            for (int32_t ty = y * span; ty < (y + 1) * span && ty < s; ++ty)
            {
              for (int32_t tx = x * span; tx < (x + 1) * span && tx < s; ++tx)
              {
                const int64_t i = ((int64_t)view * s + ty) * s + tx;
                if (!mrgi_rsm_texel_usable(&map->rsm, i))
                {
                  continue;
                }
                const float* p = map->position + 4 * i;
                const double d[3] = { p[0] - rx[0], p[1] - rx[1], p[2] - rx[2] };
                const double area = map->flux[4 * i + 3];
                const double d2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
                const double form = area / (MRGI_PI * d2 + area);
                if (!(form <= limit))
                {
                  MRGI_FAIL("level %d node (%d, %d): texel (%d, %d) has form factor %.9g > "
                            "bound %.9g", level, x, y, tx, ty, form, bound);
                }
                ++checked;
              }
            }
          }
        }
      }
    }
  }
  printf("  %lld texel/receiver pairs under their node's bound, %lld node pairs with B > 0.5\n",
         (long long)checked, (long long)tight);
  MRGI_CHECK(checked > 500 && tight > 50);
  mrgi_vpl_tree_destroy(&tree);
}

static void test_bound_is_conservative(void)
{
  for (int which = 0; which < MAP_COUNT; ++which)
  {
    test_rsm map = make_map(which);
    check_bounds(&map, 97u + (uint32_t)which);
    test_rsm_free(&map);
  }
  /* NULL arguments: refine (conservative). */
  const double x[3] = { 0.0, 0.0, 0.0 };
  MRGI_CHECK(mrgi_vpl_tree_refinement_bound(NULL, x) == 1.0);
}

/* ---- the cull ----------------------------------------------------------- */

/* (a) A receiver with every node's bounding sphere behind its plane pops
 * only the roots and uses nothing, at tau = 0. (b) Receivers on the corner's
 * walls with normals tilted 60-89 degrees off the wall, so their planes cut
 * through the nodes: at tau = 0 they still equal the gather over every
 * texel, and they visit fewer nodes than a receiver facing everything. */
static void test_cull_is_exact(void)
{
  test_rsm map = make_map(MAP_SPOT);
  mrgi_vpl_tree tree;
  MRGI_CHECK(mrgi_vpl_tree_build(&map.rsm, map.cameras, &tree, NULL) == MRGI_OK);
  const int32_t roots = mrgi_vpl_tree_root_count(&tree);

  test_receivers away;
  receivers_alloc(&away, 1, 1);
  away.position[2] = 1000.0f; /* every texel has |p| < 60, every R_P < 120 */
  away.position[3] = MRGI_GBUFFER_VALID;
  away.normal[2] = 1.0f;
  mrgi_image image;
  mrgi_vpl_tree_gather_info info;
  tree_gather(&away, &tree, 0.0, &image, NULL, &info);
  MRGI_CHECK(image.pixels[0] == 0.0f && image.pixels[1] == 0.0f && image.pixels[2] == 0.0f);
  MRGI_CHECK(info.vpls_used == 0);
  MRGI_CHECK(info.nodes_visited == roots);
  mrgi_image_destroy(&image);
  away.normal[2] = -1.0f; /* the same point facing the scene refines everything */
  tree_gather(&away, &tree, 0.0, &image, NULL, &info);
  MRGI_CHECK(info.nodes_visited > 10 * roots && info.vpls_used > 0);
  const int64_t facing_visited = info.nodes_visited;
  mrgi_image_destroy(&image);
  receivers_free(&away);

  /* (b) Receivers on the surfaces, normals tilted towards a random tangent. */
  test_receivers tilted;
  const int32_t side = 64;
  receivers_alloc(&tilted, side, side);
  uint32_t state = 123u;
  for (size_t i = 0; i < (size_t)side * (size_t)side; ++i)
  {
    memcpy(tilted.position + 4 * i, map.position + 4 * i, 4 * sizeof(float));
    const float* n = map.normal + 4 * i;
    double t[3] = { test_uniform(&state) - 0.5, test_uniform(&state) - 0.5,
                    test_uniform(&state) - 0.5 };
    const double along = t[0] * n[0] + t[1] * n[1] + t[2] * n[2];
    for (int c = 0; c < 3; ++c)
    {
      t[c] -= along * n[c];
    }
    const double tl = sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]) + 1e-12;
    const double angle = (60.0 + 29.0 * test_uniform(&state)) * MRGI_PI / 180.0;
    for (int c = 0; c < 3; ++c)
    {
      tilted.normal[4 * i + c] = (float)(cos(angle) * n[c] + sin(angle) * t[c] / tl);
    }
  }
  int64_t count = 0;
  mrgi_vpl* texels = texel_vpls(&map, &count);
  double* reference = (double*)malloc(sizeof(double) * 3 * (size_t)side * (size_t)side);
  MRGI_CHECK(reference);
  gather_chunks(&tilted, texels, count, reference);
  tree_gather(&tilted, &tree, 0.0, &image, NULL, &info);
  check_close(image.pixels, reference, 3 * (size_t)side * (size_t)side, 1e-6,
              "tilted receivers, tau 0 vs every texel");
  const double mean_visited = (double)info.nodes_visited / (double)info.receivers_gathered;
  printf("  nodes visited per receiver: %.1f tilted, %lld facing the scene\n", mean_visited,
         (long long)facing_visited);
  MRGI_CHECK(mean_visited < 0.9 * (double)facing_visited); /* the cull did cut */
  mrgi_image_destroy(&image);
  free(reference);
  free(texels);
  receivers_free(&tilted);
  mrgi_vpl_tree_destroy(&tree);
  test_rsm_free(&map);
}

/* ---- statistics, stack and batches -------------------------------------- */

/* A tree struct with only the fields the batch functions read, for sides
 * too large to build in a unit test. */
static mrgi_vpl_tree layout_only_tree(int32_t rsm_size, int32_t views, mrgi_vpl* dummy)
{
  mrgi_vpl_tree tree;
  memset(&tree, 0, sizeof(tree));
  tree.rsm_size = rsm_size;
  tree.side = mrgi_vpl_tree_side(rsm_size);
  tree.view_count = views;
  MRGI_CHECK(mrgi_multires_layout_init(&tree.layout, tree.side, tree.side,
                                       MRGI_VPL_TREE_ROOT_SIDE, NULL) == MRGI_OK);
  tree.nodes = dummy;
  tree.node_count = 1;
  return tree;
}

static void test_statistics_and_batches(void)
{
  const int maps[] = { MAP_SPOT, MAP_CUBE, MAP_CUBE_NPOT, MAP_SPOT_NPOT };
  const double taus[] = { 0.0, 0.02, 0.3, 1.0 };
  for (size_t m = 0; m < sizeof(maps) / sizeof(maps[0]); ++m)
  {
    test_rsm map = make_map(maps[m]);
    mrgi_vpl_tree tree;
    MRGI_CHECK(mrgi_vpl_tree_build(&map.rsm, map.cameras, &tree, NULL) == MRGI_OK);
    const int32_t levels = tree.layout.level_count - 1;
    test_receivers rec = random_receivers(57u + (uint32_t)m, 24, 20);
    for (size_t k = 0; k < sizeof(taus) / sizeof(taus[0]); ++k)
    {
      mrgi_image image;
      mrgi_image vpls;
      mrgi_vpl_tree_gather_info info;
      tree_gather(&rec, &tree, taus[k], &image, &vpls, &info);
      MRGI_CHECK(vpls.width == 24 && vpls.height == 20 && vpls.channels == 1);
      double sum = 0.0;
      float largest = 0.0f;
      for (size_t p = 0; p < 24 * 20; ++p)
      {
        sum += vpls.pixels[p];
        largest = vpls.pixels[p] > largest ? vpls.pixels[p] : largest;
        if (rec.position[4 * p + 3] == 0.0f)
        {
          MRGI_CHECK(vpls.pixels[p] == 0.0f && image.pixels[3 * p] == 0.0f);
        }
      }
      MRGI_CHECK(sum == (double)info.vpls_used);
      MRGI_CHECK(largest == (float)info.max_vpls_per_pixel);
      MRGI_CHECK(info.receivers_gathered + info.receivers_invalid == 24 * 20);
      MRGI_CHECK(info.receivers_malformed == 0);
      MRGI_CHECK(info.mean_vpls_per_pixel ==
                 (double)info.vpls_used / (double)info.receivers_gathered);
      MRGI_CHECK(info.nodes_visited >= info.vpls_used);
      MRGI_CHECK(info.max_stack_depth >= 1 && info.max_stack_depth <= 3 * levels + 1);
      if (taus[k] == 0.0)
      {
        MRGI_CHECK(info.max_stack_depth == 3 * levels + 1); /* the bound is reached */
      }
      mrgi_image_destroy(&image);
      mrgi_image_destroy(&vpls);
    }
    /* The texture holds every record, coarse levels first. */
    int32_t tw = 0;
    int32_t th = 0;
    MRGI_CHECK(mrgi_vpl_tree_texture_size(&tree, &tw, &th, NULL) == MRGI_OK);
    MRGI_CHECK(tw == MRGI_VPL_TREE_RECORDS_PER_ROW * MRGI_VPL_TEXELS);
    MRGI_CHECK((int64_t)th * MRGI_VPL_TREE_RECORDS_PER_ROW >= tree.node_count);
    MRGI_CHECK((int64_t)(th - 1) * MRGI_VPL_TREE_RECORDS_PER_ROW < tree.node_count);
    receivers_free(&rec);
    mrgi_vpl_tree_destroy(&tree);
    test_rsm_free(&map);
  }
  /* Batches: the largest K with K * N_sub <= 65,535, for every accepted side. */
  mrgi_vpl dummy;
  memset(&dummy, 0, sizeof(dummy));
  const int32_t sides[] = { 1, 7, 16, 24, 32, 100, 256, 512, 1000, 1024 };
  for (size_t k = 0; k < sizeof(sides) / sizeof(sides[0]); ++k)
  {
    for (int32_t views = 1; views <= 6; views += 5)
    {
      mrgi_vpl_tree tree = layout_only_tree(sides[k], views, &dummy);
      const int32_t levels = tree.layout.level_count - 1;
      const int64_t n_sub = ((int64_t)1 << (2 * (levels + 1))) / 3; /* (4^(L+1) - 1) / 3 */
      const int64_t batch = mrgi_vpl_tree_roots_per_batch(&tree);
      MRGI_CHECK(batch >= 1);
      MRGI_CHECK(batch * n_sub <= MRGI_VPL_TREE_MAX_LOOP_ITERATIONS);
      MRGI_CHECK((batch + 1) * n_sub > MRGI_VPL_TREE_MAX_LOOP_ITERATIONS);
      MRGI_CHECK(3 * levels + 1 <= MRGI_VPL_TREE_STACK_SIZE);
      const int32_t w = tree.layout.level_width[levels];
      MRGI_CHECK(mrgi_vpl_tree_root_count(&tree) == views * w * w);
      MRGI_CHECK(w == (sides[k] < 16 ? mrgi_vpl_tree_side(sides[k]) : 16));
    }
  }
  mrgi_vpl_tree s1024 = layout_only_tree(1024, 6, &dummy);
  MRGI_CHECK(mrgi_vpl_tree_roots_per_batch(&s1024) == 12); /* N_sub = 5461 for L = 6 */
  mrgi_vpl_tree unbuilt;
  memset(&unbuilt, 0, sizeof(unbuilt));
  MRGI_CHECK(mrgi_vpl_tree_roots_per_batch(&unbuilt) == 0);
  MRGI_CHECK(mrgi_vpl_tree_root_count(&unbuilt) == 0);
  MRGI_CHECK(mrgi_vpl_tree_roots_per_batch(NULL) == 0);
}

/* ---- bad input ---------------------------------------------------------- */

static void expect_error(const test_receivers* rec, const mrgi_vpl_tree* tree, double tau,
                         const float* matrix, const char* needle)
{
  mrgi_error err;
  mrgi_image image;
  mrgi_image vpls;
  mrgi_vpl_tree_gather_info info;
  info.vpls_used = 77;
  const mrgi_status status = mrgi_vpl_tree_gather(rec ? &rec->r : NULL, tree, tau, matrix,
                                                  &image, &vpls, &info, &err);
  if (status != MRGI_ERR_INVALID_ARGUMENT || !strstr(err.message, needle))
  {
    MRGI_FAIL("expected an error naming '%s', got status %d: %s", needle, (int)status,
              status == MRGI_OK ? "(none)" : err.message);
  }
  MRGI_CHECK(image.pixels == NULL && vpls.pixels == NULL && info.vpls_used == 0);
}

static void test_bad_arguments(void)
{
  test_rsm map = make_map(MAP_SPOT_NPOT);
  mrgi_vpl_tree tree;
  MRGI_CHECK(mrgi_vpl_tree_build(&map.rsm, map.cameras, &tree, NULL) == MRGI_OK);
  test_receivers rec = random_receivers(5u, 8, 8);
  expect_error(NULL, &tree, 0.1, NULL, "receivers");
  expect_error(&rec, NULL, 0.1, NULL, "tree is NULL");
  mrgi_vpl_tree unbuilt;
  memset(&unbuilt, 0, sizeof(unbuilt));
  expect_error(&rec, &unbuilt, 0.1, NULL, "not built");
  expect_error(&rec, &tree, NAN, NULL, "tau");
  expect_error(&rec, &tree, -0.5, NULL, "tau");
  expect_error(&rec, &tree, -INFINITY, NULL, "tau");
  mrgi_vpl dummy;
  memset(&dummy, 0, sizeof(dummy));
  mrgi_vpl_tree big = layout_only_tree(MRGI_VPL_TREE_GATHER_MAX_RSM_SIZE + 1, 1, &dummy);
  expect_error(&rec, &big, 0.1, NULL, "MRGI_VPL_TREE_GATHER_MAX_RSM_SIZE");
  mrgi_vpl_tree modified = tree;
  modified.node_count -= 1;
  expect_error(&rec, &modified, 0.1, NULL, "do not match");
  modified = tree;
  modified.level_first[0] += 1;
  expect_error(&rec, &modified, 0.1, NULL, "do not match");
  float scaled[16] = { 2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 1 };
  expect_error(&rec, &tree, 0.1, scaled, "rigid");
  float projective[16] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, -1, 0, 0, 0, 0 };
  expect_error(&rec, &tree, 0.1, projective, "rigid");
  test_receivers empty = rec;
  empty.r.width = 0;
  MRGI_CHECK(mrgi_vpl_tree_gather(&empty.r, &tree, 0.1, NULL, &(mrgi_image){ 0 }, NULL, NULL,
                                  NULL) == MRGI_ERR_INVALID_ARGUMENT);
  test_receivers no_normals = rec;
  no_normals.r.normal = NULL;
  expect_error(&no_normals, &tree, 0.1, NULL, "normal");
  MRGI_CHECK(mrgi_vpl_tree_gather(&rec.r, &tree, 0.1, NULL, NULL, NULL, NULL, NULL) ==
             MRGI_ERR_INVALID_ARGUMENT);
  int32_t tw = 1;
  int32_t th = 1;
  MRGI_CHECK(mrgi_vpl_tree_texture_size(&unbuilt, &tw, &th, NULL) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(tw == 0 && th == 0);
  MRGI_CHECK(mrgi_vpl_tree_texture_size(&tree, NULL, &th, NULL) == MRGI_ERR_INVALID_ARGUMENT);

  /* Invalid and malformed receivers get 0 and 0 VPLs; +inf is a valid tau. */
  test_receivers bad;
  receivers_alloc(&bad, 4, 1);
  const float valid = MRGI_GBUFFER_VALID;
  const float setup[4][8] = {
    { 0, 0, 0, 0, 0, 0, 1, 0 },           /* flag not set */
    { NAN, 0, 0, valid, 0, 0, 1, 0 },     /* NaN position */
    { 0, 0, 0, valid, 0, 0, 0, 0 },       /* zero normal */
    { 0, 0, INFINITY, valid, 0, 0, 1, 0 } /* infinite position */
  };
  for (int i = 0; i < 4; ++i)
  {
    memcpy(bad.position + 4 * i, setup[i], 4 * sizeof(float));
    memcpy(bad.normal + 4 * i, setup[i] + 4, 4 * sizeof(float));
  }
  bad.normal[4 * 1 + 0] = NAN;
  mrgi_image image;
  mrgi_image vpls;
  mrgi_vpl_tree_gather_info info;
  tree_gather(&bad, &tree, INFINITY, &image, &vpls, &info);
  MRGI_CHECK(info.receivers_invalid == 1 && info.receivers_malformed == 3);
  MRGI_CHECK(info.receivers_gathered == 0 && info.vpls_used == 0);
  MRGI_CHECK(info.mean_vpls_per_pixel == 0.0);
  for (int k = 0; k < 12; ++k)
  {
    MRGI_CHECK(image.pixels[k] == 0.0f);
  }
  for (int k = 0; k < 4; ++k)
  {
    MRGI_CHECK(vpls.pixels[k] == 0.0f);
  }
  mrgi_image_destroy(&image);
  mrgi_image_destroy(&vpls);
  receivers_free(&bad);

  /* An all-black RSM (surfaces seen, no flux) and an empty one give 0
   * everywhere, no VPL, no error. */
  for (int black = 0; black < 2; ++black)
  {
    test_rsm dark = make_map(MAP_CUBE_NPOT);
    const size_t texels = 6 * 40 * 40;
    for (size_t i = 0; i < texels; ++i)
    {
      dark.flux[4 * i + 0] = dark.flux[4 * i + 1] = dark.flux[4 * i + 2] = 0.0f;
      if (!black)
      {
        dark.position[4 * i + 3] = 0.0f;
      }
    }
    mrgi_vpl_tree dark_tree;
    MRGI_CHECK(mrgi_vpl_tree_build(&dark.rsm, dark.cameras, &dark_tree, NULL) == MRGI_OK);
    tree_gather(&rec, &dark_tree, 0.0, &image, &vpls, &info);
    MRGI_CHECK(info.vpls_used == 0 && info.receivers_gathered > 0);
    MRGI_CHECK(info.nodes_visited ==
               info.receivers_gathered * mrgi_vpl_tree_root_count(&dark_tree));
    for (size_t k = 0; k < 3 * 64; ++k)
    {
      MRGI_CHECK(image.pixels[k] == 0.0f);
    }
    mrgi_image_destroy(&image);
    mrgi_image_destroy(&vpls);
    mrgi_vpl_tree_destroy(&dark_tree);
    test_rsm_free(&dark);
  }
  receivers_free(&rec);
  mrgi_vpl_tree_destroy(&tree);
  test_rsm_free(&map);
}

int main(int argc, char** argv)
{
  static const mrgi_test_case cases[] = {
    MRGI_TEST_CASE(test_threshold_one_is_the_grid),
    MRGI_TEST_CASE(test_threshold_zero_is_every_texel),
    MRGI_TEST_CASE(test_error_falls_with_threshold),
    MRGI_TEST_CASE(test_bound_is_conservative),
    MRGI_TEST_CASE(test_cull_is_exact),
    MRGI_TEST_CASE(test_statistics_and_batches),
    MRGI_TEST_CASE(test_bad_arguments),
  };
  return MRGI_TEST_MAIN(argc, argv, cases);
}
