/* Fuzzes mrgi_pcd_check_buffer(), the guard in front of PCL's PCD reader:
 * any bytes give MRGI_OK with a header whose sizes bound what PCL will
 * allocate (points within the limit, the body within the buffer), or a
 * format error with a message; nothing is read outside the buffer (ASan). */
#include "mrgi_fuzz.h"
#include "mrgi_pcd_check.h"

int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  mrgi_pcd_info info;
  memset(&info, 0, sizeof(info));
  mrgi_error err;
  memset(&err, 0, sizeof(err));
  const mrgi_status status = mrgi_pcd_check_buffer(data, size, "fuzz.pcd", 1 << 20, &info, &err);
  if (status == MRGI_OK)
  {
    MRGI_FUZZ_REQUIRE(info.points >= 1 && info.points <= (1 << 20));
    MRGI_FUZZ_REQUIRE(info.width * info.height == info.points);
    MRGI_FUZZ_REQUIRE(info.field_count >= 3 && info.field_count <= MRGI_PCD_MAX_FIELDS);
    MRGI_FUZZ_REQUIRE(info.record_size >= 12 && info.record_size <= MRGI_PCD_MAX_RECORD);
    MRGI_FUZZ_REQUIRE(info.header_size > 0 && (size_t)info.header_size <= size);
    if (info.data == MRGI_PCD_BINARY)
    {
      MRGI_FUZZ_REQUIRE((uint64_t)info.points * (uint64_t)info.record_size <=
        (uint64_t)(size - (size_t)info.header_size));
    }
    else if (info.data == MRGI_PCD_BINARY_COMPRESSED)
    {
      MRGI_FUZZ_REQUIRE((uint64_t)info.points * (uint64_t)info.record_size <=
        (uint64_t)MRGI_PCD_MAX_LZF_RATIO * (uint64_t)size);
    }
    else
    {
      MRGI_FUZZ_REQUIRE(info.data == MRGI_PCD_ASCII);
    }
  }
  else
  {
    MRGI_FUZZ_REQUIRE(status == MRGI_ERR_FORMAT);
    MRGI_FUZZ_REQUIRE_ERROR(status, err);
  }
  return 0;
}
