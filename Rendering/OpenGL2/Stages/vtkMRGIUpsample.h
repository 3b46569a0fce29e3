/**
 * @class   vtkMRGIUpsample
 * @brief   Upsampling and resolve of a multiresolution gather
 *          (nichols-wyman-2009 3.5): coarse to fine, each texel that was
 *          not gathered is interpolated from the coarser level, never from
 *          texels that hold nothing; then the full-resolution E and
 *          strength x albedo x E.
 *
 * Inputs are arguments: the vtkMRGIMultiresolution buffer (layout, flags),
 * the flattened irradiance a gather wrote (vtkMRGIGather), and the
 * flattened mask of the texels that gather rendered (the buffer's selection,
 * the incremental stencil's or the specular stencil's colour). C twin:
 * mrgi_upsample() and mrgi_surface_detail_factor() (mrgi_upsample.h);
 * shader vtkMRGIMultiresUpsampleFS.glsl (stages 0 state/value, 1 filter,
 * 2 resolve).
 */
#ifndef vtkMRGIUpsample_h
#define vtkMRGIUpsample_h

#include "MRGIRenderingModule.h" // For export macro
#include "vtkObject.h"

#include <memory> // For std::unique_ptr

struct vtkMRGIFrameContext;
class vtkFloatArray;
class vtkMRGIMultiresolution;
class vtkRenderWindow;
class vtkTextureObject;
class vtkWindow;

class MRGIRENDERING_EXPORT vtkMRGIUpsample : public vtkObject
{
public:
  static vtkMRGIUpsample* New();
  vtkTypeMacro(vtkMRGIUpsample, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum UpsampleModes
  {
    UpsampleTent = 0,        ///< nichols-wyman-2009 3.5 (default)
    UpsampleMaskWeighted = 1 ///< besenthal et al. eq. 1
  };

#ifndef __VTK_WRAP__
  /**
   * Upsample and combine the levels of `irradiance` (the flattened output
   * of a gather on `buffer`) where `rendered` (a flattened mask, red > 0.5)
   * says texels were gathered. `mode`: UpsampleTent or
   * UpsampleMaskWeighted with `maskWeight`. Timer step "upsample.levels".
   * `scratch`, when given (RGBA32F, at least level 0's size), is
   * overwritten with the per-level values instead of a texture of the
   * stage's own: Resolve()'s irradiance target can be it, as Resolve()
   * reads only the filtered values (one level-0-sized float texture less
   * to allocate; Documentation/Multiresolution.md, "Cold start"). False on
   * error.
   */
  bool Upsample(const vtkMRGIFrameContext& frame, vtkMRGIMultiresolution* buffer,
    vtkTextureObject* irradiance, vtkTextureObject* rendered, int mode, double maskWeight,
    vtkTextureObject* scratch = nullptr);

  /**
   * After Upsample(): write the full-resolution irradiance E and the
   * radiance strength x albedo x E into `irradianceTarget` and `target`
   * (window-sized textures, like the frame's G-buffer) over the frame's
   * viewport, E multiplied by the surface-detail modulation alpha
   * max(V.N, 0) + 1 - alpha (nichols-wyman-2009 section 4.2, eq. 2; 0:
   * off). Timer step "upsample.resolve". False on error.
   */
  bool Resolve(const vtkMRGIFrameContext& frame, vtkMRGIMultiresolution* buffer,
    vtkTextureObject* albedo, vtkTextureObject* irradianceTarget, vtkTextureObject* target,
    double strength, double surfaceDetail);
#endif

  /** Read the upsampled level 0 (RGB = E, A = 1 where it holds data) back, W x H RGBA. */
  bool ReadUpsampled(vtkRenderWindow* window, vtkFloatArray* upsampled);

  /** Free every GL resource. */
  void ReleaseGraphicsResources(vtkWindow* w);

protected:
  vtkMRGIUpsample();
  ~vtkMRGIUpsample() override;

  struct Internals;
  std::unique_ptr<Internals> Internal;

private:
  vtkMRGIUpsample(const vtkMRGIUpsample&) = delete;
  void operator=(const vtkMRGIUpsample&) = delete;
};

#endif
