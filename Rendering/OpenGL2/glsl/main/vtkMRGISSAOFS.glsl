// MRGI screen-space ambient occlusion as VTK 9.1's vtkSSAOPass computes it;
// C twin and exact rules: mrgi_ssao.h (same operations in the same order).
// MRGI_SSAO_STAGE
// 0: the AO factor of every texel of one level (block side 2^mrgiLevel;
//    level 0 is full resolution), into a level-sized target at (0, 0);
// 1: apply: the target's RGB times AO (multiplicative blending set by the
//    stage, alpha kept), with vtkSSAOPass's 3x3 Gaussian when mrgiBlur.
// MRGI_SSAO_KERNEL_SIZE: the kernel's sample count (stage 0).
in vec2 texCoord; // bound by vtkOpenGLQuadHelper; texels are addressed by gl_FragCoord
uniform sampler2D mrgiInput0; // 0: G-buffer position; 1: AO (viewport-sized, at (0, 0))
uniform sampler2D mrgiInput1; // 0: G-buffer normal
uniform sampler2D mrgiNoise;  // 0: the window's noise tile (vtkOpenGLRenderWindow)
uniform ivec2 mrgiOrigin;     // the viewport's origin in the G-buffer / colour target
uniform ivec2 mrgiSize;       // the viewport's size
uniform int mrgiLevel;        // 0: level
uniform mat4 mrgiProjection;  // 0: eye -> clip
uniform float mrgiRadius;     // 0: kernel radius (eye units)
uniform float mrgiBias;       // 0: depth bias (eye units)
uniform int mrgiBlur;         // 1: vtkSSAOPass's Blur
uniform int mrgiOcclusion;    // 0: write 1 - AO (BMR levels); 1: the input holds 1 - AO
#if MRGI_SSAO_STAGE == 0
uniform vec3 mrgiKernel[MRGI_SSAO_KERNEL_SIZE];
#endif
//VTK::Output::Dec

#if MRGI_SSAO_STAGE == 0
bool mrgiFinite3(vec3 v)
{
  return !any(isnan(v)) && !any(isinf(v));
}

// floor(u * n) clamped to [0, n - 1], NaN to 0 (nearest, clamp to edge).
int mrgiTexel(float u, int n)
{
  float f = u * float(n);
  if (!(f >= 1.0)) { return 0; }
  if (f >= float(n - 1)) { return n - 1; }
  return int(floor(f));
}

float mrgiAO(ivec2 px)
{
  vec4 p = texelFetch(mrgiInput0, mrgiOrigin + px, 0);
  vec3 n = texelFetch(mrgiInput1, mrgiOrigin + px, 0).xyz;
  if (!(p.w > MRGI_GBUFFER_VALID_THRESHOLD) || !mrgiFinite3(p.xyz) || !mrgiFinite3(n) ||
    !(dot(n, n) > 0.0))
  {
    return 1.0;
  }
  vec4 d = mrgiProjection * vec4(p.xyz, 1.0);
  float depth = d.z / d.w * 0.5 + 0.5;
  if (!(depth > 0.0 && depth < 1.0))
  {
    return 1.0;
  }
  // vtkSSAOPass's noise lookup: tiling shift by integer division.
  ivec2 shift = mrgiSize / ivec2(MRGI_SSAO_NOISE_SIZE);
  vec2 c = (vec2(px) + 0.5) / vec2(mrgiSize) * vec2(shift);
  ivec2 t = ivec2(floor(c * float(MRGI_SSAO_NOISE_SIZE))) % MRGI_SSAO_NOISE_SIZE;
  float angle = 6.283185 * texelFetch(mrgiNoise, t, 0).r;
  vec3 v = vec3(cos(angle), sin(angle), 0.0);
  vec3 tangent = v - n * dot(v, n);
  float t2 = dot(tangent, tangent);
  if (!(t2 > 0.0) || isinf(t2))
  {
    return 1.0; // n parallel to v: no tangent frame (vtkSSAOPass: NaN)
  }
  tangent *= 1.0 / sqrt(t2);
  vec3 bitangent = cross(n, tangent);
  mat3 tbn = mat3(tangent, bitangent, n);
  float occlusion = 0.0;
  for (int i = 0; i < MRGI_SSAO_KERNEL_SIZE; ++i)
  {
    vec3 s = p.xyz + (tbn * mrgiKernel[i]) * mrgiRadius;
    vec4 sc = mrgiProjection * vec4(s, 1.0);
    vec2 u = sc.xy / sc.w * 0.5 + 0.5;
    ivec2 q = ivec2(mrgiTexel(u.x, mrgiSize.x), mrgiTexel(u.y, mrgiSize.y));
    vec4 sp = texelFetch(mrgiInput0, mrgiOrigin + q, 0);
    if (!(sp.w > MRGI_GBUFFER_VALID_THRESHOLD) || isnan(sp.z) || isinf(sp.z))
    {
      continue; // the background never occludes
    }
    float range = smoothstep(0.0, 1.0, mrgiRadius / abs(p.z - sp.z));
    occlusion += (sp.z >= s.z + mrgiBias ? 1.0 : 0.0) * range;
  }
  return clamp(1.0 - occlusion / float(MRGI_SSAO_KERNEL_SIZE), 0.0, 1.0);
}
#endif

void main()
{
#if MRGI_SSAO_STAGE == 0
  ivec2 t = ivec2(gl_FragCoord.xy);
  int side = 1 << mrgiLevel;
  ivec2 px = min(t * side + ivec2(side / 2), mrgiSize - ivec2(1));
  float ao = mrgiAO(px);
  gl_FragData[0] = vec4(mrgiOcclusion != 0 ? 1.0 - ao : ao, 0.0, 0.0, 1.0);
#else
  ivec2 t = ivec2(gl_FragCoord.xy) - mrgiOrigin;
  // 1 - AO is blurred as AO is (the Gaussian's weights sum to 1).
  float ao = texelFetch(mrgiInput0, t, 0).r;
  if (mrgiBlur != 0)
  {
    // vtkSSAOPass's 3x3 Gaussian (its weights); taps clamp to the viewport
    // (vtkSSAOPass's texture repeats: its border pixels read the opposite side).
    ivec2 hi = mrgiSize - ivec2(1);
    ao = 0.195346 * ao;
    ao += 0.077847 * texelFetch(mrgiInput0, clamp(t + ivec2(-1, -1), ivec2(0), hi), 0).r;
    ao += 0.077847 * texelFetch(mrgiInput0, clamp(t + ivec2(-1, 1), ivec2(0), hi), 0).r;
    ao += 0.077847 * texelFetch(mrgiInput0, clamp(t + ivec2(1, -1), ivec2(0), hi), 0).r;
    ao += 0.077847 * texelFetch(mrgiInput0, clamp(t + ivec2(1, 1), ivec2(0), hi), 0).r;
    ao += 0.123317 * texelFetch(mrgiInput0, clamp(t + ivec2(-1, 0), ivec2(0), hi), 0).r;
    ao += 0.123317 * texelFetch(mrgiInput0, clamp(t + ivec2(1, 0), ivec2(0), hi), 0).r;
    ao += 0.123317 * texelFetch(mrgiInput0, clamp(t + ivec2(0, -1), ivec2(0), hi), 0).r;
    ao += 0.123317 * texelFetch(mrgiInput0, clamp(t + ivec2(0, 1), ivec2(0), hi), 0).r;
  }
  if (mrgiOcclusion != 0)
  {
    ao = 1.0 - ao;
  }
  gl_FragData[0] = vec4(vec3(ao), 1.0);
#endif
}
