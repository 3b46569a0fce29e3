// MRGI grid VPL selection (nichols-wyman-2009 section 3.1), one view at a
// time, in two stages so that no fragment loops over a whole block (llvmpipe
// stops every shader invocation after 65535 loop iterations in all, which a
// 256 x 256 block exceeds) and float sums stay short:
// - MRGI_GRID_STAGE 0 ("rows"): fragment (i, y) reduces row y of block column
//   i: output 0 = sums of flux rgb and area of its usable texels, output 1 =
//   (x of the usable texel nearest to the block's centre column, its squared
//   x distance, 1 if the row has a usable texel, 0);
// - MRGI_GRID_STAGE 1 ("blocks"): fragment (k, row) of the VPL texture is
//   texel k of VPL firstVPL + row; it combines the rows of its block.
// C twin: mrgi_vpl_select_grid() (mrgi_vpl.h), which defines the block
// bounds, the representative texel (nearest to the block centre, ties to the
// lowest index y * S + x: the lowest x within a row, then the lowest row) and
// the sums mirrored here.
in vec2 texCoord; // bound by vtkOpenGLQuadHelper; these passes address texels by gl_FragCoord
uniform sampler2D mrgiRSMPosition;
uniform sampler2D mrgiRSMNormal;
uniform sampler2D mrgiRSMFlux;
uniform sampler2D mrgiRowSums;  // stage 1: output 0 of stage 0 (G x S)
uniform sampler2D mrgiRowBest;  // stage 1: output 1 of stage 0 (G x S)
uniform int mrgiRSMSize;     // S
uniform int mrgiGridSide;    // G
uniform int mrgiFirstVPL;    // VPL number (texture row) of this view's block (0, 0)
//VTK::Output::Dec
void main()
{
  ivec2 fragment = ivec2(gl_FragCoord.xy);
#if MRGI_GRID_STAGE == 0
  int bi = fragment.x;
  int y = fragment.y;
  int x0 = (bi * mrgiRSMSize) / mrgiGridSide;
  int x1 = ((bi + 1) * mrgiRSMSize) / mrgiGridSide;
  float cx = 0.5 * float(x0 + x1);
  vec3 flux = vec3(0.0);
  float area = 0.0;
  float nearest = 3.4e38;
  int best = -1;
  for (int x = x0; x < x1; ++x)
  {
    vec4 p = texelFetch(mrgiRSMPosition, ivec2(x, y), 0);
    if (p.w <= MRGI_VALID_THRESHOLD) { continue; }
    vec4 f = texelFetch(mrgiRSMFlux, ivec2(x, y), 0);
    vec3 n = texelFetch(mrgiRSMNormal, ivec2(x, y), 0).xyz;
    // Usable texels only (mrgi_vpl.h): finite values, non-negative flux and area.
    if (any(isnan(p.xyz)) || any(isinf(p.xyz)) || any(isnan(n)) || any(isinf(n)) ||
      any(isnan(f)) || any(isinf(f)) || any(lessThan(f, vec4(0.0)))) { continue; }
    flux += f.rgb;
    area += f.a;
    float dx = float(x) + 0.5 - cx;
    if (dx * dx < nearest) { nearest = dx * dx; best = x; }
  }
  gl_FragData[0] = vec4(flux, area);
  gl_FragData[1] = best >= 0 ? vec4(float(best), nearest, 1.0, 0.0) : vec4(-1.0, 0.0, 0.0, 0.0);
#else
  int block = fragment.y - mrgiFirstVPL;
  int bi = block - (block / mrgiGridSide) * mrgiGridSide;
  int bj = block / mrgiGridSide;
  int y0 = (bj * mrgiRSMSize) / mrgiGridSide;
  int y1 = ((bj + 1) * mrgiRSMSize) / mrgiGridSide;
  float cy = 0.5 * float(y0 + y1);
  vec3 flux = vec3(0.0);
  float area = 0.0;
  float nearest = 3.4e38;
  ivec2 best = ivec2(-1);
  for (int y = y0; y < y1; ++y)
  {
    vec4 row = texelFetch(mrgiRowBest, ivec2(bi, y), 0);
    if (row.z < 0.5) { continue; }
    vec4 sums = texelFetch(mrgiRowSums, ivec2(bi, y), 0);
    flux += sums.rgb;
    area += sums.a;
    float dy = float(y) + 0.5 - cy;
    float d2 = row.y + dy * dy; // exact: multiples of 1/4 below 2^21
    if (d2 < nearest) { nearest = d2; best = ivec2(int(row.x), y); }
  }
  vec4 record = vec4(0.0);
  if (best.x >= 0)
  {
    int texel = fragment.x;
    if (texel == MRGI_VPL_TEXEL_POSITION)
      record = vec4(texelFetch(mrgiRSMPosition, best, 0).xyz, area);
    else if (texel == MRGI_VPL_TEXEL_NORMAL)
      record = vec4(texelFetch(mrgiRSMNormal, best, 0).xyz, 0.0);
    else
      record = vec4(flux, 0.0);
  }
  gl_FragData[0] = record;
#endif
}
