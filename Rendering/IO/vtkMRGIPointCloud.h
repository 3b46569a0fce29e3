/**
 * @class   vtkMRGIPointCloud
 * @brief   What MRGI treats as a point cloud, and a cloud ready to draw.
 *
 * A point cloud is a point set with at least one point whose cells are all
 * vertices (or poly-vertices), or that has no cells at all: a vtkPolyData
 * without lines, polygons or strips (a PLY or OBJ of bare vertices), or a
 * vtkUnstructuredGrid of vertex cells (a .vtu of points). Whatever reader made
 * it (LAS, PCD, PLY, legacy or XML VTK), vtkMRGISceneBuilder draws such data
 * through its point-cloud path.
 *
 * NewFiniteCloud() makes the form that path draws: every point with finite
 * coordinates, once, as one vertex cell, with its point data; points with a
 * NaN or infinite coordinate (scanners pad organized clouds with NaN) are
 * left out. Field data (e.g. the LAS reader's "Origin") are kept.
 */
#ifndef vtkMRGIPointCloud_h
#define vtkMRGIPointCloud_h

#include "MRGIRenderingIOModule.h" // For export macro
#include "vtkObject.h"
#include "vtkWrappingHints.h" // For VTK_NEWINSTANCE

class vtkDataObject;
class vtkPointSet;
class vtkPolyData;

class MRGIRENDERINGIO_EXPORT vtkMRGIPointCloud : public vtkObject
{
public:
  static vtkMRGIPointCloud* New();
  vtkTypeMacro(vtkMRGIPointCloud, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * True when `data` is a vtkPolyData with points and no lines, polygons or
   * strips, or another vtkPointSet with points whose cells are all
   * VTK_VERTEX or VTK_POLY_VERTEX (or that has none). False for nullptr,
   * empty data and any other type.
   */
  static bool IsPointCloud(vtkDataObject* data);

  /** The number of points of `cloud` whose three coordinates are finite; 0 for nullptr. */
  static vtkIdType CountFinitePoints(vtkPointSet* cloud);

  /**
   * A new vtkPolyData holding the finite points of `cloud`, one vertex cell
   * each, with their point data and the cloud's field data. When every
   * point is finite and already has its vertex, the arrays are shared, not
   * copied. nullptr when `cloud` is not a point cloud (IsPointCloud()); an
   * empty vtkPolyData when no point is finite. The caller owns the result.
   */
  VTK_NEWINSTANCE static vtkPolyData* NewFiniteCloud(vtkPointSet* cloud);

protected:
  vtkMRGIPointCloud() = default;
  ~vtkMRGIPointCloud() override = default;

private:
  vtkMRGIPointCloud(const vtkMRGIPointCloud&) = delete;
  void operator=(const vtkMRGIPointCloud&) = delete;
};

#endif
