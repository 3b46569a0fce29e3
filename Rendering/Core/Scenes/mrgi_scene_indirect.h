/**
 * @file mrgi_scene_indirect.h
 * @brief Built-in scenes where indirect light and indirect shadows dominate:
 *        "corridor", "corridor-large", "corner" and "u-shape", after the
 *        figures of Ritschel, Eisemann, Ha, Kim and Seidel 2011, "Making
 *        Imperfect Shadow Maps View-Adaptive" (RIHKS11).
 *
 * Units are METRES; y is up. One spot light each (::MRGI_LIGHT_SPOT,
 * vtkLight semantics: no distance attenuation, falloff pow(cos, exponent)),
 * white, exponent 1, intensities below. Every surface is diffuse; walls
 * face into the space the camera stands in (their counter-clockwise side, as in the Cornell box),
 * the statue's faces point out of it.
 *
 * Large faces are cut into square-ish tiles of at most
 * MRGI_INDIRECT_TILE_M (a quad of 4 vertices and 2 triangles each): point
 * sets drawn per triangle (RIHKS11 5.1-5.2, probability proportional to a
 * triangle's solid angle) can only adapt to the view across triangles, so a
 * wall made of two triangles would defeat the adaptive sampler.
 *
 * Meshes and their names:
 * - "corridor" (RIHKS11 figure 7 and section 5.1: "A light is pointed at the
 *   wall towards the end of the corridor. The observer watches a statue at
 *   the other end. The statue is solely illuminated by indirect light."):
 *   a closed box corridor, x -1..1, y 0..2.5, z 0..12, meshes "floor",
 *   "ceiling", "left_wall" (x = +1, on the image's left), "right_wall"
 *   (x = -1), "near_wall" (z = 0, behind the camera), "far_wall" (z = 12);
 *   a "statue": a 0.5 x 0.7 x 0.5 pedestal centred at (-0.3, 0, 4) under a
 *   ball of radius 0.3 (a 24 x 12 UV sphere with smooth normals).
 *   The spot hangs high by the right wall, at (-0.8, 2.3, 1.2), between
 *   camera and statue, and is pointed across at the left wall, (1, 1, 1),
 *   cone half-angle MRGI_INDIRECT_CORRIDOR_CONE_DEG:  it lights a patch of
 *   the left wall (z ~ 0..2.3) beside the camera and the floor below it.
 *   Every vertex of the statue is more than 10 deg outside the cone and the ground truth
 *   finds no direct light on it: the statue is lit only by the bounce off
 *   that patch, on the side the camera sees, and casts its indirect shadow
 *   back and to the right, onto the floor and the right wall behind it,
 *   where the camera sees it past the statue. Camera at (0, 1.6, 0.3)
 *   looking at (0, 0.6, 6), up +y, 55 deg; of the direct light it sees only
 *   the lit floor's edge at the bottom left.
 *   (The figure's light is "pointed at the wall"; which wall is ours. Lit
 *   from the far end, the statue would show the camera its unlit back and
 *   throw its shadow towards the camera; lit from the end wall behind the
 *   camera, its shadow would hide behind it.)
 * - "corridor-large": the same with the corridor 120 m long (RIHKS11 figure
 *   10c, d: the scale test); only the far part of floor, ceiling and walls
 *   and the far wall move. Camera, spot and statue are unchanged, so both
 *   corridors have nearly the same light where the camera looks, and ten
 *   times the surface area for a uniform point set to cover.
 * - "corner" (RIHKS11 figure 5 and section 4.2: VPLs near a corner, close to
 *   the receivers): an open corner, a 4 x 4 "floor" (x 0..4, z 0..4), the
 *   "back_wall" (z = 4, 3 m high, facing the camera) and the "side_wall"
 *   (x = 0, facing +x, on the image's right), meeting at
 *   x = 0, z = 4. The spot at (2.2, 2.6, 1.8) points into the corner at
 *   (0.2, 0.3, 3.8) (cone MRGI_INDIRECT_CORNER_CONE_DEG); the camera at
 *   (3.2, 1.7, -1.2) looks at (1.2, 0.9, 3.0), 55 deg. Open on the other
 *   two sides and the top: light escapes, as in the figure.
 * - "u-shape" (RIHKS11 figure 10: "the camera faces the back of one side of
 *   the u-shaped scene and the light is placed on the other side [...] only
 *   very few view samples are connected with light samples"): a closed
 *   U-shaped corridor 2.5 m high over x 0..6, z 0..6 without the inner
 *   block x 2..4, z 0..4. Two arms (x 0..2 and x 4..6) joined by the base
 *   (z 4..6). Meshes "floor", "ceiling", "outer_wall" (x = 0, z = 6, x = 6
 *   and the arms' end walls at z = 0), "inner_wall" (the block's three
 *   faces). The spot in the left arm at (1, 2.2, 0.5) aims down the arm at
 *   (1.3, 1, 6) (cone MRGI_INDIRECT_U_SHAPE_CONE_DEG); the camera in the
 *   right arm at (5, 1.6, 0.5) looks at (4.6, 0.9, 6), 55 deg, and sees no
 *   directly lit surface: all its light is one bounce off the base's back
 *   wall (x < 2.6), most of it through the gap past the block's corner
 *   (4, 4). Without secondary visibility the left arm's light leaks
 *   through the block into the whole right arm.
 *
 * Albedos: walls, ceilings and the statue the Cornell box's white (0.725,
 * 0.71, 0.68); floors grey (0.5, 0.5, 0.5); the corner's side wall a warm
 * (0.75, 0.5, 0.3), so that its bounce is told apart by its colour, and the
 * corridor's near wall (0.8, 0.7, 0.55) (behind the camera; a leftover of
 * an earlier layout that lit it, harmless: it only adds a faint tint).
 */
#ifndef MRGI_SCENE_INDIRECT_H
#define MRGI_SCENE_INDIRECT_H

#include "mrgi_error.h"
#include "mrgi_scene.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Largest side of a wall tile (metres); see the file comment. */
#define MRGI_INDIRECT_TILE_M 0.5
/** Spot half-angle (degrees) of both corridors. */
#define MRGI_INDIRECT_CORRIDOR_CONE_DEG 30.0
/** Spot half-angle (degrees) of "corner". */
#define MRGI_INDIRECT_CORNER_CONE_DEG 30.0
/**
 * Spot half-angle (degrees) of "u-shape": it lights the far end of the left
 * arm and the base's back wall up to x = 2.6 m, where the inner block's
 * corner starts to shadow it. (At 35 degrees the cone's rim reached the
 * back wall behind the block, x ~ 4.5, where the GPU's soft and hard
 * direct shadows of 2026-12-03 let a thin arc of direct light through.)
 */
#define MRGI_INDIRECT_U_SHAPE_CONE_DEG 20.0
/**
 * Spot intensities. The camera of the corridors and of "u-shape" sees only
 * indirect light; these put the image of each near 0 EV under the project's
 * auto exposure (mrgi-render at 256 x 256: +0.5 EV for the corridor at 10,
 * +0.25 EV for u-shape at 40), so that fixed-exposure
 * pictures of the ground truth show the light too. "corner" keeps 1 (its
 * camera sees the direct light: +0.75 EV).
 */
#define MRGI_INDIRECT_CORRIDOR_INTENSITY 10.0
#define MRGI_INDIRECT_U_SHAPE_INTENSITY 40.0

/** Which scene. */
typedef enum mrgi_indirect_scene
{
  MRGI_INDIRECT_CORRIDOR = 0, /**< "corridor" */
  MRGI_INDIRECT_CORRIDOR_LARGE, /**< "corridor-large" */
  MRGI_INDIRECT_CORNER, /**< "corner" */
  MRGI_INDIRECT_U_SHAPE /**< "u-shape" */
} mrgi_indirect_scene;

/** @brief The scene's name as above; NULL for a value outside the enum. */
const char* mrgi_indirect_scene_name(mrgi_indirect_scene which);

/**
 * @brief Parse a name as mrgi_indirect_scene_name() spells it.
 * @return ::MRGI_ERR_INVALID_ARGUMENT for NULL or an unknown name (the
 *         message lists the known ones).
 */
mrgi_status mrgi_indirect_scene_parse(const char* name, mrgi_indirect_scene* out,
                                      mrgi_error* err);

/**
 * @brief Build one of the scenes (see the file comment).
 * @param out Receives the scene; zeroed on failure. Release with mrgi_scene_destroy().
 * @return ::MRGI_ERR_INVALID_ARGUMENT for NULL `out` or an unknown scene;
 *         ::MRGI_ERR_OUT_OF_MEMORY.
 */
mrgi_status mrgi_scene_indirect(mrgi_indirect_scene which, mrgi_scene* out, mrgi_error* err);

#ifdef __cplusplus
}
#endif

#endif
