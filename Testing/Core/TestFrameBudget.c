/* Tests of mrgi_frame_budget: the fit recovers known coefficients from
 * synthetic (noisy) timings and keeps the prior of an unobserved term; the
 * choice respects the budget and minimises the predicted error; the error
 * budget takes the cheapest setting within it; the controller does not
 * switch on noisy constant timings and switches once on a real load change;
 * the controller takes the gather's measured work share; the calibration
 * text round-trips and corrupt files are refused by name. */
#include "mrgi_frame_budget.h"

#include "mrgi_multires.h"
#include "mrgi_test.h"

#include <math.h>
#include <stdint.h>
#include <string.h>

/* Deterministic noise in [-1, 1] (xorshift). */
static double noise(uint32_t* state)
{
  uint32_t x = *state;
  x ^= x << 13;
  x ^= x >> 17;
  x ^= x << 5;
  *state = x;
  return 2.0 * ((double)x / 4294967295.0) - 1.0;
}

static const double truth[MRGI_FRAME_BUDGET_TERMS] = { 7.0, 150.0, 4000.0, 25.0, 0.0 };

static double true_ms(const mrgi_frame_setting* s, int64_t pixels)
{
  mrgi_frame_budget_calibration c;
  mrgi_frame_budget_default(&c);
  memcpy(c.coef, truth, sizeof(truth));
  return mrgi_frame_budget_predict(&c, s, pixels);
}

static void test_fit_recovers(void)
{
  mrgi_frame_setting cand[MRGI_FRAME_BUDGET_MAX_CANDIDATES];
  const int32_t n = mrgi_frame_budget_default_candidates(0, cand, MRGI_FRAME_BUDGET_MAX_CANDIDATES);
  MRGI_CHECK(n > 20 && n <= MRGI_FRAME_BUDGET_MAX_CANDIDATES);
  enum { F = 24 };
  double terms[F * MRGI_FRAME_BUDGET_TERMS], ms[F];
  uint32_t rng = 12345u;
  for (int f = 0; f < F; ++f)
  {
    const mrgi_frame_setting* s = &cand[(f * 37) % n];
    const int64_t pixels = (f % 3 == 0) ? 65536 : (f % 3 == 1) ? 262144 : 16384;
    MRGI_CHECK(mrgi_frame_budget_terms(s, pixels, terms + f * MRGI_FRAME_BUDGET_TERMS, NULL) == MRGI_OK);
    ms[f] = true_ms(s, pixels) * (1.0 + 0.01 * noise(&rng));
  }
  mrgi_frame_budget_calibration cal;
  mrgi_frame_budget_default(&cal);
  const double prior_voxel = cal.coef[4];
  MRGI_CHECK(mrgi_frame_budget_fit(terms, ms, F, &cal, NULL) == MRGI_OK);
  MRGI_CHECK(cal.frames == F);
  for (int i = 0; i < 4; ++i)
  {
    MRGI_CHECK(fabs(cal.coef[i] - truth[i]) <= 0.05 * truth[i] + 0.5);
  }
  MRGI_CHECK(cal.coef[4] == prior_voxel); /* no voxels in any frame: prior kept */

  /* Exact timings: exact coefficients. */
  for (int f = 0; f < F; ++f)
  {
    double y = 0;
    for (int i = 0; i < MRGI_FRAME_BUDGET_TERMS; ++i)
    {
      y += truth[i] * terms[f * MRGI_FRAME_BUDGET_TERMS + i];
    }
    ms[f] = y;
  }
  MRGI_CHECK(mrgi_frame_budget_fit(terms, ms, F, &cal, NULL) == MRGI_OK);
  for (int i = 0; i < 4; ++i)
  {
    MRGI_CHECK_NEAR(cal.coef[i], truth[i], 1e-6 * truth[i]);
  }

  /* One window size: the pixel term keeps its prior, the fixed cost absorbs
   * the rest, and the predictions at that size are exact. */
  mrgi_frame_budget_calibration one;
  mrgi_frame_budget_default(&one);
  const double prior_pixel = one.coef[1];
  for (int f = 0; f < F; ++f)
  {
    const mrgi_frame_setting* s = &cand[(f * 37) % n];
    MRGI_CHECK(mrgi_frame_budget_terms(s, 65536, terms + f * MRGI_FRAME_BUDGET_TERMS, NULL) == MRGI_OK);
    ms[f] = true_ms(s, 65536);
  }
  MRGI_CHECK(mrgi_frame_budget_fit(terms, ms, F, &one, NULL) == MRGI_OK);
  MRGI_CHECK(one.coef[1] == prior_pixel);
  for (int f = 0; f < F; ++f)
  {
    MRGI_CHECK_NEAR(mrgi_frame_budget_predict(&one, &cand[(f * 37) % n], 65536), ms[f], 1e-6 * ms[f]);
  }

  /* A term that would come out negative is fixed at 0, never negative. */
  for (int f = 0; f < F; ++f)
  {
    ms[f] = 5.0 + 100.0 * terms[f * MRGI_FRAME_BUDGET_TERMS + 2] -
      2.0 * terms[f * MRGI_FRAME_BUDGET_TERMS + 3];
    ms[f] = ms[f] > 0 ? ms[f] : 0;
  }
  MRGI_CHECK(mrgi_frame_budget_fit(terms, ms, F, &cal, NULL) == MRGI_OK);
  for (int i = 0; i < MRGI_FRAME_BUDGET_TERMS; ++i)
  {
    MRGI_CHECK(cal.coef[i] >= 0.0);
  }

  /* Too few distinct frames, and bad values, are refused by name. */
  mrgi_error err;
  mrgi_frame_budget_calibration before = cal;
  MRGI_CHECK(mrgi_frame_budget_fit(terms, ms, 2, &cal, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "do not determine") != NULL);
  MRGI_CHECK(memcmp(&cal, &before, sizeof(cal)) == 0);
  ms[3] = NAN;
  MRGI_CHECK(mrgi_frame_budget_fit(terms, ms, F, &cal, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "frame 3") != NULL);
  MRGI_CHECK(mrgi_frame_budget_fit(terms, ms, 0, &cal, &err) == MRGI_ERR_INVALID_ARGUMENT);
}

static void test_choice_respects_budget(void)
{
  mrgi_frame_setting cand[MRGI_FRAME_BUDGET_MAX_CANDIDATES];
  const int32_t n = mrgi_frame_budget_default_candidates(0, cand, MRGI_FRAME_BUDGET_MAX_CANDIDATES);
  mrgi_frame_budget_calibration cal;
  mrgi_frame_budget_default(&cal);
  const int64_t pixels = 256 * 256;
  double lo = 1e30, hi = 0;
  for (int32_t i = 0; i < n; ++i)
  {
    const double ms = mrgi_frame_budget_predict(&cal, &cand[i], pixels);
    MRGI_CHECK(ms > 0);
    lo = ms < lo ? ms : lo;
    hi = ms > hi ? ms : hi;
  }
  double last_error = 1e30;
  for (int b = 0; b <= 20; ++b)
  {
    const double budget = lo + (hi - lo) * b / 20.0;
    int32_t index = -1;
    int within = 0;
    MRGI_CHECK(mrgi_frame_budget_choose(&cal, cand, n, pixels, budget, 1.0, &index, &within, NULL) == MRGI_OK);
    MRGI_CHECK(within);
    const double ms = mrgi_frame_budget_predict(&cal, &cand[index], pixels);
    const double e = mrgi_frame_budget_error(&cand[index]);
    MRGI_CHECK(ms <= budget);
    for (int32_t i = 0; i < n; ++i)
    {
      /* No candidate within the budget has a lower predicted error. */
      if (mrgi_frame_budget_predict(&cal, &cand[i], pixels) <= budget)
      {
        MRGI_CHECK(mrgi_frame_budget_error(&cand[i]) >= e);
      }
    }
    MRGI_CHECK(e <= last_error); /* a larger budget never predicts more error */
    last_error = e;
    /* Twice the load: the choice fits half the budget. */
    MRGI_CHECK(mrgi_frame_budget_choose(&cal, cand, n, pixels, budget, 2.0, &index, &within, NULL) == MRGI_OK);
    MRGI_CHECK(!within || 2.0 * mrgi_frame_budget_predict(&cal, &cand[index], pixels) <= budget);
  }
  /* Below the cheapest: flagged; the least error among the settings about
   * as cheap as the cheapest. */
  int32_t index = -1;
  int within = 1;
  MRGI_CHECK(mrgi_frame_budget_choose(&cal, cand, n, pixels, 0.5 * lo, 1.0, &index, &within, NULL) == MRGI_OK);
  MRGI_CHECK(!within);
  const double near = MRGI_FRAME_BUDGET_NEAR_CHEAPEST * lo;
  MRGI_CHECK(mrgi_frame_budget_predict(&cal, &cand[index], pixels) <= near);
  int alternatives = 0;
  for (int32_t i = 0; i < n; ++i)
  {
    if (mrgi_frame_budget_predict(&cal, &cand[i], pixels) <= near)
    {
      alternatives++;
      MRGI_CHECK(mrgi_frame_budget_error(&cand[i]) >= mrgi_frame_budget_error(&cand[index]));
    }
  }
  MRGI_CHECK(alternatives > 1);

  /* Error budget: the cheapest within it. */
  const double target = 0.08;
  MRGI_CHECK(mrgi_frame_budget_choose_for_error(&cal, cand, n, pixels, target, &index, &within, NULL) == MRGI_OK);
  MRGI_CHECK(within && mrgi_frame_budget_error(&cand[index]) <= target);
  const double cost = mrgi_frame_budget_predict(&cal, &cand[index], pixels);
  for (int32_t i = 0; i < n; ++i)
  {
    if (mrgi_frame_budget_error(&cand[i]) <= target)
    {
      MRGI_CHECK(mrgi_frame_budget_predict(&cal, &cand[i], pixels) >= cost);
    }
  }
  MRGI_CHECK(mrgi_frame_budget_choose_for_error(&cal, cand, n, pixels, 1e-6, &index, &within, NULL) == MRGI_OK);
  MRGI_CHECK(!within);

  /* Bad input named. */
  mrgi_error err;
  MRGI_CHECK(mrgi_frame_budget_choose(&cal, cand, n, pixels, -1.0, 1.0, &index, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "budget") != NULL);
  MRGI_CHECK(mrgi_frame_budget_choose(&cal, cand, n, pixels, NAN, 1.0, &index, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_frame_budget_choose_for_error(&cal, cand, n, pixels, 0.0, &index, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "error budget") != NULL);
  mrgi_frame_setting bad[2] = { cand[0], cand[1] };
  bad[1].vpls = 0;
  MRGI_CHECK(mrgi_frame_budget_choose(&cal, bad, 2, pixels, 100.0, 1.0, &index, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "candidate 1") != NULL && strstr(err.message, "VPL count") != NULL);
  /* Voxel candidates exist only when asked for, and cost more. */
  mrgi_frame_setting vox[MRGI_FRAME_BUDGET_MAX_CANDIDATES];
  const int32_t nv = mrgi_frame_budget_default_candidates(1, vox, MRGI_FRAME_BUDGET_MAX_CANDIDATES);
  MRGI_CHECK(nv == 3 * n && vox[0].voxel_side > 0 && cand[0].voxel_side == 0);
}

/* Frames of a constant load with noise: `amp` relative, uniform. */
static int run_controller(mrgi_frame_budget_controller* ctl, const mrgi_frame_budget_calibration* cal,
  const mrgi_frame_setting* cand, int32_t n, int64_t pixels, double load, double amp, int frames,
  uint32_t* rng, int* first_switch)
{
  int switches = 0;
  for (int f = 0; f < frames; ++f)
  {
    const double spike = f % 40 == 17 ? 1.5 : 1.0;
    const double ms = load * spike * true_ms(&cand[ctl->current], pixels) * (1.0 + amp * noise(rng));
    int changed = 0;
    MRGI_CHECK(mrgi_frame_budget_controller_update(
                 ctl, cal, cand, n, pixels, ms, 0.0, &changed, NULL) == MRGI_OK);
    if (changed && switches++ == 0 && first_switch)
    {
      *first_switch = f;
    }
  }
  return switches;
}

static void test_hysteresis(void)
{
  mrgi_frame_setting cand[MRGI_FRAME_BUDGET_MAX_CANDIDATES];
  const int32_t n = mrgi_frame_budget_default_candidates(0, cand, MRGI_FRAME_BUDGET_MAX_CANDIDATES);
  mrgi_frame_budget_calibration cal;
  mrgi_frame_budget_default(&cal);
  memcpy(cal.coef, truth, sizeof(truth));
  const int64_t pixels = 256 * 256;
  mrgi_frame_budget_controller ctl;
  MRGI_CHECK(mrgi_frame_budget_controller_init(&ctl, &cal, cand, n, pixels, 60.0,
               MRGI_FRAME_BUDGET_DEFAULT_MARGIN, MRGI_FRAME_BUDGET_DEFAULT_PATIENCE, NULL) == MRGI_OK);
  uint32_t rng = 777u;
  /* Noise up to +-8% with spikes (a frame in 40 takes 1.5x), constant
   * load: the first measured frames may correct the calibration's choice
   * once; then it holds. */
  MRGI_CHECK(run_controller(&ctl, &cal, cand, n, pixels, 1.0, 0.08, 10, &rng, NULL) <= 1);
  const int32_t start = ctl.current;
  MRGI_CHECK(run_controller(&ctl, &cal, cand, n, pixels, 1.0, 0.08, 2000, &rng, NULL) == 0);
  MRGI_CHECK(fabs(true_ms(&cand[start], pixels) / 60.0 - 1.0) <= 0.10);
  /* The load doubles (another program takes the cores): the first switch
   * comes after patience frames, the load estimate settles within 30
   * frames, to a setting that fits the budget at the new load, and holds. */
  int first = -1;
  const int s = run_controller(&ctl, &cal, cand, n, pixels, 2.0, 0.05, 30, &rng, &first);
  MRGI_CHECK(s >= 1 && s <= 3);
  MRGI_CHECK(first >= MRGI_FRAME_BUDGET_DEFAULT_PATIENCE - 1 && first <= MRGI_FRAME_BUDGET_DEFAULT_PATIENCE + 4);
  MRGI_CHECK(run_controller(&ctl, &cal, cand, n, pixels, 2.0, 0.05, 470, &rng, NULL) == 0);
  MRGI_CHECK(fabs(2.0 * true_ms(&cand[ctl.current], pixels) / 60.0 - 1.0) <= 0.10);
  MRGI_CHECK(ctl.load > 1.8 && ctl.load < 2.2);
  /* The load goes back: back within 10% of the budget, and it stays. */
  run_controller(&ctl, &cal, cand, n, pixels, 1.0, 0.05, 500, &rng, NULL);
  MRGI_CHECK(fabs(true_ms(&cand[ctl.current], pixels) / 60.0 - 1.0) <= 0.10);
  const int32_t settled = ctl.switches;
  MRGI_CHECK(run_controller(&ctl, &cal, cand, n, pixels, 1.0, 0.05, 1000, &rng, NULL) == 0);
  MRGI_CHECK(ctl.switches == settled);

  mrgi_error err;
  MRGI_CHECK(mrgi_frame_budget_controller_update(
               &ctl, &cal, cand, n, pixels, -3.0, 0.0, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "measured time") != NULL);
  MRGI_CHECK(mrgi_frame_budget_controller_init(&ctl, &cal, cand, n, pixels, 60.0, 0.0, 5, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "margin") != NULL);
}

/* The default candidates, a calibration holding `truth` and the real cost:
 * `truth` with the terms first..last multiplied by `scale`. */
static int32_t misjudged_model(mrgi_frame_setting* cand, mrgi_frame_budget_calibration* cal,
  mrgi_frame_budget_calibration* real, int first, int last, double scale)
{
  mrgi_frame_budget_default(cal);
  memcpy(cal->coef, truth, sizeof(truth));
  *real = *cal;
  for (int i = first; i <= last; ++i)
  {
    real->coef[i] *= scale;
  }
  return mrgi_frame_budget_default_candidates(0, cand, MRGI_FRAME_BUDGET_MAX_CANDIDATES);
}

/* The situation of an interactive orbit (Documentation/FrameBudget.md): the
 * calibration misjudges the gather (real cost 1.3x the model's) and what the
 * view costs drifts by 40% over 100 frames, with +-5% noise. The frame time
 * must stay within 10% of the budget on >= 90% of the frames after the
 * first 5 (issue 17's target), without alternating between settings. */
static void test_tracks_drift(void)
{
  mrgi_frame_setting cand[MRGI_FRAME_BUDGET_MAX_CANDIDATES];
  mrgi_frame_budget_calibration cal, real;
  const int32_t n = misjudged_model(cand, &cal, &real, 2, 2, 1.3);
  const int64_t pixels = 256 * 256;
  /* Budgets in the dense part of the frontier, multiples of the cheapest
   * setting's real cost mid-orbit (above fast with 4096 VPLs, ~3.3x, the
   * next better setting costs 1.6x more: the tuner rightly stays under). */
  double lo = 0.0;
  for (int32_t i = 0; i < n; ++i)
  {
    const double ms = 1.2 * mrgi_frame_budget_predict(&real, &cand[i], pixels);
    lo = i == 0 ? ms : fmin(lo, ms);
  }
  const double budgets[] = { 1.5 * lo, 2.0 * lo, 2.8 * lo };
  for (size_t b = 0; b < sizeof(budgets) / sizeof(budgets[0]); ++b)
  {
    mrgi_frame_budget_controller ctl;
    MRGI_CHECK(mrgi_frame_budget_controller_init(&ctl, &cal, cand, n, pixels, budgets[b],
                 MRGI_FRAME_BUDGET_DEFAULT_MARGIN, MRGI_FRAME_BUDGET_DEFAULT_PATIENCE, NULL) == MRGI_OK);
    uint32_t rng = 4242u + (uint32_t)b;
    int within = 0, counted = 0;
    for (int f = 0; f < 100; ++f)
    {
      const double view = 1.0 + 0.4 * f / 99.0;
      const double ms = view * mrgi_frame_budget_predict(&real, &cand[ctl.current], pixels) *
        (1.0 + 0.05 * noise(&rng));
      if (f >= 5)
      {
        counted++;
        within += fabs(ms / budgets[b] - 1.0) <= 0.10;
      }
      MRGI_CHECK(mrgi_frame_budget_controller_update(
                   &ctl, &cal, cand, n, pixels, ms, 0.0, NULL, NULL) == MRGI_OK);
    }
    if (within < 0.9 * counted || ctl.switches > 12)
    {
      MRGI_FAIL("budget %g ms: %d of %d frames within 10%%, %d switches", budgets[b], within,
        counted, (int)ctl.switches);
    }
  }
}

/* The shape factor: the setting-dependent terms cost 1.5x what the model
 * says, at a constant load. Budgets that alternate force switches between
 * settings of different shares; the controller must learn k = 1.5, after
 * which its expected times are the real ones. */
static void test_learns_shape(void)
{
  mrgi_frame_setting cand[MRGI_FRAME_BUDGET_MAX_CANDIDATES];
  mrgi_frame_budget_calibration cal, real;
  const int32_t n = misjudged_model(cand, &cal, &real, 2, MRGI_FRAME_BUDGET_TERMS - 1, 1.5);
  const int64_t pixels = 256 * 256;
  mrgi_frame_budget_controller ctl;
  MRGI_CHECK(mrgi_frame_budget_controller_init(&ctl, &cal, cand, n, pixels, 30.0,
               MRGI_FRAME_BUDGET_DEFAULT_MARGIN, MRGI_FRAME_BUDGET_DEFAULT_PATIENCE, NULL) == MRGI_OK);
  MRGI_CHECK(ctl.shape == 1.0);
  for (int f = 0; f < 400; ++f)
  {
    ctl.budget_ms = (f / 40) % 2 ? 60.0 : 30.0;
    const double ms = mrgi_frame_budget_predict(&real, &cand[ctl.current], pixels);
    MRGI_CHECK(mrgi_frame_budget_controller_update(
                 &ctl, &cal, cand, n, pixels, ms, 0.0, NULL, NULL) == MRGI_OK);
  }
  if (fabs(ctl.shape / 1.5 - 1.0) > 0.03)
  {
    MRGI_FAIL("shape %g after %d switches, expected 1.5", ctl.shape, (int)ctl.switches);
  }
  const double expected = mrgi_frame_budget_controller_expected(&ctl, &cal, cand, n, pixels);
  MRGI_CHECK_NEAR(expected, mrgi_frame_budget_predict(&real, &cand[ctl.current], pixels), 0.03 * expected);
  MRGI_CHECK(mrgi_frame_budget_controller_expected(NULL, &cal, cand, n, pixels) < 0.0);
}

/* The share of pixels a preset gathers, by window: the table's values at
 * 256^2, 512^2 and 1024^2, in between monotone, constant beyond. */
static void test_work_fraction_by_window(void)
{
  for (int32_t p = 0; p < MRGI_MULTIRES_PRESET_COUNT; ++p)
  {
    const double w256 = mrgi_frame_budget_work_fraction_at(p, 256 * 256);
    const double w512 = mrgi_frame_budget_work_fraction_at(p, 512 * 512);
    const double w1024 = mrgi_frame_budget_work_fraction_at(p, 1024 * 1024);
    MRGI_CHECK(w256 > w512 && w512 > w1024 && w1024 > 0.0 && w256 < 1.0);
    MRGI_CHECK(mrgi_frame_budget_work_fraction(p) == w1024);
    const double w384 = mrgi_frame_budget_work_fraction_at(p, 384 * 384);
    MRGI_CHECK(w384 < w256 && w384 > w512);
    MRGI_CHECK(mrgi_frame_budget_work_fraction_at(p, 16 * 16) == w256);
    MRGI_CHECK(mrgi_frame_budget_work_fraction_at(p, 4096 * 4096) == w1024);
  }
  /* Fast gathers a larger share at a small window (coarse levels and edges). */
  MRGI_CHECK(mrgi_frame_budget_work_fraction_at(MRGI_MULTIRES_PRESET_FAST, 256 * 256) >
    2.0 * mrgi_frame_budget_work_fraction_at(MRGI_MULTIRES_PRESET_FAST, 1024 * 1024));
  MRGI_CHECK(mrgi_frame_budget_work_fraction_at(-1, 65536) == 0.0);
  MRGI_CHECK(mrgi_frame_budget_work_fraction_at(MRGI_MULTIRES_PRESET_COUNT, 65536) == 0.0);
  MRGI_CHECK(mrgi_frame_budget_work_fraction_at(0, 0) == 0.0);
  /* A measured share replaces the table's in the gather term; a bad one does not. */
  const mrgi_frame_setting s = { MRGI_MULTIRES_PRESET_BALANCED, 256, 256, 0 };
  double table[MRGI_FRAME_BUDGET_TERMS], measured[MRGI_FRAME_BUDGET_TERMS],
    bad[MRGI_FRAME_BUDGET_TERMS];
  MRGI_CHECK(mrgi_frame_budget_terms(&s, 65536, table, NULL) == MRGI_OK);
  MRGI_CHECK(mrgi_frame_budget_terms_at(&s, 65536, 0.5, measured, NULL) == MRGI_OK);
  MRGI_CHECK_NEAR(measured[2], 65536.0 * 0.5 * 256.0 * 1e-9, 1e-12);
  MRGI_CHECK(mrgi_frame_budget_terms_at(&s, 65536, NAN, bad, NULL) == MRGI_OK);
  MRGI_CHECK(bad[2] == table[2] && measured[3] == table[3]);
  MRGI_CHECK(mrgi_frame_budget_terms_at(&s, 65536, 1e9, bad, NULL) == MRGI_OK);
  MRGI_CHECK_NEAR(bad[2], 65536.0 * MRGI_FRAME_BUDGET_MAX_WORK * 256.0 * 1e-9, 1e-9);
}

/* The view decides how much the gather works: here every preset gathers
 * 1.8x the table's share (as fast does at 256^2 against its 1024^2 value),
 * at the calibration's cost per texel. Fed the gather's measured shares,
 * the controller must hold each preset's share and expect the real time of
 * its setting; a share it cannot use (NaN, <= 0) changes nothing. */
static void test_learns_work_share(void)
{
  mrgi_frame_setting cand[MRGI_FRAME_BUDGET_MAX_CANDIDATES];
  mrgi_frame_budget_calibration cal, real;
  const int32_t n = misjudged_model(cand, &cal, &real, 2, 2, 1.0);
  const int64_t pixels = 256 * 256;
  for (int32_t p = 0; p < MRGI_MULTIRES_PRESET_COUNT; ++p)
  {
    real.work_share[p] = 1.8 * mrgi_frame_budget_work_fraction_at(p, pixels);
  }
  mrgi_frame_budget_controller ctl;
  MRGI_CHECK(
    mrgi_frame_budget_controller_init(&ctl, &cal, cand, n, pixels, 40.0,
      MRGI_FRAME_BUDGET_DEFAULT_MARGIN, MRGI_FRAME_BUDGET_DEFAULT_PATIENCE, NULL) == MRGI_OK);
  for (int f = 0; f < 60; ++f)
  {
    const mrgi_frame_setting* s = &cand[ctl.current];
    const double ms = mrgi_frame_budget_predict(&real, s, pixels);
    MRGI_CHECK(mrgi_frame_budget_controller_update(&ctl, &cal, cand, n, pixels, ms,
                 real.work_share[s->preset], NULL, NULL) == MRGI_OK);
  }
  const int32_t p = cand[ctl.current].preset;
  MRGI_CHECK_NEAR(ctl.work[p], real.work_share[p], 1e-9);
  MRGI_CHECK_NEAR(ctl.work_ratio, 1.8, 1e-9);
  /* The share explains the time: the load stays that of the fixed costs (1). */
  const double expected = mrgi_frame_budget_controller_expected(&ctl, &cal, cand, n, pixels);
  const double actual = mrgi_frame_budget_predict(&real, &cand[ctl.current], pixels);
  if (fabs(expected / actual - 1.0) > 0.02 || fabs(ctl.load - 1.0) > 0.02)
  {
    MRGI_FAIL("expected %.2f ms for a real %.2f ms, load %.3f", expected, actual, ctl.load);
  }
  const double before = ctl.work[p];
  MRGI_CHECK(mrgi_frame_budget_controller_update(
               &ctl, &cal, cand, n, pixels, actual, NAN, NULL, NULL) == MRGI_OK);
  MRGI_CHECK(mrgi_frame_budget_controller_update(
               &ctl, &cal, cand, n, pixels, actual, -1.0, NULL, NULL) == MRGI_OK);
  MRGI_CHECK(ctl.work[p] == before);
}

/* `frames` frames that take exactly what `real` predicts for the current setting. */
static void run_at_real_cost(mrgi_frame_budget_controller* ctl, const mrgi_frame_budget_calibration* cal,
  const mrgi_frame_budget_calibration* real, const mrgi_frame_setting* cand, int32_t n, int64_t pixels,
  int frames)
{
  for (int f = 0; f < frames; ++f)
  {
    const double ms = mrgi_frame_budget_predict(real, &cand[ctl->current], pixels);
    MRGI_CHECK(mrgi_frame_budget_controller_update(
                 ctl, cal, cand, n, pixels, ms, 0.0, NULL, NULL) == MRGI_OK);
  }
}

/* A new budget during interaction: every term costs 1.4x the calibration's.
 * After 60 frames at one budget, retargeting to another must choose under the
 * learnt load (real time within the budget and near it), where a fresh
 * controller would overshoot; the next frames then need no switch. A bad
 * budget is refused and leaves the controller as it was. */
static void test_retarget(void)
{
  mrgi_frame_setting cand[MRGI_FRAME_BUDGET_MAX_CANDIDATES];
  mrgi_frame_budget_calibration cal, real;
  const int32_t n = misjudged_model(cand, &cal, &real, 0, MRGI_FRAME_BUDGET_TERMS - 1, 1.4);
  const int64_t pixels = 256 * 256;
  mrgi_frame_budget_controller ctl;
  MRGI_CHECK(mrgi_frame_budget_controller_init(&ctl, &cal, cand, n, pixels, 40.0,
               MRGI_FRAME_BUDGET_DEFAULT_MARGIN, MRGI_FRAME_BUDGET_DEFAULT_PATIENCE, NULL) == MRGI_OK);
  run_at_real_cost(&ctl, &cal, &real, cand, n, pixels, 60);
  MRGI_CHECK_NEAR(ctl.load, 1.4, 0.02);
  /* The first budget above 50 ms where a fresh start (load 1) overshoots by
   * more than 20%: there the learnt load must make the difference. */
  double budget = 0.0, restarted = 0.0;
  mrgi_frame_budget_controller fresh;
  for (double b = 50.0; b < 400.0 && budget == 0.0; b += 5.0)
  {
    MRGI_CHECK(mrgi_frame_budget_controller_init(&fresh, &cal, cand, n, pixels, b,
                 MRGI_FRAME_BUDGET_DEFAULT_MARGIN, MRGI_FRAME_BUDGET_DEFAULT_PATIENCE, NULL) == MRGI_OK);
    restarted = mrgi_frame_budget_predict(&real, &cand[fresh.current], pixels);
    budget = restarted > 1.2 * b ? b : 0.0;
  }
  MRGI_CHECK(budget > 0.0);
  int changed = 0;
  MRGI_CHECK(mrgi_frame_budget_controller_retarget(&ctl, &cal, cand, n, pixels, budget, &changed, NULL) == MRGI_OK);
  MRGI_CHECK(changed == 1 && ctl.budget_ms == budget);
  const double kept = mrgi_frame_budget_predict(&real, &cand[ctl.current], pixels);
  printf("budget 40 -> %g ms at load 1.4: retarget %.1f ms, fresh start %.1f ms\n", budget, kept, restarted);
  if (!(kept <= budget * (1.0 + MRGI_FRAME_BUDGET_DEFAULT_MARGIN) && kept >= 0.85 * budget))
  {
    MRGI_FAIL("retarget chose %.1f ms for %g ms (a fresh start %.1f ms)", kept, budget, restarted);
  }
  const int32_t switches = ctl.switches;
  run_at_real_cost(&ctl, &cal, &real, cand, n, pixels, 40);
  MRGI_CHECK(ctl.switches == switches);
  mrgi_error err;
  const mrgi_frame_budget_controller before = ctl;
  MRGI_CHECK(mrgi_frame_budget_controller_retarget(&ctl, &cal, cand, n, pixels, -5.0, &changed, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(changed == 0 && memcmp(&before, &ctl, sizeof(ctl)) == 0);
  MRGI_CHECK(mrgi_frame_budget_controller_retarget(NULL, &cal, cand, n, pixels, 50.0, NULL, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
}

static void test_text(void)
{
  mrgi_frame_budget_calibration cal, back;
  mrgi_frame_budget_default(&cal);
  cal.coef[2] = 1234.5678;
  cal.frames = 17;
  strcpy(cal.renderer, "llvmpipe (LLVM 15.0.6, 256 bits)");
  char text[MRGI_FRAME_BUDGET_TEXT_SIZE];
  MRGI_CHECK(mrgi_frame_budget_format(&cal, text, sizeof(text), NULL) == MRGI_OK);
  MRGI_CHECK(mrgi_frame_budget_parse(text, &back, NULL) == MRGI_OK);
  MRGI_CHECK(back.frames == 17 && strcmp(back.renderer, cal.renderer) == 0);
  for (int i = 0; i < MRGI_FRAME_BUDGET_TERMS; ++i)
  {
    MRGI_CHECK_NEAR(back.coef[i], cal.coef[i], 1e-8 * cal.coef[i]);
  }

  /* Corrupt files: refused with the problem named, `cal` untouched. */
  static const struct
  {
    const char* text;
    const char* says;
  } bad[] = {
    { "", "truncated" },
    { "hello\n", "line 1" },
    { "mrgi-frame-budget 2\n", "line 1" },
    { "mrgi-frame-budget 1\nrenderer x\nframes 3\nfixed_ms 1\n", "truncated" },
    { "mrgi-frame-budget 1\nrenderer x\nframes 3\nfixed_ms nan\npixel_ms 1\ngather_ms 1\nrsm_ms 1\nvoxel_ms 1\nend\n", "fixed_ms" },
    { "mrgi-frame-budget 1\nrenderer x\nframes 3\nfixed_ms 1\npixel_ms -4\ngather_ms 1\nrsm_ms 1\nvoxel_ms 1\nend\n", "pixel_ms" },
    { "mrgi-frame-budget 1\nrenderer x\nframes 3\nfixed_ms 1\npixel_ms 1\ngather_ms 1e999\nrsm_ms 1\nvoxel_ms 1\nend\n", "gather_ms" },
    { "mrgi-frame-budget 1\nrenderer x\nframes 3\nfixed_ms 1\npixel_ms 1\ngather_ms 1\nrsm 1\nvoxel_ms 1\nend\n", "rsm_ms" },
    { "mrgi-frame-budget 1\nrenderer x\nframes 3.5\nfixed_ms 1\npixel_ms 1\ngather_ms 1\nrsm_ms 1\nvoxel_ms 1\nend\n", "frames" },
    { "mrgi-frame-budget 1\nrenderer x\nframes 3\nfixed_ms 1\npixel_ms 1\ngather_ms 1\nrsm_ms 1\nvoxel_ms 1x\nend\n", "voxel_ms" },
    { "mrgi-frame-budget 1\nrenderer x\nframes 3\nfixed_ms 1\npixel_ms 1\ngather_ms 1\nrsm_ms 1\nvoxel_ms 1\nfin\n", "'end'" },
    { "mrgi-frame-budget 1\nframes 3\n", "renderer" },
  };
  for (size_t i = 0; i < sizeof(bad) / sizeof(bad[0]); ++i)
  {
    mrgi_frame_budget_calibration keep = back;
    mrgi_error err;
    MRGI_CHECK(mrgi_frame_budget_parse(bad[i].text, &keep, &err) == MRGI_ERR_FORMAT);
    if (strstr(err.message, bad[i].says) == NULL)
    {
      MRGI_FAIL("case %zu: '%s' does not name '%s'", i, err.message, bad[i].says);
    }
    MRGI_CHECK(memcmp(&keep, &back, sizeof(keep)) == 0);
  }
  /* Windows line ends are read too. */
  char crlf[2 * MRGI_FRAME_BUDGET_TEXT_SIZE];
  size_t k = 0;
  for (const char* p = text; *p; ++p)
  {
    if (*p == '\n')
    {
      crlf[k++] = '\r';
    }
    crlf[k++] = *p;
  }
  crlf[k] = '\0';
  MRGI_CHECK(mrgi_frame_budget_parse(crlf, &back, NULL) == MRGI_OK);
  MRGI_CHECK(back.frames == 17);
  /* A bad coefficient is not written. */
  cal.coef[1] = -1;
  MRGI_CHECK(mrgi_frame_budget_format(&cal, text, sizeof(text), NULL) == MRGI_ERR_INVALID_ARGUMENT);
}

static void test_error_proxy(void)
{
  mrgi_frame_setting s = { MRGI_MULTIRES_PRESET_BALANCED, 256, 256, 0 };
  const double e = mrgi_frame_budget_error(&s);
  s.vpls = 1024;
  MRGI_CHECK(mrgi_frame_budget_error(&s) < e); /* more VPLs: less error */
  s.vpls = 256;
  s.preset = MRGI_MULTIRES_PRESET_FAST;
  MRGI_CHECK(mrgi_frame_budget_error(&s) > e); /* a coarser preset: more error */
  s.preset = 7;
  MRGI_CHECK(mrgi_frame_budget_error(&s) < 0);
  MRGI_CHECK(mrgi_frame_budget_predict(NULL, &s, 10) < 0);
}

int main(int argc, char** argv)
{
  static const mrgi_test_case cases[] = {
    MRGI_TEST_CASE(test_fit_recovers),
    MRGI_TEST_CASE(test_choice_respects_budget),
    MRGI_TEST_CASE(test_hysteresis),
    MRGI_TEST_CASE(test_tracks_drift),
    MRGI_TEST_CASE(test_learns_shape),
    MRGI_TEST_CASE(test_work_fraction_by_window),
    MRGI_TEST_CASE(test_learns_work_share),
    MRGI_TEST_CASE(test_retarget),
    MRGI_TEST_CASE(test_text),
    MRGI_TEST_CASE(test_error_proxy),
  };
  return MRGI_TEST_MAIN(argc, argv, cases);
}
