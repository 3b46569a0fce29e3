#include "vtkMRGIMeshSampler.h"

#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkFloatArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkTypeInt32Array.h"
#include "vtkTypeInt64Array.h"

#include "mrgi_mesh.h"
#include "mrgi_mesh_sample.h"

#include <cstdint>
#include <limits>

vtkStandardNewMacro(vtkMRGIMeshSampler);

//------------------------------------------------------------------------------
vtkMRGIMeshSampler::vtkMRGIMeshSampler()
  : RadiusFactor(MRGI_MESH_SAMPLE_RADIUS_FACTOR)
{
}

//------------------------------------------------------------------------------
int vtkMRGIMeshSampler::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  return 1;
}

namespace
{
// Owns a core mesh for the length of one update.
struct CoreMesh
{
  mrgi_mesh Mesh = {};
  ~CoreMesh() { mrgi_mesh_destroy(&this->Mesh); }
};

// One vertex cell per point, `ArrayT` (32 or 64 bit) offsets and connectivity.
template <typename ArrayT>
void SetVertexCells(vtkPolyData* output, vtkIdType count)
{
  using ValueT = typename ArrayT::ValueType;
  vtkNew<ArrayT> offsets;
  vtkNew<ArrayT> connectivity;
  offsets->SetNumberOfValues(count + 1);
  connectivity->SetNumberOfValues(count);
  for (vtkIdType i = 0; i <= count; ++i)
  {
    offsets->SetValue(i, static_cast<ValueT>(i));
  }
  for (vtkIdType i = 0; i < count; ++i)
  {
    connectivity->SetValue(i, static_cast<ValueT>(i));
  }
  vtkNew<vtkCellArray> verts;
  verts->SetData(offsets, connectivity);
  output->SetVerts(verts);
}
}

//------------------------------------------------------------------------------
int vtkMRGIMeshSampler::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0], 0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  this->SampledRadius = 0.0;
  if (!input || !output)
  {
    vtkErrorMacro("vtkMRGIMeshSampler: no input mesh (a vtkPolyData) is connected");
    return 0;
  }
  if (input->GetNumberOfStrips() > 0)
  {
    vtkErrorMacro("vtkMRGIMeshSampler: the mesh has " << input->GetNumberOfStrips()
                                                      << " triangle strips; put vtkTriangleFilter "
                                                         "before the sampler");
    return 0;
  }
  vtkCellArray* polys = input->GetPolys();
  vtkIdType triangles = 0;
  {
    auto it = vtk::TakeSmartPointer(polys->NewIterator());
    for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell())
    {
      vtkIdType n;
      const vtkIdType* ids;
      it->GetCurrentCell(n, ids);
      triangles += n >= 3 ? n - 2 : 0;
    }
  }
  const vtkIdType vertices = input->GetNumberOfPoints();
  if (triangles == 0 || vertices < 3)
  {
    vtkErrorMacro("vtkMRGIMeshSampler: the mesh has no polygon with 3 or more points: no surface "
                  "to sample");
    return 0;
  }
  if (vertices > MRGI_MESH_MAX_VERTICES || triangles > MRGI_MESH_MAX_TRIANGLES)
  {
    vtkErrorMacro("vtkMRGIMeshSampler: the mesh has " << vertices << " points and " << triangles
                                                      << " triangles, more than the core's "
                                                         "limits");
    return 0;
  }
  CoreMesh mesh;
  mrgi_error err;
  if (mrgi_mesh_create(&mesh.Mesh, "vtkMRGIMeshSampler input", vertices, triangles, 0, &err) !=
    MRGI_OK)
  {
    vtkErrorMacro("vtkMRGIMeshSampler: " << err.message);
    return 0;
  }
  for (vtkIdType i = 0; i < vertices; ++i)
  {
    double p[3];
    input->GetPoint(i, p);
    for (int c = 0; c < 3; ++c)
    {
      mesh.Mesh.positions[3 * i + c] = static_cast<float>(p[c]);
    }
  }
  {
    vtkIdType t = 0;
    auto it = vtk::TakeSmartPointer(polys->NewIterator());
    for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell())
    {
      vtkIdType n;
      const vtkIdType* ids;
      it->GetCurrentCell(n, ids);
      for (vtkIdType k = 1; k + 1 < n; ++k, ++t)
      {
        mesh.Mesh.indices[3 * t] = static_cast<uint32_t>(ids[0]);
        mesh.Mesh.indices[3 * t + 1] = static_cast<uint32_t>(ids[k]);
        mesh.Mesh.indices[3 * t + 2] = static_cast<uint32_t>(ids[k + 1]);
      }
    }
  }

  const vtkIdType count = this->NumberOfPoints;
  vtkNew<vtkFloatArray> positions;
  positions->SetNumberOfComponents(3);
  positions->SetNumberOfTuples(count);
  vtkNew<vtkFloatArray> normals;
  normals->SetName("Normals");
  normals->SetNumberOfComponents(3);
  normals->SetNumberOfTuples(count);
  vtkNew<vtkFloatArray> radii;
  radii->SetName("Radius");
  radii->SetNumberOfTuples(count);
  const mrgi_mesh_samples out = { static_cast<int64_t>(count), positions->GetPointer(0),
    normals->GetPointer(0), radii->GetPointer(0) };
  double radius = 0.0;
  if (mrgi_mesh_sample(&mesh.Mesh, static_cast<int64_t>(count), this->Seed, this->RadiusFactor,
        &out, &radius, &err) != MRGI_OK)
  {
    vtkErrorMacro("vtkMRGIMeshSampler: " << err.message);
    return 0;
  }
  this->SampledRadius = radius;

  vtkNew<vtkPoints> points;
  points->SetData(positions);
  output->SetPoints(points);
  output->GetPointData()->SetNormals(normals);
  output->GetPointData()->AddArray(radii);
  if (count < static_cast<vtkIdType>(std::numeric_limits<int32_t>::max()))
  {
    SetVertexCells<vtkTypeInt32Array>(output, count);
  }
  else
  {
    SetVertexCells<vtkTypeInt64Array>(output, count);
  }
  return 1;
}

//------------------------------------------------------------------------------
void vtkMRGIMeshSampler::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "NumberOfPoints: " << this->NumberOfPoints << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "RadiusFactor: " << this->RadiusFactor << "\n";
  os << indent << "SampledRadius: " << this->SampledRadius << "\n";
}
