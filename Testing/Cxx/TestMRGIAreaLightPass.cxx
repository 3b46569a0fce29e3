// Area lights in vtkMRGIPass (nichols-penmatsa-wyman-2010 3.2, no
// visibility): with thresholds 0 the pass's area-light buffer is, pixel by
// pixel, albedo x mrgi_area_light_diffuse() of the G-buffer (the C twin);
// it is drawn with indirect light off; two lights add up; samples are
// re-uploaded only when the light changes, and a changed texture image
// shows on the next render; an invalid light draws nothing, with an error,
// and leaves the image finite.
#include "mrgiPassSceneFixture.h"
#include "mrgiTestUtilities.h"
#include "mrgiVoxelTestUtilities.h"

#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkMRGIAreaLight.h"
#include "vtkMRGIAreaLightStage.h"
#include "vtkMRGIIncrementalStencil.h"
#include "vtkMRGIMultiresolution.h"
#include "vtkMRGIPass.h"
#include "vtkMRGISceneBuilder.h"
#include "vtkPointData.h"
#include "vtkRenderStepsPass.h"
#include "vtkRenderer.h"
#include "vtkUnsignedCharArray.h"

#include "mrgi_area_light.h"
#include "mrgi_irradiance_stencil.h"
#include "mrgi_voxel_march.h"
#include "mrgi_incremental_stencil.h"
#include "mrgi_multires.h"
#include "mrgi_visibility_pyramid.h"
#include "vtkFloatArray.h"
#include "vtkActor.h"
#include "vtkActorCollection.h"
#include "vtkMRGIVisibilityPyramid.h"
#include "vtkProperty.h"
#include "vtkMRGIVoxelization.h"
#include "vtkTypeUInt32Array.h"

#include <cmath>
#include <cstdio>
#include <vector>

namespace
{
// G-buffer pixel i in world space as the shaders compute it (float, eye ->
// world by the column-major m): position, normal, and the view direction
// towards a perspective eye.
void ToWorld(const float m[16], vtkDataArray* P, vtkDataArray* N, vtkIdType i, float p[3], float n[3],
  float v[3])
{
  for (int r = 0; r < 3; ++r)
  {
    p[r] = m[12 + r];
    n[r] = 0.0f;
    v[r] = 0.0f;
    for (int k = 0; k < 3; ++k)
    {
      p[r] += m[4 * k + r] * static_cast<float>(P->GetComponent(i, k));
      n[r] += m[4 * k + r] * static_cast<float>(N->GetComponent(i, k));
      v[r] -= m[4 * k + r] * static_cast<float>(P->GetComponent(i, k));
    }
  }
}

using mrgitest::AreaBuffer;

double Sum(vtkImageData* image)
{
  vtkDataArray* a = image->GetPointData()->GetScalars();
  double sum = 0.0;
  for (vtkIdType i = 0; i < a->GetNumberOfValues(); ++i)
  {
    const double v = a->GetVariantValue(i).ToDouble();
    MRGI_TEST_CHECK(std::isfinite(v) && v >= 0.0);
    sum += v;
  }
  return sum;
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

  // A textured light just under the ceiling, facing down (u x v = -y).
  vtkNew<vtkImageData> picture;
  picture->SetDimensions(4, 4, 1);
  picture->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  auto paint = [&](int phase) {
    auto* p = static_cast<unsigned char*>(picture->GetScalarPointer());
    for (int i = 0; i < 16; ++i)
    {
      p[3 * i + 0] = static_cast<unsigned char>(((i + phase) % 4) * 80);
      p[3 * i + 1] = static_cast<unsigned char>(255 - 40 * (i % 5));
      p[3 * i + 2] = static_cast<unsigned char>(phase ? 30 : 200);
    }
    picture->Modified();
  };
  paint(0);
  vtkNew<vtkMRGIAreaLight> light;
  light->SetCenter(0.5 * (b[0] + b[1]), b[2] + 0.95 * (b[3] - b[2]), 0.5 * (b[4] + b[5]));
  light->SetEdgeU(0.35 * (b[1] - b[0]), 0.0, 0.0);
  light->SetEdgeV(0.0, 0.0, 0.3 * (b[5] - b[4]));
  light->SetIntensity(2.0);
  light->SetNumberOfSamples(256);
  light->SetTextureData(picture);
  pass->AddAreaLight(light);
  pass->AddAreaLight(light); // once only
  MRGI_TEST_CHECK(pass->GetNumberOfAreaLights() == 1 && pass->GetAreaLight(0) == light);

  // 1. Thresholds 0: every pixel gathers at full resolution, so the buffer
  // is albedo x X(G-buffer) exactly (C twin, float, the shader's transform).
  vtkMRGIMultiresolution* mr = pass->GetMultiresolution();
  mr->SetDepthThreshold(0.0);
  mr->SetNormalThreshold(0.0);
  mr->SetAreaLightDepthThreshold(0.0);
  mr->SetAreaLightNormalThreshold(0.0);
  MRGI_TEST_CHECK(pass->GetAreaLightVisibility() == vtkMRGIPass::VisibilityIncremental); // the default
  pass->SetAreaLightVisibility(vtkMRGIPass::VisibilityOff);
  window->Render();
  MRGI_TEST_CHECK(pass->GetAreaLightsComputed() && !pass->GetIndirectComputed());
  vtkSmartPointer<vtkImageData> gpu = AreaBuffer(pass, window);
  vtkNew<vtkImageData> gP, gN, gA;
  MRGI_TEST_CHECK(pass->GetGBuffer(window, gP, gN, gA));
  int count = 0;
  const mrgi_area_light_sample* samples = light->GetCoreSamples(&count);
  mrgi_area_light_uniforms uniforms;
  MRGI_TEST_CHECK(samples && count > 0 && light->GetCoreUniforms(&uniforms));
  const double* v2w = pass->GetLastViewToWorld();
  float m[16];
  for (int k = 0; k < 16; ++k)
  {
    m[k] = static_cast<float>(v2w[k]);
  }
  vtkDataArray* P = gP->GetPointData()->GetScalars();
  vtkDataArray* N = gN->GetPointData()->GetScalars();
  vtkDataArray* A = gA->GetPointData()->GetScalars();
  vtkDataArray* G = gpu->GetPointData()->GetScalars();
  double num = 0, den = 0;
  int lit = 0;
  for (vtkIdType i = 0; i < P->GetNumberOfTuples(); ++i)
  {
    float X[3] = { 0.0f, 0.0f, 0.0f };
    if (P->GetComponent(i, 3) > 0.5)
    {
      float p[3], n[3], v[3];
      ToWorld(m, P, N, i, p, n, v);
      mrgi_area_light_diffuse(&uniforms, samples, count, p, n, X);
    }
    lit += X[0] + X[1] + X[2] > 0.0f;
    for (int k = 0; k < 3; ++k)
    {
      const double expected = A->GetComponent(i, k) * X[k];
      const double got = G->GetComponent(i, k);
      MRGI_TEST_CHECK(std::isfinite(got));
      num += (got - expected) * (got - expected);
      den += expected * expected;
    }
  }
  const double error = std::sqrt(num / (den > 0 ? den : 1.0));
  std::printf("full resolution: %d lit pixels of %d, relative RMS against albedo x C twin %.3g\n", lit,
    W * H, error);
  MRGI_TEST_CHECK(lit > W * H / 4 && error < 1e-4);

  // 1b. Naive voxel visibility (NPW10 3.3.1), still at full resolution:
  // each sample's term counts where mrgi_voxel_march() on the read-back
  // voxel buffer, in eye space, finds it visible.
  // 256 samples x up to 256 steps per texel: more loop iterations than
  // llvmpipe runs in one invocation, so this also covers the batching.
  pass->SetAreaLightVisibility(vtkMRGIPass::VisibilityNaive);
  pass->GetVoxelization()->SetVoxelSide(256);
  window->Render();
  vtkSmartPointer<vtkImageData> shadowed = AreaBuffer(pass, window);
  vtkMRGIVoxelization* voxelization = pass->GetVoxelization();
  vtkNew<vtkTypeUInt32Array> voxelWords;
  double w2v[16];
  const mrgi_voxel_view view = mrgitest::ReadVoxelView(voxelization, window, voxelWords, w2v);
  mrgi_error err;
  vtkDataArray* S = shadowed->GetPointData()->GetScalars();
  num = den = 0;
  double unshadowedSum = 0, shadowedSum = 0;
  for (vtkIdType i = 0; i < P->GetNumberOfTuples(); ++i)
  {
    double X[3] = { 0.0, 0.0, 0.0 };
    if (P->GetComponent(i, 3) > 0.5)
    {
      float p[3], n[3], v[3], pv[3], nv[3];
      ToWorld(m, P, N, i, p, n, v);
      for (int r = 0; r < 3; ++r)
      {
        pv[r] = static_cast<float>(P->GetComponent(i, r));
        nv[r] = static_cast<float>(N->GetComponent(i, r));
      }
      for (int j = 0; j < count; ++j)
      {
        float Xj[3];
        mrgi_area_light_diffuse(&uniforms, samples + j, 1, p, n, Xj);
        if (Xj[0] + Xj[1] + Xj[2] == 0.0f)
        {
          continue;
        }
        float L[3], NL[3];
        for (int r = 0; r < 3; ++r)
        {
          L[r] = static_cast<float>(w2v[12 + r]);
          NL[r] = 0.0f;
          for (int k = 0; k < 3; ++k)
          {
            L[r] += static_cast<float>(w2v[4 * k + r]) * samples[j].position[k];
            NL[r] += static_cast<float>(w2v[4 * k + r]) * samples[j].normal[k];
          }
        }
        if (mrgi_voxel_march(&view, pv, nv, L, NL))
        {
          for (int k = 0; k < 3; ++k)
          {
            X[k] += Xj[k];
          }
        }
      }
    }
    for (int k = 0; k < 3; ++k)
    {
      const double expected = A->GetComponent(i, k) * X[k];
      const double got = S->GetComponent(i, k);
      MRGI_TEST_CHECK(std::isfinite(got));
      num += (got - expected) * (got - expected);
      den += expected * expected;
      shadowedSum += got;
      unshadowedSum += G->GetComponent(i, k);
    }
  }
  const double visibilityError = std::sqrt(num / (den > 0 ? den : 1.0));
  std::printf("naive visibility: %.1f%% of the unshadowed light arrives; relative RMS against the C twins "
              "(mrgi_area_light_diffuse x mrgi_voxel_march) %.3g\n",
    100.0 * shadowedSum / unshadowedSum, visibilityError);
  MRGI_TEST_CHECK(shadowedSum < 0.97 * unshadowedSum && shadowedSum > 0.2 * unshadowedSum);
  MRGI_TEST_CHECK(visibilityError < 1e-3);

  // 1c. Incremental visibility (NPW10 3.3.2): the gather weights each
  // sample by the texel's bit of the visibility pyramid (read back here),
  // and stays close to the naive image while marching far fewer rays.
  pass->SetAreaLightVisibility(vtkMRGIPass::VisibilityIncremental);
  pass->GetVisibilityPyramid()->CollectStatisticsOn();
  window->Render();
  vtkSmartPointer<vtkImageData> incremental = AreaBuffer(pass, window);
  vtkMRGIVisibilityPyramid* pyramid = pass->GetVisibilityPyramid();
  vtkNew<vtkTypeUInt32Array> masks;
  MRGI_TEST_CHECK(pyramid->ReadMasks(window, masks));
  const int words = pyramid->GetNumberOfMaskWords();
  MRGI_TEST_CHECK(words == (count + 31) / 32);
  vtkDataArray* I = incremental->GetPointData()->GetScalars();
  double inum = 0, iden = 0, nnum = 0;
  for (vtkIdType i = 0; i < P->GetNumberOfTuples(); ++i)
  {
    // Thresholds 0: every pixel gathers at level 0, whose flattened texel
    // is the pixel (level 0 starts the layout).
    const int x = static_cast<int>(i % W), y = static_cast<int>(i / W);
    const vtkIdType flat = static_cast<vtkIdType>(y) * mr->GetFlattenedWidth() + x;
    double X[3] = { 0.0, 0.0, 0.0 };
    if (P->GetComponent(i, 3) > 0.5)
    {
      float p[3], n[3], v[3];
      ToWorld(m, P, N, i, p, n, v);
      for (int j = 0; j < count; ++j)
      {
        if (((masks->GetValue(flat * words + j / 32) >> (j % 32)) & 1u) == 0u)
        {
          continue;
        }
        float Xj[3];
        mrgi_area_light_diffuse(&uniforms, samples + j, 1, p, n, Xj);
        for (int k = 0; k < 3; ++k)
        {
          X[k] += Xj[k];
        }
      }
    }
    for (int k = 0; k < 3; ++k)
    {
      const double expected = A->GetComponent(i, k) * X[k];
      const double got = I->GetComponent(i, k);
      MRGI_TEST_CHECK(std::isfinite(got));
      inum += (got - expected) * (got - expected);
      iden += expected * expected;
      nnum += (got - S->GetComponent(i, k)) * (got - S->GetComponent(i, k));
    }
  }
  const double maskError = std::sqrt(inum / (iden > 0 ? iden : 1.0));
  const double againstNaive = std::sqrt(nnum / (den > 0 ? den : 1.0));
  std::printf("incremental visibility: relative RMS against the masks x C twin %.3g, against naive %.3g; "
              "rays %lld of naive %lld (%.2f)\n",
    maskError, againstNaive, static_cast<long long>(pyramid->GetTotalNumberOfRays()),
    static_cast<long long>(pyramid->GetNumberOfNaiveRays()),
    double(pyramid->GetTotalNumberOfRays()) / double(pyramid->GetNumberOfNaiveRays()));
  MRGI_TEST_CHECK(maskError < 1e-5);
  // Reused coarse bits trade some per-pixel accuracy for fewer rays
  // (measured at 96x80: 5.3% from naive with 35% of its rays by default;
  // with 2x2 interleaving 7.3% with 15% of the rays).
  MRGI_TEST_CHECK(againstNaive < 0.12);
  MRGI_TEST_CHECK(pyramid->GetTotalNumberOfRays() < pyramid->GetNumberOfNaiveRays() / 2);

  // 1c2. Incremental stencil rendering (NPW10 3.4) at the Balanced preset:
  // the texels the GPU rendered equal mrgi_incremental_stencil_build() fed
  // with the GPU's own flags, selection, receivers and masks, bit for bit;
  // it adds texels below the geometric cut (the shadow edges), so the test
  // can fail; switched off, the gather uses the selection alone.
  mr->SetPreset(vtkMRGIMultiresolution::PresetBalanced);
  vtkMRGIAreaLightStage* area = pass->GetAreaLightStage();
  MRGI_TEST_CHECK(area->GetIncrementalStencil()); // the default
  window->Render();
  vtkSmartPointer<vtkImageData> stenciled = AreaBuffer(pass, window);
  {
    vtkNew<vtkUnsignedCharArray> gpuRendered, flags, selection;
    vtkNew<vtkFloatArray> position, normal;
    vtkNew<vtkTypeUInt32Array> levelMasks;
    mrgi_multires_layout layout;
    MRGI_TEST_CHECK(area->GetIncrementalStencilUsed());
    MRGI_TEST_CHECK(area->GetIncrementalStencilStage()->ReadStencil(window, gpuRendered) &&
      mr->ReadFlags(window, flags) &&
      mr->ReadSelection(window, selection, false) && mr->ReadReceivers(window, position, normal) &&
      pyramid->ReadMasks(window, levelMasks) && mr->GetLayout(&layout));
    const size_t texels = static_cast<size_t>(mrgi_multires_texel_count(&layout));
    std::vector<uint8_t> rendered(texels, 0);
    mrgi_incremental_stencil_stats stats;
    const int threshold =
      mrgi_voxel_refine_threshold(static_cast<float>(area->GetIncrementalStencilStage()->GetFraction()), count);
    MRGI_TEST_CHECK(mrgi_incremental_stencil_build(&layout, mr->GetFinestLevel(), flags->GetPointer(0),
                      selection->GetPointer(0), texels, position->GetPointer(0),
                      static_cast<size_t>(position->GetNumberOfValues()), levelMasks->GetPointer(0), words,
                      static_cast<size_t>(levelMasks->GetNumberOfValues()), pyramid->GetMetric(), threshold,
                      rendered.data(), texels, &stats, &err) == MRGI_OK);
    // The irradiance term (mrgi_irradiance_stencil.h) is float: the GPU
    // must lie between the twin at tau (1 + 1e-4) (fewer texels) and at
    // tau (1 - 1e-4) (more).
    const float tau = static_cast<float>(area->GetIncrementalStencilStage()->GetIrradianceTolerance());
    float viewToWorld[16];
    std::copy(v2w, v2w + 16, viewToWorld);
    std::vector<uint8_t> lo(rendered), hi(rendered);
    int64_t byIrradiance[MRGI_MULTIRES_MAX_LEVELS];
    const size_t floats = static_cast<size_t>(position->GetNumberOfValues());
    MRGI_TEST_CHECK(tau > 0.0f &&
      mrgi_irradiance_stencil_add(&layout, mr->GetFinestLevel(), flags->GetPointer(0), texels,
        position->GetPointer(0), normal->GetPointer(0), floats, viewToWorld, &uniforms, tau * (1.0f + 1e-4f),
        lo.data(), texels, byIrradiance, &err) == MRGI_OK &&
      mrgi_irradiance_stencil_add(&layout, mr->GetFinestLevel(), flags->GetPointer(0), texels,
        position->GetPointer(0), normal->GetPointer(0), floats, viewToWorld, &uniforms, tau * (1.0f - 1e-4f),
        hi.data(), texels, nullptr, &err) == MRGI_OK);
    long long differ = 0, added = 0, irradianceAdded = 0, ambiguous = 0;
    for (size_t t = 0; t < texels; ++t)
    {
      const bool onGPU = gpuRendered->GetValue(static_cast<vtkIdType>(t)) != 0;
      differ += (onGPU && !hi[t]) || (!onGPU && lo[t]);
      ambiguous += lo[t] != hi[t];
      added += lo[t] && !selection->GetValue(static_cast<vtkIdType>(t));
      irradianceAdded += lo[t] && !rendered[t];
    }
    std::printf("incremental stencil: %lld texels rendered, %lld added below the geometric cut "
                "(visibility, level 0: %lld; irradiance: %lld), %lld differ from the C twin "
                "(%lld within 1e-4 of tau)\n",
      static_cast<long long>(stats.rendered_total), added, static_cast<long long>(stats.added[0]),
      irradianceAdded, differ, ambiguous);
    MRGI_TEST_CHECK(differ == 0);
    MRGI_TEST_CHECK(added > 0 && stats.added[0] > 0 && irradianceAdded > 0);
  }
  area->IncrementalStencilOff();
  window->Render();
  vtkSmartPointer<vtkImageData> geometric = AreaBuffer(pass, window);
  {
    MRGI_TEST_CHECK(!area->GetIncrementalStencilUsed());
    vtkDataArray* a = stenciled->GetPointData()->GetScalars();
    vtkDataArray* g = geometric->GetPointData()->GetScalars();
    vtkIdType changed = 0;
    for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i)
    {
      changed += std::abs(a->GetComponent(i, 0) - g->GetComponent(i, 0)) > 1e-6 ? 1 : 0;
    }
    std::printf("incremental stencil: %lld of %lld pixels change against the geometric selection\n",
      static_cast<long long>(changed), static_cast<long long>(a->GetNumberOfTuples()));
    MRGI_TEST_CHECK(changed > 0);
  }
  area->IncrementalStencilOn();
  mr->SetDepthThreshold(0.0);
  mr->SetNormalThreshold(0.0);
  mr->SetAreaLightDepthThreshold(0.0);
  mr->SetAreaLightNormalThreshold(0.0);
  mr->SetFinestLevel(0);
  pass->SetAreaLightVisibility(vtkMRGIPass::VisibilityOff);

  // 1d. Phong highlights (NPW10 3.2.1): with specular materials, the area
  // buffer gains k_s c_s S(P, N, V, n) per pixel (the C twin
  // mrgi_area_light_specular on the captured G-buffer), in its own pass.
  {
    vtkActorCollection* actors = renderer->GetActors();
    actors->InitTraversal();
    int shiny = 0;
    while (vtkActor* actor = actors->GetNextActor())
    {
      if (actor->GetProperty()->GetAmbient() == 0.0 && shiny++ % 2 == 0)
      {
        actor->GetProperty()->SetSpecular(0.6);
        actor->GetProperty()->SetSpecularColor(1.0, 0.9, 0.8);
        actor->GetProperty()->SetSpecularPower(shiny < 3 ? 40.0 : 5.0);
      }
    }
    pass->SetAreaLightSpecular(false);
    window->Render();
    vtkSmartPointer<vtkImageData> matte = AreaBuffer(pass, window);
    vtkNew<vtkImageData> noSpecular, noShininess;
    vtkNew<mrgitest::ErrorCatcher> notCaptured;
    const unsigned long tag = pass->AddObserver(vtkCommand::ErrorEvent, notCaptured);
    MRGI_TEST_CHECK(!pass->GetSpecularGBuffer(window, noSpecular, noShininess)); // not captured
    MRGI_TEST_CHECK(notCaptured->Caught("Specular"));
    pass->RemoveObserver(tag);
    pass->SetAreaLightSpecular(true);
    window->Render();
    vtkSmartPointer<vtkImageData> glossy = AreaBuffer(pass, window);
    vtkNew<vtkImageData> specular, shininess;
    MRGI_TEST_CHECK(pass->GetSpecularGBuffer(window, specular, shininess));
    const mrgi_area_light_texture_pyramid* corePyramid = nullptr;
    MRGI_TEST_CHECK(light->GetCorePyramid(&corePyramid));
    vtkDataArray* K = specular->GetPointData()->GetScalars();
    vtkDataArray* E = shininess->GetPointData()->GetScalars();
    vtkDataArray* G0 = matte->GetPointData()->GetScalars();
    vtkDataArray* G1 = glossy->GetPointData()->GetScalars();
    double snum = 0, sden = 0;
    int highlighted = 0;
    for (vtkIdType i = 0; i < P->GetNumberOfTuples(); ++i)
    {
      double expected[3] = { 0.0, 0.0, 0.0 };
      if (P->GetComponent(i, 3) > 0.5 && K->GetComponent(i, 0) + K->GetComponent(i, 1) + K->GetComponent(i, 2) > 0)
      {
        float p[3], n[3], v[3], lobe[3];
        ToWorld(m, P, N, i, p, n, v);
        mrgi_area_light_specular(&uniforms, samples, count, corePyramid, p, n, v,
          static_cast<float>(E->GetComponent(i, 0)), lobe, nullptr);
        for (int k = 0; k < 3; ++k)
        {
          expected[k] = K->GetComponent(i, k) * lobe[k];
        }
        highlighted += lobe[0] + lobe[1] + lobe[2] > 0.0f;
      }
      for (int k = 0; k < 3; ++k)
      {
        const double got = G1->GetComponent(i, k) - G0->GetComponent(i, k);
        snum += (got - expected[k]) * (got - expected[k]);
        sden += expected[k] * expected[k];
      }
    }
    const double specularError = std::sqrt(snum / (sden > 0 ? sden : 1.0));
    std::printf("specular: %d highlighted pixels, relative RMS of the added light against k_s c_s x C twin %.3g\n",
      highlighted, specularError);
    MRGI_TEST_CHECK(highlighted > 100 && sden > 0);
    MRGI_TEST_CHECK(specularError < 1e-3);
    actors->InitTraversal();
    while (vtkActor* actor = actors->GetNextActor())
    {
      actor->GetProperty()->SetSpecular(0.0);
    }
    // No specular material left: the specular pass and its G-buffer targets
    // do not run, and the image is the matte one.
    window->Render();
    const unsigned long again = pass->AddObserver(vtkCommand::ErrorEvent, notCaptured);
    MRGI_TEST_CHECK(!pass->GetSpecularGBuffer(window, noSpecular, noShininess));
    MRGI_TEST_CHECK(notCaptured->Caught("Specular"));
    pass->RemoveObserver(again);
    vtkSmartPointer<vtkImageData> matteAgain = AreaBuffer(pass, window);
    vtkDataArray* M = matteAgain->GetPointData()->GetScalars();
    for (vtkIdType i = 0; i < M->GetNumberOfValues(); ++i)
    {
      MRGI_TEST_CHECK(M->GetVariantValue(i).ToDouble() == G0->GetVariantValue(i).ToDouble());
    }
  }

  // 2. Multiresolution (Balanced): close to the full-resolution buffer.
  mr->SetPreset(vtkMRGIMultiresolution::PresetBalanced);
  window->Render();
  vtkSmartPointer<vtkImageData> balanced = AreaBuffer(pass, window);
  vtkDataArray* B = balanced->GetPointData()->GetScalars();
  num = den = 0;
  for (vtkIdType i = 0; i < B->GetNumberOfValues(); ++i)
  {
    const double d = B->GetVariantValue(i).ToDouble() - G->GetVariantValue(i).ToDouble();
    num += d * d;
    den += G->GetVariantValue(i).ToDouble() * G->GetVariantValue(i).ToDouble();
  }
  const double mrError = std::sqrt(num / den);
  std::printf("balanced preset: relative RMS against full resolution %.3g\n", mrError);
  MRGI_TEST_CHECK(mrError > 0.0 && mrError < 0.1);

  // 3. Caching: no rebuild while nothing changes; a new frame of the
  // picture rebuilds and changes the light.
  const int builds = light->GetNumberOfSampleBuilds();
  window->Render();
  MRGI_TEST_CHECK(light->GetNumberOfSampleBuilds() == builds);
  const double before = Sum(AreaBuffer(pass, window));
  paint(1);
  window->Render();
  const double after = Sum(AreaBuffer(pass, window));
  std::printf("sample builds %d -> %d; buffer sum %.4g -> %.4g after the picture changed\n", builds,
    light->GetNumberOfSampleBuilds(), before, after);
  MRGI_TEST_CHECK(light->GetNumberOfSampleBuilds() == builds + 1);
  MRGI_TEST_CHECK(std::fabs(after - before) > 1e-3 * before);

  // 4. Two lights add up.
  vtkNew<vtkMRGIAreaLight> second;
  second->SetCenter(b[0] + 0.05 * (b[1] - b[0]), 0.5 * (b[2] + b[3]), 0.5 * (b[4] + b[5]));
  second->SetEdgeU(0.0, 0.0, 0.3 * (b[5] - b[4])); // u x v = +x: faces into the box
  second->SetEdgeV(0.0, 0.3 * (b[3] - b[2]), 0.0);
  second->SetColor(0.2, 0.4, 1.0);
  second->SetNumberOfSamples(16);
  pass->RemoveAreaLight(light);
  pass->AddAreaLight(second);
  window->Render();
  const double secondSum = Sum(AreaBuffer(pass, window));
  pass->AddAreaLight(light);
  window->Render();
  const double both = Sum(AreaBuffer(pass, window));
  std::printf("first %.4g + second %.4g vs both %.4g\n", after, secondSum, both);
  MRGI_TEST_CHECK(secondSum > 0.0 && std::fabs(both - (after + secondSum)) <= 1e-4 * both);

  // 5. An invalid light (zero edge) draws nothing, says why, and the image
  // stays finite; removing all lights turns the area light off.
  vtkNew<mrgitest::ErrorCatcher> errors;
  vtkNew<vtkMRGIAreaLight> broken;
  broken->AddObserver(vtkCommand::ErrorEvent, errors);
  broken->SetEdgeU(0.0, 0.0, 0.0);
  pass->RemoveAllAreaLights();
  pass->AddAreaLight(broken);
  window->Render();
  std::printf("invalid light: %d error(s), last: %s\n", errors->Count, errors->Last.c_str());
  MRGI_TEST_CHECK(errors->Count > 0 && !pass->GetAreaLightsComputed());
  vtkNew<vtkImageData> color;
  MRGI_TEST_CHECK(pass->GetColorBuffer(window, color));
  Sum(color);
  pass->RemoveAllAreaLights();
  window->Render();
  MRGI_TEST_CHECK(!pass->GetAreaLightsComputed() && pass->GetNumberOfAreaLights() == 0);

  renderer->SetPass(nullptr);
  pass->ReleaseGraphicsResources(window);
  return 0;
}
