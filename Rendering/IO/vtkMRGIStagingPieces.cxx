#include "vtkMRGIStagingPieces.h"

#include "vtkMRGIPointCloudNormals.h"

#include "vtkActor.h"
#include "vtkActorCollection.h"
#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkCompositeDataIterator.h"
#include "vtkCompositeDataSet.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkMapper.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"

#include "mrgi_error.h"
#include "mrgi_up_axis.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <utility>

namespace
{
using vtkMRGIStagingPieces::Finite;
using vtkMRGIStagingPieces::Piece;
using vtkMRGIStagingPieces::ToWorld;

// Adds the edges used by one polygon of `polys` only to the evidence.
// (VTK 9.1's vtkFeatureEdges throws std::bad_alloc on a 2M-triangle
// sphere: the edges are sorted here instead, 8 bytes each.)
void AddBoundaryEdges(const Piece& piece, vtkCellArray* polys, mrgi_up_evidence& evidence)
{
  vtkPoints* points = piece.Data->GetPoints();
  const vtkIdType npoints = points->GetNumberOfPoints();
  if (npoints >= (vtkIdType(1) << 32))
  {
    return; // not packable in 64 bits; the other cues decide
  }
  std::vector<uint64_t> edges;
  edges.reserve(static_cast<size_t>(polys->GetNumberOfConnectivityIds()));
  vtkSmartPointer<vtkCellArrayIterator> it;
  it.TakeReference(polys->NewIterator());
  for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell())
  {
    vtkIdType size = 0;
    const vtkIdType* ids = nullptr;
    it->GetCurrentCell(size, ids);
    for (vtkIdType v = 0; v < size; ++v)
    {
      const auto i = static_cast<uint64_t>(ids[v]);
      const auto j = static_cast<uint64_t>(ids[(v + 1) % size]);
      edges.push_back(i < j ? (i << 32) | j : (j << 32) | i);
    }
  }
  std::sort(edges.begin(), edges.end());
  for (size_t e = 0; e < edges.size();)
  {
    size_t run = e + 1;
    while (run < edges.size() && edges[run] == edges[e])
    {
      ++run;
    }
    if (run == e + 1)
    {
      double a[3], b[3];
      points->GetPoint(static_cast<vtkIdType>(edges[e] >> 32), a);
      points->GetPoint(static_cast<vtkIdType>(edges[e] & 0xFFFFFFFFu), b);
      ToWorld(piece, a, a);
      ToWorld(piece, b, b);
      mrgi_up_add_boundary_edge(&evidence, a, b);
    }
    e = run;
  }
}

// Whether any of the cells of `cells` would draw something: a vertex; a
// line or polygon spanning some length or area (strips: their consecutive
// triples). Degenerate files (every point at one place, zero spacing)
// draw nothing.
bool DrawsSomething(vtkPoints* points, vtkCellArray* cells, int kind)
{
  if (!cells || cells->GetNumberOfCells() == 0)
  {
    return false;
  }
  if (kind == 0)
  {
    return true; // vertices draw at least a pixel
  }
  const vtkIdType npoints = points->GetNumberOfPoints();
  vtkSmartPointer<vtkCellArrayIterator> it;
  it.TakeReference(cells->NewIterator());
  for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell())
  {
    vtkIdType size = 0;
    const vtkIdType* ids = nullptr;
    it->GetCurrentCell(size, ids);
    if (std::any_of(ids, ids + size, [npoints](vtkIdType id) { return id < 0 || id >= npoints; }))
    {
      continue;
    }
    for (vtkIdType v = 1; v < size; ++v)
    {
      double a[3], b[3], c[3];
      points->GetPoint(ids[kind == 2 ? v - 1 : 0], a);
      points->GetPoint(ids[v], b);
      if (kind == 1)
      {
        if (Finite(a) && Finite(b) && vtkMath::Distance2BetweenPoints(a, b) > 0)
        {
          return true;
        }
        continue;
      }
      if (v + 1 >= size)
      {
        break;
      }
      points->GetPoint(ids[v + 1], c);
      double e1[3], e2[3], n[3];
      vtkMath::Subtract(b, a, e1);
      vtkMath::Subtract(c, a, e2);
      vtkMath::Cross(e1, e2, n);
      if (Finite(n) && vtkMath::Norm(n) > 0)
      {
        return true;
      }
    }
  }
  return false;
}
}

//------------------------------------------------------------------------------
void vtkMRGIStagingPieces::ToWorld(const Piece& piece, const double in[3], double out[3])
{
  if (!piece.Matrix)
  {
    std::copy(in, in + 3, out);
    return;
  }
  const double h[4] = { in[0], in[1], in[2], 1.0 };
  double o[4];
  piece.Matrix->MultiplyPoint(h, o);
  const double w = o[3] != 0.0 ? o[3] : 1.0;
  for (int k = 0; k < 3; ++k)
  {
    out[k] = o[k] / w;
  }
}

//------------------------------------------------------------------------------
bool vtkMRGIStagingPieces::Finite(const double p[3])
{
  return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
}

//------------------------------------------------------------------------------
bool vtkMRGIStagingPieces::Drawable(const Piece& piece)
{
  vtkPoints* points = piece.Data->GetPoints();
  if (!points)
  {
    return false;
  }
  // Kinds: 0 vertices, 1 lines, 2 strips (consecutive triples), 3 polygons (fans).
  return DrawsSomething(points, piece.Data->GetVerts(), 0) ||
    DrawsSomething(points, piece.Data->GetLines(), 1) ||
    DrawsSomething(points, piece.Data->GetPolys(), 3) ||
    DrawsSomething(points, piece.Data->GetStrips(), 2);
}

//------------------------------------------------------------------------------
void vtkMRGIStagingPieces::Collect(vtkRenderer* renderer, vtkActor* skip, std::vector<Piece>& pieces)
{
  vtkActorCollection* actors = renderer->GetActors();
  vtkCollectionSimpleIterator ait;
  actors->InitTraversal(ait);
  while (vtkActor* actor = actors->GetNextActor(ait))
  {
    if (actor == skip || !actor->GetVisibility() || !actor->GetMapper())
    {
      continue;
    }
    vtkMatrix4x4* matrix = actor->GetMatrix();
    if (matrix && matrix->IsIdentity())
    {
      matrix = nullptr;
    }
    vtkDataObject* input = actor->GetMapper()->GetInputDataObject(0, 0);
    if (auto* poly = vtkPolyData::SafeDownCast(input))
    {
      pieces.push_back({ poly, matrix, { poly->GetFieldData(), nullptr } });
    }
    else if (auto* composite = vtkCompositeDataSet::SafeDownCast(input))
    {
      vtkSmartPointer<vtkCompositeDataIterator> it;
      it.TakeReference(composite->NewIterator());
      for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem())
      {
        if (auto* leaf = vtkPolyData::SafeDownCast(it->GetCurrentDataObject()))
        {
          pieces.push_back({ leaf, matrix, { leaf->GetFieldData(), composite->GetFieldData() } });
        }
      }
    }
  }
}

//------------------------------------------------------------------------------
// The data field cues of the class documentation; -1 when there is none.
// A sensor pose (PCD) also gives the direction the sensor looked in
// (`sensorForward`, set when `hasForward` becomes true): a depth frame is a
// surface seen from there, and only from there does it look whole.
int vtkMRGIStagingPieces::UpFromFields(vtkFieldData* fields, std::string& reason, double sensorForward[3], bool& hasForward)
{
  if (!fields)
  {
    return -1;
  }
  for (int a = 0; a < fields->GetNumberOfArrays(); ++a)
  {
    vtkAbstractArray* array = fields->GetAbstractArray(a);
    const char* name = array ? array->GetName() : nullptr;
    if (name && std::strncmp(name, "LAS", 3) == 0)
    {
      reason = std::string("LAS field data (") + name + ")";
      return MRGI_AXIS_POS_Z;
    }
  }
  double q[4] = { 0, 0, 0, 0 };
  bool sensor = false;
  if (vtkDataArray* viewpoint = fields->GetArray("VIEWPOINT"))
  {
    if (viewpoint->GetNumberOfValues() == 7)
    {
      for (int c = 0; c < 4; ++c)
      {
        q[c] = viewpoint->GetComponent(0, 3 + c);
        if (viewpoint->GetNumberOfComponents() == 1)
        {
          q[c] = viewpoint->GetComponent(3 + c, 0);
        }
      }
      sensor = true;
      reason = "PCD VIEWPOINT";
    }
  }
  if (!sensor)
  {
    vtkDataArray* orientation = fields->GetArray("SensorOrientation");
    // PCL writes the identity pose into every file: only a real sensor's
    // pose (vtkMRGIPointCloudNormals' rule) says which way is up.
    if (orientation && vtkMRGIPointCloudNormals::SensorPoseIsMeaningful(fields))
    {
      if (orientation->GetNumberOfValues() == 4)
      {
        for (int c = 0; c < 4; ++c)
        {
          q[c] = orientation->GetNumberOfComponents() == 1 ? orientation->GetComponent(c, 0)
                                                           : orientation->GetComponent(0, c);
        }
        sensor = true;
        reason = "PCD SensorOrientation";
      }
    }
  }
  const double norm = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  if (!sensor || !(norm > 0) || !std::isfinite(norm))
  {
    return -1;
  }
  for (double& c : q)
  {
    c /= norm;
  }
  double m[3][3];
  vtkMath::QuaternionToMatrix3x3(q, m);
  const double down[3] = { 0, -1, 0 }; // a depth camera's image y points down
  double up[3];
  vtkMath::Multiply3x3(m, down, up);
  const double ahead[3] = { 0, 0, 1 }; // and it looks along its +z
  vtkMath::Multiply3x3(m, ahead, sensorForward);
  hasForward = true;
  int k = 0;
  for (int i = 1; i < 3; ++i)
  {
    if (std::fabs(up[i]) > std::fabs(up[k]))
    {
      k = i;
    }
  }
  return 2 * k + (up[k] < 0 ? 1 : 0);
}

//------------------------------------------------------------------------------
int vtkMRGIStagingPieces::UpFromPieceFields(const std::vector<Piece>& pieces, std::string& reason,
  double sensorForward[3], bool& hasForward)
{
  int up = -1;
  for (const Piece& piece : pieces)
  {
    for (vtkFieldData* fields : piece.Fields)
    {
      if (up < 0)
      {
        const int found = UpFromFields(fields, reason, sensorForward, hasForward);
        up = found >= 0 ? found : up;
      }
    }
  }
  return up;
}

//------------------------------------------------------------------------------
bool vtkMRGIStagingPieces::UpFromGeometry(const std::vector<Piece>& pieces, const double bounds[6],
  const std::vector<double>& samples, int& up, std::string& reason, std::string& error)
{
  mrgi_up_evidence evidence;
  mrgi_error err;
  if (mrgi_up_evidence_init(&evidence, bounds, &err) != MRGI_OK)
  {
    error = std::string("cannot stage: ") + err.message;
    return false;
  }
  std::vector<std::pair<const Piece*, vtkSmartPointer<vtkCellArray>>> validPolys;
  for (const Piece& piece : pieces)
  {
    vtkCellArray* polys = piece.Data->GetPolys();
    if (!polys || polys->GetNumberOfCells() == 0)
    {
      continue;
    }
    vtkPoints* points = piece.Data->GetPoints();
    // The polygons of 3 points or more: VTK's cell links (vtkFeatureEdges)
    // fail on the empty faces a file may hold.
    auto valid = vtkSmartPointer<vtkCellArray>::New();
    vtkSmartPointer<vtkCellArrayIterator> it;
    it.TakeReference(polys->NewIterator());
    for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell())
    {
      vtkIdType size = 0;
      const vtkIdType* ids = nullptr;
      it->GetCurrentCell(size, ids);
      double a[3], b[3], c[3];
      // Faces of fewer than 3 points or with ids outside the points
      // (a data set not checked by vtkMRGISceneBuilder) are left out.
      const vtkIdType npoints = points->GetNumberOfPoints();
      if (size < 3 ||
        std::any_of(ids, ids + size, [npoints](vtkIdType id) { return id < 0 || id >= npoints; }))
      {
        continue;
      }
      valid->InsertNextCell(size, ids);
      points->GetPoint(ids[0], a);
      ToWorld(piece, a, a);
      points->GetPoint(ids[1], b);
      ToWorld(piece, b, b);
      for (vtkIdType v = 2; v < size; ++v)
      {
        points->GetPoint(ids[v], c);
        ToWorld(piece, c, c);
        mrgi_up_add_triangle(&evidence, a, b, c);
        std::copy(c, c + 3, b);
      }
    }
    validPolys.emplace_back(&piece, valid);
  }
  if (!(evidence.total_area > 0))
  {
    // A cloud: its points (the framing's sample) are the evidence.
    for (size_t i = 0; i + 2 < samples.size(); i += 3)
    {
      mrgi_up_add_point(&evidence, &samples[i]);
    }
  }
  mrgi_up_decision decision;
  if (mrgi_up_decide(&evidence, &decision, &err) != MRGI_OK)
  {
    error = std::string("cannot stage: ") + err.message;
    return false;
  }
  if (decision.reason != MRGI_UP_REASON_FLAT_BASE && evidence.total_area > 0)
  {
    // No flat base: the edges of one polygon only (a scan's holes) may
    // say where the base is.
    for (const auto& pv : validPolys)
    {
      AddBoundaryEdges(*pv.first, pv.second, evidence);
    }
    if (mrgi_up_decide(&evidence, &decision, &err) != MRGI_OK)
    {
      error = std::string("cannot stage: ") + err.message;
      return false;
    }
  }
  up = static_cast<int>(decision.up);
  reason = mrgi_up_reason_name(decision.reason);
  return true;
}
