/* Tests of mrgi_screen_space_preset: every preset is in range for the
 * stages it feeds, Balanced is the defaults, the presets are ordered (Fast
 * takes no more samples than Balanced, Balanced no more than Accurate, and
 * at least one count differs), names round-trip, bad input is refused with
 * params untouched. */
#include "mrgi_screen_space_preset.h"

#include "mrgi_bmr_mask.h"
#include "mrgi_direct_shadow.h"
#include "mrgi_ssao.h"
#include "mrgi_ssgi.h"
#include "mrgi_test.h"

#include <math.h>
#include <string.h>

static void test_ranges(void)
{
  for (int32_t p = 0; p < MRGI_SCREEN_SPACE_PRESET_COUNT; ++p)
  {
    mrgi_screen_space_preset_params s;
    MRGI_CHECK(mrgi_screen_space_preset_get(p, &s, NULL) == MRGI_OK);
    MRGI_CHECK(s.ssao_kernel_size >= 1 && s.ssao_kernel_size <= MRGI_SSAO_MAX_KERNEL_SIZE);
    MRGI_CHECK(s.shadow_kernel_side >= 1 && s.shadow_kernel_side <= MRGI_DIRECT_SHADOW_MAX_SIDE);
    MRGI_CHECK(s.ssgi_samples >= 1 && s.ssgi_samples <= MRGI_SSGI_MAX_SAMPLES);
    MRGI_CHECK(isfinite(s.bmr_depth_threshold) && s.bmr_depth_threshold > 0.0);
    MRGI_CHECK(isfinite(s.bmr_normal_threshold) && s.bmr_normal_threshold > 0.0);
    const int32_t r[3] = { s.ssao_resolution, s.shadow_resolution, s.ssgi_resolution };
    for (int i = 0; i < 3; ++i)
    {
      MRGI_CHECK(r[i] == MRGI_SCREEN_SPACE_FULL || r[i] == MRGI_SCREEN_SPACE_MULTIRESOLUTION);
    }
  }
}

static void test_balanced_is_default(void)
{
  mrgi_screen_space_preset_params s;
  MRGI_CHECK(mrgi_screen_space_preset_get(MRGI_SCREEN_SPACE_PRESET_BALANCED, &s, NULL) == MRGI_OK);
  MRGI_CHECK(s.ssao_kernel_size == MRGI_SSAO_DEFAULT_KERNEL_SIZE);
  MRGI_CHECK(s.shadow_kernel_side == MRGI_DIRECT_SHADOW_DEFAULT_SIDE);
  MRGI_CHECK(s.ssgi_samples == MRGI_SSGI_DEFAULT_SAMPLES);
  MRGI_CHECK(s.bmr_depth_threshold == MRGI_BMR_DEFAULT_DEPTH_THRESHOLD);
  MRGI_CHECK(s.bmr_normal_threshold == MRGI_BMR_DEFAULT_NORMAL_THRESHOLD);
  MRGI_CHECK(s.ssao_resolution == MRGI_SCREEN_SPACE_FULL);
  MRGI_CHECK(s.shadow_resolution == MRGI_SCREEN_SPACE_FULL);
  MRGI_CHECK(s.ssgi_resolution == MRGI_SCREEN_SPACE_FULL);
}

static void test_ordered(void)
{
  mrgi_screen_space_preset_params f, b, a;
  MRGI_CHECK(mrgi_screen_space_preset_get(MRGI_SCREEN_SPACE_PRESET_FAST, &f, NULL) == MRGI_OK);
  MRGI_CHECK(mrgi_screen_space_preset_get(MRGI_SCREEN_SPACE_PRESET_BALANCED, &b, NULL) == MRGI_OK);
  MRGI_CHECK(mrgi_screen_space_preset_get(MRGI_SCREEN_SPACE_PRESET_ACCURATE, &a, NULL) == MRGI_OK);
  MRGI_CHECK(f.ssao_kernel_size <= b.ssao_kernel_size && b.ssao_kernel_size <= a.ssao_kernel_size);
  MRGI_CHECK(
    f.shadow_kernel_side <= b.shadow_kernel_side && b.shadow_kernel_side <= a.shadow_kernel_side);
  MRGI_CHECK(f.ssgi_samples <= b.ssgi_samples && b.ssgi_samples <= a.ssgi_samples);
  MRGI_CHECK(f.ssao_kernel_size < a.ssao_kernel_size || f.ssgi_samples < a.ssgi_samples);
  /* Coarser masks for Fast, finer for Accurate (a larger threshold refines less). */
  MRGI_CHECK(f.bmr_depth_threshold >= b.bmr_depth_threshold);
  MRGI_CHECK(b.bmr_depth_threshold >= a.bmr_depth_threshold);
  /* BMR figure 6's sample counts for Accurate. */
  MRGI_CHECK(a.ssao_kernel_size == 64 && a.shadow_kernel_side * a.shadow_kernel_side == 196 &&
    a.ssgi_samples == 228);
}

static void test_names_and_bad_input(void)
{
  MRGI_CHECK(strcmp(mrgi_screen_space_preset_name(MRGI_SCREEN_SPACE_PRESET_FAST), "fast") == 0);
  MRGI_CHECK(
    strcmp(mrgi_screen_space_preset_name(MRGI_SCREEN_SPACE_PRESET_BALANCED), "balanced") == 0);
  MRGI_CHECK(
    strcmp(mrgi_screen_space_preset_name(MRGI_SCREEN_SPACE_PRESET_ACCURATE), "accurate") == 0);
  MRGI_CHECK(mrgi_screen_space_preset_name(-1) == NULL);
  MRGI_CHECK(mrgi_screen_space_preset_name(MRGI_SCREEN_SPACE_PRESET_COUNT) == NULL);
  mrgi_screen_space_preset_params s;
  memset(&s, 0x5a, sizeof(s));
  mrgi_screen_space_preset_params before = s;
  mrgi_error err;
  MRGI_CHECK(mrgi_screen_space_preset_get(3, &s, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "unknown preset 3") != NULL);
  MRGI_CHECK(memcmp(&s, &before, sizeof(s)) == 0);
  MRGI_CHECK(mrgi_screen_space_preset_get(-1, &s, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_screen_space_preset_get(0, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "NULL") != NULL);
}

int main(int argc, char** argv)
{
  static const mrgi_test_case cases[] = {
    MRGI_TEST_CASE(test_ranges),
    MRGI_TEST_CASE(test_balanced_is_default),
    MRGI_TEST_CASE(test_ordered),
    MRGI_TEST_CASE(test_names_and_bad_input),
  };
  return MRGI_TEST_MAIN(argc, argv, cases);
}
