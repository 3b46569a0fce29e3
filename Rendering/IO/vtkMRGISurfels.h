/**
 * @class   vtkMRGISurfels
 * @brief   Turns an oriented point cloud into surfels: one small flat polygon
 *          per point, in its tangent plane, that every MRGI stage draws as a
 *          surface.
 *
 * A point cloud drawn as VTK's points gives the G-buffer and the reflective
 * shadow maps pixels with no usable normal and holes between them, so the
 * indirect light sees no surface. This filter replaces each point by a
 * square (default) or a hexagon of area pi r^2 centred on it, normal to the
 * point's normal (the C core's mrgi_surfels.h: corners at 1.25 r or 1.10 r),
 * so VTK's direct light, the G-buffer, every light type's RSM, the area-light
 * voxelization, IceT and the CPU reference renderer all see a continuous
 * surface with no change of their own (Documentation/PointClouds-Surfels.md).
 *
 * Input: a vtkPolyData point cloud: vertex cells only, or no cells (every
 * point is used; a mesh with lines, polygons or strips is refused). It needs
 * - normals: the point-data array NormalsArrayName (default: the active
 *   normals, else an array called "Normals"), 3 components; and
 * - radii: the point-data array RadiusArrayName (default "Radius"), 1
 *   component, when present; else every point has the radius Radius.
 *   RadiusScale multiplies either.
 * vtkMRGIPointCloudNormals estimates both for a cloud that has neither.
 * Missing normals, or neither a radius array nor a Radius > 0, fail the
 * update with an error naming what is missing.
 *
 * Output: polygons (4 or 6 points each, counter-clockwise around the normal)
 * with float points and the point normals ("Normals", active); every other
 * point-data array of the input (RGB colours, Intensity, Classification, the
 * radius...) repeated on each corner, so scalar colouring and lookup tables
 * work as on the cloud. Points with a non-finite position, normal or radius
 * are skipped and counted (GetNumberOfSkippedPoints(), one warning per
 * update). The cell array uses 32-bit storage up to 2^31 corners.
 * MaximumNumberOfSurfels sets a level of detail for very dense clouds.
 */
#ifndef vtkMRGISurfels_h
#define vtkMRGISurfels_h

#include "MRGIRenderingIOModule.h" // For export macro
#include "vtkPolyDataAlgorithm.h"

#include <string> // For std::string

class vtkProp3D;
class vtkRenderer;

class MRGIRENDERINGIO_EXPORT vtkMRGISurfels : public vtkPolyDataAlgorithm
{
public:
  static vtkMRGISurfels* New();
  vtkTypeMacro(vtkMRGISurfels, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /** The polygon of each point. */
  enum ShapeType
  {
    Square = 4, ///< 4 corners, 2 triangles (default)
    Hexagon = 6 ///< 6 corners, 4 triangles, closer to the disk
  };

  ///@{
  /** Square (4, default) or Hexagon (6). */
  vtkSetClampMacro(Shape, int, Square, Hexagon);
  vtkGetMacro(Shape, int);
  void SetShapeToSquare() { this->SetShape(Square); }
  void SetShapeToHexagon() { this->SetShape(Hexagon); }
  ///@}

  ///@{
  /** The point-data array of the normals; empty (default): the active normals, else "Normals". */
  vtkSetStdStringFromCharMacro(NormalsArrayName);
  vtkGetCharFromStdStringMacro(NormalsArrayName);
  ///@}

  ///@{
  /** The point-data array of the disk radii (default "Radius"); used when present. */
  vtkSetStdStringFromCharMacro(RadiusArrayName);
  vtkGetCharFromStdStringMacro(RadiusArrayName);
  ///@}

  ///@{
  /** Radius of every point when the input has no radius array (scene units; default 0: none). */
  vtkSetClampMacro(Radius, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(Radius, double);
  ///@}

  ///@{
  /** Multiplies every radius (default 1). */
  vtkSetClampMacro(RadiusScale, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(RadiusScale, double);
  ///@}

  ///@{
  /**
   * Level of detail (default 0: every point). With a budget M below the
   * point count N, only every k-th point becomes a surfel, k = ceil(N / M),
   * with its radius times sqrt(k): the sparser disks cover the same area, so
   * a cloud much denser than the pixels it covers looks the same for 1/k of
   * the geometry (and of the G-buffer and shadow-map cost). Coarser
   * silhouettes and detail below the new spacing are the price; use it for
   * clouds with many points per pixel (Documentation/PointClouds-Surfels.md).
   */
  vtkSetClampMacro(MaximumNumberOfSurfels, vtkIdType, 0, VTK_ID_MAX);
  vtkGetMacro(MaximumNumberOfSurfels, vtkIdType);
  ///@}

  /**
   * A budget for SetMaximumNumberOfSurfels() from a view: `surfelsPerPixel`
   * times the pixels that the bounding box of `prop` covers in `renderer`'s
   * viewport with its current camera (the box's projected corners, clipped
   * to the viewport: an upper bound of the cloud's coverage; a box reaching
   * out of the clipping range counts as the whole viewport). At least 1; 0
   * without a renderer, window, prop or a positive `surfelsPerPixel`. Call
   * it again when the view changes much: the filter does not watch the
   * camera.
   */
  static vtkIdType SuggestMaximumNumberOfSurfels(
    vtkRenderer* renderer, vtkProp3D* prop, double surfelsPerPixel);

  /** The stride k the last update used (1: every point). */
  vtkGetMacro(Stride, vtkIdType);

  /** Points the last update skipped: non-finite position, normal or radius, or a radius <= 0. */
  vtkGetMacro(NumberOfSkippedPoints, vtkIdType);

protected:
  vtkMRGISurfels();
  ~vtkMRGISurfels() override = default;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

  int Shape = Square;
  std::string NormalsArrayName;
  std::string RadiusArrayName = "Radius";
  double Radius = 0.0;
  double RadiusScale = 1.0;
  vtkIdType MaximumNumberOfSurfels = 0;
  vtkIdType Stride = 1;
  vtkIdType NumberOfSkippedPoints = 0;

private:
  vtkMRGISurfels(const vtkMRGISurfels&) = delete;
  void operator=(const vtkMRGISurfels&) = delete;
};

#endif
