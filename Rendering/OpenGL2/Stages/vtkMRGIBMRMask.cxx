#include "vtk_glew.h"

#include "vtkMRGIBMRMask.h"

#include "vtkMRGIBMRLevels.h"
#include "vtkMRGIFrameContext.h"
#include "vtkMRGIFullScreenStep.h"
#include "vtkMRGIMultiresolution.h"
#include "vtkMRGIProgramCache.h"
#include "vtkMRGIShaderUtilities.h"
#include "vtkMRGIStageResources.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLQuadHelper.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"

#include "vtkMRGIBMRMaskFS.h"

#include "mrgi_bmr_mask.h"

#include <cmath>
#include <memory>
#include <string>

vtkStandardNewMacro(vtkMRGIBMRMask);

struct vtkMRGIBMRMask::Internals
{
  // Two frame-sized scratch targets; level k uses their lower-left
  // w_k x h_k (the shaders clamp reads to the level's size): A (RGBA8:
  // 0 and 1 are exact) holds E, NE (stages 0, 1, 5) and the stencil pass's
  // throw-away colour, B (R32F) the horizontal blur. Small formats because
  // llvmpipe pays for every byte a full-screen pass writes: RGBA32F
  // scratch targets made the mask about 1.5 times slower at 1280 x 720.
  vtkTextureObject* ScratchA = nullptr;
  vtkTextureObject* ScratchB = nullptr;
  int Size[2] = { 0, 0 };
  vtkMRGIStageResources GL; // framebuffer and programs

  vtkOpenGLQuadHelper* Ready(vtkOpenGLRenderWindow* window, int stage)
  {
    return this->GL.Programs.Ready(window, "bmr.mask",
      "#define MRGI_BMR_STAGE " + std::to_string(stage) + "\n", [] { return vtkMRGIBMRMaskFS; });
  }

  void ReleaseTextures(vtkWindow* w)
  {
    vtkMRGIShaderUtilities::ReleaseTexture(this->ScratchA, w);
    vtkMRGIShaderUtilities::ReleaseTexture(this->ScratchB, w);
    this->Size[0] = this->Size[1] = 0;
  }

  bool Prepare(vtkOpenGLRenderWindow* window, int w, int h)
  {
    if (this->Size[0] != w || this->Size[1] != h)
    {
      this->ReleaseTextures(window);
      this->ScratchA = vtkMRGIShaderUtilities::NewTexture(window, GL_RGBA8, w, h);
      this->ScratchB = vtkMRGIShaderUtilities::NewTexture(window, GL_R32F, w, h);
      if (!this->ScratchA || !this->ScratchB)
      {
        this->ReleaseTextures(window);
        return false;
      }
      this->Size[0] = w;
      this->Size[1] = h;
    }
    this->GL.Prepare(window);
    return true;
  }
};

//------------------------------------------------------------------------------
vtkMRGIBMRMask::vtkMRGIBMRMask()
  : Internal(new Internals)
{
  this->SetPreset(SSAO);
}

//------------------------------------------------------------------------------
vtkMRGIBMRMask::~vtkMRGIBMRMask()
{
  if (this->Internal->GL.FrameBuffer || this->Internal->ScratchA)
  {
    vtkErrorMacro("GL resources should have been freed in ReleaseGraphicsResources().");
  }
  this->Internal->ReleaseTextures(nullptr);
}

//------------------------------------------------------------------------------
void vtkMRGIBMRMask::ReleaseGraphicsResources(vtkWindow* w)
{
  this->Internal->ReleaseTextures(w);
  this->Internal->GL.Release(w);
}

//------------------------------------------------------------------------------
void vtkMRGIBMRMask::SetPreset(int effect)
{
  mrgi_bmr_params params;
  mrgi_error err;
  if (mrgi_bmr_preset_params(effect, &params, &err) != MRGI_OK)
  {
    vtkErrorMacro("SetPreset: " << err.message);
    return;
  }
  this->DepthThreshold = params.depth_threshold;
  this->NormalThreshold = params.normal_threshold;
  this->Combine = params.combine;
  for (int k = 0; k < MRGI_BMR_LEVELS; ++k)
  {
    this->Variance[k] = params.variance[k];
    this->Skip[k] = params.skip[k] != 0;
  }
  this->Modified();
}

//------------------------------------------------------------------------------
void vtkMRGIBMRMask::SetVariance(int level, double variance)
{
  if (level < 0 || level >= MRGI_BMR_LEVELS ||
    !(variance >= 0.0 && variance <= MRGI_BMR_MAX_VARIANCE))
  {
    vtkErrorMacro("SetVariance: level must be 0.."
      << MRGI_BMR_LEVELS - 1 << " and the variance in [0, " << MRGI_BMR_MAX_VARIANCE
      << "], got level " << level << ", variance " << variance);
    return;
  }
  this->Variance[level] = variance;
  this->Modified();
}

//------------------------------------------------------------------------------
double vtkMRGIBMRMask::GetVariance(int level) const
{
  return level >= 0 && level < MRGI_BMR_LEVELS ? this->Variance[level] : 0.0;
}

//------------------------------------------------------------------------------
void vtkMRGIBMRMask::SetSkipLevel(int level, bool skip)
{
  if (level < 0 || level >= MRGI_BMR_LEVELS - 1)
  {
    vtkErrorMacro("SetSkipLevel: only levels 0.."
      << MRGI_BMR_LEVELS - 2 << " may be skipped (the coarsest covers every pixel), got " << level);
    return;
  }
  this->Skip[level] = skip;
  this->Modified();
}

//------------------------------------------------------------------------------
bool vtkMRGIBMRMask::GetSkipLevel(int level) const
{
  return level >= 0 && level < MRGI_BMR_LEVELS && this->Skip[level];
}

//------------------------------------------------------------------------------
void vtkMRGIBMRMask::GetParams(mrgi_bmr_params* params) const
{
  *params = mrgi_bmr_params();
  params->depth_threshold = this->DepthThreshold < 0.0 ? HUGE_VAL : this->DepthThreshold;
  params->normal_threshold = this->NormalThreshold < 0.0 ? HUGE_VAL : this->NormalThreshold;
  params->combine = this->Combine;
  for (int k = 0; k < MRGI_BMR_LEVELS; ++k)
  {
    params->variance[k] = this->Variance[k];
    params->skip[k] = this->Skip[k] ? 1 : 0;
  }
}

//------------------------------------------------------------------------------
bool vtkMRGIBMRMask::Build(
  const vtkMRGIFrameContext& frame, vtkMRGIBMRLevels* levels, vtkTextureObject* shadow)
{
  return this->Run(frame, levels, shadow, nullptr);
}

//------------------------------------------------------------------------------
bool vtkMRGIBMRMask::BuildFromFlags(
  const vtkMRGIFrameContext& frame, vtkMRGIBMRLevels* levels, vtkMRGIMultiresolution* buffer)
{
  if (!buffer || buffer->GetNumberOfLevels() < 1)
  {
    vtkErrorMacro("BuildFromFlags needs a multiresolution buffer updated for this frame");
    return false;
  }
  return this->Run(frame, levels, nullptr, buffer);
}

//------------------------------------------------------------------------------
bool vtkMRGIBMRMask::Run(const vtkMRGIFrameContext& frame, vtkMRGIBMRLevels* levels,
  vtkTextureObject* shadow, vtkMRGIMultiresolution* buffer)
{
  Internals& in = *this->Internal;
  vtkOpenGLRenderWindow* window = frame.Window;
  const int W = frame.Viewport[2], H = frame.Viewport[3];
  mrgi_bmr_params params;
  this->GetParams(&params);
  mrgi_error err;
  if (mrgi_bmr_params_validate(&params, &err) != MRGI_OK)
  {
    vtkErrorMacro("BMR mask: " << err.message);
    return false;
  }
  if (!window || !levels || !frame.Position || !frame.Normal || W < 1 || H < 1 ||
    levels->GetWidth() != W || levels->GetHeight() != H)
  {
    vtkErrorMacro("BMR mask needs the frame's G-buffer and levels prepared for its "
      << W << " x " << H << " viewport (they are " << (levels ? levels->GetWidth() : 0) << " x "
      << (levels ? levels->GetHeight() : 0) << ")");
    return false;
  }
  if (buffer && (buffer->GetFlagsTexture(0) == nullptr))
  {
    vtkErrorMacro("BMR mask from flags: the multiresolution buffer has no flags");
    return false;
  }
  if (!in.Prepare(window, W, H))
  {
    vtkErrorMacro("could not allocate the BMR mask buffers (" << W << " x " << H << ")");
    return false;
  }
  vtkOpenGLQuadHelper* quads[6];
  for (int s = 0; s < 6; ++s)
  {
    quads[s] = in.Ready(window, s);
    if (!quads[s])
    {
      vtkErrorMacro("could not build the BMR mask shader, stage " << s);
      return false;
    }
  }
  const int flagLevels = buffer ? buffer->GetNumberOfLevels() : 0;
  vtkMRGIShaderUtilities::ScopedStage step(frame.Timer, "bmr.mask");
  vtkMRGIFullScreenStep steps(window, levels->GetFramebuffer());
  int finer[2] = { 0, 0 };
  for (int k = 0; k < MRGI_BMR_LEVELS; ++k)
  {
    int size[2];
    levels->GetLevelSize(k, size);
    // Level 0 has no finer mask: the coarsest level's mask stands in,
    // unread (never a texture the pass draws into: a feedback loop).
    vtkTextureObject* finerMask = levels->GetMaskTexture(k > 0 ? k - 1 : MRGI_BMR_LEVELS - 1);
    // E_k and NE_k into A.
    std::unique_ptr<vtkMRGIShaderUtilities::ScopedStage> sub(
      new vtkMRGIShaderUtilities::ScopedStage(frame.Timer, "bmr.mask.edges"));
    steps.Target(in.ScratchA, nullptr, 0, 0, size[0], size[1]);
    if (buffer && k < flagLevels)
    {
      vtkShaderProgram* p = quads[5]->Program;
      window->GetShaderCache()->ReadyShaderProgram(p);
      vtkTextureObject* flags = buffer->GetFlagsTexture(k);
      vtkMRGIFullScreenStep::BindInputs(p, { flags });
      quads[5]->Render();
      vtkMRGIFullScreenStep::UnbindInputs({ flags });
    }
    else if (k == 0)
    {
      vtkShaderProgram* p = quads[0]->Program;
      window->GetShaderCache()->ReadyShaderProgram(p);
      // A missing shadow image: scratch B stands in, never read.
      vtkTextureObject* third = shadow ? shadow : in.ScratchB;
      vtkMRGIFullScreenStep::BindInputs(p, { frame.Position, frame.Normal, third });
      const int offset[2] = { frame.Viewport[0], frame.Viewport[1] };
      p->SetUniform2i("mrgiOffset", offset);
      p->SetUniform2i("mrgiSize", size);
      const float ab[2] = { static_cast<float>(frame.PixelSize[0]),
        static_cast<float>(frame.PixelSize[1]) };
      p->SetUniform2f("mrgiPixelSize", ab);
      p->SetUniformf("mrgiDepthThreshold",
        std::isinf(params.depth_threshold) ? -1.0f : static_cast<float>(params.depth_threshold));
      p->SetUniformf("mrgiNormalThreshold",
        std::isinf(params.normal_threshold) ? -1.0f : static_cast<float>(params.normal_threshold));
      p->SetUniformi("mrgiCombine", params.combine);
      p->SetUniformi("mrgiHasShadow", shadow ? 1 : 0);
      quads[0]->Render();
      vtkMRGIFullScreenStep::UnbindInputs({ frame.Position, frame.Normal, third });
    }
    else
    {
      vtkShaderProgram* p = quads[1]->Program;
      window->GetShaderCache()->ReadyShaderProgram(p);
      vtkMRGIFullScreenStep::BindInputs(p, { finerMask });
      p->SetUniform2i("mrgiFinerSize", finer);
      quads[1]->Render();
      vtkMRGIFullScreenStep::UnbindInputs({ finerMask });
    }
    // The Gaussian's radius and variance as the C twin computes them.
    const float variance = static_cast<float>(params.variance[k]);
    const int radius =
      variance > 0.0f ? static_cast<int>(std::ceil(3.0f * std::sqrt(variance))) : 0;
    float gauss[MRGI_BMR_MAX_RADIUS + 1] = {};
    for (int j = 0; j <= radius; ++j)
    {
      gauss[j] = radius == 0 ? 1.0f : std::exp(-static_cast<float>(j * j) / (2.0f * variance));
    }
    // Horizontal blur into B.
    sub.reset();
    sub.reset(new vtkMRGIShaderUtilities::ScopedStage(frame.Timer, "bmr.mask.blur"));
    {
      steps.Target(in.ScratchB, nullptr, 0, 0, size[0], size[1]);
      vtkShaderProgram* p = quads[2]->Program;
      window->GetShaderCache()->ReadyShaderProgram(p);
      vtkMRGIFullScreenStep::BindInputs(p, { in.ScratchA });
      p->SetUniform2i("mrgiSize", size);
      p->SetUniformi("mrgiRadius", radius);
      p->SetUniform1fv("mrgiGauss", MRGI_BMR_MAX_RADIUS + 1, gauss);
      quads[2]->Render();
      vtkMRGIFullScreenStep::UnbindInputs({ in.ScratchA });
    }
    // Vertical blur and the stencil rule into the level's mask.
    vtkTextureObject* mask = levels->GetMaskTexture(k);
    {
      steps.Target(mask, nullptr, 0, 0, size[0], size[1]);
      vtkShaderProgram* p = quads[3]->Program;
      window->GetShaderCache()->ReadyShaderProgram(p);
      vtkMRGIFullScreenStep::BindInputs(p, { in.ScratchB, finerMask, in.ScratchA });
      p->SetUniform2i("mrgiSize", size);
      p->SetUniform2i("mrgiFinerSize", finer);
      p->SetUniformi("mrgiRadius", radius);
      p->SetUniform1fv("mrgiGauss", MRGI_BMR_MAX_RADIUS + 1, gauss);
      p->SetUniformi("mrgiLevel", k);
      p->SetUniformi("mrgiSkip", params.skip[k]);
      quads[3]->Render();
      vtkMRGIFullScreenStep::UnbindInputs({ in.ScratchB, finerMask, in.ScratchA });
    }
    // S_k into the level's stencil (the colour goes to A, unused now).
    sub.reset();
    sub.reset(new vtkMRGIShaderUtilities::ScopedStage(frame.Timer, "bmr.mask.stencil"));
    {
      steps.Target(in.ScratchA, nullptr, 0, 0, size[0], size[1]);
      steps.BeginMaskWrite(levels->GetDepthStencilTexture(k));
      vtkShaderProgram* p = quads[4]->Program;
      window->GetShaderCache()->ReadyShaderProgram(p);
      vtkMRGIFullScreenStep::BindInputs(p, { mask });
      quads[4]->Render();
      vtkMRGIFullScreenStep::UnbindInputs({ mask });
      steps.EndMaskWrite();
    }
    sub.reset();
    finer[0] = size[0];
    finer[1] = size[1];
  }
  const GLenum error = glGetError();
  if (error != GL_NO_ERROR)
  {
    vtkErrorMacro("OpenGL error " << error << " in the BMR masks");
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
void vtkMRGIBMRMask::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "DepthThreshold: " << this->DepthThreshold << "\n";
  os << indent << "NormalThreshold: " << this->NormalThreshold << "\n";
  os << indent << "Combine: " << (this->Combine == CombineMin ? "min" : "max") << "\n";
  for (int k = 0; k < MRGI_BMR_LEVELS; ++k)
  {
    os << indent << "Level " << k + 1 << ": variance " << this->Variance[k]
       << (this->Skip[k] ? ", skipped" : "") << "\n";
  }
}
