/**
 * @file mrgi_variance_shadow.h
 * @brief The variance shadow query for sharp Phong lobes: the C twin of
 *        vtkMRGIVarianceShadowQuery (moments pass and resolve).
 *
 * Paper: Nichols, Penmatsa and Wyman 2010 (NPW10), section 3.3.3 (variance
 * shadow query after Donnelly and Lauritzen 2006 [DL06]). The rays are
 * mrgi_voxel_march() (mrgi_voxel_march.h); the sample sets, phases and
 * masks are those of mrgi_visibility_pyramid.h, whose section numbers the
 * text below continues.
 *
 * ## 6. Variance shadow query for sharp lobes (NPW10 3.3.3, [DL06])
 *
 * For a sharp BRDF, Q = MRGI_VOXEL_VSM_QUERIES = 24 queries toward light
 * samples in the specular lobe: the G x G lobe grid of mrgi_area_light.h
 * (G = MRGI_AREA_LIGHT_LOBE_GRID = 5, cells (a, b), a, b in -2..2, around
 * the reflection direction) "ignoring one corner": query j is cell
 * (a, b) = (j % G - G/2, j / G - G/2), j = 0..23, the corner (2, 2) is
 * dropped. Placing the cells on the light is the area-light code's; this
 * file fixes which cell each query is.
 * Instead of a bit, each query stores the moments (z, z^2) of z =
 * mrgi_voxel_march_occluder_fraction(): the distance from the light sample
 * to the nearest occluder as a fraction of the ray, 1 when unoccluded. What
 * the paper leaves open and was decided here:
 * - distances are measured from the light (the shadow-map convention DL06's
 *   test assumes) and normalized by the ray length, so that neighbouring
 *   receivers at different distances blur consistently and the receiver
 *   sits at exactly 1: an unoccluded neighbourhood gives mean 1 and is lit
 *   exactly;
 * - the "screen space blur" is a box filter of radius r over the receiver
 *   texels of one level that computed query j (with interleaving, only
 *   pixels of j's phase compute it: query j is phase j & 3; 6 queries and 12
 *   floats per pixel, in MRGI_VOXEL_VSM_TARGETS = 3 RGBA32F targets, local
 *   query k = j >> 2 in target k >> 1, channels 2 (k & 1) and 2 (k & 1) + 1);
 * - DL06's Chebyshev bound with the receiver at t = 1:
 *     p = 1 if mean >= 1, else var / (var + (1 - mean)^2),
 *     var = max(mean_sq - mean^2, min_variance)
 *   (min_variance >= 0, DL06's minimum variance against numeric trouble).
 *   A query no texel in the window computed is visible (p = 1).
 *
 * The moments pass of a specular G-buffer (mrgi_voxel_vsm_specular_moments(),
 * C twin of vtkMRGIVarianceShadowQuery's pass), per pixel with a specular
 * material: only a receiver whose highlight takes the lobe-grid path
 * (mrgi_area_light_specular_classify()) computes; with 2x2 interleaving
 * always on (the 12 floats per pixel above), pixel (x, y) of the viewport
 * computes the queries of phase mrgi_voxel_interleave_phase(x, y). Query j
 * aims at the centre of lobe-grid cell j (mrgi_area_light_lobe_grid_cells(),
 * the point the specular sum uses), brought to eye space by the caller's
 * world -> eye matrix (column-major, summed x, y, z, w in that order), with
 * the light's normal as the sample normal (flipped to face the receiver for
 * a two-sided light, as mrgi_voxel_samples.two_sided); a cell off the light
 * (clipped away) has no light to hide: z = 1, nothing marched. The
 * specular sum then weights cell j by the resolved p of query j
 * (mrgi_area_light_specular_visible(), which also fixes what the dropped
 * corner uses). Blur defaults: radius MRGI_VOXEL_VSM_DEFAULT_RADIUS (2:
 * with interleaving a 5 x 5 window holds 4 to 9 texels of each phase),
 * minimum variance MRGI_VOXEL_VSM_DEFAULT_MIN_VARIANCE (1e-4 of the
 * squared ray length: a window that agrees on one occluder at z < 0.99
 * keeps p < 1e-4 / (1e-4 + 0.01^2) = 0.5 there and p < 1e-3 below z = 0.68).
 */
#ifndef mrgi_variance_shadow_h
#define mrgi_variance_shadow_h

#include "mrgi_visibility_pyramid.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Variance shadow queries (section 6): the lobe grid of mrgi_area_light.h less one corner (24). */
#define MRGI_VOXEL_VSM_QUERIES (MRGI_AREA_LIGHT_LOBE_GRID * MRGI_AREA_LIGHT_LOBE_GRID - 1)
/** RGBA32F targets holding one pixel's interleaved moments: 2 floats x queries / 4 phases / 4 channels (3). */
#define MRGI_VOXEL_VSM_TARGETS (((MRGI_VOXEL_VSM_QUERIES + 3) / 4 * 2 + 3) / 4)
/** Largest box blur radius of the variance shadow query, in pixels. */
#define MRGI_VOXEL_VSM_MAX_RADIUS 16
/** Default box blur radius (section 6). */
#define MRGI_VOXEL_VSM_DEFAULT_RADIUS 2
/** Default minimum variance of the Chebyshev bound ([DL06]), in squared ray lengths (section 6). */
#define MRGI_VOXEL_VSM_DEFAULT_MIN_VARIANCE 1.0e-4f

/** @brief Lobe grid cell (a, b) = (j % G - G/2, j / G - G/2) of VSM query j (section 6); j in 0..MRGI_VOXEL_VSM_QUERIES-1. */
void mrgi_voxel_vsm_query_cell(int32_t query, int32_t* cell_x, int32_t* cell_y);

/**
 * @brief Moments (z, z^2) of the queries of `phase_set` at one receiver
 *        (section 6); other queries get (0, 0). Same preconditions as
 *        mrgi_voxel_visibility(); `queries` may hold any count.
 * @param moments Receives 2 * queries->count floats.
 */
void mrgi_voxel_vsm_moments(const mrgi_voxel_view* view, const mrgi_voxel_samples* queries,
                            const float receiver[3], const float* normal, uint32_t phase_set,
                            float* moments);

/** @brief DL06's bound with the receiver at 1 (section 6), in [0, 1]. */
float mrgi_voxel_vsm_chebyshev(float mean, float mean_sq, float min_variance);

/**
 * @brief Blur the moments and evaluate the bound (section 6) over a W x H image.
 * @param moments    W H 2 Q floats: pixel p's query j at (p Q + j) 2.
 * @param phase_sets W H bytes: the phases each pixel computed (0: not a receiver).
 * @param radius     Box radius in pixels, 0..MRGI_VOXEL_VSM_MAX_RADIUS.
 * @param min_variance >= 0, finite.
 * @param visibility Receives W H Q floats in [0, 1]; 0 at non-receivers.
 * @return ::MRGI_ERR_INVALID_ARGUMENT for NULL pointers or values out of range.
 */
mrgi_status mrgi_voxel_vsm_resolve(int32_t width, int32_t height, int32_t query_count,
                                   const float* moments, const uint8_t* phase_sets,
                                   int32_t radius, float min_variance, float* visibility,
                                   mrgi_error* err);

/**
 * @brief The moments pass at one pixel of a specular G-buffer (section 6):
 *        the twin of vtkMRGIVarianceShadowQuery's moments shader.
 *
 * Computes when the receiver's highlight takes the lobe-grid path
 * (mrgi_area_light_specular_classify() on position, normal, view and
 * power, world space as the specular shader sees them): query j of
 * `phase_set` gets the moments (z, z^2) of
 * mrgi_voxel_march_occluder_fraction() from (receiver_eye, normal_eye) to
 * lobe-grid cell j's centre in eye space, or (1, 1) for a cell off the
 * light; the other queries get (0, 0). No checks (per pixel): `view`
 * checked, inputs finite. The caller skips pixels without a specular
 * material, as the shader does.
 * @param world_to_eye Column-major world -> eye (the voxels' space).
 * @param moments      Receives 2 * MRGI_VOXEL_VSM_QUERIES floats.
 * @return 1 when the pixel computed (lobe-grid path), 0 otherwise (moments all 0).
 */
int mrgi_voxel_vsm_specular_moments(const mrgi_voxel_view* view,
                                    const mrgi_area_light_uniforms* light,
                                    const mrgi_area_light_sample* samples, int32_t count,
                                    const float world_to_eye[16], const float position[3],
                                    const float normal[3], const float view_dir[3], float power,
                                    const float receiver_eye[3], const float normal_eye[3],
                                    uint32_t phase_set, float* moments);

#ifdef __cplusplus
}
#endif

#endif
