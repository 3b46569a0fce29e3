#include "vtk_glew.h"

#include "vtkMRGIVPLTreeTexture.h"

#include "vtkMRGIResourceStatistics.h"
#include "vtkMRGIShaderUtilities.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"

#include "mrgi_multires.h"
#include "mrgi_vpl_tree.h"
#include "mrgi_vpl_tree_gather.h"

#include <algorithm>
#include <cstring>
#include <sstream>
#include <vector>

namespace
{
// The tree texture's size, checked against GL_MAX_TEXTURE_SIZE.
bool TextureSize(const mrgi_vpl_tree* tree, int32_t& width, int32_t& height, std::string& error)
{
  mrgi_error err;
  if (!tree || mrgi_vpl_tree_texture_size(tree, &width, &height, &err) != MRGI_OK)
  {
    error = tree ? std::string("the VPL tree: ") + err.message : "no VPL tree";
    return false;
  }
  GLint maxSize = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
  if (width > maxSize || height > maxSize)
  {
    std::ostringstream message;
    message << "the VPL tree texture (" << width << " x " << height
            << " texels) exceeds GL_MAX_TEXTURE_SIZE (" << maxSize << ")";
    error = message.str();
    return false;
  }
  return true;
}
}

//------------------------------------------------------------------------------
bool vtkMRGIVPLTreeTexture::Upload(vtkOpenGLRenderWindow* window, const mrgi_vpl_tree* tree,
  vtkTextureObject* nodes, std::string& error)
{
  int32_t width = 0, height = 0;
  if (!window || !nodes)
  {
    error = "uploading the VPL tree needs a window and a texture";
    return false;
  }
  if (!TextureSize(tree, width, height, error))
  {
    return false;
  }
  // Records, then zero records up to the last row's end.
  std::vector<float> texels(static_cast<size_t>(width) * static_cast<size_t>(height) * 4, 0.0f);
  std::memcpy(texels.data(), tree->nodes, sizeof(mrgi_vpl) * static_cast<size_t>(tree->node_count));
  nodes->SetContext(window);
  vtkMRGIResourceStatistics::RecordTextureAllocation(width, height, 16);
  if (!nodes->Create2DFromRaw(static_cast<unsigned int>(width), static_cast<unsigned int>(height),
        4, VTK_FLOAT, texels.data()))
  {
    std::ostringstream message;
    message << "could not allocate the VPL tree texture (" << width << " x " << height << ")";
    error = message.str();
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkMRGIVPLTreeTexture::Check(const mrgi_vpl_tree* tree, vtkTextureObject* nodes,
  double threshold, int& roots, int& rootsPerBatch, std::string& error)
{
  std::ostringstream message;
  if (!tree || !nodes)
  {
    error = "the tree gather needs the tree texture and the C tree it holds";
    return false;
  }
  if (!tree->nodes || tree->node_count < 1)
  {
    error = "the tree gather's VPL tree was not built (no nodes)";
    return false;
  }
  if (tree->rsm_size > MRGI_VPL_TREE_GATHER_MAX_RSM_SIZE)
  {
    message << "the VPL tree's RSM is " << tree->rsm_size << " texels wide, more than "
            << "MRGI_VPL_TREE_GATHER_MAX_RSM_SIZE (" << MRGI_VPL_TREE_GATHER_MAX_RSM_SIZE << ")";
    error = message.str();
    return false;
  }
  if (!(threshold >= 0.0))
  {
    message << "the tree threshold tau is " << threshold << ": it must be >= 0";
    error = message.str();
    return false;
  }
  int32_t width = 0, height = 0;
  if (!TextureSize(tree, width, height, error))
  {
    return false;
  }
  if (nodes->GetWidth() != static_cast<unsigned int>(width) ||
    nodes->GetHeight() != static_cast<unsigned int>(height))
  {
    message << "the tree texture is " << nodes->GetWidth() << " x " << nodes->GetHeight()
            << " texels; the tree needs " << width << " x " << height
            << " (mrgi_vpl_tree_texture_size())";
    error = message.str();
    return false;
  }
  roots = mrgi_vpl_tree_root_count(tree);
  rootsPerBatch = mrgi_vpl_tree_roots_per_batch(tree);
  if (roots < 1 || rootsPerBatch < 1 || tree->layout.level_count > MRGI_MULTIRES_MAX_LEVELS)
  {
    message << "the VPL tree has " << roots << " roots, " << rootsPerBatch << " per batch, and "
            << tree->layout.level_count << " levels: it cannot be gathered";
    error = message.str();
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
void vtkMRGIVPLTreeTexture::DrawBatches(vtkShaderProgram* program, const mrgi_vpl_tree* tree,
  vtkTextureObject* nodes, double threshold, int roots, int rootsPerBatch, vtkOpenGLState* ostate,
  const std::function<void(int batch)>& draw)
{
  // mrgi_vpl_tree_gather.h section 3: one draw per batch of roots, so that
  // no invocation loops more than MRGI_VPL_TREE_MAX_LOOP_ITERATIONS times.
  int levelFirst[MRGI_MULTIRES_MAX_LEVELS] = { 0 };
  for (int i = 0; i < tree->layout.level_count; ++i)
  {
    levelFirst[i] = static_cast<int>(tree->level_first[i]);
  }
  program->SetUniformi("mrgiTreeNodes", nodes->GetTextureUnit());
  program->SetUniform1iv("mrgiTreeLevelFirst", MRGI_MULTIRES_MAX_LEVELS, levelFirst);
  program->SetUniformi("mrgiTreeLevels", tree->layout.level_count);
  program->SetUniformi("mrgiTreeSide", tree->side);
  // tau >= 1 refines nothing (B_P <= 1): +inf is sent as 2.
  program->SetUniformf("mrgiTreeThreshold", static_cast<float>(std::min(threshold, 2.0)));
  vtkOpenGLState::ScopedglBlendFuncSeparate blendFunc(ostate);
  vtkOpenGLState::ScopedglEnableDisable blend(ostate, GL_BLEND);
  ostate->vtkglDisable(GL_BLEND);
  for (int batch = 0, first = 0; first < roots; ++batch, first += rootsPerBatch)
  {
    if (batch == 1)
    {
      // Later batches add: RGB (and the counts' red) summed, alpha kept
      // (1 at gathered receivers, as the first batch wrote it).
      ostate->vtkglEnable(GL_BLEND);
      ostate->vtkglBlendEquationSeparate(GL_FUNC_ADD, GL_FUNC_ADD);
      ostate->vtkglBlendFuncSeparate(GL_ONE, GL_ONE, GL_ZERO, GL_ONE);
    }
    program->SetUniformi("mrgiTreeRootFirst", first);
    program->SetUniformi("mrgiTreeRootCount", std::min(rootsPerBatch, roots - first));
    draw(batch);
  }
}

//------------------------------------------------------------------------------
bool vtkMRGIVPLTreeTexture::ReadCounts(vtkOpenGLRenderWindow* window, vtkTextureObject* counts,
  const int region[4], double& mean, double& max)
{
  std::vector<float> rgba;
  if (!counts || !vtkMRGIShaderUtilities::ReadTextureRGBA(window, counts, rgba))
  {
    return false;
  }
  const size_t width = counts->GetWidth();
  double sum = 0.0;
  long long gathered = 0;
  max = 0.0;
  for (int y = region[1]; y < region[1] + region[3]; ++y)
  {
    for (int x = region[0]; x < region[0] + region[2]; ++x)
    {
      const float* texel =
        rgba.data() + 4 * (static_cast<size_t>(y) * width + static_cast<size_t>(x));
      if (texel[3] > 0.5f)
      {
        ++gathered;
        sum += texel[0];
        max = std::max(max, static_cast<double>(texel[0]));
      }
    }
  }
  mean = gathered > 0 ? sum / static_cast<double>(gathered) : 0.0;
  return true;
}
