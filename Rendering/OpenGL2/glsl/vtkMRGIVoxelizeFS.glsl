// Screen-space voxelization (nichols-penmatsa-wyman-2010 section 3.3, after
// Dong et al. 2004 and Eisemann and Decoret 2006), fragment stage: the mask of
// the depth slices the surface spans over this voxel pixel, OR-ed into the
// RGBA32UI target by glLogicOp(GL_OR). The rule, the bit layout and the
// slicing are mrgi_voxel.h's (sections 1, 2, 5); its C twin is
// mrgi_voxel_fragment_mask(), and the two must agree bit for bit except where
// lo or hi lies within float rounding of a slice boundary.
in float mrgiDepthGS;
flat in float mrgiDepthMinGS;
flat in float mrgiDepthMaxGS;

uniform float mrgiNear;       // grid near_depth (float)
uniform float mrgiFar;        // grid far_depth (float)
uniform float mrgiSliceScale; // grid slice_scale: MRGI_VOXEL_SLICES / (far - near) as float

out uvec4 mrgiVoxels;

// slice(d) = int(clamp((d - near) * scale, 0.0, 127.0))  (mrgi_voxel_slice)
int mrgiSlice(float d)
{
  return int(clamp((d - mrgiNear) * mrgiSliceScale, 0.0, float(MRGI_VOXEL_SLICES - 1)));
}

// Slices lo..hi inclusive (mrgi_voxel_range_mask): per channel c,
// a = max(lo - 32c, 0), b = min(hi - 32c, 31), bits a..b; no shift by 32,
// which GLSL leaves undefined, hence the a <= b test first.
uvec4 mrgiRangeMask(int lo, int hi)
{
  lo = max(lo, 0);
  hi = min(hi, MRGI_VOXEL_SLICES - 1);
  uvec4 mask = uvec4(0u);
  for (int c = 0; c < MRGI_VOXEL_CHANNELS; ++c)
  {
    int a = max(lo - MRGI_VOXEL_CHANNEL_BITS * c, 0);
    int b = min(hi - MRGI_VOXEL_CHANNEL_BITS * c, MRGI_VOXEL_CHANNEL_BITS - 1);
    if (a <= b)
    {
      mask[c] = (0xFFFFFFFFu >> uint(MRGI_VOXEL_CHANNEL_BITS - 1 - b)) & (0xFFFFFFFFu << uint(a));
    }
  }
  return mask;
}

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
  if (!(d >= mrgiNear && d <= mrgiFar))
  {
    discard;
  }
  h = h > 0.0 ? h : 0.0; // NaN -> 0
  // Clamp to the triangle's own depth range, always keeping the centre.
  float lo = min(max(d - h, mrgiDepthMinGS), d);
  float hi = max(min(d + h, mrgiDepthMaxGS), d);
  mrgiVoxels = mrgiRangeMask(mrgiSlice(lo), mrgiSlice(hi));
}
