/**
 * @file mrgi_screen_space_preset.h
 * @brief Presets for the screen-space effects (SSAO, soft shadows, SSGI):
 *        one table of sample counts, BMR mask thresholds and resolutions,
 *        following the multiresolution presets (mrgi_multires.h).
 *
 * A preset sets, for vtkMRGIPass::SetScreenSpacePreset() and
 * `mrgi-render --screen-space-preset`:
 * - `ssao_kernel_size`: SSAO hemisphere samples (1..MRGI_SSAO_MAX_KERNEL_SIZE);
 * - `shadow_kernel_side`: soft-shadow PCSS filter taps per side
 *   (1..MRGI_DIRECT_SHADOW_MAX_SIDE; side^2 taps);
 * - `ssgi_samples`: SSGI hemisphere samples (1..MRGI_SSGI_MAX_SAMPLES);
 * - `bmr_depth_threshold`, `bmr_normal_threshold`: the BMR edge tests of
 *   every effect's mask (mrgi_bmr_mask.h; used by the multiresolution
 *   paths only);
 * - `ssao_resolution`, `shadow_resolution`, `ssgi_resolution`:
 *   MRGI_SCREEN_SPACE_FULL (0) or MRGI_SCREEN_SPACE_MULTIRESOLUTION (1)
 *   (vtkMRGIPass::ResolutionFull / ResolutionMultiresolution).
 *
 * It never switches an effect on or off and leaves radii, biases and the
 * shadow light radius alone (they are scene units). Balanced is today's
 * defaults, so a pass without a preset and one with Balanced render the
 * same. Accurate takes BMR figure 6's sample counts (SSAO 64, soft shadows
 * 196 taps = 14 x 14, SSGI 228). The sample counts of Fast are the cheapest
 * whose error against Accurate is documented in
 * Documentation/ScreenSpaceEffects.md ("Presets", measured by
 * Testing/Benchmarks/screen_space_presets.py), with the times of each preset.
 * Resolutions: SSAO and soft shadows are full in every preset (on this
 * project's llvmpipe machine their BMR masks and blend cost more than they
 * save, Documentation/ScreenSpaceEffects-Benchmark.md); SSGI is
 * multiresolution in Fast only (2.8x / 4.25x faster at 720p / 1080p with
 * 228 samples, absolute RMS 0.0005 against full, same page), full
 * elsewhere so that Balanced stays the defaults.
 */
#ifndef MRGI_SCREEN_SPACE_PRESET_H
#define MRGI_SCREEN_SPACE_PRESET_H

#include "mrgi_error.h"

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef enum mrgi_screen_space_preset
{
  MRGI_SCREEN_SPACE_PRESET_FAST = 0,
  MRGI_SCREEN_SPACE_PRESET_BALANCED = 1,
  MRGI_SCREEN_SPACE_PRESET_ACCURATE = 2
} mrgi_screen_space_preset;

#define MRGI_SCREEN_SPACE_PRESET_COUNT 3

/** Where an effect is evaluated (the values of vtkMRGIPass::ScreenSpaceResolutions). */
#define MRGI_SCREEN_SPACE_FULL 0
#define MRGI_SCREEN_SPACE_MULTIRESOLUTION 1

/** The settings of one preset (see the file comment for ranges). */
typedef struct mrgi_screen_space_preset_params
{
  int32_t ssao_kernel_size;
  int32_t shadow_kernel_side;
  int32_t ssgi_samples;
  double bmr_depth_threshold;
  double bmr_normal_threshold;
  int32_t ssao_resolution;
  int32_t shadow_resolution;
  int32_t ssgi_resolution;
} mrgi_screen_space_preset_params;

/**
 * @brief The settings of a preset.
 * @return ::MRGI_ERR_INVALID_ARGUMENT for NULL `params` or an unknown preset
 *         (params untouched).
 */
mrgi_status mrgi_screen_space_preset_get(
  int32_t preset, mrgi_screen_space_preset_params* params, mrgi_error* err);

/** @brief "fast", "balanced", "accurate"; NULL for an unknown preset. */
const char* mrgi_screen_space_preset_name(int32_t preset);

#ifdef __cplusplus
}
#endif

#endif
