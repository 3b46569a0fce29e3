#include "vtk_glew.h"

#include "vtkMRGIDirectShadows.h"

#include "vtkFloatArray.h"
#include "vtkMRGIBMRBlend.h"
#include "vtkMRGIBMRLevels.h"
#include "vtkMRGIBMRMask.h"
#include "vtkMRGIFrameContext.h"
#include "vtkMRGIFullScreenStep.h"
#include "vtkMRGIProgramCache.h"
#include "vtkMRGIReflectiveShadowMapPass.h"
#include "vtkMRGIShaderUtilities.h"
#include "vtkMRGIStageResources.h"
#include "vtkNew.h"
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
  // The multiresolution path's: the hard factors (shadow edges), the
  // blended 1 - factor (viewport-sized), levels, mask and blend.
  vtkTextureObject* Edges = nullptr;
  vtkTextureObject* Blended = nullptr;
  vtkNew<vtkMRGIBMRLevels> Levels;
  vtkNew<vtkMRGIBMRMask> Mask;
  vtkNew<vtkMRGIBMRBlend> Blend;

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
  this->Internal->Mask->SetPreset(vtkMRGIBMRMask::SSM);
  this->Internal->Blend->SetPreset(vtkMRGIBMRMask::SSM);
}

//------------------------------------------------------------------------------
vtkMRGIDirectShadows::~vtkMRGIDirectShadows()
{
  if (this->Internal->GL.FrameBuffer || !this->Internal->Depth.empty() ||
    this->Internal->Edges || this->Internal->Blended)
  {
    vtkErrorMacro("GL resources should have been freed in ReleaseGraphicsResources().");
  }
  this->Internal->ReleaseDepth(nullptr);
  vtkMRGIShaderUtilities::ReleaseTexture(this->Internal->Edges, nullptr);
  vtkMRGIShaderUtilities::ReleaseTexture(this->Internal->Blended, nullptr);
}

//------------------------------------------------------------------------------
void vtkMRGIDirectShadows::ReleaseGraphicsResources(vtkWindow* w)
{
  this->Internal->ReleaseDepth(w);
  vtkMRGIShaderUtilities::ReleaseTexture(this->Internal->Edges, w);
  vtkMRGIShaderUtilities::ReleaseTexture(this->Internal->Blended, w);
  this->Internal->Levels->ReleaseGraphicsResources(w);
  this->Internal->Mask->ReleaseGraphicsResources(w);
  this->Internal->Blend->ReleaseGraphicsResources(w);
  this->Internal->GL.Release(w);
}

//------------------------------------------------------------------------------
vtkMRGIBMRMask* vtkMRGIDirectShadows::GetBMRMask()
{
  return this->Internal->Mask;
}

//------------------------------------------------------------------------------
vtkMRGIBMRBlend* vtkMRGIDirectShadows::GetBMRBlend()
{
  return this->Internal->Blend;
}

//------------------------------------------------------------------------------
vtkMRGIBMRLevels* vtkMRGIDirectShadows::GetBMRLevels()
{
  return this->Internal->Levels;
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
  return this->Run(frame, rsm, slotLights, params, factors, nullptr);
}

//------------------------------------------------------------------------------
bool vtkMRGIDirectShadows::ComputeLevels(const vtkMRGIFrameContext& frame,
  vtkMRGIReflectiveShadowMapPass* rsm, const int* slotLights,
  const mrgi_direct_shadow_params& params, vtkMRGIBMRLevels* levels)
{
  if (!levels || levels->GetWidth() != frame.Viewport[2] ||
    levels->GetHeight() != frame.Viewport[3])
  {
    vtkErrorMacro("ComputeLevels: the BMR levels must be prepared for the frame's viewport ("
      << frame.Viewport[2] << " x " << frame.Viewport[3] << ")");
    return false;
  }
  return this->Run(frame, rsm, slotLights, params, nullptr, levels);
}

//------------------------------------------------------------------------------
bool vtkMRGIDirectShadows::ComputeMultiresolution(const vtkMRGIFrameContext& frame,
  vtkMRGIReflectiveShadowMapPass* rsm, const int* slotLights,
  const mrgi_direct_shadow_params& params, vtkTextureObject* factors)
{
  Internals& in = *this->Internal;
  vtkOpenGLRenderWindow* window = frame.Window;
  const int w = frame.Viewport[2], h = frame.Viewport[3];
  if (!window || !factors || w < 1 || h < 1 ||
    frame.Viewport[0] + w > static_cast<int>(factors->GetWidth()) ||
    frame.Viewport[1] + h > static_cast<int>(factors->GetHeight()))
  {
    vtkErrorMacro("ComputeMultiresolution needs the frame's window and viewport and a factor "
                  "texture that holds the viewport");
    return false;
  }
  const int tw = static_cast<int>(factors->GetWidth());
  const int th = static_cast<int>(factors->GetHeight());
  if (!in.Edges || static_cast<int>(in.Edges->GetWidth()) != tw ||
    static_cast<int>(in.Edges->GetHeight()) != th)
  {
    vtkMRGIShaderUtilities::ReleaseTexture(in.Edges, window);
    in.Edges = vtkMRGIShaderUtilities::NewTexture(window, GL_RGBA32F, tw, th);
  }
  if (!in.Blended || static_cast<int>(in.Blended->GetWidth()) != w ||
    static_cast<int>(in.Blended->GetHeight()) != h)
  {
    vtkMRGIShaderUtilities::ReleaseTexture(in.Blended, window);
    in.Blended = vtkMRGIShaderUtilities::NewTexture(window, GL_RGBA32F, w, h);
  }
  if (!in.Edges || !in.Blended || !in.Levels->Prepare(window, w, h))
  {
    vtkErrorMacro("ComputeMultiresolution: could not allocate its targets (" << w << " x " << h
                                                                            << ")");
    return false;
  }
  // The shadow edges of the SSM mask: the hard (PCF) factors of the first
  // slot, cheap against the soft ones.
  mrgi_direct_shadow_params hard = params;
  hard.mode = MRGI_DIRECT_SHADOW_HARD;
  vtkMRGIFrameContext atOrigin = frame;
  atOrigin.Viewport[0] = atOrigin.Viewport[1] = 0;
  if (!this->Run(frame, rsm, slotLights, hard, in.Edges, nullptr) ||
    !in.Mask->Build(frame, in.Levels, in.Edges) ||
    !this->Run(frame, rsm, slotLights, params, nullptr, in.Levels) ||
    !in.Blend->Blend(atOrigin, in.Levels, in.Blended))
  {
    return false;
  }
  // factors = 1 - blended shadowing over the viewport.
  vtkOpenGLQuadHelper* quad = in.Ready(window, 2);
  if (!quad)
  {
    vtkErrorMacro("could not build the direct-shadow conversion shader");
    return false;
  }
  {
    vtkMRGIShaderUtilities::ScopedStage step(frame.Timer, "shadows.factors.invert");
    vtkMRGIFullScreenStep steps(window, in.GL.FrameBuffer);
    steps.Target(factors, nullptr, frame.Viewport[0], frame.Viewport[1], w, h);
    window->GetShaderCache()->ReadyShaderProgram(quad->Program);
    vtkMRGIFullScreenStep::BindInputs(quad->Program, { in.Blended });
    const int origin[2] = { frame.Viewport[0], frame.Viewport[1] };
    quad->Program->SetUniform2i("mrgiOrigin", origin);
    quad->Render();
    vtkMRGIFullScreenStep::UnbindInputs({ in.Blended });
  }
  const GLenum error = glGetError();
  if (error != GL_NO_ERROR)
  {
    vtkErrorMacro("OpenGL error " << error << " in the multiresolution direct-shadow stage");
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkMRGIDirectShadows::Run(const vtkMRGIFrameContext& frame,
  vtkMRGIReflectiveShadowMapPass* rsm, const int* slotLights,
  const mrgi_direct_shadow_params& params, vtkTextureObject* factors, vtkMRGIBMRLevels* levels)
{
  this->NumberOfDraws = 0;
  vtkOpenGLRenderWindow* window = frame.Window;
  const int x0 = frame.Viewport[0], y0 = frame.Viewport[1];
  const int w = frame.Viewport[2], h = frame.Viewport[3];
  if (!window || !frame.Position || !frame.Normal || !rsm || !slotLights || (!factors && !levels))
  {
    vtkErrorMacro("Compute needs the frame's window and G-buffer (position, normal), the RSM "
                  "pass, the slots' lights and a factor texture");
    return false;
  }
  if (w < 1 || h < 1 || x0 < 0 || y0 < 0 ||
    (factors &&
      (x0 + w > static_cast<int>(factors->GetWidth()) ||
        y0 + h > static_cast<int>(factors->GetHeight()))))
  {
    vtkErrorMacro("Compute: the viewport (" << x0 << ", " << y0 << ", " << w << ", " << h
                                            << ") does not fit in the "
                                            << (factors ? factors->GetWidth() : 0) << " x "
                                            << (factors ? factors->GetHeight() : 0)
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
  // The per-slot draws of one target: the factors (level -1), or one BMR
  // level's colour target under its stencil, 1 - factor (LevelStep clears
  // it to 0: lit).
  auto draw = [&](int level) {
    window->GetShaderCache()->ReadyShaderProgram(program);
    program->SetUniformMatrix4x4("mrgiVCToWC", const_cast<float*>(frame.ViewToWorld));
    program->SetUniformi("mrgiSize", size);
    program->SetUniformi("mrgiMode", params.mode);
    program->SetUniformi("mrgiSamplesSide", params.samples_side);
    program->SetUniformf("mrgiLightRadius", static_cast<float>(params.light_radius));
    const int origin[2] = { x0, y0 };
    const int frameSize[2] = { w, h };
    program->SetUniformi("mrgiLevel", level);
    program->SetUniform2i("mrgiOrigin", origin);
    program->SetUniform2i("mrgiFrameSize", frameSize);
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
    ostate->vtkglColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  };
  if (levels)
  {
    for (int k = 0; k < vtkMRGIBMRLevels::GetNumberOfLevels(); ++k)
    {
      vtkMRGIBMRLevels::LevelStep levelStep(window, levels, k);
      if (!levelStep.IsValid())
      {
        vtkErrorMacro("Compute: could not bind BMR level " << k);
        return false;
      }
      draw(k);
    }
  }
  else
  {
    steps.Target(factors, nullptr, x0, y0, w, h);
    // Every channel starts lit (1) over the viewport only.
    ostate->vtkglColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    ostate->vtkglEnable(GL_SCISSOR_TEST);
    ostate->vtkglScissor(x0, y0, w, h);
    ostate->vtkglClearColor(1.0, 1.0, 1.0, 1.0);
    ostate->vtkglClear(GL_COLOR_BUFFER_BIT);
    ostate->vtkglDisable(GL_SCISSOR_TEST);
    draw(-1);
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
