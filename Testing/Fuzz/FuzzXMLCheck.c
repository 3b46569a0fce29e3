/* Fuzzes mrgi_xml_check_buffer(), the guard in front of VTK's XML readers:
 * any bytes give MRGI_OK or a format error with a message, and never read
 * outside the buffer (ASan) or loop forever. */
#include "mrgi_fuzz.h"
#include "mrgi_xml_check.h"

int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  mrgi_error err;
  memset(&err, 0, sizeof(err));
  const mrgi_status status = mrgi_xml_check_buffer(size ? data : NULL, size, "fuzz.vtp", &err);
  if (status != MRGI_OK)
  {
    MRGI_FUZZ_REQUIRE(status == MRGI_ERR_FORMAT);
    MRGI_FUZZ_REQUIRE_ERROR(status, err);
  }
  return 0;
}
