// The GPU imperfect shadow maps (vtkMRGIImperfectShadowMaps, ritschel-et-al-
// 2008 3.3, ritschel-et-al-2011 5-6.1) against the C twin
// (mrgi_ism_atlas_render, mrgi_ism_atlas.h section 5).
//
// Render(): random points and random VPLs (several V, T, one empty VPL with
// a zero normal) drawn on the GPU and by the twin, both push-pulled: the
// share of texels that differ and the worst depth error are printed and
// bounded. The GPU projects in float, the twin in double, so a point within
// float rounding of a texel edge (1e-4 texel, counted) may land in the
// neighbour texel: with no such point the atlases must agree exactly (depth
// within 4e-5), otherwise at most T^2 texels per edge point and 2% of all
// may differ; every point away from edges must find, on the GPU, a depth
// no larger than its own in its twin texel. Empty tiles stay empty and
// tiles never mix (a VPL with no points keeps an empty tile beside full
// ones).
//
// Update(): a Cornell scene through vtkMRGIPass (for the G-buffer's view
// samples): the atlas is not empty, the lazy update redraws exactly
// floor/ceil(P / LazyFrames) records per frame (all of them after a change
// of point mode or seed), moving an actor moves the points by its
// translation, and bad input (no geometry, tile 6, an atlas
// over MRGI_ISM_MAX_ATLAS) gives a clear error and no atlas.
// Set MRGI_ISM_BREAK=1 to give the twin a shifted VPL: the parity must fail.
#include "mrgiPassSceneFixture.h"
#include "mrgiTestUtilities.h"

#include "vtkActor.h"
#include "vtkActorCollection.h"
#include "vtkAssembly.h"
#include "vtkCompositeDataDisplayAttributes.h"
#include "vtkCompositePolyDataMapper2.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkCamera.h"
#include "vtkCommand.h"
#include "vtkFloatArray.h"
#include "vtkMRGIFrameContext.h"
#include "vtkMRGIImperfectShadowMaps.h"
#include "vtkMatrix4x4.h"
#include "vtkMinimalStandardRandomSequence.h"
#include "vtkNew.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"
#include "vtkPlaneSource.h"
#include "vtkPoints.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkCellArray.h"
#include "vtkRenderer.h"
#include "vtkTextureObject.h"

#include "mrgi_ism_atlas.h"
#include "mrgi_ism_points.h"
#include "mrgi_vpl.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <sstream>
#include <vector>

namespace
{
struct Random
{
  vtkNew<vtkMinimalStandardRandomSequence> Seq;
  double Next(double lo, double hi)
  {
    this->Seq->Next();
    return lo + (hi - lo) * this->Seq->GetValue();
  }
};

vtkSmartPointer<vtkTextureObject> VPLTexture(
  vtkOpenGLRenderWindow* window, const std::vector<mrgi_vpl>& vpls)
{
  auto t = vtkSmartPointer<vtkTextureObject>::New();
  t->SetContext(window);
  MRGI_TEST_CHECK(t->Create2DFromRaw(MRGI_VPL_TEXELS, static_cast<unsigned int>(vpls.size()), 4,
    VTK_FLOAT, const_cast<mrgi_vpl*>(vpls.data())));
  return t;
}

// Whether point x, seen from VPL l, lies within `margin` texels of a texel
// edge of its tile (or at the hemisphere's rim): the only points float and
// double may place differently.
bool NearEdge(const mrgi_ism_atlas_layout& L, const mrgi_vpl& v, const float* x, double margin)
{
  const double d[3] = { x[0] - v.position[0], x[1] - v.position[1], x[2] - v.position[2] };
  const double r = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  const double n[3] = { v.normal[0], v.normal[1], v.normal[2] };
  const double u[3] = { d[0] / r, d[1] / r, d[2] / r };
  if (std::fabs(u[0] * n[0] + u[1] * n[1] + u[2] * n[2]) < 1e-5)
  {
    return true;
  }
  double t[3], b[3];
  mrgi_ism_vpl_frame(n, t, b);
  const double st[2] = { u[0] * t[0] + u[1] * t[1] + u[2] * t[2],
    u[0] * b[0] + u[1] * b[1] + u[2] * b[2] };
  for (double c : st)
  {
    const double f = (c + 1.0) * 0.5 * L.tile_size;
    if (std::fabs(f - std::round(f)) < margin)
    {
      return true;
    }
  }
  return false;
}

void RenderParity()
{
  vtkSmartPointer<vtkRenderWindow> window = mrgitest::HeadlessWindow(32, 32);
  vtkNew<vtkRenderer> ren;
  window->AddRenderer(ren);
  window->Render();
  auto* gl = vtkOpenGLRenderWindow::SafeDownCast(window);
  const bool breakIt = std::getenv("MRGI_ISM_BREAK") != nullptr;
  vtkNew<vtkMRGIImperfectShadowMaps> ism;
  Random rnd;
  const int cases[][3] = { { 1, 8, 500 }, { 5, 16, 6000 }, { 16, 4, 3000 }, { 7, 32, 20000 },
    { 30, 8, 9000 } };
  int caseIndex = 0;
  for (const auto& c : cases)
  {
    const int V = c[0], T = c[1], N = c[2];
    // Push-pull off, over the default levels, over 2 levels and over the
    // whole tile in turn: every atlas matches its twin.
    const int pushPullChoices[4] = { 0, MRGI_ISM_DEFAULT_PUSH_PULL_LEVELS, 2,
      MRGI_ISM_MAX_PUSH_PULL_LEVELS };
    const int pushPull = pushPullChoices[caseIndex++ % 4];
    ism->SetPushPullLevels(pushPull);
    std::vector<mrgi_vpl> vpls(static_cast<size_t>(V));
    for (int l = 0; l < V; ++l)
    {
      mrgi_vpl& v = vpls[static_cast<size_t>(l)];
      v = mrgi_vpl{};
      double n[3] = { rnd.Next(-1, 1), rnd.Next(-1, 1), rnd.Next(-1, 1) };
      const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      for (int k = 0; k < 3; ++k)
      {
        v.position[k] = static_cast<float>(rnd.Next(-0.5, 0.5));
        // VPL 2 is empty (zero normal): its tile must stay empty.
        v.normal[k] = l == 2 ? 0.0f : static_cast<float>(n[k] / len);
        v.flux[k] = l == 2 ? 0.0f : 1.0f;
      }
    }
    std::vector<float> points(static_cast<size_t>(N) * 3);
    for (float& p : points)
    {
      p = static_cast<float>(rnd.Next(-2.0, 2.0));
    }
    // Non-finite points land nowhere (never a NaN texel).
    points[0] = std::nanf("");
    points[4] = std::numeric_limits<float>::infinity();
    ism->SetTileSize(T);
    auto tex = VPLTexture(gl, vpls);
    // A large point size left by someone else must not matter.
    gl->GetState()->vtkglPointSize(c[0] == 5 ? 7.0f : 1.0f);
    MRGI_TEST_CHECK(ism->Render(gl, points.data(), N, tex, V));
    vtkNew<vtkFloatArray> gpu;
    MRGI_TEST_CHECK(ism->ReadAtlas(window, gpu));
    const mrgi_ism_atlas_layout L = ism->GetLayout();
    MRGI_TEST_CHECK(L.vpl_count == V && L.tile_size == T);
    const size_t texels = static_cast<size_t>(L.width) * L.height;
    MRGI_TEST_CHECK(static_cast<size_t>(gpu->GetNumberOfTuples()) == texels);

    std::vector<mrgi_vpl> twinVPLs = vpls;
    if (breakIt)
    {
      twinVPLs[0].position[0] += 0.05f;
    }
    std::vector<float> raw(texels), twin(texels);
    std::vector<float> scratch(mrgi_ism_push_pull_scratch_size(&L));
    MRGI_TEST_CHECK(mrgi_ism_atlas_render(&L, points.data(), N, twinVPLs.data(), 0, raw.data(),
                      nullptr, 0, nullptr) == MRGI_OK);
    MRGI_TEST_CHECK(mrgi_ism_atlas_render(&L, points.data(), N, twinVPLs.data(), pushPull, twin.data(),
                      scratch.data(), scratch.size(), nullptr) == MRGI_OK);

    // Texel by texel: a texel differs when one atlas is empty and the other
    // not, or their depths differ by more than float rounding.
    size_t differ = 0;
    double worst = 0.0;
    for (size_t k = 0; k < texels; ++k)
    {
      const float g = gpu->GetValue(static_cast<vtkIdType>(k));
      const float t = twin[k];
      const bool ge = !(g < MRGI_ISM_EMPTY_DEPTH), te = !(t < MRGI_ISM_EMPTY_DEPTH);
      MRGI_TEST_CHECK(std::isfinite(g) && g > 0.0f);
      if (ge != te || (!ge && std::fabs(g - t) > 1e-5 * std::max(1.0f, t)))
      {
        ++differ;
      }
      if (!ge && !te)
      {
        worst = std::max(worst, static_cast<double>(std::fabs(g - t)));
      }
    }
    // Point by point: a point away from texel edges lands in the twin's
    // texel on the GPU too, so the GPU's nearest depth there is at most its
    // distance (+ float rounding). Points near an edge are counted.
    int edgePoints = 0, undercut = 0;
    for (int i = 0; i < N; ++i)
    {
      const int l = i % V;
      const mrgi_vpl& v = vpls[static_cast<size_t>(l)];
      const float* x = &points[3 * static_cast<size_t>(i)];
      if (!std::isfinite(x[0]) || !std::isfinite(x[1]) || !std::isfinite(x[2]))
      {
        continue;
      }
      if (v.normal[0] == 0.0f && v.normal[1] == 0.0f && v.normal[2] == 0.0f)
      {
        continue;
      }
      if (NearEdge(L, v, x, 1e-4))
      {
        ++edgePoints;
        continue;
      }
      const double vp[3] = { v.position[0], v.position[1], v.position[2] };
      const double vn[3] = { v.normal[0], v.normal[1], v.normal[2] };
      const double xd[3] = { x[0], x[1], x[2] };
      int64_t texel;
      float d;
      if (mrgi_ism_point_texel(&L, l, vp, vn, xd, &texel, &d) &&
        !(gpu->GetValue(static_cast<vtkIdType>(texel)) <= d * (1.0f + 1e-5f)))
      {
        ++undercut;
      }
    }
    MRGI_TEST_CHECK(undercut == 0);
    const double share = static_cast<double>(differ) / static_cast<double>(texels);
    std::printf("V %2d T %2d points %5d push-pull %d: %zu of %zu texels differ (%.4f%%), worst depth error "
                "%.3g, %d points within 1e-4 texel of an edge\n",
      V, T, N, pushPull ? 1 : 0, differ, texels, 100.0 * share, worst, edgePoints);
    // An edge point can change its texel and, through push-pull, the texels
    // that inherit from it: at most a tile's worth per edge point.
    MRGI_TEST_CHECK(differ <= static_cast<size_t>(edgePoints) * static_cast<size_t>(T * T));
    if (edgePoints == 0)
    {
      MRGI_TEST_CHECK(differ == 0);
    }
    MRGI_TEST_CHECK(share <= 0.02);
    if (edgePoints == 0)
    {
      MRGI_TEST_CHECK(worst <= 1e-5 * 4.0);
    }
    // Tiles never mix; the empty VPL's tile stays empty beside full ones
    // (full only after push-pull over the whole tile).
    int wholeTile = 0;
    for (int side = T; side > 1; side >>= 1)
    {
      ++wholeTile;
    }
    for (int l = 0; l < V; ++l)
    {
      const int x0 = (l % L.tiles_per_row) * T, y0 = (l / L.tiles_per_row) * T;
      int empty = 0;
      for (int y = 0; y < T; ++y)
      {
        for (int x = 0; x < T; ++x)
        {
          empty +=
            !(gpu->GetValue(static_cast<vtkIdType>(y0 + y) * L.width + x0 + x) < MRGI_ISM_EMPTY_DEPTH);
        }
      }
      MRGI_TEST_CHECK(l == 2 ? empty == T * T : (pushPull < wholeTile || empty == 0));
    }
    tex->ReleaseGraphicsResources(window);
  }
  // No points: every tile empty.
  std::vector<mrgi_vpl> one(1);
  one[0].normal[2] = 1.0f;
  auto tex = VPLTexture(gl, one);
  MRGI_TEST_CHECK(ism->Render(gl, nullptr, 0, tex, 1));
  vtkNew<vtkFloatArray> gpu;
  MRGI_TEST_CHECK(ism->ReadAtlas(window, gpu));
  for (vtkIdType k = 0; k < gpu->GetNumberOfTuples(); ++k)
  {
    MRGI_TEST_CHECK(gpu->GetValue(k) == MRGI_ISM_EMPTY_DEPTH);
  }
  std::ostringstream printed;
  ism->Print(printed);
  MRGI_TEST_CHECK(printed.str().find("TileSize: 8") != std::string::npos);
  tex->ReleaseGraphicsResources(window);
  ism->ReleaseGraphicsResources(window);
  MRGI_TEST_CHECK(ism->GetAtlasTexture() == nullptr);
}

// The frame a pass would hand the stage: the window, renderer, G-buffer
// position and the camera's eye -> world.
vtkMRGIFrameContext Frame(mrgitest::PassScene& scene)
{
  vtkMRGIFrameContext frame;
  frame.Window = vtkOpenGLRenderWindow::SafeDownCast(scene.Window);
  frame.Renderer = scene.Renderer;
  frame.Position = scene.Pass->GetPositionTexture();
  int size[2];
  int origin[2];
  scene.Renderer->GetTiledSizeAndOrigin(&size[0], &size[1], &origin[0], &origin[1]);
  frame.Viewport[0] = origin[0];
  frame.Viewport[1] = origin[1];
  frame.Viewport[2] = size[0];
  frame.Viewport[3] = size[1];
  vtkNew<vtkMatrix4x4> inv;
  vtkMatrix4x4::Invert(scene.Renderer->GetActiveCamera()->GetModelViewTransformMatrix(), inv);
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      frame.ViewToWorldDouble[4 * c + r] = inv->GetElement(r, c);
      frame.ViewToWorld[4 * c + r] = static_cast<float>(inv->GetElement(r, c));
    }
  }
  return frame;
}

void UpdateScene()
{
  mrgitest::PassScene scene(64, 64, "cornell-spot");
  scene.Window->Render();
  auto* gl = vtkOpenGLRenderWindow::SafeDownCast(scene.Window);
  vtkMRGIFrameContext frame = Frame(scene);
  MRGI_TEST_CHECK(frame.Position != nullptr);
  const int V = 6;
  std::vector<mrgi_vpl> vpls(V);
  for (int l = 0; l < V; ++l)
  {
    vpls[static_cast<size_t>(l)].position[1] = 0.5f + 0.05f * l; // inside the box
    vpls[static_cast<size_t>(l)].normal[1] = -1.0f;
    vpls[static_cast<size_t>(l)].flux[0] = 1.0f;
  }
  auto tex = VPLTexture(gl, vpls);
  vtkNew<vtkMRGIImperfectShadowMaps> ism;
  ism->SetPointsPerVPL(100); // P = 600
  ism->SetTileSize(16);
  const int P = 600;
  for (int lazy : { 8, 1, 7 })
  {
    ism->SetLazyFrames(lazy);
    ism->ReleaseGraphicsResources(scene.Window); // restart the point set
    MRGI_TEST_CHECK(ism->Update(frame, tex, V));
    MRGI_TEST_CHECK(ism->GetNumberOfPoints() == P);
    MRGI_TEST_CHECK(ism->GetNumberOfResampledPoints() == P);
    MRGI_TEST_CHECK(ism->GetNumberOfTriangles() > 0);
    std::vector<mrgi_ism_point> before(ism->GetPointRecords(), ism->GetPointRecords() + P);
    for (int f = 0; f < lazy + 1; ++f)
    {
      MRGI_TEST_CHECK(ism->Update(frame, tex, V));
      const mrgi_ism_point* now = ism->GetPointRecords();
      int changed = 0;
      for (int i = 0; i < P; ++i)
      {
        changed += (now[i].index != before[static_cast<size_t>(i)].index ||
                     now[i].u != before[static_cast<size_t>(i)].u ||
                     now[i].v != before[static_cast<size_t>(i)].v)
          ? 1
          : 0;
      }
      const int n = static_cast<int>(ism->GetNumberOfResampledPoints());
      MRGI_TEST_CHECK(n == P / lazy || n == (P + lazy - 1) / lazy);
      MRGI_TEST_CHECK(changed == n);
      before.assign(now, now + P);
    }
  }
  // Another point mode or seed is another distribution: the next frame
  // redraws every record, not 1 / LazyFrames of them (the lazy update would
  // mix the two distributions for LazyFrames frames).
  for (int step = 0; step < 3; ++step)
  {
    if (step == 0)
    {
      ism->SetPointMode(vtkMRGIImperfectShadowMaps::Uniform);
    }
    else if (step == 1)
    {
      ism->SetSeed(ism->GetSeed() + 1);
    }
    else
    {
      ism->SetPointMode(vtkMRGIImperfectShadowMaps::Adaptive8);
    }
    MRGI_TEST_CHECK(ism->Update(frame, tex, V));
    MRGI_TEST_CHECK(ism->GetNumberOfResampledPoints() == P);
    MRGI_TEST_CHECK(ism->Update(frame, tex, V));
    MRGI_TEST_CHECK(ism->GetNumberOfResampledPoints() < P);
  }
  ism->SetSeed(ism->GetSeed() - 1);

  // Adaptive8 (the default) read view samples from the G-buffer; the same
  // seed in Uniform mode draws other records (the pdf differs).
  MRGI_TEST_CHECK(ism->GetPointMode() == vtkMRGIImperfectShadowMaps::Adaptive8);
  MRGI_TEST_CHECK(ism->GetNumberOfViewSamples() > 100);
  MRGI_TEST_CHECK(ism->GetNumberOfViewSamples() <= 4096);
  {
    vtkNew<vtkMRGIImperfectShadowMaps> uniform;
    uniform->SetPointsPerVPL(100);
    uniform->SetTileSize(16);
    uniform->SetPointMode(vtkMRGIImperfectShadowMaps::Uniform);
    ism->ReleaseGraphicsResources(scene.Window);
    MRGI_TEST_CHECK(ism->Update(frame, tex, V));
    MRGI_TEST_CHECK(uniform->Update(frame, tex, V));
    MRGI_TEST_CHECK(uniform->GetNumberOfViewSamples() == 0);
    int differ = 0;
    for (int i = 0; i < P; ++i)
    {
      differ += ism->GetPointRecords()[i].index != uniform->GetPointRecords()[i].index ? 1 : 0;
    }
    std::printf("Adaptive8 vs Uniform: %d of %d records on other triangles, %lld view samples\n",
      differ, P, static_cast<long long>(ism->GetNumberOfViewSamples()));
    MRGI_TEST_CHECK(differ > 0);
    uniform->ReleaseGraphicsResources(scene.Window);
  }

  // The atlas holds depths.
  vtkNew<vtkFloatArray> depth;
  MRGI_TEST_CHECK(ism->ReadAtlas(scene.Window, depth));
  int valid = 0;
  for (vtkIdType k = 0; k < depth->GetNumberOfTuples(); ++k)
  {
    valid += depth->GetValue(k) < MRGI_ISM_EMPTY_DEPTH ? 1 : 0;
  }
  std::printf("atlas %d x %d: %d of %lld texels valid\n", ism->GetLayout().width,
    ism->GetLayout().height, valid, static_cast<long long>(depth->GetNumberOfTuples()));
  // Push-pull over the whole tile fills every texel; over fewer levels (the
  // default: one) or none, the points' texels and their blocks hold depths.
  int wholeTile = 0;
  for (int side = ism->GetTileSize(); side > 1; side >>= 1)
  {
    ++wholeTile;
  }
  MRGI_TEST_CHECK(
    ism->GetPushPullLevels() >= wholeTile ? valid == depth->GetNumberOfTuples() : valid > 0);

  // Moving an actor moves its points by the translation (records kept).
  vtkActorCollection* actors = scene.Renderer->GetActors();
  actors->InitTraversal();
  vtkActor* first = actors->GetNextActor();
  MRGI_TEST_CHECK(first != nullptr);
  ism->SetLazyFrames(64);
  ism->ReleaseGraphicsResources(scene.Window);
  MRGI_TEST_CHECK(ism->Update(frame, tex, V));
  std::vector<float> p0(ism->GetPointPositions(), ism->GetPointPositions() + 3 * P);
  std::vector<mrgi_ism_point> r0(ism->GetPointRecords(), ism->GetPointRecords() + P);
  const double* pos = first->GetPosition();
  first->SetPosition(pos[0] + 0.25, pos[1], pos[2]);
  MRGI_TEST_CHECK(ism->Update(frame, tex, V));
  const float* p1 = ism->GetPointPositions();
  const mrgi_ism_point* r1 = ism->GetPointRecords();
  int moved = 0, kept = 0;
  for (int i = 0; i < P; ++i)
  {
    if (r1[i].index != r0[static_cast<size_t>(i)].index || r1[i].u != r0[static_cast<size_t>(i)].u)
    {
      continue; // redrawn by this frame's lazy range
    }
    // Float positions: tolerances relative to the coordinates' size.
    const float* a = &p0[3 * static_cast<size_t>(i)];
    const float* b = &p1[3 * i];
    const double tol =
      4e-7 * (1.0 + std::fabs(a[0]) + std::fabs(a[1]) + std::fabs(a[2]) + 0.25);
    const double dx = b[0] - a[0];
    const bool same = std::fabs(b[1] - a[1]) <= tol && std::fabs(b[2] - a[2]) <= tol;
    moved += (std::fabs(dx - 0.25) <= tol && same) ? 1 : 0;
    kept += (std::fabs(dx) <= tol && same) ? 1 : 0;
  }
  std::printf("moved actor: %d points moved by 0.25, %d kept\n", moved, kept);
  MRGI_TEST_CHECK(moved > 0);
  MRGI_TEST_CHECK(moved + kept >= P - P / 64 - 1);

  // Bad input: clear errors, no atlas, no crash.
  vtkNew<mrgitest::ErrorCatcher> errors;
  ism->AddObserver(vtkCommand::ErrorEvent, errors);
  ism->SetTileSize(3); // clamped to 4
  MRGI_TEST_CHECK(ism->GetTileSize() == 4);
  ism->SetTileSize(6);
  MRGI_TEST_CHECK(!ism->Update(frame, tex, V));
  MRGI_TEST_CHECK(errors->Caught("power of two"));
  MRGI_TEST_CHECK(ism->GetAtlasTexture() == nullptr);
  ism->SetTileSize(1024);
  MRGI_TEST_CHECK(!ism->Update(frame, tex, 4096));
  MRGI_TEST_CHECK(errors->Caught("atlas"));
  ism->SetTileSize(16);
  MRGI_TEST_CHECK(!ism->Update(frame, nullptr, V));
  MRGI_TEST_CHECK(errors->Caught("VPL texture"));
  actors->InitTraversal();
  while (vtkActor* a = actors->GetNextActor())
  {
    a->VisibilityOff();
  }
  MRGI_TEST_CHECK(!ism->Update(frame, tex, V));
  MRGI_TEST_CHECK(errors->Caught("no opaque geometry"));
  MRGI_TEST_CHECK(ism->GetAtlasTexture() == nullptr);
  tex->ReleaseGraphicsResources(scene.Window);
  ism->ReleaseGraphicsResources(scene.Window);
}

// A point cloud (verts with normals) is its own point set (mrgi_ism_points.h
// section 4): no triangles, every point is a cloud point moved by the
// actor's matrix; a translucent mesh beside it is skipped, an opaque mesh
// takes over from the cloud; a triangle strip is split into triangles.
void PointCloud()
{
  vtkSmartPointer<vtkRenderWindow> window = mrgitest::HeadlessWindow(32, 32);
  vtkNew<vtkRenderer> ren;
  window->AddRenderer(ren);
  vtkNew<vtkPolyData> cloud;
  vtkNew<vtkPoints> pts;
  vtkNew<vtkFloatArray> normals;
  normals->SetNumberOfComponents(3);
  vtkNew<vtkCellArray> verts;
  for (int i = 0; i < 50; ++i)
  {
    pts->InsertNextPoint(0.1 * i, 0.0, 0.0);
    normals->InsertNextTuple3(0.0, 0.0, 1.0);
    const vtkIdType id = i;
    verts->InsertNextCell(1, &id);
  }
  cloud->SetPoints(pts);
  cloud->SetVerts(verts);
  cloud->GetPointData()->SetNormals(normals);
  vtkNew<vtkPolyDataMapper> cloudMapper;
  cloudMapper->SetInputData(cloud);
  vtkNew<vtkActor> cloudActor;
  cloudActor->SetMapper(cloudMapper);
  cloudActor->SetPosition(0.0, 2.0, 0.0);
  ren->AddActor(cloudActor);
  vtkNew<vtkPlaneSource> plane;
  vtkNew<vtkPolyDataMapper> planeMapper;
  planeMapper->SetInputConnection(plane->GetOutputPort());
  vtkNew<vtkActor> planeActor;
  planeActor->SetMapper(planeMapper);
  planeActor->GetProperty()->SetOpacity(0.5);
  ren->AddActor(planeActor);
  window->Render();

  auto* gl = vtkOpenGLRenderWindow::SafeDownCast(window);
  std::vector<mrgi_vpl> vpls(2);
  for (mrgi_vpl& v : vpls)
  {
    v.normal[1] = 1.0f;
    v.flux[0] = 1.0f;
  }
  auto tex = VPLTexture(gl, vpls);
  vtkMRGIFrameContext frame;
  frame.Window = gl;
  frame.Renderer = ren;
  vtkNew<vtkMRGIImperfectShadowMaps> ism;
  ism->SetPointsPerVPL(40);
  MRGI_TEST_CHECK(ism->Update(frame, tex, 2));
  MRGI_TEST_CHECK(ism->GetNumberOfTriangles() == 0);
  MRGI_TEST_CHECK(ism->GetNumberOfPoints() == 80);
  const float* p = ism->GetPointPositions();
  const mrgi_ism_point* r = ism->GetPointRecords();
  for (int i = 0; i < 80; ++i)
  {
    MRGI_TEST_CHECK(r[i].index >= 0 && r[i].index < 50);
    MRGI_TEST_CHECK(std::fabs(p[3 * i] - 0.1f * r[i].index) < 1e-5f);
    MRGI_TEST_CHECK(p[3 * i + 1] == 2.0f && p[3 * i + 2] == 0.0f);
  }
  // The opaque plane: a mesh, two triangles; the cloud is then not used.
  planeActor->GetProperty()->SetOpacity(1.0);
  window->Render();
  MRGI_TEST_CHECK(ism->Update(frame, tex, 2));
  MRGI_TEST_CHECK(ism->GetNumberOfTriangles() == 2);
  // A strip of 5 points adds 3 triangles, every point on the strip's plane z = 1.
  vtkNew<vtkPolyData> strip;
  vtkNew<vtkPoints> stripPoints;
  vtkNew<vtkCellArray> strips;
  const vtkIdType ids[5] = { 0, 1, 2, 3, 4 };
  for (int i = 0; i < 5; ++i)
  {
    stripPoints->InsertNextPoint(0.5 * (i / 2), 0.5 * (i % 2), 1.0);
  }
  strips->InsertNextCell(5, ids);
  strip->SetPoints(stripPoints);
  strip->SetStrips(strips);
  vtkNew<vtkPolyDataMapper> stripMapper;
  stripMapper->SetInputData(strip);
  vtkNew<vtkActor> stripActor;
  stripActor->SetMapper(stripMapper);
  ren->AddActor(stripActor);
  planeActor->VisibilityOff();
  window->Render();
  MRGI_TEST_CHECK(ism->Update(frame, tex, 2));
  MRGI_TEST_CHECK(ism->GetNumberOfTriangles() == 3);
  for (int i = 0; i < 80; ++i)
  {
    MRGI_TEST_CHECK(ism->GetPointPositions()[3 * i + 2] == 1.0f);
  }
  tex->ReleaseGraphicsResources(window);
  ism->ReleaseGraphicsResources(window);
}

// What ParaView and assemblies deliver: the opaque, visible blocks of a
// composite data set drawn by vtkCompositePolyDataMapper2, and the parts of
// a vtkAssembly with the assembly's matrix.
void CompositeAndAssembly()
{
  vtkSmartPointer<vtkRenderWindow> window = mrgitest::HeadlessWindow(32, 32);
  vtkNew<vtkRenderer> ren;
  window->AddRenderer(ren);
  vtkNew<vtkPlaneSource> planeA, planeB; // 2 triangles each
  planeA->Update();
  planeB->SetResolution(2, 1);           // 4 triangles
  planeB->Update();
  vtkNew<vtkMultiBlockDataSet> blocks;
  blocks->SetNumberOfBlocks(2);
  blocks->SetBlock(0, planeA->GetOutput());
  blocks->SetBlock(1, planeB->GetOutput());
  vtkNew<vtkCompositePolyDataMapper2> compositeMapper;
  compositeMapper->SetInputDataObject(blocks);
  vtkNew<vtkCompositeDataDisplayAttributes> attributes;
  compositeMapper->SetCompositeDataDisplayAttributes(attributes);
  vtkNew<vtkActor> compositeActor;
  compositeActor->SetMapper(compositeMapper);
  ren->AddActor(compositeActor);
  window->Render();
  auto* gl = vtkOpenGLRenderWindow::SafeDownCast(window);
  std::vector<mrgi_vpl> vpls(1);
  vpls[0].normal[2] = 1.0f;
  vpls[0].flux[0] = 1.0f;
  auto tex = VPLTexture(gl, vpls);
  vtkMRGIFrameContext frame;
  frame.Window = gl;
  frame.Renderer = ren;
  vtkNew<vtkMRGIImperfectShadowMaps> ism;
  ism->SetPointsPerVPL(64);
  MRGI_TEST_CHECK(ism->Update(frame, tex, 1));
  MRGI_TEST_CHECK(ism->GetNumberOfTriangles() == 6);
  attributes->SetBlockVisibility(planeB->GetOutput(), false);
  compositeMapper->Modified();
  window->Render();
  MRGI_TEST_CHECK(ism->Update(frame, tex, 1));
  MRGI_TEST_CHECK(ism->GetNumberOfTriangles() == 2);

  // An assembly moved by 3 in z: its part's points lie at z = 3.
  ren->RemoveActor(compositeActor);
  vtkNew<vtkPolyDataMapper> partMapper;
  partMapper->SetInputConnection(planeA->GetOutputPort());
  vtkNew<vtkActor> part;
  part->SetMapper(partMapper);
  vtkNew<vtkAssembly> assembly;
  assembly->AddPart(part);
  assembly->SetPosition(0.0, 0.0, 3.0);
  ren->AddViewProp(assembly);
  window->Render();
  MRGI_TEST_CHECK(ism->Update(frame, tex, 1));
  MRGI_TEST_CHECK(ism->GetNumberOfTriangles() == 2);
  for (int i = 0; i < 64; ++i)
  {
    MRGI_TEST_CHECK(std::fabs(ism->GetPointPositions()[3 * i + 2] - 3.0f) < 1e-6f);
  }
  tex->ReleaseGraphicsResources(window);
  ism->ReleaseGraphicsResources(window);
}
}

int main(int argc, char* argv[])
{
  return mrgitest::RunCases(
    argc, argv, { MRGI_TEST_CASE(RenderParity), MRGI_TEST_CASE(UpdateScene), MRGI_TEST_CASE(PointCloud),
                    MRGI_TEST_CASE(CompositeAndAssembly) });
}
