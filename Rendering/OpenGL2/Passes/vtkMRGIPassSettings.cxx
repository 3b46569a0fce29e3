// vtkMRGIPass's settings that live in its stages: the forwarding setters
// and getters (one statement each) and the knobs the frame-budget tuner
// turns, apart from the frame logic in vtkMRGIPass.cxx. The class is
// documented in vtkMRGIPass.h.
#include "vtkMRGIPass.h"

#include "vtkMRGIAreaLightStage.h"
#include "vtkMRGIGather.h"
#include "vtkMRGIImperfectShadowMaps.h"
#include "vtkMRGIIndirectLight.h"
#include "vtkMRGIMultiresolution.h"
#include "vtkMRGIReflectiveShadowMapPass.h"
#include "vtkMRGIShadowedDirectLight.h"
#include "vtkMRGIVPLSelection.h"
#include "vtkMRGIVoxelization.h"

namespace
{
// The pass is modified only when the stage's value changed (clamping
// included), so that setting a value it already has (the frame-budget tuner
// does every frame) invalidates nothing.
template <typename Get, typename Set>
void SetAndModify(vtkMRGIPass* pass, Get get, Set set)
{
  const auto before = get();
  set();
  if (!(get() == before))
  {
    pass->Modified();
  }
}
}

//------------------------------------------------------------------------------
void vtkMRGIPass::AddAreaLight(vtkMRGIAreaLight* light)
{
  this->AreaLightStage->AddLight(light);
}
void vtkMRGIPass::RemoveAreaLight(vtkMRGIAreaLight* light)
{
  this->AreaLightStage->RemoveLight(light);
}
void vtkMRGIPass::RemoveAllAreaLights()
{
  this->AreaLightStage->RemoveAllLights();
}
int vtkMRGIPass::GetNumberOfAreaLights() const
{
  return this->AreaLightStage->GetNumberOfLights();
}
vtkMRGIAreaLight* vtkMRGIPass::GetAreaLight(int index) const
{
  return this->AreaLightStage->GetLight(index);
}
void vtkMRGIPass::SetAreaLightVisibility(int mode)
{
  this->AreaLightStage->SetVisibility(mode);
}
int vtkMRGIPass::GetAreaLightVisibility()
{
  return this->AreaLightStage->GetVisibility();
}
void vtkMRGIPass::SetAreaLightSpecular(bool specular)
{
  this->AreaLightStage->SetSpecular(specular);
}
bool vtkMRGIPass::GetAreaLightSpecular()
{
  return this->AreaLightStage->GetSpecular();
}
void vtkMRGIPass::SetAreaLightSpecularResolution(int resolution)
{
  this->AreaLightStage->SetSpecularResolution(resolution);
}
int vtkMRGIPass::GetAreaLightSpecularResolution()
{
  return this->AreaLightStage->GetSpecularResolution();
}
void vtkMRGIPass::SetAreaLightReuse(bool reuse)
{
  this->AreaLightStage->SetReuse(reuse);
}
bool vtkMRGIPass::GetAreaLightReuse()
{
  return this->AreaLightStage->GetReuse();
}
vtkIdType vtkMRGIPass::GetNumberOfAreaLightUpdates()
{
  return this->AreaLightStage->GetNumberOfUpdates();
}
vtkMRGIVoxelization* vtkMRGIPass::GetVoxelization()
{
  return this->AreaLightStage->GetVoxelization();
}
vtkMRGIVisibilityPyramid* vtkMRGIPass::GetVisibilityPyramid()
{
  return this->AreaLightStage->GetVisibilityPyramid();
}
vtkMRGIVarianceShadowQuery* vtkMRGIPass::GetVarianceShadowQuery()
{
  return this->AreaLightStage->GetVarianceShadowQuery();
}

//------------------------------------------------------------------------------
// The upsampling settings apply to the indirect light and to the area
// lights' gathers alike; the area-light stage holds them.
void vtkMRGIPass::SetUpsampleMode(int mode)
{
  this->AreaLightStage->SetUpsampleMode(mode);
}
int vtkMRGIPass::GetUpsampleMode()
{
  return this->AreaLightStage->GetUpsampleMode();
}
void vtkMRGIPass::SetUpsampleMaskWeight(double weight)
{
  this->AreaLightStage->SetUpsampleMaskWeight(weight);
}
double vtkMRGIPass::GetUpsampleMaskWeight()
{
  return this->AreaLightStage->GetUpsampleMaskWeight();
}

//------------------------------------------------------------------------------
vtkMRGIDirectShadows* vtkMRGIPass::GetDirectShadowStage()
{
  return this->DirectLight->GetDirectShadows();
}

//------------------------------------------------------------------------------
// The indirect light's settings live in its stage and the stages it owns.
vtkMRGIVPLSelection* vtkMRGIPass::GetVPLSelection()
{
  return this->IndirectLight->GetVPLSelection();
}
vtkMRGIGather* vtkMRGIPass::GetGather()
{
  return this->IndirectLight->GetGather();
}
vtkMRGIUpsample* vtkMRGIPass::GetUpsample()
{
  return this->IndirectLight->GetUpsample();
}
void vtkMRGIPass::SetIndirectVisibility(int mode)
{
  this->IndirectLight->SetVisibility(mode);
}
int vtkMRGIPass::GetIndirectVisibility()
{
  return this->IndirectLight->GetVisibility();
}
void vtkMRGIPass::SetRefinement(int mode)
{
  // Asked for by hand: at any view size (the presets' minimum is theirs).
  this->Multiresolution->SetRefinement(mode);
  this->Multiresolution->SetIlluminationMinimumPixels(0);
}
int vtkMRGIPass::GetRefinement()
{
  return this->Multiresolution->GetRefinement();
}
void vtkMRGIPass::SetIlluminationThreshold(double threshold)
{
  this->Multiresolution->SetIlluminationThreshold(threshold);
}
double vtkMRGIPass::GetIlluminationThreshold()
{
  return this->Multiresolution->GetIlluminationThreshold();
}
void vtkMRGIPass::SetISMPointsPerVPL(int points)
{
  this->IndirectLight->GetImperfectShadowMaps()->SetPointsPerVPL(points);
}
int vtkMRGIPass::GetISMPointsPerVPL()
{
  return this->IndirectLight->GetImperfectShadowMaps()->GetPointsPerVPL();
}
void vtkMRGIPass::SetISMTileSize(int side)
{
  this->IndirectLight->GetImperfectShadowMaps()->SetTileSize(side);
}
int vtkMRGIPass::GetISMTileSize()
{
  return this->IndirectLight->GetImperfectShadowMaps()->GetTileSize();
}
void vtkMRGIPass::SetISMPointMode(int mode)
{
  this->IndirectLight->GetImperfectShadowMaps()->SetPointMode(mode);
}
int vtkMRGIPass::GetISMPointMode()
{
  return this->IndirectLight->GetImperfectShadowMaps()->GetPointMode();
}
void vtkMRGIPass::SetISMLazyFrames(int frames)
{
  this->IndirectLight->GetImperfectShadowMaps()->SetLazyFrames(frames);
}
int vtkMRGIPass::GetISMLazyFrames()
{
  return this->IndirectLight->GetImperfectShadowMaps()->GetLazyFrames();
}

//------------------------------------------------------------------------------
void vtkMRGIPass::SetNumberOfVPLs(int count)
{
  vtkMRGIVPLSelection* selection = this->GetVPLSelection();
  SetAndModify(
    this, [selection] { return selection->GetNumberOfVPLs(); },
    [selection, count] { selection->SetNumberOfVPLs(count); });
}
int vtkMRGIPass::GetNumberOfVPLs()
{
  return this->GetVPLSelection()->GetNumberOfVPLs();
}
void vtkMRGIPass::SetVPLSelectionMode(int mode)
{
  vtkMRGIVPLSelection* selection = this->GetVPLSelection();
  SetAndModify(
    this, [selection] { return selection->GetMode(); },
    [selection, mode] { selection->SetMode(mode); });
}
int vtkMRGIPass::GetVPLSelectionMode()
{
  return this->GetVPLSelection()->GetMode();
}
void vtkMRGIPass::SetClusterDepthThreshold(double threshold)
{
  vtkMRGIVPLSelection* selection = this->GetVPLSelection();
  SetAndModify(
    this, [selection] { return selection->GetClusterDepthThreshold(); },
    [selection, threshold] { selection->SetClusterDepthThreshold(threshold); });
}
double vtkMRGIPass::GetClusterDepthThreshold()
{
  return this->GetVPLSelection()->GetClusterDepthThreshold();
}
void vtkMRGIPass::SetClusterNormalThreshold(double threshold)
{
  vtkMRGIVPLSelection* selection = this->GetVPLSelection();
  SetAndModify(
    this, [selection] { return selection->GetClusterNormalThreshold(); },
    [selection, threshold] { selection->SetClusterNormalThreshold(threshold); });
}
double vtkMRGIPass::GetClusterNormalThreshold()
{
  return this->GetVPLSelection()->GetClusterNormalThreshold();
}
void vtkMRGIPass::SetTreeThreshold(double threshold)
{
  vtkMRGIVPLSelection* selection = this->GetVPLSelection();
  SetAndModify(
    this, [selection] { return selection->GetTreeThreshold(); },
    [selection, threshold] { selection->SetTreeThreshold(threshold); });
}
double vtkMRGIPass::GetTreeThreshold()
{
  return this->GetVPLSelection()->GetTreeThreshold();
}
void vtkMRGIPass::SetRSMResolution(int resolution)
{
  vtkMRGIReflectiveShadowMapPass* rsm = this->RSMPass;
  SetAndModify(
    this, [rsm] { return rsm->GetResolution(); },
    [rsm, resolution] { rsm->SetResolution(resolution); });
}
int vtkMRGIPass::GetRSMResolution()
{
  return this->RSMPass->GetResolution();
}
void vtkMRGIPass::SetRSMCompositor(vtkMRGIRSMCompositor* compositor)
{
  if (compositor != this->RSMPass->GetCompositor())
  {
    this->RSMPass->SetCompositor(compositor);
    this->AreaLightStage->SetCompositor(compositor);
    this->Modified();
  }
}
vtkMRGIRSMCompositor* vtkMRGIPass::GetRSMCompositor()
{
  return this->RSMPass->GetCompositor();
}
vtkTypeInt64 vtkMRGIPass::GetRSMCompositeBytes()
{
  return this->RSMPass->GetCompositeBytes();
}

//------------------------------------------------------------------------------
vtkMRGIFrameBudget::Knobs vtkMRGIPass::FrameBudgetKnobs()
{
  vtkMRGIFrameBudget::Knobs knobs;
  knobs.Voxels = this->GetIndirectVisibility() == vtkMRGIIndirectLight::VisibilityVoxels;
  knobs.Apply = [this](const mrgi_frame_setting& s) {
    this->GetMultiresolution()->SetPreset(s.preset);
    this->SetNumberOfVPLs(s.vpls);
    this->SetRSMResolution(s.rsm_size);
    if (s.voxel_side > 0)
    {
      // The knob exists when the indirect light uses voxels (knobs.Voxels):
      // its own voxelization, not the area lights' (GetVoxelization()).
      this->IndirectLight->GetVoxelization()->SetVoxelSide(s.voxel_side);
    }
  };
  knobs.WorkShare = [this]() { return this->GetGather()->GetGatherWorkFraction(); };
  return knobs;
}

//------------------------------------------------------------------------------
bool vtkMRGIPass::Calibrate(vtkRenderWindow* window)
{
  // The calibration turns the knobs; the user's own settings come back after.
  vtkMRGIMultiresolution* mr = this->GetMultiresolution();
  const double depth = mr->GetDepthThreshold(), normal = mr->GetNormalThreshold();
  const int finest = mr->GetFinestLevel(), vpls = this->GetNumberOfVPLs();
  const int rsm = this->GetRSMResolution(), refinement = mr->GetRefinement();
  const double illumination = mr->GetIlluminationThreshold();
  const vtkIdType minimumPixels = mr->GetIlluminationMinimumPixels();
  const double areaDepth = mr->GetAreaLightDepthThreshold();
  const double areaNormal = mr->GetAreaLightNormalThreshold();
  const bool balance = mr->GetBalance();
  vtkMRGIVoxelization* voxels = this->IndirectLight->GetVoxelization();
  int voxelSize[2];
  voxels->GetVoxelSize(voxelSize);
  const bool automaticVoxelSize = voxels->GetAutomaticVoxelSize();
  const bool ok = this->FrameBudgetTuner->Calibrate(window, this->FrameBudgetKnobs());
  mr->SetDepthThreshold(depth);
  mr->SetNormalThreshold(normal);
  mr->SetFinestLevel(finest);
  mr->SetRefinement(refinement);
  mr->SetIlluminationThreshold(illumination);
  mr->SetIlluminationMinimumPixels(minimumPixels);
  mr->SetAreaLightDepthThreshold(areaDepth);
  mr->SetAreaLightNormalThreshold(areaNormal);
  mr->SetBalance(balance);
  this->SetNumberOfVPLs(vpls);
  this->SetRSMResolution(rsm);
  voxels->SetVoxelSize(voxelSize);
  voxels->SetAutomaticVoxelSize(automaticVoxelSize);
  return ok;
}
