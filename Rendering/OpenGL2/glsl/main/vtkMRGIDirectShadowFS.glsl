// MRGI direct shadows. C twin and exact rules: mrgi_direct_shadow.h; this
// file follows mrgi_direct_shadow.c statement by statement, in float.
// MRGI_DS_STAGE 0: the depth map of one RSM view (mrgi_direct_shadow_depth_map),
//   S x S, red = light-view depth or MRGI_DIRECT_SHADOW_NO_OCCLUDER;
// MRGI_DS_STAGE 1: the shadow factor of one light at each G-buffer pixel from
//   one of its views (hard PCF or PCSS). One draw per (light slot, view); a
//   pixel is written only by the view that holds it (the rule of
//   mrgi_direct_shadow_select_view), into the slot's channel (colour mask).
// MRGI_DS_STAGE 2: factor = 1 - the blended 1 - factor of the BMR levels
//   (input 0, viewport-sized at (0, 0)) over the viewport.
in vec2 texCoord; // bound by vtkOpenGLQuadHelper; texels are addressed by gl_FragCoord
uniform sampler2D mrgiInput0; // 0: the view's RSM world positions, w = valid; 1: G-buffer eye-space position
uniform sampler2D mrgiInput1; // 1: G-buffer eye-space normal
uniform sampler2D mrgiInput2; // 1: this view's depth map (stage 0's output)
uniform mat4 mrgiVCToWC;      // eye -> world of the rendered camera
uniform mat4 mrgiWorldToView[MRGI_DIRECT_SHADOW_MAX_VIEWS]; // the light's views
uniform vec4 mrgiViewTerms[MRGI_DIRECT_SHADOW_MAX_VIEWS];   // sx, sy, near, perspective (1 or 0)
uniform int mrgiViewCount;    // views of the light
uniform int mrgiView;         // the view this draw reads and writes
uniform int mrgiSize;         // S of the views
uniform int mrgiMode;         // MRGI_DIRECT_SHADOW_HARD or _SOFT
uniform int mrgiSamplesSide;  // SOFT: PCF side n
uniform float mrgiLightRadius; // world units
uniform int mrgiLevel;        // 1: -1 the factors at each pixel; k >= 0: BMR level k, 1 - factor
uniform ivec2 mrgiOrigin;     // 1 (level >= 0), 2: the viewport's origin in the G-buffer
uniform ivec2 mrgiFrameSize;  // 1 (level >= 0): the viewport's size
//VTK::Output::Dec

// c of the view rule, -1 when view v does not hold view-space point q.
float mrgiCentrality(int v, vec3 q)
{
  vec4 terms = mrgiViewTerms[v];
  float d = -q.z;
  float m = max(abs(terms.x * q.x), abs(terms.y * q.y));
  float c = m;
  if (terms.w > 0.5)
  {
    if (!(d > terms.z)) { return -1.0; }
    c = m / d;
  }
  return c <= 1.0 ? c : -1.0;
}

// The receiver as the view sees it (mrgi_direct_shadow.c's `receiver`).
vec3 mrgiQ;  // view coordinates
vec3 mrgiN;  // view-space unit normal facing the light
float mrgiD; // depth
float mrgiT; // texel size
float mrgiF; // footprint
vec2 mrgiUV; // continuous texel coordinates
bool mrgiPerspective;
vec2 mrgiScale;

float mrgiPlaneDepth(ivec2 t)
{
  float S = float(mrgiSize);
  float cx = (float(t.x) + 0.5) / S * 2.0 - 1.0;
  float cy = (float(t.y) + 0.5) / S * 2.0 - 1.0;
  if (mrgiPerspective)
  {
    float a = cx / mrgiScale.x, b = cy / mrgiScale.y;
    float aP = mrgiQ.x / mrgiD, bP = mrgiQ.y / mrgiD;
    float den = min(mrgiN.x * a + mrgiN.y * b - mrgiN.z, -1.0 / MRGI_DIRECT_SHADOW_MAX_SLOPE);
    return mrgiD + mrgiD * (mrgiN.x * (aP - a) + mrgiN.y * (bP - b)) / den;
  }
  float den = max(mrgiN.z, 1.0 / MRGI_DIRECT_SHADOW_MAX_SLOPE);
  return mrgiD + (mrgiN.x * (cx / mrgiScale.x - mrgiQ.x) + mrgiN.y * (cy / mrgiScale.y - mrgiQ.y)) / den;
}

// One texel of mrgi_direct_shadow_depth_map for the view mrgiView: the
// light-view depth of a valid, finite position, else no occluder.
float mrgiPositionDepth(ivec2 t)
{
  vec4 q = texelFetch(mrgiInput0, t, 0);
  if (!(q.w > MRGI_GBUFFER_VALID_THRESHOLD) || any(isnan(q.xyz)) || any(isinf(q.xyz)))
  {
    return MRGI_DIRECT_SHADOW_NO_OCCLUDER;
  }
  float z = (mrgiWorldToView[mrgiView] * vec4(q.xyz, 1.0)).z;
  if (-z > 0.0 && !isinf(z))
  {
    return -z;
  }
  return MRGI_DIRECT_SHADOW_NO_OCCLUDER;
}

float mrgiTexelDepth(ivec2 t)
{
  return texelFetch(mrgiInput2, t, 0).r;
}

bool mrgiTapOccludes(vec2 tap, out float depth)
{
  depth = 0.0;
  vec2 f = floor(tap);
  if (!(f.x >= 0.0 && f.y >= 0.0 && f.x < float(mrgiSize) && f.y < float(mrgiSize)))
  {
    return false;
  }
  ivec2 t = ivec2(f);
  float dt = mrgiTexelDepth(t);
  if (!(dt > 0.0))
  {
    return false;
  }
  depth = dt;
  return dt < mrgiPlaneDepth(t) - MRGI_DIRECT_SHADOW_BIAS_TEXELS * mrgiF;
}

int mrgiGridOccluders(int n, float w, out float depthSum)
{
  int count = 0;
  float sum = 0.0;
  for (int l = 0; l < n; ++l)
  {
    float ov = ((float(l) + 0.5) / float(n) * 2.0 - 1.0) * w;
    for (int k = 0; k < n; ++k)
    {
      float ou = ((float(k) + 0.5) / float(n) * 2.0 - 1.0) * w;
      float dt;
      if (mrgiTapOccludes(mrgiUV + vec2(ou, ov), dt))
      {
        ++count;
        sum += dt;
      }
    }
  }
  depthSum = sum;
  return count;
}

float mrgiClampRadius(float w)
{
  return min(max(w, MRGI_DIRECT_SHADOW_MIN_RADIUS), MRGI_DIRECT_SHADOW_MAX_RADIUS);
}

void main()
{
  ivec2 pixel = ivec2(gl_FragCoord.xy);
#if MRGI_DS_STAGE == 0
  gl_FragData[0] = vec4(mrgiPositionDepth(pixel), 0.0, 0.0, 1.0);
#elif MRGI_DS_STAGE == 2
  gl_FragData[0] = vec4(1.0) - texelFetch(mrgiInput0, pixel - mrgiOrigin, 0);
#else
  if (mrgiLevel >= 0)
  {
    // A level texel is the receiver at its block's centre pixel.
    int side = 1 << mrgiLevel;
    pixel = mrgiOrigin + min(pixel * side + ivec2(side / 2), mrgiFrameSize - ivec2(1));
  }
  vec4 e = texelFetch(mrgiInput0, pixel, 0);
  if (!(e.w > MRGI_GBUFFER_VALID_THRESHOLD))
  {
    discard; // no geometry: the factor stays 1
  }
  vec3 p = (mrgiVCToWC * vec4(e.xyz, 1.0)).xyz;
  vec3 n = mat3(mrgiVCToWC) * texelFetch(mrgiInput1, pixel, 0).xyz;
  float nn = sqrt(dot(n, n));
  if (any(isnan(p)) || any(isinf(p)) || !(nn > 0.0) || isinf(nn))
  {
    discard; // invalid receiver: factor 1
  }
  // The view that holds the receiver: smallest c, ties to the lowest index.
  int best = -1;
  float bestC = 0.0;
  for (int v = 0; v < mrgiViewCount; ++v)
  {
    vec3 q = (mrgiWorldToView[v] * vec4(p, 1.0)).xyz;
    float c = mrgiCentrality(v, q);
    if (c >= 0.0 && (best < 0 || c < bestC))
    {
      best = v;
      bestC = c;
    }
  }
  if (best != mrgiView)
  {
    discard; // another view (or none: factor 1) decides this pixel
  }
  mat4 M = mrgiWorldToView[mrgiView];
  vec4 terms = mrgiViewTerms[mrgiView];
  mrgiPerspective = terms.w > 0.5;
  mrgiScale = terms.xy;
  mrgiQ = (M * vec4(p, 1.0)).xyz;
  mrgiN = mat3(M) * (n / nn);
  float facing = mrgiPerspective ? -dot(mrgiN, mrgiQ) : mrgiN.z;
  if (facing < 0.0)
  {
    mrgiN = -mrgiN;
  }
  // Grazing receivers: the shadow fades out past the slope clamp
  // (mrgi_direct_shadow_grazing_weight()).
  float qn = length(mrgiQ);
  float cosine = mrgiPerspective ? (qn > 0.0 ? abs(facing) / qn : 1.0) : abs(facing);
  float c0 = 1.0 / sqrt(1.0 + MRGI_DIRECT_SHADOW_MAX_SLOPE * MRGI_DIRECT_SHADOW_MAX_SLOPE);
  float grazing = clamp((cosine - c0) / c0, 0.0, 1.0);
  if (!(grazing > 0.0))
  {
    discard; // factor 1
  }
  float S = float(mrgiSize);
  float sMin = min(mrgiScale.x, mrgiScale.y);
  mrgiD = -mrgiQ.z;
  mrgiT = 2.0 / (S * sMin);
  mrgiF = mrgiPerspective ? mrgiD * mrgiT : mrgiT;
  float nx = mrgiPerspective ? mrgiScale.x * mrgiQ.x / mrgiD : mrgiScale.x * mrgiQ.x;
  float ny = mrgiPerspective ? mrgiScale.y * mrgiQ.y / mrgiD : mrgiScale.y * mrgiQ.y;
  mrgiUV = vec2((nx * 0.5 + 0.5) * S, (ny * 0.5 + 0.5) * S);

  float factor = 1.0;
  float sum;
  if (mrgiMode == MRGI_DIRECT_SHADOW_HARD)
  {
    int side = MRGI_DIRECT_SHADOW_HARD_SIDE;
    int blocked = mrgiGridOccluders(side, 0.5 * float(side), sum);
    factor = 1.0 - grazing * float(blocked) / float(side * side);
  }
  else
  {
    float radius = mrgiLightRadius;
    float nearPlane = mrgiPerspective ? terms.z : 0.0;
    float dn = max(nearPlane, MRGI_DIRECT_SHADOW_SEARCH_NEAR * mrgiD);
    float theta = radius * sMin;
    float search = mrgiClampRadius(mrgiPerspective ? radius * (mrgiD - dn) / (mrgiD * dn * mrgiT)
                                                   : theta * (mrgiD - dn) / mrgiT);
    int blockers = mrgiGridOccluders(MRGI_DIRECT_SHADOW_BLOCKER_SIDE, search, sum);
    if (blockers > 0)
    {
      float db = sum / float(blockers);
      float width = mrgiClampRadius(mrgiPerspective ? radius * (mrgiD - db) / (mrgiD * db * mrgiT)
                                                    : theta * (mrgiD - db) / mrgiT);
      int side = mrgiSamplesSide;
      int blocked = mrgiGridOccluders(side, width, sum);
      factor = 1.0 - grazing * float(blocked) / float(side * side);
    }
  }
  if (mrgiLevel >= 0)
  {
    factor = 1.0 - factor;
  }
  gl_FragData[0] = vec4(factor, factor, factor, 1.0);
#endif
}
