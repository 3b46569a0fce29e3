/**
 * @class   vtkMRGIBMRMask
 * @brief   BMR edge masks and inclusive per-level stencils
 *          (besenthal-maisch-ropinski 3.1, 4.1): from the G-buffer (and an
 *          optional shadow image) to each level's mask a_k and stencil S_k
 *          in a vtkMRGIBMRLevels buffer.
 *
 * e(p) is 1 at normal creases, depth kinks (scale-free through the pixel
 * size s(d) of the multiresolution thresholds) and shadow edges; per level
 * it is max-downsampled and blurred by a Gaussian of variance sigma_k^2 in
 * level-k texels; S_k = NE_k && (a_k > 0 || S_{k-1} under it), level 4
 * everywhere. As an ablation, BuildFromFlags() takes the NW09 min-max flags
 * of a vtkMRGIMultiresolution buffer instead of e. Inputs are arguments.
 * C twin: mrgi_bmr_mask_build(), mrgi_bmr_mask_from_flags()
 * (mrgi_bmr_mask.h); shader vtkMRGIBMRMaskFS.glsl. Timer step "bmr.mask".
 */
#ifndef vtkMRGIBMRMask_h
#define vtkMRGIBMRMask_h

#include "MRGIRenderingModule.h" // For export macro
#include "vtkObject.h"

#include <memory> // For std::unique_ptr

struct vtkMRGIFrameContext;
struct mrgi_bmr_params;
class vtkMRGIBMRLevels;
class vtkMRGIMultiresolution;
class vtkTextureObject;
class vtkWindow;

class MRGIRENDERING_EXPORT vtkMRGIBMRMask : public vtkObject
{
public:
  static vtkMRGIBMRMask* New();
  vtkTypeMacro(vtkMRGIBMRMask, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum Effects
  {
    SSAO = 0, ///< BMR Table 1, screen-space ambient occlusion
    SSM = 1,  ///< soft shadow mapping
    SSGI = 2  ///< screen-space global illumination (level 2 skipped)
  };

  enum Combinations
  {
    CombineMax = 0, ///< e = 1 when any test that is on passes (OR; default)
    CombineMin = 1  ///< e = 1 when all tests that are on pass (AND)
  };

  /** Table 1's variances and skip flags of an effect, the default thresholds and CombineMax. */
  void SetPreset(int effect);

  ///@{
  /**
   * Depth threshold T_d (a depth kink in pixel widths) and normal threshold
   * T_n (change of a unit-normal component); a negative value turns the
   * test off, 0 makes every valid pixel an edge (the full-resolution path).
   */
  vtkSetMacro(DepthThreshold, double);
  vtkGetMacro(DepthThreshold, double);
  vtkSetMacro(NormalThreshold, double);
  vtkGetMacro(NormalThreshold, double);
  ///@}

  ///@{
  /** How the tests combine: CombineMax (default) or CombineMin. */
  vtkSetClampMacro(Combine, int, CombineMax, CombineMin);
  vtkGetMacro(Combine, int);
  ///@}

  ///@{
  /** sigma_k^2 of level k = 0..3 in level-k texels^2, 0..16 (MRGI_BMR_MAX_VARIANCE). */
  void SetVariance(int level, double variance);
  double GetVariance(int level) const;
  ///@}

  ///@{
  /** Whether level k (0..2) is skipped (S_k = 0; SSGI skips level 1). */
  void SetSkipLevel(int level, bool skip);
  bool GetSkipLevel(int level) const;
  ///@}

#ifndef __VTK_WRAP__
  /** The settings as the C twin's parameters (weights left 0). */
  void GetParams(mrgi_bmr_params* params) const;

  /**
   * Masks and stencils of the frame's G-buffer into `levels` (prepared for
   * the frame's viewport size). `shadow`: null, or a window-sized texture
   * whose red channel is a one-sample shadow factor (the shadow test).
   * False (with an error) on bad input or a GL error.
   */
  bool Build(const vtkMRGIFrameContext& frame, vtkMRGIBMRLevels* levels, vtkTextureObject* shadow);

  /**
   * The ablation: the same masks with E_k from `buffer`'s NW09 flags
   * (updated for this frame's G-buffer) instead of e; thresholds unused.
   */
  bool BuildFromFlags(
    const vtkMRGIFrameContext& frame, vtkMRGIBMRLevels* levels, vtkMRGIMultiresolution* buffer);
#endif

  /** Free every GL resource. */
  void ReleaseGraphicsResources(vtkWindow* w);

protected:
  vtkMRGIBMRMask();
  ~vtkMRGIBMRMask() override;

  double DepthThreshold;
  double NormalThreshold;
  int Combine = CombineMax;
  double Variance[4];
  bool Skip[4];

  struct Internals;
  std::unique_ptr<Internals> Internal;

private:
  vtkMRGIBMRMask(const vtkMRGIBMRMask&) = delete;
  void operator=(const vtkMRGIBMRMask&) = delete;

#ifndef __VTK_WRAP__
  bool Run(const vtkMRGIFrameContext& frame, vtkMRGIBMRLevels* levels, vtkTextureObject* shadow,
    vtkMRGIMultiresolution* buffer);
#endif
};

#endif
