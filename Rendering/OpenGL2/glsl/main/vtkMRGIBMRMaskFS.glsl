// MRGI BMR masks and inclusive stencils (besenthal-maisch-ropinski 3.1,
// 4.1); C twin and exact rules: mrgi_bmr_mask.h (same operations in the
// same order). One level k at a time, fine to coarse. MRGI_BMR_STAGE
// 0: e(p) at level 0 from the G-buffer: (E, NE, 0, 0);
// 1: E_k, NE_k as the max over the children in level k-1's mask: (E, NE, 0, 0);
// 2: horizontal Gaussian of E_k: (h, 0, 0, 0) (a one-channel float target);
// 3: vertical Gaussian of h and the stencil rule, with E and NE from stage
//    0/1: the level's mask (a, E, R + 2 S, NE);
// 4: stencil write: keeps the fragments whose S is set (the caller's
//    stencil op writes 1), discards the rest;
// 5: the ablation source: E_k, NE_k from the NW09 flags of level k
//    (DISCONTINUOUS, NONEMPTY): (E, NE, 0, 0).
in vec2 texCoord; // bound by vtkOpenGLQuadHelper; texels are addressed by gl_FragCoord
uniform sampler2D mrgiInput0; // 0: position; 1: mask of level k-1; 2: stage 0/1/5 output; 3: stage 2 output; 4: mask of level k; 5: flags of level k
uniform sampler2D mrgiInput1; // 0: normal; 3: mask of level k-1 (unread at level 0)
uniform sampler2D mrgiInput2; // 0: shadow factor (red), unread unless mrgiHasShadow; 3: stage 0/1 output
uniform ivec2 mrgiOffset;     // 0: the frame's origin in the G-buffer textures
uniform ivec2 mrgiSize;       // size of level k (stage 0: W x H)
uniform ivec2 mrgiFinerSize;  // 1, 3: size of level k-1
uniform vec2 mrgiPixelSize;   // 0: (a, b) of s(d)
uniform float mrgiDepthThreshold;  // 0: T_d, < 0: off
uniform float mrgiNormalThreshold; // 0: T_n, < 0: off
uniform int mrgiCombine;      // 0: MRGI_BMR_COMBINE_MAX or _MIN
uniform int mrgiHasShadow;    // 0: 1 when mrgiInput2 holds the shadow image
uniform int mrgiRadius;       // 2, 3: R = ceil(3 sigma_k), 0 for no blur
// 2, 3: the Gaussian's weights g(0..R), computed once in C++ with the C
// twin's expf (the same floats, and no exp per tap).
uniform float mrgiGauss[MRGI_BMR_MAX_RADIUS + 1];
uniform int mrgiLevel;        // 3: k
uniform int mrgiSkip;         // 3: level k is skipped
//VTK::Output::Dec

#if MRGI_BMR_STAGE == 0
bool mrgiValid(vec4 P, vec3 N)
{
  return P.w > MRGI_GBUFFER_VALID_THRESHOLD && !isnan(P.z) && !isinf(P.z) &&
    !any(isnan(N)) && !any(isinf(N));
}
vec3 mrgiUnitNormal(vec3 N)
{
  float length2 = N.x * N.x + N.y * N.y + N.z * N.z;
  if (!(length2 > MRGI_MULTIRES_MIN_PIXEL_SIZE)) { length2 = MRGI_MULTIRES_MIN_PIXEL_SIZE; }
  float inverseLength = 1.0 / sqrt(length2);
  return vec3(N.x * inverseLength, N.y * inverseLength, N.z * inverseLength);
}
#endif

void main()
{
  ivec2 t = ivec2(gl_FragCoord.xy);
#if MRGI_BMR_STAGE == 0
  // Every G-buffer texel is fetched once: the pixel, then left, right,
  // down, up (an outside neighbour is the pixel itself, as the C twin's
  // clamped central differences).
  vec4 P = texelFetch(mrgiInput0, t + mrgiOffset, 0);
  vec3 N = texelFetch(mrgiInput1, t + mrgiOffset, 0).xyz;
  if (!mrgiValid(P, N))
  {
    gl_FragData[0] = vec4(0.0);
    return;
  }
  ivec2 q[4];
  q[0] = t + ivec2(-1, 0);
  q[1] = t + ivec2(1, 0);
  q[2] = t + ivec2(0, -1);
  q[3] = t + ivec2(0, 1);
  bool inside[4];
  vec4 Pq[4];
  vec3 Nq[4];
  bool silhouette = false;
  bool shadowEdge = false;
  float shadowHere = mrgiHasShadow != 0 ? texelFetch(mrgiInput2, t + mrgiOffset, 0).r : 0.0;
  for (int i = 0; i < 4; ++i)
  {
    inside[i] = all(greaterThanEqual(q[i], ivec2(0))) && all(lessThan(q[i], mrgiSize));
    if (!inside[i]) { q[i] = t; }
    Pq[i] = texelFetch(mrgiInput0, q[i] + mrgiOffset, 0);
    Nq[i] = texelFetch(mrgiInput1, q[i] + mrgiOffset, 0).xyz;
    if (!mrgiValid(Pq[i], Nq[i]))
    {
      silhouette = true;
    }
    else if (mrgiHasShadow != 0 && inside[i] &&
      texelFetch(mrgiInput2, q[i] + mrgiOffset, 0).r != shadowHere)
    {
      shadowEdge = true;
    }
  }
  bool depthOn = mrgiDepthThreshold >= 0.0;
  bool normalOn = mrgiNormalThreshold >= 0.0;
  bool depthEdge = silhouette;
  bool normalEdge = silhouette;
  if (!silhouette && normalOn)
  {
    vec3 n0 = mrgiUnitNormal(Nq[0]), n1 = mrgiUnitNormal(Nq[1]);
    vec3 n2 = mrgiUnitNormal(Nq[2]), n3 = mrgiUnitNormal(Nq[3]);
    float m = 0.0;
    for (int c = 0; c < 3; ++c)
    {
      float dx = abs(n1[c] - n0[c]);
      float dy = abs(n3[c] - n2[c]);
      m = max(m, max(dx, dy));
    }
    normalEdge = m * 0.5 >= mrgiNormalThreshold;
  }
  if (!silhouette && depthOn)
  {
    float d = -P.z;
    float sum = 0.0;
    if (inside[0] && inside[1])
    {
      sum += abs(-Pq[1].z + -Pq[0].z - 2.0 * d);
    }
    if (inside[2] && inside[3])
    {
      sum += abs(-Pq[3].z + -Pq[2].z - 2.0 * d);
    }
    float s = mrgiPixelSize.x * abs(d) + mrgiPixelSize.y;
    s = s > MRGI_MULTIRES_MIN_PIXEL_SIZE ? s : MRGI_MULTIRES_MIN_PIXEL_SIZE;
    depthEdge = sum / s >= mrgiDepthThreshold;
  }
  bool anyEdge = false, allEdges = true;
  int on = 0;
  if (depthOn) { ++on; anyEdge = anyEdge || depthEdge; allEdges = allEdges && depthEdge; }
  if (normalOn) { ++on; anyEdge = anyEdge || normalEdge; allEdges = allEdges && normalEdge; }
  if (mrgiHasShadow != 0) { ++on; anyEdge = anyEdge || shadowEdge; allEdges = allEdges && shadowEdge; }
  bool e = on > 0 && (mrgiCombine == MRGI_BMR_COMBINE_MIN ? allEdges : anyEdge);
  gl_FragData[0] = vec4(e ? 1.0 : 0.0, 1.0, 0.0, 0.0);
#elif MRGI_BMR_STAGE == 1
  float e = 0.0, ne = 0.0;
  for (int b = 0; b < 2; ++b)
  {
    for (int a = 0; a < 2; ++a)
    {
      ivec2 c = 2 * t + ivec2(a, b);
      if (c.x < mrgiFinerSize.x && c.y < mrgiFinerSize.y)
      {
        vec4 m = texelFetch(mrgiInput0, c, 0);
        e = max(e, m.g);
        ne = max(ne, m.a);
      }
    }
  }
  gl_FragData[0] = vec4(e, ne, 0.0, 0.0);
#elif MRGI_BMR_STAGE == 2
  // Taps outside the level are skipped (the C twin's renormalisation);
  // the loop runs over the uniform radius, the same for every fragment.
  float sum = 0.0, wsum = 0.0;
  for (int j = -mrgiRadius; j <= mrgiRadius; ++j)
  {
    int x = t.x + j;
    if (x < 0 || x >= mrgiSize.x) { continue; }
    float g = mrgiGauss[abs(j)];
    sum += g * texelFetch(mrgiInput0, ivec2(x, t.y), 0).r;
    wsum += g;
  }
  gl_FragData[0] = vec4(sum / wsum, 0.0, 0.0, 0.0);
#elif MRGI_BMR_STAGE == 3
  vec4 here = texelFetch(mrgiInput2, t, 0); // (E, NE)
  float a = 0.0;
  if (mrgiSkip == 0)
  {
    float sum = 0.0, wsum = 0.0;
    for (int j = -mrgiRadius; j <= mrgiRadius; ++j)
    {
      int y = t.y + j;
      if (y < 0 || y >= mrgiSize.y) { continue; }
      float g = mrgiGauss[abs(j)];
      sum += g * texelFetch(mrgiInput0, ivec2(t.x, y), 0).r;
      wsum += g;
    }
    a = sum / wsum;
  }
  bool nonEmpty = here.g > 0.5;
  bool required = false;
  if (nonEmpty)
  {
    if (mrgiLevel == MRGI_BMR_LEVELS - 1 || a > 0.0)
    {
      required = true;
    }
    else if (mrgiLevel > 0)
    {
      for (int b = 0; b < 2; ++b)
      {
        for (int c = 0; c < 2; ++c)
        {
          ivec2 child = 2 * t + ivec2(c, b);
          if (child.x < mrgiFinerSize.x && child.y < mrgiFinerSize.y &&
            (int(texelFetch(mrgiInput1, child, 0).b) & 1) != 0)
          {
            required = true;
          }
        }
      }
    }
  }
  bool stencil = required && mrgiSkip == 0;
  gl_FragData[0] = vec4(a, here.r > 0.5 ? 1.0 : 0.0, float((required ? 1 : 0) + (stencil ? 2 : 0)),
    nonEmpty ? 1.0 : 0.0);
#elif MRGI_BMR_STAGE == 5
  int flags = int(texelFetch(mrgiInput0, t, 0).r);
  gl_FragData[0] = vec4((flags & MRGI_MULTIRES_FLAG_DISCONTINUOUS) != 0 ? 1.0 : 0.0,
    (flags & MRGI_MULTIRES_FLAG_NONEMPTY) != 0 ? 1.0 : 0.0, 0.0, 0.0);
#else
  if ((int(texelFetch(mrgiInput0, t, 0).b) & 2) == 0)
  {
    discard;
  }
  gl_FragData[0] = vec4(1.0);
#endif
}
