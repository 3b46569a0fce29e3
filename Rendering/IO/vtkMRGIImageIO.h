/**
 * @class   vtkMRGIImageIO
 * @brief   Writes and reads vtkImageData as OpenEXR (half or float) and PNG
 *          through MRGI's C core.
 *
 * EXR keeps float images unclamped (HDR colour buffers, indirect-only
 * buffers); PNG takes unsigned-char images as they are and float images
 * clamped to [0, 1] (no sRGB curve: VTK writes linear values to its 8-bit
 * window, and PNGs of float buffers match what the window shows).
 *
 * Outputs are written atomically: a failed write leaves no file behind and
 * never a partial one. Errors are reported through GetLastErrorMessage() and
 * a false return, never by crashing: empty images, NaN pixels (written as 0
 * and counted in the message), unsupported scalar types, unwritable paths.
 *
 * vtkImageData rows run bottom-up; files are top-down; the conversion flips.
 */
#ifndef vtkMRGIImageIO_h
#define vtkMRGIImageIO_h

#include "MRGIRenderingIOModule.h" // For export macro
#include "vtkObject.h"

#include <string> // For std::string

class vtkImageData;
struct mrgi_image;

class MRGIRENDERINGIO_EXPORT vtkMRGIImageIO : public vtkObject
{
public:
  static vtkMRGIImageIO* New();
  vtkTypeMacro(vtkMRGIImageIO, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /** EXR pixel type for float output: half (16-bit, max 65504) or float (32-bit). */
  vtkSetMacro(HalfFloat, bool);
  vtkGetMacro(HalfFloat, bool);
  vtkBooleanMacro(HalfFloat, bool);
  ///@}

  /** Write `image` to `path`; the extension (.exr or .png) picks the format. */
  bool Write(vtkImageData* image, const char* path);
  bool WriteEXR(vtkImageData* image, const char* path);
  bool WritePNG(vtkImageData* image, const char* path);

  /** Read an EXR or PNG file into `image` (float scalars, bottom-up rows). */
  bool Read(const char* path, vtkImageData* image);

  /** Why the last call failed; empty after a success. */
  const char* GetLastErrorMessage() { return this->LastErrorMessage.c_str(); }

  /**
   * Convert between vtkImageData (2D, 1-4 components, any numeric scalar type;
   * unsigned char is scaled by 1/255) and the core's float image. The core
   * image is created by the call and owned by the caller.
   */
#ifndef __VTK_WRAP__
  static bool ToCoreImage(vtkImageData* image, mrgi_image* out, std::string& why);
  static bool FromCoreImage(const mrgi_image* in, vtkImageData* image, std::string& why);
#endif

protected:
  vtkMRGIImageIO() = default;
  ~vtkMRGIImageIO() override = default;

  bool Fail(const std::string& why);
  /** Validate the arguments of a write and convert the image; false (with the reason) on error. */
  bool PrepareWrite(vtkImageData* image, const char* path, mrgi_image* core);

  bool HalfFloat = false;
  std::string LastErrorMessage;

private:
  vtkMRGIImageIO(const vtkMRGIImageIO&) = delete;
  void operator=(const vtkMRGIImageIO&) = delete;
};

#endif
