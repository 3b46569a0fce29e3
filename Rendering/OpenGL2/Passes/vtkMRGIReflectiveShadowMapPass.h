/**
 * @class   vtkMRGIReflectiveShadowMapPass
 * @brief   Renders reflective shadow maps (RSMs) of a renderer's lights.
 *
 * A reflective shadow map (Dachsbacher and Stamminger 2005; used by
 * nichols-wyman-2009 section 3.1) is the scene seen from a light, storing per
 * texel what the surface there reflects: world position, normal, reflected
 * flux and the surface area the texel covers (layout in mrgi_buffers.h,
 * definitions in mrgi_vpl.h and Documentation/IndirectLight.md).
 *
 * Views per light (the light's transformed position and focal point, so
 * headlights and camera lights, e.g. ParaView's light kit, work):
 * - spot light with a half-angle up to MRGI_RSM_MAX_SPOT_HALF_ANGLE_DEG:
 *   one perspective view of twice the cone angle;
 * - positional light (or a wider spot): the six faces of a cube, faces
 *   outside a spot's cone skipped;
 * - directional light: one orthographic view fitted to the bounds of the
 *   visible props.
 *
 * Only what the scene requires is rendered: lights that are off, have zero
 * intensity, or whose views do not reach the visible props get no view; and
 * nothing is re-rendered while lights, props, their data and the resolution
 * are unchanged (GetNumberOfRenders() counts actual renders).
 *
 * The projection of every view is square and set explicitly, so the window's
 * aspect ratio never distorts it. All visible opaque props are rendered, also
 * those outside the camera's view: light bounces off them into the image.
 */
#ifndef vtkMRGIReflectiveShadowMapPass_h
#define vtkMRGIReflectiveShadowMapPass_h

#include "MRGIRenderingModule.h" // For export macro
#include "vtkOpenGLRenderPass.h"

#include <memory> // For std::unique_ptr

class vtkImageData;
class vtkOpenGLRenderWindow;
class vtkRenderWindow;
class vtkRenderer;
class vtkTextureObject;
class vtkMatrix4x4;

class MRGIRENDERING_EXPORT vtkMRGIReflectiveShadowMapPass : public vtkOpenGLRenderPass
{
public:
  static vtkMRGIReflectiveShadowMapPass* New();
  vtkTypeMacro(vtkMRGIReflectiveShadowMapPass, vtkOpenGLRenderPass);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * Bring the RSMs of the renderer in `s` up to date (rendering only when
   * something they depend on changed). The renderer's lights must already
   * be placed for this frame (VTK's lights pass has run).
   */
  void Render(const vtkRenderState* s) override;

  /** Free every GL resource. */
  void ReleaseGraphicsResources(vtkWindow* w) override;

  ///@{
  /** RSM texels per side, MRGI_RSM_MIN_SIZE..MRGI_RSM_MAX_SIZE (default 256). */
  vtkSetClampMacro(Resolution, int, 16, 2048);
  vtkGetMacro(Resolution, int);
  ///@}

  /** Number of views rendered for the current lights (0 when nothing is lit). */
  int GetNumberOfViews() const;

  /** Textures of view `i` (position, normal, flux; see mrgi_buffers.h). */
  vtkTextureObject* GetPositionTexture(int i) const;
  vtkTextureObject* GetNormalTexture(int i) const;
  vtkTextureObject* GetFluxTexture(int i) const;

  /**
   * Read view `i` back (RGBA float each, rows bottom-up; layout in
   * mrgi_buffers.h). False when there is no such view.
   */
  bool ReadView(vtkRenderWindow* window, int i, vtkImageData* position, vtkImageData* normal,
    vtkImageData* flux);

  /** Index, in the renderer's light collection, of the light of view `i`. */
  int GetViewLight(int i) const;

  /** How many times views were actually rendered since creation. */
  vtkGetMacro(NumberOfRenders, vtkIdType);

  /** Modified time of the RSM contents (changes only when they are re-rendered). */
  vtkMTimeType GetContentTime() const;

  ///@{
  /** Shader hooks: emit the RSM quantities instead of VTK's colour. */
  bool PostReplaceShaderValues(std::string& vertexShader, std::string& geometryShader,
    std::string& fragmentShader, vtkAbstractMapper* mapper, vtkProp* prop) override;
  bool PreReplaceShaderValues(std::string& vertexShader, std::string& geometryShader,
    std::string& fragmentShader, vtkAbstractMapper* mapper, vtkProp* prop) override;
  bool SetShaderParameters(vtkShaderProgram* program, vtkAbstractMapper* mapper, vtkProp* prop,
    vtkOpenGLVertexArrayObject* VAO = nullptr) override;
  ///@}

protected:
  vtkMRGIReflectiveShadowMapPass();
  ~vtkMRGIReflectiveShadowMapPass() override;

  /** Warn once per data change when a prop's points or normals hold NaN/Inf. */
  void CheckInput(vtkProp* prop);

  int Resolution = 256;
  vtkIdType NumberOfRenders = 0;

  struct Internals;
  std::unique_ptr<Internals> Internal;

private:
  vtkMRGIReflectiveShadowMapPass(const vtkMRGIReflectiveShadowMapPass&) = delete;
  void operator=(const vtkMRGIReflectiveShadowMapPass&) = delete;
};

#endif
