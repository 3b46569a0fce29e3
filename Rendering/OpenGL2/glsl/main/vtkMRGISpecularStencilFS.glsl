// MRGI specular stencil (nichols-penmatsa-wyman-2010 3.2.1: "image-space
// sample spacing must be denser than the lobe width, which we add as a
// Phong-specific refinement metric"; 3.4: the stencil from depth, normal and
// BRDF frequency metrics). GPU side of mrgi_specular_material_build() and
// mrgi_specular_stencil_build() (Rendering/Core/Twins/mrgi_specular_stencil.h,
// whose file comment is the contract). MRGI_SPEC_STAGE
// 0: material pyramid, level 0 from the G-buffer (viewport at mrgiOffset);
// 1: material pyramid, level i from level i-1 (2x2, clamped);
// 2: the refinement bits Q of level i into its rectangle of the flattened
//    layout (vtkMRGIAreaLightSpecular.glsl prepended for the lobe);
// 3: the selection of level i (writes 1 and the stencil; discards the rest),
//    walking the ancestors' bits in the flattened layout.
// Each stage defines mrgiSpecularStage(), called by the one main() at the end.
in vec2 texCoord; // bound by vtkOpenGLQuadHelper; texels are addressed by gl_FragCoord
//VTK::Output::Dec
#if MRGI_SPEC_STAGE == 0
uniform sampler2D mrgiInput0; // G-buffer position (w = validity)
uniform sampler2D mrgiInput1; // k_s c_s
uniform sampler2D mrgiInput2; // r: Phong exponent
uniform ivec2 mrgiOffset;
void mrgiSpecularStage()
{
  ivec2 p = ivec2(gl_FragCoord.xy) + mrgiOffset;
  vec3 ks = texelFetch(mrgiInput1, p, 0).rgb;
  float k = max(ks.r, max(ks.g, ks.b));
  bool spec = texelFetch(mrgiInput0, p, 0).w > MRGI_GBUFFER_VALID_THRESHOLD && k > 0.0;
  float n = texelFetch(mrgiInput2, p, 0).r;
  gl_FragData[0] = spec ? vec4(k, n, n, 0.0) : vec4(0.0, 0.0, MRGI_MULTIRES_FLT_MAX, 0.0);
}
#elif MRGI_SPEC_STAGE == 1
uniform sampler2D mrgiInput0; // level i-1 material
uniform ivec2 mrgiSize;       // size of level i-1
void mrgiSpecularStage()
{
  ivec2 t = ivec2(gl_FragCoord.xy);
  vec3 r = vec3(0.0, 0.0, MRGI_MULTIRES_FLT_MAX);
  for (int k = 0; k < 4; ++k)
  {
    ivec2 c = min(2 * t + ivec2(k & 1, k >> 1), mrgiSize - 1);
    vec3 m = texelFetch(mrgiInput0, c, 0).xyz;
    r = vec3(max(r.x, m.x), max(r.y, m.y), min(r.z, m.z));
  }
  gl_FragData[0] = vec4(r, 0.0);
}
#elif MRGI_SPEC_STAGE == 2
uniform sampler2D mrgiFlags;    // level i flags (red, level-local)
uniform sampler2D mrgiMaterial; // level i material (level-local)
uniform sampler2D mrgiPosition; // level i receivers (BindReceivers: flattened texel + offset)
uniform sampler2D mrgiNormal;
uniform ivec2 mrgiReceiverOffset;
uniform int mrgiLevelOffset;
uniform int mrgiLevel;
uniform int mrgiFinest;      // 1 when level i is the finest gathering level
uniform int mrgiLobe;        // 1: the lobe metric is on
uniform float mrgiLobeThreshold; // refine where m > this (mrgi_specular_stencil_view.lobe_threshold)
uniform int mrgiParallel;
uniform vec2 mrgiPixelSize;  // (a, b)
uniform mat4 mrgiVCToWC;
// mrgi_specular_stencil_metric().
float mrgiSpecularStencilMetric(ivec2 f, float power)
{
  vec4 p = texelFetch(mrgiPosition, f + mrgiReceiverOffset, 0);
  vec3 n = texelFetch(mrgiNormal, f + mrgiReceiverOffset, 0).xyz;
  if (!(p.w > MRGI_GBUFFER_VALID_THRESHOLD) || any(isnan(p.xyz)) || any(isinf(p.xyz)) ||
    any(isnan(n)) || any(isinf(n)) || dot(n, n) == 0.0)
  {
    return 0.0;
  }
  vec3 P = (mrgiVCToWC * vec4(p.xyz, 1.0)).xyz;
  vec3 N = (mrgiVCToWC * vec4(n, 0.0)).xyz;
  vec3 toward = mrgiParallel != 0 ? vec3(0.0, 0.0, 1.0) : -p.xyz;
  vec3 V = (mrgiVCToWC * vec4(toward, 0.0)).xyz;
  mrgiAreaLightLobe lobe = mrgiAreaLightPhongLobe(P, N, V, power);
  float e = mrgiParallel != 0 ? MRGI_MULTIRES_FLT_MAX : length(p.xyz);
  float s = float(1 << mrgiLevel) *
    max(mrgiPixelSize.x * abs(p.z) + mrgiPixelSize.y, MRGI_MULTIRES_MIN_PIXEL_SIZE);
  return mrgiAreaLightPhongRefinement(lobe, e, s);
}
void mrgiSpecularStage()
{
  ivec2 f = ivec2(gl_FragCoord.xy);
  ivec2 t = ivec2(f.x - mrgiLevelOffset, f.y);
  int flags = int(texelFetch(mrgiFlags, t, 0).r);
  vec4 m = texelFetch(mrgiMaterial, t, 0);
  bool k = m.x > 0.0;
  int bits = 0;
  if ((flags & MRGI_MULTIRES_FLAG_NONEMPTY) != 0)
  {
    bits = k ? MRGI_SPECULAR_STENCIL_SPECULAR : 0;
    if (mrgiFinest == 0)
    {
      bool q = (flags & MRGI_MULTIRES_FLAG_REFINE) != 0;
      if (k)
      {
        q = q || m.z < m.y;
        if (mrgiLobe != 0 && mrgiSpecularStencilMetric(f, m.y) > mrgiLobeThreshold)
        {
          bits |= MRGI_SPECULAR_STENCIL_LOBE;
          q = true;
        }
      }
      bits |= q ? MRGI_SPECULAR_STENCIL_REFINE : 0;
    }
  }
  gl_FragData[0] = vec4(float(bits), 0.0, 0.0, 1.0);
}
#else
uniform sampler2D mrgiRefine; // the bits of stage 2, flattened
uniform int mrgiLevel;
uniform int mrgiCoarsestLevel;
uniform int mrgiOffsets[MRGI_MULTIRES_MAX_LEVELS];
void mrgiSpecularStage()
{
  ivec2 f = ivec2(gl_FragCoord.xy);
  ivec2 t = ivec2(f.x - mrgiOffsets[mrgiLevel], f.y);
  int bits = int(texelFetch(mrgiRefine, f, 0).r);
  bool selected = (bits & MRGI_SPECULAR_STENCIL_SPECULAR) != 0 &&
    (bits & MRGI_SPECULAR_STENCIL_REFINE) == 0;
  for (int j = mrgiLevel + 1; j <= mrgiCoarsestLevel; ++j)
  {
    int d = j - mrgiLevel;
    ivec2 a = ivec2(mrgiOffsets[j] + (t.x >> d), t.y >> d);
    selected = selected && (int(texelFetch(mrgiRefine, a, 0).r) & MRGI_SPECULAR_STENCIL_REFINE) != 0;
  }
  if (!selected)
  {
    discard;
  }
  gl_FragData[0] = vec4(1.0);
}
#endif
// One main() for every stage (vtkMRGIShaderUtilities::FullScreenShader() edits it).
void main()
{
  mrgiSpecularStage();
}
