#include "vtkPVMRGIAreaLights.h"

#include "vtkActor.h"
#include "vtkActorCollection.h"
#include "vtkCellData.h"
#include "vtkCompositeDataIterator.h"
#include "vtkCompositeDataSet.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkMRGIAreaLight.h"
#include "vtkMRGIAreaLightSource.h"
#include "vtkMRGIPass.h"
#include "vtkMapper.h"
#include "vtkMatrix4x4.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"

#include <algorithm>
#include <cstring>

namespace
{
// The marked leaves of an actor's input, in the composite's order.
void MarkedLeaves(vtkDataObject* data, std::vector<vtkPolyData*>& leaves)
{
  // A light has cells: ParaView's other representations of the same source
  // (its selection, empty until something is selected) keep the field data
  // but no geometry, and must not light the scene twice.
  auto marked = [](vtkDataObject* object) {
    auto* poly = vtkPolyData::SafeDownCast(object);
    return poly && poly->GetNumberOfCells() > 0 &&
        poly->GetFieldData()->GetAbstractArray("MRGIAreaLight")
      ? poly
      : nullptr;
  };
  if (auto* composite = vtkCompositeDataSet::SafeDownCast(data))
  {
    vtkSmartPointer<vtkCompositeDataIterator> it;
    it.TakeReference(composite->NewIterator());
    for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem())
    {
      if (vtkPolyData* poly = marked(it->GetCurrentDataObject()))
      {
        leaves.push_back(poly);
      }
    }
  }
  else if (vtkPolyData* poly = marked(data))
  {
    leaves.push_back(poly);
  }
}
}

//------------------------------------------------------------------------------
bool vtkPVMRGIAreaLights::ReadLight(vtkPolyData* data, const double matrix[16],
  vtkMRGIAreaLight* light, bool readPicture, vtkObject* reporter)
{
  auto* mark =
    vtkDoubleArray::SafeDownCast(data->GetFieldData()->GetAbstractArray("MRGIAreaLight"));
  if (!mark || mark->GetNumberOfComponents() != VTK_MRGI_AREA_LIGHT_FIELD_SIZE ||
    mark->GetNumberOfTuples() < 1)
  {
    vtkErrorWithObjectMacro(reporter,
      "MRGI area light data: the field array MRGIAreaLight is not one tuple of "
        << VTK_MRGI_AREA_LIGHT_FIELD_SIZE << " doubles (made by vtkMRGIAreaLightSource?)");
    return false;
  }
  double v[VTK_MRGI_AREA_LIGHT_FIELD_SIZE];
  mark->GetTypedTuple(0, v);
  // Where the actor draws the rectangle (ParaView's display Position,
  // Orientation, Scale): the centre as a point, the edges as vectors. A
  // non-uniform scale can make the edges oblique: the light reports it.
  double placed[9];
  for (int r = 0; r < 3; ++r)
  {
    const double* row = matrix + 4 * r;
    placed[r] = row[0] * v[0] + row[1] * v[1] + row[2] * v[2] + row[3];
    placed[3 + r] = row[0] * v[3] + row[1] * v[4] + row[2] * v[5];
    placed[6 + r] = row[0] * v[6] + row[1] * v[7] + row[2] * v[8];
  }
  light->SetCenter(placed);
  light->SetEdgeU(placed + 3);
  light->SetEdgeV(placed + 6);
  light->SetColor(v + 9);
  light->SetIntensity(v[12]);
  light->SetTwoSided(v[13] != 0.0);
  // The representation draws the rectangle: the light's own emitter stays hidden.
  light->SetVisible(false);

  if (!readPicture)
  {
    return true; // moved only: the picture the light holds is still the data's
  }
  const double width = v[14];
  const double height = v[15];
  if (width == 0.0 && height == 0.0)
  {
    light->SetTextureData(nullptr);
    return true;
  }
  auto* texels = vtkFloatArray::SafeDownCast(data->GetCellData()->GetAbstractArray("Texture"));
  const bool sized = width >= 1.0 && height >= 1.0 && width <= VTK_INT_MAX &&
    height <= VTK_INT_MAX && width == static_cast<int>(width) && height == static_cast<int>(height);
  if (!sized || !texels || texels->GetNumberOfComponents() != 3 ||
    static_cast<double>(texels->GetNumberOfTuples()) != width * height)
  {
    vtkErrorWithObjectMacro(reporter,
      "MRGI area light data: the picture is "
        << width << " x " << height << " texels but the cell array Texture "
        << (texels ? "does not hold that many float RGB tuples" : "is missing or not float")
        << "; the light is left out");
    return false;
  }
  // A copy: the light keeps its picture while ParaView replaces its data.
  vtkNew<vtkImageData> image;
  image->SetDimensions(static_cast<int>(width), static_cast<int>(height), 1);
  vtkNew<vtkFloatArray> scalars;
  scalars->DeepCopy(texels);
  scalars->SetName("Texture");
  image->GetPointData()->SetScalars(scalars);
  light->SetTextureData(image);
  return true;
}

//------------------------------------------------------------------------------
void vtkPVMRGIAreaLights::Synchronize(vtkRenderer* renderer, vtkMRGIPass* pass, vtkObject* reporter)
{
  if (!renderer || !pass)
  {
    return;
  }
  std::vector<Entry> kept;
  vtkActorCollection* actors = renderer->GetActors();
  vtkCollectionSimpleIterator cookie;
  actors->InitTraversal(cookie);
  while (vtkActor* actor = actors->GetNextActor(cookie))
  {
    vtkMapper* mapper = actor->GetMapper();
    if (!actor->GetVisibility() || !mapper || mapper->GetNumberOfInputPorts() < 1 ||
      mapper->GetNumberOfInputConnections(0) < 1)
    {
      continue;
    }
    std::vector<vtkPolyData*> leaves;
    MarkedLeaves(mapper->GetInputDataObject(0, 0), leaves);
    for (vtkPolyData* data : leaves)
    {
      // One light per data object: ParaView draws a representation's data
      // through more than one actor (e.g. two visible vtkPVLODActors).
      auto same = [&](const Entry& e) { return e.Data == data; };
      if (std::any_of(kept.begin(), kept.end(), same))
      {
        continue;
      }
      auto found = std::find_if(this->Entries.begin(), this->Entries.end(), same);
      Entry entry;
      if (found != this->Entries.end())
      {
        entry = *found;
        this->Entries.erase(found);
      }
      else
      {
        entry.Data = data;
        entry.Light = vtkSmartPointer<vtkMRGIAreaLight>::New();
      }
      double matrix[16];
      vtkMatrix4x4::DeepCopy(matrix, actor->GetMatrix());
      const bool dataChanged = entry.DataTime != data->GetMTime();
      if (dataChanged || !std::equal(matrix, matrix + 16, entry.Matrix))
      {
        entry.DataTime = data->GetMTime();
        std::copy(matrix, matrix + 16, entry.Matrix);
        const bool wasValid = entry.Valid;
        // An invalid light holds no picture: read it whenever it is read.
        entry.Valid = ReadLight(data, matrix, entry.Light, dataChanged || !wasValid, reporter);
        ++this->NumberOfUpdates;
        if (entry.Valid && !wasValid)
        {
          pass->AddAreaLight(entry.Light);
        }
        else if (!entry.Valid && wasValid)
        {
          pass->RemoveAreaLight(entry.Light);
          entry.Light->ReleaseGraphicsResources(renderer->GetRenderWindow());
        }
      }
      kept.push_back(entry);
    }
  }
  // What is left was hidden, removed or unmarked since the last render (or
  // its data was replaced: a new entry took over). The light goes with its
  // GPU textures, freed now while the window's context is current (the
  // renderer made it current before its StartEvent).
  for (const Entry& gone : this->Entries)
  {
    if (gone.Valid)
    {
      pass->RemoveAreaLight(gone.Light);
    }
    gone.Light->ReleaseGraphicsResources(renderer->GetRenderWindow());
  }
  this->Entries.swap(kept);
}

//------------------------------------------------------------------------------
void vtkPVMRGIAreaLights::RemoveAll(vtkMRGIPass* pass)
{
  if (pass)
  {
    for (const Entry& entry : this->Entries)
    {
      if (entry.Valid)
      {
        pass->RemoveAreaLight(entry.Light);
      }
    }
  }
  this->Entries.clear();
}

//------------------------------------------------------------------------------
int vtkPVMRGIAreaLights::GetNumberOfLights() const
{
  return static_cast<int>(std::count_if(
    this->Entries.begin(), this->Entries.end(), [](const Entry& e) { return e.Valid; }));
}
