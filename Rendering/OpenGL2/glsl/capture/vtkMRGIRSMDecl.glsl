// MRGI reflective shadow map uniforms (see vtkMRGIRSMCapture.glsl).
uniform mat4 mrgiLightVCToWC;      // light view eye coordinates -> world
uniform int mrgiPerspective;       // 1: perspective view, 0: orthographic
uniform float mrgiTexelSize;       // perspective: 2 tan(fov/2) / S; orthographic: view width / S
uniform vec3 mrgiLightColor;       // intensity * diffuse colour of the light
uniform vec3 mrgiAttenuationValues;
uniform vec3 mrgiSpotAxisVC;       // spot axis in this view's eye coordinates
uniform float mrgiSpotCosCutoff;   // cos(cone half angle); < -1.5 for no cone
uniform float mrgiSpotExponent;
// Area-light views (mrgi_area_light_rsm.h): > 0 samples replace the VTK
// light's X by the emitter's, in world coordinates. Sample j is texels
// 3j (position xyz, area), 3j + 1 (light normal xyz) and 3j + 2 (radiance
// rgb), the record of mrgi_area_light_sample.
uniform int mrgiAreaSampleCount;
uniform int mrgiAreaTwoSided;
uniform vec4 mrgiAreaSamples[3 * MRGI_AREA_LIGHT_RSM_SAMPLES];
