#include "vtk_glew.h"

#include "vtkMRGIPass.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCameraPass.h"
#include "vtkFloatArray.h"
#include "vtkHardwareSelector.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMRGIAreaLightStage.h"
#include "vtkMRGIBMRMask.h"
#include "vtkMRGIFrameContext.h"
#include "vtkMRGIFullScreenStep.h"
#include "vtkMRGIGBuffer.h"
#include "vtkMRGIGather.h"
#include "vtkMRGIMultiresolution.h"
#include "vtkMRGIProgramCache.h"
#include "vtkMRGIReflectiveShadowMapPass.h"
#include "vtkMRGIRenderSteps.h"
#include "vtkMRGISSAO.h"
#include "vtkMRGISSGI.h"
#include "vtkMRGIShaderLibraries.h"
#include "vtkMRGIShaderUtilities.h"
#include "vtkMRGIShadowComposite.h"
#include "vtkMRGIDirectShadows.h"
#include "vtkMRGIUpsample.h"
#include "vtkMRGIVPLSelection.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLError.h"
#include "vtkOpenGLFXAAFilter.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLPolyDataMapper.h"
#include "vtkOpenGLQuadHelper.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLRenderer.h"
#include "vtkOpenGLState.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProp.h"
#include "vtkProp3D.h"
#include "vtkPropCollection.h"
#include "vtkProperty.h"
#include "vtkRenderPassCollection.h"
#include "vtkRenderState.h"
#include "vtkRenderStepsPass.h"
#include "vtkRenderTimerLog.h"
#include "vtkRenderer.h"
#include "vtkSequencePass.h"
#include "vtkShaderProgram.h"
#include "vtkSmartPointer.h"
#include "vtkTextureObject.h"
#include "vtkWeakPointer.h"

#include "vtkMRGICompositeFS.h"
#include "vtkMRGIGBufferCapture.h"

#include "mrgi_buffers.h"
#include "mrgi_direct_shadow.h"
#include "mrgi_exposure.h"
#include "mrgi_screen_space_preset.h"
#include "mrgi_multires.h"
#include "mrgi_vpl.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkMRGIPass);

namespace
{
using vtkMRGIShaderUtilities::ScopedStage;
using vtkMRGIShaderUtilities::StagePrefix;


}

struct vtkMRGIPass::Internals
{
  vtkMRGIGBuffer GBuffer;
  // The full-resolution gather, the add and the output programs.
  vtkMRGIProgramCache Programs;
  // A stage that fails (e.g. a buffer larger than GL_MAX_TEXTURE_SIZE) fails
  // every frame: the pass says so once, until the light is computed again.
  bool IndirectFailureReported = false;
  bool AreaLightFailureReported = false;
  bool ShadowFailureReported = false;
  bool ExtraLightsReported = false; // lights past MRGI_SHADOW_SLOTS stay unshadowed
  // Actors already warned about as point clouds drawn as pixels (once each).
  std::vector<vtkWeakPointer<vtkProp>> PointCloudsReported;
};

//------------------------------------------------------------------------------
vtkMRGIPass::vtkMRGIPass()
  : AutoExposureKey(MRGI_EXPOSURE_KEY)
  , Internal(new Internals)
{
  this->RSMPass = vtkMRGIReflectiveShadowMapPass::New();
  this->VPLSelection = vtkMRGIVPLSelection::New();
  this->Multiresolution = vtkMRGIMultiresolution::New();
  this->Gather = vtkMRGIGather::New();
  this->Upsample = vtkMRGIUpsample::New();
  this->SSAOStage = vtkMRGISSAO::New();
  this->SSGIStage = vtkMRGISSGI::New();
  this->AreaLightStage = vtkMRGIAreaLightStage::New();
  this->ShadowComposite = vtkMRGIShadowComposite::New();
  this->DirectShadowStage = vtkMRGIDirectShadows::New();
  this->OpaqueSequence = vtkSequencePass::New();
  for (int i = 0; i < 16; ++i)
  {
    this->LastViewToWorld[i] = (i % 5 == 0) ? 1.0 : 0.0;
  }
}

//------------------------------------------------------------------------------
vtkMRGIPass::~vtkMRGIPass()
{
  if (this->Internal->GBuffer.HoldsResources())
  {
    vtkErrorMacro("vtkMRGIPass destroyed while it still holds GL resources: call "
                  "ReleaseGraphicsResources() first (the render window does so).");
  }
  this->ReleaseResources(nullptr);
  this->RSMPass->Delete();
  this->VPLSelection->Delete();
  this->Multiresolution->Delete();
  this->Gather->Delete();
  this->Upsample->Delete();
  this->SSAOStage->Delete();
  this->SSGIStage->Delete();
  this->AreaLightStage->Delete();
  this->ShadowComposite->Delete();
  this->DirectShadowStage->Delete();
  this->OpaqueSequence->Delete();
}

//------------------------------------------------------------------------------
void vtkMRGIPass::ReleaseGraphicsResources(vtkWindow* w)
{
  this->Superclass::ReleaseGraphicsResources(w);
  this->RSMPass->ReleaseGraphicsResources(w);
  this->VPLSelection->ReleaseGraphicsResources(w);
  this->Multiresolution->ReleaseGraphicsResources(w);
  this->Gather->ReleaseGraphicsResources(w);
  this->Upsample->ReleaseGraphicsResources(w);
  this->SSAOStage->ReleaseGraphicsResources(w);
  this->SSGIStage->ReleaseGraphicsResources(w);
  this->AreaLightStage->ReleaseGraphicsResources(w);
  this->ShadowComposite->ReleaseGraphicsResources(w);
  this->DirectShadowStage->ReleaseGraphicsResources(w);
  this->ReleaseResources(w);
}

//------------------------------------------------------------------------------
void vtkMRGIPass::ReleaseResources(vtkWindow* w)
{
  this->Internal->Programs.ReleaseGraphicsResources(w);
  this->Internal->GBuffer.Release(w);
  if (this->FXAAFilter)
  {
    if (w)
    {
      this->FXAAFilter->ReleaseGraphicsResources();
    }
    this->FXAAFilter->Delete();
    this->FXAAFilter = nullptr;
  }
  this->BufferSize[0] = this->BufferSize[1] = 0;
  this->IndirectComputed = false;
  this->AreaLightsComputed = false;
}

//------------------------------------------------------------------------------
namespace
{
// VTK's shader lights are the renderer's switched-on lights, in collection
// order (vtkOpenGLRenderer::UpdateLightingUniforms numbers them so).
// `slots[s]`: the collection index of shader light s, or -1. Returns how
// many shader lights can cast a visible shadow: lit (intensity > 0) and not
// a headlight, whose shadows hide behind what it lights. `unshadowedScene`:
// how many of those past the slots are scene lights (camera lights past
// the slots are a light kit's fill and back lights, unshadowed by design).
int ShaderLights(vtkRenderer* renderer, int slots[MRGI_SHADOW_SLOTS], int& unshadowedScene)
{
  std::fill(slots, slots + MRGI_SHADOW_SLOTS, -1);
  unshadowedScene = 0;
  vtkLightCollection* lights = renderer->GetLights();
  vtkCollectionSimpleIterator it;
  lights->InitTraversal(it);
  int index = 0, shaderLight = 0, casting = 0;
  while (vtkLight* light = lights->GetNextLight(it))
  {
    if (light->GetSwitch() > 0)
    {
      const bool casts = light->GetIntensity() > 0 && !light->LightTypeIsHeadlight();
      if (shaderLight < MRGI_SHADOW_SLOTS)
      {
        slots[shaderLight] = index;
      }
      else if (casts && light->LightTypeIsSceneLight())
      {
        ++unshadowedScene;
      }
      ++shaderLight;
      casting += casts;
    }
    ++index;
  }
  return casting;
}

// Whether some visible prop may reflect specularly: an actor with Specular
// > 0; other 3D props (assemblies, volumes) are not looked into and count
// as possibly specular; 2D props (text, overlays) never reach the G-buffer.
bool AnySpecularProp(vtkRenderer* renderer)
{
  vtkPropCollection* props = renderer->GetViewProps();
  vtkCollectionSimpleIterator it;
  props->InitTraversal(it);
  while (vtkProp* prop = props->GetNextProp(it))
  {
    if (!prop->GetVisibility() || !vtkProp3D::SafeDownCast(prop))
    {
      continue;
    }
    vtkActor* actor = vtkActor::SafeDownCast(prop);
    if (!actor || actor->GetProperty()->GetSpecular() > 0.0)
    {
      return true;
    }
  }
  return false;
}
}

//------------------------------------------------------------------------------
namespace
{
// Points of an actor's polydata input that is a point cloud (vertex cells
// only, or no cells at all), or 0: such an actor is drawn as pixels, so the
// G-buffer and the RSMs get no surface and no usable normal from it.
vtkIdType PointCloudPoints(vtkActor* actor)
{
  vtkPolyDataMapper* mapper = vtkPolyDataMapper::SafeDownCast(actor->GetMapper());
  vtkPolyData* data = mapper ? mapper->GetInput() : nullptr;
  if (!data || data->GetNumberOfPoints() == 0)
  {
    return 0;
  }
  const bool surfaceless = data->GetNumberOfPolys() == 0 && data->GetNumberOfStrips() == 0 &&
    data->GetNumberOfLines() == 0;
  return surfaceless ? data->GetNumberOfPoints() : 0;
}
}

//------------------------------------------------------------------------------
void vtkMRGIPass::WarnPointClouds(vtkRenderer* renderer)
{
  std::vector<vtkWeakPointer<vtkProp>>& reported = this->Internal->PointCloudsReported;
  // Forget actors that were deleted, so the list stays as short as the scene.
  reported.erase(std::remove_if(reported.begin(), reported.end(),
                   [](const vtkWeakPointer<vtkProp>& p) { return p == nullptr; }),
    reported.end());
  vtkPropCollection* props = renderer->GetViewProps();
  vtkCollectionSimpleIterator it;
  props->InitTraversal(it);
  while (vtkProp* prop = props->GetNextProp(it))
  {
    vtkActor* actor = vtkActor::SafeDownCast(prop);
    if (!actor || !actor->GetVisibility())
    {
      continue;
    }
    const vtkIdType points = PointCloudPoints(actor);
    if (points == 0 ||
      std::find(reported.begin(), reported.end(), vtkWeakPointer<vtkProp>(prop)) != reported.end())
    {
      continue;
    }
    reported.emplace_back(prop);
    vtkWarningMacro("actor " << actor << " draws " << points
                             << " points as pixels: the indirect light sees no surface; put "
                                "vtkMRGISurfels (after vtkMRGIPointCloudNormals) before its mapper "
                                "(Documentation/PointClouds-Surfels.md)");
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
void vtkMRGIPass::SetExposure(double ev)
{
  const double clamped = std::isnan(ev)
    ? 0.0
    : std::min(std::max(ev, double(MRGI_EXPOSURE_MIN_EV)), double(MRGI_EXPOSURE_MAX_EV));
  if (clamped != this->Exposure)
  {
    this->Exposure = clamped;
    this->Modified();
  }
}

void vtkMRGIPass::SetAutoExposureKey(double key)
{
  if (!(key > 0.0) || std::isinf(key))
  {
    vtkErrorMacro("AutoExposureKey must be a finite number > 0 (got " << key << "); kept "
                                                                      << this->AutoExposureKey);
    return;
  }
  if (key != this->AutoExposureKey)
  {
    this->AutoExposureKey = key;
    this->Modified();
  }
}

//------------------------------------------------------------------------------
vtkTextureObject* vtkMRGIPass::GetPositionTexture()
{
  return this->Internal->GBuffer.Position;
}
vtkTextureObject* vtkMRGIPass::GetNormalTexture()
{
  return this->Internal->GBuffer.Normal;
}
vtkTextureObject* vtkMRGIPass::GetAlbedoTexture()
{
  return this->Internal->GBuffer.Albedo;
}
vtkTextureObject* vtkMRGIPass::GetIrradianceTexture()
{
  return this->Internal->GBuffer.Irradiance;
}

//------------------------------------------------------------------------------
void vtkMRGIPass::SetNumberOfVPLs(int count)
{
  this->VPLSelection->SetNumberOfVPLs(count);
  this->Modified();
}
int vtkMRGIPass::GetNumberOfVPLs()
{
  return this->VPLSelection->GetNumberOfVPLs();
}
void vtkMRGIPass::SetVPLSelectionMode(int mode)
{
  this->VPLSelection->SetMode(mode);
  this->Modified();
}
int vtkMRGIPass::GetVPLSelectionMode()
{
  return this->VPLSelection->GetMode();
}
void vtkMRGIPass::SetRSMResolution(int resolution)
{
  this->RSMPass->SetResolution(resolution);
  this->Modified();
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
void vtkMRGIPass::RenderScene(const vtkRenderState* s, bool capture, bool split)
{
  Internals& in = *this->Internal;
  vtkOpenGLFramebufferObject* fbo = in.GBuffer.FrameBuffer;
  fbo->SaveCurrentBindingsAndBuffers();
  fbo->Bind();
  fbo->AddColorAttachment(MRGI_GBUFFER_DIRECT, in.GBuffer.Color);
  if (capture)
  {
    fbo->AddColorAttachment(MRGI_GBUFFER_POSITION, in.GBuffer.Position);
    fbo->AddColorAttachment(MRGI_GBUFFER_NORMAL, in.GBuffer.Normal);
    fbo->AddColorAttachment(MRGI_GBUFFER_ALBEDO, in.GBuffer.Albedo);
    // Specular data only when something reads it: every named draw buffer
    // needs an attachment (GL 3.2 completeness).
    if (this->SpecularCaptured)
    {
      fbo->AddColorAttachment(MRGI_GBUFFER_SPECULAR, in.GBuffer.Specular);
      fbo->AddColorAttachment(MRGI_GBUFFER_SHININESS, in.GBuffer.Shininess);
    }
    for (int slot = 0; this->ShadowsCaptured && slot < MRGI_SHADOW_SLOTS; ++slot)
    {
      fbo->AddColorAttachment(MRGI_GBUFFER_LIGHT0 + slot, in.GBuffer.LightTerms[slot]);
    }
    vtkMRGIShaderUtilities::SelectGBufferDrawBuffers(
      fbo, this->SpecularCaptured, this->ShadowsCaptured);
  }
  else
  {
    fbo->RemoveColorAttachments(MRGI_GBUFFER_MAX_ATTACHMENTS);
    fbo->AddColorAttachment(MRGI_GBUFFER_DIRECT, in.GBuffer.Color);
    vtkMRGIShaderUtilities::SelectDrawBuffers(fbo, 1);
  }
  fbo->AddDepthAttachment(in.GBuffer.Depth);

  // The camera pass sets the renderer's viewport and clears: MRGI's buffers
  // are as large as the window, so the renderer's tile lands where it does
  // in the window.
  if (capture)
  {
    this->PreRender(s);
    this->Capturing = true;
  }
  if (split)
  {
    vtkRenderStepsPass* steps = vtkRenderStepsPass::SafeDownCast(this->DelegatePass);
    vtkNew<vtkRenderPassCollection> passes;
    vtkSmartPointer<vtkRenderPass> clear = vtkMRGIRenderSteps::NewClearGBufferPass();
    if (capture)
    {
      passes->AddItem(clear);
    }
    passes->AddItem(steps->GetLightsPass());
    passes->AddItem(steps->GetOpaquePass());
    this->OpaqueSequence->SetPasses(passes);
    vtkMRGIRenderSteps::RenderCameraWith(steps->GetCameraPass(), this->OpaqueSequence, s);
    this->NumberOfRenderedProps += steps->GetCameraPass()->GetNumberOfRenderedProps();
  }
  else
  {
    // Another delegate clears and draws in one go: the G-buffer is cleared
    // first, and VTK's clear then writes the background alpha to its w
    // (valid only if that alpha exceeds MRGI_GBUFFER_VALID_THRESHOLD, which
    // VTK's default background alpha of 0 does not).
    const float zero[4] = { 0.0f, 0.0f, 0.0f, 0.0f };
    for (int a = MRGI_GBUFFER_POSITION; capture && a < MRGI_GBUFFER_MAX_ATTACHMENTS; ++a)
    {
      glClearBufferfv(GL_COLOR, a, zero);
    }
    this->DelegatePass->Render(s);
    this->NumberOfRenderedProps += this->DelegatePass->GetNumberOfRenderedProps();
  }
  if (capture)
  {
    this->Capturing = false;
    this->PostRender(s);
  }
  // Later steps draw through the same framebuffer at other sizes: only the
  // colour and depth stay attached.
  fbo->RemoveColorAttachments(MRGI_GBUFFER_MAX_ATTACHMENTS);
  fbo->UnBind();
  fbo->RestorePreviousBindingsAndBuffers();
}

//------------------------------------------------------------------------------
void vtkMRGIPass::RenderForward(const vtkRenderState* s)
{
  // Translucent props and volumes, over the lit opaque scene, into
  // the colour buffer only (the G-buffer is for opaque surfaces).
  Internals& in = *this->Internal;
  this->NumberOfRenderedProps +=
    vtkMRGIRenderSteps::RenderForward(s, vtkRenderStepsPass::SafeDownCast(this->DelegatePass),
      in.GBuffer.FrameBuffer, in.GBuffer.Color, in.GBuffer.Depth, this->Viewport);
}

//------------------------------------------------------------------------------
bool vtkMRGIPass::RenderGather(const vtkMRGIFrameContext& frame, int vplCount)
{
  Internals& in = *this->Internal;
  vtkOpenGLRenderWindow* renWin = frame.Window;
  vtkOpenGLQuadHelper* quad = in.Programs.Ready(
    renWin, "gather.full", "", [] { return vtkMRGIShaderLibraries::Compose({ "vtkMRGIGatherFS" }); });
  if (!quad)
  {
    vtkErrorMacro("could not build the MRGI gather shader");
    return false;
  }
  vtkShaderProgram* program = quad->Program;
  vtkTextureObject* vpls = this->VPLSelection->GetVPLTexture();
  vtkOpenGLFramebufferObject* fbo = in.GBuffer.FrameBuffer;
  vtkMRGIViewportStep state(renWin->GetState(), frame.Viewport);
  fbo->SaveCurrentBindingsAndBuffers();
  fbo->Bind();
  fbo->RemoveColorAttachments(MRGI_GBUFFER_MAX_ATTACHMENTS);
  fbo->AddColorAttachment(0, in.GBuffer.Irradiance);
  fbo->AddColorAttachment(1, in.GBuffer.Indirect);
  vtkMRGIShaderUtilities::SelectDrawBuffers(fbo, 2);
  in.GBuffer.Position->Activate();
  in.GBuffer.Normal->Activate();
  in.GBuffer.Albedo->Activate();
  vpls->Activate();
  program->SetUniformi("mrgiPosition", in.GBuffer.Position->GetTextureUnit());
  program->SetUniformi("mrgiNormal", in.GBuffer.Normal->GetTextureUnit());
  program->SetUniformi("mrgiAlbedo", in.GBuffer.Albedo->GetTextureUnit());
  program->SetUniformi("mrgiVPLs", vpls->GetTextureUnit());
  program->SetUniformi("mrgiVPLCount", vplCount);
  program->SetUniformf("mrgiStrength", static_cast<float>(this->IndirectStrength));
  program->SetUniformMatrix4x4("mrgiVCToWC", const_cast<float*>(frame.ViewToWorld));
  quad->Render();
  vpls->Deactivate();
  in.GBuffer.Albedo->Deactivate();
  in.GBuffer.Normal->Deactivate();
  in.GBuffer.Position->Deactivate();
  fbo->RemoveColorAttachments(2);
  fbo->UnBind();
  fbo->RestorePreviousBindingsAndBuffers();
  return true;
}

//------------------------------------------------------------------------------
bool vtkMRGIPass::MakeFrame(vtkOpenGLRenderWindow* renWin, vtkRenderer* renderer,
  vtkRenderTimerLog* timer, bool capture, vtkMRGIFrameContext& frame)
{
  const vtkMRGIGBuffer& g = this->Internal->GBuffer;
  frame.Window = renWin;
  frame.Renderer = renderer;
  frame.Position = capture ? g.Position : nullptr;
  frame.Normal = capture ? g.Normal : nullptr;
  frame.Albedo = capture ? g.Albedo : nullptr;
  frame.Specular = this->SpecularCaptured ? g.Specular : nullptr;
  frame.Shininess = this->SpecularCaptured ? g.Shininess : nullptr;
  std::copy(this->Viewport, this->Viewport + 4, frame.Viewport);
  frame.Timer = timer;
  // Eye -> world: the inverse of the camera's view matrix.
  vtkCamera* camera = renderer->GetActiveCamera();
  vtkNew<vtkMatrix4x4> inverse;
  vtkMatrix4x4::Invert(camera->GetModelViewTransformMatrix(), inverse);
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      frame.ViewToWorld[c * 4 + r] = static_cast<float>(inverse->GetElement(r, c));
      frame.ViewToWorldDouble[c * 4 + r] = inverse->GetElement(r, c);
    }
  }
  const mrgi_multires_projection projection = { camera->GetParallelProjection() ? 1 : 0,
    camera->GetViewAngle(), camera->GetParallelScale() };
  frame.Parallel = projection.parallel != 0;
  if (!capture)
  {
    return false; // nothing gathers this frame
  }
  std::copy(frame.ViewToWorldDouble, frame.ViewToWorldDouble + 16, this->LastViewToWorld);
  // Pixel size at depth d for the scale-invariant thresholds (mrgi_multires.h).
  float ab[2];
  mrgi_error err;
  if (mrgi_multires_pixel_size_coefficients(&projection, this->Viewport[3], ab, &err) != MRGI_OK)
  {
    vtkErrorMacro(<< "multiresolution: " << err.message);
    return false;
  }
  frame.PixelSize[0] = ab[0];
  frame.PixelSize[1] = ab[1];
  return true;
}

//------------------------------------------------------------------------------
bool vtkMRGIPass::RenderMultiresolution(const vtkMRGIFrameContext& frame, int vplCount)
{
  vtkMRGIMultiresolution* mr = this->Multiresolution;
  vtkRenderTimerLog* timer = frame.Timer;
  {
    ScopedStage stage(timer, "select");
    if (!mr->Update(frame.Window, frame.Position, frame.Normal, frame.Viewport[0], frame.Viewport[1],
          frame.Viewport[2], frame.Viewport[3], frame.PixelSize[0], frame.PixelSize[1], timer))
    {
      return false;
    }
  }
  {
    ScopedStage stage(timer, "gather");
    if (!mr->BuildReceivers(
          frame.Window, frame.Position, frame.Normal, frame.Viewport[0], frame.Viewport[1], timer) ||
      !this->Gather->GatherVPLs(frame, mr, this->VPLSelection->GetVPLTexture(), vplCount))
    {
      return false;
    }
  }
  Internals& in = *this->Internal;
  ScopedStage stage(timer, "upsample");
  return this->Upsample->Upsample(frame, mr, this->Gather->GetIrradianceTexture(),
           mr->GetSelectionTexture(), this->GetUpsampleMode(), this->GetUpsampleMaskWeight()) &&
    this->Upsample->Resolve(frame, mr, frame.Albedo, in.GBuffer.Irradiance, in.GBuffer.Indirect,
      this->IndirectStrength, this->SurfaceDetail);
}

//------------------------------------------------------------------------------
bool vtkMRGIPass::RenderDirectShadows(
  const vtkMRGIFrameContext& frame, const int slotLights[MRGI_SHADOW_SLOTS])
{
  Internals& in = *this->Internal;
  vtkMRGIGBuffer& g = in.GBuffer;
  ScopedStage stage(frame.Timer, "shadows");
  mrgi_direct_shadow_params params;
  mrgi_direct_shadow_params_default(&params);
  params.mode =
    this->DirectShadows == DirectShadowsHard ? MRGI_DIRECT_SHADOW_HARD : MRGI_DIRECT_SHADOW_SOFT;
  params.samples_side = this->SoftShadowKernelSize;
  params.light_radius = this->ShadowLightRadius;
  if (params.light_radius <= 0)
  {
    // Automatic: a light of MRGI_SHADOW_AUTO_LIGHT_RADIUS of the visible
    // scene's bounding radius (Documentation/DirectShadows.md).
    double bounds[6];
    frame.Renderer->ComputeVisiblePropBounds(bounds);
    const double diagonal = vtkMath::AreBoundsInitialized(bounds)
      ? std::sqrt((bounds[1] - bounds[0]) * (bounds[1] - bounds[0]) +
          (bounds[3] - bounds[2]) * (bounds[3] - bounds[2]) +
          (bounds[5] - bounds[4]) * (bounds[5] - bounds[4]))
      : 0.0;
    params.light_radius = std::isfinite(diagonal) ? 0.5 * diagonal * MRGI_SHADOW_AUTO_LIGHT_RADIUS : 0.0;
  }
  bool applied =
    (this->ShadowResolution == ResolutionMultiresolution
        ? this->DirectShadowStage->ComputeMultiresolution(
            frame, this->RSMPass, slotLights, params, g.ShadowFactors)
        : this->DirectShadowStage->Compute(
            frame, this->RSMPass, slotLights, params, g.ShadowFactors));
  applied = applied &&
    this->ShadowComposite->Apply(frame, g.Color, g.LightTerms, g.ShadowFactors, g.Shadowed);
  if (applied)
  {
    // Color is the frame's colour from here on; Shadowed keeps VTK's
    // unshadowed light for GetUnshadowedBuffer().
    std::swap(g.Color, g.Shadowed);
    in.ShadowFailureReported = false;
  }
  else if (!in.ShadowFailureReported)
  {
    in.ShadowFailureReported = true;
    vtkErrorMacro("the direct shadows could not be computed at "
      << frame.Viewport[2] << " x " << frame.Viewport[3]
      << " pixels: this frame has VTK's unshadowed direct light");
  }
  return applied;
}

//------------------------------------------------------------------------------
void vtkMRGIPass::RenderAdd(
  const vtkMRGIFrameContext& frame, vtkTextureObject* source, vtkTextureObject* target)
{
  Internals& in = *this->Internal;
  if (!vtkMRGIFullScreenStep::AddRGB(
        frame.Window, in.Programs, in.GBuffer.FrameBuffer, frame.Viewport, source, target))
  {
    vtkErrorMacro("could not build the MRGI composite shader");
  }
}

//------------------------------------------------------------------------------
void vtkMRGIPass::RenderOutput(
  const vtkMRGIFrameContext& frame, vtkTextureObject* source, float scale, bool toneMap, bool depth)
{
  Internals& in = *this->Internal;
  vtkOpenGLRenderWindow* renWin = frame.Window;
  // The enclosing pass's G-buffer (vtkSSAOPass) is written with the depth.
  const bool gbuffer = depth && this->OuterGBuffer && this->Captured;
  vtkOpenGLQuadHelper* quad = in.Programs.Ready(renWin, "output",
    !depth      ? "#define MRGI_OUTPUT_NO_DEPTH\n"
      : gbuffer ? "#define MRGI_OUTPUT_GBUFFER\n"
                : "",
    [] { return vtkMRGICompositeFS; });
  if (!quad)
  {
    vtkErrorMacro("could not build the MRGI output shader");
    return;
  }
  vtkShaderProgram* program = quad->Program;
  vtkOpenGLState* ostate = renWin->GetState();
  vtkMRGIViewportStep state(ostate, frame.Viewport);
  vtkOpenGLState::ScopedglDepthFunc depthFunc(ostate);
  vtkOpenGLState::ScopedglDepthMask depthMask(ostate);
  if (depth)
  {
    ostate->vtkglEnable(GL_DEPTH_TEST); // writes the scene's depth (GL_ALWAYS)
    ostate->vtkglDepthFunc(GL_ALWAYS);
    ostate->vtkglDepthMask(GL_TRUE);
    in.GBuffer.Depth->Activate();
    program->SetUniformi("mrgiDepth", in.GBuffer.Depth->GetTextureUnit());
  }
  else
  {
    ostate->vtkglDisable(GL_DEPTH_TEST);
    ostate->vtkglDepthMask(GL_FALSE);
  }
  if (gbuffer)
  {
    in.GBuffer.Position->Activate();
    in.GBuffer.Normal->Activate();
    program->SetUniformi("mrgiPosition", in.GBuffer.Position->GetTextureUnit());
    program->SetUniformi("mrgiNormal", in.GBuffer.Normal->GetTextureUnit());
  }
  source->Activate();
  program->SetUniformi("mrgiColor", source->GetTextureUnit());
  program->SetUniformf("mrgiExposureScale", scale);
  program->SetUniformi("mrgiToneMap", toneMap ? 1 : 0);
  quad->Render();
  source->Deactivate();
  if (gbuffer)
  {
    in.GBuffer.Normal->Deactivate();
    in.GBuffer.Position->Deactivate();
  }
  if (depth)
  {
    in.GBuffer.Depth->Deactivate();
  }
}

//------------------------------------------------------------------------------
void vtkMRGIPass::RenderOutputFXAA(const vtkMRGIFrameContext& frame, float scale)
{
  Internals& in = *this->Internal;
  vtkOpenGLFramebufferObject* fbo = in.GBuffer.FrameBuffer;
  fbo->SaveCurrentBindingsAndBuffers();
  fbo->Bind();
  fbo->RemoveColorAttachments(MRGI_GBUFFER_MAX_ATTACHMENTS);
  fbo->AddColorAttachment(0, in.GBuffer.Display);
  vtkMRGIShaderUtilities::SelectDrawBuffers(fbo, 1);
  this->RenderOutput(frame, in.GBuffer.Color, scale, this->ToneMapping, false);
  fbo->UnBind();
  fbo->RestorePreviousBindingsAndBuffers();
  vtkMRGIRenderSteps::RenderFXAA(
    frame.Renderer, fbo, in.GBuffer.Display, frame.Viewport, this->FXAAFilter);
  // The display image is final: copied as it is.
  this->RenderOutput(frame, in.GBuffer.Display, 1.0f, false, true);
}

//------------------------------------------------------------------------------
double vtkMRGIPass::MeasureAutoExposure(vtkOpenGLRenderWindow* renWin)
{
  Internals& in = *this->Internal;
  std::vector<float> rgba;
  if (!vtkMRGIShaderUtilities::ReadTextureRGBA(renWin, in.GBuffer.Color, rgba))
  {
    vtkErrorMacro("automatic exposure: reading the colour back failed; EV 0 used");
    return 0.0;
  }
  const int x0 = this->Viewport[0], y0 = this->Viewport[1];
  const int w = this->Viewport[2], h = this->Viewport[3];
  const size_t fullWidth = in.GBuffer.Color->GetWidth();
  std::vector<float> depth(static_cast<size_t>(w) * h);
  vtkOpenGLFramebufferObject* fbo = in.GBuffer.FrameBuffer;
  fbo->SaveCurrentBindingsAndBuffers();
  fbo->Bind();
  fbo->AddDepthAttachment(in.GBuffer.Depth);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(x0, y0, w, h, GL_DEPTH_COMPONENT, GL_FLOAT, depth.data());
  fbo->UnBind();
  fbo->RestorePreviousBindingsAndBuffers();
  // The viewport's pixels, in the depth's order.
  std::vector<float> colour(static_cast<size_t>(w) * h * 4);
  for (int y = 0; y < h; ++y)
  {
    std::copy(rgba.begin() + static_cast<long>(4 * ((y + y0) * fullWidth + x0)),
      rgba.begin() + static_cast<long>(4 * ((y + y0) * fullWidth + x0 + w)),
      colour.begin() + static_cast<long>(4 * static_cast<size_t>(y) * w));
  }
  double logAverage = 0.0, highlight = 0.0;
  mrgi_error err;
  const int64_t count = static_cast<int64_t>(w) * h;
  if (mrgi_exposure_log_average(
        colour.data(), 4, depth.data(), count, &logAverage, nullptr, &err) != MRGI_OK ||
    mrgi_exposure_quantile(colour.data(), 4, depth.data(), count, MRGI_EXPOSURE_HIGHLIGHT_FRACTION,
      &highlight, &err) != MRGI_OK)
  {
    vtkErrorMacro(<< "automatic exposure: " << err.message);
    return 0.0;
  }
  return mrgi_exposure_auto_ev(logAverage, highlight, this->AutoExposureKey);
}

//------------------------------------------------------------------------------
void vtkMRGIPass::Render(const vtkRenderState* s)
{
  vtkOpenGLClearErrorMacro();
  this->NumberOfRenderedProps = 0;

  vtkRenderer* renderer = s->GetRenderer();
  vtkOpenGLRenderWindow* renWin =
    vtkOpenGLRenderWindow::SafeDownCast(renderer ? renderer->GetRenderWindow() : nullptr);
  if (!renWin)
  {
    vtkErrorMacro("vtkMRGIPass needs a renderer in an OpenGL render window");
    return;
  }
  if (!this->DelegatePass)
  {
    vtkWarningMacro("vtkMRGIPass has no delegate pass: nothing to render "
                    "(SetDelegatePass(vtkRenderStepsPass) is the usual choice)");
    return;
  }

  // MSAA cannot reach MRGI's single-sample float buffers, and VTK 9.1's
  // FXAA filter gives a black image in a multisampled window (measured:
  // also with MRGI's own buffer as its input): FXAA is skipped there.
  const bool multisampled = renWin->GetMultiSamples() > 1;
  if (multisampled && !this->MultiSamplesReported)
  {
    this->MultiSamplesReported = true;
    vtkErrorMacro("the render window asks for "
      << renWin->GetMultiSamples()
      << " multisamples (MSAA), which vtkMRGIPass cannot honour: it renders into single-sample "
         "float buffers. Rendering without MSAA"
      << (renderer->GetUseFXAA() ? " and without FXAA (black in a multisampled window)" : "")
      << "; call window->SetMultiSamples(0) and use renderer->UseFXAAOn() for anti-aliasing.");
  }

  // An image-processing delegate (vtkSSAOPass, vtkToneMappingPass,
  // vtkOpenGLFXAAPass, vtkEDLShading, vtkDepthOfFieldPass, another
  // vtkMRGIPass) draws the scene into its own buffers: MRGI's G-buffer
  // capture never reaches MRGI's targets, and the image would silently lose
  // the indirect light. Refused once, with the nesting that works; the
  // delegate then renders on its own (its effect without MRGI's).
  if (vtkImageProcessingPass::SafeDownCast(this->DelegatePass))
  {
    if (!this->NestingReported)
    {
      this->NestingReported = true;
      const char* name = this->DelegatePass->GetClassName();
      vtkErrorMacro(<< name << " as the delegate of vtkMRGIPass is not supported: it draws the "
                    << "scene into its own buffers, out of MRGI's reach, so no indirect or area "
                    << "light would be added. Nest it the other way round: " << name
                    << "->SetDelegatePass(mrgi) and mrgi->SetDelegatePass(vtkRenderStepsPass) "
                    << "(Documentation/Composition.md). Rendering the " << name << " alone.");
    }
    this->IndirectComputed = false;
    this->AreaLightsComputed = false;
    this->DelegatePass->Render(s);
    this->NumberOfRenderedProps += this->DelegatePass->GetNumberOfRenderedProps();
    return;
  }

  // An enclosing pass that reads VTK's G-buffer convention (vtkSSAOPass:
  // view-space position and normal in draw buffers 1 and 2) gets them from
  // MRGI's output: the scene is drawn into MRGI's buffers, not its.
  {
    GLint drawBuffer1 = GL_NONE, drawBuffer2 = GL_NONE;
    glGetIntegerv(GL_DRAW_BUFFER1, &drawBuffer1);
    glGetIntegerv(GL_DRAW_BUFFER2, &drawBuffer2);
    this->OuterGBuffer = drawBuffer1 == GL_COLOR_ATTACHMENT1 && drawBuffer2 == GL_COLOR_ATTACHMENT2;
  }

  int x = 0, y = 0, w = 0, h = 0;
  renderer->GetTiledSizeAndOrigin(&w, &h, &x, &y);
  if (w < 1 || h < 1)
  {
    return; // a zero-size viewport has nothing to show; not an error
  }
  this->Viewport[0] = x;
  this->Viewport[1] = y;
  this->Viewport[2] = w;
  this->Viewport[3] = h;

  // Hardware selection (picking): only the props' selection colours matter,
  // drawn where the selector reads them (the current framebuffer); no
  // G-buffer, no indirect light, which would change the colours.
  if (renderer->GetSelector())
  {
    this->IndirectComputed = false;
    vtkRenderStepsPass* steps = vtkRenderStepsPass::SafeDownCast(this->DelegatePass);
    if (steps && steps->GetCameraPass())
    {
      vtkNew<vtkRenderPassCollection> passes;
      vtkSmartPointer<vtkRenderPass> select = vtkMRGIRenderSteps::NewSelectionPass();
      if (steps->GetLightsPass())
      {
        passes->AddItem(steps->GetLightsPass());
      }
      passes->AddItem(select);
      this->OpaqueSequence->SetPasses(passes);
      vtkMRGIRenderSteps::RenderCameraWith(steps->GetCameraPass(), this->OpaqueSequence, s);
      this->NumberOfRenderedProps += steps->GetCameraPass()->GetNumberOfRenderedProps();
    }
    else
    {
      this->DelegatePass->Render(s);
      this->NumberOfRenderedProps += this->DelegatePass->GetNumberOfRenderedProps();
    }
    return;
  }

  // Model only what the frame requires: no capture, no maps, no gather
  // when indirect light is off or cannot contribute.
  Internals& in = *this->Internal;
  const bool areaLights = this->AreaLightStage->GetNumberOfLights() > 0;
  // SSGI and the VPL gather are exclusive (no bounce counted twice).
  const bool indirect =
    !this->SSGI && this->IndirectMode != IndirectOff && this->GetNumberOfVPLs() > 0;
  int slotLights[MRGI_SHADOW_SLOTS];
  int unshadowedSceneLights = 0;
  const int shadowedLights = this->DirectShadows != DirectShadowsOff
    ? ShaderLights(renderer, slotLights, unshadowedSceneLights)
    : 0;
  const bool shadows = shadowedLights > 0;
  const bool capture = indirect || areaLights || this->OuterGBuffer || shadows || this->SSAO ||
    this->SSGI;
  const bool split = vtkRenderStepsPass::SafeDownCast(this->DelegatePass) != nullptr;
  vtkRenderTimerLog* timer = vtkMRGIShaderUtilities::StageTimer(renderer, this->StageTimingEnabled);
  this->IndirectComputed = false;
  this->AreaLightsComputed = false;
  this->Captured = capture;
  this->ShadowsCaptured = shadows;
  this->ShadowsComputed = false;
  if (unshadowedSceneLights > 0 && !in.ExtraLightsReported)
  {
    in.ExtraLightsReported = true;
    vtkWarningMacro(<< "direct shadows are cast by the first " << MRGI_SHADOW_SLOTS
                    << " switched-on lights only; " << unshadowedSceneLights
                    << " more scene light(s) light as VTK lights them, unshadowed");
  }
  // The specular pass cannot change the image when no visible prop has a
  // specular material: then neither it nor its G-buffer targets run.
  this->SpecularCaptured =
    capture && areaLights && this->AreaLightStage->GetSpecular() && AnySpecularProp(renderer);

  const bool fxaa = renderer->GetUseFXAA() && !multisampled;
  in.GBuffer.Prepare(renWin, x + w, y + h, capture, this->SpecularCaptured, shadows, fxaa);
  this->BufferSize[0] = w;
  this->BufferSize[1] = h;
  {
    ScopedStage stage(timer, "scene");
    this->RenderScene(s, capture, split);
  }
  if (capture)
  {
    // After the scene pass: the mappers' inputs are up to date now.
    this->WarnPointClouds(renderer);
  }
  // The frame's context, built once; `framed`: the multiresolution terms
  // (pixel size) are defined, which only a captured frame needs.
  vtkMRGIFrameContext frame;
  const bool framed = this->MakeFrame(renWin, renderer, timer, capture, frame);
  bool selected = false; // this frame's multiresolution selection exists
  if (indirect || (shadows && framed))
  {
    // The reflective shadow maps are the indirect light's VPLs and the
    // direct light's shadow maps: rendered once for both.
    ScopedStage stage(timer, "rsm");
    this->RSMPass->Render(s);
  }
  if (shadows && framed)
  {
    this->ShadowsComputed = this->RenderDirectShadows(frame, slotLights);
  }
  if (framed)
  {
    this->RenderScreenSpaceEffects(frame, in.GBuffer.Color);
  }
  if (indirect)
  {
    int vplCount = 0;
    {
      ScopedStage stage(timer, "vpl");
      vplCount = this->VPLSelection->Update(renWin, this->RSMPass);
    }
    if (vplCount > 0)
    {
      bool gathered = true;
      if (this->IndirectMode == IndirectMultires)
      {
        gathered = framed && this->RenderMultiresolution(frame, vplCount);
        selected = gathered;
      }
      else
      {
        ScopedStage stage(timer, "gather");
        gathered = this->RenderGather(frame, vplCount);
      }
      if (gathered)
      {
        ScopedStage stage(timer, "add");
        this->RenderAdd(frame, in.GBuffer.Indirect, in.GBuffer.Color);
        this->IndirectComputed = true;
        in.IndirectFailureReported = false;
      }
      else if (!in.IndirectFailureReported)
      {
        // Never a silent fallback: the image has no indirect light.
        in.IndirectFailureReported = true;
        vtkErrorMacro("the indirect light could not be computed at "
          << w << " x " << h << " pixels: this frame has direct light only");
      }
    }
  }
  if (areaLights && framed)
  {
    this->AreaLightsComputed =
      this->AreaLightStage->Render(frame, this->Multiresolution, selected, in.GBuffer.Color);
    if (this->AreaLightsComputed)
    {
      in.AreaLightFailureReported = false;
    }
    else if (!in.AreaLightFailureReported)
    {
      in.AreaLightFailureReported = true;
      vtkErrorMacro("the area lights could not be computed at "
        << w << " x " << h << " pixels: this frame has none of their light");
    }
  }
  if (split)
  {
    ScopedStage stage(timer, "forward");
    this->RenderForward(s);
  }
  {
    ScopedStage stage(timer, "output");
    this->LastExposure = this->AutoExposure ? this->MeasureAutoExposure(renWin) : this->Exposure;
    const float scale = mrgi_exposure_scale(this->LastExposure);
    if (fxaa)
    {
      this->RenderOutputFXAA(frame, scale);
    }
    else
    {
      this->RenderOutput(frame, in.GBuffer.Color, scale, this->ToneMapping, true);
    }
    if (split)
    {
      this->NumberOfRenderedProps += vtkMRGIRenderSteps::RenderOverlays(
        s, vtkRenderStepsPass::SafeDownCast(this->DelegatePass), this->Viewport);
    }
  }
  vtkOpenGLCheckErrorMacro("failed after vtkMRGIPass::Render");
}

//------------------------------------------------------------------------------
bool vtkMRGIPass::PreReplaceShaderValues(std::string&, std::string&, std::string& fragmentShader,
  vtkAbstractMapper* mapper, vtkProp*)
{
  if (vtkOpenGLPolyDataMapper::SafeDownCast(mapper))
  {
    vtkMRGIShaderUtilities::AddCaptureMarkers(fragmentShader);
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkMRGIPass::PostReplaceShaderValues(std::string&, std::string&, std::string& fragmentShader,
  vtkAbstractMapper* mapper, vtkProp* prop)
{
  if (!vtkOpenGLPolyDataMapper::SafeDownCast(mapper))
  {
    return true;
  }
  // Translucent props are not lit indirectly and never touch the G-buffer.
  const bool opaque = !prop || !prop->HasTranslucentPolygonalGeometry();
  if (opaque && vtkMRGIShaderUtilities::CanCapture(fragmentShader))
  {
    // VTK's lit shaders (not PBR) compute specularColor and specularPower.
    const bool phong = fragmentShader.find("float specularPower") != std::string::npos &&
      fragmentShader.find("vec3 specularColor") != std::string::npos;
    // The light terms are written whether or not this frame has shadows:
    // the shader then never changes with the shadow setting.
    std::string declarations = phong ? "#define MRGI_SPECULAR_MATERIAL 1\n" : "";
    std::string lightTerms;
    vtkMRGIShaderUtilities::InsertLightTerms(fragmentShader, declarations, lightTerms);
    vtkMRGIShaderUtilities::InsertCapture(
      fragmentShader, declarations, std::string(vtkMRGIGBufferCapture) + lightTerms);
  }
  else
  {
    // Unlit or normal-less geometry: the G-buffer says "nothing here".
    vtkMRGIShaderUtilities::InsertCapture(fragmentShader, "",
      "  gl_FragData[MRGI_GBUFFER_POSITION] = vec4(0.0);\n"
      "  gl_FragData[MRGI_GBUFFER_NORMAL] = vec4(0.0);\n"
      "  gl_FragData[MRGI_GBUFFER_ALBEDO] = vec4(0.0);\n"
      "  gl_FragData[MRGI_GBUFFER_SPECULAR] = vec4(0.0);\n"
      "  gl_FragData[MRGI_GBUFFER_SHININESS] = vec4(0.0);\n" +
        vtkMRGIShaderUtilities::NoLightTerms());
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkMRGIPass::SetShaderParameters(
  vtkShaderProgram*, vtkAbstractMapper* mapper, vtkProp*, vtkOpenGLVertexArrayObject*)
{
  // The mapper calls every pass in the order they were entered, outermost
  // first: this runs after an enclosing pass (vtkSSAOPass) changed the draw
  // buffers.
  if (this->Capturing && vtkOpenGLPolyDataMapper::SafeDownCast(mapper))
  {
    vtkMRGIShaderUtilities::SelectGBufferDrawBuffers(
      this->Internal->GBuffer.FrameBuffer, this->SpecularCaptured, this->ShadowsCaptured);
  }
  return true;
}

//------------------------------------------------------------------------------
int vtkMRGIPass::FetchStageTimings(vtkRenderWindow* window, bool wait)
{
  vtkRenderTimerLog* timer = window ? window->GetRenderTimer() : nullptr;
  if (!timer || !this->StageTimingEnabled || !timer->IsSupported())
  {
    return 0;
  }
  if (!timer->GetLoggingEnabled())
  {
    // Between frames is the safe moment to switch logging on; the next frame
    // is the first one timed.
    timer->SetLoggingEnabled(true);
    return 0;
  }
  if (wait)
  {
    // Close the frame just rendered and drain the GPU so its queries are done.
    window->MakeCurrent();
    timer->MarkFrame();
    if (vtkOpenGLRenderWindow::SafeDownCast(window))
    {
      glFinish();
    }
  }
  return vtkMRGIShaderUtilities::CollectStageTimes(timer, this->StageNames, this->StageTimes)
    ? this->GetNumberOfStages()
    : 0;
}

//------------------------------------------------------------------------------
const char* vtkMRGIPass::GetStageName(int stage) const
{
  if (stage < 0 || stage >= this->GetNumberOfStages())
  {
    return nullptr;
  }
  return this->StageNames[static_cast<size_t>(stage)].c_str();
}

//------------------------------------------------------------------------------
double vtkMRGIPass::GetStageTimeMilliseconds(int stage) const
{
  if (stage < 0 || stage >= this->GetNumberOfStages())
  {
    return -1.0;
  }
  return this->StageTimes[static_cast<size_t>(stage)];
}

//------------------------------------------------------------------------------
bool vtkMRGIPass::ReadViewport(vtkRenderWindow* window, vtkTextureObject* texture, int components,
  vtkImageData* image, const char* what)
{
  vtkOpenGLRenderWindow* renWin = vtkOpenGLRenderWindow::SafeDownCast(window);
  if (!renWin || !image)
  {
    vtkErrorMacro("reading the " << what << " buffer needs an OpenGL render window and an image");
    return false;
  }
  if (!texture || this->BufferSize[0] < 1)
  {
    vtkErrorMacro("no " << what << " buffer: nothing rendered yet, or not computed this frame");
    return false;
  }
  if (!vtkMRGIGBuffer::ReadViewport(renWin, texture, this->Viewport, components, image))
  {
    vtkErrorMacro("reading the " << what << " buffer back failed");
    return false;
  }
  image->GetPointData()->GetScalars()->SetName(what);
  return true;
}

bool vtkMRGIPass::GetColorBuffer(vtkRenderWindow* window, vtkImageData* image)
{
  Internals& in = *this->Internal;
  return this->ReadViewport(window, in.GBuffer.Color, 4, image, "HDRColor");
}

bool vtkMRGIPass::GetUnshadowedBuffer(vtkRenderWindow* window, vtkImageData* image)
{
  Internals& in = *this->Internal;
  return this->ReadViewport(
    window, this->ShadowsComputed ? in.GBuffer.Shadowed : nullptr, 4, image, "Unshadowed");
}

bool vtkMRGIPass::GetShadowFactorBuffer(vtkRenderWindow* window, vtkImageData* image)
{
  Internals& in = *this->Internal;
  return this->ReadViewport(
    window, this->ShadowsComputed ? in.GBuffer.ShadowFactors : nullptr, 4, image, "ShadowFactors");
}

bool vtkMRGIPass::GetLightTermBuffer(vtkRenderWindow* window, int slot, vtkImageData* image)
{
  Internals& in = *this->Internal;
  if (slot < 0 || slot >= MRGI_SHADOW_SLOTS)
  {
    vtkErrorMacro("light term " << slot << " does not exist: slots are 0.." << MRGI_SHADOW_SLOTS - 1);
    return false;
  }
  return this->ReadViewport(window,
    this->ShadowsCaptured ? in.GBuffer.LightTerms[slot] : nullptr, 4, image, "LightTerm");
}

bool vtkMRGIPass::GetIndirectBuffer(vtkRenderWindow* window, vtkImageData* image)
{
  Internals& in = *this->Internal;
  return this->ReadViewport(
    window, this->IndirectComputed ? in.GBuffer.Indirect : nullptr, 3, image, "Indirect");
}

bool vtkMRGIPass::GetAreaLightBuffer(vtkRenderWindow* window, vtkImageData* image)
{
  return this->ReadViewport(window,
    this->AreaLightsComputed ? this->AreaLightStage->GetSumTexture() : nullptr, 3, image, "Area light");
}

bool vtkMRGIPass::GetIrradianceBuffer(vtkRenderWindow* window, vtkImageData* image)
{
  Internals& in = *this->Internal;
  return this->ReadViewport(
    window, this->IndirectComputed ? in.GBuffer.Irradiance : nullptr, 3, image, "Irradiance");
}

bool vtkMRGIPass::GetGBuffer(
  vtkRenderWindow* window, vtkImageData* position, vtkImageData* normal, vtkImageData* albedo)
{
  Internals& in = *this->Internal;
  const bool captured = in.GBuffer.Position && this->Captured;
  return this->ReadViewport(window, captured ? in.GBuffer.Position : nullptr, 4, position, "Position") &&
    this->ReadViewport(window, captured ? in.GBuffer.Normal : nullptr, 4, normal, "Normal") &&
    this->ReadViewport(window, captured ? in.GBuffer.Albedo : nullptr, 4, albedo, "Albedo");
}

bool vtkMRGIPass::GetSpecularGBuffer(vtkRenderWindow* window, vtkImageData* specular, vtkImageData* shininess)
{
  Internals& in = *this->Internal;
  const bool captured = in.GBuffer.Specular && this->SpecularCaptured;
  return this->ReadViewport(window, captured ? in.GBuffer.Specular : nullptr, 4, specular, "Specular") &&
    this->ReadViewport(window, captured ? in.GBuffer.Shininess : nullptr, 4, shininess, "Shininess");
}

bool vtkMRGIPass::GetVPLs(vtkRenderWindow* window, vtkFloatArray* vpls)
{
  vtkOpenGLRenderWindow* renWin = vtkOpenGLRenderWindow::SafeDownCast(window);
  vtkTextureObject* texture = this->VPLSelection->GetVPLTexture();
  std::vector<float> rgba;
  if (!renWin || !vpls || !texture || !vtkMRGIShaderUtilities::ReadTextureRGBA(renWin, texture, rgba))
  {
    vtkErrorMacro("no VPLs to read back");
    return false;
  }
  vpls->SetNumberOfComponents(MRGI_VPL_FLOATS);
  vpls->SetNumberOfTuples(this->VPLSelection->GetVPLCount());
  std::copy(rgba.begin(), rgba.begin() + static_cast<long>(MRGI_VPL_FLOATS) * this->VPLSelection->GetVPLCount(),
    vpls->GetPointer(0));
  return true;
}

//------------------------------------------------------------------------------
void vtkMRGIPass::RenderScreenSpaceEffects(const vtkMRGIFrameContext& frame, vtkTextureObject* colour)
{
  // SSAO as vtkSSAOPass applies it, to the direct light only: the indirect
  // and area light added below are not ambient terms and model their own
  // visibility. (After the direct shadows, which subtract shadowed light
  // terms from the unshadowed colour: AO multiplies their result.)
  if (this->SSAO)
  {
    ScopedStage stage(frame.Timer, "ssao");
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
    ScopedStage stage(frame.Timer, "ssgi");
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
         this->DirectShadowStage->GetBMRMask() })
  {
    mask->SetDepthThreshold(p.bmr_depth_threshold);
    mask->SetNormalThreshold(p.bmr_normal_threshold);
  }
  this->ScreenSpacePreset = preset;
  this->Modified();
  return true;
}

//------------------------------------------------------------------------------
void vtkMRGIPass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "IndirectMode: "
     << (this->IndirectMode == IndirectOff ? "Off" : this->IndirectMode == IndirectFull ? "Full" : "Multires")
     << "\n";
  os << indent << "UpsampleMode: " << this->GetUpsampleMode() << "\n";
  os << indent << "UpsampleMaskWeight: " << this->GetUpsampleMaskWeight() << "\n";
  os << indent << "SurfaceDetail: " << this->SurfaceDetail << "\n";
  os << indent << "DirectShadows: "
     << (this->DirectShadows == DirectShadowsOff ? "Off"
           : this->DirectShadows == DirectShadowsHard ? "Hard"
                                                      : "Soft")
     << " (kernel " << this->SoftShadowKernelSize << ", light radius " << this->ShadowLightRadius
     << ", "
     << (this->ShadowResolution == ResolutionMultiresolution ? "multiresolution"
                                                             : "full resolution")
     << ")\n";
  os << indent << "SSAO: " << (this->SSAO ? "on" : "off") << " (kernel " << this->SSAOKernelSize
     << ", radius " << this->SSAORadius << ", bias " << this->SSAOBias << ", blur "
     << (this->SSAOBlur ? "on" : "off") << ", "
     << (this->SSAOResolution == ResolutionMultiresolution ? "multiresolution" : "full resolution")
     << ")\n";
  os << indent << "ScreenSpacePreset: "
     << (this->ScreenSpacePreset >= 0 ? mrgi_screen_space_preset_name(this->ScreenSpacePreset)
                                      : "none")
     << "\n";
  os << indent << "SSGI: " << (this->SSGI ? "on" : "off") << " (samples " << this->SSGISamples
     << ", radius " << this->SSGIRadius << ", bias " << this->SSGIBias << ", "
     << (this->SSGIResolution == ResolutionMultiresolution ? "multiresolution" : "full resolution")
     << ")\n";
  os << indent << "IndirectStrength: " << this->IndirectStrength << "\n";
  os << indent << "NumberOfVPLs: " << this->VPLSelection->GetNumberOfVPLs() << "\n";
  os << indent << "VPLSelectionMode: " << this->VPLSelection->GetMode() << "\n";
  os << indent << "RSMResolution: " << this->RSMPass->GetResolution() << "\n";
  os << indent << "RSMCompositor: " << this->RSMPass->GetCompositor() << "\n";
  os << indent << "Exposure: " << this->Exposure << " EV\n";
  os << indent << "AutoExposure: " << (this->AutoExposure ? "On" : "Off") << "\n";
  os << indent << "AutoExposureKey: " << this->AutoExposureKey << "\n";
  os << indent << "LastExposure: " << this->LastExposure << " EV\n";
  os << indent << "ToneMapping: " << (this->ToneMapping ? "On" : "Off") << "\n";
  os << indent << "StageTimingEnabled: " << (this->StageTimingEnabled ? "On" : "Off") << "\n";
  os << indent << "Multiresolution:\n";
  this->Multiresolution->PrintSelf(os, indent.GetNextIndent());
  os << indent << "Gather:\n";
  this->Gather->PrintSelf(os, indent.GetNextIndent());
  os << indent << "AreaLightStage:\n";
  this->AreaLightStage->PrintSelf(os, indent.GetNextIndent());
  os << indent << "BufferSize: " << this->BufferSize[0] << " x " << this->BufferSize[1] << "\n";
  for (int i = 0; i < this->GetNumberOfStages(); ++i)
  {
    os << indent << "Stage " << this->GetStageName(i) << ": " << this->GetStageTimeMilliseconds(i)
       << " ms\n";
  }
}
