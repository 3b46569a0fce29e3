/**
 * @file mrgi_iso_value.h
 * @brief The default iso-value of a volume: Otsu's threshold of its
 *        scalar histogram.
 *
 * A volume read from a file (an electron density, a CT scan) is shown as
 * the iso-surface that separates its two main populations of values (the
 * background and the object). Otsu's method (Otsu 1979, "A threshold
 * selection method from gray-level histograms") picks the threshold t
 * that maximises the between-class variance w0 w1 (m0 - m1)^2 of the
 * values below and above t. On ironProt.vtk (0..255, two thirds zeros) it
 * gives about 87 (Documentation/Staging.md).
 *
 * The histogram has `bins` >= 2 equal bins over [lo, hi] (lo < hi, both
 * finite): bin i covers [lo + i w, lo + (i + 1) w), w = (hi - lo) / bins;
 * counts are >= 0 and finite. The threshold returned is the boundary
 * lo + t w (1 <= t <= bins - 1) between the classes. Empty bins between
 * two populations give every t among them the same variance: the
 * threshold is then the middle of that run of tied t (a 0/1 mask: 0.5),
 * not its first bin's edge. When the counts leave one class empty for every t (all values in one
 * bin), the midpoint (lo + hi) / 2 is returned with `*otsu` = 0 (1 when
 * Otsu's rule decided; `otsu` may be NULL).
 *
 * Errors (::MRGI_ERR_INVALID_ARGUMENT): NULL histogram or threshold,
 * bins < 2, lo >= hi or not finite, a count that is negative or not
 * finite, or all counts zero.
 */
#ifndef MRGI_ISO_VALUE_H
#define MRGI_ISO_VALUE_H

#include "mrgi_error.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Bins MRGI's callers use for the histogram of a volume. */
#define MRGI_ISO_VALUE_BINS 256

/**
 * @brief Otsu's threshold of a histogram (file comment).
 * @return ::MRGI_OK; ::MRGI_ERR_INVALID_ARGUMENT (file comment).
 */
mrgi_status mrgi_iso_value_otsu(const double* counts, int bins, double lo, double hi,
  double* threshold, int* otsu, mrgi_error* err);

#ifdef __cplusplus
}
#endif
#endif
