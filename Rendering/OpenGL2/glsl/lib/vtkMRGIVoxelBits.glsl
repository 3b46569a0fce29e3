// MRGI screen-space voxels: the depth slicing and the bit masks of
// mrgi_voxel.h (sections 1 and 2), defined once for the voxelization
// (vtkMRGIVoxelizeFS.glsl) and the ray march (vtkMRGIVoxelMarch.glsl), which
// both come after it. No main, no #version.
// mrgi_voxel_grid's slices S, [near, far] and S / (far - near), as the core's ints and floats.
uniform int mrgiVoxelSlices;
uniform float mrgiVoxelNear;
uniform float mrgiVoxelFar;
uniform float mrgiVoxelSliceScale;

// slice(d) = int(clamp((d - near) * scale, 0.0, float(S - 1))) (mrgi_voxel_slice). The
// lower clamp is a comparison so that NaN maps to 0 as fmaxf() makes it in C.
int mrgiVoxelSlice(float d)
{
  float x = (d - mrgiVoxelNear) * mrgiVoxelSliceScale;
  x = x > 0.0 ? x : 0.0;
  return int(min(x, float(mrgiVoxelSlices - 1)));
}

// One layer's slices lo..hi (numbered 0..127 within the layer) inclusive,
// clamped to 0..127, empty when lo > hi (mrgi_voxel_range_mask; layer l of a
// pixel's range [a, b] is mrgiVoxelRangeMask(a - 128 l, b - 128 l)): per
// channel c, a = max(lo - 32c, 0), b = min(hi - 32c, 31), bits a..b; a <= b
// is tested first because GLSL (like C) leaves a shift by 32 undefined.
// The four channels are written out, not looped: llvmpipe ends every loop of
// an invocation after 65535 iterations in all (mrgi_voxel_march.h,
// MRGI_VOXEL_ITERATION_BUDGET), and the march calls this once per step and layer.
uint mrgiVoxelChannelMask(int lo, int hi, int c)
{
  int a = max(lo - MRGI_VOXEL_CHANNEL_BITS * c, 0);
  int b = min(hi - MRGI_VOXEL_CHANNEL_BITS * c, MRGI_VOXEL_CHANNEL_BITS - 1);
  return a <= b ? (0xFFFFFFFFu >> uint(MRGI_VOXEL_CHANNEL_BITS - 1 - b)) & (0xFFFFFFFFu << uint(a))
                : 0u;
}

uvec4 mrgiVoxelRangeMask(int lo, int hi)
{
  lo = max(lo, 0);
  hi = min(hi, MRGI_VOXEL_LAYER_SLICES - 1);
  return uvec4(mrgiVoxelChannelMask(lo, hi, 0), mrgiVoxelChannelMask(lo, hi, 1),
    mrgiVoxelChannelMask(lo, hi, 2), mrgiVoxelChannelMask(lo, hi, 3));
}

