#include "mrgi_error.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

mrgi_status mrgi_error_set(mrgi_error* err, mrgi_status status, const char* fmt, ...)
{
  if (!err)
  {
    return status;
  }
  err->status = status;
  err->message[0] = '\0';
  if (fmt)
  {
    va_list args;
    va_start(args, fmt);
    vsnprintf(err->message, sizeof(err->message), fmt, args);
    va_end(args);
  }
  return status;
}

void mrgi_error_prefix(mrgi_error* err, const char* fmt, ...)
{
  if (!err || !fmt)
  {
    return;
  }
  /* The old message is copied out first because the prefix is written into
   * the same buffer. */
  char previous[MRGI_ERROR_MESSAGE_SIZE];
  memcpy(previous, err->message, sizeof(previous));
  previous[sizeof(previous) - 1] = '\0';

  va_list args;
  va_start(args, fmt);
  int prefix_length = vsnprintf(err->message, sizeof(err->message), fmt, args);
  va_end(args);
  if (prefix_length < 0)
  {
    memcpy(err->message, previous, sizeof(previous));
    return;
  }
  size_t used = (size_t)prefix_length;
  if (used < sizeof(err->message) - 1)
  {
    snprintf(err->message + used, sizeof(err->message) - used, "%s", previous);
  }
}

void mrgi_error_clear(mrgi_error* err)
{
  if (err)
  {
    err->status = MRGI_OK;
    err->message[0] = '\0';
  }
}

const char* mrgi_status_name(mrgi_status status)
{
  switch (status)
  {
    case MRGI_OK:
      return "MRGI_OK";
    case MRGI_ERR_INVALID_ARGUMENT:
      return "MRGI_ERR_INVALID_ARGUMENT";
    case MRGI_ERR_OUT_OF_MEMORY:
      return "MRGI_ERR_OUT_OF_MEMORY";
    case MRGI_ERR_IO:
      return "MRGI_ERR_IO";
    case MRGI_ERR_FORMAT:
      return "MRGI_ERR_FORMAT";
    case MRGI_ERR_UNSUPPORTED:
      return "MRGI_ERR_UNSUPPORTED";
  }
  return "MRGI_ERR_UNKNOWN";
}
