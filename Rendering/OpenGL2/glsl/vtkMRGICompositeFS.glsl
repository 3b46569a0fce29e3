//VTK::System::Dec

// MRGI composite: writes the frame MRGI rendered into its own float buffers to
// the framebuffer VTK expects, with the scene's depth, so that later passes
// (translucency, overlays) and picking see the scene as if drawn directly.
// Later stages add the indirect term here: direct + albedo * indirect.

in vec2 texCoord;

uniform sampler2D mrgiDirect;  // HDR colour of the delegate's rendering
uniform sampler2D mrgiDepth;   // window-space depth of the same rendering

//VTK::Output::Dec

void main()
{
  vec4 direct = texture(mrgiDirect, texCoord);
  gl_FragData[0] = direct;
  gl_FragDepth = texture(mrgiDepth, texCoord).r;
}
