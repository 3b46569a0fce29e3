/**
 * @file vtkMRGIShaderUtilities.h
 * @brief Internal helpers shared by MRGI's passes to build GLSL: the
 *        constants block from the C core, and injection into VTK's
 *        polygonal shaders. Not wrapped, not installed.
 */
#ifndef vtkMRGIShaderUtilities_h
#define vtkMRGIShaderUtilities_h

#include "vtkRenderTimerLog.h" // For vtkRenderTimerLog::ScopedEventLogger

#include <string>
#include <vector>

class vtkOpenGLFramebufferObject;
class vtkOpenGLRenderWindow;
class vtkRenderer;
class vtkTextureObject;
class vtkWindow;

namespace vtkMRGIShaderUtilities
{
/**
 * Select the first `count` colour attachments of the bound `fbo` as draw
 * buffers: fbo->ActivateDrawBuffers(count), then glDrawBuffers directly.
 * VTK 9.1's vtkOpenGLState skips the call when its cache says they are
 * selected already, and an enclosing vtkSSAOPass puts that cache out of
 * step with OpenGL (it selects draw buffers through a framebuffer object
 * that is not the bound one; measured: MRGI's stages then wrote only their
 * first target inside it).
 */
void SelectDrawBuffers(vtkOpenGLFramebufferObject* fbo, unsigned int count);

/**
 * The `#define` block of every constant the core defines for GLSL
 * (mrgi_glsl_defines()), generated once per process.
 */
const std::string& Defines();

/**
 * Replace every `gl_FragData[NAME]` whose NAME is a G-buffer/RSM attachment
 * macro by its number: VTK's shader cache declares fragment outputs only for
 * literal `gl_FragData[N]` indices.
 */
std::string ResolveAttachments(std::string code);

/**
 * A complete full-screen-quad fragment shader: VTK's version/precision line,
 * the constants block, then `body` (which declares its own inputs and main()).
 */
std::string FullScreenShader(const char* body);

/**
 * Prepare a VTK polygonal fragment shader for capture code at its end: adds
 * the `//MRGI::Dec` marker after the system declarations and the
 * `//MRGI::Capture::Impl` marker before depth peeling (after texturing).
 * Call from PreReplaceShaderValues.
 */
void AddCaptureMarkers(std::string& fragmentShader);

/**
 * Whether the shader computes what capture needs (eye-space position, normal
 * and diffuse colour): false for unlit or normal-less geometry.
 */
bool CanCapture(const std::string& fragmentShader);

/**
 * Fill the markers: `declarations` go after the system declarations (with
 * the constants block), `capture` at the end of main(), preceded by
 * `vec3 mrgiTextureFactor`, the colour of VTK's texture where VTK applied one.
 */
void InsertCapture(
  std::string& fragmentShader, const std::string& declarations, const std::string& capture);

/**
 * Instrument VTK's light loop in `fragmentShader` (after VTK replaced
 * //VTK::Light::Impl, before InsertCapture) so that it also sums the term
 * of each of its first MRGI_SHADOW_SLOTS lights separately, and return the
 * declarations and the capture code that write those terms to the
 * MRGI_GBUFFER_LIGHT0.. attachments (mrgi_buffers.h): Phong terms times
 * VTK's texture colour; PBR terms times its ambient-occlusion factor, stored
 * negated (VTK encodes PBR colours with a display gamma). Light loops that
 * do not have VTK 9.1/9.2's form leave the terms at 0: those pixels keep
 * VTK's unshadowed colour.
 */
void InsertLightTerms(std::string& fragmentShader, std::string& declarations, std::string& capture);

/** Capture code that writes zero light terms (geometry VTK does not light). */
std::string NoLightTerms();

/**
 * Select the G-buffer's draw buffers for the scene: the first
 * MRGI_GBUFFER_SPECULAR attachments, the specular pair when `specular`, the
 * light terms when `lightTerms` (GL_NONE between, which OpenGL 3.2 requires
 * for attachment points without an image).
 */
void SelectGBufferDrawBuffers(vtkOpenGLFramebufferObject* fbo, bool specular, bool lightTerms);

/** Free a texture's GL resources (when `w` is given) and delete it; null-safe, nulls `t`. */
void ReleaseTexture(vtkTextureObject*& t, vtkWindow* w);

/**
 * A new w x h texture, nearest filtering, clamped to its edge:
 * `internalFormat` a float or normalized format (GL_RGBA32F, GL_RGBA16F,
 * GL_R16F, GL_R8; shaders read missing channels as 0, alpha as 1) or
 * GL_RGBA32UI. Null (nothing left allocated) when the allocation fails.
 */
vtkTextureObject* NewTexture(vtkOpenGLRenderWindow* window, int internalFormat, int w, int h);

/**
 * Keep `t` a w x h NewTexture() of `internalFormat`: reallocated when
 * `size` (the size it was made at, updated here) differs. False, with `t`
 * null and `size` 0 x 0, when the allocation fails.
 */
bool EnsureTexture(
  vtkOpenGLRenderWindow* window, vtkTextureObject*& t, int size[2], int internalFormat, int w, int h);

/**
 * The camera's projection (eye -> clip) at the renderer's tiled aspect
 * ratio, depth in [-1, 1], as vtkSSAOPass takes it; column-major floats
 * for a GLSL mat4 uniform (the screen-space effects and their twins).
 */
void CameraProjection(vtkRenderer* renderer, float matrix[16]);

/**
 * A new w x h selection mask (the flattened selections of the
 * multiresolution, incremental and specular stencils): the selecting shader
 * writes 1 to red where a texel is selected, the clear leaves 0, and every
 * reader tests red > 0.5. One normalized byte (GL_R8) holds both exactly,
 * a sixteenth of RGBA32F. Null when the allocation fails.
 */
vtkTextureObject* NewMaskTexture(vtkOpenGLRenderWindow* window, int w, int h);

/**
 * A new w x h texture of per-texel flags: small non-negative integers
 * (MRGI_MULTIRES_FLAG_*, MRGI_SPECULAR_STENCIL_* bits) that the shaders write
 * as float(flags) to red and read back with int(texel.r). A half float holds
 * every integer up to 2048 exactly, so one GL_R16F channel (2 bytes, an
 * eighth of RGBA32F) keeps the values and the shaders as they are. Null when
 * the allocation fails.
 */
vtkTextureObject* NewFlagsTexture(vtkOpenGLRenderWindow* window, int w, int h);

/**
 * Bytes per texel of `internalFormat` (the formats MRGI allocates; 16 for
 * any other), for vtkMRGIResourceStatistics.
 */
int BytesPerTexel(int internalFormat);

/**
 * Give `t` storage of w x h when its size differs (vtkTextureObject::Resize),
 * counting that allocation in vtkMRGIResourceStatistics; nothing otherwise.
 */
void ResizeTexture(vtkTextureObject* t, int w, int h);

/** A new w x h depth-stencil texture, nearest filtering; null when the allocation fails. */
vtkTextureObject* NewDepthStencil(vtkOpenGLRenderWindow* window, int w, int h);

/**
 * Read a colour texture back as RGBA floats (rows bottom-up, as OpenGL
 * stores them). Returns false when the texture or context is missing.
 */
bool ReadTextureRGBA(vtkOpenGLRenderWindow* window, vtkTextureObject* texture, std::vector<float>& rgba);

// Reads the w x h region at (x, y) of a float colour texture into `out`
// (rows bottom-up, `components` = 3 (RGB) or 4 (RGBA) floats a pixel, w * h *
// components values), with no copy of the whole texture in between; false
// on a GL error or a region outside the texture.
bool ReadTextureRegion(vtkOpenGLRenderWindow* window, vtkTextureObject* texture, int x, int y,
  int w, int h, int components, float* out);

/**
 * Every MRGI timer event carries this prefix so that
 * vtkMRGIPass::FetchStageTimings() finds MRGI's stages among the events
 * other passes log on the same window.
 */
extern const char* const StagePrefix;

/**
 * The window's timer log when stage timing is `enabled` and the log is
 * logging; null otherwise (logging is switched on between frames only:
 * VTK brackets its own rendering with timer events).
 */
vtkRenderTimerLog* StageTimer(vtkRenderer* renderer, bool enabled);

/**
 * The MRGI stages (events named StagePrefix + stage) of the newest frame
 * whose queries have completed, in render order, with their times in ms
 * (a step drawn once per level: the sum). False, `names` and `times`
 * untouched, when no completed frame has MRGI stages.
 */
bool CollectStageTimes(vtkRenderTimerLog* timer, std::vector<std::string>& names, std::vector<double>& times);

/**
 * Opens a GPU timer event for one stage (nested events are sub-stages,
 * named "stage.step"), or nothing when `timer` is null (timing off).
 */
class ScopedStage
{
public:
  ScopedStage(vtkRenderTimerLog* timer, const char* stage);

private:
  vtkRenderTimerLog::ScopedEventLogger Logger;
};
}

#endif
