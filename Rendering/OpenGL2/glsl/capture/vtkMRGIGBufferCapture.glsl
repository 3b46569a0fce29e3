// MRGI G-buffer capture: inserted at the end of VTK's polygonal fragment
// shader for opaque props while the eye view is rendered (see vtkMRGIPass).
// gl_FragData[0] keeps VTK's own direct lighting; the G-buffer gets the
// eye-space position, the (two-sided, viewer-facing) normal and the albedo.
  {
    vec3 mrgiNormalVC = normalize(normalVCVSOutput);
    // NaN/Inf in the input data (or a zero normal): the pixel gathers nothing
    // (invalid), so no non-finite value reaches the gather.
    if (any(isnan(vertexVC.xyz)) || any(isinf(vertexVC.xyz)) || any(isnan(mrgiNormalVC)) ||
      any(isinf(mrgiNormalVC)))
    {
      gl_FragData[MRGI_GBUFFER_POSITION] = vec4(0.0);
      gl_FragData[MRGI_GBUFFER_NORMAL] = vec4(0.0);
      gl_FragData[MRGI_GBUFFER_ALBEDO] = vec4(0.0);
      gl_FragData[MRGI_GBUFFER_SPECULAR] = vec4(0.0);
      gl_FragData[MRGI_GBUFFER_SHININESS] = vec4(0.0);
    }
    else
    {
      gl_FragData[MRGI_GBUFFER_POSITION] = vec4(vertexVC.xyz, MRGI_GBUFFER_VALID);
      gl_FragData[MRGI_GBUFFER_NORMAL] = vec4(mrgiNormalVC, MRGI_GBUFFER_VALID);
      gl_FragData[MRGI_GBUFFER_ALBEDO] = vec4(diffuseColor * mrgiTextureFactor, MRGI_GBUFFER_VALID);
      // Phong material for the area lights' specular gather (written only
      // where the pass attached these targets).
#ifdef MRGI_SPECULAR_MATERIAL
      gl_FragData[MRGI_GBUFFER_SPECULAR] = vec4(specularColor, MRGI_GBUFFER_VALID);
      gl_FragData[MRGI_GBUFFER_SHININESS] = vec4(specularPower, 0.0, 0.0, MRGI_GBUFFER_VALID);
#else
      gl_FragData[MRGI_GBUFFER_SPECULAR] = vec4(0.0, 0.0, 0.0, MRGI_GBUFFER_VALID);
      gl_FragData[MRGI_GBUFFER_SHININESS] = vec4(0.0, 0.0, 0.0, MRGI_GBUFFER_VALID);
#endif
    }
  }
