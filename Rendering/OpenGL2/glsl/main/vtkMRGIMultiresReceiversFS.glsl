// MRGI multiresolution receivers: the mean eye-space position and normal of
// each texel's valid pixels, level by level (C twin and exact rules:
// mrgi_multires_receivers.h). MRGI_MR_STAGE 0: level 0 from the G-buffer
// (only read back for tests: the gather reads level 0 from the G-buffer
// itself); 1: level i from level i-1 (children outside the level skipped,
// weighted by their pixel counts); 2: level 1 straight from the G-buffer,
// the same sums as stage 0 followed by stage 1 (pixel counts of 1 make
// every product exact), without writing level 0.
in vec2 texCoord; // bound by vtkOpenGLQuadHelper; texels are addressed by gl_FragCoord
uniform sampler2D mrgiInput0;  // position (stages 0, 2: G-buffer; 1: level i-1)
uniform sampler2D mrgiInput1;  // normal
uniform ivec2 mrgiOffset;      // stages 0, 2: G-buffer texel of pixel (0, 0)
uniform ivec2 mrgiSize;        // stages 1, 2: size of level i-1
//VTK::Output::Dec
vec3 mrgiNormalize(vec3 n)
{
  float length2 = n.x * n.x + n.y * n.y + n.z * n.z;
  if (!(length2 > MRGI_MULTIRES_MIN_PIXEL_SIZE)) { length2 = MRGI_MULTIRES_MIN_PIXEL_SIZE; }
  return n * (1.0 / sqrt(length2));
}
// Level-0 receiver of G-buffer pixel p: (position, 1) and its unit normal, or zeros.
void mrgiPixel(ivec2 p, out vec4 position, out vec4 normal)
{
  vec4 P = texelFetch(mrgiInput0, p + mrgiOffset, 0);
  vec3 N = texelFetch(mrgiInput1, p + mrgiOffset, 0).xyz;
  bool valid = P.w > MRGI_GBUFFER_VALID_THRESHOLD && !any(isnan(P.xyz)) && !any(isinf(P.xyz)) &&
    !any(isnan(N)) && !any(isinf(N));
  position = valid ? vec4(P.xyz, 1.0) : vec4(0.0);
  normal = valid ? vec4(mrgiNormalize(N), 0.0) : vec4(0.0);
}
void main()
{
  ivec2 t = ivec2(gl_FragCoord.xy);
#if MRGI_MR_STAGE == 0
  vec4 position, normal;
  mrgiPixel(t, position, normal);
  gl_FragData[0] = position;
  gl_FragData[1] = normal;
#else
  vec3 sumP = vec3(0.0);
  vec3 sumN = vec3(0.0);
  float total = 0.0;
  for (int b = 0; b < 2; ++b)
  {
    for (int c = 0; c < 2; ++c)
    {
      ivec2 s = 2 * t + ivec2(c, b);
      if (s.x >= mrgiSize.x || s.y >= mrgiSize.y) { continue; }
#if MRGI_MR_STAGE == 1
      vec4 p = texelFetch(mrgiInput0, s, 0);
      if (!(p.w > 0.0)) { continue; }
      vec4 n = texelFetch(mrgiInput1, s, 0);
#else
      vec4 p, n;
      mrgiPixel(s, p, n);
      if (!(p.w > 0.0)) { continue; }
#endif
      sumP += p.w * p.xyz;
      sumN += p.w * n.xyz;
      total += p.w;
    }
  }
  if (!(total > 0.0))
  {
    gl_FragData[0] = vec4(0.0);
    gl_FragData[1] = vec4(0.0);
    return;
  }
  gl_FragData[0] = vec4(sumP / total, total);
  gl_FragData[1] = vec4(mrgiNormalize(sumN), 0.0);
#endif
}
