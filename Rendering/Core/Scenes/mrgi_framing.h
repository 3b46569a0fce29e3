/**
 * @file mrgi_framing.h
 * @brief Place a perspective camera so that a set of points fills a given
 *        fraction of the image, measured on their projection.
 *
 * VTK's ResetCamera() fits the bounding sphere of the data into the view:
 * a statue ends up small in the frame, by an amount that depends on its
 * shape. This file fits the projection of the points themselves.
 *
 * The camera looks along `direction` (unit, from the camera towards the
 * data) with `view_up` (any vector not parallel to it; it is
 * orthogonalised), a vertical field of view `view_angle_deg` in (0, 180)
 * and an image aspect `aspect` = width / height > 0. A point x at depth
 * z = (x - position) . direction > 0 projects to
 *   sx = ((x - position) . right) / (z tan(h) aspect),
 *   sy = ((x - position) . up)    / (z tan(h)),        h = view_angle / 2,
 * i.e. to [-1, 1]^2 across the image. The "fill" of the points is
 *   max((max sx - min sx) / 2, (max sy - min sy) / 2):
 * the fraction of the image width or height that their projected bounding
 * rectangle covers, whichever is larger (so with a square image, the
 * fraction of its side; with a wide one, the height usually limits).
 *
 * mrgi_frame_points() keeps the direction and finds the position and the
 * focal point such that the fill equals `fill` (within 1e-3 relative) and
 * the projected rectangle is centred in the image (within 1e-3 of the
 * image half-size), by alternating a bisection on the distance with a
 * sideways shift of the camera (a few rounds: the shift changes the
 * depths). Every point ends in front of the camera.
 *
 * Errors (::MRGI_ERR_INVALID_ARGUMENT, the message names the argument):
 * NULL arguments, count < 1, a non-finite coordinate, a direction or
 * view_up that is zero, not finite or parallel, an angle, aspect or fill
 * outside its range (fill in (0, 1]).
 * A single point (or all points equal) cannot fill anything: the camera
 * is placed at distance 1 from it and `fill` in the result is 0.
 */
#ifndef MRGI_FRAMING_H
#define MRGI_FRAMING_H

#include "mrgi_error.h"

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Where mrgi_frame_points() puts the camera. */
typedef struct mrgi_framing
{
  double position[3]; /**< Camera position. */
  double focal[3];    /**< Focal point: on the view axis at the depth of the points' centre. */
  double view_up[3];  /**< view_up orthogonalised to the direction, unit. */
  double fill;        /**< The fill reached (see the file comment). */
} mrgi_framing;

/**
 * @brief The fill of `count` points (xyz interleaved) seen from `position`
 *        along `direction` (file comment), and the centre of their
 *        projected rectangle in [-1, 1]^2 units (`center`, may be NULL).
 *        Points at depth <= 0 make the fill infinite.
 * @return ::MRGI_OK; ::MRGI_ERR_INVALID_ARGUMENT (file comment).
 */
mrgi_status mrgi_frame_fill(const double* points, int64_t count, const double position[3],
  const double direction[3], const double view_up[3], double view_angle_deg, double aspect,
  double* fill, double center[2], mrgi_error* err);

/**
 * @brief Place the camera (file comment).
 * @return ::MRGI_OK; ::MRGI_ERR_INVALID_ARGUMENT (file comment).
 */
mrgi_status mrgi_frame_points(const double* points, int64_t count, const double direction[3],
  const double view_up[3], double view_angle_deg, double aspect, double fill, mrgi_framing* out,
  mrgi_error* err);

#ifdef __cplusplus
}
#endif
#endif
