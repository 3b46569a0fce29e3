#include "vtk_glew.h"

#include "vtkMRGISSAO.h"

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
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtkRenderer.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"

#include "vtkMRGISSAOFS.h"

#include "mrgi_ssao.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkMRGISSAO);

struct vtkMRGISSAO::Internals
{
  vtkTextureObject* AO = nullptr; // full-resolution AO of Render(), R32F
  int Size[2] = { 0, 0 };
  vtkTextureObject* Occlusion = nullptr; // 1 - AO of RenderMultiresolution(), RGBA32F
  int OcclusionSize[2] = { 0, 0 };
  vtkNew<vtkMRGIBMRLevels> Levels;
  vtkNew<vtkMRGIBMRMask> Mask;
  vtkNew<vtkMRGIBMRBlend> Blend;
  std::vector<float> Kernel; // the kernel of KernelSize samples
  int KernelSize = 0;
  vtkMRGIStageResources GL;

  // The stage's program: 0 AO (one program per kernel size: the kernel is a
  // uniform array, like vtkSSAOPass's), 1 apply.
  vtkOpenGLQuadHelper* Ready(vtkOpenGLRenderWindow* window, int stage, int kernelSize)
  {
    std::string defines = "#define MRGI_SSAO_STAGE " + std::to_string(stage) + "\n";
    if (stage == 0)
    {
      defines += "#define MRGI_SSAO_KERNEL_SIZE " + std::to_string(kernelSize) + "\n";
    }
    return this->GL.Programs.Ready(
      window, stage == 0 ? "ssao" : "ssao.apply", defines, [] { return vtkMRGISSAOFS; });
  }
};

//------------------------------------------------------------------------------
vtkMRGISSAO::vtkMRGISSAO()
  : Internal(new Internals)
{
  this->Internal->Mask->SetPreset(vtkMRGIBMRMask::SSAO);
  this->Internal->Blend->SetPreset(vtkMRGIBMRMask::SSAO);
}

//------------------------------------------------------------------------------
vtkMRGISSAO::~vtkMRGISSAO()
{
  if (this->Internal->GL.FrameBuffer || this->Internal->AO || this->Internal->Occlusion)
  {
    vtkErrorMacro("GL resources should have been freed in ReleaseGraphicsResources().");
  }
  vtkMRGIShaderUtilities::ReleaseTexture(this->Internal->AO, nullptr);
  vtkMRGIShaderUtilities::ReleaseTexture(this->Internal->Occlusion, nullptr);
}

//------------------------------------------------------------------------------
void vtkMRGISSAO::ReleaseGraphicsResources(vtkWindow* w)
{
  vtkMRGIShaderUtilities::ReleaseTexture(this->Internal->AO, w);
  this->Internal->Size[0] = this->Internal->Size[1] = 0;
  vtkMRGIShaderUtilities::ReleaseTexture(this->Internal->Occlusion, w);
  this->Internal->OcclusionSize[0] = this->Internal->OcclusionSize[1] = 0;
  this->Internal->Levels->ReleaseGraphicsResources(w);
  this->Internal->Mask->ReleaseGraphicsResources(w);
  this->Internal->Blend->ReleaseGraphicsResources(w);
  this->Internal->GL.Release(w);
}

//------------------------------------------------------------------------------
bool vtkMRGISSAO::CheckAO(
  const vtkMRGIFrameContext& frame, int kernelSize, double radius, double bias)
{
  Internals& in = *this->Internal;
  const int w = frame.Viewport[2], h = frame.Viewport[3];
  if (!frame.Window || !frame.Renderer || !frame.Position || !frame.Normal || w < 1 || h < 1)
  {
    vtkErrorMacro("SSAO needs the frame's window, renderer, G-buffer position and normal, a "
                  "viewport and a target");
    return false;
  }
  if (kernelSize < 1 || kernelSize > MRGI_SSAO_MAX_KERNEL_SIZE)
  {
    vtkErrorMacro(
      "SSAO kernel size " << kernelSize << " is outside 1.." << MRGI_SSAO_MAX_KERNEL_SIZE);
    return false;
  }
  if (!(radius > 0.0) || !std::isfinite(radius) || !std::isfinite(bias) ||
    !std::isfinite(static_cast<float>(radius)) || !std::isfinite(static_cast<float>(bias)))
  {
    vtkErrorMacro(
      "SSAO radius " << radius << " must be finite and > 0, bias " << bias << " finite");
    return false;
  }
  if (in.KernelSize != kernelSize)
  {
    in.Kernel.resize(3 * static_cast<size_t>(kernelSize));
    mrgi_error err;
    if (mrgi_ssao_kernel(kernelSize, in.Kernel.data(), &err) != MRGI_OK)
    {
      vtkErrorMacro(<< err.message);
      in.KernelSize = 0;
      return false;
    }
    in.KernelSize = kernelSize;
  }
  return true;
}

//------------------------------------------------------------------------------
vtkOpenGLQuadHelper* vtkMRGISSAO::ReadyAO(
  const vtkMRGIFrameContext& frame, int kernelSize, double radius, double bias, int level)
{
  Internals& in = *this->Internal;
  vtkOpenGLRenderWindow* window = frame.Window;
  // vtkSSAOPass's projection: the camera's at the tile's aspect ratio.
  float matrix[16];
  vtkMRGIShaderUtilities::CameraProjection(frame.Renderer, matrix);
  vtkOpenGLQuadHelper* quad = in.Ready(window, 0, kernelSize);
  if (!quad)
  {
    vtkErrorMacro("could not build the SSAO shader (kernel size " << kernelSize << ")");
    return nullptr;
  }
  vtkShaderProgram* program = quad->Program;
  vtkMRGIFullScreenStep::BindInputs(program, { frame.Position, frame.Normal });
  program->SetUniformi("mrgiNoise", window->GetNoiseTextureUnit());
  const int origin[2] = { frame.Viewport[0], frame.Viewport[1] };
  const int size[2] = { frame.Viewport[2], frame.Viewport[3] };
  program->SetUniform2i("mrgiOrigin", origin);
  program->SetUniform2i("mrgiSize", size);
  program->SetUniformi("mrgiLevel", level);
  program->SetUniformMatrix4x4("mrgiProjection", matrix);
  program->SetUniformf("mrgiRadius", static_cast<float>(radius));
  program->SetUniformf("mrgiBias", static_cast<float>(bias));
  program->SetUniform3fv("mrgiKernel", kernelSize, in.Kernel.data());
  return quad;
}

//------------------------------------------------------------------------------
bool vtkMRGISSAO::ComputeAO(const vtkMRGIFrameContext& frame, int kernelSize, double radius,
  double bias, int level, vtkTextureObject* target)
{
  Internals& in = *this->Internal;
  vtkOpenGLRenderWindow* window = frame.Window;
  const int w = frame.Viewport[2], h = frame.Viewport[3];
  if (!this->CheckAO(frame, kernelSize, radius, bias))
  {
    return false;
  }
  int levelSize[2];
  if (!vtkMRGIBMRLevels::CheckLevelTarget(
        this, "SSAO", level, MRGI_SSAO_MAX_LEVEL, w, h, target, levelSize))
  {
    return false;
  }
  const int lw = levelSize[0], lh = levelSize[1];
  in.GL.Prepare(window);
  {
    vtkMRGIShaderUtilities::ScopedStage step(frame.Timer, "ssao.ao");
    vtkMRGIFullScreenStep steps(window, in.GL.FrameBuffer);
    steps.Target(target, nullptr, 0, 0, lw, lh);
    vtkOpenGLQuadHelper* quad = this->ReadyAO(frame, kernelSize, radius, bias, level);
    if (!quad)
    {
      return false;
    }
    quad->Program->SetUniformi("mrgiOcclusion", 0);
    quad->Render();
    vtkMRGIFullScreenStep::UnbindInputs({ frame.Position, frame.Normal });
  }
  const GLenum error = glGetError();
  if (error != GL_NO_ERROR)
  {
    vtkErrorMacro("OpenGL error " << error << " in the SSAO stage");
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkMRGISSAO::ComputeOcclusionLevels(const vtkMRGIFrameContext& frame, int kernelSize,
  double radius, double bias, vtkMRGIBMRLevels* levels)
{
  Internals& in = *this->Internal;
  vtkOpenGLRenderWindow* window = frame.Window;
  if (!levels || levels->GetWidth() != frame.Viewport[2] ||
    levels->GetHeight() != frame.Viewport[3])
  {
    vtkErrorMacro("SSAO levels must be prepared for the frame's viewport ("
      << frame.Viewport[2] << " x " << frame.Viewport[3] << ")");
    return false;
  }
  if (!this->CheckAO(frame, kernelSize, radius, bias))
  {
    return false;
  }
  in.GL.Prepare(window);
  vtkMRGIShaderUtilities::ScopedStage step(frame.Timer, "ssao.ao");
  return vtkMRGIBMRLevels::RenderLevels(window, levels, [&](int k) {
    vtkOpenGLQuadHelper* quad = this->ReadyAO(frame, kernelSize, radius, bias, k);
    if (!quad)
    {
      return false;
    }
    quad->Program->SetUniformi("mrgiOcclusion", 1);
    quad->Render();
    vtkMRGIFullScreenStep::UnbindInputs({ frame.Position, frame.Normal });
    return true;
  });
}

//------------------------------------------------------------------------------
bool vtkMRGISSAO::ComputeOcclusionMultiresolution(const vtkMRGIFrameContext& frame,
  int kernelSize, double radius, double bias, vtkTextureObject* target)
{
  Internals& in = *this->Internal;
  return vtkMRGIBMRBlend::RenderMultiresolution(frame, in.Mask, in.Blend, in.Levels,
    [&](vtkMRGIBMRLevels* levels) {
      return this->ComputeOcclusionLevels(frame, kernelSize, radius, bias, levels);
    },
    target);
}

//------------------------------------------------------------------------------
bool vtkMRGISSAO::RenderMultiresolution(const vtkMRGIFrameContext& frame, int kernelSize,
  double radius, double bias, bool blur, vtkTextureObject* colour)
{
  Internals& in = *this->Internal;
  const int w = frame.Viewport[2], h = frame.Viewport[3];
  if (!frame.Window || w < 1 || h < 1)
  {
    vtkErrorMacro("SSAO needs the frame's window and a viewport");
    return false;
  }
  if (!vtkMRGIShaderUtilities::EnsureTexture(
        frame.Window, in.Occlusion, in.OcclusionSize, GL_RGBA32F, w, h))
  {
    vtkErrorMacro("could not allocate the multiresolution SSAO target (" << w << " x " << h
                                                                        << ")");
    return false;
  }
  return this->ComputeOcclusionMultiresolution(frame, kernelSize, radius, bias, in.Occlusion) &&
    this->ApplyTexture(frame, in.Occlusion, true, blur, colour);
}

//------------------------------------------------------------------------------
vtkMRGIBMRMask* vtkMRGISSAO::GetBMRMask()
{
  return this->Internal->Mask;
}

//------------------------------------------------------------------------------
vtkMRGIBMRBlend* vtkMRGISSAO::GetBMRBlend()
{
  return this->Internal->Blend;
}

//------------------------------------------------------------------------------
vtkMRGIBMRLevels* vtkMRGISSAO::GetBMRLevels()
{
  return this->Internal->Levels;
}

//------------------------------------------------------------------------------
bool vtkMRGISSAO::Apply(
  const vtkMRGIFrameContext& frame, vtkTextureObject* ao, bool blur, vtkTextureObject* colour)
{
  return this->ApplyTexture(frame, ao, false, blur, colour);
}

//------------------------------------------------------------------------------
bool vtkMRGISSAO::ApplyTexture(const vtkMRGIFrameContext& frame, vtkTextureObject* ao,
  bool occlusion, bool blur, vtkTextureObject* colour)
{
  Internals& in = *this->Internal;
  vtkOpenGLRenderWindow* window = frame.Window;
  if (!window || !ao || !colour || frame.Viewport[2] < 1 || frame.Viewport[3] < 1)
  {
    vtkErrorMacro("SSAO Apply needs the frame's window and viewport, an AO texture and a colour");
    return false;
  }
  in.GL.Prepare(window);
  vtkOpenGLQuadHelper* quad = in.Ready(window, 1, 0);
  if (!quad)
  {
    vtkErrorMacro("could not build the SSAO apply shader");
    return false;
  }
  vtkMRGIShaderUtilities::ScopedStage step(frame.Timer, "ssao.apply");
  // colour.rgb * AO in place: multiplicative blending (the same float
  // product as vtkSSAOPass's col.rgb * ao), alpha kept.
  if (!vtkMRGIFullScreenStep::BlendInto(window, in.GL.FrameBuffer, quad, frame.Viewport, ao,
        GL_ZERO, GL_SRC_COLOR, colour, [&](vtkShaderProgram* program) {
          program->SetUniformi("mrgiBlur", blur ? 1 : 0);
          program->SetUniformi("mrgiOcclusion", occlusion ? 1 : 0);
        }))
  {
    vtkErrorMacro("OpenGL error in the SSAO apply step");
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkMRGISSAO::Render(const vtkMRGIFrameContext& frame, int kernelSize, double radius,
  double bias, bool blur, vtkTextureObject* colour)
{
  Internals& in = *this->Internal;
  const int w = frame.Viewport[2], h = frame.Viewport[3];
  if (!frame.Window || w < 1 || h < 1)
  {
    vtkErrorMacro("SSAO needs the frame's window and a viewport");
    return false;
  }
  if (!vtkMRGIShaderUtilities::EnsureTexture(frame.Window, in.AO, in.Size, GL_R32F, w, h))
  {
    vtkErrorMacro("could not allocate the SSAO target (" << w << " x " << h << ")");
    return false;
  }
  return this->ComputeAO(frame, kernelSize, radius, bias, 0, in.AO) &&
    this->Apply(frame, in.AO, blur, colour);
}

//------------------------------------------------------------------------------
vtkTextureObject* vtkMRGISSAO::GetAOTexture()
{
  return this->Internal->AO;
}

//------------------------------------------------------------------------------
bool vtkMRGISSAO::ReadAO(vtkRenderWindow* window, vtkFloatArray* ao)
{
  vtkOpenGLRenderWindow* renWin = vtkOpenGLRenderWindow::SafeDownCast(window);
  Internals& in = *this->Internal;
  std::vector<float> rgba;
  if (!renWin || !ao || !in.AO || !vtkMRGIShaderUtilities::ReadTextureRGBA(renWin, in.AO, rgba))
  {
    vtkErrorMacro("ReadAO: no AO rendered yet");
    return false;
  }
  const size_t n = rgba.size() / 4;
  ao->SetNumberOfComponents(1);
  ao->SetNumberOfTuples(static_cast<vtkIdType>(n));
  for (size_t i = 0; i < n; ++i)
  {
    ao->SetValue(static_cast<vtkIdType>(i), rgba[4 * i]);
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkMRGISSAO::ReadNoise(vtkOpenGLRenderWindow* window, std::vector<float>& noise)
{
  if (!window)
  {
    return false;
  }
  const int unit = window->GetNoiseTextureUnit();
  if (unit < 0)
  {
    return false;
  }
  vtkOpenGLState* ostate = window->GetState();
  vtkOpenGLState::ScopedglActiveTexture activeSaver(ostate);
  ostate->vtkglActiveTexture(GL_TEXTURE0 + static_cast<unsigned int>(unit));
  GLint width = 0, height = 0;
  glGetTexLevelParameteriv(GL_TEXTURE_2D, 0, GL_TEXTURE_WIDTH, &width);
  glGetTexLevelParameteriv(GL_TEXTURE_2D, 0, GL_TEXTURE_HEIGHT, &height);
  if (width != MRGI_SSAO_NOISE_SIZE || height != MRGI_SSAO_NOISE_SIZE)
  {
    return false;
  }
  noise.assign(static_cast<size_t>(width) * static_cast<size_t>(height), 0.0f);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glGetTexImage(GL_TEXTURE_2D, 0, GL_RED, GL_FLOAT, noise.data());
  return glGetError() == GL_NO_ERROR;
}

//------------------------------------------------------------------------------
void vtkMRGISSAO::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "KernelSize (cached): " << this->Internal->KernelSize << "\n";
  os << indent << "AO size: " << this->Internal->Size[0] << " x " << this->Internal->Size[1]
     << "\n";
}
