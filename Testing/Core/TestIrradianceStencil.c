/**
 * @file TestIrradianceStencil.c
 * @brief mrgi_irradiance_stencil_estimate() and mrgi_irradiance_stencil_add()
 *        (NPW10 3.4's colour term, predicted): the estimate against the
 *        point form factor, one-sided and two-sided lights; texels added on
 *        a floor under a near light, none under a far one, none at tau 0,
 *        refined texels and the coarsest level left out; bad input.
 */
#include "mrgi_irradiance_stencil.h"
#include "mrgi_test.h"

#include <string.h>

enum
{
  SIDE = 64,
  COARSEST = 8 /* levels 64, 32, 16, 8 */
};
static const float IDENTITY[16] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };

/* A light of side `size` at height `height` over (1, 0, 1), facing down. */
static mrgi_area_light_uniforms make_light(double height, double size, int two_sided)
{
  mrgi_area_light light;
  memset(&light, 0, sizeof(light));
  light.center[0] = 1.0;
  light.center[1] = height;
  light.center[2] = 1.0;
  light.edge_u[0] = size;
  light.edge_v[2] = size; /* u x v = -y */
  light.color[0] = light.color[1] = light.color[2] = 1.0;
  light.intensity = 1.0;
  light.two_sided = two_sided;
  mrgi_area_light_uniforms uniforms;
  MRGI_CHECK(mrgi_area_light_uniforms_init(&light, NULL, &uniforms, NULL) == MRGI_OK);
  return uniforms;
}

static void test_estimate(void)
{
  const mrgi_area_light_uniforms light = make_light(3.0, 0.1, 0);
  const float below[3] = { 1.0f, 0.0f, 1.0f };
  const float up[3] = { 0.0f, 1.0f, 0.0f };
  const float down[3] = { 0.0f, -1.0f, 0.0f };
  const float above[3] = { 1.0f, 6.0f, 1.0f };
  /* A small light far away: A / (pi d^2) within 0.1%. */
  const float E = mrgi_irradiance_stencil_estimate(&light, below, up);
  const float expected = (float)(0.01 / (MRGI_PI * 9.0));
  MRGI_CHECK(fabsf(E - expected) < 1e-3f * expected);
  MRGI_CHECK(mrgi_irradiance_stencil_estimate(&light, below, down) == 0.0f); /* facing away */
  MRGI_CHECK(mrgi_irradiance_stencil_estimate(&light, above, down) == 0.0f); /* behind */
  const mrgi_area_light_uniforms two = make_light(3.0, 0.1, 1);
  MRGI_CHECK(fabsf(mrgi_irradiance_stencil_estimate(&two, above, down) - expected) < 1e-3f * expected);
}

typedef struct floor_scene
{
  mrgi_multires_layout layout;
  size_t texels;
  uint8_t* flags;
  float* position;
  float* normal;
  uint8_t* rendered;
} floor_scene;

/* A 2 x 2 floor (y = 0, normal +y), eye space = world space; every texel
 * NONEMPTY and receiving; the coarsest level is the selection. */
static void floor_init(floor_scene* s)
{
  MRGI_CHECK(mrgi_multires_layout_init(&s->layout, SIDE, SIDE, COARSEST, NULL) == MRGI_OK);
  MRGI_CHECK(s->layout.level_count == 4);
  s->texels = (size_t)mrgi_multires_texel_count(&s->layout);
  s->flags = calloc(s->texels, 1);
  s->position = calloc(4 * s->texels, sizeof(float));
  s->normal = calloc(4 * s->texels, sizeof(float));
  s->rendered = calloc(s->texels, 1);
  MRGI_CHECK(s->flags && s->position && s->normal && s->rendered);
  for (int32_t i = 0; i < s->layout.level_count; ++i)
  {
    for (int32_t y = 0; y < s->layout.level_height[i]; ++y)
    {
      for (int32_t x = 0; x < s->layout.level_width[i]; ++x)
      {
        const size_t t = mrgi_multires_index(&s->layout, i, x, y);
        s->flags[t] = MRGI_MULTIRES_FLAG_NONEMPTY;
        s->rendered[t] = i == s->layout.level_count - 1;
        s->position[4 * t + 0] = (float)((x + 0.5) * (double)(1 << i) * 2.0 / SIDE);
        s->position[4 * t + 2] = (float)((y + 0.5) * (double)(1 << i) * 2.0 / SIDE);
        s->position[4 * t + 3] = 1.0f;
        s->normal[4 * t + 1] = 1.0f;
      }
    }
  }
}

static void floor_free(floor_scene* s)
{
  free(s->flags);
  free(s->position);
  free(s->normal);
  free(s->rendered);
}

static mrgi_status add(floor_scene* s, int32_t finest, const mrgi_area_light_uniforms* light,
                       float tau, int64_t added[MRGI_MULTIRES_MAX_LEVELS])
{
  return mrgi_irradiance_stencil_add(&s->layout, finest, s->flags, s->texels, s->position,
                                     s->normal, 4 * s->texels, IDENTITY, light, tau, s->rendered,
                                     s->texels, added, NULL);
}

static void test_floor(void)
{
  floor_scene s;
  floor_init(&s);
  int64_t added[MRGI_MULTIRES_MAX_LEVELS];
  /* Far light: the floor's irradiance varies by less than 25% over any 3x3. */
  const mrgi_area_light_uniforms far = make_light(50.0, 0.5, 0);
  MRGI_CHECK(add(&s, 0, &far, 0.25f, added) == MRGI_OK);
  for (int32_t i = 0; i < s.layout.level_count; ++i)
  {
    MRGI_CHECK(added[i] == 0);
  }
  /* Near light: texels added at every level below the coarsest, more at
   * finer levels; none at the coarsest; selected texels not counted. */
  const mrgi_area_light_uniforms near = make_light(0.3, 0.4, 0);
  MRGI_CHECK(add(&s, 0, &near, 0.0f, added) == MRGI_OK);
  MRGI_CHECK(added[0] == 0 && added[1] == 0 && added[2] == 0); /* tau 0: off */
  MRGI_CHECK(add(&s, 0, &near, 0.25f, added) == MRGI_OK);
  printf("near light: added %lld / %lld / %lld / %lld texels (levels 0..3)\n", (long long)added[0],
         (long long)added[1], (long long)added[2], (long long)added[3]);
  MRGI_CHECK(added[0] > 0 && added[1] > 0 && added[2] > 0 && added[3] == 0);
  MRGI_CHECK(added[0] > added[1] && added[1] > added[2]);
  /* Under the light's centre the irradiance has its flat maximum: not added. */
  MRGI_CHECK(added[0] < SIDE * SIDE);
  MRGI_CHECK(s.rendered[mrgi_multires_index(&s.layout, 0, SIDE / 2, SIDE / 2)] == 0);
  MRGI_CHECK(s.rendered[mrgi_multires_index(&s.layout, 0, 2, 2)] == 1);
  /* A second call adds nothing new; refined texels above the finest level
   * and levels below the finest are left out. */
  MRGI_CHECK(add(&s, 0, &near, 0.25f, added) == MRGI_OK && added[0] == 0 && added[1] == 0);
  memset(s.rendered, 0, s.texels);
  for (size_t t = 0; t < s.texels; ++t)
  {
    s.flags[t] |= MRGI_MULTIRES_FLAG_REFINE;
  }
  MRGI_CHECK(add(&s, 1, &near, 0.25f, added) == MRGI_OK);
  MRGI_CHECK(added[0] == 0 && added[1] > 0 && added[2] == 0);
  floor_free(&s);
}

static void test_bad_input(void)
{
  floor_scene s;
  floor_init(&s);
  memset(s.rendered, 7, s.texels);
  const mrgi_area_light_uniforms light = make_light(0.3, 0.4, 0);
  mrgi_error err;
  MRGI_CHECK(mrgi_irradiance_stencil_add(&s.layout, 0, s.flags, s.texels, s.position, s.normal,
                                         4 * s.texels, IDENTITY, &light, 1.5f, s.rendered, s.texels,
                                         NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "irradiance tolerance") != NULL);
  MRGI_CHECK(mrgi_irradiance_stencil_add(&s.layout, 0, s.flags, s.texels, s.position, s.normal,
                                         4 * s.texels, IDENTITY, &light, NAN, s.rendered, s.texels,
                                         NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_irradiance_stencil_add(&s.layout, 0, s.flags, s.texels, s.position, s.normal,
                                         4 * s.texels, IDENTITY, NULL, 0.25f, s.rendered, s.texels,
                                         NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "light") != NULL);
  MRGI_CHECK(mrgi_irradiance_stencil_add(&s.layout, 0, s.flags, s.texels, s.position, s.normal,
                                         4 * s.texels - 1, IDENTITY, &light, 0.25f, s.rendered,
                                         s.texels, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "receiver positions") != NULL);
  MRGI_CHECK(mrgi_irradiance_stencil_add(&s.layout, -1, s.flags, s.texels, s.position, s.normal,
                                         4 * s.texels, IDENTITY, &light, 0.25f, s.rendered,
                                         s.texels, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  for (size_t t = 0; t < s.texels; ++t)
  {
    MRGI_CHECK(s.rendered[t] == 7); /* nothing written */
  }
  floor_free(&s);
}

int main(int argc, char** argv)
{
  static const mrgi_test_case cases[] = {
    MRGI_TEST_CASE(test_estimate),
    MRGI_TEST_CASE(test_floor),
    MRGI_TEST_CASE(test_bad_input),
  };
  return MRGI_TEST_MAIN(argc, argv, cases);
}
