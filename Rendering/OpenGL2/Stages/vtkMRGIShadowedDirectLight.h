/**
 * @class   vtkMRGIShadowedDirectLight
 * @brief   VTK's direct light with shadows: which of VTK's lights are
 *          shadowed, the lights' radius, the shadow factors
 *          (vtkMRGIDirectShadows) and their application to VTK's own light
 *          terms (vtkMRGIShadowComposite), with the failure reporting.
 *
 * vtkMRGIPass's "shadows" step (Documentation/DirectShadows.md). Two calls
 * per frame, each with its inputs as arguments:
 * 1. before the scene is drawn, AssignLights() says which of VTK's shader
 *    lights get a shadow slot (the scene pass then captures their terms);
 * 2. once the G-buffer and the reflective shadow maps exist, Apply()
 *    computes the factors of those slots and writes the shadowed colour.
 * Apply() takes the slots AssignLights() returned as an argument: nothing
 * is remembered between the two but the once-only warnings, the cached
 * automatic light radius and the owned stages' GL resources.
 *
 * The automatic light radius (Settings::LightRadius 0) is
 * MRGI_SHADOW_AUTO_LIGHT_RADIUS of the visible props' bounding radius
 * (vtkRenderer::ComputeVisiblePropBounds). The bounds are computed again
 * only when the reflective shadow maps were re-rendered
 * (vtkMRGIReflectiveShadowMapPass::GetContentTime() changed: a visible
 * opaque prop, its data or a light changed), not every frame;
 * GetNumberOfLightRadiusUpdates() counts how often.
 */
#ifndef vtkMRGIShadowedDirectLight_h
#define vtkMRGIShadowedDirectLight_h

#include "MRGIRenderingModule.h" // For export macro
#include "vtkObject.h"

#include "mrgi_buffers.h"       // For MRGI_SHADOW_SLOTS
#include "mrgi_direct_shadow.h" // For MRGI_DIRECT_SHADOW_DEFAULT_SIDE

struct vtkMRGIFrameContext;
class vtkMRGIDirectShadows;
class vtkMRGIReflectiveShadowMapPass;
class vtkMRGIShadowComposite;
class vtkRenderer;
class vtkTextureObject;
class vtkWindow;

class MRGIRENDERING_EXPORT vtkMRGIShadowedDirectLight : public vtkObject
{
public:
  static vtkMRGIShadowedDirectLight* New();
  vtkTypeMacro(vtkMRGIShadowedDirectLight, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

#ifndef __VTK_WRAP__
  /** How the shadows are computed: vtkMRGIPass's shadow settings, by value. */
  struct Settings
  {
    int Mode = MRGI_DIRECT_SHADOW_SOFT; ///< MRGI_DIRECT_SHADOW_HARD or _SOFT
    int SamplesSide = MRGI_DIRECT_SHADOW_DEFAULT_SIDE; ///< soft: PCF side, 1..MRGI_DIRECT_SHADOW_MAX_SIDE
    double LightRadius = 0.0;     ///< world units, > 0; 0: automatic (see the class comment)
    bool Multiresolution = false; ///< BMR levels (vtkMRGIDirectShadows::ComputeMultiresolution)
  };

  /** Which of VTK's lights are shadowed this frame. */
  struct Lights
  {
    /**
     * Slot s: the index in the renderer's light collection of VTK's shader
     * light s, or -1. VTK's shader lights are the switched-on lights in
     * collection order (vtkOpenGLRenderer::UpdateLightingUniforms).
     */
    int Slots[MRGI_SHADOW_SLOTS];
    /**
     * Shader lights that cast a visible shadow: lit (intensity > 0) and not
     * a headlight, whose shadows hide behind what it lights. 0: nothing to
     * shadow (no capture of light terms needed).
     */
    int Casting = 0;
    /**
     * Casting scene lights past the slots: lit as VTK lights them,
     * unshadowed (camera lights past the slots are a light kit's fill and
     * back lights, unshadowed by design).
     */
    int UnshadowedSceneLights = 0;
    Lights()
    {
      for (int& slot : this->Slots)
      {
        slot = -1;
      }
    }
  };

  /**
   * The shadowed lights of `renderer` (null: none). Warns once, for the
   * lifetime of this object, when scene lights are left unshadowed.
   */
  Lights AssignLights(vtkRenderer* renderer);

  /**
   * Shadow factors of `lights` (into `factors`) from `rsm`'s views, applied
   * to `colour` with the slots' light `terms` into `target` (window-sized
   * textures, mrgi_buffers.h; `target` must not be `colour`), over the
   * frame's viewport. Needs frame.Window, Renderer, Position, Normal,
   * ViewToWorld, Viewport. Timer step "shadows". False when they could not
   * be computed: an error is given once, until a frame succeeds again, and
   * `target` must then not be used.
   */
  bool Apply(const vtkMRGIFrameContext& frame, vtkMRGIReflectiveShadowMapPass* rsm,
    const Lights& lights, const Settings& settings, vtkTextureObject* colour,
    vtkTextureObject* const terms[MRGI_SHADOW_SLOTS], vtkTextureObject* factors,
    vtkTextureObject* target);

  /**
   * The light radius Apply() uses: settings.LightRadius when > 0, else the
   * automatic one (class comment), from the cache while `rsm`'s content
   * time is the one it was computed at. 0 for a scene without bounds.
   */
  double ResolveLightRadius(
    vtkRenderer* renderer, vtkMRGIReflectiveShadowMapPass* rsm, const Settings& settings);
#endif

  /** The light radius of the last Apply() (world units; 0 before). */
  vtkGetMacro(LastLightRadius, double);

  /**
   * How many times the automatic light radius was computed from the
   * visible props' bounds (once per re-render of the reflective shadow
   * maps, at most once per frame).
   */
  vtkGetMacro(NumberOfLightRadiusUpdates, vtkIdType);

  ///@{
  /** The owned stages: factors (BMR mask, blend, levels, statistics) and composite. */
  vtkMRGIDirectShadows* GetDirectShadows() { return this->DirectShadows; }
  vtkMRGIShadowComposite* GetComposite() { return this->Composite; }
  ///@}

  /** Free every GL resource (both stages'). */
  void ReleaseGraphicsResources(vtkWindow* w);

protected:
  vtkMRGIShadowedDirectLight();
  ~vtkMRGIShadowedDirectLight() override;

  vtkMRGIDirectShadows* DirectShadows = nullptr;
  vtkMRGIShadowComposite* Composite = nullptr;
  double LastLightRadius = 0.0;
  double AutoLightRadius = 0.0;   // cached automatic radius ...
  vtkMTimeType AutoRadiusTime = 0; // ... computed at this RSM content time (0: never)
  vtkIdType NumberOfLightRadiusUpdates = 0;
  bool FailureReported = false;     // the failure error is given once until a success
  bool ExtraLightsReported = false; // lights past MRGI_SHADOW_SLOTS stay unshadowed

private:
  vtkMRGIShadowedDirectLight(const vtkMRGIShadowedDirectLight&) = delete;
  void operator=(const vtkMRGIShadowedDirectLight&) = delete;
};

#endif
