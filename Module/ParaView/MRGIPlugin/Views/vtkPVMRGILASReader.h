/**
 * @class   vtkPVMRGILASReader
 * @brief   ParaView's LAS reader: vtkMRGILASReader behind a class that
 *          ParaView's client-server layer can call.
 *
 * The plugin wraps only its own module (MRGI::ParaViewMRGI) for ParaView's
 * client-server layer; MRGI::RenderingIO, where vtkMRGILASReader lives, is
 * not wrapped there. This class holds the properties ParaView sets and runs
 * a vtkMRGILASReader with them; its output is that reader's output (shallow
 * copy): float points recentred on their bounding box (field data "Origin"
 * gives the world position to add back), one vertex per point, point data
 * "Intensity", "Classification", "ReturnNumber", "NumberOfReturns", "RGB"
 * when the file has colour, and the display colours as active scalars.
 *
 * Errors (missing file, compressed LAZ, bad header, truncated data) are the
 * reader's: one error naming the file and the problem, an empty output,
 * GetErrorCode() set.
 */
#ifndef vtkPVMRGILASReader_h
#define vtkPVMRGILASReader_h

#include "MRGIParaViewModule.h" // For export macro
#include "vtkPolyDataAlgorithm.h"

#include <string> // For std::string

class MRGIPARAVIEW_EXPORT vtkPVMRGILASReader : public vtkPolyDataAlgorithm
{
public:
  static vtkPVMRGILASReader* New();
  vtkTypeMacro(vtkPVMRGILASReader, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /** The LAS file to read. */
  vtkSetStdStringFromCharMacro(FileName);
  vtkGetCharFromStdStringMacro(FileName);
  ///@}

  ///@{
  /**
   * What the active colours show: vtkMRGILASReader::ColorByModes, 0 auto
   * (default), 1 RGB, 2 classification, 3 intensity.
   */
  vtkSetClampMacro(ColorBy, int, 0, 3);
  vtkGetMacro(ColorBy, int);
  ///@}

  /** Whether the file's name ends in .las (any case): ParaView's check before it offers this
   * reader. */
  int CanReadFile(const char* fileName);

protected:
  vtkPVMRGILASReader();
  ~vtkPVMRGILASReader() override = default;

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  std::string FileName;
  int ColorBy = 0;

private:
  vtkPVMRGILASReader(const vtkPVMRGILASReader&) = delete;
  void operator=(const vtkPVMRGILASReader&) = delete;
};

#endif
