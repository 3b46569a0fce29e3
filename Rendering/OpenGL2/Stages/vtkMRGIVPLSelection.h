/**
 * @class   vtkMRGIVPLSelection
 * @brief   Selects virtual point lights (VPLs) from reflective shadow maps
 *          into the VPL cache texture the gather reads.
 *
 * The VPL cache (nichols-shopf-wyman-2009 section 3.2.2) is one texture of
 * MRGI_VPL_TEXELS x count RGBA32F texels, one row per VPL, in the record
 * layout of mrgi_vpl.h, so that the gather reads VPLs coherently.
 *
 * Modes:
 * - Grid (default, the papers' choice): a regular grid over each light view;
 *   each VPL carries the flux and area of its whole block. Runs on the GPU;
 *   its C twin is mrgi_vpl_select_grid().
 * - FluxImportance: VPLs drawn with probability proportional to texel flux,
 *   weighted by 1 / (N p) so the estimate stays unbiased. The RSMs are read
 *   back and mrgi_vpl_select_importance() (C core) selects; the result is
 *   uploaded.
 * - Clusters: multiresolution VPL clusters (image-space radiosity,
 *   nichols-shopf-wyman-2009 sections 3.3-3.4). The RSMs are read back;
 *   mrgi_vpl_select_clusters() (C core) splits each light view into patches
 *   from 16 x 16 roots down to the finest light level, refining where the
 *   light-space depth or normal changes (ClusterDepthThreshold,
 *   ClusterNormalThreshold, the eye side's meanings). Each patch is one VPL
 *   carrying its patch's flux and area sums, so the count varies per frame;
 *   it is capped at MRGI_VPL_CLUSTER_MAX, split evenly among the lights
 *   (NumberOfVPLs does not apply). Thresholds +inf give the 16 x 16 grid.
 * - Tree: the hierarchical image-space radiosity VPL tree
 *   (nichols-shopf-wyman-2009 section 3.5). The RSMs are read back as in
 *   Clusters mode; mrgi_vpl_tree_build() (C core) builds one record per node
 *   of every view's light-space pyramid, and the records go into ONE RGBA32F
 *   texture (GetTreeTexture()) in the layout of mrgi_vpl_tree_gather.h
 *   section 3 (MRGI_VPL_TREE_RECORDS_PER_ROW records per row, coarse levels
 *   first, zero records after the last). The gather walks it per receiver
 *   with TreeThreshold (tau). The flat VPL cache holds the tree's 16 x 16
 *   roots of every view (the 256-per-view grid, pads cleared), so what reads
 *   the cache (area-light bounce, splatting, GetVPLs()) keeps working;
 *   NumberOfVPLs does not apply. All lights' views go into one tree: at
 *   most MRGI_RSM_MAX_VIEWS views (one point light, or up to six spot or
 *   directional lights) and RSMs of at most MRGI_VPL_TREE_GATHER_MAX_RSM_SIZE
 *   texels per side; beyond that Update() reports an error and builds no tree.
 *
 * - BRSM: bidirectional RSM importance (ritschel-et-al-2011 sections 4,
 *   4.1, 4.2, 6.5). The importance of each RSM texel is its contribution,
 *   as a VPL, to a few view samples of the frame (a 32 x 32 subsample of
 *   the G-buffer on a fixed jittered grid, Private/vtkMRGIViewSamples), chosen per texel with the
 *   clamped 1/x^2 guide around its projection; blurred geometry-aware
 *   (BRSMBlur), mixed with a share BRSMFluxShare of flux importance (so that
 *   every texel with flux keeps p > 0 and the 1 / (N p) estimate stays
 *   unbiased), sampled through a 2-D CDF, with inter-texel VPLs
 *   (BRSMInterTexel). The RSMs are read back and the C core
 *   (mrgi_brsm_*.h, Private/vtkMRGIBRSM) builds the weights and the CDF;
 *   with texel VPLs (BRSMInterTexel off) the CDF is rounded to float and
 *   inverted on the GPU (vtkMRGIBRSMInversion, exact parity with
 *   mrgi_brsm_cdf_float.h), with inter-texel VPLs the C core samples and the
 *   records are uploaded. Every random number (the view samples' jitter, the
 *   K guided draws per texel, the CDF strata) comes from Seed, never from
 *   the frame: a static scene gives the same VPLs every frame and a moving
 *   one changes them smoothly (no temporal noise from re-drawing). The
 *   cache is recomputed only when the RSMs, the settings or the view
 *   samples (the camera and the visible props) change. Without view samples
 *   it equals FluxImportance.
 *
 * With several lights, the VPL budget is split evenly among the lights that
 * have views. Nothing is recomputed while the RSMs and the settings are unchanged.
 */
#ifndef vtkMRGIVPLSelection_h
#define vtkMRGIVPLSelection_h

#include "MRGIRenderingModule.h" // For export macro
#include "vtkObject.h"

#include <limits> // For std::numeric_limits
#include <memory> // For std::unique_ptr
#include <vector> // For std::vector

struct mrgi_vpl;
struct mrgi_vpl_tree;
struct mrgi_rsm_view_camera;
struct vtkMRGIFrameContext;
struct vtkMRGIVPLTreeTerm;
class vtkMRGIViewSamples;

class vtkFloatArray;
class vtkMRGIReflectiveShadowMapPass;
class vtkOpenGLRenderWindow;
class vtkTextureObject;
class vtkWindow;

class MRGIRENDERING_EXPORT vtkMRGIVPLSelection : public vtkObject
{
public:
  static vtkMRGIVPLSelection* New();
  vtkTypeMacro(vtkMRGIVPLSelection, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum SelectionMode
  {
    Grid = 0,
    FluxImportance = 1,
    Clusters = 2,
    Tree = 3,
    BRSM = 4
  };

  ///@{
  /** Grid (default), FluxImportance, Clusters, Tree or BRSM. */
  vtkSetClampMacro(Mode, int, Grid, BRSM);
  vtkGetMacro(Mode, int);
  void SetModeToGrid() { this->SetMode(Grid); }
  void SetModeToFluxImportance() { this->SetMode(FluxImportance); }
  void SetModeToClusters() { this->SetMode(Clusters); }
  void SetModeToTree() { this->SetMode(Tree); }
  void SetModeToBRSM() { this->SetMode(BRSM); }

  ///@{
  /**
   * BRSM mode: the share beta of flux importance in the pdf (default 0.1;
   * 0 is the paper's pure BRSM, which never picks a texel its view samples
   * missed), the geometry-aware blur and the inter-texel VPLs (both on).
   */
  vtkSetClampMacro(BRSMFluxShare, double, 0.0, 1.0);
  vtkGetMacro(BRSMFluxShare, double);
  vtkSetMacro(BRSMBlur, bool);
  vtkGetMacro(BRSMBlur, bool);
  vtkBooleanMacro(BRSMBlur, bool);
  vtkSetMacro(BRSMInterTexel, bool);
  vtkGetMacro(BRSMInterTexel, bool);
  vtkBooleanMacro(BRSMInterTexel, bool);
  ///@}

  ///@{
  /**
   * BRSM mode: view samples K each RSM texel draws to estimate its
   * importance (the RMS of its contributions, mrgi_brsm_importance.h);
   * default MRGI_BRSM_DEFAULT_SAMPLES_PER_TEXEL = 32. More samples make the
   * pdf less noisy at a CPU cost linear in K; at most the view samples read
   * (1024). Clamped to 1..MRGI_BRSM_MAX_VIEW_SAMPLES.
   */
  vtkSetClampMacro(BRSMSamplesPerTexel, int, 1, 1024);
  vtkGetMacro(BRSMSamplesPerTexel, int);
  ///@}

  ///@{
  /**
   * BRSM mode: weight a of this frame's pdf in its moving average over the
   * selections (mrgi_brsm_temporal_blend(), beyond RIHKS11; default
   * MRGI_BRSM_DEFAULT_TEMPORAL_WEIGHT = 0.005, a time constant of about 200
   * frames; 1 re-estimates the pdf from scratch every frame, the paper's
   * rule). The pdf estimated from a few view samples per texel changes
   * from frame to frame, and VPLs drawn from it move where a grid's stay;
   * averaging keeps them still. The estimate stays unbiased (the VPL
   * weights divide by the blended pdf, which is positive wherever this
   * frame's is). One history per light, restarted when its RSM size
   * changes or by ResetBRSMHistory() (which makes the next frame select
   * again, from its own pdf), and dropped by itself when it shares
   * less than half its mass with this frame's pdf (a cut, a light moved
   * far: a stale history costs noise, not bias). Clamped to
   * MRGI_BRSM_MIN_TEMPORAL_WEIGHT..1.
   */
  vtkSetClampMacro(BRSMTemporalWeight, double, 0.001, 1.0);
  vtkGetMacro(BRSMTemporalWeight, double);
  void ResetBRSMHistory();
  ///@}

  /** BRSM mode: view samples of the last BRSM selection (0 before one, or without a G-buffer). */
  int GetNumberOfViewSamples() const;
  ///@}

  ///@{
  /** VPLs requested for the whole frame, 0..MRGI_VPL_MAX_COUNT (default 256). */
  vtkSetClampMacro(NumberOfVPLs, int, 0, 4096);
  vtkGetMacro(NumberOfVPLs, int);
  ///@}

  ///@{
  /** Seed of the importance sampler; the same seed gives the same VPLs. */
  vtkSetMacro(Seed, vtkTypeUInt64);
  vtkGetMacro(Seed, vtkTypeUInt64);
  ///@}

  ///@{
  /**
   * Clusters mode: light-space depth and normal thresholds (>= 0; +inf
   * turns a test off; defaults MRGI_MULTIRES_DEFAULT_DEPTH_THRESHOLD and
   * MRGI_MULTIRES_DEFAULT_NORMAL_THRESHOLD). NaN is reported by Update().
   */
  vtkSetClampMacro(ClusterDepthThreshold, double, 0.0, std::numeric_limits<double>::infinity());
  vtkGetMacro(ClusterDepthThreshold, double);
  vtkSetClampMacro(ClusterNormalThreshold, double, 0.0, std::numeric_limits<double>::infinity());
  vtkGetMacro(ClusterNormalThreshold, double);
  ///@}

  ///@{
  /**
   * Clusters mode: finest light level f_L a patch may reach (0 = single
   * texels), or -1 (default) for the level 64 texels wide (mrgi_vpl_clusters.h).
   */
  vtkSetClampMacro(ClusterFinestLevel, int, -1, 23);
  vtkGetMacro(ClusterFinestLevel, int);
  ///@}

  /**
   * Clusters mode, last selection: refinements the cap refused (0 when the
   * thresholds alone decided the VPLs).
   */
  vtkGetMacro(ClusterRefinementsCapped, int);

  ///@{
  /**
   * Tree mode: the refinement threshold tau on the form-factor bound
   * (mrgi_vpl_tree_gather.h section 1), 0..+inf, default
   * MRGI_VPL_TREE_DEFAULT_THRESHOLD. tau >= 1 gathers the 16 x 16 roots,
   * tau = 0 every RSM texel. Negative values clamp to 0; NaN is kept and
   * refused by the gather (vtkMRGIGather::GatherVPLTree: no indirect light,
   * an error naming tau). The tree itself does not depend on tau, only the
   * gather's traversal does (GetTreeTerm()): setting it does not mark the
   * selection modified, so the tree is not read back and rebuilt for a new
   * tau.
   */
  void SetTreeThreshold(double threshold);
  vtkGetMacro(TreeThreshold, double);
  ///@}

  /**
   * Tree mode: the node texture of the last Update() (RGBA32F,
   * MRGI_VPL_TREE_RECORDS_PER_ROW * MRGI_VPL_TEXELS texels wide), or nullptr
   * when there is no tree (another mode, or an error).
   */
  vtkTextureObject* GetTreeTexture() const;

  /** Tree mode: nodes of the last tree (all views, all levels); 0 without one. */
  vtkIdType GetNumberOfTreeNodes() const;

  /**
   * Tree mode: read the whole tree texture back, padding included: width *
   * height / MRGI_VPL_TEXELS tuples of MRGI_VPL_FLOATS floats (node records
   * in texture order, then the zero records). False, with an error, without a tree.
   */
  bool ReadTreeTexture(vtkOpenGLRenderWindow* window, vtkFloatArray* records);

#ifndef __VTK_WRAP__
  /** Tree mode: the C tree the texture was uploaded from (world space), or nullptr. */
  const mrgi_vpl_tree* GetTree() const;

  /** Tree mode: the gather's light term (texture, tree, TreeThreshold); null members without a tree. */
  vtkMRGIVPLTreeTerm GetTreeTerm() const;
#endif

  /**
   * Bring the VPL cache up to date for `rsm`'s current maps. Returns the
   * number of VPL rows in the cache (0: no light reaches anything, or no VPLs asked).
   */
  int Update(vtkOpenGLRenderWindow* window, vtkMRGIReflectiveShadowMapPass* rsm);

#ifndef __VTK_WRAP__
  /**
   * The same, for the frame `frame` (its G-buffer captured): in BRSM mode
   * the view samples are brought up to date from it first, in `shared`
   * (the frame's one read-back, vtkMRGIIndirectLight's) or, when null, in
   * this object's own. The other modes ignore `frame`.
   */
  int Update(vtkOpenGLRenderWindow* window, vtkMRGIReflectiveShadowMapPass* rsm,
    const vtkMRGIFrameContext& frame, vtkMRGIViewSamples* shared = nullptr);
#endif

  /** The VPL cache texture (MRGI_VPL_TEXELS x GetVPLCount()), or nullptr. */
  vtkTextureObject* GetVPLTexture() const;

  /** Rows of the VPL cache after the last Update(). */
  int GetVPLCount() const;

  /**
   * Read the VPL cache back: GetVPLCount() tuples of MRGI_VPL_FLOATS floats
   * (mrgi_vpl records). False, with an error, when there is no cache.
   */
  bool ReadVPLs(vtkOpenGLRenderWindow* window, vtkFloatArray* vpls);

  /** How many times the cache was recomputed. */
  vtkGetMacro(NumberOfSelections, vtkIdType);

  /** Free every GL resource. */
  void ReleaseGraphicsResources(vtkWindow* w);

protected:
  vtkMRGIVPLSelection();
  ~vtkMRGIVPLSelection() override;

  int Mode = Grid;
  int NumberOfVPLs = 256;
  vtkTypeUInt64 Seed = 1;
  double ClusterDepthThreshold;  // set from mrgi_vpl_cluster_params_default()
  double ClusterNormalThreshold;
  int ClusterFinestLevel;
  int ClusterRefinementsCapped = 0;
  double TreeThreshold;          // MRGI_VPL_TREE_DEFAULT_THRESHOLD
  double BRSMFluxShare;          // MRGI_BRSM_DEFAULT_FLUX_SHARE
  int BRSMSamplesPerTexel;       // MRGI_BRSM_DEFAULT_SAMPLES_PER_TEXEL
  bool BRSMBlur = true;
  bool BRSMInterTexel = true;
  double BRSMTemporalWeight;     // MRGI_BRSM_DEFAULT_TEMPORAL_WEIGHT
  vtkIdType NumberOfSelections = 0;

  // Clusters mode: read back each light's views, select with the C core;
  // `lights` lists each light's RSM views. Returns the VPL count (0 on error).
  int SelectClusters(vtkOpenGLRenderWindow* window, vtkMRGIReflectiveShadowMapPass* rsm,
    const std::vector<std::vector<int>>& lights, std::vector<mrgi_vpl>& vpls);

  // Read back the RSM views `views` (of any lights) into one mrgi_rsm's
  // arrays, and their light-space cameras (at most MRGI_RSM_MAX_VIEWS).
  // `what` names the mode in the errors. Returns false after an error.
  bool ReadLight(vtkOpenGLRenderWindow* window, vtkMRGIReflectiveShadowMapPass* rsm,
    const std::vector<int>& views, const char* what, mrgi_rsm_view_camera* cameras,
    std::vector<float>& position, std::vector<float>& normal, std::vector<float>& flux);

  // Tree mode: read back every view, build the tree, upload its texture;
  // `roots` receives the flat cache's VPLs. Returns the root count (0 on error).
  int SelectTree(vtkOpenGLRenderWindow* window, vtkMRGIReflectiveShadowMapPass* rsm,
    std::vector<mrgi_vpl>& roots);

  // Tree mode: free the tree (CPU) and its texture (GL, with `w`).
  void ReleaseTree(vtkWindow* w);

  // BRSM mode: bring `samples` up to date for `frame` and take them when
  // they changed (the cache is then stale). An error falls back to none.
  void UpdateViewSamples(const vtkMRGIFrameContext& frame, vtkMRGIViewSamples& samples);

  struct Internals;
  std::unique_ptr<Internals> Internal;

private:
  vtkMRGIVPLSelection(const vtkMRGIVPLSelection&) = delete;
  void operator=(const vtkMRGIVPLSelection&) = delete;
};

#endif
