/**
 * @class   vtkMRGISSAO
 * @brief   Screen-space ambient occlusion from MRGI's G-buffer, as VTK
 *          9.1's vtkSSAOPass computes and applies it: its hemisphere kernel
 *          (the same samples for the same size), its window noise, range
 *          check and bias; AO multiplies a colour's RGB.
 *
 * Inputs are arguments; the stage keeps only GL resources and caches (the
 * kernel of the last size, the full-resolution AO of the last Render()).
 * ComputeAO() evaluates one level: level 0 is full resolution; a level-l
 * texel is the receiver at its 2^l block's centre pixel, whose samples read
 * the full-resolution G-buffer (for multiresolution blending, BMR). Apply()
 * multiplies a colour target by an AO texture over the frame's viewport, with
 * vtkSSAOPass's optional 3x3 Gaussian. C twin: mrgi_ssao.h (the differences
 * from vtkSSAOPass, and why, are listed there). Shader vtkMRGISSAOFS.glsl.
 * Each invocation loops over the kernel once (at most 1000 samples: below
 * llvmpipe's 65535 iterations).
 *
 * Multiresolution (BMR 3-4, RenderMultiresolution()): the stage's own
 * vtkMRGIBMRMask and vtkMRGIBMRBlend (SSAO preset of Table 1; GetBMRMask()
 * and GetBMRBlend() to tune them) and vtkMRGIBMRLevels; each level's AO is
 * the same shader as ComputeAO() at that level, drawn under the level's
 * stencil; the blended image is applied as Apply() does.
 * Documentation/ScreenSpaceEffects-SSAO.md has the measured error and cost.
 */
#ifndef vtkMRGISSAO_h
#define vtkMRGISSAO_h

#include "MRGIRenderingModule.h" // For export macro
#include "vtkObject.h"

#include <memory> // For std::unique_ptr
#include <vector> // For std::vector

struct vtkMRGIFrameContext;
class vtkFloatArray;
class vtkMRGIBMRBlend;
class vtkMRGIBMRLevels;
class vtkMRGIBMRMask;
class vtkOpenGLQuadHelper;
class vtkOpenGLRenderWindow;
class vtkRenderWindow;
class vtkTextureObject;
class vtkWindow;

class MRGIRENDERING_EXPORT vtkMRGISSAO : public vtkObject
{
public:
  static vtkMRGISSAO* New();
  vtkTypeMacro(vtkMRGISSAO, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

#ifndef __VTK_WRAP__
  /**
   * The AO factor of every texel of level `level` (0..MRGI_SSAO_MAX_LEVEL)
   * of the frame's viewport into `target`'s red channel at (0, 0) ..
   * (ceil(w / 2^l), ceil(h / 2^l)) (the target must be at least that large;
   * a float format keeps AO unquantized). `kernelSize` 1..1000, `radius` > 0
   * and `bias` in eye-space units, finite. Needs the frame's Position and
   * Normal, Renderer (its camera's projection) and Window (its noise
   * texture). Timer step "ssao.ao". False, with an error naming the
   * problem, on bad input or a GL failure.
   */
  bool ComputeAO(const vtkMRGIFrameContext& frame, int kernelSize, double radius, double bias,
    int level, vtkTextureObject* target);

  /**
   * Multiply the RGB of `colour` (a window-sized texture like the
   * G-buffer's) by the full-resolution AO in `ao` (viewport-sized, at (0,
   * 0), as ComputeAO(level 0) writes it) over the frame's viewport; alpha
   * is kept. `blur`: vtkSSAOPass's 3x3 Gaussian of AO first (taps clamped
   * to the viewport). Timer step "ssao.apply". False on error.
   */
  bool Apply(
    const vtkMRGIFrameContext& frame, vtkTextureObject* ao, bool blur, vtkTextureObject* colour);
#endif

  /**
   * ComputeAO() at full resolution into the stage's own AO texture, then
   * Apply() it to `colour`: vtkSSAOPass's effect on MRGI's direct light.
   */
  bool Render(const vtkMRGIFrameContext& frame, int kernelSize, double radius, double bias,
    bool blur, vtkTextureObject* colour);

#ifndef __VTK_WRAP__
  /**
   * The occlusion 1 - AO of every stencilled texel of every level of
   * `levels` (prepared for the frame's viewport, stencils built by a
   * vtkMRGIBMRMask) into the levels' colour targets' red channel: for each
   * level k, ComputeAO()'s shader at level k under vtkMRGIBMRLevels::LevelStep.
   * Occlusion rather than AO because the blend writes 0 at background
   * pixels, where AO is 1. Same argument ranges as ComputeAO(). Timer step
   * "ssao.ao". False, with an error, on bad input or a GL failure.
   */
  bool ComputeOcclusionLevels(const vtkMRGIFrameContext& frame, int kernelSize, double radius,
    double bias, vtkMRGIBMRLevels* levels);
  /**
   * The multiresolution occlusion 1 - AO of the frame's viewport into the
   * red channel of `target` (RGBA32F, at least viewport-sized) at (0, 0):
   * the stage's masks (GetBMRMask()), ComputeOcclusionLevels() and the
   * stage's blend (GetBMRBlend()). False, with an error, on failure.
   */
  bool ComputeOcclusionMultiresolution(const vtkMRGIFrameContext& frame, int kernelSize,
    double radius, double bias, vtkTextureObject* target);
#endif
  /**
   * RenderMultiresolution: as Render(), with the AO of
   * ComputeOcclusionMultiresolution() (BMR) instead of the full-resolution
   * one. GetAOTexture() and ReadAO() then return nothing new.
   */
  bool RenderMultiresolution(const vtkMRGIFrameContext& frame, int kernelSize, double radius,
    double bias, bool blur, vtkTextureObject* colour);
  ///@{
  /**
   * The multiresolution path's mask and blend (vtkMRGIBMRMask::SSAO preset
   * unless changed) and levels; never null.
   */
  vtkMRGIBMRMask* GetBMRMask();
  vtkMRGIBMRBlend* GetBMRBlend();
  vtkMRGIBMRLevels* GetBMRLevels();
  ///@}
  /** The full-resolution AO of the last Render() (R32F, viewport-sized); null before. */
  vtkTextureObject* GetAOTexture();

  /** Read the AO of the last Render() back, one float per pixel, rows bottom-up. */
  bool ReadAO(vtkRenderWindow* window, vtkFloatArray* ao);

#ifndef __VTK_WRAP__
  /**
   * The window's noise tile that vtkSSAOPass and this stage rotate the
   * kernel with (vtkOpenGLRenderWindow::GetNoiseTextureUnit(): 64 x 64,
   * one float per texel, rows bottom-up), for the C twin.
   */
  static bool ReadNoise(vtkOpenGLRenderWindow* window, std::vector<float>& noise);
#endif

  /** Free every GL resource. */
  void ReleaseGraphicsResources(vtkWindow* w);

protected:
  vtkMRGISSAO();
  ~vtkMRGISSAO() override;

  struct Internals;
  std::unique_ptr<Internals> Internal;

private:
#ifndef __VTK_WRAP__
  // Apply() of an AO (occlusion false) or 1 - AO (true) texture.
  bool ApplyTexture(const vtkMRGIFrameContext& frame, vtkTextureObject* ao, bool occlusion,
    bool blur, vtkTextureObject* colour);
  // The checks of ComputeAO() but the level's; the kernel of `kernelSize` cached.
  bool CheckAO(const vtkMRGIFrameContext& frame, int kernelSize, double radius, double bias);
  // Ready the AO program and set every uniform (level `level`); null on error.
  vtkOpenGLQuadHelper* ReadyAO(const vtkMRGIFrameContext& frame, int kernelSize, double radius,
    double bias, int level);
#endif
  vtkMRGISSAO(const vtkMRGISSAO&) = delete;
  void operator=(const vtkMRGISSAO&) = delete;
};

#endif
