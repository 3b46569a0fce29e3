// vtkMRGIImageIO: EXR (float and half) and PNG round trips through the C core,
// row order, and bad input that must fail without leaving files behind.
#include "mrgiTestUtilities.h"

#include "vtkFloatArray.h"

#include <cmath>
#include <fstream>
#include <limits>

int main()
{
  vtkNew<vtkImageData> image;
  image->SetDimensions(7, 5, 1);
  image->AllocateScalars(VTK_FLOAT, 4);
  vtkFloatArray* values = vtkFloatArray::SafeDownCast(image->GetPointData()->GetScalars());
  for (vtkIdType i = 0; i < values->GetNumberOfValues(); ++i)
  {
    values->SetValue(i, 0.01f * static_cast<float>(i) + (i % 4 == 0 ? 100.0f : 0.0f));
  }

  vtkNew<vtkMRGIImageIO> io;
  for (bool half : { false, true })
  {
    io->SetHalfFloat(half);
    const std::string path = mrgitest::TempPath(half ? "io_half.exr" : "io_float.exr");
    MRGI_TEST_CHECK(io->Write(image, path.c_str()));
    vtkNew<vtkImageData> back;
    MRGI_TEST_CHECK(io->Read(path.c_str(), back));
    MRGI_TEST_CHECK(back->GetDimensions()[0] == 7 && back->GetDimensions()[1] == 5);
    vtkDataArray* b = back->GetPointData()->GetScalars();
    MRGI_TEST_CHECK(b->GetNumberOfComponents() == 4);
    for (vtkIdType i = 0; i < values->GetNumberOfValues(); ++i)
    {
      const double expected = values->GetValue(i);
      const double tol = half ? 1e-3 * std::fabs(expected) + 1e-3 : 0.0;
      if (!(std::fabs(b->GetVariantValue(i).ToDouble() - expected) <= tol))
      {
        std::fprintf(stderr, "value %lld: %g read back, %g written (half %d)\n", static_cast<long long>(i),
          b->GetVariantValue(i).ToDouble(), expected, half ? 1 : 0);
        return 1;
      }
    }
  }

  // PNG: 8-bit, values clamped to [0, 1]; bottom-up rows survive the round trip.
  vtkNew<vtkImageData> ramp;
  ramp->SetDimensions(4, 3, 1);
  ramp->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 4; ++x)
      for (int c = 0; c < 3; ++c)
        ramp->SetScalarComponentFromDouble(x, y, 0, c, 20 * x + 80 * y + c);
  const std::string png = mrgitest::TempPath("io.png");
  MRGI_TEST_CHECK(io->Write(ramp, png.c_str()));
  vtkNew<vtkImageData> pngBack;
  MRGI_TEST_CHECK(io->Read(png.c_str(), pngBack));
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 4; ++x)
      for (int c = 0; c < 3; ++c)
        MRGI_TEST_CHECK(std::fabs(pngBack->GetScalarComponentAsDouble(x, y, 0, c) * 255.0 -
                          (20 * x + 80 * y + c)) < 0.51);

  // Bad input.
  vtkNew<vtkImageData> empty;
  MRGI_TEST_CHECK(!io->Write(empty, mrgitest::TempPath("empty.exr").c_str()));
  MRGI_TEST_CHECK(std::string(io->GetLastErrorMessage()).find("empty") != std::string::npos);
  MRGI_TEST_CHECK(!std::ifstream(mrgitest::TempPath("empty.exr")).good());
  MRGI_TEST_CHECK(!io->Write(image, mrgitest::TempPath("image.tiff").c_str()));
  MRGI_TEST_CHECK(std::string(io->GetLastErrorMessage()).find(".exr or .png") != std::string::npos);
  MRGI_TEST_CHECK(!io->Write(image, "/nonexistent-dir/x.exr"));
  MRGI_TEST_CHECK(!std::ifstream("/nonexistent-dir/x.exr").good());
  MRGI_TEST_CHECK(!io->Read(mrgitest::TempPath("missing.exr").c_str(), empty));
  // NaN pixels never reach the file: they are written as 0.
  values->SetValue(5, std::numeric_limits<float>::quiet_NaN());
  io->SetHalfFloat(false);
  const std::string nanPath = mrgitest::TempPath("nan.exr");
  MRGI_TEST_CHECK(io->Write(image, nanPath.c_str()));
  vtkNew<vtkImageData> nanBack;
  MRGI_TEST_CHECK(io->Read(nanPath.c_str(), nanBack));
  for (vtkIdType i = 0; i < values->GetNumberOfValues(); ++i)
  {
    MRGI_TEST_CHECK(std::isfinite(nanBack->GetPointData()->GetScalars()->GetVariantValue(i).ToDouble()));
  }
  return 0;
}
