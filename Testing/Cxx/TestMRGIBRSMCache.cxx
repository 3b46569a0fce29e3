// BRSM's caches and fixed patterns (issue 13 part 5; RIHKS11 4):
// 1. Static scene: a second frame recomputes nothing (no VPL selection, no
//    G-buffer read-back) and the VPL cache is bit for bit the same.
// 2. The view samples are one read-back per frame shared by BRSM and the
//    adaptive imperfect shadow map points: a camera move costs exactly one.
// 3. Fixed patterns: moving the camera away and back (the same view, but
//    every cache invalidated) recomputes the selection; the pdf's moving
//    average remembers the detour, and ResetBRSMHistory() alone selects
//    again: the VPLs are the first frame's bit for bit, with inter-texel
//    VPLs (C path) and texel VPLs (GPU inversion). A frame-dependent jitter or seed (the old
//    flicker) fails.
#include "mrgiPassSceneFixture.h"
#include "mrgiTestUtilities.h"

#include "vtkCamera.h"
#include "vtkMRGIIndirectLight.h"
#include "vtkMRGIVPLSelection.h"

#include "mrgi_vpl.h"

#include <cstdio>
#include <cstring>
#include <vector>

namespace
{
bool Same(const std::vector<mrgi_vpl>& a, const std::vector<mrgi_vpl>& b)
{
  return a.size() == b.size() && !a.empty() &&
    std::memcmp(a.data(), b.data(), sizeof(mrgi_vpl) * a.size()) == 0;
}

struct CameraState
{
  double Position[3], Focal[3], Up[3];
  explicit CameraState(vtkCamera* c)
  {
    c->GetPosition(this->Position);
    c->GetFocalPoint(this->Focal);
    c->GetViewUp(this->Up);
  }
  void Restore(vtkCamera* c) const
  {
    c->SetPosition(this->Position);
    c->SetFocalPoint(this->Focal);
    c->SetViewUp(this->Up);
  }
};

void StaticAndShared()
{
  mrgitest::PassScene scene(48, 48, "cornell-spot");
  vtkMRGIPass* pass = scene.Pass;
  pass->SetIndirectMode(vtkMRGIPass::IndirectFull);
  pass->SetNumberOfVPLs(64);
  pass->SetRSMResolution(32);
  pass->SetVPLSelectionMode(vtkMRGIVPLSelection::BRSM);
  pass->SetIndirectVisibility(vtkMRGIIndirectLight::VisibilityISM); // adaptive points (default)
  vtkMRGIVPLSelection* selection = pass->GetVPLSelection();
  vtkMRGIIndirectLight* indirect = pass->GetIndirectLightStage();
  vtkCamera* camera = scene.Renderer->GetActiveCamera();
  const CameraState home(camera);

  scene.Window->Render();
  const vtkIdType selections = selection->GetNumberOfSelections();
  const long long reads = indirect->GetNumberOfViewSampleReadBacks();
  const std::vector<mrgi_vpl> first = mrgitest::ReadVPLs(pass, scene.Window);
  std::printf("frame 1: %lld selections, %lld read-backs, %d view samples\n",
    static_cast<long long>(selections), reads, selection->GetNumberOfViewSamples());
  MRGI_TEST_CHECK(selections == 1);
  MRGI_TEST_CHECK(reads == 1); // BRSM and the ISM points share one
  MRGI_TEST_CHECK(selection->GetNumberOfViewSamples() == 1024);
  MRGI_TEST_CHECK(first.size() == 64);

  // 1. Static: nothing recomputed, nothing read back, the same VPLs.
  scene.Window->Render();
  scene.Window->Render();
  MRGI_TEST_CHECK(selection->GetNumberOfSelections() == selections);
  MRGI_TEST_CHECK(indirect->GetNumberOfViewSampleReadBacks() == reads);
  MRGI_TEST_CHECK(Same(mrgitest::ReadVPLs(pass, scene.Window), first));

  // 2. The camera moves: one read-back for both stages, a new selection.
  camera->Azimuth(15.0);
  scene.Window->Render();
  std::printf("moved: %lld read-backs, %lld selections\n",
    indirect->GetNumberOfViewSampleReadBacks(),
    static_cast<long long>(selection->GetNumberOfSelections()));
  MRGI_TEST_CHECK(indirect->GetNumberOfViewSampleReadBacks() == reads + 1);
  MRGI_TEST_CHECK(selection->GetNumberOfSelections() == selections + 1);
  const std::vector<mrgi_vpl> moved = mrgitest::ReadVPLs(pass, scene.Window);
  MRGI_TEST_CHECK(!Same(moved, first)); // the view samples did change

  // 3. Back to the same view: recomputed. The pdf's moving average over the
  // selections (BRSMTemporalWeight, default 0.005) remembers the moved view,
  // so the VPLs differ; without that history they are the very same.
  home.Restore(camera);
  scene.Window->Render();
  MRGI_TEST_CHECK(indirect->GetNumberOfViewSampleReadBacks() == reads + 2);
  MRGI_TEST_CHECK(selection->GetNumberOfSelections() == selections + 2);
  const bool remembered = !Same(mrgitest::ReadVPLs(pass, scene.Window), first);
  // The reset alone selects again (nothing else changed): from this
  // frame's pdf, not one frame late.
  selection->ResetBRSMHistory();
  scene.Window->Render();
  MRGI_TEST_CHECK(selection->GetNumberOfSelections() == selections + 3);
  const bool same = Same(mrgitest::ReadVPLs(pass, scene.Window), first);
  std::printf("back home (inter-texel VPLs): %s with the history, %s after ResetBRSMHistory()\n",
    remembered ? "different" : "IDENTICAL", same ? "identical" : "DIFFERENT");
  MRGI_TEST_CHECK(remembered);
  MRGI_TEST_CHECK(same);

  // The same with texel VPLs (the GPU inversion) and the pdf of each frame
  // alone (weight 1, RIHKS11's rule): a recomputation gives the same VPLs.
  selection->SetBRSMTemporalWeight(1.0);
  selection->SetBRSMInterTexel(false);
  scene.Window->Render();
  const std::vector<mrgi_vpl> texel = mrgitest::ReadVPLs(pass, scene.Window);
  camera->Modified(); // the same view, every cache stale
  scene.Window->Render();
  MRGI_TEST_CHECK(selection->GetNumberOfSelections() == selections + 5);
  const bool sameTexel = Same(mrgitest::ReadVPLs(pass, scene.Window), texel);
  std::printf("recomputed (texel VPLs): %s\n", sameTexel ? "identical" : "DIFFERENT");
  MRGI_TEST_CHECK(sameTexel);
  scene.Renderer->SetPass(nullptr);
  pass->ReleaseGraphicsResources(scene.Window);
}
}

int main(int argc, char* argv[])
{
  return mrgitest::RunCases(argc, argv, { MRGI_TEST_CASE(StaticAndShared) });
}
