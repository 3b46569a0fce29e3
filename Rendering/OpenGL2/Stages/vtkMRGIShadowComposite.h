/**
 * @class   vtkMRGIShadowComposite
 * @brief   Shadows applied to VTK's direct light: each light's term, as
 *          VTK's own light loop computed it, scaled by its shadow factor.
 *
 * The scene pass captures the terms of VTK's first MRGI_SHADOW_SLOTS
 * shader lights beside its colour (mrgi_buffers.h, MRGI_GBUFFER_LIGHT0..);
 * vtkMRGIDirectShadows computes a factor per light and pixel; this stage
 * writes colour - sum (1 - f) x term (PBR colours through their display
 * gamma), so a lit pixel is VTK's colour bit for bit. Why this design and
 * not a second scene render: Documentation/DirectShadows.md.
 *
 * Inputs are arguments. C twin: mrgi_shadow_composite() (mrgi_shadow_composite.h);
 * shader vtkMRGIShadowCompositeFS.glsl; parity test TestMRGIShadowComposite.
 */
#ifndef vtkMRGIShadowComposite_h
#define vtkMRGIShadowComposite_h

#include "MRGIRenderingModule.h" // For export macro
#include "vtkObject.h"

#include "mrgi_buffers.h" // For MRGI_SHADOW_SLOTS

#include <memory> // For std::unique_ptr

struct vtkMRGIFrameContext;
class vtkTextureObject;
class vtkWindow;

class MRGIRENDERING_EXPORT vtkMRGIShadowComposite : public vtkObject
{
public:
  static vtkMRGIShadowComposite* New();
  vtkTypeMacro(vtkMRGIShadowComposite, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

#ifndef __VTK_WRAP__
  /**
   * Write the shadowed `colour` into `target` over the frame's viewport
   * (window-sized textures, like the G-buffer; `target` must not be
   * `colour`). `terms[s]`: slot s's light term; `factors`: channel s = slot
   * s's factor. Timer step "shadows.apply". False (with an error) when an
   * input is missing or the program cannot be built.
   */
  bool Apply(const vtkMRGIFrameContext& frame, vtkTextureObject* colour,
    vtkTextureObject* const terms[MRGI_SHADOW_SLOTS], vtkTextureObject* factors,
    vtkTextureObject* target);
#endif

  /** Free every GL resource. */
  void ReleaseGraphicsResources(vtkWindow* w);

protected:
  vtkMRGIShadowComposite();
  ~vtkMRGIShadowComposite() override;

  struct Internals;
  std::unique_ptr<Internals> Internal;

private:
  vtkMRGIShadowComposite(const vtkMRGIShadowComposite&) = delete;
  void operator=(const vtkMRGIShadowComposite&) = delete;
};

#endif
