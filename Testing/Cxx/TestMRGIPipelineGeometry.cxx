// vtkMRGIPass with the geometry real pipelines produce:
// 1. vtkCompositePolyDataMapper2 drawing a vtkMultiBlockDataSet (nested
//    blocks, a per-block colour): the G-buffer holds every block (albedo of
//    the recoloured block = block colour x Diffuse), the reflective shadow map
//    holds them (ReadView: valid texels inside the blocks' bounds, flux > 0),
//    indirect light is computed;
// 2. polygons without normals (VTK derives them per fragment): G-buffer
//    normals are unit vectors facing the viewer and match the facets' true
//    normals; the RSM normals are unit vectors too;
// 3. parallel projection: G-buffer positions are exactly where the
//    orthographic camera puts them, normals still face the viewer, indirect
//    light is computed, positive and finite.
// With IndirectMode Off every image is VTK's own (max difference 1/255).
#include "TestMRGIPipelineCommon.h"

#include "vtkCompositeDataDisplayAttributes.h"
#include "vtkCompositePolyDataMapper2.h"
#include "vtkCubeSource.h"
#include "vtkLight.h"
#include "vtkMRGIReflectiveShadowMapPass.h"
#include "vtkMultiBlockDataSet.h"

namespace
{
vtkSmartPointer<vtkPolyData> Output(vtkPolyDataAlgorithm* source)
{
  source->Update();
  auto copy = vtkSmartPointer<vtkPolyData>::New();
  copy->DeepCopy(source->GetOutput());
  return copy;
}

// Render with VTK alone and with MRGI (IndirectMode Off): the same image.
void CheckOffIsVTK(vtkRenderWindow* window, vtkRenderer* renderer, vtkMRGIPass* pass)
{
  renderer->SetPass(nullptr);
  window->Render();
  vtkSmartPointer<vtkImageData> plain = mrgitest::GrabRGB(window);
  renderer->SetPass(pass);
  pass->SetIndirectMode(vtkMRGIPass::IndirectOff);
  window->Render();
  vtkSmartPointer<vtkImageData> off = mrgitest::GrabRGB(window);
  const double diff = mrgipipe::MaxDifference(plain, off);
  std::printf("IndirectMode Off vs VTK: max difference %.0f / 255\n", diff);
  MRGI_TEST_CHECK(diff <= 1.0);
  pass->SetIndirectMode(vtkMRGIPass::IndirectFull);
}

// Every valid G-buffer normal is a unit vector facing the viewer; returns
// how many there are. Interpolated vertex normals may lean up to `slack`
// away from the eye along silhouettes (VTK shades with them as they are);
// the normals VTK derives for normal-less polygons always face the eye.
// Only pixels whose albedo's blue channel is `blue` are looked at, unless
// `blue` is negative.
int CheckNormalsFaceViewer(vtkImageData* position, vtkImageData* normal, vtkImageData* albedo,
  bool parallel, double slack, double blue = -1)
{
  int dims[3];
  normal->GetDimensions(dims);
  int n = 0;
  double worstLength = 0, worstFacing = 1;
  for (int y = 0; y < dims[1]; ++y)
  {
    for (int x = 0; x < dims[0]; ++x)
    {
      if (!mrgipipe::Valid(normal, x, y) ||
        (blue >= 0 && std::fabs(mrgipipe::At(albedo, x, y, 2) - blue) > 0.003))
      {
        continue;
      }
      ++n;
      double v[3], p[3];
      for (int c = 0; c < 3; ++c)
      {
        v[c] = mrgipipe::At(normal, x, y, c);
        p[c] = mrgipipe::At(position, x, y, c);
      }
      const double length = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
      worstLength = std::max(worstLength, std::fabs(length - 1.0));
      // Towards the eye: -p in perspective, +z in parallel projection.
      const double toEye[3] = { parallel ? 0.0 : -p[0], parallel ? 0.0 : -p[1],
        parallel ? 1.0 : -p[2] };
      const double facing = (v[0] * toEye[0] + v[1] * toEye[1] + v[2] * toEye[2]) /
        std::sqrt(toEye[0] * toEye[0] + toEye[1] * toEye[1] + toEye[2] * toEye[2]);
      worstFacing = std::min(worstFacing, facing);
    }
  }
  std::printf("%d G-buffer normals: worst |length - 1| %.4f, worst cos to the eye %.4f\n", n,
    worstLength, worstFacing);
  MRGI_TEST_CHECK(worstLength < 0.003);
  MRGI_TEST_CHECK(worstFacing > -slack);
  return n;
}
}

int main()
{
  using namespace mrgipipe;
  const int W = 160, H = 120;
  vtkSmartPointer<vtkRenderWindow> window = mrgitest::HeadlessWindow(W, H);
  vtkNew<vtkRenderer> renderer;
  window->AddRenderer(renderer);

  // 1. A multiblock: floor, back wall, a nested block holding a cube and a
  // sphere; the sphere recoloured through the mapper's display attributes.
  vtkNew<vtkPlaneSource> floorSource;
  floorSource->SetOrigin(-2, -1, 2);
  floorSource->SetPoint1(2, -1, 2);
  floorSource->SetPoint2(-2, -1, -2);
  vtkNew<vtkPlaneSource> wallSource;
  wallSource->SetOrigin(-2, -1, -1.5);
  wallSource->SetPoint1(2, -1, -1.5);
  wallSource->SetPoint2(-2, 2, -1.5);
  vtkNew<vtkCubeSource> cubeSource;
  cubeSource->SetCenter(-0.8, -0.5, 0);
  vtkNew<vtkSphereSource> sphereSource;
  sphereSource->SetCenter(0.8, -0.4, 0);
  sphereSource->SetRadius(0.6);
  sphereSource->SetThetaResolution(24);
  sphereSource->SetPhiResolution(24);
  vtkSmartPointer<vtkPolyData> sphere = Output(sphereSource);
  vtkNew<vtkMultiBlockDataSet> nested;
  nested->SetNumberOfBlocks(2);
  nested->SetBlock(0, Output(cubeSource));
  nested->SetBlock(1, sphere);
  vtkNew<vtkMultiBlockDataSet> blocks;
  blocks->SetNumberOfBlocks(3);
  blocks->SetBlock(0, Output(floorSource));
  blocks->SetBlock(1, Output(wallSource));
  blocks->SetBlock(2, nested);
  vtkNew<vtkCompositePolyDataMapper2> compositeMapper;
  compositeMapper->SetInputDataObject(blocks);
  vtkNew<vtkCompositeDataDisplayAttributes> attributes;
  compositeMapper->SetCompositeDataDisplayAttributes(attributes);
  const double sphereColour[3] = { 0.9, 0.15, 0.1 };
  attributes->SetBlockColor(sphere, sphereColour);
  vtkNew<vtkActor> composite;
  composite->SetMapper(compositeMapper);
  composite->GetProperty()->SetColor(0.8, 0.8, 0.8);
  composite->GetProperty()->SetDiffuse(0.9);
  composite->GetProperty()->SetSpecular(0);
  renderer->AddActor(composite);

  vtkNew<vtkLight> light;
  light->SetLightTypeToSceneLight();
  light->SetPositional(true);
  light->SetConeAngle(50);
  light->SetPosition(0.5, 2.5, 2.0);
  light->SetFocalPoint(0, -0.8, 0);
  renderer->AddLight(light);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(0, 0.8, 5);
  camera->SetFocalPoint(0, -0.3, 0);
  camera->SetViewAngle(40);
  renderer->ResetCameraClippingRange();

  vtkSmartPointer<vtkMRGIPass> pass = Install(renderer);
  pass->SetRSMResolution(128);
  CheckOffIsVTK(window, renderer, pass);
  window->Render();
  DebugWrite(mrgitest::GrabRGB(window), "TestMRGIPipelineGeometry-composite");
  MRGI_TEST_CHECK(pass->GetIndirectComputed());
  vtkNew<vtkImageData> position, normal, albedo, indirect;
  MRGI_TEST_CHECK(pass->GetGBuffer(window, position, normal, albedo));
  MRGI_TEST_CHECK(pass->GetIndirectBuffer(window, indirect));
  MRGI_TEST_CHECK(AllFinite(indirect) && AllFinite(position) && AllFinite(normal));
  // Every block is in the G-buffer, at the pixel its centre projects to.
  struct Probe
  {
    const char* What;
    double World[3];
    double Albedo[3];
  } probes[] = { { "floor", { 0, -1, 1.2 }, { 0.72, 0.72, 0.72 } },
    { "wall", { 0, 1.2, -1.5 }, { 0.72, 0.72, 0.72 } },
    { "cube (nested block)", { -0.8, -0.5, 0.5 }, { 0.72, 0.72, 0.72 } },
    { "sphere (nested, block colour)", { 0.8, -0.4, 0.6 },
      { 0.9 * sphereColour[0], 0.9 * sphereColour[1], 0.9 * sphereColour[2] } } };
  for (const Probe& probe : probes)
  {
    renderer->SetWorldPoint(probe.World[0], probe.World[1], probe.World[2], 1.0);
    renderer->WorldToDisplay();
    const int x = static_cast<int>(renderer->GetDisplayPoint()[0]);
    const int y = static_cast<int>(renderer->GetDisplayPoint()[1]);
    MRGI_TEST_CHECK(x > 0 && y > 0 && x < W && y < H);
    double eye[3];
    WorldToEye(renderer, probe.World, eye);
    std::printf("%-30s pixel %d %d: z %.3f (expected %.3f), albedo %.3f %.3f %.3f\n", probe.What, x,
      y, At(position, x, y, 2), eye[2], At(albedo, x, y, 0), At(albedo, x, y, 1),
      At(albedo, x, y, 2));
    MRGI_TEST_CHECK(Valid(position, x, y));
    MRGI_TEST_CHECK(std::fabs(At(position, x, y, 2) - eye[2]) < 0.05);
    for (int c = 0; c < 3; ++c)
    {
      MRGI_TEST_CHECK(std::fabs(At(albedo, x, y, c) - probe.Albedo[c]) < 0.003);
    }
  }
  // The RSM holds the blocks: valid texels, inside the multiblock's bounds, with flux.
  vtkMRGIReflectiveShadowMapPass* rsm = pass->GetReflectiveShadowMapPass();
  MRGI_TEST_CHECK(rsm->GetNumberOfViews() == 1);
  vtkNew<vtkImageData> rsmPosition, rsmNormal, rsmFlux;
  MRGI_TEST_CHECK(rsm->ReadView(window, 0, rsmPosition, rsmNormal, rsmFlux));
  double bounds[6];
  composite->GetBounds(bounds);
  int valid = 0, outside = 0;
  double flux = 0, worstNormal = 0;
  for (int y = 0; y < 128; ++y)
  {
    for (int x = 0; x < 128; ++x)
    {
      if (!Valid(rsmPosition, x, y))
      {
        continue;
      }
      ++valid;
      for (int k = 0; k < 3; ++k)
      {
        const double v = At(rsmPosition, x, y, k);
        outside += (v < bounds[2 * k] - 1e-3 || v > bounds[2 * k + 1] + 1e-3) ? 1 : 0;
      }
      flux += At(rsmFlux, x, y, 0) + At(rsmFlux, x, y, 1) + At(rsmFlux, x, y, 2);
      const double n = std::sqrt(At(rsmNormal, x, y, 0) * At(rsmNormal, x, y, 0) +
        At(rsmNormal, x, y, 1) * At(rsmNormal, x, y, 1) +
        At(rsmNormal, x, y, 2) * At(rsmNormal, x, y, 2));
      worstNormal = std::max(worstNormal, std::fabs(n - 1.0));
    }
  }
  std::printf(
    "RSM: %d valid texels, %d coordinates outside the bounds, flux %.4f\n", valid, outside, flux);
  MRGI_TEST_CHECK(valid > 128 * 128 / 4);
  MRGI_TEST_CHECK(outside == 0);
  MRGI_TEST_CHECK(flux > 0 && std::isfinite(flux));
  MRGI_TEST_CHECK(worstNormal < 0.003);
  // Red light from the sphere lands on the floor next to it.
  MRGI_TEST_CHECK(SumRGB(indirect, 0, 0, W, H) > 0);
  CheckNormalsFaceViewer(position, normal, albedo, false, 0.1);

  // 2. The same blocks and two more props without normals: VTK derives
  // per-fragment normals; so must the G-buffer.
  vtkNew<vtkSphereSource> bareSphereSource;
  bareSphereSource->SetCenter(0, 0.6, -0.6);
  bareSphereSource->SetRadius(0.45);
  bareSphereSource->SetThetaResolution(16);
  bareSphereSource->SetPhiResolution(16);
  vtkSmartPointer<vtkPolyData> bareSphere = Output(bareSphereSource);
  bareSphere->GetPointData()->SetNormals(nullptr);
  vtkNew<vtkPlaneSource> tiltedSource;
  tiltedSource->SetCenter(-1.2, 0.8, -0.8);
  tiltedSource->SetNormal(0.5, 0.2, 1.0);
  vtkSmartPointer<vtkPolyData> tilted = Output(tiltedSource);
  tilted->GetPointData()->SetNormals(nullptr);
  tilted->GetPointData()->SetTCoords(nullptr);
  MRGI_TEST_CHECK(
    !bareSphere->GetPointData()->GetNormals() && !tilted->GetPointData()->GetNormals());
  vtkNew<vtkPolyDataMapper> bareMapper, tiltedMapper;
  bareMapper->SetInputData(bareSphere);
  tiltedMapper->SetInputData(tilted);
  vtkNew<vtkActor> bareActor, tiltedActor;
  bareActor->SetMapper(bareMapper);
  bareActor->GetProperty()->SetColor(0.2, 0.5, 0.9);
  tiltedActor->SetMapper(tiltedMapper);
  tiltedActor->GetProperty()->SetColor(0.9, 0.8, 0.2);
  renderer->AddActor(bareActor);
  renderer->AddActor(tiltedActor);
  renderer->ResetCameraClippingRange();
  CheckOffIsVTK(window, renderer, pass);
  window->Render();
  DebugWrite(mrgitest::GrabRGB(window), "TestMRGIPipelineGeometry-nonormals");
  MRGI_TEST_CHECK(pass->GetIndirectComputed());
  MRGI_TEST_CHECK(pass->GetGBuffer(window, position, normal, albedo));
  MRGI_TEST_CHECK(pass->GetIndirectBuffer(window, indirect));
  MRGI_TEST_CHECK(AllFinite(indirect));
  CheckNormalsFaceViewer(position, normal, albedo, false, 0.1);
  // The normal-less sphere (blue 0.9) and square (blue 0.2) face the eye everywhere.
  MRGI_TEST_CHECK(CheckNormalsFaceViewer(position, normal, albedo, false, 1e-3, 0.9) > 100);
  MRGI_TEST_CHECK(CheckNormalsFaceViewer(position, normal, albedo, false, 1e-3, 0.2) > 100);
  {
    // The tilted square's G-buffer normal is its true normal, towards the eye.
    double world[3] = { -1.2, 0.8, -0.8 };
    renderer->SetWorldPoint(world[0], world[1], world[2], 1.0);
    renderer->WorldToDisplay();
    const int x = static_cast<int>(renderer->GetDisplayPoint()[0]);
    const int y = static_cast<int>(renderer->GetDisplayPoint()[1]);
    double n[3] = { 0.5, 0.2, 1.0 };
    vtkMath::Normalize(n);
    vtkMatrix4x4* view = camera->GetModelViewTransformMatrix();
    double ne[3];
    for (int r = 0; r < 3; ++r)
    {
      ne[r] = view->GetElement(r, 0) * n[0] + view->GetElement(r, 1) * n[1] +
        view->GetElement(r, 2) * n[2];
    }
    const double cosine =
      ne[0] * At(normal, x, y, 0) + ne[1] * At(normal, x, y, 1) + ne[2] * At(normal, x, y, 2);
    std::printf(
      "normal-less square at pixel %d %d: cos(G-buffer normal, true normal) %.5f\n", x, y, cosine);
    MRGI_TEST_CHECK(Valid(normal, x, y) && cosine > 0.999);
    // The normal-less sphere is in the G-buffer too, with its colour.
    const double top[3] = { 0, 0.6, -0.15 };
    renderer->SetWorldPoint(top[0], top[1], top[2], 1.0);
    renderer->WorldToDisplay();
    const int sx = static_cast<int>(renderer->GetDisplayPoint()[0]);
    const int sy = static_cast<int>(renderer->GetDisplayPoint()[1]);
    MRGI_TEST_CHECK(Valid(albedo, sx, sy) && std::fabs(At(albedo, sx, sy, 2) - 0.9) < 0.003);
  }
  // Normal-less props reflect light too: RSM normals stay unit vectors.
  MRGI_TEST_CHECK(rsm->ReadView(window, 0, rsmPosition, rsmNormal, rsmFlux));
  worstNormal = 0;
  for (int y = 0; y < 128; ++y)
  {
    for (int x = 0; x < 128; ++x)
    {
      if (Valid(rsmPosition, x, y))
      {
        const double n = std::sqrt(At(rsmNormal, x, y, 0) * At(rsmNormal, x, y, 0) +
          At(rsmNormal, x, y, 1) * At(rsmNormal, x, y, 1) +
          At(rsmNormal, x, y, 2) * At(rsmNormal, x, y, 2));
        worstNormal = std::max(worstNormal, std::fabs(n - 1.0));
      }
    }
  }
  MRGI_TEST_CHECK(worstNormal < 0.003);

  // 3. Parallel projection: positions as the orthographic camera puts them.
  camera->ParallelProjectionOn();
  camera->SetParallelScale(1.6);
  renderer->ResetCameraClippingRange();
  CheckOffIsVTK(window, renderer, pass);
  window->Render();
  DebugWrite(mrgitest::GrabRGB(window), "TestMRGIPipelineGeometry-parallel");
  MRGI_TEST_CHECK(pass->GetIndirectComputed());
  MRGI_TEST_CHECK(pass->GetGBuffer(window, position, normal, albedo));
  MRGI_TEST_CHECK(pass->GetIndirectBuffer(window, indirect));
  MRGI_TEST_CHECK(AllFinite(indirect) && AllFinite(position));
  MRGI_TEST_CHECK(SumRGB(indirect, 0, 0, W, H) > 0);
  const int count = CheckNormalsFaceViewer(position, normal, albedo, true, 0.1);
  MRGI_TEST_CHECK(count > W * H / 2);
  MRGI_TEST_CHECK(CheckNormalsFaceViewer(position, normal, albedo, true, 1e-3, 0.9) > 100);
  MRGI_TEST_CHECK(CheckNormalsFaceViewer(position, normal, albedo, true, 1e-3, 0.2) > 100);
  // Eye x and y of a pixel centre follow from the parallel scale alone; the
  // eye z of the wall (a plane) from the camera.
  double worstXY = 0, worstZ = 0;
  int wallPixels = 0;
  const double scale = camera->GetParallelScale();
  for (int y = 0; y < H; ++y)
  {
    for (int x = 0; x < W; ++x)
    {
      if (!Valid(position, x, y))
      {
        continue;
      }
      const double ex = ((x + 0.5) - 0.5 * W) / (0.5 * H) * scale;
      const double ey = ((y + 0.5) - 0.5 * H) / (0.5 * H) * scale;
      worstXY = std::max(
        { worstXY, std::fabs(At(position, x, y, 0) - ex), std::fabs(At(position, x, y, 1) - ey) });
      // The wall: z = -1.5 in the world.
      double eye[3] = { At(position, x, y, 0), At(position, x, y, 1), At(position, x, y, 2) };
      double world[3];
      EyeToWorld(renderer, eye, world);
      if (std::fabs(At(albedo, x, y, 0) - 0.72) < 0.003 && std::fabs(world[2] + 1.5) < 0.05)
      {
        ++wallPixels;
        // Where the eye ray of this pixel meets z = -1.5.
        const double* dop = camera->GetDirectionOfProjection();
        const double* pos = camera->GetPosition();
        vtkMatrix4x4* view = camera->GetModelViewTransformMatrix();
        double start[3];
        for (int k = 0; k < 3; ++k)
        {
          // Eye (ex, ey, 0) in the world: camera position + ex right + ey up.
          start[k] = pos[k] + ex * view->GetElement(0, k) + ey * view->GetElement(1, k);
        }
        const double t = (-1.5 - start[2]) / dop[2];
        const double expectedZ = -t; // eye z is minus the distance along the view direction
        worstZ = std::max(worstZ, std::fabs(At(position, x, y, 2) - expectedZ));
      }
    }
  }
  std::printf("parallel: worst eye x/y error %.5f, wall eye z error %.5f over %d pixels\n", worstXY,
    worstZ, wallPixels);
  MRGI_TEST_CHECK(worstXY < 1e-3);
  MRGI_TEST_CHECK(wallPixels > 200 && worstZ < 1e-3);

  Uninstall(renderer, window, pass);
  return 0;
}
