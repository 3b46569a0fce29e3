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
#include "vtkMRGIVPLIrradiance.h"
#include "vtkMRGIAreaLightDiffuse.h"
#include "mrgi_area_light.h"
#include "vtkMRGIVisibilityPyramid.h"
#include "vtkMRGIVoxelization.h"
#include "mrgi_voxel_march.h"
#include "vtkMRGIMultiresSplatFS.h"
#include "vtkMRGIMultiresSplatVS.h"
#include "vtkMRGIMultiresReceiversFS.h"
#include "vtkMRGIMultiresUpsampleFS.h"
#include "vtkMRGIMultiresSelectFS.h"
#include "vtkMRGIIncrementalStencilFS.h"
#include "vtkMRGISpecularStencilFS.h"
#include "vtkMRGIAreaLightSpecular.h"
#include "mrgi_specular_stencil.h"
#include "vtkMRGIVisibilityBits.h"
#include "mrgi_voxel_incremental.h"
#include "vtkFloatArray.h"

#include "mrgi_multires.h"

#include <algorithm>
#include <array>
#include <map>
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
  Select = 3,
  MipmapReduceLevel0 = 4, // stage 1 reading level 0 (one normal texture)
  FlagsLevel0 = 5,        // stage 2 of level 0 (one normal texture)
  StageCount = 6
};

vtkTextureObject* MakeFloatTexture(vtkOpenGLRenderWindow* window, int w, int h)
{
  return vtkMRGIShaderUtilities::NewTexture(window, GL_RGBA32F, w, h);
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

// Writing a flattened mask as colour and stencil (the selection, the
// incremental and the specular stencils): the colour target already set on
// the bound framebuffer and `depthStencil` are cleared to 0, and every
// fragment that passes sets its stencil to 1. EndMaskWrite() restores the
// stencil state and detaches the depth-stencil texture.
void BeginMaskWrite(vtkOpenGLState* ostate, vtkTextureObject* depthStencil)
{
  glFramebufferTexture2D(
    GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_TEXTURE_2D, depthStencil->GetHandle(), 0);
  ostate->vtkglClearColor(0.0, 0.0, 0.0, 0.0);
  ostate->vtkglStencilMask(0xFF);
  glClearStencil(0);
  ostate->vtkglClear(GL_COLOR_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
  ostate->vtkglEnable(GL_STENCIL_TEST);
  ostate->vtkglStencilFunc(GL_ALWAYS, 1, 0xFF);
  ostate->vtkglStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
}

void EndMaskWrite(vtkOpenGLState* ostate)
{
  ostate->vtkglStencilFunc(GL_ALWAYS, 0, 0xFF);
  ostate->vtkglStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_TEXTURE_2D, 0, 0);
}

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

// Read every level's texture back into the flattened layout (rows bottom-up,
// `components` of each texel's RGBA kept; 0 outside the levels).
template <typename LevelTexture>
bool ReadFlattened(vtkOpenGLRenderWindow* window, const mrgi_multires_layout& layout,
  int components, LevelTexture levelTexture, std::vector<float>& flat)
{
  const size_t W = static_cast<size_t>(layout.total_width);
  flat.assign(W * static_cast<size_t>(layout.total_height) * static_cast<size_t>(components), 0.0f);
  for (int i = 0; i < layout.level_count; ++i)
  {
    std::vector<float> rgba;
    if (!vtkMRGIShaderUtilities::ReadTextureRGBA(window, levelTexture(i), rgba))
    {
      return false;
    }
    const size_t w = static_cast<size_t>(layout.level_width[i]);
    for (size_t y = 0; y < static_cast<size_t>(layout.level_height[i]); ++y)
    {
      for (size_t x = 0; x < w; ++x)
      {
        const size_t to = (y * W + static_cast<size_t>(layout.level_offset[i]) + x) *
          static_cast<size_t>(components);
        for (int c = 0; c < components; ++c)
        {
          flat[to + static_cast<size_t>(c)] = rgba[(y * w + x) * 4 + static_cast<size_t>(c)];
        }
      }
    }
  }
  return true;
}
}

namespace
{
// One byte per texel of a flattened mask: the red channel of `colour`
// (> 0.5 -> 1) or, with fromStencil, the stencil of `stencil` as it is.
bool ReadMask(vtkOpenGLRenderWindow* window, vtkOpenGLFramebufferObject* fbo,
  const mrgi_multires_layout& layout, vtkTextureObject* colour, vtkTextureObject* stencil,
  bool fromStencil, vtkUnsignedCharArray* mask)
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
}

struct vtkMRGIMultiresolution::Internals
{
  mrgi_multires_layout Layout{};
  bool HasLayout = false;
  // Per level: mipmap (MRGI_MULTIRES_TEX_*) and flags.
  std::vector<std::array<vtkTextureObject*, MRGI_MULTIRES_TEX_COUNT + 1>> Levels;
  // Receivers: per level (position, normal); level 0 is the G-buffer itself
  // and its textures are filled only when read back. The gather's output is
  // flattened.
  std::vector<std::array<vtkTextureObject*, 2>> Receivers;
  vtkTextureObject* FlatIrradiance = nullptr;
  vtkOpenGLQuadHelper* ReceiverQuads[3] = { nullptr, nullptr, nullptr };
  // The G-buffer of the last Gather(), for ReadReceivers() (not owned).
  vtkTextureObject* LastPosition = nullptr;
  vtkTextureObject* LastNormal = nullptr;
  int LastOffset[2] = { 0, 0 };
  // Statistics of the last Gather() (occlusion queries, one per level).
  std::vector<unsigned int> Queries;
  std::vector<long long> GatheredTexels;
  long long ValidPixels = -1;
  vtkOpenGLQuadHelper* GatherQuad = nullptr;
  // The area-light gather (same pass, MRGI_GATHER_AREA_LIGHT), and the light
  // of the GatherAreaLight() call in progress (not owned; null otherwise).
  vtkOpenGLQuadHelper* AreaGatherQuad = nullptr;
  vtkOpenGLQuadHelper* AreaVisibleGatherQuad = nullptr; // with the voxel march
  vtkOpenGLQuadHelper* AreaMaskedGatherQuad = nullptr;  // with visibility masks
  vtkMRGIVisibilityPyramid* AreaMasks = nullptr;
  const mrgi_area_light_uniforms* AreaLight = nullptr;
  vtkMRGIVoxelization* AreaVoxels = nullptr;
  // Receivers built for the current selection (Update() clears it).
  bool ReceiversValid = false;
  // Multiresolution splatting: the subsplat list (the selected texels,
  // sorted by level; host copy kept so that its capacity is reused from
  // frame to frame) in a vertex buffer with its vertex array.
  std::vector<int> SplatTexels;
  std::vector<long long> SplatFirst;
  std::vector<long long> SplatCount;
  unsigned int SplatArray = 0;
  unsigned int SplatBuffer = 0;
  // Upsampling: per level (state/value, filtered).
  std::vector<std::array<vtkTextureObject*, 2>> Upsampled;
  vtkOpenGLQuadHelper* UpsampleQuads[3] = { nullptr, nullptr, nullptr };
  vtkTextureObject* FlatSelection = nullptr;
  vtkTextureObject* DepthStencil = nullptr;
  // Incremental stencil (NPW10 3.4): the texels the area-light gather
  // renders, as colour and stencil; programs per mask word count; whether
  // the last gather used it (then Upsample() reads it instead of the
  // selection).
  vtkTextureObject* FlatIncremental = nullptr;
  vtkTextureObject* IncrementalDepthStencil = nullptr;
  std::map<int, vtkOpenGLQuadHelper*> IncrementalQuads;
  bool LastGatherIncremental = false;
  // The specular stencil (NPW10 3.2.1, mrgi_specular_stencil.h): material
  // pyramid per level, refinement bits and selection (flattened), its
  // stencil, programs per stage; whether the last gather was the specular
  // one (then Upsample() reads the specular selection). Pixel size
  // coefficients of the last Update().
  std::vector<vtkTextureObject*> SpecularMaterial;
  vtkTextureObject* FlatSpecularBits = nullptr;
  vtkTextureObject* FlatSpecularSelection = nullptr;
  vtkTextureObject* SpecularDepthStencil = nullptr;
  vtkOpenGLQuadHelper* SpecularQuads[4] = { nullptr, nullptr, nullptr, nullptr };
  bool SpecularStencilValid = false;
  bool LastGatherSpecular = false;
  double PixelSize[2] = { 0.0, 0.0 };
  vtkOpenGLFramebufferObject* FrameBuffer = nullptr;
  vtkOpenGLQuadHelper* Quads[StageCount] = { nullptr, nullptr, nullptr, nullptr, nullptr, nullptr };

  void ReleaseTextures(vtkWindow* w)
  {
    for (auto& level : this->Levels)
    {
      for (auto*& t : level)
      {
        vtkMRGIShaderUtilities::ReleaseTexture(t, w);
      }
    }
    this->Levels.clear();
    for (auto& level : this->Receivers)
    {
      for (auto*& t : level)
      {
        vtkMRGIShaderUtilities::ReleaseTexture(t, w);
      }
    }
    this->Receivers.clear();
    for (auto& level : this->Upsampled)
    {
      for (auto*& t : level)
      {
        vtkMRGIShaderUtilities::ReleaseTexture(t, w);
      }
    }
    this->Upsampled.clear();
    vtkMRGIShaderUtilities::ReleaseTexture(this->FlatIrradiance, w);
    vtkMRGIShaderUtilities::ReleaseTexture(this->FlatSelection, w);
    vtkMRGIShaderUtilities::ReleaseTexture(this->DepthStencil, w);
    vtkMRGIShaderUtilities::ReleaseTexture(this->FlatIncremental, w);
    vtkMRGIShaderUtilities::ReleaseTexture(this->IncrementalDepthStencil, w);
    this->LastGatherIncremental = false;
    for (auto*& t : this->SpecularMaterial)
    {
      vtkMRGIShaderUtilities::ReleaseTexture(t, w);
    }
    this->SpecularMaterial.clear();
    vtkMRGIShaderUtilities::ReleaseTexture(this->FlatSpecularBits, w);
    vtkMRGIShaderUtilities::ReleaseTexture(this->FlatSpecularSelection, w);
    vtkMRGIShaderUtilities::ReleaseTexture(this->SpecularDepthStencil, w);
    this->SpecularStencilValid = false;
    this->LastGatherSpecular = false;
    this->HasLayout = false;
    this->LastPosition = this->LastNormal = nullptr;
    this->ReceiversValid = false;
    this->GatheredTexels.clear();
    this->ValidPixels = -1;
  }

  // Occlusion queries need the context: only with a window.
  void ReleaseQueries(vtkWindow* w)
  {
    if (w && !this->Queries.empty())
    {
      glDeleteQueries(static_cast<GLsizei>(this->Queries.size()), this->Queries.data());
    }
    this->Queries.clear();
  }

  // Bind level i's receivers (level 0: the G-buffer at (x0, y0)) as
  // mrgiPosition / mrgiNormal with the gather's texel offset; the caller
  // deactivates the two textures returned.
  std::array<vtkTextureObject*, 2> BindReceivers(vtkShaderProgram* program, int i,
    vtkTextureObject* position, vtkTextureObject* normal, int x0, int y0)
  {
    vtkTextureObject* p = i == 0 ? position : this->Receivers[static_cast<size_t>(i)][0];
    vtkTextureObject* n = i == 0 ? normal : this->Receivers[static_cast<size_t>(i)][1];
    const int offset[2] = { i == 0 ? x0 : -this->Layout.level_offset[i], i == 0 ? y0 : 0 };
    p->Activate();
    n->Activate();
    program->SetUniformi("mrgiPosition", p->GetTextureUnit());
    program->SetUniformi("mrgiNormal", n->GetTextureUnit());
    program->SetUniform2i("mrgiReceiverOffset", offset);
    return { p, n };
  }

  // Vertex array and buffer need the context: only with a window.
  void ReleaseSplats(vtkWindow* w)
  {
    if (w && this->SplatArray)
    {
      glDeleteVertexArrays(1, &this->SplatArray);
    }
    if (w && this->SplatBuffer)
    {
      glDeleteBuffers(1, &this->SplatBuffer);
    }
    this->SplatArray = this->SplatBuffer = 0;
  }
};

//------------------------------------------------------------------------------
vtkMRGIMultiresolution::vtkMRGIMultiresolution()
  : Internal(new Internals)
{
  this->SetPreset(PresetBalanced);
}

//------------------------------------------------------------------------------
bool vtkMRGIMultiresolution::GetPresetSettings(int preset, double settings[3])
{
  mrgi_multires_params params;
  if (!settings || mrgi_multires_preset_params(preset, &params, nullptr) != MRGI_OK)
  {
    return false;
  }
  settings[0] = std::isinf(params.depth_threshold) ? -1.0 : params.depth_threshold;
  settings[1] = std::isinf(params.normal_threshold) ? -1.0 : params.normal_threshold;
  settings[2] = params.finest_level;
  return true;
}

//------------------------------------------------------------------------------
const char* vtkMRGIMultiresolution::GetPresetName(int preset)
{
  return mrgi_multires_preset_name(preset);
}

//------------------------------------------------------------------------------
bool vtkMRGIMultiresolution::SetPreset(int preset)
{
  double settings[3];
  if (!GetPresetSettings(preset, settings))
  {
    vtkErrorMacro("unknown multiresolution preset " << preset << " (0 fast, 1 balanced, 2 accurate)");
    return false;
  }
  this->SetDepthThreshold(settings[0]);
  this->SetNormalThreshold(settings[1]);
  this->SetFinestLevel(static_cast<int>(settings[2]));
  this->SetBalance(true);
  return true;
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
  delete this->Internal->AreaGatherQuad;
  delete this->Internal->AreaVisibleGatherQuad;
  delete this->Internal->AreaMaskedGatherQuad;
  for (auto& q : this->Internal->IncrementalQuads)
  {
    delete q.second;
  }
}

//------------------------------------------------------------------------------
void vtkMRGIMultiresolution::ReleaseGraphicsResources(vtkWindow* w)
{
  this->Internal->ReleaseQueries(w);
  this->Internal->ReleaseSplats(w);
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
  releaseQuad(this->Internal->AreaGatherQuad);
  releaseQuad(this->Internal->AreaVisibleGatherQuad);
  releaseQuad(this->Internal->AreaMaskedGatherQuad);
  for (auto*& q : this->Internal->SpecularQuads)
  {
    releaseQuad(q);
  }
  for (auto& q : this->Internal->IncrementalQuads)
  {
    releaseQuad(q.second);
  }
  this->Internal->IncrementalQuads.clear();
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
bool vtkMRGIMultiresolution::GetLevelSize(int level, int size[2]) const
{
  const Internals& in = *this->Internal;
  if (!in.HasLayout || level < 0 || level >= in.Layout.level_count)
  {
    return false;
  }
  size[0] = in.Layout.level_width[level];
  size[1] = in.Layout.level_height[level];
  return true;
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
  this->Internal->ReceiversValid = false; // a new selection: its receivers come with the next gather
  this->Internal->LastGatherIncremental = false;
  this->Internal->LastGatherSpecular = false;
  this->Internal->SpecularStencilValid = false;
  this->Internal->PixelSize[0] = a;
  this->Internal->PixelSize[1] = b;
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
    in.Receivers.resize(static_cast<size_t>(levels));
    for (int i = 0; i < levels; ++i)
    {
      for (auto*& t : in.Receivers[i])
      {
        t = MakeFloatTexture(window, layout.level_width[i], layout.level_height[i]);
      }
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
    in.DepthStencil = vtkMRGIShaderUtilities::NewDepthStencil(window, layout.total_width, layout.total_height);
    in.FlatIncremental = MakeFloatTexture(window, layout.total_width, layout.total_height);
    in.IncrementalDepthStencil =
      vtkMRGIShaderUtilities::NewDepthStencil(window, layout.total_width, layout.total_height);
    bool allocated = in.FlatIrradiance && in.FlatSelection && in.DepthStencil && in.FlatIncremental &&
      in.IncrementalDepthStencil;
    for (int i = 0; i < levels; ++i)
    {
      for (auto* list : { in.Levels[i].data(), in.Receivers[i].data(), in.Upsampled[i].data() })
      {
        allocated = allocated && list[0] && list[1];
      }
      allocated = allocated && in.Levels[i][2] && in.Levels[i][3];
    }
    if (!allocated)
    {
      in.ReleaseTextures(window);
      vtkErrorMacro("could not allocate the multiresolution buffers (" << layout.total_width << " x "
                                                                       << layout.total_height << ")");
      return false;
    }
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
      const int stage = s == MipmapReduceLevel0 ? MipmapReduce : s == FlagsLevel0 ? Flags : s;
      const std::string body = "#define MRGI_MR_STAGE " + std::to_string(stage) + "\n" +
        (s >= MipmapReduceLevel0 ? "#define MRGI_MR_LEVEL0 1\n" : "") + vtkMRGIMultiresSelectFS;
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

  using vtkMRGIShaderUtilities::ScopedStage;
  // 1. Level 0 of the mipmaps, from the G-buffer.
  {
    ScopedStage step(this->StageTimer, "select.mipmap0");
    auto& level = in.Levels[0];
    // One normal texture at level 0 (min = max; NORMAL_MAX stays unused).
    target({ level[MRGI_MULTIRES_TEX_DEPTH], level[MRGI_MULTIRES_TEX_NORMAL_MIN] }, width, height);
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
    ScopedStage step(this->StageTimer, "select.mipmaps");
    auto& fine = in.Levels[i - 1];
    auto& level = in.Levels[i];
    target({ level[MRGI_MULTIRES_TEX_DEPTH], level[MRGI_MULTIRES_TEX_NORMAL_MIN],
             level[MRGI_MULTIRES_TEX_NORMAL_MAX] },
      layout.level_width[i], layout.level_height[i]);
    const int stage = i == 1 ? MipmapReduceLevel0 : MipmapReduce;
    vtkShaderProgram* p = programs[stage];
    vtkTextureObject* normalMax = fine[i == 1 ? MRGI_MULTIRES_TEX_NORMAL_MIN : MRGI_MULTIRES_TEX_NORMAL_MAX];
    bind(p, { fine[MRGI_MULTIRES_TEX_DEPTH], fine[MRGI_MULTIRES_TEX_NORMAL_MIN] });
    if (i != 1)
    {
      normalMax->Activate();
      p->SetUniformi("mrgiInput2", normalMax->GetTextureUnit());
    }
    const int size[2] = { layout.level_width[i - 1], layout.level_height[i - 1] };
    p->SetUniform2i("mrgiSize", size);
    in.Quads[stage]->Render();
    unbind({ fine[MRGI_MULTIRES_TEX_DEPTH], fine[MRGI_MULTIRES_TEX_NORMAL_MIN] });
    if (i != 1)
    {
      normalMax->Deactivate();
    }
  }
  // 3. Flags, fine to coarse (refinement and balance read the finer level).
  const float depthThreshold = mrgi_multires_threshold_uniform(
    this->DepthThreshold < 0 ? INFINITY : this->DepthThreshold);
  const float normalThreshold = mrgi_multires_threshold_uniform(
    this->NormalThreshold < 0 ? INFINITY : this->NormalThreshold);
  for (int i = 0; i < levels; ++i)
  {
    ScopedStage step(this->StageTimer, i == 0 ? "select.flags0" : "select.flags");
    auto& level = in.Levels[i];
    const int flagsSlot = MRGI_MULTIRES_TEX_COUNT;
    target({ level[flagsSlot] }, layout.level_width[i], layout.level_height[i]);
    const int stage = i == 0 ? FlagsLevel0 : Flags;
    vtkShaderProgram* p = programs[stage];
    // Level 0 has no finer level: its own (not yet written) flags stand in,
    // unread since level 0 <= the finest level.
    vtkTextureObject* finer = in.Levels[i > 0 ? i - 1 : 0][flagsSlot];
    if (i == 0)
    {
      finer = in.Levels[std::min(1, levels - 1)][MRGI_MULTIRES_TEX_DEPTH];
    }
    // Level 0: one normal texture (FlagsLevel0 reads mrgiInput1 only; the
    // NORMAL_MAX slot stands in for the unread mrgiInput2).
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
    in.Quads[stage]->Render();
    unbind({ level[MRGI_MULTIRES_TEX_DEPTH], level[MRGI_MULTIRES_TEX_NORMAL_MIN],
      level[MRGI_MULTIRES_TEX_NORMAL_MAX], finer });
  }
  // 4. Selection (nichols-shopf-wyman-2009 3.2.1): one draw per level from
  // the finest that gathers, into that level's rectangle of the flattened
  // layout; the texels that survive set the stencil.
  ScopedStage stencilStep(this->StageTimer, "select.stencil");
  target({ in.FlatSelection }, layout.total_width, layout.total_height);
  BeginMaskWrite(ostate, in.DepthStencil);
  for (int i = finest; i < levels; ++i)
  {
    vtkShaderProgram* p = programs[Select];
    vtkTextureObject* flags = in.Levels[i][MRGI_MULTIRES_TEX_COUNT];
    // The coarsest level has no parent: its own flags stand in, unread.
    vtkTextureObject* parent = in.Levels[std::min(i + 1, levels - 1)][MRGI_MULTIRES_TEX_COUNT];
    ostate->vtkglViewport(layout.level_offset[i], 0, layout.level_width[i], layout.level_height[i]);
    bind(p, { flags, parent });
    const int offset[2] = { layout.level_offset[i], 0 };
    p->SetUniform2i("mrgiOffset", offset);
    p->SetUniformi("mrgiLevel", i);
    p->SetUniformi("mrgiFinestLevel", finest);
    p->SetUniformi("mrgiCoarsest", i == levels - 1 ? 1 : 0);
    in.Quads[Select]->Render();
    unbind({ flags, parent });
  }
  EndMaskWrite(ostate);
  const GLenum error = glGetError();
  if (error != GL_NO_ERROR)
  {
    vtkErrorMacro("OpenGL error 0x" << std::hex << error << " in the multiresolution selection");
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkMRGIMultiresolution::BuildReceivers(
  vtkOpenGLRenderWindow* window, vtkTextureObject* position, vtkTextureObject* normal, int x0, int y0)
{
  Internals& in = *this->Internal;
  if (!window || !position || !normal || !in.HasLayout)
  {
    vtkErrorMacro("BuildReceivers needs Update() first and the G-buffer");
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
  bool ok = true;
  using vtkMRGIShaderUtilities::ScopedStage;
  in.LastPosition = position;
  in.LastNormal = normal;
  in.LastOffset[0] = x0;
  in.LastOffset[1] = y0;
  // 1. Receivers, level by level from level 1 (level 1 straight from the
  // G-buffer; the gather reads level 0 from the G-buffer itself).
  {
    ScopedStage receiverStep(this->StageTimer, "gather.receivers");
    QuadSteps steps(window, in.FrameBuffer);
    auto target = [&](vtkTextureObject* a, vtkTextureObject* b, int w, int h) {
      steps.Target(a, b, 0, 0, w, h);
    };
    auto inputs = [&](vtkShaderProgram* p, vtkTextureObject* a, vtkTextureObject* b) {
      a->Activate();
      b->Activate();
      p->SetUniformi("mrgiInput0", a->GetTextureUnit());
      p->SetUniformi("mrgiInput1", b->GetTextureUnit());
    };
    for (int i = 1; i < levels && ok; ++i)
    {
      const int stage = i == 1 ? 2 : 1;
      vtkShaderProgram* p = ready(in.ReceiverQuads[stage],
        "#define MRGI_MR_STAGE " + std::to_string(stage) + "\n" + vtkMRGIMultiresReceiversFS);
      if (!p)
      {
        ok = false;
        break;
      }
      target(in.Receivers[i][0], in.Receivers[i][1], layout.level_width[i], layout.level_height[i]);
      vtkTextureObject* srcP = i == 1 ? position : in.Receivers[i - 1][0];
      vtkTextureObject* srcN = i == 1 ? normal : in.Receivers[i - 1][1];
      inputs(p, srcP, srcN);
      const int offset[2] = { x0, y0 };
      const int size[2] = { layout.level_width[i - 1], layout.level_height[i - 1] };
      p->SetUniform2i("mrgiOffset", offset);
      p->SetUniform2i("mrgiSize", size);
      in.ReceiverQuads[stage]->Render();
      srcP->Deactivate();
      srcN->Deactivate();
    }
  }
  in.ReceiversValid = ok;
  return ok;
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
  bool ok = in.ReceiversValid && in.LastPosition == position && in.LastNormal == normal &&
      in.LastOffset[0] == x0 && in.LastOffset[1] == y0
    ? true
    : this->BuildReceivers(window, position, normal, x0, y0);
  in.GatheredTexels.assign(static_cast<size_t>(levels), -1);
  in.ValidPixels = -1;
  if (ok && this->GatherMode == GatherSplatting && !in.AreaLight)
  {
    ok = this->RunSplatting(window, position, normal, x0, y0, vpls, vplCount, viewToWorld);
  }
  else if (ok)
  {
    ok = this->RunStenciledGather(window, position, normal, x0, y0, vpls, vplCount, viewToWorld);
  }
  if (ok && this->CollectStatistics)
  {
    // The coarsest receivers carry their pixel counts: their sum is the
    // number of valid pixels, the work of the full-resolution gather.
    // With one level, the validity bits of the level-0 mipmap count them.
    std::vector<float> coarsest;
    if (levels > 1 && vtkMRGIShaderUtilities::ReadTextureRGBA(window, in.Receivers[levels - 1][0], coarsest))
    {
      double sum = 0.0;
      for (size_t k = 3; k < coarsest.size(); k += 4)
      {
        sum += coarsest[k];
      }
      in.ValidPixels = static_cast<long long>(sum + 0.5);
    }
    else if (levels == 1 &&
      vtkMRGIShaderUtilities::ReadTextureRGBA(window, in.Levels[0][MRGI_MULTIRES_TEX_DEPTH], coarsest))
    {
      in.ValidPixels = 0;
      for (size_t k = 3; k < coarsest.size(); k += 4)
      {
        in.ValidPixels += (static_cast<int>(coarsest[k]) & MRGI_MULTIRES_VALID_BIT) ? 1 : 0;
      }
    }
  }
  if (!ok)
  {
    vtkErrorMacro("could not build or run the multiresolution gather");
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
bool vtkMRGIMultiresolution::GatherAreaLight(vtkOpenGLRenderWindow* window,
  vtkTextureObject* position, vtkTextureObject* normal, int x0, int y0, vtkTextureObject* samples,
  int sampleCount, const mrgi_area_light_uniforms& light, const float viewToWorld[16],
  vtkMRGIVoxelization* visibility, vtkMRGIVisibilityPyramid* masks)
{
  // The same receivers, selection and stenciled gather as the VPLs', with
  // the area-light term (nichols-penmatsa-wyman-2010 3.2: "we use the same
  // multiresolution framework").
  struct Clear
  {
    Internals& In;
    ~Clear()
    {
      this->In.AreaLight = nullptr;
      this->In.AreaVoxels = nullptr;
      this->In.AreaMasks = nullptr;
    }
  } clear{ *this->Internal };
  this->Internal->AreaLight = &light;
  this->Internal->AreaVoxels = masks ? nullptr : visibility;
  this->Internal->AreaMasks = masks;
  return this->Gather(window, position, normal, x0, y0, samples, sampleCount, viewToWorld);
}

//------------------------------------------------------------------------------
bool vtkMRGIMultiresolution::RunStenciledGather(vtkOpenGLRenderWindow* window,
  vtkTextureObject* position, vtkTextureObject* normal, int x0, int y0, vtkTextureObject* vpls,
  int vplCount, const float viewToWorld[16])
{
  // The stenciled gather, one draw per level into its rectangle of the
  // flattened layout (early stencil culling skips the texels not selected).
  // With statistics on, an occlusion query per level counts the texels that
  // passed the stencil, i.e. the texels gathered.
  Internals& in = *this->Internal;
  const mrgi_multires_layout& layout = in.Layout;
  const int levels = layout.level_count;
  const int finest = std::min(this->FinestLevel, levels - 1);
  using vtkMRGIShaderUtilities::ScopedStage;
  const bool area = in.AreaLight != nullptr;
  const bool visibility = area && in.AreaVoxels != nullptr;
  const bool masked = area && in.AreaMasks != nullptr;
  // NPW10 3.4: with visibility masks the stencil also follows the light's
  // discontinuities (built before the gather's own GL state is set).
  const bool incremental = masked && this->IncrementalStencil;
  in.LastGatherIncremental = false;
  in.LastGatherSpecular = false;
  if (incremental && !this->BuildIncrementalStencil(window, in.AreaMasks))
  {
    return false;
  }
  in.LastGatherIncremental = incremental;
  vtkTextureObject* stencil = incremental ? in.IncrementalDepthStencil : in.DepthStencil;
  ScopedStage gatherStep(this->StageTimer, area ? "gather.samples" : "gather.vpls");
  vtkOpenGLQuadHelper*& quad = visibility ? in.AreaVisibleGatherQuad
    : masked                              ? in.AreaMaskedGatherQuad
    : area                                ? in.AreaGatherQuad
                                          : in.GatherQuad;
  if (!quad)
  {
    const std::string body = std::string("#define MRGI_GATHER_IRRADIANCE_ONLY 1\n") +
      (masked ? std::string("#define MRGI_AREA_VISIBILITY_MASKS 1\n") : std::string()) +
      (visibility ? std::string("#define MRGI_AREA_VISIBILITY 1\n") + vtkMRGIVoxelization::GetMarchShaderSource()
                  : std::string()) +
      (area ? std::string("#define MRGI_GATHER_AREA_LIGHT 1\n") + vtkMRGIAreaLightDiffuse : std::string()) +
      vtkMRGIVPLIrradiance + vtkMRGIGatherFS;
    quad = new vtkOpenGLQuadHelper(window,
      vtkOpenGLRenderUtilities::GetFullScreenQuadVertexShader().c_str(),
      vtkMRGIShaderUtilities::FullScreenShader(body.c_str()).c_str(), "");
  }
  window->GetShaderCache()->ReadyShaderProgram(quad->Program);
  vtkShaderProgram* gather = (quad->Program && quad->Program->GetCompiled()) ? quad->Program : nullptr;
  if (!gather)
  {
    return false;
  }
  if (this->CollectStatistics && in.Queries.size() != static_cast<size_t>(levels))
  {
    in.ReleaseQueries(window);
    in.Queries.resize(static_cast<size_t>(levels));
    glGenQueries(levels, in.Queries.data());
  }
  QuadSteps steps(window, in.FrameBuffer);
  vtkOpenGLState* ostate = steps.State;
  steps.Target(in.FlatIrradiance, nullptr, 0, 0, layout.total_width, layout.total_height);
  glFramebufferTexture2D(
    GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_TEXTURE_2D, stencil->GetHandle(), 0);
  ostate->vtkglClearColor(0.0, 0.0, 0.0, 0.0);
  ostate->vtkglClear(GL_COLOR_BUFFER_BIT);
  ostate->vtkglEnable(GL_STENCIL_TEST);
  ostate->vtkglStencilMask(0x00);
  ostate->vtkglStencilFunc(GL_EQUAL, 1, 0xFF);
  ostate->vtkglStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
  vpls->Activate();
  if (area)
  {
    const mrgi_area_light_uniforms& light = *in.AreaLight;
    gather->SetUniformi("mrgiAreaSamples", vpls->GetTextureUnit());
    // mrgiAreaSampleFirst/Count: set per draw below.
    gather->SetUniform3f("mrgiAreaCenter", light.center);
    gather->SetUniform3f("mrgiAreaNormal", light.normal);
    gather->SetUniform3fv("mrgiAreaCorners", 4, light.corners);
    gather->SetUniformi("mrgiAreaTwoSided", light.two_sided);
    if (visibility)
    {
      double worldToView[16];
      if (!in.AreaVoxels->GetLastWorldToView(worldToView) || !in.AreaVoxels->SetMarchUniforms(gather))
      {
        vpls->Deactivate();
        return false;
      }
      float m[16];
      std::copy(worldToView, worldToView + 16, m);
      gather->SetUniformMatrix4x4("mrgiWCToVC", m);
    }
  }
  else
  {
    gather->SetUniformi("mrgiVPLs", vpls->GetTextureUnit());
    gather->SetUniformi("mrgiVPLCount", vplCount);
  }
  gather->SetUniformMatrix4x4("mrgiVCToWC", const_cast<float*>(viewToWorld));
  // Marching every sample in one fragment can run past the total loop
  // iterations a fragment may take on llvmpipe (gallivm stops every loop of
  // an invocation after 65535 iterations in all, silently: samples went
  // missing, measured), and long draws trip GPU watchdogs elsewhere: with
  // visibility, the samples are gathered in batches whose marches fit the
  // budget, each batch one draw added to the previous ones (RGB summed,
  // alpha kept at 1). The sums change order only by batch.
  const int batch = visibility
    ? mrgi_voxel_samples_per_batch(in.AreaVoxels->GetMaxSteps())
    : std::max(vplCount, 1);
  vtkOpenGLState::ScopedglBlendFuncSeparate blendFunc(ostate);
  if (area)
  {
    gather->SetUniformi("mrgiAreaSampleFirst", 0);
    gather->SetUniformi("mrgiAreaSampleCount", std::min(batch, vplCount));
  }
  if (vplCount > batch)
  {
    ostate->vtkglEnable(GL_BLEND);
    ostate->vtkglBlendFuncSeparate(GL_ONE, GL_ONE, GL_ONE, GL_ONE);
    ostate->vtkglBlendEquationSeparate(GL_FUNC_ADD, GL_MAX);
  }
  for (int i = finest; i < levels; ++i)
  {
    const std::array<vtkTextureObject*, 2> receivers = in.BindReceivers(gather, i, position, normal, x0, y0);
    std::vector<vtkTextureObject*> maskTextures;
    if (masked)
    {
      // Missing words (fewer than 384 samples) read the first texture:
      // their bits are never asked for. One texture activated once.
      vtkTextureObject* first = in.AreaMasks->GetMaskTexture(i, 0);
      first->Activate();
      maskTextures.push_back(first);
      for (int w = 0; w < 4; ++w)
      {
        vtkTextureObject* t = in.AreaMasks->GetMaskTexture(i, w);
        if (t && t != first)
        {
          t->Activate();
          maskTextures.push_back(t);
        }
        gather->SetUniformi(("mrgiVisibilityMask" + std::to_string(w)).c_str(),
          (t ? t : first)->GetTextureUnit());
      }
      const int maskOffset[2] = { -layout.level_offset[i], 0 };
      gather->SetUniform2i("mrgiMaskOffset", maskOffset);
    }
    ostate->vtkglViewport(layout.level_offset[i], 0, layout.level_width[i], layout.level_height[i]);
    if (this->CollectStatistics)
    {
      glBeginQuery(GL_SAMPLES_PASSED, in.Queries[static_cast<size_t>(i)]);
    }
    quad->Render();
    if (this->CollectStatistics)
    {
      glEndQuery(GL_SAMPLES_PASSED);
    }
    for (int first = batch; first < vplCount; first += batch)
    {
      gather->SetUniformi("mrgiAreaSampleFirst", first);
      gather->SetUniformi("mrgiAreaSampleCount", std::min(batch, vplCount - first));
      quad->Render();
    }
    if (area && vplCount > batch)
    {
      gather->SetUniformi("mrgiAreaSampleFirst", 0);
      gather->SetUniformi("mrgiAreaSampleCount", batch);
    }
    for (vtkTextureObject* t : maskTextures)
    {
      t->Deactivate();
    }
    receivers[1]->Deactivate();
    receivers[0]->Deactivate();
  }
  vpls->Deactivate();
  if (vplCount > batch)
  {
    ostate->vtkglBlendEquationSeparate(GL_FUNC_ADD, GL_FUNC_ADD);
  }
  if (visibility)
  {
    in.AreaVoxels->GetVoxelTexture()->Deactivate();
  }
  ostate->vtkglStencilMask(0xFF);
  ostate->vtkglStencilFunc(GL_ALWAYS, 0, 0xFF);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_TEXTURE_2D, 0, 0);
  if (this->CollectStatistics)
  {
    // Blocking reads, which is why statistics are opt-in.
    for (int i = 0; i < levels; ++i)
    {
      GLuint passed = 0;
      if (i >= finest)
      {
        glGetQueryObjectuiv(in.Queries[static_cast<size_t>(i)], GL_QUERY_RESULT, &passed);
      }
      in.GatheredTexels[static_cast<size_t>(i)] = static_cast<long long>(passed);
    }
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkMRGIMultiresolution::RunSplatting(vtkOpenGLRenderWindow* window,
  vtkTextureObject* position, vtkTextureObject* normal, int x0, int y0, vtkTextureObject* vpls,
  int vplCount, const float viewToWorld[16])
{
  // Multiresolution splatting (nichols-wyman-2009 section 3.4), the method
  // the stenciled gather replaced (nichols-shopf-wyman-2009 section 3.2.2,
  // table 1): every VPL draws one point per selected texel ("subsplat"),
  // additive blending sums them.
  Internals& in = *this->Internal;
  in.LastGatherIncremental = false;
  in.LastGatherSpecular = false;
  const mrgi_multires_layout& layout = in.Layout;
  const int levels = layout.level_count;
  const int finest = std::min(this->FinestLevel, levels - 1);
  using vtkMRGIShaderUtilities::ScopedStage;
  // 1. The subsplat list: the selected texels, level by level. The paper
  // streams it out on the GPU; here the selection is read back, which is
  // its own timed step ("gather.subsplats") so that the splatting itself
  // ("gather.vpls") compares with the stenciled gather's step of that name.
  {
    ScopedStage listStep(this->StageTimer, "gather.subsplats");
    std::vector<float> selection;
    if (!vtkMRGIShaderUtilities::ReadTextureRGBA(window, in.FlatSelection, selection))
    {
      return false;
    }
    const size_t width = static_cast<size_t>(layout.total_width);
    in.SplatTexels.clear();
    in.SplatFirst.assign(static_cast<size_t>(levels), 0);
    in.SplatCount.assign(static_cast<size_t>(levels), 0);
    for (int i = finest; i < levels; ++i)
    {
      in.SplatFirst[static_cast<size_t>(i)] = static_cast<long long>(in.SplatTexels.size() / 2);
      for (int y = 0; y < layout.level_height[i]; ++y)
      {
        for (int x = layout.level_offset[i]; x < layout.level_offset[i] + layout.level_width[i]; ++x)
        {
          if (selection[4 * (static_cast<size_t>(y) * width + static_cast<size_t>(x))] > 0.5f)
          {
            in.SplatTexels.push_back(x);
            in.SplatTexels.push_back(y);
          }
        }
      }
      in.SplatCount[static_cast<size_t>(i)] =
        static_cast<long long>(in.SplatTexels.size() / 2) - in.SplatFirst[static_cast<size_t>(i)];
    }
    if (!in.SplatArray)
    {
      glGenVertexArrays(1, &in.SplatArray);
      glGenBuffers(1, &in.SplatBuffer);
    }
    glBindBuffer(GL_ARRAY_BUFFER, in.SplatBuffer);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(in.SplatTexels.size() * sizeof(int)),
      in.SplatTexels.empty() ? nullptr : in.SplatTexels.data(), GL_STREAM_DRAW);
  }
  // 2. The splats.
  ScopedStage splatStep(this->StageTimer, "gather.vpls");
  static const std::string vertexShader =
    "//VTK::System::Dec\n" + vtkMRGIShaderUtilities::Defines() + vtkMRGIVPLIrradiance + vtkMRGIMultiresSplatVS;
  vtkShaderProgram* splat =
    window->GetShaderCache()->ReadyShaderProgram(vertexShader.c_str(), vtkMRGIMultiresSplatFS, "");
  if (!splat || !splat->GetCompiled())
  {
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    return false;
  }
  const GLint texelAttribute = glGetAttribLocation(splat->GetHandle(), "mrgiTexel");
  if (texelAttribute < 0)
  {
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    return false;
  }
  glBindVertexArray(in.SplatArray);
  glEnableVertexAttribArray(static_cast<GLuint>(texelAttribute));
  glVertexAttribIPointer(static_cast<GLuint>(texelAttribute), 2, GL_INT, 0, nullptr);
  QuadSteps steps(window, in.FrameBuffer);
  vtkOpenGLState* ostate = steps.State;
  steps.Target(in.FlatIrradiance, nullptr, 0, 0, layout.total_width, layout.total_height);
  ostate->vtkglClearColor(0.0, 0.0, 0.0, 0.0);
  ostate->vtkglClear(GL_COLOR_BUFFER_BIT);
  vtkOpenGLState::ScopedglBlendFuncSeparate blendFunc(ostate);
  ostate->vtkglEnable(GL_BLEND);
  ostate->vtkglBlendFuncSeparate(GL_ONE, GL_ONE, GL_ONE, GL_ONE);
  // RGB sums the VPLs; alpha stays 1 where a texel got subsplats.
  ostate->vtkglBlendEquationSeparate(GL_FUNC_ADD, GL_MAX);
  vpls->Activate();
  splat->SetUniformi("mrgiVPLs", vpls->GetTextureUnit());
  splat->SetUniformMatrix4x4("mrgiVCToWC", const_cast<float*>(viewToWorld));
  const float targetSize[2] = { static_cast<float>(layout.total_width),
    static_cast<float>(layout.total_height) };
  splat->SetUniform2f("mrgiTargetSize", targetSize);
  for (int i = finest; i < levels; ++i)
  {
    const long long count = in.SplatCount[static_cast<size_t>(i)];
    in.GatheredTexels[static_cast<size_t>(i)] = count;
    if (count == 0)
    {
      continue;
    }
    const std::array<vtkTextureObject*, 2> receivers = in.BindReceivers(splat, i, position, normal, x0, y0);
    glDrawArraysInstanced(GL_POINTS, static_cast<GLint>(in.SplatFirst[static_cast<size_t>(i)]),
      static_cast<GLsizei>(count), vplCount);
    receivers[1]->Deactivate();
    receivers[0]->Deactivate();
  }
  for (int i = 0; i < finest; ++i)
  {
    in.GatheredTexels[static_cast<size_t>(i)] = 0;
  }
  vpls->Deactivate();
  ostate->vtkglBlendEquationSeparate(GL_FUNC_ADD, GL_FUNC_ADD);
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
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
  vtkMRGIShaderUtilities::ScopedStage step(this->StageTimer, "upsample.levels");
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
    // The texels the last gather rendered: the selection, or the
    // incremental stencil (NPW10 3.4 step 3: upsample where not rendered).
    // The specular gather (NPW10 3.2.1) renders its own selection.
    vtkTextureObject* rendered = in.LastGatherSpecular ? in.FlatSpecularSelection
      : in.LastGatherIncremental                        ? in.FlatIncremental
                                                        : in.FlatSelection;
    BindInputs(state, { rendered, flags, in.FlatIrradiance, parent });
    const int offset[2] = { layout.level_offset[i], 0 };
    state->SetUniform2i("mrgiOffset", offset);
    state->SetUniformi("mrgiCoarsest", i == coarsest ? 1 : 0);
    in.UpsampleQuads[0]->Render();
    UnbindInputs({ rendered, flags, in.FlatIrradiance, parent });

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
  vtkTextureObject* position, vtkTextureObject* normal, bool parallel,
  vtkTextureObject* irradiance, vtkTextureObject* indirect, int x0, int y0, double strength)
{
  Internals& in = *this->Internal;
  vtkShaderProgram* resolve =
    window ? ReadyStage(in.UpsampleQuads[2], window, vtkMRGIMultiresUpsampleFS, 2) : nullptr;
  if (!resolve || !in.HasLayout || !albedo || !position || !normal || !irradiance || !indirect)
  {
    vtkErrorMacro("Resolve needs Upsample() first, the G-buffer and both targets");
    return false;
  }
  {
    vtkMRGIShaderUtilities::ScopedStage step(this->StageTimer, "upsample.resolve");
    QuadSteps steps(window, in.FrameBuffer);
    steps.Target(irradiance, indirect, x0, y0, in.Layout.width, in.Layout.height);
    vtkTextureObject* flags = in.Levels[0][MRGI_MULTIRES_TEX_COUNT];
    BindInputs(resolve, { in.Upsampled[0][1], flags, albedo, position, normal });
    const int offset[2] = { x0, y0 };
    resolve->SetUniform2i("mrgiOffset", offset);
    resolve->SetUniformf("mrgiStrength", static_cast<float>(strength));
    resolve->SetUniformf("mrgiSurfaceDetail", static_cast<float>(this->SurfaceDetail));
    resolve->SetUniformi("mrgiParallel", parallel ? 1 : 0);
    in.UpsampleQuads[2]->Render();
    UnbindInputs({ in.Upsampled[0][1], flags, albedo, position, normal });
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
  if (!renWin || !position || !normal || !in.HasLayout || !in.LastPosition || !in.LastNormal)
  {
    vtkErrorMacro("ReadReceivers: nothing gathered yet");
    return false;
  }
  // Level 0 is the G-buffer of the last Gather(), turned into receivers here
  // (the gather itself never writes it).
  renWin->MakeCurrent();
  vtkShaderProgram* p = ReadyStage(in.ReceiverQuads[0], renWin, vtkMRGIMultiresReceiversFS, 0);
  if (!p)
  {
    vtkErrorMacro("could not build the multiresolution receivers shader");
    return false;
  }
  {
    QuadSteps steps(renWin, in.FrameBuffer);
    steps.Target(in.Receivers[0][0], in.Receivers[0][1], 0, 0, in.Layout.width, in.Layout.height);
    BindInputs(p, { in.LastPosition, in.LastNormal });
    p->SetUniform2i("mrgiOffset", in.LastOffset);
    in.ReceiverQuads[0]->Render();
    UnbindInputs({ in.LastPosition, in.LastNormal });
  }
  vtkFloatArray* out[2] = { position, normal };
  for (int k = 0; k < 2; ++k)
  {
    std::vector<float> flat;
    if (!ReadFlattened(renWin, in.Layout, 4,
          [&](int level) { return in.Receivers[static_cast<size_t>(level)][static_cast<size_t>(k)]; }, flat))
    {
      vtkErrorMacro("ReadReceivers: could not read the receivers back");
      return false;
    }
    out[k]->SetNumberOfComponents(4);
    out[k]->SetNumberOfTuples(static_cast<vtkIdType>(flat.size() / 4));
    std::copy(flat.begin(), flat.end(), out[k]->GetPointer(0));
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
  return ReadMask(renWin, in.FrameBuffer, in.Layout, in.FlatSelection, in.DepthStencil, fromStencil, mask);
}

//------------------------------------------------------------------------------
bool vtkMRGIMultiresolution::BuildIncrementalStencil(
  vtkOpenGLRenderWindow* window, vtkMRGIVisibilityPyramid* masks)
{
  // NPW10 3.4, one draw per level into its rectangle of the flattened
  // layout: a texel is rendered when selected, or when its parent's 3x3
  // masks show a light discontinuity (mrgi_incremental_stencil_build()).
  // Each draw reads the coarser level's masks and receivers only, so the
  // levels are independent and the order does not matter.
  Internals& in = *this->Internal;
  const mrgi_multires_layout& layout = in.Layout;
  const int levels = layout.level_count;
  const int finest = std::min(this->FinestLevel, levels - 1);
  const int words = masks->GetNumberOfMaskWords();
  const int targets = masks->GetNumberOfMaskTextures();
  const int threshold =
    mrgi_voxel_refine_threshold(static_cast<float>(this->IncrementalStencilFraction),
      masks->GetNumberOfSamples());
  if (masks->GetNumberOfLevels() != levels || words < 1 || targets < 1 || targets > 4 ||
    threshold < 0)
  {
    vtkErrorMacro("the incremental stencil needs visibility masks of this frame's "
      << levels << " levels (they have " << masks->GetNumberOfLevels() << " levels, " << words
      << " words)");
    return false;
  }
  vtkOpenGLQuadHelper*& quad = in.IncrementalQuads[words];
  if (!quad)
  {
    const std::string body = "#define MRGI_STENCIL_WORDS " + std::to_string(words) +
      "\n#define MRGI_STENCIL_TARGETS " + std::to_string(targets) + "\n" + vtkMRGIVisibilityBits +
      vtkMRGIIncrementalStencilFS;
    quad = new vtkOpenGLQuadHelper(window,
      vtkOpenGLRenderUtilities::GetFullScreenQuadVertexShader().c_str(),
      vtkMRGIShaderUtilities::FullScreenShader(body.c_str()).c_str(), "");
  }
  window->GetShaderCache()->ReadyShaderProgram(quad->Program);
  vtkShaderProgram* program = (quad->Program && quad->Program->GetCompiled()) ? quad->Program : nullptr;
  if (!program)
  {
    vtkErrorMacro("could not build the incremental stencil shader");
    return false;
  }
  using vtkMRGIShaderUtilities::ScopedStage;
  ScopedStage step(this->StageTimer, "select.incremental");
  QuadSteps steps(window, in.FrameBuffer);
  vtkOpenGLState* ostate = steps.State;
  steps.Target(in.FlatIncremental, nullptr, 0, 0, layout.total_width, layout.total_height);
  BeginMaskWrite(ostate, in.IncrementalDepthStencil);
  program->SetUniformi("mrgiThreshold", threshold);
  program->SetUniformi("mrgiMetric", masks->GetMetric());
  bool ok = true;
  for (int i = finest; i < levels && ok; ++i)
  {
    // The coarsest level has no parent: its own receivers and masks stand
    // in, unread.
    const int parent = std::min(i + 1, levels - 1);
    std::vector<vtkTextureObject*> inputs = { in.Levels[i][MRGI_MULTIRES_TEX_COUNT], in.FlatSelection,
      in.Receivers[parent][0] };
    const char* names[7] = { "mrgiFlags", "mrgiSelection", "mrgiParentPosition", "mrgiParentMask0",
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
  EndMaskWrite(ostate);
  const GLenum error = glGetError();
  if (error != GL_NO_ERROR)
  {
    vtkErrorMacro("OpenGL error 0x" << std::hex << error << " in the incremental stencil");
    return false;
  }
  return ok;
}

//------------------------------------------------------------------------------
bool vtkMRGIMultiresolution::ReadIncrementalStencil(vtkRenderWindow* window, vtkUnsignedCharArray* mask)
{
  vtkOpenGLRenderWindow* renWin = vtkOpenGLRenderWindow::SafeDownCast(window);
  Internals& in = *this->Internal;
  if (!renWin || !mask || !in.HasLayout || !in.LastGatherIncremental)
  {
    vtkErrorMacro("ReadIncrementalStencil: the last gather did not use the incremental stencil");
    return false;
  }
  return ReadMask(renWin, in.FrameBuffer, in.Layout, in.FlatIncremental, in.IncrementalDepthStencil,
    false, mask);
}

//------------------------------------------------------------------------------
bool vtkMRGIMultiresolution::ReadFlags(vtkRenderWindow* window, vtkUnsignedCharArray* flags)
{
  vtkOpenGLRenderWindow* renWin = vtkOpenGLRenderWindow::SafeDownCast(window);
  Internals& in = *this->Internal;
  std::vector<float> flat;
  if (!renWin || !flags || !in.HasLayout ||
    !ReadFlattened(renWin, in.Layout, 1,
      [&](int level) { return in.Levels[static_cast<size_t>(level)][MRGI_MULTIRES_TEX_COUNT]; }, flat))
  {
    vtkErrorMacro("ReadFlags: nothing selected yet");
    return false;
  }
  flags->SetNumberOfComponents(1);
  flags->SetNumberOfTuples(static_cast<vtkIdType>(flat.size()));
  for (vtkIdType i = 0; i < flags->GetNumberOfTuples(); ++i)
  {
    flags->SetValue(i, static_cast<unsigned char>(flat[static_cast<size_t>(i)]));
  }
  return true;
}

//------------------------------------------------------------------------------
vtkIdType vtkMRGIMultiresolution::GetNumberOfGatheredTexels(int level) const
{
  const Internals& in = *this->Internal;
  if (level < 0 || static_cast<size_t>(level) >= in.GatheredTexels.size())
  {
    return -1;
  }
  return static_cast<vtkIdType>(in.GatheredTexels[static_cast<size_t>(level)]);
}

//------------------------------------------------------------------------------
vtkIdType vtkMRGIMultiresolution::GetNumberOfValidPixels() const
{
  return static_cast<vtkIdType>(this->Internal->ValidPixels);
}

//------------------------------------------------------------------------------
double vtkMRGIMultiresolution::GetGatherWorkFraction() const
{
  const Internals& in = *this->Internal;
  long long total = 0;
  for (long long n : in.GatheredTexels)
  {
    if (n < 0)
    {
      return -1.0;
    }
    total += n;
  }
  if (in.GatheredTexels.empty() || in.ValidPixels < 0)
  {
    return -1.0;
  }
  return in.ValidPixels > 0 ? static_cast<double>(total) / static_cast<double>(in.ValidPixels) : 0.0;
}

//------------------------------------------------------------------------------
vtkTextureObject* vtkMRGIMultiresolution::GetReceiverTexture(int level, int which) const
{
  const Internals& in = *this->Internal;
  if (!in.ReceiversValid || level < 0 || level >= in.Layout.level_count || which < 0 || which > 1)
  {
    return nullptr;
  }
  if (level == 0)
  {
    return which == 0 ? in.LastPosition : in.LastNormal;
  }
  return in.Receivers[static_cast<size_t>(level)][static_cast<size_t>(which)];
}

bool vtkMRGIMultiresolution::GetReceiverOffset(int level, int offset[2]) const
{
  const Internals& in = *this->Internal;
  if (!in.ReceiversValid || level < 0 || level >= in.Layout.level_count)
  {
    return false;
  }
  offset[0] = level == 0 ? in.LastOffset[0] : -in.Layout.level_offset[level];
  offset[1] = level == 0 ? in.LastOffset[1] : 0;
  return true;
}

vtkTextureObject* vtkMRGIMultiresolution::GetFlagsTexture(int level) const
{
  const Internals& in = *this->Internal;
  return in.HasLayout && level >= 0 && level < in.Layout.level_count
    ? in.Levels[static_cast<size_t>(level)][MRGI_MULTIRES_TEX_COUNT]
    : nullptr;
}

vtkTextureObject* vtkMRGIMultiresolution::GetSelectionTexture() const
{
  return this->Internal->HasLayout ? this->Internal->FlatSelection : nullptr;
}

bool vtkMRGIMultiresolution::GetLayout(mrgi_multires_layout* layout) const
{
  if (!this->Internal->HasLayout || !layout)
  {
    return false;
  }
  *layout = this->Internal->Layout;
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
  os << indent << "SurfaceDetail: " << this->SurfaceDetail << "\n";
  os << indent << "IncrementalStencil: " << (this->IncrementalStencil ? "On" : "Off") << "\n";
  os << indent << "IncrementalStencilFraction: " << this->IncrementalStencilFraction << "\n";
  os << indent << "SpecularLobeRefinement: " << (this->SpecularLobeRefinement ? "On" : "Off") << "\n";
  os << indent << "SpecularLobeThreshold: " << this->SpecularLobeThreshold << "\n";
  os << indent << "GatherMode: " << (this->GatherMode == GatherSplatting ? "Splatting" : "Stenciled") << "\n";
  os << indent << "CollectStatistics: " << (this->CollectStatistics ? "On" : "Off") << "\n";
  os << indent << "Levels: " << this->GetNumberOfLevels() << "\n";
}

//------------------------------------------------------------------------------
void vtkMRGIMultiresolution::GetPixelSizeCoefficients(double coefficients[2]) const
{
  coefficients[0] = this->Internal->PixelSize[0];
  coefficients[1] = this->Internal->PixelSize[1];
}

//------------------------------------------------------------------------------
bool vtkMRGIMultiresolution::BuildSpecularStencil(vtkOpenGLRenderWindow* window,
  vtkTextureObject* position, vtkTextureObject* normal, vtkTextureObject* specular,
  vtkTextureObject* shininess, int x0, int y0, const mrgi_area_light_uniforms& light,
  const float viewToWorld[16], bool parallel)
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
  if (!window || !position || !normal || !specular || !shininess || !in.HasLayout)
  {
    vtkErrorMacro("BuildSpecularStencil needs Update() first and the G-buffer with its specular targets");
    return false;
  }
  if (!in.ReceiversValid && !this->BuildReceivers(window, position, normal, x0, y0))
  {
    return false;
  }
  const mrgi_multires_layout& layout = in.Layout;
  const int levels = layout.level_count;
  const int finest = std::min(this->FinestLevel, levels - 1);
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
    in.FlatSpecularBits = MakeFloatTexture(window, layout.total_width, layout.total_height);
    in.FlatSpecularSelection = MakeFloatTexture(window, layout.total_width, layout.total_height);
    in.SpecularDepthStencil =
      vtkMRGIShaderUtilities::NewDepthStencil(window, layout.total_width, layout.total_height);
  }
  if (!in.FlatSpecularBits || !in.FlatSpecularSelection || !in.SpecularDepthStencil ||
    std::find(in.SpecularMaterial.begin(), in.SpecularMaterial.end(), nullptr) != in.SpecularMaterial.end())
  {
    vtkErrorMacro("could not allocate the specular stencil's buffers");
    return false;
  }
  vtkShaderProgram* programs[4];
  for (int stage = 0; stage < 4; ++stage)
  {
    if (!in.SpecularQuads[stage])
    {
      std::string body = "#define MRGI_SPEC_STAGE " + std::to_string(stage) + "\n";
      if (stage == 2)
      {
        body += std::string(vtkMRGIAreaLightDiffuse) + "\n#define MRGI_AREA_LIGHT_DIFFUSE_DECLARED\n" +
          vtkMRGIAreaLightSpecular;
      }
      body += vtkMRGISpecularStencilFS;
      in.SpecularQuads[stage] = new vtkOpenGLQuadHelper(window,
        vtkOpenGLRenderUtilities::GetFullScreenQuadVertexShader().c_str(),
        vtkMRGIShaderUtilities::FullScreenShader(body.c_str()).c_str(), "");
    }
    window->GetShaderCache()->ReadyShaderProgram(in.SpecularQuads[stage]->Program);
    vtkShaderProgram* p = in.SpecularQuads[stage]->Program;
    programs[stage] = (p && p->GetCompiled()) ? p : nullptr;
    if (!programs[stage])
    {
      vtkErrorMacro("could not build the specular stencil shader (stage " << stage << ")");
      return false;
    }
  }
  using vtkMRGIShaderUtilities::ScopedStage;
  ScopedStage step(this->StageTimer, "select.specular");
  QuadSteps steps(window, in.FrameBuffer);
  vtkOpenGLState* ostate = steps.State;
  // 1. Material pyramid.
  for (int i = 0; i < levels; ++i)
  {
    vtkShaderProgram* p = programs[i == 0 ? 0 : 1];
    window->GetShaderCache()->ReadyShaderProgram(p);
    steps.Target(in.SpecularMaterial[static_cast<size_t>(i)], nullptr, 0, 0, layout.level_width[i],
      layout.level_height[i]);
    if (i == 0)
    {
      BindInputs(p, { position, specular, shininess });
      const int offset[2] = { x0, y0 };
      p->SetUniform2i("mrgiOffset", offset);
      in.SpecularQuads[0]->Render();
      UnbindInputs({ position, specular, shininess });
    }
    else
    {
      vtkTextureObject* child = in.SpecularMaterial[static_cast<size_t>(i - 1)];
      BindInputs(p, { child });
      const int size[2] = { layout.level_width[i - 1], layout.level_height[i - 1] };
      p->SetUniform2i("mrgiSize", size);
      in.SpecularQuads[1]->Render();
      UnbindInputs({ child });
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
    p->SetUniformMatrix4x4("mrgiVCToWC", const_cast<float*>(viewToWorld));
    p->SetUniformi("mrgiParallel", parallel ? 1 : 0);
    p->SetUniformi("mrgiLobe", this->SpecularLobeRefinement ? 1 : 0);
    p->SetUniformf("mrgiLobeThreshold", static_cast<float>(this->SpecularLobeThreshold));
    const float pixelSize[2] = { static_cast<float>(in.PixelSize[0]),
      static_cast<float>(in.PixelSize[1]) };
    p->SetUniform2f("mrgiPixelSize", pixelSize);
    for (int i = finest; i < levels; ++i)
    {
      const std::array<vtkTextureObject*, 2> receivers = in.BindReceivers(p, i, position, normal, x0, y0);
      vtkTextureObject* flags = in.Levels[static_cast<size_t>(i)][MRGI_MULTIRES_TEX_COUNT];
      vtkTextureObject* material = in.SpecularMaterial[static_cast<size_t>(i)];
      flags->Activate();
      material->Activate();
      p->SetUniformi("mrgiFlags", flags->GetTextureUnit());
      p->SetUniformi("mrgiMaterial", material->GetTextureUnit());
      p->SetUniformi("mrgiLevelOffset", layout.level_offset[i]);
      p->SetUniformi("mrgiLevel", i);
      p->SetUniformi("mrgiFinest", i == finest ? 1 : 0);
      ostate->vtkglViewport(layout.level_offset[i], 0, layout.level_width[i], layout.level_height[i]);
      in.SpecularQuads[2]->Render();
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
    BeginMaskWrite(ostate, in.SpecularDepthStencil);
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
      in.SpecularQuads[3]->Render();
    }
    in.FlatSpecularBits->Deactivate();
    EndMaskWrite(ostate);
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
bool vtkMRGIMultiresolution::GatherAreaSpecular(vtkOpenGLRenderWindow* window,
  vtkTextureObject* position, vtkTextureObject* normal, int x0, int y0, vtkShaderProgram* program,
  const std::function<bool(int level)>& draw)
{
  // NPW10 3.2.1: "we separate diffuse and Phong components into separate
  // gather passes": the specular gather at the texels of the specular
  // stencil, one draw per level (early stencil culling).
  Internals& in = *this->Internal;
  if (!window || !program || !in.SpecularStencilValid)
  {
    vtkErrorMacro("GatherAreaSpecular needs BuildSpecularStencil() first and a program");
    return false;
  }
  const mrgi_multires_layout& layout = in.Layout;
  const int levels = layout.level_count;
  const int finest = std::min(this->FinestLevel, levels - 1);
  vtkMRGIShaderUtilities::ScopedStage step(this->StageTimer, "gather.specular");
  in.LastGatherIncremental = false;
  in.LastGatherSpecular = false;
  bool ok = true;
  {
    QuadSteps steps(window, in.FrameBuffer);
    vtkOpenGLState* ostate = steps.State;
    vtkOpenGLState::ScopedglBlendFuncSeparate blendFunc(ostate);
    steps.Target(in.FlatIrradiance, nullptr, 0, 0, layout.total_width, layout.total_height);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_TEXTURE_2D,
      in.SpecularDepthStencil->GetHandle(), 0);
    ostate->vtkglClearColor(0.0, 0.0, 0.0, 0.0);
    ostate->vtkglClear(GL_COLOR_BUFFER_BIT);
    ostate->vtkglEnable(GL_STENCIL_TEST);
    ostate->vtkglStencilMask(0x00);
    ostate->vtkglStencilFunc(GL_EQUAL, 1, 0xFF);
    ostate->vtkglStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
    for (int i = finest; i < levels && ok; ++i)
    {
      const std::array<vtkTextureObject*, 2> receivers =
        in.BindReceivers(program, i, position, normal, x0, y0);
      vtkTextureObject* material = in.SpecularMaterial[static_cast<size_t>(i)];
      material->Activate();
      program->SetUniformi("mrgiMaterial", material->GetTextureUnit());
      const int origin[2] = { layout.level_offset[i], 0 };
      program->SetUniform2i("mrgiLevelOrigin", origin);
      program->SetUniformi("mrgiLevelScale", 1 << i);
      ostate->vtkglDisable(GL_BLEND);
      ostate->vtkglViewport(layout.level_offset[i], 0, layout.level_width[i], layout.level_height[i]);
      ok = draw(i);
      material->Deactivate();
      receivers[1]->Deactivate();
      receivers[0]->Deactivate();
    }
    ostate->vtkglStencilMask(0xFF);
    ostate->vtkglStencilFunc(GL_ALWAYS, 0, 0xFF);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_TEXTURE_2D, 0, 0);
  }
  in.LastGatherSpecular = ok;
  return ok && glGetError() == GL_NO_ERROR;
}

//------------------------------------------------------------------------------
bool vtkMRGIMultiresolution::ReadSpecularStencil(vtkRenderWindow* window,
  vtkUnsignedCharArray* selection, vtkUnsignedCharArray* bits, bool fromStencil)
{
  vtkOpenGLRenderWindow* renWin = vtkOpenGLRenderWindow::SafeDownCast(window);
  Internals& in = *this->Internal;
  if (!renWin || !selection || !in.SpecularStencilValid)
  {
    vtkErrorMacro("ReadSpecularStencil: no specular stencil built");
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
  return ReadMask(renWin, in.FrameBuffer, in.Layout, in.FlatSpecularSelection,
    in.SpecularDepthStencil, fromStencil, selection);
}

//------------------------------------------------------------------------------
bool vtkMRGIMultiresolution::ReadSpecularMaterial(vtkRenderWindow* window, vtkFloatArray* material)
{
  vtkOpenGLRenderWindow* renWin = vtkOpenGLRenderWindow::SafeDownCast(window);
  Internals& in = *this->Internal;
  std::vector<float> flat;
  if (!renWin || !material || !in.SpecularStencilValid ||
    !ReadFlattened(renWin, in.Layout, 4,
      [&](int level) { return in.SpecularMaterial[static_cast<size_t>(level)]; }, flat))
  {
    vtkErrorMacro("ReadSpecularMaterial: no specular stencil built");
    return false;
  }
  material->SetNumberOfComponents(4);
  material->SetNumberOfTuples(static_cast<vtkIdType>(flat.size() / 4));
  std::copy(flat.begin(), flat.end(), material->GetPointer(0));
  return true;
}
