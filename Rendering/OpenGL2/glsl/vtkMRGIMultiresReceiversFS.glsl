// MRGI multiresolution receivers: the mean eye-space position and normal of
// each texel's valid pixels, level by level (C twin and exact rules:
// mrgi_multires_receivers.h). MRGI_MR_STAGE 0: level 0 from the G-buffer;
// 1: level i from level i-1 (children outside the level skipped, weighted
// by their pixel counts); 2: copy a level into the flattened layout.
in vec2 texCoord; // bound by vtkOpenGLQuadHelper; texels are addressed by gl_FragCoord
uniform sampler2D mrgiInput0;  // position (stage 0: G-buffer; 1: level i-1; 2: level i)
uniform sampler2D mrgiInput1;  // normal
uniform ivec2 mrgiOffset;      // stage 0: G-buffer texel of pixel (0, 0); stage 2: level offset
uniform ivec2 mrgiSize;        // stage 1: size of level i-1
//VTK::Output::Dec
vec3 mrgiNormalize(vec3 n)
{
  float length2 = n.x * n.x + n.y * n.y + n.z * n.z;
  if (!(length2 > MRGI_MULTIRES_MIN_PIXEL_SIZE)) { length2 = MRGI_MULTIRES_MIN_PIXEL_SIZE; }
  return n * (1.0 / sqrt(length2));
}
void main()
{
  ivec2 t = ivec2(gl_FragCoord.xy);
#if MRGI_MR_STAGE == 0
  vec4 P = texelFetch(mrgiInput0, t + mrgiOffset, 0);
  vec3 N = texelFetch(mrgiInput1, t + mrgiOffset, 0).xyz;
  bool valid = P.w > MRGI_GBUFFER_VALID_THRESHOLD && !any(isnan(P.xyz)) && !any(isinf(P.xyz)) &&
    !any(isnan(N)) && !any(isinf(N));
  gl_FragData[0] = valid ? vec4(P.xyz, 1.0) : vec4(0.0);
  gl_FragData[1] = valid ? vec4(mrgiNormalize(N), 0.0) : vec4(0.0);
#elif MRGI_MR_STAGE == 1
  vec3 sumP = vec3(0.0);
  vec3 sumN = vec3(0.0);
  float total = 0.0;
  for (int b = 0; b < 2; ++b)
  {
    for (int c = 0; c < 2; ++c)
    {
      ivec2 s = 2 * t + ivec2(c, b);
      if (s.x >= mrgiSize.x || s.y >= mrgiSize.y) { continue; }
      vec4 p = texelFetch(mrgiInput0, s, 0);
      if (!(p.w > 0.0)) { continue; }
      sumP += p.w * p.xyz;
      sumN += p.w * texelFetch(mrgiInput1, s, 0).xyz;
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
#else
  gl_FragData[0] = texelFetch(mrgiInput0, t - mrgiOffset, 0);
  gl_FragData[1] = texelFetch(mrgiInput1, t - mrgiOffset, 0);
#endif
}
