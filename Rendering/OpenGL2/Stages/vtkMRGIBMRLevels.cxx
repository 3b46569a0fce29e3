#include "vtk_glew.h"

#include "vtkMRGIBMRLevels.h"

#include "vtkFloatArray.h"
#include "vtkMRGIFrameContext.h"
#include "vtkMRGIFullScreenStep.h"
#include "vtkMRGIShaderUtilities.h"
#include "vtkMRGIStageResources.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"
#include "vtkTextureObject.h"
#include "vtkUnsignedCharArray.h"

#include "mrgi_bmr_mask.h"

#include <algorithm>
#include <vector>

vtkStandardNewMacro(vtkMRGIBMRLevels);

struct vtkMRGIBMRLevels::Internals
{
  vtkTextureObject* Color[MRGI_BMR_LEVELS] = {};
  vtkTextureObject* Mask[MRGI_BMR_LEVELS] = {};
  vtkTextureObject* DepthStencil[MRGI_BMR_LEVELS] = {};
  int LevelSize[MRGI_BMR_LEVELS][2] = {};
  vtkMRGIStageResources GL; // the framebuffer (no programs)

  void ReleaseTextures(vtkWindow* w)
  {
    for (int k = 0; k < MRGI_BMR_LEVELS; ++k)
    {
      vtkMRGIShaderUtilities::ReleaseTexture(this->Color[k], w);
      vtkMRGIShaderUtilities::ReleaseTexture(this->Mask[k], w);
      vtkMRGIShaderUtilities::ReleaseTexture(this->DepthStencil[k], w);
      this->LevelSize[k][0] = this->LevelSize[k][1] = 0;
    }
  }
};

//------------------------------------------------------------------------------
vtkMRGIBMRLevels::vtkMRGIBMRLevels()
  : Internal(new Internals)
{
}

//------------------------------------------------------------------------------
vtkMRGIBMRLevels::~vtkMRGIBMRLevels()
{
  if (this->Internal->GL.FrameBuffer || this->Internal->Color[0])
  {
    vtkErrorMacro("GL resources should have been freed in ReleaseGraphicsResources().");
  }
  this->Internal->ReleaseTextures(nullptr);
}

//------------------------------------------------------------------------------
int vtkMRGIBMRLevels::GetNumberOfLevels()
{
  return MRGI_BMR_LEVELS;
}

//------------------------------------------------------------------------------
void vtkMRGIBMRLevels::ReleaseGraphicsResources(vtkWindow* w)
{
  this->Internal->ReleaseTextures(w);
  this->Internal->GL.Release(w);
  this->Size[0] = this->Size[1] = 0;
}

//------------------------------------------------------------------------------
bool vtkMRGIBMRLevels::Prepare(vtkOpenGLRenderWindow* window, int width, int height)
{
  Internals& in = *this->Internal;
  if (!window || width < 1 || height < 1)
  {
    vtkErrorMacro("Prepare needs a window and a frame of at least 1 x 1 pixels, got "
      << width << " x " << height);
    return false;
  }
  in.GL.Prepare(window);
  if (this->Size[0] == width && this->Size[1] == height && in.Color[0])
  {
    return true;
  }
  in.ReleaseTextures(window);
  this->Size[0] = this->Size[1] = 0;
  for (int k = 0; k < MRGI_BMR_LEVELS; ++k)
  {
    const int scale = 1 << k;
    const int w = (width + scale - 1) / scale, h = (height + scale - 1) / scale;
    in.Color[k] = vtkMRGIShaderUtilities::NewTexture(window, GL_RGBA32F, w, h);
    in.Mask[k] = vtkMRGIShaderUtilities::NewTexture(window, GL_RGBA32F, w, h);
    in.DepthStencil[k] = vtkMRGIShaderUtilities::NewDepthStencil(window, w, h);
    if (!in.Color[k] || !in.Mask[k] || !in.DepthStencil[k])
    {
      in.ReleaseTextures(window);
      vtkErrorMacro("could not allocate the BMR level " << k + 1 << " (" << w << " x " << h << ")");
      return false;
    }
    in.LevelSize[k][0] = w;
    in.LevelSize[k][1] = h;
  }
  this->Size[0] = width;
  this->Size[1] = height;
  return true;
}

//------------------------------------------------------------------------------
bool vtkMRGIBMRLevels::GetLevelSize(int level, int size[2]) const
{
  if (level < 0 || level >= MRGI_BMR_LEVELS || !this->Internal->Color[level])
  {
    return false;
  }
  size[0] = this->Internal->LevelSize[level][0];
  size[1] = this->Internal->LevelSize[level][1];
  return true;
}

//------------------------------------------------------------------------------
vtkTextureObject* vtkMRGIBMRLevels::GetColorTexture(int level) const
{
  return level >= 0 && level < MRGI_BMR_LEVELS ? this->Internal->Color[level] : nullptr;
}

//------------------------------------------------------------------------------
vtkTextureObject* vtkMRGIBMRLevels::GetMaskTexture(int level) const
{
  return level >= 0 && level < MRGI_BMR_LEVELS ? this->Internal->Mask[level] : nullptr;
}

//------------------------------------------------------------------------------
vtkTextureObject* vtkMRGIBMRLevels::GetDepthStencilTexture(int level) const
{
  return level >= 0 && level < MRGI_BMR_LEVELS ? this->Internal->DepthStencil[level] : nullptr;
}

//------------------------------------------------------------------------------
vtkOpenGLFramebufferObject* vtkMRGIBMRLevels::GetFramebuffer() const
{
  return this->Internal->GL.FrameBuffer;
}

//------------------------------------------------------------------------------
namespace
{
bool ReadRGBA(vtkRenderWindow* window, vtkTextureObject* texture, vtkFloatArray* rgba)
{
  vtkOpenGLRenderWindow* renWin = vtkOpenGLRenderWindow::SafeDownCast(window);
  std::vector<float> data;
  if (!renWin || !rgba || !texture ||
    !vtkMRGIShaderUtilities::ReadTextureRGBA(renWin, texture, data))
  {
    return false;
  }
  rgba->SetNumberOfComponents(4);
  rgba->SetNumberOfTuples(static_cast<vtkIdType>(data.size() / 4));
  std::copy(data.begin(), data.end(), rgba->GetPointer(0));
  return true;
}
}

//------------------------------------------------------------------------------
bool vtkMRGIBMRLevels::ReadColor(vtkRenderWindow* window, int level, vtkFloatArray* rgba)
{
  if (!ReadRGBA(window, this->GetColorTexture(level), rgba))
  {
    vtkErrorMacro("ReadColor: no level " << level << " to read");
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkMRGIBMRLevels::ReadMask(vtkRenderWindow* window, int level, vtkFloatArray* rgba)
{
  if (!ReadRGBA(window, this->GetMaskTexture(level), rgba))
  {
    vtkErrorMacro("ReadMask: no level " << level << " to read");
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkMRGIBMRLevels::ReadStencil(
  vtkRenderWindow* window, int level, vtkUnsignedCharArray* stencil)
{
  vtkOpenGLRenderWindow* renWin = vtkOpenGLRenderWindow::SafeDownCast(window);
  int size[2];
  vtkOpenGLFramebufferObject* fbo = this->Internal->GL.FrameBuffer;
  if (!renWin || !stencil || !fbo || !this->GetLevelSize(level, size))
  {
    vtkErrorMacro("ReadStencil: no level " << level << " to read");
    return false;
  }
  stencil->SetNumberOfComponents(1);
  stencil->SetNumberOfTuples(static_cast<vtkIdType>(size[0]) * size[1]);
  renWin->MakeCurrent();
  vtkOpenGLState* ostate = renWin->GetState();
  ostate->PushReadFramebufferBinding();
  fbo->Bind(GL_READ_FRAMEBUFFER);
  // VTK 9.1 attaches depth-stencil textures at GL_DEPTH_ATTACHMENT only.
  glFramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_TEXTURE_2D,
    this->Internal->DepthStencil[level]->GetHandle(), 0);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, size[0], size[1], GL_STENCIL_INDEX, GL_UNSIGNED_BYTE, stencil->GetPointer(0));
  glFramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_TEXTURE_2D, 0, 0);
  ostate->PopReadFramebufferBinding();
  return glGetError() == GL_NO_ERROR;
}

//------------------------------------------------------------------------------
void vtkMRGIBMRLevels::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Size: " << this->Size[0] << " x " << this->Size[1] << "\n";
}

//------------------------------------------------------------------------------
vtkMRGIBMRLevels::LevelStep::LevelStep(
  vtkOpenGLRenderWindow* window, vtkMRGIBMRLevels* levels, int level)
{
  int size[2];
  if (!window || !levels || !levels->GetFramebuffer() || !levels->GetLevelSize(level, size))
  {
    return;
  }
  this->Step.reset(new vtkMRGIFullScreenStep(window, levels->GetFramebuffer()));
  this->Step->Target(levels->GetColorTexture(level), nullptr, 0, 0, size[0], size[1]);
  // Clears the colour target to 0 and tests stencil == 1.
  this->Step->BeginStencilRead(levels->GetDepthStencilTexture(level));
}

//------------------------------------------------------------------------------
vtkMRGIBMRLevels::LevelStep::~LevelStep()
{
  if (this->Step)
  {
    this->Step->EndStencilRead();
  }
}

//------------------------------------------------------------------------------
bool vtkMRGIBMRLevels::CheckLevelTarget(vtkObject* reporter, const char* effect, int level,
  int maxLevel, int width, int height, vtkTextureObject* target, int levelSize[2])
{
  if (!target)
  {
    vtkErrorWithObjectMacro(reporter, << effect << " needs a target");
    return false;
  }
  if (level < 0 || level > maxLevel)
  {
    vtkErrorWithObjectMacro(
      reporter, << effect << " level " << level << " is outside 0.." << maxLevel);
    return false;
  }
  const int side = 1 << level;
  levelSize[0] = (width + side - 1) / side;
  levelSize[1] = (height + side - 1) / side;
  if (target->GetWidth() < static_cast<unsigned int>(levelSize[0]) ||
    target->GetHeight() < static_cast<unsigned int>(levelSize[1]))
  {
    vtkErrorWithObjectMacro(reporter,
      << effect << " target " << target->GetWidth() << " x " << target->GetHeight()
      << " is smaller than level " << level << " (" << levelSize[0] << " x " << levelSize[1]
      << ")");
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkMRGIBMRLevels::RenderLevels(vtkOpenGLRenderWindow* window, vtkMRGIBMRLevels* levels,
  const std::function<bool(int level)>& renderLevel)
{
  for (int k = 0; k < GetNumberOfLevels(); ++k)
  {
    LevelStep step(window, levels, k);
    if (!step.IsValid())
    {
      vtkErrorWithObjectMacro(levels, "could not bind BMR level " << k);
      return false;
    }
    if (!renderLevel(k))
    {
      return false;
    }
  }
  const GLenum error = glGetError();
  if (error != GL_NO_ERROR)
  {
    vtkErrorWithObjectMacro(levels, "OpenGL error " << error << " rendering the BMR levels");
    return false;
  }
  return true;
}

