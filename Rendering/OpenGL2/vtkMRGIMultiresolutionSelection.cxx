#include "vtk_glew.h"

#include "vtkMRGIMultiresolutionSelection.h"

#include "vtkMRGIShaderUtilities.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLError.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLQuadHelper.h"
#include "vtkOpenGLRenderUtilities.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"
#include "vtkUnsignedCharArray.h"

#include "vtkMRGIMultiresSelectFS.h"

#include "mrgi_multires.h"

#include <array>
#include <cmath>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkMRGIMultiresolutionSelection);

namespace
{
enum Stage
{
  MipmapBase = 0,
  MipmapReduce = 1,
  Flags = 2,
  FlattenFlags = 3,
  Select = 4,
  StageCount = 5
};

vtkTextureObject* MakeFloatTexture(vtkOpenGLRenderWindow* window, int w, int h)
{
  vtkTextureObject* t = vtkTextureObject::New();
  t->SetContext(window);
  t->SetFormat(GL_RGBA);
  t->SetInternalFormat(GL_RGBA32F);
  t->SetDataType(GL_FLOAT);
  t->SetMinificationFilter(vtkTextureObject::Nearest);
  t->SetMagnificationFilter(vtkTextureObject::Nearest);
  t->Allocate2D(w, h, 4, VTK_FLOAT);
  return t;
}

void ReleaseTexture(vtkTextureObject*& t, vtkWindow* w)
{
  if (t)
  {
    if (w)
    {
      t->ReleaseGraphicsResources(w);
    }
    t->Delete();
    t = nullptr;
  }
}
}

struct vtkMRGIMultiresolutionSelection::Internals
{
  mrgi_multires_layout Layout{};
  bool HasLayout = false;
  // Per level: mipmap (MRGI_MULTIRES_TEX_*) and flags.
  std::vector<std::array<vtkTextureObject*, MRGI_MULTIRES_TEX_COUNT + 1>> Levels;
  vtkTextureObject* FlatFlags = nullptr;
  vtkTextureObject* FlatSelection = nullptr;
  vtkTextureObject* DepthStencil = nullptr;
  vtkOpenGLFramebufferObject* FrameBuffer = nullptr;
  vtkOpenGLQuadHelper* Quads[StageCount] = { nullptr, nullptr, nullptr, nullptr, nullptr };

  void ReleaseTextures(vtkWindow* w)
  {
    for (auto& level : this->Levels)
    {
      for (auto*& t : level)
      {
        ReleaseTexture(t, w);
      }
    }
    this->Levels.clear();
    ReleaseTexture(this->FlatFlags, w);
    ReleaseTexture(this->FlatSelection, w);
    ReleaseTexture(this->DepthStencil, w);
    this->HasLayout = false;
  }
};

//------------------------------------------------------------------------------
vtkMRGIMultiresolutionSelection::vtkMRGIMultiresolutionSelection()
  : Internal(new Internals)
{
}

//------------------------------------------------------------------------------
vtkMRGIMultiresolutionSelection::~vtkMRGIMultiresolutionSelection()
{
  if (this->Internal->FrameBuffer || this->Internal->DepthStencil)
  {
    vtkErrorMacro("GL resources should have been freed in ReleaseGraphicsResources().");
  }
  this->Internal->ReleaseTextures(nullptr);
  if (this->Internal->FrameBuffer)
  {
    this->Internal->FrameBuffer->Delete();
  }
  for (auto*& q : this->Internal->Quads)
  {
    delete q;
  }
}

//------------------------------------------------------------------------------
void vtkMRGIMultiresolutionSelection::ReleaseGraphicsResources(vtkWindow* w)
{
  this->Internal->ReleaseTextures(w);
  for (auto*& q : this->Internal->Quads)
  {
    if (q)
    {
      q->ReleaseGraphicsResources(w);
      delete q;
      q = nullptr;
    }
  }
  if (this->Internal->FrameBuffer)
  {
    this->Internal->FrameBuffer->ReleaseGraphicsResources(w);
    this->Internal->FrameBuffer->Delete();
    this->Internal->FrameBuffer = nullptr;
  }
}

int vtkMRGIMultiresolutionSelection::GetFlattenedWidth() const
{
  return this->Internal->HasLayout ? this->Internal->Layout.total_width : 0;
}
int vtkMRGIMultiresolutionSelection::GetFlattenedHeight() const
{
  return this->Internal->HasLayout ? this->Internal->Layout.total_height : 0;
}
int vtkMRGIMultiresolutionSelection::GetNumberOfLevels() const
{
  return this->Internal->HasLayout ? this->Internal->Layout.level_count : 0;
}
vtkTextureObject* vtkMRGIMultiresolutionSelection::GetStencilTexture() const
{
  return this->Internal->DepthStencil;
}

//------------------------------------------------------------------------------
bool vtkMRGIMultiresolutionSelection::Update(vtkOpenGLRenderWindow* window,
  vtkTextureObject* position, vtkTextureObject* normal, int x0, int y0, int width, int height,
  double a, double b)
{
  if (!window || !position || !normal)
  {
    vtkErrorMacro("Update needs a window and the G-buffer position and normal textures");
    return false;
  }
  mrgi_multires_layout layout;
  mrgi_error err;
  if (mrgi_multires_layout_init(&layout, width, height, this->CoarsestSide, &err) != MRGI_OK)
  {
    vtkErrorMacro(<< err.message);
    return false;
  }
  if (!(std::isfinite(a) && std::isfinite(b) && a >= 0 && b >= 0 && a + b > 0))
  {
    vtkErrorMacro("pixel size coefficients (" << a << ", " << b << ") must be finite, >= 0, not both 0");
    return false;
  }
  Internals& in = *this->Internal;
  const int levels = layout.level_count;
  const int finest = std::min(this->FinestLevel, levels - 1);

  // Textures, reallocated only when the layout changes.
  if (!in.HasLayout || in.Layout.width != layout.width || in.Layout.height != layout.height ||
    in.Layout.level_count != levels)
  {
    in.ReleaseTextures(window);
    in.Levels.resize(static_cast<size_t>(levels));
    for (int i = 0; i < levels; ++i)
    {
      for (auto*& t : in.Levels[i])
      {
        t = MakeFloatTexture(window, layout.level_width[i], layout.level_height[i]);
      }
    }
    in.FlatFlags = MakeFloatTexture(window, layout.total_width, layout.total_height);
    in.FlatSelection = MakeFloatTexture(window, layout.total_width, layout.total_height);
    in.DepthStencil = vtkTextureObject::New();
    in.DepthStencil->SetContext(window);
    in.DepthStencil->SetMinificationFilter(vtkTextureObject::Nearest);
    in.DepthStencil->SetMagnificationFilter(vtkTextureObject::Nearest);
    in.DepthStencil->AllocateDepthStencil(layout.total_width, layout.total_height);
  }
  in.Layout = layout;
  in.HasLayout = true;
  if (!in.FrameBuffer)
  {
    in.FrameBuffer = vtkOpenGLFramebufferObject::New();
    in.FrameBuffer->SetContext(window);
  }

  // Programs, one per stage.
  vtkShaderProgram* programs[StageCount];
  for (int s = 0; s < StageCount; ++s)
  {
    if (!in.Quads[s])
    {
      const std::string body =
        "#define MRGI_MR_STAGE " + std::to_string(s) + "\n" + vtkMRGIMultiresSelectFS;
      in.Quads[s] = new vtkOpenGLQuadHelper(window,
        vtkOpenGLRenderUtilities::GetFullScreenQuadVertexShader().c_str(),
        vtkMRGIShaderUtilities::FullScreenShader(body.c_str()).c_str(), "");
    }
    else
    {
      window->GetShaderCache()->ReadyShaderProgram(in.Quads[s]->Program);
    }
    programs[s] = in.Quads[s]->Program;
    if (!programs[s] || !programs[s]->GetCompiled())
    {
      vtkErrorMacro("could not build the multiresolution selection shader (stage " << s << ")");
      return false;
    }
  }

  vtkOpenGLState* ostate = window->GetState();
  vtkOpenGLState::ScopedglEnableDisable blend(ostate, GL_BLEND);
  vtkOpenGLState::ScopedglEnableDisable depthTest(ostate, GL_DEPTH_TEST);
  vtkOpenGLState::ScopedglEnableDisable scissor(ostate, GL_SCISSOR_TEST);
  vtkOpenGLState::ScopedglEnableDisable stencilTest(ostate, GL_STENCIL_TEST);
  vtkOpenGLState::ScopedglViewport viewport(ostate);
  vtkOpenGLState::ScopedglClearColor clearColor(ostate);
  ostate->vtkglDisable(GL_BLEND);
  ostate->vtkglDisable(GL_DEPTH_TEST);
  ostate->vtkglDisable(GL_SCISSOR_TEST);
  ostate->vtkglDisable(GL_STENCIL_TEST);

  vtkOpenGLFramebufferObject* fbo = in.FrameBuffer;
  fbo->SaveCurrentBindingsAndBuffers();
  fbo->Bind();
  auto target = [&](std::initializer_list<vtkTextureObject*> textures, int w, int h) {
    fbo->RemoveColorAttachments(MRGI_MULTIRES_TEX_COUNT + 1);
    unsigned int k = 0;
    for (vtkTextureObject* t : textures)
    {
      fbo->AddColorAttachment(k++, t);
    }
    fbo->ActivateDrawBuffers(k);
    ostate->vtkglViewport(0, 0, w, h);
  };
  auto bind = [&](vtkShaderProgram* program, std::initializer_list<vtkTextureObject*> textures) {
    // Uniforms go to the bound program: bind this stage's first.
    window->GetShaderCache()->ReadyShaderProgram(program);
    int k = 0;
    for (vtkTextureObject* t : textures)
    {
      t->Activate();
      program->SetUniformi(("mrgiInput" + std::to_string(k++)).c_str(), t->GetTextureUnit());
    }
  };
  auto unbind = [](std::initializer_list<vtkTextureObject*> textures) {
    for (vtkTextureObject* t : textures)
    {
      t->Deactivate();
    }
  };
  const float pixelSize[2] = { static_cast<float>(a), static_cast<float>(b) };

  // 1. Level 0 of the mipmaps, from the G-buffer.
  {
    auto& level = in.Levels[0];
    target({ level[MRGI_MULTIRES_TEX_DEPTH], level[MRGI_MULTIRES_TEX_NORMAL_MIN],
             level[MRGI_MULTIRES_TEX_NORMAL_MAX] },
      width, height);
    vtkShaderProgram* p = programs[MipmapBase];
    bind(p, { position, normal });
    const int offset[2] = { x0, y0 };
    const int size[2] = { width, height };
    p->SetUniform2i("mrgiOffset", offset);
    p->SetUniform2i("mrgiSize", size);
    p->SetUniform2f("mrgiPixelSize", pixelSize);
    in.Quads[MipmapBase]->Render();
    unbind({ position, normal });
  }
  // 2. Coarser levels: 2x2 reduction of the finer one.
  for (int i = 1; i < levels; ++i)
  {
    auto& fine = in.Levels[i - 1];
    auto& level = in.Levels[i];
    target({ level[MRGI_MULTIRES_TEX_DEPTH], level[MRGI_MULTIRES_TEX_NORMAL_MIN],
             level[MRGI_MULTIRES_TEX_NORMAL_MAX] },
      layout.level_width[i], layout.level_height[i]);
    vtkShaderProgram* p = programs[MipmapReduce];
    bind(p, { fine[MRGI_MULTIRES_TEX_DEPTH], fine[MRGI_MULTIRES_TEX_NORMAL_MIN],
              fine[MRGI_MULTIRES_TEX_NORMAL_MAX] });
    const int size[2] = { layout.level_width[i - 1], layout.level_height[i - 1] };
    p->SetUniform2i("mrgiSize", size);
    in.Quads[MipmapReduce]->Render();
    unbind({ fine[MRGI_MULTIRES_TEX_DEPTH], fine[MRGI_MULTIRES_TEX_NORMAL_MIN],
      fine[MRGI_MULTIRES_TEX_NORMAL_MAX] });
  }
  // 3. Flags, fine to coarse (refinement and balance read the finer level).
  const float depthThreshold = mrgi_multires_threshold_uniform(
    this->DepthThreshold < 0 ? INFINITY : this->DepthThreshold);
  const float normalThreshold = mrgi_multires_threshold_uniform(
    this->NormalThreshold < 0 ? INFINITY : this->NormalThreshold);
  for (int i = 0; i < levels; ++i)
  {
    auto& level = in.Levels[i];
    const int flagsSlot = MRGI_MULTIRES_TEX_COUNT;
    target({ level[flagsSlot] }, layout.level_width[i], layout.level_height[i]);
    vtkShaderProgram* p = programs[Flags];
    // Level 0 has no finer level: its own (not yet written) flags stand in,
    // unread since level 0 <= the finest level.
    vtkTextureObject* finer = in.Levels[i > 0 ? i - 1 : 0][flagsSlot];
    if (i == 0)
    {
      finer = in.Levels[std::min(1, levels - 1)][MRGI_MULTIRES_TEX_DEPTH];
    }
    bind(p, { level[MRGI_MULTIRES_TEX_DEPTH], level[MRGI_MULTIRES_TEX_NORMAL_MIN],
              level[MRGI_MULTIRES_TEX_NORMAL_MAX], finer });
    const int size[2] = { layout.level_width[i], layout.level_height[i] };
    const int childSize[2] = { layout.level_width[i > 0 ? i - 1 : 0],
      layout.level_height[i > 0 ? i - 1 : 0] };
    p->SetUniform2i("mrgiSize", size);
    p->SetUniform2i("mrgiChildSize", childSize);
    p->SetUniformf("mrgiDepthThreshold", depthThreshold);
    p->SetUniformf("mrgiNormalThreshold", normalThreshold);
    p->SetUniformi("mrgiLevel", i);
    p->SetUniformi("mrgiFinestLevel", finest);
    p->SetUniformi("mrgiBalance", this->Balance ? 1 : 0);
    in.Quads[Flags]->Render();
    unbind({ level[MRGI_MULTIRES_TEX_DEPTH], level[MRGI_MULTIRES_TEX_NORMAL_MIN],
      level[MRGI_MULTIRES_TEX_NORMAL_MAX], finer });
  }
  // 4. The flags of every level into the flattened layout.
  target({ in.FlatFlags }, layout.total_width, layout.total_height);
  ostate->vtkglClearColor(0.0, 0.0, 0.0, 0.0);
  ostate->vtkglClear(GL_COLOR_BUFFER_BIT);
  for (int i = 0; i < levels; ++i)
  {
    ostate->vtkglViewport(
      layout.level_offset[i], 0, layout.level_width[i], layout.level_height[i]);
    vtkTextureObject* flags = in.Levels[i][MRGI_MULTIRES_TEX_COUNT];
    vtkShaderProgram* p = programs[FlattenFlags];
    bind(p, { flags });
    const int offset[2] = { layout.level_offset[i], 0 };
    p->SetUniform2i("mrgiOffset", offset);
    in.Quads[FlattenFlags]->Render();
    unbind({ flags });
  }
  // 5. One pass over the flattened layout: selected texels set the stencil.
  target({ in.FlatSelection }, layout.total_width, layout.total_height);
  glFramebufferTexture2D(
    GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_TEXTURE_2D, in.DepthStencil->GetHandle(), 0);
  ostate->vtkglClearColor(0.0, 0.0, 0.0, 0.0);
  ostate->vtkglStencilMask(0xFF);
  glClearStencil(0);
  ostate->vtkglClear(GL_COLOR_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
  ostate->vtkglEnable(GL_STENCIL_TEST);
  ostate->vtkglStencilFunc(GL_ALWAYS, 1, 0xFF);
  ostate->vtkglStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
  {
    vtkShaderProgram* p = programs[Select];
    bind(p, { in.FlatFlags });
    p->SetUniformi("mrgiLevelCount", levels);
    p->SetUniformi("mrgiFinestLevel", finest);
    p->SetUniform1iv("mrgiLevelOffset", levels, layout.level_offset);
    p->SetUniform1iv("mrgiLevelWidth", levels, layout.level_width);
    p->SetUniform1iv("mrgiLevelHeight", levels, layout.level_height);
    in.Quads[Select]->Render();
    unbind({ in.FlatFlags });
  }
  ostate->vtkglStencilFunc(GL_ALWAYS, 0, 0xFF);
  ostate->vtkglStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_TEXTURE_2D, 0, 0);
  fbo->RemoveColorAttachments(MRGI_MULTIRES_TEX_COUNT + 1);
  fbo->UnBind();
  fbo->RestorePreviousBindingsAndBuffers();
  const GLenum error = glGetError();
  if (error != GL_NO_ERROR)
  {
    vtkErrorMacro("OpenGL error 0x" << std::hex << error << " in the multiresolution selection");
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkMRGIMultiresolutionSelection::ReadSelection(
  vtkRenderWindow* window, vtkUnsignedCharArray* mask, bool fromStencil)
{
  vtkOpenGLRenderWindow* renWin = vtkOpenGLRenderWindow::SafeDownCast(window);
  Internals& in = *this->Internal;
  if (!renWin || !mask || !in.HasLayout)
  {
    vtkErrorMacro("ReadSelection: nothing selected yet");
    return false;
  }
  const int w = in.Layout.total_width, h = in.Layout.total_height;
  mask->SetNumberOfComponents(1);
  mask->SetNumberOfTuples(static_cast<vtkIdType>(w) * h);
  if (!fromStencil)
  {
    std::vector<float> rgba;
    if (!vtkMRGIShaderUtilities::ReadTextureRGBA(renWin, in.FlatSelection, rgba))
    {
      return false;
    }
    for (vtkIdType i = 0; i < mask->GetNumberOfTuples(); ++i)
    {
      mask->SetValue(i, rgba[4 * static_cast<size_t>(i)] > 0.5f ? 1 : 0);
    }
    return true;
  }
  renWin->MakeCurrent();
  vtkOpenGLState* ostate = renWin->GetState();
  ostate->PushReadFramebufferBinding();
  in.FrameBuffer->Bind(GL_READ_FRAMEBUFFER);
  glFramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_TEXTURE_2D,
    in.DepthStencil->GetHandle(), 0);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, w, h, GL_STENCIL_INDEX, GL_UNSIGNED_BYTE, mask->GetPointer(0));
  glFramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_TEXTURE_2D, 0, 0);
  ostate->PopReadFramebufferBinding();
  return glGetError() == GL_NO_ERROR;
}

//------------------------------------------------------------------------------
bool vtkMRGIMultiresolutionSelection::ReadFlags(vtkRenderWindow* window, vtkUnsignedCharArray* flags)
{
  vtkOpenGLRenderWindow* renWin = vtkOpenGLRenderWindow::SafeDownCast(window);
  Internals& in = *this->Internal;
  std::vector<float> rgba;
  if (!renWin || !flags || !in.HasLayout ||
    !vtkMRGIShaderUtilities::ReadTextureRGBA(renWin, in.FlatFlags, rgba))
  {
    vtkErrorMacro("ReadFlags: nothing selected yet");
    return false;
  }
  flags->SetNumberOfComponents(1);
  flags->SetNumberOfTuples(static_cast<vtkIdType>(rgba.size() / 4));
  for (vtkIdType i = 0; i < flags->GetNumberOfTuples(); ++i)
  {
    flags->SetValue(i, static_cast<unsigned char>(rgba[4 * static_cast<size_t>(i)]));
  }
  return true;
}

//------------------------------------------------------------------------------
void vtkMRGIMultiresolutionSelection::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "DepthThreshold: " << this->DepthThreshold << "\n";
  os << indent << "NormalThreshold: " << this->NormalThreshold << "\n";
  os << indent << "FinestLevel: " << this->FinestLevel << "\n";
  os << indent << "Balance: " << (this->Balance ? "On" : "Off") << "\n";
  os << indent << "CoarsestSide: " << this->CoarsestSide << "\n";
  os << indent << "Levels: " << this->GetNumberOfLevels() << "\n";
}
