/**
 * @class   vtkMRGIAreaLightRSMViews
 * @brief   Internal: the reflective shadow map views of area lights, the
 *          hemicube faces of each emitter seen from its centre.
 *
 * vtkMRGIReflectiveShadowMapPass::RenderWithAreaLights() asks this class,
 * in two steps whose inputs are all arguments:
 * 1. SampleEmitters(): each usable area light's MRGI_AREA_LIGHT_RSM_SAMPLES
 *    light samples (mrgi_area_light_make_samples(), cell-filtered radiance,
 *    [NPW10] 3.1), and the values every process must agree on before the
 *    maps are re-rendered or composited;
 * 2. AddViews(): for each sampled emitter, the 5 (one-sided) or 6
 *    (two-sided) 90-degree faces of mrgi_area_light_rsm_views(), from the
 *    emitter's centre, each carrying the samples that light its texels
 *    (the flux of mrgi_area_light_rsm.h, [NSW09] eq. 1 per sample).
 * SetShaderParameters() then gives the RSM capture a view's samples.
 *
 * The class holds no GL resource: the views' textures belong to the pass
 * (it reuses them across frames), so there is nothing to release. Not
 * wrapped, not installed.
 *
 * @sa vtkMRGIReflectiveShadowMapPass vtkMRGIRSMView vtkMRGIAreaLight
 */
#ifndef vtkMRGIAreaLightRSMViews_h
#define vtkMRGIAreaLightRSMViews_h

#include "vtkObject.h"

#include "mrgi_area_light.h"     // For mrgi_area_light, mrgi_area_light_sample
#include "mrgi_area_light_rsm.h" // For MRGI_AREA_LIGHT_RSM_SAMPLES

#include <iosfwd> // For std::ostream
#include <memory> // For std::unique_ptr
#include <vector> // For std::vector

class vtkMRGIAreaLight;
class vtkShaderProgram;
struct vtkMRGIRSMView;

class vtkMRGIAreaLightRSMViews : public vtkObject
{
public:
  static vtkMRGIAreaLightRSMViews* New();
  vtkTypeMacro(vtkMRGIAreaLightRSMViews, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /** One area light that gets views: its core light and light samples. */
  struct Emitter
  {
    int Index = -1; // in the caller's array; its views get Light == -2 - Index
    mrgi_area_light Core;
    mrgi_area_light_sample Samples[MRGI_AREA_LIGHT_RSM_SAMPLES];
    int SampleCount = 0;
  };

  /**
   * Append to `emitters` the area lights among `lights[0..count)` that
   * bounce light: lights that are null, have zero intensity or colour, or
   * are invalid (the light reports why) are skipped, as are lights whose
   * samples cannot be made (an error naming the light). Appends to
   * `signature` what the views depend on, as values (the samples and the
   * sidedness, never addresses or modified times), so that processes can
   * compare them. `lights` may be null when `count` is 0.
   */
  void SampleEmitters(vtkMRGIAreaLight* const* lights, int count, std::vector<Emitter>& emitters,
    std::ostream& signature);

  /**
   * Append to `views` the hemicube faces of every emitter (each a square
   * 90-degree perspective view from the emitter's centre whose depth range
   * covers the sphere (center, radius) of the visible props, for
   * `texelsPerSide` texels per side), carrying the emitter's samples. The
   * caller culls the views that miss the props and allocates textures.
   */
  void AddViews(const std::vector<Emitter>& emitters, const double center[3], double radius,
    double texelsPerSide, std::vector<std::unique_ptr<vtkMRGIRSMView>>& views);

  /**
   * The area-light uniforms of the RSM capture for `view`
   * (mrgiAreaSampleCount, mrgiAreaTwoSided, and mrgiAreaSamples for an
   * area light's view; a vtkLight's view sets the count to 0).
   */
  static void SetShaderParameters(vtkShaderProgram* program, const vtkMRGIRSMView& view);

  /** Emitters the last SampleEmitters() call appended. */
  vtkGetMacro(NumberOfEmitters, int);

  /** Views the last AddViews() call appended. */
  vtkGetMacro(NumberOfViews, int);

protected:
  vtkMRGIAreaLightRSMViews() = default;
  ~vtkMRGIAreaLightRSMViews() override = default;

  int NumberOfEmitters = 0;
  int NumberOfViews = 0;

private:
  vtkMRGIAreaLightRSMViews(const vtkMRGIAreaLightRSMViews&) = delete;
  void operator=(const vtkMRGIAreaLightRSMViews&) = delete;
};

#endif
