#include "vtk_glew.h"

#include "vtkMRGIBMRBlend.h"

#include "vtkMRGIBMRLevels.h"
#include "vtkMRGIBMRMask.h"
#include "vtkMRGIFrameContext.h"
#include "vtkMRGIFullScreenStep.h"
#include "vtkMRGIProgramCache.h"
#include "vtkMRGIShaderUtilities.h"
#include "vtkMRGIStageResources.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLQuadHelper.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"

#include "vtkMRGIBMRBlendFS.h"

#include "mrgi_bmr_mask.h"

#include <string>

vtkStandardNewMacro(vtkMRGIBMRBlend);

struct vtkMRGIBMRBlend::Internals
{
  vtkMRGIStageResources GL; // framebuffer and program
};

//------------------------------------------------------------------------------
vtkMRGIBMRBlend::vtkMRGIBMRBlend()
  : Internal(new Internals)
{
  this->SetPreset(0);
}

//------------------------------------------------------------------------------
vtkMRGIBMRBlend::~vtkMRGIBMRBlend()
{
  if (this->Internal->GL.FrameBuffer)
  {
    vtkErrorMacro("GL resources should have been freed in ReleaseGraphicsResources().");
  }
}

//------------------------------------------------------------------------------
void vtkMRGIBMRBlend::ReleaseGraphicsResources(vtkWindow* w)
{
  this->Internal->GL.Release(w);
}

//------------------------------------------------------------------------------
void vtkMRGIBMRBlend::SetPreset(int effect)
{
  mrgi_bmr_params params;
  mrgi_error err;
  if (mrgi_bmr_preset_params(effect, &params, &err) != MRGI_OK)
  {
    vtkErrorMacro("SetPreset: " << err.message);
    return;
  }
  for (int k = 0; k < MRGI_BMR_LEVELS; ++k)
  {
    this->Weight[k] = params.weight[k];
  }
  this->Modified();
}

//------------------------------------------------------------------------------
void vtkMRGIBMRBlend::SetWeight(int level, double weight)
{
  if (level < 0 || level >= MRGI_BMR_LEVELS || !(weight >= 0.0 && weight <= 1e30))
  {
    vtkErrorMacro("SetWeight: level must be 0.."
      << MRGI_BMR_LEVELS - 1 << " and the weight finite and >= 0, got level " << level
      << ", weight " << weight);
    return;
  }
  this->Weight[level] = weight;
  this->Modified();
}

//------------------------------------------------------------------------------
double vtkMRGIBMRBlend::GetWeight(int level) const
{
  return level >= 0 && level < MRGI_BMR_LEVELS ? this->Weight[level] : 0.0;
}

//------------------------------------------------------------------------------
bool vtkMRGIBMRBlend::Blend(
  const vtkMRGIFrameContext& frame, vtkMRGIBMRLevels* levels, vtkTextureObject* target)
{
  Internals& in = *this->Internal;
  vtkOpenGLRenderWindow* window = frame.Window;
  const int W = frame.Viewport[2], H = frame.Viewport[3];
  if (!window || !levels || !target || W < 1 || H < 1 || levels->GetWidth() != W ||
    levels->GetHeight() != H)
  {
    vtkErrorMacro("BMR blend needs a target and levels prepared for the frame's " << W << " x " << H
                                                                                  << " viewport");
    return false;
  }
  if (static_cast<int>(target->GetWidth()) < frame.Viewport[0] + W ||
    static_cast<int>(target->GetHeight()) < frame.Viewport[1] + H)
  {
    vtkErrorMacro("BMR blend: the target (" << target->GetWidth() << " x " << target->GetHeight()
                                            << ") does not hold the frame's viewport");
    return false;
  }
  in.GL.Prepare(window);
  vtkOpenGLQuadHelper* quad =
    in.GL.Programs.Ready(window, "bmr.blend", "", [] { return vtkMRGIBMRBlendFS; });
  if (!quad)
  {
    vtkErrorMacro("could not build the BMR blend shader");
    return false;
  }
  vtkShaderProgram* p = quad->Program;
  vtkMRGIShaderUtilities::ScopedStage step(frame.Timer, "bmr.blend");
  {
    vtkMRGIFullScreenStep steps(window, in.GL.FrameBuffer);
    steps.Target(target, nullptr, frame.Viewport[0], frame.Viewport[1], W, H);
    vtkTextureObject* c0 = levels->GetColorTexture(0);
    vtkTextureObject* c1 = levels->GetColorTexture(1);
    vtkTextureObject* c2 = levels->GetColorTexture(2);
    vtkTextureObject* c3 = levels->GetColorTexture(3);
    vtkTextureObject* m0 = levels->GetMaskTexture(0);
    vtkTextureObject* m1 = levels->GetMaskTexture(1);
    vtkTextureObject* m2 = levels->GetMaskTexture(2);
    vtkTextureObject* m3 = levels->GetMaskTexture(3);
    vtkMRGIFullScreenStep::BindInputs(p, { c0, c1, c2, c3, m0, m1, m2, m3 });
    const int offset[2] = { frame.Viewport[0], frame.Viewport[1] };
    p->SetUniform2i("mrgiOffset", offset);
    int sizes[2 * MRGI_BMR_LEVELS];
    float weights[MRGI_BMR_LEVELS];
    for (int k = 0; k < MRGI_BMR_LEVELS; ++k)
    {
      levels->GetLevelSize(k, sizes + 2 * k);
      weights[k] = static_cast<float>(this->Weight[k]);
    }
    for (int k = 0; k < MRGI_BMR_LEVELS; ++k)
    {
      p->SetUniform2i(("mrgiLevelSize[" + std::to_string(k) + "]").c_str(), sizes + 2 * k);
    }
    p->SetUniform1fv("mrgiWeight", MRGI_BMR_LEVELS, weights);
    quad->Render();
    vtkMRGIFullScreenStep::UnbindInputs({ c0, c1, c2, c3, m0, m1, m2, m3 });
  }
  const GLenum error = glGetError();
  if (error != GL_NO_ERROR)
  {
    vtkErrorMacro("OpenGL error " << error << " in the BMR blend");
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
void vtkMRGIBMRBlend::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  for (int k = 0; k < MRGI_BMR_LEVELS; ++k)
  {
    os << indent << "Weight " << k + 1 << ": " << this->Weight[k] << "\n";
  }
}

//------------------------------------------------------------------------------
bool vtkMRGIBMRBlend::RenderMultiresolution(const vtkMRGIFrameContext& frame,
  vtkMRGIBMRMask* mask, vtkMRGIBMRBlend* blend, vtkMRGIBMRLevels* levels,
  const std::function<bool(vtkMRGIBMRLevels*)>& computeLevels, vtkTextureObject* target)
{
  const int w = frame.Viewport[2], h = frame.Viewport[3];
  if (!levels)
  {
    vtkGenericWarningMacro("a multiresolution effect needs its BMR levels");
    return false;
  }
  if (!frame.Window || !mask || !blend || !target || w < 1 || h < 1 ||
    target->GetWidth() < static_cast<unsigned int>(w) ||
    target->GetHeight() < static_cast<unsigned int>(h))
  {
    vtkErrorWithObjectMacro(levels,
      "a multiresolution effect needs the frame's window, a viewport, its mask, blend and "
      "levels, and a target at least as large as the viewport");
    return false;
  }
  if (!levels->Prepare(frame.Window, w, h))
  {
    vtkErrorWithObjectMacro(levels, "could not allocate the BMR levels (" << w << " x " << h << ")");
    return false;
  }
  // The blend writes the frame's viewport at its origin; the target is
  // viewport-sized at (0, 0), so the origin is moved.
  vtkMRGIFrameContext atOrigin = frame;
  atOrigin.Viewport[0] = atOrigin.Viewport[1] = 0;
  return mask->Build(frame, levels, nullptr) && computeLevels(levels) &&
    blend->Blend(atOrigin, levels, target);
}
