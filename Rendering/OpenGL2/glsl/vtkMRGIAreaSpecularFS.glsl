// MRGI: the Phong highlight of one area light (nichols-penmatsa-wyman-2010
// 3.2.1: "diffuse and specular are gathered in separate passes"), at every
// pixel whose G-buffer holds a specular material: k_s c_s S, S from
// mrgiAreaLightSpecular() (vtkMRGIAreaLightSpecular.glsl, C twin
// mrgi_area_light_specular()), which the C++ side prepends with the
// receiver test (vtkMRGIVPLIrradiance.glsl). Full resolution: sharp lobes
// change from pixel to pixel, and the lobe grid keeps their cost at 25
// lookups. No visibility (the voxel masks are the diffuse gather's).
in vec2 texCoord; // bound by vtkOpenGLQuadHelper; texels are addressed by gl_FragCoord
uniform sampler2D mrgiPosition;  // G-buffer, eye space
uniform sampler2D mrgiNormal;
uniform sampler2D mrgiSpecular;  // k_s c_s
uniform sampler2D mrgiShininess; // r: Phong exponent
uniform mat4 mrgiVCToWC;         // eye -> world (rigid)
uniform int mrgiParallel;        // 1: parallel projection (view direction +z in eye space)
//VTK::Output::Dec
void main()
{
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  vec4 positionVC = texelFetch(mrgiPosition, pixel, 0);
  vec3 ks = texelFetch(mrgiSpecular, pixel, 0).rgb;
  vec3 P;
  vec3 N;
  if (max(ks.r, max(ks.g, ks.b)) <= 0.0 ||
    mrgiClassifyReceiver(positionVC, texelFetch(mrgiNormal, pixel, 0).xyz, mrgiVCToWC, P, N) != 2)
  {
    gl_FragData[0] = vec4(0.0);
    return;
  }
  vec3 viewVC = mrgiParallel != 0 ? vec3(0.0, 0.0, 1.0) : -positionVC.xyz;
  vec3 V = mat3(mrgiVCToWC) * viewVC;
  int path;
  vec3 S = mrgiAreaLightSpecular(P, N, V, texelFetch(mrgiShininess, pixel, 0).r, path);
  gl_FragData[0] = vec4(ks * S, 0.0);
}
