#include "vtkMRGIAreaLightEmitter.h"

#include "vtkActor.h"
#include "vtkCellArray.h"
#include "vtkFloatArray.h"
#include "vtkImageAlgorithm.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMRGIAreaLightUtilities.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataAlgorithm.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkTexture.h"
#include "vtkUnsignedCharArray.h"
#include "vtkWeakPointer.h"

#include "mrgi_image.h"

#include <algorithm>
#include <utility>
#include <vector>

//------------------------------------------------------------------------------
// The emitter quad, regenerated whenever the light's own properties change
// (not when only its texture image does).
class vtkMRGIAreaLightGeometrySource : public vtkPolyDataAlgorithm
{
public:
  static vtkMRGIAreaLightGeometrySource* New();
  vtkTypeMacro(vtkMRGIAreaLightGeometrySource, vtkPolyDataAlgorithm);

  // Weak: the light owns this source (through its emitter's actor), while a
  // renderer may keep the actor after the light is gone.
  vtkWeakPointer<vtkObject> Light;
  vtkMRGIAreaLightEmitter::QuadFunction AskQuad;
  // Set for the sources of ShareActor()'s views only: they keep the light
  // alive (it holds them weakly, so there is no cycle).
  vtkSmartPointer<vtkObject> Owner;

  vtkMTimeType GetMTime() override
  {
    vtkMTimeType mtime = this->Superclass::GetMTime();
    if (this->Light)
    {
      mtime = std::max(mtime, this->Light->vtkObject::GetMTime());
    }
    return mtime;
  }

protected:
  vtkMRGIAreaLightGeometrySource() { this->SetNumberOfInputPorts(0); }

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector* out) override
  {
    vtkPolyData* output = vtkPolyData::GetData(out);
    if (!this->Light || !this->AskQuad(output))
    {
      output->Initialize(); // an invalid light draws nothing
    }
    return 1;
  }

private:
  vtkMRGIAreaLightGeometrySource(const vtkMRGIAreaLightGeometrySource&) = delete;
  void operator=(const vtkMRGIAreaLightGeometrySource&) = delete;
};
vtkStandardNewMacro(vtkMRGIAreaLightGeometrySource);

//------------------------------------------------------------------------------
// The emitter's picture: Intensity * Color * T scaled for display
// (vtkMRGIAreaLightUtilities::EncodeDisplayPicture()) as 8-bit sRGB RGB,
// the input of the actor's texture; regenerated when the light or its
// texture image changes (the next video frame).
class vtkMRGIAreaLightEmissionSource : public vtkImageAlgorithm
{
public:
  static vtkMRGIAreaLightEmissionSource* New();
  vtkTypeMacro(vtkMRGIAreaLightEmissionSource, vtkImageAlgorithm);

  vtkWeakPointer<vtkObject> Light;
  vtkMRGIAreaLightEmitter::PictureFunction AskPicture;

  vtkMTimeType GetMTime() override
  {
    vtkMTimeType mtime = this->Superclass::GetMTime();
    if (this->Light)
    {
      mtime = std::max(mtime, this->Light->GetMTime());
    }
    return mtime;
  }

protected:
  vtkMRGIAreaLightEmissionSource() { this->SetNumberOfInputPorts(0); }

  int RequestInformation(
    vtkInformation*, vtkInformationVector**, vtkInformationVector* out) override
  {
    // No picture: 1 x 1 black.
    const mrgi_image* picture = this->Light ? this->AskPicture().Image : nullptr;
    const int width = picture ? picture->width : 1;
    const int height = picture ? picture->height : 1;
    vtkInformation* info = out->GetInformationObject(0);
    int extent[6] = { 0, width - 1, 0, height - 1, 0, 0 };
    info->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
    vtkDataObject::SetPointDataActiveScalarInfo(info, VTK_UNSIGNED_CHAR, 3);
    return 1;
  }

  void ExecuteDataWithInformation(vtkDataObject* data, vtkInformation* info) override
  {
    vtkImageData* image = this->AllocateOutputData(data, info);
    auto* rgb = vtkArrayDownCast<vtkUnsignedCharArray>(image->GetPointData()->GetScalars());
    vtkMRGIAreaLightEmitter::Picture picture;
    if (this->Light)
    {
      picture = this->AskPicture();
    }
    int dims[3];
    image->GetDimensions(dims);
    if (!rgb || !picture.Image || picture.Image->width != dims[0] ||
      picture.Image->height != dims[1])
    {
      if (rgb)
      {
        rgb->FillValue(0);
      }
      return;
    }
    vtkMRGIAreaLightUtilities::EncodeDisplayPicture(
      picture.Image, picture.Intensity, picture.Color, rgb->GetPointer(0));
  }

private:
  vtkMRGIAreaLightEmissionSource(const vtkMRGIAreaLightEmissionSource&) = delete;
  void operator=(const vtkMRGIAreaLightEmissionSource&) = delete;
};
vtkStandardNewMacro(vtkMRGIAreaLightEmissionSource);

//------------------------------------------------------------------------------
struct vtkMRGIAreaLightEmitter::vtkInternals
{
  vtkWeakPointer<vtkObject> Light;
  QuadFunction AskQuad;
  PictureFunction AskPicture;
  // The emitter's actor and what feeds it (created on first request).
  vtkSmartPointer<vtkActor> Actor;
  vtkSmartPointer<vtkTexture> EmissionTexture;
  vtkSmartPointer<vtkProperty> BackProperty;
  // Actors given to ShareActor(): kept in step with Actor's look.
  std::vector<vtkWeakPointer<vtkActor>> Views;
};

//------------------------------------------------------------------------------
vtkStandardNewMacro(vtkMRGIAreaLightEmitter);

//------------------------------------------------------------------------------
vtkMRGIAreaLightEmitter::vtkMRGIAreaLightEmitter()
  : Internals(new vtkInternals)
{
}

//------------------------------------------------------------------------------
vtkMRGIAreaLightEmitter::~vtkMRGIAreaLightEmitter() = default;

//------------------------------------------------------------------------------
void vtkMRGIAreaLightEmitter::SetLight(vtkObject* light, QuadFunction quad, PictureFunction picture)
{
  this->Internals->Light = light;
  this->Internals->AskQuad = std::move(quad);
  this->Internals->AskPicture = std::move(picture);
}

//------------------------------------------------------------------------------
void vtkMRGIAreaLightEmitter::MakeQuad(
  const double center[3], const double edgeU[3], const double edgeV[3], vtkPolyData* quad)
{
  // Corners in the order of mrgi_area_light_uniforms::corners (counter-
  // clockwise seen from the emitting side, so VTK's front face is the
  // emitting one), with texture coordinates (s, t) of the core's mapping.
  static const double signs[4][2] = { { -0.5, -0.5 }, { 0.5, -0.5 }, { 0.5, 0.5 }, { -0.5, 0.5 } };
  double normal[3];
  vtkMath::Cross(edgeU, edgeV, normal);
  vtkMath::Normalize(normal);
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkFloatArray> normals;
  normals->SetName("Normals");
  normals->SetNumberOfComponents(3);
  vtkNew<vtkFloatArray> tcoords;
  tcoords->SetName("TCoords");
  tcoords->SetNumberOfComponents(2);
  for (const auto& sign : signs)
  {
    double corner[3];
    for (int c = 0; c < 3; ++c)
    {
      corner[c] = center[c] + sign[0] * edgeU[c] + sign[1] * edgeV[c];
    }
    points->InsertNextPoint(corner);
    normals->InsertNextTuple(normal);
    const double st[2] = { sign[0] + 0.5, sign[1] + 0.5 };
    tcoords->InsertNextTuple(st);
  }
  vtkNew<vtkCellArray> polys;
  const vtkIdType ids[4] = { 0, 1, 2, 3 };
  polys->InsertNextCell(4, ids);
  quad->Initialize();
  quad->SetPoints(points);
  quad->SetPolys(polys);
  quad->GetPointData()->SetNormals(normals);
  quad->GetPointData()->SetTCoords(tcoords);
}

//------------------------------------------------------------------------------
vtkActor* vtkMRGIAreaLightEmitter::GetActor()
{
  vtkInternals& internals = *this->Internals;
  if (!internals.Actor)
  {
    vtkNew<vtkMRGIAreaLightGeometrySource> geometry;
    geometry->Light = internals.Light;
    geometry->AskQuad = internals.AskQuad;
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputConnection(geometry->GetOutputPort());
    mapper->ScalarVisibilityOff();
    internals.Actor = vtkSmartPointer<vtkActor>::New();
    internals.Actor->SetMapper(mapper);

    vtkNew<vtkMRGIAreaLightEmissionSource> emission;
    emission->Light = internals.Light;
    emission->AskPicture = internals.AskPicture;
    internals.EmissionTexture = vtkSmartPointer<vtkTexture>::New();
    internals.EmissionTexture->SetInputConnection(emission->GetOutputPort());
    // 8 bits sRGB-encoded keep dark radiances; GL decodes back to linear.
    internals.EmissionTexture->UseSRGBColorSpaceOn();
    internals.EmissionTexture->InterpolateOn();
    internals.EmissionTexture->MipmapOn(); // a video frame seen small must not alias
    // Mesa llvmpipe's anisotropic filtering (VTK's default 4x) blends coarser
    // levels in even where the texture is magnified (measured: a 2 x 2
    // picture drawn 64 pixels wide mixed all four texels where bilinear
    // filtering gives one texel's colour): plain trilinear filtering.
    internals.EmissionTexture->SetMaximumAnisotropicFiltering(1.0f);
    internals.EmissionTexture->RepeatOff();
    internals.EmissionTexture->EdgeClampOn();

    // The back of a one-sided emitter emits nothing: black, not see-through.
    internals.BackProperty = vtkSmartPointer<vtkProperty>::New();
    internals.BackProperty->LightingOff();
    internals.BackProperty->SetAmbient(1.0);
    internals.BackProperty->SetDiffuse(0.0);
    internals.BackProperty->SetSpecular(0.0);
  }
  return internals.Actor;
}

//------------------------------------------------------------------------------
void vtkMRGIAreaLightEmitter::UpdateActor(const Look& look)
{
  this->GetActor();
  vtkInternals& internals = *this->Internals;
  vtkActor* actor = internals.Actor;
  actor->SetVisibility(look.Visible ? 1 : 0);
  vtkProperty* property = actor->GetProperty();
  // An emitter shows its radiance whatever the lights (as the emitters of
  // vtkMRGISceneBuilder): VTK's ambient term only.
  property->LightingOff();
  property->SetAmbient(1.0);
  property->SetDiffuse(0.0);
  property->SetSpecular(0.0);
  double front[3] = { 1.0, 1.0, 1.0 };
  if (!look.Textured)
  {
    for (int c = 0; c < 3; ++c)
    {
      front[c] = vtkMRGIAreaLightUtilities::Sanitized(look.Intensity) *
        vtkMRGIAreaLightUtilities::Sanitized(look.Color[c]);
    }
  }
  vtkTexture* texture = look.Textured ? internals.EmissionTexture.Get() : nullptr;
  actor->SetTexture(texture);
  // With a texture, VTK clamps the colour to [0, 1] before it modulates
  // the texture: the radiance scale is in the emission picture and the
  // colour is white. Without one, the colour is the radiance.
  property->SetAmbientColor(front);
  property->SetColor(front);
  // The backface property stays set (VTK 9.1's mapper keeps reading it
  // once its shader was built with it, even after it is removed): black
  // for a one-sided light, the front's look for a two-sided one.
  double back[3];
  for (int c = 0; c < 3; ++c)
  {
    back[c] = look.TwoSided ? front[c] : 0.0;
  }
  internals.BackProperty->SetAmbientColor(back);
  internals.BackProperty->SetColor(back);
  actor->SetBackfaceProperty(internals.BackProperty);
  // The shared views follow the texture switch (everything else they share).
  for (const vtkWeakPointer<vtkActor>& view : internals.Views)
  {
    if (view)
    {
      view->SetTexture(texture);
    }
  }
}

//------------------------------------------------------------------------------
void vtkMRGIAreaLightEmitter::ShareActor(vtkActor* actor)
{
  vtkActor* own = this->GetActor();
  if (!actor || actor == own)
  {
    return;
  }
  // Forget views that are gone; add this one once.
  auto& views = this->Internals->Views;
  views.erase(std::remove_if(views.begin(), views.end(),
                [](const vtkWeakPointer<vtkActor>& view) { return !view; }),
    views.end());
  if (std::none_of(views.begin(), views.end(),
        [actor](const vtkWeakPointer<vtkActor>& view) { return view.Get() == actor; }))
  {
    views.emplace_back(actor);
  }
  // Its own quad source (the same quad), which keeps the light alive: the
  // view may outlive whoever made it (a scene builder).
  vtkNew<vtkMRGIAreaLightGeometrySource> geometry;
  geometry->Light = this->Internals->Light;
  geometry->AskQuad = this->Internals->AskQuad;
  geometry->Owner = this->Internals->Light.Get();
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(geometry->GetOutputPort());
  mapper->ScalarVisibilityOff();
  actor->SetMapper(mapper);
  actor->SetProperty(own->GetProperty());
  actor->SetBackfaceProperty(own->GetBackfaceProperty());
  actor->SetTexture(own->GetTexture());
}

//------------------------------------------------------------------------------
void vtkMRGIAreaLightEmitter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  const vtkInternals& internals = *this->Internals;
  os << indent << "Light: " << static_cast<void*>(internals.Light.Get()) << "\n";
  os << indent << "Actor: " << static_cast<void*>(internals.Actor.Get()) << "\n";
  size_t views = 0;
  for (const vtkWeakPointer<vtkActor>& view : internals.Views)
  {
    views += view ? 1 : 0;
  }
  os << indent << "SharedViews: " << views << "\n";
}
