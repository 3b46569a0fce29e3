// vtkMRGIPass::SetScreenSpacePreset applies the one table of
// mrgi_screen_space_preset_get(): for every preset, after the knobs were set
// to values no preset has, the pass's SSAO kernel, soft-shadow kernel, SSGI
// samples and the three resolutions, and the BMR mask thresholds of the
// SSAO, SSGI and direct-shadow stages, equal the table's; effects, radii
// and biases are untouched; an unknown preset is refused and changes
// nothing; a knob set afterwards overrides the preset's. No rendering.
#include "mrgiTestUtilities.h"

#include "vtkMRGIBMRMask.h"
#include "vtkMRGIDirectShadows.h"
#include "vtkMRGIPass.h"
#include "vtkMRGISSAO.h"
#include "vtkMRGISSGI.h"
#include "vtkNew.h"

#include "mrgi_screen_space_preset.h"

#include <cstdio>
#include <sstream>

namespace
{
// Knob values no preset uses, so that each assertion can fail.
void Scramble(vtkMRGIPass* pass)
{
  pass->SetSSAOKernelSize(999);
  pass->SetSoftShadowKernelSize(13);
  pass->SetSSGISamples(511);
  pass->SetSSAOResolution(vtkMRGIPass::ResolutionMultiresolution);
  pass->SetShadowResolution(vtkMRGIPass::ResolutionMultiresolution);
  pass->SetSSGIResolution(vtkMRGIPass::ResolutionMultiresolution);
  for (vtkMRGIBMRMask* mask : { pass->GetSSAOStage()->GetBMRMask(),
         pass->GetSSGIStage()->GetBMRMask(), pass->GetDirectShadowStage()->GetBMRMask() })
  {
    mask->SetDepthThreshold(123.0);
    mask->SetNormalThreshold(0.987);
  }
}

void CheckApplied(vtkMRGIPass* pass, const mrgi_screen_space_preset_params& p)
{
  MRGI_TEST_CHECK(pass->GetSSAOKernelSize() == p.ssao_kernel_size);
  MRGI_TEST_CHECK(pass->GetSoftShadowKernelSize() == p.shadow_kernel_side);
  MRGI_TEST_CHECK(pass->GetSSGISamples() == p.ssgi_samples);
  MRGI_TEST_CHECK(pass->GetSSAOResolution() == p.ssao_resolution);
  MRGI_TEST_CHECK(pass->GetShadowResolution() == p.shadow_resolution);
  MRGI_TEST_CHECK(pass->GetSSGIResolution() == p.ssgi_resolution);
  for (vtkMRGIBMRMask* mask : { pass->GetSSAOStage()->GetBMRMask(),
         pass->GetSSGIStage()->GetBMRMask(), pass->GetDirectShadowStage()->GetBMRMask() })
  {
    MRGI_TEST_CHECK(mask->GetDepthThreshold() == p.bmr_depth_threshold);
    MRGI_TEST_CHECK(mask->GetNormalThreshold() == p.bmr_normal_threshold);
  }
}

void EachPreset()
{
  for (int preset = 0; preset < MRGI_SCREEN_SPACE_PRESET_COUNT; ++preset)
  {
    vtkNew<vtkMRGIPass> pass;
    MRGI_TEST_CHECK(pass->GetScreenSpacePreset() == -1);
    pass->SSAOOn();
    pass->SetSSAORadius(7.0);
    pass->SetSSGIBias(0.3);
    Scramble(pass);
    mrgi_screen_space_preset_params p;
    MRGI_TEST_CHECK(mrgi_screen_space_preset_get(preset, &p, nullptr) == MRGI_OK);
    MRGI_TEST_CHECK(pass->SetScreenSpacePreset(preset));
    MRGI_TEST_CHECK(pass->GetScreenSpacePreset() == preset);
    CheckApplied(pass, p);
    // Effects, radii and biases are not the preset's.
    MRGI_TEST_CHECK(pass->GetSSAO() && !pass->GetSSGI());
    MRGI_TEST_CHECK(pass->GetSSAORadius() == 7.0 && pass->GetSSGIBias() == 0.3);
    std::ostringstream printed;
    pass->PrintSelf(printed, vtkIndent());
    MRGI_TEST_CHECK(
      printed.str().find(mrgi_screen_space_preset_name(preset)) != std::string::npos);
    std::printf("preset %s: SSAO %d, shadow side %d, SSGI %d, BMR thresholds %g / %g\n",
      mrgi_screen_space_preset_name(preset), p.ssao_kernel_size, p.shadow_kernel_side,
      p.ssgi_samples, p.bmr_depth_threshold, p.bmr_normal_threshold);
    // A knob set afterwards overrides the preset's.
    pass->SetSSGISamples(3);
    MRGI_TEST_CHECK(pass->GetSSGISamples() == 3);
  }
}

// Balanced is the defaults: a new pass equals one with Balanced applied.
void BalancedIsDefault()
{
  vtkNew<vtkMRGIPass> pass;
  mrgi_screen_space_preset_params p;
  MRGI_TEST_CHECK(
    mrgi_screen_space_preset_get(MRGI_SCREEN_SPACE_PRESET_BALANCED, &p, nullptr) == MRGI_OK);
  CheckApplied(pass, p);
}

void Unknown()
{
  vtkNew<vtkMRGIPass> pass;
  Scramble(pass);
  std::printf("(two errors about unknown presets are expected)\n");
  MRGI_TEST_CHECK(!pass->SetScreenSpacePreset(3));
  MRGI_TEST_CHECK(!pass->SetScreenSpacePreset(-1));
  MRGI_TEST_CHECK(pass->GetScreenSpacePreset() == -1);
  MRGI_TEST_CHECK(pass->GetSSAOKernelSize() == 999 && pass->GetSSGISamples() == 511);
  MRGI_TEST_CHECK(pass->GetSSAOStage()->GetBMRMask()->GetDepthThreshold() == 123.0);
}
}

int main(int argc, char* argv[])
{
  return mrgitest::RunCases(argc, argv,
    { MRGI_TEST_CASE(EachPreset), MRGI_TEST_CASE(BalancedIsDefault), MRGI_TEST_CASE(Unknown) });
}
