// MRGI multiresolution selection, the GPU side of mrgi_multires.h (C twins:
// mrgi_multires_mipmap_build, mrgi_multires_flags_compute,
// mrgi_multires_select_one_pass). One shader, four stages chosen by
// MRGI_MR_STAGE; every rule and its float order mirror the C code:
// 0: level-0 mipmap from the G-buffer (validity, depth, depth derivative g).
//    A pixel's normal range is its unit normal itself (min = max), and the
//    passes that read level 0's normals (stage 1 and stage 2 with
//    MRGI_MR_LEVEL0) normalize the G-buffer's normal where they read it
//    (mrgiUnitNormal) instead of reading a stored copy: level 0 has no
//    normal texture, one window-sized RGBA32F texture less to allocate and
//    to write (on llvmpipe, allocation zero-fills host memory: the first
//    frame's largest cost, Documentation/Multiresolution.md "Cold start");
// 1: level i mipmap, 2x2 min/max/OR of level i-1 (children clamped to the level);
// 2: flags of level i (3x3 window, refinement from level i-1's flags, balance);
// 3: the one-pass selection of nichols-shopf-wyman-2009 3.2.1, drawn once
//    per level into that level's rectangle of the flattened layout (no
//    per-fragment search for the level, nothing drawn outside the levels):
//    fragments that survive set the stencil.
in vec2 texCoord; // bound by vtkOpenGLQuadHelper; texels are addressed by gl_FragCoord
uniform sampler2D mrgiInput0;
uniform sampler2D mrgiInput1;
uniform sampler2D mrgiInput2;
uniform sampler2D mrgiInput3;
uniform ivec2 mrgiOffset;      // stages 0-2 at level 0: G-buffer texel of pixel (0, 0); stage 3: level offset in the flattened layout
uniform ivec2 mrgiSize;        // size of the level read (stages 0-2: level i-1 or i, see below)
uniform ivec2 mrgiChildSize;   // stage 2: size of level i-1
uniform vec2 mrgiPixelSize;    // (a, b): s(d) = max(a |d| + b, MRGI_MULTIRES_MIN_PIXEL_SIZE)
uniform float mrgiDepthThreshold;   // MRGI_MULTIRES_THRESHOLD_OFF when off
uniform float mrgiNormalThreshold;
uniform int mrgiLevel;         // stage 2: i
uniform int mrgiFinestLevel;   // f
uniform int mrgiBalance;
uniform int mrgiCoarsest;      // stage 3: whether level i is the coarsest (no parent)
//VTK::Output::Dec

// The unit normal of mrgi_multires.h section 2, N * inversesqrt(max(N.N,
// MRGI_MULTIRES_MIN_PIXEL_SIZE)), in the C twin's float order (a zero
// normal stays zero).
vec3 mrgiUnitNormal(vec3 N)
{
  float length2 = N.x * N.x + N.y * N.y + N.z * N.z;
  if (!(length2 > MRGI_MULTIRES_MIN_PIXEL_SIZE)) { length2 = MRGI_MULTIRES_MIN_PIXEL_SIZE; }
  return N * (1.0 / sqrt(length2));
}
#ifdef MRGI_MR_LEVEL0
// Level 0's normal at pixel s (mrgiInput1 is the G-buffer normal there).
vec3 mrgiLevel0Normal(ivec2 s)
{
  return mrgiUnitNormal(texelFetch(mrgiInput1, s + mrgiOffset, 0).xyz);
}
#endif

#if MRGI_MR_STAGE == 0
bool mrgiValid(ivec2 p, out float d, out vec3 n)
{
  vec4 P = texelFetch(mrgiInput0, p + mrgiOffset, 0);
  vec3 N = texelFetch(mrgiInput1, p + mrgiOffset, 0).xyz;
  d = -P.z;
  n = N;
  return P.w > MRGI_GBUFFER_VALID_THRESHOLD && !isnan(P.z) && !isinf(P.z) &&
    !any(isnan(N)) && !any(isinf(N));
}
// Depth of a neighbour for the derivative: flag and finite depth suffice.
bool mrgiDepthValid(ivec2 p, out float d)
{
  vec4 P = texelFetch(mrgiInput0, p + mrgiOffset, 0);
  d = -P.z;
  return P.w > MRGI_GBUFFER_VALID_THRESHOLD && !isnan(P.z) && !isinf(P.z);
}
float mrgiPixelSizeAt(float d)
{
  float s = mrgiPixelSize.x * abs(d) + mrgiPixelSize.y;
  return s > MRGI_MULTIRES_MIN_PIXEL_SIZE ? s : MRGI_MULTIRES_MIN_PIXEL_SIZE;
}
#endif

void main()
{
  ivec2 t = ivec2(gl_FragCoord.xy);
#if MRGI_MR_STAGE == 0
  float dp;
  vec3 N;
  if (!mrgiValid(t, dp, N))
  {
    // The normal of an invalid pixel is never read: the passes that read
    // level 0 (stage 1 and stage 2 with MRGI_MR_LEVEL0) skip invalid
    // pixels, as the C twin's (+FLT_MAX, -FLT_MAX) range does.
    gl_FragData[0] = vec4(MRGI_MULTIRES_FLT_MAX, -MRGI_MULTIRES_FLT_MAX, 0.0, float(MRGI_MULTIRES_INVALID_BIT));
    return;
  }
  float g = 0.0;
  for (int dy = -1; dy <= 1; ++dy)
  {
    for (int dx = -1; dx <= 1; ++dx)
    {
      ivec2 q = clamp(t + ivec2(dx, dy), ivec2(0), mrgiSize - 1);
      float dq;
      // Straight-line code (llvmpipe pays for divergent branches): invalid
      // neighbours contribute 0, which leaves the max unchanged as in the C twin.
      bool valid = mrgiDepthValid(q, dq);
      float s = mrgiPixelSizeAt(min(abs(dp), abs(dq)));
      float slope = abs(dq - dp) / s;
      slope = slope <= MRGI_MULTIRES_FLT_MAX ? slope : MRGI_MULTIRES_FLT_MAX;
      g = max(g, valid ? slope : 0.0);
    }
  }
  gl_FragData[0] = vec4(dp, dp, g, float(MRGI_MULTIRES_VALID_BIT));
#elif MRGI_MR_STAGE == 1
  vec4 a = vec4(MRGI_MULTIRES_FLT_MAX, -MRGI_MULTIRES_FLT_MAX, 0.0, 0.0);
  vec3 lo = vec3(MRGI_MULTIRES_FLT_MAX);
  vec3 hi = vec3(-MRGI_MULTIRES_FLT_MAX);
  int bits = 0;
  for (int b = 0; b < 2; ++b)
  {
    for (int c = 0; c < 2; ++c)
    {
      ivec2 s = clamp(2 * t + ivec2(c, b), ivec2(0), mrgiSize - 1);
      vec4 depth = texelFetch(mrgiInput0, s, 0);
      a.x = min(a.x, depth.x);
      a.y = max(a.y, depth.y);
      a.z = max(a.z, depth.z);
      bits |= int(depth.w);
#ifdef MRGI_MR_LEVEL0
      // Level 0: one normal per pixel (min = max), from the G-buffer;
      // invalid pixels widen nothing.
      bool valid = (int(depth.w) & MRGI_MULTIRES_VALID_BIT) != 0;
      vec3 n = mrgiLevel0Normal(s);
      lo = min(lo, valid ? n : vec3(MRGI_MULTIRES_FLT_MAX));
      hi = max(hi, valid ? n : vec3(-MRGI_MULTIRES_FLT_MAX));
#else
      lo = min(lo, texelFetch(mrgiInput1, s, 0).xyz);
      hi = max(hi, texelFetch(mrgiInput2, s, 0).xyz);
#endif
    }
  }
  gl_FragData[0] = vec4(a.xyz, float(bits));
  gl_FragData[1] = vec4(lo, 0.0);
  gl_FragData[2] = vec4(hi, 0.0);
#elif MRGI_MR_STAGE == 2
  int bits = int(texelFetch(mrgiInput0, t, 0).w);
  int flag = 0;
  if ((bits & MRGI_MULTIRES_VALID_BIT) != 0)
  {
    flag = MRGI_MULTIRES_FLAG_NONEMPTY;
    bool mixed = (bits & MRGI_MULTIRES_INVALID_BIT) != 0;
    if (mixed) { flag |= MRGI_MULTIRES_FLAG_MIXED; }
    float g = 0.0;
    vec3 lo = vec3(MRGI_MULTIRES_FLT_MAX);
    vec3 hi = vec3(-MRGI_MULTIRES_FLT_MAX);
    for (int dy = -1; dy <= 1; ++dy)
    {
      for (int dx = -1; dx <= 1; ++dx)
      {
        ivec2 s = clamp(t + ivec2(dx, dy), ivec2(0), mrgiSize - 1);
        g = max(g, texelFetch(mrgiInput0, s, 0).z);
#ifdef MRGI_MR_LEVEL0
        // One normal per pixel (min = max), from the G-buffer; invalid
        // pixels widen nothing.
        bool valid = (int(texelFetch(mrgiInput0, s, 0).w) & MRGI_MULTIRES_VALID_BIT) != 0;
        vec3 n = mrgiLevel0Normal(s);
        lo = min(lo, valid ? n : vec3(MRGI_MULTIRES_FLT_MAX));
        hi = max(hi, valid ? n : vec3(-MRGI_MULTIRES_FLT_MAX));
#else
        lo = min(lo, texelFetch(mrgiInput1, s, 0).xyz);
        hi = max(hi, texelFetch(mrgiInput2, s, 0).xyz);
#endif
      }
    }
    bool discontinuous = false;
    if (mrgiDepthThreshold >= 0.0 && (mixed || g >= mrgiDepthThreshold)) { discontinuous = true; }
    if (!discontinuous && mrgiNormalThreshold >= 0.0)
    {
      float spread = max(max(hi.x - lo.x, hi.y - lo.y), hi.z - lo.z);
      if (spread >= mrgiNormalThreshold) { discontinuous = true; }
    }
    if (discontinuous) { flag |= MRGI_MULTIRES_FLAG_DISCONTINUOUS; }
    bool refine = false;
    if (mrgiLevel == mrgiFinestLevel)
    {
      refine = discontinuous;
    }
    else if (mrgiLevel > mrgiFinestLevel)
    {
      refine = discontinuous;
      int reachLo = mrgiBalance != 0 ? -1 : 0;
      int reachHi = mrgiBalance != 0 ? 2 : 1;
      for (int b = reachLo; b <= reachHi; ++b)
      {
        for (int c = reachLo; c <= reachHi; ++c)
        {
          ivec2 s = clamp(2 * t + ivec2(c, b), ivec2(0), mrgiChildSize - 1);
          refine = refine || (int(texelFetch(mrgiInput3, s, 0).r) & MRGI_MULTIRES_FLAG_REFINE) != 0;
        }
      }
    }
    if (refine) { flag |= MRGI_MULTIRES_FLAG_REFINE; }
  }
  gl_FragData[0] = vec4(float(flag), 0.0, 0.0, 0.0);
#else
  ivec2 p = t - mrgiOffset;
  int flag = int(texelFetch(mrgiInput0, p, 0).r);
  bool selected = (flag & MRGI_MULTIRES_FLAG_NONEMPTY) != 0 &&
    (mrgiLevel == mrgiFinestLevel || (flag & MRGI_MULTIRES_FLAG_REFINE) == 0);
  if (selected && mrgiCoarsest == 0)
  {
    int parent = int(texelFetch(mrgiInput1, p / 2, 0).r);
    selected = (parent & MRGI_MULTIRES_FLAG_REFINE) != 0;
  }
  if (!selected) { discard; }
  gl_FragData[0] = vec4(1.0, float(mrgiLevel), 0.0, 0.0);
#endif
}
