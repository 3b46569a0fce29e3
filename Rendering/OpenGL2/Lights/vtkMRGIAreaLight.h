/**
 * @class   vtkMRGIAreaLight
 * @brief   A rectangular, optionally textured (e.g. video) area light.
 *
 * The VTK face of the C core's ::mrgi_area_light (Rendering/Core/Twins/
 * mrgi_area_light.h, whose file comment is the reference for geometry,
 * units and sampling). This class holds the light's properties, turns them
 * into the core's structs, caches the texture pyramid and the light samples
 * and draws the emitter. The GPU gather that lights a scene with these
 * samples (Nichols, Penmatsa and Wyman 2010, [NPW10] section 3.2) is
 * vtkMRGIPass's: give the light to vtkMRGIPass::AddAreaLight() (its
 * emitter geometry, GetGeometryActor(), is added to the renderer
 * separately).
 *
 * Geometry: a rectangle with centre Center and FULL edge vectors EdgeU and
 * EdgeV (world units, perpendicular), corners Center +- EdgeU/2 +- EdgeV/2,
 * normal n = normalize(EdgeU x EdgeV). A one-sided light emits towards n
 * only; a TwoSided light emits the same radiance on both sides.
 *
 * Radiance (VTK units, see the core): L(s, t) = Intensity * Color * T(s, t)
 * with T the texture (T = 1 without one). Texture coordinate (s, t) in
 * [0, 1]^2 is the point Center + (s - 1/2) EdgeU + (t - 1/2) EdgeV. The
 * texture is a VTK image read as VTK maps textures: image row 0 (VTK's
 * bottom row) is t = 0 and column 0 is s = 0, so seen from the emitting
 * side (EdgeU pointing right, EdgeV up) the picture is upright, as a
 * vtkTexture on a vtkPlaneSource shows it.
 *
 * Texture input: SetTextureData(vtkImageData*) or SetTexture(vtkTexture*)
 * (its input image is used, its pipeline updated when the light needs it);
 * the last one set wins. Accepted: a 2D image (W x H x 1) with point
 * scalars of unsigned char (v / 255; sRGB-decoded when given through a
 * vtkTexture whose UseSRGBColorSpace is on) or float (HDR, used as is,
 * finite and >= 0), with 1 (gray), 2 (gray + alpha), 3 (RGB) or 4 (RGBA)
 * components; alpha is ignored.
 *
 * Caching: the texture pyramid is rebuilt only when the texture image
 * changes (its MTime, e.g. after Modified() for the next video frame), the
 * samples only when a property they depend on or the pyramid changes;
 * GetNumberOfTextureBuilds() and GetNumberOfSampleBuilds() count rebuilds.
 *
 * Errors: properties are stored as given; every request (GetSamples(),
 * GetCoreLight(), ...) validates them and, for a non-finite Center or
 * edge, edges that are zero, parallel or not perpendicular, a negative or
 * non-finite Intensity or Color, or an unusable texture (empty, 3D, wrong
 * scalar type or component count, a negative or non-finite float texel),
 * reports a vtkErrorMacro naming the problem, returns false and writes
 * nothing; fixing the property makes the next request succeed.
 *
 * @sa vtkMRGIPass vtkLight vtkTexture
 */
#ifndef vtkMRGIAreaLight_h
#define vtkMRGIAreaLight_h

#include "MRGIRenderingModule.h" // For export macro
#include "vtkObject.h"

#include <memory> // For std::unique_ptr
#include <string> // For std::string

class vtkActor;
class vtkFloatArray;
class vtkImageData;
class vtkOpenGLRenderWindow;
class vtkPolyData;
class vtkShaderProgram;
class vtkTexture;
class vtkTextureObject;
class vtkWindow;
struct mrgi_area_light;
struct mrgi_area_light_sample;
struct mrgi_area_light_texture_pyramid;
struct mrgi_area_light_uniforms;

class MRGIRENDERING_EXPORT vtkMRGIAreaLight : public vtkObject
{
public:
  static vtkMRGIAreaLight* New();
  vtkTypeMacro(vtkMRGIAreaLight, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /** Centre of the rectangle, world units. Default (0, 0, 0). */
  vtkSetVector3Macro(Center, double);
  vtkGetVector3Macro(Center, double);
  ///@}

  ///@{
  /**
   * The FULL edge vectors (not half edges), perpendicular to each other;
   * corners are Center +- EdgeU/2 +- EdgeV/2 and the emitting side is
   * EdgeU x EdgeV. Defaults (1, 0, 0) and (0, 1, 0): a unit square
   * emitting towards +z.
   */
  vtkSetVector3Macro(EdgeU, double);
  vtkGetVector3Macro(EdgeU, double);
  vtkSetVector3Macro(EdgeV, double);
  vtkGetVector3Macro(EdgeV, double);
  ///@}

  ///@{
  /** Linear RGB colour, each component >= 0. Default (1, 1, 1). */
  vtkSetVector3Macro(Color, double);
  vtkGetVector3Macro(Color, double);
  ///@}

  ///@{
  /**
   * Radiance scale, >= 0 (L = Intensity * Color * texture). Stored as given
   * and checked on use: a negative value is reported, not silently clamped
   * to 0. Default 1.
   */
  vtkSetMacro(Intensity, double);
  vtkGetMacro(Intensity, double);
  ///@}

  ///@{
  /** Emit on both sides of the rectangle. Default off (towards EdgeU x EdgeV). */
  vtkSetMacro(TwoSided, bool);
  vtkGetMacro(TwoSided, bool);
  vtkBooleanMacro(TwoSided, bool);
  ///@}

  ///@{
  /**
   * Requested light samples N ("VPLs on the area light", [NPW10] 3.2),
   * 1..4096, default 256 (the paper's). The core lays out an sx x sy grid
   * with sx * sy <= N cells as square as the aspect ratio allows, so fewer
   * than N samples may come back (e.g. 992 for N = 1000).
   */
  vtkSetClampMacro(NumberOfSamples, int, 1, 4096);
  vtkGetMacro(NumberOfSamples, int);
  ///@}

  ///@{
  /**
   * Off (default): samples at cell centres. On: one uniformly random point
   * per cell from the stream of Seed (deterministic for a seed). Jitter
   * moves positions, never radiances.
   */
  vtkSetMacro(Jitter, bool);
  vtkGetMacro(Jitter, bool);
  vtkBooleanMacro(Jitter, bool);
  vtkSetMacro(Seed, vtkTypeUInt64);
  vtkGetMacro(Seed, vtkTypeUInt64);
  ///@}

  ///@{
  /** Whether the geometry actor (GetGeometryActor()) is shown. Default on. */
  vtkSetMacro(Visible, bool);
  vtkGetMacro(Visible, bool);
  vtkBooleanMacro(Visible, bool);
  ///@}

  ///@{
  /**
   * The light's texture as a vtkTexture (its input image is used) or as an
   * image. Setting one clears the other; nullptr for an untextured light.
   */
  virtual void SetTexture(vtkTexture* texture);
  vtkGetObjectMacro(Texture, vtkTexture);
  virtual void SetTextureData(vtkImageData* image);
  vtkGetObjectMacro(TextureData, vtkImageData);
  ///@}

  /** Includes the texture's and its image's modification times. */
  vtkMTimeType GetMTime() override;

  /** Also keeps the geometry actor's look in step with the light. */
  void Modified() override;

  /**
   * The light samples, as the GPU sample texture lays them out: `samples`
   * gets 4 components and 3 * count tuples; tuple 3 j + k is RGBA texel k
   * of sample j: k = 0 position xyz and cell area, k = 1 the light's unit
   * normal and 0, k = 2 radiance rgb and 0 (MRGI_AREA_LIGHT_SAMPLE_TEXEL_*).
   * count = tuples / 3 <= NumberOfSamples. Cached (see the class
   * documentation). Returns false, leaving `samples` unchanged, on error.
   */
  bool GetSamples(vtkFloatArray* samples);

  /**
   * The emitter quad: 4 points (the corners, counter-clockwise seen from
   * the emitting side: -u-v, +u-v, +u+v, -u+v halves), one polygon, point
   * normals n and texture coordinates (s, t) of the class documentation.
   * False (output untouched) for an invalid light.
   */
  bool MakeGeometry(vtkPolyData* quad);

  /**
   * An actor that draws the emitter, owned by the light and kept in step
   * with it at render time: the quad of MakeGeometry() with VTK lighting
   * off (self-luminous: ambient 1, diffuse and specular 0; MRGI's passes
   * neither capture nor light unlit geometry, so nothing is added to it).
   *
   * Untextured, it shows Intensity * Color as its colour (unclamped: float
   * buffers keep it HDR). Textured, it shows the light's picture through
   * the quad's texture coordinates (the mapping of the class
   * documentation: upright from the emitting side), an 8-bit sRGB
   * vtkTexture holding Intensity * Color * T scaled for display: divided
   * by P = Intensity * max(Color) * max(1, max texel) when P > 1, else
   * shown as is. So a texture with values in [0, 1] (every 8-bit one)
   * appears with its full range, tinted by Color / max(Color), whatever
   * the Intensity (a bright TV is a visible picture, not a white square),
   * and the scale stays the same from one video frame to the next; a dim
   * light (P <= 1) shows its true radiance. This is a display picture, not
   * the radiance: GetSamples() and vtkMRGIPass use the true one. The
   * picture follows the texture image: after Modified() (the next video
   * frame) the next render shows it, with no other call.
   *
   * The back of a one-sided light is black; a two-sided light shows the
   * same picture on its back (seen from behind, mirrored: each point emits
   * the same radiance on both sides). Hidden when Visible is off; empty
   * while the light is invalid. [NPW10] 3.2 notes that the gather can skip
   * the emitter's own pixels.
   */
  vtkActor* GetGeometryActor();

  /**
   * Make `actor` a second view of the emitter: it gets a mapper of the
   * light's quad and GetGeometryActor()'s front and back properties and
   * picture texture, and is kept in step with the light as that actor is
   * (also when a texture is set or removed), but keeps its own visibility,
   * which Visible does not drive. For scenes that own their emitter's
   * actor: vtkMRGISceneBuilder draws a textured light's screen this way.
   * The view's mapper keeps the light alive (the light holds `actor` only
   * weakly: no cycle); nullptr and GetGeometryActor() itself are ignored.
   */
  void ShareGeometryActor(vtkActor* actor);

  ///@{
  /** Pyramid and sample rebuilds so far (for tests and profiling). */
  vtkGetMacro(NumberOfTextureBuilds, int);
  vtkGetMacro(NumberOfSampleBuilds, int);
  ///@}

  ///@{
  /**
   * GPU uploads so far of the pyramid texture (GetPyramidTexture()) and of
   * the sample texture (GetSampleTexture()): each happens once per rebuild
   * (or per new window / after ReleaseGraphicsResources()), not per request.
   */
  vtkGetMacro(NumberOfPyramidUploads, int);
  vtkGetMacro(NumberOfSampleUploads, int);
  ///@}

  /**
   * Free the GPU textures (pyramid, samples) in `window`'s context, the
   * window they were uploaded in; nullptr forgets them without GL calls
   * (their context is gone). The next request uploads again.
   */
  void ReleaseGraphicsResources(vtkWindow* window);

  /** Why the last request failed; empty after a success. */
  const char* GetLastErrorMessage() { return this->LastErrorMessage.c_str(); }

#ifndef __VTK_WRAP__
  /**
   * The core light. Its `texture` points to the light's converted float
   * image (row 0 = top, as the core wants), valid until the texture or
   * its image changes or the light is deleted. False (nothing written) on
   * error.
   */
  bool GetCoreLight(mrgi_area_light* light);

  /**
   * The core light (no texture) of these parameters, checked as the light
   * checks its own (mrgi_area_light_check(), the message naming the
   * properties: Center, EdgeU, ...). For objects that describe a light
   * without being one (ParaView's MRGI Area Light source). False with the
   * reason in `why` (nothing written) when invalid.
   */
  static bool MakeCoreLight(const double center[3], const double edgeU[3], const double edgeV[3],
    const double color[3], double intensity, bool twoSided, mrgi_area_light* light,
    std::string* why);

  /** The gather shaders' uniforms (mrgi_area_light_uniforms_init()). */
  bool GetCoreUniforms(mrgi_area_light_uniforms* uniforms);

  /**
   * The cached texture pyramid: *pyramid is nullptr for an untextured light
   * (what the core takes then). Valid as GetCoreLight()'s texture.
   */
  bool GetCorePyramid(const mrgi_area_light_texture_pyramid** pyramid);

  /**
   * The cached samples (the GPU texture's memory, count records) or
   * nullptr on error. Valid until the next request after a change.
   */
  const mrgi_area_light_sample* GetCoreSamples(int* count);

  /**
   * The texture pyramid as one GL texture in `window`'s context: mip level
   * k holds pyramid level k (GL_RGB32F, GL's mip sizes, which are the
   * core's; GL's first row is the picture's TOP row as the core stores it;
   * CLAMP_TO_EDGE, LINEAR_MIPMAP_LINEAR, MAX_LEVEL = levels - 1: the upload
   * of mrgi_area_light.h "The texture pyramid"). An untextured light gets
   * its 1 x 1 white pyramid. vtkMRGIAreaLightSpecular.glsl reads it with
   * texelFetch() only. Uploaded again only after the pyramid was rebuilt
   * (GetNumberOfPyramidUploads()). Owned by the light; nullptr (error
   * reported) for an invalid texture or no window. Makes `window` current.
   */
  vtkTextureObject* GetPyramidTexture(vtkOpenGLRenderWindow* window);

  /**
   * The light samples as the GPU sample texture (RGBA32F,
   * MRGI_AREA_LIGHT_SAMPLE_TEXELS wide, one row per sample, NEAREST; the
   * memory of GetCoreSamples()), uploaded again only after the samples were
   * rebuilt. `count` (may be nullptr) receives the rows. nullptr on error.
   */
  vtkTextureObject* GetSampleTexture(vtkOpenGLRenderWindow* window, int* count = nullptr);

  /**
   * Set every uniform of the area-light GLSL libraries in `program`
   * (bound, as after vtkOpenGLShaderCache::ReadyShaderProgram(), in
   * `window`'s context): ::mrgi_area_light_uniforms as GetCoreUniforms()
   * gives them (mrgiAreaCenter, mrgiAreaNormal, mrgiAreaCorners,
   * mrgiAreaTwoSided, mrgiAreaAxisU, mrgiAreaAxisV, mrgiAreaHalfU,
   * mrgiAreaHalfV, mrgiAreaScale, mrgiAreaTextureSize, mrgiAreaTextureLevels),
   * mrgiAreaTextured, the samples (mrgiAreaSamples on an activated unit,
   * mrgiAreaSampleFirst = 0, mrgiAreaSampleCount = all of them) and the
   * pyramid (mrgiAreaPyramid on an activated unit): the same floats and
   * ints the C twins read. Uniforms the program does not use are skipped.
   * Call DeactivateTextures() after drawing. False, with an error and
   * nothing set, for a null program or window or an invalid light.
   */
  bool SetShaderUniforms(vtkShaderProgram* program, vtkOpenGLRenderWindow* window);

  /** Free the texture units SetShaderUniforms() activated. */
  void DeactivateTextures();

  /**
   * The GLSL of the specular library (vtkMRGIAreaLightSpecular.glsl):
   * uniforms and functions, no main() and no #version. Put it after
   * //VTK::System::Dec and the constants block (vtkMRGIShaderUtilities::
   * Defines()).
   */
  static const char* GetSpecularShaderSource();

  /**
   * The area-light GLSL libraries in the order they must appear: the
   * diffuse one (vtkMRGIAreaLightDiffuse.glsl; with MRGI_AREA_VISIBILITY
   * defined it needs the voxel march before it), then, when both are asked
   * for, `#define MRGI_AREA_LIGHT_DIFFUSE_DECLARED` (the uniforms both use
   * are declared once), then the specular one.
   */
  static std::string GetShaderSource(bool diffuse, bool specular);
#endif

protected:
  vtkMRGIAreaLight();
  ~vtkMRGIAreaLight() override;

  /** Refresh the texture cache; false (error reported) when unusable. */
  bool UpdateTexture();
  /** Refresh the sample cache (and the texture cache first). */
  bool UpdateSamples();
  /** Fill `light` from the properties and the texture cache and check it. */
  bool BuildCoreLight(mrgi_area_light* light, bool withTexture);
  /** The image the texture comes from (nullptr: none); updates a vtkTexture's pipeline. */
  vtkImageData* ResolveTextureImage(bool updatePipeline);
  bool Fail(const std::string& why);
  /** Keep the geometry actor (if made) in step with the light (vtkMRGIAreaLightEmitter). */
  void UpdateGeometryActor();

  double Center[3] = { 0.0, 0.0, 0.0 };
  double EdgeU[3] = { 1.0, 0.0, 0.0 };
  double EdgeV[3] = { 0.0, 1.0, 0.0 };
  double Color[3] = { 1.0, 1.0, 1.0 };
  double Intensity = 1.0;
  bool TwoSided = false;
  int NumberOfSamples = 256;
  bool Jitter = false;
  vtkTypeUInt64 Seed = 1;
  bool Visible = true;
  vtkTexture* Texture = nullptr;
  vtkImageData* TextureData = nullptr;
  int NumberOfTextureBuilds = 0;
  int NumberOfSampleBuilds = 0;
  int NumberOfPyramidUploads = 0;
  int NumberOfSampleUploads = 0;
  std::string LastErrorMessage;

  /** Forget or free the GL textures when `window` is not the one they live in. */
  void UseGraphicsWindow(vtkOpenGLRenderWindow* window);

private:
  vtkMRGIAreaLight(const vtkMRGIAreaLight&) = delete;
  void operator=(const vtkMRGIAreaLight&) = delete;

  struct vtkInternals;
  std::unique_ptr<vtkInternals> Internals;
};

#endif
