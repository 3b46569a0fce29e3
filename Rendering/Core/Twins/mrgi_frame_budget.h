/**
 * @file mrgi_frame_budget.h
 * @brief The frame-budget tuner (issue 17 part 4): a cost model fitted from
 *        timed frames, an error model per setting, the choice of the setting
 *        that meets a time (or error) budget, and a controller with
 *        hysteresis for interaction. No VTK, no GL, no file I/O, no global
 *        state, no allocation.
 *
 * **Settings.** A ::mrgi_frame_setting is what the tuner may change: the
 * multiresolution preset (mrgi_multires.h: thresholds and finest level
 * together, the measured frontier of Documentation/Multiresolution.md), the
 * VPL count, the RSM side and the voxel side (0 when the frame uses no
 * voxels; the tuner never turns visibility on or off).
 *
 * **Cost model** (milliseconds per frame, linear in five terms, each a
 * product of the setting and the frame's pixel count P):
 *
 *   ms = c0 + c1 * P/1e6 + c2 * G/1e9 + c3 * R/1e6 + c4 * V/1e9
 *
 * with G = P * w(preset) * VPLs the texel-VPL pairs the gather evaluates
 * (w: the share of pixels a preset gathers at some level, measured by the
 * gather's occlusion queries where known, else a table by window size,
 * mrgi_frame_budget_work_fraction_at(): nichols-shopf-wyman-2009 table 1 shows that the
 * selection's cost is fixed per pixel and the gather's follows the texels
 * selected), R = rsm_size^2 the RSM texels (RSM rendering plus VPL selection),
 * and V = G * voxel_side / 128 the voxel march steps of the visibility term
 * (0 without voxels; a march crosses about voxel_side voxels). The
 * coefficients are fitted by least squares (non-negative) from timed frames:
 * mrgi_frame_budget_fit(). The defaults (mrgi_frame_budget_default()) were
 * measured once on Mesa llvmpipe, 2 cores; they are a starting point, not a
 * calibration.
 *
 * **Error model** (a documented analytic proxy, mrgi_frame_budget_error()):
 * the predicted relative RMS error of the indirect light against the dense
 * reference (a full-resolution gather with many VPLs and a large RSM),
 * combined in quadrature from three independent sources:
 *  - the multiresolution error of the preset against the full gather with the
 *    same VPLs (Documentation/Multiresolution.md, cornell-spot, 256 VPLs:
 *    fast 0.043, balanced 0.016, accurate 0.010);
 *  - the VPL sampling error k_v / sqrt(VPLs) (the grid's stratified estimate);
 *  - the RSM resolution error k_r * 256 / rsm_size and, with voxels, the
 *    voxel error k_x * 128 / voxel_side.
 * The constants are MRGI_FRAME_BUDGET_ERROR_*; Testing/Benchmarks/
 * frame_budget.py measures the real error of every candidate against the
 * dense reference, so the proxy is checked, not trusted.
 *
 * **Control during interaction** (mrgi_frame_budget_controller_update()):
 * the controller estimates the load factor s = measured / predicted of the
 * frames it sees: an exponential average (weight
 * MRGI_FRAME_BUDGET_AVERAGE_WEIGHT) of the median of the last three frames'
 * log(measured / predicted), so that a lone spike does not move it. s follows
 * the view: what a frame costs depends on what it shows (Documentation/
 * FrameBudget.md measures one setting along an orbit), so the model's
 * prediction is corrected every frame, not only on a switch.
 * Hysteresis: the setting is chosen again only when the current one's
 * expected time s x predicted stays outside [budget / (1 + margin),
 * budget x (1 + margin)] (default margin 5%: with +-5% frame noise, frames
 * stay within 10%) for `patience` frames in a row (default 3). It then takes
 * the setting of least predicted error whose expected time is within
 * budget / (1 + margin / 2), the band's lower half, so that the load
 * estimate's own noise does not carry it over the upper edge; going to a
 * dearer setting, within budget / (1 + margin), the band's lower edge, so
 * that a load estimate a few percent low does not pick a setting that only
 * just fits, which the next high estimate sends back (when the
 * grid's next dearer setting does not fit, it may stay below the band: it
 * chooses again, and holds). A reversal (cheaper after dearer, or back)
 * corrects an overshoot; a second reversal in a row within
 * MRGI_FRAME_BUDGET_REVERSAL_WINDOW frames of the last switch waits
 * MRGI_FRAME_BUDGET_REVERSAL_FACTOR x patience frames, so that two settings
 * the model misjudges do not alternate. The first frame of a new setting
 * (shaders, buffers) is not measured.
 * A load factor cannot correct a model whose setting-dependent part is off
 * (the work share of a preset changes with the window size and the view;
 * with the gather underestimated, a cheap setting runs faster than the
 * load measured on a dear one predicts). So the controller also learns a
 * shape factor k that scales the gather, RSM and voxel terms (c2..c4): a
 * switch compares the
 * left setting's last three frames (their median, when they agree within
 * MRGI_FRAME_BUDGET_SHAPE_STEADY) with the new one's first
 * MRGI_FRAME_BUDGET_SHAPE_FRAMES measured frames, assumes the load did not
 * change in between, and solves for k (mrgi_frame_budget_controller.c,
 * learn_shape). The work share itself is measured: each update takes the
 * share of pixels the frame's gather worked on (its occlusion queries),
 * averaged per preset (MRGI_FRAME_BUDGET_WORK_WEIGHT); a preset not run yet
 * gets the table's share times the last measured preset's ratio to its
 * table value.
 *
 * **Calibration file** (mrgi_frame_budget_format(), _parse()): text, one key
 * and value per line, in this order:
 *   mrgi-frame-budget 1
 *   renderer <the GL renderer string, to the end of the line>
 *   frames <frames fitted>
 *   fixed_ms <c0>   pixel_ms <c1>   gather_ms <c2>   rsm_ms <c3>   voxel_ms <c4>
 *   end
 * Anything else (a missing or unknown key, a negative, non-finite or
 * unparsable number, no `end`) is refused with a message that names it.
 */
#ifndef MRGI_FRAME_BUDGET_H
#define MRGI_FRAME_BUDGET_H

#include "mrgi_error.h"
#include "mrgi_multires.h"

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Number of terms of the cost model. */
#define MRGI_FRAME_BUDGET_TERMS 5
/** Size of ::mrgi_frame_budget_calibration::renderer, NUL included. */
#define MRGI_FRAME_BUDGET_RENDERER_SIZE 128
/** Most candidates mrgi_frame_budget_default_candidates() writes. */
#define MRGI_FRAME_BUDGET_MAX_CANDIDATES 1024
/** Size a buffer for mrgi_frame_budget_format() needs at most. */
#define MRGI_FRAME_BUDGET_TEXT_SIZE 512
/** When no setting fits, those within this factor of the cheapest's time are as cheap. */
#define MRGI_FRAME_BUDGET_NEAR_CHEAPEST 1.05
/** Default hysteresis margin (relative) and patience (frames). */
#define MRGI_FRAME_BUDGET_DEFAULT_MARGIN 0.05
#define MRGI_FRAME_BUDGET_DEFAULT_PATIENCE 3
/** Weight of a new frame in the controller's load estimate. */
#define MRGI_FRAME_BUDGET_AVERAGE_WEIGHT 0.3
/** A switch that reverses the previous one, made less than
 *  MRGI_FRAME_BUDGET_REVERSAL_WINDOW measured frames ago, waits this times patience. */
#define MRGI_FRAME_BUDGET_REVERSAL_FACTOR 3
#define MRGI_FRAME_BUDGET_REVERSAL_WINDOW 30
/** Frames of a new setting whose mean time teaches the shape factor. */
#define MRGI_FRAME_BUDGET_SHAPE_FRAMES 3
/** Least ratio of two settings' variable/fixed cost ratios that teaches the shape. */
#define MRGI_FRAME_BUDGET_SHAPE_CONTRAST 1.5
/** The left setting's last three frames must agree within this ratio to teach the shape. */
#define MRGI_FRAME_BUDGET_SHAPE_STEADY 1.1
/** Share of the way (in log) the shape moves towards one switch's solution. */
#define MRGI_FRAME_BUDGET_SHAPE_RATE 0.3
/** The shape factor stays within [1 / limit, limit]. */
#define MRGI_FRAME_BUDGET_SHAPE_LIMIT 4.0

/** Largest share of gathered texels over valid pixels the model takes (all
 *  levels gathering every pixel would be 4/3; anything above is a bad count). */
#define MRGI_FRAME_BUDGET_MAX_WORK 2.0
/** Weight of a new frame's measured work share in the controller's estimate. */
#define MRGI_FRAME_BUDGET_WORK_WEIGHT 0.5

/** Error proxy constants (see the file comment). */
#define MRGI_FRAME_BUDGET_ERROR_VPL 1.6
#define MRGI_FRAME_BUDGET_ERROR_RSM 0.01
#define MRGI_FRAME_BUDGET_ERROR_VOXEL 0.02

/** What the tuner may change. */
typedef struct mrgi_frame_setting
{
  int32_t preset;     /**< mrgi_multires_preset, 0..MRGI_MULTIRES_PRESET_COUNT-1. */
  int32_t vpls;       /**< VPL count, 1..4096. */
  int32_t rsm_size;   /**< RSM texels per side, 16..2048. */
  int32_t voxel_side; /**< Voxel buffer side, 0 (no voxels) or 1..4096. */
} mrgi_frame_setting;

/** Fitted cost model: ms per unit of each term (see the file comment). */
typedef struct mrgi_frame_budget_calibration
{
  double coef[MRGI_FRAME_BUDGET_TERMS];           /**< c0..c4, >= 0, finite. */
  /** Measured share of pixels each preset gathers where the model is used
   *  (window size, view), or 0 for mrgi_frame_budget_work_fraction()'s
   *  table. Not part of the calibration file: the controller measures it
   *  (see "Control during interaction"). */
  double work_share[MRGI_MULTIRES_PRESET_COUNT];
  int32_t frames;                                 /**< Frames fitted; 0 for the defaults. */
  char renderer[MRGI_FRAME_BUDGET_RENDERER_SIZE]; /**< GL renderer the fit holds for. */
} mrgi_frame_budget_calibration;

/** @brief The llvmpipe defaults (frames = 0, renderer empty). NULL is a no-op. */
void mrgi_frame_budget_default(mrgi_frame_budget_calibration* cal);

/** @brief Share of pixels a preset gathers at 1024 x 1024 (cornell-spot); 0 for an unknown preset.
 */
double mrgi_frame_budget_work_fraction(int32_t preset);

/**
 * @brief Share of pixels a preset gathers at a window of `pixels` pixels:
 *        cornell-spot's at 256^2, 512^2 and 1024^2, interpolated in log-log
 *        and constant beyond (coarse levels and edges are a larger part of a
 *        small image: fast gathers 10% at 256^2, 3.3% at 1024^2). 0 for an
 *        unknown preset or pixels < 1.
 */
double mrgi_frame_budget_work_fraction_at(int32_t preset, int64_t pixels);

/** @brief ::MRGI_ERR_INVALID_ARGUMENT naming the first out-of-range field. */
mrgi_status mrgi_frame_budget_check_setting(const mrgi_frame_setting* s, mrgi_error* err);

/**
 * @brief The five terms of the cost model for `s` at `pixels` pixels, with
 *        the preset's share of gathered pixels from the table
 *        (mrgi_frame_budget_work_fraction()).
 * @return ::MRGI_ERR_INVALID_ARGUMENT for a bad setting, pixels < 1 or NULL.
 */
mrgi_status mrgi_frame_budget_terms(
  const mrgi_frame_setting* s, int64_t pixels, double terms[MRGI_FRAME_BUDGET_TERMS], mrgi_error* err);

/**
 * @brief The same with a measured share of gathered pixels (the pass's
 *        gathered texels over valid pixels, clamped to MRGI_FRAME_BUDGET_MAX_WORK);
 *        a share not finite or <= 0 means the table's.
 */
mrgi_status mrgi_frame_budget_terms_at(const mrgi_frame_setting* s, int64_t pixels,
  double work_share, double terms[MRGI_FRAME_BUDGET_TERMS], mrgi_error* err);

/** @brief Predicted ms of `s` at `pixels` (with cal->work_share where set);
 *         a negative value for bad input. */
double mrgi_frame_budget_predict(
  const mrgi_frame_budget_calibration* cal, const mrgi_frame_setting* s, int64_t pixels);

/** @brief Predicted relative RMS error of `s` (the proxy); negative for a bad setting. */
double mrgi_frame_budget_error(const mrgi_frame_setting* s);

/**
 * @brief Least-squares fit of the coefficients from `count` timed frames:
 *        `terms` holds count rows of MRGI_FRAME_BUDGET_TERMS values
 *        (mrgi_frame_budget_terms()), `ms` the measured times.
 *
 * Non-negative: a coefficient the unconstrained fit makes negative is fixed
 * at 0 and the others are fitted again. A term that is zero in every frame
 * (e.g. no voxels) keeps the coefficient `cal` had on entry (the prior); so
 * does a term other than the fixed one with the same value in every frame
 * (all frames at one window size: the pixel term cannot be told from the
 * fixed cost, which then absorbs the difference at that size).
 * `cal->frames` becomes `count`; the renderer string is kept.
 * @return ::MRGI_ERR_INVALID_ARGUMENT for NULL, count < 1, non-finite or
 *         negative values, or fewer distinct frames than observed terms
 *         (`cal` untouched on failure).
 */
mrgi_status mrgi_frame_budget_fit(const double* terms, const double* ms, int32_t count,
  mrgi_frame_budget_calibration* cal, mrgi_error* err);

/**
 * @brief The default candidate grid: every preset x square VPL counts 16..4096
 *        x RSM sides 128, 256, 512; x voxel sides 64, 128, 256 when `voxels`
 *        (else voxel_side 0). Writes at most `capacity`.
 * @return The number written (the full grid needs at most
 *         MRGI_FRAME_BUDGET_MAX_CANDIDATES).
 */
int32_t mrgi_frame_budget_default_candidates(
  int voxels, mrgi_frame_setting* out, int32_t capacity);

/**
 * @brief The setting of least predicted error whose predicted time,
 *        multiplied by `load` (1 = as calibrated), is within `budget_ms`;
 *        ties go to the cheaper. When none fits, the least predicted error
 *        among those within MRGI_FRAME_BUDGET_NEAR_CHEAPEST x the cheapest's
 *        time, and `*within` = 0.
 * @param within May be NULL.
 * @return ::MRGI_ERR_INVALID_ARGUMENT for NULL, count < 1, pixels < 1,
 *         budget or load not finite and > 0, or a bad candidate (named by index).
 */
mrgi_status mrgi_frame_budget_choose(const mrgi_frame_budget_calibration* cal,
  const mrgi_frame_setting* candidates, int32_t count, int64_t pixels, double budget_ms,
  double load, int32_t* index, int* within, mrgi_error* err);

/**
 * @brief The cheapest predicted setting whose predicted error is at most
 *        `max_error`; when none is, the one of least error, and `*within` = 0.
 * @return As mrgi_frame_budget_choose() (max_error finite and > 0).
 */
mrgi_status mrgi_frame_budget_choose_for_error(const mrgi_frame_budget_calibration* cal,
  const mrgi_frame_setting* candidates, int32_t count, int64_t pixels, double max_error,
  int32_t* index, int* within, mrgi_error* err);

/** The interaction controller (hysteresis; see the file comment). Plain data. */
typedef struct mrgi_frame_budget_controller
{
  double budget_ms;  /**< Target frame time. */
  double margin;     /**< Relative miss that counts, > 0. */
  int32_t patience;  /**< Frames in a row outside the band that choose again, >= 1. */
  double load;       /**< Estimated measured / predicted, exp(average); 1 at start. */
  int32_t current;   /**< Index of the chosen candidate. */
  double average;    /**< Exponential average of log(measured / predicted). */
  int32_t streak;    /**< Frames the expected time was outside the band (signed: > 0 slower). */
  int32_t last_direction; /**< Last switch: +1 to a cheaper setting, -1 dearer, 0 none. */
  int32_t last_reversed;  /**< 1 when the last switch reversed the one before, soon after it. */
  int32_t skip;      /**< Frames still to leave out (the first of a new setting). */
  double recent[3];  /**< The last three frames' log(measured / predicted), a ring. */
  int64_t frames;    /**< Frames measured since init (position in the ring). */
  int64_t last_switch_frame; /**< ::frames at the last switch. */
  double shape;       /**< Measured / modelled setting-dependent cost (c2..c4), 1 at start. */
  int32_t previous;   /**< The setting before the last switch, until the shape is learnt; -1 none. */
  double previous_ms; /**< Its time when it was left (median of its last three frames). */
  int32_t after;      /**< Frames of the new setting measured since the switch. */
  double after_log;   /**< Sum of their log(measured ms). */
  int32_t switches;  /**< Times the choice changed since init. */
  double work[MRGI_MULTIRES_PRESET_COUNT]; /**< Measured work share per preset (0: not yet). */
  double work_ratio; /**< Last measured share over the table's for its preset (0: none yet). */
} mrgi_frame_budget_controller;

/**
 * @brief Start a controller: load 1, the choice of mrgi_frame_budget_choose()
 *        for budget / (1 + margin / 2).
 * @return As mrgi_frame_budget_choose(); margin must be finite and > 0,
 *         patience >= 1.
 */
mrgi_status mrgi_frame_budget_controller_init(mrgi_frame_budget_controller* ctl,
  const mrgi_frame_budget_calibration* cal, const mrgi_frame_setting* candidates, int32_t count,
  int64_t pixels, double budget_ms, double margin, int32_t patience, mrgi_error* err);

/**
 * @brief Take one measured frame of the current candidate: its time and the
 *        share of pixels its gather worked on (gathered texels over valid
 *        pixels, vtkMRGIGather::GetGatherWorkFraction(); not finite or <= 0
 *        when unknown: the table's, or what earlier frames measured, stays).
 *        May choose again. `*changed` (may be NULL) is 1 when ctl->current
 *        changed.
 * @return ::MRGI_ERR_INVALID_ARGUMENT for NULL, a measured time not finite
 *         and > 0, or the errors of mrgi_frame_budget_choose().
 */
mrgi_status mrgi_frame_budget_controller_update(mrgi_frame_budget_controller* ctl,
  const mrgi_frame_budget_calibration* cal, const mrgi_frame_setting* candidates, int32_t count,
  int64_t pixels, double measured_ms, double work_share, int* changed, mrgi_error* err);

/**
 * @brief A new budget for a running controller: choose again for
 *        budget / (1 + margin / 2) under the load and shape factor it has
 *        learnt, instead of starting over from the calibration's load of 1
 *        (mrgi_frame_budget_controller_init()). The hysteresis streak and
 *        the reversal rule restart; a switch is measured (shape) as one the
 *        controller made itself. `*changed` (may be NULL) is 1 when
 *        ctl->current changed.
 * @return As mrgi_frame_budget_choose() (e.g. a budget not finite and > 0);
 *         the controller is unchanged on failure.
 */
mrgi_status mrgi_frame_budget_controller_retarget(mrgi_frame_budget_controller* ctl,
  const mrgi_frame_budget_calibration* cal, const mrgi_frame_setting* candidates, int32_t count,
  int64_t pixels, double budget_ms, int* changed, mrgi_error* err);

/**
 * @brief The controller's expected time of its current setting: load x the
 *        prediction under its shape factor; a negative value for bad input.
 */
double mrgi_frame_budget_controller_expected(const mrgi_frame_budget_controller* ctl,
  const mrgi_frame_budget_calibration* cal, const mrgi_frame_setting* candidates, int32_t count,
  int64_t pixels);

/**
 * @brief Write the calibration as text (format in the file comment).
 * @return ::MRGI_ERR_INVALID_ARGUMENT for NULL, a bad coefficient or a
 *         buffer under MRGI_FRAME_BUDGET_TEXT_SIZE.
 */
mrgi_status mrgi_frame_budget_format(
  const mrgi_frame_budget_calibration* cal, char* text, size_t size, mrgi_error* err);

/**
 * @brief Read a calibration written by mrgi_frame_budget_format().
 * @return ::MRGI_ERR_FORMAT naming the line and problem for anything else
 *         (`cal` untouched); ::MRGI_ERR_INVALID_ARGUMENT for NULL.
 */
mrgi_status mrgi_frame_budget_parse(
  const char* text, mrgi_frame_budget_calibration* cal, mrgi_error* err);

#ifdef __cplusplus
}
#endif

#endif
