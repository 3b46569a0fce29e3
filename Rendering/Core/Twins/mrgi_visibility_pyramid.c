#include "mrgi_visibility_pyramid.h"

#include "mrgi_buffers.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

mrgi_status mrgi_voxel_samples_check(const mrgi_voxel_samples* samples, mrgi_error* err)
{
  if (!samples)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "light samples are NULL");
  }
  if (samples->count < 1 || samples->count > MRGI_VOXEL_MAX_SAMPLES)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "light sample count %d is outside 1..%d", samples->count,
                          MRGI_VOXEL_MAX_SAMPLES);
  }
  if (!samples->position)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "light sample positions are NULL");
  }
  for (int32_t j = 0; j < samples->count; ++j)
  {
    for (int c = 0; c < 3; ++c)
    {
      if (!isfinite(samples->position[3 * j + c]) ||
          (samples->normal && !isfinite(samples->normal[3 * j + c])))
      {
        return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                              "light sample %d has a non-finite %s", j,
                              isfinite(samples->position[3 * j + c]) ? "normal" : "position");
      }
    }
  }
  return MRGI_OK;
}

uint32_t mrgi_voxel_phase_word_mask(uint32_t phase_set)
{
  return (phase_set & 15u) * 0x11111111u;
}

uint32_t mrgi_voxel_popcount(uint32_t v)
{
  v = v - ((v >> 1) & 0x55555555u);
  v = (v & 0x33333333u) + ((v >> 2) & 0x33333333u);
  v = (v + (v >> 4)) & 0x0F0F0F0Fu;
  return (v * 0x01010101u) >> 24;
}

/* Bits of word w that hold samples (bits >= N of the last word are 0). */
static uint32_t mrgi_voxel_valid_bits(int32_t count, int32_t w)
{
  const int32_t rest = count - 32 * w;
  return rest >= 32 ? 0xFFFFFFFFu : ((1u << (uint32_t)rest) - 1u);
}

int64_t mrgi_voxel_visibility(const mrgi_voxel_view* view, const mrgi_voxel_samples* samples,
                              const float receiver[3], const float* normal,
                              const uint32_t* const* coarse, int reuse_hidden, uint32_t phase_set,
                              uint32_t* mask)
{
  const int32_t words = mrgi_voxel_mask_words(samples->count);
  const uint32_t phase_bits = mrgi_voxel_phase_word_mask(phase_set);
  int64_t rays = 0;
  for (int32_t w = 0; w < words; ++w)
  {
    const uint32_t wanted = phase_bits & mrgi_voxel_valid_bits(samples->count, w);
    uint32_t all = 0xFFFFFFFFu; /* AND */
    uint32_t any = 0u;          /* OR */
    int have = 0;
    if (coarse)
    {
      for (int k = 0; k < MRGI_VOXEL_NEIGHBOURS; ++k)
      {
        if (coarse[k])
        {
          all &= coarse[k][w];
          any |= coarse[k][w];
          have = 1;
        }
      }
    }
    /* Agreed bits are reused; without reuse_hidden only the agreed visible
     * ones (section 3, the surround rule). */
    const uint32_t agree = !have ? 0u : reuse_hidden ? wanted & ~(all ^ any) : wanted & all;
    uint32_t result = all & agree;
    const uint32_t todo = wanted & ~agree;
    for (int32_t b = 0; b < 32; ++b)
    {
      if ((todo >> (uint32_t)b) & 1u)
      {
        const int32_t j = 32 * w + b;
        const float* y = samples->position + 3 * j;
        const float* n = samples->normal ? samples->normal + 3 * j : NULL;
        float facing[3];
        if (n && samples->two_sided &&
            n[0] * (receiver[0] - y[0]) + n[1] * (receiver[1] - y[1]) + n[2] * (receiver[2] - y[2]) < 0.0f)
        {
          facing[0] = -n[0];
          facing[1] = -n[1];
          facing[2] = -n[2];
          n = facing;
        }
        if (mrgi_voxel_march(view, receiver, normal, y, n))
        {
          result |= 1u << (uint32_t)b;
        }
        ++rays;
      }
    }
    mask[w] = result;
  }
  return rays;
}

void mrgi_voxel_neighbourhood_metric(const uint32_t* const* masks, int32_t words,
                                     mrgi_voxel_metric* metric)
{
  mrgi_voxel_metric m = { 0, 0, 0, 0 };
  int32_t counts[MRGI_VOXEL_NEIGHBOURS];
  for (int k = 0; k < MRGI_VOXEL_NEIGHBOURS; ++k)
  {
    counts[k] = 0;
  }
  for (int32_t w = 0; w < words; ++w)
  {
    uint32_t all = 0xFFFFFFFFu;
    uint32_t any = 0u;
    for (int k = 0; k < MRGI_VOXEL_NEIGHBOURS; ++k)
    {
      if (masks[k])
      {
        all &= masks[k][w];
        any |= masks[k][w];
        counts[k] += (int32_t)mrgi_voxel_popcount(masks[k][w]);
      }
    }
    m.disagree += (int32_t)mrgi_voxel_popcount(any & ~all);
  }
  int first = 1;
  for (int k = 0; k < MRGI_VOXEL_NEIGHBOURS; ++k)
  {
    if (masks[k])
    {
      ++m.masks;
      if (first || counts[k] < m.count_min)
      {
        m.count_min = counts[k];
      }
      if (first || counts[k] > m.count_max)
      {
        m.count_max = counts[k];
      }
      first = 0;
    }
  }
  if (m.masks == 0)
  {
    m.disagree = 0;
  }
  *metric = m;
}

int mrgi_voxel_needs_refinement(const mrgi_voxel_metric* metric, int32_t metric_kind,
                                int32_t threshold)
{
  const int32_t value = metric_kind == MRGI_VOXEL_METRIC_COUNT_SPREAD
                          ? metric->count_max - metric->count_min
                          : metric->disagree;
  return value >= threshold;
}

void mrgi_voxel_interleave_combine(const uint32_t* const quarter[MRGI_VOXEL_INTERLEAVE_PHASES],
                                   int32_t words, uint32_t* out)
{
  for (int32_t w = 0; w < words; ++w)
  {
    uint32_t v = 0u;
    for (int q = 0; q < MRGI_VOXEL_INTERLEAVE_PHASES; ++q)
    {
      if (quarter[q])
      {
        v |= quarter[q][w] & mrgi_voxel_phase_word_mask(1u << (uint32_t)q);
      }
    }
    out[w] = v;
  }
}

void mrgi_voxel_incremental_params_default(mrgi_voxel_incremental_params* params)
{
  if (!params)
  {
    return;
  }
  params->interleave = 1;
  params->metric = MRGI_VOXEL_METRIC_DISAGREE;
  params->refine_fraction = MRGI_VOXEL_DEFAULT_REFINE_FRACTION;
}

int32_t mrgi_voxel_refine_threshold(float refine_fraction, int32_t count)
{
  if (!(refine_fraction >= 0.0f && refine_fraction <= 1.0f) || count < 1 ||
      count > MRGI_VOXEL_MAX_SAMPLES)
  {
    return -1;
  }
  const int32_t t = (int32_t)ceil((double)refine_fraction * (double)count);
  return refine_fraction > 0.0f && t < 1 ? 1 : t;
}

/* Receiver of flattened texel t: 1 when valid; *normal NULL without a usable normal. */
static int mrgi_voxel_receiver(const float* position, const float* normal, size_t t,
                               const float** p, const float** n)
{
  const float* P = position + 4 * t;
  if (!(P[3] > MRGI_GBUFFER_VALID_THRESHOLD) || !isfinite(P[0]) || !isfinite(P[1]) ||
      !isfinite(P[2]))
  {
    return 0;
  }
  const float* N = normal + 4 * t;
  *p = P;
  *n = (isfinite(N[0]) && isfinite(N[1]) && isfinite(N[2]) &&
        (N[0] != 0.0f || N[1] != 0.0f || N[2] != 0.0f))
         ? N
         : NULL;
  return 1;
}

int mrgi_voxel_same_surface(const float p[3], const float n[3], const float q[3],
                            const float m[3])
{
  if (!n || !m)
  {
    return 0;
  }
  const float nn = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
  const float mm = m[0] * m[0] + m[1] * m[1] + m[2] * m[2];
  const float nm = n[0] * m[0] + n[1] * m[1] + n[2] * m[2];
  /* cos(n, m) >= MIN_COS, as nm >= MIN_COS sqrt(nn mm) without a division */
  if (!(nm > 0.0f && nm * nm >= MRGI_VOXEL_INTERLEAVE_MIN_COS * MRGI_VOXEL_INTERLEAVE_MIN_COS * nn * mm))
  {
    return 0;
  }
  const float d[3] = { q[0] - p[0], q[1] - p[1], q[2] - p[2] };
  const float dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
  const float nd = n[0] * d[0] + n[1] * d[1] + n[2] * d[2];
  const float md = m[0] * d[0] + m[1] * d[1] + m[2] * d[2];
  const float s2 = MRGI_VOXEL_INTERLEAVE_MAX_SLOPE * MRGI_VOXEL_INTERLEAVE_MAX_SLOPE;
  return nd * nd <= s2 * dd * nn && md * md <= s2 * dd * mm;
}

int mrgi_voxel_screen_side(const float p[3], const float q[3], int parallel, int axis)
{
  if (q[0] == p[0] && q[1] == p[1] && q[2] == p[2])
  {
    return 0;
  }
  /* Perspective: sign of q_a / -q_z - p_a / -p_z, both depths in front
   * (z < 0), without a division: p_a q_z - q_a p_z. */
  const float d = parallel ? q[axis] - p[axis] : p[axis] * q[2] - q[axis] * p[2];
  return d > 0.0f ? 1 : d < 0.0f ? -1 : 0;
}

/* The coarse neighbourhood of a level-(level - 1) texel with receiver (p, n)
 * (section 3): the 3x3 level-`level` texels around its parent (cx, cy),
 * clamped; non-receivers NULL. The same-surface guard: *kept counts the
 * receivers on the texel's surface (mrgi_voxel_same_surface(p, n, q, m));
 * returns 1 when the parent itself (the centre) is one of them.
 * *surrounded: the kept receivers surround p on screen (section 3's
 * surround rule; 0 without any kept). */
static int mrgi_voxel_gather_neighbours(const mrgi_multires_layout* layout, int32_t level,
                                        int32_t cx, int32_t cy, const float* position,
                                        const float* normal, const float* p, const float* n,
                                        int parallel, const uint32_t* masks, int32_t words,
                                        const uint32_t* out[MRGI_VOXEL_NEIGHBOURS], int* kept,
                                        int* surrounded)
{
  int k = 0;
  int parent_kept = 0;
  /* Per axis, bit 0: a kept receiver at or before p, bit 1: at or after. */
  int sides[2] = { 0, 0 };
  *kept = 0;
  for (int32_t dy = -1; dy <= 1; ++dy)
  {
    for (int32_t dx = -1; dx <= 1; ++dx)
    {
      const size_t t = mrgi_multires_clamped_index(layout, level, cx, cy, dx, dy);
      const float* q;
      const float* m;
      const int receiver = mrgi_voxel_receiver(position, normal, t, &q, &m);
      const int same = receiver && mrgi_voxel_same_surface(p, n, q, m);
      *kept += same;
      for (int axis = 0; same && axis < 2; ++axis)
      {
        const int side = mrgi_voxel_screen_side(p, q, parallel, axis);
        sides[axis] |= (side <= 0 ? 1 : 0) | (side >= 0 ? 2 : 0);
      }
      parent_kept = k == MRGI_VOXEL_NEIGHBOURS / 2 ? same : parent_kept;
      out[k++] = receiver ? masks + t * (size_t)words : NULL;
    }
  }
  *surrounded = sides[0] == 3 && sides[1] == 3;
  return parent_kept;
}

mrgi_status mrgi_voxel_visibility_pyramid(
  const mrgi_multires_layout* layout, const float* receiver_position,
  const float* receiver_normal, size_t receiver_floats, const mrgi_voxel_view* view,
  const mrgi_voxel_samples* samples, const uint8_t* refine, size_t refine_size,
  const mrgi_voxel_incremental_params* params, uint32_t* masks, size_t mask_words,
  mrgi_voxel_incremental_stats* stats, mrgi_error* err)
{
  mrgi_status status = mrgi_multires_layout_check(layout, err);
  if (status == MRGI_OK)
  {
    status = mrgi_voxel_view_check(view, err);
  }
  if (status == MRGI_OK)
  {
    status = mrgi_voxel_samples_check(samples, err);
  }
  if (status != MRGI_OK)
  {
    return status;
  }
  mrgi_voxel_incremental_params knobs;
  mrgi_voxel_incremental_params_default(&knobs);
  if (params)
  {
    knobs = *params;
  }
  if (knobs.interleave != 0 && knobs.interleave != 1)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "'interleave' is %d, not 0 or 1",
                          knobs.interleave);
  }
  if (knobs.metric != MRGI_VOXEL_METRIC_DISAGREE && knobs.metric != MRGI_VOXEL_METRIC_COUNT_SPREAD)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "unknown refinement metric %d",
                          knobs.metric);
  }
  const int32_t threshold = mrgi_voxel_refine_threshold(knobs.refine_fraction, samples->count);
  if (threshold < 0)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "refine fraction %g is outside [0, 1]", (double)knobs.refine_fraction);
  }
  const size_t texels = (size_t)mrgi_multires_texel_count(layout);
  const int32_t words = mrgi_voxel_mask_words(samples->count);
  if (!receiver_position || !receiver_normal || receiver_floats < 4 * texels)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "receiver arrays are NULL or hold %zu floats; the layout needs %zu",
                          receiver_floats, 4 * texels);
  }
  if (!masks || mask_words < texels * (size_t)words)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "mask array is NULL or holds %zu words; %zu texels x %d words needed",
                          mask_words, texels, words);
  }
  if (refine && refine_size < texels)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "refine mask holds %zu bytes; the layout needs %zu", refine_size,
                          texels);
  }
  size_t largest = 0;
  for (int32_t i = 0; i < layout->level_count; ++i)
  {
    const size_t n = (size_t)layout->level_width[i] * (size_t)layout->level_height[i];
    largest = n > largest ? n : largest;
  }
  uint8_t* computed = (uint8_t*)calloc(texels, 1);
  uint32_t* combined = (uint32_t*)malloc(largest * (size_t)words * sizeof(uint32_t));
  if (!computed || !combined)
  {
    free(computed);
    free(combined);
    return mrgi_error_set(err, MRGI_ERR_OUT_OF_MEMORY,
                          "cannot allocate visibility scratch (%zu texels x %d words)", largest,
                          words);
  }
  mrgi_voxel_incremental_stats s;
  memset(&s, 0, sizeof(s));
  memset(masks, 0, texels * (size_t)words * sizeof(uint32_t));
  const int32_t coarsest = layout->level_count - 1;
  const int parallel = view->projection.parallel != 0;

  for (int32_t i = coarsest; i >= 0; --i)
  {
    const int32_t lw = layout->level_width[i];
    const int32_t lh = layout->level_height[i];
    /* Pass 1: decide, then compute the own phase (or all) or inherit. */
    for (int32_t y = 0; y < lh; ++y)
    {
      for (int32_t x = 0; x < lw; ++x)
      {
        const size_t t = mrgi_multires_index(layout, i, x, y);
        const float* P;
        const float* N;
        if (!mrgi_voxel_receiver(receiver_position, receiver_normal, t, &P, &N))
        {
          continue;
        }
        uint32_t* mask = masks + t * (size_t)words;
        const uint32_t* neighbours[MRGI_VOXEL_NEIGHBOURS];
        int kept = 0;
        int surrounded = 1;
        int compute = i == coarsest;
        const int surround_rule = i >= MRGI_VOXEL_SURROUND_MIN_LEVEL;
        if (!compute)
        {
          /* Same-surface guard (section 3): t inherits only from a parent on
           * its surface, and reuses only with a neighbour on its surface;
           * the surround rule: it inherits only between kept receivers. */
          const int parent_kept = mrgi_voxel_gather_neighbours(
            layout, i + 1, x / 2, y / 2, receiver_position, receiver_normal, P, N, parallel, masks,
            words, neighbours, &kept, &surrounded);
          surrounded = surrounded || !surround_rule;
          mrgi_voxel_metric metric;
          mrgi_voxel_neighbourhood_metric(neighbours, words, &metric);
          compute = (refine && refine[t]) || !parent_kept || !surrounded ||
                    mrgi_voxel_needs_refinement(&metric, knobs.metric, threshold);
        }
        if (!compute)
        {
          const uint32_t* parent =
            masks + mrgi_multires_index(layout, i + 1, x / 2, y / 2) * (size_t)words;
          memcpy(mask, parent, (size_t)words * sizeof(uint32_t));
          ++s.inherited[i];
          continue;
        }
        computed[t] = 1;
        ++s.computed[i];
        const uint32_t phases =
          knobs.interleave ? 1u << (uint32_t)mrgi_voxel_interleave_phase(x, y)
                           : (uint32_t)MRGI_VOXEL_ALL_PHASES;
        s.rays[i] += mrgi_voxel_visibility(view, samples, P, N,
                                           i == coarsest || kept == 0 ? NULL : neighbours,
                                           surrounded, phases, mask);
      }
    }
    if (!knobs.interleave)
    {
      continue;
    }
    /* Pass 2: combine the quarters of each computed texel's 2x2 block. */
    for (int32_t y = 0; y < lh; ++y)
    {
      for (int32_t x = 0; x < lw; ++x)
      {
        const size_t t = mrgi_multires_index(layout, i, x, y);
        if (!computed[t])
        {
          continue;
        }
        const float* P;
        const float* N;
        mrgi_voxel_receiver(receiver_position, receiver_normal, t, &P, &N);
        const uint32_t* neighbours[MRGI_VOXEL_NEIGHBOURS];
        int kept = 0;
        int surrounded = 1;
        if (i != coarsest)
        {
          mrgi_voxel_gather_neighbours(layout, i + 1, x / 2, y / 2, receiver_position,
                                       receiver_normal, P, N, parallel, masks, words, neighbours,
                                       &kept, &surrounded);
          surrounded = surrounded || i < MRGI_VOXEL_SURROUND_MIN_LEVEL;
        }
        uint32_t* out = combined + ((size_t)y * (size_t)lw + (size_t)x) * (size_t)words;
        memset(out, 0, (size_t)words * sizeof(uint32_t));
        for (int32_t q = 0; q < MRGI_VOXEL_INTERLEAVE_PHASES; ++q)
        {
          const int32_t bx = (x & ~1) | (q & 1);
          const int32_t by = (y & ~1) | (q >> 1);
          const uint32_t phase_bits = mrgi_voxel_phase_word_mask(1u << (uint32_t)q);
          const size_t source = bx < lw && by < lh ? mrgi_multires_index(layout, i, bx, by) : 0;
          const float* Q;
          const float* M;
          if (bx < lw && by < lh && computed[source] &&
              (source == t ||
               (mrgi_voxel_receiver(receiver_position, receiver_normal, source, &Q, &M) &&
                mrgi_voxel_same_surface(P, N, Q, M))))
          {
            const uint32_t* from = masks + source * (size_t)words;
            for (int32_t w = 0; w < words; ++w)
            {
              out[w] |= from[w] & phase_bits;
            }
          }
          else
          {
            uint32_t own[MRGI_VOXEL_MAX_MASK_WORDS];
            s.rays[i] += mrgi_voxel_visibility(view, samples, P, N,
                                               i == coarsest || kept == 0 ? NULL : neighbours,
                                               surrounded, 1u << (uint32_t)q, own);
            for (int32_t w = 0; w < words; ++w)
            {
              out[w] |= own[w];
            }
          }
        }
      }
    }
    for (int32_t y = 0; y < lh; ++y)
    {
      for (int32_t x = 0; x < lw; ++x)
      {
        const size_t t = mrgi_multires_index(layout, i, x, y);
        if (computed[t])
        {
          memcpy(masks + t * (size_t)words,
                 combined + ((size_t)y * (size_t)lw + (size_t)x) * (size_t)words,
                 (size_t)words * sizeof(uint32_t));
        }
      }
    }
  }
  for (int32_t i = 0; i < layout->level_count; ++i)
  {
    s.rays_total += s.rays[i];
  }
  for (int32_t y = 0; y < layout->level_height[0]; ++y)
  {
    for (int32_t x = 0; x < layout->level_width[0]; ++x)
    {
      const float* P;
      const float* N;
      if (mrgi_voxel_receiver(receiver_position, receiver_normal,
                              mrgi_multires_index(layout, 0, x, y), &P, &N))
      {
        s.rays_naive += samples->count;
      }
    }
  }
  free(computed);
  free(combined);
  if (stats)
  {
    *stats = s;
  }
  return MRGI_OK;
}
