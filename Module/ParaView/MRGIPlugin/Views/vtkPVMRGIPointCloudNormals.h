/**
 * @class   vtkPVMRGIPointCloudNormals
 * @brief   ParaView's "MRGI Point Cloud Normals" filter: vtkMRGIPointCloudNormals
 *          behind a class that ParaView's client-server layer can call.
 *
 * Runs vtkMRGIPointCloudNormals (MRGI::RenderingIO, not wrapped for
 * ParaView) with this object's properties on the input point cloud and
 * outputs its result: the input with point data "Normals" (active) and
 * "Radius" (the surfel radius from the local spacing). The ParaView build
 * has no PCL, so the estimate is always the C core's (mrgi_point_normals.h:
 * exact kNN, PCA normals, single-threaded); see vtkMRGIPointCloudNormals
 * for the orientation rules (towards the field data "SensorOrigin" of an
 * organized cloud, else along Up when it is not zero, else away from the
 * centroid).
 *
 * Bad input (a non-finite or non-positive RadiusScale, a mesh) is the
 * inner filter's error; the output is then empty.
 */
#ifndef vtkPVMRGIPointCloudNormals_h
#define vtkPVMRGIPointCloudNormals_h

#include "MRGIParaViewModule.h" // For export macro
#include "vtkPolyDataAlgorithm.h"

class MRGIPARAVIEW_EXPORT vtkPVMRGIPointCloudNormals : public vtkPolyDataAlgorithm
{
public:
  static vtkPVMRGIPointCloudNormals* New();
  vtkTypeMacro(vtkPVMRGIPointCloudNormals, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /** Neighbours per point, [3, 128]; 16 by default. */
  vtkSetClampMacro(NumberOfNeighbors, int, 3, 128);
  vtkGetMacro(NumberOfNeighbors, int);
  ///@}

  ///@{
  /** Factor on the local spacing giving the radius; > 0; 1 by default. */
  vtkSetMacro(RadiusScale, double);
  vtkGetMacro(RadiusScale, double);
  ///@}

  ///@{
  /** Orient normals along this direction (LAS: 0 0 1); 0 0 0 (default): away from the centroid. */
  vtkSetVector3Macro(Up, double);
  vtkGetVector3Macro(Up, double);
  ///@}

  ///@{
  /** Estimate normals even when the input has some (off by default: only the radii are computed).
   */
  vtkSetMacro(ComputeNormals, bool);
  vtkGetMacro(ComputeNormals, bool);
  ///@}

  ///@{
  /** What the last run did (vtkMRGIPointCloudNormals): points with a fallback normal, non-finite
   * points. */
  vtkGetMacro(NumberOfDegeneratePoints, vtkIdType);
  vtkGetMacro(NumberOfNonFinitePoints, vtkIdType);
  ///@}

protected:
  vtkPVMRGIPointCloudNormals() = default;
  ~vtkPVMRGIPointCloudNormals() override = default;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int NumberOfNeighbors = 16;
  double RadiusScale = 1.0;
  double Up[3] = { 0.0, 0.0, 0.0 };
  bool ComputeNormals = false;
  vtkIdType NumberOfDegeneratePoints = 0;
  vtkIdType NumberOfNonFinitePoints = 0;

private:
  vtkPVMRGIPointCloudNormals(const vtkPVMRGIPointCloudNormals&) = delete;
  void operator=(const vtkPVMRGIPointCloudNormals&) = delete;
};

#endif
