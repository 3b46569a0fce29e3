/**
 * @file    vtkMRGIReaderOutput.h
 * @brief   Internal (MRGI::RenderingIO): checks of what a VTK reader
 *          returned, before any filter or mapper touches it.
 *
 * VTK 9.1's filters and mappers index with point ids unchecked and allocate
 * what a header claims; vtkMRGISceneBuilder runs these checks on every data
 * set a reader returns (the structure checks of mrgi_ply_check.h and its
 * siblings run earlier, on the file). Not wrapped, not installed.
 */
#ifndef vtkMRGIReaderOutput_h
#define vtkMRGIReaderOutput_h

#include "vtkType.h" // For vtkIdType

#include <string> // For std::string

class vtkCellArray;
class vtkDataObject;

namespace vtkMRGIReaderOutput
{
/**
 * Largest data set MRGI draws from a file: its outer surface must fit in
 * memory, whatever a header claims (the readers allocate what it says).
 */
constexpr vtkIdType MaxPoints = vtkIdType(1) << 28;

/**
 * Whether every cell of `cells` has only point ids in [0, npoints), with
 * valid offsets; false with `why` naming the first bad one (`what` names
 * the cell kind in the message). True for nullptr.
 */
bool CellsInRange(vtkCellArray* cells, vtkIdType npoints, const char* what, std::string& why);

/**
 * Whether a data set, or every leaf of a composite data set, is safe to
 * filter and draw: point ids in range, known cell types with their point
 * counts, finite coordinates, at most MaxPoints points. False with `why`
 * saying what is wrong.
 */
bool ValidData(vtkDataObject* data, std::string& why);
}

#endif
