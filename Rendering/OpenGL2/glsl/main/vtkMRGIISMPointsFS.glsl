// MRGI imperfect shadow maps, the point draw's fragment: the distance to
// the VPL (scene units) into the R32F atlas, where GL_MIN blending keeps
// the nearest point of each texel (ritschel-et-al-2008 3.3; C twin
// mrgi_ism_atlas_render(), mrgi_ism_atlas.h section 5).
//VTK::Output::Dec
flat in float mrgiDepth;
void main()
{
  gl_FragData[0] = vec4(mrgiDepth, 0.0, 0.0, 1.0);
}
