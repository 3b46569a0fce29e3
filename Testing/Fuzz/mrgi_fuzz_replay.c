/*
 * Replays inputs through a harness's LLVMFuzzerTestOneInput() without
 * libFuzzer: the regression test of every harness, in every build.
 *
 * Usage: ReplayNAME FILE|DIR...   (a directory's regular files, in name order)
 * Exits 1 when an argument cannot be read or no input was found, so a
 * missing seed directory fails the test instead of passing it empty. A
 * crash or a broken contract aborts, like under the fuzzer.
 */
#include "mrgi_fuzz.h"

#include <dirent.h>
#include <sys/stat.h>

static int replay_file(const char* path)
{
  FILE* file = fopen(path, "rb");
  if (!file)
  {
    fprintf(stderr, "replay: cannot open '%s'\n", path);
    return 0;
  }
  size_t capacity = 4096, size = 0;
  uint8_t* data = (uint8_t*)malloc(capacity);
  size_t got = 0;
  while (data && (got = fread(data + size, 1, capacity - size, file)) > 0)
  {
    size += got;
    if (size == capacity)
    {
      capacity *= 2;
      uint8_t* grown = (uint8_t*)realloc(data, capacity);
      if (!grown)
      {
        free(data);
      }
      data = grown;
    }
  }
  fclose(file);
  if (!data)
  {
    fprintf(stderr, "replay: out of memory reading '%s'\n", path);
    return 0;
  }
  /* An exact-size copy, so that a read past the end is caught by ASan. */
  uint8_t* exact = (uint8_t*)malloc(size ? size : 1);
  if (!exact)
  {
    free(data);
    return 0;
  }
  memcpy(exact, data, size);
  free(data);
  printf("replay: %s (%zu bytes)\n", path, size);
  fflush(stdout);
  LLVMFuzzerTestOneInput(exact, size);
  free(exact);
  return 1;
}

static int compare_names(const void* a, const void* b)
{
  return strcmp(*(const char* const*)a, *(const char* const*)b);
}

/* Replays the regular files of `dir` in name order; returns how many, -1 on error. */
static int replay_dir(const char* dir)
{
  DIR* d = opendir(dir);
  if (!d)
  {
    fprintf(stderr, "replay: cannot open directory '%s'\n", dir);
    return -1;
  }
  char** names = NULL;
  size_t count = 0;
  struct dirent* entry;
  while ((entry = readdir(d)) != NULL)
  {
    if (entry->d_name[0] == '.')
    {
      continue;
    }
    char** grown = (char**)realloc(names, (count + 1) * sizeof(*names));
    if (!grown)
    {
      break;
    }
    names = grown;
    names[count] = (char*)malloc(strlen(dir) + strlen(entry->d_name) + 2);
    if (!names[count])
    {
      break;
    }
    sprintf(names[count], "%s/%s", dir, entry->d_name);
    ++count;
  }
  closedir(d);
  if (count > 0)
  {
    qsort(names, count, sizeof(*names), compare_names);
  }
  int replayed = 0;
  for (size_t i = 0; i < count; ++i)
  {
    struct stat info;
    if (stat(names[i], &info) == 0 && S_ISREG(info.st_mode))
    {
      if (!replay_file(names[i]))
      {
        replayed = -1;
      }
      else if (replayed >= 0)
      {
        ++replayed;
      }
    }
    free(names[i]);
  }
  free(names);
  return replayed;
}

int main(int argc, char** argv)
{
  int total = 0;
  int failed = 0;
  for (int i = 1; i < argc; ++i)
  {
    struct stat info;
    if (stat(argv[i], &info) != 0)
    {
      fprintf(stderr, "replay: '%s' does not exist\n", argv[i]);
      failed = 1;
    }
    else if (S_ISDIR(info.st_mode))
    {
      const int n = replay_dir(argv[i]);
      failed |= n < 0;
      total += n > 0 ? n : 0;
    }
    else
    {
      failed |= !replay_file(argv[i]);
      ++total;
    }
  }
  printf("replay: %d inputs replayed%s\n", total, failed ? ", some could not be read" : "");
  return failed || total == 0 ? 1 : 0;
}
