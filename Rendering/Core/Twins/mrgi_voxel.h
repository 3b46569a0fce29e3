/**
 * @file mrgi_voxel.h
 * @brief Screen-space voxels: the bit layout (128 to 512 slices), the depth
 *        slicing, the voxel buffer's resolution and its mapping from window
 *        pixels, the camera projection the march uses, and the C twin of the
 *        voxelization pass (rasterized fragments OR-ed into the buffer).
 *
 * Paper: Nichols, Penmatsa and Wyman 2010, "Interactive, Multiresolution
 * Image-Space Rendering for Dynamic Area Lighting" (NPW10), section 3.3
 * (screen-space voxelization after Dong et al. 2004 [DCB*04] and Eisemann
 * and Decoret 2006 [ED06]; Figure 2) and section 4.2 ("All our results use
 * 128 bits of depth, via a 32-bit per channel buffer"; a 128^2 x 128 buffer
 * is "almost indistinguishable" from 1024^2 x 128). The ray march is in
 * mrgi_voxel_march.h, the incremental visibility in mrgi_visibility_pyramid.h.
 * Every rule below is the GPU contract (OpenGL 3.2 core, GLSL 1.50: RGBA32UI
 * targets, integer and bitwise ops; no image load/store, no atomics); the
 * constants reach GLSL through mrgi_glsl_defines().
 *
 * ## 1. Bit layout (defined once)
 *
 * A voxel pixel holds S one-bit voxels, one per depth slice, S = 128 L for
 * L = 1..MRGI_VOXEL_MAX_LAYERS layers (S = 128, 256, 384 or 512;
 * mrgi_voxel_grid::slices, default MRGI_VOXEL_DEFAULT_SLICES = 128). A layer
 * is MRGI_VOXEL_LAYER_SLICES = 128 slices in MRGI_VOXEL_CHANNELS = 4
 * unsigned 32-bit channels (R, G, B, A of an RGBA32UI texel); on the GPU
 * layer l is layer l of a 2D array texture, written as the l-th render
 * target of one draw (NPW10 3.3: "more bits may be obtained using multiple
 * render targets"). Slice s, 0 <= s < S, is
 *
 *     layer l = s >> 7,   channel c = (s >> 5) & 3,   bit b = s & 31,
 *
 * i.e. word s >> 5 of the pixel's 4 L words: slice 0 (nearest) is bit 0 of
 * layer 0's R, slice S - 1 (farthest) bit 31 of layer L - 1's A.
 * A bit is 1 when some surface passes through that voxel.
 *
 * Why more than 128 (beyond NPW10 4.2's "128 bits of depth"): a voxel is
 * as fat as its slice, and the march's bias and its thickened rays
 * (mrgi_voxel_march.h) scale with the voxel. In a deep view 128 slices are
 * several centimetres each, and rays passing an object's edge at less than
 * a slice are hidden (Documentation/AreaLights.md measures the slices).
 *
 * ## 2. Depth slicing: uniform in linear eye depth over [near, far]
 *
 * Depth is linear eye-space depth d = -z_eye (VTK eye space looks down -z;
 * the same for parallel projection). The range [near, far] is the caller's:
 * the depth range of the visible scene (e.g. the G-buffer's min and max, the
 * coarsest multires texel's (dmin, dmax)) widened to include the area
 * light's corners, within the camera's clipping range. With
 * scale = S / (far - near), rounded to float (the shader's uniform), the
 * slice of depth d is
 *
 *     slice(d) = int(clamp((d - near) * scale, 0.0, float(S - 1)))   (float math)
 *
 * i.e. floor((d - near) / thickness) clamped to 0..S-1, thickness
 * (far - near) / S; slice(near) = 0, slice(far) = S - 1 (the top end is
 * closed). NaN maps to 0 in the C twin (fmaxf returns the non-NaN operand);
 * callers never pass NaN (the functions below drop such fragments first).
 *
 * Why uniform in linear depth (not in 1/d like the z-buffer): the paper's
 * voxels are equal "quanta of depth" (Figure 2) and ED06 slice the depth
 * range uniformly; uniform slices make (a) a depth interval a contiguous
 * range of bits from one multiply-add per end (the march tests whole
 * intervals, mrgi_voxel_march.h), (b) the voxel depth thickness the same
 * everywhere, so a self-occlusion bias in voxel units is one eye-space
 * distance for the whole frame (NPW10 4.3), (c) with [near, far] fitted to
 * the scene (not the clipping planes) few of the S bits are wasted; a
 * 1/d slicing would spend most bits just in front of the camera.
 *
 * Fragments outside [near, far] are dropped (on the GPU the voxelization
 * pass's projection uses near and far as clipping planes; GL clips -w <= z <= w
 * inclusively, so d == near and d == far are kept).
 *
 * ## 3. Voxel buffer resolution and the window -> voxel pixel mapping
 *
 * The buffer is VW x VH voxel pixels, 1..MRGI_VOXEL_MAX_SIZE per side,
 * independent of the W x H window (NPW10 4.2: 128^2 .. 1024^2;
 * MRGI_VOXEL_DEFAULT_SIZE = 128; "up to full resolution" is the useful range,
 * larger is allowed). vtkMRGIVoxelization chooses it by default with
 * mrgi_voxel_isotropic_size() (voxels about as wide as deep). It covers the same view frustum as
 * the window (same projection, the viewport is VW x VH), so window pixel (x, y) maps to the voxel
 * pixel whose area contains the window pixel's centre:
 *
 *     vx = ((2 x + 1) VW) / (2 W),   vy = ((2 y + 1) VH) / (2 H)   (integer division)
 *
 * = floor((x + 0.5) VW / W), exact in 32-bit integers for sides up to
 * MRGI_VOXEL_MAX_SIZE. Every voxel pixel receives floor(W/VW) or
 * ceil(W/VW) window columns when VW <= W.
 *
 * Storage: uint32 words, row-major, row 0 = BOTTOM (OpenGL order), the
 * 4 L words of texel (x, y) together: word 4 L (y VW + x) + (s >> 5) holds
 * slice s (layer l's channel c at 4 L (y VW + x) + 4 l + c). 4 L VW VH
 * words in all (mrgi_voxel_buffer_words()); 256 KiB per layer at 128^2,
 * 4 MiB per layer at 512^2.
 *
 * ## 4. Projection (eye space -> voxel pixel coordinates)
 *
 * A plain struct: normalized device coordinates are
 *
 *     ndc_x = scale_x x / w + offset_x,  ndc_y = scale_y y / w + offset_y,
 *     w = d (perspective) or 1 (parallel),
 *
 * i.e. an OpenGL projection matrix's P00, P11 and offsets -P02, -P12
 * (perspective) or P03, P13 (parallel); continuous voxel coordinates are
 * u = (ndc_x + 1) VW / 2, v = (ndc_y + 1) VH / 2 (the viewport transform),
 * and the voxel pixel is (floor(u), floor(v)). The centre of window pixel
 * x is at ndc (2x + 1) / W - 1, which gives u = (x + 0.5) VW / W: the
 * integer mapping of section 3.
 *
 * ## 5. Voxelization (the C twin of the rasterization pass)
 *
 * The GPU draws every surface (hidden ones too: no depth test) into the
 * RGBA32UI target of VW x VH with glLogicOp(GL_OR); each fragment writes
 * the 4-channel mask of the slices its surface spans over the pixel. The
 * conservative choices made here:
 *
 * - a fragment sets the bits of the depth interval [d - h, d + h],
 *   h = its half depth span over the pixel, in GLSL
 *   h = 0.5 fwidth(d) = 0.5 (|dFdx(d)| + |dFdy(d)|) (exactly half the depth
 *   range of a planar surface over the pixel square), not only the bit of
 *   its centre depth: a surface steep in depth (seen at a grazing angle)
 *   would otherwise leave empty slices between neighbouring pixels that a
 *   ray slips through. h = 0 sets one bit.
 * - that interval is clamped to the primitive's own depth range
 *   [dmin, dmax] (the min and max eye depth of the triangle's vertices,
 *   passed by a geometry shader as flat varyings; GL 3.2 core has geometry
 *   shaders): near a triangle's edge the plane extended over the whole
 *   pixel reaches depths the triangle never has, and an obliquely seen face
 *   would grow a "skirt" in front of and behind the object. TestVoxel's
 *   random box scenes: false occlusions at 128^2 fall from 9.7% to 2.5% of
 *   the rays with the clamp.
 * - [dmin, dmax] is the depth range of the triangle CLIPPED TO THE PIXEL
 *   SQUARE (mrgi_voxel_triangle_pixel_range(); the fragment stage gets the
 *   three vertices from the geometry shader), not the whole triangle's:
 *   a large face seen edge-on (the tall Cornell block's top, seen from
 *   below) covers one or two voxel rows, and with the whole triangle's
 *   range every pixel of those rows held the depths of the face's nearest
 *   corner, a slab in front of the face's edge there that shadowed rays
 *   leaving the block's front face (cornell-area, 128^2 voxels: the dark
 *   smear on the tall block's front). When the clipped polygon is empty
 *   (float rounding at an edge) or a vertex is at or behind the eye, the
 *   whole triangle's range is used.
 *
 * A fragment at d in [near, far] writes, to each layer l < L,
 *
 *     h'   = h > 0 ? h : 0                                   (NaN -> 0)
 *     lo   = min(max(d - h', dmin), d),  hi = max(min(d + h', dmax), d)
 *     mask_l = range_mask(slice(lo) - 128 l, slice(hi) - 128 l)
 *
 * (the centre depth is always kept, even when rounding puts it just
 * outside [dmin, dmax]; the interval is clipped to the range by slice()'s
 * clamp); other fragments write nothing. dmin = -FLT_MAX, dmax = FLT_MAX
 * turns the clamp off (in C, NaN does too). The GPU fragment shader, the
 * blend and this twin agree bit for bit except where lo or hi lies within
 * float rounding of a slice boundary (derivatives come from 2x2 quads on
 * the GPU).
 *
 * What a surface voxelization cannot hold (NPW10 4.3: "our method yields
 * best results for geometry occupying multiple voxels"): only surfaces get
 * bits, not the inside of objects (OR, not the XOR solid voxelization of
 * ED08), and without conservative rasterization (not in GL 3.2) a face
 * gets fragments only where it covers a pixel centre. An object thinner
 * than a voxel pixel seen edge-on therefore has voxels at its front and
 * back faces only, and a ray crossing it at mid depth passes (TestVoxel
 * prints this case).
 *
 * range_mask(lo, hi) (mrgi_voxel_range_mask()): the slices lo..hi of one
 * layer (numbered 0..127 within it), inclusive, clamped to 0..127, empty
 * when lo > hi; per channel c with
 * a = max(lo - 32c, 0), b = min(hi - 32c, 31):
 * (0xFFFFFFFF >> (31 - b)) & (0xFFFFFFFF << a) when a <= b, else 0 (no shift
 * by 32, which GLSL and C leave undefined).
 */
#ifndef MRGI_VOXEL_H
#define MRGI_VOXEL_H

#include "mrgi_error.h"
#include "mrgi_multires.h"

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Depth slices (bits) per layer, one RGBA32UI texel (NPW10 4.2: 128). */
#define MRGI_VOXEL_LAYER_SLICES 128
/** Most layers (render targets) per voxel pixel: up to 512 slices (section 1). */
#define MRGI_VOXEL_MAX_LAYERS 4
/** Most slices per voxel pixel. */
#define MRGI_VOXEL_MAX_SLICES (MRGI_VOXEL_LAYER_SLICES * MRGI_VOXEL_MAX_LAYERS)
/** Default slices per voxel pixel (NPW10 4.2: 128, one layer). */
#define MRGI_VOXEL_DEFAULT_SLICES 128
/**
 * Slices of the area lights' voxels in vtkMRGIPass (two layers): at the
 * same voxel side they cost the march little and thin the voxels that
 * hide penumbrae (Documentation/AreaLights.md, "Depth slices").
 */
#define MRGI_VOXEL_AREA_LIGHT_SLICES 256
/**
 * Slices of the VPL visibility's voxels (vtkMRGIIndirectLight, four
 * layers): rays from VPLs to receivers run along the view's depth, where
 * deep slices make surfaces occlude themselves; the fewer slices cost most
 * in deep scenes (Documentation/IndirectShadows.md, "Session 21").
 */
#define MRGI_VOXEL_INDIRECT_SLICES 512
/** Unsigned 32-bit channels per layer (RGBA32UI). */
#define MRGI_VOXEL_CHANNELS 4
/** Most words per voxel pixel. */
#define MRGI_VOXEL_MAX_WORDS (MRGI_VOXEL_CHANNELS * MRGI_VOXEL_MAX_LAYERS)
/** Bits per channel; slice s is in channel s / 32, bit s % 32. */
#define MRGI_VOXEL_CHANNEL_BITS 32
/** Largest voxel buffer side (keeps (2x+1) VW within 32-bit ints; GL's usual texture limit). */
#define MRGI_VOXEL_MAX_SIZE 16384
/** Margin of mrgi_voxel_fit_depth_range(), as a fraction of the box's depth range per side. */
#define MRGI_VOXEL_FIT_MARGIN 0.01
/** Default voxel buffer side (NPW10 4.2). */
#define MRGI_VOXEL_DEFAULT_SIZE 128

/** The voxel buffer's size and depth slicing (sections 1-3). Plain data, from mrgi_voxel_grid_init(). */
typedef struct mrgi_voxel_grid
{
  int32_t width;    /**< VW, 1..MRGI_VOXEL_MAX_SIZE. */
  int32_t height;   /**< VH, 1..MRGI_VOXEL_MAX_SIZE. */
  int32_t slices;   /**< S: 128 L, L = 1..MRGI_VOXEL_MAX_LAYERS (section 1). */
  float near_depth; /**< Linear eye depth of the front of slice 0 (float, finite). */
  float far_depth;  /**< Linear eye depth of the back of slice S - 1 (float, finite, > near). */
  float slice_scale; /**< S / (far - near) as float, finite > 0 (the shader's uniform). */
} mrgi_voxel_grid;

/**
 * @brief Set up a VW x VH grid of S slices over [near, far] (sections 1-3).
 * @param grid   Receives the grid; zeroed on failure.
 * @param width  VW, 1..MRGI_VOXEL_MAX_SIZE.
 * @param height VH, 1..MRGI_VOXEL_MAX_SIZE.
 * @param slices S: 128, 256, 384 or 512 (a multiple of MRGI_VOXEL_LAYER_SLICES
 *               up to MRGI_VOXEL_MAX_SLICES).
 * @param near_depth,far_depth Linear eye depths; finite as floats, near < far
 *               after rounding to float, and S / (far - near) finite and > 0
 *               as a float. Negative depths are allowed (parallel projection);
 *               the march requires near > 0 for perspective (mrgi_voxel_march.h).
 * @return ::MRGI_ERR_INVALID_ARGUMENT for NULL `grid`, a zero, negative or too
 *         large size, a slice count that is not a multiple of 128 in
 *         128..512, NaN/infinite depths, near == far ("empty depth range"),
 *         far < near ("reversed"), or a range too small or too large for float.
 */
mrgi_status mrgi_voxel_grid_init(mrgi_voxel_grid* grid, int32_t width, int32_t height,
  int32_t slices, double near_depth, double far_depth, mrgi_error* err);

/**
 * @brief Check that `grid` is what mrgi_voxel_grid_init() makes for its own
 *        size and range (every function taking a grid runs this once).
 * @return ::MRGI_ERR_INVALID_ARGUMENT for NULL or a modified grid.
 */
mrgi_status mrgi_voxel_grid_check(const mrgi_voxel_grid* grid, mrgi_error* err);

/**
 * @brief Fit the slicing range to the scene: the eye-depth range of the
 *        eight corners of a world-space box (the visible props' bounds),
 *        widened by MRGI_VOXEL_FIT_MARGIN of its length on each side and
 *        intersected with the camera's clipping range [clip[0], clip[1]].
 *
 * Why (section 2: "[near, far] fitted to the scene, not the clipping
 * planes"): VTK's automatic clipping range pads the scene's depth range
 * (cornell-area at 256^2: [512, 1796] mm for a box seen over about
 * [800, 1360] mm), so more than half the 128 slices held nothing and each
 * slice was 10 mm where 4.5 mm do. A slice is the voxel's depth, and the
 * march's bias and its thickened rays (mrgi_voxel_march.h) scale with it:
 * thick slices darken every ray that passes near an occluder.
 *
 * Every surface the voxelization draws lies inside the box, so no voxel
 * is lost; depths outside the box hold no voxels either way.
 *
 * @param world_to_eye Row-major 4x4 (vtkMatrix4x4's element order); only
 *               row 2 (eye z) is read; depth d = -z_eye.
 * @param bounds (xmin, xmax, ymin, ymax, zmin, zmax); an uninitialised box
 *               (xmin > xmax, VTK's (1, -1, ...)) or a non-finite value
 *               returns the clipping range unchanged.
 * @param clip   The clipping range, finite, clip[0] < clip[1].
 * @param range  Receives [near, far]: within clip, near < far; the clipping
 *               range when the box lies outside it or its depth range is
 *               too thin to slice (far - near <= 1e-6 (clip[1] - clip[0])).
 * @return ::MRGI_ERR_INVALID_ARGUMENT for NULL pointers, a non-finite matrix
 *         row or an invalid clipping range.
 */
mrgi_status mrgi_voxel_fit_depth_range(const double world_to_eye[16], const double bounds[6],
                                       const double clip[2], double range[2], mrgi_error* err);

/** @brief Words of the voxel buffer: 4 L VW VH; 0 for NULL. */
size_t mrgi_voxel_buffer_words(const mrgi_voxel_grid* grid);

/** @brief Layers L = S / 128 of a valid grid (section 1). */
static inline int32_t mrgi_voxel_layers(const mrgi_voxel_grid* grid)
{
  return grid->slices / MRGI_VOXEL_LAYER_SLICES;
}

/** @brief Words per voxel pixel, 4 L. */
static inline int32_t mrgi_voxel_pixel_words(const mrgi_voxel_grid* grid)
{
  return mrgi_voxel_layers(grid) * MRGI_VOXEL_CHANNELS;
}

/** @brief Word index of layer 0's channel 0 of voxel pixel (x, y). No checks (hot loops). */
static inline size_t mrgi_voxel_index(const mrgi_voxel_grid* grid, int32_t x, int32_t y)
{
  return ((size_t)y * (size_t)grid->width + (size_t)x) * (size_t)mrgi_voxel_pixel_words(grid);
}

/** @brief Slice of linear depth d (section 2): int(clamp((d - near) scale, 0, S - 1)). */
int32_t mrgi_voxel_slice(const mrgi_voxel_grid* grid, float depth);

/** @brief Word of slice s within its pixel's 4 L words (s >> 5; layer s >> 7, channel (s >> 5) &
 * 3). */
static inline int32_t mrgi_voxel_slice_channel(int32_t slice)
{
  return slice >> 5;
}

/** @brief Bit of slice s in its channel (s & 31). */
static inline int32_t mrgi_voxel_slice_bit(int32_t slice)
{
  return slice & 31;
}

/** @brief Linear depth at the middle of slice s: near + (s + 0.5) / scale (double). */
double mrgi_voxel_slice_center(const mrgi_voxel_grid* grid, int32_t slice);

/**
 * @brief One layer's mask of its slices lo..hi (numbered 0..127 within the
 *        layer) inclusive, clamped to 0..127; all zero when lo > hi (section
 *        5). Layer l of a range [a, b] of the whole pixel is
 *        range_mask(a - 128 l, b - 128 l).
 */
void mrgi_voxel_range_mask(int32_t lo, int32_t hi, uint32_t mask[MRGI_VOXEL_CHANNELS]);

/**
 * @brief Voxel pixel of window pixel `x` along one axis (section 3):
 *        ((2x + 1) voxel_size) / (2 window_size). Arguments are not checked:
 *        0 <= x < window_size, both sizes 1..MRGI_VOXEL_MAX_SIZE.
 */
static inline int32_t mrgi_voxel_pixel_from_window(int32_t x, int32_t window_size,
                                                   int32_t voxel_size)
{
  return (int32_t)(((int64_t)(2 * x + 1) * voxel_size) / (2 * (int64_t)window_size));
}

/** Camera projection (section 4). Plain data. */
typedef struct mrgi_voxel_projection
{
  int32_t parallel; /**< 0: perspective (w = d), 1: parallel (w = 1). */
  float scale_x;    /**< P00: finite > 0. */
  float scale_y;    /**< P11: finite > 0. */
  float offset_x;   /**< -P02 (perspective) or P03 (parallel): finite. */
  float offset_y;   /**< -P12 (perspective) or P13 (parallel): finite. */
} mrgi_voxel_projection;

/**
 * @brief Projection of a VTK-style camera (centred window).
 * @param camera Perspective view angle (vertical, degrees, (0, 180)) or parallel
 *               scale (half view height, finite > 0), as in mrgi_multires.h.
 * @param aspect Window width / height, finite > 0.
 * @return ::MRGI_ERR_INVALID_ARGUMENT for NULL pointers or values out of range.
 */
mrgi_status mrgi_voxel_projection_from_camera(mrgi_voxel_projection* projection,
                                              const mrgi_multires_projection* camera,
                                              double aspect, mrgi_error* err);

/**
 * @brief Projection from an OpenGL projection matrix (column-major, element
 *        (row, col) at m[4 col + row]): perspective when the last row is
 *        (0, 0, -1, 0), parallel when it is (0, 0, 0, 1).
 * @return ::MRGI_ERR_INVALID_ARGUMENT for NULL, another last row, non-finite
 *         values, or a non-positive P00 or P11 (mirrored views are not supported).
 */
mrgi_status mrgi_voxel_projection_from_matrix(mrgi_voxel_projection* projection,
                                              const double matrix[16], mrgi_error* err);

/** @brief Check a projection's fields (section 4). ::MRGI_ERR_INVALID_ARGUMENT naming the field. */
mrgi_status mrgi_voxel_projection_check(const mrgi_voxel_projection* projection,
                                        mrgi_error* err);

/** Automatic voxel buffer side (mrgi_voxel_isotropic_size()): least, largest, and the step it is rounded to. */
#define MRGI_VOXEL_AUTO_MIN_SIZE MRGI_VOXEL_DEFAULT_SIZE
#define MRGI_VOXEL_AUTO_MAX_SIZE 512
#define MRGI_VOXEL_AUTO_STEP 16

/**
 * @brief The voxel buffer size whose voxels are about as wide as they are
 *        deep: at the middle depth of [near, far], a voxel pixel's eye-space
 *        width (height) equals the slice thickness (far - near) / S.
 *
 * Why (beyond NPW10, whose 128^2 default is one fixed size for every
 * scene): the march's bias and its conservative intervals work in voxel
 * sizes, the larger of the pixel's eye-space size and the slice thickness
 * (mrgi_voxel_march.h, step 3), so a shadow is only as sharp as the
 * coarser of the two dimensions. Finer pixels than slices buy little, and
 * coarser pixels than slices waste the bits: in `cornell-area`
 * (slices 4.5 mm, 128^2 voxel pixels 5.7 mm wide at mid depth) the error on
 * 4x4 boxes falls from 128^2 to the isotropic side and then stays
 * (Documentation/AreaLights.md). A deep scene (a room seen from inside,
 * thick slices) gets the least side.
 *
 * Perspective: VW = 2 d / (scale_x t), VH = 2 d / (scale_y t), d = (near +
 * far) / 2, t = (far - near) / S (the pixel width at depth
 * d is 2 d / (scale_x VW), section 4). Parallel: the same with d = 1. Each
 * side is rounded to the nearest multiple of MRGI_VOXEL_AUTO_STEP (so that
 * a moving camera changes the buffer's size only now and then) and clamped
 * to [MRGI_VOXEL_AUTO_MIN_SIZE, MRGI_VOXEL_AUTO_MAX_SIZE] (the march's
 * cost grows with the side; 128 is NPW10 4.2's default).
 *
 * @param projection A valid projection (mrgi_voxel_projection_check()).
 * @param slices S, as for mrgi_voxel_grid_init().
 * @param near_depth,far_depth The slicing range (as for
 *               mrgi_voxel_grid_init()): finite, near < far, and near + far
 *               > 0 for perspective.
 * @param size   Receives (VW, VH); untouched on failure.
 * @return ::MRGI_ERR_INVALID_ARGUMENT naming a NULL argument, an invalid
 *         projection, a slice count mrgi_voxel_grid_init() refuses, a
 *         non-finite or empty range, or a perspective range whose middle is
 *         not in front of the eye.
 */
mrgi_status mrgi_voxel_isotropic_size(const mrgi_voxel_projection* projection, int32_t slices,
  double near_depth, double far_depth, int32_t size[2], mrgi_error* err);

/**
 * @brief Project an eye-space point: uvd = (u, v, d), continuous voxel
 *        coordinates and linear depth (section 4).
 * @return 1, or 0 when the point is at or behind the eye of a perspective
 *         projection (d <= 0; uvd holds (0, 0, d) then).
 */
int mrgi_voxel_project(const mrgi_voxel_grid* grid, const mrgi_voxel_projection* projection,
                       const float point[3], float uvd[3]);

/** A rasterized fragment of the voxelization pass. */
typedef struct mrgi_voxel_fragment
{
  int32_t x;       /**< Voxel pixel column, 0..VW-1. */
  int32_t y;       /**< Voxel pixel row, 0..VH-1 (row 0 = bottom). */
  float depth;     /**< Linear eye depth at the pixel centre. */
  float half_span; /**< h >= 0: half the surface's depth range over the pixel (0: one bit). */
  float depth_min; /**< dmin: the primitive's smallest eye depth (-FLT_MAX: no clamp). */
  float depth_max; /**< dmax: the primitive's largest eye depth (FLT_MAX: no clamp). */
} mrgi_voxel_fragment;

/** What a voxelization wrote. */
typedef struct mrgi_voxel_info
{
  int64_t fragments_written; /**< Fragments that OR-ed a non-empty mask. */
  int64_t fragments_clipped; /**< Fragments dropped: depth outside [near, far] or not finite. */
} mrgi_voxel_info;

/**
 * @brief The fragment shader's outputs for one fragment (section 5): the
 *        slices of [d - h, d + h] clamped to [dmin, dmax] (centre kept), or
 *        all zero when d is outside [near, far] or NaN; 4 L words (layer l's
 *        render target in words 4 l .. 4 l + 3).
 */
void mrgi_voxel_fragment_mask(const mrgi_voxel_grid* grid, float depth, float half_span,
  float depth_min, float depth_max, uint32_t mask[MRGI_VOXEL_MAX_WORDS]);

/**
 * @brief Depth range of a triangle clipped to voxel pixel (x, y)'s square
 *        [x, x + 1] x [y, y + 1] (section 5; the fragment stage's clamp).
 *
 * Vertices in voxel pixel coordinates (u, v) with their linear depth d and
 * clip w (w = d for perspective, 1 for parallel). Sutherland-Hodgman
 * clipping against u >= x, u <= x + 1, v >= y, v <= y + 1 in that order,
 * interpolating a = d / w and b = 1 / w linearly in screen space (exact for
 * both projections: the perspective-correct pair), then d = a / b at every
 * vertex of the clipped polygon (at most 7); the range is their min and max
 * (a planar polygon's depth is monotone along lines in screen space, so its
 * extremes are at the polygon's vertices). Float, in this order; the GLSL
 * (vtkMRGIVoxelizeFS.glsl) translates it statement by statement.
 *
 * @param u,v,depth,w Three vertices.
 * @param range Receives [dmin, dmax] when the clipped polygon is not empty.
 * @return 1 when the clipped polygon has at least one vertex, else 0
 *         (`range` untouched; the caller clamps to the whole triangle's
 *         range): also when a vertex has w <= 0 or NaN (at or behind the
 *         eye: GL clips such a triangle, but its vertices' (u, v) mean
 *         nothing).
 */
int mrgi_voxel_triangle_pixel_range(const float u[3], const float v[3], const float depth[3],
                                    const float w[3], int32_t x, int32_t y, float range[2]);

/**
 * @brief Zero the voxel buffer (the pass's glClear to 0).
 * @return ::MRGI_ERR_INVALID_ARGUMENT for NULL pointers, a bad grid or a short buffer.
 */
mrgi_status mrgi_voxel_clear(const mrgi_voxel_grid* grid, uint32_t* voxels, size_t voxel_words,
                             mrgi_error* err);

/**
 * @brief OR the masks of `count` fragments into `voxels` (the blend stage
 *        with glLogicOp(GL_OR)); does not clear first.
 * @param fragments Fragment list (may be NULL when count is 0).
 * @param info      Receives counts; may be NULL.
 * @return ::MRGI_ERR_INVALID_ARGUMENT for NULL pointers, a bad grid, a short
 *         buffer, or a fragment whose pixel lies outside the grid (the
 *         message names its index); the buffer is untouched then.
 */
mrgi_status mrgi_voxel_voxelize(const mrgi_voxel_grid* grid, const mrgi_voxel_fragment* fragments,
                                size_t count, uint32_t* voxels, size_t voxel_words,
                                mrgi_voxel_info* info, mrgi_error* err);

/**
 * @brief Voxelize a depth buffer (one surface per pixel; for tests and for
 *        the visible-surfaces-only approximation): window pixel (x, y) is a
 *        fragment at voxel pixel (vx, vy) of section 3 with its depth, OR-ed
 *        into `voxels` (not cleared first).
 *
 * No primitive depth range (no clamp). Half span when `conservative` is 1:
 * h = 0.5 (gx + gy) where gx is the smaller of the two one-sided differences |d(x+1) - d(x)|, |d(x) - d(x-1)|
 * over the neighbours that hold a depth (0 without any), gy likewise: for a
 * plane it is the exact half range over the pixel, and at a silhouette it
 * takes the side on the same surface instead of bridging the gap to the
 * background (GPU derivatives never cross primitives). `conservative` 0:
 * h = 0, one bit per pixel. A window pixel covers one window pixel's depth
 * range, so when VW > W voxel pixels that no window pixel centre maps to
 * stay empty.
 *
 * @param depth  W x H linear eye depths, row 0 = bottom; a non-finite value
 *               marks an empty pixel (background).
 * @param width,height W, H: 1..MRGI_VOXEL_MAX_SIZE.
 * @param conservative 0 or 1 (see above).
 * @return ::MRGI_ERR_INVALID_ARGUMENT for NULL pointers, a bad grid, sizes
 *         out of range, a short buffer or `conservative` not 0/1.
 */
mrgi_status mrgi_voxel_voxelize_depth(const mrgi_voxel_grid* grid, const float* depth,
                                      int32_t width, int32_t height, int32_t conservative,
                                      uint32_t* voxels, size_t voxel_words,
                                      mrgi_voxel_info* info, mrgi_error* err);

#ifdef __cplusplus
}
#endif

#endif
