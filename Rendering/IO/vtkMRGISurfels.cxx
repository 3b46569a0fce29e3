#include "vtkMRGISurfels.h"

#include "vtkCellArray.h"
#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkProp3D.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkTypeInt32Array.h"
#include "vtkTypeInt64Array.h"

#include "mrgi_surfels.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

vtkStandardNewMacro(vtkMRGISurfels);

//------------------------------------------------------------------------------
vtkMRGISurfels::vtkMRGISurfels() = default;

//------------------------------------------------------------------------------
int vtkMRGISurfels::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  return 1;
}

namespace
{
// A contiguous float copy of `array`'s first `components` components (or the
// array's own memory when it is a float array with exactly that layout).
const float* AsFloats(vtkDataArray* array, int components, std::vector<float>& copy)
{
  vtkFloatArray* floats = vtkFloatArray::SafeDownCast(array);
  if (floats && floats->GetNumberOfComponents() == components)
  {
    return floats->GetPointer(0);
  }
  const vtkIdType n = array->GetNumberOfTuples();
  copy.resize(static_cast<size_t>(n) * components);
  for (vtkIdType i = 0; i < n; ++i)
  {
    for (int c = 0; c < components; ++c)
    {
      copy[static_cast<size_t>(i) * components + c] = static_cast<float>(array->GetComponent(i, c));
    }
  }
  return copy.data();
}

// `in`'s tuple source[j] repeated on corners j*corners .. j*corners+corners-1.
vtkSmartPointer<vtkAbstractArray> RepeatTuples(
  vtkAbstractArray* in, const std::vector<int64_t>& source, int corners)
{
  vtkSmartPointer<vtkAbstractArray> out =
    vtkSmartPointer<vtkAbstractArray>::Take(in->NewInstance());
  out->SetName(in->GetName());
  out->SetNumberOfComponents(in->GetNumberOfComponents());
  const vtkIdType kept = static_cast<vtkIdType>(source.size());
  out->SetNumberOfTuples(kept * corners);
  vtkDataArray* data = vtkDataArray::SafeDownCast(in);
  if (data && data->HasStandardMemoryLayout() && in->GetDataType() != VTK_BIT &&
    in->GetDataTypeSize() > 0)
  {
    // Plain arrays (all of VTK's numeric ones): byte copies, no virtual call per tuple.
    const size_t bytes = static_cast<size_t>(in->GetDataTypeSize()) * in->GetNumberOfComponents();
    const char* from = static_cast<const char*>(in->GetVoidPointer(0));
    char* to = static_cast<char*>(out->GetVoidPointer(0));
    for (vtkIdType j = 0; j < kept; ++j)
    {
      const char* tuple = from + static_cast<size_t>(source[j]) * bytes;
      for (int k = 0; k < corners; ++k)
      {
        std::memcpy(to + (static_cast<size_t>(j) * corners + k) * bytes, tuple, bytes);
      }
    }
    return out;
  }
  for (vtkIdType j = 0; j < kept; ++j)
  {
    for (int k = 0; k < corners; ++k)
    {
      out->SetTuple(j * corners + k, source[j], in);
    }
  }
  return out;
}

// The cells: polygon j has corners j*corners .. j*corners+corners-1.
template <typename ArrayT>
vtkSmartPointer<vtkCellArray> MakePolygons(vtkIdType kept, int corners)
{
  vtkNew<ArrayT> offsets;
  vtkNew<ArrayT> connectivity;
  offsets->SetNumberOfValues(kept + 1);
  connectivity->SetNumberOfValues(kept * corners);
  auto* o = offsets->GetPointer(0);
  auto* c = connectivity->GetPointer(0);
  using ValueT = typename ArrayT::ValueType;
  for (vtkIdType j = 0; j <= kept; ++j)
  {
    o[j] = static_cast<ValueT>(j * corners);
  }
  for (vtkIdType i = 0; i < kept * corners; ++i)
  {
    c[i] = static_cast<ValueT>(i);
  }
  vtkNew<vtkCellArray> polys;
  polys->SetData(offsets, connectivity);
  return vtkSmartPointer<vtkCellArray>(polys.GetPointer());
}
}

//------------------------------------------------------------------------------
int vtkMRGISurfels::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0], 0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  this->NumberOfSkippedPoints = 0;
  this->Stride = 1;
  if (!input || !output)
  {
    vtkErrorMacro("vtkMRGISurfels: no input point cloud (a vtkPolyData) is connected");
    return 0;
  }
  const vtkIdType count = input->GetNumberOfPoints();
  if (count == 0)
  {
    return 1; // an empty cloud gives an empty output: nothing is missing
  }
  if (input->GetNumberOfLines() > 0 || input->GetNumberOfPolys() > 0 ||
    input->GetNumberOfStrips() > 0)
  {
    vtkErrorMacro("vtkMRGISurfels: the input is not a point cloud: it has "
      << input->GetNumberOfLines() << " lines, " << input->GetNumberOfPolys() << " polygons and "
      << input->GetNumberOfStrips()
      << " strips (a point cloud has vertex cells or no cells); draw a mesh as it is");
    return 0;
  }
  if (!(this->RadiusScale > 0.0))
  {
    vtkErrorMacro("vtkMRGISurfels: RadiusScale is " << this->RadiusScale
                                                    << "; it must be > 0 (1 keeps the radii)");
    return 0;
  }

  vtkPointData* inPD = input->GetPointData();
  vtkDataArray* normals = nullptr;
  if (this->NormalsArrayName.empty())
  {
    normals = inPD->GetNormals() ? inPD->GetNormals() : inPD->GetArray("Normals");
  }
  else
  {
    normals = inPD->GetArray(this->NormalsArrayName.c_str());
  }
  if (!normals)
  {
    vtkErrorMacro("vtkMRGISurfels: the point cloud of "
      << count << " points has no normals (point-data array "
      << (this->NormalsArrayName.empty() ? std::string("active normals or 'Normals'")
                                         : "'" + this->NormalsArrayName + "'")
      << "): surfels need one orientation per point; put vtkMRGIPointCloudNormals before "
         "vtkMRGISurfels, or set NormalsArrayName");
    return 0;
  }
  if (normals->GetNumberOfComponents() != 3)
  {
    vtkErrorMacro("vtkMRGISurfels: the normals array '"
      << (normals->GetName() ? normals->GetName() : "") << "' has "
      << normals->GetNumberOfComponents() << " components; normals need 3");
    return 0;
  }
  if (normals->GetNumberOfTuples() != count)
  {
    vtkErrorMacro("vtkMRGISurfels: the normals array '"
      << (normals->GetName() ? normals->GetName() : "") << "' has " << normals->GetNumberOfTuples()
      << " tuples for " << count << " points");
    return 0;
  }
  vtkDataArray* radii =
    this->RadiusArrayName.empty() ? nullptr : inPD->GetArray(this->RadiusArrayName.c_str());
  if (radii && radii->GetNumberOfComponents() != 1)
  {
    vtkErrorMacro("vtkMRGISurfels: the radius array '" << this->RadiusArrayName << "' has "
                                                       << radii->GetNumberOfComponents()
                                                       << " components; a radius is 1");
    return 0;
  }
  if (radii && radii->GetNumberOfTuples() != count)
  {
    vtkErrorMacro("vtkMRGISurfels: the radius array '"
      << this->RadiusArrayName << "' has " << radii->GetNumberOfTuples() << " tuples for " << count
      << " points");
    return 0;
  }
  const double radius = this->Radius;
  if (!radii && !(radius > 0.0 && radius <= std::numeric_limits<float>::max()))
  {
    vtkErrorMacro("vtkMRGISurfels: the point cloud has no radius array '"
      << this->RadiusArrayName << "' and Radius is " << radius
      << ": give each point a radius (vtkMRGIPointCloudNormals adds 'Radius') or SetRadius(r) "
         "in scene units");
    return 0;
  }

  std::vector<float> positionCopy, normalCopy, radiusCopy;
  mrgi_surfel_input in;
  in.count = static_cast<int64_t>(count);
  in.positions = AsFloats(input->GetPoints()->GetData(), 3, positionCopy);
  in.normals = AsFloats(normals, 3, normalCopy);
  in.radii = radii ? AsFloats(radii, 1, radiusCopy) : nullptr;
  in.radius = static_cast<float>(radius);
  in.radius_scale = static_cast<float>(this->RadiusScale);
  // Level of detail: the smallest stride that keeps at most the budget.
  in.stride = this->MaximumNumberOfSurfels > 0
    ? static_cast<int64_t>(
        (count + this->MaximumNumberOfSurfels - 1) / this->MaximumNumberOfSurfels)
    : 1;
  this->Stride = static_cast<vtkIdType>(in.stride);

  mrgi_surfel_counts counts;
  mrgi_error err;
  if (mrgi_surfels_count(&in, &counts, &err) != MRGI_OK)
  {
    vtkErrorMacro("vtkMRGISurfels: " << err.message);
    return 0;
  }
  const int corners = this->Shape == Hexagon ? 6 : 4;
  const vtkIdType kept = static_cast<vtkIdType>(counts.kept);
  const vtkIdType vertices = kept * corners;

  vtkNew<vtkFloatArray> outPositions;
  outPositions->SetNumberOfComponents(3);
  outPositions->SetNumberOfTuples(vertices);
  vtkNew<vtkFloatArray> outNormals;
  outNormals->SetName("Normals");
  outNormals->SetNumberOfComponents(3);
  outNormals->SetNumberOfTuples(vertices);
  std::vector<int64_t> source(static_cast<size_t>(kept));
  mrgi_surfel_output out;
  out.positions = outPositions->GetPointer(0);
  out.positions_capacity = static_cast<int64_t>(3 * vertices);
  out.normals = outNormals->GetPointer(0);
  out.normals_capacity = static_cast<int64_t>(3 * vertices);
  out.source = source.data();
  out.source_capacity = static_cast<int64_t>(kept);
  if (kept > 0 &&
    mrgi_surfels_build(&in, static_cast<mrgi_surfel_shape>(corners), &out, &counts, &err) !=
      MRGI_OK)
  {
    vtkErrorMacro("vtkMRGISurfels: " << err.message);
    return 0;
  }
  positionCopy = std::vector<float>();
  normalCopy = std::vector<float>();
  radiusCopy = std::vector<float>();

  this->NumberOfSkippedPoints =
    static_cast<vtkIdType>(counts.bad_position + counts.bad_normal + counts.bad_radius);
  if (this->NumberOfSkippedPoints > 0)
  {
    vtkWarningMacro("vtkMRGISurfels: skipped "
      << this->NumberOfSkippedPoints << " of " << count << " points: " << counts.bad_position
      << " with a non-finite position, " << counts.bad_normal
      << " with a non-finite or zero normal, " << counts.bad_radius
      << " with a radius that is not a positive number");
  }

  vtkNew<vtkPoints> points;
  points->SetData(outPositions);
  output->SetPoints(points);
  // 32-bit offsets and connectivity halve the cell array while they can hold it.
  if (vertices <= static_cast<vtkIdType>(std::numeric_limits<int32_t>::max()))
  {
    output->SetPolys(MakePolygons<vtkTypeInt32Array>(kept, corners));
  }
  else
  {
    output->SetPolys(MakePolygons<vtkTypeInt64Array>(kept, corners));
  }

  vtkPointData* outPD = output->GetPointData();
  for (int a = 0; a < inPD->GetNumberOfArrays(); ++a)
  {
    vtkAbstractArray* array = inPD->GetAbstractArray(a);
    if (!array || array == normals)
    {
      continue;
    }
    if (array->GetNumberOfTuples() != count)
    {
      // Reading it per point would run past its end: left out, said once per update.
      vtkWarningMacro("vtkMRGISurfels: point array '"
        << (array->GetName() ? array->GetName() : "(unnamed)") << "' has "
        << array->GetNumberOfTuples() << " tuples for " << count << " points; left out");
      continue;
    }
    vtkSmartPointer<vtkAbstractArray> repeated = RepeatTuples(array, source, corners);
    outPD->AddArray(repeated);
    // Active scalars (colours), tensors... stay active; the normals are the surfels' own.
    const int attribute = inPD->IsArrayAnAttribute(a);
    if (attribute >= 0 && attribute != vtkDataSetAttributes::NORMALS && array->GetName())
    {
      outPD->SetActiveAttribute(array->GetName(), attribute);
    }
  }
  outPD->SetNormals(outNormals);
  return 1;
}

//------------------------------------------------------------------------------
vtkIdType vtkMRGISurfels::SuggestMaximumNumberOfSurfels(
  vtkRenderer* renderer, vtkProp3D* prop, double surfelsPerPixel)
{
  if (!renderer || !prop || !renderer->GetRenderWindow() || !(surfelsPerPixel > 0.0))
  {
    return 0;
  }
  const double* bounds = prop->GetBounds();
  if (!bounds || !(bounds[0] <= bounds[1]))
  {
    return 0;
  }
  const int* size = renderer->GetSize();
  const int* origin = renderer->GetOrigin();
  double lo[2] = { VTK_DOUBLE_MAX, VTK_DOUBLE_MAX };
  double hi[2] = { -VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX };
  for (int corner = 0; corner < 8; ++corner)
  {
    renderer->SetWorldPoint(
      bounds[corner & 1], bounds[2 + ((corner >> 1) & 1)], bounds[4 + ((corner >> 2) & 1)], 1.0);
    renderer->WorldToDisplay();
    const double* d = renderer->GetDisplayPoint();
    // Display z in [0, 1] is between the clipping planes; a corner behind the
    // camera projects mirrored, so the box then counts as the whole viewport.
    if (d[2] < 0.0 || d[2] > 1.0)
    {
      lo[0] = origin[0];
      lo[1] = origin[1];
      hi[0] = origin[0] + size[0];
      hi[1] = origin[1] + size[1];
      break;
    }
    for (int a = 0; a < 2; ++a)
    {
      lo[a] = std::min(lo[a], d[a]);
      hi[a] = std::max(hi[a], d[a]);
    }
  }
  double pixels = 1.0;
  for (int a = 0; a < 2; ++a)
  {
    const double from = std::max(lo[a], static_cast<double>(origin[a]));
    const double to = std::min(hi[a], static_cast<double>(origin[a] + size[a]));
    pixels *= std::max(0.0, to - from);
  }
  const double budget = std::ceil(pixels * surfelsPerPixel);
  return budget < 1.0 ? 1 : static_cast<vtkIdType>(std::min(budget, 1e15));
}

//------------------------------------------------------------------------------
void vtkMRGISurfels::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Shape: " << (this->Shape == Hexagon ? "Hexagon" : "Square") << "\n";
  os << indent << "NormalsArrayName: "
     << (this->NormalsArrayName.empty() ? "(active normals, else Normals)" : this->NormalsArrayName)
     << "\n";
  os << indent << "RadiusArrayName: " << this->RadiusArrayName << "\n";
  os << indent << "Radius: " << this->Radius << "\n";
  os << indent << "RadiusScale: " << this->RadiusScale << "\n";
  os << indent << "MaximumNumberOfSurfels: " << this->MaximumNumberOfSurfels << "\n";
  os << indent << "Stride: " << this->Stride << "\n";
  os << indent << "NumberOfSkippedPoints: " << this->NumberOfSkippedPoints << "\n";
}
