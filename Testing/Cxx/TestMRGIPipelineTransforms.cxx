// vtkMRGIPass with many actors placed by SetPosition / RotateX / RotateY /
// SetOrigin / SetScale / SetUserMatrix:
// - the G-buffer holds each actor's surface where the actor's full transform
//   puts it: every captured position, taken back to the actor's model
//   coordinates, lies on the model (cube faces, sphere, square), its normal
//   is the model's, and the position projects to the pixel it was read at;
// - indirect light follows the actors: a lit red wall on the left and a lit
//   green wall on the right bleed onto a white cube next to them, and moving
//   the cube (and a square placed by a user matrix) to the other side swaps
//   which colour it receives;
// - with IndirectMode Off the image is VTK's own (max difference 1/255);
// - the lit image matches its baseline (relative RMS 0.02).
#include "TestMRGIPipelineCommon.h"

#include "vtkCubeSource.h"
#include "vtkLight.h"
#include "vtkMath.h"

#include <vector>

namespace
{
enum Model
{
  Cube,   // vtkCubeSource: unit cube at the origin
  Square, // vtkPlaneSource: unit square in z = 0
  Sphere  // vtkSphereSource of radius 0.5
};

struct Placed
{
  vtkSmartPointer<vtkActor> Actor;
  double Albedo; // unique grey level: identifies the actor in the G-buffer
  Model Kind;
};

// Model-space distance from `p` to the model's surface.
double Distance(Model kind, const double p[3])
{
  switch (kind)
  {
    case Cube:
      return std::fabs(std::max({ std::fabs(p[0]), std::fabs(p[1]), std::fabs(p[2]) }) - 0.5);
    case Square:
      return std::fabs(p[2]) + std::max(0.0, std::max(std::fabs(p[0]), std::fabs(p[1])) - 0.5);
    default:
      return std::fabs(std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) - 0.5);
  }
}

// 1 - |cos| of the angle between `n` and the model's normal at surface point
// `p` (on a cube edge, the better of the two faces').
double NormalError(Model kind, const double p[3], const double n[3])
{
  if (kind == Cube)
  {
    double best = 1;
    for (int k = 0; k < 3; ++k)
    {
      if (std::fabs(p[k]) > 0.49)
      {
        best = std::min(best, 1.0 - std::fabs(n[k]));
      }
    }
    return best;
  }
  if (kind == Square)
  {
    return 1.0 - std::fabs(n[2]);
  }
  const double r = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
  return 1.0 - std::fabs((p[0] * n[0] + p[1] * n[1] + p[2] * n[2]) / r);
}

// Model-space point and normal of G-buffer pixel (x, y) of `actor`.
void ToModel(vtkRenderer* renderer, vtkActor* actor, vtkImageData* position, vtkImageData* normal,
  int x, int y, double model[3], double modelNormal[3])
{
  double eye[3] = { mrgipipe::At(position, x, y, 0), mrgipipe::At(position, x, y, 1),
    mrgipipe::At(position, x, y, 2) };
  double world[3];
  mrgipipe::EyeToWorld(renderer, eye, world);
  vtkNew<vtkMatrix4x4> inverse;
  vtkMatrix4x4::Invert(actor->GetMatrix(), inverse);
  const double w4[4] = { world[0], world[1], world[2], 1 };
  double m4[4];
  inverse->MultiplyPoint(w4, m4);
  for (int k = 0; k < 3; ++k)
  {
    model[k] = m4[k] / m4[3];
  }
  // Normals: eye -> world with the inverse view rotation, world -> model
  // with the transpose of the actor matrix (inverse transpose of its inverse).
  vtkMatrix4x4* view = renderer->GetActiveCamera()->GetModelViewTransformMatrix();
  double ne[3] = { mrgipipe::At(normal, x, y, 0), mrgipipe::At(normal, x, y, 1),
    mrgipipe::At(normal, x, y, 2) };
  double nw[3];
  for (int r = 0; r < 3; ++r)
  {
    nw[r] = view->GetElement(0, r) * ne[0] + view->GetElement(1, r) * ne[1] +
      view->GetElement(2, r) * ne[2];
  }
  vtkMatrix4x4* m = actor->GetMatrix();
  for (int r = 0; r < 3; ++r)
  {
    modelNormal[r] =
      m->GetElement(0, r) * nw[0] + m->GetElement(1, r) * nw[1] + m->GetElement(2, r) * nw[2];
  }
  const double len = std::sqrt(modelNormal[0] * modelNormal[0] + modelNormal[1] * modelNormal[1] +
    modelNormal[2] * modelNormal[2]);
  for (int k = 0; k < 3; ++k)
  {
    modelNormal[k] /= (len > 0 ? len : 1);
  }
}

// Whether pixel (x, y) and its 8 neighbours show the actor of grey `albedo`.
bool Interior(vtkImageData* albedo, int x, int y, double grey)
{
  int dims[3];
  albedo->GetDimensions(dims);
  for (int dy = -1; dy <= 1; ++dy)
  {
    for (int dx = -1; dx <= 1; ++dx)
    {
      const int xx = x + dx, yy = y + dy;
      if (xx < 0 || yy < 0 || xx >= dims[0] || yy >= dims[1] || !mrgipipe::Valid(albedo, xx, yy))
      {
        return false;
      }
      for (int c = 0; c < 3; ++c)
      {
        if (std::fabs(mrgipipe::At(albedo, xx, yy, c) - grey) > 0.003)
        {
          return false;
        }
      }
    }
  }
  return true;
}

// Mean indirect RGB over the interior pixels of the actor of grey `albedo`.
int MeanIndirect(vtkImageData* albedo, vtkImageData* indirect, double grey, double mean[3])
{
  int dims[3];
  albedo->GetDimensions(dims);
  mean[0] = mean[1] = mean[2] = 0;
  int n = 0;
  for (int y = 0; y < dims[1]; ++y)
  {
    for (int x = 0; x < dims[0]; ++x)
    {
      if (Interior(albedo, x, y, grey))
      {
        for (int c = 0; c < 3; ++c)
        {
          mean[c] += mrgipipe::At(indirect, x, y, c);
        }
        ++n;
      }
    }
  }
  for (int c = 0; c < 3; ++c)
  {
    mean[c] /= (n > 0 ? n : 1);
  }
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
  renderer->SetBackground(0.05, 0.05, 0.08);

  // Room: red wall left, green wall right, white back wall and floor.
  const double cl[3] = { -2, 0, 0 }, nl[3] = { 1, 0, 0 };
  const double cr[3] = { 2, 0, 0 }, nr[3] = { -1, 0, 0 };
  const double cb[3] = { 0, 0, -2 }, nb[3] = { 0, 0, 1 };
  const double cf[3] = { 0, -1.5, 0 }, nf[3] = { 0, 1, 0 };
  renderer->AddActor(MakeQuad(cl, nl, 4, 0.9, 0.05, 0.05, 4));
  renderer->AddActor(MakeQuad(cr, nr, 4, 0.05, 0.9, 0.05, 4));
  renderer->AddActor(MakeQuad(cb, nb, 4, 0.7, 0.7, 0.7, 4));
  renderer->AddActor(MakeQuad(cf, nf, 4, 0.6, 0.6, 0.6, 4));

  std::vector<Placed> placed;
  // A white cube: SetPosition, RotateX, RotateY, SetScale.
  vtkNew<vtkCubeSource> cubeSource;
  {
    Placed p{ MakeActor(cubeSource, 0.95, 0.95, 0.95), 0.95, Cube };
    p.Actor->SetPosition(-1.25, -0.7, 0.2);
    p.Actor->RotateX(30);
    p.Actor->RotateY(25);
    p.Actor->SetScale(0.7);
    placed.push_back(p);
  }
  // A square placed by a user matrix only (rotation about y and a translation).
  vtkNew<vtkPlaneSource> squareSource;
  {
    Placed p{ MakeActor(squareSource, 0.85, 0.85, 0.85), 0.85, Square };
    vtkNew<vtkMatrix4x4> m;
    const double a = vtkMath::RadiansFromDegrees(35.0), s = 0.9;
    m->SetElement(0, 0, s * std::cos(a));
    m->SetElement(0, 2, s * std::sin(a));
    m->SetElement(1, 1, s);
    m->SetElement(2, 0, -s * std::sin(a));
    m->SetElement(2, 2, s * std::cos(a));
    m->SetElement(0, 3, 1.2);
    m->SetElement(1, 3, -0.6);
    m->SetElement(2, 3, -0.4);
    p.Actor->SetUserMatrix(m);
    placed.push_back(p);
  }
  // An ellipsoid: SetOrigin (rotation centre), SetPosition, RotateZ, non-uniform SetScale.
  vtkNew<vtkSphereSource> sphereSource;
  sphereSource->SetThetaResolution(32);
  sphereSource->SetPhiResolution(32);
  sphereSource->SetRadius(0.5);
  {
    Placed p{ MakeActor(sphereSource, 0.75, 0.75, 0.75), 0.75, Sphere };
    p.Actor->SetOrigin(0.2, 0, 0);
    p.Actor->SetPosition(0, 0.7, -0.8);
    p.Actor->RotateZ(40);
    p.Actor->SetScale(0.8, 0.5, 0.6);
    placed.push_back(p);
  }
  // Many small cubes in two rows, each its own position, rotation, scale and grey.
  for (int i = 0; i < 12; ++i)
  {
    const double grey = 0.30 + 0.025 * i;
    Placed p{ MakeActor(cubeSource, grey, grey, grey), grey, Cube };
    p.Actor->SetPosition(-1.5 + 0.6 * (i % 6), 0.95 + 0.5 * (i / 6), -1.6 + 0.05 * i);
    p.Actor->RotateX(15.0 * i);
    p.Actor->RotateY(10.0 * i);
    p.Actor->SetScale(0.26 + 0.005 * i);
    placed.push_back(p);
  }
  for (const Placed& p : placed)
  {
    renderer->AddActor(p.Actor);
  }

  vtkNew<vtkLight> light;
  light->SetLightTypeToSceneLight();
  light->SetPositional(true);
  light->SetConeAngle(180);
  light->SetPosition(0, 1.2, 1.0);
  light->SetFocalPoint(0, 0, 0);
  renderer->AddLight(light);

  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(0, 0.3, 6.5);
  camera->SetFocalPoint(0, -0.1, 0);
  camera->SetViewAngle(40);
  renderer->ResetCameraClippingRange();

  // VTK alone.
  window->Render();
  vtkSmartPointer<vtkImageData> plain = mrgitest::GrabRGB(window);

  vtkSmartPointer<vtkMRGIPass> pass = Install(renderer);
  pass->SetRSMResolution(128);
  pass->SetIndirectMode(vtkMRGIPass::IndirectOff);
  window->Render();
  vtkSmartPointer<vtkImageData> off = mrgitest::GrabRGB(window);
  std::printf("IndirectMode Off vs VTK: max difference %.0f / 255\n", MaxDifference(plain, off));
  MRGI_TEST_CHECK(MaxDifference(plain, off) <= 1.0);

  pass->SetIndirectMode(vtkMRGIPass::IndirectFull);
  window->Render();
  MRGI_TEST_CHECK(pass->GetIndirectComputed());
  vtkNew<vtkImageData> position, normal, albedo, indirect;
  MRGI_TEST_CHECK(pass->GetGBuffer(window, position, normal, albedo));
  MRGI_TEST_CHECK(pass->GetIndirectBuffer(window, indirect));
  MRGI_TEST_CHECK(AllFinite(indirect));
  // The picture as a whole (colour bleeding from both walls onto the actors).
  MRGI_TEST_CHECK(
    mrgitest::CompareWithBaseline(mrgitest::GrabRGB(window), "TestMRGIPipelineTransforms", 0.02));

  // 1. Every actor's G-buffer pixels lie on its model, under its transform.
  for (size_t i = 0; i < placed.size(); ++i)
  {
    const Placed& p = placed[i];
    int count = 0;
    double worstDistance = 0, worstNormal = 0, worstPixel = 0;
    for (int y = 1; y < H - 1; ++y)
    {
      for (int x = 1; x < W - 1; ++x)
      {
        if (!Interior(albedo, x, y, p.Albedo))
        {
          continue;
        }
        ++count;
        double model[3], modelNormal[3];
        ToModel(renderer, p.Actor, position, normal, x, y, model, modelNormal);
        worstDistance = std::max(worstDistance, Distance(p.Kind, model));
        worstNormal = std::max(worstNormal, NormalError(p.Kind, model, modelNormal));
        // The position projects back to the pixel it was read at.
        double eye[3] = { At(position, x, y, 0), At(position, x, y, 1), At(position, x, y, 2) };
        double world[3];
        EyeToWorld(renderer, eye, world);
        renderer->SetWorldPoint(world[0], world[1], world[2], 1.0);
        renderer->WorldToDisplay();
        const double* d = renderer->GetDisplayPoint();
        worstPixel =
          std::max({ worstPixel, std::fabs(d[0] - (x + 0.5)), std::fabs(d[1] - (y + 0.5)) });
      }
    }
    std::printf("actor %zu (grey %.3f): %d pixels, distance to model %.4f, normal error %.4f, "
                "reprojection %.3f px\n",
      i, p.Albedo, count, worstDistance, worstNormal, worstPixel);
    MRGI_TEST_CHECK(count >= (i < 3 ? 40 : 4));
    // Flat sphere facets lie within 0.5 (1 - cos(pi / 32)) = 0.0024 of the sphere.
    MRGI_TEST_CHECK(worstDistance < 0.01);
    MRGI_TEST_CHECK(worstNormal < (p.Kind == Sphere ? 0.02 : 0.002));
    MRGI_TEST_CHECK(worstPixel < 0.05);
  }

  // 2. Indirect light follows the actors: the cube near the red wall gets red.
  double cubeLeft[3], squareRight[3];
  MRGI_TEST_CHECK(MeanIndirect(albedo, indirect, 0.95, cubeLeft) > 40);
  MRGI_TEST_CHECK(MeanIndirect(albedo, indirect, 0.85, squareRight) > 40);
  std::printf("indirect on the cube (left) %.4f %.4f %.4f, on the square (right) %.4f %.4f %.4f\n",
    cubeLeft[0], cubeLeft[1], cubeLeft[2], squareRight[0], squareRight[1], squareRight[2]);
  // Each side's colour dominates what the actor next to it receives.
  MRGI_TEST_CHECK(cubeLeft[0] > 1.1 * cubeLeft[1] && cubeLeft[0] > 0.01);
  MRGI_TEST_CHECK(squareRight[1] > 1.3 * squareRight[0] && squareRight[1] > 0.01);

  // Swap sides: the cube by SetPosition, the square by a new user matrix
  // (mirrored, so that it faces the red wall as it faced the green one).
  placed[0].Actor->SetPosition(1.25, -0.7, 0.2);
  vtkNew<vtkMatrix4x4> moved;
  moved->DeepCopy(placed[1].Actor->GetUserMatrix());
  moved->SetElement(0, 3, -1.2);
  moved->SetElement(0, 2, -moved->GetElement(0, 2));
  moved->SetElement(2, 0, -moved->GetElement(2, 0));
  placed[1].Actor->SetUserMatrix(moved);
  window->Render();
  MRGI_TEST_CHECK(pass->GetGBuffer(window, position, normal, albedo));
  MRGI_TEST_CHECK(pass->GetIndirectBuffer(window, indirect));
  double cubeRight[3], squareLeft[3];
  MRGI_TEST_CHECK(MeanIndirect(albedo, indirect, 0.95, cubeRight) > 40);
  MRGI_TEST_CHECK(MeanIndirect(albedo, indirect, 0.85, squareLeft) > 40);
  std::printf("after moving: cube (right) %.4f %.4f %.4f, square (left) %.4f %.4f %.4f\n",
    cubeRight[0], cubeRight[1], cubeRight[2], squareLeft[0], squareLeft[1], squareLeft[2]);
  MRGI_TEST_CHECK(cubeRight[1] > 1.1 * cubeRight[0]);
  MRGI_TEST_CHECK(squareLeft[0] > 1.3 * squareLeft[1]);
  // The swap, relative to itself (independent of the room's grey bounce).
  MRGI_TEST_CHECK(cubeLeft[0] / cubeLeft[1] > 1.5 * cubeRight[0] / cubeRight[1]);
  MRGI_TEST_CHECK(squareLeft[0] / squareLeft[1] > 3.0 * squareRight[0] / squareRight[1]);

  Uninstall(renderer, window, pass);
  return 0;
}
