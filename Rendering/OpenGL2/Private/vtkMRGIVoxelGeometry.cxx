#include "vtk_glew.h"

#include "vtkMRGIVoxelGeometry.h"

#include "vtkActor.h"
#include "vtkAssemblyNode.h"
#include "vtkAssemblyPath.h"
#include "vtkCellArray.h"
#include "vtkCompositeDataDisplayAttributes.h"
#include "vtkCompositeDataIterator.h"
#include "vtkCompositeDataSet.h"
#include "vtkCompositePolyDataMapper2.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProp.h"
#include "vtkPropCollection.h"
#include "vtkRenderer.h"
#include "vtkShaderProgram.h"
#include "vtkSmartPointer.h"
#include "vtkTriangleFilter.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

namespace
{
// One polydata's triangles in a vertex buffer: three float vertices per
// triangle (no index buffer: GL_TRIANGLES over the whole buffer), each the
// point minus `Centre` so that data far from the origin keeps float precision.
struct Geometry
{
  vtkMTimeType DataTime = 0;
  GLuint Buffer = 0;
  GLsizei Vertices = 0;
  double Centre[3] = { 0, 0, 0 };
  bool Seen = false;
};

// What one Voxelize() draws: a geometry with its object -> world matrix.
struct DrawItem
{
  Geometry* Geom;
  double ObjectToWorld[16]; // row-major (vtkMatrix4x4 order)
};

// The triangles of `data` (polygons and strips; vtkTriangleFilter where they
// are not all triangles already), as float xyz relative to `centre`.
void Triangulate(vtkPolyData* data, std::vector<float>& xyz, double centre[3])
{
  xyz.clear();
  vtkSmartPointer<vtkPolyData> tri = data;
  bool allTriangles = data->GetNumberOfStrips() == 0;
  if (allTriangles)
  {
    vtkCellArray* polys = data->GetPolys();
    allTriangles = polys->GetNumberOfCells() == 0 || polys->IsHomogeneous() == 3;
  }
  if (!allTriangles)
  {
    vtkNew<vtkTriangleFilter> filter;
    filter->SetInputData(data);
    filter->PassVertsOff();
    filter->PassLinesOff();
    filter->Update();
    tri = filter->GetOutput();
  }
  vtkPoints* points = tri->GetPoints();
  vtkCellArray* polys = tri->GetPolys();
  if (!points || polys->GetNumberOfCells() == 0)
  {
    centre[0] = centre[1] = centre[2] = 0;
    return;
  }
  double bounds[6];
  points->GetBounds(bounds);
  for (int k = 0; k < 3; ++k)
  {
    centre[k] = 0.5 * (bounds[2 * k] + bounds[2 * k + 1]);
    if (!std::isfinite(centre[k]))
    {
      centre[k] = 0;
    }
  }
  xyz.reserve(static_cast<size_t>(polys->GetNumberOfCells()) * 9);
  vtkIdType n = 0;
  const vtkIdType* ids = nullptr;
  for (polys->InitTraversal(); polys->GetNextCell(n, ids);)
  {
    if (n != 3)
    {
      continue; // vtkTriangleFilter leaves only triangles; degenerate input cells
    }
    for (vtkIdType k = 0; k < 3; ++k)
    {
      double p[3];
      points->GetPoint(ids[k], p);
      for (int c = 0; c < 3; ++c)
      {
        xyz.push_back(static_cast<float>(p[c] - centre[c]));
      }
    }
  }
}

// The assembly path's world matrix: a lone actor's own matrix (its path's
// node holds none, or a snapshot), an assembly part's concatenated one.
void PathMatrix(vtkAssemblyPath* path, vtkActor* actor, double m[16])
{
  vtkAssemblyNode* last = path->GetLastNode();
  vtkMatrix4x4* matrix =
    (path->GetNumberOfItems() > 1 && last->GetMatrix()) ? last->GetMatrix() : actor->GetMatrix();
  std::copy(matrix->GetData(), matrix->GetData() + 16, m);
}

// a * b for row-major 4x4 matrices.
void Multiply(const double a[16], const double b[16], double out[16])
{
  double r[16];
  for (int i = 0; i < 4; ++i)
  {
    for (int j = 0; j < 4; ++j)
    {
      double s = 0;
      for (int k = 0; k < 4; ++k)
      {
        s += a[4 * i + k] * b[4 * k + j];
      }
      r[4 * i + j] = s;
    }
  }
  std::copy(r, r + 16, out);
}
}

//------------------------------------------------------------------------------
struct vtkMRGIVoxelGeometry::vtkInternals
{
  GLuint VertexArray = 0;
  std::map<vtkPolyData*, Geometry> Geometries;
  // What the last Collect() found (pointers into Geometries).
  std::vector<DrawItem> Items;
  int Skipped = 0;
};

//------------------------------------------------------------------------------
vtkMRGIVoxelGeometry::vtkMRGIVoxelGeometry()
  : Internals(new vtkInternals)
{
}

//------------------------------------------------------------------------------
vtkMRGIVoxelGeometry::~vtkMRGIVoxelGeometry()
{
  this->Release(false);
}

//------------------------------------------------------------------------------
void vtkMRGIVoxelGeometry::Release(bool haveContext)
{
  vtkInternals& in = *this->Internals;
  in.Items.clear();
  for (auto& entry : in.Geometries)
  {
    if (haveContext && entry.second.Buffer)
    {
      glDeleteBuffers(1, &entry.second.Buffer);
    }
  }
  in.Geometries.clear();
  if (haveContext && in.VertexArray)
  {
    glDeleteVertexArrays(1, &in.VertexArray);
  }
  in.VertexArray = 0;
}

//------------------------------------------------------------------------------
bool vtkMRGIVoxelGeometry::HoldsResources() const
{
  return this->Internals->VertexArray || !this->Internals->Geometries.empty();
}

//------------------------------------------------------------------------------
int vtkMRGIVoxelGeometry::GetNumberOfDrawnProps() const
{
  return static_cast<int>(this->Internals->Items.size());
}

//------------------------------------------------------------------------------
int vtkMRGIVoxelGeometry::GetNumberOfSkippedProps() const
{
  return this->Internals->Skipped;
}

//------------------------------------------------------------------------------
size_t vtkMRGIVoxelGeometry::GetNumberOfCachedGeometries() const
{
  return this->Internals->Geometries.size();
}

namespace
{
// The polydata `mapper` draws: its vtkPolyData input, or the vtkPolyData
// leaves of a composite input of a vtkCompositePolyDataMapper2 that its
// display attributes leave visible and opaque. False when the input is
// neither (nothing of it is drawn).
bool PolyDataLeaves(vtkPolyDataMapper* mapper, std::vector<vtkPolyData*>& leaves)
{
  vtkDataObject* input = mapper->GetInputDataObject(0, 0);
  if (auto* data = vtkPolyData::SafeDownCast(input))
  {
    leaves.push_back(data);
    return true;
  }
  auto* composite = vtkCompositeDataSet::SafeDownCast(input);
  auto* compositeMapper = vtkCompositePolyDataMapper2::SafeDownCast(mapper);
  if (!composite || !compositeMapper)
  {
    return false;
  }
  vtkCompositeDataDisplayAttributes* attributes =
    compositeMapper->GetCompositeDataDisplayAttributes();
  vtkSmartPointer<vtkCompositeDataIterator> it;
  it.TakeReference(composite->NewIterator());
  for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem())
  {
    auto* data = vtkPolyData::SafeDownCast(it->GetCurrentDataObject());
    if (!data)
    {
      continue;
    }
    if (attributes && attributes->HasBlockVisibility(data) && !attributes->GetBlockVisibility(data))
    {
      continue;
    }
    if (attributes && attributes->HasBlockOpacity(data) && attributes->GetBlockOpacity(data) < 1.0)
    {
      continue; // translucent: as translucent actors (Collect())
    }
    leaves.push_back(data);
  }
  return true;
}
}

//------------------------------------------------------------------------------
void vtkMRGIVoxelGeometry::Collect(vtkRenderer* ren)
{
  vtkInternals& in = *this->Internals;
  for (auto& entry : in.Geometries)
  {
    entry.second.Seen = false;
  }
  std::vector<DrawItem>& items = in.Items;
  items.clear();
  int skipped = 0;
  std::vector<float> xyz;
  vtkPropCollection* props = ren->GetViewProps();
  vtkCollectionSimpleIterator pit;
  props->InitTraversal(pit);
  while (vtkProp* prop = props->GetNextProp(pit))
  {
    if (!prop->GetVisibility())
    {
      continue;
    }
    prop->InitPathTraversal();
    while (vtkAssemblyPath* path = prop->GetNextPath())
    {
      vtkActor* actor = vtkActor::SafeDownCast(path->GetLastNode()->GetViewProp());
      if (!actor)
      {
        ++skipped; // volumes, 2D props, ...
        continue;
      }
      if (!actor->GetVisibility())
      {
        continue;
      }
      vtkPolyDataMapper* mapper = vtkPolyDataMapper::SafeDownCast(actor->GetMapper());
      // Translucent actors do not block the light in MRGI's opaque passes:
      // left out so that visibility agrees with what is shaded.
      if (!mapper || !actor->HasOpaqueGeometry())
      {
        ++skipped;
        continue;
      }
      if (mapper->GetNumberOfInputConnections(0) > 0)
      {
        mapper->Update();
      }
      // Polydata, or the polydata leaves of a composite data set drawn by
      // vtkCompositePolyDataMapper2 (what ParaView delivers to every
      // geometry representation), minus the blocks it hides or draws
      // translucent.
      std::vector<vtkPolyData*> leaves;
      if (!PolyDataLeaves(mapper, leaves))
      {
        ++skipped; // other non-polydata inputs
        continue;
      }
      double objectToWorld[16];
      PathMatrix(path, actor, objectToWorld);
      for (vtkPolyData* data : leaves)
      {
        Geometry& geom = in.Geometries[data];
        const vtkMTimeType dataTime = data->GetMTime();
        if (geom.Buffer == 0 || geom.DataTime != dataTime)
        {
          Triangulate(data, xyz, geom.Centre);
          if (geom.Buffer == 0)
          {
            glGenBuffers(1, &geom.Buffer);
          }
          glBindBuffer(GL_ARRAY_BUFFER, geom.Buffer);
          glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(xyz.size() * sizeof(float)),
            xyz.empty() ? nullptr : xyz.data(), GL_STATIC_DRAW);
          glBindBuffer(GL_ARRAY_BUFFER, 0);
          geom.Vertices = static_cast<GLsizei>(xyz.size() / 3);
          geom.DataTime = dataTime;
        }
        geom.Seen = true;
        if (geom.Vertices == 0)
        {
          continue;
        }
        DrawItem item;
        item.Geom = &geom;
        std::copy(objectToWorld, objectToWorld + 16, item.ObjectToWorld);
        items.push_back(item);
      }
    }
  }
  in.Skipped = skipped;
  // Data no longer in the scene: free its buffers.
  for (auto it = in.Geometries.begin(); it != in.Geometries.end();)
  {
    if (!it->second.Seen)
    {
      if (it->second.Buffer)
      {
        glDeleteBuffers(1, &it->second.Buffer);
      }
      it = in.Geometries.erase(it);
    }
    else
    {
      ++it;
    }
  }
  if (!in.VertexArray)
  {
    glGenVertexArrays(1, &in.VertexArray);
  }
}

//------------------------------------------------------------------------------
vtkIdType vtkMRGIVoxelGeometry::Draw(vtkShaderProgram* program, const double worldToView[16])
{
  vtkInternals& in = *this->Internals;
  const GLint vertexLocation = glGetAttribLocation(program->GetHandle(), "vertexMC");
  glBindVertexArray(in.VertexArray);
  vtkIdType triangles = 0;
  for (const DrawItem& item : in.Items)
  {
    // model-view = view x object->world x translate(centre), in double.
    double shift[16] = { 1, 0, 0, item.Geom->Centre[0], 0, 1, 0, item.Geom->Centre[1], 0, 0, 1,
      item.Geom->Centre[2], 0, 0, 0, 1 };
    double mv[16];
    Multiply(item.ObjectToWorld, shift, mv);
    Multiply(worldToView, mv, mv);
    float mvColumns[16];
    for (int r = 0; r < 4; ++r)
    {
      for (int c = 0; c < 4; ++c)
      {
        mvColumns[4 * c + r] = static_cast<float>(mv[4 * r + c]);
      }
    }
    program->SetUniformMatrix4x4("mrgiModelView", mvColumns);
    glBindBuffer(GL_ARRAY_BUFFER, item.Geom->Buffer);
    if (vertexLocation >= 0)
    {
      glEnableVertexAttribArray(static_cast<GLuint>(vertexLocation));
      glVertexAttribPointer(static_cast<GLuint>(vertexLocation), 3, GL_FLOAT, GL_FALSE, 0, nullptr);
    }
    glDrawArrays(GL_TRIANGLES, 0, item.Geom->Vertices);
    triangles += item.Geom->Vertices / 3;
  }
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  glBindVertexArray(0);
  return triangles;
}
