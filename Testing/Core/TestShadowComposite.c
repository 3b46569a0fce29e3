/* Tests of mrgi_shadow_composite: VTK's direct light with per-light terms
 * removed by (1 - shadow factor). */
#include "mrgi_shadow_composite.h"

#include "mrgi_test.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static float uniform(unsigned* state)
{
  *state = *state * 1664525u + 1013904223u;
  return (float)(*state >> 8) / 16777216.0f;
}

/* A pixel lit by every slot keeps VTK's colour bit for bit, whatever the
 * terms hold (also NaN terms and PBR's negated terms). */
static void test_lit_is_exact(void)
{
  unsigned state = 7u;
  for (int i = 0; i < 1000; ++i)
  {
    const float colour[4] = { uniform(&state) * 3.0f, uniform(&state), 1e-30f * uniform(&state),
      uniform(&state) };
    float terms[4 * MRGI_SHADOW_SLOTS];
    for (int k = 0; k < 4 * MRGI_SHADOW_SLOTS; ++k)
    {
      terms[k] = (uniform(&state) - 0.5f) * 4.0f;
    }
    terms[1] = (i % 3 == 0) ? NAN : terms[1];
    float factors[MRGI_SHADOW_SLOTS];
    for (int s = 0; s < MRGI_SHADOW_SLOTS; ++s)
    {
      factors[s] = 1.0f;
    }
    float out[4];
    mrgi_shadow_composite_pixel(colour, terms, factors, out);
    MRGI_CHECK(memcmp(out, colour, sizeof(out)) == 0);
  }
}

/* Linear law: colour = ambient + sum of terms; a fully shadowed slot
 * removes its term, a half-shadowed one half of it. */
static void test_linear_law(void)
{
  const float ambient[3] = { 0.05f, 0.1f, 0.02f };
  float terms[4 * MRGI_SHADOW_SLOTS] = { 0 };
  float colour[4] = { ambient[0], ambient[1], ambient[2], 0.75f };
  for (int s = 0; s < MRGI_SHADOW_SLOTS; ++s)
  {
    for (int c = 0; c < 3; ++c)
    {
      terms[4 * s + c] = 0.2f * (float)(s + 1) + 0.1f * (float)c;
      colour[c] += terms[4 * s + c];
    }
    terms[4 * s + 3] = 1.0f;
  }
  float factors[MRGI_SHADOW_SLOTS];
  for (int s = 0; s < MRGI_SHADOW_SLOTS; ++s)
  {
    factors[s] = 0.0f;
  }
  float out[4];
  mrgi_shadow_composite_pixel(colour, terms, factors, out);
  for (int c = 0; c < 3; ++c)
  {
    MRGI_CHECK_NEAR(out[c], ambient[c], 1e-6);
  }
  MRGI_CHECK(out[3] == 0.75f);
  factors[0] = 0.5f;
  mrgi_shadow_composite_pixel(colour, terms, factors, out);
  for (int c = 0; c < 3; ++c)
  {
    MRGI_CHECK_NEAR(out[c], ambient[c] + 0.5f * terms[c], 1e-6);
  }
  /* Terms larger than the colour (rounding in VTK's sum) never go below 0. */
  const float dark[4] = { 0.01f, 0.01f, 0.01f, 1.0f };
  factors[0] = 0.0f;
  mrgi_shadow_composite_pixel(dark, terms, factors, out);
  MRGI_CHECK(out[0] == 0.0f && out[1] == 0.0f && out[2] == 0.0f);
}

/* PBR law: the colour is pow(linear, 1/2.2) and the terms are stored negated. */
static void test_gamma_law(void)
{
  const float base = 0.04f, term = 0.3f;
  const float linear = base + term;
  const float colour[4] = { powf(linear, 1.0f / 2.2f), powf(linear, 1.0f / 2.2f),
    powf(linear, 1.0f / 2.2f), 1.0f };
  float terms[4 * MRGI_SHADOW_SLOTS] = { 0 };
  terms[0] = terms[1] = terms[2] = -term;
  float factors[MRGI_SHADOW_SLOTS];
  for (int s = 0; s < MRGI_SHADOW_SLOTS; ++s)
  {
    factors[s] = 1.0f;
  }
  factors[0] = 0.0f;
  float out[4];
  mrgi_shadow_composite_pixel(colour, terms, factors, out);
  MRGI_CHECK_NEAR(out[0], powf(base, 1.0f / 2.2f), 1e-5);
  /* Read as linear, the same record would have given a different value:
   * the sign really selects the law. */
  terms[0] = terms[1] = terms[2] = term;
  float linearOut[4];
  mrgi_shadow_composite_pixel(colour, terms, factors, linearOut);
  MRGI_CHECK(fabsf(linearOut[0] - out[0]) > 0.05f);
}

/* Broken factors never darken; broken terms remove nothing. */
static void test_bad_values(void)
{
  const float colour[4] = { 0.5f, 0.5f, 0.5f, 1.0f };
  float terms[4 * MRGI_SHADOW_SLOTS] = { 0 };
  terms[0] = terms[1] = terms[2] = 0.25f;
  const float bad[] = { NAN, INFINITY, -INFINITY, -0.5f, 1.5f };
  for (size_t i = 0; i < sizeof(bad) / sizeof(bad[0]); ++i)
  {
    float factors[MRGI_SHADOW_SLOTS];
    for (int s = 0; s < MRGI_SHADOW_SLOTS; ++s)
    {
      factors[s] = bad[i];
    }
    float out[4];
    mrgi_shadow_composite_pixel(colour, terms, factors, out);
    MRGI_CHECK(memcmp(out, colour, sizeof(out)) == 0);
  }
  float factors[MRGI_SHADOW_SLOTS] = { 0 };
  terms[0] = INFINITY;
  terms[1] = NAN;
  float out[4];
  mrgi_shadow_composite_pixel(colour, terms, factors, out);
  MRGI_CHECK(out[0] == 0.5f && out[1] == 0.5f && out[2] == 0.25f);
  for (int c = 0; c < 4; ++c)
  {
    MRGI_CHECK(isfinite(out[c]));
  }
}

/* The array form equals the pixel form, in place too; missing arrays are errors. */
static void test_arrays(void)
{
  enum { N = 64 };
  unsigned state = 3u;
  float colour[4 * N], factors[4 * N], expected[4 * N];
  float slotTerms[MRGI_SHADOW_SLOTS][4 * N];
  const float* terms[MRGI_SHADOW_SLOTS];
  for (int s = 0; s < MRGI_SHADOW_SLOTS; ++s)
  {
    terms[s] = slotTerms[s];
  }
  for (int i = 0; i < 4 * N; ++i)
  {
    colour[i] = uniform(&state) * 2.0f;
    factors[i] = uniform(&state);
    for (int s = 0; s < MRGI_SHADOW_SLOTS; ++s)
    {
      slotTerms[s][i] = (uniform(&state) - 0.2f) * 0.5f;
    }
  }
  for (int i = 0; i < N; ++i)
  {
    float pixelTerms[4 * MRGI_SHADOW_SLOTS], pixelFactors[MRGI_SHADOW_SLOTS];
    for (int s = 0; s < MRGI_SHADOW_SLOTS; ++s)
    {
      memcpy(pixelTerms + 4 * s, slotTerms[s] + 4 * i, 4 * sizeof(float));
      pixelFactors[s] = factors[4 * i + s];
    }
    mrgi_shadow_composite_pixel(colour + 4 * i, pixelTerms, pixelFactors, expected + 4 * i);
  }
  mrgi_error err;
  MRGI_CHECK(mrgi_shadow_composite(colour, terms, factors, N, colour, &err) == MRGI_OK);
  MRGI_CHECK(memcmp(colour, expected, sizeof(expected)) == 0);
  MRGI_CHECK(mrgi_shadow_composite(NULL, terms, factors, N, colour, &err) ==
    MRGI_ERR_INVALID_ARGUMENT);
  terms[MRGI_SHADOW_SLOTS - 1] = NULL;
  MRGI_CHECK(mrgi_shadow_composite(colour, terms, factors, N, colour, &err) ==
    MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "slot") != NULL);
}

int main(int argc, char** argv)
{
  static const mrgi_test_case cases[] = { MRGI_TEST_CASE(test_lit_is_exact),
    MRGI_TEST_CASE(test_linear_law), MRGI_TEST_CASE(test_gamma_law),
    MRGI_TEST_CASE(test_bad_values), MRGI_TEST_CASE(test_arrays) };
  return MRGI_TEST_MAIN(argc, argv, cases);
}
