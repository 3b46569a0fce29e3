/**
 * @class   vtkMRGIStaging
 * @brief   Stages data read from a file so that MRGI's light shows: the up
 *          axis, a camera that frames the data, a ground plane under it,
 *          a key light from above and in front; volumes as iso-surfaces.
 *
 * A data file brings no camera, no lights and no floor: VTK frames it by
 * its bounding sphere, lights it with a headlight and floats it in black,
 * so indirect light has nothing to bounce from and nothing to land on.
 * Stage() is called once the data's actors are in the renderer (it reads
 * their geometry and bounds) and adds what is missing:
 *
 * - **Up axis** (GetDetectedUp()): Up when set (UpPositiveX..UpNegativeZ),
 *   else, for UpAuto, the first cue found in the actors' data:
 *   1. field data of a LAS file (an array whose name starts with "LAS"):
 *      +z, as LAS stores elevation in z;
 *   2. field data of a PCD file (a "VIEWPOINT" array of 7 values tx ty tz
 *      qw qx qy qz, or a "SensorOrientation" array qw qx qy qz that
 *      vtkMRGIPointCloudNormals::SensorPoseIsMeaningful() accepts: PCL
 *      writes the identity pose into every file): the sensor's -y axis
 *      rotated by the orientation (depth cameras have y down), rounded to
 *      the nearest world axis;
 *   3. the geometry (mrgi_up_axis.h): a flat base, an open base (a scan's
 *      hole where the turntable was), for point clouds a point base (one
 *      end of an axis holding many more points than the others: a scan's
 *      base, terrain's ground), a thin extent, else +y, VTK's convention.
 *      GetUpReason() names the cue.
 * - **Camera**: the view direction is the "front" (+z for a y or x up
 *   axis, -y for +z, +y for -z; for a sensor pose, the side the sensor
 *   looked from: a depth frame seen from behind shows the backs of its
 *   surfaces) raised by CameraElevation degrees (default 25) towards up; the camera is placed so that the projection of the
 *   data's points (at most 65536 of them, evenly strided) fills
 *   FillFraction (default 0.8) of the image's width or height, whichever
 *   limits, centred (mrgi_framing.h), with the renderer's aspect and the
 *   camera's view angle. The parallel scale is set to match at the focal
 *   point.
 * - **Ground** (Ground, default on): a matte grey (albedo 0.7, no specular)
 *   quad just under the data along up (1e-3 of its size below its lowest
 *   point), facing up, covering what the camera sees of its plane (the
 *   view's corner rays hit it), at least 3 and at most 20 times the data's
 *   horizontal size around its centre (at most 6 with an area key light:
 *   its voxel shadows slice the depth range the ground stretches): it
 *   receives the bounce and the shadows. GetGroundActor().
 * - **Key light** (KeyLight): KeyLightSpot (default) a spot light above
 *   (55 degrees) and in front of the data, 35 degrees to the camera's
 *   left, at 4 bounding radii, its cone covering 3.5 radii around the data
 *   with a cos^10 fall-off inside it (a soft edge on the ground), intensity
 *   1 (GetKeyLightObject()); KeyLightArea a square vtkMRGIAreaLight of one radius
 *   at the same place facing the data, its radiance such that the data's
 *   centre receives the irradiance of the spot (GetAreaLight(); give it to
 *   vtkMRGIPass::AddAreaLight(); its emitter is not drawn), with a switched
 *   on light of intensity 0 that keeps VTK's lighting on; KeyLightNone
 *   leaves the renderer's lights as they are. Spot and Area remove the
 *   renderer's lights and switch its automatic headlight off.
 * - **Volumes**: IsVolume() tells a data set with 3D cells (an image with
 *   three dimensions above 1 included) and active one-component point
 *   scalars; MakeIsoSurface() contours it (vtkFlyingEdges3D for images,
 *   vtkContourFilter otherwise) at IsoValue, or, with AutomaticIsoValue
 *   (default on), at Otsu's threshold of its scalars' histogram
 *   (mrgi_iso_value.h). vtkMRGISceneBuilder calls it for the volumes it
 *   reads when it stages.
 *
 * Stage() may be called again (after a change of a property): it removes
 * what it added before. What it added stays when the staging object is
 * deleted (the renderer holds it). Errors (no renderer, nothing visible, geometry that
 * is not finite) return false and GetLastErrorMessage() says why; the
 * renderer is then left as it was.
 */
#ifndef vtkMRGIStaging_h
#define vtkMRGIStaging_h

#include "MRGIRenderingIOModule.h" // For export macro
#include "vtkObject.h"

#include "vtkSmartPointer.h" // For vtkSmartPointer
#include "vtkWeakPointer.h"  // For vtkWeakPointer
#include <limits>            // For std::numeric_limits
#include <string>            // For std::string

class vtkActor;
class vtkDataObject;
class vtkDataSet;
class vtkLight;
class vtkMRGIAreaLight;
class vtkPolyData;
class vtkRenderer;

class MRGIRENDERINGIO_EXPORT vtkMRGIStaging : public vtkObject
{
public:
  static vtkMRGIStaging* New();
  vtkTypeMacro(vtkMRGIStaging, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /** Up axis choices; the axes have the values of mrgi_axis. */
  enum UpAxis
  {
    UpAuto = -1,
    UpPositiveX = 0,
    UpNegativeX = 1,
    UpPositiveY = 2,
    UpNegativeY = 3,
    UpPositiveZ = 4,
    UpNegativeZ = 5
  };

  /** Key light choices. */
  enum KeyLightType
  {
    KeyLightNone = 0,
    KeyLightSpot = 1,
    KeyLightArea = 2
  };

  ///@{
  /** The up axis, or UpAuto (default) to detect it (class documentation). */
  vtkSetClampMacro(Up, int, UpAuto, UpNegativeZ);
  vtkGetMacro(Up, int);
  ///@}

  ///@{
  /** Add a ground plane under the data. Default on. */
  vtkSetMacro(Ground, bool);
  vtkGetMacro(Ground, bool);
  vtkBooleanMacro(Ground, bool);
  ///@}

  ///@{
  /** The key light: KeyLightNone, KeyLightSpot (default) or KeyLightArea. */
  vtkSetClampMacro(KeyLight, int, KeyLightNone, KeyLightArea);
  vtkGetMacro(KeyLight, int);
  ///@}

  ///@{
  /** Fraction of the image the data's projection fills, in [0.05, 1]. Default 0.8. */
  vtkSetClampMacro(FillFraction, double, 0.05, 1.0);
  vtkGetMacro(FillFraction, double);
  ///@}

  ///@{
  /** Camera elevation above the front direction, degrees in [0, 89]. Default 25. */
  vtkSetClampMacro(CameraElevation, double, 0.0, 89.0);
  vtkGetMacro(CameraElevation, double);
  ///@}

  ///@{
  /**
   * The iso-value of volumes when AutomaticIsoValue is off. Setting it does
   * not switch AutomaticIsoValue off by itself.
   */
  vtkSetMacro(IsoValue, double);
  vtkGetMacro(IsoValue, double);
  ///@}

  ///@{
  /** Contour volumes at Otsu's threshold of their scalars. Default on. */
  vtkSetMacro(AutomaticIsoValue, bool);
  vtkGetMacro(AutomaticIsoValue, bool);
  vtkBooleanMacro(AutomaticIsoValue, bool);
  ///@}

  /**
   * Stage the renderer's visible actors (class documentation). Returns
   * false, leaving the renderer as it was, on error.
   */
  bool Stage(vtkRenderer* renderer);

  /** Whether `data` is a volume that MakeIsoSurface() contours. */
  static bool IsVolume(vtkDataObject* data);

  /**
   * Contour `volume`'s active point scalars into `output` (points,
   * triangles and normals; no scalars) at IsoValue or the automatic value
   * (GetLastIsoValue()). False, with GetLastErrorMessage(), when it is not a
   * volume, its scalars are not finite, or the surface is empty.
   */
  bool MakeIsoSurface(vtkDataSet* volume, vtkPolyData* output);

  ///@{
  /**
   * What the last Stage() found (the up axis and the cue that gave it) and
   * the iso-value the last MakeIsoSurface() used (NaN before one ran).
   */
  vtkGetMacro(DetectedUp, int);
  const char* GetUpReason() { return this->UpReason.c_str(); }
  vtkGetMacro(LastIsoValue, double);
  vtkActor* GetGroundActor();
  vtkLight* GetKeyLightObject();
  vtkMRGIAreaLight* GetAreaLight();
  const char* GetLastErrorMessage() { return this->LastErrorMessage.c_str(); }
  ///@}

  /** "auto", "+x", ..., "-z" for an UpAxis value; nullptr for others. */
  static const char* GetUpAxisName(int up);

protected:
  vtkMRGIStaging();
  ~vtkMRGIStaging() override;

  bool Fail(const std::string& why);
  void RemoveStaged();

  int Up = UpAuto;
  bool Ground = true;
  int KeyLight = KeyLightSpot;
  double FillFraction = 0.8;
  double CameraElevation = 25.0;
  double IsoValue = 0.0;
  bool AutomaticIsoValue = true;

  int DetectedUp = UpPositiveY;
  std::string UpReason;
  double LastIsoValue = std::numeric_limits<double>::quiet_NaN();
  std::string LastErrorMessage;

  vtkWeakPointer<vtkRenderer> StagedRenderer; // where RemoveStaged() undoes the last Stage()
  vtkSmartPointer<vtkActor> GroundActor;
  vtkSmartPointer<vtkLight> KeyLightObject;
  vtkSmartPointer<vtkLight> DarkLight;
  vtkSmartPointer<vtkMRGIAreaLight> AreaLight;

private:
  vtkMRGIStaging(const vtkMRGIStaging&) = delete;
  void operator=(const vtkMRGIStaging&) = delete;
};

#endif
