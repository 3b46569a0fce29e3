// vtkMRGISurfels and vtkMRGIMeshSampler: the polygons and their per-corner
// data, 32-bit cells, skipped points, the errors that name what is missing;
// and the warnings of vtkMRGIPass (one per actor drawn as pixels) and of the
// ground truth, which a cloud drawn as surfels does not get. (The image
// comparison of a cloud with its mesh is python.PointCloudMeshVsCloud.)
#include "mrgiPassSceneFixture.h"
#include "mrgiTestUtilities.h"

#include "mrgi_scene.h"

#include "vtkActor.h"
#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkCommand.h"
#include "vtkDoubleArray.h"
#include "vtkExecutive.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkMRGIMeshSampler.h"
#include "vtkMRGIPass.h"
#include "vtkMRGIReferenceRenderer.h"
#include "vtkMRGISceneBuilder.h"
#include "vtkMRGISurfels.h"
#include "vtkMath.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkRenderStepsPass.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"
#include "vtkUnsignedCharArray.h"

#include <cmath>
#include <cstdlib>
#include <limits>
#include <string>

namespace
{
// A cloud of n points on the plane z = 1 with normals (0, 0, 2) (not unit),
// radius 0.1 + 0.01 i, RGB colours (active scalars) and an Intensity array.
vtkSmartPointer<vtkPolyData> MakeCloud(int n, bool vertexCells)
{
  vtkNew<vtkPoints> points;
  vtkNew<vtkFloatArray> normals;
  normals->SetName("Normals");
  normals->SetNumberOfComponents(3);
  vtkNew<vtkFloatArray> radius;
  radius->SetName("Radius");
  vtkNew<vtkUnsignedCharArray> rgb;
  rgb->SetName("RGB");
  rgb->SetNumberOfComponents(3);
  vtkNew<vtkFloatArray> intensity;
  intensity->SetName("Intensity");
  vtkNew<vtkCellArray> verts;
  for (int i = 0; i < n; ++i)
  {
    points->InsertNextPoint(i, 2 * i, 1.0);
    normals->InsertNextTuple3(0, 0, 2);
    radius->InsertNextValue(0.1f + 0.01f * static_cast<float>(i));
    rgb->InsertNextTuple3(i % 256, 255 - i % 256, 7);
    intensity->InsertNextValue(static_cast<float>(100 + i));
    if (vertexCells)
    {
      vtkIdType id = i;
      verts->InsertNextCell(1, &id);
    }
  }
  vtkSmartPointer<vtkPolyData> cloud = vtkSmartPointer<vtkPolyData>::New();
  cloud->SetPoints(points);
  if (vertexCells)
  {
    cloud->SetVerts(verts);
  }
  cloud->GetPointData()->SetNormals(normals);
  cloud->GetPointData()->AddArray(radius);
  cloud->GetPointData()->SetScalars(rgb);
  cloud->GetPointData()->AddArray(intensity);
  return cloud;
}

void TestPolygonsAndData()
{
  const int n = 50;
  vtkSmartPointer<vtkPolyData> cloud = MakeCloud(n, true);
  // Point 7 gets a NaN position, point 9 a zero normal: both skipped, counted.
  cloud->GetPoints()->SetPoint(7, std::nan(""), 0, 0);
  cloud->GetPointData()->GetNormals()->SetTuple3(9, 0, 0, 0);
  for (int shape : { vtkMRGISurfels::Square, vtkMRGISurfels::Hexagon })
  {
    vtkNew<vtkMRGISurfels> surfels;
    surfels->SetInputData(cloud);
    surfels->SetShape(shape);
    surfels->SetRadiusScale(2.0);
    surfels->Update();
    vtkPolyData* out = surfels->GetOutput();
    const int corners = shape;
    const int kept = n - 2;
    MRGI_TEST_CHECK(surfels->GetNumberOfSkippedPoints() == 2);
    MRGI_TEST_CHECK(out->GetNumberOfPolys() == kept);
    MRGI_TEST_CHECK(out->GetNumberOfPoints() == kept * corners);
    MRGI_TEST_CHECK(out->GetNumberOfVerts() == 0);
    MRGI_TEST_CHECK(!out->GetPolys()->IsStorage64Bit());
    vtkDataArray* normals = out->GetPointData()->GetNormals();
    vtkDataArray* rgb = out->GetPointData()->GetScalars();
    vtkDataArray* intensity = out->GetPointData()->GetArray("Intensity");
    MRGI_TEST_CHECK(normals && rgb && intensity);
    MRGI_TEST_CHECK(std::string(rgb->GetName()) == "RGB");
    MRGI_TEST_CHECK(vtkUnsignedCharArray::SafeDownCast(rgb) != nullptr);
    const double factor = corners == 4 ? std::sqrt(vtkMath::Pi() / 2.0)
                                       : std::sqrt(2.0 * vtkMath::Pi() / (3.0 * std::sqrt(3.0)));
    vtkIdType cell = 0;
    for (int i = 0; i < n; ++i)
    {
      if (i == 7 || i == 9)
      {
        continue;
      }
      vtkIdType size;
      const vtkIdType* ids;
      out->GetPolys()->GetCellAtId(cell, size, ids);
      MRGI_TEST_CHECK(size == corners);
      const double r = 2.0 * (0.1 + 0.01 * i);
      for (int k = 0; k < corners; ++k)
      {
        double p[3];
        out->GetPoint(ids[k], p);
        // On the plane z = 1, at the circumradius from the point.
        MRGI_TEST_CHECK(std::abs(p[2] - 1.0) < 1e-5);
        const double d = std::hypot(p[0] - i, p[1] - 2 * i);
        MRGI_TEST_CHECK(std::abs(d - factor * r) < 1e-4);
        double nn[3];
        normals->GetTuple(ids[k], nn);
        MRGI_TEST_CHECK(nn[0] == 0 && nn[1] == 0 && nn[2] == 1);
        MRGI_TEST_CHECK(rgb->GetComponent(ids[k], 0) == i % 256);
        MRGI_TEST_CHECK(rgb->GetComponent(ids[k], 1) == 255 - i % 256);
        MRGI_TEST_CHECK(intensity->GetComponent(ids[k], 0) == 100 + i);
      }
      ++cell;
    }
  }
}

void TestFixedRadiusNoCells()
{
  vtkSmartPointer<vtkPolyData> cloud = MakeCloud(10, false);
  cloud->GetPointData()->RemoveArray("Radius");
  // Double points and normals are converted.
  vtkNew<vtkPoints> doublePoints;
  doublePoints->SetDataTypeToDouble();
  doublePoints->DeepCopy(cloud->GetPoints());
  cloud->SetPoints(doublePoints);
  vtkNew<vtkDoubleArray> doubleNormals;
  doubleNormals->DeepCopy(cloud->GetPointData()->GetNormals());
  doubleNormals->SetName("Normals");
  cloud->GetPointData()->SetNormals(doubleNormals);
  vtkNew<vtkMRGISurfels> surfels;
  surfels->SetInputData(cloud);
  surfels->SetRadius(0.5);
  surfels->Update();
  vtkPolyData* out = surfels->GetOutput();
  MRGI_TEST_CHECK(out->GetNumberOfPolys() == 10);
  MRGI_TEST_CHECK(doublePoints->GetDataType() == VTK_DOUBLE);
  double p[3];
  out->GetPoint(0, p);
  MRGI_TEST_CHECK(std::abs(p[2] - 1.0) < 1e-6);
  MRGI_TEST_CHECK(std::abs(std::hypot(p[0], p[1]) - 0.5 * std::sqrt(vtkMath::Pi() / 2.0)) < 1e-5);
}

void TestLevelOfDetail()
{
  vtkSmartPointer<vtkPolyData> cloud = MakeCloud(10, true);
  vtkNew<vtkMRGISurfels> surfels;
  surfels->SetInputData(cloud);
  surfels->SetMaximumNumberOfSurfels(4); // stride 3: points 0, 3, 6, 9
  surfels->Update();
  vtkPolyData* out = surfels->GetOutput();
  MRGI_TEST_CHECK(surfels->GetStride() == 3);
  MRGI_TEST_CHECK(surfels->GetNumberOfSkippedPoints() == 0);
  MRGI_TEST_CHECK(out->GetNumberOfPolys() == 4);
  vtkDataArray* intensity = out->GetPointData()->GetArray("Intensity");
  for (int j = 0; j < 4; ++j)
  {
    MRGI_TEST_CHECK(intensity->GetComponent(4 * j, 0) == 100 + 3 * j);
    double p[3];
    out->GetPoint(4 * j, p);
    // Radius x sqrt(3): the sparser disks cover the same area.
    const double r = (0.1 + 0.01 * 3 * j) * std::sqrt(3.0) * std::sqrt(vtkMath::Pi() / 2.0);
    MRGI_TEST_CHECK(std::abs(std::hypot(p[0] - 3 * j, p[1] - 6 * j) - r) < 1e-4);
  }
  // An array shorter than the points is left out (never read past its end).
  vtkNew<vtkFloatArray> shortArray;
  shortArray->SetName("Short");
  shortArray->SetNumberOfTuples(3);
  cloud->GetPointData()->AddArray(shortArray);
  surfels->Update();
  MRGI_TEST_CHECK(surfels->GetOutput()->GetPointData()->GetArray("Short") == nullptr);
  MRGI_TEST_CHECK(surfels->GetOutput()->GetPointData()->GetArray("Intensity") != nullptr);
  surfels->SetMaximumNumberOfSurfels(10);
  surfels->Update();
  MRGI_TEST_CHECK(surfels->GetStride() == 1 && surfels->GetOutput()->GetNumberOfPolys() == 10);
}

// The budget from a view follows the pixels the prop's box covers.
void TestSuggestedBudget()
{
  vtkSmartPointer<vtkRenderWindow> window = mrgitest::HeadlessWindow(100, 80);
  vtkNew<vtkRenderer> renderer;
  window->AddRenderer(renderer);
  vtkNew<vtkPlaneSource> plane; // a unit square facing the default camera
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(plane->GetOutputPort());
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  renderer->AddActor(actor);
  renderer->ResetCamera();
  window->Render();
  const vtkIdType one = vtkMRGISurfels::SuggestMaximumNumberOfSurfels(renderer, actor, 1.0);
  const vtkIdType four = vtkMRGISurfels::SuggestMaximumNumberOfSurfels(renderer, actor, 4.0);
  std::printf("budget: %lld at 1 surfel per pixel, %lld at 4\n", static_cast<long long>(one),
    static_cast<long long>(four));
  MRGI_TEST_CHECK(one > 100 && one <= 100 * 80);
  MRGI_TEST_CHECK(std::llabs(static_cast<long long>(four - 4 * one)) <= 4);
  // Half the size on screen: a quarter of the pixels.
  renderer->GetActiveCamera()->Zoom(0.5);
  renderer->ResetCameraClippingRange();
  const vtkIdType far = vtkMRGISurfels::SuggestMaximumNumberOfSurfels(renderer, actor, 1.0);
  MRGI_TEST_CHECK(std::abs(static_cast<double>(far) / one - 0.25) < 0.05);
  MRGI_TEST_CHECK(vtkMRGISurfels::SuggestMaximumNumberOfSurfels(nullptr, actor, 1.0) == 0);
  MRGI_TEST_CHECK(vtkMRGISurfels::SuggestMaximumNumberOfSurfels(renderer, nullptr, 1.0) == 0);
  MRGI_TEST_CHECK(vtkMRGISurfels::SuggestMaximumNumberOfSurfels(renderer, actor, 0.0) == 0);
}

void TestErrorsNameWhatIsMissing()
{
  vtkNew<mrgitest::ErrorCatcher> errors;
  vtkNew<vtkMRGISurfels> surfels;
  surfels->AddObserver(vtkCommand::ErrorEvent, errors);
  // The executive's own "returned failure" follows each error: kept apart.
  vtkNew<mrgitest::ErrorCatcher> executiveErrors;
  surfels->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, executiveErrors);

  vtkSmartPointer<vtkPolyData> cloud = MakeCloud(5, true);
  cloud->GetPointData()->SetNormals(nullptr);
  cloud->GetPointData()->RemoveArray("Normals");
  surfels->SetInputData(cloud);
  surfels->Update();
  MRGI_TEST_CHECK(errors->Caught("no normals"));
  MRGI_TEST_CHECK(surfels->GetOutput()->GetNumberOfPoints() == 0);

  cloud = MakeCloud(5, true);
  cloud->GetPointData()->RemoveArray("Radius");
  surfels->SetInputData(cloud);
  surfels->Update();
  MRGI_TEST_CHECK(errors->Caught("no radius array 'Radius'"));

  // Any 1-component array can be the radius.
  surfels->SetRadiusArrayName("Intensity");
  surfels->Update();
  MRGI_TEST_CHECK(errors->Count == 0 && surfels->GetOutput()->GetNumberOfPolys() == 5);
  surfels->SetNormalsArrayName("Intensity");
  surfels->Update();
  MRGI_TEST_CHECK(errors->Caught("has 1 components; normals need 3"));
  surfels->SetNormalsArrayName(nullptr);

  cloud = MakeCloud(5, true);
  cloud->GetPointData()->GetNormals()->SetNumberOfTuples(4);
  surfels->SetInputData(cloud);
  surfels->Update();
  MRGI_TEST_CHECK(errors->Caught("has 4 tuples for 5 points"));
  cloud = MakeCloud(5, true);
  surfels->SetRadiusArrayName("Radius");
  vtkDataArray::SafeDownCast(cloud->GetPointData()->GetAbstractArray("Radius"))
    ->SetNumberOfTuples(2);
  surfels->SetInputData(cloud);
  surfels->Update();
  MRGI_TEST_CHECK(errors->Caught("has 2 tuples for 5 points"));

  vtkNew<vtkSphereSource> sphere;
  sphere->Update();
  surfels->SetInputData(sphere->GetOutput());
  surfels->Update();
  MRGI_TEST_CHECK(errors->Caught("not a point cloud"));
}

// Counts the warnings of an object that contain two phrases.
struct WarningCount
{
  WarningCount(vtkObject* watched, const char* phrase, const char* other)
    : Phrase(phrase)
    , Other(other)
  {
    this->Observer->SetClientData(this);
    this->Observer->SetCallback(WarningCount::Callback);
    watched->AddObserver(vtkCommand::WarningEvent, this->Observer);
  }
  static void Callback(vtkObject*, unsigned long, void* client, void* data)
  {
    auto* self = static_cast<WarningCount*>(client);
    const std::string text = data ? static_cast<const char*>(data) : "";
    if (text.find(self->Phrase) != std::string::npos && text.find(self->Other) != std::string::npos)
    {
      ++self->Count;
    }
  }
  int Count = 0;
  std::string Phrase, Other;
  vtkNew<vtkCallbackCommand> Observer;
};

// cornell-spot in a headless window, and a cloud sampled from a square on
// its floor (drawn as pixels until a vtkMRGISurfels is put in between).
struct FloorCloudScene
{
  explicit FloorCloudScene(int size, vtkIdType points)
    : Window(mrgitest::HeadlessWindow(size, size))
  {
    this->Window->AddRenderer(this->Renderer);
    vtkNew<vtkMRGISceneBuilder> builder;
    builder->SetScene("cornell-spot");
    MRGI_TEST_CHECK(builder->Build(this->Renderer));
    vtkNew<vtkPlaneSource> plane;
    plane->SetOrigin(100, 1, 100);
    plane->SetPoint1(400, 1, 100);
    plane->SetPoint2(100, 1, 400);
    this->Sampler->SetInputConnection(plane->GetOutputPort());
    this->Sampler->SetNumberOfPoints(points);
    this->PixelsMapper->SetInputConnection(this->Sampler->GetOutputPort());
    this->Pixels->SetMapper(this->PixelsMapper);
    this->Renderer->AddActor(this->Pixels);
  }
  vtkSmartPointer<vtkRenderWindow> Window;
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkMRGIMeshSampler> Sampler;
  vtkNew<vtkPolyDataMapper> PixelsMapper;
  vtkNew<vtkActor> Pixels;
};

void TestPassWarnsOncePerPixelCloud()
{
  FloorCloudScene scene(64, 5000);
  vtkNew<vtkRenderStepsPass> steps;
  vtkNew<vtkMRGIPass> pass;
  pass->SetDelegatePass(steps);
  scene.Renderer->SetPass(pass);
  WarningCount warnings(pass, "points as pixels", "vtkMRGISurfels");
  vtkRenderWindow* window = scene.Window;
  vtkRenderer* renderer = scene.Renderer;
  vtkMRGIMeshSampler* sampler = scene.Sampler;
  vtkPolyDataMapper* pixelsMapper = scene.PixelsMapper;
  vtkActor* pixels = scene.Pixels;
  window->Render();
  window->Render();
  MRGI_TEST_CHECK(warnings.Count == 1);

  // The same cloud as surfels: no warning; the floor under it is covered.
  renderer->RemoveActor(pixels);
  vtkNew<vtkMRGISurfels> surfels;
  surfels->SetInputConnection(sampler->GetOutputPort());
  vtkNew<vtkPolyDataMapper> surfelsMapper;
  surfelsMapper->SetInputConnection(surfels->GetOutputPort());
  vtkNew<vtkActor> disks;
  disks->SetMapper(surfelsMapper);
  renderer->AddActor(disks);
  window->Render();
  MRGI_TEST_CHECK(warnings.Count == 1);
  MRGI_TEST_CHECK(surfels->GetOutput()->GetNumberOfPolys() == 5000);
  MRGI_TEST_CHECK(sampler->GetSampledRadius() > 0.0);

  // A second pixel actor gets its own warning.
  vtkNew<vtkActor> other;
  other->SetMapper(pixelsMapper);
  renderer->AddActor(other);
  window->Render();
  window->Render();
  MRGI_TEST_CHECK(warnings.Count == 2);
}

// The ground truth has no surface for a cloud drawn as vertices: it says so
// (a warning naming the surfels) instead of leaving the cloud out silently;
// the same cloud as surfels is in its scene and raises no warning.
void TestReferenceWarnsOnPixelCloud()
{
  FloorCloudScene floor(32, 2000);
  vtkRenderer* renderer = floor.Renderer;
  WarningCount warnings(renderer, "draw only vertices", "vtkMRGISurfels");

  mrgi_scene scene;
  std::string why;
  MRGI_TEST_CHECK(vtkMRGIReferenceRenderer::ExportScene(renderer, &scene, why));
  const int32_t meshesWithPixels = scene.mesh_count;
  mrgi_scene_destroy(&scene);
  MRGI_TEST_CHECK(warnings.Count == 1);

  vtkNew<vtkMRGISurfels> surfels;
  surfels->SetInputConnection(floor.Sampler->GetOutputPort());
  floor.PixelsMapper->SetInputConnection(surfels->GetOutputPort());
  MRGI_TEST_CHECK(vtkMRGIReferenceRenderer::ExportScene(renderer, &scene, why));
  MRGI_TEST_CHECK(scene.mesh_count == meshesWithPixels + 1);
  mrgi_scene_destroy(&scene);
  MRGI_TEST_CHECK(warnings.Count == 1);
}

// The area light's voxelization and visibility see surfels: a cloud sampled
// from a downward-facing plate under the Cornell box's ceiling light
// shadows what is under it, as the plate itself would.
void TestAreaLightShadowFromSurfels()
{
  mrgitest::PassScene scene(64, 64, "cornell-area");
  vtkRenderWindow* window = scene.Window;
  vtkRenderer* renderer = scene.Renderer;
  vtkMRGIPass* pass = scene.Pass;
  MRGI_TEST_CHECK(scene.Builder->GetNumberOfAreaLights() == 1);
  pass->SetIndirectMode(vtkMRGIPass::IndirectOff);
  pass->AddAreaLight(scene.Builder->GetAreaLight(0));
  auto mean = [&]() {
    window->Render();
    vtkSmartPointer<vtkImageData> area = mrgitest::AreaBuffer(pass, window);
    vtkDataArray* values = area->GetPointData()->GetScalars();
    double sum = 0.0;
    for (vtkIdType i = 0; i < values->GetNumberOfValues(); ++i)
    {
      const double v = values->GetVariantValue(i).ToDouble();
      MRGI_TEST_CHECK(std::isfinite(v));
      sum += v;
    }
    return sum / static_cast<double>(values->GetNumberOfValues());
  };
  const double open = mean();
  pass->SetAreaLightVisibility(0);
  const double openUnshadowed = mean();
  pass->SetAreaLightVisibility(2);

  vtkNew<vtkPlaneSource> plate; // normal (0, -1, 0): its front faces the floor
  plate->SetOrigin(130, 400, 130);
  plate->SetPoint1(420, 400, 130);
  plate->SetPoint2(130, 400, 420);
  vtkNew<vtkMRGIMeshSampler> sampler;
  sampler->SetInputConnection(plate->GetOutputPort());
  sampler->SetNumberOfPoints(20000);
  vtkNew<vtkMRGISurfels> surfels;
  surfels->SetInputConnection(sampler->GetOutputPort());
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(surfels->GetOutputPort());
  vtkNew<vtkActor> blocker;
  blocker->SetMapper(mapper);
  renderer->AddActor(blocker);
  const double shadowed = mean();
  // Without shadows the plate still hides what is behind it from the camera
  // but lights what is under it: the ratio of shadowed to unshadowed light
  // must drop below the open box's (whose blocks cast shadows too).
  pass->SetAreaLightVisibility(0);
  const double unshadowed = mean();
  std::printf("area light, mean over the image (shadows on / off): open box %.5f / %.5f, with "
              "the surfel plate %.5f / %.5f\n",
    open, openUnshadowed, shadowed, unshadowed);
  MRGI_TEST_CHECK(open > 0.0 && unshadowed > 0.0);
  MRGI_TEST_CHECK(shadowed / unshadowed < 0.85 * (open / openUnshadowed));
}
}

int main(int argc, char* argv[])
{
  return mrgitest::RunCases(argc, argv,
    { MRGI_TEST_CASE(TestPolygonsAndData), MRGI_TEST_CASE(TestFixedRadiusNoCells),
      MRGI_TEST_CASE(TestLevelOfDetail), MRGI_TEST_CASE(TestSuggestedBudget),
      MRGI_TEST_CASE(TestErrorsNameWhatIsMissing), MRGI_TEST_CASE(TestPassWarnsOncePerPixelCloud),
      MRGI_TEST_CASE(TestReferenceWarnsOnPixelCloud),
      MRGI_TEST_CASE(TestAreaLightShadowFromSurfels) });
}
