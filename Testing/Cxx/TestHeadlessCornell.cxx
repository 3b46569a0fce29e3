// Renders the built-in Cornell box headless (DISPLAY unset by ctest) through
// vtkMRGIPass with one-bounce indirect light and checks the pixels: the red
// wall is red, the green wall is green, the floor is lit, colour bleeds (red
// onto the tall block's side facing the red wall, green onto the short
// block's side facing the green wall, both onto the ceiling), and the image
// matches its baseline.
#include "mrgiPassSceneFixture.h"
#include "mrgiTestUtilities.h"

#include "vtkMRGIPass.h"
#include "vtkMRGISceneBuilder.h"
#include "vtkRenderStepsPass.h"
#include "vtkRenderer.h"

#include <cstdlib>

int main()
{
  MRGI_TEST_CHECK(std::getenv("DISPLAY") == nullptr || std::getenv("DISPLAY")[0] == '\0');
  const int size = 256;
  mrgitest::PassScene scene(size, size, "cornell");
  vtkRenderWindow* window = scene.Window;
  vtkRenderer* renderer = scene.Renderer;
  vtkMRGIPass* pass = scene.Pass;
  MRGI_TEST_CHECK(scene.Builder->GetBuiltTriangleCount() > 20);

  window->Render();

  vtkSmartPointer<vtkImageData> image = mrgitest::GrabRGB(window);
  double left[3], right[3], floor[3], background[3];
  // The camera looks down +z from z = -800: the red wall (x ~ 556) is on the
  // left of the image, the green wall (x = 0) on the right.
  mrgitest::MeanColor(image, 20, 100, 35, 160, left);
  mrgitest::MeanColor(image, 221, 100, 236, 160, right);
  mrgitest::MeanColor(image, 100, 15, 156, 30, floor);
  mrgitest::MeanColor(image, 0, 0, 4, 4, background);
  std::printf("left wall %.0f %.0f %.0f, right wall %.0f %.0f %.0f, floor %.0f %.0f %.0f\n",
    left[0], left[1], left[2], right[0], right[1], right[2], floor[0], floor[1], floor[2]);
  MRGI_TEST_CHECK(left[0] > 40 && left[0] > 3 * left[1] && left[0] > 3 * left[2]);
  MRGI_TEST_CHECK(right[1] > 40 && right[1] > 2 * right[0] && right[1] > 2 * right[2]);
  MRGI_TEST_CHECK(floor[0] > 30 && floor[1] > 30 && floor[2] > 30);

  // Colour bleeding, read from the indirect radiance buffer (HDR, bottom-up).
  vtkNew<vtkImageData> indirect;
  MRGI_TEST_CHECK(pass->GetIndirectComputed());
  MRGI_TEST_CHECK(pass->GetIndirectBuffer(window, indirect));
  double tallLeft[3], shortRight[3], ceilingLeft[3], ceilingRight[3];
  mrgitest::MeanColor(indirect, 72, 80, 76, 120, tallLeft);     // tall block, side facing the red wall
  mrgitest::MeanColor(indirect, 190, 40, 194, 70, shortRight);  // short block, side facing the green wall
  mrgitest::MeanColor(indirect, 40, 235, 60, 245, ceilingLeft); // ceiling near the red wall
  mrgitest::MeanColor(indirect, 196, 235, 216, 245, ceilingRight);
  std::printf("indirect: tall block %.3f %.3f %.3f, short block %.3f %.3f %.3f, ceiling left "
              "%.3f %.3f %.3f, right %.3f %.3f %.3f\n",
    tallLeft[0], tallLeft[1], tallLeft[2], shortRight[0], shortRight[1], shortRight[2],
    ceilingLeft[0], ceilingLeft[1], ceilingLeft[2], ceilingRight[0], ceilingRight[1],
    ceilingRight[2]);
  MRGI_TEST_CHECK(tallLeft[0] > 1.5 * tallLeft[1]);
  MRGI_TEST_CHECK(shortRight[1] > 1.2 * shortRight[0]);
  MRGI_TEST_CHECK(ceilingLeft[0] > 0.01 && ceilingRight[1] > 0.01);
  MRGI_TEST_CHECK(ceilingLeft[0] / ceilingLeft[1] > ceilingRight[0] / ceilingRight[1]);

  MRGI_TEST_CHECK(mrgitest::CompareWithBaseline(image, "TestHeadlessCornell", 0.02));

  renderer->SetPass(nullptr);
  pass->ReleaseGraphicsResources(window);
  return 0;
}
