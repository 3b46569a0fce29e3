/**
 * @class   vtkMRGIAreaLightSource
 * @brief   A rectangular MRGI area light as pipeline data, optionally textured by an image.
 *
 * The ParaView face of vtkMRGIAreaLight: its output is the light's
 * rectangle as vtkPolyData, marked as an area light, and a
 * vtkPVMRGIRenderView that shows it lights its scene with it (the view
 * reads the mark from the data it renders; showing or hiding the output
 * switches the light on or off). The server-manager proxies are "MRGI Area
 * Light" (sources, no input: a uniform light) and "MRGI Textured Area
 * Light" (filters, an image input: the picture it emits).
 *
 * Geometry (as vtkMRGIAreaLight): centre Center, FULL perpendicular edges
 * EdgeU and EdgeV, emitting towards EdgeU x EdgeV (both sides when
 * TwoSided); radiance L = Intensity * Color * T, T the picture (1 without
 * input).
 *
 * Input (optional, port 0): a vtkImageData. Its active point scalars (else
 * its first point array) give T: 1 (grey), 2 (grey, alpha), 3 (RGB) or 4
 * (RGBA) components, alpha ignored; unsigned char values are divided by
 * 255, any other type is used as is (HDR: the values are radiance factors,
 * so e.g. a float image with values near 100 wants an Intensity near
 * 0.01). A 2D image in any axis-aligned plane is used whole: its first
 * axis of more than one point (x, else y) runs along EdgeU, the next along
 * EdgeV. A 3D image gives its first z slice (its lowest z index). The whole
 * image is requested, whatever piece this filter produces.
 *
 * Output: the rectangle split into W x H quads, one per texel (a single
 * quad without input), points ordered row by row from the corner
 * Center - EdgeU/2 - EdgeV/2, quads counter-clockwise seen from the
 * emitting side, with
 * - cell array "Radiance" (float RGB): L per texel (HDR; colour-map it to
 *   see the values);
 * - cell array "DisplayColors" (unsigned char RGB, the active cell
 *   scalars, so ParaView colours by it when shown): what to show (with Map
 *   Scalars off), as vtkMRGIAreaLight's own emitter shows
 *   the light: a uniform light its radiance clamped to 1 (a bright light
 *   is white), a picture its radiance divided by its peak when that is
 *   above 1 (a bright picture stays a picture);
 * - cell array "Texture" (float RGB, only with an input): T per texel, the
 *   picture the light emits, VTK image order (row 0 at -EdgeV/2);
 * - field array "MRGIAreaLight" (double, one tuple of
 *   VTK_MRGI_AREA_LIGHT_FIELD_SIZE components: centre (3), EdgeU (3), EdgeV
 *   (3), colour (3), intensity, two-sided (0/1), picture width and height
 *   (0 0 without input)), the mark the view looks for.
 * Every piece holds the whole light: in a parallel render each rank
 * lights its own part of the scene with it.
 *
 * Bad input: a non-finite or zero edge, edges not perpendicular, a negative
 * or non-finite Color or Intensity, an input image without point scalars,
 * with more than 4 components or with a negative or non-finite texel is an
 * error naming the property and the problem, and the output is empty (no
 * light).
 *
 * @sa vtkMRGIAreaLight vtkPVMRGIRenderView
 */
#ifndef vtkMRGIAreaLightSource_h
#define vtkMRGIAreaLightSource_h

#include "MRGIParaViewModule.h" // For export macro
#include "vtkPolyDataAlgorithm.h"

#include <string> // For std::string

/** Components of the "MRGIAreaLight" field array (see the class documentation). */
#define VTK_MRGI_AREA_LIGHT_FIELD_SIZE 16

class MRGIPARAVIEW_EXPORT vtkMRGIAreaLightSource : public vtkPolyDataAlgorithm
{
public:
  static vtkMRGIAreaLightSource* New();
  vtkTypeMacro(vtkMRGIAreaLightSource, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /** Centre of the rectangle, world units. Default (0, 0, 0). */
  vtkSetVector3Macro(Center, double);
  vtkGetVector3Macro(Center, double);
  ///@}

  ///@{
  /**
   * The FULL edge vectors, perpendicular; the light emits towards
   * EdgeU x EdgeV. Defaults (1, 0, 0) and (0, 1, 0).
   */
  vtkSetVector3Macro(EdgeU, double);
  vtkGetVector3Macro(EdgeU, double);
  vtkSetVector3Macro(EdgeV, double);
  vtkGetVector3Macro(EdgeV, double);
  ///@}

  ///@{
  /** Linear RGB colour, each >= 0. Default (1, 1, 1). */
  vtkSetVector3Macro(Color, double);
  vtkGetVector3Macro(Color, double);
  ///@}

  ///@{
  /** Radiance scale, >= 0. Default 1. */
  vtkSetMacro(Intensity, double);
  vtkGetMacro(Intensity, double);
  ///@}

  ///@{
  /** Emit on both sides. Default off. */
  vtkSetMacro(TwoSided, bool);
  vtkGetMacro(TwoSided, bool);
  vtkBooleanMacro(TwoSided, bool);
  ///@}

  /** Why the last update gave no light; empty after a success. */
  const char* GetLastErrorMessage() { return this->LastErrorMessage.c_str(); }

protected:
  vtkMRGIAreaLightSource();
  ~vtkMRGIAreaLightSource() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  /** Reports `why` (prefixed with the light's name) and returns 1: an empty output. */
  int Fail(const std::string& why);

  double Center[3] = { 0.0, 0.0, 0.0 };
  double EdgeU[3] = { 1.0, 0.0, 0.0 };
  double EdgeV[3] = { 0.0, 1.0, 0.0 };
  double Color[3] = { 1.0, 1.0, 1.0 };
  double Intensity = 1.0;
  bool TwoSided = false;
  std::string LastErrorMessage;

private:
  vtkMRGIAreaLightSource(const vtkMRGIAreaLightSource&) = delete;
  void operator=(const vtkMRGIAreaLightSource&) = delete;
};

#endif
