/* Tests of mrgi_error: setting, prefixing, clearing, status names. */
#include "mrgi_error.h"
#include "mrgi_test.h"

#include <string.h>

static void test_set_formats_and_returns_status(void)
{
  mrgi_error err;
  mrgi_error_clear(&err);
  mrgi_status s = mrgi_error_set(&err, MRGI_ERR_IO, "cannot open '%s': %d", "a.exr", 42);
  MRGI_CHECK(s == MRGI_ERR_IO);
  MRGI_CHECK(err.status == MRGI_ERR_IO);
  MRGI_CHECK(strcmp(err.message, "cannot open 'a.exr': 42") == 0);
}

static void test_set_accepts_null_error(void)
{
  MRGI_CHECK(mrgi_error_set(NULL, MRGI_ERR_FORMAT, "ignored %d", 1) == MRGI_ERR_FORMAT);
  mrgi_error_clear(NULL);
  mrgi_error_prefix(NULL, "x");
}

static void test_set_with_null_format_leaves_empty_message(void)
{
  mrgi_error err;
  mrgi_error_set(&err, MRGI_ERR_IO, "old");
  MRGI_CHECK(mrgi_error_set(&err, MRGI_ERR_FORMAT, NULL) == MRGI_ERR_FORMAT);
  MRGI_CHECK(err.message[0] == '\0');
}

static void test_long_message_is_truncated_and_terminated(void)
{
  char big[2000];
  memset(big, 'a', sizeof(big) - 1);
  big[sizeof(big) - 1] = '\0';
  mrgi_error err;
  mrgi_error_set(&err, MRGI_ERR_INVALID_ARGUMENT, "%s", big);
  MRGI_CHECK(strlen(err.message) == MRGI_ERROR_MESSAGE_SIZE - 1);
}

static void test_prefix_keeps_status_and_message(void)
{
  mrgi_error err;
  mrgi_error_set(&err, MRGI_ERR_IO, "No such file or directory");
  mrgi_error_prefix(&err, "writing '%s': ", "out.png");
  MRGI_CHECK(err.status == MRGI_ERR_IO);
  MRGI_CHECK(strcmp(err.message, "writing 'out.png': No such file or directory") == 0);

  /* A prefix that fills the buffer truncates but stays terminated. */
  char big[700];
  memset(big, 'p', sizeof(big) - 1);
  big[sizeof(big) - 1] = '\0';
  mrgi_error_prefix(&err, "%s", big);
  MRGI_CHECK(strlen(err.message) == MRGI_ERROR_MESSAGE_SIZE - 1);
}

static void test_clear(void)
{
  mrgi_error err;
  mrgi_error_set(&err, MRGI_ERR_OUT_OF_MEMORY, "boom");
  mrgi_error_clear(&err);
  MRGI_CHECK(err.status == MRGI_OK);
  MRGI_CHECK(err.message[0] == '\0');
}

static void test_status_names(void)
{
  MRGI_CHECK(strcmp(mrgi_status_name(MRGI_OK), "MRGI_OK") == 0);
  MRGI_CHECK(strcmp(mrgi_status_name(MRGI_ERR_INVALID_ARGUMENT), "MRGI_ERR_INVALID_ARGUMENT") == 0);
  MRGI_CHECK(strcmp(mrgi_status_name(MRGI_ERR_OUT_OF_MEMORY), "MRGI_ERR_OUT_OF_MEMORY") == 0);
  MRGI_CHECK(strcmp(mrgi_status_name(MRGI_ERR_IO), "MRGI_ERR_IO") == 0);
  MRGI_CHECK(strcmp(mrgi_status_name(MRGI_ERR_FORMAT), "MRGI_ERR_FORMAT") == 0);
  MRGI_CHECK(strcmp(mrgi_status_name(MRGI_ERR_UNSUPPORTED), "MRGI_ERR_UNSUPPORTED") == 0);
  /* Bad input: a value outside the enum gets a name, not a crash. */
  MRGI_CHECK(strcmp(mrgi_status_name((mrgi_status)1234), "MRGI_ERR_UNKNOWN") == 0);
}

int main(int argc, char** argv)
{
  static const mrgi_test_case cases[] = {
    MRGI_TEST_CASE(test_set_formats_and_returns_status),
    MRGI_TEST_CASE(test_set_accepts_null_error),
    MRGI_TEST_CASE(test_set_with_null_format_leaves_empty_message),
    MRGI_TEST_CASE(test_long_message_is_truncated_and_terminated),
    MRGI_TEST_CASE(test_prefix_keeps_status_and_message),
    MRGI_TEST_CASE(test_clear),
    MRGI_TEST_CASE(test_status_names),
  };
  return MRGI_TEST_MAIN(argc, argv, cases);
}
