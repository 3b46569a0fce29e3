// Picking is the same with vtkMRGIPass installed as without any pass:
// - vtkPropPicker (hardware selection of the prop under a pixel) and
//   vtkHardwareSelector (props and cells of an area, pixel by pixel) pick the
//   same prop and cell at the same pixel. VTK 9.1's vtkRenderStepsPass alone
//   breaks both (its passes never tell the selector which prop is drawn);
//   vtkMRGIPass hands the props to the selector as the renderer does;
// - vtkWorldPointPicker (reads the depth buffer MRGI writes) finds the same
//   world points; vtkCellPicker (geometric) the same cells;
// - after picking, the next frame is the same image as before it.
#include "TestMRGIPipelineCommon.h"

#include "vtkCellPicker.h"
#include "vtkCubeSource.h"
#include "vtkHardwareSelector.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkLight.h"
#include "vtkPropPicker.h"
#include "vtkSelection.h"
#include "vtkSelectionNode.h"
#include "vtkWorldPointPicker.h"

#include <map>
#include <set>
#include <vector>

namespace
{
struct Picks
{
  std::vector<vtkProp*> PropPicker; // per probe pixel
  std::vector<std::array<double, 3>> PropPosition;
  std::vector<vtkProp*> CellPickerProp;
  std::vector<vtkIdType> CellPickerCell;
  std::vector<std::array<double, 3>> WorldPoint;
  std::vector<std::pair<vtkProp*, vtkIdType>>
    Pixel;                                      // hardware selector, prop and cell per probe pixel
  std::map<vtkProp*, std::set<vtkIdType>> Area; // hardware selector, whole window
};

Picks PickAll(
  vtkRenderWindow* window, vtkRenderer* renderer, const std::vector<std::array<int, 2>>& probes)
{
  Picks picks;
  window->Render();
  for (const auto& p : probes)
  {
    vtkNew<vtkPropPicker> propPicker;
    propPicker->Pick(p[0], p[1], 0, renderer);
    picks.PropPicker.push_back(propPicker->GetViewProp());
    const double* pos = propPicker->GetPickPosition();
    picks.PropPosition.push_back({ { pos[0], pos[1], pos[2] } });
    vtkNew<vtkCellPicker> cellPicker;
    cellPicker->SetTolerance(0.0);
    cellPicker->Pick(p[0], p[1], 0, renderer);
    picks.CellPickerProp.push_back(cellPicker->GetViewProp());
    picks.CellPickerCell.push_back(cellPicker->GetCellId());
    vtkNew<vtkWorldPointPicker> worldPicker;
    worldPicker->Pick(p[0], p[1], 0, renderer);
    const double* w = worldPicker->GetPickPosition();
    picks.WorldPoint.push_back({ { w[0], w[1], w[2] } });
  }
  vtkNew<vtkHardwareSelector> selector;
  selector->SetRenderer(renderer);
  selector->SetFieldAssociation(vtkDataObject::FIELD_ASSOCIATION_CELLS);
  const int* size = window->GetSize();
  selector->SetArea(0, 0, size[0] - 1, size[1] - 1);
  MRGI_TEST_CHECK(selector->CaptureBuffers());
  for (const auto& p : probes)
  {
    unsigned int position[2] = { static_cast<unsigned int>(p[0]), static_cast<unsigned int>(p[1]) };
    vtkHardwareSelector::PixelInformation info = selector->GetPixelInformation(position, 0);
    picks.Pixel.emplace_back(info.Valid ? info.Prop : nullptr, info.Valid ? info.AttributeID : -1);
  }
  selector->ClearBuffers();
  vtkSmartPointer<vtkSelection> selection = vtkSmartPointer<vtkSelection>::Take(selector->Select());
  MRGI_TEST_CHECK(selection != nullptr);
  for (unsigned int n = 0; n < selection->GetNumberOfNodes(); ++n)
  {
    vtkSelectionNode* node = selection->GetNode(n);
    vtkProp* prop = vtkProp::SafeDownCast(node->GetProperties()->Get(vtkSelectionNode::PROP()));
    vtkIdTypeArray* ids = vtkIdTypeArray::SafeDownCast(node->GetSelectionList());
    std::set<vtkIdType>& cells = picks.Area[prop];
    for (vtkIdType i = 0; ids && i < ids->GetNumberOfTuples(); ++i)
    {
      cells.insert(ids->GetValue(i));
    }
  }
  return picks;
}

double Distance(const std::array<double, 3>& a, const std::array<double, 3>& b)
{
  return std::sqrt(
    (a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

void Compare(const char* what, const Picks& ref, const Picks& got)
{
  int hits = 0;
  double worstProp = 0, worstWorld = 0;
  for (size_t i = 0; i < ref.PropPicker.size(); ++i)
  {
    MRGI_TEST_CHECK(got.PropPicker[i] == ref.PropPicker[i]);
    MRGI_TEST_CHECK(got.CellPickerProp[i] == ref.CellPickerProp[i]);
    MRGI_TEST_CHECK(got.CellPickerCell[i] == ref.CellPickerCell[i]);
    MRGI_TEST_CHECK(got.Pixel[i] == ref.Pixel[i]);
    hits += ref.PropPicker[i] ? 1 : 0;
    worstProp = std::max(worstProp, Distance(got.PropPosition[i], ref.PropPosition[i]));
    worstWorld = std::max(worstWorld, Distance(got.WorldPoint[i], ref.WorldPoint[i]));
  }
  size_t cells = 0;
  for (const auto& entry : ref.Area)
  {
    cells += entry.second.size();
  }
  std::printf("%s: %zu probes (%d on props), prop positions within %.2g, world points within "
              "%.2g; area selection %zu props, %zu cells\n",
    what, ref.PropPicker.size(), hits, worstProp, worstWorld, got.Area.size(), cells);
  MRGI_TEST_CHECK(got.Area == ref.Area);
  MRGI_TEST_CHECK(worstProp < 1e-4 && worstWorld < 1e-4);
}
}

int main()
{
  using namespace mrgipipe;
  const int W = 160, H = 120;
  vtkSmartPointer<vtkRenderWindow> window = mrgitest::HeadlessWindow(W, H);
  vtkNew<vtkRenderer> renderer;
  window->AddRenderer(renderer);
  const double cf[3] = { 0, -1, 0 }, nf[3] = { 0, 1, 0 };
  const double cw[3] = { 0, 0.5, -1.5 }, nw[3] = { 0, 0, 1 };
  renderer->AddActor(MakeQuad(cf, nf, 3, 0.8, 0.8, 0.8, 6));
  renderer->AddActor(MakeQuad(cw, nw, 3, 0.7, 0.7, 0.8, 6));
  vtkNew<vtkCubeSource> cube;
  vtkSmartPointer<vtkActor> box = MakeActor(cube, 0.9, 0.2, 0.1);
  box->SetPosition(-0.6, -0.5, -0.3);
  box->RotateY(30);
  renderer->AddActor(box);
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(16);
  sphere->SetPhiResolution(16);
  vtkSmartPointer<vtkActor> ball = MakeActor(sphere, 0.2, 0.4, 0.9);
  ball->SetPosition(0.7, -0.4, 0.2);
  renderer->AddActor(ball);
  vtkNew<vtkLight> light;
  light->SetLightTypeToSceneLight();
  light->SetPositional(true);
  light->SetConeAngle(50);
  light->SetPosition(0.5, 2.5, 2.0);
  light->SetFocalPoint(0, -0.8, 0);
  renderer->AddLight(light);
  renderer->GetActiveCamera()->SetPosition(0.2, 0.8, 4.5);
  renderer->GetActiveCamera()->SetFocalPoint(0, -0.2, 0);
  renderer->ResetCameraClippingRange();

  std::vector<std::array<int, 2>> probes;
  for (int y = 4; y < H; y += 9)
  {
    for (int x = 3; x < W; x += 11)
    {
      probes.push_back({ { x, y } });
    }
  }

  Picks plain = PickAll(window, renderer, probes);
  int onBox = 0, onBall = 0;
  for (vtkProp* p : plain.PropPicker)
  {
    onBox += p == box ? 1 : 0;
    onBall += p == ball ? 1 : 0;
  }
  MRGI_TEST_CHECK(onBox >= 4 && onBall >= 4);
  MRGI_TEST_CHECK(plain.Area.size() == 4);

  vtkSmartPointer<vtkMRGIPass> pass = Install(renderer);
  pass->SetRSMResolution(64);
  window->Render();
  vtkSmartPointer<vtkImageData> before = mrgitest::GrabRGB(window);
  MRGI_TEST_CHECK(pass->GetIndirectComputed());
  Compare("vtkMRGIPass, indirect light on", plain, PickAll(window, renderer, probes));
  window->Render();
  MRGI_TEST_CHECK(pass->GetIndirectComputed());
  std::printf("image after picking vs before: max difference %.0f\n",
    MaxDifference(before, mrgitest::GrabRGB(window)));
  MRGI_TEST_CHECK(MaxDifference(before, mrgitest::GrabRGB(window)) <= 1.0);

  pass->SetIndirectMode(vtkMRGIPass::IndirectOff);
  Compare("vtkMRGIPass, indirect light off", plain, PickAll(window, renderer, probes));

  Uninstall(renderer, window, pass);
  return 0;
}
