/**
 * @class   vtkMRGIVisibilityPyramid
 * @brief   Incremental voxel-space visibility on the GPU
 *          (nichols-penmatsa-wyman-2010 sections 3.3.2 and 3.4): per
 *          multiresolution texel, a bit mask saying which light samples it
 *          sees, computed coarse to fine, reusing the coarser level's answers
 *          where its 3x3 neighbours agree.
 *
 * The contract is the C twin mrgi_voxel_visibility_pyramid()
 * (Rendering/Core/Twins/mrgi_visibility_pyramid.h): sample j is bit j & 31 of word
 * j >> 5; from the coarsest level down, a receiver texel is COMPUTED (coarsest
 * level, refinement metric of its parent's 3x3 at or above the threshold, or
 * forced by the selection, or its parent not on its surface) with the
 * incremental rule (agree = wanted & ~(AND ^ OR) reused, the rest marched;
 * nothing reused without a neighbour on its surface; the agreed hidden
 * bits marched again where the kept neighbours do not surround the texel on
 * screen), else INHERITED (the parent's mask; only between kept
 * neighbours); the same-surface guard and the surround rule are the C
 * twin's section 3 and read the parent level's receiver normals too;
 * with 2x2 interleaving each texel marches the samples of its phase and the
 * block's quarters are combined between texels on the same surface. One ray
 * is the GLSL march of vtkMRGIVoxelMarch.glsl (C twin mrgi_voxel_march()).
 * Incremental off is the naive query everywhere: every receiver of every
 * level is COMPUTED without coarse masks (as if each level were the coarsest).
 *
 * Passes per level (vtkMRGIVisibilityPyramidFS.glsl), each drawn over the
 * level's W_i x H_i texels. Without interleaving: decide once (INHERITED
 * masks, reused bits, and the bits left to march), mark the texels with
 * bits left in a stencil, and march only there (early stencil culling
 * skips the INHERITED texels, NPW10 section 4); with interleaving, stage 0
 * (decide, inherit or compute the own phase) and stage 1 (combine the
 * quarters, re-march what no same-surface block texel computed). With
 * CollectStatistics a last stage counts the rays the others march. Marching stages are split into
 * draws over sample ranges so that one fragment's marches fit llvmpipe's
 * loop budget (mrgi_voxel_samples_per_batch()); the draws are ORed
 * (glLogicOp(GL_OR); every bit a draw writes outside its range is the same
 * in all of them).
 *
 * Mask layout: per level, GetNumberOfMaskTextures() = ceil(W / 4) RGBA32UI
 * textures of the level's size, W = ceil(N / 32) words: word w of texel
 * (x, y) is channel w % 4 of texel (x, y) of texture w / 4 (texelFetch,
 * level-local coordinates, not the flattened layout). The masks are unpacked
 * (all N bits per texel, also with interleaving), so N <=
 * GetMaximumNumberOfSamples() (512: 4 targets; the pass also binds the
 * parent's masks, receiver positions and normals and the quarters'
 * textures: 15 samplers with the voxels, within the 16 texture units
 * OpenGL 3.2 guarantees). ReadMasks() gives the C twin's flattened layout.
 *
 * Inputs: after vtkMRGIMultiresolution::Update() and BuildReceivers(), the
 * receivers of each level (GetReceiverTexture(), GetReceiverOffset(); level
 * 0, the raw G-buffer, is made a receiver as mrgi_multires_receivers_build()
 * does), a voxelization of this frame (vtkMRGIVoxelization::Voxelize(); its
 * march knobs via SetMarchUniforms()), and the light samples: the core's
 * mrgi_area_light_sample records in world space
 * (MRGI_AREA_LIGHT_SAMPLE_TEXELS RGBA32F texels per sample, one row each, as
 * vtkMRGIAreaLightDiffuse.glsl reads them) with the world -> eye matrix.
 * Two-sided lights flip a sample's normal to face the receiver (the C twin
 * takes fixed sample normals: parity holds for one-sided lights).
 */
#ifndef vtkMRGIVisibilityPyramid_h
#define vtkMRGIVisibilityPyramid_h

#include "MRGIRenderingModule.h" // For export macro
#include "vtkObject.h"

#include <memory> // For std::unique_ptr

class vtkMRGIMultiresolution;
class vtkMRGIVoxelization;
class vtkOpenGLRenderWindow;
class vtkRenderTimerLog;
class vtkRenderWindow;
class vtkTextureObject;
class vtkTypeUInt32Array;
class vtkWindow;

class MRGIRENDERING_EXPORT vtkMRGIVisibilityPyramid : public vtkObject
{
public:
  static vtkMRGIVisibilityPyramid* New();
  vtkTypeMacro(vtkMRGIVisibilityPyramid, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Incremental visibility (default on): coarse to fine with reuse and the
   * refinement metric. Off: the naive query (NPW10 3.3.1) at every texel of
   * every level.
   */
  vtkSetMacro(Incremental, bool);
  vtkGetMacro(Incremental, bool);
  vtkBooleanMacro(Incremental, bool);
  ///@}

  ///@{
  /**
   * Refinement fraction f in [0, 1] (mrgi_voxel_incremental_params): a texel
   * is COMPUTED when its parent's metric >= ceil(f N) (>= 1 when f > 0);
   * 0 computes every texel. Default MRGI_VOXEL_DEFAULT_REFINE_FRACTION (0.5,
   * the paper's "half the VPLs").
   */
  vtkSetClampMacro(RefineFraction, double, 0.0, 1.0);
  vtkGetMacro(RefineFraction, double);
  ///@}

  enum Metrics
  {
    MetricDisagree = 0,   ///< popcount(OR ^ AND) over the 3x3 (the paper's, default)
    MetricCountSpread = 1 ///< max - min of the visible counts
  };

  ///@{
  /** The refinement metric (MRGI_VOXEL_METRIC_*). */
  vtkSetClampMacro(Metric, int, MetricDisagree, MetricCountSpread);
  vtkGetMacro(Metric, int);
  ///@}

  ///@{
  /** 2x2 interleaved sampling with the same-surface test (default on). */
  vtkSetMacro(Interleave, bool);
  vtkGetMacro(Interleave, bool);
  vtkBooleanMacro(Interleave, bool);
  ///@}

  ///@{
  /**
   * Force COMPUTED where the multiresolution selection is set (the C twin's
   * `refine` mask = vtkMRGIMultiresolution::ReadSelection()). Default off.
   */
  vtkSetMacro(RefineSelected, bool);
  vtkGetMacro(RefineSelected, bool);
  vtkBooleanMacro(RefineSelected, bool);
  ///@}

  ///@{
  /**
   * Count the rays marched and the COMPUTED / INHERITED texels per level in
   * Update() (one extra pass per level and a read back: waits for the GPU).
   * Default off.
   */
  vtkSetMacro(CollectStatistics, bool);
  vtkGetMacro(CollectStatistics, bool);
  vtkBooleanMacro(CollectStatistics, bool);
  ///@}

  /** Most light samples Update() takes (unpacked masks in 4 RGBA32UI targets: 512). */
  static int GetMaximumNumberOfSamples();

  /**
   * Compute the masks of every level of `multires` (Update() and
   * BuildReceivers() done this frame) for `sampleCount` light samples
   * (texture described in the class notes), coarse to fine, marching
   * through `voxels` (voxelized this frame, its own march knobs).
   * `worldToView` is column-major. Timer step "visibility.pyramid" on
   * `timer` when given, with its passes summed over the levels as
   * sub-steps "visibility.decide", ".mark", ".march", ".copies" (and
   * ".compute", ".combine" with interleaving, ".statistics" when
   * collected). False, with an error, on bad input or an OpenGL failure.
   */
  bool Update(vtkOpenGLRenderWindow* window, vtkMRGIMultiresolution* multires,
    vtkMRGIVoxelization* voxels, vtkTextureObject* samples, int sampleCount, bool twoSided,
    const float worldToView[16], vtkRenderTimerLog* timer = nullptr);

  /** Levels, samples and words of the last successful Update() (0 before). */
  int GetNumberOfLevels() const;
  int GetNumberOfSamples() const;
  int GetNumberOfMaskWords() const;
  int GetNumberOfMaskTextures() const;

  /** The refinement threshold the last Update() used (mrgi_voxel_refine_threshold()). */
  int GetThreshold() const;

  /**
   * Mask texture `word4` (words 4 word4 .. 4 word4 + 3) of `level` (layout in
   * the class notes); null when there is none.
   */
  vtkTextureObject* GetMaskTexture(int level, int word4) const;

  /**
   * Read every level's masks back in the C twin's layout: one tuple of W
   * words per flattened texel (mrgi_multires_index()), zeros outside the
   * levels. False before a successful Update().
   */
  bool ReadMasks(vtkRenderWindow* window, vtkTypeUInt32Array* masks);

  ///@{
  /**
   * Statistics of the last Update() with CollectStatistics on (-1 otherwise):
   * rays marched at `level` (all draws), its COMPUTED and INHERITED receiver
   * texels, the total over levels, and the naive cost N x level-0 receivers
   * (mrgi_voxel_incremental_stats).
   */
  vtkIdType GetNumberOfRays(int level) const;
  vtkIdType GetNumberOfComputedTexels(int level) const;
  vtkIdType GetNumberOfInheritedTexels(int level) const;
  vtkIdType GetTotalNumberOfRays() const;
  vtkIdType GetNumberOfNaiveRays() const;
  ///@}

  /** Draws of the last Update() (passes x batches). */
  int GetNumberOfDraws() const;


  /** Free every GL resource. */
  void ReleaseGraphicsResources(vtkWindow* w);

protected:
  vtkMRGIVisibilityPyramid();
  ~vtkMRGIVisibilityPyramid() override;

  bool Incremental = true;
  double RefineFraction = 0.5; // MRGI_VOXEL_DEFAULT_REFINE_FRACTION, set by the constructor
  int Metric = MetricDisagree;
  bool Interleave = true;
  bool RefineSelected = false;
  bool CollectStatistics = false;

  struct Internals;
  std::unique_ptr<Internals> Internal;

private:
  vtkMRGIVisibilityPyramid(const vtkMRGIVisibilityPyramid&) = delete;
  void operator=(const vtkMRGIVisibilityPyramid&) = delete;
};

#endif
