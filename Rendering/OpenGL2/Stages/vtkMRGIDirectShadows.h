/**
 * @class   vtkMRGIDirectShadows
 * @brief   Screen-space shadow factors of VTK's lights from the reflective
 *          shadow maps: hard (3 x 3 PCF) or soft (PCSS, Fernando 2005).
 *
 * After the eye G-buffer is captured, Compute() writes, for each of the
 * first MRGI_SHADOW_SLOTS shader lights, a factor in [0, 1] per pixel: 1
 * lit, 0 in the umbra. The RSM views (vtkMRGIReflectiveShadowMapPass: spot
 * = one perspective view, point = up to six cube faces, directional = one
 * orthographic view) are the shadow maps, so no extra render of the scene
 * is needed. vtkMRGIPass applies the factors to each light's contribution
 * (Documentation/DirectShadows.md).
 *
 * Inputs are arguments: the frame (G-buffer position and normal, viewport,
 * eye -> world, timer), the RSM pass, the light of each slot, the
 * parameters, and the target. C twin: mrgi_direct_shadow.h
 * (mrgi_direct_shadow_gbuffer() per slot); shader
 * vtkMRGIDirectShadowFS.glsl. Each RSM view's depth map (light-view depth,
 * mrgi_direct_shadow_depth_map()) is derived once per RSM render; then one
 * draw per (slot, view): the slot's channel only (colour mask), each draw
 * writing the pixels its view holds.
 *
 * Multiresolution (BMR 3-4, SSM preset of Table 1): ComputeLevels() runs
 * the same draws into each level of a vtkMRGIBMRLevels buffer under its
 * stencil (a level-k texel is the receiver at its 2^k block's centre
 * pixel, as vtkMRGISSAO does); ComputeMultiresolution() builds the masks
 * with the shadow edges of the hard factors of slot 0, blends the levels
 * and writes the factors as Compute() does.
 */
#ifndef vtkMRGIDirectShadows_h
#define vtkMRGIDirectShadows_h

#include "MRGIRenderingModule.h" // For export macro
#include "vtkObject.h"

#include <memory> // For std::unique_ptr

struct mrgi_direct_shadow_params;
struct vtkMRGIFrameContext;
class vtkFloatArray;
class vtkMRGIBMRBlend;
class vtkMRGIBMRLevels;
class vtkMRGIBMRMask;
class vtkMRGIReflectiveShadowMapPass;
class vtkRenderWindow;
class vtkTextureObject;
class vtkWindow;

class MRGIRENDERING_EXPORT vtkMRGIDirectShadows : public vtkObject
{
public:
  static vtkMRGIDirectShadows* New();
  vtkTypeMacro(vtkMRGIDirectShadows, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

#ifndef __VTK_WRAP__
  /**
   * Write the shadow factors into `factors` (a window-sized RGBA float
   * texture, like the G-buffer's) over frame.Viewport: channel s = factor
   * of slot s (s < MRGI_SHADOW_SLOTS, so red and green), 1 where there is
   * no geometry, no view holds the pixel, or slotLights[s] is -1; the other
   * channels 1. `slotLights` has MRGI_SHADOW_SLOTS entries: the index, in
   * the renderer's light collection, of VTK's shader light s, or -1.
   * Needs frame.Window, frame.Position, frame.Normal and frame.ViewToWorld.
   * Timer step "shadows.factors". False (with an error naming the problem) on bad
   * input, a light with more than MRGI_DIRECT_SHADOW_MAX_VIEWS views, or a
   * shader that does not build.
   */
  bool Compute(const vtkMRGIFrameContext& frame, vtkMRGIReflectiveShadowMapPass* rsm,
    const int* slotLights, const mrgi_direct_shadow_params& params, vtkTextureObject* factors);
  /**
   * Compute()'s draws into every level of `levels` (prepared for the
   * frame's viewport, stencils built) under its stencil: level k texel t
   * holds 1 - factor of the receiver at pixel min(t 2^k + 2^(k-1), size - 1)
   * (level 0: t), channel s = slot s; 0 (lit) where nothing was drawn.
   * 1 - factor because the blend writes 0 at background pixels.
   * Timer step "shadows.factors". False (with an error) on bad input.
   */
  bool ComputeLevels(const vtkMRGIFrameContext& frame, vtkMRGIReflectiveShadowMapPass* rsm,
    const int* slotLights, const mrgi_direct_shadow_params& params, vtkMRGIBMRLevels* levels);
  /**
   * The factors of Compute() (same target, layout and contract) at
   * multiple resolutions: hard factors for the shadow edges, the stage's
   * masks (GetBMRMask(), SSM preset), ComputeLevels(), the stage's blend
   * (GetBMRBlend()), then factor = 1 - blended over the viewport (timer
   * step "shadows.factors.invert"). False (with an error) on failure.
   */
  bool ComputeMultiresolution(const vtkMRGIFrameContext& frame,
    vtkMRGIReflectiveShadowMapPass* rsm, const int* slotLights,
    const mrgi_direct_shadow_params& params, vtkTextureObject* factors);
#endif
  ///@{
  /** The multiresolution path's mask, blend (SSM preset unless changed) and levels; never null. */
  vtkMRGIBMRMask* GetBMRMask();
  vtkMRGIBMRBlend* GetBMRBlend();
  vtkMRGIBMRLevels* GetBMRLevels();
  ///@}

  /** Read `factors` back (RGBA floats, the whole texture, rows bottom-up). */
  static bool ReadFactors(vtkRenderWindow* window, vtkTextureObject* factors, vtkFloatArray* out);

  /** Number of (slot, view) draws of the last Compute(). */
  vtkGetMacro(NumberOfDraws, int);

  /**
   * How many times the views' depth maps were derived from the RSM
   * positions: only when the RSMs were re-rendered
   * (vtkMRGIReflectiveShadowMapPass::GetContentTime()), the resolution or
   * the number of views changed, or after ReleaseGraphicsResources().
   */
  vtkIdType GetNumberOfDepthUpdates() const;

  /** Free every GL resource. */
  void ReleaseGraphicsResources(vtkWindow* w);

protected:
  vtkMRGIDirectShadows();
  ~vtkMRGIDirectShadows() override;

  int NumberOfDraws = 0;

  struct Internals;
  std::unique_ptr<Internals> Internal;

private:
#ifndef __VTK_WRAP__
  // Compute() into `factors`, or ComputeLevels() into `levels` (the other null).
  bool Run(const vtkMRGIFrameContext& frame, vtkMRGIReflectiveShadowMapPass* rsm,
    const int* slotLights, const mrgi_direct_shadow_params& params, vtkTextureObject* factors,
    vtkMRGIBMRLevels* levels);
#endif
  vtkMRGIDirectShadows(const vtkMRGIDirectShadows&) = delete;
  void operator=(const vtkMRGIDirectShadows&) = delete;
};

#endif
