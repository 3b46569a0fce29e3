#include "vtkMRGIPass.h"

#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLError.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLQuadHelper.h"
#include "vtkOpenGLRenderUtilities.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtkPointData.h"
#include "vtkRenderState.h"
#include "vtkRenderTimerLog.h"
#include "vtkRenderer.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"

#include "vtkMRGICompositeFS.h"

#include <cstring>

vtkStandardNewMacro(vtkMRGIPass);

namespace
{
// Every MRGI timer event carries this prefix so that FetchStageTimings() can
// find MRGI's stages among the events other passes log on the same window.
const char* const StagePrefix = "MRGI ";

void CollectStages(const vtkRenderTimerLog::Event& event, std::vector<std::string>& names,
  std::vector<double>& times)
{
  if (event.Name.compare(0, std::strlen(StagePrefix), StagePrefix) == 0)
  {
    names.push_back(event.Name.substr(std::strlen(StagePrefix)));
    times.push_back(static_cast<double>(event.ElapsedTimeNanoseconds()) * 1e-6);
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

// Opens a timer event for one stage, or nothing when timing is off.
class ScopedStage
{
public:
  ScopedStage(vtkRenderTimerLog* timer, const char* stage)
  {
    if (timer)
    {
      this->Logger = timer->StartScopedEvent(std::string(StagePrefix) + stage);
    }
  }

private:
  vtkRenderTimerLog::ScopedEventLogger Logger;
};
}

//------------------------------------------------------------------------------
vtkMRGIPass::vtkMRGIPass() = default;

//------------------------------------------------------------------------------
vtkMRGIPass::~vtkMRGIPass()
{
  if (this->FrameBuffer || this->ColorTexture || this->DepthTexture || this->CompositeQuad)
  {
    vtkErrorMacro("vtkMRGIPass destroyed while it still holds GL resources: call "
                  "ReleaseGraphicsResources() first (the render window does so).");
  }
  if (this->FrameBuffer)
  {
    this->FrameBuffer->Delete();
  }
  if (this->ColorTexture)
  {
    this->ColorTexture->Delete();
  }
  if (this->DepthTexture)
  {
    this->DepthTexture->Delete();
  }
  delete this->CompositeQuad;
}

//------------------------------------------------------------------------------
void vtkMRGIPass::ReleaseGraphicsResources(vtkWindow* w)
{
  this->Superclass::ReleaseGraphicsResources(w);
  if (this->CompositeQuad)
  {
    this->CompositeQuad->ReleaseGraphicsResources(w);
    delete this->CompositeQuad;
    this->CompositeQuad = nullptr;
  }
  if (this->FrameBuffer)
  {
    this->FrameBuffer->ReleaseGraphicsResources(w);
    this->FrameBuffer->Delete();
    this->FrameBuffer = nullptr;
  }
  if (this->ColorTexture)
  {
    this->ColorTexture->ReleaseGraphicsResources(w);
    this->ColorTexture->Delete();
    this->ColorTexture = nullptr;
  }
  if (this->DepthTexture)
  {
    this->DepthTexture->ReleaseGraphicsResources(w);
    this->DepthTexture->Delete();
    this->DepthTexture = nullptr;
  }
  this->BufferSize[0] = this->BufferSize[1] = 0;
}

//------------------------------------------------------------------------------
void vtkMRGIPass::PrepareBuffers(vtkOpenGLRenderWindow* renWin, int w, int h)
{
  if (!this->ColorTexture)
  {
    // Float colour: VTK's lighting is unclamped, and the HDR result is what
    // EXR output and the later indirect stages read.
    this->ColorTexture = vtkTextureObject::New();
    this->ColorTexture->SetContext(renWin);
    this->ColorTexture->SetFormat(GL_RGBA);
    this->ColorTexture->SetInternalFormat(GL_RGBA32F);
    this->ColorTexture->SetDataType(GL_FLOAT);
    this->ColorTexture->SetMinificationFilter(vtkTextureObject::Nearest);
    this->ColorTexture->SetMagnificationFilter(vtkTextureObject::Nearest);
    this->ColorTexture->Allocate2D(w, h, 4, VTK_FLOAT);
  }
  if (!this->DepthTexture)
  {
    this->DepthTexture = vtkTextureObject::New();
    this->DepthTexture->SetContext(renWin);
    this->DepthTexture->SetMinificationFilter(vtkTextureObject::Nearest);
    this->DepthTexture->SetMagnificationFilter(vtkTextureObject::Nearest);
    this->DepthTexture->AllocateDepth(w, h, vtkTextureObject::Float32);
  }
  if (!this->FrameBuffer)
  {
    this->FrameBuffer = vtkOpenGLFramebufferObject::New();
    this->FrameBuffer->SetContext(renWin);
  }
  this->ColorTexture->Resize(w, h);
  this->DepthTexture->Resize(w, h);
  this->BufferSize[0] = w;
  this->BufferSize[1] = h;
}

//------------------------------------------------------------------------------
void vtkMRGIPass::RenderScene(const vtkRenderState* s, int w, int h)
{
  this->PreRender(s);
  this->FrameBuffer->SaveCurrentBindingsAndBuffers();
  this->FrameBuffer->Bind();
  this->FrameBuffer->AddColorAttachment(0, this->ColorTexture);
  this->FrameBuffer->ActivateDrawBuffers(1);
  this->FrameBuffer->AddDepthAttachment(this->DepthTexture);
  this->FrameBuffer->StartNonOrtho(w, h);

  this->DelegatePass->Render(s);
  this->NumberOfRenderedProps += this->DelegatePass->GetNumberOfRenderedProps();

  this->FrameBuffer->UnBind();
  this->FrameBuffer->RestorePreviousBindingsAndBuffers();
  this->PostRender(s);
}

//------------------------------------------------------------------------------
void vtkMRGIPass::RenderComposite(vtkOpenGLRenderWindow* renWin)
{
  if (!this->CompositeQuad)
  {
    this->CompositeQuad = new vtkOpenGLQuadHelper(renWin,
      vtkOpenGLRenderUtilities::GetFullScreenQuadVertexShader().c_str(), vtkMRGICompositeFS, "");
  }
  else
  {
    renWin->GetShaderCache()->ReadyShaderProgram(this->CompositeQuad->Program);
  }
  vtkShaderProgram* program = this->CompositeQuad->Program;
  if (!program || !program->GetCompiled())
  {
    vtkErrorMacro("could not build the MRGI composite shader program");
    return;
  }

  vtkOpenGLState* ostate = renWin->GetState();
  vtkOpenGLState::ScopedglEnableDisable depthTest(ostate, GL_DEPTH_TEST);
  vtkOpenGLState::ScopedglEnableDisable blend(ostate, GL_BLEND);
  vtkOpenGLState::ScopedglDepthFunc depthFunc(ostate);
  vtkOpenGLState::ScopedglDepthMask depthMask(ostate);
  ostate->vtkglDisable(GL_BLEND);
  ostate->vtkglEnable(GL_DEPTH_TEST);
  ostate->vtkglDepthFunc(GL_ALWAYS);
  ostate->vtkglDepthMask(GL_TRUE);

  this->ColorTexture->Activate();
  this->DepthTexture->Activate();
  program->SetUniformi("mrgiDirect", this->ColorTexture->GetTextureUnit());
  program->SetUniformi("mrgiDepth", this->DepthTexture->GetTextureUnit());
  this->CompositeQuad->Render();
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
    // A zero-size viewport has nothing to show; it is not an error.
    return;
  }

  vtkRenderTimerLog* timer = TimerFor(renderer, this->StageTimingEnabled);
  this->PrepareBuffers(renWin, w, h);
  {
    ScopedStage stage(timer, "scene");
    this->RenderScene(s, w, h);
  }
  {
    ScopedStage stage(timer, "composite");
    vtkOpenGLState* ostate = renWin->GetState();
    vtkOpenGLState::ScopedglViewport viewport(ostate);
    vtkOpenGLState::ScopedglScissor scissor(ostate);
    ostate->vtkglViewport(x, y, w, h);
    ostate->vtkglScissor(x, y, w, h);
    this->RenderComposite(renWin);
  }
  vtkOpenGLCheckErrorMacro("failed after vtkMRGIPass::Render");
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
    vtkOpenGLRenderWindow* glWindow = vtkOpenGLRenderWindow::SafeDownCast(window);
    if (glWindow)
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
bool vtkMRGIPass::GetColorBuffer(vtkRenderWindow* window, vtkImageData* image)
{
  vtkOpenGLRenderWindow* renWin = vtkOpenGLRenderWindow::SafeDownCast(window);
  if (!renWin || !image)
  {
    vtkErrorMacro("GetColorBuffer needs an OpenGL render window and an output image");
    return false;
  }
  if (!this->FrameBuffer || this->BufferSize[0] < 1 || this->BufferSize[1] < 1)
  {
    vtkErrorMacro("GetColorBuffer: nothing rendered yet");
    return false;
  }
  const int w = this->BufferSize[0];
  const int h = this->BufferSize[1];
  renWin->MakeCurrent();
  vtkOpenGLState* ostate = renWin->GetState();
  ostate->PushReadFramebufferBinding();
  this->FrameBuffer->Bind(GL_READ_FRAMEBUFFER);
  this->FrameBuffer->AddColorAttachment(0, this->ColorTexture);
  this->FrameBuffer->ActivateReadBuffer(0);

  image->SetDimensions(w, h, 1);
  image->AllocateScalars(VTK_FLOAT, 4);
  vtkFloatArray* pixels = vtkFloatArray::SafeDownCast(image->GetPointData()->GetScalars());
  pixels->SetName("HDRColor");
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, w, h, GL_RGBA, GL_FLOAT, pixels->GetPointer(0));
  ostate->PopReadFramebufferBinding();
  return glGetError() == GL_NO_ERROR;
}

//------------------------------------------------------------------------------
void vtkMRGIPass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "StageTimingEnabled: " << (this->StageTimingEnabled ? "On" : "Off") << "\n";
  os << indent << "BufferSize: " << this->BufferSize[0] << " x " << this->BufferSize[1] << "\n";
  for (int i = 0; i < this->GetNumberOfStages(); ++i)
  {
    os << indent << "Stage " << this->GetStageName(i) << ": " << this->GetStageTimeMilliseconds(i)
       << " ms\n";
  }
}
