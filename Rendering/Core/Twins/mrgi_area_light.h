/**
 * @file mrgi_area_light.h
 * @brief Rectangular area lights: the light, its texture pyramid, its light
 *        samples (the record shared by C and GLSL) and the per-receiver
 *        direct light without visibility, diffuse and Phong. C twins of the
 *        GPU area-light gather passes.
 *
 * Nichols, Penmatsa and Wyman 2010, "Interactive, Multiresolution
 * Image-Space Rendering for Dynamic Area Lighting" ([NPW10]), sections 3
 * (eq. 1 and 2), 3.1, 3.2 and 3.2.1; the disk-to-point form factor of
 * Nichols, Shopf and Wyman 2009 ([NSW09]) eq. 1, as in mrgi_gather.h.
 * Units and the VPL gather: Documentation/IndirectLight.md.
 *
 * ## The light
 *
 * A rectangle with centre c and FULL edge vectors u and v (world units; u
 * and v perpendicular), corners c +- u/2 +- v/2. One-sided lights emit on
 * the side of n = normalize(u x v) only; two-sided lights emit on both
 * sides (the same radiance). Texture coordinates (s, t) in [0, 1]^2 map to
 * the point c + (s - 1/2) u + (t - 1/2) v. Seen from the emitting side,
 * u points right and v up: the texture (an ::mrgi_image, row 0 = TOP) is
 * shown upright, not mirrored; its column x covers s in [x/W, (x+1)/W) and
 * its row y covers t in (1 - (y+1)/H, 1 - y/H].
 *
 * ## Units: what "intensity" means
 *
 * The light emits the radiance (Lambertian: the same in every direction of
 * its emitting half-space)
 *
 *     L(s, t) = intensity * color * T(s, t)
 *
 * where T is the texture read as a picture of texels, each a uniformly
 * emitting patch (T(s, t) = the RGB of the texel containing (s, t), like a
 * screen's pixels), and T = 1 without a texture. L is in VTK's units
 * (Documentation/IndirectLight.md section 1): the same units as the
 * radiance a surface shows on screen, since an emitter mesh of emission
 * E shows E. A receiver point p with unit normal N_p gets the "VTK
 * irradiance" (physical irradiance / pi)
 *
 *     X(p) = (1/pi) * integral over the light of L(y) cos_p cos_y / |y - p|^2 dA_y
 *
 * and a Lambertian receiver of albedo rho shows rho * X(p), exactly as it
 * shows rho * X for a vtkLight. Why radiance and not power: (1) it is the
 * only reading under which the light, the emitter mesh drawn for it and
 * the light it casts agree (the mesh shows L, a receiver enclosed by the
 * light shows rho * L); (2) with intensity 1 and white colour, a light
 * filling a receiver's hemisphere gives X = 1, the X a vtkLight of
 * intensity 1 gives at normal incidence, so intensities mean the same for
 * both kinds of light; (3) textures map to radiance directly (a video
 * frame is a picture of radiance). Unlike VTK's lights, an area light
 * falls off with distance: it is a physical emitter, and a tiny one is a
 * Lambertian point source of power Phi = L * A (VTK flux units, physical
 * flux / pi): X = Phi cos_p cos_y / (pi r^2), the formula of a VPL of zero
 * area in mrgi_gather.h. Doubling a light's size at fixed intensity doubles
 * its power.
 *
 * ## The texture pyramid
 *
 * A box-filtered mip pyramid of the texture ([NPW10] 3.1 and 3.2.1 read
 * the light texture "using a mipmap level" matching a footprint). Level 0
 * is the texture's RGB (a 4th channel, if any, is ignored); level k+1 has
 * the OpenGL mip size max(1, floor(W_k / 2)) x max(1, floor(H_k / 2)),
 * and there are 1 + floor(log2(max(W, H))) levels (OpenGL's full chain, so
 * the levels can be uploaded as the mip levels of one GL texture). Texel
 * (x, y) of level k+1 is the exact box average of level k over its
 * footprint [x r, (x+1) r) x [y q, (y+1) q), r = W_k / W_{k+1},
 * q = H_k / H_{k+1}, weighting each level-k texel by the fraction of it
 * inside (a plain 2x2 average when the sizes are even). Every level
 * therefore has the same mean as the texture, and for power-of-two sizes
 * a level-k texel is the exact mean of the 2^k x 2^k texels below it.
 *
 * Storage: levels one after another, level k at float offset offset[k],
 * 3 floats (RGB) per texel, rows top to bottom as in ::mrgi_image. Either
 * caller memory (mrgi_area_light_texture_pyramid_init(), at least
 * mrgi_area_light_texture_pyramid_float_count() floats, never freed by the
 * core) or memory the core allocates once
 * (mrgi_area_light_texture_pyramid_create(), released by
 * mrgi_area_light_texture_pyramid_destroy()). A light without texture has
 * a 1 x 1 pyramid holding (1, 1, 1).
 *
 * GPU: upload level k with glTexImage2D(GL_TEXTURE_2D, k, GL_RGB32F, W_k,
 * H_k, 0, GL_RGB, GL_FLOAT, texels + offset[k]) (GL_UNPACK_ALIGNMENT 4),
 * GL_TEXTURE_MAX_LEVEL = levels - 1, CLAMP_TO_EDGE, LINEAR_MIPMAP_LINEAR.
 * GL's first row is the picture's TOP row, so GLSL reads texture
 * coordinates (s, t) as texture(tex, vec2(s, 1.0 - t)).
 * mrgi_area_light_texture_sample() is the C twin of that lookup
 * (trilinear, OpenGL's formulas); hardware filtering quantizes its weights
 * (8 bits on current GPUs), so a shader that must match the C twin to 1e-4
 * does the 8 texelFetch()es itself.
 *
 * ## Light samples and the GPU sample texture
 *
 * [NPW10] eq. 2 turns the light into N samples y_j ("virtual point
 * lights", 3.1). The rectangle is cut into an sx x sy grid (sx cells along
 * u), cell (i, j) covering s in [i/sx, (i+1)/sx), t in [j/sy, (j+1)/sy):
 *
 *     sx = clamp(round(sqrt(N |u| / |v|)), 1, N),   sy = max(1, floor(N / sx))
 *
 * (cells as square as N and the aspect ratio allow; sx * sy <= N samples,
 * reported to the caller, e.g. all 256 of a square light, 4096 = 256 x 16
 * of a 16:1 light, 992 = 32 x 31 for N = 1000). Sample k = j * sx + i lies
 * at the cell's centre, or, with jitter, at a uniformly random point of the
 * cell (splitmix64 stream of the seed; deterministic for a seed). Its
 * record:
 *
 * - position: the sample point; normal: n (also for two-sided lights);
 * - area: A_j = |u x v| / (sx sy), the cell's area (the areas sum to the
 *   light's area);
 * - radiance: intensity * color * the pyramid read (trilinear) at the
 *   CELL CENTRE with lod = log2(max(W / sx, H / sy)) (clamped to the
 *   levels): the texture filtered at the level whose texel footprint
 *   matches the cell, so that a sample carries the mean radiance of its
 *   cell, not of one texel (for W / sx = H / sy = 2^k this is the cell's
 *   exact mean; otherwise the isotropic footprint of the longer cell side,
 *   as GL's own lod; the authors' code reads VPL flux from a mip level the
 *   same way). Cells smaller than texels (lod < 0) read the bilinear
 *   reconstruction of level 0 (GL's magnification): about the same flux
 *   overall, smoothed within a texel. Jitter moves positions, never
 *   radiances.
 *
 * A sample is ::MRGI_AREA_LIGHT_SAMPLE_TEXELS RGBA32F texels (one
 * ::mrgi_area_light_sample, ::MRGI_AREA_LIGHT_SAMPLE_FLOATS floats):
 * texel MRGI_AREA_LIGHT_SAMPLE_TEXEL_POSITION = position xyz + area A_j,
 * texel MRGI_AREA_LIGHT_SAMPLE_TEXEL_NORMAL   = unit normal xyz + 0,
 * texel MRGI_AREA_LIGHT_SAMPLE_TEXEL_RADIANCE = radiance rgb + 0.
 * An array of N records IS the GPU texture's memory: upload it as a 2D
 * RGBA32F texture MRGI_AREA_LIGHT_SAMPLE_TEXELS texels wide and N rows tall
 * (`glTexImage2D(..., MRGI_AREA_LIGHT_SAMPLE_TEXELS, N, 0, GL_RGBA,
 * GL_FLOAT, samples)`) and read sample j's texel k with
 * `texelFetch(samples, ivec2(k, j), 0)`. (Same shape as the VPL texture of
 * mrgi_vpl.h, with radiance where a VPL has flux: flux = radiance * area.)
 * What is per light rather than per sample (corners, normal, sidedness,
 * radiance scale, texture size) is in ::mrgi_area_light_uniforms, the
 * shader's uniforms.
 *
 * ## Direct light without visibility ([NPW10] 3.2)
 *
 * All positions and directions in one space (world, or any rigid image of
 * it: eye space after the view matrix; rigid maps keep areas, distances
 * and cosines). For receiver P with unit normal N (normalized here) and
 * sample j, d = y_j - P, r2 = d.d:
 *
 *     skip j when r2 == 0                              (direction undefined)
 *     cos_i_r = N.d;  cos_j_r = -n.d  (two-sided: |n.d|)  (cosines times r)
 *     skip j when cos_i_r <= 0 or cos_j_r <= 0         (receiver faces away,
 *                                                       or behind the light)
 *     T_j = A_j * (cos_i_r * cos_j_r / r2) / (pi * r2 + A_j)
 *     X  += radiance_j * T_j                            (diffuse, VTK irradiance)
 *
 * T_j is [NSW09] eq. 1's disk-to-point form factor F_j->P (the VPL gather's
 * term with flux = radiance * area, mrgi_gather.h), converging to the
 * integral of the section "Units" as the samples get small against r:
 * pi r^2 + A_j -> pi r^2. It is bounded, T_j < 1, however close the
 * receiver; the price is that a receiver much closer to the light than
 * the sample spacing sees too little of it (a light 1e4 times the scene's
 * size needs as many samples as it has "scene sizes" along an edge, or a
 * receiver distance comparable to its spacing).
 *
 * Two early-outs ([NPW10] 3.2) return 0 before the loop. Both are exact:
 * whenever they apply, every term of the loop is skipped anyway (samples
 * lie in the rectangle, which is the convex hull of its corners and lies
 * in the plane through c with normal n), so they change no result, up to
 * the float rounding of sample positions (a term they drop has a cosine of
 * rounding size):
 *
 * 1. receiver behind a one-sided light or in its plane: n.(P - c) <= 0
 *    (two-sided: n.(P - c) == 0) ("for one-sided lights ... we also
 *    discard fragments behind the source");
 * 2. receiver facing away from every corner C_k: N.(C_k - P) <= 0 for all
 *    four ("If N.L_j < 0 for all j, we trivially discard the fragment").
 *
 * No NaN: a receiver on a sample (r2 = 0), in the light's plane, with a
 * zero normal, or facing away gets finite (zero) terms.
 *
 * ## Phong specular ([NPW10] 3.2.1)
 *
 * VTK's vtkProperty Specular k_s, SpecularColor c_s and SpecularPower n
 * (VTK clamps n to [0, 128]) map to the energy-normalised Phong lobe
 * (Lafortune and Willems 1994, "Using the modified Phong reflectance model
 * for physically based rendering"):
 *
 *     f_s(w) = k_s c_s (n + 2) / (2 pi) * max(0, R.w)^n,   R = reflect(-V, N)
 *
 * V = unit direction from the receiver to the eye. VTK's own point-light
 * term k_s c_s (R.V)^n has no normalisation: integrated over an extended
 * light its highlight would dim as n grows. With the (n + 2) / (2 pi)
 * factor, a white light of radiance L filling the hemisphere reflects
 * exactly k_s c_s L at normal view for every n, and a sharp lobe reflects
 * the light's picture, k_s c_s L(y_R) cos(theta_R). The shown radiance is
 * L_s = k_s c_s S(P) with
 *
 *     S = sum_j radiance_j * ((n + 2) / 2) * max(0, R.w_j)^n * T_j
 *
 * (f_s L cos dw with cos_P dw_j = pi T_j, w_j = d / |d|); the composite
 * multiplies by k_s c_s, the diffuse term by the albedo; the two are
 * returned separately (separate GPU passes, [NPW10] 3.2.1). Around the
 * sample sum:
 *
 * - the two early-outs above (exact);
 * - lobe miss: S = 0 when the lobe's peak over the light,
 *   p = max over the rectangle of max(0, R.w)^n, is below
 *   ::MRGI_AREA_LIGHT_LOBE_DISCARD ("we discard fragments where the Phong
 *   lobe misses the light", tested by R hitting the light or the lobe at
 *   the light's outline). Not exact but bounded: it drops at most
 *   MRGI_AREA_LIGHT_LOBE_DISCARD * (n + 2) / 2 * X (X the diffuse term).
 *   p is exact: 1 when R hits the rectangle, else the largest cosine
 *   between R and a point of the four EDGES (the paper tests the corners
 *   only, which misses a lobe passing close to the middle of an edge);
 * - lobe sampling: when fewer than ::MRGI_AREA_LIGHT_LOBE_MIN_SAMPLES (9)
 *   samples lie inside the half-maximum cone (max(0, R.w_j)^n >=
 *   ::MRGI_AREA_LIGHT_LOBE_CUTOFF) and R reaches the light's plane, the sum
 *   over samples is replaced by a 5 x 5 grid (::MRGI_AREA_LIGHT_LOBE_GRID)
 *   around the point H where R meets the plane ("we directly sample the
 *   light texture 25 times inside the lobe using a mipmap level dependent
 *   on the lobe size"): the half-maximum cone cuts the plane in an ellipse
 *   with semi-axes t tan(theta_h) / max(|R.n|, ::MRGI_AREA_LIGHT_MIN_COS)
 *   along R's projection on the plane and t tan(theta_h) across it
 *   (t = distance from P to H along R, cos(theta_h) = 2^(-1/n)); its half
 *   extents h_u, h_v along the light's edges are the grid spacings. Cell
 *   (a, b), a, b in -2..2, is [H_u + (a - 1/2) h_u, H_u + (a + 1/2) h_u] x
 *   (same along v) clipped to the rectangle (skipped when empty); it acts
 *   as a sample at the clipped cell's centre, with the clipped area, the
 *   light's normal and radiance intensity * color * the pyramid read there
 *   with lod = log2(max(h_u W / |u|, h_v H / |v|)). With the spacing tied
 *   to the lobe, the grid follows the lobe however sharp; a lobe of
 *   infinite width (n = 0) keeps the sample sum.
 *
 * Refinement ([NPW10] 3.2.1: "image-space sample spacing must be denser
 * than the lobe width"): the lobe's cross-section at the light is
 * width = 2 t tan(theta_h) (::mrgi_area_light_lobe). Moving the receiver
 * by s moves the reflected point on the light by about s (1 + t / e) (a
 * flat mirror seen from distance e: the reflected ray pivots about the
 * mirrored eye), so samples of spacing s resolve the highlight when
 * s (1 + t / e) <= width, i.e. when the metric
 *
 *     m = s * (1 / e + 1 / t) / (2 tan(theta_h))
 *
 * is at most 1 (mrgi_area_light_phong_refinement(); 1 / t = 0 when R does
 * not reach the plane). s is the world size of a multiresolution texel at
 * the receiver (2^level pixels: s = 2^level * 2 e tan(fov / 2) / height
 * for a perspective camera), e the distance from the eye.
 *
 * ## Shadowed highlights ([NPW10] 3.3.1-3.3.3)
 *
 * mrgi_area_light_specular_visible() is mrgi_area_light_specular() with
 * visibility; the visibility itself is computed elsewhere (voxel marches,
 * mrgi_voxel_march.h; incremental masks and the variance shadow query,
 * mrgi_visibility_pyramid.h) and passed in, so that this stays the twin of
 * the specular shader alone:
 *
 * - the path (samples or lobe grid) is decided exactly as without
 *   visibility: samples_in_lobe counts every sample inside the half-maximum
 *   cone, visible or not (visibility changes the light that arrives, not
 *   how densely the light is sampled inside the lobe);
 * - sample path (glossy lobes): sample j's term is multiplied by its
 *   visibility bit, bit j & 31 of word j >> 5 of `sample_mask` (the layout
 *   of mrgi_visibility_pyramid.h section 1; "visibility from a fixed set of
 *   256 VPLs", 3.3.3);
 * - lobe-grid path (sharp lobes): cell (a, b)'s term is multiplied by a
 *   visibility in [0, 1] from `query_visibility`, G G - 1 floats (the
 *   variance shadow query's MRGI_VOXEL_VSM_QUERIES): cell (a, b) is query
 *   (b + G/2) G + (a + G/2) (mrgi_voxel_vsm_query_cell() is its inverse;
 *   "we send only 24 visibility queries (ignoring one corner on the 5 x 5
 *   grid)"). The paper does not say what the dropped corner (G/2, G/2)
 *   receives; here it takes the mean of its two edge neighbours in the
 *   grid, (G/2 - 1, G/2) and (G/2, G/2 - 1), the queried cells nearest to
 *   it, as far from the lobe's centre as it is along one axis (its lobe
 *   weight is small: about 2^-8 of the peak for a round footprint, 2^-4 at
 *   most, since the spacing is the half-maximum extent). Neither 1 (light
 *   leaking through a shadow's edge) nor 0 (a dark fringe on lit floors)
 *   would follow the shadow.
 *
 * NULL for either means visible (the unshadowed function, bit for bit).
 * mrgi_area_light_lobe_grid_cells() gives the cells' geometry, the points
 * the queries aim at; mrgi_area_light_specular_classify() the path alone.
 *
 * ## Precision
 *
 * The per-receiver functions compute in float, in the order written, with
 * the float library functions GLSL 1.50 has (sqrt, pow, exp2, log2,
 * floor), so that a shader translates them line by line; the GPU must agree
 * to 1e-4 relative error. Constants GLSL needs are in mrgi_glsl_defines().
 */
#ifndef MRGI_AREA_LIGHT_H
#define MRGI_AREA_LIGHT_H

#include "mrgi_error.h"
#include "mrgi_image.h"

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Fewest light samples a caller may request. */
#define MRGI_AREA_LIGHT_MIN_SAMPLES 1
/** Most light samples a caller may request or a gather may take (a 64 x 64 grid). */
#define MRGI_AREA_LIGHT_MAX_SAMPLES 4096
/** Light samples of [NPW10] ("we use 256 VPL samples"). */
#define MRGI_AREA_LIGHT_DEFAULT_SAMPLES 256
/** RGBA32F texels per light sample in the GPU sample texture. */
#define MRGI_AREA_LIGHT_SAMPLE_TEXELS 3
/** Texel holding position xyz and area A_j. */
#define MRGI_AREA_LIGHT_SAMPLE_TEXEL_POSITION 0
/** Texel holding the light's unit normal xyz (w = 0). */
#define MRGI_AREA_LIGHT_SAMPLE_TEXEL_NORMAL 1
/** Texel holding the radiance rgb (w = 0). */
#define MRGI_AREA_LIGHT_SAMPLE_TEXEL_RADIANCE 2
/** Floats per sample record (MRGI_AREA_LIGHT_SAMPLE_TEXELS RGBA texels). */
#define MRGI_AREA_LIGHT_SAMPLE_FLOATS 12
/** Largest |u.v| / (|u| |v|) accepted as perpendicular edges. */
#define MRGI_AREA_LIGHT_PERPENDICULAR_TOLERANCE 1e-6
/** Most pyramid levels: 1 + log2(MRGI_IMAGE_MAX_DIMENSION). */
#define MRGI_AREA_LIGHT_MAX_LEVELS 21
/** Lobe sampling grid side ([NPW10] 3.2.1: "a regular 5 x 5 grid"). */
#define MRGI_AREA_LIGHT_LOBE_GRID 5
/** Below this many samples inside the lobe, the lobe grid replaces the sample sum ([NPW10]: 9). */
#define MRGI_AREA_LIGHT_LOBE_MIN_SAMPLES 9
/** A sample is inside the lobe when max(0, R.w)^n is at least this (half maximum). */
#define MRGI_AREA_LIGHT_LOBE_CUTOFF 0.5f
/** Lobe miss: the specular term is 0 when the lobe's peak over the light is below this. */
#define MRGI_AREA_LIGHT_LOBE_DISCARD 1.0e-3f
/** Lower bound of |R.n| when the lobe's footprint is stretched over the light's plane. */
#define MRGI_AREA_LIGHT_MIN_COS 0.05f
/** Lobe grid: below this length of R's projection on the light's plane, the grid's first axis is u. */
#define MRGI_AREA_LIGHT_MIN_ALONG 1.0e-6f

/**
 * A rectangular area light (file comment: geometry, units, texture mapping).
 * Also the area light of ::mrgi_scene.
 */
typedef struct mrgi_area_light
{
  double center[3];          /**< Centre c of the rectangle, world units. */
  double edge_u[3];          /**< Full first edge u (not half), world units. */
  double edge_v[3];          /**< Full second edge v, perpendicular to u. */
  double color[3];           /**< Linear RGB, each >= 0. */
  double intensity;          /**< Radiance scale, >= 0: L = intensity * color * texture. */
  const mrgi_image* texture; /**< Borrowed RGB(A) float image, row 0 = top; NULL = uniform 1. */
  int two_sided;             /**< Non-zero: emits on both sides; else towards u x v only. */
} mrgi_area_light;

/**
 * @brief Check a light: every vector, colour and intensity finite; colour
 *        and intensity >= 0 and intensity * color within the float range;
 *        edges non-zero, perpendicular (::MRGI_AREA_LIGHT_PERPENDICULAR_TOLERANCE)
 *        and of a non-zero float area; a texture, if any, valid
 *        (mrgi_image_validate()), of 3 or 4 channels, with finite RGB >= 0.
 * @return ::MRGI_OK, or ::MRGI_ERR_INVALID_ARGUMENT with a message naming
 *         the field ("center", "edge_u", "color[1]", "intensity", "texture", ...).
 */
mrgi_status mrgi_area_light_check(const mrgi_area_light* light, mrgi_error* err);

/**
 * @brief The emitted radiance L(s, t) = intensity * color * T(s, t) (file
 *        comment): the texel containing (s, t) (s, t clamped to [0, 1]),
 *        without filtering. The ground truth the samples approximate.
 * @param light A light that passes mrgi_area_light_check() (not re-checked).
 */
void mrgi_area_light_emitted(const mrgi_area_light* light, double s, double t, double rgb[3]);

/* ---- texture pyramid ---- */

/** A box-filtered mip pyramid of a light's texture (file comment). */
typedef struct mrgi_area_light_texture_pyramid
{
  int32_t level_count;                         /**< 1..MRGI_AREA_LIGHT_MAX_LEVELS. */
  int32_t width[MRGI_AREA_LIGHT_MAX_LEVELS];   /**< W_k of each level. */
  int32_t height[MRGI_AREA_LIGHT_MAX_LEVELS];  /**< H_k of each level. */
  size_t offset[MRGI_AREA_LIGHT_MAX_LEVELS];   /**< First float of level k in `texels`. */
  float* texels;      /**< All levels, RGB, rows top to bottom; caller's or owned. */
  size_t float_count; /**< Floats used in `texels`. */
  int owned;          /**< 1 when `texels` was allocated by mrgi_area_light_texture_pyramid_create(). */
} mrgi_area_light_texture_pyramid;

/**
 * @brief Floats a pyramid of a width x height texture needs (all levels, RGB).
 * @return 0 when a size is outside 1..MRGI_IMAGE_MAX_DIMENSION.
 */
size_t mrgi_area_light_texture_pyramid_float_count(int64_t width, int64_t height);

/**
 * @brief Build the pyramid of `texture` in caller memory (nothing is allocated).
 * @param out           Receives the pyramid (borrowing `storage`, owned = 0);
 *                      zeroed on failure.
 * @param texture       The light's texture (checked as mrgi_area_light_check()
 *                      does), or NULL for a 1 x 1 pyramid holding (1, 1, 1).
 * @param storage       At least mrgi_area_light_texture_pyramid_float_count() floats.
 * @param storage_count Floats in `storage`.
 * @return ::MRGI_ERR_INVALID_ARGUMENT for NULL `out` or `storage`, a bad
 *         texture or too little storage (the message names the size needed).
 */
mrgi_status mrgi_area_light_texture_pyramid_init(mrgi_area_light_texture_pyramid* out,
                                                 const mrgi_image* texture, float* storage,
                                                 size_t storage_count, mrgi_error* err);

/**
 * @brief Allocate (once) and build the pyramid of `texture` (NULL: 1 x 1 white).
 * @param out Receives the pyramid (owned = 1); zeroed on failure.
 * @return As mrgi_area_light_texture_pyramid_init(), and ::MRGI_ERR_OUT_OF_MEMORY.
 */
mrgi_status mrgi_area_light_texture_pyramid_create(mrgi_area_light_texture_pyramid* out,
                                                   const mrgi_image* texture, mrgi_error* err);

/** @brief Free owned texels (never caller storage) and zero the struct. NULL-safe, idempotent. */
void mrgi_area_light_texture_pyramid_destroy(mrgi_area_light_texture_pyramid* pyramid);

/**
 * @brief Trilinear lookup at texture coordinates (s, t) and level of detail
 *        `lod`: the C twin of GLSL's textureLod(tex, vec2(s, 1.0 - t), lod)
 *        with the GPU settings of the file comment.
 *
 * lod is clamped to [0, level_count - 1]; levels k0 = floor(lod) and
 * k1 = min(k0 + 1, last) are read bilinearly (texel centres at
 * (x + 1/2) / W_k, clamp to edge) and mixed with weight lod - k0. Float
 * math. No checks (hot loop): a valid pyramid, finite s, t and lod.
 */
void mrgi_area_light_texture_sample(const mrgi_area_light_texture_pyramid* pyramid, float s,
                                    float t, float lod, float rgb[3]);

/* ---- light samples ---- */

/**
 * One light sample; the same 12 floats, in the same order, as its
 * MRGI_AREA_LIGHT_SAMPLE_TEXELS RGBA texels (checked at compile time).
 */
typedef struct mrgi_area_light_sample
{
  float position[3]; /**< Sample point y_j (texel MRGI_AREA_LIGHT_SAMPLE_TEXEL_POSITION, xyz). */
  float area;        /**< Cell area A_j > 0 (texel MRGI_AREA_LIGHT_SAMPLE_TEXEL_POSITION, w). */
  float normal[3];   /**< The light's unit normal n (texel MRGI_AREA_LIGHT_SAMPLE_TEXEL_NORMAL). */
  float pad0;        /**< Always 0. */
  float radiance[3]; /**< Mean radiance of the cell, >= 0 (texel MRGI_AREA_LIGHT_SAMPLE_TEXEL_RADIANCE). */
  float pad1;        /**< Always 0. */
} mrgi_area_light_sample;

/**
 * @brief The sample grid for a request (file comment): sx, sy and the
 *        number of samples sx * sy (<= requested_count).
 * @param light           A valid light (mrgi_area_light_check()).
 * @param requested_count MRGI_AREA_LIGHT_MIN_SAMPLES..MRGI_AREA_LIGHT_MAX_SAMPLES.
 * @param out_sx, out_sy, out_count Receive the grid; each may be NULL.
 * @return ::MRGI_ERR_INVALID_ARGUMENT for a bad light or count.
 */
mrgi_status mrgi_area_light_sample_layout(const mrgi_area_light* light, int32_t requested_count,
                                          int32_t* out_sx, int32_t* out_sy, int32_t* out_count,
                                          mrgi_error* err);

/**
 * @brief Stratified light samples with cell-filtered radiance (file comment).
 *
 * Positions are computed in double and stored as floats; radiance is
 * intensity * color * mrgi_area_light_texture_sample() at the cell centre.
 *
 * @param light           A valid light.
 * @param pyramid         Pyramid of light->texture (same level-0 size), or
 *                        NULL for a light without texture.
 * @param requested_count N, MRGI_AREA_LIGHT_MIN_SAMPLES..MRGI_AREA_LIGHT_MAX_SAMPLES.
 * @param jitter          0: cell centres; 1: one uniform point per cell.
 * @param seed            Jitter stream; the same seed gives the same samples.
 * @param samples         Receives sx * sy records (the GPU texture's memory).
 * @param capacity        Records `samples` can hold; at least sx * sy.
 * @param out_count       Receives sx * sy; may be NULL.
 * @return ::MRGI_ERR_INVALID_ARGUMENT for a bad light, count, jitter flag,
 *         capacity, a NULL `samples`, a missing or mismatched pyramid.
 *         Nothing is written on failure.
 */
mrgi_status mrgi_area_light_make_samples(const mrgi_area_light* light,
                                         const mrgi_area_light_texture_pyramid* pyramid,
                                         int32_t requested_count, int32_t jitter, uint64_t seed,
                                         mrgi_area_light_sample* samples, int32_t capacity,
                                         int32_t* out_count, mrgi_error* err);

/**
 * @brief The GPU sample texture's data for `samples`: MRGI_AREA_LIGHT_SAMPLE_FLOATS
 *        floats per sample (the same memory, no copy).
 */
static inline const float* mrgi_area_light_sample_texture_data(const mrgi_area_light_sample* samples)
{
  return (const float*)(const void*)samples;
}

/* ---- per-receiver direct light (C twins of the gather shaders) ---- */

/** What the gather shaders get per light as uniforms, in float. */
typedef struct mrgi_area_light_uniforms
{
  float center[3];      /**< c. */
  float normal[3];      /**< n = normalize(u x v). */
  float axis_u[3];      /**< u / |u|. */
  float axis_v[3];      /**< v / |v|. */
  float half_u;         /**< |u| / 2. */
  float half_v;         /**< |v| / 2. */
  float corners[4][3];  /**< c - u/2 - v/2, c + u/2 - v/2, c + u/2 + v/2, c - u/2 + v/2. */
  float area;           /**< |u x v|. */
  float scale[3];       /**< intensity * color: radiance = scale * texture. */
  int32_t two_sided;    /**< 0 or 1. */
  int32_t texture_width;  /**< Pyramid level-0 width (1 without texture). */
  int32_t texture_height; /**< Pyramid level-0 height (1 without texture). */
  int32_t texture_levels; /**< Pyramid levels (1 without texture). */
} mrgi_area_light_uniforms;

/**
 * @brief Fill the uniforms of `light` (geometry in double, stored as float).
 * @param pyramid Pyramid of light->texture, or NULL for a light without texture.
 * @return ::MRGI_ERR_INVALID_ARGUMENT for NULL `out`, a bad light, a missing
 *         or mismatched pyramid.
 */
mrgi_status mrgi_area_light_uniforms_init(const mrgi_area_light* light,
                                          const mrgi_area_light_texture_pyramid* pyramid,
                                          mrgi_area_light_uniforms* out, mrgi_error* err);

/**
 * @brief Diffuse direct light without visibility: the VTK irradiance X at a
 *        receiver (file comment, [NPW10] 3.2). The receiver shows albedo * X.
 *
 * No checks (per receiver): valid uniforms, `count` records, finite inputs.
 * @param position Receiver P.
 * @param normal   Receiver normal (normalized here; a zero normal gives 0).
 * @param out      Receives X rgb, >= 0.
 */
void mrgi_area_light_diffuse(const mrgi_area_light_uniforms* light,
                             const mrgi_area_light_sample* samples, int32_t count,
                             const float position[3], const float normal[3], float out[3]);

/** The Phong lobe of a receiver relative to a light ([NPW10] 3.2.1). */
typedef struct mrgi_area_light_lobe
{
  float reflect[3];       /**< R = reflect(-V, N), unit. */
  float peak;             /**< max over the rectangle of max(0, R.w)^n, in [0, 1]. */
  float tan_half;         /**< tan(theta_h), cos(theta_h) = 2^(-1/n); FLT_MAX when n = 0. */
  int32_t reaches_plane;  /**< 1 when R meets the light's plane at some t > 0. */
  int32_t hits_light;     /**< 1 when it meets it inside the rectangle. */
  float distance;         /**< t (0 when !reaches_plane). */
  float inverse_distance; /**< 1 / t (0 when !reaches_plane). */
  float width;            /**< Cross-section 2 t tan(theta_h) at the light; FLT_MAX when !reaches_plane or unbounded. */
  float hit_u;            /**< (H - c).axis_u of the plane point H (0 when !reaches_plane). */
  float hit_v;            /**< (H - c).axis_v. */
} mrgi_area_light_lobe;

/**
 * @brief The lobe of receiver P (normal N, towards-eye direction V, both
 *        normalized here) for Phong power n >= 0 (file comment).
 *
 * A zero N or V gives a lobe with peak 0 (nothing reflected).
 */
void mrgi_area_light_phong_lobe(const mrgi_area_light_uniforms* light, const float position[3],
                                const float normal[3], const float view[3], float power,
                                mrgi_area_light_lobe* out);

/**
 * @brief The lobe-size refinement metric m = s (1/e + 1/t) / (2 tan(theta_h))
 *        (file comment); refine where m > 1.
 * @param lobe         From mrgi_area_light_phong_lobe().
 * @param eye_distance e > 0: receiver's distance from the eye.
 * @param texel_size   s >= 0: world size of the texel at the receiver.
 * @return m >= 0 (0 for an unbounded lobe, n = 0; FLT_MAX for e <= 0).
 */
float mrgi_area_light_phong_refinement(const mrgi_area_light_lobe* lobe, float eye_distance,
                                       float texel_size);

/** Which way mrgi_area_light_specular() computed its value. */
typedef enum mrgi_area_light_specular_path
{
  MRGI_AREA_LIGHT_SPECULAR_SAMPLES = 0, /**< Sum over the light samples. */
  MRGI_AREA_LIGHT_SPECULAR_LOBE_GRID,   /**< 5 x 5 lobe grid (too few samples in the lobe). */
  MRGI_AREA_LIGHT_SPECULAR_BEHIND,      /**< Early-out 1: behind a one-sided light or in its plane. */
  MRGI_AREA_LIGHT_SPECULAR_FACING_AWAY, /**< Early-out 2: facing away from every corner (or zero normal/view). */
  MRGI_AREA_LIGHT_SPECULAR_LOBE_MISS    /**< Lobe peak below MRGI_AREA_LIGHT_LOBE_DISCARD. */
} mrgi_area_light_specular_path;

/** What one specular evaluation did, for tests and debugging views. */
typedef struct mrgi_area_light_specular_info
{
  mrgi_area_light_specular_path path;
  int32_t samples_in_lobe; /**< Samples with max(0, R.w)^n >= MRGI_AREA_LIGHT_LOBE_CUTOFF (0 after an early-out). */
  int32_t grid_cells;      /**< Lobe grid cells that overlapped the light (lobe grid path). */
  mrgi_area_light_lobe lobe; /**< The lobe (zeroed after early-outs 1 and 2). */
} mrgi_area_light_specular_info;

/**
 * @brief Phong specular direct light without visibility: S with
 *        L_s = k_s * c_s * S (file comment, [NPW10] 3.2.1).
 *
 * No checks (per receiver): valid uniforms, `count` records, finite inputs.
 * @param pyramid  The light's pyramid for the lobe grid; NULL reads 1 (untextured).
 * @param position Receiver P.
 * @param normal   Receiver normal N (normalized here).
 * @param view     Direction from P towards the eye V (normalized here).
 * @param power    Phong exponent n >= 0 (vtkProperty::SpecularPower).
 * @param out      Receives S rgb, >= 0.
 * @param info     Receives what was done; may be NULL.
 */
void mrgi_area_light_specular(const mrgi_area_light_uniforms* light,
                              const mrgi_area_light_sample* samples, int32_t count,
                              const mrgi_area_light_texture_pyramid* pyramid,
                              const float position[3], const float normal[3], const float view[3],
                              float power, float out[3], mrgi_area_light_specular_info* info);

/**
 * @brief mrgi_area_light_specular() with visibility (file comment, "Shadowed
 *        highlights").
 * @param sample_mask      mrgi_voxel_mask_words(count) words, sample j = bit
 *                         j & 31 of word j >> 5 (1 visible), or NULL (all visible).
 * @param query_visibility MRGI_AREA_LIGHT_LOBE_GRID^2 - 1 floats in [0, 1],
 *                         cell (a, b) = query (b + G/2) G + (a + G/2), the
 *                         corner (G/2, G/2) the mean of queries G G - 2 and
 *                         G G - 1 - G; or NULL (all visible).
 * Other parameters as mrgi_area_light_specular(); `info` is the same as
 * without visibility.
 */
void mrgi_area_light_specular_visible(const mrgi_area_light_uniforms* light,
                                      const mrgi_area_light_sample* samples, int32_t count,
                                      const mrgi_area_light_texture_pyramid* pyramid,
                                      const float position[3], const float normal[3],
                                      const float view[3], float power, const uint32_t* sample_mask,
                                      const float* query_visibility, float out[3],
                                      mrgi_area_light_specular_info* info);

/**
 * @brief What mrgi_area_light_specular() decides before summing: the path,
 *        samples_in_lobe, grid_cells and the lobe, as its `info` (file
 *        comment). The GPU's variance shadow query pass needs the path
 *        alone (it marches toward the lobe grid's cells only).
 */
void mrgi_area_light_specular_classify(const mrgi_area_light_uniforms* light,
                                       const mrgi_area_light_sample* samples, int32_t count,
                                       const float position[3], const float normal[3],
                                       const float view[3], float power,
                                       mrgi_area_light_specular_info* info);

/** Cells of the lobe grid (G x G). */
#define MRGI_AREA_LIGHT_LOBE_CELLS (MRGI_AREA_LIGHT_LOBE_GRID * MRGI_AREA_LIGHT_LOBE_GRID)

/**
 * The lobe grid of one receiver (file comment, "Phong specular"): cell
 * (a, b), a, b in -G/2..G/2, is entry (b + G/2) G + (a + G/2) (rows of
 * constant b, a fastest: the order of the sum).
 */
typedef struct mrgi_area_light_lobe_grid
{
  float spacing_u;  /**< h_u: the cells' size along u before clipping. */
  float spacing_v;  /**< h_v. */
  float lod;        /**< Pyramid level of detail of the cells' texture reads. */
  int32_t cells;    /**< Cells on the light (grid_cells of the info). */
  int32_t on_light[MRGI_AREA_LIGHT_LOBE_CELLS]; /**< 1: the clipped cell is not empty. */
  float u[MRGI_AREA_LIGHT_LOBE_CELLS];    /**< Clipped cell centre, (y - c).axis_u (0 when off the light). */
  float v[MRGI_AREA_LIGHT_LOBE_CELLS];    /**< ... (y - c).axis_v. */
  float area[MRGI_AREA_LIGHT_LOBE_CELLS]; /**< Clipped cell area (0 when off the light). */
  float position[MRGI_AREA_LIGHT_LOBE_CELLS][3]; /**< The centre c + u axis_u + v axis_v, the light's space. */
} mrgi_area_light_lobe_grid;

/**
 * @brief The lobe grid of `lobe` (from mrgi_area_light_phong_lobe(), with
 *        reaches_plane), in float as the specular sum computes it.
 * @return 1, or 0 (grid zeroed) when the lobe has no finite footprint (the
 *         specular then keeps the sample sum).
 */
int mrgi_area_light_lobe_grid_cells(const mrgi_area_light_uniforms* light,
                                    const mrgi_area_light_lobe* lobe,
                                    mrgi_area_light_lobe_grid* grid);

#ifdef __cplusplus
}
#endif

#endif
