// The Clusters VPL selection (nichols-shopf-wyman-2009 section 3.4) in the
// pass, on the built-in Cornell box lit by its spot light:
// 1. thresholds +inf upload the 16 x 16 grid: the same count as the GPU grid
//    selection, positions and normals bit for bit, flux and area within 1e-4
//    relative (the grid's GPU/C parity tolerance, TestMRGIParity);
// 2. default and zero thresholds upload more VPLs (the box has corners),
//    at most MRGI_VPL_CLUSTER_MAX, whose total flux equals the grid's within
//    1e-4 relative (energy conservation through read-back and upload);
// 3. every rendered pixel and irradiance value is finite and >= 0;
// 4. nothing is reselected while the RSMs and settings are unchanged;
// 5. the uploaded VPLs equal mrgi_vpl_select_clusters() run here on the
//    read-back RSM, with the light view's camera rebuilt from the RSM pass's
//    matrices, bit for bit (the stage is C; this checks its inputs and upload).
#include "mrgiPassSceneFixture.h"
#include "mrgiTestUtilities.h"

#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkMath.h"
#include "vtkMRGIPass.h"
#include "vtkMRGIReflectiveShadowMapPass.h"
#include "vtkMRGISceneBuilder.h"
#include "vtkMRGIVPLSelection.h"
#include "vtkPointData.h"
#include "vtkRenderStepsPass.h"
#include "vtkRenderer.h"

#include "mrgi_vpl.h"
#include "mrgi_vpl_clusters.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <vector>

namespace
{
void TotalFlux(const std::vector<mrgi_vpl>& vpls, double total[4])
{
  total[0] = total[1] = total[2] = total[3] = 0.0;
  for (const mrgi_vpl& v : vpls)
  {
    for (int c = 0; c < 3; ++c)
    {
      MRGI_TEST_CHECK(std::isfinite(v.flux[c]) && v.flux[c] >= 0.0f);
      total[c] += v.flux[c];
    }
    total[3] += v.area;
  }
}

// Every value of `image` finite and >= 0; returns their sum.
double CheckFinite(vtkImageData* image)
{
  vtkDataArray* a = image->GetPointData()->GetScalars();
  MRGI_TEST_CHECK(a && a->GetNumberOfValues() > 0);
  double sum = 0.0;
  for (vtkIdType i = 0; i < a->GetNumberOfValues(); ++i)
  {
    const double v = a->GetVariantValue(i).ToDouble();
    MRGI_TEST_CHECK(std::isfinite(v) && v >= 0.0);
    sum += v;
  }
  return sum;
}

// 5. A fresh C selection on the read-back RSM (the Cornell box has one spot light: view 0).
void CheckAgainstCore(vtkMRGIPass* pass, vtkRenderWindow* window, const std::vector<mrgi_vpl>& gpu)
{
  const mrgitest::SpotRSMView view(pass, window);
  mrgi_vpl_cluster_params params;
  mrgi_vpl_cluster_params_default(&params);
  params.depth_threshold = pass->GetClusterDepthThreshold();
  params.normal_threshold = pass->GetClusterNormalThreshold();
  std::vector<mrgi_vpl> c(MRGI_VPL_CLUSTER_MAX);
  mrgi_vpl_cluster_info info;
  mrgi_error err;
  MRGI_TEST_CHECK(mrgi_vpl_select_clusters(&view.Map, &view.Camera, &params, c.data(), MRGI_VPL_CLUSTER_MAX,
                    &info, &err) == MRGI_OK);
  MRGI_TEST_CHECK(static_cast<size_t>(info.vpl_count) == gpu.size());
  MRGI_TEST_CHECK(std::memcmp(c.data(), gpu.data(), sizeof(mrgi_vpl) * gpu.size()) == 0);
}

void CheckSameFlux(const double a[4], const double b[4], const char* what)
{
  for (int c = 0; c < 4; ++c)
  {
    MRGI_TEST_CHECK(b[c] > 0.0);
    const double relative = std::fabs(a[c] - b[c]) / b[c];
    if (!(relative <= 1e-4))
    {
      std::fprintf(stderr, "%s: component %d totals %.9g vs the grid's %.9g (%.3g relative)\n",
        what, c, a[c], b[c], relative);
      MRGI_TEST_CHECK(relative <= 1e-4);
    }
  }
}
}

int main()
{
  const int W = 96, H = 80;
  mrgitest::PassScene scene(W, H, "cornell-spot");
  vtkRenderWindow* window = scene.Window;
  vtkMRGIPass* pass = scene.Pass;
  pass->SetIndirectMode(vtkMRGIPass::IndirectFull);
  pass->SetNumberOfVPLs(256);
  pass->SetRSMResolution(128);

  // The grid (GPU) first.
  pass->SetVPLSelectionMode(vtkMRGIVPLSelection::Grid);
  window->Render();
  MRGI_TEST_CHECK(pass->GetIndirectComputed());
  const std::vector<mrgi_vpl> grid = mrgitest::ReadVPLs(pass, window);
  MRGI_TEST_CHECK(grid.size() == 256);
  double gridFlux[4];
  TotalFlux(grid, gridFlux);

  // 1. Thresholds +inf: the 16 x 16 grid.
  const double inf = std::numeric_limits<double>::infinity();
  pass->SetVPLSelectionMode(vtkMRGIVPLSelection::Clusters);
  pass->SetClusterDepthThreshold(inf);
  pass->SetClusterNormalThreshold(inf);
  window->Render();
  const std::vector<mrgi_vpl> roots = mrgitest::ReadVPLs(pass, window);
  MRGI_TEST_CHECK(roots.size() == grid.size());
  for (size_t i = 0; i < roots.size(); ++i)
  {
    MRGI_TEST_CHECK(std::memcmp(roots[i].position, grid[i].position, sizeof(float) * 3) == 0);
    MRGI_TEST_CHECK(std::memcmp(roots[i].normal, grid[i].normal, sizeof(float) * 3) == 0);
    for (int c = 0; c < 3; ++c)
    {
      MRGI_TEST_CHECK(std::fabs(roots[i].flux[c] - grid[i].flux[c]) <=
        1e-4 * std::fabs(grid[i].flux[c]) + 1e-30);
    }
    MRGI_TEST_CHECK(std::fabs(roots[i].area - grid[i].area) <= 1e-4 * std::fabs(grid[i].area) + 1e-30);
  }
  MRGI_TEST_CHECK(pass->GetVPLSelection()->GetClusterRefinementsCapped() == 0);

  // 2.-3. Default and zero thresholds.
  const double settings[][2] = { { 4.0, 0.25 }, { 1.0, 0.1 }, { 0.0, 0.0 } };
  size_t previous = roots.size();
  for (const auto& t : settings)
  {
    pass->SetClusterDepthThreshold(t[0]);
    pass->SetClusterNormalThreshold(t[1]);
    window->Render();
    MRGI_TEST_CHECK(pass->GetIndirectComputed());
    const std::vector<mrgi_vpl> clusters = mrgitest::ReadVPLs(pass, window);
    std::printf("thresholds %g / %g: %zu cluster VPLs (%d refinements capped)\n", t[0], t[1],
      clusters.size(), pass->GetVPLSelection()->GetClusterRefinementsCapped());
    MRGI_TEST_CHECK(clusters.size() > previous); // lower thresholds split more
    MRGI_TEST_CHECK(clusters.size() <= static_cast<size_t>(MRGI_VPL_CLUSTER_MAX));
    previous = clusters.size();
    double flux[4];
    TotalFlux(clusters, flux);
    CheckSameFlux(flux, gridFlux, "cluster VPLs");
    CheckAgainstCore(pass, window, clusters);
    vtkNew<vtkImageData> color, irradiance;
    MRGI_TEST_CHECK(pass->GetColorBuffer(window, color));
    MRGI_TEST_CHECK(pass->GetIrradianceBuffer(window, irradiance));
    CheckFinite(color);
    MRGI_TEST_CHECK(CheckFinite(irradiance) > 0.0);
  }

  // 4. Cached while nothing changes.
  const vtkIdType selections = pass->GetVPLSelection()->GetNumberOfSelections();
  window->Render();
  MRGI_TEST_CHECK(pass->GetVPLSelection()->GetNumberOfSelections() == selections);

  std::printf("grid flux %.6g %.6g %.6g; clusters conserve it within 1e-4\n", gridFlux[0],
    gridFlux[1], gridFlux[2]);
  return EXIT_SUCCESS;
}
