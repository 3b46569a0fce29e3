// The multiresolution area-light specular gather (vtkMRGIPass
// AreaLightSpecularResolution = SpecularMultiresolution,
// nichols-penmatsa-wyman-2010 3.2.1): (1) the GPU's specular stencil equals
// mrgi_specular_stencil_build() fed with the GPU's own flags, receivers and
// material pyramid, bit for bit except where the lobe metric is within float
// rounding of 1; (2) the lobe metric adds refinement for a sharp exponent
// and lowers the error (with it off, fewer texels and a larger error), so
// the test can fail; (3) the multiresolution highlight stays within a
// stated error of the full-resolution one.
#include "mrgiPassSceneFixture.h"
#include "mrgiTestUtilities.h"

#include "vtkActor.h"
#include "vtkActorCollection.h"
#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkMRGIAreaLight.h"
#include "vtkMRGIAreaLightStage.h"
#include "vtkMRGIMultiresolution.h"
#include "vtkMRGISpecularStencil.h"
#include "vtkMRGIPass.h"
#include "vtkMRGISceneBuilder.h"
#include "vtkPointData.h"
#include "vtkProperty.h"
#include "vtkRenderStepsPass.h"
#include "vtkRenderer.h"
#include "vtkUnsignedCharArray.h"

#include "mrgi_multires.h"
#include "mrgi_specular_stencil.h"

#include <cmath>
#include <cstdio>
#include <vector>

namespace
{
using mrgitest::AreaBuffer;

// ||a - b|| / ||ref - base|| over RGB.
double RelativeError(vtkImageData* a, vtkImageData* b, vtkImageData* ref, vtkImageData* base)
{
  vtkDataArray* A = a->GetPointData()->GetScalars();
  vtkDataArray* B = b->GetPointData()->GetScalars();
  vtkDataArray* R = ref->GetPointData()->GetScalars();
  vtkDataArray* Z = base->GetPointData()->GetScalars();
  double num = 0.0, den = 0.0;
  for (vtkIdType i = 0; i < A->GetNumberOfTuples(); ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      const double d = A->GetComponent(i, c) - B->GetComponent(i, c);
      const double s = R->GetComponent(i, c) - Z->GetComponent(i, c);
      num += d * d;
      den += s * s;
    }
  }
  MRGI_TEST_CHECK(den > 0.0);
  return std::sqrt(num / den);
}
}

int main()
{
  const int W = 96, H = 80;
  mrgitest::PassScene scene(W, H, "cornell-spot");
  vtkRenderWindow* window = scene.Window;
  vtkRenderer* renderer = scene.Renderer;
  vtkMRGIPass* pass = scene.Pass;
  double b[6];
  renderer->ComputeVisiblePropBounds(b);
  pass->SetIndirectMode(vtkMRGIPass::IndirectOff);
  pass->SetAreaLightVisibility(vtkMRGIPass::VisibilityOff);
  vtkNew<vtkMRGIAreaLight> light;
  light->SetCenter(0.5 * (b[0] + b[1]), b[2] + 0.95 * (b[3] - b[2]), 0.5 * (b[4] + b[5]));
  light->SetEdgeU(0.35 * (b[1] - b[0]), 0.0, 0.0);
  light->SetEdgeV(0.0, 0.0, 0.3 * (b[5] - b[4]));
  light->SetIntensity(2.0);
  light->SetNumberOfSamples(64);
  pass->AddAreaLight(light);
  // A sharp exponent everywhere.
  vtkActorCollection* actors = renderer->GetActors();
  actors->InitTraversal();
  while (vtkActor* actor = actors->GetNextActor())
  {
    actor->GetProperty()->SetSpecular(0.5);
    actor->GetProperty()->SetSpecularPower(128.0);
  }
  MRGI_TEST_CHECK(pass->GetAreaLightSpecularResolution() == vtkMRGIPass::SpecularFullResolution);
  vtkMRGIMultiresolution* mr = pass->GetMultiresolution();
  vtkMRGISpecularStencil* specularStencil = pass->GetAreaLightStage()->GetSpecularStencilStage();

  // References: diffuse only, full-resolution highlight.
  pass->AreaLightSpecularOff();
  window->Render();
  vtkSmartPointer<vtkImageData> diffuse = AreaBuffer(pass, window);
  pass->AreaLightSpecularOn();
  window->Render();
  vtkSmartPointer<vtkImageData> full = AreaBuffer(pass, window);

  pass->SetAreaLightSpecularResolution(vtkMRGIPass::SpecularMultiresolution);
  double error[2] = { 0.0, 0.0 };
  long long selected[2] = { 0, 0 }, lobeFired[2] = { 0, 0 };
  for (int lobe = 1; lobe >= 0; --lobe)
  {
    specularStencil->SetLobeRefinement(lobe != 0);
    window->Render();
    MRGI_TEST_CHECK(pass->GetAreaLightsComputed());
    vtkSmartPointer<vtkImageData> multires = AreaBuffer(pass, window);
    error[lobe] = RelativeError(multires, full, full, diffuse);

    // 1. Parity of the stencil with the C twin on the GPU's inputs.
    vtkNew<vtkUnsignedCharArray> gpuSelection, gpuStencil, gpuBits, flags;
    vtkNew<vtkFloatArray> position, normal, material;
    mrgi_multires_layout layout;
    MRGI_TEST_CHECK(specularStencil->ReadStencil(window, gpuSelection, gpuBits) &&
      specularStencil->ReadStencil(window, gpuStencil, nullptr, true) && mr->ReadFlags(window, flags) &&
      mr->ReadReceivers(window, position, normal) && specularStencil->ReadMaterial(window, material) &&
      mr->GetLayout(&layout));
    const size_t texels = static_cast<size_t>(mrgi_multires_texel_count(&layout));
    mrgi_area_light_uniforms uniforms;
    MRGI_TEST_CHECK(light->GetCoreUniforms(&uniforms));
    mrgi_specular_stencil_view view{};
    const double* v2w = pass->GetLastViewToWorld();
    for (int k = 0; k < 16; ++k)
    {
      view.view_to_world[k] = static_cast<float>(v2w[k]);
    }
    double ab[2];
    mr->GetPixelSizeCoefficients(ab);
    view.pixel_size[0] = static_cast<float>(ab[0]);
    view.pixel_size[1] = static_cast<float>(ab[1]);
    view.parallel = 0;
    view.lobe = lobe;
    view.lobe_threshold = static_cast<float>(specularStencil->GetLobeThreshold());
    std::vector<uint8_t> bits(texels), selection(texels);
    mrgi_specular_stencil_stats stats;
    mrgi_error err;
    MRGI_TEST_CHECK(mrgi_specular_stencil_build(&layout, mr->GetFinestLevel(), flags->GetPointer(0),
                      material->GetPointer(0), static_cast<size_t>(material->GetNumberOfValues()),
                      position->GetPointer(0), normal->GetPointer(0),
                      static_cast<size_t>(position->GetNumberOfValues()), &uniforms, &view,
                      bits.data(), selection.data(), texels, &stats, &err) == MRGI_OK);
    long long differ = 0, near = 0, stencilDiffer = 0;
    for (size_t t = 0; t < texels; ++t)
    {
      const vtkIdType i = static_cast<vtkIdType>(t);
      stencilDiffer += (gpuStencil->GetValue(i) != 0) != (gpuSelection->GetValue(i) != 0);
      if ((gpuSelection->GetValue(i) != 0) == (selection[t] != 0) && gpuBits->GetValue(i) == bits[t])
      {
        continue;
      }
      // Allowed only where a lobe metric on the texel's ancestor chain is
      // within float rounding of 1.
      bool explained = false;
      int level = 0;
      for (int l = 0; l < layout.level_count; ++l)
      {
        if (static_cast<int>(t % static_cast<size_t>(layout.total_width)) >= layout.level_offset[l])
        {
          level = l;
        }
      }
      const int x = static_cast<int>(t % static_cast<size_t>(layout.total_width)) - layout.level_offset[level];
      const int y = static_cast<int>(t / static_cast<size_t>(layout.total_width));
      for (int j = level; j < layout.level_count && lobe; ++j)
      {
        const size_t u = mrgi_multires_index(&layout, j, x >> (j - level), y >> (j - level));
        const float m = mrgi_specular_stencil_metric(&uniforms, &view, position->GetPointer(0) + 4 * u,
          normal->GetPointer(0) + 4 * u, material->GetValue(static_cast<vtkIdType>(4 * u + 1)), j);
        explained = explained || std::fabs(m - 1.0f) < 1e-3f;
      }
      ++(explained ? near : differ);
    }
    long long gpuSelected = 0, gpuLobe = 0;
    for (size_t t = 0; t < texels; ++t)
    {
      gpuSelected += gpuSelection->GetValue(static_cast<vtkIdType>(t)) != 0;
      gpuLobe += (gpuBits->GetValue(static_cast<vtkIdType>(t)) & MRGI_SPECULAR_STENCIL_LOBE) != 0;
    }
    selected[lobe] = gpuSelected;
    lobeFired[lobe] = gpuLobe;
    std::printf("lobe metric %s: %lld texels selected (C %lld; per level", lobe ? "on" : "off",
      gpuSelected, static_cast<long long>(stats.selected_total));
    for (int l = 0; l < layout.level_count; ++l)
    {
      std::printf(" %lld", static_cast<long long>(stats.selected[l]));
    }
    std::printf("), lobe fired at %lld; %lld texels differ from the C twin (%lld more at m ~ 1); "
                "stencil vs colour %lld; highlight rel. error vs full resolution %.4f\n",
      gpuLobe, differ, near, stencilDiffer, error[lobe]);
    MRGI_TEST_CHECK(differ == 0 && stencilDiffer == 0 && gpuSelected == stats.selected_total);
  }
  // 2. The lobe metric refines the sharp exponent and helps.
  MRGI_TEST_CHECK(lobeFired[1] > 0 && lobeFired[0] == 0);
  MRGI_TEST_CHECK(selected[1] > selected[0]);
  MRGI_TEST_CHECK(error[1] < error[0]);
  // 3. Within a stated error of full resolution (measured 96x80, n = 128:
  // 0.10 with the lobe metric at the default threshold 0.125, 0.32 at
  // NPW10's 1, 0.44 without it).
  MRGI_TEST_CHECK(error[1] < 0.2);
  return 0;
}
