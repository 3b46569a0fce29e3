// MRGI area light, diffuse direct light without visibility
// (nichols-penmatsa-wyman-2010 section 3.2, eq. 2; the disk-to-point form
// factor of nichols-shopf-wyman-2009 eq. 1). C twin:
// mrgi_area_light_diffuse() (mrgi_area_light.h, "Direct light without
// visibility"), which this translates line by line, in float, in the same
// order; world space throughout. The samples texture is the core's
// ::mrgi_area_light_sample records (MRGI_AREA_LIGHT_SAMPLE_TEXELS RGBA32F
// texels per sample, one row per sample); the uniforms are
// ::mrgi_area_light_uniforms.
uniform sampler2D mrgiAreaSamples;
uniform int mrgiAreaSampleFirst; // this draw's samples: first .. first + count - 1
uniform int mrgiAreaSampleCount;
uniform vec3 mrgiAreaCenter;
uniform vec3 mrgiAreaNormal;
uniform vec3 mrgiAreaCorners[4];
uniform int mrgiAreaTwoSided;
#ifdef MRGI_AREA_VISIBILITY
// Visibility of each sample by a march through the screen-space voxels
// (nichols-penmatsa-wyman-2010 3.3.1, vtkMRGIVoxelMarch.glsl, prepended,
// with its uniforms), in eye space: the voxels' space.
uniform mat4 mrgiWCToVC;
#endif
#ifdef MRGI_AREA_VISIBILITY_MASKS
// Visibility from the incremental pyramid (3.3.2, vtkMRGIVisibilityPyramid):
// one bit per sample at this texel, sample j in word j >> 5 (texture
// (j >> 5) >> 2, channel (j >> 5) & 3), bit j & 31; level-local texels.
uniform usampler2D mrgiVisibilityMask0;
uniform usampler2D mrgiVisibilityMask1;
uniform usampler2D mrgiVisibilityMask2;
uniform usampler2D mrgiVisibilityMask3;
uniform ivec2 mrgiMaskOffset; // level-local texel = flattened texel + this
#endif

// The VTK irradiance X at receiver (P, N) (world space; Pvc, Nvc the same
// receiver in eye space, for the visibility march): the receiver shows
// albedo * X.
vec3 mrgiAreaLightDiffuse(vec3 P, vec3 N, vec3 Pvc, vec3 Nvc)
{
  // Early-out 1: behind a one-sided light or in its plane (two-sided: in
  // its plane). "for one-sided lights ... we also discard fragments behind
  // the source" (3.2); it also keeps the emitter's own pixels dark.
  float side = dot(mrgiAreaNormal, P - mrgiAreaCenter);
  if (mrgiAreaTwoSided != 0 ? side == 0.0 : !(side > 0.0))
  {
    return vec3(0.0);
  }
  // Early-out 2: facing away from every corner ("If N.L_j < 0 for all j,
  // we trivially discard the fragment").
  bool facing = false;
  for (int k = 0; k < 4; ++k)
  {
    facing = facing || dot(N, mrgiAreaCorners[k] - P) > 0.0;
  }
  if (!facing)
  {
    return vec3(0.0);
  }
  vec3 X = vec3(0.0);
#ifdef MRGI_AREA_VISIBILITY_MASKS
  ivec2 maskTexel = ivec2(gl_FragCoord.xy) + mrgiMaskOffset;
  uvec4 masks[4];
  masks[0] = texelFetch(mrgiVisibilityMask0, maskTexel, 0);
  masks[1] = texelFetch(mrgiVisibilityMask1, maskTexel, 0);
  masks[2] = texelFetch(mrgiVisibilityMask2, maskTexel, 0);
  masks[3] = texelFetch(mrgiVisibilityMask3, maskTexel, 0);
#endif
  for (int j = mrgiAreaSampleFirst; j < mrgiAreaSampleFirst + mrgiAreaSampleCount; ++j)
  {
    vec4 position = texelFetch(mrgiAreaSamples, ivec2(MRGI_AREA_LIGHT_SAMPLE_TEXEL_POSITION, j), 0);
    vec3 d = position.xyz - P;
    float r2 = dot(d, d);
    if (!(r2 > 0.0)) { continue; } // on the sample: direction undefined
    vec3 sampleNormal = texelFetch(mrgiAreaSamples, ivec2(MRGI_AREA_LIGHT_SAMPLE_TEXEL_NORMAL, j), 0).xyz;
    float cosIr = dot(N, d);
    float cosJr = -dot(sampleNormal, d);
    if (mrgiAreaTwoSided != 0) { cosJr = abs(cosJr); }
    if (!(cosIr > 0.0) || !(cosJr > 0.0)) { continue; }
#ifdef MRGI_AREA_VISIBILITY
    // The naive query (3.3.1): one march per receiver and sample.
    vec3 Lvc = (mrgiWCToVC * vec4(position.xyz, 1.0)).xyz;
    vec3 NLvc = mat3(mrgiWCToVC) * sampleNormal;
    // A two-sided light emits from the side facing the receiver: that
    // side's normal (the horizon test and the bias at the light end).
    if (mrgiAreaTwoSided != 0 && mrgiVoxelDot(NLvc, Pvc - Lvc) < 0.0) { NLvc = -NLvc; }
    if (!mrgiVoxelVisible(Pvc, Nvc, Lvc, NLvc)) { continue; }
#endif
#ifdef MRGI_AREA_VISIBILITY_MASKS
    if (((masks[j >> 7][(j >> 5) & 3] >> uint(j & 31)) & 1u) == 0u) { continue; }
#endif
    vec3 radiance = texelFetch(mrgiAreaSamples, ivec2(MRGI_AREA_LIGHT_SAMPLE_TEXEL_RADIANCE, j), 0).rgb;
    X += radiance * (position.w * (cosIr * cosJr / r2) / (MRGI_PI * r2 + position.w));
  }
  return X;
}

#define MRGI_AREA_LIGHT_DIFFUSE_DECLARED
