// The extremes of window size: 4096x4096 renders through vtkMRGIPass with a
// finite HDR buffer of the right size, and the Cornell box is still there.
#include "mrgiPassSceneFixture.h"
#include "mrgiTestUtilities.h"

#include "vtkFloatArray.h"
#include "vtkMRGIPass.h"
#include "vtkMRGISceneBuilder.h"
#include "vtkRenderStepsPass.h"
#include "vtkRenderer.h"

#include <cmath>

int main()
{
  const int size = 4096;
  mrgitest::PassScene scene(size, size, "cornell");
  vtkRenderWindow* window = scene.Window;
  vtkMRGIPass* pass = scene.Pass;
  window->Render();
  MRGI_TEST_CHECK(pass->GetBufferSize()[0] == size && pass->GetBufferSize()[1] == size);
  vtkNew<vtkImageData> hdr;
  MRGI_TEST_CHECK(pass->GetColorBuffer(window, hdr));
  vtkFloatArray* v = vtkFloatArray::SafeDownCast(hdr->GetPointData()->GetScalars());
  MRGI_TEST_CHECK(v->GetNumberOfTuples() == static_cast<vtkIdType>(size) * size);
  double lit = 0;
  for (vtkIdType i = 0; i < v->GetNumberOfTuples(); ++i)
  {
    const float r = v->GetValue(4 * i);
    MRGI_TEST_CHECK(std::isfinite(r));
    lit += r > 0.05f ? 1 : 0;
  }
  std::printf("lit fraction %.3f\n", lit / (double(size) * size));
  MRGI_TEST_CHECK(lit / (double(size) * size) > 0.5);
  scene.Renderer->SetPass(nullptr);
  pass->ReleaseGraphicsResources(window);
  return 0;
}
