/* The frame-budget tuner's interaction controller: load and shape factors,
 * hysteresis, retargeting (contract in mrgi_frame_budget.h, "Control during
 * interaction"). The cost model, the error proxy and the choice are in
 * mrgi_frame_budget.c. */
#include "mrgi_frame_budget.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The calibration as the controller sees it: the setting-dependent terms
 * (gather, RSM, voxels) scaled by `shape`, and the presets' work shares: as
 * measured, or for a preset not run yet the table's times what the last
 * measured preset had over its table value (the view moves every preset's
 * share the same way, roughly). */
static mrgi_frame_budget_calibration shaped(const mrgi_frame_budget_controller* ctl,
  const mrgi_frame_budget_calibration* cal, int64_t pixels, double shape)
{
  mrgi_frame_budget_calibration c = *cal;
  for (int i = 2; i < MRGI_FRAME_BUDGET_TERMS; ++i)
  {
    c.coef[i] *= shape;
  }
  for (int p = 0; p < MRGI_MULTIRES_PRESET_COUNT; ++p)
  {
    if (ctl->work[p] > 0.0)
    {
      c.work_share[p] = ctl->work[p];
    }
    else if (ctl->work_ratio > 0.0 && !(cal->work_share[p] > 0.0))
    {
      c.work_share[p] = ctl->work_ratio * mrgi_frame_budget_work_fraction_at(p, pixels);
    }
  }
  return c;
}

/* The model's prediction split into the part every setting pays (c0, c1)
 * and the part that depends on the setting (c2..c4). */
static void predict_parts(const mrgi_frame_budget_calibration* cal, const mrgi_frame_setting* s,
  int64_t pixels, double* fixed, double* variable)
{
  double t[MRGI_FRAME_BUDGET_TERMS] = { 0.0 };
  mrgi_frame_budget_terms_at(s, pixels, cal->work_share[s->preset], t, NULL);
  *fixed = cal->coef[0] * t[0] + cal->coef[1] * t[1];
  *variable = cal->coef[2] * t[2] + cal->coef[3] * t[3] + cal->coef[4] * t[4];
}

/* After a switch from A (smoothed time y_a) to B (y_b), with the load the
 * same on both sides: y_a / (f_a + k v_a) = y_b / (f_b + k v_b), solved for
 * the shape k. Frame noise of a few percent moves k by that over the
 * contrast of the two settings, so only a pair whose variable/fixed ratios
 * differ by MRGI_FRAME_BUDGET_SHAPE_CONTRAST or more counts, and the shape
 * moves only part of the way (MRGI_FRAME_BUDGET_SHAPE_RATE, in log) towards
 * the solution, within [1/MRGI_FRAME_BUDGET_SHAPE_LIMIT,
 * MRGI_FRAME_BUDGET_SHAPE_LIMIT]. */
static void learn_shape(mrgi_frame_budget_controller* ctl, const mrgi_frame_budget_calibration* cal,
  const mrgi_frame_setting* a, const mrgi_frame_setting* b, int64_t pixels, double y_a, double y_b)
{
  /* The parts under the measured work shares, without the shape. */
  const mrgi_frame_budget_calibration base = shaped(ctl, cal, pixels, 1.0);
  cal = &base;
  double fa, va, fb, vb;
  predict_parts(cal, a, pixels, &fa, &va);
  predict_parts(cal, b, pixels, &fb, &vb);
  if (!(fa > 0.0 && fb > 0.0 && va > 0.0 && vb > 0.0) ||
    fabs(log((vb / fb) / (va / fa))) < log(MRGI_FRAME_BUDGET_SHAPE_CONTRAST))
  {
    return;
  }
  const double k = (y_b * fa - y_a * fb) / (y_a * vb - y_b * va);
  if (!(isfinite(k) && k > 0.0))
  {
    return;
  }
  const double limit = log(MRGI_FRAME_BUDGET_SHAPE_LIMIT);
  const double target = fmin(fmax(log(k), -limit), limit);
  ctl->shape = exp(log(ctl->shape) + MRGI_FRAME_BUDGET_SHAPE_RATE * (target - log(ctl->shape)));
}

/* The controller aims at the lower half of its band: a setting chosen right
 * at the budget would leave the load estimate's own noise no room before the
 * band's upper edge, and alternate with its cheaper neighbour. */
static double controller_target(double budget_ms, double margin)
{
  return budget_ms / (1.0 + 0.5 * margin);
}

/* Median of the last three frames' log(measured / predicted) (fewer at the start). */
static double recent_level(const mrgi_frame_budget_controller* ctl)
{
  if (ctl->frames <= 1)
  {
    return ctl->recent[0];
  }
  if (ctl->frames == 2)
  {
    return 0.5 * (ctl->recent[0] + ctl->recent[1]);
  }
  const double a = ctl->recent[0], b = ctl->recent[1], c = ctl->recent[2];
  return fmax(fmin(a, b), fmin(fmax(a, b), c));
}

/* Move to candidate `index` (!= current): the reversal rule's bookkeeping and
 * the left setting's level for learn_shape(). `predicted` is the current
 * setting's modelled time, `level` its recent_level(). */
static void controller_switch(mrgi_frame_budget_controller* ctl, const mrgi_frame_budget_calibration* model,
  const mrgi_frame_setting* candidates, int64_t pixels, int32_t index, double predicted, double level)
{
  const double next = mrgi_frame_budget_predict(model, &candidates[index], pixels);
  const int32_t direction = next < predicted ? 1 : -1;
  ctl->last_reversed = ctl->last_direction != 0 && direction != ctl->last_direction &&
    ctl->frames - ctl->last_switch_frame < MRGI_FRAME_BUDGET_REVERSAL_WINDOW;
  ctl->last_direction = direction;
  /* The left setting's level: the median of its last three frames (not
   * the average, which lags), and only when those agree (no load change
   * under way, which would be taken for a shape). */
  const double a = ctl->recent[0], b = ctl->recent[1], c = ctl->recent[2];
  const double spread = fmax(a, fmax(b, c)) - fmin(a, fmin(b, c));
  ctl->previous = ctl->frames >= 3 && spread < log(MRGI_FRAME_BUDGET_SHAPE_STEADY) ? ctl->current : -1;
  ctl->previous_ms = predicted * exp(level);
  ctl->after = 0;
  ctl->after_log = 0.0;
  ctl->last_switch_frame = ctl->frames;
  ctl->current = index;
  ctl->skip = 1;
  ctl->switches++;
}

/* 1 when a running controller can be asked about its current candidate. */
static int is_running(const mrgi_frame_budget_controller* ctl,
  const mrgi_frame_budget_calibration* cal, const mrgi_frame_setting* candidates, int32_t count)
{
  return ctl && cal && candidates && ctl->current >= 0 && ctl->current < count;
}

/* The arguments update and retarget share; clears `*changed` (may be NULL). */
static mrgi_status check_running(const mrgi_frame_budget_controller* ctl,
  const mrgi_frame_budget_calibration* cal, const mrgi_frame_setting* candidates, int32_t count,
  int* changed, mrgi_error* err)
{
  if (changed)
  {
    *changed = 0;
  }
  if (!is_running(ctl, cal, candidates, count))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "frame budget controller: NULL argument or current candidate outside the list");
  }
  return MRGI_OK;
}

mrgi_status mrgi_frame_budget_controller_init(mrgi_frame_budget_controller* ctl,
  const mrgi_frame_budget_calibration* cal, const mrgi_frame_setting* candidates, int32_t count,
  int64_t pixels, double budget_ms, double margin, int32_t patience, mrgi_error* err)
{
  if (!ctl)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "frame budget controller: NULL");
  }
  if (!(isfinite(margin) && margin > 0.0) || patience < 1)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "frame budget controller: margin %g must be finite and > 0, patience %d >= 1", margin,
      (int)patience);
  }
  int32_t index = 0;
  const mrgi_status st = mrgi_frame_budget_choose(
    cal, candidates, count, pixels, controller_target(budget_ms, margin), 1.0, &index, NULL, err);
  if (st != MRGI_OK)
  {
    return st;
  }
  memset(ctl, 0, sizeof(*ctl));
  ctl->budget_ms = budget_ms;
  ctl->margin = margin;
  ctl->patience = patience;
  ctl->load = 1.0;
  ctl->skip = 1; /* the first frame compiles and allocates */
  ctl->shape = 1.0;
  ctl->previous = -1;
  ctl->current = index;
  return MRGI_OK;
}

mrgi_status mrgi_frame_budget_controller_update(mrgi_frame_budget_controller* ctl,
  const mrgi_frame_budget_calibration* cal, const mrgi_frame_setting* candidates, int32_t count,
  int64_t pixels, double measured_ms, double work_share, int* changed, mrgi_error* err)
{
  const mrgi_status checked = check_running(ctl, cal, candidates, count, changed, err);
  if (checked != MRGI_OK)
  {
    return checked;
  }
  if (!(isfinite(measured_ms) && measured_ms > 0.0))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "frame budget controller: measured time %g ms must be finite and > 0", measured_ms);
  }
  /* The share of pixels the current preset gathered (the view and the
   * window decide it; the table's is one view at 1024 x 1024): even the
   * first frame of a setting tells it. */
  const int32_t preset = candidates[ctl->current].preset;
  if (isfinite(work_share) && work_share > 0.0 && preset >= 0 &&
    preset < MRGI_MULTIRES_PRESET_COUNT)
  {
    const double w = fmin(work_share, MRGI_FRAME_BUDGET_MAX_WORK);
    double* known = &ctl->work[preset];
    *known = *known > 0.0 ? *known + MRGI_FRAME_BUDGET_WORK_WEIGHT * (w - *known) : w;
    const double table = mrgi_frame_budget_work_fraction_at(preset, pixels);
    ctl->work_ratio = table > 0.0 ? *known / table : 0.0;
  }
  if (ctl->skip > 0)
  {
    /* The first frame of a new setting pays for its shaders and buffers. */
    ctl->skip--;
    return MRGI_OK;
  }
  if (ctl->previous >= 0 && ctl->previous < count)
  {
    /* The frames just after a switch tell the model's shape. */
    ctl->after_log += log(measured_ms);
    if (++ctl->after == MRGI_FRAME_BUDGET_SHAPE_FRAMES)
    {
      const double y_b = exp(ctl->after_log / ctl->after);
      learn_shape(ctl, cal, &candidates[ctl->previous], &candidates[ctl->current], pixels,
        ctl->previous_ms, y_b);
      ctl->previous = -1;
      /* The load restarts from this setting's frames, under the new shape. */
      const mrgi_frame_budget_calibration m = shaped(ctl, cal, pixels, ctl->shape);
      const double level = log(y_b / mrgi_frame_budget_predict(&m, &candidates[ctl->current], pixels));
      ctl->average = level;
      ctl->recent[0] = ctl->recent[1] = ctl->recent[2] = level;
      ctl->streak = 0;
    }
  }
  const mrgi_frame_budget_calibration model = shaped(ctl, cal, pixels, ctl->shape);
  const double predicted = mrgi_frame_budget_predict(&model, &candidates[ctl->current], pixels);
  if (!(predicted > 0.0))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "frame budget controller: candidate %d has no positive predicted time", (int)ctl->current);
  }
  /* The load estimate follows every frame, through the median of the last
   * three frames' log(measured / predicted), so that a lone spike does not
   * move it. */
  ctl->recent[ctl->frames % 3] = log(measured_ms / predicted);
  ctl->frames++;
  const double ratio = recent_level(ctl);
  /* The first measured frame replaces the calibration's load of 1. */
  ctl->average += (ctl->frames == 1 ? 1.0 : MRGI_FRAME_BUDGET_AVERAGE_WEIGHT) * (ratio - ctl->average);
  ctl->load = exp(ctl->average);
  /* Hysteresis: only an expected time outside the band, frames in a row. */
  const double deviation = log(ctl->load * predicted / ctl->budget_ms);
  const double bound = log1p(ctl->margin);
  const int dir = deviation > bound ? 1 : deviation < -bound ? -1 : 0;
  if (dir == 0 || (ctl->streak > 0) != (dir > 0))
  {
    ctl->streak = 0;
  }
  ctl->streak += dir;
  /* Over budget means going cheaper (+1), under means going dearer (-1).
   * One reversal corrects an overshoot; a second one in a row, soon after,
   * would start an alternation, and waits longer. */
  const int reverses = ctl->last_reversed && ctl->last_direction != 0 && dir != 0 &&
    dir != ctl->last_direction &&
    ctl->frames - ctl->last_switch_frame < MRGI_FRAME_BUDGET_REVERSAL_WINDOW;
  const int32_t wait = ctl->patience * (reverses ? MRGI_FRAME_BUDGET_REVERSAL_FACTOR : 1);
  if (dir == 0 || abs(ctl->streak) < wait)
  {
    return MRGI_OK;
  }
  ctl->streak = 0;
  /* Going cheaper aims at the band's lower half; going dearer at its lower
   * edge: a load estimate a few percent low (noise) must not make a setting
   * that only just fits look cheap enough, or the next high estimate sends
   * it back (an alternation at constant load). */
  const double aim =
    dir > 0 ? controller_target(ctl->budget_ms, ctl->margin) : ctl->budget_ms / (1.0 + ctl->margin);
  int32_t index = ctl->current;
  const mrgi_status st =
    mrgi_frame_budget_choose(&model, candidates, count, pixels, aim, ctl->load, &index, NULL, err);
  if (st != MRGI_OK)
  {
    return st;
  }
  if (index != ctl->current)
  {
    controller_switch(ctl, &model, candidates, pixels, index, predicted, ratio);
    if (changed)
    {
      *changed = 1;
    }
  }
  return MRGI_OK;
}

mrgi_status mrgi_frame_budget_controller_retarget(mrgi_frame_budget_controller* ctl,
  const mrgi_frame_budget_calibration* cal, const mrgi_frame_setting* candidates, int32_t count,
  int64_t pixels, double budget_ms, int* changed, mrgi_error* err)
{
  const mrgi_status checked = check_running(ctl, cal, candidates, count, changed, err);
  if (checked != MRGI_OK)
  {
    return checked;
  }
  const mrgi_frame_budget_calibration model = shaped(ctl, cal, pixels, ctl->shape);
  int32_t index = ctl->current;
  const mrgi_status st = mrgi_frame_budget_choose(&model, candidates, count, pixels,
    controller_target(budget_ms, ctl->margin), ctl->load, &index, NULL, err);
  if (st != MRGI_OK)
  {
    return st; /* names a bad budget; the controller is unchanged */
  }
  ctl->budget_ms = budget_ms;
  ctl->streak = 0; /* it counted misses of the old target */
  if (index != ctl->current)
  {
    const double predicted = mrgi_frame_budget_predict(&model, &candidates[ctl->current], pixels);
    controller_switch(ctl, &model, candidates, pixels, index, predicted, recent_level(ctl));
    if (changed)
    {
      *changed = 1;
    }
  }
  /* A new target is not a reversal of the last switch, nor this one of it. */
  ctl->last_direction = 0;
  ctl->last_reversed = 0;
  return MRGI_OK;
}

double mrgi_frame_budget_controller_expected(const mrgi_frame_budget_controller* ctl,
  const mrgi_frame_budget_calibration* cal, const mrgi_frame_setting* candidates, int32_t count,
  int64_t pixels)
{
  if (!is_running(ctl, cal, candidates, count))
  {
    return -1.0;
  }
  const mrgi_frame_budget_calibration model = shaped(ctl, cal, pixels, ctl->shape);
  const double ms = mrgi_frame_budget_predict(&model, &candidates[ctl->current], pixels);
  return ms > 0.0 ? ctl->load * ms : -1.0;
}
