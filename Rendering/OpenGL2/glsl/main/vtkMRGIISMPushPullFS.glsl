// MRGI imperfect shadow maps, push-pull hole filling (ritschel-et-al-2008
// 3.3 "pull-push"; C twin mrgi_ism_push_pull(), mrgi_ism_atlas.h section 4).
// The atlas' mip level k is (C T >> k) x (R T >> k) texels; since T is a
// power of two, the 2 x 2 children of a level-k texel and its parent all
// lie in the same tile, so tiles never mix. Full-screen over level k:
//   MRGI_ISM_PUSH_PULL_STAGE 0 (pull): mrgiInput0 = level k-1 (pulled);
//     the mean of its valid children, summed in the C twin's order (empty
//     if none);
//   MRGI_ISM_PUSH_PULL_STAGE 1 (push): mrgiInput0 = level k pulled,
//     mrgiInput1 = level k+1 pushed; an empty texel takes its parent's.
//VTK::Output::Dec
in vec2 texCoord;
uniform sampler2D mrgiInput0;
uniform sampler2D mrgiInput1;
void main()
{
  ivec2 t = ivec2(gl_FragCoord.xy);
  float E = float(MRGI_ISM_EMPTY_DEPTH);
#if MRGI_ISM_PUSH_PULL_STAGE == 0
  float sum = 0.0;
  int count = 0;
  for (int k = 0; k < 4; ++k)
  {
    float c = texelFetch(mrgiInput0, 2 * t + ivec2(k % 2, k / 2), 0).r;
    bool valid = !isnan(c) && c < E;
    sum += valid ? c : 0.0;
    count += valid ? 1 : 0;
  }
  gl_FragData[0] = vec4(count > 0 ? sum / float(count) : E, 0.0, 0.0, 1.0);
#else
  float d = texelFetch(mrgiInput0, t, 0).r;
  if (!(d < E))
  {
    d = texelFetch(mrgiInput1, t / 2, 0).r;
  }
  gl_FragData[0] = vec4(d, 0.0, 0.0, 1.0);
#endif
}
