#include "vtk_glew.h"

#include "vtkMRGIVarianceShadowQuery.h"

#include "vtkFloatArray.h"
#include "vtkMRGIAreaLight.h"
#include "vtkMRGIFrameContext.h"
#include "vtkMRGIShaderLibraries.h"
#include "vtkMRGIShaderUtilities.h"
#include "vtkMRGIVoxelization.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLQuadHelper.h"
#include "vtkOpenGLRenderUtilities.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"
#include "vtkUnsignedCharArray.h"

#include "vtkMRGIVPLIrradiance.h"
#include "vtkMRGIVarianceShadowMomentsFS.h"
#include "vtkMRGIVarianceShadowResolve.h"

#include "mrgi_variance_shadow.h"
#include "mrgi_visibility_pyramid.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkMRGIVarianceShadowQuery);

namespace
{
constexpr int Targets = MRGI_VOXEL_VSM_TARGETS;
// Queries per pixel with 2x2 interleaving, two floats each.
constexpr int LocalQueries = MRGI_VOXEL_VSM_QUERIES / MRGI_VOXEL_INTERLEAVE_PHASES;
static_assert(MRGI_VOXEL_VSM_QUERIES % MRGI_VOXEL_INTERLEAVE_PHASES == 0, "whole queries per phase");
static_assert(2 * LocalQueries == 4 * Targets, "the moments fill the targets' channels");
static_assert(Targets == 3, "the GLSL names three moments textures");
}

struct vtkMRGIVarianceShadowQuery::Internals
{
  std::array<vtkTextureObject*, Targets> Moments{};
  vtkOpenGLFramebufferObject* FrameBuffer = nullptr;
  vtkOpenGLQuadHelper* Quad = nullptr;
  vtkOpenGLRenderWindow* Window = nullptr;
  int Size[2] = { 0, 0 };
  bool Valid = false;
  bool Active = false;
};

//------------------------------------------------------------------------------
vtkMRGIVarianceShadowQuery::vtkMRGIVarianceShadowQuery()
  : Internal(new Internals)
{
  this->BlurRadius = MRGI_VOXEL_VSM_DEFAULT_RADIUS;
  this->MinVariance = MRGI_VOXEL_VSM_DEFAULT_MIN_VARIANCE;
}

vtkMRGIVarianceShadowQuery::~vtkMRGIVarianceShadowQuery()
{
  this->ReleaseGraphicsResources(nullptr);
}

//------------------------------------------------------------------------------
void vtkMRGIVarianceShadowQuery::SetBlurRadius(int radius)
{
  radius = std::min(std::max(radius, 0), static_cast<int>(MRGI_VOXEL_VSM_MAX_RADIUS));
  if (radius != this->BlurRadius)
  {
    this->BlurRadius = radius;
    this->Modified();
  }
}

void vtkMRGIVarianceShadowQuery::SetMinVariance(double variance)
{
  // Clamped to [0, float max] (a float uniform); NaN is ignored.
  if (std::isnan(variance))
  {
    return;
  }
  variance = std::min(std::max(variance, 0.0), static_cast<double>(VTK_FLOAT_MAX));
  if (variance != this->MinVariance)
  {
    this->MinVariance = variance;
    this->Modified();
  }
}

//------------------------------------------------------------------------------
const char* vtkMRGIVarianceShadowQuery::GetResolveShaderSource()
{
  return vtkMRGIVarianceShadowResolve;
}

//------------------------------------------------------------------------------
void vtkMRGIVarianceShadowQuery::ReleaseGraphicsResources(vtkWindow* w)
{
  Internals& in = *this->Internal;
  for (auto*& t : in.Moments)
  {
    vtkMRGIShaderUtilities::ReleaseTexture(t, w);
  }
  if (in.Quad)
  {
    if (w)
    {
      in.Quad->ReleaseGraphicsResources(w);
    }
    delete in.Quad;
    in.Quad = nullptr;
  }
  if (in.FrameBuffer)
  {
    if (w)
    {
      in.FrameBuffer->ReleaseGraphicsResources(w);
    }
    in.FrameBuffer->Delete();
    in.FrameBuffer = nullptr;
  }
  in.Window = nullptr;
  in.Size[0] = in.Size[1] = 0;
  in.Valid = false;
  in.Active = false;
}

//------------------------------------------------------------------------------
bool vtkMRGIVarianceShadowQuery::ComputeMoments(
  const vtkMRGIFrameContext& frame, vtkMRGIAreaLight* light, vtkMRGIVoxelization* voxels)
{
  vtkOpenGLRenderWindow* window = frame.Window;
  vtkTextureObject* position = frame.Position;
  vtkTextureObject* normal = frame.Normal;
  vtkTextureObject* specular = frame.Specular;
  vtkTextureObject* shininess = frame.Shininess;
  const int* viewport = frame.Viewport;
  const float* viewToWorld = frame.ViewToWorld;
  const bool parallel = frame.Parallel;
  Internals& in = *this->Internal;
  in.Valid = false;
  double worldToView[16];
  if (!window || !position || !normal || !specular || !shininess || !viewport || !light ||
    !voxels || !viewToWorld || viewport[2] < 1 || viewport[3] < 1 ||
    !voxels->GetLastWorldToView(worldToView))
  {
    vtkErrorMacro("ComputeMoments needs a window, the G-buffer (position, normal, specular, "
                  "shininess), a viewport, a light, a voxelization of this frame and the eye -> "
                  "world matrix");
    return false;
  }
  if (in.Window && in.Window != window)
  {
    this->ReleaseGraphicsResources(in.Window);
  }
  in.Window = window;
  vtkMRGIShaderUtilities::ScopedStage step(frame.Timer, "specular.moments");
  const int w = viewport[2], h = viewport[3];
  for (auto*& t : in.Moments)
  {
    if (!t)
    {
      t = vtkMRGIShaderUtilities::NewTexture(window, GL_RGBA32F, w, h);
      if (!t)
      {
        vtkErrorMacro("ComputeMoments: could not allocate the moments (" << w << " x " << h << ")");
        return false;
      }
    }
    else if (static_cast<int>(t->GetWidth()) != w || static_cast<int>(t->GetHeight()) != h)
    {
      vtkMRGIShaderUtilities::ResizeTexture(t, w, h);
    }
  }
  if (!in.FrameBuffer)
  {
    in.FrameBuffer = vtkOpenGLFramebufferObject::New();
    in.FrameBuffer->SetContext(window);
  }
  if (!in.Quad)
  {
    const std::string body = vtkMRGIShaderLibraries::Compose({ "vtkMRGIVarianceShadowMomentsFS" });
    in.Quad = new vtkOpenGLQuadHelper(window,
      vtkOpenGLRenderUtilities::GetFullScreenQuadVertexShader().c_str(),
      vtkMRGIShaderUtilities::FullScreenShader(body.c_str()).c_str(), "");
  }
  else
  {
    window->GetShaderCache()->ReadyShaderProgram(in.Quad->Program);
  }
  vtkShaderProgram* program =
    (in.Quad->Program && in.Quad->Program->GetCompiled()) ? in.Quad->Program : nullptr;
  if (!program)
  {
    vtkErrorMacro("ComputeMoments: could not build the variance shadow query's moments shader");
    return false;
  }
  if (!light->SetShaderUniforms(program, window))
  {
    return false;
  }
  if (!voxels->SetMarchUniforms(program))
  {
    light->DeactivateTextures();
    return false;
  }
  float w2v[16];
  std::copy(worldToView, worldToView + 16, w2v);
  program->SetUniformMatrix4x4("mrgiWCToVC", w2v);
  program->SetUniformMatrix4x4("mrgiVCToWC", const_cast<float*>(viewToWorld));
  program->SetUniformi("mrgiParallel", parallel ? 1 : 0);
  const int origin[2] = { viewport[0], viewport[1] };
  program->SetUniform2i("mrgiViewportOrigin", origin);
  vtkTextureObject* inputs[4] = { position, normal, specular, shininess };
  const char* names[4] = { "mrgiPosition", "mrgiNormal", "mrgiSpecular", "mrgiShininess" };
  for (int k = 0; k < 4; ++k)
  {
    inputs[k]->Activate();
    program->SetUniformi(names[k], inputs[k]->GetTextureUnit());
  }
  {
    vtkOpenGLState* ostate = window->GetState();
    vtkOpenGLState::ScopedglEnableDisable blend(ostate, GL_BLEND);
    vtkOpenGLState::ScopedglEnableDisable depth(ostate, GL_DEPTH_TEST);
    vtkOpenGLState::ScopedglEnableDisable scissor(ostate, GL_SCISSOR_TEST);
    vtkOpenGLState::ScopedglViewport savedViewport(ostate);
    ostate->vtkglDisable(GL_BLEND);
    ostate->vtkglDisable(GL_DEPTH_TEST);
    ostate->vtkglDisable(GL_SCISSOR_TEST);
    vtkOpenGLFramebufferObject* fbo = in.FrameBuffer;
    fbo->SaveCurrentBindingsAndBuffers();
    fbo->Bind();
    for (int k = 0; k < Targets; ++k)
    {
      fbo->AddColorAttachment(static_cast<unsigned int>(k), in.Moments[static_cast<size_t>(k)]);
    }
    vtkMRGIShaderUtilities::SelectDrawBuffers(fbo, Targets);
    ostate->vtkglViewport(0, 0, w, h);
    in.Quad->Render();
    fbo->RemoveColorAttachments(Targets);
    fbo->UnBind();
    fbo->RestorePreviousBindingsAndBuffers();
  }
  for (vtkTextureObject* t : inputs)
  {
    t->Deactivate();
  }
  voxels->GetVoxelTexture()->Deactivate();
  light->DeactivateTextures();
  in.Size[0] = w;
  in.Size[1] = h;
  in.Valid = true;
  return true;
}

//------------------------------------------------------------------------------
bool vtkMRGIVarianceShadowQuery::SetResolveUniforms(vtkShaderProgram* program)
{
  Internals& in = *this->Internal;
  if (!program || !in.Valid)
  {
    vtkErrorMacro("SetResolveUniforms: " << (program ? "no moments yet (ComputeMoments())" : "no shader program"));
    return false;
  }
  for (int k = 0; k < Targets; ++k)
  {
    vtkTextureObject* t = in.Moments[static_cast<size_t>(k)];
    t->Activate();
    program->SetUniformi(("mrgiVsmMoments" + std::to_string(k)).c_str(), t->GetTextureUnit());
  }
  in.Active = true;
  program->SetUniform2i("mrgiVsmSize", in.Size);
  program->SetUniformi("mrgiVsmRadius", this->BlurRadius);
  program->SetUniformf("mrgiVsmMinVariance", static_cast<float>(this->MinVariance));
  return true;
}

void vtkMRGIVarianceShadowQuery::DeactivateTextures()
{
  Internals& in = *this->Internal;
  if (!in.Active)
  {
    return;
  }
  for (vtkTextureObject* t : in.Moments)
  {
    if (t)
    {
      t->Deactivate();
    }
  }
  in.Active = false;
}

//------------------------------------------------------------------------------
void vtkMRGIVarianceShadowQuery::GetMomentsSize(int size[2]) const
{
  size[0] = this->Internal->Valid ? this->Internal->Size[0] : 0;
  size[1] = this->Internal->Valid ? this->Internal->Size[1] : 0;
}

vtkTextureObject* vtkMRGIVarianceShadowQuery::GetMomentsTexture(int target) const
{
  if (!this->Internal->Valid || target < 0 || target >= Targets)
  {
    return nullptr;
  }
  return this->Internal->Moments[static_cast<size_t>(target)];
}

//------------------------------------------------------------------------------
bool vtkMRGIVarianceShadowQuery::ReadMoments(
  vtkRenderWindow* window, vtkFloatArray* moments, vtkUnsignedCharArray* phaseSets)
{
  Internals& in = *this->Internal;
  vtkOpenGLRenderWindow* gl = vtkOpenGLRenderWindow::SafeDownCast(window);
  if (!in.Valid || !gl || gl != in.Window || !moments || !phaseSets)
  {
    vtkErrorMacro("ReadMoments: no moments of this window yet, or no arrays given");
    return false;
  }
  std::array<std::vector<float>, Targets> rgba;
  for (int k = 0; k < Targets; ++k)
  {
    if (!vtkMRGIShaderUtilities::ReadTextureRGBA(gl, in.Moments[static_cast<size_t>(k)], rgba[static_cast<size_t>(k)]))
    {
      vtkErrorMacro("ReadMoments: could not read the moments back");
      return false;
    }
  }
  const vtkIdType pixels = static_cast<vtkIdType>(in.Size[0]) * in.Size[1];
  moments->SetNumberOfComponents(2 * MRGI_VOXEL_VSM_QUERIES);
  moments->SetNumberOfTuples(pixels);
  moments->Fill(0.0);
  phaseSets->SetNumberOfComponents(1);
  phaseSets->SetNumberOfTuples(pixels);
  float* out = moments->GetPointer(0);
  for (vtkIdType p = 0; p < pixels; ++p)
  {
    const int x = static_cast<int>(p % in.Size[0]), y = static_cast<int>(p / in.Size[0]);
    if (!(rgba[0][static_cast<size_t>(4 * p)] >= 0.0f))
    {
      phaseSets->SetValue(p, 0);
      continue;
    }
    const int q = mrgi_voxel_interleave_phase(x, y);
    phaseSets->SetValue(p, static_cast<unsigned char>(1u << q));
    for (int k = 0; k < LocalQueries; ++k)
    {
      const int j = MRGI_VOXEL_INTERLEAVE_PHASES * k + q;
      const float* texel = rgba[static_cast<size_t>(k >> 1)].data() + 4 * p;
      out[p * 2 * MRGI_VOXEL_VSM_QUERIES + 2 * j] = texel[2 * (k & 1)];
      out[p * 2 * MRGI_VOXEL_VSM_QUERIES + 2 * j + 1] = texel[2 * (k & 1) + 1];
    }
  }
  return true;
}

//------------------------------------------------------------------------------
void vtkMRGIVarianceShadowQuery::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "BlurRadius: " << this->BlurRadius << "\n";
  os << indent << "MinVariance: " << this->MinVariance << "\n";
  os << indent << "MomentsSize: " << this->Internal->Size[0] << " x " << this->Internal->Size[1]
     << (this->Internal->Valid ? "" : " (none)") << "\n";
}
