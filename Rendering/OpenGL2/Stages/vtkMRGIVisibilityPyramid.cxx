#include "vtk_glew.h"

#include "vtkMRGIVisibilityPyramid.h"

#include "vtkMRGIMultiresolution.h"
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
#include "vtkTypeUInt32Array.h"

#include "vtkMRGIVisibilityBits.h"
#include "vtkMRGIVisibilityPyramidFS.h"

#include "mrgi_area_light.h"
#include "mrgi_multires.h"
#include "mrgi_visibility_pyramid.h"
#include "mrgi_voxel_march.h"

#include <algorithm>
#include <array>
#include <map>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkMRGIVisibilityPyramid);

namespace
{
// Mask targets per pass: 4 x 128 samples (see the class notes).
constexpr int MaxTargets = 4;

// Shader stages (vtkMRGIVisibilityPyramidFS.glsl's MRGI_VIS_STAGE).
enum Stage
{
  StageCompute = 0,
  StageCombine = 1,
  StageStatistics = 2,
  StageDecide = 3,
  StageMarch = 4,
  StageMark = 5,
  StageCopies = 6
};

// Timer sub-steps of "visibility.pyramid", summed over the levels.
const char* StageTimerName(int stage)
{
  switch (stage)
  {
    case StageCompute:
      return "visibility.compute";
    case StageCombine:
      return "visibility.combine";
    case StageStatistics:
      return "visibility.statistics";
    case StageDecide:
      return "visibility.decide";
    case StageMarch:
      return "visibility.march";
    case StageMark:
      return "visibility.mark";
    default:
      return "visibility.copies";
  }
}

// Levels with both sides below this are marched as copies side by side, one
// copy per sample range (vtkMRGIVisibilityPyramidFS.glsl, stages 4-6).
constexpr int CopyLevelSide = 128;
// Copies are padded to this width, so that no SIMD group of fragments
// straddles two copies (it would march both ranges: past the loop budget).
constexpr int CopyAlign = 16;
// Widest copy strip.
constexpr int MaxCopyWidth = 8192;

vtkTextureObject* MakeUIntTexture(vtkOpenGLRenderWindow* window, int w, int h)
{
  return vtkMRGIShaderUtilities::NewTexture(window, GL_RGBA32UI, w, h);
}


// What vtkOpenGLState does not track: the logic op.
struct ScopedLogicOp
{
  ScopedLogicOp()
  {
    this->Enabled = glIsEnabled(GL_COLOR_LOGIC_OP) == GL_TRUE;
    glGetIntegerv(GL_LOGIC_OP_MODE, &this->Mode);
  }
  ~ScopedLogicOp()
  {
    if (this->Enabled)
    {
      glEnable(GL_COLOR_LOGIC_OP);
    }
    else
    {
      glDisable(GL_COLOR_LOGIC_OP);
    }
    glLogicOp(static_cast<GLenum>(this->Mode));
  }
  bool Enabled = false;
  GLint Mode = GL_COPY;
};
}

struct vtkMRGIVisibilityPyramid::Internals
{
  vtkOpenGLFramebufferObject* FrameBuffer = nullptr;
  // Per level: mask textures (level size) and the statistics texture.
  std::vector<std::array<vtkTextureObject*, MaxTargets>> Masks;
  std::vector<vtkTextureObject*> Stats;
  // Stage 0's masks with interleaving, or stage 3's todo bits without
  // (level-0 size, reused by every level).
  std::array<vtkTextureObject*, MaxTargets> Quarters{};
  // Stencil of the texels with bits to march (level-0 size, every level).
  vtkTextureObject* DepthStencil = nullptr;
  // Small levels' copies: masks and stencil (CopyWidth x CopyHeight).
  std::array<vtkTextureObject*, MaxTargets> CopyMasks{};
  vtkTextureObject* CopyStencil = nullptr;
  // 1 x 1 RGBA32UI for the integer samplers a stage does not read (every
  // sampler on a unit holding a texture of its type; the voxels are a 3D
  // texture, and a stage's own targets must not be bound).
  vtkTextureObject* Spare = nullptr;
  int CopyWidth = 0, CopyHeight = 0, CopyTargets = 0;
  mrgi_multires_layout Layout{};
  int Levels = 0, Samples = 0, Words = 0, Targets = 0, Threshold = 0, Draws = 0;
  bool Valid = false;
  // Programs by (stage, words): stage 2 is the statistics.
  std::map<std::pair<int, int>, vtkOpenGLQuadHelper*> Quads;
  std::vector<vtkIdType> Rays, Computed, Inherited;

  void ReleaseTextures(vtkWindow* w)
  {
    for (auto& level : this->Masks)
    {
      for (auto*& t : level)
      {
        vtkMRGIShaderUtilities::ReleaseTexture(t, w);
      }
    }
    this->Masks.clear();
    for (auto*& t : this->Stats)
    {
      vtkMRGIShaderUtilities::ReleaseTexture(t, w);
    }
    this->Stats.clear();
    for (auto*& t : this->Quarters)
    {
      vtkMRGIShaderUtilities::ReleaseTexture(t, w);
    }
    vtkMRGIShaderUtilities::ReleaseTexture(this->DepthStencil, w);
    vtkMRGIShaderUtilities::ReleaseTexture(this->Spare, w);
    this->ReleaseCopies(w);
    this->Valid = false;
  }

  void ReleaseCopies(vtkWindow* w)
  {
    for (auto*& t : this->CopyMasks)
    {
      vtkMRGIShaderUtilities::ReleaseTexture(t, w);
    }
    vtkMRGIShaderUtilities::ReleaseTexture(this->CopyStencil, w);
    this->CopyWidth = this->CopyHeight = this->CopyTargets = 0;
  }
};

//------------------------------------------------------------------------------
vtkMRGIVisibilityPyramid::vtkMRGIVisibilityPyramid()
  : Internal(new Internals)
{
  this->RefineFraction = MRGI_VOXEL_DEFAULT_REFINE_FRACTION;
}

vtkMRGIVisibilityPyramid::~vtkMRGIVisibilityPyramid()
{
  this->ReleaseGraphicsResources(nullptr);
}

int vtkMRGIVisibilityPyramid::GetMaximumNumberOfSamples()
{
  return std::min(MaxTargets * 128, static_cast<int>(MRGI_VOXEL_MAX_SAMPLES));
}

//------------------------------------------------------------------------------
void vtkMRGIVisibilityPyramid::ReleaseGraphicsResources(vtkWindow* w)
{
  Internals& in = *this->Internal;
  in.ReleaseTextures(w);
  for (auto& q : in.Quads)
  {
    if (w && q.second)
    {
      q.second->ReleaseGraphicsResources(w);
    }
    delete q.second;
  }
  in.Quads.clear();
  if (in.FrameBuffer)
  {
    if (w)
    {
      in.FrameBuffer->ReleaseGraphicsResources(w);
    }
    in.FrameBuffer->Delete();
    in.FrameBuffer = nullptr;
  }
}

//------------------------------------------------------------------------------
bool vtkMRGIVisibilityPyramid::Update(vtkOpenGLRenderWindow* window,
  vtkMRGIMultiresolution* multires, vtkMRGIVoxelization* voxels, vtkTextureObject* samples,
  int sampleCount, bool twoSided, const float worldToView[16], vtkRenderTimerLog* timer)
{
  Internals& in = *this->Internal;
  in.Valid = false;
  in.Rays.clear();
  in.Computed.clear();
  in.Inherited.clear();
  mrgi_multires_layout layout;
  if (!window || !multires || !voxels || !samples || !worldToView ||
    !multires->GetLayout(&layout) || !multires->GetReceiverTexture(0, 0) || !voxels->GetVoxelTexture())
  {
    vtkErrorMacro("Update needs a window, a multiresolution with receivers built "
                  "(Update() + BuildReceivers()), a voxelization and the light samples");
    return false;
  }
  if (sampleCount < 1 || sampleCount > GetMaximumNumberOfSamples())
  {
    vtkErrorMacro("Update: " << sampleCount << " light samples, outside 1.."
                             << GetMaximumNumberOfSamples());
    return false;
  }
  const int threshold =
    mrgi_voxel_refine_threshold(static_cast<float>(this->RefineFraction), sampleCount);
  if (threshold < 0)
  {
    vtkErrorMacro("Update: refine fraction " << this->RefineFraction << " is outside [0, 1]");
    return false;
  }
  const int levels = layout.level_count;
  const int words = mrgi_voxel_mask_words(sampleCount);
  const int targets = (words + 3) / 4;
  window->MakeCurrent();
  while (glGetError() != GL_NO_ERROR)
  {
    // errors of earlier passes are not this pass's
  }

  // Textures: (re)allocate on a new layout or mask size.
  const bool sameShape = !in.Masks.empty() && in.Targets == targets && in.Levels == levels &&
    in.Layout.width == layout.width && in.Layout.height == layout.height &&
    in.Layout.total_width == layout.total_width;
  if (!sameShape)
  {
    in.ReleaseTextures(window);
    in.Masks.resize(static_cast<size_t>(levels));
    in.Stats.assign(static_cast<size_t>(levels), nullptr);
    bool ok = true;
    for (int i = 0; i < levels && ok; ++i)
    {
      auto& level = in.Masks[static_cast<size_t>(i)];
      level.fill(nullptr);
      for (int k = 0; k < targets && ok; ++k)
      {
        level[static_cast<size_t>(k)] =
          MakeUIntTexture(window, layout.level_width[i], layout.level_height[i]);
        ok = level[static_cast<size_t>(k)] != nullptr;
      }
      in.Stats[static_cast<size_t>(i)] =
        ok ? MakeUIntTexture(window, layout.level_width[i], layout.level_height[i]) : nullptr;
      ok = ok && in.Stats[static_cast<size_t>(i)];
    }
    for (int k = 0; k < targets && ok; ++k)
    {
      in.Quarters[static_cast<size_t>(k)] = MakeUIntTexture(window, layout.width, layout.height);
      ok = in.Quarters[static_cast<size_t>(k)] != nullptr;
    }
    if (ok)
    {
      in.DepthStencil = vtkMRGIShaderUtilities::NewDepthStencil(window, layout.width, layout.height);
      ok = in.DepthStencil != nullptr;
    }
    if (ok)
    {
      in.Spare = MakeUIntTexture(window, 1, 1);
      ok = in.Spare != nullptr;
    }
    if (!ok)
    {
      in.ReleaseTextures(window);
      vtkErrorMacro("Update: could not allocate the RGBA32UI mask textures");
      return false;
    }
  }
  in.Layout = layout;
  in.Levels = levels;
  in.Samples = sampleCount;
  in.Words = words;
  in.Targets = targets;
  in.Threshold = threshold;
  in.Draws = 0;
  if (!in.FrameBuffer)
  {
    in.FrameBuffer = vtkOpenGLFramebufferObject::New();
    in.FrameBuffer->SetContext(window);
  }

  // Programs: one per (stage, words).
  auto ready = [&](int stage) -> vtkOpenGLQuadHelper* {
    vtkOpenGLQuadHelper*& quad = in.Quads[std::make_pair(stage, words)];
    if (!quad)
    {
      const int outputs = (stage == StageStatistics || stage == StageMark) ? 1
        : stage == StageDecide                                       ? 2 * targets
                                                                     : targets;
      // The outputs are uvec4 (declared by the shader); naming gl_FragData[k]
      // here makes VTK bind fragOutputK to draw buffer k.
      std::string body = "// outputs:";
      for (int k = 0; k < outputs; ++k)
      {
        body += " gl_FragData[" + std::to_string(k) + "]";
      }
      body += "\n#define MRGI_VIS_STAGE " + std::to_string(stage) + "\n#define MRGI_VIS_WORDS " +
        std::to_string(words) + "\n#define MRGI_VIS_TARGETS " + std::to_string(targets) +
        "\n#define MRGI_VIS_OUTPUTS " + std::to_string(outputs) + "\n" +
        vtkMRGIShaderLibraries::Compose({ "vtkMRGIVisibilityPyramidFS" });
      quad = new vtkOpenGLQuadHelper(window,
        vtkOpenGLRenderUtilities::GetFullScreenQuadVertexShader().c_str(),
        vtkMRGIShaderUtilities::FullScreenShader(body.c_str()).c_str(), "");
    }
    window->GetShaderCache()->ReadyShaderProgram(quad->Program);
    return (quad->Program && quad->Program->GetCompiled()) ? quad : nullptr;
  };

  using vtkMRGIShaderUtilities::ScopedStage;
  ScopedStage step(timer, "visibility.pyramid");
  vtkOpenGLState* ostate = window->GetState();
  vtkOpenGLState::ScopedglEnableDisable blend(ostate, GL_BLEND), depth(ostate, GL_DEPTH_TEST),
    scissor(ostate, GL_SCISSOR_TEST), stencil(ostate, GL_STENCIL_TEST);
  vtkOpenGLState::ScopedglViewport viewport(ostate);
  ScopedLogicOp logicOp;
  ostate->vtkglDisable(GL_BLEND);
  ostate->vtkglDisable(GL_DEPTH_TEST);
  ostate->vtkglDisable(GL_SCISSOR_TEST);
  ostate->vtkglDisable(GL_STENCIL_TEST);
  glLogicOp(GL_OR);
  vtkOpenGLFramebufferObject* fbo = in.FrameBuffer;
  fbo->SaveCurrentBindingsAndBuffers();
  fbo->Bind();

  vtkTextureObject* selection = multires->GetSelectionTexture();
  const bool refine = this->RefineSelected && selection;
  const bool interleave = this->Interleave;
  // Samples per draw within llvmpipe's loop budget
  // (mrgi_voxel_samples_per_batch()). The budget counts the iterations of a
  // SIMD group of fragments, i.e. the union of its fragments' loops: a draw
  // may march at most perBatch samples in lockstep. Interleaved stage 0
  // visits only the own phase, in lockstep over the 2x2 phases: ranges of
  // 4 perBatch. Stage 1 visits each phase q for every fragment (those that
  // take q from a block texel skip its marches): perBatch.
  const int perBatch = mrgi_voxel_samples_per_batch(voxels->GetMarchStepBound());
  const int range0 = interleave ? 4 * perBatch : perBatch;
  const int range1 = perBatch;

  bool ok = true;
  for (int i = levels - 1; i >= 0 && ok; --i)
  {
    const bool naive = !this->Incremental || i == levels - 1;
    const int lw = layout.level_width[i], lh = layout.level_height[i];
    int receiverOffset[2];
    multires->GetReceiverOffset(i, receiverOffset);
    receiverOffset[0] += layout.level_offset[i];
    vtkTextureObject* position = multires->GetReceiverTexture(i, 0);
    vtkTextureObject* normal = multires->GetReceiverTexture(i, 1);
    vtkTextureObject* parentPosition = naive ? position : multires->GetReceiverTexture(i + 1, 0);
    // The same-surface guard reads the parent level's normals too.
    vtkTextureObject* parentNormal = naive ? normal : multires->GetReceiverTexture(i + 1, 1);
    int parentOffset[2] = { 0, 0 };
    if (!naive)
    {
      multires->GetReceiverOffset(i + 1, parentOffset);
      parentOffset[0] += layout.level_offset[i + 1];
    }
    const auto& parentMasks = in.Masks[static_cast<size_t>(naive ? i : i + 1)];
    if (!position || !normal || !parentPosition || !parentNormal)
    {
      vtkErrorMacro("Update: the receivers of level " << i << " are missing");
      ok = false;
      break;
    }

    // stage: 0 compute, 1 combine, 2 statistics.
    // copies > 0: stages 4 and 5 over that many copies of the level (one
    // draw, into CopyMasks), stage 6 ORs them into `out`.
    const int stride = (lw + CopyAlign - 1) / CopyAlign * CopyAlign;
    auto run = [&](int stage, const std::array<vtkTextureObject*, MaxTargets>& out, int range,
                 int copies = 0) -> bool {
      ScopedStage kind(timer, StageTimerName(stage));
      vtkOpenGLQuadHelper* quad = ready(stage);
      if (!quad)
      {
        vtkErrorMacro("Update: the visibility shader (stage " << stage << ") did not compile");
        return false;
      }
      vtkShaderProgram* p = quad->Program;
      if (!voxels->SetMarchUniforms(p))
      {
        return false;
      }
      // Stage 3 writes the masks and the todo bits; stage 5 writes only the
      // stencil (its colour goes to the statistics texture, which stage 2
      // rewrites).
      const bool single = stage == StageStatistics || stage == StageMark;
      const int outputs = single ? 1 : stage == StageDecide ? 2 * targets : targets;
      const bool onCopies = copies > 0 && (stage == StageMark || stage == StageMarch);
      fbo->RemoveColorAttachments(2 * MaxTargets);
      for (int k = 0; k < outputs; ++k)
      {
        const size_t kk = static_cast<size_t>(k);
        fbo->AddColorAttachment(static_cast<unsigned int>(k),
          onCopies ? in.CopyMasks[kk]
            : single ? in.Stats[static_cast<size_t>(i)]
                     : (k < targets ? out[kk] : in.Quarters[kk - static_cast<size_t>(targets)]));
      }
      vtkMRGIShaderUtilities::SelectDrawBuffers(fbo, static_cast<unsigned int>(outputs));
      ostate->vtkglViewport(0, 0, onCopies ? copies * stride : lw, lh);
      if (onCopies && stage == StageMarch)
      {
        // The texels the stencil culls keep what an earlier level wrote:
        // start from zeros (clears ignore the stencil test).
        const GLuint zero[4] = { 0, 0, 0, 0 };
        for (int k = 0; k < outputs; ++k)
        {
          glClearBufferuiv(GL_COLOR, k, zero);
        }
      }
      // Every sampler on a unit holding a texture of its type (unused ones too).
      // The voxels too: SetMarchUniforms() activates them only when the
      // program marches (not in the statistics stage); activating again
      // keeps the unit, one Deactivate() frees it.
      std::vector<vtkTextureObject*> active{ voxels->GetVoxelTexture() };
      voxels->GetVoxelTexture()->Activate();
      auto bind = [&](const char* name, vtkTextureObject* t) {
        if (std::find(active.begin(), active.end(), t) == active.end())
        {
          t->Activate();
          active.push_back(t);
        }
        p->SetUniformi(name, t->GetTextureUnit());
      };
      bind("mrgiVisPosition", position);
      bind("mrgiVisNormal", normal);
      bind("mrgiVisParentPosition", parentPosition);
      bind("mrgiVisParentNormal", parentNormal);
      bind("mrgiVisSamples", samples);
      bind("mrgiVisSelection", selection ? selection : samples);
      // Unused integer samplers read the spare texel (never a texture
      // attached now: no feedback loop).
      vtkTextureObject* spare = in.Spare;
      for (int k = 0; k < MaxTargets; ++k)
      {
        const size_t kk = static_cast<size_t>(std::min(k, targets - 1));
        bind(("mrgiVisParent" + std::to_string(k)).c_str(), naive ? spare : parentMasks[kk]);
        const bool quarters = stage == StageCombine || stage == StageMarch || stage == StageMark;
        bind(("mrgiVisQuarter" + std::to_string(k)).c_str(),
          stage == StageCopies ? in.CopyMasks[kk] : quarters ? in.Quarters[kk] : spare);
      }
      const int levelSize[2] = { lw, lh };
      const int parentSize[2] = { naive ? lw : layout.level_width[i + 1],
        naive ? lh : layout.level_height[i + 1] };
      p->SetUniform2i("mrgiVisReceiverOffset", receiverOffset);
      p->SetUniformi("mrgiVisGBuffer", i == 0 ? 1 : 0);
      p->SetUniformi("mrgiVisLevel", i);
      p->SetUniform2i("mrgiVisLevelSize", levelSize);
      p->SetUniform2i("mrgiVisParentOffset", parentOffset);
      p->SetUniform2i("mrgiVisParentSize", parentSize);
      p->SetUniformi("mrgiVisNaive", naive ? 1 : 0);
      p->SetUniformi("mrgiVisThreshold", threshold);
      p->SetUniformi("mrgiVisMetric", this->Metric);
      p->SetUniformi("mrgiVisInterleave", interleave ? 1 : 0);
      p->SetUniformi("mrgiVisRefine", refine ? 1 : 0);
      p->SetUniformi("mrgiVisLevelOffset", layout.level_offset[i]);
      p->SetUniformMatrix4x4("mrgiVisWCToVC", const_cast<float*>(worldToView));
      p->SetUniformi("mrgiVisTwoSided", twoSided ? 1 : 0);
      p->SetUniformi("mrgiVisSampleCount", sampleCount);
      p->SetUniformi("mrgiVisCopyStride", copies > 0 ? stride : 0);
      p->SetUniformi("mrgiVisCopyRange", range0);
      p->SetUniformi("mrgiVisCopies", copies);
      // Batches: the first draw replaces, the others OR into it; stage 4's
      // all OR into stage 3's masks.
      if ((stage == StageMarch && !onCopies) || stage == StageCopies)
      {
        glEnable(GL_COLOR_LOGIC_OP);
      }
      else
      {
        glDisable(GL_COLOR_LOGIC_OP);
      }
      for (int first = 0; first < sampleCount; first += onCopies ? sampleCount : range)
      {
        p->SetUniformi("mrgiVisFirst", first);
        p->SetUniformi("mrgiVisLast", std::min(first + range, sampleCount));
        quad->Render();
        ++in.Draws;
        glEnable(GL_COLOR_LOGIC_OP);
      }
      glDisable(GL_COLOR_LOGIC_OP);
      for (vtkTextureObject* t : active)
      {
        t->Deactivate();
      }
      return true;
    };

    const auto& finalMasks = in.Masks[static_cast<size_t>(i)];
    if (interleave)
    {
      ok = run(StageCompute, in.Quarters, range0) && run(StageCombine, finalMasks, range1);
    }
    else
    {
      // Decide (masks + todo bits), mark the texels with bits left in the
      // stencil, march only there (early stencil culling skips the rest):
      // the same masks as stage 0 alone, without paying the decision once
      // per batch nor the marches' SIMD groups for texels that march
      // nothing (mostly INHERITED ones).
      ok = run(StageDecide, finalMasks, sampleCount);
      const int batches = (sampleCount + range0 - 1) / range0;
      const int copies = batches > 1 && lw < CopyLevelSide && lh < CopyLevelSide &&
          batches * stride <= MaxCopyWidth
        ? batches
        : 0;
      if (ok && copies > 0 &&
        (in.CopyWidth < copies * stride || in.CopyHeight < lh || in.CopyTargets != targets))
      {
        // Sized for the largest small level of this layout.
        in.ReleaseCopies(window);
        in.CopyWidth = std::min(batches * (CopyLevelSide + CopyAlign), MaxCopyWidth);
        in.CopyHeight = CopyLevelSide;
        in.CopyTargets = targets;
        for (int k = 0; k < targets && ok; ++k)
        {
          in.CopyMasks[static_cast<size_t>(k)] = MakeUIntTexture(window, in.CopyWidth, in.CopyHeight);
          ok = in.CopyMasks[static_cast<size_t>(k)] != nullptr;
        }
        in.CopyStencil = vtkMRGIShaderUtilities::NewDepthStencil(window, in.CopyWidth, in.CopyHeight);
        ok = ok && in.CopyStencil != nullptr;
        if (!ok)
        {
          in.ReleaseCopies(window);
          vtkErrorMacro("Update: could not allocate the copies of the small levels");
        }
      }
      if (ok)
      {
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_TEXTURE_2D,
          (copies > 0 ? in.CopyStencil : in.DepthStencil)->GetHandle(), 0);
        ostate->vtkglEnable(GL_STENCIL_TEST);
        ostate->vtkglStencilMask(0xFF);
        glClearStencil(0);
        ostate->vtkglClear(GL_STENCIL_BUFFER_BIT);
        ostate->vtkglStencilFunc(GL_ALWAYS, 1, 0xFF);
        ostate->vtkglStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
        ok = run(StageMark, finalMasks, sampleCount, copies);
        ostate->vtkglStencilMask(0x00);
        ostate->vtkglStencilFunc(GL_EQUAL, 1, 0xFF);
        ostate->vtkglStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
        ok = ok && run(StageMarch, finalMasks, range0, copies);
        ostate->vtkglStencilMask(0xFF);
        ostate->vtkglStencilFunc(GL_ALWAYS, 0, 0xFF);
        ostate->vtkglDisable(GL_STENCIL_TEST);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_TEXTURE_2D, 0, 0);
        ok = ok && (copies == 0 || run(StageCopies, finalMasks, sampleCount, copies));
      }
    }
    if (ok && this->CollectStatistics)
    {
      // One draw: the range is every sample (nothing is marched).
      ok = run(StageStatistics, finalMasks, sampleCount);
    }
  }
  fbo->RemoveColorAttachments(2 * MaxTargets);
  fbo->UnBind();
  fbo->RestorePreviousBindingsAndBuffers();
  if (!ok)
  {
    vtkErrorMacro("Update: the visibility passes failed");
    return false;
  }
  const GLenum error = glGetError();
  if (error != GL_NO_ERROR)
  {
    vtkErrorMacro("Update: OpenGL error 0x" << std::hex << error << std::dec);
    return false;
  }
  in.Valid = true;

  if (this->CollectStatistics)
  {
    // Sum the statistics textures (rays, computed, inherited, receiver).
    in.Rays.assign(static_cast<size_t>(levels), 0);
    in.Computed.assign(static_cast<size_t>(levels), 0);
    in.Inherited.assign(static_cast<size_t>(levels), 0);
    ostate->PushReadFramebufferBinding();
    fbo->Bind(GL_READ_FRAMEBUFFER);
    for (int i = 0; i < levels; ++i)
    {
      const int lw = layout.level_width[i], lh = layout.level_height[i];
      std::vector<GLuint> words4(static_cast<size_t>(lw) * lh * 4);
      fbo->AddColorAttachment(0, in.Stats[static_cast<size_t>(i)]);
      fbo->ActivateReadBuffer(0);
      glPixelStorei(GL_PACK_ALIGNMENT, 4);
      glReadPixels(0, 0, lw, lh, GL_RGBA_INTEGER, GL_UNSIGNED_INT, words4.data());
      for (size_t k = 0; k < words4.size(); k += 4)
      {
        in.Rays[static_cast<size_t>(i)] += words4[k];
        in.Computed[static_cast<size_t>(i)] += words4[k + 1];
        in.Inherited[static_cast<size_t>(i)] += words4[k + 2];
      }
    }
    fbo->RemoveColorAttachments(1);
    fbo->UnBind(GL_READ_FRAMEBUFFER);
    ostate->PopReadFramebufferBinding();
  }
  return glGetError() == GL_NO_ERROR;
}

//------------------------------------------------------------------------------
bool vtkMRGIVisibilityPyramid::ReadMasks(vtkRenderWindow* window, vtkTypeUInt32Array* masks)
{
  Internals& in = *this->Internal;
  vtkOpenGLRenderWindow* renWin = vtkOpenGLRenderWindow::SafeDownCast(window);
  if (!renWin || !masks || !in.Valid)
  {
    vtkErrorMacro("ReadMasks: needs an OpenGL window, an array and a successful Update()");
    return false;
  }
  const mrgi_multires_layout& layout = in.Layout;
  const size_t texels = static_cast<size_t>(mrgi_multires_texel_count(&layout));
  const int words = in.Words;
  masks->SetNumberOfComponents(words);
  masks->SetNumberOfTuples(static_cast<vtkIdType>(texels));
  std::fill_n(masks->GetPointer(0), texels * static_cast<size_t>(words), 0u);
  renWin->MakeCurrent();
  vtkOpenGLState* ostate = renWin->GetState();
  ostate->PushReadFramebufferBinding();
  vtkOpenGLFramebufferObject* fbo = in.FrameBuffer;
  fbo->Bind(GL_READ_FRAMEBUFFER);
  for (int i = 0; i < in.Levels; ++i)
  {
    const int lw = layout.level_width[i], lh = layout.level_height[i];
    std::vector<GLuint> words4(static_cast<size_t>(lw) * lh * 4);
    for (int k = 0; k < in.Targets; ++k)
    {
      fbo->AddColorAttachment(0, in.Masks[static_cast<size_t>(i)][static_cast<size_t>(k)]);
      fbo->ActivateReadBuffer(0);
      glPixelStorei(GL_PACK_ALIGNMENT, 4);
      glReadPixels(0, 0, lw, lh, GL_RGBA_INTEGER, GL_UNSIGNED_INT, words4.data());
      for (int y = 0; y < lh; ++y)
      {
        for (int x = 0; x < lw; ++x)
        {
          uint32_t* out = masks->GetPointer(0) + mrgi_multires_index(&layout, i, x, y) * static_cast<size_t>(words);
          for (int c = 0; c < 4 && 4 * k + c < words; ++c)
          {
            out[4 * k + c] = words4[(static_cast<size_t>(y) * lw + x) * 4 + static_cast<size_t>(c)];
          }
        }
      }
    }
  }
  fbo->RemoveColorAttachments(1);
  fbo->UnBind(GL_READ_FRAMEBUFFER);
  ostate->PopReadFramebufferBinding();
  const GLenum error = glGetError();
  if (error != GL_NO_ERROR)
  {
    vtkErrorMacro("ReadMasks: OpenGL error 0x" << std::hex << error << std::dec);
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
int vtkMRGIVisibilityPyramid::GetNumberOfLevels() const
{
  return this->Internal->Valid ? this->Internal->Levels : 0;
}
int vtkMRGIVisibilityPyramid::GetNumberOfSamples() const
{
  return this->Internal->Valid ? this->Internal->Samples : 0;
}
int vtkMRGIVisibilityPyramid::GetNumberOfMaskWords() const
{
  return this->Internal->Valid ? this->Internal->Words : 0;
}
int vtkMRGIVisibilityPyramid::GetNumberOfMaskTextures() const
{
  return this->Internal->Valid ? this->Internal->Targets : 0;
}
int vtkMRGIVisibilityPyramid::GetThreshold() const
{
  return this->Internal->Threshold;
}
int vtkMRGIVisibilityPyramid::GetNumberOfDraws() const
{
  return this->Internal->Draws;
}

vtkTextureObject* vtkMRGIVisibilityPyramid::GetMaskTexture(int level, int word4) const
{
  const Internals& in = *this->Internal;
  if (!in.Valid || level < 0 || level >= in.Levels || word4 < 0 || word4 >= in.Targets)
  {
    return nullptr;
  }
  return in.Masks[static_cast<size_t>(level)][static_cast<size_t>(word4)];
}

namespace
{
vtkIdType At(const std::vector<vtkIdType>& v, int level)
{
  return level >= 0 && static_cast<size_t>(level) < v.size() ? v[static_cast<size_t>(level)] : -1;
}
}

vtkIdType vtkMRGIVisibilityPyramid::GetNumberOfRays(int level) const
{
  return At(this->Internal->Rays, level);
}
vtkIdType vtkMRGIVisibilityPyramid::GetNumberOfComputedTexels(int level) const
{
  return At(this->Internal->Computed, level);
}
vtkIdType vtkMRGIVisibilityPyramid::GetNumberOfInheritedTexels(int level) const
{
  return At(this->Internal->Inherited, level);
}
vtkIdType vtkMRGIVisibilityPyramid::GetTotalNumberOfRays() const
{
  const Internals& in = *this->Internal;
  if (in.Rays.empty())
  {
    return -1;
  }
  vtkIdType total = 0;
  for (vtkIdType r : in.Rays)
  {
    total += r;
  }
  return total;
}
vtkIdType vtkMRGIVisibilityPyramid::GetNumberOfNaiveRays() const
{
  const Internals& in = *this->Internal;
  if (in.Computed.empty())
  {
    return -1;
  }
  return static_cast<vtkIdType>(in.Samples) * (in.Computed[0] + in.Inherited[0]);
}

//------------------------------------------------------------------------------
void vtkMRGIVisibilityPyramid::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Incremental: " << (this->Incremental ? "On" : "Off") << "\n";
  os << indent << "RefineFraction: " << this->RefineFraction << "\n";
  os << indent << "Metric: " << (this->Metric == MetricCountSpread ? "CountSpread" : "Disagree") << "\n";
  os << indent << "Interleave: " << (this->Interleave ? "On" : "Off") << "\n";
  os << indent << "RefineSelected: " << (this->RefineSelected ? "On" : "Off") << "\n";
  os << indent << "CollectStatistics: " << (this->CollectStatistics ? "On" : "Off") << "\n";
  os << indent << "Levels: " << this->GetNumberOfLevels() << "\n";
  os << indent << "Samples: " << this->GetNumberOfSamples() << "\n";
}
