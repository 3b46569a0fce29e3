// MRGI full-resolution gather (nichols-shopf-wyman-2009 section 3.2.2,
// equations 1 and 5, no visibility): every pixel sums every VPL. C twin:
// mrgi_gather_full() (mrgi_gather.h). The per-VPL term and the receiver test
// are vtkMRGIVPLIrradiance.glsl, prepended by the C++ side. With
// MRGI_GATHER_AREA_LIGHT defined (and vtkMRGIAreaLightDiffuse.glsl prepended) the
// same pass gathers an area light's samples instead of the VPLs
// (nichols-penmatsa-wyman-2010 3.2): same receivers, same selection. With
// MRGI_GATHER_TREE defined (and vtkMRGIVPLTree.glsl prepended) the light
// term is one batch of the VPL tree's roots (nichols-shopf-wyman-2009 3.5,
// C twin mrgi_vpl_tree_gather()); with MRGI_GATHER_COUNT_TARGET also
// defined, that output gets (nodes used as VPLs, 0, 0, 1) at gathered
// receivers (the VPLs-per-pixel statistic), batches summed by blending.
// MRGI's buffers are as large as the window: gl_FragCoord addresses them
// directly; the multiresolution gather, drawn level by level into the
// flattened layout, reads each level's receivers at gl_FragCoord + mrgiReceiverOffset.
in vec2 texCoord; // bound by vtkOpenGLQuadHelper; these passes address texels by gl_FragCoord
uniform sampler2D mrgiPosition;  // G-buffer, eye space
uniform sampler2D mrgiNormal;
uniform sampler2D mrgiAlbedo;
uniform sampler2D mrgiVPLs;      // MRGI_VPL_TEXELS x count
uniform int mrgiVPLFirst;        // this draw's VPLs: first .. first + count - 1 (batches)
uniform int mrgiVPLCount;
uniform mat4 mrgiVCToWC;         // eye -> world (rigid)
uniform float mrgiStrength;      // IndirectStrength
uniform ivec2 mrgiReceiverOffset; // receiver texel of fragment (0, 0); 0 for the full gather
//VTK::Output::Dec
// The count target's write (VTK renames gl_FragData[i] by its literal index).
#if defined(MRGI_GATHER_COUNT_TARGET) && MRGI_GATHER_COUNT_TARGET == 1
#define mrgiWriteCount(value) gl_FragData[1] = (value)
#elif defined(MRGI_GATHER_COUNT_TARGET)
#define mrgiWriteCount(value) gl_FragData[2] = (value)
#else
#define mrgiWriteCount(value)
#endif
void main()
{
  ivec2 pixel = ivec2(gl_FragCoord.xy) + mrgiReceiverOffset;
  vec4 positionVC = texelFetch(mrgiPosition, pixel, 0);
  if (positionVC.w <= MRGI_VALID_THRESHOLD)
  {
    gl_FragData[0] = vec4(0.0);
#ifndef MRGI_GATHER_IRRADIANCE_ONLY
    gl_FragData[1] = vec4(0.0);
#endif
    mrgiWriteCount(vec4(0.0));
    return;
  }
  vec3 P;
  vec3 N;
  vec3 normalVC = texelFetch(mrgiNormal, pixel, 0).xyz;
  if (mrgiClassifyReceiver(positionVC, normalVC, mrgiVCToWC, P, N) == 1)
  {
    gl_FragData[0] = vec4(0.0, 0.0, 0.0, 1.0);
#ifndef MRGI_GATHER_IRRADIANCE_ONLY
    gl_FragData[1] = vec4(0.0, 0.0, 0.0, 1.0);
#endif
    mrgiWriteCount(vec4(0.0)); // malformed: not a gathered receiver
    return;
  }
#ifdef MRGI_INDIRECT_VOXELS
  mrgiReceiverVC = positionVC.xyz; // the march's receiver: eye space, as stored
  mrgiReceiverNormalVC = normalVC;
#endif
#ifdef MRGI_GATHER_AREA_LIGHT
  // Direct light of one area light (vtkMRGIAreaLightDiffuse.glsl, prepended).
  vec3 E = mrgiAreaLightDiffuse(P, N, positionVC.xyz, normalVC);
#elif defined(MRGI_GATHER_TREE)
  // One batch of roots of the VPL tree (vtkMRGIVPLTree.glsl, prepended).
  int used;
  vec3 E = mrgiVPLTreeIrradiance(P, N, used);
  mrgiWriteCount(vec4(float(used), 0.0, 0.0, 1.0));
#else
  vec3 E = vec3(0.0);
  for (int j = mrgiVPLFirst; j < mrgiVPLFirst + mrgiVPLCount; ++j)
  {
    E += mrgiVPLIrradiance(mrgiVPLs, j, P, N);
  }
#endif
  gl_FragData[0] = vec4(E, 1.0);           // E_i, compared with the C twin
#ifndef MRGI_GATHER_IRRADIANCE_ONLY
  vec3 albedo = texelFetch(mrgiAlbedo, pixel, 0).rgb;
  gl_FragData[1] = vec4(mrgiStrength * albedo * E, 1.0);  // indirect radiance added to the direct light
#endif
}
