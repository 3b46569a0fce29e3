/**
 * @class   vtkMRGIPCDReader
 * @brief   Reads a Point Cloud Library PCD file as a vtkPolyData of vertices.
 *
 * The base of an object-factory override, like vtkRenderWindow: PCD files
 * are read through PCL's own I/O, which lives in MRGI's PCL module
 * (MRGI::RenderingPCL, library MRGIRenderingPCL). That module is built only
 * against Debian's VTK 9.1, the VTK PCL itself links, and never in the
 * ParaView (VTK 9.2) build. When it is loaded (mrgi-render, the tests and
 * the Python package `mrgi` load it in the VTK 9.1 build; a C++ program
 * links MRGI::RenderingPCL and lists it in vtk_module_autoinit),
 * vtkMRGIPCDReader::New() returns a vtkMRGIPCLPCDReader. Without it, this
 * class itself is returned and every read fails with "reading PCD needs
 * MRGI's PCL module (MRGI::RenderingPCL), which this build lacks".
 *
 * What the PCL reader produces (see vtkMRGIPCLPCDReader): one vertex per
 * finite point; "RGB" (unsigned char, 3 components, the active scalars)
 * from rgb/rgba; "Normals" from normal_x/y/z; "Intensity"; "Curvature";
 * for organized clouds "PixelIndex" (the row-major index of each point in
 * the WIDTH x HEIGHT image) and field data "OrganizedDimensions" (width,
 * height); the VIEWPOINT as field data "SensorOrigin" (x, y, z) and
 * "SensorOrientation" (quaternion w, x, y, z).
 *
 * Errors (no file name, a file that cannot be read, a corrupt file) give an
 * error naming the file and an empty output; the request fails.
 */
#ifndef vtkMRGIPCDReader_h
#define vtkMRGIPCDReader_h

#include "MRGIRenderingIOModule.h" // For export macro
#include "vtkPolyDataAlgorithm.h"

class MRGIRENDERINGIO_EXPORT vtkMRGIPCDReader : public vtkPolyDataAlgorithm
{
public:
  /**
   * The object factory's override when MRGI::RenderingPCL is loaded, else
   * this class (whose reads fail, saying why).
   */
  static vtkMRGIPCDReader* New();
  vtkTypeMacro(vtkMRGIPCDReader, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * The PCD file to read.
   */
  vtkSetStringMacro(FileName);
  vtkGetStringMacro(FileName);
  ///@}

protected:
  vtkMRGIPCDReader();
  ~vtkMRGIPCDReader() override;

  /**
   * Fails: the base class cannot read PCD (see the class documentation).
   */
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  char* FileName = nullptr;

private:
  vtkMRGIPCDReader(const vtkMRGIPCDReader&) = delete;
  void operator=(const vtkMRGIPCDReader&) = delete;
};

#endif
