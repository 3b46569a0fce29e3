/**
 * @file vtkMRGIBRSM.h
 * @brief Internal: bidirectional RSM (BRSM) VPL selection for
 *        vtkMRGIVPLSelection's BRSM mode (RIHKS11 4, 4.1, 4.2, 6.5): the C
 *        core's chain
 *        (mrgi_brsm_importance -> mrgi_brsm_blur -> mrgi_brsm_mix ->
 *        mrgi_brsm_temporal_blend -> mrgi_brsm_cdf_build ->
 *        mrgi_brsm_sample_vpls) on read-back RSMs.
 *        Not wrapped, not installed.
 */
#ifndef vtkMRGIBRSM_h
#define vtkMRGIBRSM_h

#include "mrgi_brsm_importance.h" // For MRGI_BRSM_DEFAULT_SAMPLES_PER_TEXEL

#include <cstdint> // For uint64_t
#include <string>  // For std::string
#include <vector>  // For std::vector

struct mrgi_rsm;
struct mrgi_vpl;

namespace vtkMRGIBRSM
{
/**
 * The view samples of one frame (mrgi_brsm_importance.h layout) and the
 * guide's camera; vtkMRGIViewSamples takes them from the G-buffer.
 */
struct ViewSamples
{
  std::vector<float> Samples;   // M * MRGI_BRSM_VIEW_SAMPLE_FLOATS, world space
  float WorldToClip[16] = {};   // column-major
  bool HasCamera = false;
  int Width = 0;
  int Height = 0;
};

/** Settings of one selection. */
struct Settings
{
  double FluxShare = 0.1; // beta, MRGI_BRSM_DEFAULT_FLUX_SHARE
  bool Blur = true;
  bool InterTexel = true;
  bool Guided = true;
  int SamplesPerTexel = MRGI_BRSM_DEFAULT_SAMPLES_PER_TEXEL;
  double TemporalWeight = 1.0; // a of mrgi_brsm_temporal_blend; 1: no blend
};

/**
 * `count` VPLs from `rsm` (read back, world space) into `vpls`. Without
 * view samples the importance is 0 and the mix gives flux importance.
 * `history` (may be null: no blend) is the light's pdf of the previous
 * selection, the passive buffer of mrgi_brsm_temporal_blend(): blended
 * with this frame's by settings.TemporalWeight and replaced; one of
 * another size starts over. False, with `error` naming the failed stage.
 */
bool Select(const mrgi_rsm& rsm, const ViewSamples& view, const Settings& settings, int count,
  std::uint64_t seed, std::vector<float>* history, mrgi_vpl* vpls, std::string& error);

/**
 * The GPU inversion's inputs (vtkMRGIBRSMInversion, texel VPLs): the same
 * weights as Select() (the same `history` rule), their 2-D CDF rounded to float
 * (mrgi_brsm_cdf_to_float()) and the `count` sample values
 * (mrgi_brsm_sample_values()) for `seed`. False, with `error`.
 */
bool PrepareInversion(const mrgi_rsm& rsm, const ViewSamples& view, const Settings& settings,
  int count, std::uint64_t seed, std::vector<float>* history, std::vector<float>& cdf,
  std::vector<float>& samples, std::string& error);
}

#endif
