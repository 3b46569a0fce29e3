/**
 * @file    vtkMRGIShaderLibraries.h
 * @brief   Internal: the composition table of MRGI's GLSL. Each library
 *          (files in glsl/ without main()) and entry point (with main())
 *          declares the libraries it needs once, here; a program's source
 *          is composed from the names it uses. Not wrapped, not installed.
 *
 * Compose({"vtkMRGIVoxelMarch", "vtkMRGIGatherFS"}) is vtkMRGIVoxelBits,
 * vtkMRGIVoxelMarch, vtkMRGIVPLIrradiance, vtkMRGIGatherFS: each name
 * preceded by what it needs (depth first, in the order declared), each
 * library once. Optional parts (visibility, area-light terms) are named by
 * the caller; `#define`s that select code paths go before the composed
 * source (vtkMRGIProgramCache takes them as the program's key).
 */
#ifndef vtkMRGIShaderLibraries_h
#define vtkMRGIShaderLibraries_h

#include <initializer_list> // For std::initializer_list
#include <string>           // For std::string

namespace vtkMRGIShaderLibraries
{
/**
 * The source of `names` (file stems of glsl/, e.g. "vtkMRGIGatherFS"), each
 * preceded by its dependencies, every library once. An unknown name is a
 * programming error: it throws std::invalid_argument naming it.
 */
std::string Compose(std::initializer_list<const char*> names);

/** The libraries `name` needs, directly, comma-separated (for documentation and tests). */
std::string Dependencies(const char* name);
}

#endif
