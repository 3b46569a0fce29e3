/**
 * @class   vtkMRGIImperfectShadowMaps
 * @brief   Imperfect shadow maps (ritschel-et-al-2008 3.3,
 *          ritschel-et-al-2011 5-6.1): one small cos-sphere depth map per
 *          VPL, drawn from a sparse point set of the scene, in one atlas.
 *
 * Each frame Update():
 *  1. collects the triangles of the renderer's visible opaque actors in
 *     world space (points of point-cloud actors with normals are their own
 *     point set, mrgi_ism_points.h section 4); a topology change restarts
 *     the point set, a moving or deforming mesh keeps it (records are
 *     (triangle, barycentrics));
 *  2. keeps PointsPerVPL x V point records (mrgi_ism_points.h): uniform or
 *     view-adaptive density (PointMode), view samples from the frame's
 *     G-buffer; LazyFrames > 1 resamples 1 / LazyFrames of them per frame
 *     (RIHKS11 5.3), 1 resamples all;
 *  3. evaluates the points' positions (C core, current vertices), uploads
 *     them and draws them as GL points into the atlas in ONE draw: point i
 *     goes to VPL i mod V (mrgi_ism_atlas.h section 2), cos-sphere
 *     projection, nearest distance kept (MIN blending on R32F);
 *  4. push-pulls each tile over PushPullLevels levels (default 1; 0 off;
 *     mrgi_ism_atlas.h section 4), one pass per level and direction.
 * C twins: mrgi_ism_points.h (records, positions), mrgi_ism_atlas.h
 * (texel of each point, push-pull). Shaders: vtkMRGIISMPointsVS/FS.glsl,
 * vtkMRGIISMPushPullFS.glsl, with vtkMRGIISMProjection.glsl.
 */
#ifndef vtkMRGIImperfectShadowMaps_h
#define vtkMRGIImperfectShadowMaps_h

#include "MRGIRenderingModule.h" // For export macro
#include "vtkObject.h"

#include "mrgi_ism_atlas.h"  // For mrgi_ism_atlas_layout
#include "mrgi_ism_points.h" // For mrgi_ism_point

#include <memory> // For std::unique_ptr

struct vtkMRGIFrameContext;
class vtkMRGIViewSamples;
class vtkFloatArray;
class vtkOpenGLRenderWindow;
class vtkRenderWindow;
class vtkRenderer;
class vtkTextureObject;
class vtkWindow;

class MRGIRENDERING_EXPORT vtkMRGIImperfectShadowMaps : public vtkObject
{
public:
  static vtkMRGIImperfectShadowMaps* New();
  vtkTypeMacro(vtkMRGIImperfectShadowMaps, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum PointModes
  {
    Uniform = 0,   ///< density proportional to area (ritschel-et-al-2008)
    Adaptive1 = 1, ///< solid angle from one view sample per triangle (RIHKS11 5.2)
    Adaptive8 = 2  ///< mean solid angle of 8 view samples per triangle (default)
  };

  ///@{
  /** Point density (mrgi_ism_points.h section 1). Default Adaptive8. */
  vtkSetClampMacro(PointMode, int, Uniform, Adaptive8);
  vtkGetMacro(PointMode, int);
  ///@}

  ///@{
  /** Points drawn into each VPL's tile. Default 256. */
  vtkSetClampMacro(PointsPerVPL, int, 1, 65536);
  vtkGetMacro(PointsPerVPL, int);
  ///@}

  ///@{
  /** Tile side T (a power of two, 4..MRGI_ISM_MAX_TILE). Default 32. */
  vtkSetClampMacro(TileSize, int, 4, MRGI_ISM_MAX_TILE);
  vtkGetMacro(TileSize, int);
  ///@}

  ///@{
  /**
   * Lazy update (RIHKS11 5.3): each frame resamples 1 / LazyFrames of the
   * point records; 1 resamples all of them every frame. Default 8.
   */
  vtkSetClampMacro(LazyFrames, int, 1, 64);
  vtkGetMacro(LazyFrames, int);
  ///@}

  ///@{
  /**
   * Push-pull hole filling (mrgi_ism_atlas.h section 4) after the point
   * draw, over this many levels: 1 fills a hole from its 2x2 block, log2 of
   * the tile size (or more) from the whole tile, 0 turns it off (holes stay
   * empty, i.e. visible). Default MRGI_ISM_DEFAULT_PUSH_PULL_LEVELS (1; see
   * that constant for why few levels).
   */
  vtkSetClampMacro(PushPullLevels, int, 0, MRGI_ISM_MAX_PUSH_PULL_LEVELS);
  vtkGetMacro(PushPullLevels, int);
  ///@}

  ///@{
  /** Seed of the point sampling (deterministic images). */
  vtkSetMacro(Seed, unsigned int);
  vtkGetMacro(Seed, unsigned int);
  ///@}

#ifndef __VTK_WRAP__
  /**
   * Build this frame's atlas for the `vplCount` VPLs of the VPL cache
   * `vpls` (mrgi_vpl.h records, world space), from the scene of
   * frame.Renderer (steps 1-4 of the class comment). Timer steps
   * "ism.points", "ism.draw", "ism.pushpull". False, with an error naming
   * the problem (no opaque geometry, a bad tile size, an atlas larger than
   * GL_MAX_TEXTURE_SIZE or MRGI_ISM_MAX_ATLAS), and no atlas, on failure.
   * The adaptive modes' view samples come from `shared` (the frame's one
   * G-buffer read-back, vtkMRGIIndirectLight's) or, when null, from this
   * object's own; either reads back only when the camera or the props
   * changed.
   */
  bool Update(const vtkMRGIFrameContext& frame, vtkTextureObject* vpls, int vplCount,
    vtkMRGIViewSamples* shared = nullptr);

  /**
   * Steps 3-4 alone, for given world-space point positions (xyz floats,
   * `pointCount` points, point i to VPL i mod vplCount): the parity tests'
   * entry, and the C twin's inputs.
   */
  bool Render(vtkOpenGLRenderWindow* window, const float* points, int pointCount,
    vtkTextureObject* vpls, int vplCount);
#endif

  /** The R32F atlas of the last Update()/Render() (push-pulled unless PushPullLevels is 0); null before. */
  vtkTextureObject* GetAtlasTexture() const;

  /** The last atlas' layout (vpl_count 0 before). */
  const mrgi_ism_atlas_layout& GetLayout() const;

  /** Read the atlas back (width x height floats, row 0 = atlas row 0). */
  bool ReadAtlas(vtkRenderWindow* window, vtkFloatArray* depth);

  ///@{
  /**
   * The point set of the last Update() (for tests and statistics): record
   * count P = PointsPerVPL x V, the records (mrgi_ism_points.h; triangle or
   * cloud point index and barycentrics), their world positions (3 P floats),
   * the number of triangles (0 for a point cloud), the records the last
   * Update() redrew and the view samples it read (0 in Uniform mode or
   * without a G-buffer; adaptive modes then fall back to uniform weights). Null / 0 before the first successful Update().
   */
  vtkIdType GetNumberOfPoints() const;
#ifndef __VTK_WRAP__
  const mrgi_ism_point* GetPointRecords() const;
#endif
  const float* GetPointPositions() const;
  vtkIdType GetNumberOfTriangles() const;
  vtkIdType GetNumberOfResampledPoints() const;
  vtkIdType GetNumberOfViewSamples() const;
  ///@}

  /** Free every GL resource (and the point set). */
  void ReleaseGraphicsResources(vtkWindow* w);

protected:
  vtkMRGIImperfectShadowMaps();
  ~vtkMRGIImperfectShadowMaps() override;

  int PointMode = Adaptive8;
  int PointsPerVPL = 256;
  int TileSize = 32;
  int LazyFrames = 8;
  int PushPullLevels = MRGI_ISM_DEFAULT_PUSH_PULL_LEVELS;
  unsigned int Seed = 1;

  struct Internals;
  std::unique_ptr<Internals> Internal;

private:
  bool CollectScene(vtkRenderer* ren);
  void ReadViewSamples(const vtkMRGIFrameContext& frame, vtkMRGIViewSamples& samples);


private:
  vtkMRGIImperfectShadowMaps(const vtkMRGIImperfectShadowMaps&) = delete;
  void operator=(const vtkMRGIImperfectShadowMaps&) = delete;
};

#endif
