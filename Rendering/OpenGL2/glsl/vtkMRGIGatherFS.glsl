// MRGI full-resolution gather (nichols-shopf-wyman-2009 section 3.2.2,
// equations 1 and 5, no visibility): every pixel sums every VPL. C twin:
// mrgi_gather_full() (mrgi_gather.h), whose formula this mirrors term by term.
// MRGI's buffers are as large as the window: gl_FragCoord addresses them
// directly; the multiresolution gather, drawn level by level into the
// flattened layout, reads each level's receivers at gl_FragCoord + mrgiReceiverOffset.
in vec2 texCoord; // bound by vtkOpenGLQuadHelper; these passes address texels by gl_FragCoord
uniform sampler2D mrgiPosition;  // G-buffer, eye space
uniform sampler2D mrgiNormal;
uniform sampler2D mrgiAlbedo;
uniform sampler2D mrgiVPLs;      // MRGI_VPL_TEXELS x count
uniform int mrgiVPLCount;
uniform mat4 mrgiVCToWC;         // eye -> world (rigid)
uniform float mrgiStrength;      // IndirectStrength
uniform ivec2 mrgiReceiverOffset; // receiver texel of fragment (0, 0); 0 for the full gather
//VTK::Output::Dec
void main()
{
  ivec2 pixel = ivec2(gl_FragCoord.xy) + mrgiReceiverOffset;
  vec4 positionVC = texelFetch(mrgiPosition, pixel, 0);
  if (positionVC.w <= MRGI_VALID_THRESHOLD)
  {
    gl_FragData[0] = vec4(0.0);
#ifndef MRGI_GATHER_IRRADIANCE_ONLY
    gl_FragData[1] = vec4(0.0);
#endif
    return;
  }
  // Malformed receivers (valid flag set, but a non-finite position or normal,
  // or a zero normal: NaN/Inf or zero normals in the input data) get E = 0,
  // as in the C twin; one NaN must not spread through the sums.
  vec3 normalVC = texelFetch(mrgiNormal, pixel, 0).xyz;
  if (any(isnan(positionVC.xyz)) || any(isinf(positionVC.xyz)) || any(isnan(normalVC)) ||
    any(isinf(normalVC)) || dot(normalVC, normalVC) == 0.0)
  {
    gl_FragData[0] = vec4(0.0, 0.0, 0.0, 1.0);
#ifndef MRGI_GATHER_IRRADIANCE_ONLY
    gl_FragData[1] = vec4(0.0, 0.0, 0.0, 1.0);
#endif
    return;
  }
  vec3 P = (mrgiVCToWC * vec4(positionVC.xyz, 1.0)).xyz;
  vec3 N = normalize(mat3(mrgiVCToWC) * normalVC);
  vec3 E = vec3(0.0);
  for (int j = 0; j < mrgiVPLCount; ++j)
  {
    vec4 flux = texelFetch(mrgiVPLs, ivec2(MRGI_VPL_TEXEL_FLUX, j), 0);
    if (flux.r == 0.0 && flux.g == 0.0 && flux.b == 0.0) { continue; }
    vec4 position = texelFetch(mrgiVPLs, ivec2(MRGI_VPL_TEXEL_POSITION, j), 0);
    vec3 d = position.xyz - P;
    float r2 = dot(d, d);
    if (r2 == 0.0) { continue; }
    vec3 Nj = normalize(texelFetch(mrgiVPLs, ivec2(MRGI_VPL_TEXEL_NORMAL, j), 0).xyz);
    float cosIr = dot(N, d);
    float cosJr = -dot(Nj, d);
    if (cosIr <= 0.0 || cosJr <= 0.0) { continue; }
    E += flux.rgb * ((cosIr * cosJr / r2) / (MRGI_PI * r2 + position.w));
  }
  gl_FragData[0] = vec4(E, 1.0);           // E_i, compared with the C twin
#ifndef MRGI_GATHER_IRRADIANCE_ONLY
  vec3 albedo = texelFetch(mrgiAlbedo, pixel, 0).rgb;
  gl_FragData[1] = vec4(mrgiStrength * albedo * E, 1.0);  // indirect radiance added to the direct light
#endif
}
