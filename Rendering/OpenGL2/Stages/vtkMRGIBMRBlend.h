/**
 * @class   vtkMRGIBMRBlend
 * @brief   Blends the BMR levels of an effect into one full-resolution
 *          image (besenthal-maisch-ropinski 3.3, 4.2, eq. 1 with its index
 *          corrected): from the coarsest level up, each level's bilinear
 *          value over its stencilled taps (renormalised) is mixed in with
 *          lambda_k = min(bilinear(a_k) w_k, 1).
 *
 * Inputs are arguments: the vtkMRGIBMRLevels buffer (colours rendered by an
 * effect under the stencils, masks by vtkMRGIBMRMask) and the target, a
 * window-sized RGBA32F texture written over the frame's viewport (0 at
 * background pixels). C twin: mrgi_bmr_blend() (mrgi_bmr_blend.h); shader
 * vtkMRGIBMRBlendFS.glsl. Timer step "bmr.blend".
 */
#ifndef vtkMRGIBMRBlend_h
#define vtkMRGIBMRBlend_h

#include "MRGIRenderingModule.h" // For export macro
#include "vtkObject.h"

#include <functional> // For std::function
#include <memory>     // For std::unique_ptr

struct vtkMRGIFrameContext;
class vtkMRGIBMRLevels;
class vtkMRGIBMRMask;
class vtkTextureObject;
class vtkWindow;

class MRGIRENDERING_EXPORT vtkMRGIBMRBlend : public vtkObject
{
public:
  static vtkMRGIBMRBlend* New();
  vtkTypeMacro(vtkMRGIBMRBlend, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /** Table 1's weights of an effect (vtkMRGIBMRMask::SSAO, SSM, SSGI). */
  void SetPreset(int effect);

  ///@{
  /** w_k of level k = 0..3, finite >= 0 (level 3's is not used: it is the base). */
  void SetWeight(int level, double weight);
  double GetWeight(int level) const;
  ///@}

#ifndef __VTK_WRAP__
  /**
   * Blend `levels` into `target` over the frame's viewport (the levels are
   * prepared for its size). False (with an error) on bad input or a GL error.
   */
  bool Blend(const vtkMRGIFrameContext& frame, vtkMRGIBMRLevels* levels, vtkTextureObject* target);

  /**
   * The multiresolution path of a screen-space effect (BMR 3-4) over the
   * frame's viewport into `target` (RGBA32F, at least viewport-sized,
   * written at (0, 0)): `levels` prepared for the viewport's size, `mask`
   * built from the frame's G-buffer, `computeLevels(levels)` (the effect,
   * e.g. through RenderLevels()), `blend` into the target. The one
   * sequence vtkMRGISSAO and vtkMRGISSGI share. False, with an error, on
   * failure.
   */
  static bool RenderMultiresolution(const vtkMRGIFrameContext& frame, vtkMRGIBMRMask* mask,
    vtkMRGIBMRBlend* blend, vtkMRGIBMRLevels* levels,
    const std::function<bool(vtkMRGIBMRLevels*)>& computeLevels, vtkTextureObject* target);
#endif

  /** Free every GL resource. */
  void ReleaseGraphicsResources(vtkWindow* w);

protected:
  vtkMRGIBMRBlend();
  ~vtkMRGIBMRBlend() override;

  double Weight[4];

  struct Internals;
  std::unique_ptr<Internals> Internal;

private:
  vtkMRGIBMRBlend(const vtkMRGIBMRBlend&) = delete;
  void operator=(const vtkMRGIBMRBlend&) = delete;
};

#endif
