/**
 * @class   vtkMRGIPCLPointCloudNormals
 * @brief   vtkMRGIPointCloudNormals through PCL: integral-image normals for
 *          organized clouds, multithreaded kNN normals for the rest.
 *
 * The object factory's override of vtkMRGIPointCloudNormals in MRGI's PCL
 * module (VTK 9.1 build only). Properties, outputs and orientation rules
 * are the base class's; only the estimation differs:
 * - organized input (field data "OrganizedDimensions" = width, height,
 *   both at least 40, and point data "PixelIndex", as vtkMRGIPCLPCDReader
 *   writes them; PCL 1.13's estimator crashes on images under 10 pixels
 *   high or wide): the
 *   points are put back on their width x height grid (NaN elsewhere) and
 *   pcl::IntegralImageNormalEstimation (average 3D gradient, smoothing 10
 *   pixels, depth-change factor 0.02) gives the normals; where it gives none
 *   (borders, depth discontinuities, holes) the kNN estimate below is used;
 * - otherwise pcl::NormalEstimationOMP over a k-d tree with
 *   NumberOfNeighbors neighbours (all cores through OpenMP);
 * - normals that PCL leaves undefined (fewer than 3 neighbours) get the
 *   base class's fallback direction and are counted as degenerate;
 * - radii: the base class's (the C core's grid search, RadiusScale * d_k *
 *   sqrt(pi / k)); PCL's k-d tree took 2.7 times as long for them.
 */
#ifndef vtkMRGIPCLPointCloudNormals_h
#define vtkMRGIPCLPointCloudNormals_h

#include "MRGIRenderingPCLModule.h" // For export macro
#include "vtkMRGIPointCloudNormals.h"

class MRGIRENDERINGPCL_EXPORT vtkMRGIPCLPointCloudNormals : public vtkMRGIPointCloudNormals
{
public:
  static vtkMRGIPCLPointCloudNormals* New();
  vtkTypeMacro(vtkMRGIPCLPointCloudNormals, vtkMRGIPointCloudNormals);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Whether the last run used integral-image normals (an organized input).
   */
  vtkGetMacro(UsedIntegralImage, bool);
  ///@}

protected:
  vtkMRGIPCLPointCloudNormals();
  ~vtkMRGIPCLPointCloudNormals() override;

  bool Estimate(vtkPolyData* input, const float* xyz, vtkIdType n, int orientation,
    const double reference[3], float* normals, float* radii) override;

  bool UsedIntegralImage = false;

private:
  vtkMRGIPCLPointCloudNormals(const vtkMRGIPCLPointCloudNormals&) = delete;
  void operator=(const vtkMRGIPCLPointCloudNormals&) = delete;
};

#endif
