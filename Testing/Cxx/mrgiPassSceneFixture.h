/**
 * @file mrgiPassSceneFixture.h
 * @brief The scene most C++ tests start from: a built-in MRGI scene in a
 *        headless window, drawn through a vtkMRGIPass that delegates to
 *        vtkRenderStepsPass.
 *
 *   mrgitest::PassScene scene(96, 80, "cornell-spot");
 *   vtkMRGIPass* pass = scene.Pass;
 *   pass->SetIndirectMode(vtkMRGIPass::IndirectFull);
 *   scene.Window->Render();
 *
 * The pass is installed with its defaults; a test sets what it exercises
 * before its first Render(). SceneWindow is the same without the pass
 * (VTK's own rendering). A scene that does not build fails the test
 * (naming the scene). Members are destroyed pass first, window last, as
 * the locals this replaces were.
 */
#ifndef mrgiPassSceneFixture_h
#define mrgiPassSceneFixture_h

#include "mrgiTestUtilities.h"

#include "mrgi_vpl_tree.h"

#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkMRGIPass.h"
#include "vtkMRGIReflectiveShadowMapPass.h"
#include "vtkMath.h"
#include "vtkMRGISceneBuilder.h"
#include "vtkNew.h"
#include "vtkRenderStepsPass.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"

#include <cmath>

namespace mrgitest
{
/** A scene in a headless window, drawn by VTK's own passes. */
struct SceneWindow
{
  vtkSmartPointer<vtkRenderWindow> Window;
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkMRGISceneBuilder> Builder;

  /** `scene`: a built-in scene name or a data file (vtkMRGISceneBuilder::SetScene()). */
  SceneWindow(int width, int height, const char* scene)
    : Window(HeadlessWindow(width, height))
  {
    this->Window->AddRenderer(this->Renderer);
    this->Builder->SetScene(scene);
    if (!this->Builder->Build(this->Renderer))
    {
      MRGI_TEST_FAIL("scene '%s' does not build: %s", scene, this->Builder->GetLastErrorMessage());
    }
  }
};

/** The same scene drawn through a vtkMRGIPass (with its defaults) over vtkRenderStepsPass. */
struct PassScene : SceneWindow
{
  vtkNew<vtkRenderStepsPass> Steps;
  vtkNew<vtkMRGIPass> Pass;

  PassScene(int width, int height, const char* scene)
    : SceneWindow(width, height, scene)
  {
    this->Pass->SetDelegatePass(this->Steps);
    this->Renderer->SetPass(this->Pass);
  }
};

/**
 * The RSM of a pass whose scene has one spot light (one perspective view),
 * read back after a render, as the C core's mrgi_rsm and view camera: what a
 * test hands to the core to check a GPU selection bit for bit. The arrays
 * live as long as this object.
 */
struct SpotRSMView
{
  vtkNew<vtkImageData> Position, Normal, Flux;
  mrgi_rsm Map = {};
  mrgi_rsm_view_camera Camera = {};

  SpotRSMView(vtkMRGIPass* pass, vtkRenderWindow* window)
  {
    vtkMRGIReflectiveShadowMapPass* rsm = pass->GetReflectiveShadowMapPass();
    MRGI_TEST_CHECK(rsm->GetNumberOfViews() == 1);
    MRGI_TEST_CHECK(rsm->ReadView(window, 0, this->Position, this->Normal, this->Flux));
    auto floats = [](vtkImageData* image) {
      return vtkFloatArray::SafeDownCast(image->GetPointData()->GetScalars())->GetPointer(0);
    };
    this->Map = { rsm->GetResolution(), 1, floats(this->Position), floats(this->Normal),
      floats(this->Flux) };
    double worldToView[16], projection[16];
    MRGI_TEST_CHECK(rsm->GetViewWorldToView(0, worldToView));
    MRGI_TEST_CHECK(rsm->GetViewProjection(0, projection));
    MRGI_TEST_CHECK(rsm->GetViewPerspective(0));
    for (int i = 0; i < 16; ++i)
    {
      this->Camera.world_to_view[i] = static_cast<float>(worldToView[(i % 4) * 4 + i / 4]); // transpose
    }
    this->Camera.projection.parallel = 0;
    this->Camera.projection.view_angle_deg =
      2.0 * std::atan(1.0 / projection[5]) * 180.0 / vtkMath::Pi();
    this->Camera.projection.parallel_scale = 1.0;
  }
};
}

#endif
