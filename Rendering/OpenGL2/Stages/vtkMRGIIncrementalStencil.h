/**
 * @class   vtkMRGIIncrementalStencil
 * @brief   Incremental stencil rendering for area lights with visibility
 *          masks (nichols-penmatsa-wyman-2010 section 3.4): the texels an
 *          area-light gather renders, as a flattened mask and its stencil.
 *
 * A texel is rendered when the buffer's geometric selection has it, or when
 * it lies below the geometric cut, is not refined, and its parent's 3x3
 * visibility masks disagree on at least ceil(Fraction N) of the N samples
 * (the masks' refinement metric), so that penumbrae are gathered at the
 * resolution the shadow needs instead of the coarse texel the flat
 * geometry asks for. Also rendered below the cut (the irradiance term,
 * mrgi_irradiance_stencil.h): texels whose parent's 3x3 see the light's
 * unshadowed irradiance, estimated on a grid of cells, vary by more than
 * IrradianceTolerance of its maximum, so that a flat wall near a large
 * emitter is not interpolated from coarse texels. One draw per level into its rectangle of the
 * flattened layout; each reads the coarser level's masks and receivers
 * only, so the levels are independent.
 *
 * Inputs are arguments: the vtkMRGIMultiresolution buffer (flags,
 * selection, receivers of this frame) and the vtkMRGIVisibilityPyramid
 * updated on it. C twin and contract: mrgi_incremental_stencil_build()
 * (mrgi_incremental_stencil.h); shader vtkMRGIIncrementalStencilFS.glsl.
 *
 * The same rule drives the indirect light's gather with the discontinuity
 * read from the gathered irradiance instead of masks (issue 17 part 2):
 * BeginIllumination() clears the mask, then, for each level from the
 * coarsest to the finest, BuildIlluminationLevel() writes that level from
 * the irradiance the coarser level gathered, and the gather draws it
 * (vtkMRGIGather::GatherVPLsIncremental()). C twin
 * mrgi_incremental_stencil_illumination_level(); the shader's
 * MRGI_STENCIL_ILLUMINATION variant.
 */
#ifndef vtkMRGIIncrementalStencil_h
#define vtkMRGIIncrementalStencil_h

#include "MRGIRenderingModule.h" // For export macro
#include "vtkObject.h"

#include <memory> // For std::unique_ptr

struct mrgi_area_light_uniforms;
struct vtkMRGIFrameContext;
class vtkMRGIMultiresolution;
class vtkMRGIVisibilityPyramid;
class vtkRenderWindow;
class vtkTextureObject;
class vtkUnsignedCharArray;
class vtkWindow;

class MRGIRENDERING_EXPORT vtkMRGIIncrementalStencil : public vtkObject
{
public:
  static vtkMRGIIncrementalStencil* New();
  vtkTypeMacro(vtkMRGIIncrementalStencil, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Share of a light's samples on which the parent's 3x3 masks must
   * disagree for a texel below the geometric cut to be rendered
   * (mrgi_voxel_refine_threshold(); default 0.25).
   */
  vtkSetClampMacro(Fraction, double, 0.0, 1.0);
  vtkGetMacro(Fraction, double);
  ///@}

  ///@{
  /**
   * Relative spread of the light's unshadowed irradiance over the parent's
   * 3x3 above which a texel below the geometric cut is rendered
   * (mrgi_irradiance_stencil.h; default
   * MRGI_IRRADIANCE_STENCIL_DEFAULT_TOLERANCE; 0 turns the term off).
   */
  vtkSetClampMacro(IrradianceTolerance, double, 0.0, 1.0);
  vtkGetMacro(IrradianceTolerance, double);
  ///@}

  ///@{
  /**
   * Relative threshold T of the illumination rule: a texel below the
   * geometric cut is gathered when its parent's 3x3 gathered irradiance
   * differs by more than T times the larger value in a channel
   * (mrgi_incremental_stencil.h; default
   * MRGI_INCREMENTAL_ILLUMINATION_DEFAULT_THRESHOLD = 0.1; 0: every texel
   * down to the finest level; >= 1: the geometric selection alone).
   */
  vtkSetClampMacro(IlluminationThreshold, double, 0.0, 1.0e30);
  vtkGetMacro(IlluminationThreshold, double);
  ///@}

  ///@{
  /**
   * How the illumination rule compares the parent's 3x3
   * (mrgi_incremental_stencil.h): MRGI_INCREMENTAL_ILLUMINATION_DIFFERENCE
   * (0, NPW10's neighbour difference, default) or _CURVATURE (1, the
   * deviation from the line through opposite neighbours: linear light
   * changes do not refine).
   */
  vtkSetClampMacro(IlluminationMetric, int, 0, 1);
  vtkGetMacro(IlluminationMetric, int);
  ///@}

#ifndef __VTK_WRAP__
  /**
   * Allocate the mask for `buffer` (selection and receivers of this frame)
   * and clear it, before the first BuildIlluminationLevel(). False on error.
   */
  bool BeginIllumination(const vtkMRGIFrameContext& frame, vtkMRGIMultiresolution* buffer);

  /**
   * Write level `level` (finest gathering level .. coarsest) of the mask
   * from `irradiance`, the flattened irradiance the gather wrote for level
   * level + 1 (alpha 1 where it drew a receiver), leaving the other levels
   * as they are. Timer step "select.illumination". False on error.
   */
  bool BuildIlluminationLevel(const vtkMRGIFrameContext& frame, vtkMRGIMultiresolution* buffer,
    vtkTextureObject* irradiance, int level);

  /**
   * Build the stencil from `buffer` (selection and receivers of this frame)
   * and `masks` (updated on it this frame); `light` (world space) feeds the
   * irradiance term, which is off without it. Timer step
   * "select.incremental". False on error.
   */
  bool Build(const vtkMRGIFrameContext& frame, vtkMRGIMultiresolution* buffer,
    vtkMRGIVisibilityPyramid* masks, const mrgi_area_light_uniforms* light = nullptr);
#endif

  /** The rendered texels as colour (flattened layout; 1 = rendered) after Build(); null before. */
  vtkTextureObject* GetSelectionTexture() const;

  /** The depth-stencil texture of the rendered texels after Build(); null before. */
  vtkTextureObject* GetStencilTexture() const;

  /** Read the last Build() back: one byte per flattened texel, 1 = rendered. False before. */
  bool ReadStencil(vtkRenderWindow* window, vtkUnsignedCharArray* mask);

  /** Free every GL resource. */
  void ReleaseGraphicsResources(vtkWindow* w);

protected:
  vtkMRGIIncrementalStencil();
  ~vtkMRGIIncrementalStencil() override;

  double Fraction = 0.25;
  double IrradianceTolerance; // MRGI_IRRADIANCE_STENCIL_DEFAULT_TOLERANCE (constructor)
  double IlluminationThreshold; // MRGI_INCREMENTAL_ILLUMINATION_DEFAULT_THRESHOLD (constructor)
  int IlluminationMetric;         // MRGI_INCREMENTAL_ILLUMINATION_DIFFERENCE (constructor)

  struct Internals;
  std::unique_ptr<Internals> Internal;

private:
  vtkMRGIIncrementalStencil(const vtkMRGIIncrementalStencil&) = delete;
  void operator=(const vtkMRGIIncrementalStencil&) = delete;
};

#endif
