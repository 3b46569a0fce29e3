#include "vtkMRGIPointCloud.h"

#include "vtkCellArray.h"
#include "vtkCellTypes.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkIdList.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkTypeInt32Array.h"
#include "vtkTypeInt64Array.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnstructuredGrid.h"
#include "vtkVersionMacros.h"

#include <cmath>
#include <limits>

vtkStandardNewMacro(vtkMRGIPointCloud);

namespace
{
bool Finite(const double p[3])
{
  return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
}

// One vertex cell per point, 32-bit ids when they fit.
template <typename ArrayT>
void SetOneVertexPerPoint(vtkPolyData* poly, vtkIdType n)
{
  using T = typename ArrayT::ValueType;
  vtkNew<ArrayT> offsets;
  vtkNew<ArrayT> connectivity;
  offsets->SetNumberOfValues(n + 1);
  connectivity->SetNumberOfValues(n);
  for (vtkIdType i = 0; i < n; ++i)
  {
    offsets->SetValue(i, static_cast<T>(i));
    connectivity->SetValue(i, static_cast<T>(i));
  }
  offsets->SetValue(n, static_cast<T>(n));
  vtkNew<vtkCellArray> verts;
  verts->SetData(offsets, connectivity);
  poly->SetVerts(verts);
}
}

//------------------------------------------------------------------------------
bool vtkMRGIPointCloud::IsPointCloud(vtkDataObject* data)
{
  if (auto* poly = vtkPolyData::SafeDownCast(data))
  {
    return poly->GetNumberOfPoints() > 0 && poly->GetNumberOfLines() == 0 &&
      poly->GetNumberOfPolys() == 0 && poly->GetNumberOfStrips() == 0;
  }
  auto* set = vtkPointSet::SafeDownCast(data);
  if (!set || set->GetNumberOfPoints() == 0)
  {
    return false;
  }
  if (auto* grid = vtkUnstructuredGrid::SafeDownCast(set))
  {
    // The grid's distinct cell types, not a walk over every cell. VTK 9.2
    // (ParaView's) deprecates GetCellTypes(vtkCellTypes*), which 9.1 has alone.
#if VTK_VERSION_NUMBER >= VTK_VERSION_CHECK(9, 2, 0)
    vtkUnsignedCharArray* types = grid->GetDistinctCellTypesArray();
    const vtkIdType numberOfTypes = types ? types->GetNumberOfValues() : 0;
    for (vtkIdType t = 0; t < numberOfTypes; ++t)
    {
      const unsigned char type = types->GetValue(t);
#else
    vtkNew<vtkCellTypes> types;
    grid->GetCellTypes(types);
    for (vtkIdType t = 0; t < types->GetNumberOfTypes(); ++t)
    {
      const unsigned char type = types->GetCellType(t);
#endif
      if (type != VTK_VERTEX && type != VTK_POLY_VERTEX)
      {
        return false;
      }
    }
    return true;
  }
  return set->GetNumberOfCells() == 0;
}

//------------------------------------------------------------------------------
vtkIdType vtkMRGIPointCloud::CountFinitePoints(vtkPointSet* cloud)
{
  vtkPoints* points = cloud ? cloud->GetPoints() : nullptr;
  if (!points)
  {
    return 0;
  }
  vtkIdType finite = 0;
  const vtkIdType n = points->GetNumberOfPoints();
  for (vtkIdType i = 0; i < n; ++i)
  {
    double p[3];
    points->GetPoint(i, p);
    finite += Finite(p) ? 1 : 0;
  }
  return finite;
}

//------------------------------------------------------------------------------
vtkPolyData* vtkMRGIPointCloud::NewFiniteCloud(vtkPointSet* cloud)
{
  if (!IsPointCloud(cloud))
  {
    return nullptr;
  }
  vtkPoints* points = cloud->GetPoints();
  const vtkIdType n = points->GetNumberOfPoints();
  vtkPolyData* out = vtkPolyData::New();
  const vtkIdType finite = CountFinitePoints(cloud);
  if (finite == 0)
  {
    return out;
  }
  auto* poly = vtkPolyData::SafeDownCast(cloud);
  vtkCellArray* verts = poly ? poly->GetVerts() : nullptr;
  const bool oneVertexEach =
    verts && verts->GetNumberOfCells() == n && verts->GetNumberOfConnectivityIds() == n;
  if (finite == n && oneVertexEach)
  {
    // Already drawable (the LAS reader's output): share the arrays.
    out->ShallowCopy(cloud);
    return out;
  }
  vtkPointData* inPD = cloud->GetPointData();
  vtkPointData* outPD = out->GetPointData();
  vtkNew<vtkPoints> kept;
  kept->SetDataType(points->GetDataType());
  kept->SetNumberOfPoints(finite);
  outPD->CopyAllocate(inPD, finite);
  vtkIdType k = 0;
  for (vtkIdType i = 0; i < n; ++i)
  {
    double p[3];
    points->GetPoint(i, p);
    if (Finite(p))
    {
      kept->SetPoint(k, p);
      outPD->CopyData(inPD, i, k);
      ++k;
    }
  }
  out->SetPoints(kept);
  if (finite < vtkIdType(std::numeric_limits<vtkTypeInt32>::max()))
  {
    SetOneVertexPerPoint<vtkTypeInt32Array>(out, finite);
  }
  else
  {
    SetOneVertexPerPoint<vtkTypeInt64Array>(out, finite);
  }
  out->GetFieldData()->ShallowCopy(cloud->GetFieldData());
  return out;
}

//------------------------------------------------------------------------------
void vtkMRGIPointCloud::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
