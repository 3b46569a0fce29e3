// The smallest MRGI program: the Cornell box, rendered headless through
// vtkMRGIPass, written to cornell.png and cornell.exr.
#include "vtkImageData.h"
#include "vtkMRGIImageIO.h"
#include "vtkMRGIPass.h"
#include "vtkMRGIRenderWindowFactory.h"
#include "vtkMRGISceneBuilder.h"
#include "vtkNew.h"
#include "vtkRenderStepsPass.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"

#include <cstdio>

int main()
{
  auto window = vtkSmartPointer<vtkRenderWindow>::Take(
    vtkMRGIRenderWindowFactory::CreateRenderWindow(vtkMRGIRenderWindowFactory::Headless));
  if (!window)
  {
    std::fprintf(stderr, "no headless OpenGL context on this machine\n");
    return 1;
  }
  window->SetSize(512, 512);
  vtkNew<vtkRenderer> renderer;
  window->AddRenderer(renderer);

  vtkNew<vtkMRGISceneBuilder> scene;
  scene->SetScene("cornell");
  scene->Build(renderer);

  // The three lines that add MRGI to any VTK renderer.
  vtkNew<vtkRenderStepsPass> steps;
  vtkNew<vtkMRGIPass> mrgi;
  mrgi->SetDelegatePass(steps);
  renderer->SetPass(mrgi);

  window->Render();

  vtkNew<vtkImageData> hdr;
  vtkNew<vtkMRGIImageIO> io;
  if (mrgi->GetColorBuffer(window, hdr) && io->Write(hdr, "cornell.exr"))
  {
    std::printf("wrote cornell.exr\n");
  }
  mrgi->ReleaseGraphicsResources(window);
  return 0;
}
