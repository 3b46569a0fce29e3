// MRGI: the moments pass of the variance shadow query for sharp Phong lobes
// (nichols-penmatsa-wyman-2010 3.3.3: "we send visibility rays to the 25
// samples chosen in the specular lobe [...] Instead of storing a single bit
// per visibility query, we store the distance (and distance squared) to the
// nearest occluder along the ray [...] sending only 24 visibility queries
// (ignoring one corner on the 5 x 5 grid) [...] Using 2 x 2 interleaving,
// this requires only 12 floats per pixel, which fits in three 4-channel
// render targets"). C twin: mrgi_voxel_vsm_specular_moments()
// (mrgi_variance_shadow.h section 6).
//
// Drawn over the viewport into MRGI_VOXEL_VSM_TARGETS RGBA32F targets of its
// size (gl_FragCoord is viewport-local; the G-buffer is read at
// gl_FragCoord + mrgiViewportOrigin). Per pixel with a specular material
// whose highlight takes the lobe-grid path (mrgiAreaLightSpecularClassify(),
// vtkMRGIAreaLightSpecular.glsl, prepended with the march library and
// vtkMRGIVPLIrradiance.glsl): the 6 queries of its interleaving phase q,
// query j = 4 k + q aiming at lobe-grid cell j's centre (the point the
// specular sum lights from), marched in eye space by
// mrgiVoxelOccluderFraction() (vtkMRGIVoxelMarch.glsl), z = 1 for a cell
// off the light; (z, z^2) of local query k in target k >> 1, channels
// 2 (k & 1) and 2 (k & 1) + 1. Every other pixel writes -1 (computed nothing).
in vec2 texCoord; // bound by vtkOpenGLQuadHelper; texels are addressed by gl_FragCoord
uniform sampler2D mrgiPosition;  // G-buffer, eye space
uniform sampler2D mrgiNormal;
uniform sampler2D mrgiSpecular;  // k_s c_s
uniform sampler2D mrgiShininess; // r: Phong exponent
uniform mat4 mrgiVCToWC;         // eye -> world (rigid)
uniform mat4 mrgiWCToVC;         // world -> eye: the voxels' space
uniform int mrgiParallel;        // 1: parallel projection (view direction +z in eye space)
uniform ivec2 mrgiViewportOrigin; // window pixel of the viewport's lower left corner
//VTK::Output::Dec
void main()
{
  ivec2 local = ivec2(gl_FragCoord.xy);
  ivec2 pixel = local + mrgiViewportOrigin;
  vec4 positionVC = texelFetch(mrgiPosition, pixel, 0);
  vec3 normalVC = texelFetch(mrgiNormal, pixel, 0).xyz;
  vec3 ks = texelFetch(mrgiSpecular, pixel, 0).rgb;
  vec3 P;
  vec3 N;
  int path = MRGI_AREA_LIGHT_SPECULAR_FACING_AWAY;
  vec3 n;
  mrgiAreaLightLobe lobe;
  int samplesInLobe;
  if (max(ks.r, max(ks.g, ks.b)) > 0.0 &&
    mrgiClassifyReceiver(positionVC, normalVC, mrgiVCToWC, P, N) == 2)
  {
    vec3 viewVC = mrgiParallel != 0 ? vec3(0.0, 0.0, 1.0) : -positionVC.xyz;
    vec3 V = mat3(mrgiVCToWC) * viewVC;
    path = mrgiAreaLightSpecularClassify(P, N, V, texelFetch(mrgiShininess, pixel, 0).r, n, lobe,
      samplesInLobe);
  }
  if (path != MRGI_AREA_LIGHT_SPECULAR_LOBE_GRID)
  {
    gl_FragData[0] = vec4(-1.0);
    gl_FragData[1] = vec4(-1.0);
    gl_FragData[2] = vec4(-1.0);
    return;
  }
  float hu;
  float hv;
  mrgiAreaLobeGridSpacing(lobe, hu, hv);
  int q = (local.x & 1) | ((local.y & 1) << 1);
  vec3 Pvc = positionVC.xyz;
  vec3 lightNormal = mat3(mrgiWCToVC) * mrgiAreaNormal;
  float m[2 * MRGI_VOXEL_VSM_QUERIES / MRGI_VOXEL_INTERLEAVE_PHASES];
  for (int k = 0; k < MRGI_VOXEL_VSM_QUERIES / MRGI_VOXEL_INTERLEAVE_PHASES; ++k)
  {
    int j = MRGI_VOXEL_INTERLEAVE_PHASES * k + q;
    // mrgi_voxel_vsm_query_cell(): (j % G - G/2, j / G - G/2).
    int a = j - (j / MRGI_AREA_LIGHT_LOBE_GRID) * MRGI_AREA_LIGHT_LOBE_GRID - MRGI_AREA_LIGHT_LOBE_GRID / 2;
    int b = j / MRGI_AREA_LIGHT_LOBE_GRID - MRGI_AREA_LIGHT_LOBE_GRID / 2;
    vec3 cell;
    float cu;
    float cv;
    float cellArea;
    float z = 1.0; // a cell off the light: no light there to hide
    if (mrgiAreaLobeGridCell(lobe, hu, hv, a, b, cell, cu, cv, cellArea))
    {
      vec3 L = (mrgiWCToVC * vec4(cell, 1.0)).xyz;
      vec3 NL = lightNormal;
      // A two-sided light emits from the side facing the receiver.
      if (mrgiAreaTwoSided != 0 && mrgiVoxelDot(NL, Pvc - L) < 0.0) { NL = -NL; }
      z = mrgiVoxelOccluderFraction(Pvc, normalVC, L, NL);
    }
    m[2 * k] = z;
    m[2 * k + 1] = z * z;
  }
  gl_FragData[0] = vec4(m[0], m[1], m[2], m[3]);
  gl_FragData[1] = vec4(m[4], m[5], m[6], m[7]);
  gl_FragData[2] = vec4(m[8], m[9], m[10], m[11]);
}
