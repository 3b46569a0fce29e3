/* Fuzzes mrgi_obj_check_buffer(), the guard in front of VTK's OBJ reader:
 * any bytes give MRGI_OK with plausible counts or a format error with a
 * message, and never read outside the buffer (ASan) or loop forever. */
#include "mrgi_fuzz.h"
#include "mrgi_obj_check.h"

int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  mrgi_obj_info info;
  memset(&info, 0x5a, sizeof(info));
  mrgi_error err;
  memset(&err, 0, sizeof(err));
  const mrgi_status status = mrgi_obj_check_buffer(size ? data : NULL, size, "fuzz.obj", &info, &err);
  if (status == MRGI_OK)
  {
    MRGI_FUZZ_REQUIRE(info.vertex_count >= 0 && info.face_count >= 0);
    /* Each vertex and face takes at least two bytes ("v\n"): counts are bounded by the size. */
    MRGI_FUZZ_REQUIRE((uint64_t)info.vertex_count + (uint64_t)info.face_count <= size);
  }
  else
  {
    MRGI_FUZZ_REQUIRE(status == MRGI_ERR_FORMAT);
    MRGI_FUZZ_REQUIRE_ERROR(status, err);
  }
  return 0;
}
