/* mrgi_las_colors: the automatic choice (RGB, else classes, else
 * intensity), RGB to 8 bits, the class palette (ground, vegetation,
 * building and water distinct; unknown classes grey), the intensity ramp's
 * percentile clamp and its uniform fallback, and the errors. */
#include "mrgi_las_colors.h"
#include "mrgi_test.h"

#include <stdlib.h>
#include <string.h>

enum
{
  N = 200
};

/* A cloud of N points built in memory: positions zero, the given arrays. */
typedef struct cloud
{
  mrgi_las_points p;
  float positions[3 * N];
  uint16_t intensity[N];
  uint8_t classification[N];
  uint8_t returns[N];
  float colors[3 * N];
} cloud;

static void make_cloud(cloud* c, int with_rgb)
{
  memset(c, 0, sizeof(*c));
  c->p.count = N;
  c->p.positions = c->positions;
  c->p.intensity = c->intensity;
  c->p.classification = c->classification;
  c->p.return_number = c->returns;
  c->p.number_of_returns = c->returns;
  c->p.colors = with_rgb ? c->colors : NULL;
}

static int distance(const uint8_t* a, const uint8_t* b)
{
  return abs(a[0] - b[0]) + abs(a[1] - b[1]) + abs(a[2] - b[2]);
}

static void test_auto_choice(void)
{
  static cloud c;
  make_cloud(&c, 1);
  c.classification[7] = 2;
  MRGI_CHECK(mrgi_las_auto_color_mode(&c.p) == MRGI_LAS_COLOR_RGB);
  make_cloud(&c, 0);
  MRGI_CHECK(mrgi_las_auto_color_mode(&c.p) == MRGI_LAS_COLOR_INTENSITY);
  c.classification[3] = 1; /* "unclassified" does not make a classified file */
  MRGI_CHECK(mrgi_las_auto_color_mode(&c.p) == MRGI_LAS_COLOR_INTENSITY);
  c.classification[N - 1] = 6;
  MRGI_CHECK(mrgi_las_auto_color_mode(&c.p) == MRGI_LAS_COLOR_CLASSIFICATION);
  uint8_t rgb[3 * N];
  mrgi_las_color_mode used = MRGI_LAS_COLOR_AUTO;
  MRGI_CHECK(mrgi_las_colorize(&c.p, MRGI_LAS_COLOR_AUTO, rgb, &used, NULL) == MRGI_OK);
  MRGI_CHECK(used == MRGI_LAS_COLOR_CLASSIFICATION);
  uint8_t building[3];
  mrgi_las_classification_color(6, building);
  MRGI_CHECK(memcmp(rgb + 3 * (N - 1), building, 3) == 0);
}

static void test_rgb(void)
{
  static cloud c;
  make_cloud(&c, 1);
  c.colors[0] = 1.0f;
  c.colors[1] = 0.5f;
  c.colors[2] = 0.0f;
  c.colors[3] = 10.0f / 255.0f;
  uint8_t rgb[3 * N];
  mrgi_las_color_mode used = MRGI_LAS_COLOR_AUTO;
  MRGI_CHECK(mrgi_las_colorize(&c.p, MRGI_LAS_COLOR_AUTO, rgb, &used, NULL) == MRGI_OK);
  MRGI_CHECK(used == MRGI_LAS_COLOR_RGB);
  MRGI_CHECK(rgb[0] == 255 && rgb[1] == 128 && rgb[2] == 0 && rgb[3] == 10);
  /* Classes of an RGB file on request. */
  c.classification[0] = 9;
  MRGI_CHECK(mrgi_las_colorize(&c.p, MRGI_LAS_COLOR_CLASSIFICATION, rgb, &used, NULL) == MRGI_OK);
  MRGI_CHECK(used == MRGI_LAS_COLOR_CLASSIFICATION);
  MRGI_CHECK(rgb[2] > rgb[0] && rgb[2] > rgb[1]); /* water is blue */
}

static void test_palette(void)
{
  uint8_t ground[3], low[3], high[3], building[3], water[3], unknown[3], user[3], never[3];
  mrgi_las_classification_color(2, ground);
  mrgi_las_classification_color(3, low);
  mrgi_las_classification_color(5, high);
  mrgi_las_classification_color(6, building);
  mrgi_las_classification_color(9, water);
  mrgi_las_classification_color(-1, unknown);
  mrgi_las_classification_color(200, user);
  mrgi_las_classification_color(0, never);
  MRGI_CHECK(ground[0] > ground[1] && ground[1] > ground[2]); /* brown */
  MRGI_CHECK(high[1] > high[0] && high[1] > high[2]);         /* green */
  MRGI_CHECK(low[1] > high[1]);                               /* low vegetation lighter */
  MRGI_CHECK(building[0] > building[1] && building[0] > building[2]);
  MRGI_CHECK(water[2] > water[0] && water[2] > water[1]);
  MRGI_CHECK(unknown[0] == 128 && unknown[1] == 128 && unknown[2] == 128);
  MRGI_CHECK(memcmp(unknown, user, 3) == 0);
  MRGI_CHECK(never[0] == never[1] && never[1] == never[2]);
  /* The main classes are told apart at a glance. */
  const uint8_t* main_classes[] = { ground, low, high, building, water, never };
  for (int i = 0; i < 6; ++i)
  {
    for (int j = i + 1; j < 6; ++j)
    {
      MRGI_CHECK(distance(main_classes[i], main_classes[j]) > 60);
    }
  }
}

static void test_intensity_ramp(void)
{
  static cloud c;
  make_cloud(&c, 0);
  /* 0..N-1 times 100, with one saturated return that must not set the top. */
  for (int i = 0; i < N; ++i)
  {
    c.intensity[i] = (uint16_t)(100 * i);
  }
  c.intensity[N - 1] = 65535;
  uint8_t rgb[3 * N];
  mrgi_las_color_mode used = MRGI_LAS_COLOR_AUTO;
  MRGI_CHECK(mrgi_las_colorize(&c.p, MRGI_LAS_COLOR_AUTO, rgb, &used, NULL) == MRGI_OK);
  MRGI_CHECK(used == MRGI_LAS_COLOR_INTENSITY);
  for (int i = 0; i < N; ++i)
  {
    MRGI_CHECK(rgb[3 * i] == rgb[3 * i + 1] && rgb[3 * i + 1] == rgb[3 * i + 2]);
    MRGI_CHECK(rgb[3 * i] >= 38);
    if (i > 0)
    {
      MRGI_CHECK(rgb[3 * i] >= rgb[3 * (i - 1)]);
    }
  }
  MRGI_CHECK(rgb[0] == 38);                                     /* the bottom of the ramp */
  MRGI_CHECK(rgb[3 * (N - 1)] == 255);                          /* clamped */
  MRGI_CHECK(rgb[3 * (N - 5)] == 255);                          /* at the 98th percentile */
  MRGI_CHECK(rgb[3 * (N - 6)] < 255);                           /* just under it */
  MRGI_CHECK(rgb[3 * (N / 2)] > 120 && rgb[3 * (N / 2)] < 170); /* mid grey in the middle */
  /* All equal: uniform 0.8 grey. */
  for (int i = 0; i < N; ++i)
  {
    c.intensity[i] = 7;
  }
  MRGI_CHECK(mrgi_las_colorize(&c.p, MRGI_LAS_COLOR_INTENSITY, rgb, &used, NULL) == MRGI_OK);
  MRGI_CHECK(rgb[0] == 204 && rgb[3 * (N - 1) + 2] == 204);
}

static void test_errors(void)
{
  static cloud c;
  make_cloud(&c, 0);
  uint8_t rgb[3 * N];
  memset(rgb, 77, sizeof(rgb));
  mrgi_error err;
  MRGI_CHECK(
    mrgi_las_colorize(&c.p, MRGI_LAS_COLOR_RGB, rgb, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "has no RGB") != NULL);
  MRGI_CHECK(rgb[0] == 77); /* nothing written on failure */
  MRGI_CHECK(
    mrgi_las_colorize(&c.p, (mrgi_las_color_mode)9, rgb, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(
    mrgi_las_colorize(NULL, MRGI_LAS_COLOR_AUTO, rgb, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(
    mrgi_las_colorize(&c.p, MRGI_LAS_COLOR_AUTO, NULL, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  c.p.count = 0;
  MRGI_CHECK(
    mrgi_las_colorize(&c.p, MRGI_LAS_COLOR_AUTO, rgb, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
}

int main(int argc, char** argv)
{
  static const mrgi_test_case cases[] = {
    MRGI_TEST_CASE(test_auto_choice),
    MRGI_TEST_CASE(test_rgb),
    MRGI_TEST_CASE(test_palette),
    MRGI_TEST_CASE(test_intensity_ramp),
    MRGI_TEST_CASE(test_errors),
  };
  return MRGI_TEST_MAIN(argc, argv, cases);
}
