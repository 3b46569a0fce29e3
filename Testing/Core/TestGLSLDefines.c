/* Tests of mrgi_glsl_defines: the block parses as `#define NAME VALUE` lines,
 * holds every constant GLSL needs exactly once, values read back as the C
 * values, and the buffer contract holds. */
#include "mrgi_glsl_defines.h"
#include "mrgi_ism_atlas.h"

#include "mrgi_area_light.h"
#include "mrgi_area_light_rsm.h"
#include "mrgi_direct_shadow.h"
#include "mrgi_shadow_composite.h"
#include "mrgi_bmr_mask.h"
#include "mrgi_exposure.h"
#include "mrgi_gather.h"
#include "mrgi_irradiance_stencil.h"
#include "mrgi_incremental_stencil.h"
#include "mrgi_ism_atlas.h"
#include "mrgi_ism_visibility.h"
#include "mrgi_multires.h"
#include "mrgi_specular_stencil.h"
#include "mrgi_ssao.h"
#include "mrgi_ssgi.h"
#include "mrgi_upsample.h"
#include "mrgi_test.h"
#include "mrgi_variance_shadow.h"
#include "mrgi_visibility_pyramid.h"
#include "mrgi_vpl.h"
#include "mrgi_vpl_tree_gather.h"

#include <ctype.h>
#include <locale.h>
#include <string.h>

typedef enum expected_kind
{
  EXPECT_INT,
  EXPECT_FLOAT, /* C constant is a float: compare after rounding to float */
  EXPECT_DOUBLE
} expected_kind;

typedef struct expected_constant
{
  const char* name;
  expected_kind kind;
  double value;
  int seen;
} expected_constant;

#define EXPECT(macro, kind) { #macro, kind, (double)(macro), 0 }

/* Every constant the shaders need; a missing or extra line fails the test. */
static expected_constant expected[] = {
  EXPECT(MRGI_VPL_TEXELS, EXPECT_INT),
  EXPECT(MRGI_VPL_TEXEL_POSITION, EXPECT_INT),
  EXPECT(MRGI_VPL_TEXEL_NORMAL, EXPECT_INT),
  EXPECT(MRGI_VPL_TEXEL_FLUX, EXPECT_INT),
  EXPECT(MRGI_VPL_FLOATS, EXPECT_INT),
  EXPECT(MRGI_VPL_MIN_COUNT, EXPECT_INT),
  EXPECT(MRGI_VPL_MAX_COUNT, EXPECT_INT),
  EXPECT(MRGI_RSM_MIN_COS, EXPECT_FLOAT),
  EXPECT(MRGI_RSM_MAX_VIEWS, EXPECT_INT),
  EXPECT(MRGI_VALID_THRESHOLD, EXPECT_FLOAT),
  EXPECT(MRGI_LUMINANCE_R, EXPECT_DOUBLE),
  EXPECT(MRGI_LUMINANCE_G, EXPECT_DOUBLE),
  EXPECT(MRGI_LUMINANCE_B, EXPECT_DOUBLE),
  EXPECT(MRGI_PI, EXPECT_DOUBLE),
  EXPECT(MRGI_VPL_TREE_ROOT_SIDE, EXPECT_INT),
  EXPECT(MRGI_VPL_TREE_RECORDS_PER_ROW, EXPECT_INT),
  EXPECT(MRGI_VPL_TREE_MAX_LOOP_ITERATIONS, EXPECT_INT),
  EXPECT(MRGI_VPL_TREE_STACK_SIZE, EXPECT_INT),
  EXPECT(MRGI_VPL_TREE_GATHER_MAX_RSM_SIZE, EXPECT_INT),
  EXPECT(MRGI_SSAO_NOISE_SIZE, EXPECT_INT),
  EXPECT(MRGI_SSGI_MAX_SAMPLES, EXPECT_INT),
  EXPECT(MRGI_SSGI_RANGE, EXPECT_FLOAT),
  EXPECT(MRGI_GBUFFER_VALID, EXPECT_FLOAT),
  EXPECT(MRGI_GBUFFER_VALID_THRESHOLD, EXPECT_FLOAT),
  EXPECT(MRGI_GBUFFER_DIRECT, EXPECT_INT),
  EXPECT(MRGI_GBUFFER_POSITION, EXPECT_INT),
  EXPECT(MRGI_GBUFFER_NORMAL, EXPECT_INT),
  EXPECT(MRGI_GBUFFER_ALBEDO, EXPECT_INT),
  EXPECT(MRGI_GBUFFER_SPECULAR, EXPECT_INT),
  EXPECT(MRGI_GBUFFER_SHININESS, EXPECT_INT),
  EXPECT(MRGI_GBUFFER_LIGHT0, EXPECT_INT),
  EXPECT(MRGI_SHADOW_SLOTS, EXPECT_INT),
  EXPECT(MRGI_SHADOW_PBR_GAMMA, EXPECT_FLOAT),
  EXPECT(MRGI_RSM_POSITION, EXPECT_INT),
  EXPECT(MRGI_RSM_NORMAL, EXPECT_INT),
  EXPECT(MRGI_RSM_FLUX, EXPECT_INT),
  EXPECT(MRGI_MULTIRES_MAX_LEVELS, EXPECT_INT),
  EXPECT(MRGI_SPECULAR_STENCIL_REFINE, EXPECT_INT),
  EXPECT(MRGI_SPECULAR_STENCIL_LOBE, EXPECT_INT),
  EXPECT(MRGI_SPECULAR_STENCIL_SPECULAR, EXPECT_INT),
  EXPECT(MRGI_MULTIRES_TEX_DEPTH, EXPECT_INT),
  EXPECT(MRGI_MULTIRES_TEX_NORMAL_MIN, EXPECT_INT),
  EXPECT(MRGI_MULTIRES_TEX_NORMAL_MAX, EXPECT_INT),
  EXPECT(MRGI_MULTIRES_TEX_COUNT, EXPECT_INT),
  EXPECT(MRGI_MULTIRES_VALID_BIT, EXPECT_INT),
  EXPECT(MRGI_MULTIRES_INVALID_BIT, EXPECT_INT),
  EXPECT(MRGI_MULTIRES_FLAG_NONEMPTY, EXPECT_INT),
  EXPECT(MRGI_MULTIRES_FLAG_MIXED, EXPECT_INT),
  EXPECT(MRGI_MULTIRES_FLAG_DISCONTINUOUS, EXPECT_INT),
  EXPECT(MRGI_MULTIRES_FLAG_REFINE, EXPECT_INT),
  EXPECT(MRGI_MULTIRES_FLT_MAX, EXPECT_FLOAT),
  EXPECT(MRGI_MULTIRES_MIN_PIXEL_SIZE, EXPECT_FLOAT),
  EXPECT(MRGI_MULTIRES_THRESHOLD_OFF, EXPECT_FLOAT),
  EXPECT(MRGI_UPSAMPLE_TENT, EXPECT_INT),
  EXPECT(MRGI_UPSAMPLE_MASK_WEIGHTED, EXPECT_INT),
  EXPECT(MRGI_TONE_SHOULDER, EXPECT_FLOAT),
  EXPECT(MRGI_VOXEL_LAYER_SLICES, EXPECT_INT),
  EXPECT(MRGI_VOXEL_MAX_LAYERS, EXPECT_INT),
  EXPECT(MRGI_VOXEL_CHANNELS, EXPECT_INT),
  EXPECT(MRGI_VOXEL_CHANNEL_BITS, EXPECT_INT),
  EXPECT(MRGI_VOXEL_MAX_SIZE, EXPECT_INT),
  EXPECT(MRGI_VOXEL_MAX_STEPS, EXPECT_INT),
  EXPECT(MRGI_VOXEL_OFFSET_NORMALS, EXPECT_INT),
  EXPECT(MRGI_VOXEL_OFFSET_RAY_AT_BOTH, EXPECT_INT),
  EXPECT(MRGI_VOXEL_ALONG_RAY_MIN_COS, EXPECT_FLOAT),
  EXPECT(MRGI_VOXEL_ALONG_RAY_FULL_COS, EXPECT_FLOAT),
  EXPECT(MRGI_VOXEL_ALONG_RAY_MAX_SHARE, EXPECT_FLOAT),
  EXPECT(MRGI_ISM_EMPTY_DEPTH, EXPECT_FLOAT),
  EXPECT(MRGI_ISM_MIN_DEPTH, EXPECT_FLOAT),
  EXPECT(MRGI_ISM_MAX_TILE, EXPECT_INT),
  EXPECT(MRGI_ISM_BIAS_MIN_COS, EXPECT_FLOAT),
  EXPECT(MRGI_VOXEL_MAX_SAMPLES, EXPECT_INT),
  EXPECT(MRGI_VOXEL_MAX_MASK_WORDS, EXPECT_INT),
  EXPECT(MRGI_VOXEL_INTERLEAVE_PHASES, EXPECT_INT),
  EXPECT(MRGI_VOXEL_ALL_PHASES, EXPECT_INT),
  EXPECT(MRGI_VOXEL_NEIGHBOURS, EXPECT_INT),
  EXPECT(MRGI_IRRADIANCE_STENCIL_GRID, EXPECT_INT),
  EXPECT(MRGI_VOXEL_METRIC_DISAGREE, EXPECT_INT),
  EXPECT(MRGI_VOXEL_METRIC_COUNT_SPREAD, EXPECT_INT),
  EXPECT(MRGI_INCREMENTAL_ILLUMINATION_DIFFERENCE, EXPECT_INT),
  EXPECT(MRGI_INCREMENTAL_ILLUMINATION_CURVATURE, EXPECT_INT),
  EXPECT(MRGI_VOXEL_VSM_QUERIES, EXPECT_INT),
  EXPECT(MRGI_VOXEL_VSM_TARGETS, EXPECT_INT),
  EXPECT(MRGI_VOXEL_INTERLEAVE_MIN_COS, EXPECT_FLOAT),
  EXPECT(MRGI_VOXEL_INTERLEAVE_MAX_SLOPE, EXPECT_FLOAT),
  EXPECT(MRGI_VOXEL_SURROUND_MIN_LEVEL, EXPECT_INT),
  EXPECT(MRGI_AREA_LIGHT_MIN_SAMPLES, EXPECT_INT),
  EXPECT(MRGI_AREA_LIGHT_RSM_SAMPLES, EXPECT_INT),
  EXPECT(MRGI_AREA_LIGHT_MAX_SAMPLES, EXPECT_INT),
  EXPECT(MRGI_AREA_LIGHT_SAMPLE_TEXELS, EXPECT_INT),
  EXPECT(MRGI_AREA_LIGHT_SAMPLE_TEXEL_POSITION, EXPECT_INT),
  EXPECT(MRGI_AREA_LIGHT_SAMPLE_TEXEL_NORMAL, EXPECT_INT),
  EXPECT(MRGI_AREA_LIGHT_SAMPLE_TEXEL_RADIANCE, EXPECT_INT),
  EXPECT(MRGI_AREA_LIGHT_SAMPLE_FLOATS, EXPECT_INT),
  EXPECT(MRGI_AREA_LIGHT_LOBE_GRID, EXPECT_INT),
  EXPECT(MRGI_AREA_LIGHT_LOBE_MIN_SAMPLES, EXPECT_INT),
  EXPECT(MRGI_AREA_LIGHT_LOBE_CUTOFF, EXPECT_FLOAT),
  EXPECT(MRGI_AREA_LIGHT_LOBE_DISCARD, EXPECT_FLOAT),
  EXPECT(MRGI_AREA_LIGHT_MIN_COS, EXPECT_FLOAT),
  EXPECT(MRGI_AREA_LIGHT_MIN_ALONG, EXPECT_FLOAT),
  EXPECT(MRGI_AREA_LIGHT_SPECULAR_SAMPLES, EXPECT_INT),
  EXPECT(MRGI_AREA_LIGHT_SPECULAR_LOBE_GRID, EXPECT_INT),
  EXPECT(MRGI_AREA_LIGHT_SPECULAR_BEHIND, EXPECT_INT),
  EXPECT(MRGI_AREA_LIGHT_SPECULAR_FACING_AWAY, EXPECT_INT),
  EXPECT(MRGI_AREA_LIGHT_SPECULAR_LOBE_MISS, EXPECT_INT),
  EXPECT(MRGI_DIRECT_SHADOW_HARD, EXPECT_INT),
  EXPECT(MRGI_DIRECT_SHADOW_SOFT, EXPECT_INT),
  EXPECT(MRGI_DIRECT_SHADOW_MAX_VIEWS, EXPECT_INT),
  EXPECT(MRGI_DIRECT_SHADOW_HARD_SIDE, EXPECT_INT),
  EXPECT(MRGI_DIRECT_SHADOW_BLOCKER_SIDE, EXPECT_INT),
  EXPECT(MRGI_DIRECT_SHADOW_MAX_SIDE, EXPECT_INT),
  EXPECT(MRGI_DIRECT_SHADOW_BIAS_TEXELS, EXPECT_FLOAT),
  EXPECT(MRGI_DIRECT_SHADOW_MAX_SLOPE, EXPECT_FLOAT),
  EXPECT(MRGI_DIRECT_SHADOW_SEARCH_NEAR, EXPECT_FLOAT),
  EXPECT(MRGI_DIRECT_SHADOW_MIN_RADIUS, EXPECT_FLOAT),
  EXPECT(MRGI_DIRECT_SHADOW_MAX_RADIUS, EXPECT_FLOAT),
  EXPECT(MRGI_DIRECT_SHADOW_NO_OCCLUDER, EXPECT_FLOAT),
  EXPECT(MRGI_BMR_LEVELS, EXPECT_INT),
  EXPECT(MRGI_BMR_MAX_RADIUS, EXPECT_INT),
  EXPECT(MRGI_BMR_COMBINE_MAX, EXPECT_INT),
  EXPECT(MRGI_BMR_COMBINE_MIN, EXPECT_INT),
  EXPECT(MRGI_BMR_SSGI_SKIP_LEVEL, EXPECT_INT),
  EXPECT(MRGI_BMR_SSAO_VARIANCE_1, EXPECT_FLOAT),
  EXPECT(MRGI_BMR_SSAO_VARIANCE_2, EXPECT_FLOAT),
  EXPECT(MRGI_BMR_SSAO_VARIANCE_3, EXPECT_FLOAT),
  EXPECT(MRGI_BMR_SSAO_VARIANCE_4, EXPECT_FLOAT),
  EXPECT(MRGI_BMR_SSAO_WEIGHT_1, EXPECT_FLOAT),
  EXPECT(MRGI_BMR_SSAO_WEIGHT_2, EXPECT_FLOAT),
  EXPECT(MRGI_BMR_SSAO_WEIGHT_3, EXPECT_FLOAT),
  EXPECT(MRGI_BMR_SSAO_WEIGHT_4, EXPECT_FLOAT),
  EXPECT(MRGI_BMR_SSM_VARIANCE_1, EXPECT_FLOAT),
  EXPECT(MRGI_BMR_SSM_VARIANCE_2, EXPECT_FLOAT),
  EXPECT(MRGI_BMR_SSM_VARIANCE_3, EXPECT_FLOAT),
  EXPECT(MRGI_BMR_SSM_VARIANCE_4, EXPECT_FLOAT),
  EXPECT(MRGI_BMR_SSM_WEIGHT_1, EXPECT_FLOAT),
  EXPECT(MRGI_BMR_SSM_WEIGHT_2, EXPECT_FLOAT),
  EXPECT(MRGI_BMR_SSM_WEIGHT_3, EXPECT_FLOAT),
  EXPECT(MRGI_BMR_SSM_WEIGHT_4, EXPECT_FLOAT),
  EXPECT(MRGI_BMR_SSGI_VARIANCE_1, EXPECT_FLOAT),
  EXPECT(MRGI_BMR_SSGI_VARIANCE_2, EXPECT_FLOAT),
  EXPECT(MRGI_BMR_SSGI_VARIANCE_3, EXPECT_FLOAT),
  EXPECT(MRGI_BMR_SSGI_VARIANCE_4, EXPECT_FLOAT),
  EXPECT(MRGI_BMR_SSGI_WEIGHT_1, EXPECT_FLOAT),
  EXPECT(MRGI_BMR_SSGI_WEIGHT_2, EXPECT_FLOAT),
  EXPECT(MRGI_BMR_SSGI_WEIGHT_3, EXPECT_FLOAT),
  EXPECT(MRGI_BMR_SSGI_WEIGHT_4, EXPECT_FLOAT),
};
enum { EXPECTED_COUNT = sizeof(expected) / sizeof(expected[0]) };

/* Whether `text` is a GLSL int literal (decimal digits, optional minus). */
static int is_int_literal(const char* text)
{
  if (*text == '-')
  {
    ++text;
  }
  if (!*text)
  {
    return 0;
  }
  for (; *text; ++text)
  {
    if (!isdigit((unsigned char)*text))
    {
      return 0;
    }
  }
  return 1;
}

/* Whether `text` is a GLSL float literal: digits with a '.' and/or an
 * exponent, optional leading minus, nothing else (no suffix, no comma). */
static int is_float_literal(const char* text)
{
  if (*text == '-')
  {
    ++text;
  }
  int digits = 0;
  int point = 0;
  int exponent = 0;
  for (; *text; ++text)
  {
    if (isdigit((unsigned char)*text))
    {
      ++digits;
    }
    else if (*text == '.' && !point && !exponent)
    {
      point = 1;
    }
    else if ((*text == 'e' || *text == 'E') && digits && !exponent)
    {
      exponent = 1;
      if (text[1] == '+' || text[1] == '-')
      {
        ++text;
      }
      if (!isdigit((unsigned char)text[1]))
      {
        return 0;
      }
    }
    else
    {
      return 0;
    }
  }
  return digits > 0 && (point || exponent);
}

/* Parse the whole block and check it against `expected`. */
static void check_block(const char* block)
{
  for (int k = 0; k < EXPECTED_COUNT; ++k)
  {
    expected[k].seen = 0;
  }
  const char* line = block;
  int lines = 0;
  while (*line)
  {
    const char* end = strchr(line, '\n');
    MRGI_CHECK(end != NULL); /* every line ends with '\n' */
    char text[256];
    const size_t length = (size_t)(end - line);
    MRGI_CHECK(length < sizeof(text));
    memcpy(text, line, length);
    text[length] = '\0';
    ++lines;

    MRGI_CHECK(strncmp(text, "#define ", 8) == 0);
    const char* name = text + 8;
    size_t name_length = 0;
    while (isupper((unsigned char)name[name_length]) || isdigit((unsigned char)name[name_length]) ||
           name[name_length] == '_')
    {
      ++name_length;
    }
    MRGI_CHECK(name_length > 0 && name[name_length] == ' ');
    const char* value = name + name_length + 1;
    MRGI_CHECK(*value != '\0' && strchr(value, ' ') == NULL);

    int found = 0;
    for (int k = 0; k < EXPECTED_COUNT; ++k)
    {
      if (strlen(expected[k].name) != name_length ||
          strncmp(expected[k].name, name, name_length) != 0)
      {
        continue;
      }
      found = 1;
      MRGI_CHECK(expected[k].seen == 0); /* defined once */
      expected[k].seen = 1;
      const double parsed = strtod(value, NULL);
      switch (expected[k].kind)
      {
        case EXPECT_INT:
          MRGI_CHECK(is_int_literal(value));
          MRGI_CHECK(parsed == expected[k].value);
          break;
        case EXPECT_FLOAT:
          MRGI_CHECK(is_float_literal(value));
          MRGI_CHECK((float)parsed == (float)expected[k].value);
          break;
        case EXPECT_DOUBLE:
          MRGI_CHECK(is_float_literal(value));
          MRGI_CHECK(parsed == expected[k].value);
          break;
      }
    }
    if (!found)
    {
      fprintf(stderr, "unexpected line: %s\n", text);
    }
    MRGI_CHECK(found);
    line = end + 1;
  }
  MRGI_CHECK(lines == EXPECTED_COUNT);
  for (int k = 0; k < EXPECTED_COUNT; ++k)
  {
    if (!expected[k].seen)
    {
      fprintf(stderr, "missing: %s\n", expected[k].name);
    }
    MRGI_CHECK(expected[k].seen);
  }
}

static void test_block(void)
{
  const size_t size = mrgi_glsl_defines_size();
  MRGI_CHECK(size > 1 && size <= MRGI_GLSL_DEFINES_MAX_SIZE);
  char buffer[MRGI_GLSL_DEFINES_MAX_SIZE];
  size_t written = 0;
  MRGI_CHECK(mrgi_glsl_defines(buffer, sizeof(buffer), &written, NULL) == MRGI_OK);
  MRGI_CHECK(written == size - 1 && strlen(buffer) == written);
  check_block(buffer);
  /* Short and exact forms, as a shader author reads them. */
  MRGI_CHECK(strstr(buffer, "#define MRGI_RSM_MIN_COS 0.05\n") != NULL);
  MRGI_CHECK(strstr(buffer, "#define MRGI_VPL_TEXELS 3\n") != NULL);
  MRGI_CHECK(strstr(buffer, "#define MRGI_VPL_MAX_COUNT 4096\n") != NULL);
}

static void test_buffer_contract(void)
{
  const size_t size = mrgi_glsl_defines_size();
  char* exact = (char*)malloc(size);
  MRGI_CHECK(exact != NULL);
  MRGI_CHECK(mrgi_glsl_defines(exact, size, NULL, NULL) == MRGI_OK);
  MRGI_CHECK(exact[size - 1] == '\0');
  memset(exact, 'x', size);
  mrgi_error err;
  MRGI_CHECK(mrgi_glsl_defines(exact, size - 1, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "needs") != NULL);
  MRGI_CHECK(exact[0] == 'x'); /* nothing written on failure */
  MRGI_CHECK(mrgi_glsl_defines(NULL, 100, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_glsl_defines(exact, 0, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  free(exact);
}

/* A comma-decimal C locale (set by some GUI applications) must not leak into GLSL. */
static void test_locale_independent(void)
{
  const char* locales[] = { "de_DE.UTF-8", "de_DE.utf8", "fr_FR.UTF-8", "fr_FR.utf8" };
  const char* chosen = NULL;
  for (size_t k = 0; k < sizeof(locales) / sizeof(locales[0]) && !chosen; ++k)
  {
    if (setlocale(LC_NUMERIC, locales[k]))
    {
      chosen = locales[k];
    }
  }
  if (!chosen)
  {
    printf("no comma-decimal locale installed; locale check skipped\n");
    return;
  }
  char buffer[MRGI_GLSL_DEFINES_MAX_SIZE];
  MRGI_CHECK(mrgi_glsl_defines(buffer, sizeof(buffer), NULL, NULL) == MRGI_OK);
  setlocale(LC_NUMERIC, "C");
  MRGI_CHECK(strchr(buffer, ',') == NULL);
  check_block(buffer);
}

int main(int argc, char** argv)
{
  static const mrgi_test_case cases[] = {
    MRGI_TEST_CASE(test_block),
    MRGI_TEST_CASE(test_buffer_contract),
    MRGI_TEST_CASE(test_locale_independent),
  };
  return MRGI_TEST_MAIN(argc, argv, cases);
}
