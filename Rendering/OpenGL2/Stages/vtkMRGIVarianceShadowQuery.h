/**
 * @class   vtkMRGIVarianceShadowQuery
 * @brief   Shadows of sharp Phong highlights of an area light on the GPU:
 *          the variance shadow query of nichols-penmatsa-wyman-2010
 *          section 3.3.3 (after Donnelly and Lauritzen 2006).
 *
 * Where a highlight is too sharp for the light's samples, the specular sum
 * reads the light on a 5 x 5 grid of cells around the reflection
 * (vtkMRGIAreaLightSpecular.glsl, NPW10 3.2.1). Binary visibility toward 25
 * cells bands the shadows; instead each of 24 cells (one corner dropped)
 * gets a query that stores the distance from the light to the nearest
 * occluder as a fraction z of the ray, and its square; a screen-space box
 * blur of (z, z^2) and the Chebyshev bound turn them into a visibility in
 * [0, 1] per cell ("it essentially performs per-query percentage closer
 * filtering").
 *
 * The contract is the C core's (mrgi_variance_shadow.h section 6):
 * ComputeMoments() is the twin of mrgi_voxel_vsm_specular_moments() at every
 * viewport pixel with a specular material (2x2 interleaving, 6 queries and
 * 12 floats per pixel in MRGI_VOXEL_VSM_TARGETS RGBA32F textures of the
 * viewport's size), the GLSL library GetResolveShaderSource()
 * (vtkMRGIVarianceShadowResolve.glsl, mrgiVsmResolve()) the twin of
 * mrgi_voxel_vsm_resolve() at one pixel. The specular shader resolves at
 * the pixels whose highlight takes the lobe-grid path and weights cell j by
 * query j (mrgi_area_light_specular_visible(), which also says what the
 * dropped corner uses). One ray is the march of vtkMRGIVoxelMarch.glsl
 * (mrgiVoxelOccluderFraction(), C twin mrgi_voxel_march_occluder_fraction()).
 *
 * Inputs: the pass's G-buffer (eye-space position and normal, k_s c_s and
 * Phong exponent; window-sized textures read at the viewport's pixels), the
 * area light (vtkMRGIAreaLight::SetShaderUniforms()), this frame's
 * voxelization (vtkMRGIVoxelization::Voxelize(), its march knobs and its
 * world -> eye matrix) and the eye -> world matrix of the G-buffer.
 */
#ifndef vtkMRGIVarianceShadowQuery_h
#define vtkMRGIVarianceShadowQuery_h

#include "MRGIRenderingModule.h" // For export macro
#include "vtkObject.h"

#include <memory> // For std::unique_ptr

class vtkFloatArray;
struct vtkMRGIFrameContext;
class vtkMRGIAreaLight;
class vtkMRGIVoxelization;
class vtkOpenGLRenderWindow;
class vtkRenderTimerLog;
class vtkRenderWindow;
class vtkShaderProgram;
class vtkTextureObject;
class vtkUnsignedCharArray;
class vtkWindow;

class MRGIRENDERING_EXPORT vtkMRGIVarianceShadowQuery : public vtkObject
{
public:
  static vtkMRGIVarianceShadowQuery* New();
  vtkTypeMacro(vtkMRGIVarianceShadowQuery, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Radius r of the screen-space box blur, in pixels: the moments of a query
   * are averaged over the (2r+1)^2 window's pixels that computed it (with
   * 2x2 interleaving, a quarter of them). 0..MRGI_VOXEL_VSM_MAX_RADIUS (16),
   * default MRGI_VOXEL_VSM_DEFAULT_RADIUS (2). 0 gives binary shadows with
   * the banding NPW10 3.3.3 set out to remove.
   */
  virtual void SetBlurRadius(int radius);
  vtkGetMacro(BlurRadius, int);
  ///@}

  ///@{
  /**
   * Minimum variance of the Chebyshev bound (DL06), in squared ray lengths,
   * clamped to >= 0 (NaN ignored): default MRGI_VOXEL_VSM_DEFAULT_MIN_VARIANCE (1e-4). Larger values
   * lighten shadows near their occluders' depth.
   */
  virtual void SetMinVariance(double variance);
  vtkGetMacro(MinVariance, double);
  ///@}

  /**
   * The moments pass: draws the frame viewport's moments (layout in the
   * class notes) for `light`, marching through `voxels` (voxelized this
   * frame), from the frame's G-buffer (position, normal and the specular
   * targets), eye -> world transform and projection. Timer step
   * "specular.moments" on the frame's timer. False, with an error, on bad
   * input or a shader failure.
   */
  bool ComputeMoments(
    const vtkMRGIFrameContext& frame, vtkMRGIAreaLight* light, vtkMRGIVoxelization* voxels);

  /**
   * Bind the last moments to a program that includes
   * GetResolveShaderSource(): activates the MRGI_VOXEL_VSM_TARGETS textures
   * and sets mrgiVsmMoments0..2, mrgiVsmSize, mrgiVsmRadius and
   * mrgiVsmMinVariance. Call DeactivateTextures() after drawing. False
   * before a successful ComputeMoments().
   */
  bool SetResolveUniforms(vtkShaderProgram* program);
  void DeactivateTextures();

  /**
   * The GLSL resolve library (vtkMRGIVarianceShadowResolve.glsl): uniforms and
   * mrgiVsmResolve(), mrgiVsmChebyshev(); no main(), no #version. After
   * VTK's system declarations and the core's constants block.
   */
  static const char* GetResolveShaderSource();

  /**
   * Read the last moments back in the C twin's layout (for tests):
   * `moments` W H tuples of 2 MRGI_VOXEL_VSM_QUERIES floats, pixel
   * p = y W + x (viewport-local, rows bottom-up) query j at (2 j, 2 j + 1),
   * (0, 0) for queries it did not compute; `phaseSets` W H bytes, the phases
   * each pixel computed (1 << phase, or 0), as mrgi_voxel_vsm_resolve()
   * takes them. False before a successful ComputeMoments().
   */
  bool ReadMoments(vtkRenderWindow* window, vtkFloatArray* moments, vtkUnsignedCharArray* phaseSets);

  /** Size (W, H) of the last moments; 0 before ComputeMoments(). */
  void GetMomentsSize(int size[2]) const;

  /** Moments texture `target` (0..MRGI_VOXEL_VSM_TARGETS-1) of the last pass, or null. */
  vtkTextureObject* GetMomentsTexture(int target) const;

  /** Free every GL resource (textures, framebuffer, program). */
  void ReleaseGraphicsResources(vtkWindow* w);

protected:
  vtkMRGIVarianceShadowQuery();
  ~vtkMRGIVarianceShadowQuery() override;

  int BlurRadius = 2;         // MRGI_VOXEL_VSM_DEFAULT_RADIUS, set by the constructor
  double MinVariance = 1e-4;  // MRGI_VOXEL_VSM_DEFAULT_MIN_VARIANCE, set by the constructor

  struct Internals;
  std::unique_ptr<Internals> Internal;

private:
  vtkMRGIVarianceShadowQuery(const vtkMRGIVarianceShadowQuery&) = delete;
  void operator=(const vtkMRGIVarianceShadowQuery&) = delete;
};

#endif
