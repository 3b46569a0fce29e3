/* Tests of mrgi_vpl_clusters (ISR, NSW09 3.4): thresholds +inf give the
 * 16 x 16 grid exactly, thresholds 0 give every node of the finest light
 * level, energy is conserved for random thresholds, the uncapped selection
 * is the eye side's one-pass mask, the cap is deterministic and kept, and
 * bad arguments give clear errors. */
#include "mrgi_multires.h"
#include "mrgi_test_rsm.h"
#include "mrgi_vpl.h"
#include "mrgi_vpl_clusters.h"
#include "mrgi_vpl_tree.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static mrgi_vpl vpls[MRGI_VPL_CLUSTER_MAX];
static mrgi_vpl grid[MRGI_VPL_MAX_COUNT];

static mrgi_vpl_cluster_params params_with(double depth, double normal)
{
  mrgi_vpl_cluster_params p;
  mrgi_vpl_cluster_params_default(&p);
  p.depth_threshold = depth;
  p.normal_threshold = normal;
  return p;
}

/* A spot view of the corner scene, S = `size`. */
static test_rsm corner_spot(int32_t size)
{
  test_rsm t = test_rsm_make(size, 1);
  const double where[3] = { 0.2, 0.1, -0.3 };
  test_camera(&t.cameras[0], 0.35, where, 0, 80.0);
  test_rsm_fill_corner(&t, 0);
  return t;
}

/* Thresholds +inf == mrgi_vpl_select_grid with G = 16 per view, bit for bit. */
static void test_infinite_thresholds_are_the_grid(void)
{
  test_rsm spot = corner_spot(256);
  test_rsm cube = test_rsm_make(64, 6);
  test_rsm_fill_random(&cube, 21u, 0.5);
  test_rsm ortho = test_rsm_make(128, 1);
  const double where[3] = { 0.0, 0.0, -1.0 };
  test_camera(&ortho.cameras[0], 0.2, where, 1, 5.0);
  test_rsm_fill_corner(&ortho, 0);
  test_rsm* maps[] = { &spot, &cube, &ortho };
  for (int k = 0; k < 3; ++k)
  {
    const mrgi_vpl_cluster_params p = params_with(INFINITY, INFINITY);
    mrgi_vpl_cluster_info info;
    MRGI_CHECK(mrgi_vpl_select_clusters(&maps[k]->rsm, maps[k]->cameras, &p, vpls,
                                        MRGI_VPL_CLUSTER_MAX, &info, NULL) == MRGI_OK);
    const int32_t n = 256 * maps[k]->rsm.view_count;
    mrgi_vpl_selection_info grid_info;
    MRGI_CHECK(mrgi_vpl_select_grid(&maps[k]->rsm, n, grid, MRGI_VPL_MAX_COUNT, &grid_info,
                                    NULL) == MRGI_OK);
    MRGI_CHECK(grid_info.vpl_count == n);
    MRGI_CHECK(info.vpl_count == n);
    MRGI_CHECK(info.empty_vpl_count == grid_info.empty_vpl_count);
    MRGI_CHECK(info.capped == 0);
    MRGI_CHECK(memcmp(vpls, grid, sizeof(mrgi_vpl) * (size_t)n) == 0);
    test_rsm_free(maps[k]);
  }
}

/* Thresholds 0 == every non-empty node of level f_L (default: side 64). */
static void test_zero_thresholds_are_the_finest_level(void)
{
  for (int32_t size = 128; size <= 256; size *= 2)
  {
    test_rsm t = corner_spot(size);
    mrgi_vpl_tree tree;
    MRGI_CHECK(mrgi_vpl_tree_build(&t.rsm, t.cameras, &tree, NULL) == MRGI_OK);
    const int32_t f = mrgi_vpl_cluster_finest_level(&tree, MRGI_VPL_CLUSTER_FINEST_AUTO);
    MRGI_CHECK(tree.layout.level_width[f] == 64);
    const mrgi_vpl_cluster_params p = params_with(0.0, 0.0);
    mrgi_vpl_cluster_info info;
    MRGI_CHECK(mrgi_vpl_select_clusters(&t.rsm, t.cameras, &p, vpls, MRGI_VPL_CLUSTER_MAX,
                                        &info, NULL) == MRGI_OK);
    MRGI_CHECK(info.finest_level == f);
    MRGI_CHECK(info.capped == 0);
    int32_t expected = 0;
    for (int32_t y = 0; y < 64; ++y)
    {
      for (int32_t x = 0; x < 64; ++x)
      {
        mrgi_vpl node = tree.nodes[mrgi_vpl_tree_index(&tree, f, 0, x, y)];
        if (node.area == 0.0f && node.normal[2] == 0.0f && node.normal[1] == 0.0f &&
            node.normal[0] == 0.0f)
        {
          continue; /* no usable texel */
        }
        node.pad0 = node.pad1 = 0.0f;
        MRGI_CHECK(expected < info.vpl_count);
        MRGI_CHECK(memcmp(&vpls[expected], &node, sizeof(node)) == 0);
        ++expected;
      }
    }
    /* Every texel of the corner scene but the sky is usable: a real test of refinement. */
    MRGI_CHECK(expected > 64 * 64 / 2);
    MRGI_CHECK(info.per_level[f] == expected);
    /* Only empty roots remain at coarser levels. */
    MRGI_CHECK(info.vpl_count == expected + info.empty_vpl_count);
    mrgi_vpl_tree_destroy(&tree);
    test_rsm_free(&t);
  }
}

/* Energy is conserved, and without the cap the selection is the one-pass mask. */
static void test_energy_and_one_pass(void)
{
  uint32_t state = 4242u;
  for (int trial = 0; trial < 12; ++trial)
  {
    test_rsm t = test_rsm_make(128, 2);
    const double w0[3] = { 0.1, 0.0, 0.2 };
    const double w1[3] = { -0.3, 0.2, 0.0 };
    test_camera(&t.cameras[0], 0.1 * trial, w0, 0, 60.0 + 5.0 * trial);
    test_camera(&t.cameras[1], -0.2 * trial, w1, trial % 2, trial % 2 ? 4.0 : 90.0);
    test_rsm_fill_corner(&t, 0);
    test_rsm_fill_corner(&t, 1);
    if (trial % 3 == 0)
    {
      t.flux[4 * test_rsm_index(&t, 1, 40, 40)] = NAN; /* a rejected texel */
    }
    mrgi_vpl_cluster_params p =
      params_with(trial == 0 ? INFINITY : 8.0 * test_uniform(&state),
                  trial == 1 ? INFINITY : 0.6 * test_uniform(&state));
    p.finest_level = trial % 4 == 3 ? 0 : MRGI_VPL_CLUSTER_FINEST_AUTO;
    mrgi_vpl_tree tree;
    MRGI_CHECK(mrgi_vpl_tree_build(&t.rsm, t.cameras, &tree, NULL) == MRGI_OK);
    const size_t per_view = (size_t)mrgi_multires_texel_count(&tree.layout);
    uint8_t* flags = (uint8_t*)malloc(2 * per_view);
    uint8_t* mask = (uint8_t*)malloc(per_view);
    uint8_t* selected = (uint8_t*)malloc((size_t)tree.node_count);
    MRGI_CHECK(flags && mask && selected);
    MRGI_CHECK(mrgi_vpl_cluster_flags(&t.rsm, t.cameras, &tree, &p, flags, 2 * per_view, NULL) ==
               MRGI_OK);
    mrgi_vpl_cluster_info info;
    MRGI_CHECK(mrgi_vpl_clusters_from_flags(&tree, flags, 2 * per_view, &p, selected,
                                            (size_t)tree.node_count, vpls, MRGI_VPL_CLUSTER_MAX,
                                            &info, NULL) == MRGI_OK);
    double total[4];
    test_rsm_total(&t, total);
    double sum[4] = { 0, 0, 0, 0 };
    double sum_float[4] = { 0, 0, 0, 0 };
    for (int64_t node = 0; node < tree.node_count; ++node)
    {
      for (int c = 0; c < 4 && selected[node]; ++c)
      {
        sum[c] += tree.sums[4 * node + c];
      }
    }
    for (int32_t k = 0; k < info.vpl_count; ++k)
    {
      sum_float[0] += vpls[k].flux[0];
      sum_float[1] += vpls[k].flux[1];
      sum_float[2] += vpls[k].flux[2];
      sum_float[3] += vpls[k].area;
      MRGI_CHECK(vpls[k].pad0 == 0.0f && vpls[k].pad1 == 0.0f);
    }
    for (int c = 0; c < 4; ++c)
    {
      MRGI_CHECK_NEAR(sum[c] / total[c], 1.0, 1e-12);
      MRGI_CHECK_NEAR(sum_float[c] / total[c], 1.0, 1e-6);
    }
    MRGI_CHECK(info.rejected_texel_count == (trial % 3 == 0));
    if (info.capped == 0)
    {
      for (int32_t v = 0; v < 2; ++v)
      {
        MRGI_CHECK(mrgi_multires_select_one_pass(&tree.layout, flags + per_view * (size_t)v,
                                                 per_view, info.finest_level, mask, per_view,
                                                 NULL) == MRGI_OK);
        for (int32_t level = 0; level < tree.layout.level_count; ++level)
        {
          const int32_t w = tree.layout.level_width[level];
          for (int32_t y = 0; y < w; ++y)
          {
            for (int32_t x = 0; x < w; ++x)
            {
              const uint8_t flag = flags[per_view * (size_t)v +
                                         mrgi_multires_index(&tree.layout, level, x, y)];
              const int64_t node = mrgi_vpl_tree_index(&tree, level, v, x, y);
              const int ours = selected[node] && (flag & MRGI_MULTIRES_FLAG_NONEMPTY);
              MRGI_CHECK(ours == (mask[mrgi_multires_index(&tree.layout, level, x, y)] != 0));
            }
          }
        }
      }
    }
    if (trial >= 2)
    {
      MRGI_CHECK(info.vpl_count > 2 * 256); /* the corner refines somewhere */
    }
    else
    {
      MRGI_CHECK(info.vpl_count >= 2 * 256);
    }
    free(flags);
    free(mask);
    free(selected);
    mrgi_vpl_tree_destroy(&tree);
    test_rsm_free(&t);
  }
}

/* The cap: never exceeded, energy kept, coarse levels refined first, deterministic. */
static void test_cap(void)
{
  test_rsm t = test_rsm_make(256, 6);
  for (int32_t v = 0; v < 6; ++v)
  {
    const double where[3] = { 0.05 * v, 0.0, 0.0 };
    test_camera(&t.cameras[v], 1.0471975511965976 * v, where, 0, 90.0);
    test_rsm_fill_corner(&t, v);
  }
  double total[4];
  test_rsm_total(&t, total);
  const int32_t caps[] = { 6 * 256, 6 * 256 + 3, 2000, MRGI_VPL_CLUSTER_MAX };
  for (size_t k = 0; k < sizeof(caps) / sizeof(caps[0]); ++k)
  {
    mrgi_vpl_cluster_params p = params_with(0.0, 0.0);
    p.max_count = caps[k];
    mrgi_vpl_cluster_info info;
    MRGI_CHECK(mrgi_vpl_select_clusters(&t.rsm, t.cameras, &p, vpls, MRGI_VPL_CLUSTER_MAX,
                                        &info, NULL) == MRGI_OK);
    MRGI_CHECK(info.vpl_count <= caps[k]);
    MRGI_CHECK(info.capped > 0);
    MRGI_CHECK(info.vpl_count > caps[k] - 4); /* a refinement adds at most 3 */
    double sum[3] = { 0, 0, 0 };
    for (int32_t i = 0; i < info.vpl_count; ++i)
    {
      for (int c = 0; c < 3; ++c)
      {
        sum[c] += vpls[i].flux[c];
      }
    }
    for (int c = 0; c < 3; ++c)
    {
      MRGI_CHECK_NEAR(sum[c] / total[c], 1.0, 1e-6);
    }
    mrgi_vpl_cluster_info again;
    static mrgi_vpl second[MRGI_VPL_CLUSTER_MAX];
    MRGI_CHECK(mrgi_vpl_select_clusters(&t.rsm, t.cameras, &p, second, MRGI_VPL_CLUSTER_MAX,
                                        &again, NULL) == MRGI_OK);
    MRGI_CHECK(again.vpl_count == info.vpl_count);
    MRGI_CHECK(memcmp(second, vpls, sizeof(mrgi_vpl) * (size_t)info.vpl_count) == 0);
  }
  test_rsm_free(&t);
}

static void test_bad_arguments(void)
{
  test_rsm t = corner_spot(64);
  mrgi_error err;
  mrgi_vpl_cluster_params p = params_with(NAN, 0.1);
  MRGI_CHECK(mrgi_vpl_select_clusters(&t.rsm, t.cameras, &p, vpls, MRGI_VPL_CLUSTER_MAX, NULL,
                                      &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "depth threshold") != NULL);
  p = params_with(1.0, -0.5);
  MRGI_CHECK(mrgi_vpl_select_clusters(&t.rsm, t.cameras, &p, vpls, MRGI_VPL_CLUSTER_MAX, NULL,
                                      &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "normal threshold") != NULL);
  p = params_with(1.0, 0.1);
  p.finest_level = 7;
  MRGI_CHECK(mrgi_vpl_select_clusters(&t.rsm, t.cameras, &p, vpls, MRGI_VPL_CLUSTER_MAX, NULL,
                                      &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "finest level") != NULL);
  p = params_with(1.0, 0.1);
  p.max_count = 100; /* below the 256 roots */
  MRGI_CHECK(mrgi_vpl_select_clusters(&t.rsm, t.cameras, &p, vpls, MRGI_VPL_CLUSTER_MAX, NULL,
                                      &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "cap") != NULL);
  p.max_count = MRGI_VPL_CLUSTER_MAX + 1;
  MRGI_CHECK(mrgi_vpl_select_clusters(&t.rsm, t.cameras, &p, vpls, MRGI_VPL_CLUSTER_MAX, NULL,
                                      &err) == MRGI_ERR_INVALID_ARGUMENT);
  p = params_with(1.0, 0.1);
  MRGI_CHECK(mrgi_vpl_select_clusters(&t.rsm, t.cameras, &p, vpls, 300, NULL, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "holds 300") != NULL);
  MRGI_CHECK(mrgi_vpl_select_clusters(&t.rsm, t.cameras, &p, NULL, MRGI_VPL_CLUSTER_MAX, NULL,
                                      &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_vpl_select_clusters(&t.rsm, t.cameras, NULL, vpls, MRGI_VPL_CLUSTER_MAX, NULL,
                                      &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_vpl_select_clusters(NULL, t.cameras, &p, vpls, MRGI_VPL_CLUSTER_MAX, NULL,
                                      &err) == MRGI_ERR_INVALID_ARGUMENT);
  mrgi_vpl_tree tree;
  MRGI_CHECK(mrgi_vpl_tree_build(&t.rsm, t.cameras, &tree, NULL) == MRGI_OK);
  uint8_t flags[8];
  MRGI_CHECK(mrgi_vpl_cluster_flags(&t.rsm, t.cameras, &tree, &p, flags, sizeof(flags), &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "flags hold 8 bytes") != NULL);
  test_rsm other = test_rsm_make(32, 1);
  MRGI_CHECK(mrgi_vpl_cluster_flags(&other.rsm, t.cameras, &tree, &p, flags, sizeof(flags),
                                    &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "built for") != NULL);
  MRGI_CHECK(mrgi_vpl_cluster_finest_level(&tree, 9) == -1);
  MRGI_CHECK(mrgi_vpl_cluster_finest_level(NULL, 0) == -1);
  /* An empty map: only (empty) roots, no NaN, no error. */
  test_rsm empty = test_rsm_make(64, 1);
  mrgi_vpl_cluster_info info;
  p = params_with(0.0, 0.0);
  MRGI_CHECK(mrgi_vpl_select_clusters(&empty.rsm, empty.cameras, &p, vpls, MRGI_VPL_CLUSTER_MAX,
                                      &info, NULL) == MRGI_OK);
  MRGI_CHECK(info.vpl_count == 256 && info.empty_vpl_count == 256);
  test_rsm_free(&empty);
  test_rsm_free(&other);
  mrgi_vpl_tree_destroy(&tree);
  test_rsm_free(&t);
}

int main(int argc, char** argv)
{
  static const mrgi_test_case cases[] = {
    MRGI_TEST_CASE(test_infinite_thresholds_are_the_grid),
    MRGI_TEST_CASE(test_zero_thresholds_are_the_finest_level),
    MRGI_TEST_CASE(test_energy_and_one_pass),
    MRGI_TEST_CASE(test_cap),
    MRGI_TEST_CASE(test_bad_arguments),
  };
  return MRGI_TEST_MAIN(argc, argv, cases);
}
