// MRGI incremental voxel-space visibility, coarse to fine over the
// multiresolution levels (nichols-penmatsa-wyman-2010 sections 3.3.2 and
// 3.4). GPU side of mrgi_voxel_visibility_pyramid() (Rendering/Core/Twins/
// mrgi_visibility_pyramid.h, whose file comment is the contract: sample masks,
// the naive and incremental rules, COMPUTED/INHERITED texels, the bit-count
// metric, 2x2 interleaving with the same-surface test); every function below
// translates its C counterpart in the same order. One ray is mrgiVoxelVisible()
// (vtkMRGIVoxelMarch.glsl, prepended with the core's constants block).
//
// vtkMRGIVisibilityPyramid prepends, besides the march library:
//   MRGI_VIS_STAGE    0: decide, then inherit or compute the own phase (all
//                        phases without interleaving); 1: combine the 2x2
//                        quarters (interleaving), re-marching the phases no
//                        block texel on the same surface computed; 2: count
//                        the rays stages 0 and 1 march (no march).
//                        Without interleaving stage 0 is split in three so
//                        that the marches skip the texels with nothing to
//                        march (early stencil culling, NPW10 section 4: "early
//                        stencil culling (to cull unnecessary fragments)"):
//                        3: decide, write the final mask of INHERITED texels
//                        and the reused bits of COMPUTED ones, and the bits
//                        left to march ("todo", targets T..2T-1); 5: set the
//                        stencil where some bit is left (discard elsewhere);
//                        4: under that stencil, march the todo bits (read
//                        through mrgiVisQuarterK) of this draw's samples,
//                        ORed into the masks. Stages 3+5+4 write exactly
//                        what stage 0 writes.
//                        On small levels stages 5 and 4 run over COPIES of the
//                        level side by side (mrgiVisCopyStride > 0): copy c
//                        marches samples [c range, (c + 1) range) in one draw,
//                        instead of one draw per range over the level alone
//                        (llvmpipe shades a 64x64 tile on one thread: a
//                        16 x 16 level kept one core busy); 6: OR the copies
//                        (read through mrgiVisQuarterK) into the masks.
//   MRGI_VIS_WORDS    W = ceil(N / 32) mask words
//   MRGI_VIS_TARGETS  T = ceil(W / 4) RGBA32UI mask targets
//   MRGI_VIS_OUTPUTS  outputs: T (stages 0, 1, 4), 2T (stage 3), 1 (2, 5)
// and declares the outputs `out uvec4 fragOutputK` itself (word w in target
// w / 4, channel w % 4).
//
// One draw per level (x batches): every fragment is level-i texel
// ivec2(gl_FragCoord.xy). Only samples j in [mrgiVisFirst, mrgiVisLast) are
// marched by a draw; every other bit a draw writes (reused, inherited,
// combined) is the same in every batch, so the batches are ORed together
// (glLogicOp(GL_OR), the first draw without) and each draw's marches fit
// llvmpipe's loop budget (mrgi_voxel_samples_per_batch()).
in vec2 texCoord; // bound by vtkOpenGLQuadHelper; texels are addressed by gl_FragCoord

// Receivers of level i: texel t at t + mrgiVisReceiverOffset. mrgiVisGBuffer:
// level 0 is the raw G-buffer, made a receiver as vtkMRGIMultiresReceiversFS
// stage 0 does (mrgi_multires_receivers_build()).
uniform sampler2D mrgiVisPosition;
uniform sampler2D mrgiVisNormal;
uniform ivec2 mrgiVisReceiverOffset;
uniform int mrgiVisGBuffer;
uniform ivec2 mrgiVisLevelSize;
uniform int mrgiVisLevel; // i
// Level i+1 (unused on the naive levels): receivers (the same-surface guard
// reads both) and final masks.
uniform sampler2D mrgiVisParentPosition;
uniform sampler2D mrgiVisParentNormal;
uniform ivec2 mrgiVisParentOffset;
uniform ivec2 mrgiVisParentSize;
uniform usampler2D mrgiVisParent0;
uniform usampler2D mrgiVisParent1;
uniform usampler2D mrgiVisParent2;
uniform usampler2D mrgiVisParent3;
// Stage 1: stage 0's masks of level i (own phase only).
uniform usampler2D mrgiVisQuarter0;
uniform usampler2D mrgiVisQuarter1;
uniform usampler2D mrgiVisQuarter2;
uniform usampler2D mrgiVisQuarter3;
// 1: every receiver is COMPUTED with no coarse masks (coarsest level, or
// incremental visibility off: the naive query everywhere).
uniform int mrgiVisNaive;
uniform int mrgiVisThreshold;  // mrgi_voxel_refine_threshold()
uniform int mrgiVisMetric;     // MRGI_VOXEL_METRIC_*
uniform int mrgiVisInterleave; // 0 or 1
// Optional refine mask: the multiresolution selection (flattened, red > 0.5).
uniform int mrgiVisRefine;
uniform sampler2D mrgiVisSelection;
uniform int mrgiVisLevelOffset; // level i's x offset in the flattened layout
// Light samples: mrgi_area_light_sample records in world space, as
// vtkMRGIAreaLightDiffuse.glsl reads them, and the world -> eye matrix.
uniform sampler2D mrgiVisSamples;
uniform mat4 mrgiVisWCToVC;
uniform int mrgiVisTwoSided;
uniform int mrgiVisSampleCount; // N
uniform int mrgiVisFirst;       // this draw marches samples [first, last)
uniform int mrgiVisLast;
// Stages 4-6 on copies: the copies' x stride (0: no copies), the samples
// per copy, and (stage 6) the number of copies.
uniform int mrgiVisCopyStride;
uniform int mrgiVisCopyRange;
uniform int mrgiVisCopies;
// The samples this fragment marches: [mrgiVisFirst, mrgiVisLast), or its
// copy's range (set in main()).
int mrgiVisBatchFirst;
int mrgiVisBatchLast;

out uvec4 fragOutput0;
#if MRGI_VIS_OUTPUTS > 1
out uvec4 fragOutput1;
#endif
#if MRGI_VIS_OUTPUTS > 2
out uvec4 fragOutput2;
#endif
#if MRGI_VIS_OUTPUTS > 3
out uvec4 fragOutput3;
#endif
#if MRGI_VIS_OUTPUTS > 4
out uvec4 fragOutput4;
#endif
#if MRGI_VIS_OUTPUTS > 5
out uvec4 fragOutput5;
#endif
#if MRGI_VIS_OUTPUTS > 6
out uvec4 fragOutput6;
#endif
#if MRGI_VIS_OUTPUTS > 7
out uvec4 fragOutput7;
#endif

// mrgiVisPopcount(): vtkMRGIVisibilityBits.glsl, prepended.

// mrgi_voxel_phase_word_mask()
uint mrgiVisPhaseBits(int phaseSet)
{
  return uint(phaseSet & 15) * 0x11111111u;
}

// mrgi_voxel_valid_bits(): bits of word w that hold samples.
uint mrgiVisValidBits(int w)
{
  int rest = mrgiVisSampleCount - 32 * w;
  return rest >= 32 ? 0xFFFFFFFFu : ((1u << uint(max(rest, 0))) - 1u);
}

bool mrgiVisFinite(vec3 v)
{
  return !any(isnan(v)) && !any(isinf(v));
}

// vtkMRGIMultiresReceiversFS's mrgiNormalize().
vec3 mrgiVisNormalize(vec3 n)
{
  float length2 = n.x * n.x + n.y * n.y + n.z * n.z;
  if (!(length2 > MRGI_MULTIRES_MIN_PIXEL_SIZE)) { length2 = MRGI_MULTIRES_MIN_PIXEL_SIZE; }
  return n * (1.0 / sqrt(length2));
}

// mrgi_voxel_receiver(): level-i texel t; N = 0 without a usable normal.
bool mrgiVisReceiver(ivec2 t, out vec3 P, out vec3 N)
{
  vec4 p = texelFetch(mrgiVisPosition, t + mrgiVisReceiverOffset, 0);
  vec3 n = texelFetch(mrgiVisNormal, t + mrgiVisReceiverOffset, 0).xyz;
  if (mrgiVisGBuffer != 0)
  {
    bool valid = p.w > MRGI_GBUFFER_VALID_THRESHOLD && mrgiVisFinite(p.xyz) && mrgiVisFinite(n);
    p = valid ? vec4(p.xyz, 1.0) : vec4(0.0);
    n = valid ? mrgiVisNormalize(n) : vec3(0.0);
  }
  P = p.xyz;
  N = vec3(0.0);
  if (!(p.w > MRGI_GBUFFER_VALID_THRESHOLD) || !mrgiVisFinite(p.xyz))
  {
    return false;
  }
  if (mrgiVisFinite(n) && (n.x != 0.0 || n.y != 0.0 || n.z != 0.0))
  {
    N = n;
  }
  return true;
}

// mrgi_voxel_same_surface(), squared, without divisions, in the C's order.
bool mrgiVisSameSurface(vec3 p, vec3 n, vec3 q, vec3 m)
{
  float nn = n.x * n.x + n.y * n.y + n.z * n.z;
  float mm = m.x * m.x + m.y * m.y + m.z * m.z;
  if (nn == 0.0 || mm == 0.0)
  {
    return false; // a missing normal (the C's NULL)
  }
  float nm = n.x * m.x + n.y * m.y + n.z * m.z;
  if (!(nm > 0.0 && nm * nm >= MRGI_VOXEL_INTERLEAVE_MIN_COS * MRGI_VOXEL_INTERLEAVE_MIN_COS * nn * mm))
  {
    return false;
  }
  vec3 d = vec3(q.x - p.x, q.y - p.y, q.z - p.z);
  float dd = d.x * d.x + d.y * d.y + d.z * d.z;
  float nd = n.x * d.x + n.y * d.y + n.z * d.z;
  float md = m.x * d.x + m.y * d.y + m.z * d.z;
  float s2 = MRGI_VOXEL_INTERLEAVE_MAX_SLOPE * MRGI_VOXEL_INTERLEAVE_MAX_SLOPE;
  return nd * nd <= s2 * dd * nn && md * md <= s2 * dd * mm;
}

// mrgi_voxel_screen_side(): where q lies on screen from p along `axis`
// (1 after, -1 before, 0 same place), in the C's expression order.
int mrgiVisScreenSide(vec3 p, vec3 q, int axis)
{
  if (q == p)
  {
    return 0;
  }
  float d = mrgiVoxelParallel != 0 ? q[axis] - p[axis] : p[axis] * q.z - q[axis] * p.z;
  return d > 0.0 ? 1 : (d < 0.0 ? -1 : 0);
}

// Per axis, bit 0: a kept receiver q at or before p on screen, bit 1: at or after.
ivec2 mrgiVisSides(vec3 p, vec3 q)
{
  int sx = mrgiVisScreenSide(p, q, 0);
  int sy = mrgiVisScreenSide(p, q, 1);
  return ivec2((sx <= 0 ? 1 : 0) | (sx >= 0 ? 2 : 0), (sy <= 0 ? 1 : 0) | (sy >= 0 ? 2 : 0));
}

// mrgi_voxel_receiver() at level-(i+1) texel s (never the G-buffer); M = 0
// without a usable normal.
bool mrgiVisParentReceiver(ivec2 s, out vec3 Q, out vec3 M)
{
  vec4 q = texelFetch(mrgiVisParentPosition, s + mrgiVisParentOffset, 0);
  vec3 m = texelFetch(mrgiVisParentNormal, s + mrgiVisParentOffset, 0).xyz;
  Q = q.xyz;
  M = vec3(0.0);
  if (!(q.w > MRGI_GBUFFER_VALID_THRESHOLD) || !mrgiVisFinite(q.xyz))
  {
    return false;
  }
  if (mrgiVisFinite(m) && (m.x != 0.0 || m.y != 0.0 || m.z != 0.0))
  {
    M = m;
  }
  return true;
}

// A mask of level i+1 (parent != 0) or stage 0's level-i masks.
void mrgiVisFetch(bool parent, ivec2 p, out uint m[MRGI_VIS_WORDS])
{
  uint w4[4 * MRGI_VIS_TARGETS];
  uvec4 v = parent ? texelFetch(mrgiVisParent0, p, 0) : texelFetch(mrgiVisQuarter0, p, 0);
  w4[0] = v.x; w4[1] = v.y; w4[2] = v.z; w4[3] = v.w;
#if MRGI_VIS_TARGETS > 1
  v = parent ? texelFetch(mrgiVisParent1, p, 0) : texelFetch(mrgiVisQuarter1, p, 0);
  w4[4] = v.x; w4[5] = v.y; w4[6] = v.z; w4[7] = v.w;
#endif
#if MRGI_VIS_TARGETS > 2
  v = parent ? texelFetch(mrgiVisParent2, p, 0) : texelFetch(mrgiVisQuarter2, p, 0);
  w4[8] = v.x; w4[9] = v.y; w4[10] = v.z; w4[11] = v.w;
#endif
#if MRGI_VIS_TARGETS > 3
  v = parent ? texelFetch(mrgiVisParent3, p, 0) : texelFetch(mrgiVisQuarter3, p, 0);
  w4[12] = v.x; w4[13] = v.y; w4[14] = v.z; w4[15] = v.w;
#endif
  for (int w = 0; w < MRGI_VIS_WORDS; ++w)
  {
    m[w] = w4[w];
  }
}

#if MRGI_VIS_STAGE != 2 && MRGI_VIS_STAGE != 5
void mrgiVisWrite(uint m[MRGI_VIS_WORDS])
{
  uint w4[4 * MRGI_VIS_TARGETS];
  for (int w = 0; w < 4 * MRGI_VIS_TARGETS; ++w)
  {
    w4[w] = w < MRGI_VIS_WORDS ? m[min(w, MRGI_VIS_WORDS - 1)] : 0u;
  }
  fragOutput0 = uvec4(w4[0], w4[1], w4[2], w4[3]);
#if MRGI_VIS_TARGETS > 1
  fragOutput1 = uvec4(w4[4], w4[5], w4[6], w4[7]);
#endif
#if MRGI_VIS_TARGETS > 2
  fragOutput2 = uvec4(w4[8], w4[9], w4[10], w4[11]);
#endif
#if MRGI_VIS_TARGETS > 3
  fragOutput3 = uvec4(w4[12], w4[13], w4[14], w4[15]);
#endif
}
#endif

#if MRGI_VIS_STAGE == 3
// Stage 3's second half: the bits left to march, in targets T..2T-1.
void mrgiVisWriteTodo(uint m[MRGI_VIS_WORDS])
{
  uint w4[4 * MRGI_VIS_TARGETS];
  for (int w = 0; w < 4 * MRGI_VIS_TARGETS; ++w)
  {
    w4[w] = w < MRGI_VIS_WORDS ? m[min(w, MRGI_VIS_WORDS - 1)] : 0u;
  }
#if MRGI_VIS_TARGETS == 1
  fragOutput1 = uvec4(w4[0], w4[1], w4[2], w4[3]);
#elif MRGI_VIS_TARGETS == 2
  fragOutput2 = uvec4(w4[0], w4[1], w4[2], w4[3]);
  fragOutput3 = uvec4(w4[4], w4[5], w4[6], w4[7]);
#elif MRGI_VIS_TARGETS == 3
  fragOutput3 = uvec4(w4[0], w4[1], w4[2], w4[3]);
  fragOutput4 = uvec4(w4[4], w4[5], w4[6], w4[7]);
  fragOutput5 = uvec4(w4[8], w4[9], w4[10], w4[11]);
#else
  fragOutput4 = uvec4(w4[0], w4[1], w4[2], w4[3]);
  fragOutput5 = uvec4(w4[4], w4[5], w4[6], w4[7]);
  fragOutput6 = uvec4(w4[8], w4[9], w4[10], w4[11]);
  fragOutput7 = uvec4(w4[12], w4[13], w4[14], w4[15]);
#endif
}
#endif

// The coarse neighbours of level-i texel t with receiver (P, N)
// (mrgi_voxel_gather_neighbours(): the level-(i+1) 3x3 around the parent,
// clamped, non-receivers skipped), folded into per-word AND and OR, and the
// refinement decision they make (mrgi_voxel_neighbourhood_metric() +
// mrgi_voxel_needs_refinement()). The same-surface guard (mrgi_voxel_
// incremental.h section 3): have = at least one neighbour is on t's surface
// (else nothing is reused), parentKept = the parent (the centre) is,
// surrounded = the kept neighbours surround P on screen (the surround rule,
// mrgi_visibility_pyramid.h section 3). On naive levels: no neighbours,
// every receiver refines.
bool mrgiVisNeighbours(ivec2 t, vec3 P, vec3 N, out uint all[MRGI_VIS_WORDS],
  out uint any_[MRGI_VIS_WORDS], out bool have, out bool parentKept, out bool surrounded)
{
  surrounded = true;
  for (int w = 0; w < MRGI_VIS_WORDS; ++w)
  {
    all[w] = 0xFFFFFFFFu;
    any_[w] = 0u;
  }
  have = false;
  parentKept = false;
  if (mrgiVisNaive != 0)
  {
    return true;
  }
  ivec2 c = t / 2;
  int countMin = 0;
  int countMax = 0;
  bool any_receiver = false;
  bool kept = false;
  ivec2 sides = ivec2(0);
  for (int k = 0; k < MRGI_VOXEL_NEIGHBOURS; ++k)
  {
    ivec2 s = clamp(c + ivec2(k % 3 - 1, k / 3 - 1), ivec2(0), mrgiVisParentSize - 1);
    vec3 Q;
    vec3 M;
    if (!mrgiVisParentReceiver(s, Q, M))
    {
      continue;
    }
    bool same = mrgiVisSameSurface(P, N, Q, M);
    kept = kept || same;
    if (same)
    {
      sides |= mrgiVisSides(P, Q);
    }
    if (k == MRGI_VOXEL_NEIGHBOURS / 2)
    {
      parentKept = same;
    }
    uint m[MRGI_VIS_WORDS];
    mrgiVisFetch(true, s, m);
    int count = 0;
    for (int w = 0; w < MRGI_VIS_WORDS; ++w)
    {
      all[w] &= m[w];
      any_[w] |= m[w];
      count += int(mrgiVisPopcount(m[w]));
    }
    countMin = any_receiver ? min(countMin, count) : count;
    countMax = any_receiver ? max(countMax, count) : count;
    any_receiver = true;
  }
  int disagree = 0;
  for (int w = 0; w < MRGI_VIS_WORDS; ++w)
  {
    disagree += int(mrgiVisPopcount(any_[w] & ~all[w]));
  }
  if (!any_receiver)
  {
    disagree = 0;
  }
  // No neighbour on t's surface: nothing is reused (every wanted bit marched).
  have = kept;
  surrounded = sides == ivec2(3) || mrgiVisLevel < MRGI_VOXEL_SURROUND_MIN_LEVEL;
  int value = mrgiVisMetric == MRGI_VOXEL_METRIC_COUNT_SPREAD ? countMax - countMin : disagree;
  return value >= mrgiVisThreshold;
}

bool mrgiVisRefined(ivec2 t)
{
  return mrgiVisRefine != 0 &&
    texelFetch(mrgiVisSelection, ivec2(t.x + mrgiVisLevelOffset, t.y), 0).r > 0.5;
}

// Whether level-i texel t (receiver P, N) inherits when the metric does not
// fire: its parent is on its surface (the guard) and its kept coarse
// neighbours surround it (the surround rule), as mrgiVisNeighbours() finds them.
bool mrgiVisMayInherit(ivec2 t, vec3 P, vec3 N)
{
  vec3 Q;
  vec3 M;
  if (!mrgiVisParentReceiver(t / 2, Q, M) || !mrgiVisSameSurface(P, N, Q, M))
  {
    return false;
  }
  ivec2 sides = ivec2(0);
  for (int k = 0; k < MRGI_VOXEL_NEIGHBOURS; ++k)
  {
    ivec2 s = clamp(t / 2 + ivec2(k % 3 - 1, k / 3 - 1), ivec2(0), mrgiVisParentSize - 1);
    if (mrgiVisParentReceiver(s, Q, M) && mrgiVisSameSurface(P, N, Q, M))
    {
      sides |= mrgiVisSides(P, Q);
    }
  }
  return sides == ivec2(3) || mrgiVisLevel < MRGI_VOXEL_SURROUND_MIN_LEVEL;
}

// Whether light sample j is visible from receiver (P, N): the area-light
// gather's transform (vtkMRGIAreaLightDiffuse.glsl), then the march.
bool mrgiVisSampleVisible(int j, vec3 P, vec3 N)
{
  vec4 position = texelFetch(mrgiVisSamples, ivec2(MRGI_AREA_LIGHT_SAMPLE_TEXEL_POSITION, j), 0);
  vec3 sampleNormal = texelFetch(mrgiVisSamples, ivec2(MRGI_AREA_LIGHT_SAMPLE_TEXEL_NORMAL, j), 0).xyz;
  vec3 L = (mrgiVisWCToVC * vec4(position.xyz, 1.0)).xyz;
  vec3 NL = mat3(mrgiVisWCToVC) * sampleNormal;
  // A two-sided light emits from the side facing the receiver.
  if (mrgiVisTwoSided != 0 && mrgiVoxelDot(NL, P - L) < 0.0) { NL = -NL; }
  return mrgiVoxelVisible(P, N, L, NL);
}

// mrgi_voxel_visibility() for one word: the bits of `wanted`, reused where
// the coarse neighbours agree, the others marched (this draw's samples only).
// rays (stage 2): the bits that are marched, over all draws.
// phase >= 0: `wanted` holds only that phase's bits, and the loop visits
// only them (b = phase mod 4), so that fragments of different phases march
// in lockstep: llvmpipe runs a SIMD group of fragments through the union of
// their loop iterations, and its loop budget counts them (the batch sizes of
// vtkMRGIVisibilityPyramid assume this).
// The bits of `todo` (word w) among this draw's samples that the march
// finds visible.
uint mrgiVisMarchBits(int w, uint todo, vec3 P, vec3 N, int phase)
{
  uint result = 0u;
  int lo = max(mrgiVisBatchFirst - 32 * w, 0);
  int hi = min(mrgiVisBatchLast - 32 * w, 32);
  int step = phase >= 0 ? MRGI_VOXEL_INTERLEAVE_PHASES : 1;
  if (phase >= 0)
  {
    lo += (phase - lo) & 3; // first b >= lo of the phase (32 w is a multiple of 4)
  }
  for (int b = lo; b < hi; b += step)
  {
    if (((todo >> uint(b)) & 1u) != 0u && mrgiVisSampleVisible(32 * w + b, P, N))
    {
      result |= 1u << uint(b);
    }
  }
  return result;
}

// reuseHidden: mrgi_voxel_visibility()'s reuse_hidden (false: only the bits
// all neighbours agree are visible are reused).
uint mrgiVisWord(int w, uint wanted, uint all, uint any_, bool have, bool reuseHidden, vec3 P,
  vec3 N, int phase, out uint marched)
{
  uint agree = !have ? 0u : (reuseHidden ? wanted & ~(all ^ any_) : wanted & all);
  uint result = all & agree;
  uint todo = wanted & ~agree;
  marched = todo;
#if MRGI_VIS_STAGE != 2 && MRGI_VIS_STAGE != 3
  result |= mrgiVisMarchBits(w, todo, P, N, phase);
#endif
  return result;
}

void main()
{
  ivec2 t = ivec2(gl_FragCoord.xy);
  uint mask[MRGI_VIS_WORDS];
  for (int w = 0; w < MRGI_VIS_WORDS; ++w)
  {
    mask[w] = 0u;
  }
  mrgiVisBatchFirst = mrgiVisFirst;
  mrgiVisBatchLast = mrgiVisLast;
#if MRGI_VIS_STAGE == 6
  // OR the copies' bits of texel t.
  for (int c = 0; c < mrgiVisCopies; ++c)
  {
    uint copy[MRGI_VIS_WORDS];
    mrgiVisFetch(false, ivec2(t.x + c * mrgiVisCopyStride, t.y), copy);
    for (int w = 0; w < MRGI_VIS_WORDS; ++w)
    {
      mask[w] |= copy[w];
    }
  }
  mrgiVisWrite(mask);
#elif MRGI_VIS_STAGE == 4 || MRGI_VIS_STAGE == 5
  if (mrgiVisCopyStride > 0)
  {
    // Copy c of the level: texel t, samples [c range, (c + 1) range).
    int c = t.x / mrgiVisCopyStride;
    t.x -= c * mrgiVisCopyStride;
    mrgiVisBatchFirst = c * mrgiVisCopyRange;
    mrgiVisBatchLast = min(mrgiVisBatchFirst + mrgiVisCopyRange, mrgiVisSampleCount);
    if (t.x >= mrgiVisLevelSize.x)
    {
      discard; // padding between copies
    }
  }
  // After stage 3: the todo bits of this texel.
  uint todo[MRGI_VIS_WORDS];
  mrgiVisFetch(false, t, todo);
#if MRGI_VIS_STAGE == 5
  uint left = 0u;
  for (int w = 0; w < MRGI_VIS_WORDS; ++w)
  {
    left |= todo[w];
  }
  if (left == 0u)
  {
    discard;
  }
  fragOutput0 = uvec4(0u);
#else
  vec3 P4;
  vec3 N4;
  mrgiVisReceiver(t, P4, N4);
  for (int w = 0; w < MRGI_VIS_WORDS; ++w)
  {
    mask[w] = mrgiVisMarchBits(w, todo[w], P4, N4, -1);
  }
  mrgiVisWrite(mask);
#endif
#else
  uint todo[MRGI_VIS_WORDS];
  for (int w = 0; w < MRGI_VIS_WORDS; ++w)
  {
    todo[w] = 0u;
  }
  vec3 P;
  vec3 N;
  bool receiver = mrgiVisReceiver(t, P, N);
  uint all[MRGI_VIS_WORDS];
  uint any_[MRGI_VIS_WORDS];
  bool have = false;
  bool parentKept = false;
  bool surrounded = true;
  bool fires = receiver && mrgiVisNeighbours(t, P, N, all, any_, have, parentKept, surrounded);
  // COMPUTED (mrgi_voxel_visibility_pyramid pass 1): naive level, the metric
  // fires, the parent is not on t's surface (the guard), the kept
  // neighbours do not surround t (the surround rule), or forced.
  bool computed = receiver &&
    (fires || mrgiVisNaive != 0 || !parentKept || !surrounded || mrgiVisRefined(t));
  uint rays = 0u;
  if (receiver && !computed)
  {
    // INHERITED: the parent's final mask (NPW10 3.4 step 3, upsampled).
    mrgiVisFetch(true, t / 2, mask);
  }
  else if (computed)
  {
    int own = mrgiVisInterleave != 0 ? ((t.x & 1) | ((t.y & 1) << 1)) : -1;
#if MRGI_VIS_STAGE == 0 || MRGI_VIS_STAGE == 2 || MRGI_VIS_STAGE == 3
    // Stage 0 (and its ray count, and stage 3 without the march): the own
    // phase, or every phase.
    uint phaseBits = own >= 0 ? mrgiVisPhaseBits(1 << own) : mrgiVisPhaseBits(MRGI_VOXEL_ALL_PHASES);
    for (int w = 0; w < MRGI_VIS_WORDS; ++w)
    {
      uint marched;
      mask[w] = mrgiVisWord(w, phaseBits & mrgiVisValidBits(w), all[w], any_[w], have, surrounded,
        P, N, own, marched);
      todo[w] = marched;
      rays += mrgiVisPopcount(marched);
    }
#endif
#if MRGI_VIS_STAGE == 1 || MRGI_VIS_STAGE == 2
    if (own >= 0)
    {
#if MRGI_VIS_STAGE == 1
      for (int w = 0; w < MRGI_VIS_WORDS; ++w)
      {
        mask[w] = 0u;
      }
#endif
      // Stage 1: phase q from the block texel u that computed it on the same
      // surface, else re-marched here (mrgi_voxel_visibility_pyramid pass 2).
      for (int q = 0; q < MRGI_VOXEL_INTERLEAVE_PHASES; ++q)
      {
        ivec2 u = ivec2((t.x & ~1) | (q & 1), (t.y & ~1) | (q >> 1));
        bool take = false;
        if (u.x < mrgiVisLevelSize.x && u.y < mrgiVisLevelSize.y)
        {
          if (u == t)
          {
            take = true;
          }
          else
          {
            vec3 Q;
            vec3 M;
            // u shares t's parent: the same neighbourhood, the same metric;
            // whether its parent is on its surface is u's own (the guard).
            take = mrgiVisReceiver(u, Q, M) && mrgiVisSameSurface(P, N, Q, M) &&
              (fires || mrgiVisNaive != 0 || mrgiVisRefined(u) || !mrgiVisMayInherit(u, Q, M));
          }
        }
        uint phaseBits = mrgiVisPhaseBits(1 << q);
#if MRGI_VIS_STAGE == 1
        if (take)
        {
          uint quarter[MRGI_VIS_WORDS];
          mrgiVisFetch(false, u, quarter);
          for (int w = 0; w < MRGI_VIS_WORDS; ++w)
          {
            mask[w] |= quarter[w] & phaseBits;
          }
          continue;
        }
#else
        if (take)
        {
          continue;
        }
#endif
        for (int w = 0; w < MRGI_VIS_WORDS; ++w)
        {
          uint marched;
          uint bits = mrgiVisWord(w, phaseBits & mrgiVisValidBits(w), all[w], any_[w], have,
            surrounded, P, N, q, marched);
#if MRGI_VIS_STAGE == 1
          mask[w] |= bits;
#endif
          rays += mrgiVisPopcount(marched);
        }
      }
    }
#endif
  }
#if MRGI_VIS_STAGE == 2
  fragOutput0 = uvec4(rays, computed ? 1u : 0u, receiver && !computed ? 1u : 0u, receiver ? 1u : 0u);
#else
  mrgiVisWrite(mask);
#endif
#if MRGI_VIS_STAGE == 3
  mrgiVisWriteTodo(todo);
#endif
#endif
}
