// MRGI reflective shadow map uniforms (see vtkMRGIRSMCapture.glsl).
uniform mat4 mrgiLightVCToWC;      // light view eye coordinates -> world
uniform int mrgiPerspective;       // 1: perspective view, 0: orthographic
uniform float mrgiTexelSize;       // perspective: 2 tan(fov/2) / S; orthographic: view width / S
uniform vec3 mrgiLightColor;       // intensity * diffuse colour of the light
uniform vec3 mrgiAttenuationValues;
uniform vec3 mrgiSpotAxisVC;       // spot axis in this view's eye coordinates
uniform float mrgiSpotCosCutoff;   // cos(cone half angle); < -1.5 for no cone
uniform float mrgiSpotExponent;
