/* Fuzzes mrgi_ply_check(), the guard in front of VTK's PLY reader: any bytes
 * give MRGI_OK with plausible counts or a format/IO error with a message. */
#include "mrgi_fuzz.h"
#include "mrgi_ply_check.h"

int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  const char* path = mrgi_fuzz_file(data, size, ".ply");
  mrgi_ply_info info = { -7, -7, -7 };
  mrgi_error err;
  memset(&err, 0, sizeof(err));
  const mrgi_status status = mrgi_ply_check(path, &info, &err);
  if (status == MRGI_OK)
  {
    MRGI_FUZZ_REQUIRE(info.vertex_count >= 0 && info.vertex_count < INT32_MAX);
    MRGI_FUZZ_REQUIRE(info.face_count >= 0 && info.face_count < INT32_MAX);
    MRGI_FUZZ_REQUIRE(info.binary == 0 || info.binary == 1);
  }
  else
  {
    MRGI_FUZZ_REQUIRE(status == MRGI_ERR_FORMAT || status == MRGI_ERR_IO);
    MRGI_FUZZ_REQUIRE_ERROR(status, err);
  }
  return 0;
}
