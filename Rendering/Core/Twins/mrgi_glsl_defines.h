/**
 * @file mrgi_glsl_defines.h
 * @brief The core's constants as a block of GLSL `#define` lines, so that
 *        shaders use the values the C headers define (defined once, never
 *        typed twice; see DESIGN.md "One source of truth for C and GLSL").
 *
 * The block is one line per constant, in this exact form:
 *
 *     #define NAME VALUE\n
 *
 * NAME is the C macro's name ([A-Z_0-9]+). VALUE is a GLSL int literal
 * (decimal, e.g. `4096`) for integer constants, or a GLSL float literal for
 * real ones: the shortest decimal that reads back as the same float (float
 * constants, e.g. MRGI_RSM_MIN_COS -> `0.05`) or the same double (double
 * constants, e.g. MRGI_PI -> `3.1415926535897931`), always with a '.' or an
 * exponent so GLSL types it float. strtod() of VALUE gives back the C value
 * (after rounding to float for float constants).
 *
 * Constants emitted (their meaning is documented where they are defined):
 * from mrgi_vpl.h MRGI_VPL_TEXELS, MRGI_VPL_TEXEL_POSITION,
 * MRGI_VPL_TEXEL_NORMAL, MRGI_VPL_TEXEL_FLUX, MRGI_VPL_FLOATS,
 * MRGI_VPL_MIN_COUNT, MRGI_VPL_MAX_COUNT, MRGI_RSM_MIN_COS,
 * MRGI_RSM_MAX_VIEWS, MRGI_VALID_THRESHOLD, MRGI_LUMINANCE_R,
 * MRGI_LUMINANCE_G, MRGI_LUMINANCE_B; from mrgi_gather.h MRGI_PI; from
 * mrgi_vpl_tree.h MRGI_VPL_TREE_ROOT_SIDE; from mrgi_vpl_tree_gather.h the tree
 * texture and traversal numbers MRGI_VPL_TREE_RECORDS_PER_ROW,
 * _MAX_LOOP_ITERATIONS, _STACK_SIZE and _GATHER_MAX_RSM_SIZE; from
 * mrgi_multires.h MRGI_MULTIRES_MAX_LEVELS, the MRGI_MULTIRES_TEX_*, _*_BIT and
 * _FLAG_* numbers, MRGI_MULTIRES_FLT_MAX, MRGI_MULTIRES_MIN_PIXEL_SIZE,
 * MRGI_MULTIRES_THRESHOLD_OFF; from mrgi_upsample.h MRGI_UPSAMPLE_TENT and
 * MRGI_UPSAMPLE_MASK_WEIGHTED; from mrgi_exposure.h MRGI_TONE_SHOULDER; from mrgi_voxel.h,
 * mrgi_voxel_march.h and mrgi_visibility_pyramid.h the voxel layout and visibility numbers
 * MRGI_VOXEL_LAYER_SLICES, _MAX_LAYERS, _CHANNELS, _CHANNEL_BITS, _MAX_SIZE, _MAX_STEPS,
 * _MAX_SAMPLES, _MAX_MASK_WORDS, _INTERLEAVE_PHASES, _ALL_PHASES,
 * _NEIGHBOURS, _METRIC_DISAGREE, _METRIC_COUNT_SPREAD, _VSM_QUERIES,
 * _VSM_TARGETS, _INTERLEAVE_MIN_COS, _INTERLEAVE_MAX_SLOPE; from
 * mrgi_area_light.h the light-sample record
 * and lobe numbers MRGI_AREA_LIGHT_MIN_SAMPLES, _MAX_SAMPLES, _SAMPLE_TEXELS,
 * _SAMPLE_TEXEL_POSITION, _SAMPLE_TEXEL_NORMAL, _SAMPLE_TEXEL_RADIANCE,
 * _SAMPLE_FLOATS, _LOBE_GRID, _LOBE_MIN_SAMPLES, _LOBE_CUTOFF, _LOBE_DISCARD,
 * _MIN_COS, _MIN_ALONG, MRGI_AREA_LIGHT_RSM_SAMPLES (mrgi_area_light_rsm.h) and the specular paths
 * (::mrgi_area_light_specular_path) MRGI_AREA_LIGHT_SPECULAR_SAMPLES, _LOBE_GRID, _BEHIND,
 * _FACING_AWAY, _LOBE_MISS; from mrgi_direct_shadow.h MRGI_DIRECT_SHADOW_HARD, _SOFT, _MAX_VIEWS,
 * _HARD_SIDE, _BLOCKER_SIDE, _MAX_SIDE, _BIAS_TEXELS, _MAX_SLOPE, _SEARCH_NEAR, _MIN_RADIUS,
 * _MAX_RADIUS, _NO_OCCLUDER; from mrgi_bmr_mask.h MRGI_BMR_LEVELS, _MAX_RADIUS, _COMBINE_MAX,
 * _COMBINE_MIN, _SSGI_SKIP_LEVEL and Table 1's presets
 * MRGI_BMR_{SSAO,SSM,SSGI}_{VARIANCE,WEIGHT}_{1..4}.
 *
 * Insert the block after the shader's `#version` line (a `#define` may not
 * precede it).
 */
#ifndef MRGI_GLSL_DEFINES_H
#define MRGI_GLSL_DEFINES_H

#include "mrgi_error.h"

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/** An upper bound of mrgi_glsl_defines_size(): a buffer this large always suffices. */
#define MRGI_GLSL_DEFINES_MAX_SIZE 8192

/** @brief Bytes the block needs, terminating NUL included (<= MRGI_GLSL_DEFINES_MAX_SIZE). */
size_t mrgi_glsl_defines_size(void);

/**
 * @brief Write the `#define` block (see the file comment), NUL-terminated.
 * @param buffer  Destination.
 * @param size    Bytes available in `buffer`; at least mrgi_glsl_defines_size().
 * @param written Receives the block's length without the NUL; may be NULL.
 * @return ::MRGI_ERR_INVALID_ARGUMENT for a NULL buffer or one too small
 *         (the message names the size needed); nothing is written then.
 */
mrgi_status mrgi_glsl_defines(char* buffer, size_t size, size_t* written, mrgi_error* err);

#ifdef __cplusplus
}
#endif

#endif
