// vtkMRGISceneBuilder: every built-in scene builds; every supported file
// format loads (files written here by VTK's writers, a hand-made glTF);
// volumetric data sets become their surface; bad input is a clear error that
// leaves the renderer unchanged. The living room brings its textured TV
// screen as an area light, which vtkMRGIPass renders headless.
#include "mrgiTestUtilities.h"

#include "vtkActorCollection.h"
#include "vtkDataArray.h"
#include "vtkDataSetSurfaceFilter.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMRGIAreaLight.h"
#include "vtkMRGIPass.h"
#include "vtkMRGISceneBuilder.h"
#include "vtkPLYWriter.h"
#include "vtkPolyData.h"
#include "vtkRTAnalyticSource.h"
#include "vtkRenderStepsPass.h"
#include "vtkRenderer.h"
#include "vtkSTLWriter.h"
#include "vtkSphereSource.h"
#include "vtkTriangleFilter.h"
#include "vtkUnstructuredGrid.h"
#include "vtkDataSetTriangleFilter.h"
#include "vtkXMLImageDataWriter.h"
#include "vtkXMLPolyDataWriter.h"

#include "mrgi_area_light.h"
#include "vtkXMLUnstructuredGridWriter.h"
#include "vtkPolyDataWriter.h"

#include <cstring>
#include <fstream>

namespace
{
int ActorCount(vtkRenderer* r)
{
  return r->GetActors()->GetNumberOfItems();
}

// Builds `scene` into a fresh renderer; returns the number of actors (-1 on error).
int BuildInto(const std::string& scene, vtkIdType* triangles = nullptr, std::string* error = nullptr)
{
  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkMRGISceneBuilder> builder;
  builder->SetScene(scene.c_str());
  builder->SetTriangleCount(20000);
  builder->SetObjectCount(9);
  const bool ok = builder->Build(renderer);
  if (triangles)
  {
    *triangles = builder->GetBuiltTriangleCount();
  }
  if (error)
  {
    *error = builder->GetLastErrorMessage();
  }
  if (!ok)
  {
    MRGI_TEST_CHECK(ActorCount(renderer) == 0);
    MRGI_TEST_CHECK(std::strlen(builder->GetLastErrorMessage()) > 10);
  }
  return ok ? ActorCount(renderer) : -1;
}

void WriteText(const std::string& path, const std::string& text)
{
  std::ofstream out(path, std::ios::binary);
  out << text;
}

// Finite values of `image` (all components), their sum (RGB) and how many
// pixels have any RGB above `floor`.
void Survey(vtkImageData* image, double floor, double* sum, vtkIdType* bright)
{
  vtkDataArray* a = image->GetPointData()->GetScalars();
  MRGI_TEST_CHECK(a && a->GetNumberOfComponents() >= 3);
  *sum = 0.0;
  *bright = 0;
  for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i)
  {
    bool lit = false;
    for (int c = 0; c < a->GetNumberOfComponents(); ++c)
    {
      const double v = a->GetComponent(i, c);
      MRGI_TEST_CHECK(std::isfinite(v) && v >= 0.0);
      if (c < 3)
      {
        *sum += v;
        lit = lit || v > floor;
      }
    }
    *bright += lit ? 1 : 0;
  }
}

// "living-room": the meshes, one textured area light from the core scene
// (rows flipped to VTK's bottom-up order), the dark vtkLight that keeps
// VTK's lighting on, and a headless frame of vtkMRGIPass lit by the screen.
void TestLivingRoom()
{
  const int W = 96, H = 64;
  vtkSmartPointer<vtkRenderWindow> window = mrgitest::HeadlessWindow(W, H);
  vtkNew<vtkRenderer> renderer;
  window->AddRenderer(renderer);
  vtkNew<vtkMRGISceneBuilder> builder;
  builder->SetScene("living-room");
  MRGI_TEST_CHECK(vtkMRGISceneBuilder::IsBuiltInScene("living-room"));
  MRGI_TEST_CHECK(std::strstr(vtkMRGISceneBuilder::GetBuiltInSceneNames(), "living-room"));
  MRGI_TEST_CHECK(builder->Build(renderer));
  MRGI_TEST_CHECK(ActorCount(renderer) == 13); // 6 walls, 6 furniture meshes, the screen
  std::printf("living-room: %lld triangles\n", static_cast<long long>(builder->GetBuiltTriangleCount()));
  MRGI_TEST_CHECK(builder->GetBuiltTriangleCount() > 100);
  MRGI_TEST_CHECK(renderer->GetLights()->GetNumberOfItems() == 1);
  auto* dark = vtkLight::SafeDownCast(renderer->GetLights()->GetItemAsObject(0));
  MRGI_TEST_CHECK(dark && dark->GetIntensity() == 0.0);

  MRGI_TEST_CHECK(builder->GetNumberOfAreaLights() == 1);
  vtkMRGIAreaLight* screen = builder->GetAreaLight(0);
  MRGI_TEST_CHECK(screen && !screen->GetTwoSided() && !screen->GetVisible());
  MRGI_TEST_CHECK(screen->GetIntensity() == 40.0);
  MRGI_TEST_CHECK(std::fabs(screen->GetEdgeU()[0] - 1.2) < 1e-12 && std::fabs(screen->GetEdgeV()[1] - 0.7) < 1e-12);
  vtkImageData* texture = screen->GetTextureData();
  MRGI_TEST_CHECK(texture);
  int dims[3];
  texture->GetDimensions(dims);
  MRGI_TEST_CHECK(dims[0] == 64 && dims[1] == 36 && texture->GetNumberOfScalarComponents() == 3);
  // Bottom-up: the top-left texel (the white colour bar) is VTK's row 35,
  // the bottom-left (the ramp's darkest step) row 0.
  const float topLeft = texture->GetScalarComponentAsFloat(0, 35, 0, 0);
  const float bottomLeft = texture->GetScalarComponentAsFloat(0, 0, 0, 0);
  MRGI_TEST_CHECK(topLeft == 0.75f && bottomLeft < 0.05f);
  mrgi_area_light core;
  MRGI_TEST_CHECK(screen->GetCoreLight(&core));

  vtkNew<vtkRenderStepsPass> steps;
  vtkNew<vtkMRGIPass> pass;
  pass->SetDelegatePass(steps);
  pass->AddAreaLight(screen);
  renderer->SetPass(pass);
  window->Render();
  MRGI_TEST_CHECK(pass->GetAreaLightsComputed());

  vtkNew<vtkImageData> color, area;
  MRGI_TEST_CHECK(pass->GetColorBuffer(window, color));
  MRGI_TEST_CHECK(pass->GetAreaLightBuffer(window, area));
  double colorSum = 0.0, areaSum = 0.0;
  vtkIdType colorLit = 0, areaLit = 0;
  Survey(color, 1e-3, &colorSum, &colorLit);
  Survey(area, 1e-3, &areaSum, &areaLit);
  std::printf("living-room frame %dx%d: %lld pixels lit by the screen (mean %.4f), %lld non-black "
              "(mean %.4f)\n",
    W, H, static_cast<long long>(areaLit), areaSum / (3.0 * W * H), static_cast<long long>(colorLit),
    colorSum / (3.0 * W * H));
  // The emitter quad alone covers far less than a tenth of the frame; the
  // screen lights most of the room, less what the furniture shadows (about
  // half the frame stays lit with the default voxel visibility).
  MRGI_TEST_CHECK(areaLit > W * H * 2 / 5);
  MRGI_TEST_CHECK(colorLit > W * H * 2 / 5);
  vtkNew<vtkMRGIImageIO> io;
  const std::string exr = mrgitest::TempPath("living-room.exr");
  const std::string png = mrgitest::TempPath("living-room.png");
  MRGI_TEST_CHECK(io->Write(color, exr.c_str()));
  MRGI_TEST_CHECK(io->WritePNG(mrgitest::GrabRGB(window), png.c_str()));
  std::printf("wrote %s and %s\n", exr.c_str(), png.c_str());
  renderer->SetPass(nullptr);
  pass->ReleaseGraphicsResources(window);
}

// The built-in scenes: their actors, triangles and lights.
void TestBuiltInScenes()
{
  vtkIdType triangles = 0;
  MRGI_TEST_CHECK(BuildInto("cornell", &triangles) >= 7);
  MRGI_TEST_CHECK(triangles >= 30);
  MRGI_TEST_CHECK(BuildInto("cornell-spot") >= 7);
  MRGI_TEST_CHECK(BuildInto("cornell-area") >= 8); // the emitter is drawn
  MRGI_TEST_CHECK(BuildInto("living-room", &triangles) == 13);
  MRGI_TEST_CHECK(BuildInto("scaling", &triangles) >= 10);
  std::printf("scaling: %lld triangles for 20000 asked\n", static_cast<long long>(triangles));
  MRGI_TEST_CHECK(triangles >= 18000 && triangles <= 22000);
  // The indirect-light scenes (mrgi_scene_indirect.h): their meshes, one
  // spot each, listed among the names; a near miss is refused by name.
  const struct
  {
    const char* Name;
    int Actors;
  } indirect[] = { { "corridor", 7 }, { "corridor-large", 7 }, { "corner", 3 }, { "u-shape", 4 } };
  for (const auto& scene : indirect)
  {
    MRGI_TEST_CHECK(vtkMRGISceneBuilder::IsBuiltInScene(scene.Name));
    MRGI_TEST_CHECK(std::strstr(vtkMRGISceneBuilder::GetBuiltInSceneNames(), scene.Name));
    MRGI_TEST_CHECK(BuildInto(scene.Name, &triangles) == scene.Actors);
    std::printf("%s: %lld triangles\n", scene.Name, static_cast<long long>(triangles));
    vtkNew<vtkRenderer> renderer;
    vtkNew<vtkMRGISceneBuilder> builder;
    builder->SetScene(scene.Name);
    MRGI_TEST_CHECK(builder->Build(renderer));
    MRGI_TEST_CHECK(renderer->GetLights()->GetNumberOfItems() == 1);
    auto* spot = vtkLight::SafeDownCast(renderer->GetLights()->GetItemAsObject(0));
    MRGI_TEST_CHECK(spot && spot->GetPositional() && spot->GetConeAngle() < 90.0);
  }
  std::string error;
  MRGI_TEST_CHECK(!vtkMRGISceneBuilder::IsBuiltInScene("corridor-xl"));
  MRGI_TEST_CHECK(BuildInto("corridor-xl", nullptr, &error) == -1);
  std::printf("corridor-xl: %s\n", error.c_str());
  MRGI_TEST_CHECK(error.find("corridor-xl") != std::string::npos);
  {
    vtkNew<vtkRenderer> renderer;
    vtkNew<vtkMRGISceneBuilder> builder;
    builder->SetScene("cornell-spot");
    MRGI_TEST_CHECK(builder->Build(renderer));
    MRGI_TEST_CHECK(renderer->GetLights()->GetNumberOfItems() == 1);
    MRGI_TEST_CHECK(!renderer->GetAutomaticLightCreation());
  }
}

// Files written by VTK's writers, OBJ and glTF written by hand.
void TestWrittenFiles()
{
  vtkIdType triangles = 0;
  std::string error;
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(16);
  sphere->SetPhiResolution(8);
  sphere->Update();
  const std::string vtp = mrgitest::TempPath("scene.vtp");
  const std::string stl = mrgitest::TempPath("scene.stl");
  const std::string ply = mrgitest::TempPath("scene.ply");
  const std::string vtk = mrgitest::TempPath("scene.vtk");
  const std::string vti = mrgitest::TempPath("scene.vti");
  const std::string vtu = mrgitest::TempPath("scene.vtu");
  {
    vtkNew<vtkXMLPolyDataWriter> w;
    w->SetInputConnection(sphere->GetOutputPort());
    w->SetFileName(vtp.c_str());
    MRGI_TEST_CHECK(w->Write() == 1);
    vtkNew<vtkSTLWriter> s;
    s->SetInputConnection(sphere->GetOutputPort());
    s->SetFileName(stl.c_str());
    MRGI_TEST_CHECK(s->Write() == 1);
    vtkNew<vtkPLYWriter> p;
    p->SetInputConnection(sphere->GetOutputPort());
    p->SetFileName(ply.c_str());
    MRGI_TEST_CHECK(p->Write() == 1);
    vtkNew<vtkPolyDataWriter> l;
    l->SetInputConnection(sphere->GetOutputPort());
    l->SetFileName(vtk.c_str());
    MRGI_TEST_CHECK(l->Write() == 1);
  }
  {
    vtkNew<vtkRTAnalyticSource> volume; // 21^3 image data with scalars
    volume->SetWholeExtent(0, 10, 0, 10, 0, 10);
    vtkNew<vtkXMLImageDataWriter> w;
    w->SetInputConnection(volume->GetOutputPort());
    w->SetFileName(vti.c_str());
    MRGI_TEST_CHECK(w->Write() == 1);
    vtkNew<vtkDataSetTriangleFilter> tets;
    tets->SetInputConnection(volume->GetOutputPort());
    vtkNew<vtkXMLUnstructuredGridWriter> u;
    u->SetInputConnection(tets->GetOutputPort());
    u->SetFileName(vtu.c_str());
    MRGI_TEST_CHECK(u->Write() == 1);
  }
  for (const std::string& path : { vtp, stl, ply, vtk })
  {
    MRGI_TEST_CHECK(BuildInto(path, &triangles) == 1);
    std::printf("%s: %lld triangles\n", path.c_str(), static_cast<long long>(triangles));
    MRGI_TEST_CHECK(triangles == sphere->GetOutput()->GetNumberOfPolys());
  }
  // Volumes become their outer surface: 6 faces of 10x10 quads.
  MRGI_TEST_CHECK(BuildInto(vti, &triangles) == 1);
  std::printf("vti surface: %lld cells\n", static_cast<long long>(triangles));
  MRGI_TEST_CHECK(triangles == 600);
  MRGI_TEST_CHECK(BuildInto(vtu, &triangles) == 1);
  std::printf("vtu surface: %lld cells\n", static_cast<long long>(triangles));
  MRGI_TEST_CHECK(triangles >= 600);

  // OBJ and glTF, written by hand.
  const std::string obj = mrgitest::TempPath("scene.obj");
  WriteText(obj, "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n");
  MRGI_TEST_CHECK(BuildInto(obj, &triangles) == 1);
  MRGI_TEST_CHECK(triangles == 2);
  // One triangle: 3 float positions (36 bytes), base64 embedded.
  const std::string gltf = mrgitest::TempPath("scene.gltf");
  WriteText(gltf,
    R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
    R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],)"
    R"("buffers":[{"byteLength":36,"uri":"data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}],)"
    R"("bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":36}],)"
    R"("accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","max":[1,1,0],"min":[0,0,0]}]})");
  MRGI_TEST_CHECK(BuildInto(gltf, &triangles, &error) == 1);
  MRGI_TEST_CHECK(triangles == 1);
}

// Real third-party data, when it is beside the checkout.
void TestSharedData()
{
  vtkIdType triangles = 0;
  const char* shared = std::getenv("MRGI_SHARED_DATA_DIR");
  if (shared)
  {
    const std::string iron = std::string(shared) + "/ironProt.vtk";
    std::ifstream probe(iron);
    if (probe.good())
    {
      MRGI_TEST_CHECK(BuildInto(iron, &triangles) == 1);
      std::printf("ironProt.vtk surface: %lld cells\n", static_cast<long long>(triangles));
      MRGI_TEST_CHECK(triangles == 6 * 67 * 67);
    }
  }
}

// Flat data files are looked at face on: each wall, the floor, the ceiling
// and the light of the published Cornell box (separate OBJ files, some of
// them slightly skewed quads) covers a good part of the default view.
void TestFlatFilesFaceOn()
{
  const char* shared = std::getenv("MRGI_SHARED_DATA_DIR");
  if (!shared)
  {
    std::printf("MRGI_SHARED_DATA_DIR not set: flat files not checked\n");
    return;
  }
  const char* names[] = { "back", "ceiling", "floor", "greenwall", "luminaire", "redwall" };
  for (const char* name : names)
  {
    const std::string path = std::string(shared) + "/cornell_box/meshes/cbox_" + name + ".obj";
    if (!std::ifstream(path).good())
    {
      std::printf("%s missing: not checked\n", path.c_str());
      continue;
    }
    vtkSmartPointer<vtkRenderWindow> window = mrgitest::HeadlessWindow(64, 64);
    vtkNew<vtkRenderer> renderer;
    window->AddRenderer(renderer);
    vtkNew<vtkMRGISceneBuilder> builder;
    builder->SetScene(path.c_str());
    MRGI_TEST_CHECK(builder->Build(renderer));
    renderer->SetBackground(0, 0, 0);
    window->Render();
    vtkSmartPointer<vtkImageData> image = mrgitest::GrabRGB(window);
    vtkIdType drawn = 0;
    const vtkIdType n = static_cast<vtkIdType>(64) * 64;
    for (vtkIdType i = 0; i < n; ++i)
    {
      drawn += image->GetPointData()->GetScalars()->GetComponent(i, 0) > 10 ? 1 : 0;
    }
    std::printf("cbox_%s.obj: %lld of %lld pixels drawn\n", name, static_cast<long long>(drawn),
      static_cast<long long>(n));
    MRGI_TEST_CHECK(drawn > n / 5);
  }
}

// Bad input: each a clear error naming the problem.
void TestBadInput()
{
  std::string error;
  MRGI_TEST_CHECK(BuildInto("", nullptr, &error) == -1);
  MRGI_TEST_CHECK(error.find("no scene") != std::string::npos);
  MRGI_TEST_CHECK(BuildInto(mrgitest::TempPath("missing.ply"), nullptr, &error) == -1);
  MRGI_TEST_CHECK(error.find("cannot open") != std::string::npos);
  const std::string unknown = mrgitest::TempPath("scene.xyz");
  WriteText(unknown, "1 2 3\n");
  MRGI_TEST_CHECK(BuildInto(unknown, nullptr, &error) == -1);
  MRGI_TEST_CHECK(error.find("unknown extension") != std::string::npos);
  const std::string empty = mrgitest::TempPath("empty.stl");
  WriteText(empty, "");
  MRGI_TEST_CHECK(BuildInto(empty, nullptr, &error) == -1);
  MRGI_TEST_CHECK(error.find("empty") != std::string::npos);
  const std::string corrupt = mrgitest::TempPath("corrupt.ply");
  WriteText(corrupt, "ply\nformat ascii 1.0\nelement vertex 99\nproperty float x\nend_header\n1\n");
  MRGI_TEST_CHECK(BuildInto(corrupt, nullptr, &error) == -1);
  std::printf("corrupt ply: %s\n", error.c_str());
  const std::string badVtp = mrgitest::TempPath("corrupt.vtp");
  WriteText(badVtp, "<VTKFile type=\"PolyData\"><PolyData><Piece NumberOfPoints=\"5\">");
  MRGI_TEST_CHECK(BuildInto(badVtp, nullptr, &error) == -1);
  std::printf("corrupt vtp: %s\n", error.c_str());
}
}

int main(int argc, char* argv[])
{
  return mrgitest::RunCases(argc, argv,
    { MRGI_TEST_CASE(TestBuiltInScenes), MRGI_TEST_CASE(TestLivingRoom),
      MRGI_TEST_CASE(TestWrittenFiles), MRGI_TEST_CASE(TestSharedData),
      MRGI_TEST_CASE(TestFlatFilesFaceOn),
      MRGI_TEST_CASE(TestBadInput) });
}
