#include "vtkMRGIPointCloudNormals.h"

#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include "mrgi_grid_radii.h"
#include "mrgi_point_normals.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <exception>
#include <vector>

// The factory's override (MRGI::RenderingPCL) when it is registered.
vtkObjectFactoryNewMacro(vtkMRGIPointCloudNormals);

namespace
{
/** Component i of a field-data array read as one flat tuple list. */
double Flat(vtkDataArray* array, int i)
{
  const int c = array->GetNumberOfComponents();
  return array->GetComponent(i / c, i % c);
}

// The estimators leave radius 0 where a finite point has no spacing to its
// neighbours (a lone point, duplicates): such a point would draw nothing.
// It takes the median of the positive radii, or, when none is positive,
// 1/100 of the finite points' diagonal (1 when that is 0: a single point).
// Non-finite points keep 0. Whichever estimator ran (core or PCL).
void FillMissingRadii(const float* xyz, vtkIdType n, float* radii)
{
  std::vector<float> positive;
  double lo[3] = { HUGE_VAL, HUGE_VAL, HUGE_VAL }, hi[3] = { -HUGE_VAL, -HUGE_VAL, -HUGE_VAL };
  vtkIdType missing = 0;
  for (vtkIdType i = 0; i < n; ++i)
  {
    const float* p = xyz + 3 * i;
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
    {
      continue;
    }
    for (int a = 0; a < 3; ++a)
    {
      lo[a] = std::min(lo[a], static_cast<double>(p[a]));
      hi[a] = std::max(hi[a], static_cast<double>(p[a]));
    }
    if (radii[i] > 0.0f && std::isfinite(radii[i]))
    {
      positive.push_back(radii[i]);
    }
    else
    {
      ++missing;
    }
  }
  if (missing == 0)
  {
    return;
  }
  float fallback = 1.0f;
  if (!positive.empty())
  {
    auto middle = positive.begin() + static_cast<std::ptrdiff_t>(positive.size() / 2);
    std::nth_element(positive.begin(), middle, positive.end());
    fallback = *middle;
  }
  else
  {
    const double diagonal = std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) +
      (hi[1] - lo[1]) * (hi[1] - lo[1]) + (hi[2] - lo[2]) * (hi[2] - lo[2]));
    if (diagonal > 0.0 && std::isfinite(diagonal))
    {
      fallback = static_cast<float>(diagonal / 100.0);
    }
  }
  for (vtkIdType i = 0; i < n; ++i)
  {
    const float* p = xyz + 3 * i;
    if (std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]) &&
      !(radii[i] > 0.0f && std::isfinite(radii[i])))
    {
      radii[i] = fallback;
    }
  }
}
}

bool vtkMRGIPointCloudNormals::SensorPoseIsMeaningful(vtkPolyData* input)
{
  return SensorPoseIsMeaningful(input ? input->GetFieldData() : nullptr);
}

//------------------------------------------------------------------------------
bool vtkMRGIPointCloudNormals::SensorPoseIsMeaningful(vtkFieldData* fd)
{
  vtkDataArray* origin = fd ? fd->GetArray("SensorOrigin") : nullptr;
  if (!origin || origin->GetNumberOfTuples() * origin->GetNumberOfComponents() < 3)
  {
    return false;
  }
  // A depth-camera frame is always in its sensor's coordinates.
  if (fd->GetArray("OrganizedDimensions"))
  {
    return true;
  }
  // PCL writes VIEWPOINT 0 0 0 1 0 0 0 into every file, sensor or not: only
  // another pose says where a sensor was.
  for (int a = 0; a < 3; ++a)
  {
    if (Flat(origin, a) != 0.0)
    {
      return true;
    }
  }
  vtkDataArray* orientation = fd->GetArray("SensorOrientation");
  if (orientation && orientation->GetNumberOfTuples() * orientation->GetNumberOfComponents() >= 4)
  {
    const double identity[4] = { 1.0, 0.0, 0.0, 0.0 };
    for (int a = 0; a < 4; ++a)
    {
      if (Flat(orientation, a) != identity[a])
      {
        return true;
      }
    }
  }
  return false;
}

vtkMRGIPointCloudNormals::vtkMRGIPointCloudNormals() = default;
vtkMRGIPointCloudNormals::~vtkMRGIPointCloudNormals() = default;

int vtkMRGIPointCloudNormals::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  if (!input || !output)
  {
    vtkErrorMacro(<< "needs a vtkPolyData input");
    return 0;
  }
  this->NumberOfDegeneratePoints = 0;
  this->NumberOfNonFinitePoints = 0;
  this->NumberOfGridRaisedPoints = 0;
  output->ShallowCopy(input);
  if (!std::isfinite(this->RadiusScale) || !(this->RadiusScale > 0.0))
  {
    vtkErrorMacro(<< "RadiusScale = " << this->RadiusScale << " must be finite and > 0");
    output->Initialize();
    return 0;
  }
  const vtkIdType n = input->GetNumberOfPoints();
  if (n == 0)
  {
    return 1;
  }
  if (n > static_cast<vtkIdType>(MRGI_NORMALS_MAX_POINTS))
  {
    vtkErrorMacro(<< n << " points: more than the " << MRGI_NORMALS_MAX_POINTS
                  << " this filter handles");
    output->Initialize();
    return 0;
  }

  // Positions as float xyz: the points' own array when it already is one.
  std::vector<float> copied;
  const float* xyz = nullptr;
  vtkFloatArray* floats = vtkFloatArray::SafeDownCast(input->GetPoints()->GetData());
  if (floats && floats->GetNumberOfComponents() == 3)
  {
    xyz = floats->GetPointer(0);
  }
  else
  {
    copied.resize(3 * static_cast<size_t>(n));
    for (vtkIdType i = 0; i < n; ++i)
    {
      double p[3];
      input->GetPoint(i, p);
      for (int a = 0; a < 3; ++a)
      {
        copied[3 * i + a] = static_cast<float>(p[a]);
      }
    }
    xyz = copied.data();
  }

  // Orientation: viewpoint, sensor origin, up, outward (class documentation).
  int orientation = ORIENT_OUTWARD;
  double reference[3] = { 0.0, 0.0, 0.0 };
  vtkDataArray* sensor = input->GetFieldData()->GetArray("SensorOrigin");
  if (this->UseViewPoint)
  {
    orientation = ORIENT_VIEWPOINT;
    for (int a = 0; a < 3; ++a)
    {
      reference[a] = this->ViewPoint[a];
    }
  }
  else if (SensorPoseIsMeaningful(input))
  {
    orientation = ORIENT_VIEWPOINT;
    for (int a = 0; a < 3; ++a)
    {
      reference[a] = Flat(sensor, a);
    }
  }
  else if (this->Up[0] != 0.0 || this->Up[1] != 0.0 || this->Up[2] != 0.0)
  {
    orientation = ORIENT_UP;
    for (int a = 0; a < 3; ++a)
    {
      reference[a] = this->Up[a];
    }
  }
  for (int a = 0; a < 3; ++a)
  {
    if (!std::isfinite(reference[a]))
    {
      vtkErrorMacro(<< (orientation == ORIENT_UP ? "Up" : "the viewpoint")
                    << " is not finite: cannot orient the normals");
      output->Initialize();
      return 0;
    }
  }
  this->LastOrientation = orientation;

  const bool estimateNormals = this->ComputeNormals || !input->GetPointData()->GetNormals();
  vtkNew<vtkFloatArray> normals;
  if (estimateNormals)
  {
    normals->SetName("Normals");
    normals->SetNumberOfComponents(3);
    normals->SetNumberOfTuples(n);
  }
  vtkNew<vtkFloatArray> radii;
  radii->SetName("Radius");
  radii->SetNumberOfTuples(n);
  bool estimated = false;
  try
  {
    estimated = this->Estimate(input, xyz, n, orientation, reference,
      estimateNormals ? normals->GetPointer(0) : nullptr, radii->GetPointer(0));
  }
  catch (const std::exception& e)
  {
    // PCL (the override) reports out-of-memory and its own failures so.
    vtkErrorMacro(<< "estimating normals and radii of " << n << " points failed: " << e.what());
  }
  if (!estimated ||
    (this->GridRadii && !this->RaiseRadiiOnGrid(input, xyz, n, radii->GetPointer(0))))
  {
    output->Initialize();
    return 0;
  }
  FillMissingRadii(xyz, n, radii->GetPointer(0));
  if (estimateNormals)
  {
    output->GetPointData()->SetNormals(normals);
  }
  output->GetPointData()->AddArray(radii);
  return 1;
}

bool vtkMRGIPointCloudNormals::Estimate(vtkPolyData*, const float* xyz, vtkIdType n,
  int orientation, const double reference[3], float* normals, float* radii)
{
  mrgi_point_normals_options options;
  mrgi_point_normals_default_options(&options);
  options.k = this->NumberOfNeighbors;
  options.radius_scale = this->RadiusScale;
  options.orientation = orientation == ORIENT_VIEWPOINT ? MRGI_ORIENT_VIEWPOINT
    : orientation == ORIENT_UP                          ? MRGI_ORIENT_UP
                                                        : MRGI_ORIENT_OUTWARD;
  for (int a = 0; a < 3; ++a)
  {
    options.viewpoint[a] = reference[a];
    options.up[a] = orientation == ORIENT_UP ? reference[a] : (a == 2 ? 1.0 : 0.0);
  }
  mrgi_point_normals_stats stats;
  mrgi_error err;
  if (mrgi_point_normals_compute(xyz, n, &options, normals, radii, nullptr, &stats, &err) !=
    MRGI_OK)
  {
    vtkErrorMacro(<< err.message);
    return false;
  }
  this->NumberOfDegeneratePoints = stats.degenerate;
  this->NumberOfNonFinitePoints = stats.non_finite;
  return true;
}

//------------------------------------------------------------------------------
// A depth camera samples a surface seen at a grazing angle in cells much
// longer than wide; the kNN radius (the spacing of evenly sampled surfaces)
// leaves gaps along them. On the sensor's grid each surfel is made to cover
// its own cell (mrgi_grid_radii.h). Unorganized clouds are left as they are.
bool vtkMRGIPointCloudNormals::RaiseRadiiOnGrid(
  vtkPolyData* input, const float* xyz, vtkIdType n, float* radii)
{
  this->NumberOfGridRaisedPoints = 0;
  vtkDataArray* dims = input->GetFieldData()->GetArray("OrganizedDimensions");
  vtkDataArray* pixels = input->GetPointData()->GetArray("PixelIndex");
  if (!dims || dims->GetNumberOfTuples() * dims->GetNumberOfComponents() != 2 || !pixels ||
    pixels->GetNumberOfTuples() != n || pixels->GetNumberOfComponents() != 1)
  {
    return true;
  }
  const double w = Flat(dims, 0), h = Flat(dims, 1);
  if (!(w >= 1.0 && h >= 1.0 && w * h <= static_cast<double>(MRGI_GRID_RADII_MAX_PIXELS)))
  {
    vtkErrorMacro(<< "OrganizedDimensions " << w << " x " << h
                  << " is not a grid this filter handles (each side >= 1, at most "
                  << MRGI_GRID_RADII_MAX_PIXELS << " pixels)");
    return false;
  }
  std::vector<int64_t> where(static_cast<size_t>(n));
  for (vtkIdType i = 0; i < n; ++i)
  {
    const double q = pixels->GetComponent(i, 0);
    // Out-of-range indices are left off the grid by the core.
    where[static_cast<size_t>(i)] =
      std::isfinite(q) && q >= 0.0 && q < w * h ? static_cast<int64_t>(q) : -1;
  }
  double origin[3] = { 0.0, 0.0, 0.0 };
  vtkDataArray* sensor = input->GetFieldData()->GetArray("SensorOrigin");
  if (sensor && sensor->GetNumberOfTuples() * sensor->GetNumberOfComponents() >= 3)
  {
    for (int a = 0; a < 3; ++a)
    {
      origin[a] = Flat(sensor, a);
    }
  }
  mrgi_grid_radii_stats stats;
  mrgi_error err;
  if (mrgi_grid_radii_apply(xyz, where.data(), n, static_cast<int64_t>(w), static_cast<int64_t>(h),
        origin, MRGI_GRID_RADII_DEFAULT_RANGE_STEP, this->RadiusScale, radii, &stats,
        &err) != MRGI_OK)
  {
    vtkErrorMacro(<< "radii on the grid of the organized cloud: " << err.message);
    return false;
  }
  this->NumberOfGridRaisedPoints = stats.raised;
  return true;
}

//------------------------------------------------------------------------------
void vtkMRGIPointCloudNormals::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "GridRadii: " << (this->GridRadii ? "On" : "Off") << "\n";
  os << indent << "NumberOfGridRaisedPoints: " << this->NumberOfGridRaisedPoints << "\n";
  os << indent << "NumberOfNeighbors: " << this->NumberOfNeighbors << "\n";
  os << indent << "RadiusScale: " << this->RadiusScale << "\n";
  os << indent << "ViewPoint: (" << this->ViewPoint[0] << ", " << this->ViewPoint[1] << ", "
     << this->ViewPoint[2] << ")\n";
  os << indent << "UseViewPoint: " << (this->UseViewPoint ? "On" : "Off") << "\n";
  os << indent << "Up: (" << this->Up[0] << ", " << this->Up[1] << ", " << this->Up[2] << ")\n";
  os << indent << "ComputeNormals: " << (this->ComputeNormals ? "On" : "Off") << "\n";
  os << indent << "LastOrientation: " << this->LastOrientation << "\n";
  os << indent << "NumberOfDegeneratePoints: " << this->NumberOfDegeneratePoints << "\n";
  os << indent << "NumberOfNonFinitePoints: " << this->NumberOfNonFinitePoints << "\n";
}
