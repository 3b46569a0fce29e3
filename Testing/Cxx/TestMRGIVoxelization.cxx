// The GPU's screen-space voxelization (vtkMRGIVoxelization,
// nichols-penmatsa-wyman-2010 section 3.3) against its C twin
// (mrgi_voxel_voxelize, mrgi_voxel.h) on the same triangles, projection and
// [near, far]: the Cornell box (perspective and parallel, and with [near,
// far] cutting through it), random boxes with actor transforms, an assembly,
// a mirrored box, a translucent and an invisible actor, spheres and a floor
// seen at a grazing angle, a composite data set (ParaView's input) against
// the same polydata as plain actors; voxel buffers of 128^2, window size, NPOT 97x61,
// anisotropic and larger than the window, and 1x1.
//
// The twin needs fragments: this test rasterizes the triangles itself at the
// voxel pixel centres (homogeneous edge functions in double), with the
// fragment's depth and half span from the triangle's plane as the GPU's 2x2
// quads see it (fine derivatives, helper pixels extrapolating the plane).
// The clamp is the triangle clipped to the voxel pixel's square
// (mrgi_voxel_triangle_pixel_range(), in float from the vertices' voxel
// coordinates, as the geometry shader passes them).
//
// What may differ (mrgi_voxel.h section 5): a slice boundary within float
// rounding of lo or hi (the differing bit is next to a set bit of the other
// buffer), and fragments whose existence is decided by rounding (pixel centre
// within 0.01 pixel of a triangle edge: llvmpipe snaps vertices to 1/256
// pixel; depth within 1e-4 of the range of near or far: clipping). Every
// differing bit must be one of these, and fewer than 0.5% of the voxel pixels
// may hold slice-rounding differences. Tie differences are printed, not
// bounded: an edge-on face whose line passes through pixel centres (the
// parallel Cornell box at 300x7: the floor) lights a whole row or not. A
// deliberately wrong near depth given to the twin must fail this comparison.
#include "vtk_glew.h"

#include "mrgiPassSceneFixture.h"
#include "mrgiTestUtilities.h"
#include "mrgiVoxelTestUtilities.h"

#include "vtkActor.h"
#include "vtkAssembly.h"
#include "vtkCamera.h"
#include "vtkCommand.h"
#include "vtkCompositeDataDisplayAttributes.h"
#include "vtkCompositePolyDataMapper2.h"
#include "vtkCubeSource.h"
#include "vtkDataArray.h"
#include "vtkMRGISceneBuilder.h"
#include "vtkMRGIVoxelization.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkMinimalStandardRandomSequence.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkPlaneSource.h"
#include "vtkPolyData.h"
#include "vtkPolyDataAlgorithm.h"
#include "vtkPolyDataMapper.h"
#include "vtkProp3DCollection.h"
#include "vtkPropCollection.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"
#include "vtkTextureObject.h"
#include "vtkTriangleFilter.h"
#include "vtkTypeUInt32Array.h"

#include "mrgi_voxel.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

namespace
{
using mrgitest::DepthRange;
using mrgitest::MakeActor;
using mrgitest::SceneTriangles;
using mrgitest::Triangle;
struct Twin
{
  std::vector<uint32_t> Voxels;    // the C twin's buffer
  std::vector<uint32_t> Tolerance; // masks of fragments decided by rounding
  size_t Fragments = 0;
  size_t Uncertain = 0;
};

const double EdgeEpsilon = 0.01; // pixels

// Rasterize `tris` (eye space) at the voxel pixel centres of `grid` and run
// the C twin on the fragments.
void RunTwin(const std::vector<Triangle>& tris, const mrgi_voxel_grid& grid,
  const mrgi_voxel_projection& proj, Twin& twin)
{
  const int W = grid.width, H = grid.height;
  const size_t words = mrgi_voxel_buffer_words(&grid);
  twin.Voxels.assign(words, 0u);
  twin.Tolerance.assign(words, 0u);
  twin.Fragments = twin.Uncertain = 0;
  const double depthEpsilon = 1e-4 * (static_cast<double>(grid.far_depth) - grid.near_depth);
  std::vector<mrgi_voxel_fragment> fragments;
  for (const Triangle& t : tris)
  {
    double h[3][3], d[3];
    bool allFront = true;
    for (int i = 0; i < 3; ++i)
    {
      const double x = t[3 * i], y = t[3 * i + 1], z = t[3 * i + 2];
      d[i] = -z;
      const double w = proj.parallel ? 1.0 : d[i];
      allFront = allFront && w > 0;
      // (u w, v w, w): u = (ndc_x + 1) VW / 2, ndc_x = sx x / w + ox.
      h[i][0] = (proj.scale_x * x + (proj.offset_x + 1.0) * w) * 0.5 * W;
      h[i][1] = (proj.scale_y * y + (proj.offset_y + 1.0) * w) * 0.5 * H;
      h[i][2] = w;
    }
    MRGI_TEST_CHECK(allFront); // the test scenes keep every vertex in front of the eye
    double e[3][3];
    for (int i = 0; i < 3; ++i)
    {
      const double* a = h[(i + 1) % 3];
      const double* b = h[(i + 2) % 3];
      vtkMath::Cross(a, b, e[i]);
    }
    const double det = vtkMath::Dot(h[0], e[0]);
    if (det == 0.0)
    {
      continue; // no area on screen: no fragments
    }
    double len[3];
    for (int i = 0; i < 3; ++i)
    {
      len[i] = std::hypot(e[i][0], e[i][1]);
    }
    float tu[3], tv[3], td[3], tw[3];
    for (int i = 0; i < 3; ++i)
    {
      tu[i] = static_cast<float>(h[i][0] / h[i][2]);
      tv[i] = static_cast<float>(h[i][1] / h[i][2]);
      td[i] = static_cast<float>(d[i]);
      tw[i] = static_cast<float>(h[i][2]);
    }
    const float dmin = static_cast<float>(std::min({ d[0], d[1], d[2] }));
    const float dmax = static_cast<float>(std::max({ d[0], d[1], d[2] }));
    double umin = 1e300, umax = -1e300, vmin = 1e300, vmax = -1e300;
    for (int i = 0; i < 3; ++i)
    {
      umin = std::min(umin, h[i][0] / h[i][2]);
      umax = std::max(umax, h[i][0] / h[i][2]);
      vmin = std::min(vmin, h[i][1] / h[i][2]);
      vmax = std::max(vmax, h[i][1] / h[i][2]);
    }
    const int x0 = std::max(0, static_cast<int>(std::floor(umin)) - 1);
    const int x1 = std::min(W - 1, static_cast<int>(std::ceil(umax)) + 1);
    const int y0 = std::max(0, static_cast<int>(std::floor(vmin)) - 1);
    const int y1 = std::min(H - 1, static_cast<int>(std::ceil(vmax)) + 1);
    // Linear depth of the triangle's plane at window point (px, py).
    auto planeDepth = [&](double px, double py) {
      double b[3], s = 0, bd = 0;
      for (int i = 0; i < 3; ++i)
      {
        b[i] = e[i][0] * px + e[i][1] * py + e[i][2];
        s += b[i];
        bd += b[i] * d[i];
      }
      return bd / s;
    };
    for (int y = y0; y <= y1; ++y)
    {
      for (int x = x0; x <= x1; ++x)
      {
        const double px = x + 0.5, py = y + 0.5;
        double b[3], s = 0;
        for (int i = 0; i < 3; ++i)
        {
          b[i] = e[i][0] * px + e[i][1] * py + e[i][2];
          s += b[i];
        }
        if (s == 0.0)
        {
          continue;
        }
        const double sgn = s > 0 ? 1.0 : -1.0;
        double edge = 1e300;
        bool inside = true;
        for (int i = 0; i < 3; ++i)
        {
          inside = inside && b[i] * sgn >= 0.0;
          if (len[i] > 0)
          {
            edge = std::min(edge, b[i] * sgn / len[i]);
          }
        }
        if (edge < -EdgeEpsilon)
        {
          continue; // certainly outside
        }
        const double depth = (b[0] * d[0] + b[1] * d[1] + b[2] * d[2]) / s;
        if (!proj.parallel && !(depth > 0))
        {
          continue;
        }
        // The GPU's derivatives: differences across the 2x2 quad (even
        // origin), in this fragment's row and column.
        const int qx = x & ~1, qy = y & ~1;
        const double ddx = planeDepth(qx + 1.5, py) - planeDepth(qx + 0.5, py);
        const double ddy = planeDepth(px, qy + 1.5) - planeDepth(px, qy + 0.5);
        const double half = 0.5 * (std::fabs(ddx) + std::fabs(ddy));
        // The clamp: the triangle's depths inside this pixel (mrgi_voxel.h section 5).
        float range[2] = { dmin, dmax };
        mrgi_voxel_triangle_pixel_range(tu, tv, td, tw, x, y, range);
        mrgi_voxel_fragment f = { x, y, static_cast<float>(depth), static_cast<float>(half),
          range[0], range[1] };
        if (inside)
        {
          fragments.push_back(f);
        }
        const bool edgeTie = edge <= EdgeEpsilon;
        const bool depthTie = std::fabs(depth - grid.near_depth) <= depthEpsilon ||
          std::fabs(depth - grid.far_depth) <= depthEpsilon;
        if (edgeTie || depthTie)
        {
          // Either way is right: its mask (depth brought into the range) is tolerated.
          uint32_t mask[MRGI_VOXEL_MAX_WORDS];
          const float clamped = std::min(std::max(f.depth, grid.near_depth), grid.far_depth);
          mrgi_voxel_fragment_mask(&grid, clamped, f.half_span, range[0], range[1], mask);
          uint32_t* texel = twin.Tolerance.data() + mrgi_voxel_index(&grid, x, y);
          for (int c = 0; c < mrgi_voxel_pixel_words(&grid); ++c)
          {
            texel[c] |= mask[c];
          }
          ++twin.Uncertain;
        }
      }
    }
  }
  mrgi_voxel_info info;
  mrgi_error err;
  MRGI_TEST_CHECK(mrgi_voxel_voxelize(&grid, fragments.data(), fragments.size(),
                    twin.Voxels.data(), words, &info, &err) == MRGI_OK);
  twin.Fragments = fragments.size();
}

inline bool Bit(const uint32_t* texel, int s, int slices)
{
  return s >= 0 && s < slices &&
    ((texel[mrgi_voxel_slice_channel(s)] >> mrgi_voxel_slice_bit(s)) & 1u) != 0;
}

// Differences between the GPU and the twin, per voxel pixel:
// - tie pixels: every differing bit lies in (or next to) the mask of a
//   fragment whose existence rounding decides (edge or near/far ties);
// - slice pixels: some differing bit is not a tie but is next to a set bit of
//   the other buffer (lo or hi within float rounding of a slice boundary);
// - unexplained bits: neither (a real disagreement).
struct Comparison
{
  size_t Pixels = 0, MismatchPixels = 0, TiePixels = 0, SlicePixels = 0;
  size_t MismatchBits = 0, Unexplained = 0;
  size_t GPUBits = 0, TwinBits = 0;
  double Fraction() const { return Pixels ? static_cast<double>(MismatchPixels) / Pixels : 0.0; }
  double SliceFraction() const
  {
    return Pixels ? static_cast<double>(SlicePixels) / Pixels : 0.0;
  }
  bool Passes() const { return SliceFraction() < 0.005 && Unexplained == 0; }
};

Comparison Compare(const mrgi_voxel_grid& grid, const uint32_t* gpu, const Twin& twin)
{
  Comparison c;
  c.Pixels = static_cast<size_t>(grid.width) * static_cast<size_t>(grid.height);
  for (size_t p = 0; p < c.Pixels; ++p)
  {
    const size_t words = static_cast<size_t>(mrgi_voxel_pixel_words(&grid));
    const uint32_t* g = gpu + words * p;
    const uint32_t* t = twin.Voxels.data() + words * p;
    const uint32_t* tol = twin.Tolerance.data() + words * p;
    const int S = grid.slices;
    bool differs = false, sliceOnly = false;
    for (int s = 0; s < S; ++s)
    {
      const bool a = Bit(g, s, S), b = Bit(t, s, S);
      c.GPUBits += a;
      c.TwinBits += b;
      if (a == b)
      {
        continue;
      }
      differs = true;
      ++c.MismatchBits;
      const uint32_t* other = a ? t : g;
      const bool tie = Bit(tol, s - 1, S) || Bit(tol, s, S) || Bit(tol, s + 1, S);
      const bool sliceRounding = Bit(other, s - 1, S) || Bit(other, s + 1, S);
      if (!tie)
      {
        sliceOnly = true;
        if (!sliceRounding)
        {
          ++c.Unexplained;
        }
      }
    }
    c.MismatchPixels += differs;
    c.SlicePixels += sliceOnly;
    c.TiePixels += differs && !sliceOnly;
  }
  return c;
}

// Voxelize on the GPU and compare with the twin; returns the comparison.
// More than 128 slices draw into one render target per 128 (mrgi_voxel.h
// section 1): their bits must be the twin's too.
Comparison RunCase(const char* name, vtkRenderWindow* window, vtkRenderer* ren,
  vtkMRGIVoxelization* vox, int vw, int vh, double nearDepth, double farDepth,
  int slices = MRGI_VOXEL_DEFAULT_SLICES)
{
  vox->SetVoxelSize(vw, vh);
  vox->SetNumberOfSlices(slices);
  MRGI_TEST_CHECK(vox->Voxelize(ren, nearDepth, farDepth));
  MRGI_TEST_CHECK(vox->GetLastNumberOfSlices() == slices);
  mrgi_voxel_grid grid, expectedGrid;
  mrgi_voxel_projection proj, cameraProj;
  MRGI_TEST_CHECK(vox->GetGrid(&grid, &proj));
  mrgi_error err;
  MRGI_TEST_CHECK(
    mrgi_voxel_grid_init(&expectedGrid, vw, vh, slices, nearDepth, farDepth, &err) == MRGI_OK);
  MRGI_TEST_CHECK(std::memcmp(&grid, &expectedGrid, sizeof(grid)) == 0);
  // The projection is the window's: the camera's, at the renderer's aspect.
  vtkCamera* camera = ren->GetActiveCamera();
  const int* size = window->GetSize();
  const mrgi_multires_projection cam = { camera->GetParallelProjection(), camera->GetViewAngle(),
    camera->GetParallelScale() };
  MRGI_TEST_CHECK(mrgi_voxel_projection_from_camera(&cameraProj, &cam,
                    static_cast<double>(size[0]) / size[1], &err) == MRGI_OK);
  MRGI_TEST_CHECK(proj.parallel == cameraProj.parallel);
  MRGI_TEST_CHECK(std::fabs(proj.scale_x - cameraProj.scale_x) <= 1e-6 * cameraProj.scale_x);
  MRGI_TEST_CHECK(std::fabs(proj.scale_y - cameraProj.scale_y) <= 1e-6 * cameraProj.scale_y);
  MRGI_TEST_CHECK(std::fabs(proj.offset_x) < 1e-6 && std::fabs(proj.offset_y) < 1e-6);
  double worldToView[16];
  MRGI_TEST_CHECK(vox->GetLastWorldToView(worldToView));
  vtkMatrix4x4* view = camera->GetModelViewTransformMatrix();
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      MRGI_TEST_CHECK(worldToView[4 * c + r] == view->GetElement(r, c));
    }
  }
  int last[2];
  vox->GetLastVoxelSize(last);
  MRGI_TEST_CHECK(last[0] == vw && last[1] == vh);
  vtkTextureObject* texture = vox->GetVoxelTexture();
  MRGI_TEST_CHECK(texture && texture->GetTarget() == GL_TEXTURE_3D);

  vtkNew<vtkTypeUInt32Array> gpu;
  MRGI_TEST_CHECK(vox->ReadVoxels(window, gpu));
  MRGI_TEST_CHECK(gpu->GetNumberOfComponents() == slices / MRGI_VOXEL_CHANNEL_BITS);
  MRGI_TEST_CHECK(gpu->GetNumberOfTuples() == static_cast<vtkIdType>(vw) * vh);

  const std::vector<Triangle> tris = SceneTriangles(ren);
  MRGI_TEST_CHECK(vox->GetNumberOfTriangles() == static_cast<vtkIdType>(tris.size()));
  Twin twin;
  RunTwin(tris, grid, proj, twin);
  const Comparison c = Compare(grid, gpu->GetPointer(0), twin);
  std::printf("%-34s %4dx%-4dx%-3d [%9.4g, %9.4g] %6zu tris %8zu frags (%5zu edge/depth ties): "
              "bits gpu %8zu twin %8zu; differing: %zu bits in %zu of %zu pixels (%.4f%%; "
              "ties %zu, slice rounding %zu = %.4f%%), unexplained bits %zu\n",
    name, vw, vh, slices, nearDepth, farDepth, tris.size(), twin.Fragments, twin.Uncertain,
    c.GPUBits, c.TwinBits, c.MismatchBits, c.MismatchPixels, c.Pixels, 100.0 * c.Fraction(),
    c.TiePixels, c.SlicePixels, 100.0 * c.SliceFraction(), c.Unexplained);
  MRGI_TEST_CHECK(c.TwinBits > 0 || (vw * vh <= 1));
  MRGI_TEST_CHECK(c.Passes());
  return c;
}

const int WindowW = 150, WindowH = 110;

// The sizes every scene is voxelized at.
struct Size
{
  int W, H;
};
const Size Sizes[] = { { 128, 128 }, { WindowW, WindowH }, { 97, 61 }, { 300, 7 }, { 1, 1 } };

// The Cornell box in a WindowW x WindowH window, rendered once, seen in
// perspective or in parallel projection.
void ShowCornell(vtkRenderer* renderer, vtkRenderWindow* window, bool parallel)
{
  if (parallel)
  {
    renderer->GetActiveCamera()->ParallelProjectionOn();
    renderer->ResetCamera();
  }
  window->Render();
}

void CornellBox(bool parallel)
{
  mrgitest::SceneWindow scene(WindowW, WindowH, "cornell");
  vtkRenderWindow* window = scene.Window;
  vtkRenderer* renderer = scene.Renderer;
  ShowCornell(renderer, window, parallel);
  vtkNew<vtkMRGIVoxelization> vox;
  double range[2];
  DepthRange(SceneTriangles(renderer), range);
  const double pad = 0.01 * (range[1] - range[0]);
  const std::string name = std::string("cornell ") + (parallel ? "parallel" : "perspective");
  for (const Size& s : Sizes)
  {
    RunCase(name.c_str(), window, renderer, vox, s.W, s.H, range[0] - pad, range[1] + pad);
  }
  // [near, far] cutting through the box: clipping at both planes.
  const double n = range[0] + 0.3 * (range[1] - range[0]);
  const double f = range[0] + 0.8 * (range[1] - range[0]);
  RunCase((name + ", cut").c_str(), window, renderer, vox, 128, 128, n, f);
  RunCase((name + ", cut").c_str(), window, renderer, vox, 97, 61, n, f);
  // Thinner slices: two to four render targets in one draw.
  for (int slices : { 256, 384, 512 })
  {
    RunCase(name.c_str(), window, renderer, vox, 128, 128, range[0] - pad, range[1] + pad, slices);
    RunCase((name + ", cut").c_str(), window, renderer, vox, 97, 61, n, f, slices);
  }
  vox->SetNumberOfSlices(MRGI_VOXEL_DEFAULT_SLICES);

  if (!parallel)
  {
    // The comparison can fail: the twin with a wrong near depth.
    vox->SetVoxelSize(128, 128);
    MRGI_TEST_CHECK(vox->Voxelize(renderer, range[0] - pad, range[1] + pad));
    vtkNew<vtkTypeUInt32Array> gpu;
    MRGI_TEST_CHECK(vox->ReadVoxels(window, gpu));
    mrgi_voxel_grid grid;
    mrgi_voxel_projection proj;
    MRGI_TEST_CHECK(vox->GetGrid(&grid, &proj));
    const double thickness = (grid.far_depth - grid.near_depth) / grid.slices;
    for (double shift : { 0.5, 3.0 })
    {
      mrgi_voxel_grid wrong;
      mrgi_error err;
      MRGI_TEST_CHECK(
        mrgi_voxel_grid_init(&wrong, grid.width, grid.height, MRGI_VOXEL_DEFAULT_SLICES,
          grid.near_depth + shift * thickness, grid.far_depth, &err) == MRGI_OK);
      Twin twin;
      RunTwin(SceneTriangles(renderer), wrong, proj, twin);
      const Comparison c = Compare(wrong, gpu->GetPointer(0), twin);
      std::printf("  twin with near + %.1f slices: differing pixels %.2f%% (slice rounding "
                  "%.2f%%), %zu unexplained bits -> %s (must fail)\n",
        shift, 100.0 * c.Fraction(), 100.0 * c.SliceFraction(), c.Unexplained,
        c.Passes() ? "passes" : "fails");
      MRGI_TEST_CHECK(!c.Passes());
    }
  }
  vox->ReleaseGraphicsResources(window);
}

// The automatic (isotropic) size is the default, is what ComputeVoxelSize()
// says and the core computes for the camera and range, and is what the GPU
// voxelizes with; a fixed size turns it off, AutomaticVoxelSizeOn() back on.
void AutomaticSize(bool parallel)
{
  mrgitest::SceneWindow scene(WindowW, WindowH, "cornell");
  vtkRenderWindow* window = scene.Window;
  vtkRenderer* renderer = scene.Renderer;
  ShowCornell(renderer, window, parallel);
  vtkNew<vtkMRGIVoxelization> vox;
  MRGI_TEST_CHECK(vox->GetAutomaticVoxelSize());
  double range[2];
  MRGI_TEST_CHECK(vtkMRGIVoxelization::ComputeDepthRange(renderer, range));
  vtkCamera* camera = renderer->GetActiveCamera();
  const mrgi_multires_projection cam = { camera->GetParallelProjection(), camera->GetViewAngle(),
    camera->GetParallelScale() };
  mrgi_voxel_projection proj;
  MRGI_TEST_CHECK(mrgi_voxel_projection_from_camera(
                    &proj, &cam, static_cast<double>(WindowW) / WindowH, nullptr) == MRGI_OK);
  int32_t expected[2];
  MRGI_TEST_CHECK(mrgi_voxel_isotropic_size(&proj, MRGI_VOXEL_DEFAULT_SLICES, range[0], range[1],
                    expected, nullptr) == MRGI_OK);
  int computed[2], last[2];
  MRGI_TEST_CHECK(vox->ComputeVoxelSize(renderer, range[0], range[1], computed));
  MRGI_TEST_CHECK(computed[0] == expected[0] && computed[1] == expected[1]);
  MRGI_TEST_CHECK(vox->Voxelize(renderer, range[0], range[1]));
  vox->GetLastVoxelSize(last);
  std::printf("cornell %s, depth range [%.1f, %.1f]: automatic voxel size %d x %d\n",
    parallel ? "parallel" : "perspective", range[0], range[1], last[0], last[1]);
  MRGI_TEST_CHECK(last[0] == expected[0] && last[1] == expected[1]);
  // The box is shallow seen from the front: finer than the fixed default.
  MRGI_TEST_CHECK(last[1] > MRGI_VOXEL_DEFAULT_SIZE);
  // Wider than tall, as the window.
  MRGI_TEST_CHECK(last[0] > last[1]);
  vox->SetVoxelSide(100);
  MRGI_TEST_CHECK(!vox->GetAutomaticVoxelSize());
  MRGI_TEST_CHECK(vox->Voxelize(renderer, range[0], range[1]));
  vox->GetLastVoxelSize(last);
  MRGI_TEST_CHECK(last[0] == 100 && last[1] == 100);
  vox->AutomaticVoxelSizeOn();
  MRGI_TEST_CHECK(vox->Voxelize(renderer, range[0], range[1]));
  vox->GetLastVoxelSize(last);
  MRGI_TEST_CHECK(last[0] == expected[0] && last[1] == expected[1]);
  // More slices refine the depth only: the automatic side stays 128 slices'.
  vox->SetNumberOfSlices(512);
  MRGI_TEST_CHECK(vox->Voxelize(renderer, range[0], range[1]));
  vox->GetLastVoxelSize(last);
  MRGI_TEST_CHECK(last[0] == expected[0] && last[1] == expected[1]);
  MRGI_TEST_CHECK(vox->GetLastNumberOfSlices() == 512);
  vox->SetNumberOfSlices(MRGI_VOXEL_DEFAULT_SLICES);
  // Without a renderer the automatic size cannot be computed: VoxelSize.
  MRGI_TEST_CHECK(!vox->ComputeVoxelSize(nullptr, range[0], range[1], computed));
  MRGI_TEST_CHECK(computed[0] == 100 && computed[1] == 100);
  vox->ReleaseGraphicsResources(window);
}

void RandomBoxes()
{
  vtkSmartPointer<vtkRenderWindow> window = mrgitest::HeadlessWindow(WindowW, WindowH);
  vtkNew<vtkRenderer> renderer;
  window->AddRenderer(renderer);
  vtkNew<vtkMinimalStandardRandomSequence> rng;
  rng->SetSeed(5);
  auto uniform = [&](double lo, double hi) {
    rng->Next();
    return rng->GetRangeValue(lo, hi);
  };
  std::vector<vtkSmartPointer<vtkActor>> boxes;
  for (int k = 0; k < 12; ++k)
  {
    vtkNew<vtkCubeSource> cube; // quads: triangulated by the voxelization
    cube->SetXLength(uniform(0.3, 2.5));
    cube->SetYLength(uniform(0.3, 2.5));
    cube->SetZLength(uniform(0.3, 2.5));
    auto actor = MakeActor(cube);
    actor->SetPosition(uniform(-4, 4), uniform(-4, 4), uniform(-4, 4));
    actor->SetOrientation(uniform(0, 360), uniform(0, 360), uniform(0, 360));
    renderer->AddActor(actor);
    boxes.push_back(actor);
  }
  boxes[3]->SetScale(-1.2, 0.8, 1.0); // mirrored: no culling, winding does not matter
  boxes[5]->GetProperty()->SetOpacity(0.5); // translucent: skipped
  boxes[7]->VisibilityOff();                // invisible: not drawn
  // An assembly of two parts, moved as a whole.
  vtkNew<vtkAssembly> assembly;
  vtkNew<vtkCubeSource> partCube;
  vtkNew<vtkSphereSource> partSphere;
  partSphere->SetThetaResolution(24);
  partSphere->SetPhiResolution(16);
  auto part1 = MakeActor(partCube);
  auto part2 = MakeActor(partSphere);
  part2->SetPosition(1.5, 0, 0);
  assembly->AddPart(part1);
  assembly->AddPart(part2);
  assembly->SetPosition(0.5, -1, 2);
  assembly->RotateZ(30);
  renderer->AddViewProp(assembly);
  // A sphere whose source changes below (cache invalidation).
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(32);
  sphere->SetPhiResolution(24);
  sphere->SetCenter(-2, 2, 0);
  auto sphereActor = MakeActor(sphere);
  renderer->AddActor(sphereActor);
  renderer->ResetCamera();
  renderer->GetActiveCamera()->Azimuth(20);
  renderer->GetActiveCamera()->Elevation(15);
  renderer->ResetCameraClippingRange();

  // The window's image before and after voxelizing: the pass leaves GL state alone.
  window->Render();
  vtkSmartPointer<vtkImageData> before = mrgitest::GrabRGB(window);
  vtkNew<vtkMRGIVoxelization> vox;
  double range[2];
  DepthRange(SceneTriangles(renderer), range);
  for (const Size& s : Sizes)
  {
    RunCase("random boxes", window, renderer, vox, s.W, s.H, range[0], range[1]);
  }
  // 12 boxes + sphere + 2 assembly parts - invisible - translucent.
  std::printf("  drawn props %d, skipped %d\n", vox->GetNumberOfDrawnProps(),
    vox->GetNumberOfSkippedProps());
  MRGI_TEST_CHECK(vox->GetNumberOfDrawnProps() == 13);
  MRGI_TEST_CHECK(vox->GetNumberOfSkippedProps() == 1);
  window->Render();
  vtkSmartPointer<vtkImageData> after = mrgitest::GrabRGB(window);
  vtkDataArray* a = before->GetPointData()->GetScalars();
  vtkDataArray* b = after->GetPointData()->GetScalars();
  size_t changed = 0;
  for (vtkIdType i = 0; i < a->GetNumberOfValues(); ++i)
  {
    changed += a->GetVariantValue(i).ToInt() != b->GetVariantValue(i).ToInt();
  }
  std::printf("  window pixels changed by voxelizing: %zu\n", changed);
  MRGI_TEST_CHECK(changed == 0);

  // Moving actors and changing data: the cached buffers follow.
  boxes[0]->AddPosition(0.7, -0.3, 0.2);
  assembly->RotateX(25);
  sphere->SetRadius(1.7);
  sphere->SetThetaResolution(20);
  RunCase("random boxes, moved and modified", window, renderer, vox, 128, 128, range[0], range[1]);
  // A voxelization that fails keeps the previous buffer.
  vtkNew<vtkTypeUInt32Array> kept, still;
  MRGI_TEST_CHECK(vox->ReadVoxels(window, kept));
  vtkNew<mrgitest::ErrorCatcher> errors;
  vox->AddObserver(vtkCommand::ErrorEvent, errors);
  MRGI_TEST_CHECK(!vox->Voxelize(renderer, 3.0, 2.0));
  MRGI_TEST_CHECK(errors->Caught("must be less than far"));
  MRGI_TEST_CHECK(vox->GetVoxelTexture() != nullptr);
  MRGI_TEST_CHECK(vox->ReadVoxels(window, still));
  MRGI_TEST_CHECK(still->GetNumberOfValues() == kept->GetNumberOfValues());
  MRGI_TEST_CHECK(std::equal(kept->GetPointer(0), kept->GetPointer(0) + kept->GetNumberOfValues(),
    still->GetPointer(0)));
  // WriteVoxels (how the OR of MPI ranks' voxels comes back): what is
  // written is read back; an array of another size is refused, the voxels
  // kept.
  {
    vtkNew<vtkTypeUInt32Array> flipped, back, small;
    flipped->DeepCopy(kept);
    for (vtkIdType i = 0; i < flipped->GetNumberOfValues(); ++i)
    {
      flipped->SetValue(i, ~kept->GetValue(i) ^ static_cast<vtkTypeUInt32>(i));
    }
    MRGI_TEST_CHECK(vox->WriteVoxels(window, flipped));
    MRGI_TEST_CHECK(vox->ReadVoxels(window, back));
    MRGI_TEST_CHECK(back->GetNumberOfValues() == flipped->GetNumberOfValues());
    MRGI_TEST_CHECK(std::equal(flipped->GetPointer(0),
      flipped->GetPointer(0) + flipped->GetNumberOfValues(), back->GetPointer(0)));
    small->SetNumberOfComponents(4);
    small->SetNumberOfTuples(3);
    MRGI_TEST_CHECK(!vox->WriteVoxels(window, small));
    MRGI_TEST_CHECK(errors->Caught("is not"));
    MRGI_TEST_CHECK(vox->ReadVoxels(window, back));
    MRGI_TEST_CHECK(std::equal(flipped->GetPointer(0),
      flipped->GetPointer(0) + flipped->GetNumberOfValues(), back->GetPointer(0)));
    MRGI_TEST_CHECK(vox->WriteVoxels(window, kept));
  }

  // Another window: the resources move there (freed in the first one), and back.
  {
    vtkSmartPointer<vtkRenderWindow> other = mrgitest::HeadlessWindow(64, 48);
    vtkNew<vtkRenderer> otherRenderer;
    other->AddRenderer(otherRenderer);
    vtkNew<vtkSphereSource> ball;
    otherRenderer->AddActor(MakeActor(ball));
    otherRenderer->ResetCamera();
    other->Render();
    const double dist = otherRenderer->GetActiveCamera()->GetDistance();
    RunCase("other window", other, otherRenderer, vox, 40, 30, dist - 0.6, dist + 0.6);
    MRGI_TEST_CHECK(!vox->ReadVoxels(window, still));
    MRGI_TEST_CHECK(errors->Caught("another window"));
    RunCase("random boxes, back in its window", window, renderer, vox, 97, 61, range[0], range[1]);
    MRGI_TEST_CHECK(!vox->ReadVoxels(other, still));
    MRGI_TEST_CHECK(errors->Caught("another window"));
  }
  vox->ReleaseGraphicsResources(window);
}

// `vox` is shared by calls: each call's window goes away still holding its
// resources, which the next call must forget, not free.
void Grazing(bool parallel, vtkMRGIVoxelization* vox)
{
  vtkSmartPointer<vtkRenderWindow> window = mrgitest::HeadlessWindow(WindowW, WindowH);
  vtkNew<vtkRenderer> renderer;
  window->AddRenderer(renderer);
  vtkNew<vtkPlaneSource> floor;
  floor->SetOrigin(-10, 0, -10);
  floor->SetPoint1(10, 0, -10);
  floor->SetPoint2(-10, 0, 10);
  floor->SetResolution(16, 16);
  renderer->AddActor(MakeActor(floor));
  vtkNew<vtkMinimalStandardRandomSequence> rng;
  rng->SetSeed(11);
  for (int k = 0; k < 6; ++k)
  {
    vtkNew<vtkSphereSource> sphere;
    rng->Next();
    const double x = rng->GetRangeValue(-6, 6);
    rng->Next();
    const double z = rng->GetRangeValue(-8, 6);
    rng->Next();
    const double r = rng->GetRangeValue(0.4, 1.5);
    sphere->SetCenter(x, r, z);
    sphere->SetRadius(r);
    sphere->SetThetaResolution(40);
    sphere->SetPhiResolution(30);
    renderer->AddActor(MakeActor(sphere));
  }
  // Eye 0.25 above a floor 20 long: the floor is seen at about 1 degree.
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(0.3, 0.25, 16);
  camera->SetFocalPoint(0, 0.1, 0);
  camera->SetViewUp(0, 1, 0);
  camera->SetViewAngle(40);
  if (parallel)
  {
    camera->ParallelProjectionOn();
    camera->SetParallelScale(4);
  }
  renderer->ResetCameraClippingRange();
  window->Render();
  double range[2];
  DepthRange(SceneTriangles(renderer), range);
  const std::string name = std::string("grazing floor+spheres ") + (parallel ? "parallel" : "perspective");
  for (const Size& s : Sizes)
  {
    RunCase(name.c_str(), window, renderer, vox, s.W, s.H, range[0], range[1]);
  }
}

// ParaView's geometry representations draw a vtkMultiBlockDataSet through
// vtkCompositePolyDataMapper2: its visible, opaque polydata leaves must
// voxelize exactly as the same polydata drawn by plain actors, with the
// actor's matrix; a hidden and a translucent block are left out.
void CompositeInput()
{
  vtkSmartPointer<vtkRenderWindow> window = mrgitest::HeadlessWindow(WindowW, WindowH);
  vtkNew<vtkRenderer> renderer;
  window->AddRenderer(renderer);
  auto output = [](vtkPolyDataAlgorithm* source) {
    source->Update();
    return vtkSmartPointer<vtkPolyData>(source->GetOutput());
  };
  vtkNew<vtkCubeSource> cubeSource;
  cubeSource->SetXLength(2.0);
  vtkNew<vtkSphereSource> sphereSource;
  sphereSource->SetCenter(1.5, 1.0, -0.5);
  vtkNew<vtkCubeSource> hiddenSource;
  hiddenSource->SetCenter(-2.0, 0.0, 0.0);
  vtkNew<vtkCubeSource> translucentSource;
  translucentSource->SetCenter(0.0, -2.0, 0.0);
  vtkSmartPointer<vtkPolyData> cube = output(cubeSource), sphere = output(sphereSource),
                               hidden = output(hiddenSource),
                               translucent = output(translucentSource);
  vtkNew<vtkMultiBlockDataSet> blocks;
  blocks->SetNumberOfBlocks(4);
  blocks->SetBlock(0, cube);
  blocks->SetBlock(1, sphere);
  blocks->SetBlock(2, hidden);
  blocks->SetBlock(3, translucent);
  vtkNew<vtkCompositePolyDataMapper2> compositeMapper;
  compositeMapper->SetInputDataObject(blocks);
  vtkNew<vtkCompositeDataDisplayAttributes> attributes;
  attributes->SetBlockVisibility(hidden, false);
  attributes->SetBlockOpacity(translucent, 0.5);
  compositeMapper->SetCompositeDataDisplayAttributes(attributes);
  vtkNew<vtkActor> compositeActor;
  compositeActor->SetMapper(compositeMapper);
  compositeActor->SetPosition(0.3, -0.2, 0.1);
  compositeActor->RotateY(20);
  renderer->AddActor(compositeActor);
  renderer->ResetCamera();
  renderer->GetActiveCamera()->Azimuth(25);
  renderer->GetActiveCamera()->Elevation(10);
  renderer->ResetCameraClippingRange();
  window->Render();
  const double dist = renderer->GetActiveCamera()->GetDistance();
  const double nearDepth = dist - 4.0, farDepth = dist + 4.0;

  vtkNew<vtkMRGIVoxelization> vox;
  vtkNew<vtkTypeUInt32Array> fromComposite, fromActors;
  MRGI_TEST_CHECK(vox->Voxelize(renderer, nearDepth, farDepth));
  MRGI_TEST_CHECK(vox->ReadVoxels(window, fromComposite));
  std::printf("  composite: drawn %d, skipped %d, triangles %lld\n", vox->GetNumberOfDrawnProps(),
    vox->GetNumberOfSkippedProps(), static_cast<long long>(vox->GetNumberOfTriangles()));
  MRGI_TEST_CHECK(vox->GetNumberOfDrawnProps() == 2); // the cube and the sphere
  MRGI_TEST_CHECK(vox->GetNumberOfSkippedProps() == 0);
  const vtkIdType compositeTriangles = vox->GetNumberOfTriangles();

  // The same two polydata as plain actors with the same matrix.
  renderer->RemoveActor(compositeActor);
  for (vtkPolyData* data : { cube.Get(), sphere.Get() })
  {
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputData(data);
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    actor->SetUserMatrix(compositeActor->GetMatrix());
    renderer->AddActor(actor);
  }
  window->Render();
  MRGI_TEST_CHECK(vox->Voxelize(renderer, nearDepth, farDepth));
  MRGI_TEST_CHECK(vox->ReadVoxels(window, fromActors));
  MRGI_TEST_CHECK(vox->GetNumberOfTriangles() == compositeTriangles);
  MRGI_TEST_CHECK(fromActors->GetNumberOfValues() == fromComposite->GetNumberOfValues());
  size_t bits = 0, differing = 0;
  for (vtkIdType i = 0; i < fromActors->GetNumberOfValues(); ++i)
  {
    const uint32_t a = fromActors->GetValue(i), b = fromComposite->GetValue(i);
    for (uint32_t x = a, y = a ^ b; x || y; x >>= 1, y >>= 1)
    {
      bits += x & 1u;
      differing += y & 1u;
    }
  }
  std::printf("  composite vs plain actors: %zu bits set, %zu differ\n", bits, differing);
  MRGI_TEST_CHECK(bits > 0);
  MRGI_TEST_CHECK(differing == 0);
  vox->ReleaseGraphicsResources(window);
}

void BadInputs()
{
  vtkNew<mrgitest::ErrorCatcher> errors;
  vtkNew<vtkMRGIVoxelization> vox;
  vox->AddObserver(vtkCommand::ErrorEvent, errors);

  // Size clamping.
  vox->SetVoxelSize(0, 20000);
  MRGI_TEST_CHECK(vox->GetVoxelSize()[0] == 1 && vox->GetVoxelSize()[1] == MRGI_VOXEL_MAX_SIZE);
  vox->SetVoxelSide(-3);
  MRGI_TEST_CHECK(vox->GetVoxelSize()[0] == 1 && vox->GetVoxelSize()[1] == 1);
  vox->SetVoxelSide(MRGI_VOXEL_DEFAULT_SIZE);

  MRGI_TEST_CHECK(!vox->Voxelize(nullptr, 1, 2));
  MRGI_TEST_CHECK(errors->Caught("no renderer"));
  vtkNew<vtkRenderer> lone;
  MRGI_TEST_CHECK(!vox->Voxelize(lone, 1, 2));
  MRGI_TEST_CHECK(errors->Caught("not in an OpenGL render window"));

  // A window that never rendered.
  {
    vtkSmartPointer<vtkRenderWindow> fresh = mrgitest::HeadlessWindow(32, 32);
    vtkNew<vtkRenderer> r;
    fresh->AddRenderer(r);
    r->GetActiveCamera();
    MRGI_TEST_CHECK(!vox->Voxelize(r, 1, 2));
    MRGI_TEST_CHECK(errors->Caught("never rendered"));
  }

  vtkSmartPointer<vtkRenderWindow> window = mrgitest::HeadlessWindow(64, 48);
  vtkNew<vtkRenderer> renderer;
  window->AddRenderer(renderer);
  vtkNew<vtkSphereSource> sphere;
  renderer->AddActor(MakeActor(sphere));
  renderer->ResetCamera();
  window->Render();
  const double dist = renderer->GetActiveCamera()->GetDistance();

  // Nothing voxelized yet.
  vtkNew<vtkTypeUInt32Array> out;
  MRGI_TEST_CHECK(!vox->ReadVoxels(window, out));
  MRGI_TEST_CHECK(errors->Caught("nothing voxelized"));
  MRGI_TEST_CHECK(vox->GetVoxelTexture() == nullptr);
  MRGI_TEST_CHECK(!vox->GetGrid(nullptr, nullptr));

  MRGI_TEST_CHECK(!vox->Voxelize(renderer, dist, dist));
  MRGI_TEST_CHECK(errors->Caught("must be less than far"));
  MRGI_TEST_CHECK(!vox->Voxelize(renderer, dist + 1, dist - 1));
  MRGI_TEST_CHECK(errors->Caught("must be less than far"));
  MRGI_TEST_CHECK(!vox->Voxelize(renderer, std::nan(""), dist));
  MRGI_TEST_CHECK(errors->Caught("not finite"));
  MRGI_TEST_CHECK(!vox->Voxelize(renderer, 1.0, std::numeric_limits<double>::infinity()));
  MRGI_TEST_CHECK(errors->Caught("not finite"));
  // Equal as floats although not as doubles.
  MRGI_TEST_CHECK(!vox->Voxelize(renderer, 1.0, 1.0 + 1e-12));
  MRGI_TEST_CHECK(errors->Caught("empty"));
  MRGI_TEST_CHECK(!vox->Voxelize(renderer, 0.0, dist));
  MRGI_TEST_CHECK(errors->Caught("must be > 0 with a perspective camera"));
  MRGI_TEST_CHECK(vox->GetVoxelTexture() == nullptr);

  // A renderer without a camera, and one of zero size.
  vtkNew<vtkRenderer> noCamera;
  noCamera->SetViewport(0, 0, 0.5, 0.5);
  window->AddRenderer(noCamera);
  MRGI_TEST_CHECK(!vox->Voxelize(noCamera, 1, 2));
  MRGI_TEST_CHECK(errors->Caught("no active camera"));
  vtkNew<vtkRenderer> empty;
  empty->SetViewport(0.5, 0.5, 0.5, 1.0);
  window->AddRenderer(empty);
  empty->GetActiveCamera();
  MRGI_TEST_CHECK(!vox->Voxelize(empty, 1, 2));
  MRGI_TEST_CHECK(errors->Caught("zero size"));

  // Parallel projection: a near depth <= 0 is fine.
  renderer->GetActiveCamera()->ParallelProjectionOn();
  MRGI_TEST_CHECK(vox->Voxelize(renderer, -1.0, dist + 2));
  MRGI_TEST_CHECK(errors->Count == 0);
  MRGI_TEST_CHECK(vox->GetLastParallelProjection());
  MRGI_TEST_CHECK(vox->ReadVoxels(window, out));
  MRGI_TEST_CHECK(out->GetNumberOfTuples() == MRGI_VOXEL_DEFAULT_SIZE * MRGI_VOXEL_DEFAULT_SIZE);
  vox->ReleaseGraphicsResources(window);
  MRGI_TEST_CHECK(vox->GetVoxelTexture() == nullptr);
}
}

int main(int argc, char* argv[])
{
  return mrgitest::RunCases(argc, argv,
    { { "CornellBox", [] { CornellBox(false); } },
      { "CornellBoxParallel", [] { CornellBox(true); } },
      { "AutomaticSize", [] { AutomaticSize(false); } },
      { "AutomaticSizeParallel", [] { AutomaticSize(true); } }, MRGI_TEST_CASE(RandomBoxes),
      { "Grazing",
        [] {
          // One voxelization for both projections' windows.
          vtkNew<vtkMRGIVoxelization> shared;
          Grazing(false, shared);
          Grazing(true, shared);
          // The last window is gone too: forget, then nothing is left to free.
          shared->ReleaseGraphicsResources(nullptr);
        } },
      MRGI_TEST_CASE(CompositeInput), MRGI_TEST_CASE(BadInputs) });
}
