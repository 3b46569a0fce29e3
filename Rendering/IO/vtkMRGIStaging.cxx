#include "vtkMRGIStaging.h"

#include "vtkMRGIAreaLight.h"
#include "vtkMRGIPointCloudNormals.h"

#include "vtkActor.h"
#include "vtkActorCollection.h"
#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkCompositeDataIterator.h"
#include "vtkCompositeDataSet.h"
#include "vtkContourFilter.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkFlyingEdges3D.h"
#include "vtkGenericCell.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMapper.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"

#include "mrgi_error.h"
#include "mrgi_framing.h"
#include "mrgi_iso_value.h"
#include "mrgi_up_axis.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <utility>
#include <vector>

vtkStandardNewMacro(vtkMRGIStaging);

namespace
{
// Points the framing looks at: enough for the silhouette of any file, few
// enough that the bisection stays in milliseconds.
constexpr vtkIdType MaxFramingPoints = 65536;

// The key light's placement (class documentation): above and in front,
// to the camera's left, a few bounding radii away, its cone covering the
// data and the ground around it.
constexpr double KeyElevationDeg = 55.0;
constexpr double KeyAzimuthDeg = 35.0;
constexpr double KeyDistanceRadii = 4.0;
constexpr double KeyCoverRadii = 3.5;
// cos^exponent fall-off inside the cone: the edge of the lit disc on the
// ground is soft rather than a hard circle.
constexpr double KeySpotExponent = 10.0;

// The ground: albedo, and its size around the data in horizontal sizes.
constexpr double GroundAlbedo = 0.7;
constexpr double GroundMinSizes = 3.0;
constexpr double GroundMaxSizes = 20.0;
// With an area key light, whose voxel shadows slice the camera's depth
// range into 128: a ground reaching far behind the data stretches that
// range and the data shadows itself in speckles. It ends closer (where
// the light's 1/d^2 has faded it).
constexpr double GroundMaxSizesArea = 6.0;
constexpr double GroundGap = 1e-3;

// One polygonal piece of an actor's data, with the actor's matrix.
struct Piece
{
  vtkPolyData* Data;
  vtkMatrix4x4* Matrix; // nullptr: identity
  vtkFieldData* Fields[2];
};

void ToWorld(const Piece& piece, const double in[3], double out[3])
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

bool Finite(const double p[3])
{
  return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
}

// The data field cues of the class documentation; -1 when there is none.
// A sensor pose (PCD) also gives the direction the sensor looked in
// (`sensorForward`, set when `hasForward` becomes true): a depth frame is a
// surface seen from there, and only from there does it look whole.
int UpFromFields(
  vtkFieldData* fields, std::string& reason, double sensorForward[3], bool& hasForward)
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
      return vtkMRGIStaging::UpPositiveZ;
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

bool Drawable(const Piece& piece)
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

// The "front" the camera looks from, for an up axis (class documentation).
void FrontOf(int up, double front[3])
{
  front[0] = front[1] = front[2] = 0;
  switch (up)
  {
    case vtkMRGIStaging::UpPositiveZ:
      front[1] = -1;
      break;
    case vtkMRGIStaging::UpNegativeZ:
      front[1] = 1;
      break;
    default:
      front[2] = 1;
      break;
  }
}
}

//------------------------------------------------------------------------------
vtkMRGIStaging::vtkMRGIStaging() = default;

//------------------------------------------------------------------------------
// What Stage() added stays in the renderer, which holds it, as any actor or
// light added to a renderer does: a staging object (or the scene builder
// that holds one) going out of scope before the first render must not
// silently unstage the scene.
vtkMRGIStaging::~vtkMRGIStaging() = default;

//------------------------------------------------------------------------------
bool vtkMRGIStaging::Fail(const std::string& why)
{
  this->LastErrorMessage = why;
  return false;
}

//------------------------------------------------------------------------------
vtkActor* vtkMRGIStaging::GetGroundActor()
{
  return this->GroundActor;
}

//------------------------------------------------------------------------------
vtkLight* vtkMRGIStaging::GetKeyLightObject()
{
  return this->KeyLightObject;
}

//------------------------------------------------------------------------------
vtkMRGIAreaLight* vtkMRGIStaging::GetAreaLight()
{
  return this->AreaLight;
}

//------------------------------------------------------------------------------
const char* vtkMRGIStaging::GetUpAxisName(int up)
{
  if (up == UpAuto)
  {
    return "auto";
  }
  if (up < UpPositiveX || up > UpNegativeZ)
  {
    return nullptr;
  }
  return mrgi_axis_name(static_cast<mrgi_axis>(up));
}

//------------------------------------------------------------------------------
void vtkMRGIStaging::RemoveStaged()
{
  if (vtkRenderer* renderer = this->StagedRenderer)
  {
    if (this->GroundActor)
    {
      renderer->RemoveActor(this->GroundActor);
    }
    if (this->KeyLightObject)
    {
      renderer->RemoveLight(this->KeyLightObject);
    }
    if (this->DarkLight)
    {
      renderer->RemoveLight(this->DarkLight);
    }
  }
  this->StagedRenderer = nullptr;
  this->GroundActor = nullptr;
  this->KeyLightObject = nullptr;
  this->DarkLight = nullptr;
  this->AreaLight = nullptr;
}

//------------------------------------------------------------------------------
bool vtkMRGIStaging::Stage(vtkRenderer* renderer)
{
  this->LastErrorMessage.clear();
  if (!renderer)
  {
    return this->Fail("Stage needs a renderer");
  }

  // The data: every visible actor's polygonal pieces, except what an
  // earlier Stage() added.
  std::vector<Piece> pieces;
  std::vector<vtkSmartPointer<vtkCompositeDataIterator>> iterators;
  vtkActorCollection* actors = renderer->GetActors();
  vtkCollectionSimpleIterator ait;
  actors->InitTraversal(ait);
  while (vtkActor* actor = actors->GetNextActor(ait))
  {
    if (actor == this->GroundActor || !actor->GetVisibility() || !actor->GetMapper())
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

  // Bounds of the finite points, and an even sample of them for the framing.
  vtkIdType total = 0;
  for (const Piece& piece : pieces)
  {
    total += piece.Data->GetNumberOfPoints();
  }
  const vtkIdType stride =
    std::max<vtkIdType>(1, (total + MaxFramingPoints - 1) / MaxFramingPoints);
  std::vector<double> samples;
  double bounds[6] = { VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX, VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX,
    VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX };
  vtkIdType running = 0;
  for (const Piece& piece : pieces)
  {
    vtkPoints* points = piece.Data->GetPoints();
    const vtkIdType n = points ? points->GetNumberOfPoints() : 0;
    for (vtkIdType i = 0; i < n; ++i, ++running)
    {
      double p[3];
      points->GetPoint(i, p);
      ToWorld(piece, p, p);
      if (!Finite(p))
      {
        continue; // organized clouds pad with NaN points
      }
      for (int k = 0; k < 3; ++k)
      {
        bounds[2 * k] = std::min(bounds[2 * k], p[k]);
        bounds[2 * k + 1] = std::max(bounds[2 * k + 1], p[k]);
      }
      if (running % stride == 0)
      {
        samples.insert(samples.end(), p, p + 3);
      }
    }
  }
  if (samples.empty())
  {
    return this->Fail("nothing to stage: the renderer has no visible actor with finite points");
  }
  if (!Finite(bounds) || !Finite(bounds + 3))
  {
    return this->Fail("nothing to stage: the data's bounds are not finite");
  }
  if (!std::any_of(pieces.begin(), pieces.end(), Drawable))
  {
    // The ground alone would make the picture look fine: say it instead.
    return this->Fail("nothing to draw: its polygons have no area and it has no vertices or "
                      "lines of any length (every point near " +
      std::to_string(bounds[0]) + ", " + std::to_string(bounds[2]) + ", " +
      std::to_string(bounds[4]) + ")");
  }

  // The up axis.
  double sensorForward[3] = { 0, 0, 1 };
  bool hasSensorForward = false;
  int up = this->Up;
  std::string reason = "set";
  if (up == UpAuto)
  {
    for (const Piece& piece : pieces)
    {
      for (vtkFieldData* fields : piece.Fields)
      {
        if (up == UpAuto)
        {
          const int found = UpFromFields(fields, reason, sensorForward, hasSensorForward);
          up = found >= 0 ? found : up;
        }
      }
    }
  }
  if (up == UpAuto)
  {
    mrgi_up_evidence evidence;
    mrgi_error err;
    if (mrgi_up_evidence_init(&evidence, bounds, &err) != MRGI_OK)
    {
      return this->Fail(std::string("cannot stage: ") + err.message);
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
      return this->Fail(std::string("cannot stage: ") + err.message);
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
        return this->Fail(std::string("cannot stage: ") + err.message);
      }
    }
    up = static_cast<int>(decision.up);
    reason = mrgi_up_reason_name(decision.reason);
  }
  double upv[3], front[3], left[3];
  mrgi_axis_vector(static_cast<mrgi_axis>(up), upv);
  FrontOf(up, front);
  if (hasSensorForward)
  {
    // Seen from the sensor's side (horizontally): a depth frame seen from
    // behind shows the backs of its surfaces, edge-on.
    const double along = vtkMath::Dot(sensorForward, upv);
    double towardsSensor[3];
    for (int k = 0; k < 3; ++k)
    {
      towardsSensor[k] = -(sensorForward[k] - along * upv[k]);
    }
    if (vtkMath::Normalize(towardsSensor) > 1e-3)
    {
      std::copy(towardsSensor, towardsSensor + 3, front);
    }
  }
  vtkMath::Cross(front, upv, left);

  // The camera.
  vtkCamera* camera = renderer->GetActiveCamera();
  double aspect = 1.0;
  if (vtkRenderWindow* window = renderer->GetRenderWindow())
  {
    const int* size = window->GetSize();
    const double* vp = renderer->GetViewport();
    const double w = size[0] * (vp[2] - vp[0]);
    const double h = size[1] * (vp[3] - vp[1]);
    if (w > 0 && h > 0)
    {
      aspect = w / h;
    }
  }
  const double elevation = vtkMath::RadiansFromDegrees(this->CameraElevation);
  double direction[3];
  for (int k = 0; k < 3; ++k)
  {
    direction[k] = -(std::cos(elevation) * front[k] + std::sin(elevation) * upv[k]);
  }
  const double viewAngle = camera->GetViewAngle();
  mrgi_framing framing;
  {
    mrgi_error err;
    if (mrgi_frame_points(samples.data(), static_cast<int64_t>(samples.size() / 3), direction, upv,
          viewAngle, aspect, this->FillFraction, &framing, &err) != MRGI_OK)
    {
      return this->Fail(std::string("cannot frame the data: ") + err.message);
    }
  }

  // Everything is known: from here on the renderer changes.
  this->RemoveStaged();
  this->StagedRenderer = renderer;
  this->DetectedUp = up;
  this->UpReason = reason;

  camera->SetFocalPoint(framing.focal);
  camera->SetPosition(framing.position);
  camera->SetViewUp(framing.view_up);
  const double distance =
    std::sqrt(vtkMath::Distance2BetweenPoints(framing.focal, framing.position));
  const double tanHalf = std::tan(vtkMath::RadiansFromDegrees(0.5 * viewAngle));
  camera->SetParallelScale(distance * tanHalf);

  double center[3], size[3];
  for (int k = 0; k < 3; ++k)
  {
    center[k] = 0.5 * (bounds[2 * k] + bounds[2 * k + 1]);
    size[k] = bounds[2 * k + 1] - bounds[2 * k];
  }
  double radius = 0.5 * vtkMath::Norm(size);
  if (!(radius > 0))
  {
    radius = 1.0;
  }

  if (this->Ground)
  {
    const int k = up / 2;
    const int a1 = (k + 1) % 3;
    const int a2 = (k + 2) % 3;
    const double sign = (up % 2) ? -1.0 : 1.0;
    double largest = std::max(size[0], std::max(size[1], size[2]));
    largest = largest > 0 ? largest : 1.0;
    // Just under the data along up.
    const double level =
      (sign > 0 ? bounds[2 * k] : bounds[2 * k + 1]) - sign * GroundGap * largest;
    double horizontal = std::max(size[a1], size[a2]);
    horizontal = horizontal > 0 ? horizontal : largest;
    // What the camera sees of the plane: where the corner rays of the view
    // hit it (a ray above the horizon reaches the largest size).
    double lo[2] = { center[a1] - 0.5 * GroundMinSizes * horizontal,
      center[a2] - 0.5 * GroundMinSizes * horizontal };
    double hi[2] = { center[a1] + 0.5 * GroundMinSizes * horizontal,
      center[a2] + 0.5 * GroundMinSizes * horizontal };
    double d[3], right[3], vup[3];
    for (int c = 0; c < 3; ++c)
    {
      d[c] = framing.focal[c] - framing.position[c];
    }
    vtkMath::Normalize(d);
    vtkMath::Cross(d, framing.view_up, right);
    vtkMath::Normalize(right);
    vtkMath::Cross(right, d, vup);
    const double reach =
      0.5 * (this->KeyLight == KeyLightArea ? GroundMaxSizesArea : GroundMaxSizes) * horizontal;
    for (int corner = 0; corner < 4; ++corner)
    {
      const double sx = (corner & 1) ? 1.0 : -1.0;
      const double sy = (corner & 2) ? 1.0 : -1.0;
      double ray[3];
      for (int c = 0; c < 3; ++c)
      {
        ray[c] = d[c] + sx * tanHalf * aspect * right[c] + sy * tanHalf * vup[c];
      }
      const double down = ray[k];
      const double height = framing.position[k] - level;
      double hit[3];
      if (down * sign < 0 && height * sign > 0)
      {
        const double t = height / -down;
        for (int c = 0; c < 3; ++c)
        {
          hit[c] = framing.position[c] + t * ray[c];
        }
      }
      else
      {
        // Towards the horizon: as far as the ground may reach.
        const double h1 = ray[a1], h2 = ray[a2];
        const double hn = std::sqrt(h1 * h1 + h2 * h2);
        hit[a1] = center[a1] + (hn > 0 ? reach * h1 / hn : 0);
        hit[a2] = center[a2] + (hn > 0 ? reach * h2 / hn : 0);
      }
      lo[0] = std::min(lo[0], hit[a1]);
      lo[1] = std::min(lo[1], hit[a2]);
      hi[0] = std::max(hi[0], hit[a1]);
      hi[1] = std::max(hi[1], hit[a2]);
    }
    lo[0] = std::max(lo[0], center[a1] - reach);
    lo[1] = std::max(lo[1], center[a2] - reach);
    hi[0] = std::min(hi[0], center[a1] + reach);
    hi[1] = std::min(hi[1], center[a2] + reach);

    vtkNew<vtkPoints> points;
    vtkNew<vtkFloatArray> normals;
    normals->SetName("Normals");
    normals->SetNumberOfComponents(3);
    const double uv[4][2] = { { lo[0], lo[1] }, { hi[0], lo[1] }, { hi[0], hi[1] },
      { lo[0], hi[1] } };
    for (const auto& corner : uv)
    {
      double p[3];
      p[k] = level;
      p[a1] = corner[0];
      p[a2] = corner[1];
      points->InsertNextPoint(p);
      normals->InsertNextTuple(upv);
    }
    // (a1, a2, k) is cyclic: the corners turn counter-clockwise about +k;
    // reversed for an up axis pointing to -k.
    vtkIdType quad[4] = { 0, 1, 2, 3 };
    if (sign < 0)
    {
      std::reverse(quad, quad + 4);
    }
    vtkNew<vtkCellArray> polys;
    polys->InsertNextCell(4, quad);
    vtkNew<vtkPolyData> plane;
    plane->SetPoints(points);
    plane->SetPolys(polys);
    plane->GetPointData()->SetNormals(normals);
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputData(plane);
    mapper->ScalarVisibilityOff();
    this->GroundActor = vtkSmartPointer<vtkActor>::New();
    this->GroundActor->SetMapper(mapper);
    vtkProperty* property = this->GroundActor->GetProperty();
    property->SetColor(GroundAlbedo, GroundAlbedo, GroundAlbedo);
    property->SetAmbient(0.0);
    property->SetDiffuse(1.0);
    property->SetSpecular(0.0);
    this->GroundActor->PickableOff();
    renderer->AddActor(this->GroundActor);
  }

  if (this->KeyLight != KeyLightNone)
  {
    const double el = vtkMath::RadiansFromDegrees(KeyElevationDeg);
    const double az = vtkMath::RadiansFromDegrees(KeyAzimuthDeg);
    double towards[3], position[3];
    for (int k = 0; k < 3; ++k)
    {
      towards[k] =
        std::cos(el) * (std::cos(az) * front[k] + std::sin(az) * left[k]) + std::sin(el) * upv[k];
    }
    vtkMath::Normalize(towards);
    const double lightDistance = KeyDistanceRadii * radius;
    for (int k = 0; k < 3; ++k)
    {
      position[k] = center[k] + lightDistance * towards[k];
    }
    renderer->RemoveAllLights();
    renderer->AutomaticLightCreationOff();
    if (this->KeyLight == KeyLightSpot)
    {
      this->KeyLightObject = vtkSmartPointer<vtkLight>::New();
      vtkLight* light = this->KeyLightObject;
      light->SetLightTypeToSceneLight();
      light->SetPositional(true);
      light->SetPosition(position);
      light->SetFocalPoint(center);
      light->SetConeAngle(vtkMath::DegreesFromRadians(std::atan(KeyCoverRadii / KeyDistanceRadii)));
      light->SetExponent(KeySpotExponent);
      light->SetColor(1.0, 1.0, 1.0);
      light->SetIntensity(1.0);
      renderer->AddLight(light);
    }
    else
    {
      // A square of one radius facing the data; a small Lambertian source
      // of area A at distance D gives X = L A / (pi D^2) at normal
      // incidence (mrgi_area_light.h): L = pi D^2 / A gives the spot's X = 1.
      double normal[3] = { -towards[0], -towards[1], -towards[2] };
      double edgeV[3];
      const double along = vtkMath::Dot(upv, normal);
      for (int k = 0; k < 3; ++k)
      {
        edgeV[k] = upv[k] - along * normal[k];
      }
      vtkMath::Normalize(edgeV);
      double edgeU[3];
      vtkMath::Cross(edgeV, normal, edgeU); // edgeU x edgeV = normal
      const double side = radius;
      for (int k = 0; k < 3; ++k)
      {
        edgeU[k] *= side;
        edgeV[k] *= side;
      }
      this->AreaLight = vtkSmartPointer<vtkMRGIAreaLight>::New();
      this->AreaLight->SetCenter(position);
      this->AreaLight->SetEdgeU(edgeU);
      this->AreaLight->SetEdgeV(edgeV);
      this->AreaLight->SetColor(1.0, 1.0, 1.0);
      this->AreaLight->SetIntensity(vtkMath::Pi() * lightDistance * lightDistance / (side * side));
      this->AreaLight->SetVisible(false);
      // Without any vtkLight VTK draws every surface unlit, at its full
      // colour; a light of intensity 0 keeps its lighting on, and black.
      this->DarkLight = vtkSmartPointer<vtkLight>::New();
      this->DarkLight->SetLightTypeToSceneLight();
      this->DarkLight->SetIntensity(0.0);
      renderer->AddLight(this->DarkLight);
    }
  }
  renderer->ResetCameraClippingRange();
  return true;
}

//------------------------------------------------------------------------------
bool vtkMRGIStaging::IsVolume(vtkDataObject* data)
{
  auto* ds = vtkDataSet::SafeDownCast(data);
  if (!ds || vtkPolyData::SafeDownCast(ds) || ds->GetNumberOfCells() < 1)
  {
    return false;
  }
  vtkDataArray* scalars = ds->GetPointData()->GetScalars();
  if (!scalars || scalars->GetNumberOfComponents() != 1)
  {
    return false;
  }
  if (auto* image = vtkImageData::SafeDownCast(ds))
  {
    int dims[3];
    image->GetDimensions(dims);
    return dims[0] > 1 && dims[1] > 1 && dims[2] > 1;
  }
  vtkNew<vtkGenericCell> cell;
  ds->GetCell(0, cell);
  return cell->GetCellDimension() == 3;
}

//------------------------------------------------------------------------------
bool vtkMRGIStaging::MakeIsoSurface(vtkDataSet* volume, vtkPolyData* output)
{
  this->LastErrorMessage.clear();
  if (!output || !IsVolume(volume))
  {
    return this->Fail(
      "MakeIsoSurface needs a volume (3D cells with one-component point scalars) and an output");
  }
  vtkDataArray* scalars = volume->GetPointData()->GetScalars();
  const vtkIdType n = scalars->GetNumberOfTuples();
  double lo = VTK_DOUBLE_MAX, hi = -VTK_DOUBLE_MAX;
  for (vtkIdType i = 0; i < n; ++i)
  {
    const double v = scalars->GetComponent(i, 0);
    if (std::isfinite(v))
    {
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  }
  if (!(lo <= hi))
  {
    return this->Fail("the volume's scalars hold no finite value: no iso-surface");
  }
  double iso = this->IsoValue;
  if (this->AutomaticIsoValue)
  {
    if (!(lo < hi))
    {
      return this->Fail("the volume's scalars are all " + std::to_string(lo) + ": no iso-surface");
    }
    std::vector<double> counts(MRGI_ISO_VALUE_BINS, 0.0);
    const double scale = MRGI_ISO_VALUE_BINS / (hi - lo);
    for (vtkIdType i = 0; i < n; ++i)
    {
      const double v = scalars->GetComponent(i, 0);
      if (std::isfinite(v))
      {
        const int bin = std::min(MRGI_ISO_VALUE_BINS - 1, static_cast<int>((v - lo) * scale));
        counts[static_cast<size_t>(bin)] += 1.0;
      }
    }
    mrgi_error err;
    if (mrgi_iso_value_otsu(counts.data(), MRGI_ISO_VALUE_BINS, lo, hi, &iso, nullptr, &err) !=
      MRGI_OK)
    {
      return this->Fail(std::string("no iso-value: ") + err.message);
    }
  }
  this->LastIsoValue = iso;
  vtkSmartPointer<vtkPolyData> surface;
  if (auto* image = vtkImageData::SafeDownCast(volume))
  {
    vtkNew<vtkFlyingEdges3D> contour;
    contour->SetInputData(image);
    contour->SetValue(0, iso);
    contour->ComputeNormalsOn();
    contour->ComputeScalarsOff();
    contour->Update();
    surface = contour->GetOutput();
  }
  else
  {
    vtkNew<vtkContourFilter> contour;
    contour->SetInputData(volume);
    contour->SetValue(0, iso);
    contour->ComputeNormalsOn();
    contour->ComputeScalarsOff();
    contour->Update();
    surface = vtkPolyData::SafeDownCast(contour->GetOutputDataObject(0));
  }
  if (!surface || surface->GetNumberOfPolys() == 0)
  {
    return this->Fail("the iso-surface at " + std::to_string(iso) + " is empty (scalars in [" +
      std::to_string(lo) + ", " + std::to_string(hi) + "])");
  }
  output->ShallowCopy(surface);
  return true;
}

//------------------------------------------------------------------------------
void vtkMRGIStaging::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Up: " << GetUpAxisName(this->Up) << "\n";
  os << indent << "Ground: " << (this->Ground ? "on" : "off") << "\n";
  os << indent << "KeyLight: "
     << (this->KeyLight == KeyLightSpot      ? "spot"
            : this->KeyLight == KeyLightArea ? "area"
                                             : "none")
     << "\n";
  os << indent << "FillFraction: " << this->FillFraction << "\n";
  os << indent << "CameraElevation: " << this->CameraElevation << "\n";
  os << indent << "IsoValue: " << this->IsoValue << "\n";
  os << indent << "AutomaticIsoValue: " << (this->AutomaticIsoValue ? "on" : "off") << "\n";
  os << indent << "DetectedUp: " << GetUpAxisName(this->DetectedUp) << " (" << this->UpReason
     << ")\n";
  os << indent << "LastIsoValue: " << this->LastIsoValue << "\n";
}
