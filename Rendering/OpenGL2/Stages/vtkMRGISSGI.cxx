#include "vtk_glew.h"

#include "vtkMRGISSGI.h"

#include "vtkFloatArray.h"
#include "vtkMRGIBMRBlend.h"
#include "vtkMRGIBMRLevels.h"
#include "vtkMRGIBMRMask.h"
#include "vtkMRGIFrameContext.h"
#include "vtkMRGIFullScreenStep.h"
#include "vtkMRGIProgramCache.h"
#include "vtkMRGIShaderUtilities.h"
#include "vtkMRGIStageResources.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLQuadHelper.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"
#include "vtkRenderer.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"

#include "vtkMRGISSGIFS.h"

#include "mrgi_ssgi.h"

#include <cmath>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkMRGISSGI);

struct vtkMRGISSGI::Internals
{
  vtkTextureObject* Result = nullptr; // result of Render() / RenderMultiresolution(), RGBA32F
  int Size[2] = { 0, 0 };
  vtkNew<vtkMRGIBMRLevels> Levels;
  vtkNew<vtkMRGIBMRMask> Mask;
  vtkNew<vtkMRGIBMRBlend> Blend;
  std::vector<float> Kernel; // the kernel of Samples samples
  int Samples = 0;
  vtkMRGIStageResources GL;

  // 0: compute (one program per sample count: the kernel is a uniform
  // array), 1: apply.
  vtkOpenGLQuadHelper* Ready(vtkOpenGLRenderWindow* window, int stage, int samples)
  {
    std::string defines = "#define MRGI_SSGI_STAGE " + std::to_string(stage) + "\n";
    if (stage == 0)
    {
      defines += "#define MRGI_SSGI_SAMPLES " + std::to_string(samples) + "\n";
    }
    return this->GL.Programs.Ready(
      window, stage == 0 ? "ssgi" : "ssgi.apply", defines, [] { return vtkMRGISSGIFS; });
  }
};

//------------------------------------------------------------------------------
vtkMRGISSGI::vtkMRGISSGI()
  : Internal(new Internals)
{
  // BMR Table 1's SSGI row: level 2 skipped, its own variances and weights.
  this->Internal->Mask->SetPreset(vtkMRGIBMRMask::SSGI);
  this->Internal->Blend->SetPreset(vtkMRGIBMRMask::SSGI);
}

//------------------------------------------------------------------------------
vtkMRGISSGI::~vtkMRGISSGI()
{
  if (this->Internal->GL.FrameBuffer || this->Internal->Result)
  {
    vtkErrorMacro("GL resources should have been freed in ReleaseGraphicsResources().");
  }
  vtkMRGIShaderUtilities::ReleaseTexture(this->Internal->Result, nullptr);
}

//------------------------------------------------------------------------------
void vtkMRGISSGI::ReleaseGraphicsResources(vtkWindow* w)
{
  vtkMRGIShaderUtilities::ReleaseTexture(this->Internal->Result, w);
  this->Internal->Size[0] = this->Internal->Size[1] = 0;
  this->Internal->Levels->ReleaseGraphicsResources(w);
  this->Internal->Mask->ReleaseGraphicsResources(w);
  this->Internal->Blend->ReleaseGraphicsResources(w);
  this->Internal->GL.Release(w);
}

//------------------------------------------------------------------------------
bool vtkMRGISSGI::CheckCompute(const vtkMRGIFrameContext& frame, vtkTextureObject* direct,
  int samples, double radius, double bias)
{
  Internals& in = *this->Internal;
  const int w = frame.Viewport[2], h = frame.Viewport[3];
  if (!frame.Window || !frame.Renderer || !frame.Position || !frame.Normal || !frame.Albedo ||
    !direct || w < 1 || h < 1)
  {
    vtkErrorMacro("SSGI needs the frame's window, renderer, G-buffer position, normal and "
                  "albedo, a direct-light texture, a viewport and a target");
    return false;
  }
  if (samples < 1 || samples > MRGI_SSGI_MAX_SAMPLES)
  {
    vtkErrorMacro("SSGI samples " << samples << " is outside 1.." << MRGI_SSGI_MAX_SAMPLES);
    return false;
  }
  if (!(radius > 0.0) || !std::isfinite(static_cast<float>(radius)) || !(bias >= 0.0) ||
    !std::isfinite(static_cast<float>(bias)))
  {
    vtkErrorMacro(
      "SSGI radius " << radius << " must be finite and > 0, bias " << bias << " finite and >= 0");
    return false;
  }
  if (in.Samples != samples)
  {
    in.Kernel.resize(3 * static_cast<size_t>(samples));
    mrgi_error err;
    if (mrgi_ssgi_kernel(samples, in.Kernel.data(), &err) != MRGI_OK)
    {
      vtkErrorMacro(<< err.message);
      in.Samples = 0;
      return false;
    }
    in.Samples = samples;
  }
  return true;
}

//------------------------------------------------------------------------------
vtkOpenGLQuadHelper* vtkMRGISSGI::ReadyCompute(const vtkMRGIFrameContext& frame,
  vtkTextureObject* direct, int samples, double radius, double bias, int level)
{
  Internals& in = *this->Internal;
  float matrix[16];
  vtkMRGIShaderUtilities::CameraProjection(frame.Renderer, matrix);
  vtkOpenGLQuadHelper* quad = in.Ready(frame.Window, 0, samples);
  if (!quad)
  {
    vtkErrorMacro("could not build the SSGI shader (" << samples << " samples)");
    return nullptr;
  }
  vtkShaderProgram* program = quad->Program;
  vtkMRGIFullScreenStep::BindInputs(program, { frame.Position, frame.Normal, frame.Albedo, direct });
  const int origin[2] = { frame.Viewport[0], frame.Viewport[1] };
  const int size[2] = { frame.Viewport[2], frame.Viewport[3] };
  program->SetUniform2i("mrgiOrigin", origin);
  program->SetUniform2i("mrgiSize", size);
  program->SetUniformi("mrgiLevel", level);
  program->SetUniformMatrix4x4("mrgiProjection", matrix);
  program->SetUniformf("mrgiRadius", static_cast<float>(radius));
  program->SetUniformf("mrgiBias", static_cast<float>(bias));
  program->SetUniform3fv("mrgiKernel", samples, in.Kernel.data());
  return quad;
}

//------------------------------------------------------------------------------
bool vtkMRGISSGI::Compute(const vtkMRGIFrameContext& frame, vtkTextureObject* direct, int samples,
  double radius, double bias, int level, vtkTextureObject* target)
{
  Internals& in = *this->Internal;
  vtkOpenGLRenderWindow* window = frame.Window;
  const int w = frame.Viewport[2], h = frame.Viewport[3];
  if (!this->CheckCompute(frame, direct, samples, radius, bias))
  {
    return false;
  }
  int levelSize[2];
  if (!vtkMRGIBMRLevels::CheckLevelTarget(
        this, "SSGI", level, MRGI_SSGI_MAX_LEVEL, w, h, target, levelSize))
  {
    return false;
  }
  const int lw = levelSize[0], lh = levelSize[1];
  in.GL.Prepare(window);
  {
    vtkMRGIShaderUtilities::ScopedStage step(frame.Timer, "ssgi");
    vtkMRGIFullScreenStep steps(window, in.GL.FrameBuffer);
    steps.Target(target, nullptr, 0, 0, lw, lh);
    vtkOpenGLQuadHelper* quad = this->ReadyCompute(frame, direct, samples, radius, bias, level);
    if (!quad)
    {
      return false;
    }
    quad->Render();
    vtkMRGIFullScreenStep::UnbindInputs({ frame.Position, frame.Normal, frame.Albedo, direct });
  }
  const GLenum error = glGetError();
  if (error != GL_NO_ERROR)
  {
    vtkErrorMacro("OpenGL error " << error << " in the SSGI stage");
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkMRGISSGI::ComputeLevels(const vtkMRGIFrameContext& frame, vtkTextureObject* direct,
  int samples, double radius, double bias, vtkMRGIBMRLevels* levels)
{
  Internals& in = *this->Internal;
  vtkOpenGLRenderWindow* window = frame.Window;
  if (!levels || levels->GetWidth() != frame.Viewport[2] ||
    levels->GetHeight() != frame.Viewport[3])
  {
    vtkErrorMacro("SSGI levels must be prepared for the frame's viewport ("
      << frame.Viewport[2] << " x " << frame.Viewport[3] << ")");
    return false;
  }
  if (!this->CheckCompute(frame, direct, samples, radius, bias))
  {
    return false;
  }
  in.GL.Prepare(window);
  vtkMRGIShaderUtilities::ScopedStage step(frame.Timer, "ssgi");
  return vtkMRGIBMRLevels::RenderLevels(window, levels, [&](int k) {
    vtkOpenGLQuadHelper* quad = this->ReadyCompute(frame, direct, samples, radius, bias, k);
    if (!quad)
    {
      return false;
    }
    quad->Render();
    vtkMRGIFullScreenStep::UnbindInputs({ frame.Position, frame.Normal, frame.Albedo, direct });
    return true;
  });
}

//------------------------------------------------------------------------------
bool vtkMRGISSGI::ComputeMultiresolution(const vtkMRGIFrameContext& frame,
  vtkTextureObject* direct, int samples, double radius, double bias, vtkTextureObject* target)
{
  Internals& in = *this->Internal;
  return vtkMRGIBMRBlend::RenderMultiresolution(frame, in.Mask, in.Blend, in.Levels,
    [&](vtkMRGIBMRLevels* levels) {
      return this->ComputeLevels(frame, direct, samples, radius, bias, levels);
    },
    target);
}

//------------------------------------------------------------------------------
vtkMRGIBMRMask* vtkMRGISSGI::GetBMRMask()
{
  return this->Internal->Mask;
}

//------------------------------------------------------------------------------
vtkMRGIBMRBlend* vtkMRGISSGI::GetBMRBlend()
{
  return this->Internal->Blend;
}

//------------------------------------------------------------------------------
vtkMRGIBMRLevels* vtkMRGISSGI::GetBMRLevels()
{
  return this->Internal->Levels;
}

//------------------------------------------------------------------------------
bool vtkMRGISSGI::Apply(
  const vtkMRGIFrameContext& frame, vtkTextureObject* ssgi, vtkTextureObject* colour)
{
  Internals& in = *this->Internal;
  vtkOpenGLRenderWindow* window = frame.Window;
  if (!window || !ssgi || !colour || frame.Viewport[2] < 1 || frame.Viewport[3] < 1)
  {
    vtkErrorMacro("SSGI Apply needs the frame's window and viewport, an SSGI texture and a colour");
    return false;
  }
  in.GL.Prepare(window);
  vtkOpenGLQuadHelper* quad = in.Ready(window, 1, 0);
  if (!quad)
  {
    vtkErrorMacro("could not build the SSGI apply shader");
    return false;
  }
  vtkMRGIShaderUtilities::ScopedStage step(frame.Timer, "ssgi.apply");
  // colour.rgb + bounce in place (additive blending), alpha kept.
  if (!vtkMRGIFullScreenStep::BlendInto(
        window, in.GL.FrameBuffer, quad, frame.Viewport, ssgi, GL_ONE, GL_ONE, colour, nullptr))
  {
    vtkErrorMacro("OpenGL error in the SSGI apply step");
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkMRGISSGI::PrepareResult(const vtkMRGIFrameContext& frame, vtkTextureObject* colour)
{
  Internals& in = *this->Internal;
  const int w = frame.Viewport[2], h = frame.Viewport[3];
  if (!frame.Window || !colour || w < 1 || h < 1)
  {
    vtkErrorMacro("SSGI needs the frame's window, a colour texture and a viewport");
    return false;
  }
  if (!vtkMRGIShaderUtilities::EnsureTexture(frame.Window, in.Result, in.Size, GL_RGBA32F, w, h))
  {
    vtkErrorMacro("could not allocate the SSGI target (" << w << " x " << h << ")");
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkMRGISSGI::Render(const vtkMRGIFrameContext& frame, int samples, double radius, double bias,
  vtkTextureObject* colour)
{
  return this->PrepareResult(frame, colour) &&
    this->Compute(frame, colour, samples, radius, bias, 0, this->Internal->Result) &&
    this->Apply(frame, this->Internal->Result, colour);
}

//------------------------------------------------------------------------------
bool vtkMRGISSGI::RenderMultiresolution(const vtkMRGIFrameContext& frame, int samples,
  double radius, double bias, vtkTextureObject* colour)
{
  // The levels read `colour` (the senders) before Apply() writes it.
  return this->PrepareResult(frame, colour) &&
    this->ComputeMultiresolution(
      frame, colour, samples, radius, bias, this->Internal->Result) &&
    this->Apply(frame, this->Internal->Result, colour);
}

//------------------------------------------------------------------------------
vtkTextureObject* vtkMRGISSGI::GetTexture()
{
  return this->Internal->Result;
}

//------------------------------------------------------------------------------
bool vtkMRGISSGI::ReadResult(vtkRenderWindow* window, vtkFloatArray* result)
{
  vtkOpenGLRenderWindow* renWin = vtkOpenGLRenderWindow::SafeDownCast(window);
  Internals& in = *this->Internal;
  std::vector<float> rgba;
  if (!renWin || !result || !in.Result ||
    !vtkMRGIShaderUtilities::ReadTextureRGBA(renWin, in.Result, rgba))
  {
    vtkErrorMacro("ReadResult: no SSGI rendered yet");
    return false;
  }
  result->SetNumberOfComponents(4);
  result->SetNumberOfTuples(static_cast<vtkIdType>(rgba.size() / 4));
  std::copy(rgba.begin(), rgba.end(), result->GetPointer(0));
  return true;
}

//------------------------------------------------------------------------------
void vtkMRGISSGI::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Samples (cached): " << this->Internal->Samples << "\n";
  os << indent << "Result size: " << this->Internal->Size[0] << " x " << this->Internal->Size[1]
     << "\n";
  os << indent << "BMRMask:\n";
  this->Internal->Mask->PrintSelf(os, indent.GetNextIndent());
  os << indent << "BMRBlend:\n";
  this->Internal->Blend->PrintSelf(os, indent.GetNextIndent());
}
