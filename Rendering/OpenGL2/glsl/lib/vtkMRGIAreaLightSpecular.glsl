// MRGI area light, Phong specular direct light, without visibility or with
// the including shader's (nichols-penmatsa-wyman-2010 sections 3.2.1 and
// 3.3.3). C twins: mrgi_area_light_phong_lobe(),
// mrgi_area_light_phong_refinement(), mrgi_area_light_specular(),
// mrgi_area_light_specular_visible(), mrgi_area_light_specular_classify(),
// mrgi_area_light_lobe_grid_cells() and mrgi_area_light_texture_sample()
// (mrgi_area_light.h, "Phong specular", "The texture pyramid" and
// "Precision"), which this translates line by line, in float, in the same
// order; world space throughout. A function library: no #version, no
// main(); put it after VTK's system declarations and the core's constants
// block (vtkMRGIShaderUtilities::Defines()). (No VTK shader tag may appear
// in these comments: VTK would replace it.)
//
// With vtkMRGIAreaLightDiffuse.glsl in the same shader: put the diffuse
// library FIRST; it ends with `#define MRGI_AREA_LIGHT_DIFFUSE_DECLARED`,
// so that the uniforms both use (same names, same quantities) are declared
// once (vtkMRGIShaderLibraries composes them in that order).
//
// Known difference: for 0 < n < 1/126, C's exp2f(-1/n) is a subnormal float
// (tan(theta_h) huge or infinite there), which GPUs flush to 0 (tanHalf =
// FLT_MAX); such powers mean nothing for a highlight, and the twins agree
// from n = 1/126 up (TestMRGIAreaLightSpecular tests n = 0 and 0.01..128).
//
// Uniforms: ::mrgi_area_light_uniforms (vtkMRGIAreaLight::SetShaderUniforms()
// sets them all); the samples texture is the core's ::mrgi_area_light_sample
// records as in the diffuse library. The texture pyramid
// (vtkMRGIAreaLight::GetPyramidTexture()) is one GL texture whose mip level
// k is pyramid level k (RGB32F, GL's first row = the picture's top row, as
// the core stores it); the shader reads it with texelFetch() only, doing
// the trilinear filter itself (hardware filtering quantizes its weights).
#ifndef MRGI_AREA_LIGHT_DIFFUSE_DECLARED
uniform sampler2D mrgiAreaSamples;
uniform int mrgiAreaSampleFirst; // the samples summed: first .. first + count - 1
uniform int mrgiAreaSampleCount;
uniform vec3 mrgiAreaCenter;
uniform vec3 mrgiAreaNormal;
uniform vec3 mrgiAreaCorners[4];
uniform int mrgiAreaTwoSided;
#endif
uniform vec3 mrgiAreaAxisU;        // u / |u|
uniform vec3 mrgiAreaAxisV;        // v / |v|
uniform float mrgiAreaHalfU;       // |u| / 2
uniform float mrgiAreaHalfV;       // |v| / 2
uniform vec3 mrgiAreaScale;        // intensity * color
uniform ivec2 mrgiAreaTextureSize; // pyramid level-0 size (1, 1 without texture)
uniform int mrgiAreaTextureLevels; // pyramid levels (1 without texture)
uniform int mrgiAreaTextured;      // 0: the lobe grid reads 1 (the twin's NULL pyramid)
uniform sampler2D mrgiAreaPyramid;

// Shadowed highlights (nichols-penmatsa-wyman-2010 3.3.1-3.3.3; C twin
// mrgi_area_light_specular_visible(), mrgi_area_light.h "Shadowed
// highlights"): a shader that defines MRGI_AREA_SPECULAR_VISIBILITY before
// this library defines these two functions after it; the sums weight each
// sample's term by the first (its visibility bit) and each lobe-grid cell's
// term by the second (query = (b + G/2) G + (a + G/2), the variance shadow
// query's visibility in [0, 1]; the dropped corner takes the mean of
// queries G G - 2 and G G - 1 - G). The path does not depend on them.
// With MRGI_AREA_SPECULAR_BATCHES as well, the sample sum covers only the
// samples mrgiSpecularBatchFirst .. + mrgiSpecularBatchCount - 1 (a shader
// that marches each sample draws the samples in batches; the path is still
// decided from all of them).
#ifdef MRGI_AREA_SPECULAR_VISIBILITY
bool mrgiAreaSpecularSampleVisible(int j, vec3 samplePosition, vec3 sampleNormal);
float mrgiAreaSpecularQueryVisibility(int query);
#endif
#ifdef MRGI_AREA_SPECULAR_BATCHES
uniform int mrgiSpecularBatchFirst;
uniform int mrgiSpecularBatchCount;
#endif

// ::mrgi_area_light_lobe. FLT_MAX is MRGI_MULTIRES_FLT_MAX (the core's
// spelling of FLT_MAX for GLSL).
struct mrgiAreaLightLobe
{
  vec3 reflect;          // R = reflect(-V, N), unit
  float peak;            // max over the rectangle of max(0, R.w)^n
  float tanHalf;         // tan(theta_h); FLT_MAX when n = 0
  bool reachesPlane;     // R meets the light's plane at some t > 0
  bool hitsLight;        // ... inside the rectangle
  float distance;        // t (0 when !reachesPlane)
  float inverseDistance; // 1 / t (0 when !reachesPlane)
  float width;           // 2 t tan(theta_h); FLT_MAX when !reachesPlane or unbounded
  float hitU;            // (H - c).axis_u
  float hitV;            // (H - c).axis_v
};

// al_normalizef(): false (out zeroed) when v has no (finite) length.
bool mrgiAreaNormalize(vec3 v, out vec3 unit)
{
  float length2 = dot(v, v);
  if (!(length2 > 0.0) || !(length2 < MRGI_MULTIRES_FLT_MAX))
  {
    unit = vec3(0.0);
    return false;
  }
  float inverseLength = 1.0 / sqrt(length2);
  unit = v * inverseLength;
  return true;
}

// al_bilinear(): level `level` at GL coordinates (s, tGl), texel centres at
// (x + 1/2) / W, clamp to edge. The level's size is GL's (and the core's)
// max(1, W >> k) x max(1, H >> k), not textureSize(): llvmpipe answers a
// size query for the level of one fragment of the SIMD group only (measured:
// wrong sizes, hence wrong texels, where neighbours read other levels).
vec3 mrgiAreaBilinear(int level, float s, float tGl)
{
  int w = max(1, mrgiAreaTextureSize.x >> level);
  int h = max(1, mrgiAreaTextureSize.y >> level);
  float x = min(max(s * float(w) - 0.5, -1.0), float(w));
  float y = min(max(tGl * float(h) - 0.5, -1.0), float(h));
  float x0f = floor(x);
  float y0f = floor(y);
  float fx = x - x0f;
  float fy = y - y0f;
  int x0 = clamp(int(x0f), 0, w - 1);
  int x1 = clamp(int(x0f) + 1, 0, w - 1);
  int y0 = clamp(int(y0f), 0, h - 1);
  int y1 = clamp(int(y0f) + 1, 0, h - 1);
  vec3 t00 = texelFetch(mrgiAreaPyramid, ivec2(x0, y0), level).rgb;
  vec3 t10 = texelFetch(mrgiAreaPyramid, ivec2(x1, y0), level).rgb;
  vec3 t01 = texelFetch(mrgiAreaPyramid, ivec2(x0, y1), level).rgb;
  vec3 t11 = texelFetch(mrgiAreaPyramid, ivec2(x1, y1), level).rgb;
  vec3 bottom = t00 * (1.0 - fx) + t10 * fx;
  vec3 top = t01 * (1.0 - fx) + t11 * fx;
  return bottom * (1.0 - fy) + top * fy;
}

// mrgi_area_light_texture_sample(): trilinear at texture coordinates (s, t)
// (t = 0 at the picture's bottom) and level of detail lod, with 8
// texelFetch()es.
vec3 mrgiAreaTextureSample(float s, float t, float lod)
{
  float last = float(mrgiAreaTextureLevels - 1);
  float l = lod > 0.0 ? (lod < last ? lod : last) : 0.0;
  float k0f = floor(l);
  int k0 = int(k0f);
  int k1 = k0 + 1 < mrgiAreaTextureLevels ? k0 + 1 : k0;
  float f = l - k0f;
  float tGl = 1.0 - t; // GL's first row is the picture's top row
  vec3 a = mrgiAreaBilinear(k0, s, tGl);
  vec3 b = mrgiAreaBilinear(k1, s, tGl);
  return a * (1.0 - f) + b * f;
}

// al_edge_max_cos(): largest cos(R, y - P) over the edge from a to b
// (relative to P).
float mrgiAreaEdgeMaxCos(vec3 r, vec3 a, vec3 b)
{
  float la = sqrt(dot(a, a));
  float lb = sqrt(dot(b, b));
  float best = -1.0;
  if (la > 0.0)
  {
    best = max(best, dot(r, a) / la);
  }
  if (lb > 0.0)
  {
    best = max(best, dot(r, b) / lb);
  }
  vec3 m = cross(a, b);
  float lm2 = dot(m, m);
  if (lm2 > 0.0)
  {
    float rm = dot(r, m) / lm2;
    vec3 q = r - rm * m;
    vec3 aq = cross(a, q);
    vec3 qb = cross(q, b);
    if (dot(aq, m) > 0.0 && dot(qb, m) > 0.0)
    {
      best = max(best, sqrt(dot(q, q)));
    }
  }
  return best;
}

// mrgi_area_light_phong_lobe(): the lobe of receiver P (normal N, towards-eye
// V, both normalized here) for Phong power n >= 0.
mrgiAreaLightLobe mrgiAreaLightPhongLobe(vec3 P, vec3 N, vec3 V, float power)
{
  mrgiAreaLightLobe lobe = mrgiAreaLightLobe(
    vec3(0.0), 0.0, 0.0, false, false, 0.0, 0.0, MRGI_MULTIRES_FLT_MAX, 0.0, 0.0);
  // Half-maximum cone: cos(theta_h)^n = 1/2.
  float cosHalf = power > 0.0 ? exp2(-1.0 / power) : 0.0;
  lobe.tanHalf = cosHalf > 0.0 ? sqrt(max(0.0, 1.0 - cosHalf * cosHalf)) / cosHalf
                               : MRGI_MULTIRES_FLT_MAX;
  vec3 n;
  vec3 v;
  if (!mrgiAreaNormalize(N, n) || !mrgiAreaNormalize(V, v))
  {
    return lobe;
  }
  float nv = dot(n, v);
  vec3 reflected = 2.0 * nv * n - v;
  vec3 r;
  if (!mrgiAreaNormalize(reflected, r))
  {
    return lobe;
  }
  lobe.reflect = r;
  // Where R meets the light's plane.
  vec3 toCenter = mrgiAreaCenter - P;
  float denominator = dot(r, mrgiAreaNormal);
  float t = denominator != 0.0 ? dot(toCenter, mrgiAreaNormal) / denominator : 0.0;
  if (t > 0.0 && t < MRGI_MULTIRES_FLT_MAX)
  {
    lobe.reachesPlane = true;
    lobe.distance = t;
    lobe.inverseDistance = 1.0 / t;
    float width = 2.0 * t * lobe.tanHalf;
    lobe.width = width < MRGI_MULTIRES_FLT_MAX ? width : MRGI_MULTIRES_FLT_MAX;
    lobe.hitU = t * dot(r, mrgiAreaAxisU) - dot(toCenter, mrgiAreaAxisU);
    lobe.hitV = t * dot(r, mrgiAreaAxisV) - dot(toCenter, mrgiAreaAxisV);
    lobe.hitsLight = abs(lobe.hitU) <= mrgiAreaHalfU && abs(lobe.hitV) <= mrgiAreaHalfV;
  }
  float peakCos = 1.0;
  if (!lobe.hitsLight)
  {
    // The exact peak off the rectangle: the best point of its four edges.
    peakCos = -1.0;
    for (int k = 0; k < 4; ++k)
    {
      vec3 a = mrgiAreaCorners[k] - P;
      vec3 b = mrgiAreaCorners[k == 3 ? 0 : k + 1] - P;
      peakCos = max(peakCos, mrgiAreaEdgeMaxCos(r, a, b));
    }
    peakCos = min(peakCos, 1.0);
  }
  lobe.peak = peakCos > 0.0 ? pow(peakCos, power) : 0.0;
  return lobe;
}

// mrgi_area_light_phong_refinement(): m = s (1/e + 1/t) / (2 tan(theta_h));
// refine where m > 1. eyeDistance e > 0, texelSize s >= 0 (world units).
float mrgiAreaLightPhongRefinement(mrgiAreaLightLobe lobe, float eyeDistance, float texelSize)
{
  if (!(eyeDistance > 0.0))
  {
    return MRGI_MULTIRES_FLT_MAX;
  }
  if (!(lobe.tanHalf < MRGI_MULTIRES_FLT_MAX))
  {
    return 0.0; // n = 0: the lobe is the hemisphere, nothing to resolve
  }
  if (!(lobe.tanHalf > 0.0))
  {
    return MRGI_MULTIRES_FLT_MAX; // a lobe too sharp for float: always refine
  }
  float metric = texelSize * (1.0 / eyeDistance + lobe.inverseDistance) / (2.0 * lobe.tanHalf);
  return metric < MRGI_MULTIRES_FLT_MAX ? metric : MRGI_MULTIRES_FLT_MAX;
}

// al_transfer(): the form-factor term T of one emitter patch, 0 when
// skipped; d = patch - receiver, n the receiver's unit normal.
float mrgiAreaTransfer(vec3 d, vec3 patchNormal, float patchArea, vec3 n, out float r2)
{
  r2 = dot(d, d);
  if (!(r2 > 0.0))
  {
    return 0.0; // on the patch: direction undefined
  }
  float cosIr = dot(n, d);
  float cosJr = -dot(patchNormal, d);
  if (mrgiAreaTwoSided != 0)
  {
    cosJr = abs(cosJr);
  }
  if (!(cosIr > 0.0) || !(cosJr > 0.0))
  {
    return 0.0; // receiver facing away, or behind the (one-sided) light
  }
  return patchArea * (cosIr * cosJr / r2) / (MRGI_PI * r2 + patchArea);
}

// mrgi_area_light_lobe_grid_cells(), first part: the grid's spacings h_u,
// h_v (the half-maximum ellipse's half extents along u and v); false when
// the lobe has no finite footprint.
bool mrgiAreaLobeGridSpacing(mrgiAreaLightLobe lobe, out float hu, out float hv)
{
  vec3 r = lobe.reflect;
  float rn = dot(r, mrgiAreaNormal);
  float c = max(abs(rn), MRGI_AREA_LIGHT_MIN_COS);
  vec3 along = r - rn * mrgiAreaNormal;
  vec3 e1;
  if (!(sqrt(dot(along, along)) > MRGI_AREA_LIGHT_MIN_ALONG) || !mrgiAreaNormalize(along, e1))
  {
    e1 = mrgiAreaAxisU;
  }
  vec3 e2 = cross(mrgiAreaNormal, e1);
  // Semi-axes of the half-maximum ellipse; its half extents along u and v.
  float halfWidth = lobe.distance * lobe.tanHalf;
  float a1 = halfWidth / c;
  float a2 = halfWidth;
  float pu1 = a1 * dot(e1, mrgiAreaAxisU);
  float pu2 = a2 * dot(e2, mrgiAreaAxisU);
  float pv1 = a1 * dot(e1, mrgiAreaAxisV);
  float pv2 = a2 * dot(e2, mrgiAreaAxisV);
  hu = sqrt(pu1 * pu1 + pu2 * pu2);
  hv = sqrt(pv1 * pv1 + pv2 * pv2);
  return hu > 0.0 && hu < MRGI_MULTIRES_FLT_MAX && hv > 0.0 && hv < MRGI_MULTIRES_FLT_MAX;
}

// mrgi_area_light_lobe_grid_cells(), one cell: cell (a, b), a, b in
// -G/2..G/2, clipped to the rectangle; false when nothing is left. Its
// centre (cu, cv) in the light's axes, `position` = c + cu u + cv v (the
// point the sum lights from and the variance shadow query aims at), area.
bool mrgiAreaLobeGridCell(mrgiAreaLightLobe lobe, float hu, float hv, int a, int b,
  out vec3 position, out float cu, out float cv, out float cellArea)
{
  position = vec3(0.0);
  cu = 0.0;
  cv = 0.0;
  cellArea = 0.0;
  float loV = max(lobe.hitV + (float(b) - 0.5) * hv, -mrgiAreaHalfV);
  float hiV = min(lobe.hitV + (float(b) + 0.5) * hv, mrgiAreaHalfV);
  float loU = max(lobe.hitU + (float(a) - 0.5) * hu, -mrgiAreaHalfU);
  float hiU = min(lobe.hitU + (float(a) + 0.5) * hu, mrgiAreaHalfU);
  if (!(hiV > loV) || !(hiU > loU))
  {
    return false;
  }
  cellArea = (hiU - loU) * (hiV - loV);
  cu = 0.5 * (loU + hiU);
  cv = 0.5 * (loV + hiV);
  position = mrgiAreaCenter + cu * mrgiAreaAxisU + cv * mrgiAreaAxisV;
  return true;
}

#ifdef MRGI_AREA_SPECULAR_VISIBILITY
// al_cell_visibility(): lobe grid cell `cell` (raster order, (b + G/2) G +
// (a + G/2)) takes query `cell`'s visibility; the corner the variance
// shadow query drops (the last cell) the mean of its two edge neighbours.
float mrgiAreaLobeCellVisibility(int cell)
{
  const int corner = MRGI_VOXEL_VSM_QUERIES; // G G - 1
  if (cell < corner)
  {
    return mrgiAreaSpecularQueryVisibility(cell);
  }
  return 0.5 * (mrgiAreaSpecularQueryVisibility(corner - 1) +
    mrgiAreaSpecularQueryVisibility(corner - MRGI_AREA_LIGHT_LOBE_GRID));
}
#endif

// al_lobe_grid_sum(): the 5 x 5 lobe grid around H (a finite footprint:
// mrgiAreaLobeGridSpacing() true); adds into sum, counts cells.
void mrgiAreaLobeGrid(vec3 P, vec3 n, mrgiAreaLightLobe lobe, float power, float normalisation,
  inout vec3 sum, inout int cells)
{
  vec3 r = lobe.reflect;
  float hu;
  float hv;
  mrgiAreaLobeGridSpacing(lobe, hu, hv);
  float lod = log2(max(hu * float(mrgiAreaTextureSize.x) / (2.0 * mrgiAreaHalfU),
    hv * float(mrgiAreaTextureSize.y) / (2.0 * mrgiAreaHalfV)));
  const int halfGrid = MRGI_AREA_LIGHT_LOBE_GRID / 2;
  for (int b = -halfGrid; b <= halfGrid; ++b)
  {
    for (int a = -halfGrid; a <= halfGrid; ++a)
    {
      vec3 position;
      float cu;
      float cv;
      float cellArea;
      if (!mrgiAreaLobeGridCell(lobe, hu, hv, a, b, position, cu, cv, cellArea))
      {
        continue;
      }
      ++cells;
      vec3 texel = vec3(1.0);
      if (mrgiAreaTextured != 0)
      {
        texel = mrgiAreaTextureSample(cu / (2.0 * mrgiAreaHalfU) + 0.5,
          cv / (2.0 * mrgiAreaHalfV) + 0.5, lod);
      }
      vec3 d = position - P;
      float r2;
      float transfer = mrgiAreaTransfer(d, mrgiAreaNormal, cellArea, n, r2);
      float rw = dot(r, d);
      if (!(transfer > 0.0) || !(rw > 0.0))
      {
        continue;
      }
      float weight = normalisation * pow(rw / sqrt(r2), power) * transfer;
#ifdef MRGI_AREA_SPECULAR_VISIBILITY
      weight *= mrgiAreaLobeCellVisibility((b + halfGrid) * MRGI_AREA_LIGHT_LOBE_GRID + a + halfGrid);
#endif
      sum += mrgiAreaScale * texel * weight;
    }
  }
}

// al_specular_classify() (mrgi_area_light_specular_classify()): the early-
// outs, the lobe, the samples inside the half-maximum cone (all of the
// light's samples, mrgiAreaSampleFirst .. + mrgiAreaSampleCount - 1,
// visible or not) and the path, MRGI_AREA_LIGHT_SPECULAR_*. `n` receives
// the unit normal; lobe and samplesInLobe are zeroed after early-outs 1 and
// 2 (and zero normals or views). At most MRGI_AREA_LIGHT_MAX_SAMPLES loop
// iterations, well within llvmpipe's per-invocation loop budget.
int mrgiAreaLightSpecularClassify(vec3 P, vec3 N, vec3 V, float power, out vec3 n,
  out mrgiAreaLightLobe lobe, out int samplesInLobe)
{
  lobe = mrgiAreaLightLobe(vec3(0.0), 0.0, 0.0, false, false, 0.0, 0.0, 0.0, 0.0, 0.0);
  samplesInLobe = 0;
  vec3 v;
  float side = dot(mrgiAreaNormal, P - mrgiAreaCenter);
  bool facing = false;
  if (!mrgiAreaNormalize(N, n) || !mrgiAreaNormalize(V, v))
  {
    return MRGI_AREA_LIGHT_SPECULAR_FACING_AWAY;
  }
  // Early-out 1: behind a one-sided light or in its plane.
  if (mrgiAreaTwoSided != 0 ? side == 0.0 : !(side > 0.0))
  {
    return MRGI_AREA_LIGHT_SPECULAR_BEHIND;
  }
  // Early-out 2: facing away from every corner.
  for (int k = 0; k < 4; ++k)
  {
    facing = facing || dot(n, mrgiAreaCorners[k] - P) > 0.0;
  }
  if (!facing)
  {
    return MRGI_AREA_LIGHT_SPECULAR_FACING_AWAY;
  }
  lobe = mrgiAreaLightPhongLobe(P, n, v, power);
  // Lobe miss ("we discard fragments where the Phong lobe misses the light").
  if (!(lobe.peak >= MRGI_AREA_LIGHT_LOBE_DISCARD))
  {
    return MRGI_AREA_LIGHT_SPECULAR_LOBE_MISS;
  }
  vec3 r = lobe.reflect;
  for (int j = mrgiAreaSampleFirst; j < mrgiAreaSampleFirst + mrgiAreaSampleCount; ++j)
  {
    vec4 position = texelFetch(mrgiAreaSamples, ivec2(MRGI_AREA_LIGHT_SAMPLE_TEXEL_POSITION, j), 0);
    vec3 d = position.xyz - P;
    vec3 sampleNormal = texelFetch(mrgiAreaSamples, ivec2(MRGI_AREA_LIGHT_SAMPLE_TEXEL_NORMAL, j), 0).xyz;
    float r2;
    float transfer = mrgiAreaTransfer(d, sampleNormal, position.w, n, r2);
    float rw = dot(r, d);
    if (!(transfer > 0.0) || !(rw > 0.0))
    {
      continue;
    }
    if (pow(rw / sqrt(r2), power) >= MRGI_AREA_LIGHT_LOBE_CUTOFF)
    {
      ++samplesInLobe;
    }
  }
  // Too few samples in the lobe: "we directly sample the light texture 25
  // times inside the lobe using a mipmap level dependent on the lobe size".
  float hu;
  float hv;
  if (samplesInLobe < MRGI_AREA_LIGHT_LOBE_MIN_SAMPLES && lobe.reachesPlane &&
    mrgiAreaLobeGridSpacing(lobe, hu, hv))
  {
    return MRGI_AREA_LIGHT_SPECULAR_LOBE_GRID;
  }
  return MRGI_AREA_LIGHT_SPECULAR_SAMPLES;
}

// The sum of mrgi_area_light_specular_visible() for a classified receiver
// (unit normal n, its lobe and path from mrgiAreaLightSpecularClassify()):
// S, 0 on the early-out paths; gridCells counts the lobe grid's cells on
// the light. The sample sum covers the samples of this draw: all of them,
// or with MRGI_AREA_SPECULAR_BATCHES the range mrgiSpecularBatchFirst ..
// + mrgiSpecularBatchCount - 1 of them (batched visibility marches).
vec3 mrgiAreaLightSpecularSum(vec3 P, vec3 n, mrgiAreaLightLobe lobe, float power, int path,
  out int gridCells)
{
  gridCells = 0;
  vec3 sum = vec3(0.0);
  // Normalised Phong: (n + 2) / (2 pi) times the pi of cos dw = pi T.
  float normalisation = 0.5 * (power + 2.0);
  if (path == MRGI_AREA_LIGHT_SPECULAR_LOBE_GRID)
  {
    mrgiAreaLobeGrid(P, n, lobe, power, normalisation, sum, gridCells);
  }
  else if (path == MRGI_AREA_LIGHT_SPECULAR_SAMPLES)
  {
    vec3 r = lobe.reflect;
    int first = mrgiAreaSampleFirst;
    int end = mrgiAreaSampleFirst + mrgiAreaSampleCount;
#ifdef MRGI_AREA_SPECULAR_BATCHES
    first = max(first, mrgiSpecularBatchFirst);
    end = min(end, mrgiSpecularBatchFirst + mrgiSpecularBatchCount);
#endif
    for (int j = first; j < end; ++j)
    {
      vec4 position = texelFetch(mrgiAreaSamples, ivec2(MRGI_AREA_LIGHT_SAMPLE_TEXEL_POSITION, j), 0);
      vec3 d = position.xyz - P;
      vec3 sampleNormal = texelFetch(mrgiAreaSamples, ivec2(MRGI_AREA_LIGHT_SAMPLE_TEXEL_NORMAL, j), 0).xyz;
      float r2;
      float transfer = mrgiAreaTransfer(d, sampleNormal, position.w, n, r2);
      float rw = dot(r, d);
      if (!(transfer > 0.0) || !(rw > 0.0))
      {
        continue;
      }
#ifdef MRGI_AREA_SPECULAR_VISIBILITY
      if (!mrgiAreaSpecularSampleVisible(j, position.xyz, sampleNormal))
      {
        continue; // occluded
      }
#endif
      float weight = normalisation * pow(rw / sqrt(r2), power) * transfer;
      vec3 radiance = texelFetch(mrgiAreaSamples, ivec2(MRGI_AREA_LIGHT_SAMPLE_TEXEL_RADIANCE, j), 0).rgb;
      sum += radiance * weight;
    }
  }
  return sum;
}

// mrgi_area_light_specular() with its info: S (the composite shows k_s c_s S)
// at receiver P, normal N and towards-eye V (normalized here), Phong power
// n >= 0; `path` is an MRGI_AREA_LIGHT_SPECULAR_* value, samplesInLobe the
// samples with max(0, R.w)^n >= MRGI_AREA_LIGHT_LOBE_CUTOFF, gridCells the
// lobe grid's cells on the light, lobe the lobe (zeroed after early-outs).
// Sums samples mrgiAreaSampleFirst .. + mrgiAreaSampleCount - 1 and decides
// the lobe grid from those alone: the twin's parity needs all of the
// light's samples in one call. With MRGI_AREA_SPECULAR_VISIBILITY, the
// terms are weighted by the including shader's visibility (see the top).
vec3 mrgiAreaLightSpecularInfo(vec3 P, vec3 N, vec3 V, float power, out int path,
  out int samplesInLobe, out int gridCells, out mrgiAreaLightLobe lobe)
{
  vec3 n;
  path = mrgiAreaLightSpecularClassify(P, N, V, power, n, lobe, samplesInLobe);
  return mrgiAreaLightSpecularSum(P, n, lobe, power, path, gridCells);
}

// S at receiver P (see mrgiAreaLightSpecularInfo()); `path` says how it was
// computed (MRGI_AREA_LIGHT_SPECULAR_*).
vec3 mrgiAreaLightSpecular(vec3 P, vec3 N, vec3 V, float power, out int path)
{
  int samplesInLobe;
  int gridCells;
  mrgiAreaLightLobe lobe;
  return mrgiAreaLightSpecularInfo(P, N, V, power, path, samplesInLobe, gridCells, lobe);
}
