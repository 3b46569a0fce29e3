#include "vtkMRGIBRSM.h"

#include "vtkMRGIFrameContext.h"
#include "vtkMRGIShaderUtilities.h"

#include "vtkCamera.h"
#include "vtkMatrix4x4.h"
#include "vtkRenderer.h"

#include "mrgi_brsm_blur.h"
#include "mrgi_brsm_cdf_float.h"
#include "mrgi_brsm_importance.h"
#include "mrgi_brsm_sample.h"

#include <algorithm>
#include <cmath>

//------------------------------------------------------------------------------
bool vtkMRGIBRSM::TakeViewSamples(const vtkMRGIFrameContext& frame, int side, std::uint64_t seed,
  ViewSamples& out, std::string& error)
{
  out.Samples.clear();
  out.HasCamera = false;
  const int w = frame.Viewport[2], h = frame.Viewport[3];
  if (!frame.Window || !frame.Position || !frame.Normal || !frame.Albedo || w < 1 || h < 1)
  {
    error = "BRSM view samples need the frame's G-buffer (position, normal, albedo)";
    return false;
  }
  side = std::max(1, std::min(side, 32)); // at most MRGI_BRSM_MAX_VIEW_SAMPLES
  const size_t pixels = static_cast<size_t>(w) * static_cast<size_t>(h) * 4;
  std::vector<float> position(pixels), normal(pixels), albedo(pixels);
  const int x0 = frame.Viewport[0], y0 = frame.Viewport[1];
  if (!vtkMRGIShaderUtilities::ReadTextureRegion(frame.Window, frame.Position, x0, y0, w, h, 4,
        position.data()) ||
    !vtkMRGIShaderUtilities::ReadTextureRegion(frame.Window, frame.Normal, x0, y0, w, h, 4,
      normal.data()) ||
    !vtkMRGIShaderUtilities::ReadTextureRegion(frame.Window, frame.Albedo, x0, y0, w, h, 4,
      albedo.data()))
  {
    error = "cannot read the G-buffer back for the BRSM view samples";
    return false;
  }
  const double* m = frame.ViewToWorldDouble; // column-major eye -> world
  out.Samples.assign(static_cast<size_t>(side) * side * MRGI_BRSM_VIEW_SAMPLE_FLOATS, 0.0f);
  for (int j = 0; j < side; ++j)
  {
    for (int i = 0; i < side; ++i)
    {
      const uint64_t k = static_cast<uint64_t>(j) * side + i;
      const double px = (i + mrgi_brsm_hash01(seed, 2 * k)) * w / side;
      const double py = (j + mrgi_brsm_hash01(seed, 2 * k + 1)) * h / side;
      const int x = std::min(w - 1, static_cast<int>(px));
      const int y = std::min(h - 1, static_cast<int>(py));
      const size_t p = (static_cast<size_t>(y) * w + x) * 4;
      float* s = out.Samples.data() + k * MRGI_BRSM_VIEW_SAMPLE_FLOATS;
      for (int row = 0; row < 3; ++row)
      {
        s[row] = static_cast<float>(m[row] * position[p] + m[4 + row] * position[p + 1] +
          m[8 + row] * position[p + 2] + m[12 + row]);
        s[4 + row] = static_cast<float>(
          m[row] * normal[p] + m[4 + row] * normal[p + 1] + m[8 + row] * normal[p + 2]);
        s[8 + row] = albedo[p + row];
      }
      s[3] = static_cast<float>(x + 0.5);
      s[7] = static_cast<float>(y + 0.5);
      s[11] = position[p + 3] > MRGI_VALID_THRESHOLD ? 1.0f : 0.0f;
    }
  }
  vtkCamera* camera = frame.Renderer ? frame.Renderer->GetActiveCamera() : nullptr;
  if (camera)
  {
    vtkMatrix4x4* rowMajor = camera->GetCompositeProjectionTransformMatrix(
      static_cast<double>(w) / static_cast<double>(h), -1.0, 1.0);
    for (int row = 0; row < 4; ++row)
    {
      for (int col = 0; col < 4; ++col)
      {
        out.WorldToClip[col * 4 + row] = static_cast<float>(rowMajor->GetElement(row, col));
      }
    }
    out.HasCamera = true;
  }
  out.Width = w;
  out.Height = h;
  return true;
}

namespace
{
// importance -> blur -> mix: the weights of the 2-D CDF, into a double CDF.
bool BuildCDF(const mrgi_rsm& rsm, const vtkMRGIBRSM::ViewSamples& view,
  const vtkMRGIBRSM::Settings& settings, std::uint64_t seed, std::vector<double>& cdf,
  std::string& error)
{
  const size_t texels = mrgi_vpl_importance_scratch_count(&rsm);
  std::vector<float> importance(texels, 0.0f), blurred;
  mrgi_error err;
  const int sampleCount =
    static_cast<int>(view.Samples.size() / MRGI_BRSM_VIEW_SAMPLE_FLOATS);
  if (sampleCount > 0)
  {
    const mrgi_brsm_view v = { view.Samples.data(), sampleCount,
      view.HasCamera ? view.WorldToClip : nullptr, view.Width, view.Height,
      std::min(settings.SamplesPerTexel, sampleCount), settings.Guided ? 1 : 0 };
    if (mrgi_brsm_importance(&rsm, &v, seed, importance.data(), texels, &err) != MRGI_OK)
    {
      error = std::string("BRSM importance: ") + err.message;
      return false;
    }
  }
  if (settings.Blur)
  {
    blurred.resize(texels);
    if (mrgi_brsm_blur(&rsm, importance.data(), blurred.data(), texels, &err) != MRGI_OK)
    {
      error = std::string("BRSM blur: ") + err.message;
      return false;
    }
    importance.swap(blurred);
  }
  if (mrgi_brsm_mix(&rsm, settings.FluxShare, importance.data(), texels, &err) != MRGI_OK)
  {
    error = std::string("BRSM mix: ") + err.message;
    return false;
  }
  cdf.assign(mrgi_brsm_cdf_count(&rsm), 0.0);
  if (mrgi_brsm_cdf_build(&rsm, importance.data(), texels, cdf.data(), cdf.size(), nullptr, &err) !=
    MRGI_OK)
  {
    error = std::string("BRSM CDF: ") + err.message;
    return false;
  }
  return true;
}
}

//------------------------------------------------------------------------------
bool vtkMRGIBRSM::Select(const mrgi_rsm& rsm, const ViewSamples& view, const Settings& settings,
  int count, std::uint64_t seed, mrgi_vpl* vpls, std::string& error)
{
  std::vector<double> cdf;
  if (!BuildCDF(rsm, view, settings, seed, cdf, error))
  {
    return false;
  }
  mrgi_error err;
  const mrgi_brsm_sampling sampling = { count, seed, settings.InterTexel ? 1 : 0,
    view.HasCamera ? view.WorldToClip : nullptr };
  if (mrgi_brsm_sample_vpls(&rsm, cdf.data(), cdf.size(), &sampling, nullptr, vpls, count,
        nullptr, &err) != MRGI_OK)
  {
    error = std::string("BRSM sampling: ") + err.message;
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkMRGIBRSM::PrepareInversion(const mrgi_rsm& rsm, const ViewSamples& view,
  const Settings& settings, int count, std::uint64_t seed, std::vector<float>& cdf,
  std::vector<float>& samples, std::string& error)
{
  std::vector<double> exact;
  if (!BuildCDF(rsm, view, settings, seed, exact, error))
  {
    return false;
  }
  mrgi_error err;
  cdf.assign(mrgi_brsm_cdf_float_count(&rsm), 0.0f);
  samples.assign(2 * static_cast<size_t>(std::max(count, 0)), 0.0f);
  if (mrgi_brsm_cdf_to_float(&rsm, exact.data(), exact.size(), cdf.data(), cdf.size(), &err) !=
      MRGI_OK ||
    mrgi_brsm_sample_values(count, seed, samples.data(), samples.size(), &err) != MRGI_OK)
  {
    error = std::string("BRSM GPU inputs: ") + err.message;
    return false;
  }
  return true;
}
