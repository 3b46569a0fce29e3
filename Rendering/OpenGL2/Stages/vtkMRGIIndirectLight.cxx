#include "vtkMRGIIndirectLight.h"

#include "vtkMRGIFrameContext.h"
#include "vtkMRGIGather.h"
#include "vtkMRGIImperfectShadowMaps.h"
#include "vtkMRGIIncrementalStencil.h"
#include "vtkMRGIIndirectVisibility.h"
#include "vtkMRGIMultiresolution.h"
#include "vtkMRGIShaderUtilities.h"
#include "vtkMRGIUpsample.h"
#include "vtkMRGIVPLSelection.h"
#include "vtkMRGIViewSamples.h"
#include "vtkMRGIVoxelization.h"
#include "vtkObjectFactory.h"
#include "vtkRenderer.h"

#include "mrgi_ism_visibility.h"
#include "mrgi_voxel.h"

// The public header's clamp ranges (it does not include the C core).
static_assert(MRGI_ISM_MAX_BIAS == 16.0f, "ISMRelativeBias / ISMTexelBias clamp range");
static_assert(MRGI_ISM_MAX_TEXEL_ANGLE_LIMIT == 4.0f, "ISMMaxTexelAngle clamp range");

vtkStandardNewMacro(vtkMRGIIndirectLight);

//------------------------------------------------------------------------------
vtkMRGIIndirectLight::vtkMRGIIndirectLight()
  : ISMRelativeBias(MRGI_ISM_DEFAULT_RELATIVE_BIAS)
  , ISMTexelBias(MRGI_ISM_DEFAULT_TEXEL_BIAS)
  , ISMMaxTexelAngle(MRGI_ISM_DEFAULT_MAX_TEXEL_ANGLE)
  , ViewSamples(new vtkMRGIViewSamples)
{
  this->VPLSelection = vtkMRGIVPLSelection::New();
  this->Gather = vtkMRGIGather::New();
  this->Upsample = vtkMRGIUpsample::New();
  this->ImperfectShadowMaps = vtkMRGIImperfectShadowMaps::New();
  this->Voxelization = vtkMRGIVoxelization::New();
  // VPL visibility keeps NPW10's fixed 128^2: the finer automatic voxels
  // the area lights use did not lower its error on the Cornell boxes and
  // made its gather dearer; what the camera does not see limits it, not
  // the voxel size (Documentation/IndirectShadows.md, "Session 17").
  this->Voxelization->SetVoxelSide(MRGI_VOXEL_DEFAULT_SIZE);
  this->Voxelization->SetNumberOfSlices(MRGI_VOXEL_INDIRECT_SLICES);
  this->IlluminationStencil = vtkMRGIIncrementalStencil::New();
}

//------------------------------------------------------------------------------
vtkMRGIIndirectLight::~vtkMRGIIndirectLight()
{
  this->VPLSelection->Delete();
  this->Gather->Delete();
  this->Upsample->Delete();
  this->ImperfectShadowMaps->Delete();
  this->Voxelization->Delete();
  this->IlluminationStencil->Delete();
}

//------------------------------------------------------------------------------
void vtkMRGIIndirectLight::ReleaseGraphicsResources(vtkWindow* w)
{
  this->VPLSelection->ReleaseGraphicsResources(w);
  this->Gather->ReleaseGraphicsResources(w);
  this->Upsample->ReleaseGraphicsResources(w);
  this->ImperfectShadowMaps->ReleaseGraphicsResources(w);
  this->Voxelization->ReleaseGraphicsResources(w);
  this->IlluminationStencil->ReleaseGraphicsResources(w);
  this->ViewSamples->Invalidate();
}

//------------------------------------------------------------------------------
long long vtkMRGIIndirectLight::GetNumberOfViewSampleReadBacks() const
{
  return this->ViewSamples->GetNumberOfReadBacks();
}

//------------------------------------------------------------------------------
vtkMRGIIndirectLight::Outcome vtkMRGIIndirectLight::Render(const vtkMRGIFrameContext& frame,
  vtkMRGIReflectiveShadowMapPass* rsm, vtkMRGIMultiresolution* buffer, const Settings& settings,
  vtkTextureObject* irradiance, vtkTextureObject* indirect)
{
  this->LastVPLCount = 0;
  if (!frame.Window || !rsm || !irradiance || !indirect || (settings.Multiresolution && !buffer))
  {
    vtkErrorMacro("indirect light: missing window, reflective shadow maps, buffer or targets");
    return Failed;
  }
  {
    vtkMRGIShaderUtilities::ScopedStage stage(frame.Timer, "vpl");
    this->LastVPLCount =
      this->VPLSelection->Update(frame.Window, rsm, frame, this->ViewSamples.get());
  }
  if (this->LastVPLCount <= 0)
  {
    return NoVPLs;
  }
  vtkMRGIIndirectVisibility visibility;
  if (!this->BuildVisibility(frame, this->LastVPLCount, visibility))
  {
    return Failed;
  }
  return this->RunGather(frame, buffer, settings, visibility, this->LastVPLCount, irradiance,
           indirect)
    ? Gathered
    : Failed;
}

//------------------------------------------------------------------------------
bool vtkMRGIIndirectLight::BuildVisibility(
  const vtkMRGIFrameContext& frame, int vplCount, vtkMRGIIndirectVisibility& visibility)
{
  visibility = vtkMRGIIndirectVisibility();
  if (this->Visibility == VisibilityISM)
  {
    vtkMRGIShaderUtilities::ScopedStage stage(frame.Timer, "ism");
    if (!this->ImperfectShadowMaps->Update(
          frame, this->VPLSelection->GetVPLTexture(), vplCount, this->ViewSamples.get()))
    {
      vtkErrorMacro("indirect light: the imperfect shadow maps could not be built (see the "
                    "error above); no indirect light this frame");
      return false;
    }
    visibility.Mode = vtkMRGIIndirectVisibility::ISMVisibility;
    visibility.ISMAtlas = this->ImperfectShadowMaps->GetAtlasTexture();
    visibility.ISMLayout = this->ImperfectShadowMaps->GetLayout();
    visibility.ISMLookup.relative_bias = static_cast<float>(this->ISMRelativeBias);
    visibility.ISMLookup.texel_bias = static_cast<float>(this->ISMTexelBias);
    visibility.ISMLookup.pcf = this->ISMFiltering ? 1 : 0;
    visibility.ISMLookup.max_texel_angle = static_cast<float>(this->ISMMaxTexelAngle);
  }
  else if (this->Visibility == VisibilityVoxels)
  {
    // One voxelization over the visible depth range, as the area lights'
    // (mrgi_voxel.h section 2).
    vtkMRGIShaderUtilities::ScopedStage stage(frame.Timer, "voxels");
    double range[2] = { 0.0, 1.0 };
    if (!vtkMRGIVoxelization::ComputeDepthRange(frame.Renderer, range) ||
      !this->Voxelization->Voxelize(frame.Renderer, range[0], range[1], frame.Timer))
    {
      vtkErrorMacro("indirect light: could not voxelize the scene for the VPLs' visibility; no "
                    "indirect light this frame");
      return false;
    }
    visibility.Mode = vtkMRGIIndirectVisibility::VoxelVisibility;
    visibility.Voxels = this->Voxelization;
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkMRGIIndirectLight::RunGather(const vtkMRGIFrameContext& frame,
  vtkMRGIMultiresolution* buffer, const Settings& settings,
  const vtkMRGIIndirectVisibility& visibility, int vplCount, vtkTextureObject* irradiance,
  vtkTextureObject* indirect)
{
  const bool tree = this->VPLSelection->GetMode() == vtkMRGIVPLSelection::Tree;
  if (!settings.Multiresolution)
  {
    vtkMRGIShaderUtilities::ScopedStage stage(frame.Timer, "gather");
    return tree ? this->Gather->GatherFullTree(frame, this->VPLSelection->GetTreeTerm(),
                    settings.Strength, irradiance, indirect, visibility)
                : this->Gather->GatherFull(frame, this->VPLSelection->GetVPLTexture(), vplCount,
                    settings.Strength, irradiance, indirect, visibility);
  }
  vtkRenderTimerLog* timer = frame.Timer;
  // The illumination rule (class comment): each level's stencil is built
  // from the irradiance the coarser level gathered, between the gathers.
  // Where it does not run though asked for (a view under the buffer's
  // IlluminationMinimumPixels; multiresolution splatting, nichols-wyman-
  // 2009, which has no step between its levels), the gather selects with
  // the area lights' geometric thresholds, the presets' setting without the
  // rule. LastRefinedByIllumination says which ran.
  const bool illumination = buffer->RefinesByIllumination(frame.Viewport[2], frame.Viewport[3],
    tree || this->Gather->GetGatherMode() == vtkMRGIGather::GatherStenciled);
  const bool geometricFallback =
    !illumination && buffer->GetRefinement() == vtkMRGIMultiresolution::RefinementIllumination;
  {
    vtkMRGIShaderUtilities::ScopedStage stage(timer, "select");
    if (!buffer->Update(frame.Window, frame.Position, frame.Normal, frame.Viewport[0],
          frame.Viewport[1], frame.Viewport[2], frame.Viewport[3], frame.PixelSize[0],
          frame.PixelSize[1], timer, geometricFallback))
    {
      return false;
    }
  }
  this->LastRefinedByIllumination = illumination;
  vtkMRGIIncrementalStencil* lit = this->IlluminationStencil;
  lit->SetIlluminationThreshold(buffer->GetIlluminationThreshold());
  {
    vtkMRGIShaderUtilities::ScopedStage stage(timer, "gather");
    if (!buffer->BuildReceivers(
          frame.Window, frame.Position, frame.Normal, frame.Viewport[0], frame.Viewport[1], timer))
    {
      return false;
    }
    const auto buildLevel = [&](int level) {
      return lit->BuildIlluminationLevel(
        frame, buffer, this->Gather->GetIrradianceTexture(), level);
    };
    const bool gathered = !illumination
      ? (tree ? this->Gather->GatherVPLTree(
                  frame, buffer, this->VPLSelection->GetTreeTerm(), visibility)
              : this->Gather->GatherVPLs(
                  frame, buffer, this->VPLSelection->GetVPLTexture(), vplCount, visibility))
      : lit->BeginIllumination(frame, buffer) &&
        (tree
            ? this->Gather->GatherVPLTreeIncremental(frame, buffer,
                this->VPLSelection->GetTreeTerm(), visibility, lit->GetStencilTexture(), buildLevel)
            : this->Gather->GatherVPLsIncremental(frame, buffer,
                this->VPLSelection->GetVPLTexture(), vplCount, visibility, lit->GetStencilTexture(),
                buildLevel));
    if (!gathered)
    {
      return false;
    }
  }
  vtkMRGIShaderUtilities::ScopedStage stage(timer, "upsample");
  // The irradiance target holds the per-level values until Resolve() writes it.
  return this->Upsample->Upsample(frame, buffer, this->Gather->GetIrradianceTexture(),
           illumination ? lit->GetSelectionTexture() : buffer->GetSelectionTexture(),
           settings.UpsampleMode, settings.UpsampleMaskWeight, irradiance) &&
    this->Upsample->Resolve(frame, buffer, frame.Albedo, irradiance, indirect, settings.Strength,
      settings.SurfaceDetail);
}

//------------------------------------------------------------------------------
void vtkMRGIIndirectLight::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  static const char* const names[] = { "Off", "ISM", "Voxels" };
  os << indent << "Visibility: " << names[this->Visibility] << "\n";
  os << indent << "ISMRelativeBias: " << this->ISMRelativeBias << "\n";
  os << indent << "ISMTexelBias: " << this->ISMTexelBias << "\n";
  os << indent << "ISMMaxTexelAngle: " << this->ISMMaxTexelAngle << "\n";
  os << indent << "ISMFiltering: " << (this->ISMFiltering ? "On" : "Off") << "\n";
  os << indent << "LastVPLCount: " << this->LastVPLCount << "\n";
  os << indent << "LastRefinedByIllumination: " << this->LastRefinedByIllumination << "\n";
  os << indent << "IlluminationStencil:\n";
  this->IlluminationStencil->PrintSelf(os, indent.GetNextIndent());
  os << indent << "ViewSampleReadBacks: " << this->GetNumberOfViewSampleReadBacks() << "\n";
  os << indent << "VPLSelection:\n";
  this->VPLSelection->PrintSelf(os, indent.GetNextIndent());
  os << indent << "Gather:\n";
  this->Gather->PrintSelf(os, indent.GetNextIndent());
  os << indent << "Upsample:\n";
  this->Upsample->PrintSelf(os, indent.GetNextIndent());
  os << indent << "ImperfectShadowMaps:\n";
  this->ImperfectShadowMaps->PrintSelf(os, indent.GetNextIndent());
  os << indent << "Voxelization:\n";
  this->Voxelization->PrintSelf(os, indent.GetNextIndent());
}
