/**
 * @file mrgi_up_axis.h
 * @brief Which world axis is "up" for a mesh or point cloud read from a
 *        file: the evidence gathered from its triangles and the decision.
 *
 * Data files do not say which way is up: VTK's convention is +y, scanned
 * statues (the Stanford PLYs) and terrain (LAS) are often +z. The staging
 * of a data file (vtkMRGIStaging) needs the up axis for its camera, its
 * ground and its key light. This file holds the geometric part of that
 * guess; the metadata part (a LAS or PCD file's own fields) is the VTK
 * layer's, which asks this file only when no metadata decides.
 *
 * Evidence (::mrgi_up_evidence), gathered in one pass over the triangles
 * once the bounds are known:
 * - **flat base**: triangles whose normal is within ::MRGI_UP_FLAT_DEG of
 *   an axis (either sign: file orientations are not trusted) and whose
 *   centroid lies within ::MRGI_UP_BASE_BAND of the extent from the low
 *   or the high end of that axis. A statue or a teapot stands on such a
 *   base; its area, as a fraction of the whole area, is the evidence.
 * - **open base**: a scan is open where the turntable hid it (the bunny's
 *   bottom). The sum of the triangles' area vectors of a closed surface is
 *   zero; for an open one it is the holes' area vector (up to the sign of
 *   the file's orientation). Its dominant axis, with the boundary edges'
 *   length-weighted centroid at one end of that axis, says where the base
 *   is.
 * - **point base** (point clouds: no triangle added): the points within
 *   ::MRGI_UP_BASE_BAND of the extent from each end of each axis. A scan
 *   stands on its base, terrain has its ground: one end holds many more
 *   points than the others.
 * - **extents**: an axis much shorter than the other two (terrain, a
 *   floor) is up.
 *
 * Decision (mrgi_up_decide()), the first rule that applies:
 * 1. flat base: the largest base fraction is >= ::MRGI_UP_BASE_MIN_FRACTION
 *    and >= ::MRGI_UP_BASE_DOMINANCE times every other end's: up points
 *    away from that end (base at the low end of y: +y).
 * 2. open base: |S_k| >= ::MRGI_UP_OPEN_MIN_FRACTION of the area and >=
 *    ::MRGI_UP_BASE_DOMINANCE times the other components of S, and the
 *    boundary centroid within ::MRGI_UP_OPEN_END_BAND of an end of axis k:
 *    up points away from that end.
 * 3. point base, only when no triangle was added: the end holding the most
 *    points holds >= ::MRGI_UP_POINT_BASE_MIN_FRACTION of them and >=
 *    ::MRGI_UP_BASE_DOMINANCE times every other end's: up points away
 *    from it.
 * 4. extents: the shortest extent is <= ::MRGI_UP_THIN_RATIO of the next
 *    shortest: up is +that axis.
 * 5. otherwise +y (VTK's convention).
 *
 * All functions are pure; no global state.
 */
#ifndef MRGI_UP_AXIS_H
#define MRGI_UP_AXIS_H

#include "mrgi_error.h"

#ifdef __cplusplus
extern "C" {
#endif

/** The six axis directions, in this order (the value / 2 is the axis). */
typedef enum mrgi_axis
{
  MRGI_AXIS_POS_X = 0,
  MRGI_AXIS_NEG_X = 1,
  MRGI_AXIS_POS_Y = 2,
  MRGI_AXIS_NEG_Y = 3,
  MRGI_AXIS_POS_Z = 4,
  MRGI_AXIS_NEG_Z = 5
} mrgi_axis;

/** Which rule of mrgi_up_decide() gave the answer. */
typedef enum mrgi_up_reason
{
  MRGI_UP_REASON_FLAT_BASE = 0,
  MRGI_UP_REASON_OPEN_BASE = 1,
  MRGI_UP_REASON_THIN_EXTENT = 2,
  MRGI_UP_REASON_DEFAULT = 3,
  MRGI_UP_REASON_POINT_BASE = 4
} mrgi_up_reason;

/** A triangle counts for a flat base when its normal is this close to an axis. */
#define MRGI_UP_FLAT_DEG 15.0
/** ... and its centroid this close (fraction of the extent) to that axis' end. */
#define MRGI_UP_BASE_BAND 0.03
/** A base must hold at least this fraction of the total area ... */
#define MRGI_UP_BASE_MIN_FRACTION 0.01
/** ... and this many times the area of any other end's base (also used for S). */
#define MRGI_UP_BASE_DOMINANCE 2.0
/** An open base: |S_k| at least this fraction of the total area. */
#define MRGI_UP_OPEN_MIN_FRACTION 0.005
/** An open base: the boundary centroid within this fraction of an end. */
#define MRGI_UP_OPEN_END_BAND 0.2
/** A point base: at least this fraction of the points. */
#define MRGI_UP_POINT_BASE_MIN_FRACTION 0.05
/** Thin extent: the shortest extent at most this fraction of the next. */
#define MRGI_UP_THIN_RATIO 0.25

/** What mrgi_up_add_triangle(), mrgi_up_add_boundary_edge() and mrgi_up_add_point() gather. */
typedef struct mrgi_up_evidence
{
  double bounds[6];       /**< xmin, xmax, ymin, ymax, zmin, zmax of the data. */
  double total_area;      /**< Sum of the triangle areas. */
  double base_area[6];    /**< Flat-base area at the low (even) / high (odd) end of x, y, z. */
  double area_vector[3];  /**< Sum of the triangles' area vectors (0.5 (b-a) x (c-a)). */
  double boundary_length; /**< Total length of the boundary edges given. */
  double boundary_sum[3]; /**< Sum of edge midpoints times edge lengths. */
  double point_count;     /**< Points given to mrgi_up_add_point(). */
  double point_base[6];   /**< Of those, within the base band of the low / high end of x, y, z. */
} mrgi_up_evidence;

/** What mrgi_up_decide() concludes. */
typedef struct mrgi_up_decision
{
  mrgi_axis up;          /**< The up direction. */
  mrgi_up_reason reason; /**< The rule that gave it. */
} mrgi_up_decision;

/**
 * @brief Start gathering for data with these bounds (all finite, min <= max).
 * @return ::MRGI_OK; ::MRGI_ERR_INVALID_ARGUMENT for NULL arguments or
 *         bounds that are not finite or inverted.
 */
mrgi_status mrgi_up_evidence_init(mrgi_up_evidence* ev, const double bounds[6], mrgi_error* err);

/** Add one triangle (its corners). Degenerate or non-finite ones add nothing. */
void mrgi_up_add_triangle(
  mrgi_up_evidence* ev, const double a[3], const double b[3], const double c[3]);

/** Add one point (of a cloud; a sample of it is enough). Non-finite ones add nothing. */
void mrgi_up_add_point(mrgi_up_evidence* ev, const double p[3]);

/** Add one boundary edge (an edge used by one triangle only). Non-finite ones add nothing. */
void mrgi_up_add_boundary_edge(mrgi_up_evidence* ev, const double a[3], const double b[3]);

/**
 * @brief Decide the up axis from the evidence (rules in the file comment).
 *        Evidence with no triangles decides by the extents alone.
 * @return ::MRGI_OK; ::MRGI_ERR_INVALID_ARGUMENT for NULL arguments.
 */
mrgi_status mrgi_up_decide(const mrgi_up_evidence* ev, mrgi_up_decision* out, mrgi_error* err);

/** The unit vector of `axis` ({0,0,0} for a value outside the enum). */
void mrgi_axis_vector(mrgi_axis axis, double out[3]);

/** "+x", "-x", "+y", "-y", "+z", "-z"; "?" for a value outside the enum. */
const char* mrgi_axis_name(mrgi_axis axis);

/**
 * @brief Parse "x", "+x", "-x", ... "-z" (lower or upper case).
 * @return ::MRGI_OK; ::MRGI_ERR_INVALID_ARGUMENT for anything else (the
 *         message quotes the text) and for NULL arguments.
 */
mrgi_status mrgi_axis_parse(const char* text, mrgi_axis* out, mrgi_error* err);

/** The name of a reason: "flat base", "open base", "point base", "thin extent", "default". */
const char* mrgi_up_reason_name(mrgi_up_reason reason);

#ifdef __cplusplus
}
#endif
#endif
