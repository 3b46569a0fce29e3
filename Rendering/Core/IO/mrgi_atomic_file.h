/**
 * @file mrgi_atomic_file.h
 * @brief Write outputs so that no partial file is ever visible under the final name.
 *
 * Usage:
 * @code
 *   char temp[MRGI_ATOMIC_FILE_PATH_MAX];
 *   if (mrgi_atomic_file_begin(path, temp, sizeof temp, err)) return err->status;
 *   ... write everything to `temp` ...
 *   if (writing failed) { mrgi_atomic_file_abort(temp); return ...; }
 *   return mrgi_atomic_file_commit(temp, path, err);
 * @endcode
 * The temporary file lives in the same directory as the final one
 * ("FINAL.tmp-PID-N"), so the closing rename() is atomic on POSIX file
 * systems: readers see either the old file or the complete new one.
 * Durability across power loss (fsync) is not attempted.
 */
#ifndef MRGI_ATOMIC_FILE_H
#define MRGI_ATOMIC_FILE_H

#include "mrgi_error.h"

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Characters the temporary name adds to the final path (".tmp-PID-N" plus NUL), at most. */
#define MRGI_ATOMIC_FILE_SUFFIX_MAX 48
/** A temp_path buffer size that fits any final path of up to 4096 bytes. */
#define MRGI_ATOMIC_FILE_PATH_MAX (4096 + MRGI_ATOMIC_FILE_SUFFIX_MAX)

/**
 * @brief Create a new, empty, uniquely named temporary file next to `final_path`.
 *
 * Creation uses O_CREAT|O_EXCL, so two writers (threads or processes)
 * never share a temporary file. The file is closed again; open it by name.
 * Its permissions follow the process umask, like any newly created output.
 *
 * @param final_path Where the output will finally live; not empty.
 * @param temp_path  Receives the NUL-terminated temporary path.
 * @param temp_size  Size of `temp_path`; at least strlen(final_path) + MRGI_ATOMIC_FILE_SUFFIX_MAX.
 * @return ::MRGI_ERR_INVALID_ARGUMENT for NULL/empty arguments or a short buffer,
 *         ::MRGI_ERR_IO when the directory does not exist or is not writable.
 */
mrgi_status mrgi_atomic_file_begin(const char* final_path, char* temp_path, size_t temp_size,
                                   mrgi_error* err);

/**
 * @brief Move the finished temporary file onto `final_path` (replacing it).
 *
 * On failure the temporary file is removed, so nothing is left behind either way.
 * @return ::MRGI_ERR_IO with the system's reason when rename() fails.
 */
mrgi_status mrgi_atomic_file_commit(const char* temp_path, const char* final_path,
                                    mrgi_error* err);

/**
 * @brief Remove the temporary file after a failed write. NULL or "" is a no-op;
 *        an already missing file is not an error. Never fails, for use in cleanup paths.
 */
void mrgi_atomic_file_abort(const char* temp_path);

#ifdef __cplusplus
}
#endif

#endif
