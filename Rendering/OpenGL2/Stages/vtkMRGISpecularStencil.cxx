#include "vtk_glew.h"

#include "vtkMRGISpecularStencil.h"

#include "vtkFloatArray.h"
#include "vtkMRGIFrameContext.h"
#include "vtkMRGIFullScreenStep.h"
#include "vtkMRGIMultiresolution.h"
#include "vtkMRGIProgramCache.h"
#include "vtkMRGIStageResources.h"
#include "vtkMRGIShaderLibraries.h"
#include "vtkMRGIShaderUtilities.h"
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
#include "mrgi_multires.h"
#include "mrgi_specular_stencil.h"

#include <algorithm>
#include <array>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkMRGISpecularStencil);

struct vtkMRGISpecularStencil::Internals
{
  // Material pyramid per level, refinement bits and selection (flattened),
  // its stencil; the layout they were built for.
  std::vector<vtkTextureObject*> SpecularMaterial;
  vtkTextureObject* FlatSpecularBits = nullptr;
  vtkTextureObject* FlatSpecularSelection = nullptr;
  vtkTextureObject* SpecularDepthStencil = nullptr;
  mrgi_multires_layout Layout{};
  bool SpecularStencilValid = false;
  vtkMRGIStageResources GL; // framebuffer and programs

  void ReleaseTextures(vtkWindow* w)
  {
    for (auto*& t : this->SpecularMaterial)
    {
      vtkMRGIShaderUtilities::ReleaseTexture(t, w);
    }
    this->SpecularMaterial.clear();
    vtkMRGIShaderUtilities::ReleaseTexture(this->FlatSpecularBits, w);
    vtkMRGIShaderUtilities::ReleaseTexture(this->FlatSpecularSelection, w);
    vtkMRGIShaderUtilities::ReleaseTexture(this->SpecularDepthStencil, w);
    this->SpecularStencilValid = false;
  }
};

namespace
{
vtkTextureObject* MakeFloatTexture(vtkOpenGLRenderWindow* window, int w, int h)
{
  return vtkMRGIShaderUtilities::NewTexture(window, GL_RGBA32F, w, h);
}
}

//------------------------------------------------------------------------------
vtkMRGISpecularStencil::vtkMRGISpecularStencil()
  : Internal(new Internals)
{
}

//------------------------------------------------------------------------------
vtkMRGISpecularStencil::~vtkMRGISpecularStencil()
{
  if (this->Internal->GL.FrameBuffer || this->Internal->FlatSpecularBits)
  {
    vtkErrorMacro("GL resources should have been freed in ReleaseGraphicsResources().");
  }
  this->Internal->ReleaseTextures(nullptr);
}

//------------------------------------------------------------------------------
void vtkMRGISpecularStencil::ReleaseGraphicsResources(vtkWindow* w)
{
  Internals& in = *this->Internal;
  in.ReleaseTextures(w);
  in.GL.Release(w);
}

//------------------------------------------------------------------------------
bool vtkMRGISpecularStencil::Build(const vtkMRGIFrameContext& frame,
  vtkMRGIMultiresolution* buffer, const mrgi_area_light_uniforms& light)
{
  // nichols-penmatsa-wyman-2010 3.2.1 ("when we create our depth and normal
  // mipmaps, we also compute the cross-sectional Phong lobe size at the
  // light") and 3.4 (the stencil from depth, normal and BRDF frequency
  // metrics): mrgi_specular_stencil.h. Material pyramid (one pass per
  // level), the refinement bits (one draw per level into the flattened
  // layout), then the selection with its stencil (one draw per level, each
  // walking its ancestors' bits).
  Internals& in = *this->Internal;
  in.SpecularStencilValid = false;
  vtkOpenGLRenderWindow* window = frame.Window;
  vtkTextureObject* position = frame.Position;
  vtkTextureObject* specular = frame.Specular;
  vtkTextureObject* shininess = frame.Shininess;
  const int x0 = frame.Viewport[0], y0 = frame.Viewport[1];
  mrgi_multires_layout layout;
  if (!window || !buffer || !position || !specular || !shininess || !buffer->HasReceivers() ||
    !buffer->GetLayout(&layout))
  {
    vtkErrorMacro("the specular stencil needs the buffer's selection and receivers of this frame and the G-buffer with its specular targets");
    return false;
  }
  const int levels = layout.level_count;
  const int finest = buffer->GetFinestGatherLevel();
  if (in.Layout.total_width != layout.total_width || in.Layout.total_height != layout.total_height ||
    in.Layout.width != layout.width || in.Layout.height != layout.height)
  {
    in.ReleaseTextures(window);
  }
  in.Layout = layout;
  in.GL.Prepare(window);
  if (in.SpecularMaterial.size() != static_cast<size_t>(levels))
  {
    for (auto*& t : in.SpecularMaterial)
    {
      vtkMRGIShaderUtilities::ReleaseTexture(t, window);
    }
    in.SpecularMaterial.assign(static_cast<size_t>(levels), nullptr);
    for (int i = 0; i < levels; ++i)
    {
      in.SpecularMaterial[static_cast<size_t>(i)] =
        MakeFloatTexture(window, layout.level_width[i], layout.level_height[i]);
    }
  }
  if (!in.FlatSpecularBits)
  {
    in.FlatSpecularBits = vtkMRGIShaderUtilities::NewFlagsTexture(window, layout.total_width, layout.total_height);
    in.FlatSpecularSelection = vtkMRGIShaderUtilities::NewMaskTexture(window, layout.total_width, layout.total_height);
    in.SpecularDepthStencil =
      vtkMRGIShaderUtilities::NewDepthStencil(window, layout.total_width, layout.total_height);
  }
  if (!in.FlatSpecularBits || !in.FlatSpecularSelection || !in.SpecularDepthStencil ||
    std::find(in.SpecularMaterial.begin(), in.SpecularMaterial.end(), nullptr) != in.SpecularMaterial.end())
  {
    vtkErrorMacro("could not allocate the specular stencil's buffers");
    return false;
  }
  vtkOpenGLQuadHelper* quads[4];
  vtkShaderProgram* programs[4];
  for (int stage = 0; stage < 4; ++stage)
  {
    quads[stage] = in.GL.Programs.Ready(window, "specular.stencil",
      "#define MRGI_SPEC_STAGE " + std::to_string(stage) + "\n", [stage] {
        // Stage 2 (the refinement bits) evaluates the lobe at the light.
        return stage == 2 ? vtkMRGIShaderLibraries::Compose({ "vtkMRGIAreaLightDiffuse",
                              "vtkMRGIAreaLightSpecular", "vtkMRGISpecularStencilFS" })
                          : vtkMRGIShaderLibraries::Compose({ "vtkMRGISpecularStencilFS" });
      });
    programs[stage] = quads[stage] ? quads[stage]->Program : nullptr;
    if (!programs[stage])
    {
      vtkErrorMacro("could not build the specular stencil shader (stage " << stage << ")");
      return false;
    }
  }
  using vtkMRGIShaderUtilities::ScopedStage;
  ScopedStage step(frame.Timer, "select.specular");
  vtkMRGIFullScreenStep steps(window, in.GL.FrameBuffer);
  vtkOpenGLState* ostate = steps.GetState();
  // 1. Material pyramid.
  for (int i = 0; i < levels; ++i)
  {
    vtkShaderProgram* p = programs[i == 0 ? 0 : 1];
    window->GetShaderCache()->ReadyShaderProgram(p);
    steps.Target(in.SpecularMaterial[static_cast<size_t>(i)], nullptr, 0, 0, layout.level_width[i],
      layout.level_height[i]);
    if (i == 0)
    {
      vtkMRGIFullScreenStep::BindInputs(p, { position, specular, shininess });
      const int offset[2] = { x0, y0 };
      p->SetUniform2i("mrgiOffset", offset);
      quads[0]->Render();
      vtkMRGIFullScreenStep::UnbindInputs({ position, specular, shininess });
    }
    else
    {
      vtkTextureObject* child = in.SpecularMaterial[static_cast<size_t>(i - 1)];
      vtkMRGIFullScreenStep::BindInputs(p, { child });
      const int size[2] = { layout.level_width[i - 1], layout.level_height[i - 1] };
      p->SetUniform2i("mrgiSize", size);
      quads[1]->Render();
      vtkMRGIFullScreenStep::UnbindInputs({ child });
    }
  }
  // 2. Refinement bits of every level at or above the finest.
  {
    vtkShaderProgram* p = programs[2];
    window->GetShaderCache()->ReadyShaderProgram(p);
    steps.Target(in.FlatSpecularBits, nullptr, 0, 0, layout.total_width, layout.total_height);
    ostate->vtkglClearColor(0.0, 0.0, 0.0, 0.0);
    ostate->vtkglClear(GL_COLOR_BUFFER_BIT);
    p->SetUniform3f("mrgiAreaCenter", light.center);
    p->SetUniform3f("mrgiAreaNormal", light.normal);
    p->SetUniform3fv("mrgiAreaCorners", 4, light.corners);
    p->SetUniform3f("mrgiAreaAxisU", light.axis_u);
    p->SetUniform3f("mrgiAreaAxisV", light.axis_v);
    p->SetUniformf("mrgiAreaHalfU", light.half_u);
    p->SetUniformf("mrgiAreaHalfV", light.half_v);
    p->SetUniformMatrix4x4("mrgiVCToWC", const_cast<float*>(frame.ViewToWorld));
    p->SetUniformi("mrgiParallel", frame.Parallel ? 1 : 0);
    p->SetUniformi("mrgiLobe", this->LobeRefinement ? 1 : 0);
    p->SetUniformf("mrgiLobeThreshold", static_cast<float>(this->LobeThreshold));
    double ab[2];
    buffer->GetPixelSizeCoefficients(ab);
    const float pixelSize[2] = { static_cast<float>(ab[0]), static_cast<float>(ab[1]) };
    p->SetUniform2f("mrgiPixelSize", pixelSize);
    for (int i = finest; i < levels; ++i)
    {
      const std::array<vtkTextureObject*, 2> receivers = buffer->BindReceivers(p, i);
      vtkTextureObject* flags = buffer->GetFlagsTexture(i);
      vtkTextureObject* material = in.SpecularMaterial[static_cast<size_t>(i)];
      flags->Activate();
      material->Activate();
      p->SetUniformi("mrgiFlags", flags->GetTextureUnit());
      p->SetUniformi("mrgiMaterial", material->GetTextureUnit());
      p->SetUniformi("mrgiLevelOffset", layout.level_offset[i]);
      p->SetUniformi("mrgiLevel", i);
      p->SetUniformi("mrgiFinest", i == finest ? 1 : 0);
      ostate->vtkglViewport(layout.level_offset[i], 0, layout.level_width[i], layout.level_height[i]);
      quads[2]->Render();
      material->Deactivate();
      flags->Deactivate();
      receivers[1]->Deactivate();
      receivers[0]->Deactivate();
    }
  }
  // 3. Selection and stencil.
  {
    vtkShaderProgram* p = programs[3];
    window->GetShaderCache()->ReadyShaderProgram(p);
    steps.Target(in.FlatSpecularSelection, nullptr, 0, 0, layout.total_width, layout.total_height);
    steps.BeginMaskWrite(in.SpecularDepthStencil);
    in.FlatSpecularBits->Activate();
    p->SetUniformi("mrgiRefine", in.FlatSpecularBits->GetTextureUnit());
    p->SetUniformi("mrgiCoarsestLevel", levels - 1);
    std::vector<int> offsets(MRGI_MULTIRES_MAX_LEVELS, 0);
    for (int i = 0; i < levels; ++i)
    {
      offsets[static_cast<size_t>(i)] = layout.level_offset[i];
    }
    p->SetUniform1iv("mrgiOffsets", MRGI_MULTIRES_MAX_LEVELS, offsets.data());
    for (int i = finest; i < levels; ++i)
    {
      p->SetUniformi("mrgiLevel", i);
      ostate->vtkglViewport(layout.level_offset[i], 0, layout.level_width[i], layout.level_height[i]);
      quads[3]->Render();
    }
    in.FlatSpecularBits->Deactivate();
    steps.EndMaskWrite();
  }
  const GLenum error = glGetError();
  if (error != GL_NO_ERROR)
  {
    vtkErrorMacro("OpenGL error 0x" << std::hex << error << " in the specular stencil");
    return false;
  }
  in.SpecularStencilValid = true;
  return true;
}

//------------------------------------------------------------------------------
vtkTextureObject* vtkMRGISpecularStencil::GetSelectionTexture() const
{
  return this->Internal->SpecularStencilValid ? this->Internal->FlatSpecularSelection : nullptr;
}

//------------------------------------------------------------------------------
vtkTextureObject* vtkMRGISpecularStencil::GetStencilTexture() const
{
  return this->Internal->SpecularStencilValid ? this->Internal->SpecularDepthStencil : nullptr;
}

//------------------------------------------------------------------------------
vtkTextureObject* vtkMRGISpecularStencil::GetMaterialTexture(int level) const
{
  const Internals& in = *this->Internal;
  return in.SpecularStencilValid && level >= 0 && static_cast<size_t>(level) < in.SpecularMaterial.size()
    ? in.SpecularMaterial[static_cast<size_t>(level)]
    : nullptr;
}

//------------------------------------------------------------------------------
bool vtkMRGISpecularStencil::ReadStencil(vtkRenderWindow* window,
  vtkUnsignedCharArray* selection, vtkUnsignedCharArray* bits, bool fromStencil)
{
  vtkOpenGLRenderWindow* renWin = vtkOpenGLRenderWindow::SafeDownCast(window);
  Internals& in = *this->Internal;
  if (!renWin || !selection || !in.SpecularStencilValid)
  {
    vtkErrorMacro("ReadStencil: no specular stencil built");
    return false;
  }
  const vtkIdType n = static_cast<vtkIdType>(in.Layout.total_width) * in.Layout.total_height;
  std::vector<float> rgba;
  if (bits)
  {
    if (!vtkMRGIShaderUtilities::ReadTextureRGBA(renWin, in.FlatSpecularBits, rgba))
    {
      return false;
    }
    bits->SetNumberOfComponents(1);
    bits->SetNumberOfTuples(n);
    for (vtkIdType i = 0; i < n; ++i)
    {
      bits->SetValue(i, static_cast<unsigned char>(rgba[4 * static_cast<size_t>(i)]));
    }
  }
  return vtkMRGIFullScreenStep::ReadMask(renWin, in.GL.FrameBuffer, in.Layout, in.FlatSpecularSelection,
    in.SpecularDepthStencil, fromStencil, selection);
}

//------------------------------------------------------------------------------
bool vtkMRGISpecularStencil::ReadMaterial(vtkRenderWindow* window, vtkFloatArray* material)
{
  vtkOpenGLRenderWindow* renWin = vtkOpenGLRenderWindow::SafeDownCast(window);
  Internals& in = *this->Internal;
  std::vector<float> flat;
  if (!renWin || !material || !in.SpecularStencilValid ||
    !vtkMRGIFullScreenStep::ReadFlattened(renWin, in.Layout, 4, in.SpecularMaterial, flat))
  {
    vtkErrorMacro("ReadMaterial: no specular stencil built");
    return false;
  }
  material->SetNumberOfComponents(4);
  material->SetNumberOfTuples(static_cast<vtkIdType>(flat.size() / 4));
  std::copy(flat.begin(), flat.end(), material->GetPointer(0));
  return true;
}

//------------------------------------------------------------------------------
void vtkMRGISpecularStencil::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "LobeRefinement: " << (this->LobeRefinement ? "On" : "Off") << "\n";
  os << indent << "LobeThreshold: " << this->LobeThreshold << "\n";
}
