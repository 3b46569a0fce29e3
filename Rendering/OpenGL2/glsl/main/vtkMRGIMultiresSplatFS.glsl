// MRGI multiresolution splatting: a subsplat covers one texel of the
// flattened buffer and writes its VPL's contribution; blending adds the
// colours (GL_FUNC_ADD) and keeps alpha at 1 (GL_MAX).
//VTK::System::Dec
flat in vec4 mrgiSubsplat;
//VTK::Output::Dec
void main()
{
  gl_FragData[0] = mrgiSubsplat;
}
