/* strtod_l/newlocale make number parsing independent of setlocale(). */
#define _GNU_SOURCE
#include "mrgi_parse.h"

#include <errno.h>
#include <locale.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#if defined(__APPLE__)
#include <xlocale.h>
#endif

/* Longest text echoed back in a message, so messages stay readable. */
#define MRGI_PARSE_QUOTE_MAX 64
/* Largest component accepted inside a vector, characters. */
#define MRGI_PARSE_COMPONENT_MAX 128

static int mrgi_is_digit(char c)
{
  return c >= '0' && c <= '9';
}

/* Length of the longest prefix of `s` that is a decimal number in the
 * syntax documented for mrgi_parse_double (0 if there is none). Checking
 * the syntax here rejects what strtod would otherwise accept: leading
 * spaces, hex floats, "inf", "nan". */
static size_t mrgi_decimal_syntax_length(const char* s)
{
  size_t i = 0;
  if (s[i] == '+' || s[i] == '-')
  {
    ++i;
  }
  size_t digits = 0;
  while (mrgi_is_digit(s[i]))
  {
    ++i;
    ++digits;
  }
  if (s[i] == '.')
  {
    ++i;
    while (mrgi_is_digit(s[i]))
    {
      ++i;
      ++digits;
    }
  }
  if (digits == 0)
  {
    return 0;
  }
  if (s[i] == 'e' || s[i] == 'E')
  {
    size_t j = i + 1;
    if (s[j] == '+' || s[j] == '-')
    {
      ++j;
    }
    if (!mrgi_is_digit(s[j]))
    {
      return 0;
    }
    while (mrgi_is_digit(s[j]))
    {
      ++j;
    }
    i = j;
  }
  return i;
}

static double mrgi_strtod_c_locale(const char* text)
{
#if defined(__GLIBC__) || defined(__APPLE__)
  /* The "C" locale object is static in glibc, so this does not allocate. */
  locale_t c_locale = newlocale(LC_NUMERIC_MASK, "C", (locale_t)0);
  if (c_locale != (locale_t)0)
  {
    const double value = strtod_l(text, NULL, c_locale);
    freelocale(c_locale);
    return value;
  }
#endif
  return strtod(text, NULL);
}

mrgi_status mrgi_parse_double(const char* text, double* out, mrgi_error* err)
{
  if (!text)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "number text is NULL");
  }
  if (!out)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "output pointer for '%.*s' is NULL",
                          MRGI_PARSE_QUOTE_MAX, text);
  }
  if (text[0] == '\0')
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "empty text is not a number");
  }
  const size_t length = mrgi_decimal_syntax_length(text);
  if (length == 0 || text[length] != '\0')
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "'%.*s' is not a finite decimal number", MRGI_PARSE_QUOTE_MAX, text);
  }
  const double value = mrgi_strtod_c_locale(text);
  /* Overflow gives +-HUGE_VAL (infinite); underflow (a tiny result with
   * ERANGE) is accepted as the nearest double. */
  if (!isfinite(value))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "'%.*s' is out of the range of a double", MRGI_PARSE_QUOTE_MAX, text);
  }
  *out = value;
  return MRGI_OK;
}

mrgi_status mrgi_parse_int64(const char* text, int64_t min, int64_t max, int64_t* out,
                             mrgi_error* err)
{
  if (!text)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "integer text is NULL");
  }
  if (!out)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "output pointer for '%.*s' is NULL",
                          MRGI_PARSE_QUOTE_MAX, text);
  }
  if (min > max)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "integer range [%lld, %lld] is empty (min > max)", (long long)min,
                          (long long)max);
  }
  if (text[0] == '\0')
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "empty text is not an integer");
  }
  size_t i = (text[0] == '+' || text[0] == '-') ? 1 : 0;
  const size_t first_digit = i;
  while (mrgi_is_digit(text[i]))
  {
    ++i;
  }
  if (i == first_digit || text[i] != '\0')
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "'%.*s' is not a decimal integer",
                          MRGI_PARSE_QUOTE_MAX, text);
  }
  errno = 0;
  const long long value = strtoll(text, NULL, 10);
  if (errno == ERANGE || value < min || value > max)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "integer '%.*s' is out of range [%lld, %lld]", MRGI_PARSE_QUOTE_MAX,
                          text, (long long)min, (long long)max);
  }
  *out = (int64_t)value;
  return MRGI_OK;
}

/* Parse one side of "WxH" from text[begin, end). */
static mrgi_status mrgi_parse_size_side(const char* whole, const char* begin, size_t length,
                                        const char* side_name, int32_t* out, mrgi_error* err)
{
  if (length == 0)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "size '%.*s': %s is missing",
                          MRGI_PARSE_QUOTE_MAX, whole, side_name);
  }
  size_t i = (begin[0] == '+' || begin[0] == '-') ? 1 : 0;
  const int negative = begin[0] == '-';
  const size_t first_digit = i;
  while (i < length && mrgi_is_digit(begin[i]))
  {
    ++i;
  }
  if (i == first_digit || i != length)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "size '%.*s': %s '%.*s' is not a whole number", MRGI_PARSE_QUOTE_MAX,
                          whole, side_name, (int)(length < MRGI_PARSE_QUOTE_MAX ? length : MRGI_PARSE_QUOTE_MAX),
                          begin);
  }
  /* Accumulate with saturation so "99999999999999999999" reports "too large"
   * rather than wrapping. */
  int64_t value = 0;
  for (size_t k = first_digit; k < length; ++k)
  {
    if (value <= MRGI_PARSE_MAX_SIZE)
    {
      value = value * 10 + (begin[k] - '0');
    }
  }
  if (negative || value < 1)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "size '%.*s': %s must be at least 1",
                          MRGI_PARSE_QUOTE_MAX, whole, side_name);
  }
  if (value > MRGI_PARSE_MAX_SIZE)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "size '%.*s': %s must be at most %d",
                          MRGI_PARSE_QUOTE_MAX, whole, side_name, MRGI_PARSE_MAX_SIZE);
  }
  *out = (int32_t)value;
  return MRGI_OK;
}

mrgi_status mrgi_parse_size(const char* text, int32_t* width, int32_t* height, mrgi_error* err)
{
  if (!text)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "size text is NULL");
  }
  if (!width || !height)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "output pointer for size '%.*s' is NULL", MRGI_PARSE_QUOTE_MAX, text);
  }
  const char* separator = strpbrk(text, "xX");
  if (!separator)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "size '%.*s' is not of the form WIDTHxHEIGHT (e.g. 640x480)",
                          MRGI_PARSE_QUOTE_MAX, text);
  }
  int32_t w = 0;
  int32_t h = 0;
  mrgi_status status =
    mrgi_parse_size_side(text, text, (size_t)(separator - text), "width", &w, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  status = mrgi_parse_size_side(text, separator + 1, strlen(separator + 1), "height", &h, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  *width = w;
  *height = h;
  return MRGI_OK;
}

static int mrgi_is_blank(char c)
{
  return c == ' ' || c == '\t';
}

mrgi_status mrgi_parse_vec3(const char* text, double out[3], mrgi_error* err)
{
  if (!text)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "vector text is NULL");
  }
  if (!out)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "output pointer for vector '%.*s' is NULL", MRGI_PARSE_QUOTE_MAX, text);
  }
  size_t commas = 0;
  for (const char* p = text; *p; ++p)
  {
    commas += *p == ',';
  }
  if (commas != 2)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "vector '%.*s': expected 3 comma-separated numbers x,y,z, got %zu",
                          MRGI_PARSE_QUOTE_MAX, text, commas + 1);
  }
  static const char* const axis_names[3] = { "x", "y", "z" };
  double values[3];
  const char* begin = text;
  for (int axis = 0; axis < 3; ++axis)
  {
    const char* end = strchr(begin, ',');
    if (!end)
    {
      end = begin + strlen(begin);
    }
    const char* b = begin;
    const char* e = end;
    while (b < e && mrgi_is_blank(*b))
    {
      ++b;
    }
    while (e > b && mrgi_is_blank(e[-1]))
    {
      --e;
    }
    const size_t length = (size_t)(e - b);
    if (length == 0)
    {
      return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "vector '%.*s': %s is missing",
                            MRGI_PARSE_QUOTE_MAX, text, axis_names[axis]);
    }
    if (length >= MRGI_PARSE_COMPONENT_MAX)
    {
      return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                            "vector '%.*s': %s is longer than %d characters",
                            MRGI_PARSE_QUOTE_MAX, text, axis_names[axis],
                            MRGI_PARSE_COMPONENT_MAX - 1);
    }
    char component[MRGI_PARSE_COMPONENT_MAX];
    memcpy(component, b, length);
    component[length] = '\0';
    mrgi_status status = mrgi_parse_double(component, &values[axis], err);
    if (status != MRGI_OK)
    {
      mrgi_error_prefix(err, "vector '%.*s': %s: ", MRGI_PARSE_QUOTE_MAX, text, axis_names[axis]);
      return status;
    }
    begin = end + (*end == ',' ? 1 : 0);
  }
  out[0] = values[0];
  out[1] = values[1];
  out[2] = values[2];
  return MRGI_OK;
}
