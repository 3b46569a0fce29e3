/* The frame-budget tuner: cost model fit, error proxy, choice, calibration
 * text. Contract and model in mrgi_frame_budget.h; the interaction
 * controller is mrgi_frame_budget_controller.c. */
#include "mrgi_frame_budget.h"

#include "mrgi_multires.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Rough llvmpipe numbers, 2 cores (Documentation/Multiresolution.md,
 * 1024x1024): 701 ms for 1 Mpixel x 256 VPLs full gather -> ~2.6 s per 1e9
 * pairs; selection plus upsampling ~160 ms per Mpixel; voxel visibility made
 * the gather 20-80x slower (close8). */
static const double default_coef[MRGI_FRAME_BUDGET_TERMS] = { 10.0, 200.0, 3000.0, 40.0, 1.0e5 };

static const char* const term_keys[MRGI_FRAME_BUDGET_TERMS] = { "fixed_ms", "pixel_ms",
  "gather_ms", "rsm_ms", "voxel_ms" };

void mrgi_frame_budget_default(mrgi_frame_budget_calibration* cal)
{
  if (!cal)
  {
    return;
  }
  memset(cal, 0, sizeof(*cal));
  memcpy(cal->coef, default_coef, sizeof(default_coef));
}

/* Gathered / valid pixels of each preset at windows of 256^2, 512^2 and
 * 1024^2 (mrgi-render cornell-spot --preset P --timings): coarse levels and
 * edges are a larger part of a smaller image. Balanced and accurate refine
 * by illumination (mrgi_multires_preset_illumination_threshold) from
 * MRGI_MULTIRES_ILLUMINATION_MIN_PIXELS up (512^2, 1024^2: every level
 * they gather counts), geometrically below (256^2). */
static const double work_sides[3] = { 256.0, 512.0, 1024.0 };
static const double work_table[MRGI_MULTIRES_PRESET_COUNT][3] = {
  { 0.1003, 0.0633, 0.0332 }, /* fast */
  { 0.3609, 0.1763, 0.0874 }, /* balanced */
  { 0.3661, 0.2479, 0.1188 }, /* accurate */
};

double mrgi_frame_budget_work_fraction_at(int32_t preset, int64_t pixels)
{
  if (preset < 0 || preset >= MRGI_MULTIRES_PRESET_COUNT || pixels < 1)
  {
    return 0.0;
  }
  /* Linear in log(share) over log(side), constant beyond the table. */
  const double side = fmin(fmax(sqrt((double)pixels), work_sides[0]), work_sides[2]);
  const int k = side <= work_sides[1] ? 0 : 1;
  const double t = log(side / work_sides[k]) / log(work_sides[k + 1] / work_sides[k]);
  const double* w = work_table[preset];
  return exp(log(w[k]) + t * (log(w[k + 1]) - log(w[k])));
}

double mrgi_frame_budget_work_fraction(int32_t preset)
{
  return mrgi_frame_budget_work_fraction_at(preset, 1024 * 1024);
}

mrgi_status mrgi_frame_budget_check_setting(const mrgi_frame_setting* s, mrgi_error* err)
{
  if (!s)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "frame budget: NULL setting");
  }
  if (s->preset < 0 || s->preset >= MRGI_MULTIRES_PRESET_COUNT)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "frame budget: unknown preset %d",
      (int)s->preset);
  }
  if (s->vpls < 1 || s->vpls > 4096)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "frame budget: VPL count %d outside 1..4096", (int)s->vpls);
  }
  if (s->rsm_size < 16 || s->rsm_size > 2048)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "frame budget: RSM size %d outside 16..2048", (int)s->rsm_size);
  }
  if (s->voxel_side < 0 || s->voxel_side > 4096)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "frame budget: voxel side %d outside 0..4096", (int)s->voxel_side);
  }
  return MRGI_OK;
}

mrgi_status mrgi_frame_budget_terms_at(const mrgi_frame_setting* s, int64_t pixels,
  double work_share, double terms[MRGI_FRAME_BUDGET_TERMS], mrgi_error* err)
{
  const mrgi_status st = mrgi_frame_budget_check_setting(s, err);
  if (st != MRGI_OK)
  {
    return st;
  }
  if (!terms || pixels < 1)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "frame budget: %s", terms ? "pixel count must be >= 1" : "NULL terms");
  }
  const double p = (double)pixels;
  const double w = isfinite(work_share) && work_share > 0.0
    ? fmin(work_share, MRGI_FRAME_BUDGET_MAX_WORK)
    : mrgi_frame_budget_work_fraction_at(s->preset, pixels);
  const double g = p * w * (double)s->vpls;
  terms[0] = 1.0;
  terms[1] = p * 1e-6;
  terms[2] = g * 1e-9;
  terms[3] = (double)s->rsm_size * (double)s->rsm_size * 1e-6;
  terms[4] = s->voxel_side > 0 ? g * ((double)s->voxel_side / 128.0) * 1e-9 : 0.0;
  return MRGI_OK;
}

mrgi_status mrgi_frame_budget_terms(const mrgi_frame_setting* s, int64_t pixels,
  double terms[MRGI_FRAME_BUDGET_TERMS], mrgi_error* err)
{
  return mrgi_frame_budget_terms_at(s, pixels, 0.0, terms, err);
}

double mrgi_frame_budget_predict(
  const mrgi_frame_budget_calibration* cal, const mrgi_frame_setting* s, int64_t pixels)
{
  double t[MRGI_FRAME_BUDGET_TERMS];
  const double share = cal && s && s->preset >= 0 && s->preset < MRGI_MULTIRES_PRESET_COUNT
    ? cal->work_share[s->preset]
    : 0.0;
  if (!cal || mrgi_frame_budget_terms_at(s, pixels, share, t, NULL) != MRGI_OK)
  {
    return -1.0;
  }
  double ms = 0.0;
  for (int i = 0; i < MRGI_FRAME_BUDGET_TERMS; ++i)
  {
    ms += cal->coef[i] * t[i];
  }
  return ms;
}

double mrgi_frame_budget_error(const mrgi_frame_setting* s)
{
  if (mrgi_frame_budget_check_setting(s, NULL) != MRGI_OK)
  {
    return -1.0;
  }
  /* Multires error against the full gather, 256 VPLs, cornell-spot
   * (Documentation/Multiresolution.md, presets table). */
  static const double preset_error[MRGI_MULTIRES_PRESET_COUNT] = { 0.043, 0.016, 0.010 };
  const double m = preset_error[s->preset];
  const double v = MRGI_FRAME_BUDGET_ERROR_VPL / sqrt((double)s->vpls);
  const double r = MRGI_FRAME_BUDGET_ERROR_RSM * 256.0 / (double)s->rsm_size;
  const double x = s->voxel_side > 0 ? MRGI_FRAME_BUDGET_ERROR_VOXEL * 128.0 / s->voxel_side : 0.0;
  return sqrt(m * m + v * v + r * r + x * x);
}

/* Solve the n x n system a x = b (row-major, a and b overwritten) by Gaussian
 * elimination with partial pivoting. `a` has a unit diagonal (scaled normal
 * equations); returns 0 when a pivot falls under 1e-9 (singular). */
static int solve(double* a, double* b, int n, double* x)
{
  for (int c = 0; c < n; ++c)
  {
    int pivot = c;
    for (int r = c + 1; r < n; ++r)
    {
      if (fabs(a[r * n + c]) > fabs(a[pivot * n + c]))
      {
        pivot = r;
      }
    }
    if (!(fabs(a[pivot * n + c]) > 1e-9))
    {
      return 0;
    }
    if (pivot != c)
    {
      for (int k = 0; k < n; ++k)
      {
        const double t = a[c * n + k];
        a[c * n + k] = a[pivot * n + k];
        a[pivot * n + k] = t;
      }
      const double t = b[c];
      b[c] = b[pivot];
      b[pivot] = t;
    }
    for (int r = c + 1; r < n; ++r)
    {
      const double f = a[r * n + c] / a[c * n + c];
      for (int k = c; k < n; ++k)
      {
        a[r * n + k] -= f * a[c * n + k];
      }
      b[r] -= f * b[c];
    }
  }
  for (int r = n - 1; r >= 0; --r)
  {
    double s = b[r];
    for (int k = r + 1; k < n; ++k)
    {
      s -= a[r * n + k] * x[k];
    }
    x[r] = s / a[r * n + r];
  }
  return 1;
}

mrgi_status mrgi_frame_budget_fit(const double* terms, const double* ms, int32_t count,
  mrgi_frame_budget_calibration* cal, mrgi_error* err)
{
  enum { N = MRGI_FRAME_BUDGET_TERMS };
  if (!terms || !ms || !cal || count < 1)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "frame budget fit: %s", count < 1 ? "no frames" : "NULL argument");
  }
  int active[N] = { 0 };
  for (int32_t f = 0; f < count; ++f)
  {
    if (!(isfinite(ms[f]) && ms[f] >= 0.0))
    {
      return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
        "frame budget fit: frame %d has time %g (must be finite and >= 0)", (int)f, ms[f]);
    }
    for (int i = 0; i < N; ++i)
    {
      const double t = terms[(size_t)f * N + i];
      if (!(isfinite(t) && t >= 0.0))
      {
        return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
          "frame budget fit: frame %d term %s is %g (must be finite and >= 0)", (int)f,
          term_keys[i], t);
      }
      active[i] |= t > 0.0;
    }
  }
  /* A term other than the fixed one that has the same value in every frame
   * (one window size: the pixel term) cannot be told from the fixed cost:
   * it keeps its prior, and the fixed cost absorbs the rest. */
  for (int i = 1; i < N && active[0]; ++i)
  {
    int constant = count > 1;
    for (int32_t f = 1; f < count && constant; ++f)
    {
      constant = terms[(size_t)f * N + i] == terms[i];
    }
    active[i] = active[i] && !constant;
  }
  /* Non-negative least squares by elimination: fit the active terms; fix the
   * most negative at 0; repeat. Inactive terms keep the prior. */
  double coef[N];
  memcpy(coef, cal->coef, sizeof(coef));
  for (int round = 0; round < N; ++round)
  {
    int idx[N], n = 0;
    for (int i = 0; i < N; ++i)
    {
      if (active[i])
      {
        idx[n++] = i;
      }
    }
    if (n == 0)
    {
      break;
    }
    double a[N * N] = { 0 }, b[N] = { 0 }, x[N] = { 0 };
    for (int32_t f = 0; f < count; ++f)
    {
      const double* t = terms + (size_t)f * N;
      /* The inactive terms' prior share is subtracted, never refitted. */
      double y = ms[f];
      for (int i = 0; i < N; ++i)
      {
        y -= active[i] ? 0.0 : coef[i] * t[i];
      }
      for (int r = 0; r < n; ++r)
      {
        for (int c = 0; c < n; ++c)
        {
          a[r * n + c] += t[idx[r]] * t[idx[c]];
        }
        b[r] += t[idx[r]] * y;
      }
    }
    /* Columns scaled to unit norm: the pivot test below is then relative. */
    double scale[N];
    for (int r = 0; r < n; ++r)
    {
      scale[r] = a[r * n + r] > 0.0 ? sqrt(a[r * n + r]) : 1.0;
    }
    for (int r = 0; r < n; ++r)
    {
      for (int c = 0; c < n; ++c)
      {
        a[r * n + c] /= scale[r] * scale[c];
      }
      b[r] /= scale[r];
    }
    const int solved = solve(a, b, n, x);
    for (int r = 0; r < n; ++r)
    {
      x[r] /= scale[r];
    }
    if (!solved)
    {
      return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
        "frame budget fit: %d frames do not determine %d cost terms (vary the settings)",
        (int)count, n);
    }
    int worst = -1;
    for (int r = 0; r < n; ++r)
    {
      if (x[r] < 0.0 && (worst < 0 || x[r] < x[worst]))
      {
        worst = r;
      }
    }
    for (int r = 0; r < n; ++r)
    {
      coef[idx[r]] = x[r];
    }
    if (worst < 0)
    {
      break;
    }
    coef[idx[worst]] = 0.0;
    active[idx[worst]] = 0;
  }
  for (int i = 0; i < N; ++i)
  {
    coef[i] = coef[i] > 0.0 ? coef[i] : 0.0;
  }
  memcpy(cal->coef, coef, sizeof(coef));
  cal->frames = count;
  return MRGI_OK;
}

int32_t mrgi_frame_budget_default_candidates(int voxels, mrgi_frame_setting* out, int32_t capacity)
{
  /* Grid sides close enough that neighbouring VPL counts differ by at most
   * ~30% (4..8) and ~28% down to 6.5% (8..64, step 2): the controller needs
   * a setting near any budget, not only near the presets' own. */
  static const int32_t sides[] = { 4, 5, 6, 7, 8, 10, 12, 14, 16, 18, 20, 22, 24, 26, 28, 30, 32,
    34, 36, 38, 40, 42, 44, 46, 48, 50, 52, 54, 56, 58, 60, 62, 64 };
  static const int32_t rsm[] = { 128, 256, 512 };
  static const int32_t vox[] = { 64, 128, 256 };
  const int nsides = (int)(sizeof(sides) / sizeof(sides[0]));
  const int nvox = voxels ? 3 : 1;
  int32_t n = 0;
  for (int32_t p = 0; p < MRGI_MULTIRES_PRESET_COUNT; ++p)
  {
    for (int v = 0; v < nsides; ++v)
    {
      for (int r = 0; r < 3; ++r)
      {
        for (int x = 0; x < nvox; ++x)
        {
          if (out && n < capacity)
          {
            const mrgi_frame_setting s = { p, sides[v] * sides[v], rsm[r], voxels ? vox[x] : 0 };
            out[n] = s;
          }
          n += out && n < capacity ? 1 : 0;
        }
      }
    }
  }
  return n;
}

static mrgi_status check_choice(const mrgi_frame_budget_calibration* cal,
  const mrgi_frame_setting* candidates, int32_t count, int64_t pixels, double bound,
  const char* what, int32_t* index, mrgi_error* err)
{
  if (!cal || !candidates || !index)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "frame budget: NULL argument");
  }
  if (count < 1 || pixels < 1)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "frame budget: %s", count < 1 ? "no candidates" : "pixel count must be >= 1");
  }
  if (!(isfinite(bound) && bound > 0.0))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "frame budget: %s %g must be finite and > 0", what, bound);
  }
  for (int32_t i = 0; i < count; ++i)
  {
    if (mrgi_frame_budget_check_setting(&candidates[i], err) != MRGI_OK)
    {
      mrgi_error_prefix(err, "candidate %d: ", (int)i);
      return MRGI_ERR_INVALID_ARGUMENT;
    }
  }
  return MRGI_OK;
}

mrgi_status mrgi_frame_budget_choose(const mrgi_frame_budget_calibration* cal,
  const mrgi_frame_setting* candidates, int32_t count, int64_t pixels, double budget_ms,
  double load, int32_t* index, int* within, mrgi_error* err)
{
  mrgi_status st = check_choice(cal, candidates, count, pixels, budget_ms, "budget", index, err);
  if (st == MRGI_OK && !(isfinite(load) && load > 0.0))
  {
    st = mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "frame budget: load factor %g must be finite and > 0", load);
  }
  if (st != MRGI_OK)
  {
    return st;
  }
  int32_t best = -1, cheapest = 0;
  double best_err = 0.0, best_ms = 0.0, cheapest_ms = 0.0;
  for (int32_t i = 0; i < count; ++i)
  {
    const double ms = load * mrgi_frame_budget_predict(cal, &candidates[i], pixels);
    const double e = mrgi_frame_budget_error(&candidates[i]);
    if (i == 0 || ms < cheapest_ms)
    {
      cheapest = i;
      cheapest_ms = ms;
    }
    if (ms <= budget_ms && (best < 0 || e < best_err || (e == best_err && ms < best_ms)))
    {
      best = i;
      best_err = e;
      best_ms = ms;
    }
  }
  if (within)
  {
    *within = best >= 0;
  }
  if (best < 0)
  {
    /* Nothing fits: among the settings that cost about as little as the
     * cheapest, the one of least error (16 VPLs are rarely worth saving
     * the last percent). */
    best = cheapest;
    best_err = mrgi_frame_budget_error(&candidates[cheapest]);
    best_ms = cheapest_ms;
    for (int32_t i = 0; i < count; ++i)
    {
      const double ms = load * mrgi_frame_budget_predict(cal, &candidates[i], pixels);
      const double e = mrgi_frame_budget_error(&candidates[i]);
      if (ms <= MRGI_FRAME_BUDGET_NEAR_CHEAPEST * cheapest_ms &&
        (e < best_err || (e == best_err && ms < best_ms)))
      {
        best = i;
        best_err = e;
        best_ms = ms;
      }
    }
  }
  *index = best;
  return MRGI_OK;
}

mrgi_status mrgi_frame_budget_choose_for_error(const mrgi_frame_budget_calibration* cal,
  const mrgi_frame_setting* candidates, int32_t count, int64_t pixels, double max_error,
  int32_t* index, int* within, mrgi_error* err)
{
  const mrgi_status st =
    check_choice(cal, candidates, count, pixels, max_error, "error budget", index, err);
  if (st != MRGI_OK)
  {
    return st;
  }
  int32_t best = -1, least = 0;
  double best_ms = 0.0, least_err = 0.0;
  for (int32_t i = 0; i < count; ++i)
  {
    const double ms = mrgi_frame_budget_predict(cal, &candidates[i], pixels);
    const double e = mrgi_frame_budget_error(&candidates[i]);
    if (i == 0 || e < least_err)
    {
      least = i;
      least_err = e;
    }
    if (e <= max_error && (best < 0 || ms < best_ms))
    {
      best = i;
      best_ms = ms;
    }
  }
  *index = best >= 0 ? best : least;
  if (within)
  {
    *within = best >= 0;
  }
  return MRGI_OK;
}

mrgi_status mrgi_frame_budget_format(
  const mrgi_frame_budget_calibration* cal, char* text, size_t size, mrgi_error* err)
{
  if (!cal || !text || size < MRGI_FRAME_BUDGET_TEXT_SIZE)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "frame budget: NULL argument or a buffer under %d bytes", MRGI_FRAME_BUDGET_TEXT_SIZE);
  }
  for (int i = 0; i < MRGI_FRAME_BUDGET_TERMS; ++i)
  {
    if (!(isfinite(cal->coef[i]) && cal->coef[i] >= 0.0))
    {
      return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
        "frame budget: %s is %g (must be finite and >= 0)", term_keys[i], cal->coef[i]);
    }
  }
  /* The renderer ends at the first newline (one line per key). */
  char renderer[MRGI_FRAME_BUDGET_RENDERER_SIZE];
  size_t n = 0;
  while (n + 1 < sizeof(renderer) && cal->renderer[n] && cal->renderer[n] != '\n' &&
    cal->renderer[n] != '\r')
  {
    renderer[n] = cal->renderer[n];
    ++n;
  }
  renderer[n] = '\0';
  const int w = snprintf(text, size,
    "mrgi-frame-budget 1\nrenderer %s\nframes %d\n%s %.9g\n%s %.9g\n%s %.9g\n%s %.9g\n%s %.9g\nend\n",
    renderer, (int)cal->frames, term_keys[0], cal->coef[0], term_keys[1], cal->coef[1],
    term_keys[2], cal->coef[2], term_keys[3], cal->coef[3], term_keys[4], cal->coef[4]);
  if (w < 0 || (size_t)w >= size)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "frame budget: text buffer too small");
  }
  return MRGI_OK;
}

/* Copy line `*pos` of `text` into `line` (without the newline); advance. */
static int next_line(const char** pos, char* line, size_t size)
{
  const char* p = *pos;
  if (!*p)
  {
    return 0;
  }
  size_t n = 0;
  while (*p && *p != '\n')
  {
    if (n + 1 < size)
    {
      line[n++] = *p;
    }
    ++p;
  }
  if (n > 0 && line[n - 1] == '\r')
  {
    --n;
  }
  line[n] = '\0';
  *pos = *p ? p + 1 : p;
  return 1;
}

mrgi_status mrgi_frame_budget_parse(
  const char* text, mrgi_frame_budget_calibration* cal, mrgi_error* err)
{
  if (!text || !cal)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "frame budget: NULL argument");
  }
  mrgi_frame_budget_calibration out;
  mrgi_frame_budget_default(&out);
  const char* pos = text;
  char line[256];
  int lineno = 0;
  /* Keys in their fixed order: version, renderer, frames, the terms, end. */
  for (int k = 0; k < 4 + MRGI_FRAME_BUDGET_TERMS; ++k)
  {
    ++lineno;
    if (!next_line(&pos, line, sizeof(line)))
    {
      return mrgi_error_set(err, MRGI_ERR_FORMAT,
        "frame budget calibration: truncated at line %d (no 'end')", lineno);
    }
    if (k == 0)
    {
      if (strcmp(line, "mrgi-frame-budget 1") != 0)
      {
        return mrgi_error_set(err, MRGI_ERR_FORMAT,
          "frame budget calibration: line 1 is not 'mrgi-frame-budget 1'");
      }
      continue;
    }
    if (k == 1)
    {
      if (strncmp(line, "renderer ", 9) != 0 && strcmp(line, "renderer") != 0)
      {
        return mrgi_error_set(err, MRGI_ERR_FORMAT,
          "frame budget calibration: line 2 must be 'renderer ...'");
      }
      const char* name = line[8] ? line + 9 : "";
      const size_t n = strlen(name) < sizeof(out.renderer) ? strlen(name) : sizeof(out.renderer) - 1;
      memcpy(out.renderer, name, n);
      out.renderer[n] = '\0';
      continue;
    }
    if (k == 3 + MRGI_FRAME_BUDGET_TERMS)
    {
      if (strcmp(line, "end") != 0)
      {
        return mrgi_error_set(err, MRGI_ERR_FORMAT,
          "frame budget calibration: line %d must be 'end'", lineno);
      }
      continue;
    }
    const char* key = k == 2 ? "frames" : term_keys[k - 3];
    const size_t klen = strlen(key);
    if (strncmp(line, key, klen) != 0 || line[klen] != ' ')
    {
      return mrgi_error_set(err, MRGI_ERR_FORMAT,
        "frame budget calibration: line %d must be '%s <number>'", lineno, key);
    }
    const char* v = line + klen + 1;
    char* end = NULL;
    errno = 0;
    const double value = strtod(v, &end);
    if (end == v || *end != '\0' || errno != 0 || !isfinite(value) || value < 0.0)
    {
      return mrgi_error_set(err, MRGI_ERR_FORMAT,
        "frame budget calibration: line %d, %s '%s' is not a finite number >= 0", lineno, key, v);
    }
    if (k == 2)
    {
      if (value != floor(value) || value > 1e9)
      {
        return mrgi_error_set(err, MRGI_ERR_FORMAT,
          "frame budget calibration: line %d, frames '%s' is not a whole number", lineno, v);
      }
      out.frames = (int32_t)value;
    }
    else
    {
      out.coef[k - 3] = value;
    }
  }
  *cal = out;
  return MRGI_OK;
}
