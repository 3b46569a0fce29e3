#include "vtkMRGIStaging.h"

#include "vtkMRGIAreaLight.h"
#include "vtkMRGIStagingGround.h"
#include "vtkMRGIStagingPieces.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkContourFilter.h"
#include "vtkDataArray.h"
#include "vtkFlyingEdges3D.h"
#include "vtkGenericCell.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"

#include "mrgi_error.h"
#include "mrgi_framing.h"
#include "mrgi_iso_value.h"
#include "mrgi_up_axis.h"

#include <algorithm>
#include <cmath>
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

using vtkMRGIStagingPieces::Finite;
using vtkMRGIStagingPieces::Piece;
using vtkMRGIStagingPieces::ToWorld;

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
  vtkMRGIStagingPieces::Collect(renderer, this->GroundActor, pieces);

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
  if (!std::any_of(pieces.begin(), pieces.end(), vtkMRGIStagingPieces::Drawable))
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
    up = vtkMRGIStagingPieces::UpFromPieceFields(pieces, reason, sensorForward, hasSensorForward);
  }
  if (up == UpAuto)
  {
    std::string error;
    if (!vtkMRGIStagingPieces::UpFromGeometry(pieces, bounds, samples, up, reason, error))
    {
      return this->Fail(error);
    }
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
    this->GroundActor = vtkMRGIStagingGround::Make(
      up, upv, bounds, framing, tanHalf, aspect, this->KeyLight == KeyLightArea);
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
