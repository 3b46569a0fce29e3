/**
 * @file mrgi_area_light_rsm.h
 * @brief Reflective shadow maps of rectangular area lights: the views from
 *        the emitter and the flux of an RSM texel lit by the emitter. C twin
 *        of the area-light branch of the RSM capture shader
 *        (vtkMRGIRSMCapture.glsl).
 *
 * An area light bounces like a VTK light: its RSM (Dachsbacher and
 * Stamminger 2005, [DS05] section 3, "flux" per texel) joins the RSM views
 * of the renderer's vtkLights, so the same VPL selection and gather turn it
 * into one bounce. Derivation and choices: Documentation/IndirectLight.md,
 * section "Area lights bounce".
 *
 * ## Views
 *
 * A hemicube around the light's centre c (cube faces of 90 degrees, the
 * machinery of a positional light's six faces): the face along the light's
 * normal n, the four along +-u/|u| and +-v/|v| (their halves behind the
 * light's plane see nothing lit: the emitter cosine is 0 there), and for a
 * two-sided light also the face along -n. mrgi_area_light_rsm_views() gives
 * the directions, in this order. The union of the faces is the whole
 * sphere of directions around c, so every surface point the centre sees
 * is captured once.
 *
 * ## Texel flux
 *
 * A texel that sees the surface point p (unit normal N, oriented towards
 * c, albedo rho) and covers the world area A_t (the perspective area of
 * mrgi_vpl.h, measured from c) reflects the flux
 *
 *     Phi_t = rho * X(p) * A_t
 *
 * where X(p) is the light's VTK irradiance at p without visibility,
 * mrgi_area_light_diffuse() over ::MRGI_AREA_LIGHT_RSM_SAMPLES stratified
 * light samples (mrgi_area_light_make_samples(), centres, cell-filtered
 * radiance): [NSW09] eq. 1's form factor per sample,
 *
 *     X(p) = sum_j L_j * A_j * cos_p,j * cos_y,j / (pi r_j^2 + A_j),
 *
 * which tends to (1/pi) integral L cos_p cos_y / r^2 dA as the samples
 * shrink (mrgi_area_light.h, "Units"). With one sample this is the
 * centre approximation L_e A cos_y cos_p / (pi r^2 + A); 16 samples keep
 * walls next to the light right (the centre approximation overestimates
 * them) and let a textured emitter's picture bleed where its parts shine
 * ([NPW10] 3.1: the light's samples carry the texture filtered over their
 * cell). Visibility between the emitter and p is the centre's (the view's
 * depth test), as an RSM's shadow is its light position's.
 *
 * Float math, the shader's order; no checks (per texel).
 */
#ifndef MRGI_AREA_LIGHT_RSM_H
#define MRGI_AREA_LIGHT_RSM_H

#include "mrgi_area_light.h"
#include "mrgi_error.h"

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Light samples that light an area light's RSM texels (a 4 x 4 grid on a square light). */
#define MRGI_AREA_LIGHT_RSM_SAMPLES 16
/** Most RSM views of one area light (a two-sided light's six cube faces). */
#define MRGI_AREA_LIGHT_RSM_MAX_VIEWS 6

/**
 * @brief The view directions of `light`'s RSM (file comment, "Views"):
 *        n, +u, -u, +v, -v (unit vectors), and -n for a two-sided light.
 * @param light      A valid light (mrgi_area_light_check()).
 * @param directions Receives out_count unit directions.
 * @param out_count  Receives 5 (one-sided) or 6 (two-sided).
 * @return ::MRGI_ERR_INVALID_ARGUMENT for NULL outputs or a bad light
 *         (nothing written).
 */
mrgi_status mrgi_area_light_rsm_views(const mrgi_area_light* light,
                                      double directions[MRGI_AREA_LIGHT_RSM_MAX_VIEWS][3],
                                      int32_t* out_count, mrgi_error* err);

/**
 * @brief Flux of one RSM texel lit by an area light (file comment):
 *        flux = albedo * mrgi_area_light_diffuse(position, normal) * area.
 * @param light    Uniforms of the light (mrgi_area_light_uniforms_init()).
 * @param samples  `count` light samples.
 * @param position Surface point p the texel sees.
 * @param normal   Its normal (normalized inside; a zero normal gives 0).
 * @param albedo   Diffuse reflectance rgb.
 * @param area     Texel area A_t >= 0 (world units squared).
 * @param flux     Receives Phi_t rgb >= 0.
 */
void mrgi_area_light_rsm_texel(const mrgi_area_light_uniforms* light,
                               const mrgi_area_light_sample* samples, int32_t count,
                               const float position[3], const float normal[3],
                               const float albedo[3], float area, float flux[3]);

#ifdef __cplusplus
}
#endif

#endif
