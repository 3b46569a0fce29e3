/**
 * @file    vtkMRGIStagingPieces.h
 * @brief   Internal (MRGI::RenderingIO): the data vtkMRGIStaging::Stage()
 *          looks at, as polygonal pieces of the visible actors, and what
 *          they say: whether they draw anything, and which way is up.
 *
 * The up-axis cues are those of vtkMRGIStaging's class documentation: field
 * data first (LAS files are z up; a PCD sensor pose gives up and the
 * direction the sensor looked in), then the geometry (the core's
 * mrgi_up_axis.h: a flat base, else the boundary edges of a scan, else a
 * cloud's points). Axes are mrgi_axis values (vtkMRGIStaging::UpAxis
 * has the same numbers). Not wrapped, not installed.
 */
#ifndef vtkMRGIStagingPieces_h
#define vtkMRGIStagingPieces_h

#include <string> // For std::string
#include <vector> // For std::vector

class vtkActor;
class vtkFieldData;
class vtkMatrix4x4;
class vtkPolyData;
class vtkRenderer;

namespace vtkMRGIStagingPieces
{
/** One polygonal piece of an actor's data, with the actor's matrix. */
struct Piece
{
  vtkPolyData* Data;
  vtkMatrix4x4* Matrix; // nullptr: identity
  vtkFieldData* Fields[2]; // the piece's and its composite parent's (nullptr: none)
};

/**
 * Append the polygonal pieces of every visible actor of `renderer` with a
 * mapper (a polydata, or the polydata leaves of a composite data set),
 * except `skip` (an earlier Stage()'s ground; may be nullptr).
 */
void Collect(vtkRenderer* renderer, vtkActor* skip, std::vector<Piece>& pieces);

/** `in` through the piece's matrix (`out` may be `in`). */
void ToWorld(const Piece& piece, const double in[3], double out[3]);

/** Whether all three coordinates are finite. */
bool Finite(const double p[3]);

/**
 * Whether any cell of the piece would draw something: a vertex, a line of
 * some length, a polygon or strip triangle of some area.
 */
bool Drawable(const Piece& piece);

/**
 * The up axis from one field data's cues, -1 when there is none (`fields`
 * may be nullptr); `reason` names the cue. A sensor pose also sets
 * `sensorForward` (and `hasForward`): the direction the sensor looked in.
 */
int UpFromFields(vtkFieldData* fields, std::string& reason, double sensorForward[3], bool& hasForward);

/** UpFromFields() over every piece's field data: the first cue found, or -1. */
int UpFromPieceFields(const std::vector<Piece>& pieces, std::string& reason,
  double sensorForward[3], bool& hasForward);

/**
 * The up axis from the geometry within `bounds` (finite): the pieces'
 * polygons (in world coordinates), else `samples` (x y z triples, a cloud's
 * points). False with `error` ("cannot stage: ...") when the core fails.
 */
bool UpFromGeometry(const std::vector<Piece>& pieces, const double bounds[6],
  const std::vector<double>& samples, int& up, std::string& reason, std::string& error);
}

#endif
