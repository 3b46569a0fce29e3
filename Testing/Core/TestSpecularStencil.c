/**
 * @file TestSpecularStencil.c
 * @brief mrgi_specular_material_build() and mrgi_specular_stencil_build()
 *        (NPW10 3.2.1 lobe-size refinement in the stencil of the
 *        multiresolution specular gather): the material pyramid (max k_s,
 *        max and min exponent), the lobe metric refining a sharp exponent
 *        and not a broad one, the partition, texels without specular never
 *        selected, mixed exponents, the geometric refinement kept, bad input.
 */
#include "mrgi_specular_stencil.h"
#include "mrgi_test.h"

#include <string.h>

enum
{
  SIDE = 64,
  COARSEST = 8 /* levels 64, 32, 16, 8: L = 3 */
};

typedef struct scene
{
  mrgi_multires_layout layout;
  size_t texels;
  float* gposition; /* G-buffer, 4 floats per pixel */
  float* gspecular;
  float* gshininess;
  uint8_t* flags;
  float* material;
  float* position; /* receivers, flattened */
  float* normal;
  uint8_t* refine;
  uint8_t* selection;
  mrgi_area_light_uniforms light;
  mrgi_specular_stencil_view view;
} scene;

/* A floor facing the eye at depth 2 covering x, y in [-1, 1] (pixel size
 * 1/32: a = 1/64), a 1 x 1 light between the eye and the floor, facing it, at
 * z = -0.2 (t about 1.8, e about 2): m = 0.53 s / tan(theta_h), so n = 128
 * refines level 3 (s = 1/4, also at the corners) and n = 8 nothing. Left half (x < SIDE / 2)
 * specular with `left` as exponent, right half `right` (0: not specular). */
static void scene_init(scene* s, float left, float right)
{
  memset(s, 0, sizeof(*s));
  MRGI_CHECK(mrgi_multires_layout_init(&s->layout, SIDE, SIDE, COARSEST, NULL) == MRGI_OK);
  MRGI_CHECK(s->layout.level_count == 4);
  s->texels = (size_t)mrgi_multires_texel_count(&s->layout);
  const size_t pixels = (size_t)SIDE * SIDE;
  s->gposition = calloc(4 * pixels, sizeof(float));
  s->gspecular = calloc(4 * pixels, sizeof(float));
  s->gshininess = calloc(4 * pixels, sizeof(float));
  s->flags = calloc(s->texels, 1);
  s->material = calloc(4 * s->texels, sizeof(float));
  s->position = calloc(4 * s->texels, sizeof(float));
  s->normal = calloc(4 * s->texels, sizeof(float));
  s->refine = calloc(s->texels, 1);
  s->selection = calloc(s->texels, 1);
  MRGI_CHECK(s->gposition && s->gspecular && s->gshininess && s->flags && s->material &&
             s->position && s->normal && s->refine && s->selection);
  for (int32_t y = 0; y < SIDE; ++y)
  {
    for (int32_t x = 0; x < SIDE; ++x)
    {
      const size_t p = (size_t)y * SIDE + (size_t)x;
      const float n = x < SIDE / 2 ? left : right;
      s->gposition[4 * p + 3] = 1.0f;
      s->gspecular[4 * p + 0] = n > 0.0f ? 0.5f : 0.0f;
      s->gspecular[4 * p + 2] = n > 0.0f ? 0.25f : 0.0f;
      s->gshininess[4 * p] = n;
    }
  }
  MRGI_CHECK(mrgi_specular_material_build(&s->layout, s->gposition, s->gspecular, s->gshininess,
                                          pixels, s->material, 4 * s->texels, NULL) == MRGI_OK);
  for (int32_t i = 0; i < s->layout.level_count; ++i)
  {
    for (int32_t y = 0; y < s->layout.level_height[i]; ++y)
    {
      for (int32_t x = 0; x < s->layout.level_width[i]; ++x)
      {
        const size_t t = mrgi_multires_index(&s->layout, i, x, y);
        s->flags[t] = MRGI_MULTIRES_FLAG_NONEMPTY;
        s->position[4 * t + 0] = -1.0f + (float)((x + 0.5) * (double)(1 << i) / 32.0);
        s->position[4 * t + 1] = -1.0f + (float)((y + 0.5) * (double)(1 << i) / 32.0);
        s->position[4 * t + 2] = -2.0f;
        s->position[4 * t + 3] = (float)(1 << (2 * i));
        s->normal[4 * t + 2] = 1.0f;
      }
    }
  }
  mrgi_area_light light = { { 0.0, 0.0, -0.2 }, { 1.0, 0.0, 0.0 }, { 0.0, -1.0, 0.0 },
                            { 1.0, 1.0, 1.0 }, 1.0, NULL, 0 };
  MRGI_CHECK(mrgi_area_light_uniforms_init(&light, NULL, &s->light, NULL) == MRGI_OK);
  MRGI_CHECK(s->light.normal[2] < -0.99f); /* u x v faces the floor */
  memset(&s->view, 0, sizeof(s->view));
  for (int k = 0; k < 4; ++k)
  {
    s->view.view_to_world[5 * k] = 1.0f;
  }
  s->view.pixel_size[0] = 1.0f / 64.0f;
  s->view.lobe = 1;
  s->view.lobe_threshold = 1.0f;
}

static void scene_free(scene* s)
{
  free(s->gposition);
  free(s->gspecular);
  free(s->gshininess);
  free(s->flags);
  free(s->material);
  free(s->position);
  free(s->normal);
  free(s->refine);
  free(s->selection);
}

static mrgi_status build(scene* s, int32_t finest, mrgi_specular_stencil_stats* stats,
                         mrgi_error* err)
{
  return mrgi_specular_stencil_build(&s->layout, finest, s->flags, s->material, 4 * s->texels,
                                     s->position, s->normal, 4 * s->texels, &s->light, &s->view,
                                     s->refine, s->selection, s->texels, stats, err);
}

/* Every specular pixel lies in exactly one selected footprint, every other
 * pixel in none. */
static void check_partition(const scene* s)
{
  for (int32_t y = 0; y < SIDE; ++y)
  {
    for (int32_t x = 0; x < SIDE; ++x)
    {
      int covered = 0;
      for (int32_t i = 0; i < s->layout.level_count; ++i)
      {
        covered += s->selection[mrgi_multires_index(&s->layout, i, x >> i, y >> i)];
      }
      const int specular = s->gspecular[4 * ((size_t)y * SIDE + (size_t)x)] > 0.0f;
      MRGI_CHECK(covered == specular);
    }
  }
}

static void test_material(void)
{
  scene s;
  scene_init(&s, 128.0f, 0.0f);
  /* level 3 texel 1 (x 8..15) is all specular, texel 4 (x 32..39) none;
   * level-0 k = max(0.5, 0, 0.25) */
  const float* m = s.material + 4 * mrgi_multires_index(&s.layout, 3, 1, 2);
  MRGI_CHECK(m[0] == 0.5f && m[1] == 128.0f && m[2] == 128.0f);
  m = s.material + 4 * mrgi_multires_index(&s.layout, 3, 4, 2);
  MRGI_CHECK(m[0] == 0.0f && m[1] == 0.0f && m[2] == MRGI_MULTIRES_FLT_MAX);
  scene_free(&s);
  /* mixed exponents: a level-1 texel straddling x = 32 has both */
  scene_init(&s, 20.0f, 90.0f);
  m = s.material + 4 * mrgi_multires_index(&s.layout, 2, 7, 0); /* x 28..31 */
  MRGI_CHECK(m[1] == 20.0f && m[2] == 20.0f);
  m = s.material + 4 * mrgi_multires_index(&s.layout, 3, 3, 0); /* x 24..31 */
  MRGI_CHECK(m[1] == 20.0f && m[2] == 20.0f);
  m = s.material + 4 * mrgi_multires_index(&s.layout, 1, 15, 9); /* x 30..31 */
  MRGI_CHECK(m[1] == 20.0f);
  m = s.material + 4 * mrgi_multires_index(&s.layout, 1, 16, 9); /* x 32..33 */
  MRGI_CHECK(m[1] == 90.0f && m[2] == 90.0f);
  /* an invalid pixel is not specular */
  scene_free(&s);
}

static void test_lobe(void)
{
  scene s;
  scene_init(&s, 128.0f, 0.0f);
  mrgi_specular_stencil_stats stats;
  /* the metric itself: about 4.3 s at the centre for n = 128 */
  const size_t c3 = mrgi_multires_index(&s.layout, 3, 3, 3);
  const float m3 = mrgi_specular_stencil_metric(&s.light, &s.view, s.position + 4 * c3,
                                                s.normal + 4 * c3, 128.0f, 3);
  const float m2 = mrgi_specular_stencil_metric(&s.light, &s.view, s.position + 4 * c3,
                                                s.normal + 4 * c3, 128.0f, 2);
  printf("lobe metric n = 128: level 3 %.3f, level 2 %.3f\n", m3, m2);
  MRGI_CHECK(m3 > 1.0f && m2 < 1.0f);
  MRGI_CHECK_NEAR(m3, 2.0f * m2, 1e-5);
  /* lobe on: the left half is gathered at level 2, nothing on the right */
  MRGI_CHECK(build(&s, 0, &stats, NULL) == MRGI_OK);
  check_partition(&s);
  printf("lobe on: selected L3 %lld L2 %lld L1 %lld, lobe L3 %lld\n", (long long)stats.selected[3],
         (long long)stats.selected[2], (long long)stats.selected[1], (long long)stats.lobe[3]);
  MRGI_CHECK(stats.selected[3] == 0 && stats.selected[2] == 8 * 16);
  MRGI_CHECK(stats.lobe[3] == 4 * 8 && stats.lobe[2] == 0);
  MRGI_CHECK(stats.selected_total == 8 * 16);
  /* lobe off: the geometric selection (level 3) on the specular half */
  s.view.lobe = 0;
  MRGI_CHECK(build(&s, 0, &stats, NULL) == MRGI_OK);
  check_partition(&s);
  MRGI_CHECK(stats.selected[3] == 4 * 8 && stats.selected_total == 4 * 8 && stats.lobe[3] == 0);
  /* finest level 3: nothing can refine */
  s.view.lobe = 1;
  MRGI_CHECK(build(&s, 3, &stats, NULL) == MRGI_OK);
  check_partition(&s);
  MRGI_CHECK(stats.selected[3] == 4 * 8 && stats.lobe[3] == 0);
  scene_free(&s);
  /* a broad lobe (n = 8) is not refined */
  scene_init(&s, 8.0f, 8.0f);
  MRGI_CHECK(build(&s, 0, &stats, NULL) == MRGI_OK);
  check_partition(&s);
  MRGI_CHECK(stats.selected[3] == 64 && stats.selected_total == 64);
  /* ... until the threshold asks for many samples across the lobe */
  s.view.lobe_threshold = 1e-3f;
  MRGI_CHECK(build(&s, 0, &stats, NULL) == MRGI_OK);
  check_partition(&s);
  MRGI_CHECK(stats.lobe[3] > 0 && stats.selected_total > 64);
  /* a threshold that is not finite and positive is refused */
  mrgi_error err;
  s.view.lobe_threshold = 0.0f;
  MRGI_CHECK(build(&s, 0, &stats, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "lobe threshold") != NULL);
  s.view.lobe_threshold = 1.0f;
  /* parallel projection: 1/e = 0, still finite */
  s.view.parallel = 1;
  s.view.pixel_size[0] = 0.0f;
  s.view.pixel_size[1] = 1.0f / 32.0f;
  MRGI_CHECK(build(&s, 0, &stats, NULL) == MRGI_OK);
  check_partition(&s);
  scene_free(&s);
}

static void test_mixed_and_geometric(void)
{
  scene s;
  scene_init(&s, 20.0f, 90.0f);
  mrgi_specular_stencil_stats stats;
  s.view.lobe = 0;
  MRGI_CHECK(build(&s, 0, &stats, NULL) == MRGI_OK);
  check_partition(&s);
  /* no texel mixes exponents (the boundary lies on texel borders at every
   * level): the coarsest level */
  MRGI_CHECK(stats.selected[3] == 64);
  scene_free(&s);
  /* move the boundary to x = 33: one column of texels mixes at each level,
   * refined down to level 0 where the two exponents meet */
  scene_init(&s, 20.0f, 90.0f);
  for (int32_t y = 0; y < SIDE; ++y)
  {
    s.gshininess[4 * ((size_t)y * SIDE + 32)] = 20.0f;
  }
  MRGI_CHECK(mrgi_specular_material_build(&s.layout, s.gposition, s.gspecular, s.gshininess,
                                          (size_t)SIDE * SIDE, s.material, 4 * s.texels,
                                          NULL) == MRGI_OK);
  s.view.lobe = 0;
  MRGI_CHECK(build(&s, 0, &stats, NULL) == MRGI_OK);
  check_partition(&s);
  MRGI_CHECK(stats.selected[0] == 2 * SIDE); /* x = 32, 33 */
  MRGI_CHECK(s.selection[mrgi_multires_index(&s.layout, 0, 32, 5)]);
  MRGI_CHECK(s.selection[mrgi_multires_index(&s.layout, 3, 0, 5)]);
  scene_free(&s);
  /* the geometric refinement of one level-3 texel: its children gather */
  scene_init(&s, 8.0f, 8.0f);
  s.flags[mrgi_multires_index(&s.layout, 3, 2, 2)] |= MRGI_MULTIRES_FLAG_REFINE;
  MRGI_CHECK(build(&s, 0, &stats, NULL) == MRGI_OK);
  check_partition(&s);
  MRGI_CHECK(stats.selected[3] == 63 && stats.selected[2] == 4);
  /* an empty texel is never selected */
  scene_free(&s);
}

static void test_bad_input(void)
{
  scene s;
  scene_init(&s, 8.0f, 8.0f);
  mrgi_error err;
  MRGI_CHECK(mrgi_specular_stencil_build(&s.layout, 0, NULL, s.material, 4 * s.texels, s.position,
                                         s.normal, 4 * s.texels, &s.light, &s.view, NULL,
                                         s.selection, s.texels, NULL,
                                         &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_specular_stencil_build(&s.layout, 0, s.flags, s.material, 4 * s.texels - 1,
                                         s.position, s.normal, 4 * s.texels, &s.light, &s.view,
                                         NULL, s.selection, s.texels, NULL,
                                         &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_specular_stencil_build(&s.layout, -1, s.flags, s.material, 4 * s.texels,
                                         s.position, s.normal, 4 * s.texels, &s.light, &s.view,
                                         NULL, s.selection, s.texels, NULL,
                                         &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_specular_stencil_build(&s.layout, 0, s.flags, s.material, 4 * s.texels,
                                         s.position, s.normal, 4 * s.texels, NULL, &s.view, NULL,
                                         s.selection, s.texels, NULL,
                                         &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_specular_material_build(&s.layout, s.gposition, s.gspecular, s.gshininess, 10,
                                          s.material, 4 * s.texels,
                                          &err) == MRGI_ERR_INVALID_ARGUMENT);
  /* NULL refine works (scratch) */
  MRGI_CHECK(mrgi_specular_stencil_build(&s.layout, 0, s.flags, s.material, 4 * s.texels,
                                         s.position, s.normal, 4 * s.texels, &s.light, &s.view,
                                         NULL, s.selection, s.texels, NULL, &err) == MRGI_OK);
  /* an invalid receiver has no metric */
  float bad[4] = { 0.0f, 0.0f, -2.0f, 0.0f };
  const float n[3] = { 0.0f, 0.0f, 1.0f };
  MRGI_CHECK(mrgi_specular_stencil_metric(&s.light, &s.view, bad, n, 128.0f, 3) == 0.0f);
  bad[3] = 1.0f;
  bad[0] = NAN;
  MRGI_CHECK(mrgi_specular_stencil_metric(&s.light, &s.view, bad, n, 128.0f, 3) == 0.0f);
  scene_free(&s);
}

int main(int argc, char** argv)
{
  static const mrgi_test_case cases[] = {
    MRGI_TEST_CASE(test_material),
    MRGI_TEST_CASE(test_lobe),
    MRGI_TEST_CASE(test_mixed_and_geometric),
    MRGI_TEST_CASE(test_bad_input),
  };
  return MRGI_TEST_MAIN(argc, argv, cases);
}
