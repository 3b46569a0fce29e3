// MRGI: the Phong highlight of one area light (nichols-penmatsa-wyman-2010
// 3.2.1: "diffuse and specular are gathered in separate passes"), at every
// pixel whose G-buffer holds a specular material: k_s c_s S, S from
// vtkMRGIAreaLightSpecular.glsl (C twin mrgi_area_light_specular(), or
// mrgi_area_light_specular_visible() with visibility), which the C++ side
// prepends with the receiver test (vtkMRGIVPLIrradiance.glsl). Full
// resolution: sharp lobes change from pixel to pixel, and the lobe grid
// keeps their cost at 25 lookups.
//
// Shadows (3.3.3), with MRGI_AREA_SPECULAR_VISIBILITY defined before the
// libraries (vtkMRGIAreaLightStage::RenderSpecular()):
// - sample path: sample j counts where it is visible, either bit j of this
//   pixel's level-0 mask of the incremental visibility
//   (MRGI_AREA_SPECULAR_MASKS: vtkMRGIVisibilityPyramid, word w in texture
//   w / 4 channel w % 4, viewport-local texels), or by a march through the
//   voxels (otherwise: the naive query of 3.3.1, vtkMRGIVoxelMarch.glsl
//   prepended, in batches of samples, MRGI_AREA_SPECULAR_BATCHES, each draw
//   adding its batch; draws after the first write 0 where the path is not
//   the sample sum);
// - lobe-grid path: cell j weighted by the variance shadow query's
//   visibility of query j (vtkMRGIVarianceShadowResolve.glsl prepended,
//   resolved here, at the pixels that need it).
//
// Multiresolution (MRGI_AREA_SPECULAR_MULTIRES: vtkMRGIPass
// AreaLightSpecularResolution = SpecularMultiresolution, drawn by
// vtkMRGIGather::GatherSpecular() once per level at the texels
// of the specular stencil, mrgi_specular_stencil.h): the receiver is the
// texel's (mean position and normal, mrgiPosition/mrgiNormal at
// gl_FragCoord + mrgiReceiverOffset), the exponent the largest of its
// footprint (mrgiMaterial.y), and the output is S alone (alpha 1): the
// upsampled S is multiplied by each pixel's own k_s c_s in the resolve.
// Visibility: the sample path reads the texel's own masks of that level
// (mrgiViewportOrigin = the level's origin in the flattened layout), the
// lobe grid reads the variance shadow query at the footprint's centre pixel
// (the moments are full resolution).
in vec2 texCoord; // bound by vtkOpenGLQuadHelper; texels are addressed by gl_FragCoord
uniform sampler2D mrgiPosition;  // G-buffer, eye space
uniform sampler2D mrgiNormal;
uniform sampler2D mrgiSpecular;  // k_s c_s
uniform sampler2D mrgiShininess; // r: Phong exponent
uniform mat4 mrgiVCToWC;         // eye -> world (rigid)
uniform int mrgiParallel;        // 1: parallel projection (view direction +z in eye space)
#ifdef MRGI_AREA_SPECULAR_MULTIRES
uniform ivec2 mrgiReceiverOffset; // flattened texel -> receiver texel
uniform sampler2D mrgiMaterial;   // level material: x max k_s, y largest exponent (level-local)
uniform ivec2 mrgiLevelOrigin;    // the level's origin in the flattened layout
uniform int mrgiLevelScale;       // 2^level
uniform ivec2 mrgiViewportSize;   // full-resolution viewport (variance shadow query)
#endif
#ifdef MRGI_AREA_SPECULAR_VISIBILITY
uniform ivec2 mrgiViewportOrigin; // window pixel of the viewport's lower left corner
float mrgiSpecularQueries[MRGI_VOXEL_VSM_QUERIES];
#ifdef MRGI_AREA_SPECULAR_MASKS
uniform usampler2D mrgiVisibilityMask0;
uniform usampler2D mrgiVisibilityMask1;
uniform usampler2D mrgiVisibilityMask2;
uniform usampler2D mrgiVisibilityMask3;
uvec4 mrgiSpecularMasks[4];
bool mrgiAreaSpecularSampleVisible(int j, vec3 samplePosition, vec3 sampleNormal)
{
  return ((mrgiSpecularMasks[j >> 7][(j >> 5) & 3] >> uint(j & 31)) & 1u) != 0u;
}
#else
uniform mat4 mrgiWCToVC; // world -> eye: the voxels' space
vec3 mrgiSpecularPvc;    // the receiver in eye space (G-buffer position and normal)
vec3 mrgiSpecularNvc;
bool mrgiAreaSpecularSampleVisible(int j, vec3 samplePosition, vec3 sampleNormal)
{
  vec3 L = (mrgiWCToVC * vec4(samplePosition, 1.0)).xyz;
  vec3 NL = mat3(mrgiWCToVC) * sampleNormal;
  // A two-sided light emits from the side facing the receiver.
  if (mrgiAreaTwoSided != 0 && mrgiVoxelDot(NL, mrgiSpecularPvc - L) < 0.0) { NL = -NL; }
  return mrgiVoxelVisible(mrgiSpecularPvc, mrgiSpecularNvc, L, NL);
}
#endif
float mrgiAreaSpecularQueryVisibility(int query)
{
  return mrgiSpecularQueries[query];
}
#endif
//VTK::Output::Dec
void main()
{
  ivec2 pixel = ivec2(gl_FragCoord.xy);
#ifdef MRGI_AREA_SPECULAR_MULTIRES
  vec4 positionVC = texelFetch(mrgiPosition, pixel + mrgiReceiverOffset, 0);
  vec3 normalVC = texelFetch(mrgiNormal, pixel + mrgiReceiverOffset, 0).xyz;
  vec4 material = texelFetch(mrgiMaterial, pixel - mrgiLevelOrigin, 0);
  vec3 ks = vec3(material.x);
#else
  vec4 positionVC = texelFetch(mrgiPosition, pixel, 0);
  vec3 normalVC = texelFetch(mrgiNormal, pixel, 0).xyz;
  vec3 ks = texelFetch(mrgiSpecular, pixel, 0).rgb;
#endif
  vec3 P;
  vec3 N;
  if (max(ks.r, max(ks.g, ks.b)) <= 0.0 ||
    mrgiClassifyReceiver(positionVC, normalVC, mrgiVCToWC, P, N) != 2)
  {
    gl_FragData[0] = vec4(0.0);
    return;
  }
  vec3 viewVC = mrgiParallel != 0 ? vec3(0.0, 0.0, 1.0) : -positionVC.xyz;
  vec3 V = mat3(mrgiVCToWC) * viewVC;
#ifdef MRGI_AREA_SPECULAR_MULTIRES
  float power = material.y;
#else
  float power = texelFetch(mrgiShininess, pixel, 0).r;
#endif
  vec3 n;
  mrgiAreaLightLobe lobe;
  int samplesInLobe;
  int path = mrgiAreaLightSpecularClassify(P, N, V, power, n, lobe, samplesInLobe);
#ifdef MRGI_AREA_SPECULAR_VISIBILITY
  ivec2 local = pixel - mrgiViewportOrigin;
#ifdef MRGI_AREA_SPECULAR_BATCHES
  if (mrgiSpecularBatchFirst > 0 && path != MRGI_AREA_LIGHT_SPECULAR_SAMPLES)
  {
    gl_FragData[0] = vec4(0.0); // drawn by the first batch
    return;
  }
#endif
  if (path == MRGI_AREA_LIGHT_SPECULAR_SAMPLES)
  {
#ifdef MRGI_AREA_SPECULAR_MASKS
    mrgiSpecularMasks[0] = texelFetch(mrgiVisibilityMask0, local, 0);
    mrgiSpecularMasks[1] = texelFetch(mrgiVisibilityMask1, local, 0);
    mrgiSpecularMasks[2] = texelFetch(mrgiVisibilityMask2, local, 0);
    mrgiSpecularMasks[3] = texelFetch(mrgiVisibilityMask3, local, 0);
#else
    mrgiSpecularPvc = positionVC.xyz;
    mrgiSpecularNvc = normalVC;
#endif
  }
  else if (path == MRGI_AREA_LIGHT_SPECULAR_LOBE_GRID)
  {
#ifdef MRGI_AREA_SPECULAR_MULTIRES
    mrgiVsmResolve(min(local * mrgiLevelScale + mrgiLevelScale / 2, mrgiViewportSize - 1),
      mrgiSpecularQueries);
#else
    mrgiVsmResolve(local, mrgiSpecularQueries);
#endif
  }
#endif
  int gridCells;
  vec3 S = mrgiAreaLightSpecularSum(P, n, lobe, power, path, gridCells);
#ifdef MRGI_AREA_SPECULAR_MULTIRES
  gl_FragData[0] = vec4(S, 1.0);
#else
  gl_FragData[0] = vec4(ks * S, 0.0);
#endif
}
