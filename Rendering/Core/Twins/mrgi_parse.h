/**
 * @file mrgi_parse.h
 * @brief Strict parsing of numbers, sizes and vectors from command lines and files.
 *
 * "Strict" means the whole text must be the value: no leading or trailing
 * spaces (except around the commas of a vector), no trailing junk, no hex,
 * no "nan"/"inf", no values outside the target range. Numbers use '.' as
 * the decimal point whatever the process locale is. Failures return
 * ::MRGI_ERR_INVALID_ARGUMENT with a message that quotes the text and names
 * the problem; outputs are left unchanged on failure.
 */
#ifndef MRGI_PARSE_H
#define MRGI_PARSE_H

#include "mrgi_error.h"

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Largest width or height mrgi_parse_size() accepts, in pixels. */
#define MRGI_PARSE_MAX_SIZE 16384

/**
 * @brief Parse a finite decimal number: [+-]digits[.digits][(e|E)[+-]digits].
 * @param text NUL-terminated text, e.g. "0.25", "-3", "1e-3".
 * @param out  Receives the value (nearest double). Values too small for a
 *             double round to 0 or a subnormal; values too large are rejected.
 */
mrgi_status mrgi_parse_double(const char* text, double* out, mrgi_error* err);

/**
 * @brief Parse a decimal integer [+-]digits within [min, max].
 * @return ::MRGI_ERR_INVALID_ARGUMENT also when min > max.
 */
mrgi_status mrgi_parse_int64(const char* text, int64_t min, int64_t max, int64_t* out,
                             mrgi_error* err);

/**
 * @brief Parse an image size "WxH" (or "WXH"), each side in [1, MRGI_PARSE_MAX_SIZE].
 *
 * Example message: "size '0x512': width must be at least 1".
 */
mrgi_status mrgi_parse_size(const char* text, int32_t* width, int32_t* height, mrgi_error* err);

/**
 * @brief Parse three comma-separated finite numbers "x,y,z".
 *
 * Spaces or tabs around each number are allowed ("1, 2, 3"); each number
 * follows mrgi_parse_double().
 */
mrgi_status mrgi_parse_vec3(const char* text, double out[3], mrgi_error* err);

#ifdef __cplusplus
}
#endif

#endif
