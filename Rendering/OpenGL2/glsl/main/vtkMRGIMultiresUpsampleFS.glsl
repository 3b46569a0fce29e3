// MRGI multiresolution upsampling and combination (nichols-wyman-2009 3.5;
// besenthal et al. eq. 1), one level at a time from the coarsest; C twin and
// exact rules: mrgi_upsample.h. MRGI_MR_STAGE
// 0: state and value of level i (selected: gathered value; else, non-empty
//    under a parent holding data: the parent's filtered value), RGB + state;
// 1: filter level i over the 3x3 tent of neighbours that may be blended;
// 2: resolve: full-resolution E and strength x albedo x E for the composite,
//    E modulated by the surface-detail factor (nichols-wyman-2009 eq. 2; C
//    twin mrgi_surface_detail_factor, same operations in the same order).
in vec2 texCoord; // bound by vtkOpenGLQuadHelper; texels are addressed by gl_FragCoord
uniform sampler2D mrgiInput0; // 0: flattened selection; 1: state/value of level i; 2: filtered level 0
uniform sampler2D mrgiInput1; // 0: flags of level i; 2: flags of level 0
uniform sampler2D mrgiInput2; // 0: flattened irradiance; 2: albedo (G-buffer)
uniform sampler2D mrgiInput3; // 0: filtered level i+1; 2: position (G-buffer)
uniform sampler2D mrgiInput4; // 2: normal (G-buffer)
uniform float mrgiSurfaceDetail; // 2: alpha of nichols-wyman-2009 eq. 2 (0: off)
uniform int mrgiParallel;        // 2: parallel projection
uniform ivec2 mrgiOffset;     // 0: level offset in the flattened layout; 2: viewport origin
uniform ivec2 mrgiSize;       // 1: size of level i
uniform int mrgiCoarsest;     // 0: whether level i is the coarsest
uniform int mrgiMode;         // MRGI_UPSAMPLE_TENT or MRGI_UPSAMPLE_MASK_WEIGHTED
uniform float mrgiMaskWeight;
uniform float mrgiStrength;
//VTK::Output::Dec
// State bits, as in mrgi_upsample.c.
#define MRGI_UP_HAS 1
#define MRGI_UP_SELECTED 2
#define MRGI_UP_BLEND 4
// v / |v| computed on v / max|v_i| (no underflow or overflow at any scene
// scale); false when v is zero or not finite. As mrgi_unit in mrgi_upsample.c.
bool mrgiUnit(vec3 v, out vec3 u)
{
  float m = max(max(abs(v.x), abs(v.y)), abs(v.z));
  u = vec3(0.0);
  if (!(m > 0.0 && m <= MRGI_MULTIRES_FLT_MAX)) { return false; }
  float x = v.x / m, y = v.y / m, z = v.z / m;
  float inverse = 1.0 / sqrt(x * x + y * y + z * z);
  u = vec3(x * inverse, y * inverse, z * inverse);
  return true;
}
void main()
{
  ivec2 t = ivec2(gl_FragCoord.xy);
#if MRGI_MR_STAGE == 0
  int flags = int(texelFetch(mrgiInput1, t, 0).r);
  int bits = 0;
  vec3 value = vec3(0.0);
  if (texelFetch(mrgiInput0, t + mrgiOffset, 0).r > 0.5)
  {
    bits = MRGI_UP_HAS | MRGI_UP_SELECTED;
    value = texelFetch(mrgiInput2, t + mrgiOffset, 0).rgb;
  }
  else if (mrgiCoarsest == 0 && (flags & MRGI_MULTIRES_FLAG_NONEMPTY) != 0)
  {
    vec4 parent = texelFetch(mrgiInput3, t / 2, 0);
    if ((int(parent.a) & MRGI_UP_HAS) != 0)
    {
      bits = MRGI_UP_HAS;
      value = parent.rgb;
    }
  }
  if ((bits & MRGI_UP_HAS) != 0 && (flags & MRGI_MULTIRES_FLAG_DISCONTINUOUS) == 0)
  {
    bits |= MRGI_UP_BLEND;
  }
  gl_FragData[0] = vec4(value, float(bits));
#elif MRGI_MR_STAGE == 1
  vec4 center = texelFetch(mrgiInput0, t, 0);
  int state = int(center.a);
  if ((state & MRGI_UP_BLEND) == 0)
  {
    // Filtered texels carry HAS on to the finer level in their alpha.
    gl_FragData[0] = vec4((state & MRGI_UP_HAS) != 0 ? center.rgb : vec3(0.0), float(state & MRGI_UP_HAS));
    return;
  }
  float weightAll = 0.0;
  float weightSelected = 0.0;
  vec3 sumAll = vec3(0.0);
  vec3 sumSelected = vec3(0.0);
  vec3 sumUpsampled = vec3(0.0);
  for (int dy = -1; dy <= 1; ++dy)
  {
    for (int dx = -1; dx <= 1; ++dx)
    {
      ivec2 n = t + ivec2(dx, dy);
      bool inside = n.x >= 0 && n.y >= 0 && n.x < mrgiSize.x && n.y < mrgiSize.y;
      vec4 v = texelFetch(mrgiInput0, clamp(n, ivec2(0), mrgiSize - 1), 0);
      int s = inside ? int(v.a) : 0;
      v.rgb = (s & MRGI_UP_BLEND) != 0 ? v.rgb : vec3(0.0); // no 0 * inf
      // Straight-line code (llvmpipe pays for divergent branches): texels
      // that may not be blended weigh 0, and adding exact zeros leaves every
      // sum as the C twin's, which skips them.
      float k = (s & MRGI_UP_BLEND) != 0 ? float((2 - abs(dx)) * (2 - abs(dy))) : 0.0;
      float ks = (s & MRGI_UP_SELECTED) != 0 ? k : 0.0;
      weightAll += k;
      weightSelected += ks;
      sumAll += k * v.rgb;
      sumSelected += ks * v.rgb;
      sumUpsampled += (k - ks) * v.rgb;
    }
  }
  vec3 result;
  if (mrgiMode == MRGI_UPSAMPLE_TENT)
  {
    result = sumAll / weightAll;
  }
  else
  {
    float a = weightSelected / weightAll;
    float weightUpsampled = weightAll - weightSelected;
    float lambda = min(a * mrgiMaskWeight, 1.0);
    if (a == 0.0) { result = sumUpsampled / weightUpsampled; }
    else if (a == 1.0) { result = sumSelected / weightSelected; }
    else
    {
      vec3 fine = sumSelected / weightSelected;
      vec3 coarse = sumUpsampled / weightUpsampled;
      result = coarse + lambda * (fine - coarse);
    }
  }
  gl_FragData[0] = vec4(result, float(MRGI_UP_HAS));
#else
  ivec2 p = t - mrgiOffset;
  vec3 E = vec3(0.0);
  if ((int(texelFetch(mrgiInput1, p, 0).r) & MRGI_MULTIRES_FLAG_NONEMPTY) != 0)
  {
    E = texelFetch(mrgiInput0, p, 0).rgb;
  }
  if (mrgiSurfaceDetail > 0.0)
  {
    vec3 P = texelFetch(mrgiInput3, t, 0).xyz;
    vec3 N = texelFetch(mrgiInput4, t, 0).xyz;
    vec3 V = vec3(0.0, 0.0, 1.0);
    vec3 toPoint;
    if (mrgiParallel == 0 && mrgiUnit(P, toPoint)) { V = -toPoint; }
    vec3 n;
    float facing = 0.0;
    if (mrgiUnit(N, n)) { facing = V.x * n.x + V.y * n.y + V.z * n.z; }
    facing = facing > 0.0 ? facing : 0.0;
    E *= mrgiSurfaceDetail * facing + (1.0 - mrgiSurfaceDetail);
  }
  vec3 albedo = texelFetch(mrgiInput2, t, 0).rgb;
  gl_FragData[0] = vec4(E, 1.0);
  gl_FragData[1] = vec4(mrgiStrength * albedo * E, 1.0);
#endif
}
