// MRGI reflective shadow map capture: inserted at the end of VTK's polygonal
// fragment shader while a light's view is rendered (see
// vtkMRGIReflectiveShadowMapPass). vertexVC / normalVCVSOutput are in the
// light view's eye coordinates: the light sits at the origin looking down -z.
// Definitions: mrgi_vpl.h and Documentation/IndirectLight.md.
  {
    vec3 mrgiP = vertexVC.xyz;
    vec3 mrgiN = normalize(normalVCVSOutput);
    float mrgiR = length(mrgiP);
    // Direction to the light, and the solid angle / cross-section of a texel.
    vec3 mrgiL;
    float mrgiTexelFootprint; // area of the texel across the light direction at this point
    float mrgiAttenuation = 1.0;
    if (mrgiPerspective != 0)
    {
      mrgiL = -mrgiP / max(mrgiR, 1e-30);
      // Solid angle of a texel of a square frustum: (2 tan(fov/2) / S)^2 cos^3(alpha).
      float mrgiCosAlpha = clamp(-mrgiP.z / max(mrgiR, 1e-30), 0.0, 1.0);
      mrgiTexelFootprint = mrgiTexelSize * mrgiTexelSize * mrgiCosAlpha * mrgiCosAlpha * mrgiCosAlpha * mrgiR * mrgiR;
      // VTK's positional attenuation 1 / (a0 + a1 d + a2 d^2) and spot cone.
      mrgiAttenuation = 1.0 / max(mrgiAttenuationValues.x + mrgiAttenuationValues.y * mrgiR
        + mrgiAttenuationValues.z * mrgiR * mrgiR, 1e-30);
      float mrgiConeDot = dot(-mrgiL, mrgiSpotAxisVC);
      if (mrgiSpotCosCutoff > -1.5)
      {
        mrgiAttenuation *= (mrgiConeDot >= mrgiSpotCosCutoff) ? pow(max(mrgiConeDot, 0.0), mrgiSpotExponent) : 0.0;
      }
    }
    else
    {
      mrgiL = vec3(0.0, 0.0, 1.0);
      mrgiTexelFootprint = mrgiTexelSize * mrgiTexelSize;
    }
    // Face the light (two-sided surfaces reflect on the side the light sees).
    if (dot(mrgiN, mrgiL) < 0.0) { mrgiN = -mrgiN; }
    float mrgiCosTheta = max(dot(mrgiN, mrgiL), 0.0);
    float mrgiArea = mrgiTexelFootprint / max(mrgiCosTheta, MRGI_RSM_MIN_COS);
    vec3 mrgiAlbedo = diffuseColor * mrgiTextureFactor;
    vec3 mrgiX = mrgiLightColor * (mrgiCosTheta * mrgiAttenuation);
    vec3 mrgiPositionWC = (mrgiLightVCToWC * vec4(mrgiP, 1.0)).xyz;
    vec3 mrgiNormalWC = normalize(mat3(mrgiLightVCToWC) * mrgiN);
    if (mrgiAreaSampleCount > 0)
    {
      // An area light's view from its centre: X = the emitter's VTK
      // irradiance without visibility over its samples, [NSW09] eq. 1 per
      // sample (twin: mrgi_area_light_rsm_texel(), mrgi_area_light_diffuse()).
      mrgiX = vec3(0.0);
      for (int j = 0; j < MRGI_AREA_LIGHT_RSM_SAMPLES; ++j)
      {
        if (j >= mrgiAreaSampleCount) { break; }
        vec4 mrgiSP = mrgiAreaSamples[3 * j];
        vec3 mrgiSN = mrgiAreaSamples[3 * j + 1].xyz;
        vec3 mrgiD = mrgiSP.xyz - mrgiPositionWC;
        float mrgiR2 = dot(mrgiD, mrgiD);
        float mrgiCosI = dot(mrgiNormalWC, mrgiD);
        float mrgiCosJ = -dot(mrgiSN, mrgiD);
        if (mrgiAreaTwoSided != 0) { mrgiCosJ = abs(mrgiCosJ); }
        if (mrgiR2 > 0.0 && mrgiCosI > 0.0 && mrgiCosJ > 0.0)
        {
          mrgiX += mrgiAreaSamples[3 * j + 2].rgb *
            (mrgiSP.w * (mrgiCosI * mrgiCosJ / mrgiR2) / (float(MRGI_PI) * mrgiR2 + mrgiSP.w));
        }
      }
    }
    vec4 mrgiFlux = vec4(mrgiAlbedo * mrgiX * mrgiArea, mrgiArea);
    // NaN/Inf coordinates or zero/NaN normals in the input data: the texel
    // reflects nothing (invalid), so no VPL inherits a non-finite value.
    if (any(isnan(mrgiPositionWC)) || any(isinf(mrgiPositionWC)) || any(isnan(mrgiNormalWC)) ||
      any(isinf(mrgiNormalWC)) || any(isnan(mrgiFlux)) || any(isinf(mrgiFlux)))
    {
      gl_FragData[MRGI_RSM_POSITION] = vec4(0.0);
      gl_FragData[MRGI_RSM_NORMAL] = vec4(0.0);
      gl_FragData[MRGI_RSM_FLUX] = vec4(0.0);
    }
    else
    {
      gl_FragData[MRGI_RSM_POSITION] = vec4(mrgiPositionWC, MRGI_GBUFFER_VALID);
      gl_FragData[MRGI_RSM_NORMAL] = vec4(mrgiNormalWC, 0.0);
      gl_FragData[MRGI_RSM_FLUX] = mrgiFlux;
    }
  }
