// The GPU VPL-tree gather (vtkMRGIGather::GatherFullTree() and
// GatherVPLTree(), nichols-shopf-wyman-2009 3.5) against its C twin
// mrgi_vpl_tree_gather() on the built-in Cornell box lit by its spot light:
// the RSM and the G-buffer are read back, the tree is built with
// mrgi_vpl_tree_build() and uploaded with vtkMRGIGather::UploadVPLTree().
// 1. E at every gathered receiver within 1e-4 relative RMS of the twin (the
//    gather parity tolerance of TestMRGIParity / TestMRGIMultiresParity), for
//    tau = 1, 0.05 and 0, full resolution and the stenciled multiresolution
//    gather, RSM 64 (one batch of roots) and 256 (two batches: 192 + 64
//    roots); and RSM 256 with every texel lit at tau 0, where receivers
//    on the ceiling pop every nonempty node (measured: with all 256 roots in
//    one batch llvmpipe silently cut the loop, relative RMS 0.015 and fewer
//    VPLs than usable texels; batched, every usable texel is used); and a
//    point light's six cube views (RSM 128, 1,536 roots in two draws);
// 2. nothing written outside the selected texels (stenciled), alpha 1 at
//    gathered receivers;
// 3. the VPLs-per-pixel statistic: the mean within 1e-3 relative of the
//    twin's, the max within 1 (a refinement decided differently in float);
// 4. tau = 1 equals the full gather of the GPU's 256 grid VPLs (1e-4);
// 5. bad input: a NaN or negative tau, an unbuilt tree, a texture of the
//    wrong size and an RSM over MRGI_VPL_TREE_GATHER_MAX_RSM_SIZE are
//    refused with false.
#include "mrgiTestUtilities.h"

#include "vtkCamera.h"
#include "vtkCommand.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMRGIFrameContext.h"
#include "vtkMRGIGather.h"
#include "vtkMRGIMultiresolution.h"
#include "vtkMRGIPass.h"
#include "vtkMRGIReflectiveShadowMapPass.h"
#include "vtkMRGISceneBuilder.h"
#include "vtkMRGIVPLSelection.h"
#include "vtkMath.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkPointData.h"
#include "vtkRenderStepsPass.h"
#include "vtkRenderer.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include "mrgi_gather.h"
#include "mrgi_multires.h"
#include "mrgi_multires_receivers.h"
#include "mrgi_vpl_tree.h"
#include "mrgi_vpl_tree_gather.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include "mrgiGatherTestScene.h"

using namespace mrgigather;

namespace
{

void CheckCounts(vtkMRGIGather* gather, const mrgi_vpl_tree_gather_info& info, const char* what)
{
  const double mean = gather->GetMeanVPLsPerPixel(), max = gather->GetMaxVPLsPerPixel();
  std::printf("  %s: VPLs per pixel GPU mean %.4f max %.0f, C mean %.4f max %d\n", what, mean, max,
    info.mean_vpls_per_pixel, info.max_vpls_per_pixel);
  MRGI_TEST_CHECK(std::fabs(mean - info.mean_vpls_per_pixel) <= 1e-3 * info.mean_vpls_per_pixel);
  MRGI_TEST_CHECK(std::fabs(max - info.max_vpls_per_pixel) <= 1.0);
  MRGI_TEST_CHECK(info.mean_vpls_per_pixel > 0.0);
}

// 1.-3. Full resolution: every valid pixel of the viewport.
void CheckFull(Scene& s, vtkMRGIGather* gather, double tau, std::vector<float>* keep)
{
  const int winW = s.Window->GetSize()[0], winH = s.Window->GetSize()[1];
  vtkSmartPointer<vtkTextureObject> irradiance = Target(s.GL, winW, winH);
  vtkSmartPointer<vtkTextureObject> indirect = Target(s.GL, winW, winH);
  vtkNew<vtkTextureObject> nodes;
  MRGI_TEST_CHECK(vtkMRGIGather::UploadVPLTree(s.GL, &s.Tree, nodes));
  vtkMRGIVPLTreeTerm term;
  term.Nodes = nodes;
  term.Tree = &s.Tree;
  term.Threshold = tau;
  gather->CollectStatisticsOn();
  MRGI_TEST_CHECK(gather->GatherFullTree(s.Frame, term, 1.0, irradiance, indirect));
  std::vector<float> gpu;
  MRGI_TEST_CHECK(ReadTexture(irradiance, gpu));
  mrgi_gather_receivers receivers = { s.W, s.H, Floats(s.Position), Floats(s.Normal) };
  mrgi_image cE{}, cCount{};
  mrgi_vpl_tree_gather_info info{};
  mrgi_error err;
  if (mrgi_vpl_tree_gather(&receivers, &s.Tree, tau, s.WorldToView, &cE, &cCount, &info, &err) !=
    MRGI_OK)
  {
    MRGI_TEST_FAIL("mrgi_vpl_tree_gather: %s", err.message);
  }
  Comparison c;
  for (int y = 0; y < s.H; ++y)
  {
    for (int x = 0; x < s.W; ++x)
    {
      const size_t p = static_cast<size_t>(y) * s.W + x;
      if (!(Floats(s.Position)[4 * p + 3] > MRGI_VALID_THRESHOLD))
      {
        continue;
      }
      const size_t g =
        static_cast<size_t>(y + s.Frame.Viewport[1]) * winW + x + s.Frame.Viewport[0];
      c.Add(gpu.data() + 4 * g, cE.pixels + 3 * p);
    }
  }
  char what[96];
  std::snprintf(what, sizeof(what), "full, RSM %d (%d roots per batch), tau %g", s.Tree.rsm_size,
    mrgi_vpl_tree_roots_per_batch(&s.Tree), tau);
  std::printf(
    "%s: %zu receivers, relative RMS %.3g against the twin\n", what, c.Compared, c.Error());
  MRGI_TEST_CHECK(c.Compared > 0 && c.BadAlpha == 0);
  MRGI_TEST_CHECK(c.Error() < 1e-4);
  CheckCounts(gather, info, what);
  mrgi_image_destroy(&cE);
  mrgi_image_destroy(&cCount);
  if (keep)
  {
    *keep = gpu;
  }
  nodes->ReleaseGraphicsResources(s.Window);
  irradiance->ReleaseGraphicsResources(s.Window);
  indirect->ReleaseGraphicsResources(s.Window);
}

// 1.-3. The stenciled multiresolution gather at the texels the buffer selects.
void CheckStenciled(Scene& s, vtkMRGIGather* gather, double tau)
{
  vtkNew<vtkMRGIMultiresolution> buffer;
  buffer->SetPreset(vtkMRGIMultiresolution::PresetBalanced);
  vtkCamera* camera = s.Renderer->GetActiveCamera();
  mrgi_multires_projection projection = { 0, camera->GetViewAngle(), camera->GetParallelScale() };
  float ab[2];
  mrgi_error err;
  MRGI_TEST_CHECK(mrgi_multires_pixel_size_coefficients(&projection, s.H, ab, &err) == MRGI_OK);
  const int* vp = s.Frame.Viewport;
  MRGI_TEST_CHECK(
    buffer->Update(s.GL, s.Frame.Position, s.Frame.Normal, vp[0], vp[1], s.W, s.H, ab[0], ab[1]));
  MRGI_TEST_CHECK(buffer->BuildReceivers(s.GL, s.Frame.Position, s.Frame.Normal, vp[0], vp[1]));
  vtkNew<vtkTextureObject> nodes;
  MRGI_TEST_CHECK(vtkMRGIGather::UploadVPLTree(s.GL, &s.Tree, nodes));
  vtkMRGIVPLTreeTerm term;
  term.Nodes = nodes;
  term.Tree = &s.Tree;
  term.Threshold = tau;
  gather->CollectStatisticsOn();
  MRGI_TEST_CHECK(gather->GatherVPLTree(s.Frame, buffer, term));
  vtkNew<vtkFloatArray> gpuE, gpuP, gpuN;
  MRGI_TEST_CHECK(gather->ReadIrradiance(s.Window, gpuE));
  MRGI_TEST_CHECK(buffer->ReadReceivers(s.Window, gpuP, gpuN));
  vtkNew<vtkUnsignedCharArray> mask;
  MRGI_TEST_CHECK(buffer->ReadSelection(s.Window, mask, true));
  mrgi_multires_layout layout;
  MRGI_TEST_CHECK(buffer->GetLayout(&layout));
  const size_t texels = static_cast<size_t>(layout.total_width) * layout.total_height;
  // The twin on the GPU's own flattened receivers at the selected texels
  // (their parity with mrgi_multires_receivers_build(): TestMRGIMultiresParity).
  std::vector<float> P(4 * texels, 0.0f), N(4 * texels, 0.0f);
  for (size_t t = 0; t < texels; ++t)
  {
    if (mask->GetValue(static_cast<vtkIdType>(t)))
    {
      std::copy(gpuP->GetPointer(4 * t), gpuP->GetPointer(4 * t) + 4, P.data() + 4 * t);
      std::copy(gpuN->GetPointer(4 * t), gpuN->GetPointer(4 * t) + 4, N.data() + 4 * t);
    }
  }
  mrgi_gather_receivers flat = { layout.total_width, layout.total_height, P.data(), N.data() };
  mrgi_image cE{};
  mrgi_vpl_tree_gather_info info{};
  if (mrgi_vpl_tree_gather(&flat, &s.Tree, tau, s.WorldToView, &cE, nullptr, &info, &err) !=
    MRGI_OK)
  {
    MRGI_TEST_FAIL("mrgi_vpl_tree_gather: %s", err.message);
  }
  Comparison c;
  size_t leaks = 0;
  for (size_t t = 0; t < texels; ++t)
  {
    const float* g = gpuE->GetPointer(4 * t);
    if (!mask->GetValue(static_cast<vtkIdType>(t)))
    {
      leaks += g[0] != 0.0f || g[1] != 0.0f || g[2] != 0.0f || g[3] != 0.0f;
    }
    else if (P[4 * t + 3] > MRGI_VALID_THRESHOLD)
    {
      c.Add(g, cE.pixels + 3 * t);
    }
  }
  mrgi_image_destroy(&cE);
  char what[96];
  std::snprintf(what, sizeof(what), "stenciled, RSM %d (%d roots per batch), tau %g",
    s.Tree.rsm_size, mrgi_vpl_tree_roots_per_batch(&s.Tree), tau);
  std::printf("%s: %zu selected receivers, relative RMS %.3g against the twin; unselected texels "
              "written: %zu\n",
    what, c.Compared, c.Error(), leaks);
  MRGI_TEST_CHECK(c.Compared > 0 && c.BadAlpha == 0 && leaks == 0);
  MRGI_TEST_CHECK(c.Error() < 1e-4);
  CheckCounts(gather, info, what);
  nodes->ReleaseGraphicsResources(s.Window);
  buffer->ReleaseGraphicsResources(s.Window);
}

// 4. tau = 1 against the full gather of the GPU's 16 x 16 grid VPLs.
void CheckGrid(Scene& s, vtkMRGIGather* gather, const std::vector<float>& tree)
{
  const int winW = s.Window->GetSize()[0], winH = s.Window->GetSize()[1];
  vtkSmartPointer<vtkTextureObject> irradiance = Target(s.GL, winW, winH);
  vtkSmartPointer<vtkTextureObject> indirect = Target(s.GL, winW, winH);
  vtkMRGIVPLSelection* selection = s.Pass->GetVPLSelection();
  MRGI_TEST_CHECK(selection->GetVPLCount() == 256);
  MRGI_TEST_CHECK(gather->GatherFull(
    s.Frame, selection->GetVPLTexture(), selection->GetVPLCount(), 1.0, irradiance, indirect));
  MRGI_TEST_CHECK(gather->GetMeanVPLsPerPixel() == -1.0); // not a tree gather
  std::vector<float> grid;
  MRGI_TEST_CHECK(ReadTexture(irradiance, grid));
  Comparison c;
  for (size_t t = 0; 4 * t < grid.size(); ++t)
  {
    if (grid[4 * t + 3] == 1.0f)
    {
      c.Add(tree.data() + 4 * t, grid.data() + 4 * t);
    }
  }
  std::printf("tau 1 against the GPU grid-256 gather: %zu pixels, relative RMS %.3g\n", c.Compared,
    c.Error());
  MRGI_TEST_CHECK(c.Compared > 0 && c.BadAlpha == 0 && c.Error() < 1e-4);
  irradiance->ReleaseGraphicsResources(s.Window);
  indirect->ReleaseGraphicsResources(s.Window);
}

// 5. Bad input: refused with false (and an error), never drawn.
void CheckErrors(Scene& s, vtkMRGIGather* gather)
{
  const int winW = s.Window->GetSize()[0], winH = s.Window->GetSize()[1];
  vtkSmartPointer<vtkTextureObject> irradiance = Target(s.GL, winW, winH);
  vtkSmartPointer<vtkTextureObject> indirect = Target(s.GL, winW, winH);
  vtkNew<vtkTextureObject> nodes;
  MRGI_TEST_CHECK(vtkMRGIGather::UploadVPLTree(s.GL, &s.Tree, nodes));
  vtkNew<mrgitest::ErrorCatcher> errors;
  gather->AddObserver(vtkCommand::ErrorEvent, errors);
  vtkMRGIVPLTreeTerm term;
  term.Nodes = nodes;
  term.Tree = &s.Tree;
  for (const double tau : { std::numeric_limits<double>::quiet_NaN(), -0.5 })
  {
    term.Threshold = tau;
    MRGI_TEST_CHECK(!gather->GatherFullTree(s.Frame, term, 1.0, irradiance, indirect));
    MRGI_TEST_CHECK(errors->Caught("tau"));
  }
  term.Threshold = 0.05;
  mrgi_vpl_tree empty{};
  term.Tree = &empty;
  MRGI_TEST_CHECK(!gather->GatherFullTree(s.Frame, term, 1.0, irradiance, indirect));
  MRGI_TEST_CHECK(errors->Caught("not built"));
  MRGI_TEST_CHECK(!vtkMRGIGather::UploadVPLTree(s.GL, &empty, nodes)); // a warning
  mrgi_vpl_tree big = s.Tree;
  big.rsm_size = MRGI_VPL_TREE_GATHER_MAX_RSM_SIZE + 1;
  term.Tree = &big;
  MRGI_TEST_CHECK(!gather->GatherFullTree(s.Frame, term, 1.0, irradiance, indirect));
  MRGI_TEST_CHECK(errors->Caught("MRGI_VPL_TREE_GATHER_MAX_RSM_SIZE"));
  term.Tree = &s.Tree;
  term.Nodes = irradiance; // the wrong size
  MRGI_TEST_CHECK(!gather->GatherFullTree(s.Frame, term, 1.0, irradiance, indirect));
  MRGI_TEST_CHECK(errors->Caught("the tree needs"));
  gather->RemoveObserver(errors);
  nodes->ReleaseGraphicsResources(s.Window);
  irradiance->ReleaseGraphicsResources(s.Window);
  indirect->ReleaseGraphicsResources(s.Window);
}
}

int main()
{
  vtkNew<vtkMRGIGather> gather;
  {
    // RSM 64: one batch; tau 1, 0.05, 0.
    Scene s(72, 56, 64);
    std::vector<float> roots;
    CheckFull(s, gather, 1.0, &roots);
    CheckGrid(s, gather, roots);
    for (const double tau : { 0.05, 0.0 })
    {
      CheckFull(s, gather, tau, nullptr);
    }
    for (const double tau : { 1.0, 0.05, 0.0 })
    {
      CheckStenciled(s, gather, tau);
    }
    CheckErrors(s, gather);
    gather->ReleaseGraphicsResources(s.Window);
  }
  {
    // RSM 256: two batches per view (192 + 64 roots).
    Scene s(40, 32, 256);
    MRGI_TEST_CHECK(mrgi_vpl_tree_root_count(&s.Tree) > mrgi_vpl_tree_roots_per_batch(&s.Tree));
    std::vector<float> roots;
    CheckFull(s, gather, 1.0, &roots);
    CheckGrid(s, gather, roots);
    for (const double tau : { 0.05, 0.0 })
    {
      CheckFull(s, gather, tau, nullptr);
    }
    CheckStenciled(s, gather, 0.05);
    // Every texel lit, tau 0: receivers facing down from the ceiling cull
    // nothing the spot sees, so they pop every nonempty node of each root
    // (up to 341 per root, 192 roots in the first batch) and use every
    // usable texel as a VPL.
    s.BuildTree(true);
    CheckFull(s, gather, 0.0, nullptr);
    std::printf("  every texel lit: %lld usable texels, GPU max VPLs per pixel %.0f\n",
      static_cast<long long>(s.Tree.usable_texel_count), gather->GetMaxVPLsPerPixel());
    MRGI_TEST_CHECK(gather->GetMaxVPLsPerPixel() == static_cast<double>(s.Tree.usable_texel_count));
    gather->ReleaseGraphicsResources(s.Window);
  }
  {
    // A point light: six cube views of RSM 128, 1,536 roots in two draws
    // (771 + 765): roots and children of views 1-5.
    Scene s(40, 32, 128, true);
    MRGI_TEST_CHECK(s.Tree.view_count == 6);
    MRGI_TEST_CHECK(mrgi_vpl_tree_root_count(&s.Tree) > mrgi_vpl_tree_roots_per_batch(&s.Tree));
    for (const double tau : { 1.0, 0.05 })
    {
      CheckFull(s, gather, tau, nullptr);
    }
    CheckStenciled(s, gather, 0.05);
    gather->ReleaseGraphicsResources(s.Window);
  }
  return EXIT_SUCCESS;
}
