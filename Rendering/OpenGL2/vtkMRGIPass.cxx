#include "vtkMRGIPass.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCameraPass.h"
#include "vtkFloatArray.h"
#include "vtkHardwareSelector.h"
#include "vtkImageData.h"
#include "vtkMRGIAreaLight.h"
#include "vtkMRGIMultiresolution.h"
#include "vtkMRGIReflectiveShadowMapPass.h"
#include "vtkMRGIShaderUtilities.h"
#include "vtkMRGIVPLSelection.h"
#include "vtkMRGIVarianceShadowQuery.h"
#include "vtkMRGIVisibilityPyramid.h"
#include "vtkMRGIVoxelization.h"
#include "vtkDataObject.h"
#include "vtkMapper.h"
#include "vtkMatrix4x4.h"
#include "vtkTexture.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLError.h"
#include "vtkOpenGLFXAAFilter.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLPolyDataMapper.h"
#include "vtkOpenGLQuadHelper.h"
#include "vtkOpenGLRenderUtilities.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLRenderer.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtkPointData.h"
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

#include "vtkMRGIAddIndirectFS.h"
#include "vtkMRGICompositeFS.h"
#include "vtkMRGIGBufferCapture.h"
#include "vtkMRGIGatherFS.h"
#include "vtkMRGIVPLIrradiance.h"
#include "vtkMRGIAreaSpecularFS.h"

#include "mrgi_buffers.h"
#include "mrgi_area_light.h"
#include "mrgi_multires.h"
#include "mrgi_voxel_march.h"
#include "mrgi_vpl.h"

#include <algorithm>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkMRGIPass);

namespace
{
// Draw `quad` once per batch of `batch` light samples (uniforms
// mrgiSpecularBatchFirst / Count), the later batches added to the first
// (RGB summed, alpha kept): each draw's marches stay within llvmpipe's
// loop budget (mrgi_voxel_samples_per_batch()). The caller restores the
// blend state.
void RenderSampleBatches(vtkOpenGLState* ostate, vtkShaderProgram* program,
  vtkOpenGLQuadHelper* quad, int sampleCount, int batch)
{
  for (int first = 0; first < sampleCount; first += batch)
  {
    if (first == batch)
    {
      ostate->vtkglEnable(GL_BLEND);
      ostate->vtkglBlendFuncSeparate(GL_ONE, GL_ONE, GL_ZERO, GL_ONE);
    }
    program->SetUniformi("mrgiSpecularBatchFirst", first);
    program->SetUniformi("mrgiSpecularBatchCount", std::min(batch, sampleCount - first));
    quad->Render();
  }
}
}

namespace
{
// First step of the opaque sequence: VTK's camera pass has just cleared
// every draw buffer to the background colour; the G-buffer attachments must
// say "no geometry" (0) instead. Respects the renderer's scissor.
class vtkMRGIClearGBufferPass : public vtkRenderPass
{
public:
  static vtkMRGIClearGBufferPass* New();
  vtkTypeMacro(vtkMRGIClearGBufferPass, vtkRenderPass);
  void Render(const vtkRenderState*) override
  {
    const float zero[4] = { 0.0f, 0.0f, 0.0f, 0.0f };
    for (int a = MRGI_GBUFFER_POSITION; a < MRGI_GBUFFER_ATTACHMENTS; ++a)
    {
      glClearBufferfv(GL_COLOR, a, zero);
    }
  }

protected:
  vtkMRGIClearGBufferPass() = default;
  ~vtkMRGIClearGBufferPass() override = default;
};
vtkStandardNewMacro(vtkMRGIClearGBufferPass);

// Hardware selection (vtkHardwareSelector, vtkPropPicker, vtkRenderer::PickProp)
// through a vtkRenderStepsPass: VTK 9.1's opaque/translucent passes draw the
// props without telling the selector which prop is drawn (only the renderer's
// own UpdateGeometry does), so every pick misses. This step hands the props
// to the selector as the renderer would.
class vtkMRGISelectionPass : public vtkRenderPass
{
public:
  static vtkMRGISelectionPass* New();
  vtkTypeMacro(vtkMRGISelectionPass, vtkRenderPass);
  void Render(const vtkRenderState* s) override
  {
    vtkRenderer* renderer = s->GetRenderer();
    this->NumberOfRenderedProps = renderer->GetSelector()->Render(
      renderer, s->GetPropArray(), s->GetPropArrayCount());
  }

protected:
  vtkMRGISelectionPass() = default;
  ~vtkMRGISelectionPass() override = default;
};
vtkStandardNewMacro(vtkMRGISelectionPass);

// Runs `camera` (a vtkRenderStepsPass's camera pass) with `delegate` in place
// of its usual delegate, then puts the usual one back: the same
// vtkRenderStepsPass may also be installed on its own (a GI on/off switch),
// and would otherwise keep drawing MRGI's steps only.
void RenderCameraWith(vtkCameraPass* camera, vtkRenderPass* delegate, const vtkRenderState* s)
{
  vtkSmartPointer<vtkRenderPass> usual = camera->GetDelegatePass();
  camera->SetDelegatePass(delegate);
  camera->Render(s);
  camera->SetDelegatePass(usual);
}
}

namespace
{
using vtkMRGIShaderUtilities::ScopedStage;
using vtkMRGIShaderUtilities::StagePrefix;

void CollectStages(const vtkRenderTimerLog::Event& event, std::vector<std::string>& names,
  std::vector<double>& times)
{
  if (event.Name.compare(0, std::strlen(StagePrefix), StagePrefix) == 0)
  {
    // A step drawn once per level logs one event per level: their sum.
    const std::string name = event.Name.substr(std::strlen(StagePrefix));
    const double ms = static_cast<double>(event.ElapsedTimeNanoseconds()) * 1e-6;
    const auto found = std::find(names.begin(), names.end(), name);
    if (found != names.end())
    {
      times[static_cast<size_t>(found - names.begin())] += ms;
    }
    else
    {
      names.push_back(name);
      times.push_back(ms);
    }
  }
  for (const auto& child : event.Events)
  {
    CollectStages(child, names, times);
  }
}

vtkRenderTimerLog* TimerFor(vtkRenderer* renderer, bool enabled)
{
  vtkRenderWindow* window = renderer ? renderer->GetRenderWindow() : nullptr;
  vtkRenderTimerLog* timer = window ? window->GetRenderTimer() : nullptr;
  // Logging is switched on between frames only (FetchStageTimings, or the
  // application): VTK brackets its own rendering with timer events, and
  // switching mid-frame would leave those unbalanced.
  return (timer && enabled && timer->GetLoggingEnabled()) ? timer : nullptr;
}

vtkTextureObject* MakeTexture(vtkOpenGLRenderWindow* renWin, int internalFormat, int w, int h)
{
  vtkTextureObject* t = vtkTextureObject::New();
  t->SetContext(renWin);
  t->SetFormat(GL_RGBA);
  t->SetInternalFormat(internalFormat);
  t->SetDataType(GL_FLOAT);
  t->SetMinificationFilter(vtkTextureObject::Nearest);
  t->SetMagnificationFilter(vtkTextureObject::Nearest);
  t->Allocate2D(w, h, 4, VTK_FLOAT);
  return t;
}

void Release(vtkTextureObject*& t, vtkWindow* w)
{
  if (t)
  {
    t->ReleaseGraphicsResources(w);
    t->Delete();
    t = nullptr;
  }
}

void Release(vtkOpenGLQuadHelper*& q, vtkWindow* w)
{
  if (q)
  {
    q->ReleaseGraphicsResources(w);
    delete q;
    q = nullptr;
  }
}

// GL state of a full-screen step over the renderer's viewport: blending
// and depth test off (steps turn on what they need), viewport and scissor on
// the renderer's tile; everything restored when the step ends.
struct ViewportQuadState
{
  ViewportQuadState(vtkOpenGLState* ostate, const int viewport[4])
    : Blend(ostate, GL_BLEND)
    , DepthTest(ostate, GL_DEPTH_TEST)
    , Viewport(ostate)
    , Scissor(ostate)
  {
    ostate->vtkglDisable(GL_BLEND);
    ostate->vtkglDisable(GL_DEPTH_TEST);
    ostate->vtkglViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
    ostate->vtkglScissor(viewport[0], viewport[1], viewport[2], viewport[3]);
  }
  vtkOpenGLState::ScopedglEnableDisable Blend;
  vtkOpenGLState::ScopedglEnableDisable DepthTest;
  vtkOpenGLState::ScopedglViewport Viewport;
  vtkOpenGLState::ScopedglScissor Scissor;
};

// Builds (once) or readies a full-screen program; nullptr when it fails.
vtkShaderProgram* ReadyQuad(vtkOpenGLQuadHelper*& quad, vtkOpenGLRenderWindow* renWin, const char* body)
{
  if (!quad)
  {
    quad = new vtkOpenGLQuadHelper(renWin,
      vtkOpenGLRenderUtilities::GetFullScreenQuadVertexShader().c_str(),
      vtkMRGIShaderUtilities::FullScreenShader(body).c_str(), "");
  }
  else
  {
    renWin->GetShaderCache()->ReadyShaderProgram(quad->Program);
  }
  return (quad->Program && quad->Program->GetCompiled()) ? quad->Program : nullptr;
}
}

//------------------------------------------------------------------------------
vtkMRGIPass::vtkMRGIPass()
{
  this->RSMPass = vtkMRGIReflectiveShadowMapPass::New();
  this->VPLSelection = vtkMRGIVPLSelection::New();
  this->Multiresolution = vtkMRGIMultiresolution::New();
  this->Voxelization = vtkMRGIVoxelization::New();
  this->VisibilityPyramid = vtkMRGIVisibilityPyramid::New();
  // 2x2 interleaving off by default: measured at 256^2 on llvmpipe it saved
  // 5-15% of the area-light time but raised the error against the ground
  // truth from 0.111 to 0.179 (living room; Cornell box 0.137 -> 0.142).
  this->VisibilityPyramid->InterleaveOff();
  this->VarianceShadowQuery = vtkMRGIVarianceShadowQuery::New();
  this->OpaqueSequence = vtkSequencePass::New();
  for (int i = 0; i < 16; ++i)
  {
    this->LastViewToWorld[i] = (i % 5 == 0) ? 1.0 : 0.0;
  }
}

//------------------------------------------------------------------------------
vtkMRGIPass::~vtkMRGIPass()
{
  if (this->FrameBuffer || this->ColorTexture || this->OutputQuad)
  {
    vtkErrorMacro("vtkMRGIPass destroyed while it still holds GL resources: call "
                  "ReleaseGraphicsResources() first (the render window does so).");
  }
  for (vtkTextureObject* t : { this->ColorTexture, this->PositionTexture, this->NormalTexture,
         this->AlbedoTexture, this->DepthTexture, this->IrradianceTexture, this->IndirectTexture })
  {
    if (t)
    {
      t->Delete();
    }
  }
  if (this->FrameBuffer)
  {
    this->FrameBuffer->Delete();
  }
  delete this->GatherQuad;
  delete this->AddQuad;
  delete this->OutputQuad;
  delete this->SpecularQuad;
  delete this->SpecularMaskedQuad;
  delete this->SpecularMarchedQuad;
  delete this->SpecularMultiresQuad;
  delete this->SpecularMultiresMaskedQuad;
  delete this->SpecularMultiresMarchedQuad;
  if (this->FXAAFilter)
  {
    this->FXAAFilter->Delete();
  }
  this->RSMPass->Delete();
  this->VPLSelection->Delete();
  this->Multiresolution->Delete();
  this->OpaqueSequence->Delete();
  this->Voxelization->Delete();
  this->VisibilityPyramid->Delete();
  this->VarianceShadowQuery->Delete();
  this->RemoveAllAreaLights();
}

//------------------------------------------------------------------------------
namespace
{
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
void vtkMRGIPass::AddAreaLight(vtkMRGIAreaLight* light)
{
  if (!light || std::find(this->AreaLights.begin(), this->AreaLights.end(), light) != this->AreaLights.end())
  {
    return;
  }
  light->Register(this);
  this->AreaLights.push_back(light);
  this->Modified();
}

void vtkMRGIPass::RemoveAreaLight(vtkMRGIAreaLight* light)
{
  auto it = std::find(this->AreaLights.begin(), this->AreaLights.end(), light);
  if (it == this->AreaLights.end())
  {
    return;
  }
  // The light keeps its GPU textures (its own ReleaseGraphicsResources).
  this->AreaLights.erase(it);
  light->UnRegister(this);
  this->Modified();
}

void vtkMRGIPass::RemoveAllAreaLights()
{
  while (!this->AreaLights.empty())
  {
    this->RemoveAreaLight(this->AreaLights.back());
  }
}

int vtkMRGIPass::GetNumberOfAreaLights() const
{
  return static_cast<int>(this->AreaLights.size());
}

vtkMRGIAreaLight* vtkMRGIPass::GetAreaLight(int index) const
{
  return index >= 0 && index < this->GetNumberOfAreaLights() ? this->AreaLights[static_cast<size_t>(index)]
                                                             : nullptr;
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

//------------------------------------------------------------------------------
void vtkMRGIPass::ReleaseGraphicsResources(vtkWindow* w)
{
  this->Superclass::ReleaseGraphicsResources(w);
  this->RSMPass->ReleaseGraphicsResources(w);
  this->VPLSelection->ReleaseGraphicsResources(w);
  this->Multiresolution->ReleaseGraphicsResources(w);
  this->Voxelization->ReleaseGraphicsResources(w);
  this->VisibilityPyramid->ReleaseGraphicsResources(w);
  this->VarianceShadowQuery->ReleaseGraphicsResources(w);
  this->AreaLightSignature.clear(); // the sum it describes is released below
  Release(this->GatherQuad, w);
  Release(this->AddQuad, w);
  Release(this->OutputQuad, w);
  Release(this->SpecularQuad, w);
  Release(this->SpecularMaskedQuad, w);
  Release(this->SpecularMultiresQuad, w);
  Release(this->SpecularMultiresMaskedQuad, w);
  Release(this->SpecularMultiresMarchedQuad, w);
  Release(this->SpecularMarchedQuad, w);
  for (vtkMRGIAreaLight* light : this->AreaLights)
  {
    light->ReleaseGraphicsResources(w);
  }
  if (this->FXAAFilter)
  {
    this->FXAAFilter->ReleaseGraphicsResources();
    this->FXAAFilter->Delete();
    this->FXAAFilter = nullptr;
  }
  if (this->FrameBuffer)
  {
    this->FrameBuffer->ReleaseGraphicsResources(w);
    this->FrameBuffer->Delete();
    this->FrameBuffer = nullptr;
  }
  Release(this->ColorTexture, w);
  Release(this->PositionTexture, w);
  Release(this->NormalTexture, w);
  Release(this->AlbedoTexture, w);
  Release(this->DepthTexture, w);
  Release(this->IrradianceTexture, w);
  Release(this->IndirectTexture, w);
  Release(this->AreaIrradianceTexture, w);
  Release(this->AreaDirectTexture, w);
  Release(this->AreaSumTexture, w);
  Release(this->SpecularTexture, w);
  Release(this->ShininessTexture, w);
  this->BufferSize[0] = this->BufferSize[1] = 0;
  this->IndirectComputed = false;
  this->AreaLightsComputed = false;
}

//------------------------------------------------------------------------------
void vtkMRGIPass::PrepareBuffers(vtkOpenGLRenderWindow* renWin, int w, int h, bool capture)
{
  // Float colour: VTK's lighting is unclamped and the HDR result is what EXR
  // output reads. G-buffer positions need float range; normals and albedo
  // are bounded, half floats suffice.
  auto ensure = [&](vtkTextureObject*& t, int format) {
    if (!t)
    {
      t = MakeTexture(renWin, format, w, h);
    }
    t->Resize(w, h);
  };
  ensure(this->ColorTexture, GL_RGBA32F);
  if (!this->DepthTexture)
  {
    this->DepthTexture = vtkTextureObject::New();
    this->DepthTexture->SetContext(renWin);
    this->DepthTexture->SetMinificationFilter(vtkTextureObject::Nearest);
    this->DepthTexture->SetMagnificationFilter(vtkTextureObject::Nearest);
    // The depth format of VTK's own framebuffers, chosen as
    // vtkOrderIndependentTranslucentPass chooses its depth texture (from the
    // framebuffer bound now: the window's, or an enclosing pass's): that pass
    // blits MRGI's depth into its texture, and a blit needs identical depth
    // formats (a float depth here left translucent props without depth test).
    if (renWin->GetStencilCapable())
    {
      this->DepthTexture->AllocateDepthStencil(w, h);
    }
    else
    {
      this->DepthTexture->AllocateDepth(w, h,
        renWin->GetDepthBufferSize() == 32 ? vtkTextureObject::Fixed32 : vtkTextureObject::Fixed24);
    }
  }
  this->DepthTexture->Resize(w, h);
  if (capture)
  {
    ensure(this->PositionTexture, GL_RGBA32F);
    ensure(this->NormalTexture, GL_RGBA16F);
    ensure(this->AlbedoTexture, GL_RGBA16F);
    ensure(this->IrradianceTexture, GL_RGBA32F);
    ensure(this->IndirectTexture, GL_RGBA32F);
    if (this->SpecularCaptured)
    {
      ensure(this->SpecularTexture, GL_RGBA16F);
      ensure(this->ShininessTexture, GL_RGBA16F);
    }
  }
  if (!this->FrameBuffer)
  {
    this->FrameBuffer = vtkOpenGLFramebufferObject::New();
    this->FrameBuffer->SetContext(renWin);
  }
}

//------------------------------------------------------------------------------
void vtkMRGIPass::RenderScene(const vtkRenderState* s, bool capture, bool split)
{
  vtkOpenGLFramebufferObject* fbo = this->FrameBuffer;
  fbo->SaveCurrentBindingsAndBuffers();
  fbo->Bind();
  fbo->AddColorAttachment(MRGI_GBUFFER_DIRECT, this->ColorTexture);
  if (capture)
  {
    fbo->AddColorAttachment(MRGI_GBUFFER_POSITION, this->PositionTexture);
    fbo->AddColorAttachment(MRGI_GBUFFER_NORMAL, this->NormalTexture);
    fbo->AddColorAttachment(MRGI_GBUFFER_ALBEDO, this->AlbedoTexture);
    // Specular data only when something reads it: every named draw buffer
    // needs an attachment (GL 3.2 completeness).
    if (this->SpecularCaptured)
    {
      fbo->AddColorAttachment(MRGI_GBUFFER_SPECULAR, this->SpecularTexture);
      fbo->AddColorAttachment(MRGI_GBUFFER_SHININESS, this->ShininessTexture);
    }
    fbo->ActivateDrawBuffers(this->SpecularCaptured ? MRGI_GBUFFER_ATTACHMENTS : MRGI_GBUFFER_SPECULAR);
  }
  else
  {
    fbo->RemoveColorAttachments(MRGI_GBUFFER_ATTACHMENTS);
    fbo->AddColorAttachment(MRGI_GBUFFER_DIRECT, this->ColorTexture);
    fbo->ActivateDrawBuffers(1);
  }
  fbo->AddDepthAttachment(this->DepthTexture);

  // The camera pass sets the renderer's viewport and clears: MRGI's buffers
  // are as large as the window, so the renderer's tile lands where it does
  // in the window.
  if (capture)
  {
    this->PreRender(s);
  }
  if (split)
  {
    vtkRenderStepsPass* steps = vtkRenderStepsPass::SafeDownCast(this->DelegatePass);
    vtkNew<vtkRenderPassCollection> passes;
    vtkNew<vtkMRGIClearGBufferPass> clear;
    if (capture)
    {
      passes->AddItem(clear);
    }
    passes->AddItem(steps->GetLightsPass());
    passes->AddItem(steps->GetOpaquePass());
    this->OpaqueSequence->SetPasses(passes);
    RenderCameraWith(steps->GetCameraPass(), this->OpaqueSequence, s);
    this->NumberOfRenderedProps += steps->GetCameraPass()->GetNumberOfRenderedProps();
  }
  else
  {
    // Another delegate clears and draws in one go: the G-buffer is cleared
    // first, and VTK's clear then writes the background alpha to its w
    // (valid only if that alpha exceeds MRGI_GBUFFER_VALID_THRESHOLD, which
    // VTK's default background alpha of 0 does not).
    const float zero[4] = { 0.0f, 0.0f, 0.0f, 0.0f };
    for (int a = MRGI_GBUFFER_POSITION; capture && a < MRGI_GBUFFER_ATTACHMENTS; ++a)
    {
      glClearBufferfv(GL_COLOR, a, zero);
    }
    this->DelegatePass->Render(s);
    this->NumberOfRenderedProps += this->DelegatePass->GetNumberOfRenderedProps();
  }
  if (capture)
  {
    this->PostRender(s);
  }
  fbo->UnBind();
  fbo->RestorePreviousBindingsAndBuffers();
}

//------------------------------------------------------------------------------
void vtkMRGIPass::RenderForward(const vtkRenderState* s)
{
  // Translucent props, volumes and overlays, over the lit opaque scene, into
  // the colour buffer only (the G-buffer is for opaque surfaces).
  vtkRenderStepsPass* steps = vtkRenderStepsPass::SafeDownCast(this->DelegatePass);
  vtkOpenGLFramebufferObject* fbo = this->FrameBuffer;
  fbo->SaveCurrentBindingsAndBuffers();
  fbo->Bind();
  fbo->RemoveColorAttachments(MRGI_GBUFFER_ATTACHMENTS);
  fbo->AddColorAttachment(MRGI_GBUFFER_DIRECT, this->ColorTexture);
  fbo->ActivateDrawBuffers(1);
  fbo->AddDepthAttachment(this->DepthTexture);
  vtkOpenGLRenderWindow* renWin =
    static_cast<vtkOpenGLRenderWindow*>(s->GetRenderer()->GetRenderWindow());
  vtkOpenGLState* ostate = renWin->GetState();
  vtkOpenGLState::ScopedglViewport viewport(ostate);
  vtkOpenGLState::ScopedglScissor scissor(ostate);
  ostate->vtkglViewport(this->Viewport[0], this->Viewport[1], this->Viewport[2], this->Viewport[3]);
  ostate->vtkglScissor(this->Viewport[0], this->Viewport[1], this->Viewport[2], this->Viewport[3]);
  vtkRenderer* renderer = s->GetRenderer();
  vtkOpenGLRenderer* glRenderer = vtkOpenGLRenderer::SafeDownCast(renderer);
  vtkRenderState forward(renderer);
  forward.SetPropArrayAndCount(s->GetPropArray(), s->GetPropArrayCount());
  forward.SetFrameBuffer(fbo);
  auto render = [&](vtkRenderPass* pass) {
    if (pass)
    {
      pass->Render(&forward);
      this->NumberOfRenderedProps += pass->GetNumberOfRenderedProps();
    }
  };

  // Translucent polygonal geometry. The stock vtkTranslucentPass of a
  // vtkRenderStepsPass blends in draw order and ignores the renderer's depth
  // peeling settings; without passes, vtkOpenGLRenderer draws translucency
  // order-independently, or with (dual) depth peeling when asked
  // (SetUseDepthPeeling, also for volumes). MRGI lets the renderer do exactly
  // that, so translucent props look as they do without MRGI. A translucent
  // pass the application set on the vtkRenderStepsPass is used as it is.
  vtkRenderPass* translucent = steps->GetTranslucentPass();
  bool volumesPeeled = false;
  if (translucent && glRenderer && std::strcmp(translucent->GetClassName(), "vtkTranslucentPass") == 0)
  {
    // The renderer's own test (vtkOpenGLRenderer::UpdateGeometry).
    bool translucentGeometry =
      renderer->GetUseDepthPeeling() && renderer->GetUseDepthPeelingForVolumes();
    for (int i = 0; !translucentGeometry && i < s->GetPropArrayCount(); ++i)
    {
      translucentGeometry = s->GetPropArray()[i]->HasTranslucentPolygonalGeometry() != 0;
    }
    if (translucentGeometry)
    {
      // No framebuffer argument: "the one bound now" (MRGI's), drawn in the
      // renderer's viewport, as the renderer does without passes.
      glRenderer->DeviceRenderTranslucentPolygonalGeometry(nullptr);
      // Dual depth peeling drew the volumes too (the renderer switches this
      // off when dual depth peeling is unsupported).
      volumesPeeled = renderer->GetUseDepthPeeling() && renderer->GetUseDepthPeelingForVolumes();
    }
  }
  else
  {
    render(translucent);
  }

  // FXAA (renderer->UseFXAAOn()): VTK 9.1 applies it only when a renderer has
  // no pass, after translucent geometry and before volumes and overlays
  // (text is antialiased already). MRGI does the same at the same point, on
  // its colour buffer (FXAA works on 8-bit colour: values above 1 are clamped
  // there). The filter and its buffers live as long as the pass's resources.
  if (glRenderer && renderer->GetUseFXAA())
  {
    if (!this->FXAAFilter)
    {
      this->FXAAFilter = vtkOpenGLFXAAFilter::New();
    }
    if (renderer->GetFXAAOptions())
    {
      this->FXAAFilter->UpdateConfiguration(renderer->GetFXAAOptions());
    }
    this->FXAAFilter->Execute(glRenderer);
  }

  if (!volumesPeeled)
  {
    render(steps->GetVolumetricPass());
  }
  render(steps->GetOverlayPass());
  fbo->UnBind();
  fbo->RestorePreviousBindingsAndBuffers();
}

//------------------------------------------------------------------------------
void vtkMRGIPass::RenderGather(vtkOpenGLRenderWindow* renWin, vtkRenderer* renderer, int vplCount)
{
  static const std::string body = std::string(vtkMRGIVPLIrradiance) + vtkMRGIGatherFS;
  vtkShaderProgram* program = ReadyQuad(this->GatherQuad, renWin, body.c_str());
  if (!program)
  {
    vtkErrorMacro("could not build the MRGI gather shader");
    return;
  }
  // Eye -> world: the inverse of the camera's view matrix.
  vtkNew<vtkMatrix4x4> viewToWorld;
  vtkMatrix4x4::Invert(renderer->GetActiveCamera()->GetModelViewTransformMatrix(), viewToWorld);
  float m[16];
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      m[c * 4 + r] = static_cast<float>(viewToWorld->GetElement(r, c));
      this->LastViewToWorld[c * 4 + r] = viewToWorld->GetElement(r, c);
    }
  }
  vtkTextureObject* vpls = this->VPLSelection->GetVPLTexture();
  vtkOpenGLFramebufferObject* fbo = this->FrameBuffer;
  ViewportQuadState state(renWin->GetState(), this->Viewport);
  fbo->SaveCurrentBindingsAndBuffers();
  fbo->Bind();
  fbo->RemoveColorAttachments(MRGI_GBUFFER_ATTACHMENTS);
  fbo->AddColorAttachment(0, this->IrradianceTexture);
  fbo->AddColorAttachment(1, this->IndirectTexture);
  fbo->ActivateDrawBuffers(2);
  this->PositionTexture->Activate();
  this->NormalTexture->Activate();
  this->AlbedoTexture->Activate();
  vpls->Activate();
  program->SetUniformi("mrgiPosition", this->PositionTexture->GetTextureUnit());
  program->SetUniformi("mrgiNormal", this->NormalTexture->GetTextureUnit());
  program->SetUniformi("mrgiAlbedo", this->AlbedoTexture->GetTextureUnit());
  program->SetUniformi("mrgiVPLs", vpls->GetTextureUnit());
  program->SetUniformi("mrgiVPLCount", vplCount);
  program->SetUniformf("mrgiStrength", static_cast<float>(this->IndirectStrength));
  program->SetUniformMatrix4x4("mrgiVCToWC", m);
  this->GatherQuad->Render();
  vpls->Deactivate();
  this->AlbedoTexture->Deactivate();
  this->NormalTexture->Deactivate();
  this->PositionTexture->Deactivate();
  fbo->RemoveColorAttachments(2);
  fbo->UnBind();
  fbo->RestorePreviousBindingsAndBuffers();
}

//------------------------------------------------------------------------------
bool vtkMRGIPass::SelectMultiresolution(vtkOpenGLRenderWindow* renWin, vtkRenderer* renderer,
  vtkRenderTimerLog* timer, float viewToWorld[16], bool& parallel)
{
  // Pixel size at depth d for the scale-invariant thresholds (mrgi_multires.h).
  vtkCamera* camera = renderer->GetActiveCamera();
  const mrgi_multires_projection projection = { camera->GetParallelProjection() ? 1 : 0,
    camera->GetViewAngle(), camera->GetParallelScale() };
  parallel = projection.parallel != 0;
  float ab[2];
  mrgi_error err;
  if (mrgi_multires_pixel_size_coefficients(&projection, this->Viewport[3], ab, &err) != MRGI_OK)
  {
    vtkErrorMacro(<< "multiresolution: " << err.message);
    return false;
  }
  vtkNew<vtkMatrix4x4> inverse;
  vtkMatrix4x4::Invert(camera->GetModelViewTransformMatrix(), inverse);
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      viewToWorld[c * 4 + r] = static_cast<float>(inverse->GetElement(r, c));
      this->LastViewToWorld[c * 4 + r] = inverse->GetElement(r, c);
    }
  }
  vtkMRGIMultiresolution* mr = this->Multiresolution;
  mr->SetStageTimer(timer);
  ScopedStage stage(timer, "select");
  const bool ok = mr->Update(renWin, this->PositionTexture, this->NormalTexture, this->Viewport[0],
    this->Viewport[1], this->Viewport[2], this->Viewport[3], ab[0], ab[1]);
  mr->SetStageTimer(nullptr);
  return ok;
}

//------------------------------------------------------------------------------
bool vtkMRGIPass::RenderMultiresolution(
  vtkOpenGLRenderWindow* renWin, vtkRenderer* renderer, int vplCount, vtkRenderTimerLog* timer)
{
  float* m = this->LastViewToWorldFloat;
  if (!this->SelectMultiresolution(renWin, renderer, timer, m, this->LastParallel))
  {
    return false;
  }
  vtkMRGIMultiresolution* mr = this->Multiresolution;
  mr->SetStageTimer(timer);
  struct ClearTimer
  {
    vtkMRGIMultiresolution* Target;
    ~ClearTimer() { this->Target->SetStageTimer(nullptr); }
  } clearTimer{ mr };
  {
    ScopedStage stage(timer, "gather");
    if (!mr->Gather(renWin, this->PositionTexture, this->NormalTexture, this->Viewport[0],
          this->Viewport[1], this->VPLSelection->GetVPLTexture(), vplCount, m))
    {
      return false;
    }
  }
  ScopedStage stage(timer, "upsample");
  return mr->Upsample(renWin, this->UpsampleMode, this->UpsampleMaskWeight) &&
    mr->Resolve(renWin, this->AlbedoTexture, this->PositionTexture, this->NormalTexture,
      this->LastParallel, this->IrradianceTexture, this->IndirectTexture,
      this->Viewport[0], this->Viewport[1], this->IndirectStrength);
}

//------------------------------------------------------------------------------
bool vtkMRGIPass::RenderAreaLights(
  vtkOpenGLRenderWindow* renWin, vtkRenderer* renderer, bool selected, vtkRenderTimerLog* timer)
{
  // nichols-penmatsa-wyman-2010 3.2: the area light's direct light at the
  // multiresolution texels, upsampled like the indirect light. One gather,
  // upsampling and resolve per light, each added to the lights' sum, which
  // is added to the colour once (and read by GetAreaLightBuffer()). Timed as
  // the stage "area" with its steps.
  const std::string signature = this->AreaLightInputs(renWin, renderer);
  if (!signature.empty() && signature == this->AreaLightSignature && this->AreaSumTexture)
  {
    // Nothing the lights' sum depends on changed: add it again.
    ScopedStage stage(timer, "area");
    this->RenderAdd(renWin, this->AreaSumTexture, this->ColorTexture);
    return true;
  }
  this->AreaLightSignature.clear();
  if (!selected &&
    !this->SelectMultiresolution(renWin, renderer, timer, this->LastViewToWorldFloat, this->LastParallel))
  {
    return false;
  }
  ScopedStage stage(timer, "area");
  // Steps: "voxelize", "visibility.pyramid" and "gather.samples" (the
  // gathers; receivers are this frame's, built once).
  this->VisibilityPyramid->SetStageTimer(timer);
  this->Voxelization->SetStageTimer(timer);
  this->Multiresolution->SetStageTimer(timer);
  struct ClearTimers
  {
    vtkMRGIPass* Pass;
    ~ClearTimers()
    {
      this->Pass->VisibilityPyramid->SetStageTimer(nullptr);
      this->Pass->Voxelization->SetStageTimer(nullptr);
      this->Pass->Multiresolution->SetStageTimer(nullptr);
    }
  } clearTimers{ this };
  const int w = this->ColorTexture->GetWidth(), h = this->ColorTexture->GetHeight();
  auto ensure = [&](vtkTextureObject*& t) {
    if (!t)
    {
      t = MakeTexture(renWin, GL_RGBA32F, w, h);
    }
    t->Resize(w, h);
  };
  ensure(this->AreaIrradianceTexture);
  ensure(this->AreaDirectTexture);
  ensure(this->AreaSumTexture);
  {
    // Clear the sum over the viewport.
    vtkOpenGLState* ostate = renWin->GetState();
    ViewportQuadState state(ostate, this->Viewport);
    vtkOpenGLFramebufferObject* fbo = this->FrameBuffer;
    fbo->SaveCurrentBindingsAndBuffers();
    fbo->Bind();
    fbo->RemoveColorAttachments(MRGI_GBUFFER_ATTACHMENTS);
    fbo->AddColorAttachment(0, this->AreaSumTexture);
    fbo->ActivateDrawBuffers(1);
    vtkOpenGLState::ScopedglClearColor clearColor(ostate);
    ostate->vtkglClearColor(0.0, 0.0, 0.0, 0.0);
    ostate->vtkglClear(GL_COLOR_BUFFER_BIT);
    fbo->UnBind();
    fbo->RestorePreviousBindingsAndBuffers();
  }
  // Surface-detail modulation (nichols-wyman-2009 eq. 2) is for indirect
  // light; direct light is resolved without it.
  // Visibility: one voxelization per frame for every light, over the
  // camera's clipping range (VTK fits it to the visible props' bounds: the
  // visible scene's depth range, mrgi_voxel.h section 2).
  vtkMRGIVoxelization* voxels = nullptr;
  if (this->AreaLightVisibility != VisibilityOff)
  {
    double range[2];
    renderer->GetActiveCamera()->GetClippingRange(range);
    if (this->Voxelization->Voxelize(renderer, range[0], range[1]))
    {
      voxels = this->Voxelization;
    }
    else
    {
      vtkErrorMacro("area lights: could not voxelize the scene; drawing them without shadows");
    }
  }
  vtkMRGIMultiresolution* mr = this->Multiresolution;
  const double surfaceDetail = mr->GetSurfaceDetail();
  mr->SetSurfaceDetail(0.0);
  bool drawn = false;
  for (size_t i = 0; i < this->AreaLights.size(); ++i)
  {
    vtkMRGIAreaLight* light = this->AreaLights[i];
    // The light's samples on the GPU, uploaded by the light once per rebuild.
    int count = 0;
    vtkTextureObject* texture = light->GetSampleTexture(renWin, &count);
    mrgi_area_light_uniforms uniforms;
    if (!texture || count < 1 || !light->GetCoreUniforms(&uniforms))
    {
      continue; // the light reported why
    }
    // Incremental visibility: the masks of every level first (they need
    // this selection's receivers), then the gather reads its texel's bits.
    vtkMRGIVisibilityPyramid* masks = nullptr;
    if (voxels && this->AreaLightVisibility == VisibilityIncremental &&
      count <= vtkMRGIVisibilityPyramid::GetMaximumNumberOfSamples())
    {
      double w2v[16];
      float worldToView[16];
      voxels->GetLastWorldToView(w2v);
      std::copy(w2v, w2v + 16, worldToView);
      if (mr->BuildReceivers(renWin, this->PositionTexture, this->NormalTexture, this->Viewport[0],
            this->Viewport[1]) &&
        this->VisibilityPyramid->Update(renWin, mr, voxels, texture, count, uniforms.two_sided != 0,
          worldToView))
      {
        masks = this->VisibilityPyramid;
      }
    }
    if (!mr->GatherAreaLight(renWin, this->PositionTexture, this->NormalTexture, this->Viewport[0],
          this->Viewport[1], texture, count, uniforms, this->LastViewToWorldFloat, voxels, masks) ||
      !mr->Upsample(renWin, this->UpsampleMode, this->UpsampleMaskWeight) ||
      !mr->Resolve(renWin, this->AlbedoTexture, this->PositionTexture, this->NormalTexture,
        this->LastParallel, this->AreaIrradianceTexture, this->AreaDirectTexture, this->Viewport[0],
        this->Viewport[1], 1.0))
    {
      break;
    }
    this->RenderAdd(renWin, this->AreaDirectTexture, this->AreaSumTexture);
    if (this->SpecularCaptured && this->RenderAreaSpecular(renWin, light, voxels, masks, timer))
    {
      this->RenderAdd(renWin, this->AreaDirectTexture, this->AreaSumTexture);
    }
    drawn = true;
  }
  mr->SetSurfaceDetail(surfaceDetail);
  // The lights' sum (what GetAreaLightBuffer() reads) joins the image once.
  if (drawn)
  {
    this->RenderAdd(renWin, this->AreaSumTexture, this->ColorTexture);
    this->AreaLightSignature = signature;
    ++this->NumberOfAreaLightUpdates;
  }
  return drawn;
}

//------------------------------------------------------------------------------
std::string vtkMRGIPass::AreaLightInputs(vtkOpenGLRenderWindow* renWin, vtkRenderer* renderer)
{
  // Everything the area lights' sum is computed from, as modification
  // times: the camera and viewport (the G-buffer), the visible props and
  // their data (an actor's matrix, property, texture, mapper and input;
  // other props' GetRedrawMTime()), each light and its picture (asking for its
  // samples rebuilds them when the picture changed), and the settings of
  // the pass and of its stages. Empty: do not reuse.
  if (!this->AreaLightReuse || this->Multiresolution->GetCollectStatistics() ||
    this->VisibilityPyramid->GetCollectStatistics())
  {
    return std::string();
  }
  std::ostringstream s;
  vtkCamera* camera = renderer->GetActiveCamera();
  s << camera << ':' << camera->GetMTime() << ';' << renderer->GetMTime() << ';';
  for (int k = 0; k < 4; ++k)
  {
    s << this->Viewport[k] << ',';
  }
  s << this->ColorTexture->GetWidth() << 'x' << this->ColorTexture->GetHeight() << ';'
    << this->SpecularCaptured << this->LastParallel << ';' << this->GetMTime() << ','
    << this->Multiresolution->GetMTime() << ',' << this->VisibilityPyramid->GetMTime() << ','
    << this->Voxelization->GetMTime() << ',' << this->VarianceShadowQuery->GetMTime() << ';';
  vtkPropCollection* props = renderer->GetViewProps();
  vtkCollectionSimpleIterator it;
  props->InitTraversal(it);
  while (vtkProp* prop = props->GetNextProp(it))
  {
    if (!prop->GetVisibility())
    {
      continue;
    }
    vtkActor* actor = vtkActor::SafeDownCast(prop);
    if (!actor)
    {
      s << prop << ':' << prop->GetRedrawMTime() << ';';
      continue;
    }
    // An actor by what it draws rather than its own MTime, which VTK's
    // mappers bump when they first give it a shader property (after this
    // frame's signature: the next frame would recompute for nothing).
    s << actor << ':';
    vtkMatrix4x4* matrix = actor->GetMatrix();
    for (int k = 0; k < 16; ++k)
    {
      s << matrix->GetElement(k / 4, k % 4) << ',';
    }
    s << actor->GetProperty()->GetMTime() << ','
      << (actor->GetBackfaceProperty() ? actor->GetBackfaceProperty()->GetMTime() : 0) << ','
      << (actor->GetTexture() ? actor->GetTexture()->GetMTime() : 0) << ',';
    if (vtkMapper* mapper = actor->GetMapper())
    {
      vtkDataObject* input = mapper->GetInputDataObject(0, 0);
      s << mapper->GetMTime() << ',' << (input ? input->GetMTime() : 0);
    }
    s << ';';
  }
  for (vtkMRGIAreaLight* light : this->AreaLights)
  {
    int count = 0;
    light->GetSampleTexture(renWin, &count);
    s << light << ':' << light->GetMTime() << ',' << light->GetNumberOfTextureBuilds() << ','
      << light->GetNumberOfSampleBuilds() << ';';
  }
  return s.str();
}

//------------------------------------------------------------------------------
bool vtkMRGIPass::RenderAreaSpecular(vtkOpenGLRenderWindow* renWin, vtkMRGIAreaLight* light,
  vtkMRGIVoxelization* voxels, vtkMRGIVisibilityPyramid* masks, vtkRenderTimerLog* timer)
{
  // nichols-penmatsa-wyman-2010 3.2.1 (the highlight, its own pass) and
  // 3.3.3 (its shadows): with visibility, each sample's term of a glossy
  // lobe counts where the sample is visible (the level-0 bit of the
  // incremental masks, or a march per sample: the naive query, in batches
  // that fit llvmpipe's loop budget), and each lobe-grid cell of a sharp
  // lobe is weighted by the variance shadow query (its moments pass first).
  vtkMRGIShaderUtilities::ScopedStage step(timer, "specular");
  bool shadowed = voxels != nullptr;
  if (shadowed)
  {
    this->VarianceShadowQuery->SetStageTimer(timer);
    shadowed = this->VarianceShadowQuery->ComputeMoments(renWin, this->PositionTexture,
      this->NormalTexture, this->SpecularTexture, this->ShininessTexture, this->Viewport, light,
      voxels, this->LastViewToWorldFloat, this->LastParallel);
    this->VarianceShadowQuery->SetStageTimer(nullptr);
    if (!shadowed)
    {
      vtkErrorMacro("area lights: no variance shadow query; drawing the highlights without shadows");
    }
  }
  if (this->AreaLightSpecularResolution == SpecularMultiresolution)
  {
    return this->RenderAreaSpecularMultiresolution(renWin, light, voxels, masks, shadowed);
  }
  const bool masked = shadowed && masks != nullptr;
  const bool marched = shadowed && !masked;
  static const std::string unshadowedBody = std::string(vtkMRGIVPLIrradiance) +
    vtkMRGIAreaLight::GetShaderSource(true, true) + vtkMRGIAreaSpecularFS;
  static const std::string maskedBody =
    std::string("#define MRGI_AREA_SPECULAR_VISIBILITY 1\n#define MRGI_AREA_SPECULAR_MASKS 1\n") +
    vtkMRGIVPLIrradiance + vtkMRGIVarianceShadowQuery::GetResolveShaderSource() +
    vtkMRGIAreaLight::GetShaderSource(true, true) + vtkMRGIAreaSpecularFS;
  static const std::string marchedBody =
    std::string("#define MRGI_AREA_SPECULAR_VISIBILITY 1\n#define MRGI_AREA_SPECULAR_BATCHES 1\n") +
    vtkMRGIVoxelization::GetMarchShaderSource() + vtkMRGIVPLIrradiance +
    vtkMRGIVarianceShadowQuery::GetResolveShaderSource() +
    vtkMRGIAreaLight::GetShaderSource(true, true) + vtkMRGIAreaSpecularFS;
  vtkShaderProgram* program = masked
    ? ReadyQuad(this->SpecularMaskedQuad, renWin, maskedBody.c_str())
    : marched ? ReadyQuad(this->SpecularMarchedQuad, renWin, marchedBody.c_str())
              : ReadyQuad(this->SpecularQuad, renWin, unshadowedBody.c_str());
  vtkOpenGLQuadHelper* quad =
    masked ? this->SpecularMaskedQuad : (marched ? this->SpecularMarchedQuad : this->SpecularQuad);
  if (!program)
  {
    vtkErrorMacro("could not build the area-light specular shader");
    return false;
  }
  int sampleCount = 0;
  if (!light->SetShaderUniforms(program, renWin) || !light->GetSampleTexture(renWin, &sampleCount))
  {
    return false;
  }
  // Texture units: the G-buffer's 4, the light's 2, and with shadows the
  // moments' 3 and the masks' (up to 4) or the voxels (1): 13 at most.
  std::vector<vtkTextureObject*> active;
  if (shadowed)
  {
    const int origin[2] = { this->Viewport[0], this->Viewport[1] };
    program->SetUniform2i("mrgiViewportOrigin", origin);
    this->VarianceShadowQuery->SetResolveUniforms(program);
    if (masked)
    {
      // Level 0 of the pyramid is the viewport at full resolution; missing
      // words (fewer than 384 samples) read the first texture: their bits
      // are never asked for.
      vtkTextureObject* first = masks->GetMaskTexture(0, 0);
      first->Activate();
      active.push_back(first);
      for (int w = 0; w < 4; ++w)
      {
        vtkTextureObject* t = masks->GetMaskTexture(0, w);
        if (t && t != first)
        {
          t->Activate();
          active.push_back(t);
        }
        program->SetUniformi(("mrgiVisibilityMask" + std::to_string(w)).c_str(),
          (t ? t : first)->GetTextureUnit());
      }
    }
    else
    {
      double w2v[16];
      voxels->GetLastWorldToView(w2v);
      float worldToView[16];
      std::copy(w2v, w2v + 16, worldToView);
      program->SetUniformMatrix4x4("mrgiWCToVC", worldToView);
      if (!voxels->SetMarchUniforms(program))
      {
        this->VarianceShadowQuery->DeactivateTextures();
        light->DeactivateTextures();
        return false;
      }
      active.push_back(voxels->GetVoxelTexture());
    }
  }
  vtkOpenGLFramebufferObject* fbo = this->FrameBuffer;
  vtkOpenGLState* ostate = renWin->GetState();
  ViewportQuadState state(ostate, this->Viewport);
  vtkOpenGLState::ScopedglBlendFuncSeparate blendFunc(ostate);
  fbo->SaveCurrentBindingsAndBuffers();
  fbo->Bind();
  fbo->RemoveColorAttachments(MRGI_GBUFFER_ATTACHMENTS);
  fbo->AddColorAttachment(0, this->AreaDirectTexture);
  fbo->ActivateDrawBuffers(1);
  vtkTextureObject* inputs[4] = { this->PositionTexture, this->NormalTexture, this->SpecularTexture,
    this->ShininessTexture };
  const char* names[4] = { "mrgiPosition", "mrgiNormal", "mrgiSpecular", "mrgiShininess" };
  for (int k = 0; k < 4; ++k)
  {
    inputs[k]->Activate();
    program->SetUniformi(names[k], inputs[k]->GetTextureUnit());
  }
  program->SetUniformMatrix4x4("mrgiVCToWC", this->LastViewToWorldFloat);
  program->SetUniformi("mrgiParallel", this->LastParallel ? 1 : 0);
  if (marched)
  {
    // One march per sample and pixel can run past the loop iterations
    // llvmpipe gives one invocation (mrgi_voxel_march.h): batches of
    // samples, one draw each, added to the first.
    RenderSampleBatches(ostate, program, quad, sampleCount,
      mrgi_voxel_samples_per_batch(voxels->GetMaxSteps()));
  }
  else
  {
    quad->Render();
  }
  for (vtkTextureObject* t : inputs)
  {
    t->Deactivate();
  }
  for (vtkTextureObject* t : active)
  {
    t->Deactivate();
  }
  if (shadowed)
  {
    this->VarianceShadowQuery->DeactivateTextures();
  }
  light->DeactivateTextures();
  fbo->UnBind();
  fbo->RestorePreviousBindingsAndBuffers();
  return true;
}

//------------------------------------------------------------------------------
bool vtkMRGIPass::RenderAreaSpecularMultiresolution(vtkOpenGLRenderWindow* renWin,
  vtkMRGIAreaLight* light, vtkMRGIVoxelization* voxels, vtkMRGIVisibilityPyramid* masks,
  bool shadowed)
{
  // nichols-penmatsa-wyman-2010 3.2.1: the highlight gathered at the texels
  // of the specular stencil (this frame's multiresolution selection plus
  // the lobe-size metric, texels without specular material skipped;
  // mrgi_specular_stencil.h), then upsampled and resolved like the diffuse
  // term, the resolve's "albedo" being k_s c_s. Shadows (3.3.3): the
  // sample path reads the level's incremental masks (3.3.2, every level
  // has them) or marches at the texel's receiver (naive visibility, in
  // batches); the lobe grid reads the variance shadow query at the
  // footprint's centre pixel.
  vtkMRGIMultiresolution* mr = this->Multiresolution;
  mrgi_area_light_uniforms uniforms;
  mrgi_multires_layout layout;
  int sampleCount = 0;
  if (!light->GetCoreUniforms(&uniforms) || !light->GetSampleTexture(renWin, &sampleCount) ||
    !mr->GetLayout(&layout) ||
    !mr->BuildSpecularStencil(renWin, this->PositionTexture, this->NormalTexture,
      this->SpecularTexture, this->ShininessTexture, this->Viewport[0], this->Viewport[1], uniforms,
      this->LastViewToWorldFloat, this->LastParallel))
  {
    return false;
  }
  const bool masked = shadowed && masks != nullptr &&
    masks->GetNumberOfLevels() == layout.level_count;
  const bool marched = shadowed && !masked;
  static const std::string prefix = "#define MRGI_AREA_SPECULAR_MULTIRES 1\n";
  static const std::string unshadowedBody = prefix + vtkMRGIVPLIrradiance +
    vtkMRGIAreaLight::GetShaderSource(true, true) + vtkMRGIAreaSpecularFS;
  static const std::string maskedBody = prefix +
    "#define MRGI_AREA_SPECULAR_VISIBILITY 1\n#define MRGI_AREA_SPECULAR_MASKS 1\n" +
    vtkMRGIVPLIrradiance + vtkMRGIVarianceShadowQuery::GetResolveShaderSource() +
    vtkMRGIAreaLight::GetShaderSource(true, true) + vtkMRGIAreaSpecularFS;
  static const std::string marchedBody = prefix +
    "#define MRGI_AREA_SPECULAR_VISIBILITY 1\n#define MRGI_AREA_SPECULAR_BATCHES 1\n" +
    vtkMRGIVoxelization::GetMarchShaderSource() + vtkMRGIVPLIrradiance +
    vtkMRGIVarianceShadowQuery::GetResolveShaderSource() +
    vtkMRGIAreaLight::GetShaderSource(true, true) + vtkMRGIAreaSpecularFS;
  vtkShaderProgram* program = masked
    ? ReadyQuad(this->SpecularMultiresMaskedQuad, renWin, maskedBody.c_str())
    : marched ? ReadyQuad(this->SpecularMultiresMarchedQuad, renWin, marchedBody.c_str())
              : ReadyQuad(this->SpecularMultiresQuad, renWin, unshadowedBody.c_str());
  vtkOpenGLQuadHelper* quad = masked ? this->SpecularMultiresMaskedQuad
    : (marched ? this->SpecularMultiresMarchedQuad : this->SpecularMultiresQuad);
  if (!program || !light->SetShaderUniforms(program, renWin))
  {
    vtkErrorMacro("could not build the multiresolution area-light specular shader");
    return false;
  }
  // Texture units: receivers 2, material 1, the light's 2, and with shadows
  // the moments' 3 and the masks' (up to 4) or the voxels (1): 12 at most.
  std::vector<vtkTextureObject*> active;
  bool ok = true;
  if (shadowed)
  {
    const int size[2] = { this->Viewport[2], this->Viewport[3] };
    program->SetUniform2i("mrgiViewportSize", size);
    this->VarianceShadowQuery->SetResolveUniforms(program);
    if (marched)
    {
      double w2v[16];
      voxels->GetLastWorldToView(w2v);
      float worldToView[16];
      std::copy(w2v, w2v + 16, worldToView);
      program->SetUniformMatrix4x4("mrgiWCToVC", worldToView);
      ok = voxels->SetMarchUniforms(program);
      active.push_back(voxels->GetVoxelTexture());
    }
  }
  program->SetUniformMatrix4x4("mrgiVCToWC", this->LastViewToWorldFloat);
  program->SetUniformi("mrgiParallel", this->LastParallel ? 1 : 0);
  const int batch = marched ? mrgi_voxel_samples_per_batch(voxels->GetMaxSteps()) : sampleCount;
  auto draw = [&](int level) -> bool {
    std::vector<vtkTextureObject*> levelMasks;
    if (masked)
    {
      // The level's masks, level-local texels (as the diffuse gather's).
      vtkTextureObject* first = masks->GetMaskTexture(level, 0);
      if (!first)
      {
        return false;
      }
      first->Activate();
      levelMasks.push_back(first);
      for (int w = 0; w < 4; ++w)
      {
        vtkTextureObject* t = masks->GetMaskTexture(level, w);
        if (t && t != first)
        {
          t->Activate();
          levelMasks.push_back(t);
        }
        program->SetUniformi(("mrgiVisibilityMask" + std::to_string(w)).c_str(),
          (t ? t : first)->GetTextureUnit());
      }
    }
    if (shadowed)
    {
      const int origin[2] = { layout.level_offset[level], 0 };
      program->SetUniform2i("mrgiViewportOrigin", origin);
    }
    if (marched)
    {
      RenderSampleBatches(renWin->GetState(), program, quad, sampleCount, batch);
    }
    else
    {
      quad->Render();
    }
    for (vtkTextureObject* t : levelMasks)
    {
      t->Deactivate();
    }
    return true;
  };
  ok = ok &&
    mr->GatherAreaSpecular(renWin, this->PositionTexture, this->NormalTexture, this->Viewport[0],
      this->Viewport[1], program, draw);
  for (vtkTextureObject* t : active)
  {
    t->Deactivate();
  }
  if (shadowed)
  {
    this->VarianceShadowQuery->DeactivateTextures();
  }
  light->DeactivateTextures();
  // Upsampled S times each pixel's k_s c_s (the resolve's albedo) into
  // AreaDirectTexture; the irradiance output is scratch.
  return ok && mr->Upsample(renWin, this->UpsampleMode, this->UpsampleMaskWeight) &&
    mr->Resolve(renWin, this->SpecularTexture, this->PositionTexture, this->NormalTexture,
      this->LastParallel, this->AreaIrradianceTexture, this->AreaDirectTexture, this->Viewport[0],
      this->Viewport[1], 1.0);
}

//------------------------------------------------------------------------------
void vtkMRGIPass::RenderAddIndirect(vtkOpenGLRenderWindow* renWin)
{
  this->RenderAdd(renWin, this->IndirectTexture, this->ColorTexture);
}

//------------------------------------------------------------------------------
void vtkMRGIPass::RenderAdd(vtkOpenGLRenderWindow* renWin, vtkTextureObject* source, vtkTextureObject* target)
{
  vtkShaderProgram* program = ReadyQuad(this->AddQuad, renWin, vtkMRGIAddIndirectFS);
  if (!program)
  {
    vtkErrorMacro("could not build the MRGI composite shader");
    return;
  }
  vtkOpenGLFramebufferObject* fbo = this->FrameBuffer;
  vtkOpenGLState* ostate = renWin->GetState();
  ViewportQuadState state(ostate, this->Viewport);
  vtkOpenGLState::ScopedglBlendFuncSeparate blendFunc(ostate);
  ostate->vtkglEnable(GL_BLEND);
  ostate->vtkglBlendFuncSeparate(GL_ONE, GL_ONE, GL_ZERO, GL_ONE);
  fbo->SaveCurrentBindingsAndBuffers();
  fbo->Bind();
  fbo->RemoveColorAttachments(MRGI_GBUFFER_ATTACHMENTS);
  fbo->AddColorAttachment(0, target);
  fbo->ActivateDrawBuffers(1);
  source->Activate();
  program->SetUniformi("mrgiIndirect", source->GetTextureUnit());
  this->AddQuad->Render();
  source->Deactivate();
  fbo->UnBind();
  fbo->RestorePreviousBindingsAndBuffers();
}

//------------------------------------------------------------------------------
void vtkMRGIPass::RenderOutput(vtkOpenGLRenderWindow* renWin)
{
  vtkShaderProgram* program = ReadyQuad(this->OutputQuad, renWin, vtkMRGICompositeFS);
  if (!program)
  {
    vtkErrorMacro("could not build the MRGI output shader");
    return;
  }
  vtkOpenGLState* ostate = renWin->GetState();
  ViewportQuadState state(ostate, this->Viewport);
  vtkOpenGLState::ScopedglDepthFunc depthFunc(ostate);
  vtkOpenGLState::ScopedglDepthMask depthMask(ostate);
  ostate->vtkglEnable(GL_DEPTH_TEST); // writes the scene's depth (GL_ALWAYS)
  ostate->vtkglDepthFunc(GL_ALWAYS);
  ostate->vtkglDepthMask(GL_TRUE);
  this->ColorTexture->Activate();
  this->DepthTexture->Activate();
  program->SetUniformi("mrgiColor", this->ColorTexture->GetTextureUnit());
  program->SetUniformi("mrgiDepth", this->DepthTexture->GetTextureUnit());
  this->OutputQuad->Render();
  this->DepthTexture->Deactivate();
  this->ColorTexture->Deactivate();
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
      vtkNew<vtkMRGISelectionPass> select;
      if (steps->GetLightsPass())
      {
        passes->AddItem(steps->GetLightsPass());
      }
      passes->AddItem(select);
      this->OpaqueSequence->SetPasses(passes);
      RenderCameraWith(steps->GetCameraPass(), this->OpaqueSequence, s);
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
  const bool indirect = this->IndirectMode != IndirectOff && this->GetNumberOfVPLs() > 0;
  const bool capture = indirect || !this->AreaLights.empty();
  const bool split = vtkRenderStepsPass::SafeDownCast(this->DelegatePass) != nullptr;
  vtkRenderTimerLog* timer = TimerFor(renderer, this->StageTimingEnabled);
  this->IndirectComputed = false;
  this->AreaLightsComputed = false;
  this->Captured = capture;
  // The specular pass cannot change the image when no visible prop has a
  // specular material: then neither it nor its G-buffer targets run.
  this->SpecularCaptured = capture && !this->AreaLights.empty() && this->AreaLightSpecular &&
    AnySpecularProp(renderer);

  this->PrepareBuffers(renWin, x + w, y + h, capture);
  this->BufferSize[0] = w;
  this->BufferSize[1] = h;
  {
    ScopedStage stage(timer, "scene");
    this->RenderScene(s, capture, split);
  }
  bool selected = false; // this frame's multiresolution selection exists
  if (indirect)
  {
    int vplCount = 0;
    {
      ScopedStage stage(timer, "rsm");
      this->RSMPass->Render(s);
    }
    {
      ScopedStage stage(timer, "vpl");
      vplCount = this->VPLSelection->Update(renWin, this->RSMPass);
    }
    if (vplCount > 0)
    {
      bool gathered = true;
      if (this->IndirectMode == IndirectMultires)
      {
        gathered = this->RenderMultiresolution(renWin, renderer, vplCount, timer);
        selected = gathered;
      }
      else
      {
        ScopedStage stage(timer, "gather");
        this->RenderGather(renWin, renderer, vplCount);
      }
      if (gathered)
      {
        ScopedStage stage(timer, "add");
        this->RenderAddIndirect(renWin);
        this->IndirectComputed = true;
      }
    }
  }
  if (!this->AreaLights.empty())
  {
    this->AreaLightsComputed = this->RenderAreaLights(renWin, renderer, selected, timer);
  }
  if (split)
  {
    ScopedStage stage(timer, "forward");
    this->RenderForward(s);
  }
  {
    ScopedStage stage(timer, "output");
    this->RenderOutput(renWin);
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
    vtkMRGIShaderUtilities::InsertCapture(
      fragmentShader, phong ? "#define MRGI_SPECULAR_MATERIAL 1\n" : "", vtkMRGIGBufferCapture);
  }
  else
  {
    // Unlit or normal-less geometry: the G-buffer says "nothing here".
    vtkMRGIShaderUtilities::InsertCapture(fragmentShader, "",
      "  gl_FragData[MRGI_GBUFFER_POSITION] = vec4(0.0);\n"
      "  gl_FragData[MRGI_GBUFFER_NORMAL] = vec4(0.0);\n"
      "  gl_FragData[MRGI_GBUFFER_ALBEDO] = vec4(0.0);\n"
      "  gl_FragData[MRGI_GBUFFER_SPECULAR] = vec4(0.0);\n"
      "  gl_FragData[MRGI_GBUFFER_SHININESS] = vec4(0.0);\n");
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
  bool found = false;
  std::vector<std::string> names;
  std::vector<double> times;
  while (timer->FrameReady())
  {
    vtkRenderTimerLog::Frame frame = timer->PopFirstReadyFrame();
    std::vector<std::string> frameNames;
    std::vector<double> frameTimes;
    for (const auto& event : frame.Events)
    {
      CollectStages(event, frameNames, frameTimes);
    }
    if (!frameNames.empty())
    {
      names.swap(frameNames);
      times.swap(frameTimes);
      found = true;
    }
  }
  if (found)
  {
    this->StageNames.swap(names);
    this->StageTimes.swap(times);
  }
  return found ? this->GetNumberOfStages() : 0;
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
  std::vector<float> rgba;
  if (!vtkMRGIShaderUtilities::ReadTextureRGBA(renWin, texture, rgba))
  {
    vtkErrorMacro("reading the " << what << " buffer back failed");
    return false;
  }
  const int fullWidth = static_cast<int>(texture->GetWidth());
  const int x0 = this->Viewport[0], y0 = this->Viewport[1];
  const int w = this->Viewport[2], h = this->Viewport[3];
  image->SetDimensions(w, h, 1);
  image->AllocateScalars(VTK_FLOAT, components);
  float* out = vtkFloatArray::SafeDownCast(image->GetPointData()->GetScalars())->GetPointer(0);
  for (int y = 0; y < h; ++y)
  {
    for (int x = 0; x < w; ++x)
    {
      const float* src = rgba.data() + 4 * (static_cast<size_t>(y + y0) * fullWidth + (x + x0));
      for (int c = 0; c < components; ++c)
      {
        out[(static_cast<size_t>(y) * w + x) * components + c] = src[c];
      }
    }
  }
  image->GetPointData()->GetScalars()->SetName(what);
  return true;
}

bool vtkMRGIPass::GetColorBuffer(vtkRenderWindow* window, vtkImageData* image)
{
  return this->ReadViewport(window, this->ColorTexture, 4, image, "HDRColor");
}

bool vtkMRGIPass::GetIndirectBuffer(vtkRenderWindow* window, vtkImageData* image)
{
  return this->ReadViewport(
    window, this->IndirectComputed ? this->IndirectTexture : nullptr, 3, image, "Indirect");
}

bool vtkMRGIPass::GetAreaLightBuffer(vtkRenderWindow* window, vtkImageData* image)
{
  return this->ReadViewport(
    window, this->AreaLightsComputed ? this->AreaSumTexture : nullptr, 3, image, "Area light");
}

bool vtkMRGIPass::GetIrradianceBuffer(vtkRenderWindow* window, vtkImageData* image)
{
  return this->ReadViewport(
    window, this->IndirectComputed ? this->IrradianceTexture : nullptr, 3, image, "Irradiance");
}

bool vtkMRGIPass::GetGBuffer(
  vtkRenderWindow* window, vtkImageData* position, vtkImageData* normal, vtkImageData* albedo)
{
  const bool captured = this->PositionTexture && this->Captured;
  return this->ReadViewport(window, captured ? this->PositionTexture : nullptr, 4, position, "Position") &&
    this->ReadViewport(window, captured ? this->NormalTexture : nullptr, 4, normal, "Normal") &&
    this->ReadViewport(window, captured ? this->AlbedoTexture : nullptr, 4, albedo, "Albedo");
}

bool vtkMRGIPass::GetSpecularGBuffer(vtkRenderWindow* window, vtkImageData* specular, vtkImageData* shininess)
{
  const bool captured = this->SpecularTexture && this->SpecularCaptured;
  return this->ReadViewport(window, captured ? this->SpecularTexture : nullptr, 4, specular, "Specular") &&
    this->ReadViewport(window, captured ? this->ShininessTexture : nullptr, 4, shininess, "Shininess");
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
void vtkMRGIPass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "IndirectMode: "
     << (this->IndirectMode == IndirectOff ? "Off" : this->IndirectMode == IndirectFull ? "Full" : "Multires")
     << "\n";
  os << indent << "UpsampleMode: " << this->UpsampleMode << "\n";
  os << indent << "UpsampleMaskWeight: " << this->UpsampleMaskWeight << "\n";
  os << indent << "IndirectStrength: " << this->IndirectStrength << "\n";
  os << indent << "NumberOfVPLs: " << this->VPLSelection->GetNumberOfVPLs() << "\n";
  os << indent << "VPLSelectionMode: " << this->VPLSelection->GetMode() << "\n";
  os << indent << "RSMResolution: " << this->RSMPass->GetResolution() << "\n";
  os << indent << "StageTimingEnabled: " << (this->StageTimingEnabled ? "On" : "Off") << "\n";
  os << indent << "AreaLights: " << this->AreaLights.size() << "\n";
  os << indent << "AreaLightVisibility: "
     << (this->AreaLightVisibility == VisibilityIncremental ? "Incremental"
          : this->AreaLightVisibility == VisibilityNaive    ? "Naive"
                                                            : "Off")
     << "\n";
  os << indent << "AreaLightSpecular: " << (this->AreaLightSpecular ? "On" : "Off") << "\n";
  os << indent << "AreaLightSpecularResolution: "
     << (this->AreaLightSpecularResolution == SpecularMultiresolution ? "Multiresolution" : "FullResolution")
     << "\n";
  os << indent << "Voxelization:\n";
  this->Voxelization->PrintSelf(os, indent.GetNextIndent());
  os << indent << "VisibilityPyramid:\n";
  this->VisibilityPyramid->PrintSelf(os, indent.GetNextIndent());
  os << indent << "AreaLightReuse: " << (this->AreaLightReuse ? "On" : "Off") << "\n";
  os << indent << "NumberOfAreaLightUpdates: " << this->NumberOfAreaLightUpdates << "\n";
  os << indent << "VarianceShadowQuery:\n";
  this->VarianceShadowQuery->PrintSelf(os, indent.GetNextIndent());
  os << indent << "BufferSize: " << this->BufferSize[0] << " x " << this->BufferSize[1] << "\n";
  for (int i = 0; i < this->GetNumberOfStages(); ++i)
  {
    os << indent << "Stage " << this->GetStageName(i) << ": " << this->GetStageTimeMilliseconds(i)
       << " ms\n";
  }
}
