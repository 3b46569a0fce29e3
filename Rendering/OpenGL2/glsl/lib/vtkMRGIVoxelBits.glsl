// MRGI screen-space voxels: the depth slicing and the bit masks of
// mrgi_voxel.h (sections 1 and 2), defined once for the voxelization
// (vtkMRGIVoxelizeFS.glsl) and the ray march (vtkMRGIVoxelMarch.glsl), which
// both come after it. No main, no #version.
// mrgi_voxel_grid's [near, far] and MRGI_VOXEL_SLICES / (far - near), as the core's floats.
uniform float mrgiVoxelNear;
uniform float mrgiVoxelFar;
uniform float mrgiVoxelSliceScale;

// slice(d) = int(clamp((d - near) * scale, 0.0, 127.0)) (mrgi_voxel_slice). The
// lower clamp is a comparison so that NaN maps to 0 as fmaxf() makes it in C.
int mrgiVoxelSlice(float d)
{
  float x = (d - mrgiVoxelNear) * mrgiVoxelSliceScale;
  x = x > 0.0 ? x : 0.0;
  return int(min(x, float(MRGI_VOXEL_SLICES - 1)));
}

// Slices lo..hi inclusive, clamped to 0..127, empty when lo > hi
// (mrgi_voxel_range_mask): per channel c, a = max(lo - 32c, 0),
// b = min(hi - 32c, 31), bits a..b; a <= b is tested first because GLSL (like
// C) leaves a shift by 32 undefined.
uvec4 mrgiVoxelRangeMask(int lo, int hi)
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

