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

#include "vtkMRGIPass.h"
#include "vtkMRGISceneBuilder.h"
#include "vtkNew.h"
#include "vtkRenderStepsPass.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"

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
}

#endif
