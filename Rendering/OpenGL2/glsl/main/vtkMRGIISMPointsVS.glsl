// MRGI imperfect shadow maps, the point draw (ritschel-et-al-2008 3.3,
// ritschel-et-al-2011 5 and 6.1): ONE GL_POINTS draw of all points; point
// i (gl_VertexID) goes to VPL i mod V (mrgi_ism_atlas.h section 2), is
// projected with the VPL's cos-sphere map (vtkMRGIISMProjection.glsl,
// prepended: the same texel as the gathers' lookup) and placed at the
// centre of its atlas texel; the fragment shader writes its distance and
// GL_MIN blending keeps the nearest. C twin: mrgi_ism_atlas_render()
// (mrgi_ism_atlas.h section 5), which this follows step by step (in float).
in vec3 mrgiPoint;              // world-space point
uniform sampler2D mrgiVPLs;     // MRGI_VPL_TEXELS x V (mrgi_vpl.h layout)
uniform int mrgiVPLCount;       // V
uniform int mrgiTileSize;       // T
uniform int mrgiTilesPerRow;    // C
uniform vec2 mrgiAtlasSize;     // C T, R T
flat out float mrgiDepth;
void main()
{
  int vpl = gl_VertexID % mrgiVPLCount;
  vec3 position = texelFetch(mrgiVPLs, ivec2(MRGI_VPL_TEXEL_POSITION, vpl), 0).xyz;
  vec3 normal = texelFetch(mrgiVPLs, ivec2(MRGI_VPL_TEXEL_NORMAL, vpl), 0).xyz;
  vec3 v = mrgiPoint - position;
  float dist = length(v);
  float n2 = dot(normal, normal);
  mrgiDepth = dist;
  // Off-screen (clipped) when the point lands nowhere: an empty VPL (zero
  // or non-finite normal), a non-finite distance, a point at the VPL
  // (nearer than MRGI_ISM_MIN_DEPTH) or behind it (d.n < 0).
  bool lands = n2 > 0.0 && !isinf(n2) && !isnan(n2) && !isinf(dist) && !isnan(dist) &&
    dist >= float(MRGI_ISM_MIN_DEPTH);
  vec3 d = lands ? v / dist : vec3(0.0, 0.0, 1.0);
  lands = lands && dot(d, normal) >= 0.0;
  ivec2 texel = mrgiISMTileTexel(mrgiISMTileCoordinates(normal, d, float(mrgiTileSize)), mrgiTileSize);
  ivec2 atlas = mrgiISMAtlasTexel(vpl, texel, mrgiTileSize, mrgiTilesPerRow);
  vec2 ndc = (vec2(atlas) + 0.5) / mrgiAtlasSize * 2.0 - 1.0;
  gl_PointSize = 1.0;
  gl_Position = lands ? vec4(ndc, 0.0, 1.0) : vec4(2.0, 2.0, 2.0, 1.0);
}
