/**
 * @file mrgi_reference.h
 * @brief Ground truth: a CPU ray tracer (Embree 3) for direct light and one
 *        diffuse bounce, in exactly the lighting model VTK's renderer uses.
 *
 * What every fast path of MRGI approximates, computed on the same
 * triangles (every mesh of an ::mrgi_scene) with exact visibility.
 *
 * Lighting model (VTK's, so that the GPU images and these agree):
 * - Point-like lights (::mrgi_light) have no distance attenuation. A point with
 *   unit normal n, lit from unit direction l (towards the light), receives the
 *   "VTK irradiance" X = intensity * color * max(0, n.l) * spot. Positional
 *   and spot: l = normalize(position - p); directional: the light travels from
 *   position to focal_point, l = normalize(position - focal_point) everywhere.
 *   spot = pow(max(0, cos a), exponent) when a <= cone_angle_deg and 0 outside,
 *   a being the angle between -l and the axis focal_point - position (VTK's
 *   vtkOpenGLPolyDataMapper light shader); positional and directional: 1.
 * - Surfaces are Lambertian and two-sided (VTK's default two-sided lighting):
 *   at a hit the normal is turned towards the side being looked at, i.e.
 *   towards the ray's origin. Outgoing radiance L = albedo * X (VTK's
 *   diffuse term; no 1/pi, as in VTK, so X plays the role of pi * E).
 * - Normals: X uses the shading normal, the barycentric interpolation of the
 *   mesh's vertex normals (as VTK's fragment shader), turned to the same side
 *   as the oriented geometric normal; meshes without normals, or with
 *   ::mrgi_reference_options::shading_normals off, use the geometric normal.
 *   Bounce directions and ray offsets always use the geometric normal, so no
 *   ray leaves below the surface it starts on.
 * - Emitters (a mesh with any emission channel > 0) show their emission in the
 *   direct image and reflect nothing (indirect 0). They are not light sources
 *   of this renderer, and a bounce ray reaching an emitter gathers 0
 *   (emission is direct light, not the one bounce). Light from rectangles
 *   comes from area lights (next item), which mrgi_reference_render() does
 *   not use: a scene's ::mrgi_scene::area_lights light nothing unless passed
 *   to mrgi_reference_render_area_lights().
 * - Area lights (::mrgi_area_light, units and texture mapping in
 *   mrgi_area_light.h) given to mrgi_reference_render_area_lights() add to
 *   the direct image, diffuse only (meshes carry no specular data), the VTK
 *   irradiance
 *       X_area(p) = (1/pi) * integral over the light of L(y) V(p, y) cos_p cos_y / |y - p|^2 dA_y
 *   (cos_p with the shading normal, cos_y with the light's normal, |cos_y| for
 *   two-sided lights, L(y) = intensity * color * the texel containing y,
 *   mrgi_area_light_emitted()), estimated per primary hit and pass from
 *   area_light_samples points per light: one uniform point in each cell of
 *   the light's mrgi_area_light_sample_layout() grid (stratified), weight
 *   A / (pi * cells). V is exact when `shadows` is 1: a shadow ray from p
 *   (offset as for point lights) that stops just short of y, so a mesh in
 *   the light's plane (the emitter quad drawn for it, as in the Cornell box)
 *   does not hide it; V = 1 when `shadows` is 0, the no-visibility gather
 *   of mrgi_area_light_diffuse() to compare with. Area lights are invisible
 *   to primary rays (draw an emitter mesh to see one). They light the
 *   direct image and the bounce: the L(q) of the indirect image (next list)
 *   includes albedo_q * X_area(q), with exact shadows, from the same
 *   number of stratified points per light. Their samples come from streams
 *   of their own (one for the direct image, one for the bounce), so the
 *   point-like lights' part of both images is bit for bit unchanged by
 *   adding area lights.
 *
 * Images (all width x height, row 0 = TOP, box filter over the jittered
 * primary rays of all passes; a primary ray that misses contributes 0).
 * ::mrgi_reference_options::pixel_filter MRGI_REFERENCE_PIXEL_CENTER instead
 * shoots every primary ray through the pixel's centre, as a rasterizer
 * samples a pixel: the truth of a GPU image whose pixels are centre samples
 * (no multisampling). Against the box-filtered truth such an image differs
 * at every silhouette and shadow edge (each pixel there is one sample of a
 * step the truth averages); against the centre-sampled truth only where its
 * light is wrong. The random streams are the same in both modes (the
 * jitter is drawn and ignored), so the two truths differ only by where the
 * primary rays go.
 * - direct: L_direct = albedo * sum over lights of X (and of X_area of the
 *   area lights), with exact shadows (an occlusion ray to each
 *   positional/spot light, to infinity against a directional light's travel
 *   direction, to each area-light point) or without (VTK's own direct light
 *   has none): ::mrgi_reference_options::shadows.
 * - indirect: albedo_p * X_ind(p), X_ind(p) = (1/pi) * integral over the
 *   hemisphere of p of L_direct_shadowed(q) cos(theta_p) d omega, q being the
 *   surface seen from p in direction omega and L(q) = albedo_q * X_q
 *   (X_q: the point-like lights' X plus X_area(q) of the area lights)
 *   evaluated with q's normal turned towards p (light arriving on the other
 *   side of q does not count). q's lighting is ALWAYS shadowed, whatever
 *   `shadows` says (a reflective shadow map only holds lit surfaces).
 *   Estimator: cosine-weighted directions (pdf cos/pi), so X_ind = mean L(q)
 *   (Pharr, Jakob, Humphreys, "Physically Based Rendering" 3rd ed., 13.6.3).
 *   With secondary_visibility = 0 (what reflective shadow maps assume,
 *   Dachsbacher and Stamminger 2005) nothing occludes p -> q: every surface
 *   the bounce ray crosses contributes its L(q) (each still lit with exact
 *   light visibility and only on its side facing p).
 * - albedo: the albedo of the surface seen (RGB).
 * - indirect_stderr: one channel, the standard error of the pixel's indirect
 *   (mean of its three channels) estimated from the spread of the per-pass
 *   estimates; 0 after a single pass (unknown) and for background.
 * - background: one byte per pixel, 1 when none of the pixel's primary rays
 *   hit a surface (then direct, indirect and albedo are 0).
 *
 * Camera: ::mrgi_camera with vtkCamera semantics: view_angle_deg is the full
 * VERTICAL field of view, aspect = width / height, the image's right is
 * (focal_point - position) x view_up. With parallel_projection the rays are
 * parallel to the view direction and start on the plane through the camera
 * position; parallel_scale is half the view height in world units
 * (vtkCamera::SetParallelScale).
 *
 * Progressive passes: each pass traces pixel_samples jittered primary rays
 * per pixel and indirect_samples bounce rays per primary hit. After a pass,
 * the noise is estimated from the per-pixel, per-pass indirect estimates e_k
 * (mean of the three channels): for a pixel with n passes, mean m and sample
 * variance s^2, the variance of its mean is s^2 / n. Over the N non-background
 * pixels:
 *   relative_error       = sqrt(sum of s^2/n) / sum of m
 *                          (relative standard error of the image's mean indirect),
 *   pixel_relative_error = sqrt(N) * relative_error
 *                          (RMS per-pixel standard error / mean pixel value).
 * After a single pass the spread is unknown: both are +infinity (never NaN).
 * With no indirect light at all (sum of m = 0, or indirect_samples = 0) both
 * are 0, known exactly. With area lights, the direct image is noisy too:
 * direct_relative_error and direct_stderr are the same statistics of the
 * per-pass direct estimates (mean of the three channels); without area
 * lights the direct image is exact up to pixel jitter and both are 0.
 * These image-mean statistics are reported, but they are no stopping rule:
 * relative_error is sqrt(N) times smaller than the per-pixel noise, so a
 * render stopped on it is noise per pixel (issue 12, part 4: 0.30 relative
 * RMS per pixel at relative_error 0.01 on the 256x256 Cornell box).
 * Stopping rule, per pixel: pixel_error is the target_percentile quantile
 * of the per-pixel relative standard error of the indirect image, each
 * pixel's standard error over max(its mean, the image's mean pixel value)
 * (mrgi_reference_noise.h says why that floor); direct_pixel_error is the
 * same of the direct image when area lights make it noisy (0 without).
 * Rendering stops after the first pass whose pixel_error and
 * direct_pixel_error are both at or below target_relative_error (so after
 * pass 2 at the earliest, unless both are 0), or at max_passes, or after the
 * pass that crosses max_seconds.
 *
 * Determinism: every pixel of every pass draws from its own splitmix64 stream
 * seeded by (seed, pass, pixel), so the images depend on the options only,
 * not on the number of threads or their scheduling (max_seconds aside).
 *
 * Geometry: triangles of every mesh go to one Embree scene, built once per
 * call. Zero-area triangles are left out and counted
 * (::mrgi_reference_result::skipped_triangles); they cannot poison pixels.
 * Triangles with a non-finite corner would be too, but the scene is
 * validated first and mrgi_scene_validate() already refuses them. Rays start offset along the geometric normal by a
 * scale-relative epsilon (1e-5 of max(|p|, 1 % of the scene's extent)) to
 * avoid self-intersection.
 */
#ifndef MRGI_REFERENCE_H
#define MRGI_REFERENCE_H

#include "mrgi_area_light.h"
#include "mrgi_error.h"
#include "mrgi_image.h"
#include "mrgi_reference_noise.h"
#include "mrgi_scene.h"

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Largest accepted image width or height, pixels. */
#define MRGI_REFERENCE_MAX_DIMENSION 16384
/** Largest accepted pixel_samples. */
#define MRGI_REFERENCE_MAX_PIXEL_SAMPLES 4096
/** Largest accepted indirect_samples. */
#define MRGI_REFERENCE_MAX_INDIRECT_SAMPLES 65536
/**
 * Default target of the per-pixel stopping rule (pixel_error at the 95th
 * percentile): a converged image. Chosen so that the default ground truth
 * of the 256x256 Cornell box is well below the errors the project measures
 * (0.04-0.3 relative RMS); measured in Documentation/Fidelity.md.
 */
#define MRGI_REFERENCE_DEFAULT_TARGET 0.02
/** Default max_passes: high enough that the default target, not the cap, ends a Cornell-box render. */
#define MRGI_REFERENCE_DEFAULT_MAX_PASSES 4096
/** Largest accepted max_passes. */
#define MRGI_REFERENCE_MAX_PASSES 1000000
/** Largest accepted threads. */
#define MRGI_REFERENCE_MAX_THREADS 1024
/** Largest accepted area_light_samples (the largest light-sample grid). */
#define MRGI_REFERENCE_MAX_AREA_LIGHT_SAMPLES MRGI_AREA_LIGHT_MAX_SAMPLES
/** Most area lights one mrgi_reference_render_area_lights() call takes. */
#define MRGI_REFERENCE_MAX_AREA_LIGHTS 64
/**
 * Most distinct surfaces one bounce ray records when secondary_visibility is
 * 0. Further crossings are ignored and counted in
 * ::mrgi_reference_result::hit_list_overflows (a scene needing more is a
 * pathological stack of surfaces; the count says whether it happened).
 */
#define MRGI_REFERENCE_MAX_RAY_HITS 256

/** ::mrgi_reference_options::pixel_filter: jittered primary rays over the pixel square (a box filter). */
#define MRGI_REFERENCE_PIXEL_BOX 0
/** ::mrgi_reference_options::pixel_filter: every primary ray through the pixel's centre. */
#define MRGI_REFERENCE_PIXEL_CENTER 1

/** Where a render stands, handed to ::mrgi_reference_progress_fn after each pass. */
typedef struct mrgi_reference_progress
{
  /** Passes done, 1..max_passes. */
  int32_t passes;
  /** The options' max_passes. */
  int32_t max_passes;
  /** As ::mrgi_reference_result::relative_error after these passes (+inf after one). */
  double relative_error;
  /** As ::mrgi_reference_result::direct_relative_error. */
  double direct_relative_error;
  /** As ::mrgi_reference_result::pixel_error: the stopping statistic (+inf after one pass). */
  double pixel_error;
  /** As ::mrgi_reference_result::direct_pixel_error. */
  double direct_pixel_error;
  /** The options' target_relative_error. */
  double target_relative_error;
  /** Wall time since the call began (Embree build included). */
  double seconds;
  /** Passes the render is expected to take in all: max_passes, or fewer where the stopping
   *  statistic (the larger of pixel_error and direct_pixel_error), falling as
   *  1/sqrt(passes), reaches the target sooner; >= passes. */
  double passes_expected;
  /** passes / passes_expected, in (0, 1]. */
  double fraction;
  /** Estimated wall time to the end, from the mean pass time; >= 0. */
  double seconds_left;
} mrgi_reference_progress;

/**
 * @brief Called on the calling thread after each pass (never concurrently).
 * @return 0 to go on; non-zero to stop after this pass: the images of the
 *         passes done so far are returned as usual, with
 *         ::mrgi_reference_result::cancelled set to 1.
 */
typedef int (*mrgi_reference_progress_fn)(void* user_data, const mrgi_reference_progress* progress);

/** How to render. Start from mrgi_reference_options_default(). */
typedef struct mrgi_reference_options
{
  int32_t width;                /**< Pixels per row, 1..MRGI_REFERENCE_MAX_DIMENSION. Default 256. */
  int32_t height;               /**< Rows, 1..MRGI_REFERENCE_MAX_DIMENSION. Default 256. */
  int32_t pixel_samples;        /**< Jittered primary rays per pixel per pass, 1..MRGI_REFERENCE_MAX_PIXEL_SAMPLES. Default 1. */
  int32_t pixel_filter;         /**< MRGI_REFERENCE_PIXEL_BOX (default) or MRGI_REFERENCE_PIXEL_CENTER: where the primary rays cross the pixel. */
  int32_t indirect_samples;     /**< Bounce rays per primary hit per pass, 0..MRGI_REFERENCE_MAX_INDIRECT_SAMPLES; 0 = no indirect. Default 16. */
  double target_relative_error; /**< Stop once pixel_error and direct_pixel_error are <= this (finite, >= 0); 0 = run max_passes. Default MRGI_REFERENCE_DEFAULT_TARGET. */
  double target_percentile;     /**< The quantile of the per-pixel relative standard error that pixel_error reports, in (0, 1]. Default MRGI_REFERENCE_DEFAULT_PERCENTILE (0.95). */
  int32_t max_passes;           /**< Cap on progressive passes, 1..MRGI_REFERENCE_MAX_PASSES. Default MRGI_REFERENCE_DEFAULT_MAX_PASSES. */
  double max_seconds;           /**< Stop after the pass that crosses this wall time (finite, >= 0); 0 = no limit. Default 0. */
  int32_t shadows;              /**< 0 or 1: shadows in the direct image, of point-like and area lights (the bounce is always shadowed). Default 1. */
  int32_t secondary_visibility; /**< 1 = exact p -> q visibility; 0 = every surface crossed counts (RSM). Default 1. */
  int32_t shading_normals;      /**< 0 or 1: interpolated vertex normals for X (VTK) where a mesh has them. Default 1. */
  int32_t parallel_projection;  /**< 0 = perspective (view_angle_deg), 1 = parallel (parallel_scale). Default 0. */
  double parallel_scale;        /**< Half the view height in world units; finite, > 0 when parallel_projection. Default 1. */
  uint64_t seed;                /**< Any value. Default 1. */
  int32_t threads;              /**< Worker threads, 0..MRGI_REFERENCE_MAX_THREADS; 0 = online CPUs. Default 0. */
  int32_t area_light_samples;   /**< Points (shadow rays) per area light per primary hit per pass, 0..MRGI_REFERENCE_MAX_AREA_LIGHT_SAMPLES; at least 1 when area lights are rendered (0 suits point-light renders only). The light's sample grid for this count is used (<= this many). Default 16. */
  mrgi_reference_progress_fn progress; /**< NULL (default) or called after each pass; may cancel. */
  void* progress_user_data;     /**< Handed to `progress`. Default NULL. */
} mrgi_reference_options;

/** @brief Fill `options` with the defaults listed on each field. NULL is a no-op. */
void mrgi_reference_options_default(mrgi_reference_options* options);

/**
 * @brief Check options against the documented ranges.
 * @return ::MRGI_ERR_INVALID_ARGUMENT naming the first bad field and its value.
 */
mrgi_status mrgi_reference_options_validate(const mrgi_reference_options* options,
                                            mrgi_error* err);

/** What mrgi_reference_render() produces. Release with mrgi_reference_result_destroy(). */
typedef struct mrgi_reference_result
{
  mrgi_image direct;          /**< RGB radiance L_direct (scene light units). */
  mrgi_image indirect;        /**< RGB radiance albedo_p * X_ind(p). */
  mrgi_image albedo;          /**< RGB albedo of the surface seen. */
  mrgi_image indirect_stderr; /**< 1 channel: standard error of the pixel's mean indirect (see the file comment). */
  mrgi_image direct_stderr;   /**< 1 channel: standard error of the pixel's mean direct (area lights; 0 without). */
  uint8_t* background;        /**< width*height bytes, row 0 = top; 1 = no surface in the pixel. */
  double relative_error;       /**< Achieved relative standard error of the mean indirect (file comment). */
  double pixel_relative_error; /**< RMS per-pixel relative standard error (file comment). */
  double direct_relative_error; /**< Relative standard error of the mean direct (area lights; 0 without). */
  double pixel_error;         /**< The stopping statistic of the indirect: target_percentile quantile of the
                                   per-pixel relative standard error (file comment); +inf after one pass, 0 without indirect light. */
  double direct_pixel_error;  /**< The same of the direct image (area lights; 0 without). */
  int64_t rays_traced;        /**< Primary + shadow + bounce rays, all passes. */
  int64_t skipped_triangles;  /**< Zero-area or non-finite triangles left out of the Embree scene. */
  int64_t hit_list_overflows; /**< Bounce rays that crossed more than MRGI_REFERENCE_MAX_RAY_HITS surfaces (RSM mode). */
  int32_t passes;             /**< Passes run. */
  int32_t cancelled;          /**< 1 when options->progress stopped the render early (the images
                                   hold the passes run, with their errors); else 0. */
  int32_t threads;            /**< Worker threads used. */
  double seconds;             /**< Wall time of the whole call (Embree build included). */
  double build_seconds;       /**< Wall time of building the Embree scene. */
} mrgi_reference_result;

/**
 * @brief Render ground-truth direct and one-bounce indirect images of `scene`.
 *
 * Same as mrgi_reference_render_area_lights() without area lights.
 *
 * @param scene   A scene that passes mrgi_scene_validate() and has at least
 *                one non-degenerate triangle. Its lights are used; its
 *                area lights are ignored (see the file comment).
 * @param options Valid options (mrgi_reference_options_validate()).
 * @param out     Receives the images (treated as uninitialized); zeroed on failure.
 * @return ::MRGI_ERR_INVALID_ARGUMENT for NULL arguments, bad options or a
 *         scene without usable triangles; ::MRGI_ERR_FORMAT (prefixed
 *         "mrgi_reference_render: ") for a scene that fails validation;
 *         ::MRGI_ERR_OUT_OF_MEMORY; ::MRGI_ERR_UNSUPPORTED when Embree cannot
 *         be started, cannot build the scene or (secondary_visibility = 0)
 *         was built without filter functions.
 */
mrgi_status mrgi_reference_render(const mrgi_scene* scene, const mrgi_reference_options* options,
                                  mrgi_reference_result* out, mrgi_error* err);

/**
 * @brief Render ground truth with area lights as well: the images of
 *        mrgi_reference_render() plus, in the direct image, the light of
 *        `area_lights` (diffuse, with exact visibility when options->shadows
 *        is 1, none when 0; see the file comment).
 *
 * @param area_lights      Lights that pass mrgi_area_light_check() (borrowed,
 *                         textures too, for the call only); may be NULL when
 *                         area_light_count is 0. Pass scene->area_lights to
 *                         render a scene's own.
 * @param area_light_count 0..MRGI_REFERENCE_MAX_AREA_LIGHTS.
 * @return As mrgi_reference_render(), and ::MRGI_ERR_INVALID_ARGUMENT for a
 *         count out of range, NULL lights, a light failing
 *         mrgi_area_light_check() (its message, prefixed
 *         "mrgi_reference_render: area light <i>: ") or area_light_samples = 0
 *         with lights to render.
 */
mrgi_status mrgi_reference_render_area_lights(const mrgi_scene* scene,
                                              const mrgi_reference_options* options,
                                              const mrgi_area_light* area_lights,
                                              int32_t area_light_count,
                                              mrgi_reference_result* out, mrgi_error* err);

/** @brief Free everything a result owns and zero it. NULL-safe and idempotent. */
void mrgi_reference_result_destroy(mrgi_reference_result* result);

#ifdef __cplusplus
}
#endif

#endif
