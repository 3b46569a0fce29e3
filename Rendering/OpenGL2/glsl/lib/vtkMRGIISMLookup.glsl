// MRGI imperfect shadow maps: visibility of a receiver from a VPL through
// that VPL's tile of the push-pulled ISM atlas (ritschel-et-al-2008 3.3,
// ritschel-et-al-2011 6.1), the shadow test of the VPL gathers with
// MRGI_INDIRECT_ISM. C twin: mrgi_ism_visibility() (mrgi_ism_visibility.h,
// "The test, step by step"), which this translates line by line, in float,
// in the same order. Needs vtkMRGIISMProjection.glsl (the frame and the
// cos-sphere coordinates, shared with the ISM point draw).
uniform sampler2D mrgiISMAtlas;    // R32F, mrgi_ism_atlas.h layout
uniform int mrgiISMTileSize;       // T
uniform int mrgiISMTilesPerRow;    // C
uniform float mrgiISMRelativeBias; // mrgi_ism_lookup_params
uniform float mrgiISMTexelBias;
uniform int mrgiISMPCF;            // 0: one texel; 1: 2x2 bilinear PCF
uniform float mrgiISMMaxTexelAngle; // step 2b; 0: off

// Step 5's compare at tile texel `texel` (clamped to the tile) of VPL `vpl`.
float mrgiISMTexelVisible(int vpl, ivec2 texel, float biased)
{
  ivec2 atlas = mrgiISMAtlasTexel(vpl, texel, mrgiISMTileSize, mrgiISMTilesPerRow);
  return biased <= texelFetch(mrgiISMAtlas, atlas, 0).r ? 1.0 : 0.0;
}

// V in [0, 1] of world-space receiver P from VPL `vpl` (tile index) at
// world-space position v with normal n (need not be unit).
float mrgiISMVisibility(int vpl, vec3 v, vec3 n, vec3 P)
{
  // 1. w = x - v, dist = |w|.
  vec3 w = P - v;
  float dist = sqrt(dot(w, w));
  if (!(dist >= MRGI_ISM_MIN_DEPTH) || isinf(dist)) { return 1.0; }
  // 2. d = w / dist, c = d . n (n normalized as the twin does).
  float nlen = sqrt(dot(n, n));
  if (!(nlen > 0.0) || isinf(nlen)) { return 1.0; }
  vec3 nn = n / nlen;
  vec3 d = w / dist;
  float c = dot(d, nn);
  if (!(c > 0.0)) { return 1.0; }
  float tile = float(mrgiISMTileSize);
  // 2b. Grazing: the texel is wider than the test trusts.
  if (mrgiISMMaxTexelAngle > 0.0 && 2.0 / (tile * c) > mrgiISMMaxTexelAngle) { return 1.0; }
  // 3. Cos-sphere tile coordinates (ritschel-et-al-2011 6.1).
  vec2 uv = mrgiISMTileCoordinates(nn, d, tile);
  // 4. Bias (ritschel-et-al-2008 3.3): relative plus texel footprints.
  float bias = dist * (mrgiISMRelativeBias +
    mrgiISMTexelBias * 2.0 / (tile * max(c, MRGI_ISM_BIAS_MIN_COS)));
  float biased = dist - bias;
  // 5. One texel, or 2x2 bilinear PCF clamped to the tile.
  if (mrgiISMPCF == 0)
  {
    return mrgiISMTexelVisible(vpl, mrgiISMTileTexel(uv, mrgiISMTileSize), biased);
  }
  vec2 c2 = uv - 0.5;
  vec2 f0 = floor(c2);
  vec2 fr = c2 - f0;
  ivec2 i0 = ivec2(f0);
  int last = mrgiISMTileSize - 1;
  ivec2 a = clamp(i0, ivec2(0), ivec2(last));
  ivec2 b = clamp(i0 + 1, ivec2(0), ivec2(last));
  float v00 = mrgiISMTexelVisible(vpl, ivec2(a.x, a.y), biased);
  float v10 = mrgiISMTexelVisible(vpl, ivec2(b.x, a.y), biased);
  float v01 = mrgiISMTexelVisible(vpl, ivec2(a.x, b.y), biased);
  float v11 = mrgiISMTexelVisible(vpl, ivec2(b.x, b.y), biased);
  // Lerps as a + (b - a) f: exactly 1 (0) when all four are 1 (0).
  float h0 = v00 + (v10 - v00) * fr.x;
  float h1 = v01 + (v11 - v01) * fr.x;
  return h0 + (h1 - h0) * fr.y;
}
