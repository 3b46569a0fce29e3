#include "vtk_glew.h"

#include "vtkMRGIPass.h"

#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkCommand.h"
#include "vtkCameraPass.h"
#include "vtkDataArray.h"
#include "vtkHardwareSelector.h"
#include "vtkImageData.h"
#include "vtkMRGIAreaLightStage.h"
#include "vtkMRGIFrameContext.h"
#include "vtkMRGIFullScreenStep.h"
#include "vtkMRGIGBuffer.h"
#include "vtkMRGIGather.h"
#include "vtkMRGIImperfectShadowMaps.h"
#include "vtkMRGIIndirectLight.h"
#include "vtkMRGIMultiresolution.h"
#include "vtkMRGIOutput.h"
#include "vtkMRGIProgramCache.h"
#include "vtkMRGIReflectiveShadowMapPass.h"
#include "vtkMRGIRenderSteps.h"
#include "vtkMRGISceneChecks.h"
#include "vtkMRGISSAO.h"
#include "vtkMRGISSGI.h"
#include "vtkMRGIShaderUtilities.h"
#include "vtkMRGIShadowedDirectLight.h"
#include "vtkMRGIUpsample.h"
#include "vtkMRGIVPLSelection.h"
#include "vtkMatrix4x4.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLError.h"
#include "vtkOpenGLFXAAFilter.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLPolyDataMapper.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLRenderer.h"
#include "vtkOpenGLState.h"
#include "vtkOutputWindow.h"
#include "vtkPointData.h"
#include "vtkProp.h"
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

#include "vtkMRGIGBufferCapture.h"

#include "mrgi_buffers.h"
#include "mrgi_exposure.h"
#include "mrgi_screen_space_preset.h"
#include "mrgi_ssao.h"
#include "mrgi_ssgi.h"
#include "mrgi_multires.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkMRGIPass);

namespace
{
using vtkMRGIShaderUtilities::ScopedStage;

// A step's errors and warnings are the pass's: observers of the pass (an
// application's, ParaView's) receive them; without one they are printed,
// as vtkErrorMacro does.
void ReportAsPass(vtkObject*, unsigned long event, void* pass, void* text)
{
  vtkObject* self = static_cast<vtkObject*>(pass);
  if (self->HasObserver(event))
  {
    self->InvokeEvent(event, text);
  }
  else if (event == vtkCommand::ErrorEvent)
  {
    vtkOutputWindowDisplayErrorText(static_cast<const char*>(text));
  }
  else
  {
    vtkOutputWindowDisplayWarningText(static_cast<const char*>(text));
  }
}
}

struct vtkMRGIPass::Internals
{
  vtkMRGIGBuffer GBuffer;
  // The add and the output programs.
  vtkMRGIProgramCache Programs;
  // A stage that fails (e.g. a buffer larger than GL_MAX_TEXTURE_SIZE) fails
  // every frame: the pass says so once, until the light is computed again.
  bool IndirectFailureReported = false;
  bool AreaLightFailureReported = false;
  // Actors already warned about as point clouds drawn as pixels (once each).
  std::vector<vtkWeakPointer<vtkProp>> PointCloudsReported;
};

//------------------------------------------------------------------------------
vtkMRGIPass::vtkMRGIPass()
  : SSAOKernelSize(MRGI_SSAO_DEFAULT_KERNEL_SIZE)
  , SSAORadius(MRGI_SSAO_DEFAULT_RADIUS)
  , SSAOBias(MRGI_SSAO_DEFAULT_BIAS)
  , SSGISamples(MRGI_SSGI_DEFAULT_SAMPLES)
  , SSGIRadius(MRGI_SSGI_DEFAULT_RADIUS)
  , SSGIBias(MRGI_SSGI_DEFAULT_BIAS)
  , AutoExposureKey(MRGI_EXPOSURE_KEY)
  , Internal(new Internals)
{
  this->RSMPass = vtkMRGIReflectiveShadowMapPass::New();
  this->Multiresolution = vtkMRGIMultiresolution::New();
  this->IndirectLight = vtkMRGIIndirectLight::New();
  this->SSAOStage = vtkMRGISSAO::New();
  this->SSGIStage = vtkMRGISSGI::New();
  this->AreaLightStage = vtkMRGIAreaLightStage::New();
  this->DirectLight = vtkMRGIShadowedDirectLight::New();
  vtkNew<vtkCallbackCommand> report;
  report->SetCallback(ReportAsPass);
  report->SetClientData(this);
  this->DirectLight->AddObserver(vtkCommand::ErrorEvent, report);
  this->DirectLight->AddObserver(vtkCommand::WarningEvent, report);
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
  this->Multiresolution->Delete();
  this->IndirectLight->Delete();
  this->SSAOStage->Delete();
  this->SSGIStage->Delete();
  this->AreaLightStage->Delete();
  this->DirectLight->Delete();
  this->OpaqueSequence->Delete();
}

//------------------------------------------------------------------------------
void vtkMRGIPass::ReleaseGraphicsResources(vtkWindow* w)
{
  this->Superclass::ReleaseGraphicsResources(w);
  this->RSMPass->ReleaseGraphicsResources(w);
  this->Multiresolution->ReleaseGraphicsResources(w);
  this->IndirectLight->ReleaseGraphicsResources(w);
  this->SSAOStage->ReleaseGraphicsResources(w);
  this->SSGIStage->ReleaseGraphicsResources(w);
  this->AreaLightStage->ReleaseGraphicsResources(w);
  this->DirectLight->ReleaseGraphicsResources(w);
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
  // The frame budget's settings for this frame, and its wall time (vtkMRGIFrameBudget.h).
  const vtkMRGIFrameBudget::FrameScope budgetScope(
    this->FrameBudgetTuner, renderer, this->FrameBudgetKnobs());
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
  const vtkMRGIShadowedDirectLight::Lights shadowLights = this->DirectShadows != DirectShadowsOff
    ? this->DirectLight->AssignLights(renderer)
    : vtkMRGIShadowedDirectLight::Lights();
  const bool shadows = shadowLights.Casting > 0;
  const bool capture = indirect || areaLights || this->OuterGBuffer || shadows || this->SSAO ||
    this->SSGI;
  const bool split = vtkRenderStepsPass::SafeDownCast(this->DelegatePass) != nullptr;
  vtkRenderTimerLog* timer = vtkMRGIShaderUtilities::StageTimer(renderer, this->StageTimingEnabled);
  this->IndirectComputed = false;
  this->AreaLightsComputed = false;
  this->Captured = capture;
  this->ShadowsCaptured = shadows;
  this->ShadowsComputed = false;
  // The specular pass cannot change the image when no visible prop has a
  // specular material: then neither it nor its G-buffer targets run.
  this->SpecularCaptured =
    capture && areaLights && this->AreaLightStage->GetSpecular() && vtkMRGISceneChecks::AnySpecularProp(renderer);

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
    vtkMRGISceneChecks::WarnPointClouds(this, renderer, in.PointCloudsReported);
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
    // Area lights bounce with the vtkLights (their maps are no shadow maps:
    // only when the indirect light needs them).
    std::vector<vtkMRGIAreaLight*> bouncing;
    if (indirect && this->AreaLightIndirect)
    {
      for (int i = 0; i < this->AreaLightStage->GetNumberOfLights(); ++i)
      {
        bouncing.push_back(this->AreaLightStage->GetLight(i));
      }
    }
    this->RSMPass->RenderWithAreaLights(s, bouncing.data(), static_cast<int>(bouncing.size()));
  }
  if (shadows && framed)
  {
    vtkMRGIShadowedDirectLight::Settings settings;
    settings.Mode =
      this->DirectShadows == DirectShadowsHard ? MRGI_DIRECT_SHADOW_HARD : MRGI_DIRECT_SHADOW_SOFT;
    settings.SamplesSide = this->SoftShadowKernelSize;
    settings.LightRadius = this->ShadowLightRadius;
    settings.Multiresolution = this->ShadowResolution == ResolutionMultiresolution;
    vtkMRGIGBuffer& g = in.GBuffer;
    this->ShadowsComputed = this->DirectLight->Apply(frame, this->RSMPass, shadowLights, settings,
      g.Color, g.LightTerms, g.ShadowFactors, g.Shadowed);
    if (this->ShadowsComputed)
    {
      // Color is the frame's colour from here on; Shadowed keeps VTK's
      // unshadowed light for GetUnshadowedBuffer().
      std::swap(g.Color, g.Shadowed);
    }
  }
  if (framed)
  {
    this->RenderScreenSpaceEffects(frame, in.GBuffer.Color);
  }
  if (indirect)
  {
    vtkMRGIIndirectLight::Settings settings;
    settings.Multiresolution = this->IndirectMode == IndirectMultires;
    settings.Strength = this->IndirectStrength;
    settings.SurfaceDetail = this->SurfaceDetail;
    settings.UpsampleMode = this->GetUpsampleMode();
    settings.UpsampleMaskWeight = this->GetUpsampleMaskWeight();
    // The multiresolution gather needs the frame's pixel size (`framed`).
    const vtkMRGIIndirectLight::Outcome outcome = settings.Multiresolution && !framed
      ? vtkMRGIIndirectLight::Failed
      : this->IndirectLight->Render(frame, this->RSMPass, this->Multiresolution, settings,
          in.GBuffer.Irradiance, in.GBuffer.Indirect);
    selected = settings.Multiresolution && outcome == vtkMRGIIndirectLight::Gathered;
    if (outcome == vtkMRGIIndirectLight::Gathered)
    {
      ScopedStage stage(timer, "add");
      this->RenderAdd(frame, in.GBuffer.Indirect, in.GBuffer.Color);
      this->IndirectComputed = true;
      in.IndirectFailureReported = false;
    }
    else if (outcome == vtkMRGIIndirectLight::Failed && !in.IndirectFailureReported)
    {
      // Never a silent fallback: the image has no indirect light.
      in.IndirectFailureReported = true;
      vtkErrorMacro("the indirect light could not be computed at "
        << w << " x " << h << " pixels: this frame has direct light only");
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
    this->LastExposure = this->Exposure;
    std::string problem;
    if (this->AutoExposure &&
      !vtkMRGIOutput::MeasureExposure(
        renWin, in.GBuffer, this->Viewport, this->AutoExposureKey, this->LastExposure, problem))
    {
      vtkErrorMacro(<< "automatic exposure: " << problem << "; EV 0 used");
    }
    const float scale = mrgi_exposure_scale(this->LastExposure);
    // The enclosing pass's G-buffer (vtkSSAOPass) is written with the depth.
    const vtkMRGIOutput::DepthMode depth =
      this->OuterGBuffer && this->Captured ? vtkMRGIOutput::DepthAndGBuffer
                                           : vtkMRGIOutput::Depth;
    if (!(fxaa ? vtkMRGIOutput::WriteWithFXAA(renderer, renWin, in.Programs, in.GBuffer,
                   this->Viewport, scale, this->ToneMapping, depth, this->FXAAFilter)
               : vtkMRGIOutput::Write(renWin, in.Programs, in.GBuffer, this->Viewport,
                   in.GBuffer.Color, scale, this->ToneMapping, depth)))
    {
      vtkErrorMacro("could not build the MRGI output shader");
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
  return this->GetVPLSelection()->ReadVPLs(vtkOpenGLRenderWindow::SafeDownCast(window), vpls);
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
  os << indent << "ShadowedDirectLight:\n";
  this->DirectLight->PrintSelf(os, indent.GetNextIndent());
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
  os << indent << "AreaLightIndirect: " << (this->AreaLightIndirect ? "On" : "Off") << "\n";
  os << indent << "RSMResolution: " << this->RSMPass->GetResolution() << "\n";
  os << indent << "RSMCompositor: " << this->RSMPass->GetCompositor() << "\n";
  os << indent << "Exposure: " << this->Exposure << " EV\n";
  os << indent << "AutoExposure: " << (this->AutoExposure ? "On" : "Off") << "\n";
  os << indent << "AutoExposureKey: " << this->AutoExposureKey << "\n";
  os << indent << "LastExposure: " << this->LastExposure << " EV\n";
  os << indent << "ToneMapping: " << (this->ToneMapping ? "On" : "Off") << "\n";
  this->FrameBudgetTuner->PrintSelf(os << indent << "FrameBudgetTuner:\n", indent.GetNextIndent());
  os << indent << "StageTimingEnabled: " << (this->StageTimingEnabled ? "On" : "Off") << "\n";
  os << indent << "Multiresolution:\n";
  this->Multiresolution->PrintSelf(os, indent.GetNextIndent());
  os << indent << "IndirectLight:\n"; // VPL selection, visibility, gather, upsampling
  this->IndirectLight->PrintSelf(os, indent.GetNextIndent());
  os << indent << "AreaLightStage:\n";
  this->AreaLightStage->PrintSelf(os, indent.GetNextIndent());
  os << indent << "BufferSize: " << this->BufferSize[0] << " x " << this->BufferSize[1] << "\n";
  for (int i = 0; i < this->GetNumberOfStages(); ++i)
  {
    os << indent << "Stage " << this->GetStageName(i) << ": " << this->GetStageTimeMilliseconds(i)
       << " ms\n";
  }
}
