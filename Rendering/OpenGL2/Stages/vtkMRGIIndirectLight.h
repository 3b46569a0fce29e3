/**
 * @class   vtkMRGIIndirectLight
 * @brief   One-bounce indirect light of one frame: VPL selection, the
 *          visibility of the VPLs (none, imperfect shadow maps or
 *          screen-space voxels), the gather (full or stenciled
 *          multiresolution, VPL cache or VPL tree) and the upsampling.
 *
 * vtkMRGIPass's steps "vpl", "ism"/"voxels", "gather" and "upsample"
 * (Documentation/Design.md). Render() takes the frame, the reflective
 * shadow maps and the multiresolution buffer (shared with the area lights)
 * as arguments and writes E and strength x albedo x E into the caller's
 * targets; nothing is remembered between frames but the owned stages'
 * caches (the VPL cache, the ISM point set, GL resources) and the view
 * samples: the G-buffer is read back once per frame whose camera or props
 * changed, and the samples are passed to the VPL selection (BRSM) and the
 * imperfect shadow maps (adaptive points) as an argument.
 *
 * Indirect visibility (issue 13; Documentation/IndirectLight.md, "Indirect
 * visibility"):
 * - VisibilityOff: RSM VPLs light everything they face (nichols-shopf-
 *   wyman-2009, dachsbacher-stamminger-2005): light leaks through occluders.
 * - VisibilityISM: every VPL gets an imperfect shadow map
 *   (vtkMRGIImperfectShadowMaps, ritschel-et-al-2008 3.3 / ritschel-et-al-2011)
 *   and its term is weighted by the lookup of mrgi_ism_visibility.h. Sees the
 *   whole scene, point-approximate.
 * - VisibilityVoxels: the screen-space voxels of the area lights
 *   (nichols-penmatsa-wyman-2010 3.3), marched from each receiver to each VPL.
 *   Exact at the voxel resolution for what the camera sees; blind to
 *   occluders off screen or hidden behind the visible surfaces.
 *
 * Refinement (issue 17 part 2), for the multiresolution gather of the VPL
 * cache, as the buffer it is handed says (vtkMRGIMultiresolution::
 * GetRefinement(), set by its presets):
 * - RefinementGeometry: the buffer's geometric selection (depth and normal
 *   discontinuities, mrgi_multires.h) alone.
 * - RefinementIllumination: the levels are gathered coarse to fine and a
 *   texel below the geometric cut is gathered too where its parent's 3x3
 *   gathered irradiance differs by more than the buffer's
 *   IlluminationThreshold (vtkMRGIIncrementalStencil's illumination rule,
 *   nichols-penmatsa-wyman-2010 3.4 applied to the indirect light); the
 *   upsampling reads the texels gathered. With the VPL cache and with the
 *   VPL tree alike (vtkMRGIGather::GatherVPLsIncremental(),
 *   GatherVPLTreeIncremental()); multiresolution splatting
 *   (vtkMRGIGather::GatherSplatting), which has no step between its
 *   levels, gathers the geometric selection.
 */
#ifndef vtkMRGIIndirectLight_h
#define vtkMRGIIndirectLight_h

#include "MRGIRenderingModule.h" // For export macro
#include "vtkObject.h"

#include <memory> // For std::unique_ptr

struct vtkMRGIFrameContext;
struct vtkMRGIIndirectVisibility;
class vtkMRGIGather;
class vtkMRGIIncrementalStencil;
class vtkMRGIImperfectShadowMaps;
class vtkMRGIMultiresolution;
class vtkMRGIReflectiveShadowMapPass;
class vtkMRGIUpsample;
class vtkMRGIVPLSelection;
class vtkMRGIVoxelization;
class vtkMRGIViewSamples;
class vtkTextureObject;
class vtkWindow;

class MRGIRENDERING_EXPORT vtkMRGIIndirectLight : public vtkObject
{
public:
  static vtkMRGIIndirectLight* New();
  vtkTypeMacro(vtkMRGIIndirectLight, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum VisibilityModes
  {
    VisibilityOff = 0,   ///< no indirect shadows (default: the papers' RSM assumption)
    VisibilityISM = 1,   ///< imperfect shadow maps (ritschel-et-al-2011)
    VisibilityVoxels = 2 ///< screen-space voxels (nichols-penmatsa-wyman-2010 3.3)
  };

  /** Whether the last multiresolution gather used the illumination stencil. */
  vtkGetMacro(LastRefinedByIllumination, bool);

  ///@{
  /** How the VPLs' visibility is computed (see the class comment). Default VisibilityOff. */
  vtkSetClampMacro(Visibility, int, VisibilityOff, VisibilityVoxels);
  vtkGetMacro(Visibility, int);
  ///@}

  ///@{
  /**
   * The ISM lookup (mrgi_ism_visibility.h): the bias as a fraction of the
   * distance and in texel footprints, and 2x2 percentage-closer filtering.
   */
  vtkSetClampMacro(ISMRelativeBias, double, 0.0, 16.0);
  vtkGetMacro(ISMRelativeBias, double);
  vtkSetClampMacro(ISMTexelBias, double, 0.0, 16.0);
  vtkGetMacro(ISMTexelBias, double);
  vtkSetMacro(ISMFiltering, bool);
  vtkGetMacro(ISMFiltering, bool);
  vtkBooleanMacro(ISMFiltering, bool);
  ///@}

  ///@{
  /**
   * The widest ISM texel (radians) the shadow test trusts
   * (mrgi_ism_visibility.h step 2b; default
   * MRGI_ISM_DEFAULT_MAX_TEXEL_ANGLE = 0.16): receivers in directions
   * where a tile texel spans more than this, near the VPL's horizon, are
   * not shadowed, since the surfaces around the VPL fill those wide texels
   * and shadow them falsely. 0 tests every direction.
   */
  vtkSetClampMacro(ISMMaxTexelAngle, double, 0.0, 4.0);
  vtkGetMacro(ISMMaxTexelAngle, double);
  ///@}

  /** The owned stages (their settings: points per VPL, tile size, ...). */
  vtkMRGIVPLSelection* GetVPLSelection() { return this->VPLSelection; }
  vtkMRGIGather* GetGather() { return this->Gather; }
  vtkMRGIUpsample* GetUpsample() { return this->Upsample; }
  vtkMRGIImperfectShadowMaps* GetImperfectShadowMaps() { return this->ImperfectShadowMaps; }
  vtkMRGIVoxelization* GetVoxelization() { return this->Voxelization; }
  vtkMRGIIncrementalStencil* GetIlluminationStencil() { return this->IlluminationStencil; }

#ifndef __VTK_WRAP__
  /** What Render() is asked for: the pass's indirect settings, by value. */
  struct Settings
  {
    bool Multiresolution = true; ///< stenciled multiresolution gather + upsampling; false: full resolution
    double Strength = 1.0;       ///< IndirectStrength
    double SurfaceDetail = 0.0;  ///< vtkMRGIUpsample::Resolve's surface detail
    int UpsampleMode = 0;        ///< vtkMRGIUpsample mode
    double UpsampleMaskWeight = 100.0;
  };

  /** What Render() did. */
  enum Outcome
  {
    NoVPLs = 0,  ///< the RSMs hold no flux: nothing gathered, not an error
    Gathered = 1,
    Failed = 2   ///< an error was reported; the targets hold no indirect light
  };

  /**
   * Select the VPLs from `rsm` (rendered this frame), build their
   * visibility, gather at `buffer`'s selection (Settings::Multiresolution;
   * `buffer` is updated and its receivers built here) or at every pixel,
   * and write E into `irradiance` and strength x albedo x E into `indirect`
   * (window-sized). `frame` must be a captured frame (pixel size defined)
   * for the multiresolution gather.
   */
  Outcome Render(const vtkMRGIFrameContext& frame, vtkMRGIReflectiveShadowMapPass* rsm,
    vtkMRGIMultiresolution* buffer, const Settings& settings, vtkTextureObject* irradiance,
    vtkTextureObject* indirect);
#endif

  /** VPLs of the last Render() (0 before, or when the RSMs held no flux). */
  vtkGetMacro(LastVPLCount, int);

  /**
   * G-buffer read-backs for view samples so far: one per frame whose
   * camera or visible props changed, shared by BRSM and the adaptive ISM
   * points; none while the view is static.
   */
  long long GetNumberOfViewSampleReadBacks() const;

  /** Free every GL resource of the owned stages. */
  void ReleaseGraphicsResources(vtkWindow* w);

protected:
  vtkMRGIIndirectLight();
  ~vtkMRGIIndirectLight() override;

#ifndef __VTK_WRAP__
  // This frame's visibility term for `vplCount` VPLs (steps "ism" or
  // "voxels"); false, with an error, when it cannot be built.
  bool BuildVisibility(const vtkMRGIFrameContext& frame, int vplCount,
    vtkMRGIIndirectVisibility& visibility);
  bool RunGather(const vtkMRGIFrameContext& frame, vtkMRGIMultiresolution* buffer,
    const Settings& settings, const vtkMRGIIndirectVisibility& visibility, int vplCount,
    vtkTextureObject* irradiance, vtkTextureObject* indirect);
#endif

  int Visibility = VisibilityOff;
  double ISMRelativeBias;
  double ISMTexelBias;
  double ISMMaxTexelAngle;
  bool ISMFiltering = true;
  int LastVPLCount = 0;
  bool LastRefinedByIllumination = false;
  vtkMRGIIncrementalStencil* IlluminationStencil;

  vtkMRGIVPLSelection* VPLSelection;
  vtkMRGIGather* Gather;
  vtkMRGIUpsample* Upsample;
  vtkMRGIImperfectShadowMaps* ImperfectShadowMaps;
  vtkMRGIVoxelization* Voxelization;
  std::unique_ptr<vtkMRGIViewSamples> ViewSamples; // the frame's one read-back, for both

private:
  vtkMRGIIndirectLight(const vtkMRGIIndirectLight&) = delete;
  void operator=(const vtkMRGIIndirectLight&) = delete;
};

#endif
