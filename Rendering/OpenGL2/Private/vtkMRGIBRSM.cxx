#include "vtkMRGIBRSM.h"

#include "mrgi_brsm_blur.h"
#include "mrgi_brsm_cdf_float.h"
#include "mrgi_brsm_importance.h"
#include "mrgi_brsm_sample.h"
#include "mrgi_brsm_temporal.h"

#include <algorithm>
#include <cmath>

namespace
{
// importance -> blur -> mix -> temporal blend: the weights of the 2-D CDF,
// into a double CDF.
bool BuildCDF(const mrgi_rsm& rsm, const vtkMRGIBRSM::ViewSamples& view,
  const vtkMRGIBRSM::Settings& settings, std::uint64_t seed, std::vector<float>* history,
  std::vector<double>& cdf, std::string& error)
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
  if (history)
  {
    // A history of another size (first frame, a new RSM resolution or
    // light) is not this RSM's: start over.
    const bool has = history->size() == texels;
    history->resize(texels);
    if (mrgi_brsm_temporal_blend(settings.TemporalWeight, importance.data(), history->data(),
          texels, has ? 1 : 0, &err) != MRGI_OK)
    {
      history->clear();
      error = std::string("BRSM temporal blend: ") + err.message;
      return false;
    }
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
  int count, std::uint64_t seed, std::vector<float>* history, mrgi_vpl* vpls, std::string& error)
{
  std::vector<double> cdf;
  if (!BuildCDF(rsm, view, settings, seed, history, cdf, error))
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
  const Settings& settings, int count, std::uint64_t seed, std::vector<float>* history,
  std::vector<float>& cdf, std::vector<float>& samples, std::string& error)
{
  std::vector<double> exact;
  if (!BuildCDF(rsm, view, settings, seed, history, exact, error))
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
