/**
 * @class   vtkMRGIPointCloudNormals
 * @brief   Adds point normals and splat radii to a point cloud.
 *
 * The output is the input (shallow copy) with, per point:
 * - "Normals" (float, 3 components, the active normals), estimated when the
 *   input has no normals or when ComputeNormals is on;
 * - "Radius" (float), the radius of a disk (surfel) that closes the holes
 *   between the point and its neighbours: RadiusScale times the local sample
 *   spacing, estimated from the distance d_k to the k-th nearest neighbour
 *   as d_k * sqrt(pi / k) (exact for evenly sampled surfaces).
 *   On organized clouds (depth-camera frames) it is raised where needed to
 *   cover the point's cell of the sensor's grid (GridRadii).
 *
 * Normals are oriented towards ViewPoint when UseViewPoint is on; else
 * towards the field data "SensorOrigin" (3 values) when it says where a
 * sensor was (SensorPoseIsMeaningful(): vtkMRGIPCDReader writes the PCD
 * VIEWPOINT there, and PCL writes the origin and the identity into every
 * file, so that pose counts only for organized clouds, i.e. depth-camera
 * frames); else along Up when Up is not zero (LAS clouds: (0, 0, 1)); else
 * away from the centroid of the points (right on closed, star-shaped
 * surfaces such as the Stanford bunny only).
 *
 * This class estimates with MRGI's C core (mrgi_point_normals.h: exact k
 * nearest neighbours over a uniform grid, PCA normals), single-threaded.
 * When MRGI's PCL module (MRGI::RenderingPCL) is loaded, New() returns its
 * override vtkMRGIPCLPointCloudNormals, which uses PCL: integral-image
 * normals for organized clouds (field data "OrganizedDimensions" and point
 * data "PixelIndex", as vtkMRGIPCDReader writes them), PCL's multithreaded
 * kNN normals otherwise, with the same orientation rules and radii. The
 * ParaView (VTK 9.2) build has no PCL module and always uses the core.
 *
 * Non-finite points get the fallback normal and radius 0 (the core's
 * contract). A finite point whose neighbourhood has no spacing (a lone
 * point, duplicates) gets the median of the other radii, or 1/100 of the
 * cloud's diagonal when no radius is positive (1 for a single point), so
 * that every finite point draws as a surfel.
 * The results are cached by the pipeline: RequestData runs again only when
 * the input or a property changes.
 */
#ifndef vtkMRGIPointCloudNormals_h
#define vtkMRGIPointCloudNormals_h

#include "MRGIRenderingIOModule.h" // For export macro
#include "vtkPolyDataAlgorithm.h"

class vtkFieldData;
class vtkFloatArray;

class MRGIRENDERINGIO_EXPORT vtkMRGIPointCloudNormals : public vtkPolyDataAlgorithm
{
public:
  /**
   * The PCL override when MRGI::RenderingPCL is loaded, else this class.
   */
  static vtkMRGIPointCloudNormals* New();
  vtkTypeMacro(vtkMRGIPointCloudNormals, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Neighbours per point, [3, 128]; 16 by default.
   */
  vtkSetClampMacro(NumberOfNeighbors, int, 3, 128);
  vtkGetMacro(NumberOfNeighbors, int);
  ///@}

  ///@{
  /**
   * Factor on the local spacing giving the radius; finite and > 0 (checked
   * when the filter runs); 1.0 by default (a square grid needs 0.71, a
   * hexagonal one 0.58; the margin covers irregular samples).
   */
  vtkSetMacro(RadiusScale, double);
  vtkGetMacro(RadiusScale, double);
  ///@}

  ///@{
  /**
   * Orient normals towards this point (world coordinates) when
   * UseViewPoint is on (off by default).
   */
  vtkSetVector3Macro(ViewPoint, double);
  vtkGetVector3Macro(ViewPoint, double);
  vtkSetMacro(UseViewPoint, bool);
  vtkGetMacro(UseViewPoint, bool);
  vtkBooleanMacro(UseViewPoint, bool);
  ///@}

  ///@{
  /**
   * Orient normals along this direction when there is no viewpoint; (0, 0,
   * 0) by default: no up, normals point away from the centroid.
   */
  vtkSetVector3Macro(Up, double);
  vtkGetVector3Macro(Up, double);
  ///@}

  ///@{
  /**
   * Estimate normals even when the input has some (off by default: they
   * are kept, and only the radii are computed).
   */
  vtkSetMacro(ComputeNormals, bool);
  vtkGetMacro(ComputeNormals, bool);
  vtkBooleanMacro(ComputeNormals, bool);
  ///@}

  /** How the last run oriented its normals. */
  enum OrientationMode
  {
    ORIENT_VIEWPOINT = 0,
    ORIENT_UP = 1,
    ORIENT_OUTWARD = 2
  };

  /**
   * Whether `input`'s field data "SensorOrigin" (and "SensorOrientation")
   * tell where a sensor was: present, and either the cloud is organized
   * (field data "OrganizedDimensions") or the pose is not PCL's default
   * (origin, identity).
   */
  static bool SensorPoseIsMeaningful(vtkPolyData* input);
  static bool SensorPoseIsMeaningful(vtkFieldData* fields);

  ///@{
  /**
   * On organized clouds (field data "OrganizedDimensions" and point data
   * "PixelIndex", as vtkMRGIPCDReader writes them), raise each radius so
   * that its surfel covers the point's own cell of the sensor's grid
   * (mrgi_grid_radii.h): at grazing angles the cells are much longer than
   * the kNN spacing, which leaves holes between the surfels. RadiusScale
   * multiplies these radii too. On by default; no effect on unorganized
   * clouds.
   */
  vtkSetMacro(GridRadii, bool);
  vtkGetMacro(GridRadii, bool);
  vtkBooleanMacro(GridRadii, bool);
  ///@}

  /** Points whose radius the grid raised in the last run (GridRadii). */
  vtkGetMacro(NumberOfGridRaisedPoints, vtkIdType);

  ///@{
  /**
   * What the last run did: the orientation used, the points with a fallback
   * normal (no plane in their neighbourhood) and those skipped because a
   * coordinate was not finite.
   */
  vtkGetMacro(LastOrientation, int);
  vtkGetMacro(NumberOfDegeneratePoints, vtkIdType);
  vtkGetMacro(NumberOfNonFinitePoints, vtkIdType);
  ///@}

protected:
  vtkMRGIPointCloudNormals();
  ~vtkMRGIPointCloudNormals() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  /**
   * Fills `normals` (3 * n floats; nullptr: keep the input's) and `radii`
   * (n floats) for the n points `xyz` of `input`, oriented by `orientation`
   * with `reference` (the viewpoint or the up vector). The base class calls
   * the C core; the PCL module overrides it. On failure: vtkErrorMacro and
   * false.
   */
  virtual bool Estimate(vtkPolyData* input, const float* xyz, vtkIdType n, int orientation,
    const double reference[3], float* normals, float* radii);

  /** GridRadii on `input` (true when unorganized); vtkErrorMacro and false on failure. */
  bool RaiseRadiiOnGrid(vtkPolyData* input, const float* xyz, vtkIdType n, float* radii);

  int NumberOfNeighbors = 16;
  bool GridRadii = true;
  vtkIdType NumberOfGridRaisedPoints = 0;
  double RadiusScale = 1.0;
  double ViewPoint[3] = { 0.0, 0.0, 0.0 };
  bool UseViewPoint = false;
  double Up[3] = { 0.0, 0.0, 0.0 };
  bool ComputeNormals = false;
  int LastOrientation = ORIENT_OUTWARD;
  vtkIdType NumberOfDegeneratePoints = 0;
  vtkIdType NumberOfNonFinitePoints = 0;

private:
  vtkMRGIPointCloudNormals(const vtkMRGIPointCloudNormals&) = delete;
  void operator=(const vtkMRGIPointCloudNormals&) = delete;
};

#endif
