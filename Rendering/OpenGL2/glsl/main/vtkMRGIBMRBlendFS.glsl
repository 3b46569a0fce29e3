// MRGI BMR blend (besenthal-maisch-ropinski eq. 1, index corrected,
// bilinear over stencilled taps renormalised); C twin and exact rules:
// mrgi_bmr_blend.h (same operations in the same order). Draws the frame's
// viewport; the frame's pixel p is gl_FragCoord - mrgiOffset.
in vec2 texCoord; // bound by vtkOpenGLQuadHelper; texels are addressed by gl_FragCoord
uniform sampler2D mrgiInput0; // effect values of level 0
uniform sampler2D mrgiInput1; // effect values of level 1
uniform sampler2D mrgiInput2; // effect values of level 2
uniform sampler2D mrgiInput3; // effect values of level 3
uniform sampler2D mrgiInput4; // mask of level 0: (a, E, R + 2 S, NE)
uniform sampler2D mrgiInput5; // mask of level 1
uniform sampler2D mrgiInput6; // mask of level 2
uniform sampler2D mrgiInput7; // mask of level 3
uniform ivec2 mrgiOffset;     // the frame's origin in the target
uniform ivec2 mrgiLevelSize[MRGI_BMR_LEVELS];
uniform float mrgiWeight[MRGI_BMR_LEVELS];
//VTK::Output::Dec

vec4 mrgiFetchColour(int k, ivec2 t)
{
  if (k == 0) { return texelFetch(mrgiInput0, t, 0); }
  if (k == 1) { return texelFetch(mrgiInput1, t, 0); }
  if (k == 2) { return texelFetch(mrgiInput2, t, 0); }
  return texelFetch(mrgiInput3, t, 0);
}
vec4 mrgiFetchMask(int k, ivec2 t)
{
  if (k == 0) { return texelFetch(mrgiInput4, t, 0); }
  if (k == 1) { return texelFetch(mrgiInput5, t, 0); }
  if (k == 2) { return texelFetch(mrgiInput6, t, 0); }
  return texelFetch(mrgiInput7, t, 0);
}

void main()
{
  ivec2 p = ivec2(gl_FragCoord.xy) - mrgiOffset;
  vec4 U = vec4(0.0);
  if (texelFetch(mrgiInput4, p, 0).a > 0.5)
  {
    for (int k = MRGI_BMR_LEVELS - 1; k >= 0; --k)
    {
      float scale = 1.0 / float(1 << k);
      float u = (float(p.x) + 0.5) * scale - 0.5;
      float v = (float(p.y) + 0.5) * scale - 0.5;
      float fu = floor(u), fv = floor(v);
      float fx = u - fu, fy = v - fv;
      ivec2 size = mrgiLevelSize[k];
      ivec2 t0 = ivec2(int(fu), int(fv));
      ivec2 lo = clamp(t0, ivec2(0), size - 1);
      ivec2 hi = clamp(t0 + 1, ivec2(0), size - 1);
      vec2 wx = vec2(1.0 - fx, fx);
      vec2 wy = vec2(1.0 - fy, fy);
      vec4 fine = vec4(0.0);
      float wsum = 0.0, alpha = 0.0;
      for (int b = 0; b < 2; ++b)
      {
        for (int a = 0; a < 2; ++a)
        {
          ivec2 tap = ivec2(a == 0 ? lo.x : hi.x, b == 0 ? lo.y : hi.y);
          float w = wx[a] * wy[b];
          vec4 m = mrgiFetchMask(k, tap);
          alpha += w * m.r;
          if (w > 0.0 && (int(m.b) & 2) != 0)
          {
            fine += w * mrgiFetchColour(k, tap);
            wsum += w;
          }
        }
      }
      if (!(wsum > 0.0)) { continue; }
      fine = fine / wsum;
      float lambda = k == MRGI_BMR_LEVELS - 1 ? 1.0 : alpha * mrgiWeight[k];
      lambda = lambda < 1.0 ? lambda : 1.0;
      if (lambda >= 1.0)
      {
        U = fine;
      }
      else if (lambda > 0.0)
      {
        U = U + lambda * (fine - U);
      }
    }
  }
  gl_FragData[0] = U;
}
