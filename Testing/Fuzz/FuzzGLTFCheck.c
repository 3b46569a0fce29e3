/* Fuzzes mrgi_gltf_check_buffer(), the guard in front of VTK's glTF importer,
 * on glTF JSON and GLB bytes (no folder: external URIs are refused, data
 * URIs and GLB chunks are checked): any bytes give MRGI_OK with at least one
 * mesh, or a format error with a message. */
#include "mrgi_fuzz.h"
#include "mrgi_gltf_check.h"

int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  mrgi_gltf_info info;
  memset(&info, 0x5a, sizeof(info));
  mrgi_error err;
  memset(&err, 0, sizeof(err));
  const mrgi_status status = mrgi_gltf_check_buffer(size ? data : NULL, size, "fuzz.gltf", NULL, &info, &err);
  if (status == MRGI_OK)
  {
    MRGI_FUZZ_REQUIRE(info.mesh_count >= 1 && info.node_count >= 0 && info.accessor_count >= 0);
    MRGI_FUZZ_REQUIRE(info.binary == 0 || info.binary == 1);
  }
  else
  {
    MRGI_FUZZ_REQUIRE(status == MRGI_ERR_FORMAT || status == MRGI_ERR_IO);
    MRGI_FUZZ_REQUIRE_ERROR(status, err);
  }
  return 0;
}
