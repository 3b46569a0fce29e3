// MRGI grid VPL selection (nichols-wyman-2009 section 3.1), one view at a
// time: fragment (k, row) of the VPL texture is texel k of VPL
// firstVPL + row. C twin: mrgi_vpl_select_grid() (mrgi_vpl.h), which defines
// the block bounds, the representative texel and the sums mirrored here.
in vec2 texCoord; // bound by vtkOpenGLQuadHelper; these passes address texels by gl_FragCoord
uniform sampler2D mrgiRSMPosition;
uniform sampler2D mrgiRSMNormal;
uniform sampler2D mrgiRSMFlux;
uniform int mrgiRSMSize;     // S
uniform int mrgiGridSide;    // G
uniform int mrgiFirstVPL;    // VPL number (texture row) of this view's block (0, 0)
//VTK::Output::Dec
void main()
{
  ivec2 fragment = ivec2(gl_FragCoord.xy);
  int block = fragment.y - mrgiFirstVPL;
  int bi = block - (block / mrgiGridSide) * mrgiGridSide;
  int bj = block / mrgiGridSide;
  int x0 = (bi * mrgiRSMSize) / mrgiGridSide;
  int x1 = ((bi + 1) * mrgiRSMSize) / mrgiGridSide;
  int y0 = (bj * mrgiRSMSize) / mrgiGridSide;
  int y1 = ((bj + 1) * mrgiRSMSize) / mrgiGridSide;
  float cx = 0.5 * float(x0 + x1);
  float cy = 0.5 * float(y0 + y1);
  vec3 flux = vec3(0.0);
  float area = 0.0;
  float nearest = 3.4e38;
  ivec2 best = ivec2(-1);
  for (int y = y0; y < y1; ++y)
  {
    for (int x = x0; x < x1; ++x)
    {
      vec4 p = texelFetch(mrgiRSMPosition, ivec2(x, y), 0);
      if (p.w <= MRGI_VALID_THRESHOLD) { continue; }
      vec4 f = texelFetch(mrgiRSMFlux, ivec2(x, y), 0);
      flux += f.rgb;
      area += f.a;
      float dx = float(x) + 0.5 - cx;
      float dy = float(y) + 0.5 - cy;
      float d2 = dx * dx + dy * dy;
      if (d2 < nearest) { nearest = d2; best = ivec2(x, y); }
    }
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
}
