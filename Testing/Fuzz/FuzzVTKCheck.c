/* Fuzzes mrgi_vtk_check_buffer(), the guard in front of VTK's VTK reader:
 * any bytes give MRGI_OK with plausible counts or a format error with a
 * message, and never read outside the buffer (ASan) or loop forever. */
#include "mrgi_fuzz.h"
#include "mrgi_vtk_check.h"

int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  mrgi_vtk_info info;
  memset(&info, 0x5a, sizeof(info));
  mrgi_error err;
  memset(&err, 0, sizeof(err));
  const mrgi_status status = mrgi_vtk_check_buffer(size ? data : NULL, size, "fuzz.vtk", &info, &err);
  if (status == MRGI_OK)
  {
    MRGI_FUZZ_REQUIRE(info.point_count >= 0 && info.cell_count >= 0);
    MRGI_FUZZ_REQUIRE(info.binary == 0 || info.binary == 1);
  }
  else
  {
    MRGI_FUZZ_REQUIRE(status == MRGI_ERR_FORMAT);
    MRGI_FUZZ_REQUIRE_ERROR(status, err);
  }
  return 0;
}
