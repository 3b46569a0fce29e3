/**
 * @file TestMRGIPipelineCommon.h
 * @brief Helpers shared by the TestMRGIPipeline* tests: vtkMRGIPass installed
 *        in ordinary VTK pipelines (transforms, colour sources, composite
 *        data, lights, translucency, volumes, overlays, FXAA, viewports,
 *        picking), checked on pixels and read-back buffers.
 *
 * Every scene is small (160 x 120 or so) so that the whole set runs in a few
 * seconds on llvmpipe.
 */
#ifndef TestMRGIPipelineCommon_h
#define TestMRGIPipelineCommon_h

#include "mrgiTestUtilities.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkMRGIPass.h"
#include "vtkMatrix4x4.h"
#include "vtkObjectFactory.h"
#include "vtkPlaneSource.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderStepsPass.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"
#include "vtkVersion.h"

#include "mrgi_buffers.h"


#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace mrgipipe
{
/** vtkMRGIPass with a vtkRenderStepsPass delegate, installed on `renderer`. */
inline vtkSmartPointer<vtkMRGIPass> Install(vtkRenderer* renderer)
{
  vtkNew<vtkRenderStepsPass> steps;
  auto pass = vtkSmartPointer<vtkMRGIPass>::New();
  pass->SetDelegatePass(steps);
  // These tests check that VTK's features keep working with the indirect
  // light, several against VTK's own image with IndirectMode Off; direct
  // shadows (on by default) change that image on purpose and have their
  // own tests (cxx.TestMRGIShadowComposite, cxx.TestMRGIShadowComposition).
  pass->SetDirectShadowsToOff();
  renderer->SetPass(pass);
  return pass;
}

/** Take the pass off the renderer and free its GL resources. */
inline void Uninstall(vtkRenderer* renderer, vtkRenderWindow* window, vtkMRGIPass* pass)
{
  renderer->SetPass(nullptr);
  pass->ReleaseGraphicsResources(window);
}

/** An actor showing `source`'s output with a solid diffuse colour. */
inline vtkSmartPointer<vtkActor> MakeActor(vtkAlgorithm* source, double r, double g, double b)
{
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(source->GetOutputPort());
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(r, g, b);
  actor->GetProperty()->SetSpecular(0.0);
  return actor;
}

/** A square of side `size` centred at `c` with normal `n`. */
inline vtkSmartPointer<vtkActor> MakeQuad(
  const double c[3], const double n[3], double size, double r, double g, double b, int res = 1)
{
  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(-0.5 * size, -0.5 * size, 0);
  plane->SetPoint1(0.5 * size, -0.5 * size, 0);
  plane->SetPoint2(-0.5 * size, 0.5 * size, 0);
  plane->SetResolution(res, res);
  plane->SetCenter(c[0], c[1], c[2]);
  plane->SetNormal(n[0], n[1], n[2]);
  return MakeActor(plane, r, g, b);
}

/** Value of component `c` of pixel (x, y) (bottom-up) of a float image. */
inline double At(vtkImageData* image, int x, int y, int c)
{
  return image->GetScalarComponentAsDouble(x, y, 0, c);
}

/** Whether every value of `image` is finite. */
inline bool AllFinite(vtkImageData* image)
{
  vtkDataArray* s = image->GetPointData()->GetScalars();
  for (vtkIdType i = 0; i < s->GetNumberOfValues(); ++i)
  {
    if (!std::isfinite(s->GetVariantValue(i).ToDouble()))
    {
      return false;
    }
  }
  return true;
}

/**
 * Largest absolute difference between two images of the same size and type
 * over the pixel rectangle [x0,x1) x [y0,y1) (whole image when x1 < 0).
 */
inline double MaxDifference(
  vtkImageData* a, vtkImageData* b, int x0 = 0, int y0 = 0, int x1 = -1, int y1 = -1)
{
  int dims[3], dimsB[3];
  a->GetDimensions(dims);
  b->GetDimensions(dimsB);
  MRGI_TEST_CHECK(dims[0] == dimsB[0] && dims[1] == dimsB[1]);
  vtkDataArray* sa = a->GetPointData()->GetScalars();
  vtkDataArray* sb = b->GetPointData()->GetScalars();
  MRGI_TEST_CHECK(sa->GetNumberOfComponents() == sb->GetNumberOfComponents());
  if (x1 < 0)
  {
    x1 = dims[0];
    y1 = dims[1];
  }
  double worst = 0;
  const int nc = sa->GetNumberOfComponents();
  for (int y = y0; y < y1; ++y)
  {
    for (int x = x0; x < x1; ++x)
    {
      const vtkIdType id = static_cast<vtkIdType>(y) * dims[0] + x;
      for (int c = 0; c < nc; ++c)
      {
        worst = std::max(worst, std::fabs(sa->GetComponent(id, c) - sb->GetComponent(id, c)));
      }
    }
  }
  return worst;
}

/** Number of pixels whose RGB differs by more than `threshold` in some channel. */
inline int CountDifferent(vtkImageData* a, vtkImageData* b, double threshold)
{
  vtkDataArray* sa = a->GetPointData()->GetScalars();
  vtkDataArray* sb = b->GetPointData()->GetScalars();
  int count = 0;
  for (vtkIdType p = 0; p < sa->GetNumberOfTuples(); ++p)
  {
    for (int c = 0; c < 3; ++c)
    {
      if (std::fabs(sa->GetComponent(p, c) - sb->GetComponent(p, c)) > threshold)
      {
        ++count;
        break;
      }
    }
  }
  return count;
}

/** Whether G-buffer / RSM texel (x, y) of `buffer` holds geometry (w > threshold). */
inline bool Valid(vtkImageData* buffer, int x, int y)
{
  return At(buffer, x, y, 3) > MRGI_GBUFFER_VALID_THRESHOLD;
}

/** Number of texels of an RSM / G-buffer image that hold geometry. */
inline int CountValid(vtkImageData* buffer)
{
  int dims[3];
  buffer->GetDimensions(dims);
  int n = 0;
  for (int y = 0; y < dims[1]; ++y)
  {
    for (int x = 0; x < dims[0]; ++x)
    {
      n += Valid(buffer, x, y) ? 1 : 0;
    }
  }
  return n;
}

/** Sum of RGB of a float image over a rectangle, and its maximum channel value. */
inline double SumRGB(vtkImageData* image, int x0, int y0, int x1, int y1, double rgb[3] = nullptr)
{
  double sum[3] = { 0, 0, 0 };
  for (int y = y0; y < y1; ++y)
  {
    for (int x = x0; x < x1; ++x)
    {
      for (int c = 0; c < 3; ++c)
      {
        sum[c] += At(image, x, y, c);
      }
    }
  }
  if (rgb)
  {
    std::copy(sum, sum + 3, rgb);
  }
  return sum[0] + sum[1] + sum[2];
}

/** Eye-space point (VTK "VC") of world point `w` under `renderer`'s camera. */
inline void WorldToEye(vtkRenderer* renderer, const double w[3], double e[3])
{
  vtkMatrix4x4* view = renderer->GetActiveCamera()->GetModelViewTransformMatrix();
  const double in[4] = { w[0], w[1], w[2], 1.0 };
  double out[4];
  view->MultiplyPoint(in, out);
  e[0] = out[0];
  e[1] = out[1];
  e[2] = out[2];
}

/** World point of eye-space point `e` under `renderer`'s camera. */
inline void EyeToWorld(vtkRenderer* renderer, const double e[3], double w[3])
{
  vtkNew<vtkMatrix4x4> inverse;
  vtkMatrix4x4::Invert(renderer->GetActiveCamera()->GetModelViewTransformMatrix(), inverse);
  const double in[4] = { e[0], e[1], e[2], 1.0 };
  double out[4];
  inverse->MultiplyPoint(in, out);
  for (int k = 0; k < 3; ++k)
  {
    w[k] = out[k] / out[3];
  }
}

/** With MRGI_PIPELINE_DEBUG set, write `image` to the test's scratch directory. */
inline void DebugWrite(vtkImageData* image, const std::string& name)
{
  if (std::getenv("MRGI_PIPELINE_DEBUG"))
  {
    vtkNew<vtkMRGIImageIO> io;
    io->WritePNG(image, mrgitest::TempPath(name + ".png").c_str());
  }
}

}

#endif
