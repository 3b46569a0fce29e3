/**
 * @file mrgi_buffers.h
 * @brief Layouts of the GPU buffers that MRGI's stages exchange, defined once.
 *
 * The C++ layer allocates these targets and the GLSL reads and writes them;
 * both take the numbers from here (GLSL through mrgi_glsl_defines()), so a
 * layout is never typed twice. The C twins read the same buffers back.
 *
 * G-buffer (eye space of the rendered camera, one texel per pixel, rows
 * bottom-up as OpenGL stores them):
 * - attachment 0: direct light (VTK's own shading), RGBA32F, unclamped;
 * - attachment MRGI_GBUFFER_POSITION: eye-space position xyz (VTK "VC"
 *   coordinates), w = MRGI_GBUFFER_VALID where opaque lit geometry was drawn;
 * - attachment MRGI_GBUFFER_NORMAL: eye-space unit normal facing the viewer
 *   (two-sided lighting's flip applied), w = MRGI_GBUFFER_VALID;
 * - attachment MRGI_GBUFFER_ALBEDO: diffuse albedo rgb (VTK's diffuse colour
 *   times the Diffuse coefficient: solid colour, scalars through a lookup
 *   table, texture, or PBR base colour), w = MRGI_GBUFFER_VALID;
 * - attachment MRGI_GBUFFER_SPECULAR (only while area lights reflect
 *   specularly): VTK's specular colour k_s c_s (vtkProperty Specular x
 *   SpecularColor; 0 for materials without it, e.g. PBR), w = MRGI_GBUFFER_VALID;
 * - attachment MRGI_GBUFFER_SHININESS (with MRGI_GBUFFER_SPECULAR): r = the
 *   Phong exponent (vtkProperty SpecularPower), w = MRGI_GBUFFER_VALID. Two
 *   attachments because every w must stay 1 (the blending note below).
 * - attachments MRGI_GBUFFER_LIGHT0 .. MRGI_GBUFFER_LIGHT0 +
 *   MRGI_SHADOW_SLOTS - 1 (only while direct shadows are on): the
 *   contribution of VTK's shader light s (the s-th switched-on light) to
 *   attachment 0, rgb, as VTK's own light loop computed it (after texture
 *   modulation; linear, before PBR's display gamma), w = 1 (blending-neutral,
 *   see below). Contributions are never negative; PBR pixels, whose colour
 *   VTK encodes with a display gamma of 1/2.2, store them negated, so the
 *   sign tells the composite which law to undo (mrgi_shadow_composite.h).
 *   Shadows are applied by subtracting (1 - factor) x contribution
 *   (Documentation/DirectShadows.md), so lit pixels keep VTK's value exactly.
 *
 * w = 1 marks geometry. VTK draws opaque geometry with blending on
 * (SRC_ALPHA, ONE_MINUS_SRC_ALPHA), which with alpha exactly 1 stores the
 * written value unchanged; MRGI clears the G-buffer attachments to 0 after
 * VTK's own clear (which writes the background colour to every draw buffer).
 *
 * Reflective shadow map (one "view" per spot/directional light, six cube
 * faces per point light; S x S texels, rows bottom-up):
 * - MRGI_RSM_POSITION: world position xyz, w = MRGI_GBUFFER_VALID or 0;
 * - MRGI_RSM_NORMAL: world unit normal facing the light, w = 0;
 * - MRGI_RSM_FLUX: reflected flux rgb, w = surface area of the texel
 *   (see mrgi_vpl.h for the definitions).
 */
#ifndef MRGI_BUFFERS_H
#define MRGI_BUFFERS_H

/** w of a G-buffer / RSM texel that holds geometry (1: blending-neutral). */
#define MRGI_GBUFFER_VALID 1.0f
/** Texels with w above this hold geometry; cleared texels hold 0. */
#define MRGI_GBUFFER_VALID_THRESHOLD 0.5f

/** Colour attachments of the G-buffer. */
#define MRGI_GBUFFER_DIRECT 0
#define MRGI_GBUFFER_POSITION 1
#define MRGI_GBUFFER_NORMAL 2
#define MRGI_GBUFFER_ALBEDO 3
#define MRGI_GBUFFER_SPECULAR 4
#define MRGI_GBUFFER_SHININESS 5
/** All G-buffer attachments; without specular data the first MRGI_GBUFFER_SPECULAR. */
#define MRGI_GBUFFER_ATTACHMENTS 6
/**
 * Per-light contributions for direct shadows: attachments 6 and 7 (OpenGL
 * 3.2 guarantees 8 draw buffers). VTK's shader lights past
 * MRGI_SHADOW_SLOTS stay unshadowed (the pass warns once).
 */
#define MRGI_GBUFFER_LIGHT0 6
#define MRGI_SHADOW_SLOTS 2
/** Every attachment index the G-buffer framebuffer may hold (0 .. this - 1). */
#define MRGI_GBUFFER_MAX_ATTACHMENTS (MRGI_GBUFFER_LIGHT0 + MRGI_SHADOW_SLOTS)

/** Colour attachments of a reflective shadow map view. */
#define MRGI_RSM_POSITION 0
#define MRGI_RSM_NORMAL 1
#define MRGI_RSM_FLUX 2
#define MRGI_RSM_ATTACHMENTS 3

/** Resolutions the RSM pass offers (texels per side; the core accepts up to MRGI_RSM_MAX_SIZE). */
#define MRGI_RSM_MIN_RESOLUTION 16
#define MRGI_RSM_MAX_RESOLUTION 2048
#define MRGI_RSM_DEFAULT_RESOLUTION 256

/**
 * Spot lights with a half-angle up to this get one perspective view of twice
 * the angle; wider cones and point lights get the six faces of a cube, since
 * a perspective frustum degenerates as its field of view nears 180 degrees.
 */
#define MRGI_RSM_MAX_SPOT_HALF_ANGLE_DEG 80.0

#endif
