/*
 * mrgi-flicker: temporal flicker of a sequence of images against a reference
 * sequence (mrgi_flicker.h, issue 12 part 6):
 *
 *   F = mean over k of rms((I_{k+1} - I_k) - (R_{k+1} - R_k)) / rms(R_k)
 *
 *   mrgi-flicker [--box N] [--pairs] IMAGE_0 ... IMAGE_K-1 --reference REF_0 ... REF_K-1
 *
 * Images are EXR or PNG, all the same size. Prints one line
 * `flicker=... max_pair=... pairs=... excluded=... box=N` (every value a
 * number) and, with --pairs, first one line per pair k:
 * `pair=k value=... change_rms=... reference_rms=... excluded=0|1`.
 * Exit status: 0 measured, 1 the sequences cannot be measured (unreadable,
 * sizes differ, NaN, every reference black), 2 bad usage (the usage is
 * printed), 0 after --help.
 */
#include "mrgi_error.h"
#include "mrgi_flicker.h"
#include "mrgi_image.h"
#include "mrgi_image_file.h"
#include "mrgi_parse.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char* const usage =
  "usage: mrgi-flicker [--box N] [--pairs] IMAGE... --reference REFERENCE...\n"
  "\n"
  "Temporal flicker of the frames IMAGE_0..IMAGE_K-1 (each .exr or .png, all the\n"
  "same size) against the reference frames REFERENCE_0..REFERENCE_K-1, K >= 2:\n"
  "  F = mean over k of rms((I_k+1 - I_k) - (R_k+1 - R_k)) / rms(R_k)\n"
  "(rms over pixels and RGB; pairs with a black R_k excluded and counted).\n"
  "Prints\n"
  "  flicker=... max_pair=... pairs=... excluded=... box=N\n"
  "\n"
  "  --box N           average N x N pixel boxes first, N >= 1 (default 1)\n"
  "  --pairs           also print each pair: pair=k value=... change_rms=...\n"
  "                    reference_rms=... excluded=0|1\n"
  "  --reference       the arguments after it are the reference frames\n"
  "  -h, --help        this text\n"
  "\n"
  "Exit: 0 measured, 1 not measurable, 2 bad usage.\n";

/* Bad usage: the message, then the usage, exit status 2. */
static int usage_error(const char* message, const char* value)
{
  fprintf(stderr, "mrgi-flicker: error: %s%s%s%s\n", message, value ? " '" : "", value ? value : "",
    value ? "'" : "");
  fputs(usage, stderr);
  return 2;
}

static void destroy_frames(mrgi_image* frames, int count)
{
  for (int k = 0; frames && k < count; ++k)
  {
    mrgi_image_destroy(&frames[k]);
  }
  free(frames);
}

/* Reads `count` files into a new array (*out, count entries, zeroed). */
static int read_frames(char** paths, int count, mrgi_image** out, mrgi_error* err)
{
  *out = (mrgi_image*)calloc((size_t)count, sizeof(mrgi_image));
  if (!*out)
  {
    mrgi_error_set(err, MRGI_ERR_OUT_OF_MEMORY, "out of memory for %d frames", count);
    return 0;
  }
  for (int k = 0; k < count; ++k)
  {
    if (mrgi_image_file_read(paths[k], &(*out)[k], err) != MRGI_OK)
    {
      return 0;
    }
  }
  return 1;
}

int main(int argc, char** argv)
{
  int box = 1, print_pairs = 0, in_reference = 0;
  int image_count = 0, reference_count = 0;
  char** image_paths = (char**)calloc((size_t)argc, sizeof(char*));
  char** reference_paths = (char**)calloc((size_t)argc, sizeof(char*));
  mrgi_image* images = NULL;
  mrgi_image* references = NULL;
  mrgi_flicker_pair* pairs = NULL;
  mrgi_error err;
  int code = 0;
  if (!image_paths || !reference_paths)
  {
    fputs("mrgi-flicker: error: out of memory\n", stderr);
    code = 1;
    goto done;
  }
  for (int i = 1; i < argc; ++i)
  {
    if (strcmp(argv[i], "-h") == 0 || strcmp(argv[i], "--help") == 0)
    {
      fputs(usage, stdout);
      goto done;
    }
    if (strcmp(argv[i], "--pairs") == 0)
      print_pairs = 1;
    else if (strcmp(argv[i], "--reference") == 0)
    {
      if (in_reference)
      {
        code = usage_error("--reference given twice", NULL);
        goto done;
      }
      in_reference = 1;
    }
    else if (strcmp(argv[i], "--box") == 0)
    {
      int64_t value = 0;
      if (i + 1 >= argc)
      {
        code = usage_error("--box needs a value", NULL);
        goto done;
      }
      if (mrgi_parse_int64(argv[++i], 1, 65536, &value, &err) != MRGI_OK)
      {
        code = usage_error("--box needs a whole number from 1 to 65536, not", argv[i]);
        goto done;
      }
      box = (int)value;
    }
    else if (argv[i][0] == '-' && argv[i][1] != '\0')
    {
      code = usage_error("unknown option", argv[i]);
      goto done;
    }
    else if (in_reference)
      reference_paths[reference_count++] = argv[i];
    else
      image_paths[image_count++] = argv[i];
  }
  if (!in_reference)
  {
    code = usage_error("no --reference given (the reference frames follow it)", NULL);
    goto done;
  }
  if (image_count < 2 || image_count != reference_count)
  {
    char message[160];
    snprintf(message, sizeof message,
      "%d images and %d reference frames given; the two sequences need the same count, at least 2",
      image_count, reference_count);
    code = usage_error(message, NULL);
    goto done;
  }
  pairs = (mrgi_flicker_pair*)calloc((size_t)image_count - 1, sizeof(mrgi_flicker_pair));
  mrgi_flicker_result result;
  if (!pairs || !read_frames(image_paths, image_count, &images, &err) ||
    !read_frames(reference_paths, reference_count, &references, &err) ||
    mrgi_flicker_sequence(images, references, image_count, box, pairs, &result, &err) != MRGI_OK)
  {
    fprintf(stderr, "mrgi-flicker: error: %s\n", pairs ? err.message : "out of memory");
    code = 1;
    goto done;
  }
  if (print_pairs)
  {
    for (int k = 0; k + 1 < image_count; ++k)
    {
      printf("pair=%d value=%.6g change_rms=%.6g reference_rms=%.6g excluded=%d\n", k, pairs[k].value,
        pairs[k].change_rms, pairs[k].reference_rms, pairs[k].excluded);
    }
  }
  printf("flicker=%.6g max_pair=%.6g pairs=%d excluded=%d box=%d\n", result.flicker, result.max_pair,
    (int)result.pairs_counted, (int)result.pairs_excluded, box);
done:
  destroy_frames(images, image_count);
  destroy_frames(references, reference_count);
  free(pairs);
  free(image_paths);
  free(reference_paths);
  return code;
}
