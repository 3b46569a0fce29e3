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

// Slicing and masks: vtkMRGIVoxelBits.glsl (prepended).
out uvec4 mrgiVoxels;

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
  // Clamp to the triangle's own depth range, always keeping the centre.
  float lo = min(max(d - h, mrgiDepthMinGS), d);
  float hi = max(min(d + h, mrgiDepthMaxGS), d);
  mrgiVoxels = mrgiVoxelRangeMask(mrgiVoxelSlice(lo), mrgiVoxelSlice(hi));
}
