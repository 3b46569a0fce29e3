#include "vtk_glew.h" // first: GLEW must precede every other GL header

#include "vtkMRGIHeadlessDepth.h"

#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"

namespace
{
// vtkOpenGLRenderWindow's answer before it has a context; its framebuffers
// have at least this many depth bits.
const int kDefaultDepthBits = 24;
}

int vtkMRGIHeadlessDepth::RenderFramebufferDepthBits(vtkOpenGLRenderWindow* window, bool initialized)
{
  vtkOpenGLFramebufferObject* target = window ? window->GetRenderFramebuffer() : nullptr;
  if (!initialized || !target || target->GetFBOIndex() == 0)
  {
    return kDefaultDepthBits;
  }
  window->MakeCurrent();
  vtkOpenGLState* state = window->GetState();
  while (glGetError() != GL_NO_ERROR)
  {
    // earlier errors are not this query's
  }
  state->PushDrawFramebufferBinding();
  state->vtkglBindFramebuffer(GL_DRAW_FRAMEBUFFER, target->GetFBOIndex());
  GLint bits = 0;
  glGetFramebufferAttachmentParameteriv(
    GL_DRAW_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_FRAMEBUFFER_ATTACHMENT_DEPTH_SIZE, &bits);
  const bool ok = glGetError() == GL_NO_ERROR && bits > 0;
  state->PopDrawFramebufferBinding();
  return ok ? static_cast<int>(bits) : kDefaultDepthBits;
}
