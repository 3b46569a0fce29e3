#include "vtk_glew.h"

#include "vtkMRGIGatherVisibility.h"

#include "vtkMRGIIndirectVisibility.h"
#include "vtkShaderProgram.h"
#include "vtkMRGIVoxelization.h"
#include "vtkOpenGLState.h"
#include "vtkTextureObject.h"

#include "mrgi_ism_atlas.h"
#include "mrgi_ism_visibility.h"
#include "mrgi_voxel_march.h"
#include "mrgi_vpl_tree.h"

#include <algorithm>
#include <sstream>

namespace vtkMRGIGatherVisibility
{
bool Check(const vtkMRGIIndirectVisibility& visibility, int tiles, std::string& error)
{
  switch (visibility.Mode)
  {
    case vtkMRGIIndirectVisibility::NoVisibility:
      return true;
    case vtkMRGIIndirectVisibility::VoxelVisibility:
    {
      double worldToView[16];
      if (!visibility.Voxels || !visibility.Voxels->GetVoxelTexture() ||
        !visibility.Voxels->GetLastWorldToView(worldToView))
      {
        error = visibility.Voxels
          ? "voxel visibility: the voxelization has no voxels (Voxelize() first, this frame)"
          : "voxel visibility: the voxelization is missing (vtkMRGIIndirectVisibility::Voxels)";
        return false;
      }
      return true;
    }
    case vtkMRGIIndirectVisibility::ISMVisibility:
      break;
    default:
    {
      std::ostringstream os;
      os << "indirect visibility mode " << visibility.Mode << " is not NoVisibility, "
         << "ISMVisibility or VoxelVisibility";
      error = os.str();
      return false;
    }
  }
  const mrgi_ism_atlas_layout& layout = visibility.ISMLayout;
  if (!visibility.ISMAtlas)
  {
    error = "ISM visibility: the ISM atlas is missing (run vtkMRGIImperfectShadowMaps first)";
    return false;
  }
  std::ostringstream os;
  mrgi_ism_atlas_layout expected;
  mrgi_error err;
  if (layout.vpl_count != tiles)
  {
    os << "ISM visibility: the atlas layout has " << layout.vpl_count << " tiles but the gather has "
       << tiles << " VPLs (tree: roots); rebuild the ISMs for this frame's VPLs";
  }
  else if (mrgi_ism_atlas_layout_make(layout.vpl_count, layout.tile_size, &expected, &err) !=
      MRGI_OK ||
    expected.width != layout.width || expected.height != layout.height ||
    expected.tiles_per_row != layout.tiles_per_row)
  {
    os << "ISM visibility: the atlas layout (" << layout.vpl_count << " tiles of "
       << layout.tile_size << ") is not what mrgi_ism_atlas_layout_make() makes";
  }
  else if (visibility.ISMAtlas->GetWidth() != static_cast<unsigned int>(layout.width) ||
    visibility.ISMAtlas->GetHeight() != static_cast<unsigned int>(layout.height) ||
    visibility.ISMAtlas->GetComponents() != 1)
  {
    os << "ISM visibility: the atlas texture is " << visibility.ISMAtlas->GetWidth() << "x"
       << visibility.ISMAtlas->GetHeight() << " with " << visibility.ISMAtlas->GetComponents()
       << " components; its layout needs " << layout.width << "x" << layout.height << " R32F";
  }
  else if (mrgi_ism_lookup_params_validate(&visibility.ISMLookup, &err) != MRGI_OK)
  {
    os << err.message;
  }
  error = os.str();
  return error.empty();
}

bool Enabled(const vtkMRGIIndirectVisibility& visibility)
{
  return visibility.Mode != vtkMRGIIndirectVisibility::NoVisibility;
}

std::string Defines(const vtkMRGIIndirectVisibility& visibility)
{
  switch (visibility.Mode)
  {
    case vtkMRGIIndirectVisibility::ISMVisibility:
      return "#define MRGI_INDIRECT_ISM 1\n";
    case vtkMRGIIndirectVisibility::VoxelVisibility:
      return "#define MRGI_INDIRECT_VOXELS 1\n";
    default:
      return "";
  }
}

const char* Library(const vtkMRGIIndirectVisibility& visibility)
{
  return visibility.Mode == vtkMRGIIndirectVisibility::VoxelVisibility ? "vtkMRGIVoxelMarch"
                                                                        : "vtkMRGIISMLookup";
}

bool Bind(vtkShaderProgram* program, const vtkMRGIIndirectVisibility& visibility)
{
  if (visibility.Mode == vtkMRGIIndirectVisibility::VoxelVisibility)
  {
    // The march runs in the voxelized camera's eye space (NPW10 3.3.1).
    double worldToView[16];
    if (!visibility.Voxels->GetLastWorldToView(worldToView) ||
      !visibility.Voxels->SetMarchUniforms(program))
    {
      return false;
    }
    float m[16];
    std::copy(worldToView, worldToView + 16, m);
    program->SetUniformMatrix4x4("mrgiWCToVC", m);
    return true;
  }
  if (visibility.Mode != vtkMRGIIndirectVisibility::ISMVisibility)
  {
    return true;
  }
  visibility.ISMAtlas->Activate();
  program->SetUniformi("mrgiISMAtlas", visibility.ISMAtlas->GetTextureUnit());
  program->SetUniformi("mrgiISMTileSize", visibility.ISMLayout.tile_size);
  program->SetUniformi("mrgiISMTilesPerRow", visibility.ISMLayout.tiles_per_row);
  program->SetUniformf("mrgiISMRelativeBias", visibility.ISMLookup.relative_bias);
  program->SetUniformf("mrgiISMTexelBias", visibility.ISMLookup.texel_bias);
  program->SetUniformi("mrgiISMPCF", visibility.ISMLookup.pcf);
  program->SetUniformf("mrgiISMMaxTexelAngle", visibility.ISMLookup.max_texel_angle);
  return true;
}

void Unbind(const vtkMRGIIndirectVisibility& visibility)
{
  if (visibility.Mode == vtkMRGIIndirectVisibility::ISMVisibility && visibility.ISMAtlas)
  {
    visibility.ISMAtlas->Deactivate();
  }
  if (visibility.Mode == vtkMRGIIndirectVisibility::VoxelVisibility && visibility.Voxels &&
    visibility.Voxels->GetVoxelTexture())
  {
    visibility.Voxels->GetVoxelTexture()->Deactivate();
  }
}

int VPLsPerDraw(const vtkMRGIIndirectVisibility& visibility, int vplCount)
{
  const int all = std::max(vplCount, 1);
  return visibility.Mode == vtkMRGIIndirectVisibility::VoxelVisibility
    ? std::min(all, mrgi_voxel_samples_per_batch(visibility.Voxels->GetMarchStepBound()))
    : all;
}

void DrawVPLBatches(vtkShaderProgram* program, int vplCount, int perDraw, vtkOpenGLState* ostate,
  const std::function<void()>& draw)
{
  perDraw = std::max(perDraw, 1);
  vtkOpenGLState::ScopedglBlendFuncSeparate blendFunc(ostate);
  vtkOpenGLState::ScopedglEnableDisable blend(ostate, GL_BLEND);
  ostate->vtkglDisable(GL_BLEND);
  for (int first = 0; first < vplCount; first += perDraw)
  {
    if (first == perDraw)
    {
      ostate->vtkglEnable(GL_BLEND);
      ostate->vtkglBlendEquationSeparate(GL_FUNC_ADD, GL_FUNC_ADD);
      ostate->vtkglBlendFuncSeparate(GL_ONE, GL_ONE, GL_ZERO, GL_ONE);
    }
    program->SetUniformi("mrgiVPLFirst", first);
    program->SetUniformi("mrgiVPLCount", std::min(perDraw, vplCount - first));
    draw();
  }
}

int RootsPerDraw(const vtkMRGIIndirectVisibility& visibility, const mrgi_vpl_tree* tree,
  double threshold, int rootsPerBatch, std::string& error)
{
  if (visibility.Mode != vtkMRGIIndirectVisibility::VoxelVisibility)
  {
    return rootsPerBatch;
  }
  // Nodes one root may use as VPLs, each one march (mrgi_vpl_tree_gather.h
  // section 4): its subtree, or itself alone when tau >= 1 refines nothing.
  const int levels = tree->layout.level_count;
  const long long nodes = threshold >= 1.0 ? 1 : ((1LL << (2 * levels)) - 1) / 3;
  const int marches = mrgi_voxel_samples_per_batch(visibility.Voxels->GetMarchStepBound());
  if (nodes > marches)
  {
    std::ostringstream os;
    os << "voxel visibility: a root's subtree of " << nodes << " nodes (" << levels
       << " tree levels) may need " << nodes << " marches, more than the " << marches
       << " one draw allows at " << visibility.Voxels->GetMarchStepBound()
       << " march steps (llvmpipe's loop budget); use fewer tree levels, fewer steps or "
          "tau >= 1";
    error = os.str();
    return 0;
  }
  return std::max(1, std::min(rootsPerBatch, static_cast<int>(marches / nodes)));
}
}
