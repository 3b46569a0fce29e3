/* Tests of mrgi_vpl_tree: the light-space receivers, node records equal to
 * the grid selection bit for bit at every level (spot, cube faces, ortho),
 * flux over random cuts equal to the RSM's total, rejected texels, the
 * bounding radius and max depth pads, padding of non-power-of-two maps,
 * empty views and bad arguments. */
#include "mrgi_test_rsm.h"
#include "mrgi_vpl.h"
#include "mrgi_vpl_tree.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

/* Records equal except the pads (grid VPLs have zero pads, tree nodes carry R_P, Dmax_P). */
static int same_record(const mrgi_vpl* a, const mrgi_vpl* b)
{
  mrgi_vpl x = *a;
  mrgi_vpl y = *b;
  x.pad0 = x.pad1 = y.pad0 = y.pad1 = 0.0f;
  return memcmp(&x, &y, sizeof(x)) == 0;
}

/* (a) Level-k nodes equal mrgi_vpl_select_grid() with G = S / 2^k. The grid
 * takes at most MRGI_VPL_MAX_COUNT VPLs, so each view is cut into tiles of
 * 64 * 2^k texels, each tile copied into a one-view RSM and gridded with
 * G = 64 (blocks of 2^k texels, the same texels as the tree's nodes). */
static void check_grid_equality(const test_rsm* t)
{
  mrgi_vpl_tree tree;
  MRGI_CHECK(mrgi_vpl_tree_build(&t->rsm, t->cameras, &tree, NULL) == MRGI_OK);
  const int32_t s = t->rsm.size;
  MRGI_CHECK(tree.side == s);
  test_rsm tile = test_rsm_make(s < 64 ? s : 64, 1);
  mrgi_vpl* grid = (mrgi_vpl*)malloc(sizeof(mrgi_vpl) * 4096);
  MRGI_CHECK(grid);
  int64_t compared = 0;
  for (int32_t level = 0; level < tree.layout.level_count; ++level)
  {
    const int32_t block = 1 << level;
    const int32_t w = s / block;
    const int32_t g = w < 64 ? w : 64;      /* grid side per tile */
    const int32_t tile_side = g * block;    /* texels per tile side */
    test_rsm_free(&tile);
    tile = test_rsm_make(tile_side, 1);
    for (int32_t v = 0; v < t->rsm.view_count; ++v)
    {
      for (int32_t ty = 0; ty < s / tile_side; ++ty)
      {
        for (int32_t tx = 0; tx < s / tile_side; ++tx)
        {
          for (int32_t y = 0; y < tile_side; ++y)
          {
            const size_t from = test_rsm_index(t, v, tx * tile_side, ty * tile_side + y);
            const size_t to = test_rsm_index(&tile, 0, 0, y);
            memcpy(tile.position + 4 * to, t->position + 4 * from, sizeof(float) * 4 * tile_side);
            memcpy(tile.normal + 4 * to, t->normal + 4 * from, sizeof(float) * 4 * tile_side);
            memcpy(tile.flux + 4 * to, t->flux + 4 * from, sizeof(float) * 4 * tile_side);
          }
          MRGI_CHECK(mrgi_vpl_select_grid(&tile.rsm, g * g, grid, 4096, NULL, NULL) == MRGI_OK);
          for (int32_t j = 0; j < g; ++j)
          {
            for (int32_t i = 0; i < g; ++i)
            {
              const int64_t node =
                mrgi_vpl_tree_index(&tree, level, v, tx * g + i, ty * g + j);
              if (!same_record(&tree.nodes[node], &grid[j * g + i]))
              {
                MRGI_FAIL("level %d view %d node (%d, %d) differs from the grid", level, v,
                          tx * g + i, ty * g + j);
              }
              ++compared;
            }
          }
        }
      }
    }
  }
  MRGI_CHECK(compared == tree.node_count);
  free(grid);
  test_rsm_free(&tile);
  mrgi_vpl_tree_destroy(&tree);
}

static void test_grid_equality_spot(void)
{
  test_rsm t = test_rsm_make(256, 1);
  const double where[3] = { 0.3, -0.2, 0.5 };
  test_camera(&t.cameras[0], 0.4, where, 0, 70.0);
  test_rsm_fill_random(&t, 7u, 0.8);
  check_grid_equality(&t);
  test_rsm_fill_corner(&t, 0); /* structured geometry over the random one */
  check_grid_equality(&t);
  test_rsm_free(&t);
}

static void test_grid_equality_cube(void)
{
  test_rsm t = test_rsm_make(256, 6);
  for (int32_t v = 0; v < 6; ++v)
  {
    const double where[3] = { 0.1 * v, 0.0, -0.2 };
    test_camera(&t.cameras[v], 1.0471975511965976 * v, where, 0, 90.0);
  }
  test_rsm_fill_random(&t, 11u, 0.6);
  check_grid_equality(&t);
  test_rsm_free(&t);
}

static void test_grid_equality_ortho(void)
{
  test_rsm t = test_rsm_make(256, 1);
  const double where[3] = { 0.0, 0.0, -1.0 };
  test_camera(&t.cameras[0], -0.3, where, 1, 4.0);
  test_rsm_fill_corner(&t, 0);
  check_grid_equality(&t);
  test_rsm_free(&t);
}

/* Sum over a random cut below `node` (descend with probability 1/2). */
static void cut_sum(const mrgi_vpl_tree* tree, int32_t level, int32_t view, int32_t x, int32_t y,
                    uint32_t* state, double sum[4], double sum_float[4], int64_t* nodes)
{
  if (level > 0 && test_uniform(state) < 0.5)
  {
    for (int32_t b = 0; b < 2; ++b)
    {
      for (int32_t a = 0; a < 2; ++a)
      {
        cut_sum(tree, level - 1, view, 2 * x + a, 2 * y + b, state, sum, sum_float, nodes);
      }
    }
    return;
  }
  const int64_t node = mrgi_vpl_tree_index(tree, level, view, x, y);
  for (int c = 0; c < 4; ++c)
  {
    sum[c] += tree->sums[4 * node + c];
  }
  sum_float[0] += tree->nodes[node].flux[0];
  sum_float[1] += tree->nodes[node].flux[1];
  sum_float[2] += tree->nodes[node].flux[2];
  sum_float[3] += tree->nodes[node].area;
  ++*nodes;
}

/* (b) The flux over any cut of the tree equals the RSM's total. */
static void test_cut_energy(void)
{
  test_rsm t = test_rsm_make(128, 2);
  test_rsm_fill_random(&t, 3u, 0.7);
  double total[4];
  test_rsm_total(&t, total);
  mrgi_vpl_tree tree;
  MRGI_CHECK(mrgi_vpl_tree_build(&t.rsm, t.cameras, &tree, NULL) == MRGI_OK);
  const int32_t top = tree.layout.level_count - 1;
  const int32_t roots = tree.layout.level_width[top];
  uint32_t state = 99u;
  for (int trial = 0; trial < 20; ++trial)
  {
    double sum[4] = { 0, 0, 0, 0 };
    double sum_float[4] = { 0, 0, 0, 0 };
    int64_t nodes = 0;
    for (int32_t v = 0; v < 2; ++v)
    {
      for (int32_t y = 0; y < roots; ++y)
      {
        for (int32_t x = 0; x < roots; ++x)
        {
          cut_sum(&tree, top, v, x, y, &state, sum, sum_float, &nodes);
        }
      }
    }
    MRGI_CHECK(nodes >= 2 * roots * roots);
    for (int c = 0; c < 4; ++c)
    {
      MRGI_CHECK(total[c] > 0.0);
      /* double sums in another order: equal to double rounding */
      MRGI_CHECK_NEAR(sum[c] / total[c], 1.0, 1e-12);
      /* float records: each rounded once */
      MRGI_CHECK_NEAR(sum_float[c] / total[c], 1.0, 1e-6);
    }
  }
  mrgi_vpl_tree_destroy(&tree);
  test_rsm_free(&t);
}

/* (c) NaN and negative texels are counted and skipped, as the grid does. */
static void test_rejected_texels(void)
{
  test_rsm t = test_rsm_make(64, 1);
  test_rsm_fill_random(&t, 5u, 1.0);
  /* Reject the texels nearest block centres so that representatives move too. */
  const size_t bad[] = { test_rsm_index(&t, 0, 8, 8), test_rsm_index(&t, 0, 31, 32),
                         test_rsm_index(&t, 0, 32, 32), test_rsm_index(&t, 0, 0, 63) };
  t.position[4 * bad[0] + 1] = NAN;
  t.flux[4 * bad[1] + 2] = -1.0f;
  t.normal[4 * bad[2] + 0] = INFINITY;
  t.flux[4 * bad[3] + 3] = -0.5f;
  double total[4];
  test_rsm_total(&t, total);
  mrgi_vpl_tree tree;
  MRGI_CHECK(mrgi_vpl_tree_build(&t.rsm, t.cameras, &tree, NULL) == MRGI_OK);
  MRGI_CHECK(tree.rejected_texel_count == 4);
  MRGI_CHECK(tree.usable_texel_count == 64 * 64 - 4);
  mrgi_vpl grid[16];
  mrgi_vpl_selection_info info;
  MRGI_CHECK(mrgi_vpl_select_grid(&t.rsm, 16, grid, 16, &info, NULL) == MRGI_OK);
  MRGI_CHECK(info.rejected_texel_count == tree.rejected_texel_count);
  MRGI_CHECK(info.usable_texel_count == tree.usable_texel_count);
  const int32_t top = tree.layout.level_count - 1; /* 16 x 16 roots: grid 16 is level 2 */
  MRGI_CHECK(tree.layout.level_width[top] == 16);
  double sum[4] = { 0, 0, 0, 0 };
  for (int32_t y = 0; y < 16; ++y)
  {
    for (int32_t x = 0; x < 16; ++x)
    {
      const int64_t node = mrgi_vpl_tree_index(&tree, top, 0, x, y);
      for (int c = 0; c < 4; ++c)
      {
        sum[c] += tree.sums[4 * node + c];
      }
      for (int c = 0; c < 3; ++c)
      {
        MRGI_CHECK(isfinite(tree.nodes[node].position[c]));
        MRGI_CHECK(isfinite(tree.nodes[node].normal[c]));
        MRGI_CHECK(tree.nodes[node].flux[c] >= 0.0f);
      }
    }
  }
  for (int c = 0; c < 4; ++c)
  {
    MRGI_CHECK_NEAR(sum[c] / total[c], 1.0, 1e-12);
  }
  /* The rejected level-0 nodes are empty records. */
  for (size_t k = 0; k < 4; ++k)
  {
    const int32_t x = (int32_t)(bad[k] % 64);
    const int32_t y = (int32_t)(bad[k] / 64);
    const mrgi_vpl* node = &tree.nodes[mrgi_vpl_tree_index(&tree, 0, 0, x, y)];
    MRGI_CHECK(node->flux[0] == 0.0f && node->area == 0.0f && node->normal[2] == 0.0f);
  }
  mrgi_vpl_tree_destroy(&tree);
  test_rsm_free(&t);
}

/* R_P and Dmax_P against a brute-force scan, perspective and orthographic. */
static void test_pads(void)
{
  for (int parallel = 0; parallel < 2; ++parallel)
  {
    test_rsm t = test_rsm_make(32, 1);
    const double where[3] = { 0.5, -0.25, -0.5 };
    test_camera(&t.cameras[0], 0.7, where, parallel, parallel ? 3.0 : 80.0);
    test_rsm_fill_corner(&t, 0);
    mrgi_vpl_tree tree;
    MRGI_CHECK(mrgi_vpl_tree_build(&t.rsm, t.cameras, &tree, NULL) == MRGI_OK);
    const float* m = t.cameras[0].world_to_view;
    for (int32_t level = 0; level < tree.layout.level_count; ++level)
    {
      const int32_t w = tree.layout.level_width[level];
      const int32_t span = 32 / w;
      for (int32_t y = 0; y < w; ++y)
      {
        for (int32_t x = 0; x < w; ++x)
        {
          const mrgi_vpl* node = &tree.nodes[mrgi_vpl_tree_index(&tree, level, 0, x, y)];
          double radius = 0.0;
          double depth = 0.0;
          int any = 0;
          for (int32_t j = y * span; j < (y + 1) * span; ++j)
          {
            for (int32_t i = x * span; i < (x + 1) * span; ++i)
            {
              const size_t k = test_rsm_index(&t, 0, i, j);
              if (!mrgi_rsm_texel_usable(&t.rsm, (int64_t)k))
              {
                continue;
              }
              any = 1;
              const float* p = t.position + 4 * k;
              double d2 = 0.0;
              double v[3];
              for (int c = 0; c < 3; ++c)
              {
                const double e = (double)p[c] - node->position[c];
                d2 += e * e;
                v[c] = (double)m[c] * p[0] + (double)m[4 + c] * p[1] + (double)m[8 + c] * p[2] +
                       m[12 + c];
              }
              radius = fmax(radius, sqrt(d2));
              depth = fmax(depth, parallel ? -v[2] : sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]));
            }
          }
          if (!any)
          {
            MRGI_CHECK(node->pad0 == 0.0f && node->pad1 == 0.0f);
            continue;
          }
          MRGI_CHECK(node->pad0 >= radius && node->pad0 <= radius * (1 + 1e-6) + 1e-30);
          MRGI_CHECK(node->pad1 >= depth && node->pad1 <= depth * (1 + 1e-6) + 1e-30);
          MRGI_CHECK(depth > 0.0);
        }
      }
    }
    mrgi_vpl_tree_destroy(&tree);
    test_rsm_free(&t);
  }
}

/* The receivers: light view space, padding invalid, usable texels only. */
static void test_receivers_and_padding(void)
{
  test_rsm t = test_rsm_make(100, 2);
  const double where[3] = { 1.0, 2.0, -3.0 };
  test_camera(&t.cameras[1], 0.9, where, 0, 60.0);
  test_rsm_fill_random(&t, 17u, 0.9);
  const size_t nan_texel = test_rsm_index(&t, 1, 3, 4);
  t.flux[4 * nan_texel] = NAN;
  MRGI_CHECK(mrgi_vpl_tree_side(100) == 128);
  MRGI_CHECK(mrgi_vpl_tree_side(128) == 128);
  MRGI_CHECK(mrgi_vpl_tree_side(1) == 1);
  MRGI_CHECK(mrgi_vpl_tree_side(0) == 0);
  const size_t floats = 4 * 128 * 128;
  float* position = (float*)malloc(sizeof(float) * floats);
  float* normal = (float*)malloc(sizeof(float) * floats);
  MRGI_CHECK(position && normal);
  mrgi_gather_receivers receivers;
  MRGI_CHECK(mrgi_rsm_view_receivers(&t.rsm, 1, &t.cameras[1], position, normal, floats,
                                     &receivers, NULL) == MRGI_OK);
  MRGI_CHECK(receivers.width == 128 && receivers.height == 128);
  const float* m = t.cameras[1].world_to_view;
  for (int32_t y = 0; y < 128; ++y)
  {
    for (int32_t x = 0; x < 128; ++x)
    {
      const size_t r = 4 * ((size_t)y * 128 + (size_t)x);
      if (x >= 100 || y >= 100)
      {
        MRGI_CHECK(position[r + 3] == 0.0f);
        continue;
      }
      const size_t k = test_rsm_index(&t, 1, x, y);
      const int usable = mrgi_rsm_texel_usable(&t.rsm, (int64_t)k);
      MRGI_CHECK(position[r + 3] == (usable ? MRGI_GBUFFER_VALID : 0.0f));
      if (!usable)
      {
        continue;
      }
      const float* p = t.position + 4 * k;
      const float* n = t.normal + 4 * k;
      for (int c = 0; c < 3; ++c)
      {
        const double pv = (double)m[c] * p[0] + (double)m[4 + c] * p[1] +
                          (double)m[8 + c] * p[2] + m[12 + c];
        const double nv = (double)m[c] * n[0] + (double)m[4 + c] * n[1] + (double)m[8 + c] * n[2];
        MRGI_CHECK_NEAR(position[r + (size_t)c], pv, 1e-5);
        MRGI_CHECK_NEAR(normal[r + (size_t)c], nv, 1e-6);
      }
    }
  }
  MRGI_CHECK(position[4 * (4 * 128 + 3) + 3] == 0.0f); /* the NaN texel */

  /* The padded tree: 128 x 128 levels, padding nodes empty, energy kept. */
  mrgi_vpl_tree tree;
  MRGI_CHECK(mrgi_vpl_tree_build(&t.rsm, t.cameras, &tree, NULL) == MRGI_OK);
  MRGI_CHECK(tree.side == 128 && tree.rsm_size == 100);
  MRGI_CHECK(tree.layout.level_count == 4); /* 128, 64, 32, 16 */
  MRGI_CHECK(tree.rejected_texel_count == 1);
  MRGI_CHECK(tree.nodes[mrgi_vpl_tree_index(&tree, 0, 0, 110, 5)].area == 0.0f);
  MRGI_CHECK(tree.nodes[mrgi_vpl_tree_index(&tree, 3, 1, 15, 15)].area == 0.0f);
  double total[4];
  test_rsm_total(&t, total);
  double roots[4] = { 0, 0, 0, 0 };
  for (int64_t node = 0; node < tree.level_first[2]; ++node)
  {
    for (int c = 0; c < 4; ++c)
    {
      roots[c] += tree.sums[4 * node + c];
    }
  }
  for (int c = 0; c < 4; ++c)
  {
    MRGI_CHECK_NEAR(roots[c] / total[c], 1.0, 1e-12);
  }
  /* Coarse levels first: the roots are the first V * 16 * 16 records. */
  MRGI_CHECK(tree.level_first[3] == 0 && tree.level_first[2] == 2 * 16 * 16);
  MRGI_CHECK(tree.node_count == 2 * (128 * 128 + 64 * 64 + 32 * 32 + 16 * 16));
  mrgi_vpl_tree_destroy(&tree);
  free(position);
  free(normal);
  test_rsm_free(&t);
}

/* (d) An empty view gives zero non-empty nodes; bad arguments give errors. */
static void test_empty_and_bad_arguments(void)
{
  test_rsm t = test_rsm_make(32, 1);
  mrgi_vpl_tree tree;
  MRGI_CHECK(mrgi_vpl_tree_build(&t.rsm, t.cameras, &tree, NULL) == MRGI_OK);
  MRGI_CHECK(tree.nonempty_node_count == 0);
  MRGI_CHECK(tree.usable_texel_count == 0 && tree.rejected_texel_count == 0);
  for (int64_t node = 0; node < tree.node_count; ++node)
  {
    const mrgi_vpl zero = { { 0, 0, 0 }, 0, { 0, 0, 0 }, 0, { 0, 0, 0 }, 0 };
    MRGI_CHECK(memcmp(&tree.nodes[node], &zero, sizeof(zero)) == 0);
  }
  mrgi_vpl_tree_destroy(&tree);
  mrgi_vpl_tree_destroy(&tree); /* idempotent */
  mrgi_vpl_tree_destroy(NULL);

  mrgi_error err;
  MRGI_CHECK(mrgi_vpl_tree_build(NULL, t.cameras, &tree, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "RSM") != NULL);
  MRGI_CHECK(mrgi_vpl_tree_build(&t.rsm, NULL, &tree, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "camera") != NULL);
  MRGI_CHECK(mrgi_vpl_tree_build(&t.rsm, t.cameras, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  test_rsm bad = t;
  bad.cameras[0].world_to_view[0] = 2.0f; /* not rigid */
  MRGI_CHECK(mrgi_vpl_tree_build(&t.rsm, bad.cameras, &tree, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(tree.nodes == NULL && tree.node_count == 0);
  bad = t;
  bad.cameras[0].projection.view_angle_deg = 180.0;
  MRGI_CHECK(mrgi_vpl_tree_build(&t.rsm, bad.cameras, &tree, &err) == MRGI_ERR_INVALID_ARGUMENT);
  bad = t;
  bad.cameras[0].projection.parallel = 1;
  bad.cameras[0].projection.parallel_scale = -1.0;
  MRGI_CHECK(mrgi_vpl_tree_build(&t.rsm, bad.cameras, &tree, &err) == MRGI_ERR_INVALID_ARGUMENT);
  bad = t;
  bad.rsm.size = 0;
  MRGI_CHECK(mrgi_vpl_tree_build(&bad.rsm, t.cameras, &tree, &err) == MRGI_ERR_INVALID_ARGUMENT);
  bad = t;
  bad.rsm.flux = NULL;
  MRGI_CHECK(mrgi_vpl_tree_build(&bad.rsm, t.cameras, &tree, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "flux") != NULL);

  float small[16];
  mrgi_gather_receivers receivers;
  MRGI_CHECK(mrgi_rsm_view_receivers(&t.rsm, 0, &t.cameras[0], small, small, 16, &receivers,
                                     &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "hold 16 floats") != NULL);
  MRGI_CHECK(mrgi_rsm_view_receivers(&t.rsm, 1, &t.cameras[0], small, small, 16, &receivers,
                                     &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "view 1") != NULL);
  MRGI_CHECK(mrgi_rsm_view_receivers(&t.rsm, 0, NULL, small, small, 16, &receivers, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_rsm_view_receivers(&t.rsm, 0, &t.cameras[0], NULL, small, 16, &receivers,
                                     &err) == MRGI_ERR_INVALID_ARGUMENT);
  test_rsm_free(&t);
}

int main(int argc, char** argv)
{
  static const mrgi_test_case cases[] = {
    MRGI_TEST_CASE(test_grid_equality_spot),
    MRGI_TEST_CASE(test_grid_equality_cube),
    MRGI_TEST_CASE(test_grid_equality_ortho),
    MRGI_TEST_CASE(test_cut_energy),
    MRGI_TEST_CASE(test_rejected_texels),
    MRGI_TEST_CASE(test_pads),
    MRGI_TEST_CASE(test_receivers_and_padding),
    MRGI_TEST_CASE(test_empty_and_bad_arguments),
  };
  return MRGI_TEST_MAIN(argc, argv, cases);
}
