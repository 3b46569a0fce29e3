/**
 * @class   vtkMRGIPCLPCDReader
 * @brief   vtkMRGIPCDReader through PCL's own pcl::PCDReader.
 *
 * The object factory's override of vtkMRGIPCDReader in MRGI's PCL module
 * (VTK 9.1 build only): vtkMRGIPCDReader::New() returns this class when the
 * module is loaded.
 *
 * The file is first checked by the C core (mrgi_pcd_check.h: PCL 1.13
 * crashes or over-allocates on some malformed files and silently misreads
 * others), then read by pcl::PCDReader into a pcl::PCLPointCloud2 (DATA
 * ascii, binary and binary_compressed) and converted:
 * - x y z (float or double fields) -> points (float); points with a
 *   non-finite coordinate are dropped (the NaN padding of organized clouds);
 *   one vertex cell per point;
 * - rgb (packed float or uint32) or rgba (uint32, 0xAARRGGBB) -> "RGB",
 *   unsigned char, 3 components, the active scalars;
 * - normal_x normal_y normal_z -> "Normals", the active normals (dropped
 *   with a warning when one kept point's normal is not finite, so that
 *   vtkMRGIPointCloudNormals estimates them);
 * - intensity -> "Intensity", curvature -> "Curvature" (float);
 * - organized clouds (HEIGHT > 1): "PixelIndex" (vtkIdType, row * WIDTH +
 *   column of each kept point) and field data "OrganizedDimensions" (int:
 *   WIDTH, HEIGHT);
 * - VIEWPOINT (PCL gives the origin and the identity when a file has none)
 *   -> field data "SensorOrigin" (double x y z) and "SensorOrientation"
 *   (double quaternion w x y z).
 *
 * Errors (each names the file; the output is empty and the request fails):
 * no file name, a file that cannot be read, a structure error found by the
 * check, a file PCL refuses (its own message goes to the standard error), a
 * cloud without any finite point.
 */
#ifndef vtkMRGIPCLPCDReader_h
#define vtkMRGIPCLPCDReader_h

#include "MRGIRenderingPCLModule.h" // For export macro
#include "vtkMRGIPCDReader.h"

class MRGIRENDERINGPCL_EXPORT vtkMRGIPCLPCDReader : public vtkMRGIPCDReader
{
public:
  static vtkMRGIPCLPCDReader* New();
  vtkTypeMacro(vtkMRGIPCLPCDReader, vtkMRGIPCDReader);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Files declaring more points are refused before PCL allocates them;
   * 2^28 by default (the limit of MRGI's scene builder), at least 1.
   */
  vtkSetClampMacro(MaximumNumberOfPoints, vtkIdType, 1, VTK_ID_MAX);
  vtkGetMacro(MaximumNumberOfPoints, vtkIdType);
  ///@}

  ///@{
  /**
   * What the last successful read found: the points in the file (WIDTH x
   * HEIGHT) and the non-finite ones dropped.
   */
  vtkGetMacro(NumberOfPointsInFile, vtkIdType);
  vtkGetMacro(NumberOfDroppedPoints, vtkIdType);
  ///@}

protected:
  vtkMRGIPCLPCDReader();
  ~vtkMRGIPCLPCDReader() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  vtkIdType MaximumNumberOfPoints = vtkIdType(1) << 28;
  vtkIdType NumberOfPointsInFile = 0;
  vtkIdType NumberOfDroppedPoints = 0;

private:
  vtkMRGIPCLPCDReader(const vtkMRGIPCLPCDReader&) = delete;
  void operator=(const vtkMRGIPCLPCDReader&) = delete;
};

#endif
