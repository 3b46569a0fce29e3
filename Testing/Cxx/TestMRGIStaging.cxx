// vtkMRGIStaging: the up axis of the shared Stanford meshes (y), of the
// bunny rotated to z-up (actor matrix) and x-up (data), of a pedestal the
// test makes, of clouds tagged as LAS (z) or PCD (the sensor's -y); the
// framing measured on rendered images (the data covers FillFraction of the
// image, centred; ResetCamera's is printed for comparison); the ground
// under the data; the key lights (spot: above, in front, its cone covering
// the data; area: facing the data; none: untouched); the indirect light
// adds light to the staged image; volumes become an iso-surface (a sphere
// the test makes at its radius; ironProt.vtk at Otsu's value, not its
// box); errors. The shared data (../shared/data) is used when present.
#include "mrgiTestUtilities.h"

#include "vtkActor.h"
#include "vtkActorCollection.h"
#include "vtkAppendPolyData.h"
#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkCubeSource.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkIntArray.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMRGIAreaLight.h"
#include "vtkMRGIPass.h"
#include "vtkMRGISceneBuilder.h"
#include "vtkMRGIStaging.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkPLYReader.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkRenderStepsPass.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"
#include "vtkTransform.h"
#include "vtkTransformPolyDataFilter.h"
#include "vtkTriangleFilter.h"

#include "mrgi_las.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

namespace
{
// The shared data file `name`, or "" (printed) when it is not there.
std::string Shared(const char* name)
{
  const char* dir = std::getenv("MRGI_SHARED_DATA_DIR");
  const std::string path = std::string(dir ? dir : "") + "/" + name;
  if (!dir || !std::ifstream(path).good())
  {
    std::printf("%s not found (MRGI_SHARED_DATA_DIR): not checked\n", name);
    return "";
  }
  return path;
}

vtkSmartPointer<vtkPolyData> ReadPLY(const std::string& path)
{
  vtkNew<vtkPLYReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->ShallowCopy(reader->GetOutput());
  MRGI_TEST_CHECK(poly->GetNumberOfPolys() > 0);
  return poly;
}

// A rotation taking +y to `up` (the test's own, independent of the class).
vtkSmartPointer<vtkTransform> RotateYTo(int up)
{
  auto t = vtkSmartPointer<vtkTransform>::New();
  switch (up)
  {
    case vtkMRGIStaging::UpPositiveZ:
      t->RotateX(90); // y -> z
      break;
    case vtkMRGIStaging::UpPositiveX:
      t->RotateZ(-90); // y -> x
      break;
    case vtkMRGIStaging::UpNegativeY:
      t->RotateZ(180);
      break;
    default:
      break;
  }
  return t;
}

vtkSmartPointer<vtkActor> ActorOf(vtkPolyData* data)
{
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(data);
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  return actor;
}

// Stage one actor in a fresh renderer (no window); returns the detected up.
int DetectUp(vtkActor* actor, vtkMRGIStaging* staging = nullptr)
{
  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(actor);
  vtkNew<vtkMRGIStaging> own;
  vtkMRGIStaging* s = staging ? staging : own.GetPointer();
  MRGI_TEST_CHECK(s->Stage(renderer));
  std::printf(
    "  up %s (%s)\n", vtkMRGIStaging::GetUpAxisName(s->GetDetectedUp()), s->GetUpReason());
  return s->GetDetectedUp();
}

// A pedestal: a wide flat slab with a sphere on it, y up.
vtkSmartPointer<vtkPolyData> Pedestal()
{
  vtkNew<vtkCubeSource> slab;
  slab->SetBounds(-1, 1, 0, 0.15, -1, 1);
  vtkNew<vtkSphereSource> ball;
  ball->SetCenter(0, 0.8, 0);
  ball->SetRadius(0.6);
  ball->SetThetaResolution(32);
  ball->SetPhiResolution(32);
  vtkNew<vtkAppendPolyData> both;
  both->AddInputConnection(slab->GetOutputPort());
  both->AddInputConnection(ball->GetOutputPort());
  vtkNew<vtkTriangleFilter> triangles;
  triangles->SetInputConnection(both->GetOutputPort());
  triangles->Update();
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->ShallowCopy(triangles->GetOutput());
  return poly;
}

vtkSmartPointer<vtkPolyData> Transformed(vtkPolyData* in, vtkTransform* t)
{
  vtkNew<vtkTransformPolyDataFilter> filter;
  filter->SetInputData(in);
  filter->SetTransform(t);
  filter->Update();
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->ShallowCopy(filter->GetOutput());
  return poly;
}

void TestUpShared()
{
  for (const char* name : { "bunny.ply", "dragon.ply" })
  {
    const std::string path = Shared(name);
    if (path.empty())
    {
      continue;
    }
    vtkSmartPointer<vtkPolyData> mesh = ReadPLY(path);
    std::printf("%s as read:\n", name);
    MRGI_TEST_CHECK(DetectUp(ActorOf(mesh)) == vtkMRGIStaging::UpPositiveY);
    if (std::string(name) == "bunny.ply")
    {
      // z-up through the actor's matrix, x-up and -y-up through the data.
      std::printf("bunny rotated to +z (actor matrix):\n");
      vtkSmartPointer<vtkActor> actor = ActorOf(mesh);
      actor->SetUserTransform(RotateYTo(vtkMRGIStaging::UpPositiveZ));
      MRGI_TEST_CHECK(DetectUp(actor) == vtkMRGIStaging::UpPositiveZ);
      std::printf("bunny rotated to +x (data):\n");
      MRGI_TEST_CHECK(DetectUp(ActorOf(Transformed(mesh,
                        RotateYTo(vtkMRGIStaging::UpPositiveX)))) == vtkMRGIStaging::UpPositiveX);
      std::printf("bunny upside down (data):\n");
      MRGI_TEST_CHECK(DetectUp(ActorOf(Transformed(mesh,
                        RotateYTo(vtkMRGIStaging::UpNegativeY)))) == vtkMRGIStaging::UpNegativeY);
    }
  }
}

void TestUpMade()
{
  vtkSmartPointer<vtkPolyData> pedestal = Pedestal();
  for (int up : { vtkMRGIStaging::UpPositiveY, vtkMRGIStaging::UpPositiveZ,
         vtkMRGIStaging::UpPositiveX, vtkMRGIStaging::UpNegativeY })
  {
    std::printf("pedestal, up %s:\n", vtkMRGIStaging::GetUpAxisName(up));
    MRGI_TEST_CHECK(DetectUp(ActorOf(Transformed(pedestal, RotateYTo(up)))) == up);
  }
  // An explicit setting wins over the geometry.
  vtkNew<vtkMRGIStaging> staging;
  staging->SetUp(vtkMRGIStaging::UpNegativeZ);
  MRGI_TEST_CHECK(DetectUp(ActorOf(pedestal), staging) == vtkMRGIStaging::UpNegativeZ);
  MRGI_TEST_CHECK(std::string(staging->GetUpReason()) == "set");
}

// A cloud of vertices with `points`; optional field data.
vtkSmartPointer<vtkPolyData> Cloud(vtkPoints* points)
{
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(points);
  vtkNew<vtkCellArray> verts;
  for (vtkIdType i = 0; i < points->GetNumberOfPoints(); ++i)
  {
    verts->InsertNextCell(1, &i);
  }
  poly->SetVerts(verts);
  return poly;
}

void TestUpClouds()
{
  // A LAS tile: the C core's reader, tagged as a LAS reader tags its output.
  const std::string las = Shared("file_with_both_wkt_and_geotiff_vlrs.las");
  vtkNew<vtkPoints> points;
  if (!las.empty())
  {
    mrgi_las_points cloud{};
    mrgi_error err;
    MRGI_TEST_CHECK(mrgi_las_read(las.c_str(), 100000000, &cloud, &err) == MRGI_OK);
    for (int64_t i = 0; i < cloud.count; ++i)
    {
      points->InsertNextPoint(cloud.positions + 3 * i);
    }
    mrgi_las_points_destroy(&cloud);
  }
  else
  {
    // A made terrain: a gentle 60 x 40 height field with 15-high trees.
    for (int i = 0; i < 60; ++i)
    {
      for (int j = 0; j < 40; ++j)
      {
        points->InsertNextPoint(i, j, 0.02 * i + ((i * 7 + j * 3) % 11 == 0 ? 15.0 : 0.0));
      }
    }
  }
  vtkSmartPointer<vtkPolyData> tile = Cloud(points);
  std::printf("LAS tile, geometry only:\n");
  MRGI_TEST_CHECK(DetectUp(ActorOf(tile)) == vtkMRGIStaging::UpPositiveZ); // its ground
  vtkNew<vtkIntArray> version;
  version->SetName("LASVersion");
  version->InsertNextValue(14);
  tile->GetFieldData()->AddArray(version);
  std::printf("LAS tile, with its LASVersion field:\n");
  MRGI_TEST_CHECK(DetectUp(ActorOf(tile)) == vtkMRGIStaging::UpPositiveZ);

  // The bunny's vertices as a cloud (no cells), turned to z-up and x-up.
  const std::string bunny = Shared("bunny.ply");
  if (!bunny.empty())
  {
    vtkSmartPointer<vtkPolyData> mesh = ReadPLY(bunny);
    for (int up :
      { vtkMRGIStaging::UpPositiveY, vtkMRGIStaging::UpPositiveZ, vtkMRGIStaging::UpPositiveX })
    {
      vtkSmartPointer<vtkPolyData> turned = Transformed(mesh, RotateYTo(up));
      std::printf("bunny's points, up %s:\n", vtkMRGIStaging::GetUpAxisName(up));
      MRGI_TEST_CHECK(DetectUp(ActorOf(Cloud(turned->GetPoints()))) == up);
    }
  }

  // A depth camera's cloud: the sensor looks along +z with y down; turned
  // by 90 degrees about x (its y now along world -z), up is world +z.
  vtkNew<vtkPoints> ball;
  for (int i = 0; i < 500; ++i)
  {
    const double a = 0.1 * i, b = 0.037 * i;
    ball->InsertNextPoint(std::cos(a) * std::sin(b), std::sin(a) * std::sin(b), 2 + std::cos(b));
  }
  for (int turned = 0; turned < 2; ++turned)
  {
    vtkSmartPointer<vtkPolyData> pcd = Cloud(ball);
    vtkNew<vtkDoubleArray> viewpoint;
    viewpoint->SetName("VIEWPOINT");
    const double half = vtkMath::RadiansFromDegrees(45.0);
    const double values[7] = { 0, 0, 0, turned ? std::cos(half) : 1.0,
      turned ? std::sin(half) : 0.0, 0, 0 };
    for (double v : values)
    {
      viewpoint->InsertNextValue(v);
    }
    pcd->GetFieldData()->AddArray(viewpoint);
    std::printf("PCD cloud, sensor %s:\n", turned ? "turned 90 degrees about x" : "upright");
    MRGI_TEST_CHECK(DetectUp(ActorOf(pcd)) ==
      (turned ? vtkMRGIStaging::UpNegativeZ : vtkMRGIStaging::UpNegativeY));
  }
}

// Bounding rectangle of the pixels brighter than `threshold` (bottom-up rows).
bool Covered(vtkImageData* image, int threshold, int box[4])
{
  int dims[3];
  image->GetDimensions(dims);
  box[0] = dims[0];
  box[1] = -1;
  box[2] = dims[1];
  box[3] = -1;
  vtkDataArray* rgb = image->GetPointData()->GetScalars();
  for (int y = 0; y < dims[1]; ++y)
  {
    for (int x = 0; x < dims[0]; ++x)
    {
      const vtkIdType p = static_cast<vtkIdType>(y) * dims[0] + x;
      const double v = std::max(
        rgb->GetComponent(p, 0), std::max(rgb->GetComponent(p, 1), rgb->GetComponent(p, 2)));
      if (v > threshold)
      {
        box[0] = std::min(box[0], x);
        box[1] = std::max(box[1], x);
        box[2] = std::min(box[2], y);
        box[3] = std::max(box[3], y);
      }
    }
  }
  return box[1] >= box[0];
}

// The data's covered fraction (of the limiting side) and the offset of its
// centre from the image centre (fraction of the side), rendered by VTK alone
// under a headlight, for the staging (or ResetCamera when staging is null).
void Coverage(
  vtkPolyData* data, int width, int height, vtkMRGIStaging* staging, double& fill, double offset[2])
{
  vtkSmartPointer<vtkRenderWindow> window = mrgitest::HeadlessWindow(width, height);
  vtkNew<vtkRenderer> renderer;
  window->AddRenderer(renderer);
  renderer->SetBackground(0, 0, 0);
  renderer->AddActor(ActorOf(data));
  if (staging)
  {
    MRGI_TEST_CHECK(staging->Stage(renderer));
  }
  else
  {
    renderer->ResetCamera();
  }
  window->Render();
  int box[4];
  MRGI_TEST_CHECK(Covered(mrgitest::GrabRGB(window), 0, box));
  const double w = (box[1] - box[0] + 1.0) / width;
  const double h = (box[3] - box[2] + 1.0) / height;
  fill = std::max(w, h);
  offset[0] = 0.5 * (box[0] + box[1] + 1.0) / width - 0.5;
  offset[1] = 0.5 * (box[2] + box[3] + 1.0) / height - 0.5;
}

void TestFraming()
{
  const std::string bunny = Shared("bunny.ply");
  vtkSmartPointer<vtkPolyData> data = bunny.empty() ? Pedestal() : ReadPLY(bunny);
  const int sizes[3][2] = { { 200, 200 }, { 320, 180 }, { 150, 240 } };
  for (const auto& size : sizes)
  {
    for (double asked : { 0.8, 0.5 })
    {
      vtkNew<vtkMRGIStaging> staging;
      staging->GroundOff();
      staging->SetKeyLight(vtkMRGIStaging::KeyLightNone); // VTK's headlight: every pixel lit
      staging->SetFillFraction(asked);
      double fill = 0, offset[2] = { 1, 1 };
      Coverage(data, size[0], size[1], staging, fill, offset);
      double resetFill = 0, resetOffset[2];
      Coverage(data, size[0], size[1], nullptr, resetFill, resetOffset);
      std::printf("%dx%d, fill %.2f asked: covered %.3f, centre offset %+.3f %+.3f "
                  "(ResetCamera: %.3f)\n",
        size[0], size[1], asked, fill, offset[0], offset[1], resetFill);
      // Two pixels of rasterisation on the smallest side.
      const double pixel = 2.0 / std::min(size[0], size[1]);
      MRGI_TEST_CHECK(std::fabs(fill - asked) <= 0.01 + pixel);
      MRGI_TEST_CHECK(std::fabs(offset[0]) <= pixel && std::fabs(offset[1]) <= pixel);
    }
  }
}

// The renderer's lights as a vector.
std::vector<vtkLight*> Lights(vtkRenderer* renderer)
{
  std::vector<vtkLight*> lights;
  vtkLightCollection* all = renderer->GetLights();
  all->InitTraversal();
  while (vtkLight* light = all->GetNextItem())
  {
    lights.push_back(light);
  }
  return lights;
}

void TestGroundAndLights()
{
  vtkSmartPointer<vtkPolyData> pedestal =
    Transformed(Pedestal(), RotateYTo(vtkMRGIStaging::UpPositiveZ));
  double bounds[6];
  pedestal->GetBounds(bounds);
  const double center[3] = { 0.5 * (bounds[0] + bounds[1]), 0.5 * (bounds[2] + bounds[3]),
    0.5 * (bounds[4] + bounds[5]) };
  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(ActorOf(pedestal));
  vtkNew<vtkLight> previous;
  renderer->AddLight(previous);
  vtkNew<vtkMRGIStaging> staging;
  MRGI_TEST_CHECK(staging->Stage(renderer));
  MRGI_TEST_CHECK(staging->GetDetectedUp() == vtkMRGIStaging::UpPositiveZ);

  // The ground: just under the data along +z, wider than it, facing up.
  vtkActor* ground = staging->GetGroundActor();
  MRGI_TEST_CHECK(ground != nullptr);
  MRGI_TEST_CHECK(renderer->GetActors()->IsItemPresent(ground));
  double g[6];
  ground->GetBounds(g);
  const double height = bounds[5] - bounds[4];
  MRGI_TEST_CHECK(g[5] - g[4] < 1e-9 * height + 1e-12);
  MRGI_TEST_CHECK(g[4] < bounds[4] && g[4] > bounds[4] - 0.01 * height);
  MRGI_TEST_CHECK(
    g[0] < bounds[0] - (bounds[1] - bounds[0]) && g[1] > bounds[1] + (bounds[1] - bounds[0]));
  vtkDataArray* normals =
    vtkPolyData::SafeDownCast(ground->GetMapper()->GetInput())->GetPointData()->GetNormals();
  MRGI_TEST_CHECK(normals && normals->GetComponent(0, 2) == 1.0);

  // The spot: the only light, above and in front (-y is the front for +z
  // up), aimed at the data, its cone covering every corner of the data.
  std::vector<vtkLight*> lights = Lights(renderer);
  MRGI_TEST_CHECK(lights.size() == 1 && lights[0] == staging->GetKeyLightObject());
  MRGI_TEST_CHECK(!renderer->GetAutomaticLightCreation());
  vtkLight* spot = lights[0];
  MRGI_TEST_CHECK(spot->GetPositional() && spot->GetConeAngle() < 90);
  const double* p = spot->GetPosition();
  MRGI_TEST_CHECK(p[2] > bounds[5] && p[1] < bounds[2]);
  double axis[3];
  for (int k = 0; k < 3; ++k)
  {
    axis[k] = spot->GetFocalPoint()[k] - p[k];
  }
  vtkMath::Normalize(axis);
  for (int corner = 0; corner < 8; ++corner)
  {
    double to[3] = { bounds[corner & 1] - p[0], bounds[2 + ((corner >> 1) & 1)] - p[1],
      bounds[4 + ((corner >> 2) & 1)] - p[2] };
    vtkMath::Normalize(to);
    MRGI_TEST_CHECK(
      vtkMath::DegreesFromRadians(std::acos(vtkMath::Dot(to, axis))) < spot->GetConeAngle());
  }

  // Staged again with an area light: the spot and the old ground go; the
  // light faces the data; a dark light keeps VTK's lighting on.
  staging->SetKeyLight(vtkMRGIStaging::KeyLightArea);
  MRGI_TEST_CHECK(staging->Stage(renderer));
  MRGI_TEST_CHECK(renderer->GetActors()->GetNumberOfItems() == 2);
  vtkMRGIAreaLight* area = staging->GetAreaLight();
  MRGI_TEST_CHECK(area != nullptr && staging->GetKeyLightObject() == nullptr);
  lights = Lights(renderer);
  MRGI_TEST_CHECK(lights.size() == 1 && lights[0]->GetIntensity() == 0.0);
  double n[3], to[3];
  vtkMath::Cross(area->GetEdgeU(), area->GetEdgeV(), n);
  for (int k = 0; k < 3; ++k)
  {
    to[k] = center[k] - area->GetCenter()[k];
  }
  MRGI_TEST_CHECK(vtkMath::Dot(n, to) > 0.99 * vtkMath::Norm(n) * vtkMath::Norm(to));
  MRGI_TEST_CHECK(area->GetCenter()[2] > bounds[5]);

  // No key light, no ground: the renderer's own lights stay.
  vtkNew<vtkRenderer> plain;
  plain->AddActor(ActorOf(pedestal));
  plain->AddLight(previous);
  staging->SetKeyLight(vtkMRGIStaging::KeyLightNone);
  staging->GroundOff();
  MRGI_TEST_CHECK(staging->Stage(plain));
  lights = Lights(plain);
  MRGI_TEST_CHECK(lights.size() == 1 && lights[0] == previous.GetPointer());
  MRGI_TEST_CHECK(plain->GetActors()->GetNumberOfItems() == 1);
  MRGI_TEST_CHECK(staging->GetGroundActor() == nullptr);
  // The first renderer lost what the staging had put there.
  MRGI_TEST_CHECK(renderer->GetActors()->GetNumberOfItems() == 1);
}

// The staged pedestal with MRGI: indirect light from the ground and the
// key light adds light (fixed exposure, GI on against off).
void TestIndirectShows()
{
  double sums[2] = { 0, 0 };
  for (int gi = 0; gi < 2; ++gi)
  {
    vtkSmartPointer<vtkRenderWindow> window = mrgitest::HeadlessWindow(160, 120);
    vtkNew<vtkRenderer> renderer;
    window->AddRenderer(renderer);
    renderer->AddActor(ActorOf(Pedestal()));
    vtkNew<vtkMRGIStaging> staging;
    MRGI_TEST_CHECK(staging->Stage(renderer));
    vtkNew<vtkRenderStepsPass> steps;
    vtkNew<vtkMRGIPass> pass;
    pass->SetDelegatePass(steps);
    pass->SetIndirectMode(gi ? vtkMRGIPass::IndirectMultires : vtkMRGIPass::IndirectOff);
    pass->SetAutoExposure(false);
    pass->SetExposure(0.0);
    renderer->SetPass(pass);
    window->Render();
    vtkSmartPointer<vtkImageData> image = mrgitest::GrabRGB(window);
    vtkDataArray* rgb = image->GetPointData()->GetScalars();
    for (vtkIdType i = 0; i < rgb->GetNumberOfValues(); ++i)
    {
      sums[gi] += rgb->GetComponent(i / 3, static_cast<int>(i % 3));
    }
    MRGI_TEST_CHECK(sums[gi] > 0);
  }
  std::printf("image sum: GI off %.0f, on %.0f (+%.1f%%)\n", sums[0], sums[1],
    100.0 * (sums[1] / sums[0] - 1.0));
  MRGI_TEST_CHECK(sums[1] > 1.02 * sums[0]);
}

// A sphere as a distance field: 1 inside radius 10, 0 outside, smooth in
// between; the iso-surface's points lie at the radius.
void TestIsoSurfaceMade()
{
  vtkNew<vtkImageData> volume;
  volume->SetDimensions(40, 40, 40);
  volume->AllocateScalars(VTK_FLOAT, 1);
  auto* s = static_cast<float*>(volume->GetScalarPointer());
  for (int z = 0; z < 40; ++z)
  {
    for (int y = 0; y < 40; ++y)
    {
      for (int x = 0; x < 40; ++x)
      {
        const double r =
          std::sqrt((x - 19.5) * (x - 19.5) + (y - 19.5) * (y - 19.5) + (z - 19.5) * (z - 19.5));
        *s++ = static_cast<float>(1.0 / (1.0 + std::exp(2.0 * (r - 10.0))));
      }
    }
  }
  MRGI_TEST_CHECK(vtkMRGIStaging::IsVolume(volume));
  vtkNew<vtkMRGIStaging> staging;
  vtkNew<vtkPolyData> surface;
  MRGI_TEST_CHECK(staging->MakeIsoSurface(volume, surface));
  std::printf("made sphere: iso-value %.3f, %lld triangles\n", staging->GetLastIsoValue(),
    static_cast<long long>(surface->GetNumberOfPolys()));
  MRGI_TEST_CHECK(staging->GetLastIsoValue() > 0.05 && staging->GetLastIsoValue() < 0.95);
  MRGI_TEST_CHECK(surface->GetNumberOfPolys() > 500);
  MRGI_TEST_CHECK(surface->GetPointData()->GetScalars() == nullptr);
  for (vtkIdType i = 0; i < surface->GetNumberOfPoints(); ++i)
  {
    double p[3];
    surface->GetPoint(i, p);
    const double r = std::sqrt((p[0] - 19.5) * (p[0] - 19.5) + (p[1] - 19.5) * (p[1] - 19.5) +
      (p[2] - 19.5) * (p[2] - 19.5));
    if (std::fabs(r - 10.0) > 1.5)
    {
      MRGI_TEST_FAIL("point %lld at radius %.2f", static_cast<long long>(i), r);
    }
  }
  // An explicit value.
  staging->AutomaticIsoValueOff();
  staging->SetIsoValue(0.9);
  MRGI_TEST_CHECK(staging->MakeIsoSurface(volume, surface));
  MRGI_TEST_CHECK(staging->GetLastIsoValue() == 0.9);
  // Errors: a value outside the range, constant scalars, not a volume.
  staging->SetIsoValue(5.0);
  MRGI_TEST_CHECK(!staging->MakeIsoSurface(volume, surface));
  MRGI_TEST_CHECK(
    std::string(staging->GetLastErrorMessage()).find("is empty") != std::string::npos);
  staging->AutomaticIsoValueOn();
  volume->GetPointData()->GetScalars()->Fill(3.0);
  MRGI_TEST_CHECK(!staging->MakeIsoSurface(volume, surface));
  MRGI_TEST_CHECK(std::string(staging->GetLastErrorMessage()).find("are all") != std::string::npos);
  MRGI_TEST_CHECK(!vtkMRGIStaging::IsVolume(Pedestal()));
  MRGI_TEST_CHECK(!staging->MakeIsoSurface(nullptr, surface));
  vtkNew<vtkImageData> slice;
  slice->SetDimensions(8, 8, 1);
  slice->AllocateScalars(VTK_FLOAT, 1);
  MRGI_TEST_CHECK(!vtkMRGIStaging::IsVolume(slice));
}

// ironProt.vtk through the scene builder: staged, a molecule-like surface
// (no point on the volume's outer faces, where its box would be); not
// staged, today's box.
void TestIsoSurfaceIronProt()
{
  const std::string path = Shared("ironProt.vtk");
  if (path.empty())
  {
    return;
  }
  for (int staged = 0; staged < 2; ++staged)
  {
    vtkSmartPointer<vtkRenderWindow> window = mrgitest::HeadlessWindow(64, 64);
    vtkNew<vtkRenderer> renderer;
    window->AddRenderer(renderer);
    vtkNew<vtkMRGISceneBuilder> builder;
    vtkNew<vtkMRGIStaging> staging;
    builder->SetScene(path.c_str());
    if (staged)
    {
      builder->SetStaging(staging);
    }
    MRGI_TEST_CHECK(builder->Build(renderer));
    vtkActorCollection* actors = renderer->GetActors(); // rebuilt by each GetActors()
    actors->InitTraversal();
    vtkActor* actor = actors->GetNextActor(); // the data, then the ground
    if (staged)
    {
      MRGI_TEST_CHECK(actors->GetNextActor() == staging->GetGroundActor());
    }
    auto* surface = vtkDataSet::SafeDownCast(actor->GetMapper()->GetInputDataObject(0, 0));
    MRGI_TEST_CHECK(surface != nullptr);
    // ironProt: 68^3 samples, spacing 1 from the origin.
    vtkIdType onFaces = 0;
    for (vtkIdType i = 0; i < surface->GetNumberOfPoints(); ++i)
    {
      double p[3];
      surface->GetPoint(i, p);
      bool face = false;
      for (double c : p)
      {
        face = face || c < 0.01 || c > 66.99;
      }
      onFaces += face ? 1 : 0;
    }
    const double fraction = static_cast<double>(onFaces) / surface->GetNumberOfPoints();
    std::printf("ironProt.vtk %s: %lld cells, %.3f of the points on the volume's faces%s\n",
      staged ? "staged" : "not staged", static_cast<long long>(builder->GetBuiltTriangleCount()),
      fraction,
      staged ? (", iso-value " + std::to_string(staging->GetLastIsoValue())).c_str() : "");
    if (staged)
    {
      MRGI_TEST_CHECK(fraction < 0.01);
      MRGI_TEST_CHECK(builder->GetBuiltTriangleCount() > 5000);
      MRGI_TEST_CHECK(staging->GetLastIsoValue() > 0 && staging->GetLastIsoValue() < 255);
    }
    else
    {
      MRGI_TEST_CHECK(fraction == 1.0);
    }
  }
}

void TestErrors()
{
  vtkNew<vtkMRGIStaging> staging;
  MRGI_TEST_CHECK(!staging->Stage(nullptr));
  MRGI_TEST_CHECK(
    std::string(staging->GetLastErrorMessage()).find("renderer") != std::string::npos);
  vtkNew<vtkRenderer> empty;
  MRGI_TEST_CHECK(!staging->Stage(empty));
  MRGI_TEST_CHECK(
    std::string(staging->GetLastErrorMessage()).find("nothing to stage") != std::string::npos);
  MRGI_TEST_CHECK(empty->GetActors()->GetNumberOfItems() == 0);
  // Only NaN points (an organized cloud with no valid pixel).
  vtkNew<vtkPoints> nan;
  nan->InsertNextPoint(std::nan(""), 0, 0);
  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(ActorOf(Cloud(nan)));
  MRGI_TEST_CHECK(!staging->Stage(renderer));
  MRGI_TEST_CHECK(renderer->GetActors()->GetNumberOfItems() == 1);
  MRGI_TEST_CHECK(renderer->GetLights()->GetNumberOfItems() == 0);
  // Triangles with every corner at one place draw nothing: an error, not
  // a picture of the ground alone.
  vtkNew<vtkPoints> same;
  for (int i = 0; i < 3; ++i)
  {
    same->InsertNextPoint(0.5, 0.5, 0.5);
  }
  auto degenerate = vtkSmartPointer<vtkPolyData>::New();
  degenerate->SetPoints(same);
  vtkNew<vtkCellArray> triangle;
  const vtkIdType corners[3] = { 0, 1, 2 };
  triangle->InsertNextCell(3, corners);
  degenerate->SetPolys(triangle);
  vtkNew<vtkRenderer> nothing;
  nothing->AddActor(ActorOf(degenerate));
  MRGI_TEST_CHECK(!staging->Stage(nothing));
  MRGI_TEST_CHECK(
    std::string(staging->GetLastErrorMessage()).find("nothing to draw") != std::string::npos);
  MRGI_TEST_CHECK(nothing->GetActors()->GetNumberOfItems() == 1);
  // Through the scene builder (a glTF file, the importer's path): the
  // renderer keeps nothing of the file.
  const std::string gltf = mrgitest::TempPath("staging_degenerate.gltf");
  {
    std::ofstream out(gltf);
    out << R"({"asset":{"version":"2.0"},"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
        << R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],)"
        << R"("buffers":[{"byteLength":36,"uri":"data:application/octet-stream;base64,)"
        << R"(AAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAA"}],)"
        << R"("bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":36}],)"
        << R"("accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3",)"
        << R"("max":[0,0,0],"min":[0,0,0]}]})";
  }
  vtkNew<vtkRenderer> untouched;
  vtkNew<vtkMRGISceneBuilder> builder;
  builder->SetScene(gltf.c_str());
  builder->SetStaging(staging);
  MRGI_TEST_CHECK(!builder->Build(untouched));
  std::printf("degenerate glTF: %s\n", builder->GetLastErrorMessage());
  MRGI_TEST_CHECK(
    std::string(builder->GetLastErrorMessage()).find("cannot stage") != std::string::npos);
  MRGI_TEST_CHECK(untouched->GetActors()->GetNumberOfItems() == 0);
  MRGI_TEST_CHECK(untouched->GetLights()->GetNumberOfItems() == 0);
  // One point: staged, the camera at distance 1 around it.
  vtkNew<vtkPoints> one;
  one->InsertNextPoint(1, 2, 3);
  vtkNew<vtkRenderer> single;
  single->AddActor(ActorOf(Cloud(one)));
  MRGI_TEST_CHECK(staging->Stage(single));
  const double* focal = single->GetActiveCamera()->GetFocalPoint();
  MRGI_TEST_CHECK(focal[0] == 1 && focal[1] == 2 && focal[2] == 3);
  MRGI_TEST_CHECK(vtkMRGIStaging::GetUpAxisName(7) == nullptr);
  MRGI_TEST_CHECK(std::string(vtkMRGIStaging::GetUpAxisName(vtkMRGIStaging::UpAuto)) == "auto");
}
}

int main(int argc, char* argv[])
{
  return mrgitest::RunCases(argc, argv,
    { MRGI_TEST_CASE(TestUpShared), MRGI_TEST_CASE(TestUpMade), MRGI_TEST_CASE(TestUpClouds),
      MRGI_TEST_CASE(TestFraming), MRGI_TEST_CASE(TestGroundAndLights),
      MRGI_TEST_CASE(TestIndirectShows), MRGI_TEST_CASE(TestIsoSurfaceMade),
      MRGI_TEST_CASE(TestIsoSurfaceIronProt), MRGI_TEST_CASE(TestErrors) });
}
