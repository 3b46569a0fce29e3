// MRGI composite: writes the frame MRGI rendered into its own float buffers
// to the framebuffer VTK expects, with the scene's depth, so that passes
// after MRGI and picking see the scene as if drawn directly.
in vec2 texCoord; // bound by vtkOpenGLQuadHelper; these passes address texels by gl_FragCoord
uniform sampler2D mrgiColor;  // HDR colour (direct + indirect + translucency/overlays)
uniform sampler2D mrgiDepth;  // window-space depth
//VTK::Output::Dec
void main()
{
  // MRGI's buffers are as large as the window: gl_FragCoord addresses them.
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  gl_FragData[0] = texelFetch(mrgiColor, pixel, 0);
  gl_FragDepth = texelFetch(mrgiDepth, pixel, 0).r;
}
