/* Internal to mrgi_exr.c and mrgi_exr_write.c (not installed): the stream
 * MRGI hands OpenEXRCore instead of letting it open the file.
 *
 * We give the library our own read/write callbacks for two reasons: its
 * default file handler takes over the context's user_data, which we need to
 * collect its error messages (it would otherwise print them to stderr); and
 * owning the file descriptor lets us check the magic number and file size
 * before parsing. Defined in mrgi_exr.c. */
#ifndef mrgi_exr_stream_h
#define mrgi_exr_stream_h

#include <openexr.h>

#include <stdint.h>

#ifndef O_CLOEXEC
#define O_CLOEXEC 0
#endif

typedef struct mrgi_exr_stream
{
  int fd;
  int64_t size;      /* file size in bytes (reading), -1 when unknown */
  char message[256]; /* first error the library reported, "" if none */
} mrgi_exr_stream;

/* exr_error_handler_cb_t: keeps the library's first message in the stream
 * that is the context's user_data. */
void mrgi_exr_on_error(exr_const_context_t ctxt, exr_result_t code, const char* msg);

/* exr_read_func_ptr_t, exr_query_size_func_ptr_t, exr_write_func_ptr_t over
 * stream->fd with pread/pwrite (EINTR retried). */
int64_t mrgi_exr_stream_read(exr_const_context_t ctxt, void* user_data, void* buffer, uint64_t size,
  uint64_t offset, exr_stream_error_func_ptr_t error_cb);
int64_t mrgi_exr_stream_size(exr_const_context_t ctxt, void* user_data);
int64_t mrgi_exr_stream_write(exr_const_context_t ctxt, void* user_data, const void* buffer,
  uint64_t size, uint64_t offset, exr_stream_error_func_ptr_t error_cb);

/* The library's first message for this stream, or the default text of `code`. */
const char* mrgi_exr_reason(const mrgi_exr_stream* stream, exr_result_t code);

#endif /* mrgi_exr_stream_h */
