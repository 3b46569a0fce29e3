#include "vtk_glew.h"

#include "vtkMRGIUpsample.h"

#include "vtkFloatArray.h"
#include "vtkMRGIFrameContext.h"
#include "vtkMRGIFullScreenStep.h"
#include "vtkMRGIMultiresolution.h"
#include "vtkMRGIProgramCache.h"
#include "vtkMRGIStageResources.h"
#include "vtkMRGIShaderUtilities.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLQuadHelper.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"

#include "vtkMRGIMultiresUpsampleFS.h"

#include "mrgi_multires.h"

#include <algorithm>
#include <array>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkMRGIUpsample);

struct vtkMRGIUpsample::Internals
{
  // The state/value and the filtered value, each one level-0-sized texture
  // that every level uses in its lower-left corner: level i writes its value
  // (reading level i+1's filtered value as parent), then filters it into
  // Filtered over level i+1's, which nothing reads any more. Reads stay in
  // the level's rectangle (the filter clamps to mrgiSize; a parent texel t/2
  // is inside the coarser level as its sides are ceil(side / 2)), so the
  // stale texels of other levels around it are never read. Two textures
  // instead of two per level: 32 instead of about 43 bytes per pixel.
  // Value is the caller's scratch texture when Upsample() was given one
  // (Own holds no texture then), else Own.
  vtkTextureObject* Own = nullptr;
  vtkTextureObject* Value = nullptr;
  vtkTextureObject* Filtered = nullptr;
  int Levels = 0;
  int Size[2] = { 0, 0 };
  vtkMRGIStageResources GL; // framebuffer and programs

  vtkOpenGLQuadHelper* Ready(vtkOpenGLRenderWindow* window, int stage)
  {
    return this->GL.Programs.Ready(window, "upsample", "#define MRGI_MR_STAGE " + std::to_string(stage) + "\n",
      [] { return vtkMRGIMultiresUpsampleFS; });
  }

  void ReleaseTextures(vtkWindow* w)
  {
    vtkMRGIShaderUtilities::ReleaseTexture(this->Own, w);
    vtkMRGIShaderUtilities::ReleaseTexture(this->Filtered, w);
    this->Value = nullptr;
    this->Levels = 0;
    this->Size[0] = this->Size[1] = 0;
  }

  // The level textures and framebuffer for `layout`, the value in
  // `scratch` when it fits; false when they cannot be allocated.
  bool Prepare(
    vtkOpenGLRenderWindow* window, const mrgi_multires_layout& layout, vtkTextureObject* scratch)
  {
    const bool useScratch = scratch && scratch->GetHandle() != 0 &&
      scratch->GetWidth() >= static_cast<unsigned int>(layout.width) &&
      scratch->GetHeight() >= static_cast<unsigned int>(layout.height) &&
      scratch->GetInternalFormat(VTK_FLOAT, 4, false) == GL_RGBA32F;
    if (this->Size[0] != layout.width || this->Size[1] != layout.height)
    {
      this->ReleaseTextures(window);
      this->Filtered = vtkMRGIShaderUtilities::NewTexture(window, GL_RGBA32F, layout.width, layout.height);
      if (!this->Filtered)
      {
        return false;
      }
      this->Size[0] = layout.width;
      this->Size[1] = layout.height;
    }
    if (useScratch)
    {
      vtkMRGIShaderUtilities::ReleaseTexture(this->Own, window);
    }
    else if (!this->Own)
    {
      this->Own = vtkMRGIShaderUtilities::NewTexture(window, GL_RGBA32F, layout.width, layout.height);
      if (!this->Own)
      {
        this->ReleaseTextures(window);
        return false;
      }
    }
    this->Value = useScratch ? scratch : this->Own;
    this->Levels = layout.level_count;
    this->GL.Prepare(window);
    return true;
  }
};

//------------------------------------------------------------------------------
vtkMRGIUpsample::vtkMRGIUpsample()
  : Internal(new Internals)
{
}

//------------------------------------------------------------------------------
vtkMRGIUpsample::~vtkMRGIUpsample()
{
  if (this->Internal->GL.FrameBuffer || this->Internal->Own || this->Internal->Filtered)
  {
    vtkErrorMacro("GL resources should have been freed in ReleaseGraphicsResources().");
  }
  this->Internal->ReleaseTextures(nullptr);
}

//------------------------------------------------------------------------------
void vtkMRGIUpsample::ReleaseGraphicsResources(vtkWindow* w)
{
  Internals& in = *this->Internal;
  in.ReleaseTextures(w);
  in.GL.Release(w);
}

//------------------------------------------------------------------------------
bool vtkMRGIUpsample::Upsample(const vtkMRGIFrameContext& frame, vtkMRGIMultiresolution* buffer,
  vtkTextureObject* irradiance, vtkTextureObject* rendered, int mode, double maskWeight,
  vtkTextureObject* scratch)
{
  Internals& in = *this->Internal;
  vtkOpenGLRenderWindow* window = frame.Window;
  mrgi_multires_layout layout;
  if (!window || !buffer || !irradiance || !rendered || !buffer->GetLayout(&layout))
  {
    vtkErrorMacro("Upsample needs the buffer's selection, a gather's irradiance and the mask it rendered");
    return false;
  }
  if (!in.Prepare(window, layout, scratch))
  {
    vtkErrorMacro("could not allocate the upsampling buffers (" << layout.width << " x " << layout.height << ")");
    return false;
  }
  vtkOpenGLQuadHelper* stateQuad = in.Ready(window, 0);
  vtkOpenGLQuadHelper* filterQuad = in.Ready(window, 1);
  if (!stateQuad || !filterQuad)
  {
    vtkErrorMacro("could not build the multiresolution upsampling shaders");
    return false;
  }
  vtkShaderProgram* state = stateQuad->Program;
  vtkShaderProgram* filter = filterQuad->Program;
  const int coarsest = layout.level_count - 1;
  vtkMRGIShaderUtilities::ScopedStage step(frame.Timer, "upsample.levels");
  vtkMRGIFullScreenStep steps(window, in.GL.FrameBuffer);
  for (int i = coarsest; i >= 0; --i)
  {
    const int w = layout.level_width[i], h = layout.level_height[i];
    vtkTextureObject* value = in.Value;
    vtkTextureObject* filtered = in.Filtered;
    // The parent is level i+1's filtered value, still in Filtered. The
    // coarsest level has no parent: its mipmap stands in, unread.
    vtkTextureObject* parent = i == coarsest ? buffer->GetMipmapTexture(i, MRGI_MULTIRES_TEX_DEPTH) : in.Filtered;
    vtkTextureObject* flags = buffer->GetFlagsTexture(i);
    window->GetShaderCache()->ReadyShaderProgram(state);
    steps.Target(value, nullptr, 0, 0, w, h);
    // The texels the gather rendered: the selection, the incremental
    // stencil (NPW10 3.4 step 3: upsample where not rendered) or the
    // specular stencil (NPW10 3.2.1).
    vtkMRGIFullScreenStep::BindInputs(state, { rendered, flags, irradiance, parent });
    const int offset[2] = { layout.level_offset[i], 0 };
    state->SetUniform2i("mrgiOffset", offset);
    state->SetUniformi("mrgiCoarsest", i == coarsest ? 1 : 0);
    stateQuad->Render();
    vtkMRGIFullScreenStep::UnbindInputs({ rendered, flags, irradiance, parent });

    window->GetShaderCache()->ReadyShaderProgram(filter);
    steps.Target(filtered, nullptr, 0, 0, w, h);
    vtkMRGIFullScreenStep::BindInputs(filter, { value });
    const int size[2] = { w, h };
    filter->SetUniform2i("mrgiSize", size);
    filter->SetUniformi("mrgiMode", mode == UpsampleMaskWeighted ? 1 : 0);
    filter->SetUniformf("mrgiMaskWeight", static_cast<float>(maskWeight));
    filterQuad->Render();
    vtkMRGIFullScreenStep::UnbindInputs({ value });
  }
  const GLenum error = glGetError();
  if (error != GL_NO_ERROR)
  {
    vtkErrorMacro("OpenGL error " << error << " in the multiresolution upsampling");
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkMRGIUpsample::Resolve(const vtkMRGIFrameContext& frame, vtkMRGIMultiresolution* buffer,
  vtkTextureObject* albedo, vtkTextureObject* irradianceTarget, vtkTextureObject* target,
  double strength, double surfaceDetail)
{
  Internals& in = *this->Internal;
  vtkOpenGLRenderWindow* window = frame.Window;
  vtkOpenGLQuadHelper* resolveQuad = window ? in.Ready(window, 2) : nullptr;
  vtkShaderProgram* resolve = resolveQuad ? resolveQuad->Program : nullptr;
  vtkTextureObject* position = frame.Position;
  vtkTextureObject* normal = frame.Normal;
  const int x0 = frame.Viewport[0], y0 = frame.Viewport[1];
  const bool parallel = frame.Parallel;
  mrgi_multires_layout layout;
  if (!resolve || !buffer || !buffer->GetLayout(&layout) || in.Size[0] != layout.width ||
    in.Size[1] != layout.height || !albedo || !position || !normal || !irradianceTarget || !target)
  {
    vtkErrorMacro("Resolve needs Upsample() first, the G-buffer and both targets");
    return false;
  }
  {
    vtkMRGIShaderUtilities::ScopedStage step(frame.Timer, "upsample.resolve");
    vtkMRGIFullScreenStep steps(window, in.GL.FrameBuffer);
    steps.Target(irradianceTarget, target, x0, y0, layout.width, layout.height);
    vtkTextureObject* flags = buffer->GetFlagsTexture(0);
    vtkMRGIFullScreenStep::BindInputs(resolve, { in.Filtered, flags, albedo, position, normal });
    const int offset[2] = { x0, y0 };
    resolve->SetUniform2i("mrgiOffset", offset);
    resolve->SetUniformf("mrgiStrength", static_cast<float>(strength));
    resolve->SetUniformf("mrgiSurfaceDetail", static_cast<float>(surfaceDetail));
    resolve->SetUniformi("mrgiParallel", parallel ? 1 : 0);
    resolveQuad->Render();
    vtkMRGIFullScreenStep::UnbindInputs({ in.Filtered, flags, albedo, position, normal });
  }
  return glGetError() == GL_NO_ERROR;
}

//------------------------------------------------------------------------------
bool vtkMRGIUpsample::ReadUpsampled(vtkRenderWindow* window, vtkFloatArray* upsampled)
{
  vtkOpenGLRenderWindow* renWin = vtkOpenGLRenderWindow::SafeDownCast(window);
  Internals& in = *this->Internal;
  std::vector<float> rgba;
  if (!renWin || !upsampled || !in.Filtered ||
    !vtkMRGIShaderUtilities::ReadTextureRGBA(renWin, in.Filtered, rgba))
  {
    vtkErrorMacro("ReadUpsampled: nothing upsampled yet");
    return false;
  }
  upsampled->SetNumberOfComponents(4);
  upsampled->SetNumberOfTuples(static_cast<vtkIdType>(rgba.size() / 4));
  std::copy(rgba.begin(), rgba.end(), upsampled->GetPointer(0));
  return true;
}

//------------------------------------------------------------------------------
void vtkMRGIUpsample::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Levels: " << this->Internal->Levels << "\n";
}
