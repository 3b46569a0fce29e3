#include "vtkMRGIAreaLightRSMViews.h"

#include "vtkObjectFactory.h"
#include "vtkShaderProgram.h"

#include "vtkMRGIAreaLight.h"
#include "vtkMRGIRSMView.h"

#include <algorithm>
#include <ostream>

vtkStandardNewMacro(vtkMRGIAreaLightRSMViews);

//------------------------------------------------------------------------------
void vtkMRGIAreaLightRSMViews::SampleEmitters(vtkMRGIAreaLight* const* lights, int count,
  std::vector<Emitter>& emitters, std::ostream& signature)
{
  this->NumberOfEmitters = 0;
  for (int k = 0; lights && k < count; ++k)
  {
    vtkMRGIAreaLight* area = lights[k];
    Emitter info;
    info.Index = k;
    const mrgi_area_light_texture_pyramid* pyramid = nullptr;
    // GetCoreLight() and GetCorePyramid() report a bad light themselves.
    if (!area || area->GetIntensity() <= 0 || !area->GetCoreLight(&info.Core) ||
      !area->GetCorePyramid(&pyramid))
    {
      continue;
    }
    const double* c = area->GetColor();
    if (!(std::max({ c[0], c[1], c[2] }) > 0))
    {
      continue;
    }
    mrgi_error err;
    int32_t made = 0;
    if (mrgi_area_light_make_samples(&info.Core, pyramid, MRGI_AREA_LIGHT_RSM_SAMPLES, 0, 0,
          info.Samples, MRGI_AREA_LIGHT_RSM_SAMPLES, &made, &err) != MRGI_OK)
    {
      vtkErrorMacro("area light " << k << " gets no indirect light: " << err.message);
      continue;
    }
    info.SampleCount = made;
    emitters.push_back(info);
    ++this->NumberOfEmitters;
    // Values, not the object's address or MTime: every rank must agree.
    signature << 'A' << k;
    for (int i = 0; i < made; ++i)
    {
      const float* f = &info.Samples[i].position[0];
      for (int j = 0; j < MRGI_AREA_LIGHT_SAMPLE_FLOATS; ++j)
      {
        signature << ',' << f[j];
      }
    }
    signature << ',' << info.Core.two_sided << ';';
  }
}

//------------------------------------------------------------------------------
void vtkMRGIAreaLightRSMViews::AddViews(const std::vector<Emitter>& emitters,
  const double center[3], double radius, double texelsPerSide,
  std::vector<std::unique_ptr<vtkMRGIRSMView>>& views)
{
  this->NumberOfViews = 0;
  for (const Emitter& info : emitters)
  {
    double directions[MRGI_AREA_LIGHT_RSM_MAX_VIEWS][3];
    int32_t faces = 0;
    mrgi_error err;
    if (mrgi_area_light_rsm_views(&info.Core, directions, &faces, &err) != MRGI_OK)
    {
      vtkErrorMacro("area light " << info.Index << " gets no indirect light: " << err.message);
      continue;
    }
    for (int f = 0; f < faces; ++f)
    {
      auto view = std::make_unique<vtkMRGIRSMView>();
      view->Light = -2 - info.Index;
      view->AreaSampleCount = info.SampleCount;
      view->AreaTwoSided = info.Core.two_sided != 0;
      for (int i = 0; i < info.SampleCount; ++i)
      {
        std::copy_n(&info.Samples[i].position[0], MRGI_AREA_LIGHT_SAMPLE_FLOATS, view->AreaSamples[i]);
      }
      view->SetPerspective(info.Core.center, directions[f], 90.0, center, radius, texelsPerSide);
      views.push_back(std::move(view));
      ++this->NumberOfViews;
    }
  }
}

//------------------------------------------------------------------------------
void vtkMRGIAreaLightRSMViews::SetShaderParameters(
  vtkShaderProgram* program, const vtkMRGIRSMView& view)
{
  program->SetUniformi("mrgiAreaSampleCount", view.AreaSampleCount);
  program->SetUniformi("mrgiAreaTwoSided", view.AreaTwoSided ? 1 : 0);
  if (view.AreaSampleCount > 0)
  {
    // One record = MRGI_AREA_LIGHT_SAMPLE_TEXELS vec4s (mrgi_area_light_sample).
    static_assert(MRGI_AREA_LIGHT_SAMPLE_FLOATS == 4 * MRGI_AREA_LIGHT_SAMPLE_TEXELS,
      "an area-light sample is whole vec4s");
    program->SetUniform4fv("mrgiAreaSamples",
      MRGI_AREA_LIGHT_RSM_SAMPLES * MRGI_AREA_LIGHT_SAMPLE_TEXELS, &view.AreaSamples[0][0]);
  }
}

//------------------------------------------------------------------------------
void vtkMRGIAreaLightRSMViews::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "NumberOfEmitters: " << this->NumberOfEmitters << "\n";
  os << indent << "NumberOfViews: " << this->NumberOfViews << "\n";
}
