/* Fuzzes the strict parsers of mrgi_parse.h. The first byte picks the parser
 * (and for integers the range), the rest is the text. Checked: a success
 * gives a value in range that prints and parses back to itself; a failure
 * gives MRGI_ERR_INVALID_ARGUMENT with a message and leaves the outputs
 * unchanged (as the header promises). */
#include "mrgi_fuzz.h"
#include "mrgi_parse.h"

#include <math.h>

static void check_failure(mrgi_status status, const mrgi_error* err)
{
  MRGI_FUZZ_REQUIRE(status == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_FUZZ_REQUIRE_ERROR(status, *err);
}

static void fuzz_double(const char* text)
{
  mrgi_error err;
  memset(&err, 0, sizeof(err));
  double value = 12345.0;
  const mrgi_status status = mrgi_parse_double(text, &value, &err);
  if (status != MRGI_OK)
  {
    check_failure(status, &err);
    MRGI_FUZZ_REQUIRE(value == 12345.0);
    return;
  }
  MRGI_FUZZ_REQUIRE(isfinite(value));
  char printed[64];
  snprintf(printed, sizeof(printed), "%.17g", value);
  double again = 0.0;
  MRGI_FUZZ_REQUIRE(mrgi_parse_double(printed, &again, NULL) == MRGI_OK);
  MRGI_FUZZ_REQUIRE(again == value);
}

static void fuzz_int64(const char* text, uint8_t range)
{
  static const int64_t ranges[][2] = { { INT64_MIN, INT64_MAX }, { 0, 100 },
    { 1, MRGI_PARSE_MAX_SIZE }, { -5, 5 }, { 7, 7 }, { 3, -3 } };
  const int64_t* r = ranges[range % (sizeof(ranges) / sizeof(ranges[0]))];
  mrgi_error err;
  memset(&err, 0, sizeof(err));
  int64_t value = 424242;
  const mrgi_status status = mrgi_parse_int64(text, r[0], r[1], &value, &err);
  if (status != MRGI_OK)
  {
    check_failure(status, &err);
    MRGI_FUZZ_REQUIRE(value == 424242);
    return;
  }
  MRGI_FUZZ_REQUIRE(r[0] <= r[1] && value >= r[0] && value <= r[1]);
  char printed[32];
  snprintf(printed, sizeof(printed), "%lld", (long long)value);
  int64_t again = 0;
  MRGI_FUZZ_REQUIRE(mrgi_parse_int64(printed, r[0], r[1], &again, NULL) == MRGI_OK);
  MRGI_FUZZ_REQUIRE(again == value);
}

static void fuzz_size(const char* text)
{
  mrgi_error err;
  memset(&err, 0, sizeof(err));
  int32_t width = -1, height = -2;
  const mrgi_status status = mrgi_parse_size(text, &width, &height, &err);
  if (status != MRGI_OK)
  {
    check_failure(status, &err);
    MRGI_FUZZ_REQUIRE(width == -1 && height == -2);
    return;
  }
  MRGI_FUZZ_REQUIRE(width >= 1 && width <= MRGI_PARSE_MAX_SIZE);
  MRGI_FUZZ_REQUIRE(height >= 1 && height <= MRGI_PARSE_MAX_SIZE);
}

static void fuzz_vec3(const char* text)
{
  mrgi_error err;
  memset(&err, 0, sizeof(err));
  double v[3] = { 1.5, 2.5, 3.5 };
  const mrgi_status status = mrgi_parse_vec3(text, v, &err);
  if (status != MRGI_OK)
  {
    check_failure(status, &err);
    MRGI_FUZZ_REQUIRE(v[0] == 1.5 && v[1] == 2.5 && v[2] == 3.5);
    return;
  }
  MRGI_FUZZ_REQUIRE(isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]));
}

int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  if (size < 1)
  {
    return 0;
  }
  /* An exact-size, terminated copy: a read past the NUL is caught by ASan. */
  char* text = (char*)malloc(size);
  MRGI_FUZZ_REQUIRE(text != NULL);
  memcpy(text, data + 1, size - 1);
  text[size - 1] = '\0';
  switch (data[0] & 3)
  {
    case 0:
      fuzz_double(text);
      break;
    case 1:
      fuzz_int64(text, (uint8_t)(data[0] >> 2));
      break;
    case 2:
      fuzz_size(text);
      break;
    default:
      fuzz_vec3(text);
      break;
  }
  free(text);
  return 0;
}
