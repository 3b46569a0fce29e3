#include "mrgiRenderImages.h"

#include "mrgiRenderOptions.h"

#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkUnsignedCharArray.h"

#include "mrgi_box_filter.h"
#include "mrgi_error.h"

#include <algorithm>
#include <cmath>

namespace mrgirender
{
bool ReadWindowRGB(vtkRenderWindow* window, int width, int height, vtkImageData* image)
{
  vtkNew<vtkUnsignedCharArray> pixels;
  if (!window->GetRGBACharPixelData(0, 0, width - 1, height - 1, 0, pixels))
  {
    return false;
  }
  const vtkIdType count = static_cast<vtkIdType>(width) * height;
  if (pixels->GetNumberOfValues() < 4 * count)
  {
    return false;
  }
  // RGBA -> RGB in place: each pixel moves to a lower or equal index.
  unsigned char* p = pixels->GetPointer(0);
  for (vtkIdType i = 0; i < count; ++i)
  {
    p[3 * i] = p[4 * i];
    p[3 * i + 1] = p[4 * i + 1];
    p[3 * i + 2] = p[4 * i + 2];
  }
  pixels->SetNumberOfComponents(3);
  pixels->Resize(count);
  pixels->SetNumberOfTuples(count);
  image->SetDimensions(width, height, 1);
  image->GetPointData()->SetScalars(pixels);
  return true;
}

bool ShowsDisplayImage(const Options& o)
{
  if (o.Interactive || o.Outputs.empty())
  {
    return true;
  }
  if (o.Reference || o.IndirectOnly)
  {
    return false;
  }
  return std::any_of(o.Outputs.begin(), o.Outputs.end(),
    [](const std::string& path) { return !EndsWith(path, ".exr"); });
}

bool OnlyBackground(vtkImageData* image, const double background[3])
{
  vtkDataArray* pixels = image ? image->GetPointData()->GetScalars() : nullptr;
  if (!pixels || pixels->GetNumberOfComponents() < 3)
  {
    return false;
  }
  const bool eightBit = pixels->GetDataType() == VTK_UNSIGNED_CHAR;
  // Each image is compared in its own type: 8-bit steps for the window's,
  // float for the HDR colour (its background is the clear colour rounded to
  // float). The float values live in a float array on purpose: GCC 12.2 at
  // -O3 vectorized `expected = (double)(float)background` into a copy
  // without the rounding, so that no float pixel ever matched.
  float hdrBackground[3];
  double displayBackground[3];
  for (int c = 0; c < 3; ++c)
  {
    hdrBackground[c] = static_cast<float>(background[c]);
    displayBackground[c] = std::round(255.0 * std::min(1.0, std::max(0.0, background[c])));
  }
  const vtkIdType n = pixels->GetNumberOfTuples();
  for (vtkIdType p = 0; p < n; ++p)
  {
    for (int c = 0; c < 3; ++c)
    {
      const double value = pixels->GetComponent(p, c);
      // NaN differs from every background.
      const bool same = eightBit ? std::abs(value - displayBackground[c]) <= 1.0
                                 : static_cast<float>(value) == hdrBackground[c];
      if (!same)
      {
        return false;
      }
    }
  }
  return true;
}

std::string WhyEmpty(vtkRenderer* renderer, vtkIdType triangles)
{
  if (renderer->VisibleActorCount() == 0)
  {
    return "the scene has nothing to draw";
  }
  double b[6];
  renderer->ComputeVisiblePropBounds(b);
  if (!vtkMath::AreBoundsInitialized(b))
  {
    return "the scene has no geometry with finite bounds";
  }
  bool lit = false;
  vtkLightCollection* lights = renderer->GetLights();
  lights->InitTraversal();
  while (vtkLight* light = lights->GetNextItem())
  {
    lit = lit || (light->GetSwitch() && light->GetIntensity() > 0);
  }
  if (!lit && renderer->GetLights()->GetNumberOfItems() > 0)
  {
    return "no light is on";
  }
  return triangles == 0 ? "the data has no surfaces, and its points or lines are not in view"
                        : "the geometry is outside the view, clipped, seen edge-on or unlit";
}

bool Downsample(vtkImageData* image, int factor, std::string& why)
{
  if (factor <= 1)
  {
    return true;
  }
  int dims[3];
  image->GetDimensions(dims);
  vtkDataArray* scalars = image->GetPointData()->GetScalars();
  const int channels = scalars->GetNumberOfComponents();
  mrgi_image full, small;
  mrgi_error err;
  if (mrgi_image_create(&full, dims[0], dims[1], channels, &err) != MRGI_OK)
  {
    why = std::string("supersampling: ") + err.message;
    return false;
  }
  const vtkIdType values = scalars->GetNumberOfValues();
  for (vtkIdType i = 0; i < values; ++i)
  {
    full.pixels[i] = static_cast<float>(scalars->GetVariantValue(i).ToDouble());
  }
  const mrgi_status status = mrgi_box_downsample(&full, factor, &small, &err);
  mrgi_image_destroy(&full);
  if (status != MRGI_OK)
  {
    why = std::string("supersampling: ") + err.message;
    return false;
  }
  vtkSmartPointer<vtkDataArray> out = vtkSmartPointer<vtkDataArray>::Take(scalars->NewInstance());
  out->SetNumberOfComponents(channels);
  out->SetNumberOfTuples(static_cast<vtkIdType>(small.width) * small.height);
  out->SetName(scalars->GetName());
  const bool bytes = scalars->GetDataType() == VTK_UNSIGNED_CHAR;
  for (vtkIdType i = 0; i < out->GetNumberOfValues(); ++i)
  {
    const double v = small.pixels[i];
    out->SetVariantValue(i,
      bytes ? vtkVariant(static_cast<unsigned char>(std::lround(std::min(std::max(v, 0.0), 255.0))))
            : vtkVariant(v));
  }
  image->SetDimensions(small.width, small.height, 1);
  image->GetPointData()->SetScalars(out);
  mrgi_image_destroy(&small);
  return true;
}
}
