/**
 * @class   vtkPVMRGISurfels
 * @brief   ParaView's "MRGI Surfels" filter: vtkMRGISurfels behind a class
 *          that ParaView's client-server layer can call.
 *
 * Runs vtkMRGISurfels (MRGI::RenderingIO, not wrapped for ParaView) with
 * this object's properties on the input point cloud (vertices only, or no
 * cells) and outputs its polygons: one square (4 corners) or hexagon (6)
 * per point in the point's tangent plane, with the normals and every other
 * point array repeated on the corners, so the MRGI Render View's G-buffer
 * and shadow maps see a continuous surface. The input needs normals and
 * radii: "MRGI Point Cloud Normals" before this filter gives both.
 *
 * Bad input (no normals, no radius array and Radius 0, a mesh) is the inner
 * filter's error, naming what is missing; the output is then empty.
 */
#ifndef vtkPVMRGISurfels_h
#define vtkPVMRGISurfels_h

#include "MRGIParaViewModule.h" // For export macro
#include "vtkPolyDataAlgorithm.h"

#include <string> // For std::string

class MRGIPARAVIEW_EXPORT vtkPVMRGISurfels : public vtkPolyDataAlgorithm
{
public:
  static vtkPVMRGISurfels* New();
  vtkTypeMacro(vtkPVMRGISurfels, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /** 4: squares (default), 6: hexagons (vtkMRGISurfels::ShapeType). */
  vtkSetClampMacro(Shape, int, 4, 6);
  vtkGetMacro(Shape, int);
  ///@}

  ///@{
  /** The point array of the normals; empty (default): the active normals, else "Normals". */
  vtkSetStdStringFromCharMacro(NormalsArrayName);
  vtkGetCharFromStdStringMacro(NormalsArrayName);
  ///@}

  ///@{
  /** The point array of the radii (default "Radius"), used when present. */
  vtkSetStdStringFromCharMacro(RadiusArrayName);
  vtkGetCharFromStdStringMacro(RadiusArrayName);
  ///@}

  ///@{
  /** Radius of every point when there is no radius array (default 0: none). */
  vtkSetClampMacro(Radius, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(Radius, double);
  ///@}

  ///@{
  /** Multiplies every radius (default 1). */
  vtkSetClampMacro(RadiusScale, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(RadiusScale, double);
  ///@}

  ///@{
  /** Level of detail: at most about this many surfels (every k-th point, radius x sqrt(k)); 0
   * (default): all. */
  vtkSetClampMacro(MaximumNumberOfSurfels, vtkIdType, 0, VTK_ID_MAX);
  vtkGetMacro(MaximumNumberOfSurfels, vtkIdType);
  ///@}

  ///@{
  /** What the last run did: its stride k and the points it skipped (non-finite or radius <= 0). */
  vtkGetMacro(Stride, vtkIdType);
  vtkGetMacro(NumberOfSkippedPoints, vtkIdType);
  ///@}

protected:
  vtkPVMRGISurfels();
  ~vtkPVMRGISurfels() override = default;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int Shape = 4;
  std::string NormalsArrayName;
  std::string RadiusArrayName = "Radius";
  double Radius = 0.0;
  double RadiusScale = 1.0;
  vtkIdType MaximumNumberOfSurfels = 0;
  vtkIdType Stride = 1;
  vtkIdType NumberOfSkippedPoints = 0;

private:
  vtkPVMRGISurfels(const vtkPVMRGISurfels&) = delete;
  void operator=(const vtkPVMRGISurfels&) = delete;
};

#endif
