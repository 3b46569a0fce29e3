// MRGI output: writes the frame MRGI rendered into its own float buffers
// to the framebuffer VTK expects, with the scene's depth, so that passes
// after MRGI and picking see the scene as if drawn directly. On the way the
// colour is exposed and tone mapped: the GLSL twin of mrgi_exposure_apply
// (mrgi_exposure.h), in the same order of operations.
// MRGI_OUTPUT_NO_DEPTH: colour only (into MRGI's display image).
// MRGI_OUTPUT_GBUFFER: also eye-space position and normal into draw buffers
// 1 and 2, as vtkSSAOPass's shader replacement writes them, for an
// enclosing pass that reads them (vtkSSAOPass wrapped around MRGI).
in vec2 texCoord; // bound by vtkOpenGLQuadHelper; these passes address texels by gl_FragCoord
uniform sampler2D mrgiColor;  // HDR colour (direct + indirect + translucency/volumes)
uniform sampler2D mrgiDepth;  // window-space depth
uniform float mrgiExposureScale; // 2^EV (mrgi_exposure_scale)
uniform int mrgiToneMap;         // non-zero: mrgi_tone_curve
#ifdef MRGI_OUTPUT_GBUFFER
uniform sampler2D mrgiPosition;
uniform sampler2D mrgiNormal;
#endif
//VTK::Output::Dec

// mrgi_tone_curve: identity up to the shoulder k, then k + (1-k)(1 - exp(-(x-k)/(1-k))).
float mrgiToneCurve(float x)
{
  const float k = float(MRGI_TONE_SHOULDER);
  if (!(x > 0.0))
  {
    return 0.0;
  }
  if (x <= k)
  {
    return x;
  }
  return k + (1.0 - k) * (1.0 - exp(-(x - k) / (1.0 - k)));
}

void main()
{
  // MRGI's buffers are as large as the window: gl_FragCoord addresses them.
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  vec4 color = texelFetch(mrgiColor, pixel, 0);
  vec3 x = mrgiExposureScale * color.rgb;
  if (mrgiToneMap != 0)
  {
    x = vec3(mrgiToneCurve(x.r), mrgiToneCurve(x.g), mrgiToneCurve(x.b));
  }
  gl_FragData[0] = vec4(x, color.a);
#ifndef MRGI_OUTPUT_NO_DEPTH
  gl_FragDepth = texelFetch(mrgiDepth, pixel, 0).r;
#endif
#ifdef MRGI_OUTPUT_GBUFFER
  vec4 position = texelFetch(mrgiPosition, pixel, 0);
  bool valid = position.w > MRGI_GBUFFER_VALID_THRESHOLD;
  gl_FragData[1] = valid ? vec4(position.xyz, 1.0) : vec4(0.0);
  gl_FragData[2] = valid ? vec4(texelFetch(mrgiNormal, pixel, 0).xyz, 1.0) : vec4(0.0);
#endif
}
