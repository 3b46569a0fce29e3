/**
 * @class   vtkMRGIVoxelization
 * @brief   Screen-space voxelization on the GPU (nichols-penmatsa-wyman-2010
 *          section 3.3): every opaque surface of a renderer rasterized into a
 *          VW x VH RGBA32UI texture of 128 to 512 one-bit depth slices
 *          per pixel (NumberOfSlices; 128 per layer, one render target each).
 *
 * The bit layout, the depth slicing, the projection and the per-fragment rule
 * are the contract of the C core (mrgi_voxel.h sections 1-5), whose C twin is
 * mrgi_voxel_voxelize(); this class is the GPU side of that contract:
 *
 * - the buffer is VW x VH, independent of the window: by default as many
 *   voxel pixels as make the voxels about as wide as deep
 *   (AutomaticVoxelSize), else VoxelSize; it covers
 *   the same view frustum as the renderer (same camera, same aspect: the
 *   renderer's viewport), so window pixel (x, y) maps to voxel pixel
 *   (floor((x + 0.5) VW / W), floor((y + 0.5) VH / H));
 * - slices are uniform in linear eye depth d = -z_eye over the caller's
 *   [near, far] (the depth range of what the visibility queries need, e.g.
 *   the G-buffer's range widened to the area light), not the camera's
 *   clipping range; near and far are the clip planes of the pass, so
 *   surfaces outside [near, far] write nothing;
 * - every triangle is drawn, hidden ones too (no depth test, no culling),
 *   and each fragment ORs (glLogicOp(GL_OR)) the slices of
 *   [d - h, d + h] clamped to the triangle's depth range [dmin, dmax], with
 *   h = 0.5 fwidth(d); a geometry shader passes [dmin, dmax] as flat varyings.
 *
 * What is drawn: the polygons and triangle strips (triangulated with
 * vtkTriangleFilter where they are not triangles already) of the vtkPolyData
 * input of every visible, opaque vtkActor whose mapper is a
 * vtkPolyDataMapper, assemblies included, with the actor's matrix, whatever
 * the actor's representation (the voxels hold surfaces); for a
 * vtkCompositePolyDataMapper2 with a composite input (ParaView's geometry
 * representations), each vtkPolyData leaf that the mapper's display
 * attributes do not hide or make translucent (attributes set on the leaf
 * itself). Not drawn, and counted in GetNumberOfSkippedProps(): translucent
 * actors (they do not block light in the opaque passes either), volumes,
 * composite data sets of other mappers, glyph and other non-polydata
 * mappers, 2D props. Lines and vertices have no surface and are ignored.
 *
 * Geometry goes through the pass's own shader program (not the mappers'):
 * the triangulated points are uploaded once per polydata (cached on its
 * MTime, shared by actors that share data) relative to their centre, and the
 * actor matrix and the camera's view matrix reach the shader as one
 * model-view matrix computed in double, so moving an actor or the camera
 * uploads nothing.
 *
 * Use: call Voxelize() with the renderer's window current and rendered at
 * least once (e.g. from a render pass, or after Render()); then
 * GetVoxelTexture() for the ray march (usampler3D, texelFetch; slice s
 * in layer s >> 7, channel (s >> 5) & 3, bit s & 31) and, from C++, GetGrid() for the slicing and
 * projection the march needs. ReadVoxels() reads the buffer back in the
 * layout of mrgi_voxel.h.
 *
 * The ray march (naive voxel-space visibility, NPW10 section 3.3.1) is the
 * GLSL library GetMarchShaderSource() (vtkMRGIVoxelMarch.glsl: functions
 * mrgiVoxelVisible() and mrgiVoxelOccluderFraction(), twins of
 * mrgi_voxel_march() and mrgi_voxel_march_occluder_fraction()); a shader that
 * includes it gets its uniforms and voxel texture from SetMarchUniforms(),
 * with the knobs MaxSteps, NormalOffset and SkipRadius below.
 */
#ifndef vtkMRGIVoxelization_h
#define vtkMRGIVoxelization_h

#include "MRGIRenderingModule.h" // For export macro
#include "vtkObject.h"

#include <memory> // For std::unique_ptr

class vtkRenderTimerLog;
class vtkRenderWindow;
class vtkRenderer;
class vtkShaderProgram;
class vtkTextureObject;
class vtkTypeUInt32Array;
class vtkWindow;
#ifndef __VTK_WRAP__
struct mrgi_voxel_grid;
struct mrgi_voxel_march_params;
struct mrgi_voxel_projection;
#endif

class MRGIRENDERING_EXPORT vtkMRGIVoxelization : public vtkObject
{
public:
  static vtkMRGIVoxelization* New();
  vtkTypeMacro(vtkMRGIVoxelization, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Voxel buffer size VW x VH, each side clamped to 1..MRGI_VOXEL_MAX_SIZE
   * (16384): used when AutomaticVoxelSize is off. Setting it turns
   * AutomaticVoxelSize off. Default MRGI_VOXEL_DEFAULT_SIZE (128) per side,
   * NPW10 4.2's size. SetVoxelSide(n) sets n x n. Takes effect at the next
   * Voxelize().
   */
  virtual void SetVoxelSize(int width, int height);
  void SetVoxelSize(const int size[2]) { this->SetVoxelSize(size[0], size[1]); }
  void SetVoxelSide(int side) { this->SetVoxelSize(side, side); }
  vtkGetVector2Macro(VoxelSize, int);
  ///@}

  ///@{
  /**
   * Depth slices per voxel pixel: 128 (the default, NPW10 4.2's 128 bits;
   * vtkMRGIPass's area lights use 256), 256, 384 or 512; other values are rounded up to a multiple of 128 and
   * clamped to 128..512. Each 128 slices are one more RGBA32UI render target
   * in the same draw (NPW10 3.3) and one more layer of the voxel texture.
   * Thinner slices make voxels thinner in depth: a surface no longer
   * fills a slice's depth in front of and behind itself, and rays that
   * pass an occluder's edge closer than a 128th of the depth range are
   * no longer hidden. The voxel side does not follow (see
   * AutomaticVoxelSize): a march takes one step per voxel pixel, so the
   * slices cost little (the march reads one layer per step, two where a
   * step crosses a layer's edge), while a larger side costs steps.
   * Documentation/AreaLights.md measures both. Takes effect at the next
   * Voxelize().
   */
  virtual void SetNumberOfSlices(int slices);
  vtkGetMacro(NumberOfSlices, int);
  ///@}

  ///@{
  /**
   * When on (the default), each Voxelize() sizes the buffer so that a
   * voxel pixel is about as wide as 128 slices are deep: at the middle of
   * the depth range, a pixel spans (far - near) / 128
   * (mrgi_voxel_isotropic_size() at 128 slices: 128..512 per side, in steps
   * of 16), whatever NumberOfSlices is: more slices refine the depth only.
   * A shallow scene seen up close (a Cornell box) gets finer voxel pixels
   * than 128^2, a deep one (a room seen from inside) keeps 128^2. Off:
   * VoxelSize. Documentation/AreaLights.md measures the difference.
   */
  vtkSetMacro(AutomaticVoxelSize, bool);
  vtkGetMacro(AutomaticVoxelSize, bool);
  vtkBooleanMacro(AutomaticVoxelSize, bool);
  ///@}

  /**
   * The buffer size Voxelize(ren, nearDepth, farDepth) would use: VoxelSize,
   * or with AutomaticVoxelSize the isotropic size for ren's active camera
   * and viewport. False, with VoxelSize in `size`, when the automatic size
   * cannot be computed (no renderer, camera or viewport, an invalid range
   * or projection: Voxelize() refuses those too). Every process of a
   * distributed render gets the same size from the same camera and range.
   */
  bool ComputeVoxelSize(vtkRenderer* ren, double nearDepth, double farDepth, int size[2]) const;

  /**
   * Voxelize the renderer's opaque polygonal props with its active camera
   * into the voxel texture, slicing [nearDepth, farDepth] (linear eye
   * depths). The renderer must belong to an OpenGL window that has rendered
   * at least once. False, with an error naming the problem and the previous
   * buffer kept, for: no renderer/window, a window never rendered, no active
   * camera, a renderer of zero size, NaN or infinite depths, nearDepth >=
   * farDepth (also after rounding to float), nearDepth <= 0 with a
   * perspective camera, a camera projection the voxel projection cannot
   * express (mirrored, sheared or off-axis), or an OpenGL failure. The
   * pass is a GPU timer event ("voxelize") on `timer` when given.
   */
  bool Voxelize(vtkRenderer* ren, double nearDepth, double farDepth, vtkRenderTimerLog* timer = nullptr);

  /**
   * The depth range to voxelize for `ren`'s active camera: its visible
   * props' depth range within the clipping range, with a small margin
   * (mrgi_voxel_fit_depth_range(): VTK pads the clipping range, which would
   * waste slices), or the clipping range when the bounds are unusable.
   * False (range untouched) without a renderer or camera.
   */
  static bool ComputeDepthRange(vtkRenderer* ren, double range[2]);

  /**
   * Read the last voxel buffer back: S / 32 unsigned 32-bit words per voxel
   * pixel (S slices; word w holds slices 32 w .. 32 w + 31: layer w / 4's
   * channel w % 4), rows bottom up, texel (x, y) at tuple y VW + x: the
   * storage of mrgi_voxel.h. The array gets S / 32 components and VW VH tuples. False (array
   * untouched) before a successful Voxelize(), without a window, or with a window other than the
   * one voxelized in.
   */
  bool ReadVoxels(vtkRenderWindow* window, vtkTypeUInt32Array* voxels);

  /**
   * Replace the voxels of the last successful Voxelize() by `voxels`, in
   * ReadVoxels()'s layout and size (e.g. the OR of several processes'
   * voxels over the same grid). False (voxels untouched) under the same
   * conditions as ReadVoxels(), or for an array of another size.
   */
  bool WriteVoxels(vtkRenderWindow* window, vtkTypeUInt32Array* voxels);

  /**
   * The voxel buffer (GL_TEXTURE_3D of GL_RGBA32UI, one depth layer per 128
   * slices, nearest filtering) of the last successful Voxelize(), for later
   * passes (usampler3D + texelFetch); nullptr before. Owned by this object.
   */
  vtkTextureObject* GetVoxelTexture() const;

  /** Size of the last voxel buffer (0 x 0 before a successful Voxelize()). */
  void GetLastVoxelSize(int size[2]) const;

  /** Depth slices of the last voxel buffer (0 before a successful Voxelize()). */
  int GetLastNumberOfSlices() const;

  /** Depth range [near, far] of the last voxel buffer, as the floats the shader used. */
  void GetLastDepthRange(double range[2]) const;

  /** Whether the last voxel buffer was made with a parallel projection. */
  bool GetLastParallelProjection() const;

  /**
   * The world -> eye matrix of the last voxelization (the camera's
   * model-view matrix), column-major (OpenGL order). False before.
   */
  bool GetLastWorldToView(double worldToView[16]) const;

  /** Triangles drawn by the last Voxelize(). */
  vtkIdType GetNumberOfTriangles() const;

  /** Actors (assembly parts and composite leaves count one each) drawn by the last Voxelize(). */
  int GetNumberOfDrawnProps() const;

  /** Visible props the last Voxelize() did not draw (translucent, not polygonal: see the class notes). */
  int GetNumberOfSkippedProps() const;

#ifndef __VTK_WRAP__
  /**
   * The slicing and projection of the last voxel buffer, for the ray march
   * and the C twins (mrgi_voxel_march.h): `grid` as mrgi_voxel_grid_init()
   * makes it (size, near, far, slice scale), `projection` the camera's
   * (section 4). Either pointer may be null. False (nothing written) before
   * a successful Voxelize().
   */
  bool GetGrid(mrgi_voxel_grid* grid, mrgi_voxel_projection* projection) const;
#endif

  ///@{
  /**
   * Knobs of the ray march (mrgi_voxel_march_params, mrgi_voxel_march.h),
   * used by SetMarchUniforms(program) and GetMarchParams(); defaults and
   * ranges are the core's, out-of-range values are clamped (NaN is ignored):
   * - MaxSteps: step cap, 1..MRGI_VOXEL_MAX_STEPS (4096), default
   *   MRGI_VOXEL_DEFAULT_MAX_STEPS (256, one step per voxel pixel along the
   *   diagonal of a 181^2 buffer). Longer rays take longer steps (NPW10
   *   3.3.1 samples the ray uniformly; a sparse sampling may miss thin
   *   occluders).
   * - NormalOffset: bias pushing both ends off their surfaces along their
   *   normals, in voxel sizes, 0..MRGI_VOXEL_MAX_NORMAL_OFFSET (16), default
   *   MRGI_VOXEL_DEFAULT_NORMAL_OFFSET (1.5): below 1.25 receivers shadow
   *   themselves (NPW10 4.3 "shadow acne"), larger values miss more contact
   *   shadows.
   * - SkipRadius: the (2r+1)^3 voxels around each end never occlude,
   *   0..MRGI_VOXEL_MAX_SKIP_RADIUS (8), default
   *   MRGI_VOXEL_DEFAULT_SKIP_RADIUS (1).
   */
  virtual void SetMaxSteps(int steps);
  vtkGetMacro(MaxSteps, int);
  virtual void SetNormalOffset(double offset);
  vtkGetMacro(NormalOffset, double);
  virtual void SetSkipRadius(int radius);
  vtkGetMacro(SkipRadius, int);
  ///@}

  /** Which ends of a march take their offset along the ray (mrgi_voxel_march.h, "The bias"). */
  enum OffsetAlongRayMode
  {
    OffsetNormals = 0,       ///< both along their normals (NPW10 4.3; default)
    OffsetRayAtReceiver = 1, ///< the receiver's along the ray, the light's along its normal
    OffsetRayAtBoth = 2      ///< both along the ray
  };

  ///@{
  /**
   * The NormalOffset's direction. Along a normal, the offset moves the whole
   * ray sideways, towards an occluder on that side: rays that pass close to
   * an edge (a penumbra) are then hidden. Along the ray, the same height
   * above the surface is reached without moving the ray, at the cost of
   * occluders within about two offsets of the end along grazing rays. Ends
   * whose ray leaves at cosine < 0.25 to the normal keep the normal
   * (blended up to 0.5). Measured per scene in Documentation/Status.md;
   * default OffsetNormals.
   */
  virtual void SetOffsetAlongRay(int mode);
  vtkGetMacro(OffsetAlongRay, int);
  void SetOffsetAlongRayToNormals() { this->SetOffsetAlongRay(OffsetNormals); }
  void SetOffsetAlongRayToReceiver() { this->SetOffsetAlongRay(OffsetRayAtReceiver); }
  void SetOffsetAlongRayToBoth() { this->SetOffsetAlongRay(OffsetRayAtBoth); }
  ///@}

  /**
   * Most steps one march through the last voxelization takes: MaxSteps, or
   * the buffer's larger side + 2 when that is less (mrgi_voxel_step_bound()).
   * Stages size their sample batches with it (mrgi_voxel_samples_per_batch()).
   */
  int GetMarchStepBound() const;

#ifndef __VTK_WRAP__
  /** MaxSteps, NormalOffset (as float) and SkipRadius as the core's struct. */
  void GetMarchParams(mrgi_voxel_march_params* params) const;

  /**
   * Set every uniform of the march library (GetMarchShaderSource()) in
   * `program` for the last Voxelize() and `params`: the grid (mrgiVoxelGridSize, mrgiVoxelSlices,
   * mrgiVoxelNear, mrgiVoxelFar, mrgiVoxelSliceScale), the projection
   * (mrgiVoxelProjectionScale, mrgiVoxelProjectionOffset, mrgiVoxelParallel),
   * the knobs (mrgiVoxelMaxSteps, mrgiVoxelNormalOffset, mrgiVoxelSkipRadius),
   * all as the same floats and ints the C twin reads from GetGrid() and
   * `params`; and activates the voxel texture on a texture unit bound to
   * mrgiVoxelTexture. Uniforms the program does not use are skipped. The
   * program must be bound (as after vtkOpenGLShaderCache::ReadyShaderProgram()
   * or a vtkOpenGLQuadHelper's construction) in the window voxelized in;
   * call GetVoxelTexture()->Deactivate() after drawing to free the unit.
   * False, with an error and nothing set, for a null program, no successful
   * Voxelize() yet, or `params` out of range (mrgi_voxel_march_params_validate()).
   */
  bool SetMarchUniforms(vtkShaderProgram* program, const mrgi_voxel_march_params& params);

  /** SetMarchUniforms() with this object's MaxSteps, NormalOffset and SkipRadius. */
  bool SetMarchUniforms(vtkShaderProgram* program);

  /**
   * The GLSL of the ray march (vtkMRGIVoxelMarch.glsl): uniforms and
   * functions, no main() and no #version. Put it in a fragment shader after
   * //VTK::System::Dec and the core's constants block (mrgi_glsl_defines()).
   */
  static const char* GetMarchShaderSource();
#endif

  /**
   * Free every GL resource (texture, framebuffer, vertex buffers, vertex
   * array) in `w`'s context (the window last voxelized in). Voxelizing in
   * another window frees them in the old one first (or forgets them when
   * that window is gone).
   */
  void ReleaseGraphicsResources(vtkWindow* w);

protected:
  vtkMRGIVoxelization();
  ~vtkMRGIVoxelization() override;

  int VoxelSize[2];
  int NumberOfSlices;
  bool AutomaticVoxelSize = true;
  int MaxSteps;
  double NormalOffset;
  int OffsetAlongRay;
  int SkipRadius;

  struct Internals;
  std::unique_ptr<Internals> Internal;

private:
  // ComputeVoxelSize() for a camera projection already built (Voxelize()
  // builds it once for both).
  bool VoxelSizeFor(const mrgi_voxel_projection& projection, double nearDepth, double farDepth,
    int size[2]) const;

  vtkMRGIVoxelization(const vtkMRGIVoxelization&) = delete;
  void operator=(const vtkMRGIVoxelization&) = delete;
};

#endif
