// The variance shadow query's resolve (nichols-penmatsa-wyman-2010 3.3.3,
// after Donnelly and Lauritzen 2006): at one pixel, the box blur of the
// per-query moments (z, z^2) over the pixels that computed each query, and
// the one-tailed Chebyshev bound with the receiver at 1. C twins:
// mrgi_voxel_vsm_resolve() and mrgi_voxel_vsm_chebyshev()
// (mrgi_variance_shadow.h section 6), translated in the same order: a
// query's sum runs over the window row by row, bottom to top, left to right.
// A function library: no #version, no main(); after VTK's system
// declarations and the core's constants block. (No VTK shader tag may
// appear in these comments: VTK would replace it.)
//
// The moments (vtkMRGIVarianceShadowQuery's pass): MRGI_VOXEL_VSM_TARGETS
// RGBA32F textures of the viewport's size, viewport-local texels. With 2x2
// interleaving, pixel (x, y) of phase q = (x & 1) | ((y & 1) << 1) holds
// the queries j = 4 k + q, k = 0..5: k in texture k >> 1, channels
// 2 (k & 1) (z) and 2 (k & 1) + 1 (z^2). A pixel that computed nothing
// (no specular material, or not on the lobe-grid path) holds -1 in its
// first texture's x: the C twin's phase set 0.
// vtkMRGIVarianceShadowQuery::SetResolveUniforms() sets everything below.
uniform sampler2D mrgiVsmMoments0;
uniform sampler2D mrgiVsmMoments1;
uniform sampler2D mrgiVsmMoments2;
uniform ivec2 mrgiVsmSize;       // the moments' (viewport's) size
uniform int mrgiVsmRadius;       // box radius, 0..MRGI_VOXEL_VSM_MAX_RADIUS
uniform float mrgiVsmMinVariance; // DL06's minimum variance, >= 0

// mrgi_voxel_vsm_chebyshev(): DL06's bound with the receiver at 1, in [0, 1].
// (variance + d^2 > 0 whenever mean < 1: no 0/0.)
float mrgiVsmChebyshev(float mean, float meanSq, float minVariance)
{
  if (mean >= 1.0)
  {
    return 1.0;
  }
  float variance = max(meanSq - mean * mean, minVariance);
  float d = 1.0 - mean;
  float p = variance / (variance + d * d);
  return min(max(p, 0.0), 1.0);
}

// mrgi_voxel_vsm_resolve() at viewport-local pixel `pixel` (a pixel that
// computed, so a receiver): the visibility of every query. Each window
// pixel adds its six queries' moments to its phase's sums; a query no
// pixel in the window computed is visible.
void mrgiVsmResolve(ivec2 pixel, out float visibility[MRGI_VOXEL_VSM_QUERIES])
{
  vec4 sum0[MRGI_VOXEL_INTERLEAVE_PHASES];
  vec4 sum1[MRGI_VOXEL_INTERLEAVE_PHASES];
  vec4 sum2[MRGI_VOXEL_INTERLEAVE_PHASES];
  int n[MRGI_VOXEL_INTERLEAVE_PHASES];
  for (int q = 0; q < MRGI_VOXEL_INTERLEAVE_PHASES; ++q)
  {
    sum0[q] = vec4(0.0);
    sum1[q] = vec4(0.0);
    sum2[q] = vec4(0.0);
    n[q] = 0;
  }
  for (int dy = -mrgiVsmRadius; dy <= mrgiVsmRadius; ++dy)
  {
    for (int dx = -mrgiVsmRadius; dx <= mrgiVsmRadius; ++dx)
    {
      ivec2 s = pixel + ivec2(dx, dy);
      if (s.x < 0 || s.y < 0 || s.x >= mrgiVsmSize.x || s.y >= mrgiVsmSize.y)
      {
        continue;
      }
      vec4 m0 = texelFetch(mrgiVsmMoments0, s, 0);
      if (!(m0.x >= 0.0))
      {
        continue; // computed nothing
      }
      int q = (s.x & 1) | ((s.y & 1) << 1);
      sum0[q] += m0;
      sum1[q] += texelFetch(mrgiVsmMoments1, s, 0);
      sum2[q] += texelFetch(mrgiVsmMoments2, s, 0);
      n[q] += 1;
    }
  }
  for (int q = 0; q < MRGI_VOXEL_INTERLEAVE_PHASES; ++q)
  {
    for (int k = 0; k < MRGI_VOXEL_VSM_QUERIES / MRGI_VOXEL_INTERLEAVE_PHASES; ++k)
    {
      int j = MRGI_VOXEL_INTERLEAVE_PHASES * k + q;
      int target = k >> 1;
      vec4 sums = target == 0 ? sum0[q] : (target == 1 ? sum1[q] : sum2[q]);
      vec2 m = (k & 1) == 0 ? sums.xy : sums.zw;
      float count = float(n[q]);
      visibility[j] = n[q] == 0 ? 1.0 : mrgiVsmChebyshev(m.x / count, m.y / count, mrgiVsmMinVariance);
    }
  }
}
