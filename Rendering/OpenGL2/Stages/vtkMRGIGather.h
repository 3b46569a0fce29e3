/**
 * @class   vtkMRGIGather
 * @brief   The stenciled multiresolution gather (nichols-shopf-wyman-2009
 *          3.2.2): every selected texel of a vtkMRGIMultiresolution buffer
 *          gathers the VPLs, or one area light's samples, into a flattened
 *          irradiance buffer.
 *
 * The texels and their receivers come from the buffer (Update() and
 * BuildReceivers() done this frame); which stencil selects the texels is an
 * argument (the buffer's selection, the incremental stencil of
 * vtkMRGIIncrementalStencil, or the specular stencil of
 * vtkMRGISpecularStencil), and so is the light term: VPLs (the VPL cache
 * texture) or an area light (vtkMRGIAreaLightTerm). One draw per level into
 * that level's rectangle of the flattened layout; early stencil culling
 * skips the texels not selected.
 *
 * C twins: the VPL gather is mrgi_gather_full() (mrgi_gather.h) on the same
 * receivers, the area-light term mrgi_area_light_diffuse()
 * (mrgi_area_light.h), its visibility mrgi_voxel_march() (naive) or the
 * incremental masks (mrgi_visibility_pyramid.h). Shaders:
 * vtkMRGIGatherFS.glsl with vtkMRGIVPLIrradiance.glsl and
 * vtkMRGIAreaLightDiffuse.glsl; multiresolution splatting
 * vtkMRGIMultiresSplat{VS,FS}.glsl.
 *
 * The VPL-tree gather (nichols-shopf-wyman-2009 3.5, GatherVPLTree() and
 * GatherFullTree()): the light term is the light-space VPL tree of
 * mrgi_vpl_tree.h in one texture (vtkMRGIVPLTreeTerm); every receiver walks
 * it from its roots and refines a node where its form-factor bound exceeds
 * tau. C twin mrgi_vpl_tree_gather() (mrgi_vpl_tree_gather.h, whose section
 * 3 fixes the texture layout and the batches of roots); shader
 * vtkMRGIGatherFS.glsl with MRGI_GATHER_TREE and vtkMRGIVPLTree.glsl.
 *
 * Indirect shadows: the four VPL gathers take a vtkMRGIIndirectVisibility
 * (default: none, the gathers exactly as without it). ISMVisibility
 * weights each VPL's term by its imperfect shadow map (tile j for VPL j of
 * the cache; in the tree gathers every node of root r by root r's tile,
 * looked up from root r: mrgi_vpl_tree_gather.h section 4), GLSL
 * vtkMRGIISMLookup.glsl behind MRGI_INDIRECT_ISM, C twins
 * mrgi_gather_full_visibility() and mrgi_vpl_tree_gather_visibility().
 * Errors name the problem: atlas missing, a layout whose tile count is not
 * the VPL (root) count, an atlas texture of another size.
 * VoxelVisibility marches the voxels from each receiver to each VPL (tree:
 * each node used), vtkMRGIVoxelMarch.glsl behind MRGI_INDIRECT_VOXELS, in
 * draws of mrgi_voxel_samples_per_batch() VPLs (tree: as many roots as
 * their nodes' marches allow) added by blending, to fit llvmpipe's loop
 * budget; errors: no voxelization, one never run, a tree root whose
 * subtree alone exceeds the budget. Refused by name: visibility with the
 * splatting GatherMode (each VPL splats without knowing its receivers'
 * occluders).
 *
 * With CollectStatistics on, an occlusion query per level counts the
 * texels gathered (nichols-shopf-wyman-2009 table 1), and the tree gathers
 * count the VPLs (tree nodes) each gathered texel used.
 */
#ifndef vtkMRGIGather_h
#define vtkMRGIGather_h

#include "MRGIRenderingModule.h" // For export macro
#include "vtkObject.h"

#include "mrgi_vpl_tree_gather.h" // For MRGI_VPL_TREE_DEFAULT_THRESHOLD
#include "vtkMRGIIndirectVisibility.h" // For vtkMRGIIndirectVisibility (default arguments)

#include <functional> // For std::function
#include <memory>     // For std::unique_ptr

struct mrgi_area_light_uniforms;
struct mrgi_multires_layout;
struct vtkMRGIFrameContext;
struct vtkMRGIGatherInternals;
class vtkFloatArray;
class vtkMRGIMultiresolution;
class vtkMRGISpecularStencil;
class vtkMRGIVisibilityPyramid;
class vtkMRGIVoxelization;
class vtkOpenGLRenderWindow;
class vtkRenderWindow;
class vtkShaderProgram;
class vtkTextureObject;
class vtkWindow;

#ifndef __VTK_WRAP__
/**
 * The light term of an area-light gather (nichols-penmatsa-wyman-2010 3.2):
 * its samples (MRGI_AREA_LIGHT_SAMPLE_TEXELS x SampleCount RGBA32F, the
 * core's mrgi_area_light_sample records), its uniforms
 * (mrgi_area_light_uniforms_init(), world space), and its visibility:
 * none; Voxels (voxelized this frame: each sample counts where the voxel
 * march finds it visible, 3.3.1); or Masks (updated this frame on this
 * selection: where the texel's bit of the incremental visibility is set,
 * 3.3.2).
 */
struct vtkMRGIAreaLightTerm
{
  vtkTextureObject* Samples = nullptr;
  int SampleCount = 0;
  const mrgi_area_light_uniforms* Light = nullptr;
  vtkMRGIVoxelization* Voxels = nullptr;
  vtkMRGIVisibilityPyramid* Masks = nullptr;
};

/**
 * The light term of a VPL-tree gather (nichols-shopf-wyman-2009 3.5): the
 * tree's node records in one RGBA32F texture of the
 * mrgi_vpl_tree_texture_size() layout (UploadVPLTree() makes it), the C
 * tree the texture holds (its layout, level_first and view count drive the
 * traversal; its records are not read here), and the refinement threshold
 * tau (>= 0; >= 1 gathers the 16 x 16 roots of each view only, 0 every
 * RSM texel).
 */
struct vtkMRGIVPLTreeTerm
{
  vtkTextureObject* Nodes = nullptr;     // RGBA32F tree texture, mrgi_vpl_tree_texture_size() layout
  const mrgi_vpl_tree* Tree = nullptr;   // the C tree the texture holds (layout, level_first, view_count)
  double Threshold = MRGI_VPL_TREE_DEFAULT_THRESHOLD; // tau
};
#endif

class MRGIRENDERING_EXPORT vtkMRGIGather : public vtkObject
{
public:
  static vtkMRGIGather* New();
  vtkTypeMacro(vtkMRGIGather, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum GatherModes
  {
    GatherStenciled = 0, ///< one draw per level, early stencil culling (default)
    GatherSplatting = 1  ///< multiresolution splatting, nichols-wyman-2009 3.4
  };

  ///@{
  /**
   * How GatherVPLs() computes the selected texels (the same numbers either
   * way): the stenciled gather of nichols-shopf-wyman-2009 section 3.2.2
   * (default), or the multiresolution splatting it replaced
   * (nichols-wyman-2009 section 3.4: every VPL draws one point per selected
   * texel, additive blending), kept so that the papers' comparison can be
   * repeated (Documentation/Multiresolution.md). Splatting reads the
   * selection back to build its subsplat list (timer step
   * "gather.subsplats"); the splats themselves are "gather.vpls", as the
   * stenciled gather's draws. Area lights are always gathered stenciled.
   */
  vtkSetClampMacro(GatherMode, int, GatherStenciled, GatherSplatting);
  vtkGetMacro(GatherMode, int);
  void SetGatherModeToStenciled() { this->SetGatherMode(GatherStenciled); }
  void SetGatherModeToSplatting() { this->SetGatherMode(GatherSplatting); }
  ///@}

  ///@{
  /**
   * Per-frame statistics (nichols-shopf-wyman-2009 table 1): with
   * CollectStatistics on, each gather counts the texels it gathers at each
   * level with occlusion queries and the valid pixels (the full-resolution
   * gather's work) from the coarsest receivers. Reading them waits for the
   * GPU, hence off by default.
   */
  vtkSetMacro(CollectStatistics, bool);
  vtkGetMacro(CollectStatistics, bool);
  vtkBooleanMacro(CollectStatistics, bool);
  ///@}

#ifndef __VTK_WRAP__
  /**
   * Gather `vplCount` VPLs (the VPL cache texture) at the texels the
   * buffer's selection selects (its receivers built this frame) into the
   * flattened irradiance buffer (E, RGB; 0 where nothing was selected).
   * Uses the frame's window, eye -> world matrix and timer ("gather.vpls").
   * False on error.
   */
  bool GatherVPLs(const vtkMRGIFrameContext& frame, vtkMRGIMultiresolution* buffer,
    vtkTextureObject* vpls, int vplCount,
    const vtkMRGIIndirectVisibility& visibility = vtkMRGIIndirectVisibility());

  /**
   * GatherVPLs() at the texels of `stencil`, one level at a time from the
   * coarsest to the finest gathering level, calling `beforeLevel(level)`
   * before each level's draw (it may draw elsewhere, e.g. build that
   * level's part of `stencil` from the coarser levels' irradiance:
   * vtkMRGIIncrementalStencil::BuildIlluminationLevel()); false from it
   * stops the gather with false. Stenciled only (GatherMode ignored).
   */
  bool GatherVPLsIncremental(const vtkMRGIFrameContext& frame, vtkMRGIMultiresolution* buffer,
    vtkTextureObject* vpls, int vplCount, const vtkMRGIIndirectVisibility& visibility,
    vtkTextureObject* stencil, const std::function<bool(int level)>& beforeLevel);
  /**
   * The full-resolution gather (vtkMRGIPass::IndirectFull, the reference
   * the multiresolution one approximates): every pixel of frame.Viewport
   * gathers all `vplCount` VPLs (nichols-shopf-wyman-2009 eq. 1 and 5)
   * from the frame's position, normal and albedo, writing E into
   * `irradiance` and strength x albedo x E into `indirect` (window-sized
   * textures, the viewport only). No timer step of its own. False (with an
   * error) on missing input or a program that does not build.
   */
  bool GatherFull(const vtkMRGIFrameContext& frame, vtkTextureObject* vpls, int vplCount,
    double strength, vtkTextureObject* irradiance, vtkTextureObject* indirect,
    const vtkMRGIIndirectVisibility& visibility = vtkMRGIIndirectVisibility());

  /**
   * The stenciled multiresolution gather with the VPL tree as the light
   * term: the texels the buffer's selection selects (receivers built this
   * frame) each traverse the tree (mrgi_vpl_tree_gather.h section 2) into
   * the flattened irradiance buffer, as GatherVPLs() does with the VPL
   * cache. Always stenciled: the splatting mode (GatherMode) has no tree
   * form, since each receiver chooses its own VPLs. The roots are gathered
   * in batches of mrgi_vpl_tree_roots_per_batch(), one draw per level and
   * batch, added by blending (llvmpipe stops a loop silently after 65,535
   * iterations). Timer step "gather.tree". False, with an error naming the
   * problem, on a missing or unbuilt tree, a texture of the wrong size, a
   * tau that is NaN or negative, an RSM larger than
   * MRGI_VPL_TREE_GATHER_MAX_RSM_SIZE or a tree texture taller than
   * GL_MAX_TEXTURE_SIZE.
   */
  bool GatherVPLTree(const vtkMRGIFrameContext& frame, vtkMRGIMultiresolution* buffer,
    const vtkMRGIVPLTreeTerm& tree,
    const vtkMRGIIndirectVisibility& visibility = vtkMRGIIndirectVisibility());

  /**
   * GatherVPLTree() at the texels of `stencil`, coarse to fine with
   * `beforeLevel(level)` before each level's draws, as
   * GatherVPLsIncremental() does with the VPL cache.
   */
  bool GatherVPLTreeIncremental(const vtkMRGIFrameContext& frame, vtkMRGIMultiresolution* buffer,
    const vtkMRGIVPLTreeTerm& tree, const vtkMRGIIndirectVisibility& visibility,
    vtkTextureObject* stencil, const std::function<bool(int level)>& beforeLevel);

  /**
   * The full-resolution gather (as GatherFull()) with the VPL tree as the
   * light term: every pixel of frame.Viewport traverses the tree, writing E
   * into `irradiance` and strength x albedo x E into `indirect`. Batches and
   * errors as GatherVPLTree(); no timer step of its own.
   */
  bool GatherFullTree(const vtkMRGIFrameContext& frame, const vtkMRGIVPLTreeTerm& tree,
    double strength, vtkTextureObject* irradiance, vtkTextureObject* indirect,
    const vtkMRGIIndirectVisibility& visibility = vtkMRGIIndirectVisibility());

  /**
   * Upload `tree`'s node records into `nodes` in the layout of
   * mrgi_vpl_tree_texture_size() (RGBA32F, records followed by zero
   * records), reallocating it when its size differs. False, with an error,
   * for a tree that was not built or a texture larger than
   * GL_MAX_TEXTURE_SIZE.
   */
  static bool UploadVPLTree(vtkOpenGLRenderWindow* window, const mrgi_vpl_tree* tree,
    vtkTextureObject* nodes);

  /**
   * Gather the direct light of one area light (its term, see
   * vtkMRGIAreaLightTerm) at the texels `stencil` selects: the buffer's
   * selection (GetStencilTexture()) or the incremental stencil
   * (vtkMRGIIncrementalStencil). Timer step "gather.samples". False on
   * error.
   */
  bool GatherAreaLight(const vtkMRGIFrameContext& frame, vtkMRGIMultiresolution* buffer,
    const vtkMRGIAreaLightTerm& term, vtkTextureObject* stencil);

  /**
   * The specular gather of an area light (NPW10 3.2.1) at the texels of
   * `stencil` (built this frame on this buffer), one level at a time from
   * the finest gathering level (timer step "gather.specular"). `program` is
   * the caller's (ready, its own uniforms and textures set); for each level
   * this binds the receivers (mrgiPosition, mrgiNormal, mrgiReceiverOffset
   * as the gather's), the level's material (mrgiMaterial: x max k_s, y the
   * largest exponent), mrgiLevelOrigin (the level's offset in the flattened
   * layout) and mrgiLevelScale (2^level), sets the viewport to the level and
   * calls `draw(level)`, which draws (and may bind per-level inputs).
   * False on error.
   */
  bool GatherSpecular(const vtkMRGIFrameContext& frame, vtkMRGIMultiresolution* buffer,
    vtkMRGISpecularStencil* stencil, vtkShaderProgram* program,
    const std::function<bool(int level)>& draw);
#endif

  /** The flattened irradiance of the last gather (RGBA32F, the buffer's flattened layout); null before. */
  vtkTextureObject* GetIrradianceTexture() const;

  /** Read the flattened irradiance of the last gather back (RGBA floats). */
  bool ReadIrradiance(vtkRenderWindow* window, vtkFloatArray* irradiance);

  /** Texels gathered at `level` by the last gather; -1 when not counted. */
  vtkIdType GetNumberOfGatheredTexels(int level) const;

  /** Valid (non-background) pixels of the last gather; -1 when not counted. */
  vtkIdType GetNumberOfValidPixels() const;

  /**
   * Texels gathered at all levels over the valid pixels: the share of the
   * full-resolution gather's work done (each texel gathers every VPL once,
   * as each pixel does at full resolution); -1 when not counted.
   */
  double GetGatherWorkFraction() const;

  /**
   * VPLs (tree nodes) per gathered texel of the last tree gather with
   * CollectStatistics on: the mean and the largest count over the texels
   * gathered (stenciled: the selected texels, full: the viewport's pixels;
   * background and malformed receivers not counted); -1 when not counted
   * (statistics off, or the last gather was not a tree gather).
   */
  double GetMeanVPLsPerPixel() const;
  double GetMaxVPLsPerPixel() const;

  /** Free every GL resource. */
  void ReleaseGraphicsResources(vtkWindow* w);

protected:
  vtkMRGIGather();
  ~vtkMRGIGather() override;

  int GatherMode = GatherStenciled;
  bool CollectStatistics = false;

#ifndef __VTK_WRAP__
  // The flattened irradiance for `layout`; false, with an error, when it
  // cannot be allocated.
  bool PrepareTarget(vtkOpenGLRenderWindow* window, const mrgi_multires_layout& layout);
  // The gathers after their inputs are checked: the stenciled one (VPLs, or
  // the area light of `term`), the splatting (VPLs only) and the stenciled
  // tree gather (CheckTree() passed).
  bool Run(const vtkMRGIFrameContext& frame, vtkMRGIMultiresolution* buffer, vtkTextureObject* vpls,
    int vplCount, const vtkMRGIAreaLightTerm* term, vtkTextureObject* stencil,
    const vtkMRGIVPLTreeTerm* tree = nullptr);
  bool RunStenciled(const vtkMRGIFrameContext& frame, vtkMRGIMultiresolution* buffer,
    const mrgi_multires_layout& layout, vtkTextureObject* vpls, int vplCount,
    const vtkMRGIAreaLightTerm* term, vtkTextureObject* stencil);
  bool RunSplatting(const vtkMRGIFrameContext& frame, vtkMRGIMultiresolution* buffer,
    const mrgi_multires_layout& layout, vtkTextureObject* vpls, int vplCount);
  // The full-resolution gather of the VPL cache (`tree` null) or the tree.
  bool RunFull(const vtkMRGIFrameContext& frame, vtkTextureObject* vpls, int vplCount,
    const vtkMRGIVPLTreeTerm* tree, double strength, vtkTextureObject* irradiance,
    vtkTextureObject* indirect);
  bool RunStenciledTree(const vtkMRGIFrameContext& frame, vtkMRGIMultiresolution* buffer,
    const mrgi_multires_layout& layout, const vtkMRGIVPLTreeTerm& tree, vtkTextureObject* stencil);
  // The tree term checked (section "Errors" of GatherVPLTree()): its roots
  // and roots per batch. False, with an error, when it cannot be gathered.
  bool CheckTree(vtkOpenGLRenderWindow* window, const vtkMRGIVPLTreeTerm& tree, int& roots,
    int& rootsPerBatch);
  // Check a VPL gather's visibility for `tiles` VPLs (tree: roots) and keep
  // it for this call; false, with an error naming the problem.
  bool UseVisibility(const vtkMRGIIndirectVisibility& visibility, int tiles);
#endif

  std::unique_ptr<vtkMRGIGatherInternals> Internal; // Private/vtkMRGIGatherInternals.h

private:
  vtkMRGIGather(const vtkMRGIGather&) = delete;
  void operator=(const vtkMRGIGather&) = delete;
};

#endif
