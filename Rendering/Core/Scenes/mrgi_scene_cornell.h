/**
 * @file mrgi_scene_cornell.h
 * @brief The Cornell box, built from the published measurements.
 *
 * Geometry: Cornell University Program of Computer Graphics, "Cornell Box
 * Data" (https://www.graphics.cornell.edu/online/box/data.html), encoded in
 * mrgi_scene_cornell.c. Units are MILLIMETRES; y is up; the open side faces
 * -z, where the camera stands. The box spans x 0..556, y 0..548.8,
 * z 0..559.2 (the published walls are slightly skewed, not a perfect cube).
 *
 * Meshes, in this order, each its own ::mrgi_mesh named as quoted:
 * "floor", "ceiling", "back_wall" (white), "left_wall" (red, x ~ 552..556,
 * on the left of the image), "right_wall" (green, x = 0), "short_block",
 * "tall_block" (white; top and four sides, no bottom), and for
 * ::MRGI_CORNELL_AREA also "light" (the emitter quad). Albedos are the RGB
 * values in wide use by physically based renderers: white (0.725, 0.71,
 * 0.68), red (0.63, 0.065, 0.05), green (0.14, 0.45, 0.091).
 *
 * Every published quad becomes 4 vertices and 2 triangles (0,1,2), (0,2,3)
 * in the published order, which is counter-clockwise seen from inside the
 * box: wall normals point into the box, block normals out of the blocks,
 * the emitter's down. Vertex normals are the quad's flat (Newell) normal.
 *
 * Camera (all variants): at (278, 273, -800) looking along +z at
 * (278, 273, 0), up +y, vertical view angle 2 atan(12.5 / 35) = 39.3077
 * degrees (35 mm lens on 25 mm film).
 */
#ifndef MRGI_SCENE_CORNELL_H
#define MRGI_SCENE_CORNELL_H

#include "mrgi_error.h"
#include "mrgi_scene.h"

#ifdef __cplusplus
extern "C" {
#endif

/**
 * How far (mm) the emitter quad and the area light sit below the published
 * height 548.8, which is also the ceiling's: coplanar surfaces would make
 * the depth test and a ray tracer's nearest hit pick between them at random.
 * 0.5 mm is far above float and 24-bit depth resolution at this scale and
 * under 0.1 % of the box height.
 */
#define MRGI_CORNELL_EMITTER_DROP_MM 0.5

/**
 * Half-angle (degrees) of the "cornell-spot" cone. Wide enough to light the
 * whole floor (its corners are 35.74 deg off the axis) and the side walls
 * directly from the floor up to y = 548 - 278 / tan(65 deg) = 418 mm (three
 * quarters of their height); narrow enough that the light's perspective
 * frustum (130 deg field of view) still makes a usable reflective shadow map.
 */
#define MRGI_CORNELL_SPOT_CONE_DEG 65.0

/** Which light the box is lit by. */
typedef enum mrgi_cornell_variant
{
  /**
   * "cornell": one ::MRGI_LIGHT_POSITIONAL (omnidirectional, cone 90) at
   * (278, 548, 279.5), just under the emitter's centre, white, intensity 1,
   * focal point straight below. The default scene for direct light.
   */
  MRGI_CORNELL_POINT = 0,
  /**
   * "cornell-spot": one ::MRGI_LIGHT_SPOT at (278, 548, 279.5) aimed straight
   * down, white, intensity 1, exponent 1 (VTK's falloff pow(cos, 1) is the
   * cos law of the Lambertian emitter it stands in for). Cone half-angle
   * MRGI_CORNELL_SPOT_CONE_DEG: the floor and most of the walls are lit
   * directly, all inside the light's frustum (as a reflective shadow map needs).
   */
  MRGI_CORNELL_SPOT,
  /**
   * "cornell-area": no point-like light; one one-sided ::mrgi_area_light over
   * the published 130 x 105 mm emitter (centre (278, 548.8 - drop, 279.5),
   * facing down, radiance (17, 12, 4)), and the emitter quad as the mesh
   * "light" with albedo 0 and emission (17, 12, 4).
   */
  MRGI_CORNELL_AREA
} mrgi_cornell_variant;

/** @brief "cornell", "cornell-spot" or "cornell-area"; NULL for a value outside the enum. */
const char* mrgi_cornell_variant_name(mrgi_cornell_variant variant);

/**
 * @brief Parse a variant name as mrgi_cornell_variant_name() spells it.
 * @return ::MRGI_ERR_INVALID_ARGUMENT for NULL or an unknown name (the message lists the known ones).
 */
mrgi_status mrgi_cornell_variant_parse(const char* name, mrgi_cornell_variant* out,
                                       mrgi_error* err);

/**
 * @brief Build the Cornell box lit as `variant` says (see the file comment).
 * @param out Receives the scene; zeroed on failure. Release with mrgi_scene_destroy().
 * @return ::MRGI_ERR_INVALID_ARGUMENT for NULL `out` or an unknown variant;
 *         ::MRGI_ERR_OUT_OF_MEMORY.
 */
mrgi_status mrgi_scene_cornell_box(mrgi_cornell_variant variant, mrgi_scene* out,
                                   mrgi_error* err);

#ifdef __cplusplus
}
#endif

#endif
