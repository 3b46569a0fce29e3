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
 * Area lights (vtkMRGIAreaLight, RenderWithAreaLights()) get the hemicube
 * of their emitting side(s) from the emitter's centre (mrgi_area_light_rsm.h,
 * Documentation/IndirectLight.md "Area lights bounce"); the internal
 * vtkMRGIAreaLightRSMViews samples the emitters and builds those views.
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
 *
 * **Distributed rendering** (SetCompositor() with more than one process,
 * e.g. ParaView's ranks, each holding a piece of the data; the compositor
 * over a vtkMultiProcessController is vtkMRGIControllerRSMCompositor in
 * MRGI::RenderingParallel): every rank
 * builds the same views (from the bounds of all ranks' props, and keeping a
 * view that reaches any rank's props), renders its own props into them, and
 * the views are then composited across ranks texel by texel, keeping the
 * record nearest the light (mrgi_rsm_composite.h), so that every rank holds
 * the maps one process would render over all the data, and selects the same
 * VPLs from them. Render() is then collective: every rank must call it for
 * the same frames, with the same lights and resolution. Whether the maps
 * are re-rendered is decided together (any rank's change re-renders all),
 * so the ranks never wait for each other in different collectives.
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
class vtkMRGIAreaLight;
class vtkMRGIRSMCompositor;

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

  /**
   * Render() with, in addition, the views of `count` area lights
   * (mrgi_area_light_rsm.h): from each emitter's centre, the hemicube faces
   * of its emitting side(s) (5 one-sided, 6 two-sided), their texels' flux
   * lit by the emitter's MRGI_AREA_LIGHT_RSM_SAMPLES light samples. Area
   * light k's views have GetViewLight() == -2 - k. Lights with zero
   * intensity or colour, or invalid ones (reported by the light), get no
   * view. Re-rendered only when the lights' samples, the vtkLights, the
   * props or the resolution changed, as Render().
   */
  void RenderWithAreaLights(const vtkRenderState* s, vtkMRGIAreaLight* const* areaLights, int count);

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

  /**
   * Index, in the renderer's light collection, of the light of view `i`;
   * -2 - k for area light k of RenderWithAreaLights(); -1 for no such view.
   */
  int GetViewLight(int i) const;

  ///@{
  /**
   * The camera of view `i`, for shadow lookups (vtkMRGIDirectShadows): its
   * world -> view transform and its projection (row-major, as
   * vtkMatrix4x4 stores them; view space looks down -z; the projection is
   * square and centred), and whether it is perspective (spot, cube face) or
   * orthographic (directional). False (matrices untouched) when there is no
   * such view.
   */
  bool GetViewWorldToView(int i, double worldToView[16]) const;
  bool GetViewProjection(int i, double projection[16]) const;
  bool GetViewPerspective(int i) const;
  ///@}

  /** How many times views were actually rendered since creation. */
  vtkGetMacro(NumberOfRenders, vtkIdType);

  /** Modified time of the RSM contents (changes only when they are re-rendered). */
  vtkMTimeType GetContentTime() const;

  ///@{
  /**
   * How the maps are composited across processes (see the class comment);
   * null (default) or a compositor of one process: no communication.
   */
  virtual void SetCompositor(vtkMRGIRSMCompositor* compositor);
  vtkGetObjectMacro(Compositor, vtkMRGIRSMCompositor);
  ///@}

  /**
   * Bytes this process sent for the composite in its last Render(): the
   * collective decision (a few doubles, every frame) plus, when the maps
   * were re-rendered, the maps themselves (views x Resolution^2 x 48 bytes
   * per message this process sends). 0 without a compositor.
   */
  vtkGetMacro(CompositeBytes, vtkTypeInt64);

  /** How many times the maps were composited across processes since creation. */
  vtkGetMacro(NumberOfComposites, vtkIdType);

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

  /**
   * Composite the rendered views across the compositor's processes
   * (collective); returns false (with an error) when a read-back or the
   * composite failed on this process, which still took part.
   */
  bool CompositeViews(vtkOpenGLRenderWindow* window);

  vtkMRGIRSMCompositor* Compositor = nullptr;
  vtkTypeInt64 CompositeBytes = 0;
  vtkIdType NumberOfComposites = 0;

  int Resolution = 256;
  vtkIdType NumberOfRenders = 0;

  struct Internals;
  std::unique_ptr<Internals> Internal;

private:
  vtkMRGIReflectiveShadowMapPass(const vtkMRGIReflectiveShadowMapPass&) = delete;
  void operator=(const vtkMRGIReflectiveShadowMapPass&) = delete;
};

#endif
