/**
 * @file    vtkPVMRGIAreaLights.h
 * @brief   The MRGI view's area lights, found in the data it renders.
 *
 * vtkMRGIAreaLightSource marks its output with the field array
 * "MRGIAreaLight". Before each render of a vtkPVMRGIRenderView (its
 * renderer's StartEvent, after ParaView gave every representation its
 * data), Synchronize() walks the renderer's actors: for every VISIBLE actor
 * whose mapper's input (a vtkPolyData with cells, or a composite data set, leaf by
 * leaf, as ParaView's geometry representations deliver it) carries the
 * mark, it keeps one vtkMRGIAreaLight in the pass (one per data object,
 * however many actors draw it; placed by the actor's matrix, so that
 * ParaView's display Position, Orientation and Scale move the light with
 * its rectangle), with the mark's
 * parameters and the "Texture" cell array as its picture. The light's own
 * emitter actor stays hidden (SetVisible(false)): the representation
 * already draws the rectangle. A light whose actor was hidden or removed,
 * or whose data lost the mark, is removed from the pass, its GPU textures
 * freed.
 *
 * Reading the mapper's input, not the pipeline's output, means the lights
 * come from what this process renders: in pvbatch, on every MPI rank, and
 * on the client or the server, wherever ParaView delivered the geometry.
 *
 * Caching: a light is updated (and its picture copied, so its texture
 * pyramid rebuilt) only when it is new (new data object: ParaView
 * delivered a new update) or its data's MTime changed; an actor moved
 * (matrix changed) only re-places it. NumberOfUpdates counts both.
 *
 * Bad data: a mark of the wrong size, or a Texture array that is missing,
 * of the wrong type or not width x height tuples, is reported once per data
 * change (naming the problem) and gives no light; an invalid parameter is
 * the light's own error (vtkMRGIAreaLight), reported by the pass, which
 * then skips the light.
 */
#ifndef vtkPVMRGIAreaLights_h
#define vtkPVMRGIAreaLights_h

#include "vtkSmartPointer.h"
#include "vtkType.h"
#include "vtkWeakPointer.h"

#include <vector> // For std::vector

class vtkDataObject;
class vtkMRGIAreaLight;
class vtkMRGIPass;
class vtkObject;
class vtkPolyData;
class vtkRenderer;

class vtkPVMRGIAreaLights
{
public:
  /**
   * Makes `pass`'s area lights those of `renderer`'s visible actors;
   * errors are reported as `reporter`'s (the view).
   */
  void Synchronize(vtkRenderer* renderer, vtkMRGIPass* pass, vtkObject* reporter);

  /**
   * Removes every light this object added from `pass` (nullptr: just
   * forgets them). Release the pass's graphics resources first: it frees
   * the GPU textures of the lights it still holds.
   */
  void RemoveAll(vtkMRGIPass* pass);

  /** Lights currently in the pass. */
  int GetNumberOfLights() const;

  /** Light updates (a light made or its parameters and picture read again). */
  vtkIdType GetNumberOfUpdates() const { return this->NumberOfUpdates; }

private:
  struct Entry
  {
    vtkWeakPointer<vtkPolyData> Data; // the light's key: null once ParaView freed it
    vtkMTimeType DataTime = 0;
    double Matrix[16] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 }; // the actor's

    bool Valid = false;
    vtkSmartPointer<vtkMRGIAreaLight> Light;
  };

  /**
   * Reads `data`'s mark into `light`, placed by the actor's `matrix`
   * (row-major), and its picture too when `readPicture`; false (reported)
   * when unusable.
   */
  static bool ReadLight(vtkPolyData* data, const double matrix[16], vtkMRGIAreaLight* light,
    bool readPicture, vtkObject* reporter);

  std::vector<Entry> Entries;
  vtkIdType NumberOfUpdates = 0;
};

#endif
