#include "mrgi_glsl_defines.h"

#include "mrgi_area_light.h"
#include "mrgi_direct_shadow.h"
#include "mrgi_exposure.h"
#include "mrgi_gather.h"
#include "mrgi_multires.h"
#include "mrgi_shadow_composite.h"
#include "mrgi_specular_stencil.h"
#include "mrgi_ssao.h"
#include "mrgi_upsample.h"
#include "mrgi_variance_shadow.h"
#include "mrgi_visibility_pyramid.h"
#include "mrgi_vpl.h"

#include <locale.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* How a constant is written into GLSL. */
typedef enum mrgi_glsl_kind
{
  MRGI_GLSL_INT,    /* decimal int literal */
  MRGI_GLSL_FLOAT,  /* float literal reading back as the same float */
  MRGI_GLSL_DOUBLE  /* float literal reading back as the same double */
} mrgi_glsl_kind;

typedef struct mrgi_glsl_constant
{
  const char* name;
  mrgi_glsl_kind kind;
  double value;
} mrgi_glsl_constant;

/* The name is the macro itself, stringized: each constant is typed once. */
#define MRGI_GLSL_CONSTANT(macro, kind) { #macro, kind, (double)(macro) }

static const mrgi_glsl_constant mrgi_glsl_constants[] = {
  MRGI_GLSL_CONSTANT(MRGI_VPL_TEXELS, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_VPL_TEXEL_POSITION, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_VPL_TEXEL_NORMAL, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_VPL_TEXEL_FLUX, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_VPL_FLOATS, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_VPL_MIN_COUNT, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_VPL_MAX_COUNT, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_RSM_MIN_COS, MRGI_GLSL_FLOAT),
  MRGI_GLSL_CONSTANT(MRGI_RSM_MAX_VIEWS, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_VALID_THRESHOLD, MRGI_GLSL_FLOAT),
  MRGI_GLSL_CONSTANT(MRGI_LUMINANCE_R, MRGI_GLSL_DOUBLE),
  MRGI_GLSL_CONSTANT(MRGI_LUMINANCE_G, MRGI_GLSL_DOUBLE),
  MRGI_GLSL_CONSTANT(MRGI_LUMINANCE_B, MRGI_GLSL_DOUBLE),
  MRGI_GLSL_CONSTANT(MRGI_PI, MRGI_GLSL_DOUBLE),
  MRGI_GLSL_CONSTANT(MRGI_SSAO_NOISE_SIZE, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_GBUFFER_VALID, MRGI_GLSL_FLOAT),
  MRGI_GLSL_CONSTANT(MRGI_GBUFFER_VALID_THRESHOLD, MRGI_GLSL_FLOAT),
  MRGI_GLSL_CONSTANT(MRGI_GBUFFER_DIRECT, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_GBUFFER_POSITION, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_GBUFFER_NORMAL, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_GBUFFER_ALBEDO, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_GBUFFER_SPECULAR, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_GBUFFER_SHININESS, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_GBUFFER_LIGHT0, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_SHADOW_SLOTS, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_SHADOW_PBR_GAMMA, MRGI_GLSL_FLOAT),
  MRGI_GLSL_CONSTANT(MRGI_RSM_POSITION, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_RSM_NORMAL, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_RSM_FLUX, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_MULTIRES_MAX_LEVELS, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_SPECULAR_STENCIL_REFINE, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_SPECULAR_STENCIL_LOBE, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_SPECULAR_STENCIL_SPECULAR, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_MULTIRES_TEX_DEPTH, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_MULTIRES_TEX_NORMAL_MIN, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_MULTIRES_TEX_NORMAL_MAX, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_MULTIRES_TEX_COUNT, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_MULTIRES_VALID_BIT, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_MULTIRES_INVALID_BIT, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_MULTIRES_FLAG_NONEMPTY, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_MULTIRES_FLAG_MIXED, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_MULTIRES_FLAG_DISCONTINUOUS, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_MULTIRES_FLAG_REFINE, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_MULTIRES_FLT_MAX, MRGI_GLSL_FLOAT),
  MRGI_GLSL_CONSTANT(MRGI_MULTIRES_MIN_PIXEL_SIZE, MRGI_GLSL_FLOAT),
  MRGI_GLSL_CONSTANT(MRGI_MULTIRES_THRESHOLD_OFF, MRGI_GLSL_FLOAT),
  MRGI_GLSL_CONSTANT(MRGI_UPSAMPLE_TENT, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_UPSAMPLE_MASK_WEIGHTED, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_TONE_SHOULDER, MRGI_GLSL_FLOAT),
  MRGI_GLSL_CONSTANT(MRGI_VOXEL_SLICES, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_VOXEL_CHANNELS, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_VOXEL_CHANNEL_BITS, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_VOXEL_MAX_SIZE, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_VOXEL_MAX_STEPS, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_VOXEL_MAX_SAMPLES, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_VOXEL_MAX_MASK_WORDS, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_VOXEL_INTERLEAVE_PHASES, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_VOXEL_ALL_PHASES, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_VOXEL_NEIGHBOURS, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_VOXEL_METRIC_DISAGREE, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_VOXEL_METRIC_COUNT_SPREAD, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_VOXEL_VSM_QUERIES, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_VOXEL_VSM_TARGETS, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_VOXEL_INTERLEAVE_MIN_COS, MRGI_GLSL_FLOAT),
  MRGI_GLSL_CONSTANT(MRGI_VOXEL_INTERLEAVE_MAX_SLOPE, MRGI_GLSL_FLOAT),
  MRGI_GLSL_CONSTANT(MRGI_AREA_LIGHT_MIN_SAMPLES, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_AREA_LIGHT_MAX_SAMPLES, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_AREA_LIGHT_SAMPLE_TEXELS, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_AREA_LIGHT_SAMPLE_TEXEL_POSITION, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_AREA_LIGHT_SAMPLE_TEXEL_NORMAL, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_AREA_LIGHT_SAMPLE_TEXEL_RADIANCE, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_AREA_LIGHT_SAMPLE_FLOATS, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_AREA_LIGHT_LOBE_GRID, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_AREA_LIGHT_LOBE_MIN_SAMPLES, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_AREA_LIGHT_LOBE_CUTOFF, MRGI_GLSL_FLOAT),
  MRGI_GLSL_CONSTANT(MRGI_AREA_LIGHT_LOBE_DISCARD, MRGI_GLSL_FLOAT),
  MRGI_GLSL_CONSTANT(MRGI_AREA_LIGHT_MIN_COS, MRGI_GLSL_FLOAT),
  MRGI_GLSL_CONSTANT(MRGI_AREA_LIGHT_MIN_ALONG, MRGI_GLSL_FLOAT),
  MRGI_GLSL_CONSTANT(MRGI_AREA_LIGHT_SPECULAR_SAMPLES, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_AREA_LIGHT_SPECULAR_LOBE_GRID, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_AREA_LIGHT_SPECULAR_BEHIND, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_AREA_LIGHT_SPECULAR_FACING_AWAY, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_AREA_LIGHT_SPECULAR_LOBE_MISS, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_DIRECT_SHADOW_HARD, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_DIRECT_SHADOW_SOFT, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_DIRECT_SHADOW_MAX_VIEWS, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_DIRECT_SHADOW_HARD_SIDE, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_DIRECT_SHADOW_BLOCKER_SIDE, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_DIRECT_SHADOW_MAX_SIDE, MRGI_GLSL_INT),
  MRGI_GLSL_CONSTANT(MRGI_DIRECT_SHADOW_BIAS_TEXELS, MRGI_GLSL_FLOAT),
  MRGI_GLSL_CONSTANT(MRGI_DIRECT_SHADOW_MAX_SLOPE, MRGI_GLSL_FLOAT),
  MRGI_GLSL_CONSTANT(MRGI_DIRECT_SHADOW_SEARCH_NEAR, MRGI_GLSL_FLOAT),
  MRGI_GLSL_CONSTANT(MRGI_DIRECT_SHADOW_MIN_RADIUS, MRGI_GLSL_FLOAT),
  MRGI_GLSL_CONSTANT(MRGI_DIRECT_SHADOW_MAX_RADIUS, MRGI_GLSL_FLOAT),
  MRGI_GLSL_CONSTANT(MRGI_DIRECT_SHADOW_NO_OCCLUDER, MRGI_GLSL_FLOAT),
};

/* Longest VALUE text: sign, 17 digits, point, exponent, ".0" suffix, NUL. */
#define MRGI_GLSL_VALUE_SIZE 40

/* Shortest "%.*g" text of `value` that strtod reads back exactly (as a float
 * for MRGI_GLSL_FLOAT), with '.' as decimal point whatever the C locale,
 * and a '.' or exponent present so that GLSL types it float. */
static void mrgi_glsl_format_real(double value, mrgi_glsl_kind kind, char text[MRGI_GLSL_VALUE_SIZE])
{
  const int max_digits = kind == MRGI_GLSL_FLOAT ? 9 : 17;
  for (int digits = 1; digits <= max_digits; ++digits)
  {
    snprintf(text, MRGI_GLSL_VALUE_SIZE, "%.*g", digits, value);
    const double parsed = strtod(text, NULL); /* same locale as snprintf */
    const int exact = kind == MRGI_GLSL_FLOAT ? (float)parsed == (float)value : parsed == value;
    if (exact)
    {
      break;
    }
  }
  /* Swap the locale's decimal point (e.g. "," in de_DE) for GLSL's ".". */
  const char* point = localeconv()->decimal_point;
  const size_t point_length = point ? strlen(point) : 0;
  if (point_length > 0 && strcmp(point, ".") != 0)
  {
    char* found = strstr(text, point);
    if (found)
    {
      *found = '.';
      memmove(found + 1, found + point_length, strlen(found + point_length) + 1);
    }
  }
  if (!strpbrk(text, ".eE"))
  {
    strncat(text, ".0", MRGI_GLSL_VALUE_SIZE - strlen(text) - 1);
  }
}

/* The whole block into `out` (MRGI_GLSL_DEFINES_MAX_SIZE bytes); its length. */
static size_t mrgi_glsl_defines_build(char out[MRGI_GLSL_DEFINES_MAX_SIZE])
{
  size_t length = 0;
  out[0] = '\0';
  const size_t count = sizeof(mrgi_glsl_constants) / sizeof(mrgi_glsl_constants[0]);
  for (size_t k = 0; k < count; ++k)
  {
    const mrgi_glsl_constant* constant = mrgi_glsl_constants + k;
    char value[MRGI_GLSL_VALUE_SIZE];
    if (constant->kind == MRGI_GLSL_INT)
    {
      snprintf(value, sizeof(value), "%lld", (long long)constant->value);
    }
    else
    {
      mrgi_glsl_format_real(constant->value, constant->kind, value);
    }
    const int line = snprintf(out + length, MRGI_GLSL_DEFINES_MAX_SIZE - length,
                              "#define %s %s\n", constant->name, value);
    if (line > 0)
    {
      length += (size_t)line;
    }
    if (length >= MRGI_GLSL_DEFINES_MAX_SIZE)
    {
      /* Unreachable with the table above (TestGLSLDefines checks the size);
       * keep whole lines only. */
      length -= (size_t)line;
      out[length] = '\0';
      break;
    }
  }
  return length;
}

size_t mrgi_glsl_defines_size(void)
{
  char block[MRGI_GLSL_DEFINES_MAX_SIZE];
  return mrgi_glsl_defines_build(block) + 1;
}

mrgi_status mrgi_glsl_defines(char* buffer, size_t size, size_t* written, mrgi_error* err)
{
  if (!buffer)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "GLSL defines buffer is NULL");
  }
  char block[MRGI_GLSL_DEFINES_MAX_SIZE];
  const size_t length = mrgi_glsl_defines_build(block);
  if (size < length + 1)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "GLSL defines buffer holds %zu bytes but the block needs %zu "
                          "(mrgi_glsl_defines_size())",
                          size, length + 1);
  }
  memcpy(buffer, block, length + 1);
  if (written)
  {
    *written = length;
  }
  return MRGI_OK;
}
