#include "vtk_glew.h"

#include "vtkMRGIRenderSteps.h"

#include "vtkMRGIShaderUtilities.h"

#include "vtkCameraPass.h"
#include "vtkHardwareSelector.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLFXAAFilter.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLRenderer.h"
#include "vtkOpenGLState.h"
#include "vtkProp.h"
#include "vtkRenderPass.h"
#include "vtkRenderState.h"
#include "vtkRenderStepsPass.h"
#include "vtkRenderer.h"
#include "vtkTextureObject.h"

#include "mrgi_buffers.h"

#include <cstring>

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
    for (int a = MRGI_GBUFFER_POSITION; a < MRGI_GBUFFER_MAX_ATTACHMENTS; ++a)
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

// Saves the GL viewport and scissor box, sets both to `viewport` (x, y, w, h)
// and restores them when it goes out of scope: every forward step draws
// into the renderer's viewport of MRGI's window-sized buffers.
class ScopedViewportAndScissor
{
public:
  ScopedViewportAndScissor(vtkRenderer* renderer, const int viewport[4])
    : State(static_cast<vtkOpenGLRenderWindow*>(renderer->GetRenderWindow())->GetState())
    , SavedViewport(this->State)
    , SavedScissor(this->State)
  {
    this->State->vtkglViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
    this->State->vtkglScissor(viewport[0], viewport[1], viewport[2], viewport[3]);
  }

private:
  vtkOpenGLState* State;
  vtkOpenGLState::ScopedglViewport SavedViewport;
  vtkOpenGLState::ScopedglScissor SavedScissor;
};

}

namespace vtkMRGIRenderSteps
{
//------------------------------------------------------------------------------
vtkSmartPointer<vtkRenderPass> NewClearGBufferPass()
{
  return vtkSmartPointer<vtkMRGIClearGBufferPass>::New();
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkRenderPass> NewSelectionPass()
{
  return vtkSmartPointer<vtkMRGISelectionPass>::New();
}

//------------------------------------------------------------------------------
void RenderCameraWith(vtkCameraPass* camera, vtkRenderPass* delegate, const vtkRenderState* s)
{
  vtkSmartPointer<vtkRenderPass> usual = camera->GetDelegatePass();
  camera->SetDelegatePass(delegate);
  camera->Render(s);
  camera->SetDelegatePass(usual);
}

//------------------------------------------------------------------------------
int RenderForward(const vtkRenderState* s, vtkRenderStepsPass* steps,
  vtkOpenGLFramebufferObject* fbo, vtkTextureObject* color, vtkTextureObject* depth,
  const int viewport[4])
{
  int rendered = 0;
  fbo->SaveCurrentBindingsAndBuffers();
  fbo->Bind();
  fbo->RemoveColorAttachments(MRGI_GBUFFER_MAX_ATTACHMENTS);
  fbo->AddColorAttachment(MRGI_GBUFFER_DIRECT, color);
  vtkMRGIShaderUtilities::SelectDrawBuffers(fbo, 1);
  fbo->AddDepthAttachment(depth);
  ScopedViewportAndScissor drawInViewport(s->GetRenderer(), viewport);
  vtkRenderer* renderer = s->GetRenderer();
  vtkOpenGLRenderer* glRenderer = vtkOpenGLRenderer::SafeDownCast(renderer);
  vtkRenderState forward(renderer);
  forward.SetPropArrayAndCount(s->GetPropArray(), s->GetPropArrayCount());
  forward.SetFrameBuffer(fbo);
  auto render = [&](vtkRenderPass* pass) {
    if (pass)
    {
      pass->Render(&forward);
      rendered += pass->GetNumberOfRenderedProps();
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

  if (!volumesPeeled)
  {
    render(steps->GetVolumetricPass());
  }
  fbo->UnBind();
  fbo->RestorePreviousBindingsAndBuffers();
  return rendered;
}

//------------------------------------------------------------------------------
int RenderOverlays(const vtkRenderState* s, vtkRenderStepsPass* steps, const int viewport[4])
{
  vtkRenderPass* overlay = steps ? steps->GetOverlayPass() : nullptr;
  if (!overlay)
  {
    return 0;
  }
  ScopedViewportAndScissor drawInViewport(s->GetRenderer(), viewport);
  overlay->Render(s);
  return overlay->GetNumberOfRenderedProps();
}

//------------------------------------------------------------------------------
void RenderFXAA(vtkRenderer* renderer, vtkOpenGLFramebufferObject* fbo, vtkTextureObject* display,
  const int viewport[4], vtkOpenGLFXAAFilter*& fxaa)
{
  vtkOpenGLRenderer* glRenderer = vtkOpenGLRenderer::SafeDownCast(renderer);
  if (!glRenderer)
  {
    return;
  }
  if (!fxaa)
  {
    fxaa = vtkOpenGLFXAAFilter::New();
  }
  if (renderer->GetFXAAOptions())
  {
    fxaa->UpdateConfiguration(renderer->GetFXAAOptions());
  }
  fbo->SaveCurrentBindingsAndBuffers();
  fbo->Bind();
  fbo->RemoveColorAttachments(MRGI_GBUFFER_MAX_ATTACHMENTS);
  fbo->AddColorAttachment(0, display);
  vtkMRGIShaderUtilities::SelectDrawBuffers(fbo, 1);
  fbo->ActivateReadBuffer(0);
  ScopedViewportAndScissor drawInViewport(renderer, viewport);
  // The filter copies the viewport out of the read buffer (this one) and
  // draws the filtered image back over it.
  fxaa->Execute(glRenderer);
  fbo->UnBind();
  fbo->RestorePreviousBindingsAndBuffers();
}
}
