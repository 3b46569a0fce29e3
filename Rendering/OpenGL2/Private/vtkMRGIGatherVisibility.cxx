#include "vtkMRGIGatherVisibility.h"

#include "vtkMRGIIndirectVisibility.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"

#include "mrgi_ism_atlas.h"
#include "mrgi_ism_visibility.h"

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
      error = "voxel visibility is not supported by the GPU VPL gathers (a march per VPL and "
              "receiver exceeds llvmpipe's loop budget); the C twins "
              "(mrgi_gather_full_visibility) support it";
      return false;
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
  return visibility.Mode == vtkMRGIIndirectVisibility::ISMVisibility
    ? "#define MRGI_INDIRECT_ISM 1\n"
    : "";
}

void Bind(vtkShaderProgram* program, const vtkMRGIIndirectVisibility& visibility)
{
  if (visibility.Mode != vtkMRGIIndirectVisibility::ISMVisibility)
  {
    return;
  }
  visibility.ISMAtlas->Activate();
  program->SetUniformi("mrgiISMAtlas", visibility.ISMAtlas->GetTextureUnit());
  program->SetUniformi("mrgiISMTileSize", visibility.ISMLayout.tile_size);
  program->SetUniformi("mrgiISMTilesPerRow", visibility.ISMLayout.tiles_per_row);
  program->SetUniformf("mrgiISMRelativeBias", visibility.ISMLookup.relative_bias);
  program->SetUniformf("mrgiISMTexelBias", visibility.ISMLookup.texel_bias);
  program->SetUniformi("mrgiISMPCF", visibility.ISMLookup.pcf);
}

void Unbind(const vtkMRGIIndirectVisibility& visibility)
{
  if (visibility.Mode == vtkMRGIIndirectVisibility::ISMVisibility && visibility.ISMAtlas)
  {
    visibility.ISMAtlas->Deactivate();
  }
}
}
