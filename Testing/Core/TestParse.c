/* Tests of mrgi_parse: strict numbers, integers, sizes and vectors. */
#include "mrgi_parse.h"
#include "mrgi_test.h"

#include <locale.h>
#include <string.h>

/* Parsing `text` must fail with INVALID_ARGUMENT, a message containing
 * `expected`, and leave *out untouched. */
static void expect_double_rejected(const char* text, const char* expected)
{
  mrgi_error err;
  double out = 123.0;
  mrgi_status s = mrgi_parse_double(text, &out, &err);
  if (s != MRGI_ERR_INVALID_ARGUMENT || !strstr(err.message, expected))
  {
    fprintf(stderr, "text '%s': status %s, message '%s'\n", text ? text : "(null)",
            mrgi_status_name(s), err.message);
  }
  MRGI_CHECK(s == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, expected));
  MRGI_CHECK(out == 123.0);
}

static void test_double(void)
{
  double v = 0.0;
  MRGI_CHECK(mrgi_parse_double("0.25", &v, NULL) == MRGI_OK && v == 0.25);
  MRGI_CHECK(mrgi_parse_double("-3", &v, NULL) == MRGI_OK && v == -3.0);
  MRGI_CHECK(mrgi_parse_double("+1e-3", &v, NULL) == MRGI_OK && v == 1e-3);
  MRGI_CHECK(mrgi_parse_double(".5", &v, NULL) == MRGI_OK && v == 0.5);
  MRGI_CHECK(mrgi_parse_double("5.", &v, NULL) == MRGI_OK && v == 5.0);
  MRGI_CHECK(mrgi_parse_double("2E2", &v, NULL) == MRGI_OK && v == 200.0);
  MRGI_CHECK(mrgi_parse_double("1e-400", &v, NULL) == MRGI_OK && v == 0.0); /* underflow rounds */

  expect_double_rejected("", "empty");
  expect_double_rejected("nan", "not a finite decimal number");
  expect_double_rejected("NaN", "not a finite decimal number");
  expect_double_rejected("inf", "not a finite decimal number");
  expect_double_rejected("-infinity", "not a finite decimal number");
  expect_double_rejected("1e999", "out of the range");
  expect_double_rejected("-1e999", "out of the range");
  expect_double_rejected("3x", "'3x' is not a finite decimal number");
  expect_double_rejected(" 1", "not a finite decimal number");
  expect_double_rejected("1 ", "not a finite decimal number");
  expect_double_rejected("0x10", "not a finite decimal number");
  expect_double_rejected("1e", "not a finite decimal number");
  expect_double_rejected(".", "not a finite decimal number");
  expect_double_rejected("-", "not a finite decimal number");
  expect_double_rejected("1,5", "not a finite decimal number");
  expect_double_rejected(NULL, "NULL");

  mrgi_error err;
  MRGI_CHECK(mrgi_parse_double("1", NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "output pointer"));
}

static void test_int64(void)
{
  int64_t v = 0;
  MRGI_CHECK(mrgi_parse_int64("42", 0, 100, &v, NULL) == MRGI_OK && v == 42);
  MRGI_CHECK(mrgi_parse_int64("-7", -10, 10, &v, NULL) == MRGI_OK && v == -7);
  MRGI_CHECK(mrgi_parse_int64("9223372036854775807", INT64_MIN, INT64_MAX, &v, NULL) == MRGI_OK &&
             v == INT64_MAX);

  mrgi_error err;
  v = 5;
  MRGI_CHECK(mrgi_parse_int64("300", 1, 256, &v, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "'300' is out of range [1, 256]"));
  MRGI_CHECK(v == 5);
  MRGI_CHECK(mrgi_parse_int64("9223372036854775808", INT64_MIN, INT64_MAX, &v, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "out of range"));
  MRGI_CHECK(mrgi_parse_int64("1.5", 0, 10, &v, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "not a decimal integer"));
  MRGI_CHECK(mrgi_parse_int64("12abc", 0, 100, &v, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "'12abc' is not a decimal integer"));
  MRGI_CHECK(mrgi_parse_int64("", 0, 100, &v, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "empty"));
  MRGI_CHECK(mrgi_parse_int64("+", 0, 100, &v, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_parse_int64("5", 10, 0, &v, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "min > max"));
  MRGI_CHECK(mrgi_parse_int64(NULL, 0, 1, &v, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "NULL"));
  MRGI_CHECK(mrgi_parse_int64("1", 0, 1, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "output pointer"));
}

static void expect_size_rejected(const char* text, const char* expected)
{
  mrgi_error err;
  int32_t w = -5, h = -5;
  mrgi_status s = mrgi_parse_size(text, &w, &h, &err);
  if (s != MRGI_ERR_INVALID_ARGUMENT || !strstr(err.message, expected))
  {
    fprintf(stderr, "size '%s': status %s, message '%s'\n", text ? text : "(null)",
            mrgi_status_name(s), err.message);
  }
  MRGI_CHECK(s == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, expected));
  MRGI_CHECK(w == -5 && h == -5);
}

static void test_size(void)
{
  int32_t w = 0, h = 0;
  MRGI_CHECK(mrgi_parse_size("640x480", &w, &h, NULL) == MRGI_OK && w == 640 && h == 480);
  MRGI_CHECK(mrgi_parse_size("1X1", &w, &h, NULL) == MRGI_OK && w == 1 && h == 1);
  MRGI_CHECK(mrgi_parse_size("16384x16384", &w, &h, NULL) == MRGI_OK && w == 16384);

  expect_size_rejected("0x512", "size '0x512': width must be at least 1");
  expect_size_rejected("512x0", "height must be at least 1");
  expect_size_rejected("-5x3", "width must be at least 1");
  expect_size_rejected("16385x2", "width must be at most 16384");
  expect_size_rejected("2x99999999999999999999999", "height must be at most 16384");
  expect_size_rejected("nanx3", "width 'nan' is not a whole number");
  expect_size_rejected("3xnan", "height 'nan' is not a whole number");
  expect_size_rejected("1.5x2", "width '1.5' is not a whole number");
  expect_size_rejected("640x480x3", "height '480x3' is not a whole number");
  expect_size_rejected("640", "not of the form WIDTHxHEIGHT");
  expect_size_rejected("", "not of the form WIDTHxHEIGHT");
  expect_size_rejected("x480", "width is missing");
  expect_size_rejected("640x", "height is missing");
  expect_size_rejected(" 640x480", "not a whole number");
  expect_size_rejected(NULL, "NULL");

  mrgi_error err;
  MRGI_CHECK(mrgi_parse_size("2x2", NULL, &h, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "output pointer"));
}

static void test_vec3(void)
{
  double v[3] = { 0.0, 0.0, 0.0 };
  MRGI_CHECK(mrgi_parse_vec3("1,-2.5,3e2", v, NULL) == MRGI_OK);
  MRGI_CHECK(v[0] == 1.0 && v[1] == -2.5 && v[2] == 300.0);
  MRGI_CHECK(mrgi_parse_vec3(" 0.5 , 1,\t2 ", v, NULL) == MRGI_OK);
  MRGI_CHECK(v[0] == 0.5 && v[1] == 1.0 && v[2] == 2.0);

  mrgi_error err;
  double keep[3] = { 7.0, 7.0, 7.0 };
  MRGI_CHECK(mrgi_parse_vec3("1,2", keep, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "expected 3 comma-separated numbers x,y,z, got 2"));
  MRGI_CHECK(mrgi_parse_vec3("1,2,3,4", keep, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "got 4"));
  MRGI_CHECK(mrgi_parse_vec3("1,nan,3", keep, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "y: 'nan' is not a finite decimal number"));
  MRGI_CHECK(mrgi_parse_vec3("1,2,", keep, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "z is missing"));
  MRGI_CHECK(mrgi_parse_vec3("1e999,0,0", keep, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "x: '1e999' is out of the range"));
  MRGI_CHECK(keep[0] == 7.0 && keep[1] == 7.0 && keep[2] == 7.0);
  MRGI_CHECK(mrgi_parse_vec3(NULL, keep, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "NULL"));
  MRGI_CHECK(mrgi_parse_vec3("1,2,3", NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "output pointer"));
}

/* A locale with a decimal comma must not change how "0.5" parses. Only runs
 * where such a locale is installed. */
static void test_locale_independence(void)
{
  static const char* const comma_locales[] = { "de_DE.UTF-8", "fr_FR.UTF-8", "de_DE", NULL };
  for (int i = 0; comma_locales[i]; ++i)
  {
    if (setlocale(LC_NUMERIC, comma_locales[i]))
    {
      double v = 0.0;
      MRGI_CHECK(mrgi_parse_double("0.5", &v, NULL) == MRGI_OK && v == 0.5);
      setlocale(LC_NUMERIC, "C");
      return;
    }
  }
}

int main(int argc, char** argv)
{
  static const mrgi_test_case cases[] = {
    MRGI_TEST_CASE(test_double),
    MRGI_TEST_CASE(test_int64),
    MRGI_TEST_CASE(test_size),
    MRGI_TEST_CASE(test_vec3),
    MRGI_TEST_CASE(test_locale_independence),
  };
  return MRGI_TEST_MAIN(argc, argv, cases);
}
