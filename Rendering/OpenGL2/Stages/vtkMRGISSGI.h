/**
 * @class   vtkMRGISSGI
 * @brief   Screen-space one-bounce indirect light and directional occlusion
 *          (Ritschel et al. 2009, as BMR evaluates SSGI) from MRGI's
 *          G-buffer and direct-light image.
 *
 * Inputs are arguments; the stage keeps only GL resources and caches (the
 * kernel of the last sample count, the full-resolution result of the last
 * Render()). Compute() evaluates one level: level 0 is full resolution; a
 * level-l texel is the receiver at its 2^l block's centre pixel, whose
 * samples read the full-resolution buffers (for BMR's stencilled levels).
 * Apply() adds the bounce to a colour target. The estimator, its units
 * (VTK's non-attenuating light units), the sender area and what it leaves
 * out: the C twin mrgi_ssgi.h. Shader vtkMRGISSGIFS.glsl. Each invocation
 * loops twice over the kernel (at most 2 x 512 iterations: far below
 * llvmpipe's 65535).
 *
 * Multiresolution (BMR 3-4, RenderMultiresolution()): the stage's own
 * vtkMRGIBMRMask and vtkMRGIBMRBlend (SSGI row of Table 1: level 2 skipped;
 * GetBMRMask() and GetBMRBlend() to tune them) and vtkMRGIBMRLevels; each
 * level is Compute()'s shader at that level under the level's stencil, the
 * blended image is applied as Apply() does. Documentation/
 * ScreenSpaceEffects-SSGI.md has the measured error and cost.
 */
#ifndef vtkMRGISSGI_h
#define vtkMRGISSGI_h

#include "MRGIRenderingModule.h" // For export macro
#include "vtkObject.h"

#include <memory> // For std::unique_ptr

struct vtkMRGIFrameContext;
class vtkFloatArray;
class vtkMRGIBMRBlend;
class vtkMRGIBMRLevels;
class vtkMRGIBMRMask;
class vtkOpenGLQuadHelper;
class vtkRenderWindow;
class vtkTextureObject;
class vtkWindow;

class MRGIRENDERING_EXPORT vtkMRGISSGI : public vtkObject
{
public:
  static vtkMRGISSGI* New();
  vtkTypeMacro(vtkMRGISSGI, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

#ifndef __VTK_WRAP__
  /**
   * Every texel of level `level` (0..MRGI_SSGI_MAX_LEVEL) of the frame's
   * viewport into `target` at (0, 0) .. (ceil(w / 2^l), ceil(h / 2^l)):
   * rgb = the bounce radiance rho X, a = the directional visibility V (an
   * RGBA float target). `direct` is the senders' radiance (the G-buffer's
   * direct-light attachment, window-sized like the G-buffer). `samples`
   * 1..MRGI_SSGI_MAX_SAMPLES, `radius` > 0 and `bias` >= 0 in eye-space
   * units, finite. Needs the frame's Position, Normal, Albedo and Renderer.
   * Timer step "ssgi". False, with an error naming the problem, on bad
   * input or a GL failure.
   */
  bool Compute(const vtkMRGIFrameContext& frame, vtkTextureObject* direct, int samples,
    double radius, double bias, int level, vtkTextureObject* target);

  /**
   * Add the bounce (rgb of `ssgi`, viewport-sized at (0, 0) as Compute(level
   * 0) writes it) to the RGB of `colour` over the frame's viewport; alpha
   * is kept. Timer step "ssgi.apply". False on error.
   */
  bool Apply(const vtkMRGIFrameContext& frame, vtkTextureObject* ssgi, vtkTextureObject* colour);
#endif

  /**
   * Compute() at full resolution from `colour` as the senders' radiance into
   * the stage's own texture, then Apply() it to `colour`.
   */
  bool Render(const vtkMRGIFrameContext& frame, int samples, double radius, double bias,
    vtkTextureObject* colour);

#ifndef __VTK_WRAP__
  /**
   * Compute() of every stencilled texel of every level of `levels`
   * (prepared for the frame's viewport, stencils built by a
   * vtkMRGIBMRMask) into the levels' colour targets: for each level k,
   * Compute()'s shader at level k under vtkMRGIBMRLevels::LevelStep. Same
   * argument ranges as Compute(). Timer step "ssgi". False, with an error,
   * on bad input or a GL failure.
   */
  bool ComputeLevels(const vtkMRGIFrameContext& frame, vtkTextureObject* direct, int samples,
    double radius, double bias, vtkMRGIBMRLevels* levels);
  /**
   * The multiresolution result of the frame's viewport into `target`
   * (RGBA32F, at least viewport-sized) at (0, 0): the stage's masks
   * (GetBMRMask()), ComputeLevels() and the stage's blend (GetBMRBlend()).
   * rgb is the blended bounce, a the blended V; both are 0 at background
   * pixels (the blend's convention; Compute() writes V = 1 there, and
   * Apply() reads rgb only). False, with an error, on failure.
   */
  bool ComputeMultiresolution(const vtkMRGIFrameContext& frame, vtkTextureObject* direct,
    int samples, double radius, double bias, vtkTextureObject* target);
#endif

  /**
   * As Render(), with the bounce of ComputeMultiresolution() (BMR) instead
   * of the full-resolution one; GetTexture() and ReadResult() then return
   * the blended result.
   */
  bool RenderMultiresolution(const vtkMRGIFrameContext& frame, int samples, double radius,
    double bias, vtkTextureObject* colour);

  ///@{
  /**
   * The multiresolution path's mask and blend (vtkMRGIBMRMask::SSGI preset
   * unless changed) and levels; never null.
   */
  vtkMRGIBMRMask* GetBMRMask();
  vtkMRGIBMRBlend* GetBMRBlend();
  vtkMRGIBMRLevels* GetBMRLevels();
  ///@}

  /**
   * The result of the last Render() or RenderMultiresolution() (RGBA32F,
   * viewport-sized); null before.
   */
  vtkTextureObject* GetTexture();

  /** Read the last render's result back: 4 floats per pixel (rho X rgb, V), rows bottom-up. */
  bool ReadResult(vtkRenderWindow* window, vtkFloatArray* result);

  /** Free every GL resource. */
  void ReleaseGraphicsResources(vtkWindow* w);

protected:
  vtkMRGISSGI();
  ~vtkMRGISSGI() override;

  struct Internals;
  std::unique_ptr<Internals> Internal;

private:
#ifndef __VTK_WRAP__
  // The checks of Compute() but the level's and the target's; the kernel of `samples` cached.
  bool CheckCompute(const vtkMRGIFrameContext& frame, vtkTextureObject* direct, int samples,
    double radius, double bias);
  // Ready the compute program and bind every input and uniform (level `level`); null on error.
  vtkOpenGLQuadHelper* ReadyCompute(const vtkMRGIFrameContext& frame, vtkTextureObject* direct,
    int samples, double radius, double bias, int level);
  // The stage's viewport-sized result texture, (re)allocated for the frame.
  bool PrepareResult(const vtkMRGIFrameContext& frame, vtkTextureObject* colour);
#endif
  vtkMRGISSGI(const vtkMRGISSGI&) = delete;
  void operator=(const vtkMRGISSGI&) = delete;
};

#endif
