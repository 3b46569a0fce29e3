// MRGI "shadows.apply": VTK's direct light with each captured light term
// scaled by its shadow factor (C twin and the laws: mrgi_shadow_composite.h).
// Window-sized textures: gl_FragCoord addresses them directly.
in vec2 texCoord;
uniform sampler2D mrgiInput0; // VTK's colour
uniform sampler2D mrgiInput1; // shadow factors: channel s = slot s
uniform sampler2D mrgiInput2; // light term of slot 0
uniform sampler2D mrgiInput3; // light term of slot 1
//VTK::Output::Dec
#if MRGI_SHADOW_SLOTS != 2
#error "vtkMRGIShadowCompositeFS binds one sampler per slot: update it with MRGI_SHADOW_SLOTS"
#endif

float mrgiCleanFactor(float f)
{
  // A broken factor never darkens.
  return (isnan(f) || isinf(f) || f < 0.0 || f > 1.0) ? 1.0 : f;
}

vec3 mrgiCleanTerm(vec3 t)
{
  return vec3(isnan(t.r) || isinf(t.r) ? 0.0 : t.r, isnan(t.g) || isinf(t.g) ? 0.0 : t.g,
    isnan(t.b) || isinf(t.b) ? 0.0 : t.b);
}

void main()
{
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec4 colour = texelFetch(mrgiInput0, p, 0);
  vec4 factors = texelFetch(mrgiInput1, p, 0);
  vec3 terms[MRGI_SHADOW_SLOTS];
  terms[0] = mrgiCleanTerm(texelFetch(mrgiInput2, p, 0).rgb);
  terms[1] = mrgiCleanTerm(texelFetch(mrgiInput3, p, 0).rgb);
  vec3 removed = vec3(0.0);
  bool shadowed = false;
  bool gamma = false;
  for (int s = 0; s < MRGI_SHADOW_SLOTS; ++s)
  {
    float occluded = 1.0 - mrgiCleanFactor(factors[s]);
    gamma = gamma || any(lessThan(terms[s], vec3(0.0)));
    if (occluded > 0.0)
    {
      removed += occluded * abs(terms[s]);
      shadowed = true;
    }
  }
  vec3 result = colour.rgb;
  if (shadowed)
  {
    for (int c = 0; c < 3; ++c)
    {
      float v = colour[c];
      if (isnan(v) || isinf(v))
      {
        continue;
      }
      if (gamma)
      {
        float linear = pow(max(v, 0.0), MRGI_SHADOW_PBR_GAMMA);
        result[c] = pow(max(linear - removed[c], 0.0), 1.0 / MRGI_SHADOW_PBR_GAMMA);
      }
      else
      {
        result[c] = max(v - removed[c], 0.0);
      }
    }
  }
  gl_FragData[0] = vec4(result, colour.a);
}
