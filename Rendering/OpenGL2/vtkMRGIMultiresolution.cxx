#include "vtk_glew.h"

#include "vtkMRGIMultiresolution.h"

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

#include "vtkMRGIGatherFS.h"
#include "vtkMRGIMultiresReceiversFS.h"
#include "vtkMRGIMultiresUpsampleFS.h"
#include "vtkMRGIMultiresSelectFS.h"
#include "vtkFloatArray.h"

#include "mrgi_multires.h"

#include <array>
#include <cmath>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkMRGIMultiresolution);

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

namespace
{
// GL state of the multiresolution steps: blending, depth, scissor and
// stencil tests off, viewport and clear colour restored, MRGI's framebuffer
// bound for the duration.
struct QuadSteps
{
  QuadSteps(vtkOpenGLRenderWindow* window, vtkOpenGLFramebufferObject* fbo)
    : State(window->GetState())
    , Blend(State, GL_BLEND)
    , DepthTest(State, GL_DEPTH_TEST)
    , Scissor(State, GL_SCISSOR_TEST)
    , StencilTest(State, GL_STENCIL_TEST)
    , Viewport(State)
    , ClearColor(State)
    , Fbo(fbo)
  {
    this->State->vtkglDisable(GL_BLEND);
    this->State->vtkglDisable(GL_DEPTH_TEST);
    this->State->vtkglDisable(GL_SCISSOR_TEST);
    this->State->vtkglDisable(GL_STENCIL_TEST);
    fbo->SaveCurrentBindingsAndBuffers();
    fbo->Bind();
  }
  ~QuadSteps()
  {
    this->Fbo->RemoveColorAttachments(MRGI_MULTIRES_TEX_COUNT + 1);
    this->Fbo->UnBind();
    this->Fbo->RestorePreviousBindingsAndBuffers();
  }
  void Target(vtkTextureObject* a, vtkTextureObject* b, int x, int y, int w, int h)
  {
    this->Fbo->RemoveColorAttachments(MRGI_MULTIRES_TEX_COUNT + 1);
    this->Fbo->AddColorAttachment(0, a);
    if (b)
    {
      this->Fbo->AddColorAttachment(1, b);
    }
    this->Fbo->ActivateDrawBuffers(b ? 2 : 1);
    this->State->vtkglViewport(x, y, w, h);
  }
  vtkOpenGLState* State;
  vtkOpenGLState::ScopedglEnableDisable Blend, DepthTest, Scissor, StencilTest;
  vtkOpenGLState::ScopedglViewport Viewport;
  vtkOpenGLState::ScopedglClearColor ClearColor;
  vtkOpenGLFramebufferObject* Fbo;
};

vtkShaderProgram* ReadyStage(vtkOpenGLQuadHelper*& quad, vtkOpenGLRenderWindow* window,
  const char* source, int stage)
{
  if (!quad)
  {
    const std::string body = "#define MRGI_MR_STAGE " + std::to_string(stage) + "\n" + source;
    quad = new vtkOpenGLQuadHelper(window,
      vtkOpenGLRenderUtilities::GetFullScreenQuadVertexShader().c_str(),
      vtkMRGIShaderUtilities::FullScreenShader(body.c_str()).c_str(), "");
  }
  window->GetShaderCache()->ReadyShaderProgram(quad->Program);
  return (quad->Program && quad->Program->GetCompiled()) ? quad->Program : nullptr;
}

void BindInputs(vtkShaderProgram* p, std::initializer_list<vtkTextureObject*> textures)
{
  int k = 0;
  for (vtkTextureObject* t : textures)
  {
    t->Activate();
    p->SetUniformi(("mrgiInput" + std::to_string(k++)).c_str(), t->GetTextureUnit());
  }
}

void UnbindInputs(std::initializer_list<vtkTextureObject*> textures)
{
  for (vtkTextureObject* t : textures)
  {
    t->Deactivate();
  }
}
}

struct vtkMRGIMultiresolution::Internals
{
  mrgi_multires_layout Layout{};
  bool HasLayout = false;
  // Per level: mipmap (MRGI_MULTIRES_TEX_*) and flags.
  std::vector<std::array<vtkTextureObject*, MRGI_MULTIRES_TEX_COUNT + 1>> Levels;
  vtkTextureObject* FlatFlags = nullptr;
  // Receivers: per level (position, normal) and flattened; the gather's output.
  std::vector<std::array<vtkTextureObject*, 2>> Receivers;
  vtkTextureObject* FlatReceivers[2] = { nullptr, nullptr };
  vtkTextureObject* FlatIrradiance = nullptr;
  vtkOpenGLQuadHelper* ReceiverQuads[3] = { nullptr, nullptr, nullptr };
  vtkOpenGLQuadHelper* GatherQuad = nullptr;
  // Upsampling: per level (state/value, filtered).
  std::vector<std::array<vtkTextureObject*, 2>> Upsampled;
  vtkOpenGLQuadHelper* UpsampleQuads[3] = { nullptr, nullptr, nullptr };
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
    for (auto& level : this->Receivers)
    {
      for (auto*& t : level)
      {
        ReleaseTexture(t, w);
      }
    }
    this->Receivers.clear();
    for (auto& level : this->Upsampled)
    {
      for (auto*& t : level)
      {
        ReleaseTexture(t, w);
      }
    }
    this->Upsampled.clear();
    ReleaseTexture(this->FlatReceivers[0], w);
    ReleaseTexture(this->FlatReceivers[1], w);
    ReleaseTexture(this->FlatIrradiance, w);
    ReleaseTexture(this->FlatFlags, w);
    ReleaseTexture(this->FlatSelection, w);
    ReleaseTexture(this->DepthStencil, w);
    this->HasLayout = false;
  }
};

//------------------------------------------------------------------------------
vtkMRGIMultiresolution::vtkMRGIMultiresolution()
  : Internal(new Internals)
{
}

//------------------------------------------------------------------------------
vtkMRGIMultiresolution::~vtkMRGIMultiresolution()
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
  for (auto*& q : this->Internal->ReceiverQuads)
  {
    delete q;
  }
  for (auto*& q : this->Internal->UpsampleQuads)
  {
    delete q;
  }
  delete this->Internal->GatherQuad;
}

//------------------------------------------------------------------------------
void vtkMRGIMultiresolution::ReleaseGraphicsResources(vtkWindow* w)
{
  this->Internal->ReleaseTextures(w);
  auto releaseQuad = [w](vtkOpenGLQuadHelper*& q) {
    if (q)
    {
      q->ReleaseGraphicsResources(w);
      delete q;
      q = nullptr;
    }
  };
  for (auto*& q : this->Internal->Quads)
  {
    releaseQuad(q);
  }
  for (auto*& q : this->Internal->ReceiverQuads)
  {
    releaseQuad(q);
  }
  for (auto*& q : this->Internal->UpsampleQuads)
  {
    releaseQuad(q);
  }
  releaseQuad(this->Internal->GatherQuad);
  if (this->Internal->FrameBuffer)
  {
    this->Internal->FrameBuffer->ReleaseGraphicsResources(w);
    this->Internal->FrameBuffer->Delete();
    this->Internal->FrameBuffer = nullptr;
  }
}

int vtkMRGIMultiresolution::GetFlattenedWidth() const
{
  return this->Internal->HasLayout ? this->Internal->Layout.total_width : 0;
}
int vtkMRGIMultiresolution::GetFlattenedHeight() const
{
  return this->Internal->HasLayout ? this->Internal->Layout.total_height : 0;
}
int vtkMRGIMultiresolution::GetNumberOfLevels() const
{
  return this->Internal->HasLayout ? this->Internal->Layout.level_count : 0;
}
vtkTextureObject* vtkMRGIMultiresolution::GetStencilTexture() const
{
  return this->Internal->DepthStencil;
}

//------------------------------------------------------------------------------
bool vtkMRGIMultiresolution::Update(vtkOpenGLRenderWindow* window,
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
    in.Receivers.resize(static_cast<size_t>(levels));
    for (int i = 0; i < levels; ++i)
    {
      for (auto*& t : in.Receivers[i])
      {
        t = MakeFloatTexture(window, layout.level_width[i], layout.level_height[i]);
      }
    }
    for (auto*& t : in.FlatReceivers)
    {
      t = MakeFloatTexture(window, layout.total_width, layout.total_height);
    }
    in.FlatIrradiance = MakeFloatTexture(window, layout.total_width, layout.total_height);
    in.Upsampled.resize(static_cast<size_t>(levels));
    for (int i = 0; i < levels; ++i)
    {
      for (auto*& t : in.Upsampled[i])
      {
        t = MakeFloatTexture(window, layout.level_width[i], layout.level_height[i]);
      }
    }
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

  QuadSteps steps(window, in.FrameBuffer);
  vtkOpenGLState* ostate = steps.State;
  vtkOpenGLFramebufferObject* fbo = in.FrameBuffer;
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
  const GLenum error = glGetError();
  if (error != GL_NO_ERROR)
  {
    vtkErrorMacro("OpenGL error 0x" << std::hex << error << " in the multiresolution selection");
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkMRGIMultiresolution::Gather(vtkOpenGLRenderWindow* window, vtkTextureObject* position,
  vtkTextureObject* normal, int x0, int y0, vtkTextureObject* vpls, int vplCount,
  const float viewToWorld[16])
{
  Internals& in = *this->Internal;
  if (!window || !position || !normal || !vpls || vplCount < 1 || !in.HasLayout)
  {
    vtkErrorMacro("Gather needs Update() first, the G-buffer and at least one VPL");
    return false;
  }
  const mrgi_multires_layout& layout = in.Layout;
  const int levels = layout.level_count;
  auto ready = [&](vtkOpenGLQuadHelper*& quad, const std::string& body) -> vtkShaderProgram* {
    if (!quad)
    {
      quad = new vtkOpenGLQuadHelper(window,
        vtkOpenGLRenderUtilities::GetFullScreenQuadVertexShader().c_str(),
        vtkMRGIShaderUtilities::FullScreenShader(body.c_str()).c_str(), "");
    }
    window->GetShaderCache()->ReadyShaderProgram(quad->Program);
    return (quad->Program && quad->Program->GetCompiled()) ? quad->Program : nullptr;
  };

  QuadSteps steps(window, in.FrameBuffer);
  vtkOpenGLState* ostate = steps.State;
  vtkOpenGLFramebufferObject* fbo = in.FrameBuffer;
  auto target = [&](vtkTextureObject* a, vtkTextureObject* b, int w, int h) {
    steps.Target(a, b, 0, 0, w, h);
  };
  auto inputs = [&](vtkShaderProgram* p, vtkTextureObject* a, vtkTextureObject* b) {
    a->Activate();
    b->Activate();
    p->SetUniformi("mrgiInput0", a->GetTextureUnit());
    p->SetUniformi("mrgiInput1", b->GetTextureUnit());
  };
  bool ok = true;
  // 1. Receivers, level by level, then flattened.
  for (int i = 0; i < levels && ok; ++i)
  {
    const int stage = i == 0 ? 0 : 1;
    vtkShaderProgram* p = ready(in.ReceiverQuads[stage],
      "#define MRGI_MR_STAGE " + std::to_string(stage) + "\n" + vtkMRGIMultiresReceiversFS);
    if (!p)
    {
      ok = false;
      break;
    }
    target(in.Receivers[i][0], in.Receivers[i][1], layout.level_width[i], layout.level_height[i]);
    vtkTextureObject* srcP = i == 0 ? position : in.Receivers[i - 1][0];
    vtkTextureObject* srcN = i == 0 ? normal : in.Receivers[i - 1][1];
    inputs(p, srcP, srcN);
    const int offset[2] = { x0, y0 };
    const int size[2] = { i == 0 ? 0 : layout.level_width[i - 1], i == 0 ? 0 : layout.level_height[i - 1] };
    p->SetUniform2i("mrgiOffset", offset);
    p->SetUniform2i("mrgiSize", size);
    in.ReceiverQuads[stage]->Render();
    srcP->Deactivate();
    srcN->Deactivate();
  }
  vtkShaderProgram* flatten =
    ok ? ready(in.ReceiverQuads[2], std::string("#define MRGI_MR_STAGE 2\n") + vtkMRGIMultiresReceiversFS) : nullptr;
  ok = ok && flatten;
  if (ok)
  {
    target(in.FlatReceivers[0], in.FlatReceivers[1], layout.total_width, layout.total_height);
    ostate->vtkglClearColor(0.0, 0.0, 0.0, 0.0);
    ostate->vtkglClear(GL_COLOR_BUFFER_BIT);
    for (int i = 0; i < levels; ++i)
    {
      ostate->vtkglViewport(layout.level_offset[i], 0, layout.level_width[i], layout.level_height[i]);
      inputs(flatten, in.Receivers[i][0], in.Receivers[i][1]);
      const int offset[2] = { layout.level_offset[i], 0 };
      flatten->SetUniform2i("mrgiOffset", offset);
      in.ReceiverQuads[2]->Render();
      in.Receivers[i][0]->Deactivate();
      in.Receivers[i][1]->Deactivate();
    }
  }
  // 2. The stenciled gather over the flattened layout.
  vtkShaderProgram* gather = ok
    ? ready(in.GatherQuad, std::string("#define MRGI_GATHER_IRRADIANCE_ONLY 1\n") + vtkMRGIGatherFS)
    : nullptr;
  ok = ok && gather;
  if (ok)
  {
    target(in.FlatIrradiance, nullptr, layout.total_width, layout.total_height);
    glFramebufferTexture2D(
      GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_TEXTURE_2D, in.DepthStencil->GetHandle(), 0);
    ostate->vtkglClearColor(0.0, 0.0, 0.0, 0.0);
    ostate->vtkglClear(GL_COLOR_BUFFER_BIT);
    ostate->vtkglEnable(GL_STENCIL_TEST);
    ostate->vtkglStencilMask(0x00);
    ostate->vtkglStencilFunc(GL_EQUAL, 1, 0xFF);
    ostate->vtkglStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
    in.FlatReceivers[0]->Activate();
    in.FlatReceivers[1]->Activate();
    vpls->Activate();
    gather->SetUniformi("mrgiPosition", in.FlatReceivers[0]->GetTextureUnit());
    gather->SetUniformi("mrgiNormal", in.FlatReceivers[1]->GetTextureUnit());
    gather->SetUniformi("mrgiVPLs", vpls->GetTextureUnit());
    gather->SetUniformi("mrgiVPLCount", vplCount);
    gather->SetUniformMatrix4x4("mrgiVCToWC", const_cast<float*>(viewToWorld));
    in.GatherQuad->Render();
    vpls->Deactivate();
    in.FlatReceivers[1]->Deactivate();
    in.FlatReceivers[0]->Deactivate();
    ostate->vtkglStencilMask(0xFF);
    ostate->vtkglStencilFunc(GL_ALWAYS, 0, 0xFF);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_TEXTURE_2D, 0, 0);
  }
  if (!ok)
  {
    vtkErrorMacro("could not build the multiresolution gather shaders");
    return false;
  }
  const GLenum error = glGetError();
  if (error != GL_NO_ERROR)
  {
    vtkErrorMacro("OpenGL error " << error << " in the multiresolution gather");
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkMRGIMultiresolution::Upsample(vtkOpenGLRenderWindow* window, int mode, double maskWeight)
{
  Internals& in = *this->Internal;
  if (!window || !in.HasLayout)
  {
    vtkErrorMacro("Upsample needs Update() and Gather() first");
    return false;
  }
  vtkShaderProgram* state = ReadyStage(in.UpsampleQuads[0], window, vtkMRGIMultiresUpsampleFS, 0);
  vtkShaderProgram* filter = ReadyStage(in.UpsampleQuads[1], window, vtkMRGIMultiresUpsampleFS, 1);
  if (!state || !filter)
  {
    vtkErrorMacro("could not build the multiresolution upsampling shaders");
    return false;
  }
  const mrgi_multires_layout& layout = in.Layout;
  const int coarsest = layout.level_count - 1;
  QuadSteps steps(window, in.FrameBuffer);
  for (int i = coarsest; i >= 0; --i)
  {
    const int w = layout.level_width[i], h = layout.level_height[i];
    vtkTextureObject* value = in.Upsampled[i][0];
    vtkTextureObject* filtered = in.Upsampled[i][1];
    // The coarsest level has no parent: its own flags stand in, unread.
    vtkTextureObject* parent = in.Upsampled[std::min(i + 1, coarsest)][1];
    if (i == coarsest)
    {
      parent = in.Levels[i][MRGI_MULTIRES_TEX_DEPTH];
    }
    vtkTextureObject* flags = in.Levels[i][MRGI_MULTIRES_TEX_COUNT];
    window->GetShaderCache()->ReadyShaderProgram(state);
    steps.Target(value, nullptr, 0, 0, w, h);
    BindInputs(state, { in.FlatSelection, flags, in.FlatIrradiance, parent });
    const int offset[2] = { layout.level_offset[i], 0 };
    state->SetUniform2i("mrgiOffset", offset);
    state->SetUniformi("mrgiCoarsest", i == coarsest ? 1 : 0);
    in.UpsampleQuads[0]->Render();
    UnbindInputs({ in.FlatSelection, flags, in.FlatIrradiance, parent });

    window->GetShaderCache()->ReadyShaderProgram(filter);
    steps.Target(filtered, nullptr, 0, 0, w, h);
    BindInputs(filter, { value });
    const int size[2] = { w, h };
    filter->SetUniform2i("mrgiSize", size);
    filter->SetUniformi("mrgiMode", mode == UpsampleMaskWeighted ? 1 : 0);
    filter->SetUniformf("mrgiMaskWeight", static_cast<float>(maskWeight));
    in.UpsampleQuads[1]->Render();
    UnbindInputs({ value });
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
bool vtkMRGIMultiresolution::Resolve(vtkOpenGLRenderWindow* window, vtkTextureObject* albedo,
  vtkTextureObject* irradiance, vtkTextureObject* indirect, int x0, int y0, double strength)
{
  Internals& in = *this->Internal;
  vtkShaderProgram* resolve =
    window ? ReadyStage(in.UpsampleQuads[2], window, vtkMRGIMultiresUpsampleFS, 2) : nullptr;
  if (!resolve || !in.HasLayout || !albedo || !irradiance || !indirect)
  {
    vtkErrorMacro("Resolve needs Upsample() first, the albedo and both targets");
    return false;
  }
  {
    QuadSteps steps(window, in.FrameBuffer);
    steps.Target(irradiance, indirect, x0, y0, in.Layout.width, in.Layout.height);
    vtkTextureObject* flags = in.Levels[0][MRGI_MULTIRES_TEX_COUNT];
    BindInputs(resolve, { in.Upsampled[0][1], flags, albedo });
    const int offset[2] = { x0, y0 };
    resolve->SetUniform2i("mrgiOffset", offset);
    resolve->SetUniformf("mrgiStrength", static_cast<float>(strength));
    in.UpsampleQuads[2]->Render();
    UnbindInputs({ in.Upsampled[0][1], flags, albedo });
  }
  return glGetError() == GL_NO_ERROR;
}

//------------------------------------------------------------------------------
bool vtkMRGIMultiresolution::ReadUpsampled(vtkRenderWindow* window, vtkFloatArray* upsampled)
{
  vtkOpenGLRenderWindow* renWin = vtkOpenGLRenderWindow::SafeDownCast(window);
  Internals& in = *this->Internal;
  std::vector<float> rgba;
  if (!renWin || !upsampled || !in.HasLayout || in.Upsampled.empty() ||
    !vtkMRGIShaderUtilities::ReadTextureRGBA(renWin, in.Upsampled[0][1], rgba))
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
bool vtkMRGIMultiresolution::ReadReceivers(
  vtkRenderWindow* window, vtkFloatArray* position, vtkFloatArray* normal)
{
  vtkOpenGLRenderWindow* renWin = vtkOpenGLRenderWindow::SafeDownCast(window);
  Internals& in = *this->Internal;
  vtkFloatArray* out[2] = { position, normal };
  for (int k = 0; k < 2; ++k)
  {
    std::vector<float> rgba;
    if (!renWin || !out[k] || !in.HasLayout ||
      !vtkMRGIShaderUtilities::ReadTextureRGBA(renWin, in.FlatReceivers[k], rgba))
    {
      vtkErrorMacro("ReadReceivers: nothing gathered yet");
      return false;
    }
    out[k]->SetNumberOfComponents(4);
    out[k]->SetNumberOfTuples(static_cast<vtkIdType>(rgba.size() / 4));
    std::copy(rgba.begin(), rgba.end(), out[k]->GetPointer(0));
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkMRGIMultiresolution::ReadIrradiance(vtkRenderWindow* window, vtkFloatArray* irradiance)
{
  vtkOpenGLRenderWindow* renWin = vtkOpenGLRenderWindow::SafeDownCast(window);
  Internals& in = *this->Internal;
  std::vector<float> rgba;
  if (!renWin || !irradiance || !in.HasLayout ||
    !vtkMRGIShaderUtilities::ReadTextureRGBA(renWin, in.FlatIrradiance, rgba))
  {
    vtkErrorMacro("ReadIrradiance: nothing gathered yet");
    return false;
  }
  irradiance->SetNumberOfComponents(4);
  irradiance->SetNumberOfTuples(static_cast<vtkIdType>(rgba.size() / 4));
  std::copy(rgba.begin(), rgba.end(), irradiance->GetPointer(0));
  return true;
}

//------------------------------------------------------------------------------
bool vtkMRGIMultiresolution::ReadSelection(
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
bool vtkMRGIMultiresolution::ReadFlags(vtkRenderWindow* window, vtkUnsignedCharArray* flags)
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
void vtkMRGIMultiresolution::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "DepthThreshold: " << this->DepthThreshold << "\n";
  os << indent << "NormalThreshold: " << this->NormalThreshold << "\n";
  os << indent << "FinestLevel: " << this->FinestLevel << "\n";
  os << indent << "Balance: " << (this->Balance ? "On" : "Off") << "\n";
  os << indent << "CoarsestSide: " << this->CoarsestSide << "\n";
  os << indent << "Levels: " << this->GetNumberOfLevels() << "\n";
}
