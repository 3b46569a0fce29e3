#include "vtkMRGIReaderOutput.h"

#include "vtkCellArray.h"
#include "vtkCellType.h"
#include "vtkCompositeDataIterator.h"
#include "vtkCompositeDataSet.h"
#include "vtkDataArray.h"
#include "vtkDataObject.h"
#include "vtkDataSet.h"
#include "vtkImageData.h"
#include "vtkPointSet.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnstructuredGrid.h"

#include <cmath>
#include <string>

namespace
{
// Points of a linear or quadratic cell type; -k: at least k; 0: not drawn by MRGI.
int CellPoints(int type)
{
  switch (type)
  {
    case VTK_VERTEX:
      return 1;
    case VTK_POLY_VERTEX:
      return -1;
    case VTK_LINE:
      return 2;
    case VTK_POLY_LINE:
      return -2;
    case VTK_TRIANGLE:
      return 3;
    case VTK_TRIANGLE_STRIP:
      return -3;
    case VTK_POLYGON:
      return -3;
    case VTK_PIXEL:
    case VTK_QUAD:
    case VTK_TETRA:
      return 4;
    case VTK_VOXEL:
    case VTK_HEXAHEDRON:
      return 8;
    case VTK_WEDGE:
      return 6;
    case VTK_PYRAMID:
      return 5;
    case VTK_PENTAGONAL_PRISM:
      return 10;
    case VTK_HEXAGONAL_PRISM:
      return 12;
    case VTK_QUADRATIC_EDGE:
      return 3;
    case VTK_QUADRATIC_TRIANGLE:
      return 6;
    case VTK_QUADRATIC_QUAD:
      return 8;
    case VTK_QUADRATIC_TETRA:
      return 10;
    case VTK_QUADRATIC_HEXAHEDRON:
      return 20;
    case VTK_QUADRATIC_WEDGE:
      return 15;
    case VTK_QUADRATIC_PYRAMID:
      return 13;
    default:
      return 0;
  }
}

// What a reader returned, checked before any filter or mapper touches it:
// point ids in range (VTK's filters index with them unchecked), cell types
// with their point counts, finite coordinates, bounded sizes.
bool ValidDataSet(vtkDataSet* ds, std::string& why)
{
  const vtkIdType np = ds->GetNumberOfPoints();
  if (np > vtkMRGIReaderOutput::MaxPoints)
  {
    why = "it has " + std::to_string(np) + " points, more than MRGI draws (" +
      std::to_string(vtkMRGIReaderOutput::MaxPoints) + ")";
    return false;
  }
  if (auto* image = vtkImageData::SafeDownCast(ds))
  {
    int dims[3];
    image->GetDimensions(dims);
    double spacing[3];
    image->GetSpacing(spacing);
    for (int k = 0; k < 3; ++k)
    {
      if (dims[k] < 0 || !std::isfinite(spacing[k]) || !std::isfinite(image->GetOrigin()[k]))
      {
        why = "its image extent, origin or spacing is not valid";
        return false;
      }
    }
    return true;
  }
  if (auto* pointSet = vtkPointSet::SafeDownCast(ds))
  {
    if (vtkPoints* points = pointSet->GetPoints())
    {
      for (vtkIdType i = 0; i < np; ++i)
      {
        double p[3];
        points->GetPoint(i, p);
        if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
        {
          why = "point " + std::to_string(i) + " has a coordinate that is not a finite number";
          return false;
        }
      }
    }
  }
  if (auto* poly = vtkPolyData::SafeDownCast(ds))
  {
    return vtkMRGIReaderOutput::CellsInRange(poly->GetVerts(), np, "vertex", why) &&
      vtkMRGIReaderOutput::CellsInRange(poly->GetLines(), np, "line", why) &&
      vtkMRGIReaderOutput::CellsInRange(poly->GetPolys(), np, "polygon", why) &&
      vtkMRGIReaderOutput::CellsInRange(poly->GetStrips(), np, "strip", why);
  }
  if (auto* grid = vtkUnstructuredGrid::SafeDownCast(ds))
  {
    vtkCellArray* cells = grid->GetCells();
    if (!vtkMRGIReaderOutput::CellsInRange(cells, np, "", why))
    {
      return false;
    }
    const vtkIdType n = cells ? cells->GetNumberOfCells() : 0;
    vtkUnsignedCharArray* types = grid->GetCellTypesArray();
    if (n > 0 && (!types || types->GetNumberOfValues() != n))
    {
      why = "its cell types do not match its cells";
      return false;
    }
    for (vtkIdType c = 0; c < n; ++c)
    {
      const int type = types->GetValue(c);
      const int need = CellPoints(type);
      const vtkIdType have = cells->GetCellSize(c);
      if (type == VTK_EMPTY_CELL && have == 0)
      {
        continue;
      }
      if (need == 0 || (need > 0 && have != need) || (need < 0 && have < -need))
      {
        why = "cell " + std::to_string(c) + " has type " + std::to_string(type) + " and " +
          std::to_string(have) + " points, which MRGI cannot draw";
        return false;
      }
    }
  }
  return true;
}
}

namespace vtkMRGIReaderOutput
{
//------------------------------------------------------------------------------
bool CellsInRange(vtkCellArray* cells, vtkIdType npoints, const char* what, std::string& why)
{
  if (!cells)
  {
    return true;
  }
  // The offsets first: cells are read through them.
  vtkDataArray* offsets = cells->GetOffsetsArray();
  vtkDataArray* connectivity = cells->GetConnectivityArray();
  const vtkIdType noff = offsets ? offsets->GetNumberOfValues() : 0;
  const double nconn = connectivity ? static_cast<double>(connectivity->GetNumberOfValues()) : 0.0;
  double previous = 0;
  for (vtkIdType i = 0; i < noff; ++i)
  {
    const double o = offsets->GetComponent(i, 0);
    if ((i == 0 && o != 0) || o < previous || o > nconn || (i == noff - 1 && o != nconn))
    {
      why = std::string(what) + " offsets are not valid (offset " + std::to_string(i) + " is " +
        std::to_string(static_cast<long long>(o)) + ")";
      return false;
    }
    previous = o;
  }
  if (noff == 0 && nconn > 0)
  {
    why = std::string(what) + " connectivity without offsets";
    return false;
  }
  const vtkIdType n = cells->GetNumberOfCells();
  for (vtkIdType c = 0; c < n; ++c)
  {
    vtkIdType size = 0;
    const vtkIdType* ids = nullptr;
    cells->GetCellAtId(c, size, ids);
    for (vtkIdType i = 0; i < size; ++i)
    {
      if (ids[i] < 0 || ids[i] >= npoints)
      {
        why = std::string(what) + (what[0] ? " cell " : "cell ") + std::to_string(c) +
          " refers to point " + std::to_string(ids[i]) + ", outside [0, " +
          std::to_string(npoints) + ")";
        return false;
      }
    }
  }
  return true;
}

//------------------------------------------------------------------------------
bool ValidData(vtkDataObject* data, std::string& why)
{
  if (auto* ds = vtkDataSet::SafeDownCast(data))
  {
    return ValidDataSet(ds, why);
  }
  if (auto* composite = vtkCompositeDataSet::SafeDownCast(data))
  {
    vtkSmartPointer<vtkCompositeDataIterator> it;
    it.TakeReference(composite->NewIterator());
    for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem())
    {
      if (auto* leaf = vtkDataSet::SafeDownCast(it->GetCurrentDataObject()))
      {
        if (!ValidDataSet(leaf, why))
        {
          return false;
        }
      }
    }
  }
  return true;
}
}
