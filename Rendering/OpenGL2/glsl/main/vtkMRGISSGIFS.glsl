// MRGI screen-space one bounce and directional occlusion (Ritschel et al.
// 2009, as BMR evaluates SSGI); C twin and exact rules: mrgi_ssgi.h (same
// operations in the same order).
// MRGI_SSGI_STAGE
// 0: every texel of one level (block side 2^mrgiLevel; level 0 is full
//    resolution) into a level-sized target at (0, 0): rgb = the bounce
//    radiance rho X, a = the directional visibility V;
// 1: apply: the target's RGB plus the bounce (additive blending set by the
//    stage, alpha kept).
// MRGI_SSGI_SAMPLES: the kernel's sample count (stage 0).
in vec2 texCoord; // bound by vtkOpenGLQuadHelper; texels are addressed by gl_FragCoord
uniform sampler2D mrgiInput0; // 0: G-buffer position; 1: SSGI (viewport-sized, at (0, 0))
uniform sampler2D mrgiInput1; // 0: G-buffer normal
uniform sampler2D mrgiInput2; // 0: G-buffer albedo
uniform sampler2D mrgiInput3; // 0: direct light (the senders' radiance)
uniform ivec2 mrgiOrigin;     // the viewport's origin in the G-buffer / colour target
uniform ivec2 mrgiSize;       // the viewport's size
uniform int mrgiLevel;        // 0: level
uniform mat4 mrgiProjection;  // 0: eye -> clip
uniform float mrgiRadius;     // 0: R (eye units)
uniform float mrgiBias;       // 0: depth bias (eye units)
#if MRGI_SSGI_STAGE == 0
uniform vec3 mrgiKernel[MRGI_SSGI_SAMPLES];
#endif
//VTK::Output::Dec

#if MRGI_SSGI_STAGE == 0
bool mrgiFinite3(vec3 v)
{
  return !any(isnan(v)) && !any(isinf(v));
}

// floor(u * n), or -1 outside [0, n).
int mrgiTexel(float u, int n)
{
  float f = u * float(n);
  if (!(f >= 0.0) || !(f < float(n))) { return -1; }
  return min(int(floor(f)), n - 1);
}

vec4 mrgiSSGI(ivec2 px)
{
  vec4 p = texelFetch(mrgiInput0, mrgiOrigin + px, 0);
  vec3 nv = texelFetch(mrgiInput1, mrgiOrigin + px, 0).xyz;
  vec3 albedo = texelFetch(mrgiInput2, mrgiOrigin + px, 0).rgb;
  if (!(p.w > MRGI_GBUFFER_VALID_THRESHOLD) || !mrgiFinite3(p.xyz) || !mrgiFinite3(nv) ||
    !mrgiFinite3(albedo))
  {
    return vec4(0.0, 0.0, 0.0, 1.0);
  }
  float n2 = dot(nv, nv);
  if (!(n2 > 0.0) || isinf(n2))
  {
    return vec4(0.0, 0.0, 0.0, 1.0);
  }
  vec3 n = nv * (1.0 / sqrt(n2));
  // Duff et al. 2017's orthonormal basis.
  float sg = n.z >= 0.0 ? 1.0 : -1.0;
  float a = -1.0 / (sg + n.z);
  float bb = n.x * n.y * a;
  vec3 t = vec3(1.0 + sg * n.x * n.x * a, sg * bb, -sg * n.x);
  vec3 b = vec3(bb, sg + n.y * n.y * a, -n.y);
  float r = mrgiRadius;
  float range = float(MRGI_SSGI_RANGE) * r;
  float area = r * r / float(MRGI_SSGI_SAMPLES);
  float total = 0.0;
  for (int i = 0; i < MRGI_SSGI_SAMPLES; ++i)
  {
    vec3 k = mrgiKernel[i];
    total += k.z / sqrt(dot(k, k));
  }
  float blocked = 0.0;
  vec3 x = vec3(0.0);
  for (int i = 0; i < MRGI_SSGI_SAMPLES; ++i)
  {
    vec3 k = mrgiKernel[i];
    float c = k.z / sqrt(dot(k, k)) / total;
    vec3 s = p.xyz + (t * k.x + b * k.y + n * k.z) * r;
    vec4 sc = mrgiProjection * vec4(s, 1.0);
    float u = sc.x / sc.w * 0.5 + 0.5;
    float v = sc.y / sc.w * 0.5 + 0.5;
    ivec2 q = ivec2(mrgiTexel(u, mrgiSize.x), mrgiTexel(v, mrgiSize.y));
    if (q.x < 0 || q.y < 0 || !(sc.w > 0.0))
    {
      continue; // off screen or behind the eye: taken as open
    }
    vec4 qp = texelFetch(mrgiInput0, mrgiOrigin + q, 0);
    if (!(qp.w > MRGI_GBUFFER_VALID_THRESHOLD) || !mrgiFinite3(qp.xyz))
    {
      continue; // the background neither blocks nor sends
    }
    vec3 dv = qp.xyz - p.xyz;
    float d2 = dot(dv, dv);
    float d = sqrt(d2);
    float height = dot(n, dv);
    if (!(qp.z >= s.z + mrgiBias) || !(d <= range) || !(height > mrgiBias))
    {
      continue; // in front of the depth buffer, far foreground, own plane
    }
    blocked += c;
    vec3 nq = texelFetch(mrgiInput1, mrgiOrigin + q, 0).xyz;
    vec3 lq = texelFetch(mrgiInput3, mrgiOrigin + q, 0).rgb;
    if (!(d > 0.0) || !mrgiFinite3(nq) || !mrgiFinite3(lq))
    {
      continue; // blocks, but cannot send
    }
    float cr = max(0.0, dot(n, dv) / d);
    float cs = max(0.0, -dot(nq, dv) / d);
    float f = min(area * cr * cs / (d2 + area), c);
    x += f * lq;
  }
  return vec4(albedo * x, clamp(1.0 - blocked, 0.0, 1.0));
}
#endif

void main()
{
#if MRGI_SSGI_STAGE == 0
  ivec2 t = ivec2(gl_FragCoord.xy);
  int side = 1 << mrgiLevel;
  ivec2 px = min(t * side + ivec2(side / 2), mrgiSize - ivec2(1));
  gl_FragData[0] = mrgiSSGI(px);
#else
  ivec2 t = ivec2(gl_FragCoord.xy) - mrgiOrigin;
  gl_FragData[0] = vec4(texelFetch(mrgiInput0, t, 0).rgb, 0.0);
#endif
}
