// MRGI incremental stencil rendering (nichols-penmatsa-wyman-2010 3.4): the
// area-light gather's stencil, where a level also renders below the
// geometric cut when its parent's 3x3 of visibility masks shows a light
// discontinuity. GPU side of mrgi_incremental_stencil_build()
// (Rendering/Core/Twins/mrgi_incremental_stencil.h, whose file comment is the
// contract); the metric is mrgi_voxel_neighbourhood_metric() as the
// visibility pyramid computes it (mrgiVisPopcount from
// vtkMRGIVisibilityBits.glsl, prepended).
//
// vtkMRGIIncrementalStencil prepends MRGI_STENCIL_WORDS (W = ceil(N / 32)) and
// MRGI_STENCIL_TARGETS (ceil(W / 4) mask textures per level). One draw per
// level i, into level i's rectangle of the flattened layout: a rendered
// texel writes 1 (and the stencil), any other is discarded (the target is
// cleared to 0 first).
//
// The irradiance term (mrgi_irradiance_stencil.h, the contract; C twin
// mrgi_irradiance_stencil_add()): a texel is also rendered where the
// light's unshadowed irradiance, estimated on a
// MRGI_IRRADIANCE_STENCIL_GRID^2 grid of cells, varies over the parent's 3x3
// by more than mrgiIrradianceTolerance of its maximum (0 turns it off).
//
// With MRGI_STENCIL_ILLUMINATION (the indirect light's rule,
// mrgi_incremental_stencil_illumination_level()) the parent's discontinuity
// is read from the irradiance level i+1 gathered (the gather's flattened
// target: alpha 1 where it drew a receiver), one draw per level between the
// gathers of levels i+1 and i; no masks and no irradiance term.
in vec2 texCoord; // bound by vtkOpenGLQuadHelper; texels are addressed by gl_FragCoord
//VTK::Output::Dec

uniform sampler2D mrgiFlags;          // level i's flags (red, level-local)
uniform sampler2D mrgiSelection;      // the flattened geometric selection (red > 0.5)
uniform sampler2D mrgiParentPosition; // level i+1 receivers (level-local; w = validity)
#ifdef MRGI_STENCIL_ILLUMINATION
uniform sampler2D mrgiParentIrradiance; // the flattened irradiance (level i+1 gathered)
uniform int mrgiParentOffset;           // o_{i+1}
uniform float mrgiIlluminationThreshold; // T >= 0
uniform int mrgiIlluminationMetric;      // MRGI_INCREMENTAL_ILLUMINATION_*
#else
uniform usampler2D mrgiParentMask0;   // level i+1 masks: word w in texture w / 4, channel w % 4
uniform usampler2D mrgiParentMask1;
uniform usampler2D mrgiParentMask2;
uniform usampler2D mrgiParentMask3;
#endif
uniform int mrgiLevelOffset;   // o_i
uniform ivec2 mrgiParentSize;  // w_{i+1}, h_{i+1}
uniform int mrgiFinest;        // 1 when i is the finest gathering level
uniform int mrgiCoarsest;      // 1 when i is the coarsest level (no parent)
#ifndef MRGI_STENCIL_ILLUMINATION
uniform int mrgiThreshold;     // >= 0
uniform int mrgiMetric;        // MRGI_VOXEL_METRIC_*
uniform sampler2D mrgiParentNormal;   // level i+1 receiver normals (level-local, eye space)
uniform mat4 mrgiVCToWC;              // eye -> world (column major, as the twin's matrix)
uniform float mrgiIrradianceTolerance; // tau in [0, 1]; 0: off
uniform vec3 mrgiAreaCenter;          // the light, world space (::mrgi_area_light_uniforms)
uniform vec3 mrgiAreaNormal;
uniform vec3 mrgiAreaCorners[4];
uniform float mrgiAreaArea;
uniform int mrgiAreaTwoSided;
#endif

bool mrgiStencilReceiver(ivec2 s)
{
  vec4 p = texelFetch(mrgiParentPosition, s, 0);
  return p.w > MRGI_GBUFFER_VALID_THRESHOLD && !any(isnan(p.xyz)) && !any(isinf(p.xyz));
}

#ifdef MRGI_STENCIL_ILLUMINATION
// usable_{i+1}(s): gathered (alpha) and a receiver.
bool mrgiStencilUsable(ivec2 s, out vec3 E)
{
  vec4 e = texelFetch(mrgiParentIrradiance, ivec2(s.x + mrgiParentOffset, s.y), 0);
  E = e.rgb;
  return e.a > 0.5 && mrgiStencilReceiver(s);
}

bool mrgiStencilDiffers(float En, float Ep)
{
  return abs(En - Ep) > mrgiIlluminationThreshold * max(En, Ep);
}

// F_{i+1}(c) of the illumination rule (DIFFERENCE: a usable neighbour in
// the 3x3, clamped, differs by more than T times the larger value in a
// channel; CURVATURE: c deviates from the line through two opposite
// usable neighbours, lines leaving the level skipped, or differs from the
// one usable neighbour of a line).
bool mrgiStencilDiscontinuity(ivec2 c)
{
  vec3 Ep;
  if (!mrgiStencilUsable(c, Ep))
  {
    return false;
  }
  if (mrgiIlluminationThreshold == 0.0)
  {
    return true;
  }
  if (mrgiIlluminationMetric == MRGI_INCREMENTAL_ILLUMINATION_CURVATURE)
  {
    ivec2 axes[4] = ivec2[4](ivec2(1, 0), ivec2(0, 1), ivec2(1, 1), ivec2(1, -1));
    for (int k = 0; k < 4; ++k)
    {
      ivec2 a = c - axes[k];
      ivec2 b = c + axes[k];
      if (a.x < 0 || a.y < 0 || a.y >= mrgiParentSize.y || b.x >= mrgiParentSize.x || b.y < 0 ||
        b.y >= mrgiParentSize.y)
      {
        continue;
      }
      vec3 Ea;
      vec3 Eb;
      bool ua = mrgiStencilUsable(a, Ea);
      bool ub = mrgiStencilUsable(b, Eb);
      for (int ch = 0; ch < 3; ++ch)
      {
        if (ua && ub)
        {
          float larger = max(max(Ea[ch], Eb[ch]), Ep[ch]);
          if (abs(0.5 * (Ea[ch] + Eb[ch]) - Ep[ch]) > mrgiIlluminationThreshold * larger)
          {
            return true;
          }
        }
        else if ((ua && mrgiStencilDiffers(Ea[ch], Ep[ch])) ||
          (ub && mrgiStencilDiffers(Eb[ch], Ep[ch])))
        {
          return true;
        }
      }
    }
    return false;
  }
  for (int k = 0; k < 9; ++k)
  {
    ivec2 s = clamp(c + ivec2(k % 3 - 1, k / 3 - 1), ivec2(0), mrgiParentSize - 1);
    vec3 En;
    if (!mrgiStencilUsable(s, En))
    {
      continue;
    }
    for (int ch = 0; ch < 3; ++ch)
    {
      if (mrgiStencilDiffers(En[ch], Ep[ch]))
      {
        return true;
      }
    }
  }
  return false;
}
#else
uvec4 mrgiStencilMask(int k, ivec2 s)
{
#if MRGI_STENCIL_TARGETS > 3
  if (k == 3) { return texelFetch(mrgiParentMask3, s, 0); }
#endif
#if MRGI_STENCIL_TARGETS > 2
  if (k == 2) { return texelFetch(mrgiParentMask2, s, 0); }
#endif
#if MRGI_STENCIL_TARGETS > 1
  if (k == 1) { return texelFetch(mrgiParentMask1, s, 0); }
#endif
  return texelFetch(mrgiParentMask0, s, 0);
}

// F_{i+1}(c): mrgi_voxel_neighbourhood_metric() over the 3x3 level-(i+1)
// texels around c (clamped, non-receivers skipped), then
// mrgi_voxel_needs_refinement().
bool mrgiStencilDiscontinuity(ivec2 c)
{
  uint all[4 * MRGI_STENCIL_TARGETS];
  uint any_[4 * MRGI_STENCIL_TARGETS];
  for (int w = 0; w < 4 * MRGI_STENCIL_TARGETS; ++w)
  {
    all[w] = 0xFFFFFFFFu;
    any_[w] = 0u;
  }
  int countMin = 0;
  int countMax = 0;
  bool anyReceiver = false;
  for (int k = 0; k < MRGI_VOXEL_NEIGHBOURS; ++k)
  {
    ivec2 s = clamp(c + ivec2(k % 3 - 1, k / 3 - 1), ivec2(0), mrgiParentSize - 1);
    if (!mrgiStencilReceiver(s))
    {
      continue;
    }
    int count = 0;
    for (int t = 0; t < MRGI_STENCIL_TARGETS; ++t)
    {
      uvec4 m = mrgiStencilMask(t, s);
      for (int q = 0; q < 4; ++q)
      {
        uint v = m[q];
        all[4 * t + q] &= v;
        any_[4 * t + q] |= v;
        count += int(mrgiVisPopcount(v));
      }
    }
    countMin = anyReceiver ? min(countMin, count) : count;
    countMax = anyReceiver ? max(countMax, count) : count;
    anyReceiver = true;
  }
  int disagree = 0;
  for (int w = 0; w < MRGI_STENCIL_WORDS; ++w)
  {
    disagree += int(mrgiVisPopcount(any_[w] & ~all[w]));
  }
  int value = !anyReceiver ? 0
    : (mrgiMetric == MRGI_VOXEL_METRIC_COUNT_SPREAD ? countMax - countMin : disagree);
  return value >= mrgiThreshold;
}

// E(P, N): mrgi_irradiance_stencil_estimate(), statement by statement.
float mrgiStencilEstimate(vec3 P, vec3 N)
{
  float side = dot(mrgiAreaNormal, P - mrgiAreaCenter);
  if (mrgiAreaTwoSided != 0 ? side == 0.0 : !(side > 0.0))
  {
    return 0.0;
  }
  float g = float(MRGI_IRRADIANCE_STENCIL_GRID);
  float cell = mrgiAreaArea / (g * g);
  vec3 U = mrgiAreaCorners[1] - mrgiAreaCorners[0];
  vec3 V = mrgiAreaCorners[3] - mrgiAreaCorners[0];
  float E = 0.0;
  for (int b = 0; b < MRGI_IRRADIANCE_STENCIL_GRID; ++b)
  {
    float sv = (float(b) + 0.5) / g;
    for (int a = 0; a < MRGI_IRRADIANCE_STENCIL_GRID; ++a)
    {
      float su = (float(a) + 0.5) / g;
      vec3 d = (mrgiAreaCorners[0] + su * U + sv * V) - P;
      float r2 = dot(d, d);
      if (!(r2 > 0.0)) { continue; }
      float ci = dot(N, d);
      float cj = -dot(mrgiAreaNormal, d);
      if (mrgiAreaTwoSided != 0) { cj = abs(cj); }
      if (!(ci > 0.0) || !(cj > 0.0)) { continue; }
      E += cell * (ci * cj / r2) / (float(MRGI_PI) * r2 + cell);
    }
  }
  return E;
}

// V_{i+1}(c) of mrgi_irradiance_stencil.h.
bool mrgiStencilIrradianceVaries(ivec2 c)
{
  float lo = 0.0;
  float hi = 0.0;
  bool anyReceiver = false;
  for (int k = 0; k < MRGI_VOXEL_NEIGHBOURS; ++k)
  {
    ivec2 s = clamp(c + ivec2(k % 3 - 1, k / 3 - 1), ivec2(0), mrgiParentSize - 1);
    vec3 n = texelFetch(mrgiParentNormal, s, 0).xyz;
    if (!mrgiStencilReceiver(s) || any(isnan(n)) || any(isinf(n)))
    {
      continue;
    }
    vec3 m = mat3(mrgiVCToWC) * n;
    float len2 = dot(m, m);
    if (!(len2 > 0.0)) { continue; }
    vec3 P = (mrgiVCToWC * vec4(texelFetch(mrgiParentPosition, s, 0).xyz, 1.0)).xyz;
    float E = mrgiStencilEstimate(P, m * (1.0 / sqrt(len2)));
    lo = anyReceiver ? min(E, lo) : E;
    hi = anyReceiver ? max(E, hi) : E;
    anyReceiver = true;
  }
  return anyReceiver && hi > 0.0 && hi - lo > mrgiIrradianceTolerance * hi;
}
#endif

void main()
{
  ivec2 f = ivec2(gl_FragCoord.xy);
  ivec2 t = ivec2(f.x - mrgiLevelOffset, f.y);
  int flags = int(texelFetch(mrgiFlags, t, 0).r);
  bool rendered = false;
  if ((flags & MRGI_MULTIRES_FLAG_NONEMPTY) != 0)
  {
    if (texelFetch(mrgiSelection, f, 0).r > 0.5)
    {
      rendered = true;
    }
    else if (mrgiCoarsest == 0 && (mrgiFinest != 0 || (flags & MRGI_MULTIRES_FLAG_REFINE) == 0))
    {
#ifdef MRGI_STENCIL_ILLUMINATION
      rendered = mrgiStencilDiscontinuity(t / 2);
#else
      rendered = mrgiStencilDiscontinuity(t / 2) ||
        (mrgiIrradianceTolerance > 0.0 && mrgiStencilIrradianceVaries(t / 2));
#endif
    }
  }
  if (!rendered)
  {
    discard;
  }
  gl_FragData[0] = vec4(1.0);
}
