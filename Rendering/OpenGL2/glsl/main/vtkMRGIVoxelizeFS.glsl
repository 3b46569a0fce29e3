// Screen-space voxelization (nichols-penmatsa-wyman-2010 section 3.3, after
// Dong et al. 2004 and Eisemann and Decoret 2006), fragment stage: the mask of
// the depth slices the surface spans over this voxel pixel, OR-ed into the
// RGBA32UI targets (one per layer of 128 slices) by glLogicOp(GL_OR). The rule, the bit layout and the
// slicing are mrgi_voxel.h's (sections 1, 2, 5); its C twin is
// mrgi_voxel_fragment_mask(), and the two must agree bit for bit except where
// lo or hi lies within float rounding of a slice boundary.
in float mrgiDepthGS;
flat in float mrgiDepthMinGS;
flat in float mrgiDepthMaxGS;
flat in vec3 mrgiTriUGS;
flat in vec3 mrgiTriVGS;
flat in vec3 mrgiTriDGS;
flat in vec3 mrgiTriWGS;

// One Sutherland-Hodgman pass (mrgi_voxel_clip_pass): keep the side where
// sign * (coord - edge) >= 0; p holds n vertices (u, v, d / w, 1 / w).
int mrgiVoxelClipPass(vec4 p[8], int n, int axis, float edge, float sgn, out vec4 q[8])
{
  int m = 0;
  for (int i = 0; i < 8; ++i)
  {
    q[i] = vec4(0.0);
  }
  for (int i = 0; i < 7; ++i)
  {
    if (i >= n)
    {
      break;
    }
    vec4 s0 = p[i];
    vec4 s1 = p[i + 1 < n ? i + 1 : 0];
    float f0 = sgn * (s0[axis] - edge);
    float f1 = sgn * (s1[axis] - edge);
    if (f0 >= 0.0)
    {
      q[m] = s0;
      ++m;
    }
    if ((f0 >= 0.0) != (f1 >= 0.0))
    {
      float t = f0 / (f0 - f1);
      q[m] = s0 + t * (s1 - s0);
      ++m;
    }
  }
  return m;
}

// Depth range of the triangle clipped to voxel pixel (x, y)'s square
// (mrgi_voxel_triangle_pixel_range(), mrgi_voxel.h section 5): false when
// the clipped polygon is empty.
bool mrgiVoxelTrianglePixelRange(ivec2 pixel, out vec2 range)
{
  range = vec2(0.0);
  if (!(mrgiTriWGS.x > 0.0 && mrgiTriWGS.y > 0.0 && mrgiTriWGS.z > 0.0))
  {
    return false; // a vertex at or behind the eye: its (u, v) mean nothing
  }
  vec4 a[8];
  vec4 b[8];
  for (int i = 0; i < 8; ++i)
  {
    a[i] = vec4(0.0);
  }
  for (int i = 0; i < 3; ++i)
  {
    a[i] = vec4(mrgiTriUGS[i], mrgiTriVGS[i], mrgiTriDGS[i] / mrgiTriWGS[i], 1.0 / mrgiTriWGS[i]);
  }
  int n = 3;
  n = mrgiVoxelClipPass(a, n, 0, float(pixel.x), 1.0, b);
  n = mrgiVoxelClipPass(b, n, 0, float(pixel.x + 1), -1.0, a);
  n = mrgiVoxelClipPass(a, n, 1, float(pixel.y), 1.0, b);
  n = mrgiVoxelClipPass(b, n, 1, float(pixel.y + 1), -1.0, a);
  if (n < 1)
  {
    return false;
  }
  float lo = a[0].z / a[0].w;
  float hi = lo;
  for (int i = 1; i < 8; ++i)
  {
    if (i >= n)
    {
      break;
    }
    float d = a[i].z / a[i].w;
    lo = min(lo, d);
    hi = max(hi, d);
  }
  range = vec2(lo, hi);
  return true;
}

// Slicing and masks: vtkMRGIVoxelBits.glsl (prepended).
// One output per layer of 128 slices (mrgi_voxel.h section 1): layer l is
// draw buffer l, a depth layer of the voxel 3D texture; outputs beyond the
// grid's layers go to no buffer. VTK binds output fragOutputK to draw buffer
// K for each gl_FragData[K] a fragment shader names
// (vtkOpenGLShaderCache::ReplaceShaderValues, vtkShaderProgram::Link), and
// declares them as vec4 at its Output::Dec tag, which this shader has not:
// the next line names them, turned into the fragOutputK below by that
// substitution, so that the integer outputs are declared here.
// gl_FragData[0] gl_FragData[1] gl_FragData[2] gl_FragData[3]
out uvec4 fragOutput0;
out uvec4 fragOutput1;
out uvec4 fragOutput2;
out uvec4 fragOutput3;

void main()
{
  float d = mrgiDepthGS;
  // Half the depth span of the surface over the pixel square. Taken before
  // any discard: derivatives need every invocation of the 2x2 quad. Setting
  // the whole span (not only the centre's slice) keeps a surface steep in
  // depth from leaving empty slices between neighbouring pixels that a ray
  // would slip through.
  float h = 0.5 * fwidth(d);
  // Outside [near, far] (or NaN): nothing. The clip planes already drop
  // these; the test makes the rule exact where clipping rounds.
  if (!(d >= mrgiVoxelNear && d <= mrgiVoxelFar))
  {
    discard;
  }
  h = h > 0.0 ? h : 0.0; // NaN -> 0
  // Clamp to the depths the triangle has inside this pixel (its part
  // clipped to the pixel square; the whole triangle's range when rounding
  // leaves nothing), always keeping the centre.
  vec2 range;
  if (!mrgiVoxelTrianglePixelRange(ivec2(gl_FragCoord.xy), range))
  {
    range = vec2(mrgiDepthMinGS, mrgiDepthMaxGS);
  }
  float lo = min(max(d - h, range.x), d);
  float hi = max(min(d + h, range.y), d);
  int sliceLo = mrgiVoxelSlice(lo);
  int sliceHi = mrgiVoxelSlice(hi);
  fragOutput0 = mrgiVoxelRangeMask(sliceLo, sliceHi);
  fragOutput1 = mrgiVoxelRangeMask(sliceLo - MRGI_VOXEL_LAYER_SLICES, sliceHi - MRGI_VOXEL_LAYER_SLICES);
  fragOutput2 = mrgiVoxelRangeMask(sliceLo - 2 * MRGI_VOXEL_LAYER_SLICES, sliceHi - 2 * MRGI_VOXEL_LAYER_SLICES);
  fragOutput3 = mrgiVoxelRangeMask(sliceLo - 3 * MRGI_VOXEL_LAYER_SLICES, sliceHi - 3 * MRGI_VOXEL_LAYER_SLICES);
}
