// vtkMRGIPointCloudNormals with the C core (this program does not load the
// PCL module, so New() gives the base class in every build): a sampled
// sphere gets radial normals and radii near its spacing; the orientation
// follows ViewPoint, a meaningful SensorOrigin (not PCL's default pose
// unless organized), Up, else outward; input
// normals are kept unless ComputeNormals; the pipeline caches the result
// (RequestData runs again only when the input or a property changes); bad
// settings are errors with an empty output; the PCD reader's base class
// refuses to read, naming the missing module; organized clouds get radii
// that cover their grid cells (GridRadii).
#include "mrgiTestUtilities.h"

#include "vtkCallbackCommand.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIntArray.h"
#include "vtkMRGIPCDReader.h"
#include "vtkMRGIPointCloudNormals.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include <cmath>
#include <cstring>

namespace
{
const double Pi = 3.14159265358979323846;

/** A Fibonacci sphere of n points, radius r, centred at c (double points). */
vtkSmartPointer<vtkPolyData> Sphere(int n, double r, const double c[3])
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(n);
  const double golden = Pi * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < n; ++i)
  {
    const double z = 1.0 - 2.0 * (i + 0.5) / n, s = std::sqrt(1.0 - z * z), phi = golden * i;
    points->SetPoint(i, c[0] + r * s * std::cos(phi), c[1] + r * s * std::sin(phi), c[2] + r * z);
  }
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(points);
  return poly;
}

/** Largest angle (degrees) between the output normals and sign * radial. */
double WorstRadialAngle(vtkPolyData* out, const double c[3], double sign)
{
  vtkDataArray* normals = out->GetPointData()->GetNormals();
  MRGI_TEST_CHECK(normals && normals->GetNumberOfComponents() == 3);
  double worst = 0.0;
  for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
  {
    double p[3], n[3];
    out->GetPoint(i, p);
    normals->GetTuple(i, n);
    double radial[3] = { p[0] - c[0], p[1] - c[1], p[2] - c[2] };
    const double l =
      std::sqrt(radial[0] * radial[0] + radial[1] * radial[1] + radial[2] * radial[2]);
    double d = sign * (n[0] * radial[0] + n[1] * radial[1] + n[2] * radial[2]) / l;
    d = d > 1.0 ? 1.0 : d < -1.0 ? -1.0 : d;
    worst = std::max(worst, std::acos(d) * 180.0 / Pi);
  }
  return worst;
}

int g_runs = 0;
void CountRun(vtkObject*, unsigned long, void*, void*)
{
  ++g_runs;
}

void TestSphereAndOrientation()
{
  const double c[3] = { 1.0, 2.0, 3.0 };
  const int n = 8000;
  auto sphere = Sphere(n, 2.0, c);
  vtkNew<vtkMRGIPointCloudNormals> filter;
  MRGI_TEST_CHECK(std::strcmp(filter->GetClassName(), "vtkMRGIPointCloudNormals") == 0);
  filter->SetInputData(sphere);
  filter->Update();
  vtkPolyData* out = filter->GetOutput();
  MRGI_TEST_CHECK(out->GetNumberOfPoints() == n);
  MRGI_TEST_CHECK(filter->GetLastOrientation() == vtkMRGIPointCloudNormals::ORIENT_OUTWARD);
  MRGI_TEST_CHECK(WorstRadialAngle(out, c, 1.0) < 2.0);
  vtkDataArray* radius = out->GetPointData()->GetArray("Radius");
  MRGI_TEST_CHECK(radius && radius->GetNumberOfTuples() == n);
  const double spacing = std::sqrt(4.0 * Pi * 4.0 / n);
  for (vtkIdType i = 0; i < n; ++i)
  {
    MRGI_TEST_CHECK(std::fabs(radius->GetComponent(i, 0) - spacing) < 0.15 * spacing);
  }
  // Seen from the centre: inward.
  filter->SetViewPoint(c[0], c[1], c[2]);
  filter->UseViewPointOn();
  filter->Update();
  MRGI_TEST_CHECK(filter->GetLastOrientation() == vtkMRGIPointCloudNormals::ORIENT_VIEWPOINT);
  MRGI_TEST_CHECK(WorstRadialAngle(filter->GetOutput(), c, -1.0) < 2.0);
  // A sensor origin in the field data (the PCD reader's) at the centre: inward too.
  filter->UseViewPointOff();
  vtkNew<vtkDoubleArray> origin;
  origin->SetName("SensorOrigin");
  origin->SetNumberOfComponents(3);
  origin->InsertNextTuple3(c[0], c[1], c[2]);
  sphere->GetFieldData()->AddArray(origin);
  sphere->Modified();
  filter->Update();
  MRGI_TEST_CHECK(filter->GetLastOrientation() == vtkMRGIPointCloudNormals::ORIENT_VIEWPOINT);
  MRGI_TEST_CHECK(WorstRadialAngle(filter->GetOutput(), c, -1.0) < 2.0);
  // PCL's default pose (origin, identity) on an unorganized cloud says
  // nothing about a sensor: outward again; on an organized one it does.
  origin->SetTuple3(0, 0.0, 0.0, 0.0);
  vtkNew<vtkDoubleArray> orientation;
  orientation->SetName("SensorOrientation");
  orientation->SetNumberOfComponents(4);
  orientation->InsertNextTuple4(1.0, 0.0, 0.0, 0.0);
  sphere->GetFieldData()->AddArray(orientation);
  sphere->Modified();
  filter->Update();
  MRGI_TEST_CHECK(filter->GetLastOrientation() == vtkMRGIPointCloudNormals::ORIENT_OUTWARD);
  MRGI_TEST_CHECK(!vtkMRGIPointCloudNormals::SensorPoseIsMeaningful(sphere));
  orientation->SetTuple4(0, 0.0, 1.0, 0.0, 0.0);
  MRGI_TEST_CHECK(vtkMRGIPointCloudNormals::SensorPoseIsMeaningful(sphere));
  orientation->SetTuple4(0, 1.0, 0.0, 0.0, 0.0);
  vtkNew<vtkIntArray> dims;
  dims->SetName("OrganizedDimensions");
  dims->InsertNextValue(100);
  dims->InsertNextValue(80);
  sphere->GetFieldData()->AddArray(dims);
  MRGI_TEST_CHECK(vtkMRGIPointCloudNormals::SensorPoseIsMeaningful(sphere));
  sphere->GetFieldData()->RemoveArray("OrganizedDimensions");
  sphere->GetFieldData()->RemoveArray("SensorOrientation");
  sphere->GetFieldData()->RemoveArray("SensorOrigin");
  sphere->Modified();
  // Up = -z: every normal has z <= 0.
  filter->SetUp(0.0, 0.0, -1.0);
  filter->Update();
  MRGI_TEST_CHECK(filter->GetLastOrientation() == vtkMRGIPointCloudNormals::ORIENT_UP);
  vtkDataArray* normals = filter->GetOutput()->GetPointData()->GetNormals();
  for (vtkIdType i = 0; i < n; ++i)
  {
    MRGI_TEST_CHECK(normals->GetComponent(i, 2) <= 0.0);
  }
}

void TestCaching()
{
  const double c[3] = { 0.0, 0.0, 0.0 };
  auto sphere = Sphere(2000, 1.0, c);
  vtkNew<vtkMRGIPointCloudNormals> filter;
  vtkNew<vtkCallbackCommand> counter;
  counter->SetCallback(CountRun);
  filter->AddObserver(vtkCommand::StartEvent, counter);
  filter->SetInputData(sphere);
  g_runs = 0;
  filter->Update();
  MRGI_TEST_CHECK(g_runs == 1);
  vtkDataArray* first = filter->GetOutput()->GetPointData()->GetNormals();
  filter->Update();
  filter->Update();
  MRGI_TEST_CHECK(g_runs == 1); // cached: nothing changed
  MRGI_TEST_CHECK(filter->GetOutput()->GetPointData()->GetNormals() == first);
  filter->SetNumberOfNeighbors(16); // the same value: not a change
  filter->Update();
  MRGI_TEST_CHECK(g_runs == 1);
  filter->SetNumberOfNeighbors(12);
  filter->Update();
  MRGI_TEST_CHECK(g_runs == 2);
  sphere->GetPoints()->SetPoint(0, 0.0, 0.0, 1.01);
  sphere->Modified();
  filter->Update();
  MRGI_TEST_CHECK(g_runs == 3);
  filter->Update();
  MRGI_TEST_CHECK(g_runs == 3);
}

void TestKeepsInputNormals()
{
  const double c[3] = { 0.0, 0.0, 0.0 };
  auto sphere = Sphere(500, 1.0, c);
  vtkNew<vtkFloatArray> given;
  given->SetName("Given");
  given->SetNumberOfComponents(3);
  given->SetNumberOfTuples(500);
  for (vtkIdType i = 0; i < 500; ++i)
  {
    given->SetTuple3(i, 1.0, 0.0, 0.0);
  }
  sphere->GetPointData()->SetNormals(given);
  vtkNew<vtkMRGIPointCloudNormals> filter;
  filter->SetInputData(sphere);
  filter->Update();
  MRGI_TEST_CHECK(filter->GetOutput()->GetPointData()->GetNormals() == given.GetPointer());
  MRGI_TEST_CHECK(filter->GetOutput()->GetPointData()->GetArray("Radius") != nullptr);
  filter->ComputeNormalsOn();
  filter->Update();
  vtkDataArray* computed = filter->GetOutput()->GetPointData()->GetNormals();
  MRGI_TEST_CHECK(computed != given.GetPointer());
  MRGI_TEST_CHECK(WorstRadialAngle(filter->GetOutput(), c, 1.0) < 5.0);
}

void TestDegenerateInputs()
{
  vtkNew<mrgitest::ErrorCatcher> errors;
  vtkNew<vtkMRGIPointCloudNormals> filter;
  filter->AddObserver(vtkCommand::ErrorEvent, errors);
  // No points: an empty output, no error.
  vtkNew<vtkPolyData> empty;
  filter->SetInputData(empty);
  filter->Update();
  MRGI_TEST_CHECK(errors->Count == 0 && filter->GetOutput()->GetNumberOfPoints() == 0);
  // One point and a NaN point: finite outputs, flagged counts.
  vtkNew<vtkPoints> points;
  points->InsertNextPoint(1.0, 2.0, 3.0);
  points->InsertNextPoint(std::nan(""), 0.0, 0.0);
  vtkNew<vtkPolyData> two;
  two->SetPoints(points);
  filter->SetInputData(two);
  filter->Update();
  MRGI_TEST_CHECK(errors->Count == 0);
  MRGI_TEST_CHECK(filter->GetNumberOfNonFinitePoints() == 1);
  MRGI_TEST_CHECK(filter->GetNumberOfDegeneratePoints() == 1);
  vtkDataArray* normals = filter->GetOutput()->GetPointData()->GetNormals();
  vtkDataArray* radius = filter->GetOutput()->GetPointData()->GetArray("Radius");
  for (vtkIdType i = 0; i < 2; ++i)
  {
    for (int a = 0; a < 3; ++a)
    {
      MRGI_TEST_CHECK(std::isfinite(normals->GetComponent(i, a)));
    }
  }
  // The lone finite point has no spacing: it still gets a radius (1, the
  // fallback for a single point); the NaN point keeps 0.
  MRGI_TEST_CHECK(radius->GetComponent(0, 0) == 1.0);
  MRGI_TEST_CHECK(radius->GetComponent(1, 0) == 0.0);
  // Twenty copies of one point: no spacing anywhere, no positive radius to
  // borrow; each copy gets the single-point fallback, 1.
  vtkNew<vtkPoints> copies;
  for (int i = 0; i < 20; ++i)
  {
    copies->InsertNextPoint(4.0, 5.0, 6.0);
  }
  vtkNew<vtkPolyData> same;
  same->SetPoints(copies);
  filter->SetInputData(same);
  filter->Update();
  vtkDataArray* sameRadius = filter->GetOutput()->GetPointData()->GetArray("Radius");
  MRGI_TEST_CHECK(sameRadius && sameRadius->GetRange()[0] == 1.0 && sameRadius->GetRange()[1] == 1.0);
  // A bad RadiusScale is an error and an empty output.
  filter->SetRadiusScale(0.0);
  filter->Update();
  MRGI_TEST_CHECK(errors->Caught("RadiusScale"));
  MRGI_TEST_CHECK(filter->GetOutput()->GetNumberOfPoints() == 0);
}

// An organized cloud seen at a grazing angle (cells 4x longer than wide)
// gets radii that cover its grid cells with GridRadii (the default), the
// kNN radius without; a bad OrganizedDimensions is an error.
void TestGridRadii()
{
  const int w = 40, h = 30;
  const double a = 0.002, b = 0.008;
  vtkNew<vtkPoints> points;
  points->SetDataTypeToFloat();
  vtkNew<vtkIntArray> pixels;
  pixels->SetName("PixelIndex");
  for (int y = 0; y < h; ++y)
  {
    for (int x = 0; x < w; ++x)
    {
      points->InsertNextPoint(a * x, b * y, 1.0);
      pixels->InsertNextValue(y * w + x);
    }
  }
  vtkNew<vtkPolyData> grid;
  grid->SetPoints(points);
  grid->GetPointData()->AddArray(pixels);
  vtkNew<vtkIntArray> dims;
  dims->SetName("OrganizedDimensions");
  dims->InsertNextValue(w);
  dims->InsertNextValue(h);
  grid->GetFieldData()->AddArray(dims);
  vtkNew<vtkMRGIPointCloudNormals> filter;
  filter->SetInputData(grid);
  MRGI_TEST_CHECK(filter->GetGridRadii());
  filter->Update();
  const vtkIdType middle = (h / 2) * w + w / 2;
  const double covering = std::sqrt(a * a + b * b) / std::sqrt(Pi);
  vtkDataArray* radius = filter->GetOutput()->GetPointData()->GetArray("Radius");
  MRGI_TEST_CHECK(std::fabs(radius->GetComponent(middle, 0) - covering) < 1e-6);
  // Interior points (corners and borders may have a larger kNN radius).
  MRGI_TEST_CHECK(filter->GetNumberOfGridRaisedPoints() >= (w - 2) * (h - 2));
  filter->GridRadiiOff();
  filter->Update();
  radius = filter->GetOutput()->GetPointData()->GetArray("Radius");
  // The kNN radius: its square surfel does not reach the cell's corners.
  MRGI_TEST_CHECK(radius->GetComponent(middle, 0) < 0.95 * covering);
  MRGI_TEST_CHECK(filter->GetNumberOfGridRaisedPoints() == 0);
  // Without its grid the same points are an unorganized cloud: kNN radii.
  grid->GetFieldData()->RemoveArray("OrganizedDimensions");
  filter->GridRadiiOn();
  filter->Update();
  MRGI_TEST_CHECK(filter->GetNumberOfGridRaisedPoints() == 0);
  // A grid of 0 x 30 pixels is refused.
  vtkNew<mrgitest::ErrorCatcher> errors;
  filter->AddObserver(vtkCommand::ErrorEvent, errors);
  dims->SetValue(0, 0);
  grid->GetFieldData()->AddArray(dims);
  grid->Modified();
  filter->Update();
  MRGI_TEST_CHECK(errors->Caught("OrganizedDimensions"));
  MRGI_TEST_CHECK(filter->GetOutput()->GetNumberOfPoints() == 0);
}

void TestPCDReaderBase()
{
  // This program does not load MRGI::RenderingPCL: the base class answers.
  vtkNew<mrgitest::ErrorCatcher> errors;
  vtkNew<vtkMRGIPCDReader> reader;
  MRGI_TEST_CHECK(std::strcmp(reader->GetClassName(), "vtkMRGIPCDReader") == 0);
  reader->AddObserver(vtkCommand::ErrorEvent, errors);
  reader->SetFileName("cloud.pcd");
  reader->Update();
  MRGI_TEST_CHECK(errors->Caught("MRGI::RenderingPCL"));
  MRGI_TEST_CHECK(reader->GetOutput()->GetNumberOfPoints() == 0);
}
}

int main(int argc, char* argv[])
{
  return mrgitest::RunCases(argc, argv,
    { MRGI_TEST_CASE(TestSphereAndOrientation), MRGI_TEST_CASE(TestCaching),
      MRGI_TEST_CASE(TestKeepsInputNormals), MRGI_TEST_CASE(TestDegenerateInputs),
      MRGI_TEST_CASE(TestGridRadii), MRGI_TEST_CASE(TestPCDReaderBase) });
}
