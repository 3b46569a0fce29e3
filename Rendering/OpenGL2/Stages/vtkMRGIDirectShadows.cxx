#include "vtk_glew.h"

#include "vtkMRGIDirectShadows.h"

#include "vtkFloatArray.h"
#include "vtkMRGIFrameContext.h"
#include "vtkMRGIFullScreenStep.h"
#include "vtkMRGIProgramCache.h"
#include "vtkMRGIReflectiveShadowMapPass.h"
#include "vtkMRGIShaderUtilities.h"
#include "vtkMRGIStageResources.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLQuadHelper.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"

#include "vtkMRGIDirectShadowFS.h"

#include "mrgi_buffers.h"
#include "mrgi_direct_shadow.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkMRGIDirectShadows);

struct vtkMRGIDirectShadows::Internals
{
  vtkMRGIStageResources GL; // framebuffer and programs
  // Per RSM view, its depth map (R32F, S x S), derived when the RSMs'
  // contents change (GetContentTime()), not every frame.
  std::vector<vtkTextureObject*> Depth;
  vtkMTimeType DepthTime = 0;
  int DepthSize = 0;
  vtkIdType DepthUpdates = 0;

  void ReleaseDepth(vtkWindow* w)
  {
    for (vtkTextureObject*& t : this->Depth)
    {
      vtkMRGIShaderUtilities::ReleaseTexture(t, w);
    }
    this->Depth.clear();
    this->DepthTime = 0;
    this->DepthSize = 0;
  }

  vtkOpenGLQuadHelper* Ready(vtkOpenGLRenderWindow* window, int stage)
  {
    return this->GL.Programs.Ready(window, "directshadows",
      "#define MRGI_DS_STAGE " + std::to_string(stage) + "\n",
      [] { return std::string(vtkMRGIDirectShadowFS); });
  }
};

//------------------------------------------------------------------------------
vtkMRGIDirectShadows::vtkMRGIDirectShadows()
  : Internal(new Internals)
{
}

//------------------------------------------------------------------------------
vtkMRGIDirectShadows::~vtkMRGIDirectShadows()
{
  if (this->Internal->GL.FrameBuffer || !this->Internal->Depth.empty())
  {
    vtkErrorMacro("GL resources should have been freed in ReleaseGraphicsResources().");
  }
  this->Internal->ReleaseDepth(nullptr);
}

//------------------------------------------------------------------------------
void vtkMRGIDirectShadows::ReleaseGraphicsResources(vtkWindow* w)
{
  this->Internal->ReleaseDepth(w);
  this->Internal->GL.Release(w);
}

//------------------------------------------------------------------------------
vtkIdType vtkMRGIDirectShadows::GetNumberOfDepthUpdates() const
{
  return this->Internal->DepthUpdates;
}

namespace
{
// One view as the shader takes it: world -> view column-major (the twin's
// and GLSL's order) and (sx, sy, near, perspective).
struct ViewUniforms
{
  float WorldToView[16];
  float Terms[4];
  vtkTextureObject* Positions;
  int Index; // in the RSM pass
};

bool GetViewUniforms(vtkMRGIReflectiveShadowMapPass* rsm, int i, ViewUniforms& out)
{
  double m[16], p[16];
  if (!rsm->GetViewWorldToView(i, m) || !rsm->GetViewProjection(i, p))
  {
    return false;
  }
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      out.WorldToView[4 * c + r] = static_cast<float>(m[4 * r + c]);
    }
  }
  const bool perspective = rsm->GetViewPerspective(i);
  out.Terms[0] = static_cast<float>(p[0]);
  out.Terms[1] = static_cast<float>(p[5]);
  // Perspective: P22 = (f + n) / (n - f), P23 = 2 f n / (n - f), so n = P23 / (P22 - 1).
  out.Terms[2] = perspective ? static_cast<float>(p[11] / (p[10] - 1.0)) : 0.0f;
  out.Terms[3] = perspective ? 1.0f : 0.0f;
  out.Positions = rsm->GetPositionTexture(i);
  out.Index = i;
  return out.Positions != nullptr;
}
}

//------------------------------------------------------------------------------
bool vtkMRGIDirectShadows::Compute(const vtkMRGIFrameContext& frame,
  vtkMRGIReflectiveShadowMapPass* rsm, const int* slotLights,
  const mrgi_direct_shadow_params& params, vtkTextureObject* factors)
{
  this->NumberOfDraws = 0;
  vtkOpenGLRenderWindow* window = frame.Window;
  const int x0 = frame.Viewport[0], y0 = frame.Viewport[1];
  const int w = frame.Viewport[2], h = frame.Viewport[3];
  if (!window || !frame.Position || !frame.Normal || !rsm || !slotLights || !factors)
  {
    vtkErrorMacro("Compute needs the frame's window and G-buffer (position, normal), the RSM "
                  "pass, the slots' lights and a factor texture");
    return false;
  }
  if (w < 1 || h < 1 || x0 < 0 || y0 < 0 ||
    x0 + w > static_cast<int>(factors->GetWidth()) ||
    y0 + h > static_cast<int>(factors->GetHeight()))
  {
    vtkErrorMacro("Compute: the viewport (" << x0 << ", " << y0 << ", " << w << ", " << h
                                            << ") does not fit in the " << factors->GetWidth()
                                            << " x " << factors->GetHeight()
                                            << " factor texture");
    return false;
  }
  mrgi_error err;
  if (mrgi_direct_shadow_params_check(&params, &err) != MRGI_OK)
  {
    vtkErrorMacro("Compute: " << err.message);
    return false;
  }

  // The views of each slot's light, in the RSM pass's order (the twin's view order).
  std::vector<ViewUniforms> slotViews[MRGI_SHADOW_SLOTS];
  for (int s = 0; s < MRGI_SHADOW_SLOTS; ++s)
  {
    if (slotLights[s] < 0)
    {
      continue;
    }
    for (int i = 0; i < rsm->GetNumberOfViews(); ++i)
    {
      if (rsm->GetViewLight(i) != slotLights[s])
      {
        continue;
      }
      ViewUniforms view;
      if (!GetViewUniforms(rsm, i, view))
      {
        vtkErrorMacro("Compute: RSM view " << i << " has no camera or positions");
        return false;
      }
      slotViews[s].push_back(view);
    }
    if (slotViews[s].size() > MRGI_DIRECT_SHADOW_MAX_VIEWS)
    {
      vtkErrorMacro("Compute: light " << slotLights[s] << " has " << slotViews[s].size()
                                      << " RSM views, more than "
                                      << MRGI_DIRECT_SHADOW_MAX_VIEWS);
      return false;
    }
  }

  Internals& in = *this->Internal;
  in.GL.Prepare(window);
  vtkOpenGLQuadHelper* depthQuad = in.Ready(window, 0);
  vtkOpenGLQuadHelper* quad = in.Ready(window, 1);
  if (!quad || !depthQuad)
  {
    vtkErrorMacro("could not build the direct-shadow shaders");
    return false;
  }
  vtkShaderProgram* program = quad->Program;
  // S from the maps themselves: the resolution setting may have changed
  // since they were rendered.
  const int viewCount = rsm->GetNumberOfViews();
  vtkTextureObject* first = viewCount > 0 ? rsm->GetPositionTexture(0) : nullptr;
  const int size = first ? static_cast<int>(first->GetWidth()) : 0;
  for (int i = 0; i < viewCount; ++i)
  {
    vtkTextureObject* t = rsm->GetPositionTexture(i);
    if (!t || static_cast<int>(t->GetWidth()) != size || static_cast<int>(t->GetHeight()) != size)
    {
      vtkErrorMacro("Compute: RSM view " << i << " is not a " << size << " x " << size << " map");
      return false;
    }
  }

  vtkMRGIShaderUtilities::ScopedStage step(frame.Timer, "shadows.factors");
  vtkMRGIFullScreenStep steps(window, in.GL.FrameBuffer);
  vtkOpenGLState* ostate = steps.GetState();

  // The views' depth maps, again only when the RSMs were re-rendered.
  if (in.DepthTime != rsm->GetContentTime() || in.DepthSize != size ||
    static_cast<int>(in.Depth.size()) != viewCount)
  {
    in.ReleaseDepth(window);
    vtkShaderProgram* depth = depthQuad->Program;
    window->GetShaderCache()->ReadyShaderProgram(depth);
    for (int i = 0; i < viewCount; ++i)
    {
      ViewUniforms view;
      vtkTextureObject* map = vtkMRGIShaderUtilities::NewTexture(window, GL_R32F, size, size);
      in.Depth.push_back(map);
      if (!map || !GetViewUniforms(rsm, i, view))
      {
        in.ReleaseDepth(window);
        vtkErrorMacro("Compute: could not derive the depth map of RSM view " << i << " ("
                                                                            << size << "^2)");
        return false;
      }
      steps.Targets({ map }, size, size);
      vtkMRGIFullScreenStep::BindInputs(depth, { view.Positions });
      depth->SetUniformMatrix4x4v("mrgiWorldToView", 1, view.WorldToView);
      depth->SetUniformi("mrgiView", 0);
      depthQuad->Render();
      vtkMRGIFullScreenStep::UnbindInputs({ view.Positions });
    }
    in.DepthTime = rsm->GetContentTime();
    in.DepthSize = size;
    ++in.DepthUpdates;
  }
  vtkOpenGLState::ScopedglColorMask colorMask(ostate);
  vtkOpenGLState::ScopedglScissor scissorBox(ostate); // the step saves only its enable
  steps.Target(factors, nullptr, x0, y0, w, h);
  // Every channel starts lit (1) over the viewport only.
  ostate->vtkglColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  ostate->vtkglEnable(GL_SCISSOR_TEST);
  ostate->vtkglScissor(x0, y0, w, h);
  ostate->vtkglClearColor(1.0, 1.0, 1.0, 1.0);
  ostate->vtkglClear(GL_COLOR_BUFFER_BIT);
  ostate->vtkglDisable(GL_SCISSOR_TEST);

  window->GetShaderCache()->ReadyShaderProgram(program);
  program->SetUniformMatrix4x4("mrgiVCToWC", const_cast<float*>(frame.ViewToWorld));
  program->SetUniformi("mrgiSize", size);
  program->SetUniformi("mrgiMode", params.mode);
  program->SetUniformi("mrgiSamplesSide", params.samples_side);
  program->SetUniformf("mrgiLightRadius", static_cast<float>(params.light_radius));
  for (int s = 0; s < MRGI_SHADOW_SLOTS; ++s)
  {
    const std::vector<ViewUniforms>& views = slotViews[s];
    if (views.empty())
    {
      continue;
    }
    ostate->vtkglColorMask(s == 0, s == 1, s == 2, s == 3);
    float matrices[16 * MRGI_DIRECT_SHADOW_MAX_VIEWS];
    float terms[MRGI_DIRECT_SHADOW_MAX_VIEWS][4];
    for (size_t k = 0; k < views.size(); ++k)
    {
      std::copy(views[k].WorldToView, views[k].WorldToView + 16, matrices + 16 * k);
      std::copy(views[k].Terms, views[k].Terms + 4, terms[k]);
    }
    const int count = static_cast<int>(views.size());
    program->SetUniformMatrix4x4v("mrgiWorldToView", count, matrices);
    program->SetUniform4fv("mrgiViewTerms", count, terms);
    program->SetUniformi("mrgiViewCount", count);
    for (int k = 0; k < count; ++k)
    {
      vtkTextureObject* depth = in.Depth[static_cast<size_t>(views[k].Index)];
      vtkMRGIFullScreenStep::BindInputs(program, { frame.Position, frame.Normal, depth });
      program->SetUniformi("mrgiView", k);
      quad->Render();
      vtkMRGIFullScreenStep::UnbindInputs({ frame.Position, frame.Normal, depth });
      ++this->NumberOfDraws;
    }
  }
  const GLenum error = glGetError();
  if (error != GL_NO_ERROR)
  {
    vtkErrorMacro("OpenGL error " << error << " in the direct-shadow stage");
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkMRGIDirectShadows::ReadFactors(
  vtkRenderWindow* window, vtkTextureObject* factors, vtkFloatArray* out)
{
  vtkOpenGLRenderWindow* renWin = vtkOpenGLRenderWindow::SafeDownCast(window);
  std::vector<float> rgba;
  if (!renWin || !factors || !out || !vtkMRGIShaderUtilities::ReadTextureRGBA(renWin, factors, rgba))
  {
    return false;
  }
  out->SetNumberOfComponents(4);
  out->SetNumberOfTuples(static_cast<vtkIdType>(rgba.size() / 4));
  std::copy(rgba.begin(), rgba.end(), out->GetPointer(0));
  return true;
}

//------------------------------------------------------------------------------
void vtkMRGIDirectShadows::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "NumberOfDraws: " << this->NumberOfDraws << "\n";
}
