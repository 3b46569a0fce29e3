#define _POSIX_C_SOURCE 200809L
#include "mrgi_input.h"

#include <errno.h>
#include <fcntl.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#ifndef O_CLOEXEC
#define O_CLOEXEC 0
#endif

/* What kind of thing a non-regular file is, for the message. */
static const char* file_kind(mode_t mode)
{
  if (S_ISDIR(mode))
    return "is a directory";
  if (S_ISFIFO(mode))
    return "is a FIFO (named pipe)";
  if (S_ISCHR(mode))
    return "is a character device";
  if (S_ISBLK(mode))
    return "is a block device";
  if (S_ISSOCK(mode))
    return "is a socket";
  return "is not a regular file";
}

static mrgi_status check_stat(const char* path, const struct stat* st, mrgi_error* err)
{
  if (!S_ISREG(st->st_mode))
  {
    return mrgi_error_set(err, MRGI_ERR_IO, "cannot read '%s': it %s, not a regular file", path,
      file_kind(st->st_mode));
  }
  if (st->st_size == 0)
  {
    return mrgi_error_set(err, MRGI_ERR_FORMAT, "'%s' is empty", path);
  }
  return MRGI_OK;
}

mrgi_status mrgi_input_check_regular(const char* path, mrgi_error* err)
{
  if (!path)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "input: no file name given");
  }
  struct stat st;
  if (stat(path, &st) != 0)
  {
    return mrgi_error_set(err, MRGI_ERR_IO, "cannot open '%s': %s", path, strerror(errno));
  }
  return check_stat(path, &st, err);
}

mrgi_status mrgi_input_map(const char* path, mrgi_input* in, mrgi_error* err)
{
  if (!path || !in)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "input: no file name given");
  }
  in->data = NULL;
  in->size = 0;
  /* stat before open: opening a FIFO for reading blocks until a writer comes. */
  mrgi_status status = mrgi_input_check_regular(path, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  const int fd = open(path, O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0)
  {
    return mrgi_error_set(err, MRGI_ERR_IO, "cannot open '%s': %s", path, strerror(errno));
  }
  struct stat st;
  if (fstat(fd, &st) != 0)
  {
    status = mrgi_error_set(err, MRGI_ERR_IO, "cannot read '%s': %s", path, strerror(errno));
  }
  else
  {
    status = check_stat(path, &st, err); /* it may have changed since stat() */
  }
  if (status == MRGI_OK && (uint64_t)st.st_size > (uint64_t)SIZE_MAX)
  {
    status = mrgi_error_set(err, MRGI_ERR_IO, "cannot read '%s': too large", path);
  }
  if (status == MRGI_OK)
  {
    void* map = mmap(NULL, (size_t)st.st_size, PROT_READ, MAP_PRIVATE, fd, 0);
    if (map == MAP_FAILED)
    {
      status = mrgi_error_set(err, MRGI_ERR_IO, "cannot read '%s': %s", path, strerror(errno));
    }
    else
    {
      in->data = (const unsigned char*)map;
      in->size = (size_t)st.st_size;
    }
  }
  close(fd);
  return status;
}

void mrgi_input_unmap(mrgi_input* in)
{
  if (in && in->data)
  {
    munmap((void*)in->data, in->size);
    in->data = NULL;
    in->size = 0;
  }
}

void mrgi_line_cursor_init(mrgi_line_cursor* c, const void* data, size_t size)
{
  c->data = (const unsigned char*)data;
  c->size = data ? size : 0;
  c->pos = 0;
  c->line_number = 0;
}

int mrgi_line_next(mrgi_line_cursor* c, char* line, size_t capacity)
{
  if (c->pos >= c->size || capacity == 0)
  {
    return 0;
  }
  const unsigned char* start = c->data + c->pos;
  const size_t left = c->size - c->pos;
  const unsigned char* nl = memchr(start, '\n', left);
  size_t n = nl ? (size_t)(nl - start) : left;
  if (n + 1 > capacity)
  {
    return -1;
  }
  for (size_t i = 0; i < n; ++i)
  {
    line[i] = start[i] ? (char)start[i] : ' ';
  }
  c->pos += nl ? n + 1 : n;
  if (n > 0 && line[n - 1] == '\r')
  {
    --n;
  }
  line[n] = '\0';
  ++c->line_number;
  return 1;
}
