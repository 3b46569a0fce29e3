// MRGI multiresolution splatting (nichols-wyman-2009 section 3.4): every VPL
// is splatted onto the flattened multiresolution buffer as a list of
// subsplats, one point per selected texel, and additive blending sums the
// VPLs' contributions. One vertex = one subsplat of one VPL: the vertex
// attribute is the selected texel, gl_InstanceID the VPL (instances are
// drawn in order, so every texel sums VPL 0, 1, ... in the order the
// stenciled gather's loop does). The contribution is computed here, once
// per point, with vtkMRGIVPLIrradiance.glsl (prepended): the same numbers as
// the gather, which is what the comparison of the two methods needs.
in ivec2 mrgiTexel;                // selected texel, flattened layout
uniform sampler2D mrgiPosition;    // this level's receivers (level 0: the G-buffer)
uniform sampler2D mrgiNormal;
uniform sampler2D mrgiVPLs;        // MRGI_VPL_TEXELS x count
uniform mat4 mrgiVCToWC;           // eye -> world (rigid)
uniform ivec2 mrgiReceiverOffset;  // receiver texel = flattened texel + this, as in the gather
uniform vec2 mrgiTargetSize;       // flattened layout size
flat out vec4 mrgiSubsplat;
void main()
{
  ivec2 pixel = mrgiTexel + mrgiReceiverOffset;
  vec3 P;
  vec3 N;
  int kind = mrgiClassifyReceiver(texelFetch(mrgiPosition, pixel, 0),
    texelFetch(mrgiNormal, pixel, 0).xyz, mrgiVCToWC, P, N);
  vec3 E = kind == 2 ? mrgiVPLIrradiance(mrgiVPLs, gl_InstanceID, P, N) : vec3(0.0);
  mrgiSubsplat = vec4(E, 1.0);
  // Background texels get no point (clipped away), as the gather leaves
  // them at alpha 0; malformed receivers get E = 0 with alpha 1.
  vec2 ndc = (vec2(mrgiTexel) + 0.5) / mrgiTargetSize * 2.0 - 1.0;
  gl_Position = kind == 0 ? vec4(2.0, 2.0, 2.0, 1.0) : vec4(ndc, 0.0, 1.0);
}
