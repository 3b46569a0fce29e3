/**
 * @file TestIncrementalStencil.c
 * @brief mrgi_incremental_stencil_build() (NPW10 3.4): texels re-rendered
 *        below the geometric cut where a coarser 3x3 saw a visibility
 *        discontinuity, on a flat image with a vertical shadow edge; the
 *        threshold extremes, refined texels, non-receivers, the finest level,
 *        and bad input.
 */
#include "mrgi_incremental_stencil.h"
#include "mrgi_test.h"
#include "mrgi_visibility_pyramid.h"

#include <string.h>

enum
{
  SIDE = 64,
  COARSEST = 8, /* levels 64, 32, 16, 8: L = 3 */
  SAMPLES = 64,
  WORDS = 2
};
static const double EDGE_X = 20.3; /* full-resolution x of the shadow edge */

typedef struct scene
{
  mrgi_multires_layout layout;
  size_t texels;
  uint8_t* flags;
  uint8_t* selection;
  float* position;
  uint32_t* masks;
  uint8_t* rendered;
} scene;

/* A flat, fully valid image: every texel NONEMPTY, nothing refined, the
 * geometric selection is the coarsest level; texels left of EDGE_X see every
 * sample, the others none. */
static void scene_init(scene* s)
{
  MRGI_CHECK(mrgi_multires_layout_init(&s->layout, SIDE, SIDE, COARSEST, NULL) == MRGI_OK);
  MRGI_CHECK(s->layout.level_count == 4);
  s->texels = (size_t)mrgi_multires_texel_count(&s->layout);
  s->flags = calloc(s->texels, 1);
  s->selection = calloc(s->texels, 1);
  s->position = calloc(4 * s->texels, sizeof(float));
  s->masks = calloc((size_t)WORDS * s->texels, sizeof(uint32_t));
  s->rendered = calloc(s->texels, 1);
  MRGI_CHECK(s->flags && s->selection && s->position && s->masks && s->rendered);
  const int32_t coarsest = s->layout.level_count - 1;
  for (int32_t i = 0; i <= coarsest; ++i)
  {
    for (int32_t y = 0; y < s->layout.level_height[i]; ++y)
    {
      for (int32_t x = 0; x < s->layout.level_width[i]; ++x)
      {
        const size_t t = mrgi_multires_index(&s->layout, i, x, y);
        s->flags[t] = MRGI_MULTIRES_FLAG_NONEMPTY;
        s->selection[t] = i == coarsest;
        const double cx = (x + 0.5) * (double)(1 << i);
        s->position[4 * t + 0] = (float)cx;
        s->position[4 * t + 1] = (float)((y + 0.5) * (double)(1 << i));
        s->position[4 * t + 2] = -1.0f;
        s->position[4 * t + 3] = 1.0f;
        const uint32_t bits = cx < EDGE_X ? 0xFFFFFFFFu : 0u;
        s->masks[WORDS * t + 0] = bits;
        s->masks[WORDS * t + 1] = bits;
      }
    }
  }
}

static void scene_free(scene* s)
{
  free(s->flags);
  free(s->selection);
  free(s->position);
  free(s->masks);
  free(s->rendered);
}

static mrgi_status build(scene* s, int32_t finest, int32_t metric, int32_t threshold,
                         mrgi_incremental_stencil_stats* stats, mrgi_error* err)
{
  return mrgi_incremental_stencil_build(&s->layout, finest, s->flags, s->selection, s->texels,
                                        s->position, 4 * s->texels, s->masks, WORDS,
                                        (size_t)WORDS * s->texels, metric, threshold, s->rendered,
                                        s->texels, stats, err);
}

static int rendered_at(const scene* s, int32_t level, int32_t x, int32_t y)
{
  return s->rendered[mrgi_multires_index(&s->layout, level, x, y)];
}

static void test_shadow_edge(void)
{
  scene s;
  scene_init(&s);
  mrgi_incremental_stencil_stats stats;
  const int32_t threshold = mrgi_voxel_refine_threshold(0.5f, SAMPLES);
  MRGI_CHECK(build(&s, 0, MRGI_VOXEL_METRIC_DISAGREE, threshold, &stats, NULL) == MRGI_OK);
  /* the selection is kept */
  for (size_t t = 0; t < s.texels; ++t)
  {
    MRGI_CHECK(!s.selection[t] || s.rendered[t]);
  }
  MRGI_CHECK(stats.selected[3] == 64 && stats.added[3] == 0);
  /* the edge is rendered at every level down to full resolution: level 0
   * pixels 19..21 straddle it, in every row */
  for (int32_t y = 0; y < SIDE; ++y)
  {
    MRGI_CHECK(rendered_at(&s, 0, 19, y) && rendered_at(&s, 0, 20, y) && rendered_at(&s, 0, 21, y));
    MRGI_CHECK(rendered_at(&s, 1, 10, y / 2));
    /* far from it nothing below the coarsest level */
    MRGI_CHECK(!rendered_at(&s, 0, 2, y) && !rendered_at(&s, 0, 50, y));
    MRGI_CHECK(!rendered_at(&s, 1, 28, y / 2) && !rendered_at(&s, 2, 14, y / 4));
  }
  int64_t total = 0;
  for (int32_t i = 0; i < 4; ++i)
  {
    MRGI_CHECK(stats.added[i] >= 0);
    total += stats.selected[i] + stats.added[i];
  }
  MRGI_CHECK(total == stats.rendered_total);
  /* a band around the edge, not the image: level 0 adds a few columns */
  MRGI_CHECK(stats.added[0] >= 3 * SIDE && stats.added[0] <= 8 * SIDE);
  printf("shadow edge: added per level %lld %lld %lld, selected at L %lld\n",
         (long long)stats.added[0], (long long)stats.added[1], (long long)stats.added[2],
         (long long)stats.selected[3]);

  /* the count-spread metric sees the same edge */
  mrgi_incremental_stencil_stats spread;
  MRGI_CHECK(build(&s, 0, MRGI_VOXEL_METRIC_COUNT_SPREAD, threshold, &spread, NULL) == MRGI_OK);
  MRGI_CHECK(spread.rendered_total == stats.rendered_total);

  /* threshold above N: the geometric selection alone */
  MRGI_CHECK(build(&s, 0, MRGI_VOXEL_METRIC_DISAGREE, SAMPLES + 1, &stats, NULL) == MRGI_OK);
  MRGI_CHECK(memcmp(s.rendered, s.selection, s.texels) == 0);
  /* threshold 0: every texel of every level */
  MRGI_CHECK(build(&s, 0, MRGI_VOXEL_METRIC_DISAGREE, 0, &stats, NULL) == MRGI_OK);
  MRGI_CHECK(stats.rendered_total == 64 * 64 + 32 * 32 + 16 * 16 + 8 * 8);
  /* finest level 1: nothing at level 0 */
  MRGI_CHECK(build(&s, 1, MRGI_VOXEL_METRIC_DISAGREE, threshold, &stats, NULL) == MRGI_OK);
  MRGI_CHECK(stats.added[0] == 0 && stats.selected[0] == 0 && rendered_at(&s, 1, 10, 0));
  /* finest level past the coarsest is clamped */
  MRGI_CHECK(build(&s, 9, MRGI_VOXEL_METRIC_DISAGREE, threshold, &stats, NULL) == MRGI_OK);
  MRGI_CHECK(stats.rendered_total == 64);

  /* a geometrically refined texel above the finest level is not re-rendered
   * (finer selected texels cover it); at the finest level it is */
  const size_t refined = mrgi_multires_index(&s.layout, 1, 10, 5);
  s.flags[refined] |= MRGI_MULTIRES_FLAG_REFINE;
  MRGI_CHECK(build(&s, 0, MRGI_VOXEL_METRIC_DISAGREE, threshold, NULL, NULL) == MRGI_OK);
  MRGI_CHECK(!s.rendered[refined] && rendered_at(&s, 1, 10, 6));
  MRGI_CHECK(build(&s, 1, MRGI_VOXEL_METRIC_DISAGREE, threshold, NULL, NULL) == MRGI_OK);
  MRGI_CHECK(s.rendered[refined]);
  s.flags[refined] &= (uint8_t)~MRGI_MULTIRES_FLAG_REFINE;

  /* an empty texel is never rendered */
  const size_t empty = mrgi_multires_index(&s.layout, 0, 20, 7);
  s.flags[empty] = 0;
  MRGI_CHECK(build(&s, 0, MRGI_VOXEL_METRIC_DISAGREE, threshold, NULL, NULL) == MRGI_OK);
  MRGI_CHECK(!s.rendered[empty] && rendered_at(&s, 0, 20, 8));
  scene_free(&s);
}

/* Non-receivers do not count: a uniformly lit image with one invalid texel
 * whose mask says "hidden" adds nothing. */
static void test_non_receivers(void)
{
  scene s;
  scene_init(&s);
  for (size_t t = 0; t < s.texels; ++t)
  {
    s.masks[WORDS * t] = s.masks[WORDS * t + 1] = 0xFFFFFFFFu;
  }
  const size_t hole = mrgi_multires_index(&s.layout, 1, 12, 12);
  s.masks[WORDS * hole] = s.masks[WORDS * hole + 1] = 0u;
  mrgi_incremental_stencil_stats stats;
  MRGI_CHECK(build(&s, 0, MRGI_VOXEL_METRIC_DISAGREE, 1, &stats, NULL) == MRGI_OK);
  MRGI_CHECK(stats.added[0] > 0); /* as a receiver it fires */
  s.position[4 * hole + 3] = 0.0f;
  MRGI_CHECK(build(&s, 0, MRGI_VOXEL_METRIC_DISAGREE, 1, &stats, NULL) == MRGI_OK);
  MRGI_CHECK(stats.rendered_total == stats.selected[3]);
  s.position[4 * hole + 3] = 1.0f;
  s.position[4 * hole + 0] = NAN; /* not finite: not a receiver either */
  MRGI_CHECK(build(&s, 0, MRGI_VOXEL_METRIC_DISAGREE, 1, &stats, NULL) == MRGI_OK);
  MRGI_CHECK(stats.rendered_total == stats.selected[3]);
  scene_free(&s);
}

static int message_has(const mrgi_error* err, const char* text)
{
  return strstr(err->message, text) != NULL;
}

static void test_bad_input(void)
{
  scene s;
  scene_init(&s);
  memset(s.rendered, 7, s.texels);
  mrgi_error err;
  MRGI_CHECK(build(&s, 0, 5, 1, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(message_has(&err, "metric 5"));
  MRGI_CHECK(build(&s, 0, MRGI_VOXEL_METRIC_DISAGREE, -1, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(message_has(&err, "threshold -1"));
  MRGI_CHECK(build(&s, -2, MRGI_VOXEL_METRIC_DISAGREE, 1, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(message_has(&err, "finest level -2"));
  MRGI_CHECK(mrgi_incremental_stencil_build(&s.layout, 0, s.flags, s.selection, s.texels - 1,
                                            s.position, 4 * s.texels, s.masks, WORDS,
                                            WORDS * s.texels, 0, 1, s.rendered, s.texels, NULL,
                                            &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(message_has(&err, "flags holds"));
  MRGI_CHECK(mrgi_incremental_stencil_build(&s.layout, 0, s.flags, s.selection, s.texels,
                                            s.position, 4 * s.texels, s.masks, 0,
                                            WORDS * s.texels, 0, 1, s.rendered, s.texels, NULL,
                                            &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(message_has(&err, "mask words 0"));
  MRGI_CHECK(mrgi_incremental_stencil_build(&s.layout, 0, s.flags, s.selection, s.texels,
                                            s.position, 4 * s.texels, s.masks, WORDS,
                                            WORDS * s.texels - 1, 0, 1, s.rendered, s.texels,
                                            NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(message_has(&err, "masks"));
  MRGI_CHECK(mrgi_incremental_stencil_build(&s.layout, 0, s.flags, s.selection, s.texels, NULL,
                                            0, s.masks, WORDS, WORDS * s.texels, 0, 1, s.rendered,
                                            s.texels, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(message_has(&err, "receiver positions"));
  MRGI_CHECK(mrgi_incremental_stencil_build(&s.layout, 0, s.flags, s.selection, s.texels,
                                            s.position, 4 * s.texels, s.masks, WORDS,
                                            WORDS * s.texels, 0, 1, s.rendered, s.texels - 1,
                                            NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(message_has(&err, "output mask"));
  mrgi_multires_layout broken = s.layout;
  broken.level_count = 2;
  MRGI_CHECK(mrgi_incremental_stencil_build(&broken, 0, s.flags, s.selection, s.texels,
                                            s.position, 4 * s.texels, s.masks, WORDS,
                                            WORDS * s.texels, 0, 1, s.rendered, s.texels, NULL,
                                            &err) == MRGI_ERR_INVALID_ARGUMENT);
  /* nothing written on failure */
  for (size_t t = 0; t < s.texels; ++t)
  {
    MRGI_CHECK(s.rendered[t] == 7);
  }
  scene_free(&s);
}

/* The illumination rule, coarse to fine: "gather" E = light(x) at the
 * texels each level renders (E elsewhere is garbage the rule must not
 * read), then build the next level. Returns the texels rendered. */
static int64_t illuminate(scene* s, int32_t finest, float threshold, float* E, double (*light)(double),
                          int32_t metric)
{
  const int32_t coarsest = s->layout.level_count - 1;
  for (size_t t = 0; t < 4 * s->texels; ++t)
  {
    E[t] = 1.0e30f;
  }
  memset(s->rendered, 0, s->texels);
  int64_t total = 0;
  for (int32_t i = coarsest; i >= (finest < coarsest ? finest : coarsest); --i)
  {
    MRGI_CHECK(mrgi_incremental_stencil_illumination_level(
                 &s->layout, finest, i, s->flags, s->selection, s->texels, s->position,
                 4 * s->texels, E, 4 * s->texels, metric, threshold, s->rendered, s->texels, NULL,
                 NULL) == MRGI_OK);
    for (int32_t y = 0; y < s->layout.level_height[i]; ++y)
    {
      for (int32_t x = 0; x < s->layout.level_width[i]; ++x)
      {
        const size_t t = mrgi_multires_index(&s->layout, i, x, y);
        if (s->rendered[t])
        {
          const float e = (float)light(s->position[4 * t]);
          E[4 * t] = e;
          E[4 * t + 1] = 0.5f * e;
          E[4 * t + 2] = 0.25f * e;
          ++total;
        }
      }
    }
  }
  return total;
}

enum
{
  DIFF = MRGI_INCREMENTAL_ILLUMINATION_DIFFERENCE,
  CURV = MRGI_INCREMENTAL_ILLUMINATION_CURVATURE
};
static double light_step(double x) { return x < EDGE_X ? 4.0 : 1.0; }
static double light_ramp(double x) { return 1.0 + 0.05 * x; }
static double light_smooth(double x) { return 1.0 + 0.001 * x; }

static void test_illumination(void)
{
  scene s;
  scene_init(&s);
  float* E = malloc(4 * s.texels * sizeof(float));
  MRGI_CHECK(E != NULL);
  /* a light step: refined down to full resolution along the step only */
  const int64_t step = illuminate(&s, 0, 0.1f, E, light_step, DIFF);
  for (int32_t y = 0; y < SIDE; ++y)
  {
    MRGI_CHECK(rendered_at(&s, 0, 19, y) && rendered_at(&s, 0, 20, y));
    MRGI_CHECK(!rendered_at(&s, 0, 2, y) && !rendered_at(&s, 0, 50, y));
  }
  MRGI_CHECK(step > 64 + 3 * SIDE && step < 64 + 16 * SIDE);
  /* smooth light under the threshold: the geometric selection alone */
  MRGI_CHECK(illuminate(&s, 0, 0.1f, E, light_smooth, DIFF) == 64);
  MRGI_CHECK(memcmp(s.rendered, s.selection, s.texels) == 0);
  /* the threshold matters: above the step's 75% nothing is added, at 0
   * every level is rendered in full */
  MRGI_CHECK(illuminate(&s, 0, 0.8f, E, light_step, DIFF) == 64);
  MRGI_CHECK(illuminate(&s, 0, 0.0f, E, light_smooth, DIFF) == 64 * 64 + 32 * 32 + 16 * 16 + 64);
  /* finest level 2: nothing below */
  MRGI_CHECK(illuminate(&s, 2, 0.1f, E, light_step, DIFF) < 64 + 16 * 16);
  MRGI_CHECK(!rendered_at(&s, 1, 10, 0) && rendered_at(&s, 2, 5, 0));
  /* a non-receiver parent does not refine its children */
  for (int32_t y = 0; y < 8; ++y)
  {
    s.position[4 * mrgi_multires_index(&s.layout, 3, 2, y) + 3] = 0.0f;
  }
  illuminate(&s, 0, 0.1f, E, light_step, DIFF);
  MRGI_CHECK(!rendered_at(&s, 2, 5, 3) && !rendered_at(&s, 0, 20, 30));
  for (int32_t y = 0; y < 8; ++y)
  {
    s.position[4 * mrgi_multires_index(&s.layout, 3, 2, y) + 3] = 1.0f;
  }
  /* a steep linear ramp: the difference refines it, the curvature does not;
   * both refine the step */
  const int64_t ramp = illuminate(&s, 0, 0.1f, E, light_ramp, DIFF);
  printf("ramp: difference renders %lld texels\n", (long long)ramp);
  MRGI_CHECK(ramp > 64 + 16 * 16);
  MRGI_CHECK(illuminate(&s, 0, 0.1f, E, light_ramp, CURV) == 64);
  MRGI_CHECK(illuminate(&s, 0, 0.1f, E, light_step, CURV) > 64 + 3 * SIDE);
  for (int32_t y = 0; y < SIDE; ++y)
  {
    MRGI_CHECK(rendered_at(&s, 0, 19, y) && rendered_at(&s, 0, 20, y));
    MRGI_CHECK(!rendered_at(&s, 0, 2, y) && !rendered_at(&s, 0, 50, y));
  }
  MRGI_CHECK(illuminate(&s, 0, 0.0f, E, light_ramp, CURV) == 64 * 64 + 32 * 32 + 16 * 16 + 64);
  /* bad input */
  mrgi_error err;
  MRGI_CHECK(mrgi_incremental_stencil_illumination_level(&s.layout, 0, 1, s.flags, s.selection,
               s.texels, s.position, 4 * s.texels, E, 4 * s.texels, 7, 0.1f, s.rendered,
               s.texels, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(message_has(&err, "metric 7"));
  MRGI_CHECK(mrgi_incremental_stencil_illumination_level(&s.layout, 0, 1, s.flags, s.selection,
               s.texels, s.position, 4 * s.texels, E, 4 * s.texels, DIFF, NAN, s.rendered, s.texels,
               NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(message_has(&err, "illumination threshold"));
  MRGI_CHECK(mrgi_incremental_stencil_illumination_level(&s.layout, 0, 4, s.flags, s.selection,
               s.texels, s.position, 4 * s.texels, E, 4 * s.texels, DIFF, 0.1f, s.rendered, s.texels,
               NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(message_has(&err, "level 4"));
  MRGI_CHECK(mrgi_incremental_stencil_illumination_level(&s.layout, 0, 1, s.flags, s.selection,
               s.texels, s.position, 4 * s.texels, E, 4 * s.texels - 1, DIFF, 0.1f, s.rendered,
               s.texels, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(message_has(&err, "irradiance"));
  free(E);
  scene_free(&s);
}

int main(int argc, char** argv)
{
  static const mrgi_test_case cases[] = {
    MRGI_TEST_CASE(test_shadow_edge),
    MRGI_TEST_CASE(test_non_receivers),
    MRGI_TEST_CASE(test_bad_input),
    MRGI_TEST_CASE(test_illumination),
  };
  return MRGI_TEST_MAIN(argc, argv, cases);
}
