/**
 * @file mrgi_scene_living_room.h
 * @brief A living room lit only by a textured TV screen: the area-light test
 *        scene of Nichols, Penmatsa and Wyman 2010 ([NPW10], figure 1: a living
 *        room with and without its TV as an area light), built procedurally.
 *
 * Units are METRES; y is up. The room is the box x -2.4..2.4 (4.8 m wide),
 * y 0..2.6 (high), z 0..5.2 (deep). The TV hangs on the wall z = 0 and faces
 * +z; the sofa faces it from z 3.0..4.15; the camera stands behind the sofa.
 *
 * Meshes, in this order, each its own ::mrgi_mesh named as quoted, every
 * box face a quad of 2 triangles with flat vertex normals (its own 4
 * vertices, as mrgi_mesh_put_polygon() writes them):
 *
 * | mesh | what | albedo (linear RGB) |
 * |---|---|---|
 * | "floor" | y = 0, faces up | oak (0.42, 0.28, 0.16) |
 * | "ceiling" | y = 2.6, faces down | white (0.80, 0.80, 0.78) |
 * | "tv_wall" | z = 0, behind the TV, faces +z | grey-blue (0.40, 0.46, 0.55) |
 * | "back_wall" | z = 5.2, behind the camera, faces -z | off-white (0.72, 0.68, 0.60) |
 * | "left_wall" | x = -2.4 (left in the image), faces +x | off-white |
 * | "right_wall" | x = +2.4 (right in the image), faces -x | off-white |
 * | "tv_stand" | low cabinet x -1..1, y 0..0.45, z 0.03..0.48 | walnut (0.20, 0.13, 0.08) |
 * | "tv_set" | the TV's dark box x -0.65..0.65, y 0.55..1.35, z 0.08..0.16 (wall-mounted, 10 cm above the cabinet) | (0.03, 0.03, 0.03) |
 * | "screen" | the emitter quad, exactly the area light's rectangle | 0; emission = mean radiance |
 * | "sofa" | seat (y 0..0.42, z 3.0..3.9), backrest (y 0..0.85, z 3.9..4.15), two arms (y 0..0.62, x +-1.1..1.3); x -1.3..1.3 | red fabric (0.55, 0.16, 0.12) |
 * | "table" | coffee table: top x -0.6..0.6, y 0.38..0.43, z 1.75..2.35 on four 5 cm legs | light wood (0.55, 0.42, 0.28) |
 * | "shelf" | open bookshelf against the right wall (4 cm gap): two side panels, plinth and three boards, x 1.98..2.36, y 0..1.9, z 1.3..2.3, no back | white (0.65, 0.62, 0.58) |
 * | "books" | three blocks of books on the shelf | blue (0.18, 0.32, 0.55) |
 *
 * Walls, floor and ceiling face into the room; furniture faces out of its
 * boxes (into the room). Boxes that stand on the floor have no bottom face;
 * every other box is closed. Boxes that touch (sofa parts, legs under the
 * table top, books on the boards) keep their touching faces, which are
 * hidden inside the furniture. Between the TV and the walls stand the
 * sofa, the table and the shelf: they cast shadows on the floor, the back
 * wall and the right wall.
 *
 * ## The light
 *
 * scene->area_lights[0] (area_light_count 1, light_count 0: nothing else
 * lights the room): the screen, a ONE-sided ::mrgi_area_light, 1.2 m x
 * 0.7 m (MRGI_LIVING_ROOM_SCREEN_WIDTH_M x ..._HEIGHT_M), centre
 * (0, 0.95, 0.165), edge_u = (1.2, 0, 0), edge_v = (0, 0.7, 0), so it emits
 * towards +z (u x v), the sofa; seen from there u points right and v up,
 * and the texture is upright (mrgi_area_light.h). Its plane lies
 * MRGI_LIVING_ROOM_SCREEN_OFFSET_M in front of the TV set's front face
 * (z = 0.16), inside the set's 5 cm bezel. Colour (1, 1, 1), intensity
 * MRGI_LIVING_ROOM_SCREEN_INTENSITY: radiance = intensity * texture, at
 * most 40 (a white texel), (17.27, 17.27, 18.01) on average. The "screen"
 * mesh lies in the light's plane and has emission = intensity * color *
 * (texture mean), so it shows the mean radiance (the reference renderer's
 * shadow rays stop just short of the light, so it hides nothing; see
 * mrgi_reference.h).
 *
 * The texture, MRGI_LIVING_ROOM_TEXTURE_WIDTH x ..._HEIGHT (64 x 36, 16:9)
 * RGB float, row 0 = top, deterministic: a test card. Rows 0..23: seven
 * 75 % colour bars, left to right white, yellow, cyan, green, magenta, red,
 * blue (bar = x * 7 / 64); rows 24..26: the reverse "castellations" blue,
 * black, magenta, black, cyan, black, grey; rows 27..35: a grey ramp
 * (x + 0.5) / 48 over x 0..47 and a one-texel black / white checkerboard
 * over x 48..63 (its mip levels average it to grey: texture filtering
 * shows). All values in [0, 1].
 *
 * ## Camera
 *
 * Behind the sofa, a little to the right, at eye height: position
 * (0.5, 1.45, 5.05), focal point (0, 0.7, 1.0) (just in front of the TV's
 * cabinet), up +y, vertical view angle 55 degrees. The screen, the sofa's
 * back and arms, the table, the shelf and both side walls are in view.
 *
 * Ownership: the scene owns the texture (scene->images[0], see
 * mrgi_scene_create_images()); area_lights[0].texture borrows it.
 * mrgi_scene_destroy() frees everything.
 */
#ifndef MRGI_SCENE_LIVING_ROOM_H
#define MRGI_SCENE_LIVING_ROOM_H

#include "mrgi_error.h"
#include "mrgi_scene.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Room extent along x (metres), centred on x = 0. */
#define MRGI_LIVING_ROOM_WIDTH_M 4.8
/** Room height (metres), floor at y = 0. */
#define MRGI_LIVING_ROOM_HEIGHT_M 2.6
/** Room depth (metres), the TV wall at z = 0. */
#define MRGI_LIVING_ROOM_DEPTH_M 5.2

/** Screen (area light) width along x, metres. */
#define MRGI_LIVING_ROOM_SCREEN_WIDTH_M 1.2
/** Screen (area light) height along y, metres. */
#define MRGI_LIVING_ROOM_SCREEN_HEIGHT_M 0.7
/**
 * How far (m) the light's plane lies in front of the TV set's front face:
 * coplanar surfaces would make the depth test and a ray tracer's nearest
 * hit pick between them at random. 5 mm is far above float and 24-bit depth
 * resolution at the camera's distance of about 5 m.
 */
#define MRGI_LIVING_ROOM_SCREEN_OFFSET_M 0.005
/**
 * Radiance scale of the screen: radiance = intensity * texture (colour
 * white). Chosen so that the room is lit at exposure 1: measured on the
 * GPU path (no indirect light), the floor and side walls near the TV show
 * 0.1 to 0.2 and the lit parts further away about 0.05. The mean radiance,
 * about 17, is of the order of the Cornell box emitter's (17, 12, 4).
 * A quarter of it (mean radiance about 4) gives a dim, TV-lit room.
 */
#define MRGI_LIVING_ROOM_SCREEN_INTENSITY 40.0

/** Texture width in texels (16:9 with the height, as the screen). */
#define MRGI_LIVING_ROOM_TEXTURE_WIDTH 64
/** Texture height in texels. */
#define MRGI_LIVING_ROOM_TEXTURE_HEIGHT 36

/**
 * @brief Build the living room (see the file comment).
 * @param out Receives the scene; zeroed on failure. Release with mrgi_scene_destroy().
 * @return ::MRGI_ERR_INVALID_ARGUMENT for NULL `out`; ::MRGI_ERR_OUT_OF_MEMORY.
 */
mrgi_status mrgi_scene_living_room(mrgi_scene* out, mrgi_error* err);

#ifdef __cplusplus
}
#endif

#endif
