#include "vtk_glew.h"

#include "vtkMRGIFullScreenStep.h"

#include "vtkMRGIProgramCache.h"
#include "vtkMRGIShaderUtilities.h"
#include "vtkOpenGLQuadHelper.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"
#include "vtkUnsignedCharArray.h"

#include "vtkMRGIAddIndirectFS.h"

#include "mrgi_buffers.h"
#include "mrgi_multires.h"

#include <string>

//------------------------------------------------------------------------------
vtkMRGIFullScreenStep::vtkMRGIFullScreenStep(
  vtkOpenGLRenderWindow* window, vtkOpenGLFramebufferObject* fbo)
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

//------------------------------------------------------------------------------
vtkMRGIFullScreenStep::~vtkMRGIFullScreenStep()
{
  this->Fbo->RemoveColorAttachments(MRGI_MULTIRES_TEX_COUNT + 1);
  this->Fbo->UnBind();
  this->Fbo->RestorePreviousBindingsAndBuffers();
}

//------------------------------------------------------------------------------
void vtkMRGIFullScreenStep::Target(vtkTextureObject* a, vtkTextureObject* b, int x, int y, int w, int h)
{
  this->Fbo->RemoveColorAttachments(MRGI_MULTIRES_TEX_COUNT + 1);
  this->Fbo->AddColorAttachment(0, a);
  if (b)
  {
    this->Fbo->AddColorAttachment(1, b);
  }
  vtkMRGIShaderUtilities::SelectDrawBuffers(this->Fbo, b ? 2 : 1);
  this->State->vtkglViewport(x, y, w, h);
}

//------------------------------------------------------------------------------
void vtkMRGIFullScreenStep::Targets(std::initializer_list<vtkTextureObject*> targets, int w, int h)
{
  this->Fbo->RemoveColorAttachments(MRGI_MULTIRES_TEX_COUNT + 1);
  unsigned int k = 0;
  for (vtkTextureObject* t : targets)
  {
    this->Fbo->AddColorAttachment(k++, t);
  }
  vtkMRGIShaderUtilities::SelectDrawBuffers(this->Fbo, k);
  this->State->vtkglViewport(0, 0, w, h);
}

//------------------------------------------------------------------------------
void vtkMRGIFullScreenStep::BeginMaskWrite(vtkTextureObject* depthStencil, bool clear)
{
  vtkOpenGLState* ostate = this->State;
  glFramebufferTexture2D(
    GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_TEXTURE_2D, depthStencil->GetHandle(), 0);
  ostate->vtkglClearColor(0.0, 0.0, 0.0, 0.0);
  ostate->vtkglStencilMask(0xFF);
  glClearStencil(0);
  if (clear)
  {
    ostate->vtkglClear(GL_COLOR_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
  }
  ostate->vtkglEnable(GL_STENCIL_TEST);
  ostate->vtkglStencilFunc(GL_ALWAYS, 1, 0xFF);
  ostate->vtkglStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
}

//------------------------------------------------------------------------------
void vtkMRGIFullScreenStep::EndMaskWrite()
{
  this->State->vtkglStencilFunc(GL_ALWAYS, 0, 0xFF);
  this->State->vtkglStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_TEXTURE_2D, 0, 0);
}

//------------------------------------------------------------------------------
void vtkMRGIFullScreenStep::BeginStencilRead(vtkTextureObject* depthStencil, bool clear)
{
  vtkOpenGLState* ostate = this->State;
  glFramebufferTexture2D(
    GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_TEXTURE_2D, depthStencil->GetHandle(), 0);
  ostate->vtkglClearColor(0.0, 0.0, 0.0, 0.0);
  if (clear)
  {
    ostate->vtkglClear(GL_COLOR_BUFFER_BIT);
  }
  ostate->vtkglEnable(GL_STENCIL_TEST);
  ostate->vtkglStencilMask(0x00);
  ostate->vtkglStencilFunc(GL_EQUAL, 1, 0xFF);
  ostate->vtkglStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
}

//------------------------------------------------------------------------------
void vtkMRGIFullScreenStep::EndStencilRead()
{
  this->State->vtkglStencilMask(0xFF);
  this->State->vtkglStencilFunc(GL_ALWAYS, 0, 0xFF);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_TEXTURE_2D, 0, 0);
}

//------------------------------------------------------------------------------
void vtkMRGIFullScreenStep::BindInputs(
  vtkShaderProgram* program, std::initializer_list<vtkTextureObject*> textures)
{
  int k = 0;
  for (vtkTextureObject* t : textures)
  {
    t->Activate();
    program->SetUniformi(("mrgiInput" + std::to_string(k++)).c_str(), t->GetTextureUnit());
  }
}

//------------------------------------------------------------------------------
void vtkMRGIFullScreenStep::UnbindInputs(std::initializer_list<vtkTextureObject*> textures)
{
  for (vtkTextureObject* t : textures)
  {
    t->Deactivate();
  }
}

//------------------------------------------------------------------------------
bool vtkMRGIFullScreenStep::ReadFlattened(vtkOpenGLRenderWindow* window,
  const mrgi_multires_layout& layout, int components, const std::vector<vtkTextureObject*>& levels,
  std::vector<float>& flat)
{
  if (levels.size() != static_cast<size_t>(layout.level_count))
  {
    return false;
  }
  const size_t W = static_cast<size_t>(layout.total_width);
  const size_t C = static_cast<size_t>(components);
  flat.assign(W * static_cast<size_t>(layout.total_height) * C, 0.0f);
  for (int i = 0; i < layout.level_count; ++i)
  {
    std::vector<float> rgba;
    if (!vtkMRGIShaderUtilities::ReadTextureRGBA(window, levels[static_cast<size_t>(i)], rgba))
    {
      return false;
    }
    const size_t w = static_cast<size_t>(layout.level_width[i]);
    for (size_t y = 0; y < static_cast<size_t>(layout.level_height[i]); ++y)
    {
      for (size_t x = 0; x < w; ++x)
      {
        const size_t to = (y * W + static_cast<size_t>(layout.level_offset[i]) + x) * C;
        for (size_t c = 0; c < C; ++c)
        {
          flat[to + c] = rgba[(y * w + x) * 4 + c];
        }
      }
    }
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkMRGIFullScreenStep::ReadMask(vtkOpenGLRenderWindow* window,
  vtkOpenGLFramebufferObject* fbo, const mrgi_multires_layout& layout, vtkTextureObject* colour,
  vtkTextureObject* stencil, bool fromStencil, vtkUnsignedCharArray* mask)
{
  const vtkIdType n = static_cast<vtkIdType>(layout.total_width) * layout.total_height;
  mask->SetNumberOfComponents(1);
  mask->SetNumberOfTuples(n);
  if (!fromStencil)
  {
    std::vector<float> rgba;
    if (!vtkMRGIShaderUtilities::ReadTextureRGBA(window, colour, rgba))
    {
      return false;
    }
    for (vtkIdType i = 0; i < n; ++i)
    {
      mask->SetValue(i, rgba[4 * static_cast<size_t>(i)] > 0.5f ? 1 : 0);
    }
    return true;
  }
  window->MakeCurrent();
  vtkOpenGLState* ostate = window->GetState();
  ostate->PushReadFramebufferBinding();
  fbo->Bind(GL_READ_FRAMEBUFFER);
  glFramebufferTexture2D(
    GL_READ_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_TEXTURE_2D, stencil->GetHandle(), 0);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, layout.total_width, layout.total_height, GL_STENCIL_INDEX, GL_UNSIGNED_BYTE,
    mask->GetPointer(0));
  glFramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_TEXTURE_2D, 0, 0);
  ostate->PopReadFramebufferBinding();
  return glGetError() == GL_NO_ERROR;
}

//------------------------------------------------------------------------------
bool vtkMRGIFullScreenStep::BlendInto(vtkOpenGLRenderWindow* window,
  vtkOpenGLFramebufferObject* fbo, vtkOpenGLQuadHelper* quad, const int viewport[4],
  vtkTextureObject* input, unsigned int srcRGB, unsigned int dstRGB, vtkTextureObject* colour,
  const std::function<void(vtkShaderProgram*)>& uniforms)
{
  vtkShaderProgram* program = quad->Program;
  {
    vtkMRGIFullScreenStep steps(window, fbo);
    steps.Target(colour, nullptr, viewport[0], viewport[1], viewport[2], viewport[3]);
    vtkOpenGLState* ostate = steps.GetState();
    vtkOpenGLState::ScopedglBlendFuncSeparate blendFunc(ostate);
    ostate->vtkglEnable(GL_BLEND);
    ostate->vtkglBlendFuncSeparate(srcRGB, dstRGB, GL_ZERO, GL_ONE);
    BindInputs(program, { input });
    const int origin[2] = { viewport[0], viewport[1] };
    const int size[2] = { viewport[2], viewport[3] };
    program->SetUniform2i("mrgiOrigin", origin);
    program->SetUniform2i("mrgiSize", size);
    if (uniforms)
    {
      uniforms(program);
    }
    quad->Render();
    UnbindInputs({ input });
  }
  return glGetError() == GL_NO_ERROR;
}

//------------------------------------------------------------------------------
bool vtkMRGIFullScreenStep::AddRGB(vtkOpenGLRenderWindow* window, vtkMRGIProgramCache& programs,
  vtkOpenGLFramebufferObject* fbo, const int viewport[4], vtkTextureObject* source,
  vtkTextureObject* target)
{
  vtkOpenGLQuadHelper* quad = programs.Ready(window, "add", "", [] { return vtkMRGIAddIndirectFS; });
  if (!quad || !fbo || !source || !target)
  {
    return false;
  }
  vtkShaderProgram* program = quad->Program;
  vtkOpenGLState* ostate = window->GetState();
  vtkMRGIViewportStep state(ostate, viewport);
  vtkOpenGLState::ScopedglBlendFuncSeparate blendFunc(ostate);
  ostate->vtkglEnable(GL_BLEND);
  ostate->vtkglBlendFuncSeparate(GL_ONE, GL_ONE, GL_ZERO, GL_ONE);
  fbo->SaveCurrentBindingsAndBuffers();
  fbo->Bind();
  fbo->RemoveColorAttachments(MRGI_GBUFFER_MAX_ATTACHMENTS);
  fbo->AddColorAttachment(0, target);
  vtkMRGIShaderUtilities::SelectDrawBuffers(fbo, 1);
  source->Activate();
  program->SetUniformi("mrgiIndirect", source->GetTextureUnit());
  quad->Render();
  source->Deactivate();
  fbo->UnBind();
  fbo->RestorePreviousBindingsAndBuffers();
  return true;
}
