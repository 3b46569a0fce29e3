// MRGI: adds the gather's indirect radiance (strength * albedo * E) to the
// direct light, with additive blending, where the G-buffer holds geometry.
// MRGI's buffers are as large as the window: gl_FragCoord addresses them directly.
in vec2 texCoord; // bound by vtkOpenGLQuadHelper; these passes address texels by gl_FragCoord
uniform sampler2D mrgiIndirect;
//VTK::Output::Dec
void main()
{
  vec4 indirect = texelFetch(mrgiIndirect, ivec2(gl_FragCoord.xy), 0);
  gl_FragData[0] = vec4(indirect.rgb, 0.0);
}
