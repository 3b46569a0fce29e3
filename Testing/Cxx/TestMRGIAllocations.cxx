// Cold start (issue 17 part 1): on software OpenGL every new texture is
// zero-filled in host memory, which made texture allocation the largest
// part of a first frame. These cases count what frames allocate
// (vtkMRGIResourceStatistics) instead of timing them:
// - a second frame of unchanged settings allocates nothing, nor does a
//   camera move; a new window size reallocates once, then nothing again;
// - a frame allocates only what its settings need: no indirect light <
//   full-resolution gather < multiresolution (the pyramid, the gather's
//   flattened target and the upsampling are the multiresolution's alone),
//   and direct shadows add their buffers only when on.
#include "mrgiPassSceneFixture.h"
#include "mrgiTestUtilities.h"

#include "vtkCamera.h"
#include "vtkMRGIPass.h"
#include "vtkMRGIResourceStatistics.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"

#include <cstdio>

namespace
{
struct Allocated
{
  long long Count;
  long long Bytes;
};

// What one Render() allocates.
Allocated Frame(vtkRenderWindow* window)
{
  const vtkTypeInt64 count = vtkMRGIResourceStatistics::GetNumberOfTextureAllocations();
  const vtkTypeInt64 bytes = vtkMRGIResourceStatistics::GetTextureBytesAllocated();
  window->Render();
  return { static_cast<long long>(vtkMRGIResourceStatistics::GetNumberOfTextureAllocations() - count),
    static_cast<long long>(vtkMRGIResourceStatistics::GetTextureBytesAllocated() - bytes) };
}

// The first frame's allocations of a fresh 64 x 64 cornell-spot pass.
Allocated FirstFrame(int indirectMode, int directShadows)
{
  mrgitest::PassScene scene(64, 64, "cornell-spot");
  scene.Pass->SetIndirectMode(indirectMode);
  scene.Pass->SetDirectShadows(directShadows);
  const Allocated first = Frame(scene.Window);
  scene.Renderer->SetPass(nullptr);
  scene.Pass->ReleaseGraphicsResources(scene.Window);
  return first;
}

void TestSteadyFramesAllocateNothing()
{
  for (int mode : { vtkMRGIPass::IndirectOff, vtkMRGIPass::IndirectFull,
         vtkMRGIPass::IndirectMultires })
  {
    mrgitest::PassScene scene(64, 64, "cornell-spot");
    scene.Pass->SetIndirectMode(mode);
    const Allocated first = Frame(scene.Window);
    const Allocated second = Frame(scene.Window);
    scene.Renderer->GetActiveCamera()->Azimuth(10.0);
    const Allocated moved = Frame(scene.Window);
    scene.Window->SetSize(80, 64);
    const Allocated resized = Frame(scene.Window);
    const Allocated after = Frame(scene.Window);
    std::printf("indirect mode %d: first frame %lld textures (%lld bytes), second %lld, after a "
                "camera move %lld, after a resize %lld, then %lld\n",
      mode, first.Count, first.Bytes, second.Count, moved.Count, resized.Count, after.Count);
    MRGI_TEST_CHECK(first.Count > 0 && first.Bytes > 0);
    MRGI_TEST_CHECK(second.Count == 0 && second.Bytes == 0);
    MRGI_TEST_CHECK(moved.Count == 0);
    MRGI_TEST_CHECK(resized.Count > 0);
    MRGI_TEST_CHECK(after.Count == 0);
    scene.Renderer->SetPass(nullptr);
    scene.Pass->ReleaseGraphicsResources(scene.Window);
  }
}

void TestFramesAllocateWhatTheirSettingsNeed()
{
  const Allocated off = FirstFrame(vtkMRGIPass::IndirectOff, vtkMRGIPass::DirectShadowsOff);
  const Allocated full = FirstFrame(vtkMRGIPass::IndirectFull, vtkMRGIPass::DirectShadowsOff);
  const Allocated multires =
    FirstFrame(vtkMRGIPass::IndirectMultires, vtkMRGIPass::DirectShadowsOff);
  const Allocated shadowed =
    FirstFrame(vtkMRGIPass::IndirectFull, vtkMRGIPass::DirectShadowsSoft);
  std::printf("first frame, textures (bytes): off %lld (%lld), full %lld (%lld), multires %lld "
              "(%lld), full with soft shadows %lld (%lld)\n",
    off.Count, off.Bytes, full.Count, full.Bytes, multires.Count, multires.Bytes, shadowed.Count,
    shadowed.Bytes);
  MRGI_TEST_CHECK(off.Count > 0 && off.Count < full.Count && off.Bytes < full.Bytes);
  MRGI_TEST_CHECK(full.Count < multires.Count && full.Bytes < multires.Bytes);
  MRGI_TEST_CHECK(full.Count < shadowed.Count && full.Bytes < shadowed.Bytes);
}
}

int main(int argc, char* argv[])
{
  return mrgitest::RunCases(argc, argv,
    { MRGI_TEST_CASE(TestSteadyFramesAllocateNothing),
      MRGI_TEST_CASE(TestFramesAllocateWhatTheirSettingsNeed) });
}
