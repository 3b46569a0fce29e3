/**
 * @file mrgi_exposure.h
 * @brief Exposure and tone curve of MRGI's output step: C twin of the
 *        "output" stage's colour transform (vtkMRGICompositeFS).
 *
 * ## The transform, per pixel, per colour channel c (alpha is kept)
 *
 *     s     = 2^EV                                    (mrgi_exposure_scale)
 *     x     = s * c                                   (exposure, on the HDR value)
 *     out   = x                  without tone mapping (the window clamps to [0, 1])
 *     out   = T(x)               with tone mapping    (mrgi_tone_curve)
 *
 * ## The tone curve T
 *
 * VTK writes its shading to the framebuffer as it is: no sRGB or gamma
 * encode (vtkRenderWindow::UseSRGBColorSpace is off by default), so the
 * display value of an untone-mapped linear value x is x itself (clamped).
 * T keeps that below MRGI_TONE_SHOULDER and rolls the rest off smoothly
 * towards 1 instead of clipping:
 *
 *     T(x) = 0                                      x <= 0 or NaN
 *     T(x) = x                                      0 < x <= k
 *     T(x) = k + (1 - k) (1 - exp(-(x - k) / (1 - k)))   x > k,  k = MRGI_TONE_SHOULDER
 *
 * T is continuous with a continuous slope (1 at k), increasing, below 1
 * for every finite x, and T(0.18) = 0.18: mid-grey keeps the display value
 * the plain output gives it, so tone mapping never darkens a scene
 * (VTK's vtkToneMappingPass maps 0.18 to a darker value: its filmic curve
 * assumes an encode step that VTK 9.1 does not do).
 *
 * ## Automatic exposure (Reinhard et al. 2002, "Photographic Tone
 * Reproduction for Digital Images", eq. 1 and 2)
 *
 *     Lw  = exp( (1/N) sum log(delta + L(x, y)) )   over the N foreground pixels
 *     Lh  = the MRGI_EXPOSURE_HIGHLIGHT_FRACTION quantile of L over the same pixels
 *     EV  = min( log2(key / Lw), log2(1 / Lh) )     clamped to [MRGI_EXPOSURE_MIN_EV,
 * MRGI_EXPOSURE_MAX_EV]
 *
 * L = MRGI_LUMINANCE_R r + MRGI_LUMINANCE_G g + MRGI_LUMINANCE_B b
 * (mrgi_vpl.h); delta = MRGI_EXPOSURE_DELTA keeps black pixels finite.
 * Background pixels (window depth >= 1, nothing drawn there) and pixels
 * whose luminance is not finite or negative do not count: a small object
 * on a black background is exposed for the object. With no foreground
 * pixel, EV = 0.
 *
 * The second term is ours, not Reinhard's: scenes lit only by MRGI's
 * lights have large areas in shadow (no ambient term), whose near-black
 * pixels pull Lw down by several stops (cornell-area: +5 EV from the key
 * alone, half of the image clipped). The cap keeps all but the brightest
 * (1 - MRGI_EXPOSURE_HIGHLIGHT_FRACTION) of the foreground at or below 1
 * before tone mapping. Lh is read from a histogram of log2 L with
 * MRGI_EXPOSURE_HISTOGRAM_BINS bins per stop over
 * [MRGI_EXPOSURE_HISTOGRAM_MIN_LOG2, MRGI_EXPOSURE_HISTOGRAM_MAX_LOG2)
 * (values outside go to the end bins) as the upper edge of the bin where
 * the cumulative count reaches the fraction: never below the true quantile.
 *
 * The GPU computes the transform in float in the order above; the
 * automatic EV is computed on the CPU by these functions (double sums) and
 * passed to the GPU as the scale.
 */
#ifndef MRGI_EXPOSURE_H
#define MRGI_EXPOSURE_H

#include "mrgi_error.h"

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Display value where the tone curve starts to roll off (identity below). */
#define MRGI_TONE_SHOULDER 0.5
/** Reinhard's key: the display value the log-average luminance is mapped to. */
#define MRGI_EXPOSURE_KEY 0.18
/** Reinhard's delta: luminance added before the log (black pixels stay finite). */
#define MRGI_EXPOSURE_DELTA 1e-4
/** Fraction of the foreground kept at or below 1 by the automatic exposure. */
#define MRGI_EXPOSURE_HIGHLIGHT_FRACTION 0.97
/** Histogram of log2 luminance: bins per stop and range, in stops. */
#define MRGI_EXPOSURE_HISTOGRAM_BINS 8
#define MRGI_EXPOSURE_HISTOGRAM_MIN_LOG2 -24
#define MRGI_EXPOSURE_HISTOGRAM_MAX_LOG2 8
/** Range of exposure values accepted and produced, in stops. */
#define MRGI_EXPOSURE_MIN_EV -20.0
#define MRGI_EXPOSURE_MAX_EV 20.0

/** @brief The tone curve T of the file comment: [0, 1) for every input, NaN -> 0. */
float mrgi_tone_curve(float x);

/** @brief 2^ev as float; ev is clamped to [MRGI_EXPOSURE_MIN_EV, MRGI_EXPOSURE_MAX_EV], NaN -> 1.
 */
float mrgi_exposure_scale(double ev);

/**
 * @brief The output transform of one pixel: rgb_out = T?(scale * rgb_in).
 * @param rgb_in    Three linear HDR values.
 * @param scale     mrgi_exposure_scale(EV).
 * @param tone_map  Non-zero: apply mrgi_tone_curve; zero: only the scale.
 * @param rgb_out   Three values (may alias rgb_in).
 */
void mrgi_exposure_apply(const float rgb_in[3], float scale, int tone_map, float rgb_out[3]);

/**
 * @brief Log-average luminance of the foreground (Reinhard eq. 1).
 * @param rgb        `count` pixels, `stride` floats apart (>= 3), RGB first.
 * @param stride     Floats per pixel, 3..64.
 * @param depth      `count` window depths, or NULL (every pixel is foreground).
 *                   A pixel with depth >= 1 (or NaN) is background.
 * @param count      Number of pixels, >= 0.
 * @param log_average Receives Lw; 0 when no pixel counts.
 * @param used       Receives how many pixels counted (may be NULL).
 * @return ::MRGI_ERR_INVALID_ARGUMENT for NULL rgb (with count > 0) or
 *         log_average, a stride out of range or a negative count.
 */
mrgi_status mrgi_exposure_log_average(const float* rgb, int32_t stride, const float* depth,
  int64_t count, double* log_average, int64_t* used, mrgi_error* err);

/**
 * @brief Luminance quantile of the foreground from the histogram of the
 *        file comment (same pixel rules as mrgi_exposure_log_average).
 * @param fraction  In (0, 1].
 * @param quantile  Receives Lh: the upper edge of the bin where the
 *                  cumulative count reaches fraction x N; 0 when no pixel counts.
 * @return ::MRGI_ERR_INVALID_ARGUMENT as mrgi_exposure_log_average, or a
 *         fraction outside (0, 1].
 */
mrgi_status mrgi_exposure_quantile(const float* rgb, int32_t stride, const float* depth,
  int64_t count, double fraction, double* quantile, mrgi_error* err);

/**
 * @brief The automatic EV of the file comment: min(log2(key / log_average),
 *        log2(1 / highlight)), clamped to the EV range. A term whose
 *        input is not a finite number > 0 is left out; 0 when both are.
 */
double mrgi_exposure_auto_ev(double log_average, double highlight, double key);

#ifdef __cplusplus
}
#endif

#endif
