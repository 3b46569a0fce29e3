#include "mrgi_screen_space_preset.h"

#include "mrgi_bmr_mask.h"
#include "mrgi_direct_shadow.h"
#include "mrgi_ssao.h"
#include "mrgi_ssgi.h"

/* The one table (mrgi_screen_space_preset.h). Balanced repeats the
 * defaults of vtkMRGIPass and mrgi-render (the MRGI_*_DEFAULT_* constants),
 * Accurate BMR figure 6's sample counts; the measured error and time of
 * each row: Documentation/ScreenSpaceEffects.md, "Presets". */
static const struct
{
  const char* name;
  mrgi_screen_space_preset_params params;
} mrgi_screen_space_presets[MRGI_SCREEN_SPACE_PRESET_COUNT] = {
  { "fast",
    { 16, 4, 32, 4.0 * MRGI_BMR_DEFAULT_DEPTH_THRESHOLD, 4.0 * MRGI_BMR_DEFAULT_NORMAL_THRESHOLD,
      MRGI_SCREEN_SPACE_FULL, MRGI_SCREEN_SPACE_FULL, MRGI_SCREEN_SPACE_MULTIRESOLUTION } },
  { "balanced",
    { MRGI_SSAO_DEFAULT_KERNEL_SIZE, MRGI_DIRECT_SHADOW_DEFAULT_SIDE, MRGI_SSGI_DEFAULT_SAMPLES,
      MRGI_BMR_DEFAULT_DEPTH_THRESHOLD, MRGI_BMR_DEFAULT_NORMAL_THRESHOLD, MRGI_SCREEN_SPACE_FULL,
      MRGI_SCREEN_SPACE_FULL, MRGI_SCREEN_SPACE_FULL } },
  { "accurate",
    { 64, 14, 228, 0.5 * MRGI_BMR_DEFAULT_DEPTH_THRESHOLD, 0.5 * MRGI_BMR_DEFAULT_NORMAL_THRESHOLD,
      MRGI_SCREEN_SPACE_FULL, MRGI_SCREEN_SPACE_FULL, MRGI_SCREEN_SPACE_FULL } },
};

mrgi_status mrgi_screen_space_preset_get(
  int32_t preset, mrgi_screen_space_preset_params* params, mrgi_error* err)
{
  if (!params)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "screen-space preset: params is NULL");
  }
  if (preset < 0 || preset >= MRGI_SCREEN_SPACE_PRESET_COUNT)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "screen-space preset: unknown preset %d (0 fast, 1 balanced, 2 accurate)", (int)preset);
  }
  *params = mrgi_screen_space_presets[preset].params;
  return MRGI_OK;
}

const char* mrgi_screen_space_preset_name(int32_t preset)
{
  return (preset >= 0 && preset < MRGI_SCREEN_SPACE_PRESET_COUNT)
    ? mrgi_screen_space_presets[preset].name
    : NULL;
}
