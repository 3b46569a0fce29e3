// vtkMRGIGather's VPL-tree gathers (nichols-shopf-wyman-2009 3.5): the
// tree as the light term of the stenciled multiresolution gather (also
// coarse to fine under the illumination rule) and of the full-resolution
// gather. The class is documented in vtkMRGIGather.h.
#include "vtk_glew.h"

#include "vtkMRGIGather.h"

#include "vtkMRGIFrameContext.h"
#include "vtkMRGIFullScreenStep.h"
#include "vtkMRGIGatherInternals.h"
#include "vtkMRGIGatherVisibility.h"
#include "vtkMRGIMultiresolution.h"
#include "vtkMRGIProgramCache.h"
#include "vtkMRGIShaderLibraries.h"
#include "vtkMRGIShaderUtilities.h"
#include "vtkMRGIVPLTreeTexture.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLQuadHelper.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"

#include "mrgi_multires.h"
#include "mrgi_vpl_tree.h"

#include <array>
#include <string>

using Internals = vtkMRGIGatherInternals;

//------------------------------------------------------------------------------
bool vtkMRGIGather::GatherVPLTree(const vtkMRGIFrameContext& frame, vtkMRGIMultiresolution* buffer,
  const vtkMRGIVPLTreeTerm& tree, const vtkMRGIIndirectVisibility& visibility)
{
  return this->UseVisibility(visibility, mrgi_vpl_tree_root_count(tree.Tree)) && this->Run(frame, buffer, nullptr, 0, nullptr, buffer ? buffer->GetStencilTexture() : nullptr,
    &tree);
}

//------------------------------------------------------------------------------
bool vtkMRGIGather::GatherVPLTreeIncremental(const vtkMRGIFrameContext& frame,
  vtkMRGIMultiresolution* buffer, const vtkMRGIVPLTreeTerm& tree,
  const vtkMRGIIndirectVisibility& visibility, vtkTextureObject* stencil,
  const std::function<bool(int level)>& beforeLevel)
{
  this->Internal->BeforeLevel = &beforeLevel;
  const bool ok = this->UseVisibility(visibility, mrgi_vpl_tree_root_count(tree.Tree)) &&
    this->Run(frame, buffer, nullptr, 0, nullptr, stencil, &tree);
  this->Internal->BeforeLevel = nullptr;
  return ok;
}

//------------------------------------------------------------------------------
bool vtkMRGIGather::GatherFullTree(const vtkMRGIFrameContext& frame, const vtkMRGIVPLTreeTerm& tree,
  double strength, vtkTextureObject* irradiance, vtkTextureObject* indirect,
  const vtkMRGIIndirectVisibility& visibility)
{
  return this->UseVisibility(visibility, mrgi_vpl_tree_root_count(tree.Tree)) && this->RunFull(frame, nullptr, 0, &tree, strength, irradiance, indirect);
}

//------------------------------------------------------------------------------
bool vtkMRGIGather::UploadVPLTree(
  vtkOpenGLRenderWindow* window, const mrgi_vpl_tree* tree, vtkTextureObject* nodes)
{
  std::string error;
  if (!vtkMRGIVPLTreeTexture::Upload(window, tree, nodes, error))
  {
    vtkGenericWarningMacro("vtkMRGIGather::UploadVPLTree: " << error);
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkMRGIGather::CheckTree(
  vtkOpenGLRenderWindow* window, const vtkMRGIVPLTreeTerm& tree, int& roots, int& rootsPerBatch)
{
  std::string error;
  if (!window)
  {
    error = "the tree gather needs a window";
  }
  if (!window ||
    !vtkMRGIVPLTreeTexture::Check(tree.Tree, tree.Nodes, tree.Threshold, roots, rootsPerBatch, error) ||
    (this->Internal->Visibility &&
      (rootsPerBatch = vtkMRGIGatherVisibility::RootsPerDraw(
         *this->Internal->Visibility, tree.Tree, tree.Threshold, rootsPerBatch, error)) < 1))
  {
    vtkErrorMacro(<< error);
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkMRGIGather::RunStenciledTree(const vtkMRGIFrameContext& frame, vtkMRGIMultiresolution* buffer,
  const mrgi_multires_layout& layout, const vtkMRGIVPLTreeTerm& tree, vtkTextureObject* stencil)
{
  // The stenciled gather (one draw per level, early stencil culling) with
  // the tree as the light term: per level, one draw per batch of roots.
  Internals& in = *this->Internal;
  vtkOpenGLRenderWindow* window = frame.Window;
  int roots = 0, rootsPerBatch = 0;
  if (!this->CheckTree(window, tree, roots, rootsPerBatch))
  {
    return false;
  }
  const bool count = this->CollectStatistics;
  const int levels = layout.level_count;
  const int finest = buffer->GetFinestGatherLevel();
  vtkMRGIShaderUtilities::ScopedStage gatherStep(frame.Timer, "gather.tree");
  const vtkMRGIIndirectVisibility* vis = in.Visibility;
  const std::string defines = std::string("#define MRGI_GATHER_IRRADIANCE_ONLY 1\n"
                                          "#define MRGI_GATHER_TREE 1\n") +
    (count ? "#define MRGI_GATHER_COUNT_TARGET 1\n" : "") +
    (vis ? vtkMRGIGatherVisibility::Defines(*vis) : "");
  vtkOpenGLQuadHelper* quad = in.GL.Programs.Ready(window, "gather.tree", defines, [vis] {
    return vtkMRGIShaderLibraries::Compose(
      { vis ? vtkMRGIGatherVisibility::Library(*vis) : "vtkMRGIVPLIrradiance", "vtkMRGIVPLTree",
        "vtkMRGIGatherFS" });
  });
  vtkShaderProgram* gather = quad ? quad->Program : nullptr;
  if (!gather ||
    (count &&
      !vtkMRGIShaderUtilities::EnsureTexture(window, in.TreeCounts, in.TreeCountsSize, GL_RGBA32F,
        layout.total_width, layout.total_height)))
  {
    return false;
  }
  if (this->CollectStatistics)
  {
    in.AllocateQueries(window, levels);
  }
  {
    vtkMRGIFullScreenStep steps(window, in.GL.FrameBuffer);
    vtkOpenGLState* ostate = steps.GetState();
    steps.Target(in.FlatIrradiance, count ? in.TreeCounts : nullptr, 0, 0, layout.total_width,
      layout.total_height);
    steps.BeginStencilRead(stencil);
    tree.Nodes->Activate();
    gather->SetUniformMatrix4x4("mrgiVCToWC", const_cast<float*>(frame.ViewToWorld));
    if (vis && !vtkMRGIGatherVisibility::Bind(gather, *vis))
    {
      tree.Nodes->Deactivate();
      steps.EndStencilRead();
      return false;
    }
    bool stepped = true;
    for (int k = finest; k < levels && stepped; ++k)
    {
      // Coarse to fine with a step between the levels (GatherVPLTreeIncremental()).
      const int i = in.BeforeLevel ? levels - 1 - (k - finest) : k;
      if (in.BeforeLevel)
      {
        if (!(stepped = (*in.BeforeLevel)(i) &&
                window->GetShaderCache()->ReadyShaderProgram(gather) != nullptr))
        {
          break;
        }
        steps.BeginStencilRead(stencil, false);
      }
      const std::array<vtkTextureObject*, 2> receivers = buffer->BindReceivers(gather, i);
      ostate->vtkglViewport(layout.level_offset[i], 0, layout.level_width[i], layout.level_height[i]);
      // The first batch's query counts the texels gathered at this level.
      const auto draw = [&](int batch) {
        const bool query = this->CollectStatistics && batch == 0;
        if (query)
        {
          glBeginQuery(GL_SAMPLES_PASSED, in.Queries[static_cast<size_t>(i)]);
        }
        quad->Render();
        if (query)
        {
          glEndQuery(GL_SAMPLES_PASSED);
        }
      };
      vtkMRGIVPLTreeTexture::DrawBatches(
        gather, tree.Tree, tree.Nodes, tree.Threshold, roots, rootsPerBatch, ostate, draw);
      receivers[1]->Deactivate();
      receivers[0]->Deactivate();
    }
    if (vis)
    {
      vtkMRGIGatherVisibility::Unbind(*vis);
    }
    tree.Nodes->Deactivate();
    steps.EndStencilRead();
    if (!stepped)
    {
      return false;
    }
  }
  if (this->CollectStatistics)
  {
    in.ReadQueries(finest, levels);
    const int region[4] = { 0, 0, layout.total_width, layout.total_height };
    vtkMRGIVPLTreeTexture::ReadCounts(window, in.TreeCounts, region, in.MeanVPLs, in.MaxVPLs);
  }
  return true;
}

