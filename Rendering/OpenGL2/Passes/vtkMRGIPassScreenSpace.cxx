// vtkMRGIPass's screen-space effects (SSAO and SSGI) and the preset that
// sets their quality knobs together, apart from the frame logic in
// vtkMRGIPass.cxx. The class is documented in vtkMRGIPass.h.
#include "vtkMRGIPass.h"

#include "vtkMRGIBMRMask.h"
#include "vtkMRGIDirectShadows.h"
#include "vtkMRGIFrameContext.h"
#include "vtkMRGISSAO.h"
#include "vtkMRGISSGI.h"
#include "vtkMRGIShaderUtilities.h"

#include "mrgi_screen_space_preset.h"

//------------------------------------------------------------------------------
void vtkMRGIPass::RenderScreenSpaceEffects(const vtkMRGIFrameContext& frame, vtkTextureObject* colour)
{
  // SSAO as vtkSSAOPass applies it, to the direct light only: the indirect
  // and area light added below are not ambient terms and model their own
  // visibility. (After the direct shadows, which subtract shadowed light
  // terms from the unshadowed colour: AO multiplies their result.)
  if (this->SSAO)
  {
    vtkMRGIShaderUtilities::ScopedStage stage(frame.Timer, "ssao");
    const bool multires = this->SSAOResolution == ResolutionMultiresolution;
    if (multires
        ? this->SSAOStage->RenderMultiresolution(frame, this->SSAOKernelSize, this->SSAORadius,
            this->SSAOBias, this->SSAOBlur, colour)
        : this->SSAOStage->Render(frame, this->SSAOKernelSize, this->SSAORadius, this->SSAOBias,
            this->SSAOBlur, colour))
    {
      this->SSAOFailureReported = false;
    }
    else if (!this->SSAOFailureReported)
    {
      this->SSAOFailureReported = true;
      vtkErrorMacro("SSAO could not be computed (kernel size "
        << this->SSAOKernelSize << ", radius " << this->SSAORadius << ", bias " << this->SSAOBias
        << "): this frame has no ambient occlusion");
    }
  }
  // SSGI sends the direct light as it is now (shadowed, occluded).
  if (this->SSGI)
  {
    vtkMRGIShaderUtilities::ScopedStage stage(frame.Timer, "ssgi");
    const bool multires = this->SSGIResolution == ResolutionMultiresolution;
    if (multires ? this->SSGIStage->RenderMultiresolution(frame, this->SSGISamples,
                     this->SSGIRadius, this->SSGIBias, colour)
                 : this->SSGIStage->Render(frame, this->SSGISamples, this->SSGIRadius,
                     this->SSGIBias, colour))
    {
      this->SSGIFailureReported = false;
    }
    else if (!this->SSGIFailureReported)
    {
      this->SSGIFailureReported = true;
      vtkErrorMacro("SSGI could not be computed (samples "
        << this->SSGISamples << ", radius " << this->SSGIRadius << ", bias " << this->SSGIBias
        << "): this frame has no screen-space bounce");
    }
  }
}

//------------------------------------------------------------------------------
bool vtkMRGIPass::SetScreenSpacePreset(int preset)
{
  mrgi_screen_space_preset_params p;
  mrgi_error err;
  if (mrgi_screen_space_preset_get(preset, &p, &err) != MRGI_OK)
  {
    vtkErrorMacro("SetScreenSpacePreset: " << err.message);
    return false;
  }
  this->SetSSAOKernelSize(p.ssao_kernel_size);
  this->SetSoftShadowKernelSize(p.shadow_kernel_side);
  this->SetSSGISamples(p.ssgi_samples);
  this->SetSSAOResolution(p.ssao_resolution);
  this->SetShadowResolution(p.shadow_resolution);
  this->SetSSGIResolution(p.ssgi_resolution);
  for (vtkMRGIBMRMask* mask : { this->SSAOStage->GetBMRMask(), this->SSGIStage->GetBMRMask(),
         this->GetDirectShadowStage()->GetBMRMask() })
  {
    mask->SetDepthThreshold(p.bmr_depth_threshold);
    mask->SetNormalThreshold(p.bmr_normal_threshold);
  }
  this->ScreenSpacePreset = preset;
  this->Modified();
  return true;
}

