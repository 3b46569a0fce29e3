// The Tree VPL selection (nichols-shopf-wyman-2009 section 3.5) in the pass,
// on the built-in Cornell box lit by its spot light:
// 1. the uploaded tree texture, read back, is mrgi_vpl_tree_build()'s nodes
//    bit for bit, followed by zero records up to the texture's end, in the
//    layout of mrgi_vpl_tree_gather.h section 3 (MRGI_VPL_TREE_RECORDS_PER_ROW
//    records per row), and those nodes equal a fresh C build on the
//    read-back RSM with the camera rebuilt from the RSM pass (bit for bit);
// 2. the flat VPL cache holds the 16 x 16 roots with cleared pads: the grid
//    selection's 256 VPLs (positions and normals bit for bit, flux and area
//    within the grid's GPU/C tolerance 1e-4 relative);
// 3. nothing is rebuilt while nothing changes, and the tree is rebuilt (with
//    other nodes) after the light moves;
// 4. bad thresholds: a negative one clamps to 0, NaN is refused by Update()
//    with an error naming TreeThreshold, no tree and no crash;
// 5. an RSM larger than MRGI_VPL_TREE_GATHER_MAX_RSM_SIZE: an error naming
//    it, no tree, no crash; back to a valid size, the tree returns.
// 6. the pass gathers the tree (GatherFullTree / GatherVPLTree): at
//    tau = +inf the full-resolution irradiance equals the grid mode's (256 VPLs)
//    within 1e-4 relative RMS (float order only); tau = 0.02 changes it;
//    the multiresolution gather runs with the tree, every value finite and
//    >= 0, and the VPLs-per-pixel statistic is > 1.
#include "mrgiPassSceneFixture.h"
#include "mrgiTestUtilities.h"

#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMath.h"
#include "vtkMRGIGather.h"
#include "vtkMRGIPass.h"
#include "vtkMRGIReflectiveShadowMapPass.h"
#include "vtkMRGISceneBuilder.h"
#include "vtkMRGIVPLSelection.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkPointData.h"
#include "vtkRenderStepsPass.h"
#include "vtkRenderer.h"
#include "vtkTextureObject.h"

#include "mrgi_vpl.h"
#include "mrgi_vpl_tree.h"
#include "mrgi_vpl_tree_gather.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <vector>

namespace
{
std::vector<mrgi_vpl> ToRecords(vtkFloatArray* array)
{
  MRGI_TEST_CHECK(array->GetNumberOfComponents() == MRGI_VPL_FLOATS);
  std::vector<mrgi_vpl> records(static_cast<size_t>(array->GetNumberOfTuples()));
  std::memcpy(records.data(), array->GetPointer(0), sizeof(mrgi_vpl) * records.size());
  return records;
}

std::vector<mrgi_vpl> ReadVPLs(vtkMRGIPass* pass, vtkRenderWindow* window)
{
  vtkNew<vtkFloatArray> array;
  MRGI_TEST_CHECK(pass->GetVPLs(window, array));
  return ToRecords(array);
}

// 1. The texture: the C tree's nodes bit for bit, then zero records.
void CheckTexture(vtkMRGIVPLSelection* selection, vtkRenderWindow* window)
{
  const mrgi_vpl_tree* tree = selection->GetTree();
  vtkTextureObject* texture = selection->GetTreeTexture();
  MRGI_TEST_CHECK(tree && texture && tree->node_count > 0);
  MRGI_TEST_CHECK(selection->GetNumberOfTreeNodes() == tree->node_count);
  const int64_t rows =
    (tree->node_count + MRGI_VPL_TREE_RECORDS_PER_ROW - 1) / MRGI_VPL_TREE_RECORDS_PER_ROW;
  MRGI_TEST_CHECK(texture->GetWidth() == MRGI_VPL_TREE_RECORDS_PER_ROW * MRGI_VPL_TEXELS);
  MRGI_TEST_CHECK(static_cast<int64_t>(texture->GetHeight()) == rows);
  vtkNew<vtkFloatArray> array;
  MRGI_TEST_CHECK(
    selection->ReadTreeTexture(vtkOpenGLRenderWindow::SafeDownCast(window), array));
  const std::vector<mrgi_vpl> records = ToRecords(array);
  MRGI_TEST_CHECK(static_cast<int64_t>(records.size()) == rows * MRGI_VPL_TREE_RECORDS_PER_ROW);
  MRGI_TEST_CHECK(static_cast<int64_t>(records.size()) > tree->node_count); // padding exists here
  const size_t nodes = static_cast<size_t>(tree->node_count);
  MRGI_TEST_CHECK(std::memcmp(records.data(), tree->nodes, sizeof(mrgi_vpl) * nodes) == 0);
  std::vector<mrgi_vpl> zeros(records.size() - nodes);
  std::memset(zeros.data(), 0, sizeof(mrgi_vpl) * zeros.size());
  MRGI_TEST_CHECK(
    std::memcmp(records.data() + nodes, zeros.data(), sizeof(mrgi_vpl) * zeros.size()) == 0);
}

// 1. A fresh C tree on the read-back RSM (the Cornell box has one spot light: view 0).
void CheckAgainstCore(vtkMRGIPass* pass, vtkRenderWindow* window)
{
  const mrgitest::SpotRSMView view(pass, window);
  mrgi_vpl_tree c = {};
  mrgi_error err;
  MRGI_TEST_CHECK(mrgi_vpl_tree_build(&view.Map, &view.Camera, &c, &err) == MRGI_OK);
  const mrgi_vpl_tree* gpu = pass->GetVPLSelection()->GetTree();
  MRGI_TEST_CHECK(gpu && gpu->node_count == c.node_count);
  MRGI_TEST_CHECK(std::memcmp(gpu->nodes, c.nodes, sizeof(mrgi_vpl) * static_cast<size_t>(c.node_count)) == 0);
  mrgi_vpl_tree_destroy(&c);
}

std::vector<double> Irradiance(vtkMRGIPass* pass, vtkRenderWindow* window)
{
  vtkNew<vtkImageData> image;
  MRGI_TEST_CHECK(pass->GetIrradianceBuffer(window, image));
  vtkDataArray* a = image->GetPointData()->GetScalars();
  MRGI_TEST_CHECK(a && a->GetNumberOfValues() > 0);
  std::vector<double> values(static_cast<size_t>(a->GetNumberOfValues()));
  for (vtkIdType i = 0; i < a->GetNumberOfValues(); ++i)
  {
    values[static_cast<size_t>(i)] = a->GetVariantValue(i).ToDouble();
    MRGI_TEST_CHECK(std::isfinite(values[static_cast<size_t>(i)]) && values[static_cast<size_t>(i)] >= 0.0);
  }
  return values;
}

double RelativeRMS(const std::vector<double>& a, const std::vector<double>& b)
{
  MRGI_TEST_CHECK(a.size() == b.size());
  double d2 = 0.0, b2 = 0.0;
  for (size_t i = 0; i < a.size(); ++i)
  {
    d2 += (a[i] - b[i]) * (a[i] - b[i]);
    b2 += b[i] * b[i];
  }
  MRGI_TEST_CHECK(b2 > 0.0);
  return std::sqrt(d2 / b2);
}

// 2. The flat cache: the roots, i.e. the 16 x 16 grid.
void CheckRoots(const std::vector<mrgi_vpl>& roots, const std::vector<mrgi_vpl>& grid)
{
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
    MRGI_TEST_CHECK(roots[i].pad0 == 0.0f && roots[i].pad1 == 0.0f);
  }
}
}

int main()
{
  const int W = 64, H = 48;
  vtkSmartPointer<vtkRenderWindow> window = mrgitest::HeadlessWindow(W, H);
  vtkNew<vtkRenderer> renderer;
  window->AddRenderer(renderer);
  vtkNew<vtkMRGISceneBuilder> builder;
  builder->SetScene("cornell-spot");
  MRGI_TEST_CHECK(builder->Build(renderer));
  vtkNew<vtkRenderStepsPass> steps;
  vtkNew<vtkMRGIPass> pass;
  pass->SetDelegatePass(steps);
  pass->SetIndirectMode(vtkMRGIPass::IndirectFull);
  pass->SetNumberOfVPLs(256);
  pass->SetRSMResolution(64);
  renderer->SetPass(pass);
  vtkMRGIVPLSelection* selection = pass->GetVPLSelection();
  vtkNew<mrgitest::ErrorCatcher> errors;
  selection->AddObserver(vtkCommand::ErrorEvent, errors);
  pass->AddObserver(vtkCommand::ErrorEvent, errors);
  pass->GetGather()->AddObserver(vtkCommand::ErrorEvent, errors);

  // The grid (GPU) first, for 2.
  pass->SetVPLSelectionMode(vtkMRGIVPLSelection::Grid);
  window->Render();
  MRGI_TEST_CHECK(pass->GetIndirectComputed());
  const std::vector<mrgi_vpl> grid = ReadVPLs(pass, window);
  MRGI_TEST_CHECK(grid.size() == 256);
  MRGI_TEST_CHECK(!selection->GetTree() && !selection->GetTreeTexture());

  // 1.-2. Tree mode.
  MRGI_TEST_CHECK(pass->GetTreeThreshold() == MRGI_VPL_TREE_DEFAULT_THRESHOLD);
  selection->SetModeToTree();
  MRGI_TEST_CHECK(pass->GetVPLSelectionMode() == vtkMRGIVPLSelection::Tree);
  window->Render();
  MRGI_TEST_CHECK(errors->Count == 0);
  MRGI_TEST_CHECK(pass->GetIndirectComputed());
  // 64^2 RSM: levels of 64, 32 and 16 texels.
  MRGI_TEST_CHECK(selection->GetNumberOfTreeNodes() == 64 * 64 + 32 * 32 + 16 * 16);
  CheckTexture(selection, window);
  CheckAgainstCore(pass, window);
  CheckRoots(ReadVPLs(pass, window), grid);

  // 3. Cached while nothing changes (the camera is not the light).
  const vtkIdType selections = selection->GetNumberOfSelections();
  const std::vector<mrgi_vpl> before(selection->GetTree()->nodes,
    selection->GetTree()->nodes + selection->GetTree()->node_count);
  window->Render();
  renderer->GetActiveCamera()->Azimuth(5);
  window->Render();
  MRGI_TEST_CHECK(selection->GetNumberOfSelections() == selections);
  // The light moves: rebuilt once, with other nodes, and uploaded again.
  vtkLight* light = vtkLight::SafeDownCast(renderer->GetLights()->GetItemAsObject(0));
  MRGI_TEST_CHECK(light);
  double position[3], focal[3];
  light->GetPosition(position);
  light->GetFocalPoint(focal);
  const double shift = 0.02 * std::sqrt(vtkMath::Distance2BetweenPoints(position, focal));
  light->SetPosition(position[0] + shift, position[1], position[2]);
  window->Render();
  MRGI_TEST_CHECK(selection->GetNumberOfSelections() == selections + 1);
  MRGI_TEST_CHECK(selection->GetTree()->node_count == static_cast<int64_t>(before.size()));
  MRGI_TEST_CHECK(std::memcmp(selection->GetTree()->nodes, before.data(),
                    sizeof(mrgi_vpl) * before.size()) != 0);
  CheckTexture(selection, window);
  CheckAgainstCore(pass, window);
  window->Render();
  MRGI_TEST_CHECK(selection->GetNumberOfSelections() == selections + 1);

  // 4. Bad thresholds.
  pass->SetTreeThreshold(-1.0);
  MRGI_TEST_CHECK(pass->GetTreeThreshold() == 0.0); // clamped
  pass->SetTreeThreshold(std::numeric_limits<double>::infinity());
  MRGI_TEST_CHECK(std::isinf(pass->GetTreeThreshold()));
  // A new tau changes the gather, not the tree: no read-back, no rebuild.
  const vtkIdType beforeTau = selection->GetNumberOfSelections();
  pass->SetTreeThreshold(0.3);
  window->Render();
  MRGI_TEST_CHECK(errors->Count == 0 && pass->GetIndirectComputed());
  MRGI_TEST_CHECK(selection->GetNumberOfSelections() == beforeTau);
  pass->SetTreeThreshold(std::nan(""));
  window->Render();
  MRGI_TEST_CHECK(errors->Caught("tree threshold tau is nan"));
  MRGI_TEST_CHECK(!pass->GetIndirectComputed()); // no silent fallback to another selection
  pass->SetTreeThreshold(0.1);
  window->Render();
  MRGI_TEST_CHECK(errors->Count == 0);
  MRGI_TEST_CHECK(selection->GetTree() && pass->GetIndirectComputed());
  MRGI_TEST_CHECK(selection->GetNumberOfSelections() == beforeTau);

  // 5. An RSM beyond the tree gather's limit.
  pass->SetRSMResolution(2 * MRGI_VPL_TREE_GATHER_MAX_RSM_SIZE);
  window->Render();
  MRGI_TEST_CHECK(errors->Caught("MRGI_VPL_TREE_GATHER_MAX_RSM_SIZE"));
  MRGI_TEST_CHECK(!selection->GetTree() && !selection->GetTreeTexture());
  MRGI_TEST_CHECK(!pass->GetIndirectComputed());
  pass->SetRSMResolution(64);
  window->Render();
  MRGI_TEST_CHECK(errors->Count == 0);
  CheckTexture(selection, window);

  // 6. The pass gathers the tree; the grid of this light and camera first.
  selection->SetModeToGrid();
  window->Render();
  const std::vector<double> gridIrradiance = Irradiance(pass, window);
  selection->SetModeToTree();
  pass->SetTreeThreshold(std::numeric_limits<double>::infinity());
  window->Render();
  MRGI_TEST_CHECK(pass->GetIndirectComputed());
  const std::vector<double> roots = Irradiance(pass, window);
  const double rootsVsGrid = RelativeRMS(roots, gridIrradiance);
  MRGI_TEST_CHECK(rootsVsGrid <= 1e-4);
  pass->SetTreeThreshold(0.02);
  window->Render();
  MRGI_TEST_CHECK(pass->GetIndirectComputed());
  const double refinedVsGrid = RelativeRMS(Irradiance(pass, window), gridIrradiance);
  MRGI_TEST_CHECK(refinedVsGrid > 1e-3);
  pass->SetIndirectMode(vtkMRGIPass::IndirectMultires);
  pass->GetGather()->SetCollectStatistics(true);
  window->Render();
  MRGI_TEST_CHECK(errors->Count == 0);
  MRGI_TEST_CHECK(pass->GetIndirectComputed());
  Irradiance(pass, window);
  const double vplsPerPixel = pass->GetGather()->GetMeanVPLsPerPixel();
  MRGI_TEST_CHECK(vplsPerPixel > 1.0);
  std::printf("tau inf vs grid: %.3g relative RMS; tau 0.02 vs grid: %.3g; multires tau 0.02: "
              "%.2f VPLs per gathered texel\n",
    rootsVsGrid, refinedVsGrid, vplsPerPixel);

  std::printf("tree of %lld nodes, %zu roots; texture %d x %d\n",
    static_cast<long long>(selection->GetNumberOfTreeNodes()), grid.size(),
    selection->GetTreeTexture()->GetWidth(), selection->GetTreeTexture()->GetHeight());
  return EXIT_SUCCESS;
}
