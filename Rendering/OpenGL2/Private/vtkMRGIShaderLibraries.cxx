#include "vtkMRGIShaderLibraries.h"

#include "vtkMRGIAreaLightDiffuse.h"
#include "vtkMRGIAreaLightSpecular.h"
#include "vtkMRGIAreaSpecularFS.h"
#include "vtkMRGIGatherFS.h"
#include "vtkMRGIISMLookup.h"
#include "vtkMRGIISMProjection.h"
#include "vtkMRGIIncrementalStencilFS.h"
#include "vtkMRGIMultiresSplatVS.h"
#include "vtkMRGISpecularStencilFS.h"
#include "vtkMRGIVPLIrradiance.h"
#include "vtkMRGIVPLTree.h"
#include "vtkMRGIVarianceShadowMomentsFS.h"
#include "vtkMRGIVarianceShadowResolve.h"
#include "vtkMRGIVisibilityBits.h"
#include "vtkMRGIVisibilityPyramidFS.h"
#include "vtkMRGIVoxelBits.h"
#include "vtkMRGIVoxelMarch.h"
#include "vtkMRGIVoxelizeFS.h"

#include <cstring>
#include <stdexcept>
#include <vector>

namespace
{
struct Library
{
  const char* Name;
  const char* Source;
  // What it needs, in the order it needs them (null-terminated).
  const char* Needs[4];
};

// The one place where dependencies are declared. Libraries first, then the
// entry points that compose them.
const Library Libraries[] = {
  // Libraries.
  { "vtkMRGIVoxelBits", vtkMRGIVoxelBits, { nullptr } },
  { "vtkMRGIVoxelMarch", vtkMRGIVoxelMarch, { "vtkMRGIVoxelBits", nullptr } },
  { "vtkMRGIVisibilityBits", vtkMRGIVisibilityBits, { nullptr } },
  { "vtkMRGIISMProjection", vtkMRGIISMProjection, { nullptr } },
  { "vtkMRGIISMLookup", vtkMRGIISMLookup, { "vtkMRGIISMProjection", nullptr } },
  { "vtkMRGIVPLIrradiance", vtkMRGIVPLIrradiance, { nullptr } },
  { "vtkMRGIVPLTree", vtkMRGIVPLTree, { "vtkMRGIVPLIrradiance", nullptr } },
  // Ends with MRGI_AREA_LIGHT_DIFFUSE_DECLARED: the specular library then
  // skips the uniforms both declare.
  { "vtkMRGIAreaLightDiffuse", vtkMRGIAreaLightDiffuse, { nullptr } },
  { "vtkMRGIAreaLightSpecular", vtkMRGIAreaLightSpecular, { nullptr } },
  { "vtkMRGIVarianceShadowResolve", vtkMRGIVarianceShadowResolve, { nullptr } },
  // Entry points.
  { "vtkMRGIGatherFS", vtkMRGIGatherFS, { "vtkMRGIVPLIrradiance", nullptr } },
  { "vtkMRGIMultiresSplatVS", vtkMRGIMultiresSplatVS, { "vtkMRGIVPLIrradiance", nullptr } },
  { "vtkMRGIAreaSpecularFS", vtkMRGIAreaSpecularFS,
    { "vtkMRGIVPLIrradiance", "vtkMRGIAreaLightDiffuse", "vtkMRGIAreaLightSpecular", nullptr } },
  { "vtkMRGIVarianceShadowMomentsFS", vtkMRGIVarianceShadowMomentsFS,
    { "vtkMRGIVoxelMarch", "vtkMRGIVPLIrradiance", "vtkMRGIAreaLightSpecular", nullptr } },
  { "vtkMRGIVisibilityPyramidFS", vtkMRGIVisibilityPyramidFS,
    { "vtkMRGIVoxelMarch", "vtkMRGIVisibilityBits", nullptr } },
  { "vtkMRGIIncrementalStencilFS", vtkMRGIIncrementalStencilFS, { "vtkMRGIVisibilityBits", nullptr } },
  { "vtkMRGISpecularStencilFS", vtkMRGISpecularStencilFS, { nullptr } },
  { "vtkMRGIVoxelizeFS", vtkMRGIVoxelizeFS, { "vtkMRGIVoxelBits", nullptr } },
};

const Library& Find(const char* name)
{
  for (const Library& library : Libraries)
  {
    if (std::strcmp(library.Name, name) == 0)
    {
      return library;
    }
  }
  throw std::invalid_argument(std::string("MRGI: no GLSL library named ") + name);
}

void Append(const Library& library, std::vector<const Library*>& done, std::string& source)
{
  for (const Library* d : done)
  {
    if (d == &library)
    {
      return;
    }
  }
  for (const char* const* need = library.Needs; *need; ++need)
  {
    Append(Find(*need), done, source);
  }
  done.push_back(&library);
  source += library.Source;
}
}

//------------------------------------------------------------------------------
std::string vtkMRGIShaderLibraries::Compose(std::initializer_list<const char*> names)
{
  std::vector<const Library*> done;
  std::string source;
  for (const char* name : names)
  {
    Append(Find(name), done, source);
  }
  return source;
}

//------------------------------------------------------------------------------
std::string vtkMRGIShaderLibraries::Dependencies(const char* name)
{
  std::string list;
  for (const char* const* need = Find(name).Needs; *need; ++need)
  {
    list += (list.empty() ? "" : ", ") + std::string(*need);
  }
  return list;
}
