// MRGI BRSM VPL sampling on the GPU (ritschel-et-al-2011 BRSM, RIHKS11 4.1:
// "column CDFs and a CDF of the column sums, inverted by binary search").
// Fragment (k, row) of the VPL texture is texel k of VPL n = row - mrgiFirstVPL:
// it reads sample n's (u1, u2), inverts the float 2-D CDF exactly as the C
// twin mrgi_brsm_cdf_float_invert() does (mrgi_brsm_cdf_float.h: one IEEE
// float operation per step, same search, same fractions), and writes the
// texel VPL record (mrgi_brsm_float_vpl()) when the pick lies in view
// mrgiView (one pass per view; other fragments are discarded, and an empty
// CDF writes zero records in view 0's pass).
// MRGI_BRSM_WRITE_PICKS 1 (tests): texel 0 = (x, r, fx, fy), texel 1 =
// (pdf, picked ? 1 : 0, 0, 0), texel 2 = 0, in every view's pass.
in vec2 texCoord; // bound by vtkOpenGLQuadHelper; this pass addresses texels by gl_FragCoord
uniform sampler2D mrgiRSMPosition; // view mrgiView
uniform sampler2D mrgiRSMNormal;
uniform sampler2D mrgiRSMFlux;
uniform sampler2D mrgiCDF;     // R32F, R wide, S + 1 tall (mrgi_brsm_cdf_float.h)
uniform sampler2D mrgiSamples; // RG32F, 1 wide, N tall: (u1, u2)
uniform int mrgiRSMSize;       // S
uniform int mrgiViewCount;     // V
uniform int mrgiView;          // the view this pass writes
uniform int mrgiFirstVPL;
uniform int mrgiCount;         // N
//VTK::Output::Dec

float mrgiCDFAt(int row, int i) { return texelFetch(mrgiCDF, ivec2(i, row), 0).r; }

// First i in [0, n) with c[i] > target; the last i with a positive step when none.
int mrgiSearch(int row, int n, float target)
{
  int low = 0;
  int high = n;
  while (low < high)
  {
    int middle = low + (high - low) / 2;
    if (mrgiCDFAt(row, middle) > target) { high = middle; }
    else { low = middle + 1; }
  }
  if (low >= n)
  {
    low = n - 1;
    while (low > 0 && !(mrgiCDFAt(row, low) > mrgiCDFAt(row, low - 1))) { --low; }
  }
  return low;
}

float mrgiFraction(int row, int i, float target)
{
  float before = i > 0 ? mrgiCDFAt(row, i - 1) : 0.0;
  float step = mrgiCDFAt(row, i) - before;
  float f = step > 0.0 ? (target - before) / step : 0.5;
  return f < 0.0 ? 0.0 : (f > 1.0 ? 1.0 : f);
}

void main()
{
  ivec2 fragment = ivec2(gl_FragCoord.xy);
  int n = fragment.y - mrgiFirstVPL;
  int S = mrgiRSMSize;
  int R = mrgiViewCount * S;
  vec2 u = texelFetch(mrgiSamples, ivec2(0, n), 0).rg;
  float W = mrgiCDFAt(S, S - 1);
  bool picked = W > 0.0;
  int x = 0;
  int r = 0;
  float fx = 0.0;
  float fy = 0.0;
  float pdf = 0.0;
  if (picked)
  {
    float t1 = u.x * W;
    x = mrgiSearch(S, S, t1);
    float t2 = u.y * mrgiCDFAt(x, R - 1);
    r = mrgiSearch(x, R, t2);
    fx = mrgiFraction(S, x, t1);
    fy = mrgiFraction(x, r, t2);
    pdf = (mrgiCDFAt(x, r) - (r > 0 ? mrgiCDFAt(x, r - 1) : 0.0)) / W;
  }
  int view = r / S;
#if MRGI_BRSM_WRITE_PICKS
  if (mrgiView != 0) { discard; }
  vec4 record = vec4(0.0);
  if (fragment.x == 0) { record = vec4(float(x), float(r), fx, fy); }
  else if (fragment.x == 1) { record = vec4(pdf, picked ? 1.0 : 0.0, 0.0, 0.0); }
#else
  if (picked ? view != mrgiView : mrgiView != 0) { discard; }
  vec4 record = vec4(0.0);
  if (pdf > 0.0)
  {
    ivec2 texel = ivec2(x, r - view * S);
    float scale = 1.0 / (float(mrgiCount) * pdf);
    if (fragment.x == MRGI_VPL_TEXEL_POSITION)
      record = vec4(texelFetch(mrgiRSMPosition, texel, 0).xyz, texelFetch(mrgiRSMFlux, texel, 0).a * scale);
    else if (fragment.x == MRGI_VPL_TEXEL_NORMAL)
      record = vec4(texelFetch(mrgiRSMNormal, texel, 0).xyz, 0.0);
    else
      record = vec4(texelFetch(mrgiRSMFlux, texel, 0).rgb * scale, 0.0);
  }
#endif
  gl_FragData[0] = record;
}
