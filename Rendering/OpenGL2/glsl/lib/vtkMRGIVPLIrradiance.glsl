// MRGI: the irradiance one VPL gives one receiver (nichols-shopf-wyman-2009
// section 3.2.2, equations 1 and 5, no visibility), and the test that sorts
// receivers into background, malformed and valid ones. Shared by the gather
// (vtkMRGIGatherFS.glsl) and the multiresolution splatting
// (vtkMRGIMultiresSplatVS.glsl), so that both compute the same numbers in
// the same order. C twin: mrgi_gather_full() (mrgi_gather.c), whose formula
// this mirrors term by term.

// 0: background (no data: alpha 0, nothing gathered); 1: malformed (valid
// flag set, but a non-finite position or normal, or a zero normal: E = 0,
// as in the C twin, so one NaN cannot spread through the sums); 2: valid,
// with P and N the world-space receiver.
int mrgiClassifyReceiver(vec4 positionVC, vec3 normalVC, mat4 viewToWorld, out vec3 P, out vec3 N)
{
  P = vec3(0.0);
  N = vec3(0.0);
  if (positionVC.w <= MRGI_VALID_THRESHOLD)
  {
    return 0;
  }
  if (any(isnan(positionVC.xyz)) || any(isinf(positionVC.xyz)) || any(isnan(normalVC)) ||
    any(isinf(normalVC)) || dot(normalVC, normalVC) == 0.0)
  {
    return 1;
  }
  P = (viewToWorld * vec4(positionVC.xyz, 1.0)).xyz;
  N = normalize(mat3(viewToWorld) * normalVC);
  return 2;
}

// E_ij of one VPL record (its three texels: position.xyz and area in w,
// normal.xyz, flux.rgb; the w of the normal and flux texels is ignored, so
// the VPL tree's pads R_P and Dmax_P may ride along) at receiver (P, N),
// world space. Zero-flux VPLs, coincident points and back-facing pairs
// give 0. The cache gather and the tree gather (vtkMRGIVPLTree.glsl) both
// call this, so their terms are the same float operations.
vec3 mrgiVPLRecordIrradiance(vec4 position, vec3 normal, vec3 flux, vec3 P, vec3 N)
{
  if (flux.r == 0.0 && flux.g == 0.0 && flux.b == 0.0) { return vec3(0.0); }
  vec3 d = position.xyz - P;
  float r2 = dot(d, d);
  if (r2 == 0.0) { return vec3(0.0); }
  vec3 Nj = normalize(normal);
  float cosIr = dot(N, d);
  float cosJr = -dot(Nj, d);
  if (cosIr <= 0.0 || cosJr <= 0.0) { return vec3(0.0); }
  return flux * ((cosIr * cosJr / r2) / (MRGI_PI * r2 + position.w));
}

// E_ij: VPL j of the cache (MRGI_VPL_TEXELS texels per VPL) at receiver
// (P, N), world space. The flux is read first: zero-flux VPLs fetch nothing more.
// With MRGI_INDIRECT_ISM (vtkMRGIISMLookup.glsl prepended) a term > 0 is
// weighted by VPL j's imperfect shadow map (tile j), as
// mrgi_gather_full_visibility() does (C twin).
#ifdef MRGI_INDIRECT_VOXELS
// Voxel visibility (nichols-penmatsa-wyman-2010 3.3.1, the naive query;
// vtkMRGIVoxelMarch.glsl prepended, its uniforms from
// vtkMRGIVoxelization::SetMarchUniforms()): one march from the receiver in
// eye space (the voxels' space: its G-buffer position and normal as stored,
// set by the gather's main() before the sum) to the VPL brought into eye
// space, as mrgi_gather_voxel_weight() (mrgi_gather_term.h) does.
uniform mat4 mrgiWCToVC; // world -> eye, the voxelized camera's
vec3 mrgiReceiverVC = vec3(0.0);
vec3 mrgiReceiverNormalVC = vec3(0.0);

// 1 if the world-space VPL (position, normal) is visible from the receiver, else 0.
float mrgiVPLVoxelVisibility(vec3 position, vec3 normal)
{
  vec3 Lvc = (mrgiWCToVC * vec4(position, 1.0)).xyz;
  vec3 NLvc = normalize(mat3(mrgiWCToVC) * normal);
  return mrgiVoxelVisible(mrgiReceiverVC, mrgiReceiverNormalVC, Lvc, NLvc) ? 1.0 : 0.0;
}
#endif

vec3 mrgiVPLIrradiance(sampler2D vpls, int j, vec3 P, vec3 N)
{
  vec4 flux = texelFetch(vpls, ivec2(MRGI_VPL_TEXEL_FLUX, j), 0);
  if (flux.r == 0.0 && flux.g == 0.0 && flux.b == 0.0) { return vec3(0.0); }
#ifdef MRGI_INDIRECT_VOXELS
  vec4 position = texelFetch(vpls, ivec2(MRGI_VPL_TEXEL_POSITION, j), 0);
  vec3 normal = texelFetch(vpls, ivec2(MRGI_VPL_TEXEL_NORMAL, j), 0).xyz;
  vec3 E = mrgiVPLRecordIrradiance(position, normal, flux.rgb, P, N);
  if (E != vec3(0.0)) { E *= mrgiVPLVoxelVisibility(position.xyz, normal); }
  return E;
#elif defined(MRGI_INDIRECT_ISM)
  vec4 position = texelFetch(vpls, ivec2(MRGI_VPL_TEXEL_POSITION, j), 0);
  vec3 normal = texelFetch(vpls, ivec2(MRGI_VPL_TEXEL_NORMAL, j), 0).xyz;
  vec3 E = mrgiVPLRecordIrradiance(position, normal, flux.rgb, P, N);
  if (E != vec3(0.0)) { E *= mrgiISMVisibility(j, position.xyz, normal, P); }
  return E;
#else
  return mrgiVPLRecordIrradiance(texelFetch(vpls, ivec2(MRGI_VPL_TEXEL_POSITION, j), 0),
    texelFetch(vpls, ivec2(MRGI_VPL_TEXEL_NORMAL, j), 0).xyz, flux.rgb, P, N);
#endif
}
