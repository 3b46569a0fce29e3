/**
 * @class   vtkMRGISceneSource
 * @brief   MRGI's scenes (built-in or a data file) as a pipeline source.
 *
 * The geometry that vtkMRGISceneBuilder (and so `mrgi-render SCENE`) puts
 * in a renderer, as vtkPolyData: every mesh appended (MeshIndex -1, the
 * default), each cell with its material in the cell arrays "Albedo" and
 * "Emission" (linear RGB, floats; colour by "Albedo" with MapScalars off),
 * or one mesh (MeshIndex >= 0) with its material as the field arrays
 * "Albedo" and "Emission" (one tuple each, to set a representation's
 * colours exactly). The scene's camera and lights are available from the
 * getters below, so that a ParaView script can set up the very scene
 * mrgi-render draws.
 *
 * Pieces: asked for piece p of P, the output holds the meshes whose index
 * is p modulo P (a whole-mesh partition, e.g. the Cornell box split
 * across MPI ranks); with MeshIndex >= 0, piece (MeshIndex mod P) holds
 * the mesh and the others are empty.
 *
 * Bad input: an unknown scene or an unreadable file, or a MeshIndex past
 * the scene's meshes, is an error naming the problem and gives an empty
 * output.
 */
#ifndef vtkMRGISceneSource_h
#define vtkMRGISceneSource_h

#include "MRGIParaViewModule.h" // For export macro
#include "vtkPolyDataAlgorithm.h"
#include "vtkSmartPointer.h" // For vtkSmartPointer

#include <string> // For std::string

class vtkDoubleArray;
class vtkRenderer;

class MRGIPARAVIEW_EXPORT vtkMRGISceneSource : public vtkPolyDataAlgorithm
{
public:
  static vtkMRGISceneSource* New();
  vtkTypeMacro(vtkMRGISceneSource, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /** A built-in scene name (cornell, cornell-spot, ...) or a data file path; default "cornell". */
  vtkSetStdStringFromCharMacro(Scene);
  vtkGetCharFromStdStringMacro(Scene);
  ///@}

  ///@{
  /** -1 (default): every mesh; i >= 0: mesh i alone. */
  vtkSetClampMacro(MeshIndex, int, -1, VTK_INT_MAX);
  vtkGetMacro(MeshIndex, int);
  ///@}

  /** Meshes in the scene (0 when it cannot be built). */
  int GetNumberOfMeshes();

  ///@{
  /** The scene's camera (what mrgi-render uses); zeros when it cannot be built. */
  double* GetCameraPosition() VTK_SIZEHINT(3);
  double* GetCameraFocalPoint() VTK_SIZEHINT(3);
  double* GetCameraViewUp() VTK_SIZEHINT(3);
  double GetCameraViewAngle();
  ///@}

  /**
   * The scene's lights, one tuple each of 13 components: positional (0/1),
   * position (3), focal point (3), colour (3), intensity, cone angle
   * (degrees, >= 90 for a light that is not a spot), exponent.
   */
  vtkDoubleArray* GetLightParameters();

  /**
   * The scene's area lights (cornell-area: the published emitter), one
   * tuple each of 14 components: centre (3), EdgeU (3), EdgeV (3), colour
   * (3), intensity, two-sided (0/1): the properties of an "MRGI Area Light"
   * (vtkMRGIAreaLightSource) at the same place. A textured light's picture
   * is not included.
   */
  vtkDoubleArray* GetAreaLightParameters();

  /** Why the last build failed; empty after a success. */
  const char* GetLastErrorMessage() { return this->LastErrorMessage.c_str(); }

protected:
  vtkMRGISceneSource();
  ~vtkMRGISceneSource() override;

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  /** Builds the scene into this->Renderer when Scene changed; false on error. */
  bool BuildScene();

  std::string Scene = "cornell";
  int MeshIndex = -1;
  std::string BuiltScene;
  std::string LastErrorMessage;
  vtkSmartPointer<vtkRenderer> Renderer;
  vtkSmartPointer<vtkDoubleArray> Lights;
  vtkSmartPointer<vtkDoubleArray> AreaLights;
  double CameraPosition[3] = { 0, 0, 0 };
  double CameraFocalPoint[3] = { 0, 0, 0 };
  double CameraViewUp[3] = { 0, 0, 0 };
  double CameraViewAngle = 0;

private:
  vtkMRGISceneSource(const vtkMRGISceneSource&) = delete;
  void operator=(const vtkMRGISceneSource&) = delete;
};

#endif
