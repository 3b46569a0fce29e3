#include "vtk_glew.h"

#include "vtkMRGIMultiresolution.h"

#include "vtkFloatArray.h"
#include "vtkMRGIFullScreenStep.h"
#include "vtkMRGIProgramCache.h"
#include "vtkMRGIStageResources.h"
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

#include "vtkMRGIMultiresReceiversFS.h"
#include "vtkMRGIMultiresSelectFS.h"

#include "mrgi_multires.h"

#include <algorithm>
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
  Select = 3,
  MipmapReduceLevel0 = 4, // stage 1 reading level 0 (one normal texture)
  FlagsLevel0 = 5,        // stage 2 of level 0 (one normal texture)
  StageCount = 6
};

vtkTextureObject* MakeFloatTexture(vtkOpenGLRenderWindow* window, int w, int h)
{
  return vtkMRGIShaderUtilities::NewTexture(window, GL_RGBA32F, w, h);
}

// The receivers program of `stage` (vtkMRGIMultiresReceiversFS.glsl: 0 level
// 0 from the G-buffer, 1 a 2x2 reduction, 2 level 1 from the G-buffer).
vtkOpenGLQuadHelper* ReadyReceiverStage(vtkMRGIProgramCache& programs, vtkOpenGLRenderWindow* window, int stage)
{
  return programs.Ready(window, "receivers", "#define MRGI_MR_STAGE " + std::to_string(stage) + "\n",
    [] { return vtkMRGIMultiresReceiversFS; });
}
}

struct vtkMRGIMultiresolution::Internals
{
  mrgi_multires_layout Layout{};
  bool HasLayout = false;
  // Per level: mipmap (MRGI_MULTIRES_TEX_*) and flags. Level 0 stores one
  // normal texture (min = max, vtkMRGIMultiresSelectFS.glsl stage 0): its
  // MRGI_MULTIRES_TEX_NORMAL_MAX slot is null.
  std::vector<std::array<vtkTextureObject*, MRGI_MULTIRES_TEX_COUNT + 1>> Levels;
  // Receivers: per level (position, normal); level 0 is the G-buffer itself:
  // its textures exist only for ReadReceivers(), which allocates them.
  std::vector<std::array<vtkTextureObject*, 2>> Receivers;
  // The G-buffer of the last BuildReceivers() (not owned): level 0's receivers.
  vtkTextureObject* LastPosition = nullptr;
  vtkTextureObject* LastNormal = nullptr;
  int LastOffset[2] = { 0, 0 };
  // Receivers built for the current selection (Update() clears it).
  bool ReceiversValid = false;
  bool SelectedForAreaLights = false; // the last Update() used the area lights' thresholds
  vtkTextureObject* FlatSelection = nullptr;
  vtkTextureObject* DepthStencil = nullptr;
  // Pixel size coefficients of the last Update().
  double PixelSize[2] = { 0.0, 0.0 };
  vtkMRGIStageResources GL; // framebuffer and programs

  // Slot `slot` (MRGI_MULTIRES_TEX_*, or MRGI_MULTIRES_TEX_COUNT: the flags) of every level.
  std::vector<vtkTextureObject*> LevelTextures(int slot) const
  {
    std::vector<vtkTextureObject*> textures;
    for (const auto& level : this->Levels)
    {
      textures.push_back(level[static_cast<size_t>(slot)]);
    }
    return textures;
  }

  void ReleaseTextures(vtkWindow* w)
  {
    for (auto* list : { &this->Levels })
    {
      for (auto& level : *list)
      {
        for (auto*& t : level)
        {
          vtkMRGIShaderUtilities::ReleaseTexture(t, w);
        }
      }
      list->clear();
    }
    for (auto& level : this->Receivers)
    {
      for (auto*& t : level)
      {
        vtkMRGIShaderUtilities::ReleaseTexture(t, w);
      }
    }
    this->Receivers.clear();
    vtkMRGIShaderUtilities::ReleaseTexture(this->FlatSelection, w);
    vtkMRGIShaderUtilities::ReleaseTexture(this->DepthStencil, w);
    this->HasLayout = false;
    this->LastPosition = this->LastNormal = nullptr;
    this->ReceiversValid = false;
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
bool vtkMRGIMultiresolution::AreaLightsShareSelection() const
{
  // Off is any negative value or +inf.
  const auto same = [](double a, double b) {
    const bool offA = a < 0 || std::isinf(a), offB = b < 0 || std::isinf(b);
    return offA == offB && (offA || a == b);
  };
  return same(this->AreaLightDepthThreshold, this->DepthThreshold) &&
    same(this->AreaLightNormalThreshold, this->NormalThreshold);
}

//------------------------------------------------------------------------------
bool vtkMRGIMultiresolution::RefinesByIllumination(int width, int height, bool stenciled) const
{
  return this->Refinement == RefinementIllumination && stenciled &&
    static_cast<vtkIdType>(width) * height >= this->IlluminationMinimumPixels;
}

//------------------------------------------------------------------------------
bool vtkMRGIMultiresolution::SelectionServesAreaLights() const
{
  return this->Internal->HasLayout && this->Internal->SelectedForAreaLights;
}

//------------------------------------------------------------------------------
double vtkMRGIMultiresolution::GetPresetIlluminationThreshold(int preset)
{
  double threshold = INFINITY;
  return mrgi_multires_preset_illumination_threshold(preset, &threshold, nullptr) == MRGI_OK &&
      !std::isinf(threshold)
    ? threshold
    : -1.0;
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
  const double illumination = GetPresetIlluminationThreshold(preset);
  mrgi_multires_params area;
  mrgi_multires_preset_area_light_params(preset, &area, nullptr);
  this->SetAreaLightDepthThreshold(std::isinf(area.depth_threshold) ? -1.0 : area.depth_threshold);
  this->SetAreaLightNormalThreshold(
    std::isinf(area.normal_threshold) ? -1.0 : area.normal_threshold);
  this->SetDepthThreshold(settings[0]);
  this->SetNormalThreshold(settings[1]);
  this->SetFinestLevel(static_cast<int>(settings[2]));
  this->SetBalance(true);
  this->SetRefinement(illumination < 0 ? RefinementGeometry : RefinementIllumination);
  if (illumination >= 0)
  {
    this->SetIlluminationThreshold(illumination);
  }
  this->SetIlluminationMinimumPixels(illumination >= 0 ? MRGI_MULTIRES_ILLUMINATION_MIN_PIXELS : 0);
  return true;
}

//------------------------------------------------------------------------------
vtkMRGIMultiresolution::~vtkMRGIMultiresolution()
{
  if (this->Internal->GL.FrameBuffer || this->Internal->DepthStencil)
  {
    vtkErrorMacro("GL resources should have been freed in ReleaseGraphicsResources().");
  }
  this->Internal->ReleaseTextures(nullptr);
}

//------------------------------------------------------------------------------
void vtkMRGIMultiresolution::ReleaseGraphicsResources(vtkWindow* w)
{
  this->Internal->ReleaseTextures(w);
  this->Internal->GL.Release(w);
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
  double a, double b, vtkRenderTimerLog* timer, bool forAreaLights)
{
  if (!window || !position || !normal)
  {
    vtkErrorMacro("Update needs a window and the G-buffer position and normal textures");
    return false;
  }
  this->Internal->ReceiversValid = false; // a new selection: BuildReceivers() makes its receivers
  this->Internal->SelectedForAreaLights = forAreaLights || this->AreaLightsShareSelection();
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
      auto& level = in.Levels[static_cast<size_t>(i)];
      for (int slot = 0; slot < MRGI_MULTIRES_TEX_COUNT; ++slot)
      {
        // Level 0 has no normal textures: its passes read the G-buffer's.
        level[static_cast<size_t>(slot)] = i == 0 && slot != MRGI_MULTIRES_TEX_DEPTH
          ? nullptr
          : MakeFloatTexture(window, layout.level_width[i], layout.level_height[i]);
      }
      level[MRGI_MULTIRES_TEX_COUNT] = vtkMRGIShaderUtilities::NewFlagsTexture(window, layout.level_width[i], layout.level_height[i]);
    }
    in.Receivers.resize(static_cast<size_t>(levels));
    for (int i = 1; i < levels; ++i)
    {
      for (auto*& t : in.Receivers[static_cast<size_t>(i)])
      {
        t = MakeFloatTexture(window, layout.level_width[i], layout.level_height[i]);
      }
    }
    in.FlatSelection = vtkMRGIShaderUtilities::NewMaskTexture(window, layout.total_width, layout.total_height);
    in.DepthStencil = vtkMRGIShaderUtilities::NewDepthStencil(window, layout.total_width, layout.total_height);
    bool allocated = in.FlatSelection && in.DepthStencil;
    for (int i = 0; i < levels; ++i)
    {
      const auto& level = in.Levels[static_cast<size_t>(i)];
      for (int slot = 0; slot <= MRGI_MULTIRES_TEX_COUNT; ++slot)
      {
        allocated = allocated &&
          (level[static_cast<size_t>(slot)] || (i == 0 && slot != MRGI_MULTIRES_TEX_DEPTH &&
                                                  slot != MRGI_MULTIRES_TEX_COUNT));
      }
      const auto& receivers = in.Receivers[static_cast<size_t>(i)];
      allocated = allocated && (i == 0 || (receivers[0] && receivers[1]));
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
  in.GL.Prepare(window);

  // Programs, one per stage.
  vtkOpenGLQuadHelper* quads[StageCount];
  vtkShaderProgram* programs[StageCount];
  for (int s = 0; s < StageCount; ++s)
  {
    const int stage = s == MipmapReduceLevel0 ? MipmapReduce : s == FlagsLevel0 ? Flags : s;
    const std::string defines = "#define MRGI_MR_STAGE " + std::to_string(stage) + "\n" +
      (s >= MipmapReduceLevel0 ? "#define MRGI_MR_LEVEL0 1\n" : "");
    quads[s] = in.GL.Programs.Ready(window, "select", defines, [] { return vtkMRGIMultiresSelectFS; });
    if (!quads[s])
    {
      vtkErrorMacro("could not build the multiresolution selection shader (stage " << s << ")");
      return false;
    }
    programs[s] = quads[s]->Program;
  }

  vtkMRGIFullScreenStep steps(window, in.GL.FrameBuffer);
  vtkOpenGLState* ostate = steps.GetState();

  auto bind = [&](vtkShaderProgram* program, std::initializer_list<vtkTextureObject*> textures) {
    // Uniforms go to the bound program: bind this stage's first.
    window->GetShaderCache()->ReadyShaderProgram(program);
    vtkMRGIFullScreenStep::BindInputs(program, textures);
  };
  const auto unbind = vtkMRGIFullScreenStep::UnbindInputs;
  const float pixelSize[2] = { static_cast<float>(a), static_cast<float>(b) };

  using vtkMRGIShaderUtilities::ScopedStage;
  // 1. Level 0 of the mipmaps, from the G-buffer.
  {
    ScopedStage step(timer, "select.mipmap0");
    auto& level = in.Levels[0];
    // Depth only: level 0's normal range is the G-buffer normal (min = max).
    steps.Targets({ level[MRGI_MULTIRES_TEX_DEPTH] }, width, height);
    vtkShaderProgram* p = programs[MipmapBase];
    bind(p, { position, normal });
    const int offset[2] = { x0, y0 };
    const int size[2] = { width, height };
    p->SetUniform2i("mrgiOffset", offset);
    p->SetUniform2i("mrgiSize", size);
    p->SetUniform2f("mrgiPixelSize", pixelSize);
    quads[MipmapBase]->Render();
    unbind({ position, normal });
  }
  // 2. Coarser levels: 2x2 reduction of the finer one.
  for (int i = 1; i < levels; ++i)
  {
    ScopedStage step(timer, "select.mipmaps");
    auto& fine = in.Levels[i - 1];
    auto& level = in.Levels[i];
    steps.Targets({ level[MRGI_MULTIRES_TEX_DEPTH], level[MRGI_MULTIRES_TEX_NORMAL_MIN],
             level[MRGI_MULTIRES_TEX_NORMAL_MAX] },
      layout.level_width[i], layout.level_height[i]);
    const int stage = i == 1 ? MipmapReduceLevel0 : MipmapReduce;
    vtkShaderProgram* p = programs[stage];
    // From level 0, the normals are the G-buffer's (one per pixel).
    vtkTextureObject* normalMin = i == 1 ? normal : fine[MRGI_MULTIRES_TEX_NORMAL_MIN];
    vtkTextureObject* normalMax = fine[MRGI_MULTIRES_TEX_NORMAL_MAX];
    bind(p, { fine[MRGI_MULTIRES_TEX_DEPTH], normalMin });
    if (i != 1)
    {
      normalMax->Activate();
      p->SetUniformi("mrgiInput2", normalMax->GetTextureUnit());
    }
    const int offset[2] = { x0, y0 };
    const int size[2] = { layout.level_width[i - 1], layout.level_height[i - 1] };
    if (i == 1)
    {
      p->SetUniform2i("mrgiOffset", offset); // the G-buffer's viewport origin
    }
    p->SetUniform2i("mrgiSize", size);
    quads[stage]->Render();
    unbind({ fine[MRGI_MULTIRES_TEX_DEPTH], normalMin });
    if (i != 1)
    {
      normalMax->Deactivate();
    }
  }
  // 3. Flags, fine to coarse (refinement and balance read the finer level).
  const double depth = forAreaLights ? this->AreaLightDepthThreshold : this->DepthThreshold;
  const double normalSpread = forAreaLights ? this->AreaLightNormalThreshold : this->NormalThreshold;
  const float depthThreshold = mrgi_multires_threshold_uniform(depth < 0 ? INFINITY : depth);
  const float normalThreshold =
    mrgi_multires_threshold_uniform(normalSpread < 0 ? INFINITY : normalSpread);
  for (int i = 0; i < levels; ++i)
  {
    ScopedStage step(timer, i == 0 ? "select.flags0" : "select.flags");
    auto& level = in.Levels[i];
    const int flagsSlot = MRGI_MULTIRES_TEX_COUNT;
    steps.Targets({ level[flagsSlot] }, layout.level_width[i], layout.level_height[i]);
    const int stage = i == 0 ? FlagsLevel0 : Flags;
    vtkShaderProgram* p = programs[stage];
    // Level 0 has no finer level: its own (not yet written) flags stand in,
    // unread since level 0 <= the finest level.
    vtkTextureObject* finer = in.Levels[i > 0 ? i - 1 : 0][flagsSlot];
    if (i == 0)
    {
      finer = in.Levels[std::min(1, levels - 1)][MRGI_MULTIRES_TEX_DEPTH];
    }
    // Level 0: the G-buffer normal (FlagsLevel0 reads mrgiInput1 only; the
    // selection, neither read nor a target here, stands in for the unread
    // mrgiInput2 since level 0 has no normal textures).
    vtkTextureObject* normalMin = i == 0 ? normal : level[MRGI_MULTIRES_TEX_NORMAL_MIN];
    vtkTextureObject* normalMax = i == 0 ? in.FlatSelection : level[MRGI_MULTIRES_TEX_NORMAL_MAX];
    bind(p, { level[MRGI_MULTIRES_TEX_DEPTH], normalMin, normalMax, finer });
    const int offset[2] = { x0, y0 };
    if (i == 0)
    {
      p->SetUniform2i("mrgiOffset", offset); // the G-buffer's viewport origin
    }
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
    quads[stage]->Render();
    unbind({ level[MRGI_MULTIRES_TEX_DEPTH], normalMin, normalMax, finer });
  }
  // 4. Selection (nichols-shopf-wyman-2009 3.2.1): one draw per level from
  // the finest that gathers, into that level's rectangle of the flattened
  // layout; the texels that survive set the stencil.
  ScopedStage stencilStep(timer, "select.stencil");
  steps.Targets({ in.FlatSelection }, layout.total_width, layout.total_height);
  steps.BeginMaskWrite(in.DepthStencil);
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
    quads[Select]->Render();
    unbind({ flags, parent });
  }
  steps.EndMaskWrite();
  const GLenum error = glGetError();
  if (error != GL_NO_ERROR)
  {
    vtkErrorMacro("OpenGL error 0x" << std::hex << error << " in the multiresolution selection");
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkMRGIMultiresolution::BuildReceivers(vtkOpenGLRenderWindow* window,
  vtkTextureObject* position, vtkTextureObject* normal, int x0, int y0, vtkRenderTimerLog* timer)
{
  Internals& in = *this->Internal;
  if (!window || !position || !normal || !in.HasLayout)
  {
    vtkErrorMacro("BuildReceivers needs Update() first and the G-buffer");
    return false;
  }
  const mrgi_multires_layout& layout = in.Layout;
  const int levels = layout.level_count;
  bool ok = true;
  using vtkMRGIShaderUtilities::ScopedStage;
  in.LastPosition = position;
  in.LastNormal = normal;
  in.LastOffset[0] = x0;
  in.LastOffset[1] = y0;
  // 1. Receivers, level by level from level 1 (level 1 straight from the
  // G-buffer; the gather reads level 0 from the G-buffer itself).
  {
    ScopedStage receiverStep(timer, "gather.receivers");
    vtkMRGIFullScreenStep steps(window, in.GL.FrameBuffer);
    for (int i = 1; i < levels && ok; ++i)
    {
      const int stage = i == 1 ? 2 : 1;
      vtkOpenGLQuadHelper* quad = ReadyReceiverStage(in.GL.Programs, window, stage);
      if (!quad)
      {
        ok = false;
        break;
      }
      vtkShaderProgram* p = quad->Program;
      steps.Target(in.Receivers[i][0], in.Receivers[i][1], 0, 0, layout.level_width[i], layout.level_height[i]);
      vtkTextureObject* srcP = i == 1 ? position : in.Receivers[i - 1][0];
      vtkTextureObject* srcN = i == 1 ? normal : in.Receivers[i - 1][1];
      vtkMRGIFullScreenStep::BindInputs(p, { srcP, srcN });
      const int offset[2] = { x0, y0 };
      const int size[2] = { layout.level_width[i - 1], layout.level_height[i - 1] };
      p->SetUniform2i("mrgiOffset", offset);
      p->SetUniform2i("mrgiSize", size);
      quad->Render();
      srcP->Deactivate();
      srcN->Deactivate();
    }
  }
  in.ReceiversValid = ok;
  return ok;
}

//------------------------------------------------------------------------------
bool vtkMRGIMultiresolution::HasReceivers() const
{
  return this->Internal->HasLayout && this->Internal->ReceiversValid;
}

//------------------------------------------------------------------------------
int vtkMRGIMultiresolution::GetFinestGatherLevel() const
{
  const Internals& in = *this->Internal;
  return in.HasLayout ? std::min(this->FinestLevel, in.Layout.level_count - 1) : 0;
}

//------------------------------------------------------------------------------
std::array<vtkTextureObject*, 2> vtkMRGIMultiresolution::BindReceivers(
  vtkShaderProgram* program, int level) const
{
  int offset[2];
  vtkTextureObject* p = this->GetReceiverTexture(level, 0);
  vtkTextureObject* n = this->GetReceiverTexture(level, 1);
  if (!program || !p || !n || !this->GetReceiverOffset(level, offset))
  {
    return { nullptr, nullptr };
  }
  p->Activate();
  n->Activate();
  program->SetUniformi("mrgiPosition", p->GetTextureUnit());
  program->SetUniformi("mrgiNormal", n->GetTextureUnit());
  program->SetUniform2i("mrgiReceiverOffset", offset);
  return { p, n };
}

//------------------------------------------------------------------------------
vtkTextureObject* vtkMRGIMultiresolution::GetMipmapTexture(int level, int which) const
{
  const Internals& in = *this->Internal;
  return in.HasLayout && level >= 0 && level < in.Layout.level_count && which >= 0 &&
      which < MRGI_MULTIRES_TEX_COUNT
    ? in.Levels[static_cast<size_t>(level)][static_cast<size_t>(which)]
    : nullptr;
}

//------------------------------------------------------------------------------
bool vtkMRGIMultiresolution::ReadReceivers(
  vtkRenderWindow* window, vtkFloatArray* position, vtkFloatArray* normal)
{
  vtkOpenGLRenderWindow* renWin = vtkOpenGLRenderWindow::SafeDownCast(window);
  Internals& in = *this->Internal;
  if (!renWin || !position || !normal || !in.HasLayout || !in.ReceiversValid)
  {
    vtkErrorMacro("ReadReceivers: no receivers built yet");
    return false;
  }
  // Level 0 is the G-buffer of the last BuildReceivers(), turned into
  // receivers here (the gathers read the G-buffer itself). Its two
  // full-size textures serve this read-back only: allocated on the first
  // call, not by Update().
  renWin->MakeCurrent();
  for (auto*& t : in.Receivers[0])
  {
    if (!t)
    {
      t = MakeFloatTexture(renWin, in.Layout.width, in.Layout.height);
    }
    if (!t)
    {
      vtkErrorMacro("ReadReceivers: could not allocate the level-0 receivers (" << in.Layout.width
                                                                                << " x " << in.Layout.height << ")");
      return false;
    }
  }
  vtkOpenGLQuadHelper* quad = ReadyReceiverStage(in.GL.Programs, renWin, 0);
  if (!quad)
  {
    vtkErrorMacro("could not build the multiresolution receivers shader");
    return false;
  }
  vtkShaderProgram* p = quad->Program;
  {
    vtkMRGIFullScreenStep steps(renWin, in.GL.FrameBuffer);
    steps.Target(in.Receivers[0][0], in.Receivers[0][1], 0, 0, in.Layout.width, in.Layout.height);
    vtkMRGIFullScreenStep::BindInputs(p, { in.LastPosition, in.LastNormal });
    p->SetUniform2i("mrgiOffset", in.LastOffset);
    quad->Render();
    vtkMRGIFullScreenStep::UnbindInputs({ in.LastPosition, in.LastNormal });
  }
  vtkFloatArray* out[2] = { position, normal };
  for (int k = 0; k < 2; ++k)
  {
    std::vector<float> flat;
    std::vector<vtkTextureObject*> levels;
    for (const auto& level : in.Receivers)
    {
      levels.push_back(level[static_cast<size_t>(k)]);
    }
    if (!vtkMRGIFullScreenStep::ReadFlattened(renWin, in.Layout, 4, levels, flat))
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
  return vtkMRGIFullScreenStep::ReadMask(renWin, in.GL.FrameBuffer, in.Layout, in.FlatSelection, in.DepthStencil, fromStencil, mask);
}

//------------------------------------------------------------------------------
bool vtkMRGIMultiresolution::ReadFlags(vtkRenderWindow* window, vtkUnsignedCharArray* flags)
{
  vtkOpenGLRenderWindow* renWin = vtkOpenGLRenderWindow::SafeDownCast(window);
  Internals& in = *this->Internal;
  std::vector<float> flat;
  if (!renWin || !flags || !in.HasLayout ||
    !vtkMRGIFullScreenStep::ReadFlattened(renWin, in.Layout, 1, in.LevelTextures(MRGI_MULTIRES_TEX_COUNT), flat))
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
  os << indent
     << "Refinement: " << (this->Refinement == RefinementIllumination ? "Illumination" : "Geometry")
     << "\n";
  os << indent << "IlluminationThreshold: " << this->IlluminationThreshold << "\n";
  os << indent << "IlluminationMinimumPixels: " << this->IlluminationMinimumPixels << "\n";
  os << indent << "AreaLightDepthThreshold: " << this->AreaLightDepthThreshold << "\n";
  os << indent << "AreaLightNormalThreshold: " << this->AreaLightNormalThreshold << "\n";
  os << indent << "CoarsestSide: " << this->CoarsestSide << "\n";
  os << indent << "Levels: " << this->GetNumberOfLevels() << "\n";
}

//------------------------------------------------------------------------------
void vtkMRGIMultiresolution::GetPixelSizeCoefficients(double coefficients[2]) const
{
  coefficients[0] = this->Internal->PixelSize[0];
  coefficients[1] = this->Internal->PixelSize[1];
}

