/**
 * @file vtkMRGIVPLTreeTexture.h
 * @brief Internal: the GL side of the VPL-tree gather's light term
 *        (nichols-shopf-wyman-2009 3.5): the tree texture's upload and
 *        checks, the traversal's uniforms and its batches of roots, and the
 *        VPLs-per-pixel read-back. vtkMRGIGather's tree gathers use it.
 *        Layout and batching: mrgi_vpl_tree_gather.h section 3. Not
 *        wrapped, not installed.
 */
#ifndef vtkMRGIVPLTreeTexture_h
#define vtkMRGIVPLTreeTexture_h

#include <functional> // For std::function
#include <string>     // For std::string

struct mrgi_vpl_tree;
class vtkOpenGLRenderWindow;
class vtkOpenGLState;
class vtkShaderProgram;
class vtkTextureObject;

namespace vtkMRGIVPLTreeTexture
{
/**
 * Upload `tree`'s records into `nodes` (RGBA32F, mrgi_vpl_tree_texture_size(),
 * records then zero records). False, with `error` set, for a tree that was
 * not built, a texture larger than GL_MAX_TEXTURE_SIZE or a failed allocation.
 */
bool Upload(vtkOpenGLRenderWindow* window, const mrgi_vpl_tree* tree, vtkTextureObject* nodes,
  std::string& error);

/**
 * Check a tree gather's light term: a built tree from an RSM of at most
 * MRGI_VPL_TREE_GATHER_MAX_RSM_SIZE, tau >= 0 (not NaN), a texture of the
 * tree's size within GL_MAX_TEXTURE_SIZE. Gives the roots of all views and
 * the roots per batch. False, with `error` naming the problem.
 */
bool Check(const mrgi_vpl_tree* tree, vtkTextureObject* nodes, double threshold, int& roots,
  int& rootsPerBatch, std::string& error);

/**
 * Set the traversal's uniforms on `program` (vtkMRGIVPLTree.glsl; `nodes`
 * active) and call `draw(batch)` once per batch of roots: the first batch
 * writes, the later ones add RGB (and the counts) with the destination
 * alpha kept. Blending is restored afterwards.
 */
void DrawBatches(vtkShaderProgram* program, const mrgi_vpl_tree* tree, vtkTextureObject* nodes,
  double threshold, int roots, int rootsPerBatch, vtkOpenGLState* state,
  const std::function<void(int batch)>& draw);

/**
 * The VPLs-per-pixel statistic from a count target: mean and max of red
 * over the texels of `region` (x, y, w, h) whose alpha is 1 (gathered).
 * False when it cannot be read.
 */
bool ReadCounts(vtkOpenGLRenderWindow* window, vtkTextureObject* counts, const int region[4],
  double& mean, double& max);
}

#endif
