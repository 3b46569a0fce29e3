/**
 * @file vtkMRGIGatherVisibility.h
 * @brief Internal: the GL side of the VPL gathers' visibility term
 *        (vtkMRGIIndirectVisibility): its checks, the program defines and
 *        the libraries it adds, and its uniforms and texture.
 *        vtkMRGIGather's cache, full, stenciled and tree gathers use it.
 *        Lookup: mrgi_ism_visibility.h (C twin), vtkMRGIISMLookup.glsl.
 *        Not wrapped, not installed.
 */
#ifndef vtkMRGIGatherVisibility_h
#define vtkMRGIGatherVisibility_h

#include <string> // For std::string

struct vtkMRGIIndirectVisibility;
class vtkShaderProgram;

namespace vtkMRGIGatherVisibility
{
/**
 * Check `visibility` for a gather of `tiles` VPLs (tree: roots). False,
 * with `error` naming the problem: an unknown mode; ISM: atlas missing, a
 * layout whose VPL count is not `tiles` or that mrgi_ism_atlas_layout_make()
 * would not make, an atlas texture of another size, bad lookup parameters;
 * voxels: not supported by the GPU VPL gathers (the C twins support them).
 */
bool Check(const vtkMRGIIndirectVisibility& visibility, int tiles, std::string& error);

/** True when the gather must add a visibility term (mode not NoVisibility). */
bool Enabled(const vtkMRGIIndirectVisibility& visibility);

/** The program's extra defines ("" for none): MRGI_INDIRECT_ISM. */
std::string Defines(const vtkMRGIIndirectVisibility& visibility);

/** Activate the atlas and set the lookup's uniforms (ISM; nothing for none). */
void Bind(vtkShaderProgram* program, const vtkMRGIIndirectVisibility& visibility);

/** Deactivate what Bind() activated. */
void Unbind(const vtkMRGIIndirectVisibility& visibility);
}

#endif
