/**
 * @class   vtkMRGILASReader
 * @brief   Reads an uncompressed LAS 1.0-1.4 point cloud (point formats
 *          0-10) into a vtkPolyData of vertices, through MRGI's C core.
 *
 * The core (mrgi_las.h) applies each file's scale and offset in double and
 * recentres the points on the centre of their bounding box, so that
 * UTM-sized coordinates keep millimetres in float. The output holds:
 * - float points relative to that centre, and one vertex cell per point;
 * - field data "Origin" (double, 1 tuple of 3): the world position that was
 *   subtracted: add it back to georeference (world = point + Origin);
 * - field data "LASVersion" (string, e.g. "1.4") and "LASPointFormat" (int);
 * - point data "Intensity" (unsigned short), "Classification",
 *   "ReturnNumber" and "NumberOfReturns" (unsigned char);
 * - "RGB" (unsigned char, 3 components) when the point format has colour
 *   (8- or 16-bit in the file, mrgi_las.h says how they are told apart);
 * - the display colours as the active scalars (unsigned char, 3
 *   components): "RGB" itself, or a "Colors" array from the ASPRS class
 *   palette or the intensity grey ramp (mrgi_las_colors.h), as ColorBy
 *   says. Any VTK mapper then shows them with SetColorModeToDirectScalars().
 *
 * NewClassificationLookupTable() gives the class palette as a
 * vtkLookupTable for colouring "Classification" in a user's own pipeline.
 *
 * Pieces: asked for piece k of N (ParaView under MPI), the reader outputs
 * the k-th even share of the points in file order, recentred on the same
 * origin as the whole file, so that the pieces fit together.
 *
 * Errors (missing or unreadable file, compressed LAZ: "compressed LAZ is not
 * supported", a bad header, truncated point data, absurd counts, more points
 * than MaximumNumberOfPoints) raise one vtkErrorMacro naming the file and
 * the problem and leave the output empty (the request itself succeeds, so
 * that the executive adds no second error); GetLastErrorMessage() has the
 * same line and GetErrorCode() is vtkErrorCode::CannotOpenFileError or
 * FileFormatError (NoError after a successful read). The reader never crashes on a bad file: the
 * core checks every size against the file before reading (fuzzed: fuzz.LAS).
 */
#ifndef vtkMRGILASReader_h
#define vtkMRGILASReader_h

#include "MRGIRenderingIOModule.h" // For export macro
#include "vtkPolyDataAlgorithm.h"
#include "vtkWrappingHints.h" // For VTK_NEWINSTANCE

#include <string> // For std::string

class vtkLookupTable;

class MRGIRENDERINGIO_EXPORT vtkMRGILASReader : public vtkPolyDataAlgorithm
{
public:
  static vtkMRGILASReader* New();
  vtkTypeMacro(vtkMRGILASReader, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /** The LAS file to read. */
  vtkSetStdStringFromCharMacro(FileName);
  vtkGetCharFromStdStringMacro(FileName);
  ///@}

  /** What the active "Colors"/"RGB" scalars show. */
  enum ColorByModes
  {
    COLOR_BY_AUTO = 0, ///< RGB when the format has it, else classes when classified, else intensity
    COLOR_BY_RGB = 1,  ///< the file's RGB (a file without RGB falls back to AUTO, with a warning)
    COLOR_BY_CLASSIFICATION = 2, ///< the ASPRS class palette
    COLOR_BY_INTENSITY = 3       ///< the intensity grey ramp
  };

  ///@{
  /** What the display colours show (ColorByModes), default COLOR_BY_AUTO. */
  vtkSetClampMacro(ColorBy, int, COLOR_BY_AUTO, COLOR_BY_INTENSITY);
  vtkGetMacro(ColorBy, int);
  void SetColorByToAuto() { this->SetColorBy(COLOR_BY_AUTO); }
  void SetColorByToRGB() { this->SetColorBy(COLOR_BY_RGB); }
  void SetColorByToClassification() { this->SetColorBy(COLOR_BY_CLASSIFICATION); }
  void SetColorByToIntensity() { this->SetColorBy(COLOR_BY_INTENSITY); }
  ///@}

  /**
   * What the last successful read's colours show (never COLOR_BY_AUTO), or
   * -1 before one.
   */
  vtkGetMacro(ColorByUsed, int);

  ///@{
  /**
   * Files with more points are refused (a memory bound: about 40 bytes a
   * point while reading). Default 2^28, the most MRGI's scene builder draws.
   */
  vtkSetClampMacro(MaximumNumberOfPoints, vtkTypeInt64, 1, VTK_TYPE_INT64_MAX);
  vtkGetMacro(MaximumNumberOfPoints, vtkTypeInt64);
  ///@}

  /** Why the last read failed; empty after a success. */
  const char* GetLastErrorMessage() { return this->LastErrorMessage.c_str(); }

  /**
   * The ASPRS class palette as a 256-entry lookup table over the range
   * 0..255 (value c maps to entry c), for colouring "Classification" with
   * SetColorModeToMapScalars(). The caller owns the result.
   */
  VTK_NEWINSTANCE static vtkLookupTable* NewClassificationLookupTable();

protected:
  vtkMRGILASReader();
  ~vtkMRGILASReader() override = default;

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  std::string FileName;
  int ColorBy = COLOR_BY_AUTO;
  int ColorByUsed = -1;
  vtkTypeInt64 MaximumNumberOfPoints = vtkTypeInt64(1) << 28;
  std::string LastErrorMessage;

private:
  vtkMRGILASReader(const vtkMRGILASReader&) = delete;
  void operator=(const vtkMRGILASReader&) = delete;
};

#endif
