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
    Clusters = 2
  };

  ///@{
  /** Grid (default), FluxImportance or Clusters. */
  vtkSetClampMacro(Mode, int, Grid, Clusters);
  vtkGetMacro(Mode, int);
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

  /**
   * Bring the VPL cache up to date for `rsm`'s current maps. Returns the
   * number of VPL rows in the cache (0: no light reaches anything, or no VPLs asked).
   */
  int Update(vtkOpenGLRenderWindow* window, vtkMRGIReflectiveShadowMapPass* rsm);

  /** The VPL cache texture (MRGI_VPL_TEXELS x GetVPLCount()), or nullptr. */
  vtkTextureObject* GetVPLTexture() const;

  /** Rows of the VPL cache after the last Update(). */
  int GetVPLCount() const;

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
  vtkIdType NumberOfSelections = 0;

  // Clusters mode: read back each light's views, select with the C core;
  // `lights` lists each light's RSM views. Returns the VPL count (0 on error).
  int SelectClusters(vtkOpenGLRenderWindow* window, vtkMRGIReflectiveShadowMapPass* rsm,
    const std::vector<std::vector<int>>& lights, std::vector<mrgi_vpl>& vpls);

  struct Internals;
  std::unique_ptr<Internals> Internal;

private:
  vtkMRGIVPLSelection(const vtkMRGIVPLSelection&) = delete;
  void operator=(const vtkMRGIVPLSelection&) = delete;
};

#endif
