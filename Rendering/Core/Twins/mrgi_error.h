/**
 * @file mrgi_error.h
 * @brief Status codes and error messages shared by every core function.
 *
 * Convention for the whole core: a function that can fail returns an
 * ::mrgi_status and takes a trailing `mrgi_error* err` as its last argument.
 * `err` may be NULL when the caller only needs the status. On failure the
 * function fills `err` (status plus a human-readable message naming the
 * problem); on success it leaves `err` untouched, so callers must test the
 * returned status, not `err->status`.
 */
#ifndef MRGI_ERROR_H
#define MRGI_ERROR_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Outcome of a core call. ::MRGI_OK is zero so `if (status)` tests failure. */
typedef enum mrgi_status
{
  MRGI_OK = 0,                 /**< Success. */
  MRGI_ERR_INVALID_ARGUMENT,   /**< A caller-supplied value is out of its documented range. */
  MRGI_ERR_OUT_OF_MEMORY,      /**< An allocation failed. */
  MRGI_ERR_IO,                 /**< The operating system refused a file operation. */
  MRGI_ERR_FORMAT,             /**< File contents are not what the format requires (corrupt, truncated). */
  MRGI_ERR_UNSUPPORTED         /**< Valid input that this core does not handle (e.g. tiled EXR). */
} mrgi_status;

/** Size of ::mrgi_error::message, terminating NUL included. Longer messages are truncated. */
#define MRGI_ERROR_MESSAGE_SIZE 512

/** A status together with the message that explains it. Plain data: copy freely. */
typedef struct mrgi_error
{
  mrgi_status status;                    /**< Same value the failing call returned. */
  char message[MRGI_ERROR_MESSAGE_SIZE]; /**< NUL-terminated, no trailing newline. */
} mrgi_error;

#if defined(__GNUC__) || defined(__clang__)
#define MRGI_PRINTF_FORMAT(fmt_index, first_arg) \
  __attribute__((format(printf, fmt_index, first_arg)))
#else
#define MRGI_PRINTF_FORMAT(fmt_index, first_arg)
#endif

/**
 * @brief Record a failure and return its status, so callers can write
 *        `return mrgi_error_set(err, MRGI_ERR_IO, "cannot open '%s'", path);`.
 * @param err    Destination; may be NULL (then only the status is returned).
 * @param status Status to record and return.
 * @param fmt    printf-style format of the message; NULL leaves the message empty.
 * @return `status`, unchanged.
 */
mrgi_status mrgi_error_set(mrgi_error* err, mrgi_status status, const char* fmt, ...)
  MRGI_PRINTF_FORMAT(3, 4);

/**
 * @brief Put context in front of the message already in `err`, e.g. turning
 *        "No such file or directory" into "writing 'a.exr': No such file or directory".
 * @param err Error to amend; NULL is a no-op. Its status is kept.
 * @param fmt printf-style format of the prefix (the message follows it directly).
 */
void mrgi_error_prefix(mrgi_error* err, const char* fmt, ...) MRGI_PRINTF_FORMAT(2, 3);

/** @brief Reset `err` to ::MRGI_OK with an empty message. NULL is a no-op. */
void mrgi_error_clear(mrgi_error* err);

/**
 * @brief Stable identifier of a status, e.g. "MRGI_ERR_IO".
 * @return A static string; "MRGI_ERR_UNKNOWN" for values outside the enum.
 */
const char* mrgi_status_name(mrgi_status status);

#ifdef __cplusplus
}
#endif

#endif
