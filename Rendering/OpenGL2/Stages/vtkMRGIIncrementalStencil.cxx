#include "vtk_glew.h"

#include "vtkMRGIIncrementalStencil.h"

#include "vtkMRGIFrameContext.h"
#include "vtkMRGIFullScreenStep.h"
#include "vtkMRGIMultiresolution.h"
#include "vtkMRGIProgramCache.h"
#include "vtkMRGIStageResources.h"
#include "vtkMRGIShaderLibraries.h"
#include "vtkMRGIShaderUtilities.h"
#include "vtkMRGIVisibilityPyramid.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLQuadHelper.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"
#include "vtkUnsignedCharArray.h"


#include "mrgi_area_light.h"
#include "mrgi_incremental_stencil.h"
#include "mrgi_irradiance_stencil.h"
#include "mrgi_multires.h"
#include "mrgi_visibility_pyramid.h"

#include <algorithm>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkMRGIIncrementalStencil);

struct vtkMRGIIncrementalStencil::Internals
{
  // The texels the area-light gather renders, as colour and stencil
  // (flattened layout), and the layout they were built for.
  vtkTextureObject* FlatIncremental = nullptr;
  vtkTextureObject* IncrementalDepthStencil = nullptr;
  mrgi_multires_layout Layout{};
  bool Built = false;
  vtkMRGIStageResources GL; // framebuffer and programs

  void ReleaseTextures(vtkWindow* w)
  {
    vtkMRGIShaderUtilities::ReleaseTexture(this->FlatIncremental, w);
    vtkMRGIShaderUtilities::ReleaseTexture(this->IncrementalDepthStencil, w);
    this->Built = false;
  }

  // The targets for `layout`; false when they cannot be allocated.
  bool Prepare(vtkOpenGLRenderWindow* window, const mrgi_multires_layout& layout)
  {
    this->Built = false;
    if (this->FlatIncremental &&
      (this->Layout.total_width != layout.total_width || this->Layout.total_height != layout.total_height))
    {
      this->ReleaseTextures(window);
    }
    if (!this->FlatIncremental)
    {
      this->FlatIncremental =
        vtkMRGIShaderUtilities::NewMaskTexture(window, layout.total_width, layout.total_height);
      this->IncrementalDepthStencil =
        vtkMRGIShaderUtilities::NewDepthStencil(window, layout.total_width, layout.total_height);
    }
    this->Layout = layout;
    this->GL.Prepare(window);
    if (!this->FlatIncremental || !this->IncrementalDepthStencil)
    {
      this->ReleaseTextures(window);
      return false;
    }
    return true;
  }
};

//------------------------------------------------------------------------------
vtkMRGIIncrementalStencil::vtkMRGIIncrementalStencil()
  : IrradianceTolerance(MRGI_IRRADIANCE_STENCIL_DEFAULT_TOLERANCE)
  , IlluminationThreshold(MRGI_INCREMENTAL_ILLUMINATION_DEFAULT_THRESHOLD)
  , IlluminationMetric(MRGI_INCREMENTAL_ILLUMINATION_DIFFERENCE)
  , Internal(new Internals)
{
}

//------------------------------------------------------------------------------
vtkMRGIIncrementalStencil::~vtkMRGIIncrementalStencil()
{
  if (this->Internal->GL.FrameBuffer || this->Internal->FlatIncremental)
  {
    vtkErrorMacro("GL resources should have been freed in ReleaseGraphicsResources().");
  }
  this->Internal->ReleaseTextures(nullptr);
}

//------------------------------------------------------------------------------
void vtkMRGIIncrementalStencil::ReleaseGraphicsResources(vtkWindow* w)
{
  Internals& in = *this->Internal;
  in.ReleaseTextures(w);
  in.GL.Release(w);
}

//------------------------------------------------------------------------------
bool vtkMRGIIncrementalStencil::Build(const vtkMRGIFrameContext& frame,
  vtkMRGIMultiresolution* buffer, vtkMRGIVisibilityPyramid* masks, const mrgi_area_light_uniforms* light)
{
  // NPW10 3.4, one draw per level into its rectangle of the flattened
  // layout: a texel is rendered when selected, or when its parent's 3x3
  // masks show a light discontinuity (mrgi_incremental_stencil_build()).
  // Each draw reads the coarser level's masks and receivers only, so the
  // levels are independent and the order does not matter.
  Internals& in = *this->Internal;
  vtkOpenGLRenderWindow* window = frame.Window;
  mrgi_multires_layout layout;
  in.Built = false;
  if (!window || !buffer || !masks || !buffer->HasReceivers() || !buffer->GetLayout(&layout))
  {
    vtkErrorMacro("the incremental stencil needs the buffer's selection and receivers of this frame and its visibility masks");
    return false;
  }
  if (!in.Prepare(window, layout))
  {
    vtkErrorMacro("could not allocate the incremental stencil (" << layout.total_width << " x "
                                                                 << layout.total_height << ")");
    return false;
  }
  const int levels = layout.level_count;
  const int finest = buffer->GetFinestGatherLevel();
  const int words = masks->GetNumberOfMaskWords();
  const int targets = masks->GetNumberOfMaskTextures();
  const int threshold =
    mrgi_voxel_refine_threshold(static_cast<float>(this->Fraction),
      masks->GetNumberOfSamples());
  if (masks->GetNumberOfLevels() != levels || words < 1 || targets < 1 || targets > 4 ||
    threshold < 0)
  {
    vtkErrorMacro("the incremental stencil needs visibility masks of this frame's "
      << levels << " levels (they have " << masks->GetNumberOfLevels() << " levels, " << words
      << " words)");
    return false;
  }
  vtkOpenGLQuadHelper* quad = in.GL.Programs.Ready(window, "incremental",
    "#define MRGI_STENCIL_WORDS " + std::to_string(words) + "\n#define MRGI_STENCIL_TARGETS " +
      std::to_string(targets) + "\n",
    [] { return vtkMRGIShaderLibraries::Compose({ "vtkMRGIIncrementalStencilFS" }); });
  vtkShaderProgram* program = quad ? quad->Program : nullptr;
  if (!program)
  {
    vtkErrorMacro("could not build the incremental stencil shader");
    return false;
  }
  using vtkMRGIShaderUtilities::ScopedStage;
  ScopedStage step(frame.Timer, "select.incremental");
  vtkMRGIFullScreenStep steps(window, in.GL.FrameBuffer);
  vtkOpenGLState* ostate = steps.GetState();
  steps.Target(in.FlatIncremental, nullptr, 0, 0, layout.total_width, layout.total_height);
  steps.BeginMaskWrite(in.IncrementalDepthStencil);
  program->SetUniformi("mrgiThreshold", threshold);
  program->SetUniformi("mrgiMetric", masks->GetMetric());
  // The irradiance term (mrgi_irradiance_stencil.h), off without a light.
  program->SetUniformf(
    "mrgiIrradianceTolerance", light ? static_cast<float>(this->IrradianceTolerance) : 0.0f);
  program->SetUniformMatrix4x4("mrgiVCToWC", const_cast<float*>(frame.ViewToWorld));
  if (light)
  {
    program->SetUniform3f("mrgiAreaCenter", light->center);
    program->SetUniform3f("mrgiAreaNormal", light->normal);
    program->SetUniform3fv("mrgiAreaCorners", 4, light->corners);
    program->SetUniformf("mrgiAreaArea", light->area);
    program->SetUniformi("mrgiAreaTwoSided", light->two_sided);
  }
  bool ok = true;
  for (int i = finest; i < levels && ok; ++i)
  {
    // The coarsest level has no parent: its own receivers and masks stand
    // in, unread.
    const int parent = std::min(i + 1, levels - 1);
    std::vector<vtkTextureObject*> inputs = { buffer->GetFlagsTexture(i), buffer->GetSelectionTexture(),
      buffer->GetReceiverTexture(parent, 0), buffer->GetReceiverTexture(parent, 1) };
    const char* names[8] = { "mrgiFlags", "mrgiSelection", "mrgiParentPosition", "mrgiParentNormal",
      "mrgiParentMask0",
      "mrgiParentMask1", "mrgiParentMask2", "mrgiParentMask3" };
    for (int k = 0; k < targets; ++k)
    {
      vtkTextureObject* m = masks->GetMaskTexture(parent, k);
      ok = ok && m != nullptr;
      inputs.push_back(m);
    }
    if (!ok)
    {
      vtkErrorMacro("the visibility masks of level " << parent << " are missing");
      break;
    }
    for (size_t k = 0; k < inputs.size(); ++k)
    {
      inputs[k]->Activate();
      program->SetUniformi(names[k], inputs[k]->GetTextureUnit());
    }
    const int parentSize[2] = { layout.level_width[parent], layout.level_height[parent] };
    program->SetUniformi("mrgiLevelOffset", layout.level_offset[i]);
    program->SetUniform2i("mrgiParentSize", parentSize);
    program->SetUniformi("mrgiFinest", i == finest ? 1 : 0);
    program->SetUniformi("mrgiCoarsest", i == levels - 1 ? 1 : 0);
    ostate->vtkglViewport(layout.level_offset[i], 0, layout.level_width[i], layout.level_height[i]);
    quad->Render();
    for (vtkTextureObject* t : inputs)
    {
      t->Deactivate();
    }
  }
  steps.EndMaskWrite();
  const GLenum error = glGetError();
  if (error != GL_NO_ERROR)
  {
    vtkErrorMacro("OpenGL error 0x" << std::hex << error << " in the incremental stencil");
    return false;
  }
  in.Built = ok;
  return ok;
}

//------------------------------------------------------------------------------
bool vtkMRGIIncrementalStencil::BeginIllumination(
  const vtkMRGIFrameContext& frame, vtkMRGIMultiresolution* buffer)
{
  Internals& in = *this->Internal;
  mrgi_multires_layout layout;
  in.Built = false;
  if (!frame.Window || !buffer || !buffer->HasReceivers() || !buffer->GetLayout(&layout))
  {
    vtkErrorMacro("the illumination stencil needs the buffer's selection and receivers of this frame");
    return false;
  }
  if (!in.Prepare(frame.Window, layout))
  {
    vtkErrorMacro("could not allocate the illumination stencil (" << layout.total_width << " x "
                                                                  << layout.total_height << ")");
    return false;
  }
  {
    vtkMRGIFullScreenStep steps(frame.Window, in.GL.FrameBuffer);
    steps.Target(in.FlatIncremental, nullptr, 0, 0, layout.total_width, layout.total_height);
    steps.BeginMaskWrite(in.IncrementalDepthStencil);
    steps.EndMaskWrite();
  }
  in.Built = glGetError() == GL_NO_ERROR;
  return in.Built;
}

//------------------------------------------------------------------------------
bool vtkMRGIIncrementalStencil::BuildIlluminationLevel(const vtkMRGIFrameContext& frame,
  vtkMRGIMultiresolution* buffer, vtkTextureObject* irradiance, int level)
{
  // mrgi_incremental_stencil_illumination_level(): level `level` only, read
  // from the irradiance of level + 1 (its alpha says where it was gathered).
  Internals& in = *this->Internal;
  vtkOpenGLRenderWindow* window = frame.Window;
  mrgi_multires_layout layout;
  const int finest = buffer ? buffer->GetFinestGatherLevel() : 0;
  if (!in.Built || !window || !buffer || !irradiance || !buffer->GetLayout(&layout) ||
    layout.total_width != in.Layout.total_width || layout.total_height != in.Layout.total_height ||
    level < std::min(finest, layout.level_count - 1) || level >= layout.level_count)
  {
    vtkErrorMacro("BuildIlluminationLevel: level " << level
                                                   << " without BeginIllumination() on this buffer "
                                                      "or outside its gathering levels");
    return false;
  }
  vtkOpenGLQuadHelper* quad = in.GL.Programs.Ready(window, "illumination",
    "#define MRGI_STENCIL_ILLUMINATION 1\n",
    [] { return vtkMRGIShaderLibraries::Compose({ "vtkMRGIIncrementalStencilFS" }); });
  vtkShaderProgram* program = quad ? quad->Program : nullptr;
  if (!program)
  {
    vtkErrorMacro("could not build the illumination stencil shader");
    return false;
  }
  vtkMRGIShaderUtilities::ScopedStage step(frame.Timer, "select.illumination");
  const int levels = layout.level_count;
  const int parent = std::min(level + 1, levels - 1);
  vtkMRGIFullScreenStep steps(window, in.GL.FrameBuffer);
  steps.Target(in.FlatIncremental, nullptr, 0, 0, layout.total_width, layout.total_height);
  steps.BeginMaskWrite(in.IncrementalDepthStencil, false);
  const std::vector<vtkTextureObject*> inputs = { buffer->GetFlagsTexture(level),
    buffer->GetSelectionTexture(), buffer->GetReceiverTexture(parent, 0), irradiance };
  const char* names[4] = { "mrgiFlags", "mrgiSelection", "mrgiParentPosition",
    "mrgiParentIrradiance" };
  for (size_t k = 0; k < inputs.size(); ++k)
  {
    inputs[k]->Activate();
    program->SetUniformi(names[k], inputs[k]->GetTextureUnit());
  }
  const int parentSize[2] = { layout.level_width[parent], layout.level_height[parent] };
  program->SetUniformi("mrgiLevelOffset", layout.level_offset[level]);
  program->SetUniformi("mrgiParentOffset", layout.level_offset[parent]);
  program->SetUniform2i("mrgiParentSize", parentSize);
  program->SetUniformi("mrgiFinest", level == finest ? 1 : 0);
  program->SetUniformi("mrgiCoarsest", level == levels - 1 ? 1 : 0);
  program->SetUniformf("mrgiIlluminationThreshold", static_cast<float>(this->IlluminationThreshold));
  program->SetUniformi("mrgiIlluminationMetric", this->IlluminationMetric);
  steps.GetState()->vtkglViewport(
    layout.level_offset[level], 0, layout.level_width[level], layout.level_height[level]);
  quad->Render();
  for (vtkTextureObject* t : inputs)
  {
    t->Deactivate();
  }
  steps.EndMaskWrite();
  const GLenum error = glGetError();
  if (error != GL_NO_ERROR)
  {
    vtkErrorMacro("OpenGL error 0x" << std::hex << error << " in the illumination stencil");
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
vtkTextureObject* vtkMRGIIncrementalStencil::GetSelectionTexture() const
{
  return this->Internal->Built ? this->Internal->FlatIncremental : nullptr;
}

//------------------------------------------------------------------------------
vtkTextureObject* vtkMRGIIncrementalStencil::GetStencilTexture() const
{
  return this->Internal->Built ? this->Internal->IncrementalDepthStencil : nullptr;
}

//------------------------------------------------------------------------------
bool vtkMRGIIncrementalStencil::ReadStencil(vtkRenderWindow* window, vtkUnsignedCharArray* mask)
{
  vtkOpenGLRenderWindow* renWin = vtkOpenGLRenderWindow::SafeDownCast(window);
  Internals& in = *this->Internal;
  if (!renWin || !mask || !in.Built)
  {
    vtkErrorMacro("ReadStencil: no incremental stencil built");
    return false;
  }
  return vtkMRGIFullScreenStep::ReadMask(renWin, in.GL.FrameBuffer, in.Layout, in.FlatIncremental,
    in.IncrementalDepthStencil, false, mask);
}

//------------------------------------------------------------------------------
void vtkMRGIIncrementalStencil::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Fraction: " << this->Fraction << "\n";
  os << indent << "IrradianceTolerance: " << this->IrradianceTolerance << "\n";
  os << indent << "IlluminationThreshold: " << this->IlluminationThreshold << "\n";
  os << indent << "IlluminationMetric: " << this->IlluminationMetric << "\n";
}
