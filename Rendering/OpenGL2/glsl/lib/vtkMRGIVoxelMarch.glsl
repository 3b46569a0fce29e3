// Naive voxel-space visibility (nichols-penmatsa-wyman-2010 section 3.3.1):
// "we instead sample the ray uniformly between each fragment and VPL [...]
// checking multiple bits in texels fetched from the voxel buffer. This
// essentially thickens the ray." A function library (no main, no #version):
// put it after VTK's system declarations and the constants block
// (vtkMRGIShaderUtilities::Defines(), i.e. mrgi_glsl_defines()), which
// supplies MRGI_VOXEL_LAYER_SLICES, _CHANNELS, _CHANNEL_BITS and _MAX_STEPS.
//
// This is the GLSL twin of mrgi_voxel_march() and
// mrgi_voxel_march_occluder_fraction() (Rendering/Core/Twins/mrgi_voxel_march.c);
// the bit layout, slice() and range_mask() are mrgi_voxel.h's (sections 1, 2
// and 5). Every function below translates its C counterpart statement by
// statement, in float and in the same order of operations, so that the GPU
// and the twin give the same binary answer on the same inputs: the only
// differences the contract allows (mrgi_voxel_march.h "Precision") are rays
// on which a step's middle, a depth or a clip parameter lies within float
// rounding of a pixel or slice boundary (GLSL's division, 1/d and sqrt need
// not round as C's do). TestMRGIVoxelMarch counts them. Do not "simplify" an
// expression here without changing the C twin the same way.
//
// Inputs are eye space (the G-buffer's): receiver P with normal Np (facing
// the viewer), light sample L with normal Nl (the emitter's surface normal).
// A zero normal means "none": no bias and no horizon test at that end (the
// C twin's NULL). Normals need not be unit.
//
// vtkMRGIVoxelization::SetMarchUniforms() sets every uniform below from the
// last Voxelize() and the march parameters, and binds the voxel texture to
// mrgiVoxelTexture.

// The voxel buffer (GL_RGBA32UI 3D texture, texelFetch only): slice s in
// layer s >> 7, channel (s >> 5) & 3, bit s & 31.
uniform usampler3D mrgiVoxelTexture;
// mrgi_voxel_grid: VW x VH, S slices, [near, far] and S / (far - near), as the core's ints and floats.
uniform ivec2 mrgiVoxelGridSize;
// mrgiVoxelNear, mrgiVoxelFar, mrgiVoxelSliceScale: vtkMRGIVoxelBits.glsl,
// which comes first with mrgiVoxelSlice() and mrgiVoxelRangeMask().
// mrgi_voxel_projection: ndc = scale * xy / w + offset, w = d (perspective) or 1 (parallel).
uniform vec2 mrgiVoxelProjectionScale;
uniform vec2 mrgiVoxelProjectionOffset;
uniform int mrgiVoxelParallel; // 0 perspective, 1 parallel
// mrgi_voxel_march_params.
uniform int mrgiVoxelMaxSteps;       // 1..MRGI_VOXEL_MAX_STEPS
uniform float mrgiVoxelNormalOffset; // bias along the normals, in voxel sizes
uniform int mrgiVoxelOffsetAlongRay; // MRGI_VOXEL_OFFSET_* (mrgi_voxel_march_params::offset_along_ray)
uniform int mrgiVoxelSkipRadius;     // skip box radius, in voxels

// Outcomes of mrgiVoxelMarchCore(): the C twin's private mrgi_voxel_outcome
// (not a core constant: local names, no MRGI_ macros).
const int mrgiVoxelMarchClear = 0;   // no step hit, or nothing to march
const int mrgiVoxelMarchHorizon = 1; // below a horizon (step 2)
const int mrgiVoxelMarchHit = 2;     // a step hit

// a.b summed x, y, z left to right, as mrgi_dot3() (no dot(): its summation
// order is the compiler's).
float mrgiVoxelDot(vec3 a, vec3 b)
{
  return a.x * b.x + a.y * b.y + a.z * b.z;
}

// floor(u) clamped to 0..size-1 in float first, NaN -> 0 (mrgi_voxel_pixel).
int mrgiVoxelPixel(float u, int size)
{
  float c = floor(u);
  c = c > 0.0 ? c : 0.0;
  return int(min(c, float(size - 1)));
}

// Voxel size vs(X) at linear depth d (step 3, mrgi_voxel_size_at): the larger
// of the voxel pixel's eye-space width and height there and the slice
// thickness. The bias is in these units because how far a ray must go to
// leave its receiver's own voxels scales with the voxel, not the scene
// (mrgi_voxel_march.h "The bias in voxel units"; NPW10 4.3 "shadow acne").
float mrgiVoxelSizeAt(float depth)
{
  float w = mrgiVoxelParallel != 0 ? 1.0 : abs(depth);
  float sx = 2.0 * w / (mrgiVoxelProjectionScale.x * float(mrgiVoxelGridSize.x));
  float sy = 2.0 * w / (mrgiVoxelProjectionScale.y * float(mrgiVoxelGridSize.y));
  float sz = 1.0 / mrgiVoxelSliceScale;
  return max(max(sx, sy), sz);
}

// The six frustum half-spaces f(X) >= 0 (step 4, mrgi_voxel_frustum):
// the voxels hold nothing outside [near, far] or off the screen.
void mrgiVoxelFrustum(vec3 X, out float f[6])
{
  float d = -X.z;
  float w = mrgiVoxelParallel != 0 ? 1.0 : d;
  f[0] = d - mrgiVoxelNear;
  f[1] = mrgiVoxelFar - d;
  f[2] = mrgiVoxelProjectionScale.x * X.x + (1.0 + mrgiVoxelProjectionOffset.x) * w;
  f[3] = -mrgiVoxelProjectionScale.x * X.x + (1.0 - mrgiVoxelProjectionOffset.x) * w;
  f[4] = mrgiVoxelProjectionScale.y * X.y + (1.0 + mrgiVoxelProjectionOffset.y) * w;
  f[5] = -mrgiVoxelProjectionScale.y * X.y + (1.0 - mrgiVoxelProjectionOffset.y) * w;
}

// Eye space -> (u, v, d), continuous voxel coordinates and linear depth
// (mrgi_voxel_project, mrgi_voxel.h section 4); false (and (0, 0, d)) at or
// behind the eye of a perspective projection.
bool mrgiVoxelProject(vec3 X, out vec3 uvd)
{
  float d = -X.z;
  float w = mrgiVoxelParallel != 0 ? 1.0 : d;
  if (!(w > 0.0))
  {
    uvd = vec3(0.0, 0.0, d);
    return false;
  }
  float ndcX = mrgiVoxelProjectionScale.x * X.x / w + mrgiVoxelProjectionOffset.x;
  float ndcY = mrgiVoxelProjectionScale.y * X.y / w + mrgiVoxelProjectionOffset.y;
  uvd.x = (ndcX + 1.0) * 0.5 * float(mrgiVoxelGridSize.x);
  uvd.y = (ndcY + 1.0) * 0.5 * float(mrgiVoxelGridSize.y);
  uvd.z = d;
  return true;
}

// Skip box of an end X (step 7, mrgi_voxel_skip_box): (active, x, y, slice).
// Active only for an end inside the frustum: the (2r+1)^3 voxels around it
// never occlude, so neither the receiver's own surface nor the emitter's
// shadows the ray.
ivec4 mrgiVoxelSkipBox(vec3 X)
{
  float f[6];
  mrgiVoxelFrustum(X, f);
  for (int k = 0; k < 6; ++k)
  {
    if (!(f[k] >= 0.0))
    {
      return ivec4(0);
    }
  }
  vec3 uvd;
  if (!mrgiVoxelProject(X, uvd))
  {
    return ivec4(0);
  }
  return ivec4(mrgiVoxelSkipRadius > 0 ? 1 : 0, mrgiVoxelPixel(uvd.x, mrgiVoxelGridSize.x),
    mrgiVoxelPixel(uvd.y, mrgiVoxelGridSize.y), mrgiVoxelSlice(uvd.z));
}

// Remove a skip box's slices from a step's mask when the step's pixel is
// within the radius of the box's pixel (mrgi_voxel_apply_box); `base` is
// the first slice of the mask's layer (128 l).
uvec4 mrgiVoxelApplyBox(ivec4 box, int radius, int px, int py, int base, uvec4 mask)
{
  if (box.x != 0 && abs(px - box.y) <= radius && abs(py - box.z) <= radius)
  {
    mask &= ~mrgiVoxelRangeMask(box.w - radius - base, box.w + radius - base);
  }
  return mask;
}

// Steps 1-9 of mrgi_voxel_march.h (mrgi_voxel_march_core). fromLight walks
// the steps k = n-1 down to 0 and sets hitFraction (the occluder distance of
// the variance shadow query, NPW10 3.3.3) on a hit; otherwise hitFraction is 1.
// Step 3 at one end X: the offset of height h above X's plane, along the
// ray where it leaves at cosine >= MRGI_VOXEL_ALONG_RAY_FULL_COS to the
// normal, along the normal below MRGI_VOXEL_ALONG_RAY_MIN_COS, blended
// between; at most MRGI_VOXEL_ALONG_RAY_MAX_SHARE of the segment along the
// ray (mrgi_voxel_offset_end, same order of operations).
vec3 mrgiVoxelOffsetEnd(vec3 X, vec3 n, float n2, vec3 toward, float segmentLength, float h, bool alongRay)
{
  float invN = 1.0 / sqrt(n2);
  vec3 unitN = vec3(n.x * invN, n.y * invN, n.z * invN);
  if (!alongRay)
  {
    return vec3(X.x + h * unitN.x, X.y + h * unitN.y, X.z + h * unitN.z);
  }
  vec3 u = vec3(toward.x / segmentLength, toward.y / segmentLength, toward.z / segmentLength);
  float c = mrgiVoxelDot(unitN, u);
  float w = min(max((c - MRGI_VOXEL_ALONG_RAY_MIN_COS) /
                      (MRGI_VOXEL_ALONG_RAY_FULL_COS - MRGI_VOXEL_ALONG_RAY_MIN_COS), 0.0), 1.0);
  float along = min(w * h / c, MRGI_VOXEL_ALONG_RAY_MAX_SHARE * segmentLength);
  float up = max(h - along * c, 0.0);
  return vec3(X.x + (along * u.x + up * unitN.x), X.y + (along * u.y + up * unitN.y),
    X.z + (along * u.z + up * unitN.z));
}

int mrgiVoxelMarchCore(usampler3D voxels, vec3 P, vec3 Np, vec3 L, vec3 Nl, bool fromLight,
  out float hitFraction)
{
  hitFraction = 1.0;
  // 1. Zero-length segment: nothing between the ends.
  vec3 D = L - P;
  float length2 = mrgiVoxelDot(D, D);
  if (length2 == 0.0)
  {
    return mrgiVoxelMarchClear;
  }
  // 2. Horizons: a sample below the receiver's tangent plane (or a receiver
  // behind the emitter) is hidden by that end's own surface; G's cosine is 0 there.
  float np2 = mrgiVoxelDot(Np, Np);
  float nl2 = mrgiVoxelDot(Nl, Nl);
  if (np2 > 0.0 && mrgiVoxelDot(Np, D) <= 0.0)
  {
    return mrgiVoxelMarchHorizon;
  }
  if (nl2 > 0.0 && mrgiVoxelDot(Nl, D) >= 0.0) // dot(Nl, -D) <= 0
  {
    return mrgiVoxelMarchHorizon;
  }
  // 3. Bias, part 1: push both ends off their surfaces along the normals,
  // normal_offset voxel sizes (NPW10 4.3: "a bias to push the ray origin away").
  vec3 O = P;
  vec3 E = L;
  float segmentLength = sqrt(length2);
  if (np2 > 0.0)
  {
    O = mrgiVoxelOffsetEnd(P, Np, np2, D, segmentLength, mrgiVoxelNormalOffset * mrgiVoxelSizeAt(-P.z),
      mrgiVoxelOffsetAlongRay != MRGI_VOXEL_OFFSET_NORMALS);
  }
  if (nl2 > 0.0)
  {
    E = mrgiVoxelOffsetEnd(L, Nl, nl2, -D, segmentLength, mrgiVoxelNormalOffset * mrgiVoxelSizeAt(-L.z),
      mrgiVoxelOffsetAlongRay == MRGI_VOXEL_OFFSET_RAY_AT_BOTH);
  }
  // 4. Liang-Barsky clip of O -> E to the view frustum: a screen-space
  // method knows no occluders outside it (and the near plane cuts off what
  // lies behind the camera).
  float fO[6];
  float fE[6];
  mrgiVoxelFrustum(O, fO);
  mrgiVoxelFrustum(E, fE);
  float t0 = 0.0;
  float t1 = 1.0;
  for (int k = 0; k < 6; ++k)
  {
    if (fO[k] < 0.0 && fE[k] < 0.0)
    {
      return mrgiVoxelMarchClear;
    }
    if (fO[k] < 0.0)
    {
      t0 = max(t0, fO[k] / (fO[k] - fE[k]));
    }
    else if (fE[k] < 0.0)
    {
      t1 = min(t1, fO[k] / (fO[k] - fE[k]));
    }
  }
  if (t0 > t1)
  {
    return mrgiVoxelMarchClear;
  }
  vec3 A = O + t0 * (E - O);
  vec3 B = O + t1 * (E - O);
  // 5. Project both ends (inside [near, far] up to rounding: d > 0).
  vec3 a;
  vec3 b;
  mrgiVoxelProject(A, a);
  mrgiVoxelProject(B, b);
  bool perspective = mrgiVoxelParallel == 0;
  float ia = perspective ? 1.0 / a.z : 0.0;
  float ib = perspective ? 1.0 / b.z : 0.0;
  // 6. Step rule: uniform in screen space (NPW10 3.3.1: "sample the ray
  // uniformly"), one step per voxel pixel along the major axis, capped.
  float du = b.x - a.x;
  float dv = b.y - a.y;
  float span = max(abs(du), abs(dv));
  int n = int(min(max(ceil(span), 1.0), float(mrgiVoxelMaxSteps)));
  float invN = 1.0 / float(n);
  // 7. Bias, part 2: the skip boxes around both ends.
  int radius = mrgiVoxelSkipRadius;
  ivec4 boxP = mrgiVoxelSkipBox(P);
  ivec4 boxL = mrgiVoxelSkipBox(L);
  // 8. Each step tests every slice its piece of segment passes (the depth
  // interval [depth(s0), depth(s1)]), not only the slice at its middle: the
  // "multiple bits" that thicken the ray (NPW10 3.3.1).
  for (int j = 0; j < MRGI_VOXEL_MAX_STEPS; ++j)
  {
    if (j >= n)
    {
      break;
    }
    int k = fromLight ? n - 1 - j : j;
    float s0 = float(k) * invN;
    float s1 = float(k + 1) * invN;
    float sm = (float(k) + 0.5) * invN;
    int px = mrgiVoxelPixel(a.x + du * sm, mrgiVoxelGridSize.x);
    int py = mrgiVoxelPixel(a.y + dv * sm, mrgiVoxelGridSize.y);
    float d0;
    float d1;
    if (perspective)
    {
      // 1/d is linear in screen space.
      d0 = 1.0 / (ia + (ib - ia) * s0);
      d1 = 1.0 / (ia + (ib - ia) * s1);
    }
    else
    {
      d0 = a.z + (b.z - a.z) * s0;
      d1 = a.z + (b.z - a.z) * s1;
    }
    int lo = mrgiVoxelSlice(min(d0, d1));
    int hi = mrgiVoxelSlice(max(d0, d1));
    // Only the layers the interval reaches (mrgi_voxel.h section 1; almost
    // always one texel fetch).
    uint overlap = 0u;
    for (int layer = lo / MRGI_VOXEL_LAYER_SLICES; layer <= hi / MRGI_VOXEL_LAYER_SLICES; ++layer)
    {
      int base = MRGI_VOXEL_LAYER_SLICES * layer;
      uvec4 mask = mrgiVoxelRangeMask(lo - base, hi - base);
      mask = mrgiVoxelApplyBox(boxP, radius, px, py, base, mask);
      mask = mrgiVoxelApplyBox(boxL, radius, px, py, base, mask);
      uvec4 texel = texelFetch(voxels, ivec3(px, py, layer), 0);
      overlap |= (texel.x & mask.x) | (texel.y & mask.y) | (texel.z & mask.z) | (texel.w & mask.w);
    }
    if (overlap != 0u)
    {
      if (fromLight)
      {
        // The step's middle mapped back to the segment (perspective: screen
        // parameter -> segment parameter through 1/d).
        float tau = perspective ? sm * ib / (ia + (ib - ia) * sm) : sm;
        vec3 X = A + tau * (B - A);
        vec3 LX = L - X;
        float z = sqrt(mrgiVoxelDot(LX, LX) / length2);
        hitFraction = min(max(z, 0.0), 1.0);
      }
      return mrgiVoxelMarchHit;
    }
  }
  // 9.
  return mrgiVoxelMarchClear;
}

// Whether light sample L is visible from receiver P through the voxel buffer
// `voxels` (mrgi_voxel_march()): true visible, false occluded.
bool mrgiVoxelVisible(usampler3D voxels, vec3 P, vec3 Np, vec3 L, vec3 Nl)
{
  float unused;
  return mrgiVoxelMarchCore(voxels, P, Np, L, Nl, false, unused) == mrgiVoxelMarchClear;
}

// The same on mrgiVoxelTexture (the texture SetMarchUniforms() binds).
bool mrgiVoxelVisible(vec3 P, vec3 Np, vec3 L, vec3 Nl)
{
  return mrgiVoxelVisible(mrgiVoxelTexture, P, Np, L, Nl);
}

// Distance from the light sample to the nearest occluder as a fraction of
// |L - P| in [0, 1], 1 for none, 0 below a horizon
// (mrgi_voxel_march_occluder_fraction(); NPW10 3.3.3's variance shadow query
// stores it and its square).
float mrgiVoxelOccluderFraction(usampler3D voxels, vec3 P, vec3 Np, vec3 L, vec3 Nl)
{
  float fraction;
  int outcome = mrgiVoxelMarchCore(voxels, P, Np, L, Nl, true, fraction);
  if (outcome == mrgiVoxelMarchHorizon)
  {
    return 0.0;
  }
  return outcome == mrgiVoxelMarchHit ? fraction : 1.0;
}

float mrgiVoxelOccluderFraction(vec3 P, vec3 Np, vec3 L, vec3 Nl)
{
  return mrgiVoxelOccluderFraction(mrgiVoxelTexture, P, Np, L, Nl);
}
