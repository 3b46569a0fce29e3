#include "vtk_glew.h"

#include "vtkMRGIOutput.h"

#include "vtkMRGICompositeFS.h"
#include "vtkMRGIFullScreenStep.h"
#include "vtkMRGIGBuffer.h"
#include "vtkMRGIProgramCache.h"
#include "vtkMRGIRenderSteps.h"
#include "vtkMRGIShaderUtilities.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLQuadHelper.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"

#include "mrgi_exposure.h"

#include <algorithm>
#include <vector>

//------------------------------------------------------------------------------
bool vtkMRGIOutput::Write(vtkOpenGLRenderWindow* window, vtkMRGIProgramCache& programs,
  const vtkMRGIGBuffer& g, const int viewport[4], vtkTextureObject* source, float scale,
  bool toneMap, DepthMode depth)
{
  const bool gbuffer = depth == DepthAndGBuffer;
  vtkOpenGLQuadHelper* quad = programs.Ready(window, "output",
    depth == NoDepth ? "#define MRGI_OUTPUT_NO_DEPTH\n"
      : gbuffer      ? "#define MRGI_OUTPUT_GBUFFER\n"
                     : "",
    [] { return vtkMRGICompositeFS; });
  if (!quad)
  {
    return false;
  }
  vtkShaderProgram* program = quad->Program;
  vtkOpenGLState* ostate = window->GetState();
  vtkMRGIViewportStep state(ostate, viewport);
  vtkOpenGLState::ScopedglDepthFunc depthFunc(ostate);
  vtkOpenGLState::ScopedglDepthMask depthMask(ostate);
  if (depth != NoDepth)
  {
    ostate->vtkglEnable(GL_DEPTH_TEST); // writes the scene's depth (GL_ALWAYS)
    ostate->vtkglDepthFunc(GL_ALWAYS);
    ostate->vtkglDepthMask(GL_TRUE);
    g.Depth->Activate();
    program->SetUniformi("mrgiDepth", g.Depth->GetTextureUnit());
  }
  else
  {
    ostate->vtkglDisable(GL_DEPTH_TEST);
    ostate->vtkglDepthMask(GL_FALSE);
  }
  if (gbuffer)
  {
    g.Position->Activate();
    g.Normal->Activate();
    program->SetUniformi("mrgiPosition", g.Position->GetTextureUnit());
    program->SetUniformi("mrgiNormal", g.Normal->GetTextureUnit());
  }
  source->Activate();
  program->SetUniformi("mrgiColor", source->GetTextureUnit());
  program->SetUniformf("mrgiExposureScale", scale);
  program->SetUniformi("mrgiToneMap", toneMap ? 1 : 0);
  quad->Render();
  source->Deactivate();
  if (gbuffer)
  {
    g.Normal->Deactivate();
    g.Position->Deactivate();
  }
  if (depth != NoDepth)
  {
    g.Depth->Deactivate();
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkMRGIOutput::WriteWithFXAA(vtkRenderer* renderer, vtkOpenGLRenderWindow* window,
  vtkMRGIProgramCache& programs, vtkMRGIGBuffer& g, const int viewport[4], float scale,
  bool toneMap, DepthMode depth, vtkOpenGLFXAAFilter*& fxaa)
{
  vtkOpenGLFramebufferObject* fbo = g.FrameBuffer;
  fbo->SaveCurrentBindingsAndBuffers();
  fbo->Bind();
  fbo->RemoveColorAttachments(MRGI_GBUFFER_MAX_ATTACHMENTS);
  fbo->AddColorAttachment(0, g.Display);
  vtkMRGIShaderUtilities::SelectDrawBuffers(fbo, 1);
  const bool exposed = Write(window, programs, g, viewport, g.Color, scale, toneMap, NoDepth);
  fbo->UnBind();
  fbo->RestorePreviousBindingsAndBuffers();
  if (!exposed)
  {
    return false;
  }
  vtkMRGIRenderSteps::RenderFXAA(renderer, fbo, g.Display, viewport, fxaa);
  // The display image is final: copied as it is.
  return Write(window, programs, g, viewport, g.Display, 1.0f, false, depth);
}

//------------------------------------------------------------------------------
bool vtkMRGIOutput::MeasureExposure(vtkOpenGLRenderWindow* window, const vtkMRGIGBuffer& g,
  const int viewport[4], double key, double& ev, std::string& problem)
{
  ev = 0.0;
  const int x0 = viewport[0], y0 = viewport[1];
  const int w = viewport[2], h = viewport[3];
  // The viewport's pixels straight into one buffer: a whole-texture copy
  // beside it cost a second 16 bytes per pixel, allocated and zero-filled
  // every frame (Documentation/Multiresolution.md, "Cold start").
  std::vector<float> colour(static_cast<size_t>(w) * h * 4);
  if (w < 1 || h < 1 ||
    !vtkMRGIShaderUtilities::ReadTextureRegion(window, g.Color, x0, y0, w, h, 4, colour.data()))
  {
    problem = "reading the colour back failed";
    return false;
  }
  std::vector<float> depth(static_cast<size_t>(w) * h);
  vtkOpenGLFramebufferObject* fbo = g.FrameBuffer;
  fbo->SaveCurrentBindingsAndBuffers();
  fbo->Bind();
  fbo->AddDepthAttachment(g.Depth);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(x0, y0, w, h, GL_DEPTH_COMPONENT, GL_FLOAT, depth.data());
  fbo->UnBind();
  fbo->RestorePreviousBindingsAndBuffers();
  double logAverage = 0.0, highlight = 0.0;
  mrgi_error err;
  const int64_t count = static_cast<int64_t>(w) * h;
  if (mrgi_exposure_log_average(
        colour.data(), 4, depth.data(), count, &logAverage, nullptr, &err) != MRGI_OK ||
    mrgi_exposure_quantile(colour.data(), 4, depth.data(), count, MRGI_EXPOSURE_HIGHLIGHT_FRACTION,
      &highlight, &err) != MRGI_OK)
  {
    problem = err.message;
    return false;
  }
  ev = mrgi_exposure_auto_ev(logAverage, highlight, key);
  return true;
}
