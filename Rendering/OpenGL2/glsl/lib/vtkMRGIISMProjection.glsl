// MRGI imperfect shadow maps: the VPL frame and the cos-sphere projection
// (ritschel-et-al-2011 6.1), shared by the ISM point draw
// (vtkMRGIImperfectShadowMaps) and the shadow lookup of the gathers
// (vtkMRGIISMLookup.glsl), so that both map a direction to the same texel.
// C twins: mrgi_ism_vpl_frame(), mrgi_ism_cos_sphere_forward() and
// mrgi_ism_point_texel() (mrgi_ism_atlas.h sections 1 and 3), which this
// translates line by line (in float; the C twin computes in double).

// Orthonormal tangents t, b of the unit normal n (Duff et al. 2017,
// "Building an orthonormal basis, revisited"): the same branch-free
// construction as mrgi_ism_vpl_frame().
void mrgiISMFrame(vec3 n, out vec3 t, out vec3 b)
{
  float s = n.z >= 0.0 ? 1.0 : -1.0;
  float a = -1.0 / (s + n.z);
  float c = n.x * n.y * a;
  t = vec3(1.0 + s * n.x * n.x * a, s * c, -s * n.x);
  b = vec3(c, s + n.y * n.y * a, -n.y);
}

// Tile-local continuous coordinates (u, v) in [0, T] of the unit direction
// d seen from a VPL with unit normal n: ((s + 1) / 2 T, (t + 1) / 2 T) with
// (s, t) = (d . t_n, d . b_n). Only meaningful for dot(d, n) >= 0.
vec2 mrgiISMTileCoordinates(vec3 n, vec3 d, float tileSize)
{
  vec3 t;
  vec3 b;
  mrgiISMFrame(n, t, b);
  return (vec2(dot(d, t), dot(d, b)) + 1.0) * 0.5 * tileSize;
}

// The texel of tile coordinates (u, v): floor, clamped to the tile.
ivec2 mrgiISMTileTexel(vec2 uv, int tileSize)
{
  return clamp(ivec2(floor(uv)), ivec2(0), ivec2(tileSize - 1));
}

// The atlas texel of tile texel `texel` of VPL `vpl`: tile column
// vpl % tilesPerRow, row vpl / tilesPerRow (mrgi_ism_atlas.h section 1).
ivec2 mrgiISMAtlasTexel(int vpl, ivec2 texel, int tileSize, int tilesPerRow)
{
  return ivec2(vpl % tilesPerRow, vpl / tilesPerRow) * tileSize + texel;
}
