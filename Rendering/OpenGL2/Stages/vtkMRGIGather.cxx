#include "vtk_glew.h"

#include "vtkMRGIGather.h"

#include "vtkFloatArray.h"
#include "vtkMRGIFrameContext.h"
#include "vtkMRGIFullScreenStep.h"
#include "vtkMRGIGatherInternals.h"
#include "vtkMRGIGatherVisibility.h"
#include "vtkMRGIMultiresolution.h"
#include "vtkMRGIProgramCache.h"
#include "vtkMRGIStageResources.h"
#include "vtkMRGIShaderLibraries.h"
#include "vtkMRGIShaderUtilities.h"
#include "vtkMRGISpecularStencil.h"
#include "vtkMRGIVPLTreeTexture.h"
#include "vtkMRGIVisibilityPyramid.h"
#include "vtkMRGIVoxelization.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLQuadHelper.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"

#include "vtkMRGIMultiresSplatFS.h"

#include "mrgi_area_light.h"
#include "mrgi_multires.h"
#include "mrgi_voxel_march.h"
#include "mrgi_vpl_tree.h"

#include <algorithm>
#include <array>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkMRGIGather);
using Internals = vtkMRGIGatherInternals;

//------------------------------------------------------------------------------
vtkMRGIGather::vtkMRGIGather()
  : Internal(new Internals)
{
}

//------------------------------------------------------------------------------
vtkMRGIGather::~vtkMRGIGather()
{
  if (this->Internal->GL.FrameBuffer || this->Internal->FlatIrradiance || this->Internal->TreeCounts)
  {
    vtkErrorMacro("GL resources should have been freed in ReleaseGraphicsResources().");
  }
  vtkMRGIShaderUtilities::ReleaseTexture(this->Internal->FlatIrradiance, nullptr);
  vtkMRGIShaderUtilities::ReleaseTexture(this->Internal->TreeCounts, nullptr);
}

//------------------------------------------------------------------------------
void vtkMRGIGather::ReleaseGraphicsResources(vtkWindow* w)
{
  Internals& in = *this->Internal;
  in.ReleaseQueries(w);
  in.ReleaseSplats(w);
  in.GL.Release(w);
  vtkMRGIShaderUtilities::ReleaseTexture(in.FlatIrradiance, w);
  vtkMRGIShaderUtilities::ReleaseTexture(in.TreeCounts, w);
  in.TreeCountsSize[0] = in.TreeCountsSize[1] = 0;
  in.GatheredTexels.clear();
  in.ValidPixels = -1;
  in.MeanVPLs = in.MaxVPLs = -1.0;
}

//------------------------------------------------------------------------------
bool vtkMRGIGather::PrepareTarget(vtkOpenGLRenderWindow* window, const mrgi_multires_layout& layout)
{
  if (!this->Internal->Prepare(window, layout))
  {
    vtkErrorMacro("could not allocate the flattened irradiance (" << layout.total_width << " x "
                                                                 << layout.total_height << ")");
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
vtkTextureObject* vtkMRGIGather::GetIrradianceTexture() const
{
  return this->Internal->FlatIrradiance;
}

//------------------------------------------------------------------------------
bool vtkMRGIGather::GatherVPLs(const vtkMRGIFrameContext& frame, vtkMRGIMultiresolution* buffer,
  vtkTextureObject* vpls, int vplCount, const vtkMRGIIndirectVisibility& visibility)
{
  if (!vpls || vplCount < 1)
  {
    vtkErrorMacro("GatherVPLs needs at least one VPL");
    return false;
  }
  if (this->GatherMode == GatherSplatting && vtkMRGIGatherVisibility::Enabled(visibility))
  {
    vtkErrorMacro("GatherVPLs: multiresolution splatting has no visibility term; use the "
                  "stenciled gather (SetGatherModeToStenciled) with indirect visibility");
    return false;
  }
  return this->UseVisibility(visibility, vplCount) &&
    this->Run(frame, buffer, vpls, vplCount, nullptr, buffer ? buffer->GetStencilTexture() : nullptr);
}

//------------------------------------------------------------------------------
bool vtkMRGIGather::GatherVPLsIncremental(const vtkMRGIFrameContext& frame,
  vtkMRGIMultiresolution* buffer, vtkTextureObject* vpls, int vplCount,
  const vtkMRGIIndirectVisibility& visibility, vtkTextureObject* stencil,
  const std::function<bool(int level)>& beforeLevel)
{
  const int mode = this->GatherMode; // stenciled only
  this->GatherMode = GatherStenciled, this->Internal->BeforeLevel = &beforeLevel;
  const bool ok = vpls && vplCount > 0 && this->UseVisibility(visibility, vplCount) &&
    this->Run(frame, buffer, vpls, vplCount, nullptr, stencil);
  this->Internal->BeforeLevel = nullptr;
  this->GatherMode = mode;
  return ok;
}

//------------------------------------------------------------------------------
bool vtkMRGIGather::GatherFull(const vtkMRGIFrameContext& frame, vtkTextureObject* vpls,
  int vplCount, double strength, vtkTextureObject* irradiance, vtkTextureObject* indirect,
  const vtkMRGIIndirectVisibility& visibility)
{
  if (!vpls || vplCount < 1)
  {
    this->Internal->MeanVPLs = this->Internal->MaxVPLs = -1.0;
    vtkErrorMacro("the full-resolution gather needs at least one VPL");
    return false;
  }
  return this->UseVisibility(visibility, vplCount) &&
    this->RunFull(frame, vpls, vplCount, nullptr, strength, irradiance, indirect);
}

//------------------------------------------------------------------------------
bool vtkMRGIGather::UseVisibility(const vtkMRGIIndirectVisibility& visibility, int tiles)
{
  std::string error;
  this->Internal->Visibility = nullptr;
  if (!vtkMRGIGatherVisibility::Check(visibility, tiles, error))
  {
    vtkErrorMacro("indirect visibility: " << error);
    return false;
  }
  this->Internal->Visibility = vtkMRGIGatherVisibility::Enabled(visibility) ? &visibility : nullptr;
  return true;
}

//------------------------------------------------------------------------------
bool vtkMRGIGather::RunFull(const vtkMRGIFrameContext& frame, vtkTextureObject* vpls, int vplCount,
  const vtkMRGIVPLTreeTerm* tree, double strength, vtkTextureObject* irradiance,
  vtkTextureObject* indirect)
{
  // Every pixel of the viewport gathers the VPL cache or traverses the tree.
  Internals& in = *this->Internal;
  vtkOpenGLRenderWindow* window = frame.Window;
  in.MeanVPLs = in.MaxVPLs = -1.0;
  if (!window || !frame.Position || !frame.Normal || !frame.Albedo || !irradiance || !indirect)
  {
    vtkErrorMacro("the full-resolution gather needs a window, the G-buffer and its two targets");
    return false;
  }
  int roots = 0, rootsPerBatch = 0;
  if (tree && !this->CheckTree(window, *tree, roots, rootsPerBatch))
  {
    return false;
  }
  in.GL.Prepare(window);
  const bool count = tree && this->CollectStatistics;
  const vtkMRGIIndirectVisibility* vis = in.Visibility;
  const std::string defines = std::string(tree ? "#define MRGI_GATHER_TREE 1\n" : "") +
    (count ? "#define MRGI_GATHER_COUNT_TARGET 2\n" : "") +
    (vis ? vtkMRGIGatherVisibility::Defines(*vis) : "");
  vtkOpenGLQuadHelper* quad = in.GL.Programs.Ready(window, "gather.full", defines, [tree, vis] {
    const char* term = vis ? vtkMRGIGatherVisibility::Library(*vis) : "vtkMRGIVPLIrradiance";
    return tree ? vtkMRGIShaderLibraries::Compose({ term, "vtkMRGIVPLTree", "vtkMRGIGatherFS" })
                : vtkMRGIShaderLibraries::Compose({ term, "vtkMRGIGatherFS" });
  });
  if (!quad ||
    (count &&
      !vtkMRGIShaderUtilities::EnsureTexture(window, in.TreeCounts, in.TreeCountsSize, GL_RGBA32F,
        static_cast<int>(irradiance->GetWidth()), static_cast<int>(irradiance->GetHeight()))))
  {
    vtkErrorMacro("could not build the MRGI gather shader or its count target");
    return false;
  }
  vtkShaderProgram* program = quad->Program;
  bool bound = true;
  {
    vtkMRGIFullScreenStep step(window, in.GL.FrameBuffer);
    step.Target(irradiance, indirect, frame.Viewport[0], frame.Viewport[1], frame.Viewport[2],
      frame.Viewport[3]);
    if (count)
    {
      in.GL.FrameBuffer->AddColorAttachment(2, in.TreeCounts);
      vtkMRGIShaderUtilities::SelectDrawBuffers(in.GL.FrameBuffer, 3);
    }
    vtkTextureObject* light = tree ? tree->Nodes : vpls;
    frame.Position->Activate();
    frame.Normal->Activate();
    frame.Albedo->Activate();
    light->Activate();
    program->SetUniformi("mrgiPosition", frame.Position->GetTextureUnit());
    program->SetUniformi("mrgiNormal", frame.Normal->GetTextureUnit());
    program->SetUniformi("mrgiAlbedo", frame.Albedo->GetTextureUnit());
    program->SetUniformf("mrgiStrength", static_cast<float>(strength));
    program->SetUniformMatrix4x4("mrgiVCToWC", const_cast<float*>(frame.ViewToWorld));
    bound = !vis || vtkMRGIGatherVisibility::Bind(program, *vis);
    if (bound && tree)
    {
      vtkMRGIVPLTreeTexture::DrawBatches(program, tree->Tree, tree->Nodes, tree->Threshold, roots,
        rootsPerBatch, step.GetState(), [&](int) { quad->Render(); });
    }
    else if (bound)
    {
      // Voxels: the VPLs in batches that fit the loop budget, added.
      program->SetUniformi("mrgiVPLs", vpls->GetTextureUnit());
      vtkMRGIGatherVisibility::DrawVPLBatches(program, vplCount,
        vis ? vtkMRGIGatherVisibility::VPLsPerDraw(*vis, vplCount) : vplCount, step.GetState(),
        [&] { quad->Render(); });
    }
    if (vis)
    {
      vtkMRGIGatherVisibility::Unbind(*vis);
    }
    light->Deactivate();
    frame.Albedo->Deactivate();
    frame.Normal->Deactivate();
    frame.Position->Deactivate();
  }
  if (count && bound)
  {
    vtkMRGIVPLTreeTexture::ReadCounts(window, in.TreeCounts, frame.Viewport, in.MeanVPLs, in.MaxVPLs);
  }
  if (!bound)
  {
    return false;
  }
  const GLenum error = glGetError();
  if (error != GL_NO_ERROR)
  {
    vtkErrorMacro("OpenGL error " << error << " in the full-resolution gather");
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkMRGIGather::GatherAreaLight(const vtkMRGIFrameContext& frame, vtkMRGIMultiresolution* buffer,
  const vtkMRGIAreaLightTerm& term, vtkTextureObject* stencil)
{
  // The same receivers, selection and stenciled gather as the VPLs', with
  // the area-light term (nichols-penmatsa-wyman-2010 3.2: "we use the same
  // multiresolution framework").
  if (!term.Samples || term.SampleCount < 1 || !term.Light)
  {
    vtkErrorMacro("GatherAreaLight needs the light's samples and uniforms");
    return false;
  }
  return this->Run(frame, buffer, term.Samples, term.SampleCount, &term, stencil);
}

//------------------------------------------------------------------------------
bool vtkMRGIGather::Run(const vtkMRGIFrameContext& frame, vtkMRGIMultiresolution* buffer,
  vtkTextureObject* vpls, int vplCount, const vtkMRGIAreaLightTerm* term, vtkTextureObject* stencil,
  const vtkMRGIVPLTreeTerm* tree)
{
  Internals& in = *this->Internal;
  vtkOpenGLRenderWindow* window = frame.Window;
  mrgi_multires_layout layout;
  if (!window || !buffer || !stencil || !buffer->HasReceivers() || !buffer->GetLayout(&layout))
  {
    vtkErrorMacro("the gather needs a window, a stencil, and the buffer's selection and receivers of this frame");
    return false;
  }
  if (!this->PrepareTarget(window, layout))
  {
    return false;
  }
  const int levels = layout.level_count;
  in.GatheredTexels.assign(static_cast<size_t>(levels), -1);
  in.ValidPixels = -1;
  in.MeanVPLs = in.MaxVPLs = -1.0;
  bool ok = tree ? this->RunStenciledTree(frame, buffer, layout, *tree, stencil)
    : this->GatherMode == GatherSplatting && !term
    ? this->RunSplatting(frame, buffer, layout, vpls, vplCount)
    : this->RunStenciled(frame, buffer, layout, vpls, vplCount, term, stencil);
  if (ok && this->CollectStatistics)
  {
    // The coarsest receivers carry their pixel counts: their sum is the
    // number of valid pixels, the work of the full-resolution gather.
    // With one level, the validity bits of the level-0 mipmap count them.
    std::vector<float> coarsest;
    if (levels > 1 &&
      vtkMRGIShaderUtilities::ReadTextureRGBA(window, buffer->GetReceiverTexture(levels - 1, 0), coarsest))
    {
      double sum = 0.0;
      for (size_t k = 3; k < coarsest.size(); k += 4)
      {
        sum += coarsest[k];
      }
      in.ValidPixels = static_cast<long long>(sum + 0.5);
    }
    else if (levels == 1 &&
      vtkMRGIShaderUtilities::ReadTextureRGBA(
        window, buffer->GetMipmapTexture(0, MRGI_MULTIRES_TEX_DEPTH), coarsest))
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
bool vtkMRGIGather::RunStenciled(const vtkMRGIFrameContext& frame, vtkMRGIMultiresolution* buffer,
  const mrgi_multires_layout& layout, vtkTextureObject* vpls, int vplCount,
  const vtkMRGIAreaLightTerm* term, vtkTextureObject* stencil)
{
  // The stenciled gather, one draw per level into its rectangle of the
  // flattened layout (early stencil culling skips the texels not selected).
  // With statistics on, an occlusion query per level counts the texels that
  // passed the stencil, i.e. the texels gathered.
  Internals& in = *this->Internal;
  vtkOpenGLRenderWindow* window = frame.Window;
  const int levels = layout.level_count;
  const int finest = buffer->GetFinestGatherLevel();
  using vtkMRGIShaderUtilities::ScopedStage;
  const bool area = term != nullptr;
  const bool masked = area && term->Masks != nullptr;
  const bool visibility = area && !masked && term->Voxels != nullptr;
  const vtkMRGIIndirectVisibility* vis = area ? nullptr : in.Visibility; // the VPLs' visibility
  ScopedStage gatherStep(frame.Timer, area ? "gather.samples" : "gather.vpls");
  const std::string defines = std::string("#define MRGI_GATHER_IRRADIANCE_ONLY 1\n") +
    (masked ? "#define MRGI_AREA_VISIBILITY_MASKS 1\n" : "") +
    (visibility ? "#define MRGI_AREA_VISIBILITY 1\n" : "") +
    (area ? "#define MRGI_GATHER_AREA_LIGHT 1\n" : "") +
    (vis ? vtkMRGIGatherVisibility::Defines(*vis) : "");
  vtkOpenGLQuadHelper* quad = in.GL.Programs.Ready(window, "gather", defines, [&] {
    return visibility ? vtkMRGIShaderLibraries::Compose(
                          { "vtkMRGIVoxelMarch", "vtkMRGIAreaLightDiffuse", "vtkMRGIGatherFS" })
      : area ? vtkMRGIShaderLibraries::Compose({ "vtkMRGIAreaLightDiffuse", "vtkMRGIGatherFS" })
      : vis
      ? vtkMRGIShaderLibraries::Compose({ vtkMRGIGatherVisibility::Library(*vis), "vtkMRGIGatherFS" })
             : vtkMRGIShaderLibraries::Compose({ "vtkMRGIGatherFS" });
  });
  vtkShaderProgram* gather = quad ? quad->Program : nullptr;
  if (!gather)
  {
    return false;
  }
  if (this->CollectStatistics)
  {
    in.AllocateQueries(window, levels);
  }
  vtkMRGIFullScreenStep steps(window, in.GL.FrameBuffer);
  vtkOpenGLState* ostate = steps.GetState();
  steps.Target(in.FlatIrradiance, nullptr, 0, 0, layout.total_width, layout.total_height);
  steps.BeginStencilRead(stencil);
  vpls->Activate();
  if (area)
  {
    const mrgi_area_light_uniforms& light = *term->Light;
    gather->SetUniformi("mrgiAreaSamples", vpls->GetTextureUnit());
    // mrgiAreaSampleFirst/Count: set per draw below.
    gather->SetUniform3f("mrgiAreaCenter", light.center);
    gather->SetUniform3f("mrgiAreaNormal", light.normal);
    gather->SetUniform3fv("mrgiAreaCorners", 4, light.corners);
    gather->SetUniformi("mrgiAreaTwoSided", light.two_sided);
    if (visibility)
    {
      double worldToView[16];
      if (!term->Voxels->GetLastWorldToView(worldToView) || !term->Voxels->SetMarchUniforms(gather))
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
    if (vis && !vtkMRGIGatherVisibility::Bind(gather, *vis))
    {
      vpls->Deactivate();
      return false;
    }
  }
  gather->SetUniformMatrix4x4("mrgiVCToWC", const_cast<float*>(frame.ViewToWorld));
  // Marching every sample in one fragment can run past the total loop
  // iterations a fragment may take on llvmpipe (gallivm stops every loop of
  // an invocation after 65535 iterations in all, silently: samples went
  // missing, measured), and long draws trip GPU watchdogs elsewhere: with
  // visibility, the samples are gathered in batches whose marches fit the
  // budget, each batch one draw added to the previous ones (RGB summed,
  // alpha kept at 1). The sums change order only by batch.
  // The VPLs with voxel visibility likewise (vtkMRGIGatherVisibility::VPLsPerDraw()).
  const int batch = visibility ? mrgi_voxel_samples_per_batch(term->Voxels->GetMarchStepBound())
    : vis                      ? vtkMRGIGatherVisibility::VPLsPerDraw(*vis, vplCount)
                               : std::max(vplCount, 1);
  const char* firstName = area ? "mrgiAreaSampleFirst" : "mrgiVPLFirst";
  const char* countName = area ? "mrgiAreaSampleCount" : "mrgiVPLCount";
  vtkOpenGLState::ScopedglBlendFuncSeparate blendFunc(ostate);
  gather->SetUniformi(firstName, 0);
  gather->SetUniformi(countName, std::min(batch, vplCount));
  if (vplCount > batch)
  {
    ostate->vtkglEnable(GL_BLEND);
    ostate->vtkglBlendFuncSeparate(GL_ONE, GL_ONE, GL_ONE, GL_ONE);
    ostate->vtkglBlendEquationSeparate(GL_FUNC_ADD, GL_MAX);
  }
  bool stepped = true;
  for (int k = finest; k < levels && stepped; ++k)
  {
    // Coarse to fine with a step between the levels (GatherVPLsIncremental()).
    const int i = in.BeforeLevel ? levels - 1 - (k - finest) : k;
    if (in.BeforeLevel && !(stepped = (*in.BeforeLevel)(i) &&
                              window->GetShaderCache()->ReadyShaderProgram(gather) != nullptr))
      break;
    if (in.BeforeLevel)
      steps.BeginStencilRead(stencil, false);
    const std::array<vtkTextureObject*, 2> receivers = buffer->BindReceivers(gather, i);
    std::vector<vtkTextureObject*> maskTextures;
    if (masked)
    {
      // Missing words (fewer than 384 samples) read the first texture:
      // their bits are never asked for. One texture activated once.
      vtkTextureObject* first = term->Masks->GetMaskTexture(i, 0);
      first->Activate();
      maskTextures.push_back(first);
      for (int w = 0; w < 4; ++w)
      {
        vtkTextureObject* t = term->Masks->GetMaskTexture(i, w);
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
      gather->SetUniformi(firstName, first);
      gather->SetUniformi(countName, std::min(batch, vplCount - first));
      quad->Render();
    }
    if (vplCount > batch)
    {
      gather->SetUniformi(firstName, 0);
      gather->SetUniformi(countName, batch);
    }
    for (vtkTextureObject* t : maskTextures)
    {
      t->Deactivate();
    }
    receivers[1]->Deactivate();
    receivers[0]->Deactivate();
  }
  vpls->Deactivate();
  if (vis)
  {
    vtkMRGIGatherVisibility::Unbind(*vis);
  }
  if (vplCount > batch)
  {
    ostate->vtkglBlendEquationSeparate(GL_FUNC_ADD, GL_FUNC_ADD);
  }
  if (visibility)
  {
    term->Voxels->GetVoxelTexture()->Deactivate();
  }
  steps.EndStencilRead();
  if (this->CollectStatistics && stepped)
  {
    in.ReadQueries(finest, levels);
  }
  return stepped;
}

//------------------------------------------------------------------------------
bool vtkMRGIGather::RunSplatting(const vtkMRGIFrameContext& frame, vtkMRGIMultiresolution* buffer,
  const mrgi_multires_layout& layout, vtkTextureObject* vpls, int vplCount)
{
  vtkOpenGLRenderWindow* window = frame.Window;
  const int levels = layout.level_count;
  const int finest = buffer->GetFinestGatherLevel();
  // Multiresolution splatting (nichols-wyman-2009 section 3.4), the method
  // the stenciled gather replaced (nichols-shopf-wyman-2009 section 3.2.2,
  // table 1): every VPL draws one point per selected texel ("subsplat"),
  // additive blending sums them.
  Internals& in = *this->Internal;
  using vtkMRGIShaderUtilities::ScopedStage;
  // 1. The subsplat list: the selected texels, level by level. The paper
  // streams it out on the GPU; here the selection is read back, which is
  // its own timed step ("gather.subsplats") so that the splatting itself
  // ("gather.vpls") compares with the stenciled gather's step of that name.
  {
    ScopedStage listStep(frame.Timer, "gather.subsplats");
    std::vector<float> selection;
    if (!vtkMRGIShaderUtilities::ReadTextureRGBA(window, buffer->GetSelectionTexture(), selection))
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
  ScopedStage splatStep(frame.Timer, "gather.vpls");
  static const std::string vertexShader = "//VTK::System::Dec\n" + vtkMRGIShaderUtilities::Defines() +
    vtkMRGIShaderLibraries::Compose({ "vtkMRGIMultiresSplatVS" });
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
  vtkMRGIFullScreenStep steps(window, in.GL.FrameBuffer);
  vtkOpenGLState* ostate = steps.GetState();
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
  splat->SetUniformMatrix4x4("mrgiVCToWC", const_cast<float*>(frame.ViewToWorld));
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
    const std::array<vtkTextureObject*, 2> receivers = buffer->BindReceivers(splat, i);
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
bool vtkMRGIGather::GatherSpecular(const vtkMRGIFrameContext& frame, vtkMRGIMultiresolution* buffer,
  vtkMRGISpecularStencil* stencil, vtkShaderProgram* program,
  const std::function<bool(int level)>& draw)
{
  // NPW10 3.2.1: "we separate diffuse and Phong components into separate
  // gather passes": the specular gather at the texels of the specular
  // stencil, one draw per level (early stencil culling).
  Internals& in = *this->Internal;
  vtkOpenGLRenderWindow* window = frame.Window;
  mrgi_multires_layout layout;
  if (!window || !program || !buffer || !stencil || !buffer->HasReceivers() ||
    !buffer->GetLayout(&layout) || !stencil->GetStencilTexture() ||
    !stencil->GetMaterialTexture(buffer->GetFinestGatherLevel()))
  {
    vtkErrorMacro("GatherSpecular needs a program, the buffer's receivers and its specular stencil of this frame");
    return false;
  }
  if (!this->PrepareTarget(window, layout))
  {
    return false;
  }
  const int levels = layout.level_count;
  const int finest = buffer->GetFinestGatherLevel();
  vtkMRGIShaderUtilities::ScopedStage step(frame.Timer, "gather.specular");
  bool ok = true;
  {
    vtkMRGIFullScreenStep steps(window, in.GL.FrameBuffer);
    vtkOpenGLState* ostate = steps.GetState();
    vtkOpenGLState::ScopedglBlendFuncSeparate blendFunc(ostate);
    steps.Target(in.FlatIrradiance, nullptr, 0, 0, layout.total_width, layout.total_height);
    steps.BeginStencilRead(stencil->GetStencilTexture());
    for (int i = finest; i < levels && ok; ++i)
    {
      const std::array<vtkTextureObject*, 2> receivers = buffer->BindReceivers(program, i);
      vtkTextureObject* material = stencil->GetMaterialTexture(i);
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
    steps.EndStencilRead();
  }
  return ok && glGetError() == GL_NO_ERROR;
}

//------------------------------------------------------------------------------
bool vtkMRGIGather::ReadIrradiance(vtkRenderWindow* window, vtkFloatArray* irradiance)
{
  vtkOpenGLRenderWindow* renWin = vtkOpenGLRenderWindow::SafeDownCast(window);
  Internals& in = *this->Internal;
  std::vector<float> rgba;
  if (!renWin || !irradiance || !in.FlatIrradiance ||
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
vtkIdType vtkMRGIGather::GetNumberOfGatheredTexels(int level) const
{
  const Internals& in = *this->Internal;
  if (level < 0 || static_cast<size_t>(level) >= in.GatheredTexels.size())
  {
    return -1;
  }
  return static_cast<vtkIdType>(in.GatheredTexels[static_cast<size_t>(level)]);
}

//------------------------------------------------------------------------------
vtkIdType vtkMRGIGather::GetNumberOfValidPixels() const
{
  return static_cast<vtkIdType>(this->Internal->ValidPixels);
}

//------------------------------------------------------------------------------
double vtkMRGIGather::GetGatherWorkFraction() const
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
double vtkMRGIGather::GetMeanVPLsPerPixel() const
{
  return this->Internal->MeanVPLs;
}

//------------------------------------------------------------------------------
double vtkMRGIGather::GetMaxVPLsPerPixel() const
{
  return this->Internal->MaxVPLs;
}

//------------------------------------------------------------------------------
void vtkMRGIGather::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "GatherMode: " << (this->GatherMode == GatherSplatting ? "Splatting" : "Stenciled") << "\n";
  os << indent << "CollectStatistics: " << (this->CollectStatistics ? "On" : "Off") << "\n";
}
