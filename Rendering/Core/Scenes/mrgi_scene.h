/**
 * @file mrgi_scene.h
 * @brief A renderable scene in plain data: meshes, a camera, lights.
 *
 * What every scene builder (Cornell box, scaling scene, ...) produces and
 * what the VTK layer and the ground-truth renderer consume. Cameras and
 * point-like lights follow VTK's vtkCamera / vtkLight semantics, so the VTK
 * layer copies fields one to one; area lights have no VTK counterpart and
 * are the core's own.
 *
 * Units are the builder's (documented there); angles are degrees as in VTK.
 *
 * Ownership: a scene owns its meshes and its images (::mrgi_scene::images,
 * e.g. the textures of its area lights, which only borrow them); release it
 * with mrgi_scene_destroy(). The images live in one heap array, so moving the
 * struct (a shallow copy that replaces the original) keeps the area lights'
 * texture pointers valid. Output parameters are treated as uninitialized.
 */
#ifndef MRGI_SCENE_H
#define MRGI_SCENE_H

#include "mrgi_area_light.h"
#include "mrgi_error.h"
#include "mrgi_image.h"
#include "mrgi_mesh.h"

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Capacity of ::mrgi_scene::lights (VTK's fixed-function heritage allows 8). */
#define MRGI_SCENE_MAX_LIGHTS 8
/** Capacity of ::mrgi_scene::area_lights. */
#define MRGI_SCENE_MAX_AREA_LIGHTS 4
/** Largest accepted ::mrgi_scene::mesh_count. */
#define MRGI_SCENE_MAX_MESHES (1 << 20)
/** Largest accepted ::mrgi_scene::image_count (room for the frames of a video texture). */
#define MRGI_SCENE_MAX_IMAGES 4096

/** A perspective camera, as vtkCamera. */
typedef struct mrgi_camera
{
  double position[3];    /**< Eye point. */
  double focal_point[3]; /**< Point looked at; must differ from position. */
  double view_up[3];     /**< Up direction; must not be parallel to the view direction. */
  double view_angle_deg; /**< Full VERTICAL field of view, (0, 180) degrees (vtkCamera::SetViewAngle). */
} mrgi_camera;

/** Kind of a point-like light; names follow vtkLight. */
typedef enum mrgi_light_type
{
  /** Omnidirectional point light at `position`: vtkLight positional with cone angle >= 90. */
  MRGI_LIGHT_POSITIONAL = 0,
  /** Spot light at `position` aimed at `focal_point`: vtkLight positional, cone angle < 90. */
  MRGI_LIGHT_SPOT,
  /** Light from infinity travelling from `position` towards `focal_point`: vtkLight non-positional. */
  MRGI_LIGHT_DIRECTIONAL
} mrgi_light_type;

/**
 * A point-like light with vtkLight semantics: no distance attenuation (VTK's
 * default AttenuationValues (1, 0, 0)); a surface with normal n lit from
 * direction l receives `intensity * color * max(0, n.l)`, for a spot times
 * `pow(cos(angle to the axis), exponent)` inside the cone and 0 outside.
 */
typedef struct mrgi_light
{
  mrgi_light_type type;
  double position[3];    /**< Light position (for directional: a point on the incoming ray). */
  double focal_point[3]; /**< Aim point: the axis of a spot, the direction of a directional light. */
  double color[3];       /**< Linear RGB, each >= 0. */
  double intensity;      /**< Scalar factor (vtkLight::SetIntensity), >= 0. */
  double cone_angle_deg; /**< Spot HALF-angle (vtkLight::SetConeAngle), in (0, 90); 90 for the other types. */
  double exponent;       /**< Spot falloff exponent (vtkLight::SetExponent), >= 0. */
} mrgi_light;

/* ::mrgi_area_light (a textured rectangular emitter) is defined in mrgi_area_light.h. */

/** Everything a frame needs. See the file comment for ownership. */
typedef struct mrgi_scene
{
  mrgi_mesh* meshes;  /**< mesh_count meshes, owned. */
  int32_t mesh_count; /**< 0..MRGI_SCENE_MAX_MESHES. */
  mrgi_camera camera;
  mrgi_light lights[MRGI_SCENE_MAX_LIGHTS];
  int32_t light_count; /**< 0..MRGI_SCENE_MAX_LIGHTS. */
  mrgi_area_light area_lights[MRGI_SCENE_MAX_AREA_LIGHTS];
  int32_t area_light_count; /**< 0..MRGI_SCENE_MAX_AREA_LIGHTS. */
  /**
   * image_count images the scene owns (mrgi_scene_create_images()), NULL when
   * none: storage for what its area lights' `texture` fields point at.
   */
  mrgi_image* images;
  int32_t image_count; /**< 0..MRGI_SCENE_MAX_IMAGES. */
} mrgi_scene;

/**
 * @brief Zero a scene and give it `mesh_count` empty (zeroed) meshes for a
 *        builder to create in place.
 * @param out        Receives the scene; zeroed on failure.
 * @param mesh_count 1..MRGI_SCENE_MAX_MESHES.
 * @return ::MRGI_ERR_INVALID_ARGUMENT, ::MRGI_ERR_OUT_OF_MEMORY.
 */
mrgi_status mrgi_scene_create(mrgi_scene* out, int32_t mesh_count, mrgi_error* err);

/**
 * @brief Give a scene `image_count` empty (zeroed) images for a builder to
 *        create in place (mrgi_image_create() on each), e.g. the textures its
 *        area lights borrow. The scene owns them; mrgi_scene_destroy() frees them.
 * @param scene       A scene without images (image_count 0, images NULL).
 * @param image_count 1..MRGI_SCENE_MAX_IMAGES.
 * @return ::MRGI_ERR_INVALID_ARGUMENT for NULL, a count out of range or a
 *         scene that already has images (nothing changes);
 *         ::MRGI_ERR_OUT_OF_MEMORY.
 */
mrgi_status mrgi_scene_create_images(mrgi_scene* scene, int32_t image_count, mrgi_error* err);

/**
 * @brief Destroy every mesh and image, free the arrays and zero the struct.
 *        NULL-safe and idempotent.
 */
void mrgi_scene_destroy(mrgi_scene* scene);

/**
 * @brief Check a whole scene: counts in range, every mesh valid
 *        (mrgi_mesh_validate()), camera and lights finite and well-formed
 *        (view angle in (0, 180), spot cone in (0, 90), non-degenerate
 *        directions, non-negative colours), area lights that pass
 *        mrgi_area_light_check() (its message, prefixed "area light <i>: "),
 *        owned images consistent (count in range, array present) and each
 *        valid (mrgi_image_validate(), prefixed "image <i>: ").
 * @return ::MRGI_ERR_INVALID_ARGUMENT for NULL; ::MRGI_ERR_FORMAT naming the
 *         first offence.
 */
mrgi_status mrgi_scene_validate(const mrgi_scene* scene, mrgi_error* err);

/** @brief Sum of the meshes' triangle counts; 0 for NULL. */
int64_t mrgi_scene_triangle_count(const mrgi_scene* scene);

/**
 * @brief Bounds of all meshes' vertices, xmin, xmax, ymin, ymax, zmin, zmax.
 * @return ::MRGI_ERR_INVALID_ARGUMENT for NULL or a scene without meshes;
 *         errors of mrgi_mesh_bounds(). `bounds` is only written on success.
 */
mrgi_status mrgi_scene_bounds(const mrgi_scene* scene, double bounds[6], mrgi_error* err);

/** @brief Index of the first mesh named `name`, or -1 (also for NULL arguments). */
int32_t mrgi_scene_find_mesh(const mrgi_scene* scene, const char* name);

/** @brief Area |edge_u x edge_v| of an area light (scene units squared); 0 for NULL. */
double mrgi_area_light_area(const mrgi_area_light* light);

/**
 * @brief Unit normal of the emitting side, (edge_u x edge_v) / |..|.
 * @return ::MRGI_ERR_INVALID_ARGUMENT for NULL or zero area.
 */
mrgi_status mrgi_area_light_normal(const mrgi_area_light* light, double normal[3],
                                   mrgi_error* err);

/**
 * @brief The four corners c - u/2 - v/2, c + u/2 - v/2, c + u/2 + v/2,
 *        c - u/2 + v/2: counter-clockwise seen from the emitting side.
 * @return ::MRGI_ERR_INVALID_ARGUMENT for NULL.
 */
mrgi_status mrgi_area_light_corners(const mrgi_area_light* light, double corners[4][3],
                                    mrgi_error* err);

#ifdef __cplusplus
}
#endif

#endif
