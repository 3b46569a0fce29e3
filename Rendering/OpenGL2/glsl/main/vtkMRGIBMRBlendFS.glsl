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

// Level k at the frame's pixel p: bilin*(c_k) in `fine` and bilin(a_k) in
// `alpha`; false when no stencilled tap has weight (mrgi_bmr_blend.h). One
// call per level with its own samplers: no branch picks a sampler.
bool mrgiSampleLevel(sampler2D colour, sampler2D mask, int k, ivec2 p, out vec4 fine, out float alpha)
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
  fine = vec4(0.0);
  alpha = 0.0;
  float wsum = 0.0;
  for (int b = 0; b < 2; ++b)
  {
    for (int a = 0; a < 2; ++a)
    {
      ivec2 tap = ivec2(a == 0 ? lo.x : hi.x, b == 0 ? lo.y : hi.y);
      float w = wx[a] * wy[b];
      vec4 m = texelFetch(mask, tap, 0);
      alpha += w * m.r;
      if (w > 0.0 && (int(m.b) & 2) != 0)
      {
        fine += w * texelFetch(colour, tap, 0);
        wsum += w;
      }
    }
  }
  if (!(wsum > 0.0)) { return false; }
  fine = fine / wsum;
  return true;
}

// Eq. 1, one level: U_{k+1} -> U_k.
vec4 mrgiMix(vec4 U, vec4 fine, float alpha, int k)
{
  float lambda = k == MRGI_BMR_LEVELS - 1 ? 1.0 : alpha * mrgiWeight[k];
  lambda = lambda < 1.0 ? lambda : 1.0;
  if (lambda >= 1.0) { return fine; }
  if (lambda > 0.0) { return U + lambda * (fine - U); }
  return U;
}

void main()
{
  ivec2 p = ivec2(gl_FragCoord.xy) - mrgiOffset;
  vec4 U = vec4(0.0);
  if (texelFetch(mrgiInput4, p, 0).a > 0.5)
  {
    vec4 fine;
    float alpha;
    if (mrgiSampleLevel(mrgiInput3, mrgiInput7, 3, p, fine, alpha)) { U = mrgiMix(U, fine, alpha, 3); }
    if (mrgiSampleLevel(mrgiInput2, mrgiInput6, 2, p, fine, alpha)) { U = mrgiMix(U, fine, alpha, 2); }
    if (mrgiSampleLevel(mrgiInput1, mrgiInput5, 1, p, fine, alpha)) { U = mrgiMix(U, fine, alpha, 1); }
    if (mrgiSampleLevel(mrgiInput0, mrgiInput4, 0, p, fine, alpha)) { U = mrgiMix(U, fine, alpha, 0); }
  }
  gl_FragData[0] = U;
}
