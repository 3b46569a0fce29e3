/**
 * @class   vtkMRGISpecularStencil
 * @brief   The stencil of the multiresolution specular gather of one area
 *          light (nichols-penmatsa-wyman-2010 3.2.1 and 3.4): the texels
 *          whose Phong highlight is gathered, refined where the lobe is
 *          narrower than the texel spacing.
 *
 * Builds the material pyramid (max k_s, max and min Phong exponent per
 * texel) from the G-buffer's specular targets, the refinement bits (the
 * buffer's geometric REFINE flag, mixed exponents and the lobe metric m)
 * and the selection (texels with specular material only), with its
 * stencil. vtkMRGIGather::GatherSpecular() gathers at its texels;
 * vtkMRGIUpsample reads its selection.
 *
 * Inputs are arguments: the frame (G-buffer with specular targets, view
 * transform, projection) and the vtkMRGIMultiresolution buffer (flags,
 * receivers, pixel size of this frame). C twin and contract:
 * mrgi_specular_material_build() and mrgi_specular_stencil_build()
 * (mrgi_specular_stencil.h); shader vtkMRGISpecularStencilFS.glsl.
 */
#ifndef vtkMRGISpecularStencil_h
#define vtkMRGISpecularStencil_h

#include "MRGIRenderingModule.h" // For export macro
#include "vtkObject.h"

#include <memory> // For std::unique_ptr

struct mrgi_area_light_uniforms;
struct vtkMRGIFrameContext;
class vtkFloatArray;
class vtkMRGIMultiresolution;
class vtkRenderWindow;
class vtkTextureObject;
class vtkUnsignedCharArray;
class vtkWindow;

class MRGIRENDERING_EXPORT vtkMRGISpecularStencil : public vtkObject
{
public:
  static vtkMRGISpecularStencil* New();
  vtkTypeMacro(vtkMRGISpecularStencil, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * The lobe-size refinement metric (NPW10 3.2.1, "image-space sample
   * spacing must be denser than the lobe width"; mrgi_specular_stencil.h).
   * On (default): also refine a texel whose Phong lobe is narrower than its
   * spacing (m > LobeThreshold). Off: the geometric refinement and mixed
   * exponents alone (for comparisons and tests).
   */
  vtkSetMacro(LobeRefinement, bool);
  vtkGetMacro(LobeRefinement, bool);
  vtkBooleanMacro(LobeRefinement, bool);
  ///@}

  ///@{
  /**
   * Refine where the lobe metric m exceeds this (> 0). 1 is NPW10's
   * "spacing denser than the lobe width"; smaller values refine earlier
   * (several samples across a lobe). Default 0.125 (measured:
   * Documentation/AreaLights.md).
   */
  vtkSetClampMacro(LobeThreshold, double, 1e-3, 1e3);
  vtkGetMacro(LobeThreshold, double);
  ///@}

#ifndef __VTK_WRAP__
  /**
   * Build the stencil for `light` (world space) from the frame's G-buffer
   * (Specular and Shininess required) and `buffer` (Update()d and its
   * receivers built this frame). Timer step "select.specular". False on
   * error.
   */
  bool Build(const vtkMRGIFrameContext& frame, vtkMRGIMultiresolution* buffer,
    const mrgi_area_light_uniforms& light);
#endif

  /** The selection as colour (flattened layout; 1 = gathered) after Build(); null before. */
  vtkTextureObject* GetSelectionTexture() const;

  /** The depth-stencil texture of the selection after Build(); null before. */
  vtkTextureObject* GetStencilTexture() const;

  /** Level `level` of the material pyramid (x max k_s, y max exponent, z min exponent) after Build(); null otherwise. */
  vtkTextureObject* GetMaterialTexture(int level) const;

  /**
   * Read back the last Build(): the selection (1 = selected) and the
   * refinement bits (MRGI_SPECULAR_STENCIL_*), one byte per flattened
   * texel; `fromStencil` reads the selection from the stencil. `bits` may
   * be null.
   */
  bool ReadStencil(vtkRenderWindow* window, vtkUnsignedCharArray* selection,
    vtkUnsignedCharArray* bits, bool fromStencil = false);

  /** Read the material pyramid of the last Build() (4 floats per flattened texel). */
  bool ReadMaterial(vtkRenderWindow* window, vtkFloatArray* material);

  /** Free every GL resource. */
  void ReleaseGraphicsResources(vtkWindow* w);

protected:
  vtkMRGISpecularStencil();
  ~vtkMRGISpecularStencil() override;

  bool LobeRefinement = true;
  double LobeThreshold = 0.125;

  struct Internals;
  std::unique_ptr<Internals> Internal;

private:
  vtkMRGISpecularStencil(const vtkMRGISpecularStencil&) = delete;
  void operator=(const vtkMRGISpecularStencil&) = delete;
};

#endif
