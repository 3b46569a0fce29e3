/**
 * @class   vtkMRGIRSMView
 * @brief   Internal: one rendered view of a reflective shadow map, of a
 *          vtkLight or of an area light's hemicube face.
 *
 * Plain data shared by vtkMRGIReflectiveShadowMapPass (which builds the
 * vtkLights' views, owns every view's textures and renders them) and
 * vtkMRGIAreaLightRSMViews (which builds the area lights' views). The
 * uniforms the RSM capture (glsl/capture/vtkMRGIRSMCapture.glsl) reads are
 * set from these fields. Not wrapped, not installed.
 *
 * @sa vtkMRGIReflectiveShadowMapPass vtkMRGIAreaLightRSMViews
 */
#ifndef vtkMRGIRSMView_h
#define vtkMRGIRSMView_h

#include "vtkCamera.h"       // For vtkSmartPointer<vtkCamera>
#include "vtkMatrix4x4.h"    // For vtkNew<vtkMatrix4x4>
#include "vtkNew.h"          // For vtkNew
#include "vtkSmartPointer.h" // For vtkSmartPointer

#include "mrgi_area_light_rsm.h" // For MRGI_AREA_LIGHT_RSM_SAMPLES
#include "mrgi_buffers.h"        // For MRGI_RSM_ATTACHMENTS

class vtkTextureObject;

struct vtkMRGIRSMView
{
  /** Index of the vtkLight in the renderer's collection; -2 - k for area light k. */
  int Light = -1;
  bool Perspective = true;
  double TexelSize = 0; // perspective: 2 tan(fov/2) / S; orthographic: width / S
  double LightColor[3] = { 0, 0, 0 };
  double Attenuation[3] = { 1, 0, 0 };
  double SpotAxisVC[3] = { 0, 0, -1 };
  double SpotCosCutoff = -2.0; // no cone
  double SpotExponent = 1.0;
  // Area-light views: the light samples that light the texels
  // (mrgi_area_light_rsm.h; 0 for a vtkLight's view).
  int AreaSampleCount = 0;
  bool AreaTwoSided = false;
  float AreaSamples[MRGI_AREA_LIGHT_RSM_SAMPLES][MRGI_AREA_LIGHT_SAMPLE_FLOATS] = {};
  vtkSmartPointer<vtkCamera> Camera;
  vtkNew<vtkMatrix4x4> VCToWC;
  /** Owned by vtkMRGIReflectiveShadowMapPass (null until it allocates them). */
  vtkTextureObject* Textures[MRGI_RSM_ATTACHMENTS] = { nullptr, nullptr, nullptr };

  /**
   * Make Camera (if null) a square perspective view from `eye` along `dir`
   * (any length but zero) with the full field of view `fovDeg`, whose depth
   * range covers the sphere (center, radius) of the visible props, for
   * `texelsPerSide` texels per side; sets Perspective and TexelSize. The
   * projection is explicit, so the window's aspect ratio never distorts it.
   */
  void SetPerspective(const double eye[3], const double dir[3], double fovDeg,
    const double center[3], double radius, double texelsPerSide);

  /** An up vector not parallel to `dir`. */
  static void PickUp(const double dir[3], double up[3]);
};

#endif
