/**
 * @file vtkMRGIGatherVisibility.h
 * @brief Internal: the GL side of the VPL gathers' visibility term
 *        (vtkMRGIIndirectVisibility): its checks, the program defines and
 *        the libraries it adds, and its uniforms and texture.
 *        vtkMRGIGather's cache, full, stenciled and tree gathers use it.
 *        ISM lookup: mrgi_ism_visibility.h (C twin), vtkMRGIISMLookup.glsl;
 *        voxels: mrgi_voxel_march.h (C twin), vtkMRGIVoxelMarch.glsl.
 *        Not wrapped, not installed.
 */
#ifndef vtkMRGIGatherVisibility_h
#define vtkMRGIGatherVisibility_h

#include <functional> // For std::function
#include <string>     // For std::string

struct mrgi_vpl_tree;
struct vtkMRGIIndirectVisibility;
class vtkOpenGLState;
class vtkShaderProgram;

namespace vtkMRGIGatherVisibility
{
/**
 * Check `visibility` for a gather of `tiles` VPLs (tree: roots). False,
 * with `error` naming the problem: an unknown mode; ISM: atlas missing, a
 * layout whose VPL count is not `tiles` or that mrgi_ism_atlas_layout_make()
 * would not make, an atlas texture of another size, bad lookup parameters;
 * voxels: no voxelization, or none that succeeded.
 */
bool Check(const vtkMRGIIndirectVisibility& visibility, int tiles, std::string& error);

/** True when the gather must add a visibility term (mode not NoVisibility). */
bool Enabled(const vtkMRGIIndirectVisibility& visibility);

/** The program's extra defines ("" for none): MRGI_INDIRECT_ISM or MRGI_INDIRECT_VOXELS. */
std::string Defines(const vtkMRGIIndirectVisibility& visibility);

/** The GLSL library the term needs: vtkMRGIISMLookup or vtkMRGIVoxelMarch. */
const char* Library(const vtkMRGIIndirectVisibility& visibility);

/**
 * Activate the atlas or the voxels and set the term's uniforms (nothing
 * for none). False (voxels: SetMarchUniforms() failed, it says why) with
 * nothing left active.
 */
bool Bind(vtkShaderProgram* program, const vtkMRGIIndirectVisibility& visibility);

/**
 * VPLs one draw of the cache gathers may sum: `vplCount` (all) but with
 * voxels, mrgi_voxel_samples_per_batch() of the march's step cap: one march
 * per VPL, and llvmpipe stops an invocation's loops silently past 65,535
 * iterations in all (mrgi_voxel_march.h). The draws add (blending).
 */
int VPLsPerDraw(const vtkMRGIIndirectVisibility& visibility, int vplCount);

/**
 * The cache gather's draws (vtkMRGIGatherFS.glsl): `draw` once per batch of
 * `perDraw` VPLs, mrgiVPLFirst and mrgiVPLCount set; later batches add
 * (RGB summed, alpha kept), as the tree's root batches
 * (vtkMRGIVPLTreeTexture::DrawBatches()). Blending restored after.
 */
void DrawVPLBatches(vtkShaderProgram* program, int vplCount, int perDraw, vtkOpenGLState* ostate,
  const std::function<void()>& draw);

/**
 * Roots one draw of the tree gathers may traverse: `rootsPerBatch` (the
 * traversal's own budget, mrgi_vpl_tree_roots_per_batch()) but with voxels
 * at most mrgi_voxel_samples_per_batch() / (nodes a root may use: 1 for
 * tau >= 1, else its subtree's (4^(L+1) - 1) / 3). 0, with `error`, when
 * one root's subtree alone needs more marches than the budget allows.
 */
int RootsPerDraw(const vtkMRGIIndirectVisibility& visibility, const mrgi_vpl_tree* tree,
  double threshold, int rootsPerBatch, std::string& error);

/** Deactivate what Bind() activated. */
void Unbind(const vtkMRGIIndirectVisibility& visibility);
}

#endif
