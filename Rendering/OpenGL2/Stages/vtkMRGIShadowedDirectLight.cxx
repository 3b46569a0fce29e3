#include "vtkMRGIShadowedDirectLight.h"

#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMRGIDirectShadows.h"
#include "vtkMRGIFrameContext.h"
#include "vtkMRGIReflectiveShadowMapPass.h"
#include "vtkMRGIShaderUtilities.h"
#include "vtkMRGIShadowComposite.h"
#include "vtkMath.h"
#include "vtkObjectFactory.h"
#include "vtkRenderer.h"

#include <cmath>

vtkStandardNewMacro(vtkMRGIShadowedDirectLight);

//------------------------------------------------------------------------------
vtkMRGIShadowedDirectLight::vtkMRGIShadowedDirectLight()
{
  this->DirectShadows = vtkMRGIDirectShadows::New();
  this->Composite = vtkMRGIShadowComposite::New();
}

//------------------------------------------------------------------------------
vtkMRGIShadowedDirectLight::~vtkMRGIShadowedDirectLight()
{
  // The stages complain themselves when they still hold GL resources.
  this->DirectShadows->Delete();
  this->Composite->Delete();
}

//------------------------------------------------------------------------------
void vtkMRGIShadowedDirectLight::ReleaseGraphicsResources(vtkWindow* w)
{
  this->DirectShadows->ReleaseGraphicsResources(w);
  this->Composite->ReleaseGraphicsResources(w);
}

//------------------------------------------------------------------------------
vtkMRGIShadowedDirectLight::Lights vtkMRGIShadowedDirectLight::AssignLights(vtkRenderer* renderer)
{
  Lights lights;
  vtkLightCollection* collection = renderer ? renderer->GetLights() : nullptr;
  if (!collection)
  {
    return lights;
  }
  vtkCollectionSimpleIterator it;
  collection->InitTraversal(it);
  int index = 0, shaderLight = 0;
  while (vtkLight* light = collection->GetNextLight(it))
  {
    if (light->GetSwitch() > 0)
    {
      const bool casts = light->GetIntensity() > 0 && !light->LightTypeIsHeadlight();
      if (shaderLight < MRGI_SHADOW_SLOTS)
      {
        lights.Slots[shaderLight] = index;
      }
      else if (casts && light->LightTypeIsSceneLight())
      {
        ++lights.UnshadowedSceneLights;
      }
      ++shaderLight;
      lights.Casting += casts;
    }
    ++index;
  }
  if (lights.UnshadowedSceneLights > 0 && !this->ExtraLightsReported)
  {
    this->ExtraLightsReported = true;
    vtkWarningMacro(<< "direct shadows are cast by the first " << MRGI_SHADOW_SLOTS
                    << " switched-on lights only; " << lights.UnshadowedSceneLights
                    << " more scene light(s) light as VTK lights them, unshadowed");
  }
  return lights;
}

//------------------------------------------------------------------------------
double vtkMRGIShadowedDirectLight::ResolveLightRadius(
  vtkRenderer* renderer, vtkMRGIReflectiveShadowMapPass* rsm, const Settings& settings)
{
  if (settings.LightRadius > 0)
  {
    return settings.LightRadius;
  }
  // The bounds change only with the props the maps are rendered from, so
  // the maps' content time keys the cache (0: never rendered, not cached).
  const vtkMTimeType content = rsm ? rsm->GetContentTime() : 0;
  if (content != 0 && content == this->AutoRadiusTime)
  {
    return this->AutoLightRadius;
  }
  double bounds[6];
  bool defined = false;
  if (renderer)
  {
    renderer->ComputeVisiblePropBounds(bounds);
    defined = vtkMath::AreBoundsInitialized(bounds);
  }
  const double diagonal = defined
    ? std::sqrt((bounds[1] - bounds[0]) * (bounds[1] - bounds[0]) +
        (bounds[3] - bounds[2]) * (bounds[3] - bounds[2]) +
        (bounds[5] - bounds[4]) * (bounds[5] - bounds[4]))
    : 0.0;
  // MRGI_SHADOW_AUTO_LIGHT_RADIUS of the bounding radius
  // (Documentation/DirectShadows.md measures the choice).
  this->AutoLightRadius =
    std::isfinite(diagonal) ? 0.5 * diagonal * MRGI_SHADOW_AUTO_LIGHT_RADIUS : 0.0;
  this->AutoRadiusTime = content;
  ++this->NumberOfLightRadiusUpdates;
  return this->AutoLightRadius;
}

//------------------------------------------------------------------------------
bool vtkMRGIShadowedDirectLight::Apply(const vtkMRGIFrameContext& frame,
  vtkMRGIReflectiveShadowMapPass* rsm, const Lights& lights, const Settings& settings,
  vtkTextureObject* colour, vtkTextureObject* const terms[MRGI_SHADOW_SLOTS],
  vtkTextureObject* factors, vtkTextureObject* target)
{
  vtkMRGIShaderUtilities::ScopedStage stage(frame.Timer, "shadows");
  mrgi_direct_shadow_params params;
  mrgi_direct_shadow_params_default(&params);
  params.mode = settings.Mode;
  params.samples_side = settings.SamplesSide;
  params.light_radius = this->ResolveLightRadius(frame.Renderer, rsm, settings);
  this->LastLightRadius = params.light_radius;
  // The stages check every input and name the problem.
  bool applied = settings.Multiresolution
    ? this->DirectShadows->ComputeMultiresolution(frame, rsm, lights.Slots, params, factors)
    : this->DirectShadows->Compute(frame, rsm, lights.Slots, params, factors);
  applied = applied && this->Composite->Apply(frame, colour, terms, factors, target);
  if (applied)
  {
    this->FailureReported = false;
  }
  else if (!this->FailureReported)
  {
    this->FailureReported = true;
    vtkErrorMacro("the direct shadows could not be computed at "
      << frame.Viewport[2] << " x " << frame.Viewport[3]
      << " pixels: this frame has VTK's unshadowed direct light");
  }
  return applied;
}

//------------------------------------------------------------------------------
void vtkMRGIShadowedDirectLight::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "LastLightRadius: " << this->LastLightRadius << "\n";
  os << indent << "NumberOfLightRadiusUpdates: " << this->NumberOfLightRadiusUpdates << "\n";
  os << indent << "DirectShadows:\n";
  this->DirectShadows->PrintSelf(os, indent.GetNextIndent());
  os << indent << "Composite:\n";
  this->Composite->PrintSelf(os, indent.GetNextIndent());
}
