/**
 * @class   vtkMRGISceneBuilder
 * @brief   Fills a vtkRenderer with a built-in MRGI scene or a data file.
 *
 * Built-in scenes come from MRGI's C core (the same triangles the CPU
 * reference renderer sees):
 * - "cornell": the published Cornell box (millimetres, published camera) lit
 *   by a point light just under the emitter;
 * - "cornell-spot": the same box lit by a wide spot light aimed at the floor;
 * - "cornell-area": the same box with its published emitter as an area light
 *   (drawn as an emissive quad; area lighting itself is MRGI's area-light
 *   pass, no vtkLight stands in for it);
 * - "living-room": a room (metres) with a sofa, a coffee table and a
 *   bookshelf, lit only by a TV screen: one one-sided textured area light
 *   (a 64 x 36 test card, 1.2 x 0.7 m; the screen mesh draws the light's
 *   picture through vtkMRGIAreaLight::ShareGeometryActor()),
 *   nichols-penmatsa-wyman-2010's living room (mrgi_scene_living_room.h);
 * - "scaling": ObjectCount objects with TriangleCount triangles in total,
 *   laid out so that screen coverage does not depend on the triangle count;
 * - "corridor", "corridor-large", "corner", "u-shape" (metres): scenes lit
 *   by one spot where indirect light and indirect shadows dominate, after
 *   RIHKS11 figures 7, 10 and 5 (mrgi_scene_indirect.h): a 12 m (120 m)
 *   closed corridor whose statue is lit only by the bounce off the end wall
 *   behind the camera, an open corner with a spot into it, and a closed
 *   U-shaped corridor whose camera sees no directly lit surface.
 *
 * Files are read with VTK's readers, chosen by extension: .vtp .vtu .vti
 * .vts .vtr .vtm (XML), .vtk (legacy), .ply, .obj, .stl, .gltf/.glb
 * (vtkGLTFImporter), and MRGI's: .las (vtkMRGILASReader; .laz is refused:
 * "compressed LAZ is not supported"), .pcd (vtkMRGIPCDReader, which needs
 * MRGI::RenderingPCL). Data sets that are not polygonal are reduced to their
 * outer surface as ParaView's Surface representation does
 * (vtkDataSetSurfaceFilter); active point scalars of 1 or 2 components
 * (unsigned char included) are coloured through a lookup table over the data
 * set's range, 3- and 4-component unsigned-char scalars are used directly.
 * Files bring no camera (ResetCamera frames them; flat data is seen face on)
 * and no lights (VTK's headlight lights them unless lights are added), unless
 * a vtkMRGIStaging is set (SetStaging()): it then frames them, adds a ground
 * and a key light, and volumes (vtkMRGIStaging::IsVolume()) are shown as
 * their iso-surface instead of their outer surface.
 * Point clouds (vtkMRGIPointCloud::IsPointCloud(): points with vertex
 * cells or no cells, from any reader) are drawn as oriented surfels of
 * their finite points (points with a NaN coordinate are left out; a cloud
 * without a finite point is an error): vtkMRGIPointCloudNormals estimates
 * normals the file lacks and a splat radius per point, vtkMRGISurfels
 * makes the disks, at most SurfelsPerPixel times the pixels the cloud
 * covers in the framed view. LAS clouds show their display colours (RGB,
 * classes or intensity).
 *
 * Only regular files are read. Before a VTK reader sees a PLY, OBJ, legacy
 * VTK, VTK XML or glTF file, the core's structure check of that format
 * (mrgi_ply_check.h and its siblings) refuses what would crash or exhaust
 * the reader; what a reader returns is checked before any filter runs (point
 * ids and offsets in range, known cell types with their point counts, finite
 * coordinates, at most 2^28 points).
 *
 * Errors (unknown scene, missing/unreadable/corrupt file, a file with no
 * geometry) leave the renderer unchanged and are reported by a false return
 * and GetLastErrorMessage(), a line that names the file and the problem.
 */
#ifndef vtkMRGISceneBuilder_h
#define vtkMRGISceneBuilder_h

#include "MRGIRenderingIOModule.h" // For export macro
#include "vtkObject.h"

#include "vtkSmartPointer.h" // For vtkSmartPointer
#include <string>             // For std::string
#include <vector>             // For std::vector

class vtkMRGIAreaLight;
class vtkPointSet;
class vtkMRGIStaging;
class vtkPolyData;
class vtkRenderer;
struct mrgi_mesh;
struct mrgi_scene;

class MRGIRENDERINGIO_EXPORT vtkMRGISceneBuilder : public vtkObject
{
public:
  static vtkMRGISceneBuilder* New();
  vtkTypeMacro(vtkMRGISceneBuilder, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * What to build: a built-in scene name (see the class documentation) or a
   * data file path. A name that is a built-in scene wins over a file of that
   * name in the working directory. Default "cornell".
   */
  vtkSetStdStringFromCharMacro(Scene);
  vtkGetCharFromStdStringMacro(Scene);
  ///@}

  ///@{
  /** Scaling scene: total triangle count (1e3 to 1e7 sensible), default 100000. */
  vtkSetClampMacro(TriangleCount, vtkIdType, 12, 20000000);
  vtkGetMacro(TriangleCount, vtkIdType);
  ///@}

  ///@{
  /** Scaling scene: number of objects, default 64. */
  vtkSetClampMacro(ObjectCount, int, 1, 4096);
  vtkGetMacro(ObjectCount, int);
  ///@}

  ///@{
  /**
   * Point clouds: the surfel budget per covered pixel of the framed view
   * (vtkMRGISurfels::SuggestMaximumNumberOfSurfels()); a denser cloud
   * draws every k-th point with a larger disk. 0 draws every point.
   * Default 16.
   */
  vtkSetClampMacro(SurfelsPerPixel, double, 0.0, 1.0e6);
  vtkGetMacro(SurfelsPerPixel, double);
  ///@}

  ///@{
  /** Scaling scene: random seed; the same seed gives the same scene. */
  vtkSetMacro(Seed, vtkTypeUInt64);
  vtkGetMacro(Seed, vtkTypeUInt64);
  ///@}

  /**
   * Add the scene's actors, lights and (for built-in scenes) camera to
   * `renderer`. Returns false, leaving the renderer as it was, on error.
   */
  bool Build(vtkRenderer* renderer);

  /** True when `name` is a built-in scene name. */
  static bool IsBuiltInScene(const char* name);

  /** Built-in scene names, space separated (for --help texts). */
  static const char* GetBuiltInSceneNames();

  /** Why the last Build() failed; empty after a success. */
  const char* GetLastErrorMessage() { return this->LastErrorMessage.c_str(); }

  /** Triangles added by the last successful Build() (0 for point clouds). */
  vtkGetMacro(BuiltTriangleCount, vtkIdType);

  /**
   * Points drawn by the last successful Build() of a point cloud (its
   * finite points); 0 for meshes and built-in scenes.
   */
  vtkGetMacro(BuiltPointCount, vtkIdType);

  ///@{
  /**
   * The area lights of the last built scene (cornell-area: the published
   * emitter of the Cornell box; living-room: the textured TV screen; each
   * a vtkMRGIAreaLight). They are not added
   * anywhere: give them to vtkMRGIPass::AddAreaLight(). The scene already
   * draws their emitters, so their own geometry is hidden (Visible off).
   */
  int GetNumberOfAreaLights() const { return static_cast<int>(this->AreaLights.size()); }
  vtkMRGIAreaLight* GetAreaLight(int index) const;
  ///@}

  ///@{
  /**
   * Stage data files with this vtkMRGIStaging (up axis, framing, ground,
   * key light; volumes as iso-surfaces) instead of ResetCamera() under
   * VTK's headlight. Default nullptr: not staged. Built-in scenes are never
   * staged. A staged area key light is one of the area lights above.
   */
  void SetStaging(vtkMRGIStaging* staging);
  vtkMRGIStaging* GetStaging();
  ///@}

#ifndef __VTK_WRAP__
  /** A core mesh as vtkPolyData (points, normals, triangles); caller owns it. */
  static vtkPolyData* MeshToPolyData(const mrgi_mesh* mesh);
#endif

protected:
  vtkMRGISceneBuilder();
  ~vtkMRGISceneBuilder() override;

  bool BuildCoreScene(const mrgi_scene* scene, vtkRenderer* renderer);
  bool BuildFile(const std::string& path, vtkRenderer* renderer);
  bool BuildPointCloud(const std::string& path, vtkPointSet* cloud, vtkRenderer* renderer);
  bool Fail(const std::string& why);
  bool Frame(const std::string& path, vtkRenderer* renderer);

  std::string Scene = "cornell";
  vtkIdType TriangleCount = 100000;
  int ObjectCount = 64;
  vtkTypeUInt64 Seed = 1;
  double SurfelsPerPixel = 16.0;
  vtkIdType BuiltTriangleCount = 0;
  vtkIdType BuiltPointCount = 0;
  std::string LastErrorMessage;
  std::vector<vtkSmartPointer<vtkMRGIAreaLight>> AreaLights;
  vtkSmartPointer<vtkMRGIStaging> Staging;

private:
  vtkMRGISceneBuilder(const vtkMRGISceneBuilder&) = delete;
  void operator=(const vtkMRGISceneBuilder&) = delete;
};

#endif
