// The GPU's multiresolution selection (vtkMRGIMultiresolution)
// against its C twins (mrgi_multires.h) on real G-buffers: the flags and the
// stencil must select exactly the same texels, for several scenes, NPOT
// windows, perspective and parallel cameras, thresholds 0 / default / off,
// finest levels 0 and 1, with and without the balance rule, and renderers
// whose viewport does not start at the window's origin (ParaView's tiles and
// split views: every stage reads the G-buffer at the viewport's offset).
#include "mrgiTestUtilities.h"

#include "vtkCamera.h"
#include "vtkMRGIFrameContext.h"
#include "vtkMRGIGather.h"
#include "vtkMRGIMultiresolution.h"
#include "vtkMRGIUpsample.h"
#include "vtkMRGIPass.h"
#include "vtkMRGISceneBuilder.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkRenderStepsPass.h"
#include "vtkRenderer.h"

#include "mrgi_area_light.h"
#include "mrgi_gather.h"
#include "mrgi_multires.h"
#include "mrgi_multires_receivers.h"
#include "mrgi_upsample.h"
#include "vtkFloatArray.h"
#include "vtkMRGIVPLSelection.h"
#include "vtkTextureObject.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace
{
struct Case
{
  const char* Scene;
  int Width, Height;
  bool Parallel;
  double DepthThreshold, NormalThreshold;
  int Finest;
  bool Balance;
  double ViewportX = 0.0, ViewportY = 0.0; ///< the renderer's viewport origin (normalized)
};

int RunCase(const Case& c)
{
  vtkSmartPointer<vtkRenderWindow> window = mrgitest::HeadlessWindow(c.Width, c.Height);
  vtkNew<vtkRenderer> renderer;
  window->AddRenderer(renderer);
  renderer->SetViewport(c.ViewportX, c.ViewportY, 1.0, 1.0);
  vtkNew<vtkMRGISceneBuilder> builder;
  builder->SetScene(c.Scene);
  builder->SetTriangleCount(20000);
  builder->SetObjectCount(16);
  MRGI_TEST_CHECK(builder->Build(renderer));
  vtkCamera* camera = renderer->GetActiveCamera();
  if (c.Parallel)
  {
    camera->ParallelProjectionOn();
    renderer->ResetCamera();
  }
  vtkNew<vtkRenderStepsPass> steps;
  vtkNew<vtkMRGIPass> pass;
  pass->SetDelegatePass(steps);
  pass->SetNumberOfVPLs(16);
  renderer->SetPass(pass);
  window->Render();

  // The C twin on the read-back G-buffer.
  vtkNew<vtkImageData> position, normal, albedo;
  MRGI_TEST_CHECK(pass->GetGBuffer(window, position, normal, albedo));
  const int* vp = pass->GetViewport();
  const int W = vp[2], H = vp[3];
  MRGI_TEST_CHECK((c.ViewportX > 0.0) == (vp[0] > 0) && (c.ViewportY > 0.0) == (vp[1] > 0));
  mrgi_gather_receivers gbuffer = { W, H,
    static_cast<float*>(position->GetScalarPointer()), static_cast<float*>(normal->GetScalarPointer()) };
  mrgi_multires_projection projection = { c.Parallel ? 1 : 0, camera->GetViewAngle(),
    camera->GetParallelScale() };
  float ab[2];
  mrgi_error err;
  MRGI_TEST_CHECK(mrgi_multires_pixel_size_coefficients(&projection, H, ab, &err) == MRGI_OK);
  mrgi_multires_layout layout;
  MRGI_TEST_CHECK(mrgi_multires_layout_init(&layout, W, H, 16, &err) == MRGI_OK);
  mrgi_multires_mipmap mipmap;
  MRGI_TEST_CHECK(mrgi_multires_mipmap_build(&layout, &gbuffer, ab, &mipmap, &err) == MRGI_OK);
  mrgi_multires_params params;
  mrgi_multires_params_default(&params);
  params.depth_threshold = c.DepthThreshold;
  params.normal_threshold = c.NormalThreshold;
  params.finest_level = std::min(c.Finest, layout.level_count - 1);
  params.balance = c.Balance ? 1 : 0;
  const size_t texels = static_cast<size_t>(mrgi_multires_texel_count(&layout));
  std::vector<uint8_t> flags(texels), mask(texels);
  MRGI_TEST_CHECK(mrgi_multires_flags_compute(&mipmap, &params, flags.data(), texels, &err) == MRGI_OK);
  MRGI_TEST_CHECK(mrgi_multires_select_one_pass(&layout, flags.data(), texels,
                    params.finest_level, mask.data(), texels, &err) == MRGI_OK);
  mrgi_multires_mipmap_destroy(&mipmap);

  // The GPU.
  vtkNew<vtkMRGIMultiresolution> gpu;
  gpu->SetDepthThreshold(std::isinf(c.DepthThreshold) ? -1.0 : c.DepthThreshold);
  gpu->SetNormalThreshold(std::isinf(c.NormalThreshold) ? -1.0 : c.NormalThreshold);
  gpu->SetFinestLevel(c.Finest);
  gpu->SetBalance(c.Balance);
  vtkOpenGLRenderWindow* glWindow = vtkOpenGLRenderWindow::SafeDownCast(window);
  MRGI_TEST_CHECK(gpu->Update(glWindow, pass->GetPositionTexture(), pass->GetNormalTexture(), vp[0],
    vp[1], W, H, ab[0], ab[1]));
  MRGI_TEST_CHECK(gpu->GetFlattenedWidth() == layout.total_width);
  MRGI_TEST_CHECK(gpu->GetNumberOfLevels() == layout.level_count);
  vtkNew<vtkUnsignedCharArray> gpuFlags, gpuColorMask, gpuStencil;
  MRGI_TEST_CHECK(gpu->ReadFlags(window, gpuFlags));
  MRGI_TEST_CHECK(gpu->ReadSelection(window, gpuColorMask, false));
  MRGI_TEST_CHECK(gpu->ReadSelection(window, gpuStencil, true));
  size_t flagDiff = 0, maskDiff = 0, stencilDiff = 0, selected = 0;
  for (size_t t = 0; t < texels; ++t)
  {
    flagDiff += gpuFlags->GetValue(static_cast<vtkIdType>(t)) != flags[t];
    maskDiff += gpuColorMask->GetValue(static_cast<vtkIdType>(t)) != mask[t];
    stencilDiff += gpuStencil->GetValue(static_cast<vtkIdType>(t)) != mask[t];
    selected += mask[t];
  }
  std::printf("%s %dx%d at (%d, %d) %s Td=%g Tn=%g f=%d balance=%d: %d levels, %zu selected texels; "
              "differences: flags %zu, mask %zu, stencil %zu\n",
    c.Scene, W, H, vp[0], vp[1], c.Parallel ? "parallel" : "perspective", c.DepthThreshold,
    c.NormalThreshold, c.Finest, c.Balance ? 1 : 0, layout.level_count, selected, flagDiff,
    maskDiff, stencilDiff);
  MRGI_TEST_CHECK(selected > 0);
  MRGI_TEST_CHECK(flagDiff == 0 && maskDiff == 0 && stencilDiff == 0);

  // Receivers and the stenciled gather against mrgi_multires_receivers_build
  // and mrgi_gather_full on the same receivers.
  const double* v2w = pass->GetLastViewToWorld();
  float viewToWorld[16];
  for (int k = 0; k < 16; ++k)
  {
    viewToWorld[k] = static_cast<float>(v2w[k]);
  }
  vtkTextureObject* vpls = pass->GetVPLSelection()->GetVPLTexture();
  const int vplCount = pass->GetVPLSelection()->GetVPLCount();
  MRGI_TEST_CHECK(vpls && vplCount > 0);
  // The stages take the frame's context and the buffer as arguments.
  vtkMRGIFrameContext frame;
  frame.Window = glWindow;
  frame.Position = pass->GetPositionTexture();
  frame.Normal = pass->GetNormalTexture();
  frame.Viewport[0] = vp[0];
  frame.Viewport[1] = vp[1];
  frame.Viewport[2] = W;
  frame.Viewport[3] = H;
  std::copy(viewToWorld, viewToWorld + 16, frame.ViewToWorld);
  vtkNew<vtkMRGIGather> gather;
  vtkNew<vtkMRGIUpsample> upsample;
  MRGI_TEST_CHECK(gpu->BuildReceivers(glWindow, frame.Position, frame.Normal, vp[0], vp[1]));
  MRGI_TEST_CHECK(gather->GatherVPLs(frame, gpu, vpls, vplCount));
  std::vector<float> receiverP(4 * texels), receiverN(4 * texels);
  MRGI_TEST_CHECK(mrgi_multires_receivers_build(&layout, &gbuffer, receiverP.data(),
                    receiverN.data(), 4 * texels, &err) == MRGI_OK);
  vtkNew<vtkFloatArray> gpuP, gpuN, gpuE, vplArray;
  MRGI_TEST_CHECK(gpu->ReadReceivers(window, gpuP, gpuN));
  MRGI_TEST_CHECK(gather->ReadIrradiance(window, gpuE));
  double receiverError = 0, receiverScale = 0;
  for (size_t i = 0; i < 4 * texels; ++i)
  {
    receiverError = std::fmax(receiverError, std::fabs(gpuP->GetValue(i) - receiverP[i]));
    receiverError = std::fmax(receiverError, std::fabs(gpuN->GetValue(i) - receiverN[i]));
    receiverScale = std::fmax(receiverScale, std::fabs(receiverP[i]));
  }
  MRGI_TEST_CHECK(pass->GetVPLs(window, vplArray));
  float w2r[16];
  mrgitest::WorldToViewColumnMajor(v2w, w2r);
  mrgi_gather_receivers flat = { layout.total_width, layout.total_height, receiverP.data(), receiverN.data() };
  mrgi_image cE{};
  MRGI_TEST_CHECK(mrgi_gather_full(&flat, reinterpret_cast<const mrgi_vpl*>(vplArray->GetPointer(0)),
                    vplCount, w2r, &cE, nullptr, &err) == MRGI_OK);
  double num = 0, den = 0;
  size_t leaks = 0;
  for (size_t t = 0; t < texels; ++t)
  {
    for (int k = 0; k < 3; ++k)
    {
      const double g = gpuE->GetValue(4 * t + k);
      if (!mask[t])
      {
        leaks += g != 0.0;
        continue;
      }
      const double e = cE.pixels[3 * t + k];
      num += (g - e) * (g - e);
      den += e * e;
    }
  }
  mrgi_image_destroy(&cE);
  const double gatherError = den > 0 ? std::sqrt(num / den) : std::sqrt(num);
  std::printf("  receivers: max difference %.3g (positions up to %.3g); gather at selected texels: "
              "relative RMS %.3g; unselected texels written: %zu\n",
    receiverError, receiverScale, gatherError, leaks);
  MRGI_TEST_CHECK(receiverError <= 1e-5 * std::fmax(1.0, receiverScale));
  MRGI_TEST_CHECK(gatherError < 1e-4);
  MRGI_TEST_CHECK(leaks == 0);

  // Upsampling, both modes, on the GPU's own gathered values.
  for (int mode : { vtkMRGIUpsample::UpsampleTent, vtkMRGIUpsample::UpsampleMaskWeighted })
  {
    const double weight = 100.0;
    MRGI_TEST_CHECK(upsample->Upsample(
      frame, gpu, gather->GetIrradianceTexture(), gpu->GetSelectionTexture(), mode, weight));
    vtkNew<vtkFloatArray> gpuU;
    MRGI_TEST_CHECK(upsample->ReadUpsampled(window, gpuU));
    MRGI_TEST_CHECK(gpuU->GetNumberOfTuples() == static_cast<vtkIdType>(W) * H);
    mrgi_upsample_params up;
    mrgi_upsample_params_default(&up);
    up.mode = mode == vtkMRGIUpsample::UpsampleTent ? MRGI_UPSAMPLE_TENT : MRGI_UPSAMPLE_MASK_WEIGHTED;
    up.mask_weight = static_cast<float>(weight);
    mrgi_image cU{};
    MRGI_TEST_CHECK(mrgi_upsample(&layout, flags.data(), texels, mask.data(), texels,
                      gpuE->GetPointer(0), 4 * texels, 4, &up, &cU, &err) == MRGI_OK);
    double unum = 0, uden = 0;
    for (int y = 0; y < H; ++y)
    {
      for (int x = 0; x < W; ++x)
      {
        if (!(flags[mrgi_multires_index(&layout, 0, x, y)] & MRGI_MULTIRES_FLAG_NONEMPTY))
        {
          continue;
        }
        for (int k = 0; k < 3; ++k)
        {
          const double g = gpuU->GetValue(4 * (static_cast<vtkIdType>(y) * W + x) + k);
          const double e = mrgi_image_at(&cU, x, y)[k];
          unum += (g - e) * (g - e);
          uden += e * e;
        }
      }
    }
    mrgi_image_destroy(&cU);
    const double upError = uden > 0 ? std::sqrt(unum / uden) : std::sqrt(unum);
    std::printf("  upsampling (%s): relative RMS %.3g\n", mode ? "mask-weighted" : "tent", upError);
    MRGI_TEST_CHECK(uden > 0 && upError < 1e-4);
  }
  // The area-light gather (nichols-penmatsa-wyman-2010 3.2, no visibility)
  // on the same receivers and selection against mrgi_area_light_diffuse():
  // a textured, one-sided light under the top of the scene's bounds, facing
  // down, and the same light two-sided.
  double bounds[6];
  renderer->ComputeVisiblePropBounds(bounds);
  const double ext[3] = { bounds[1] - bounds[0], bounds[3] - bounds[2], bounds[5] - bounds[4] };
  mrgi_image lightTexture{};
  MRGI_TEST_CHECK(mrgi_image_create(&lightTexture, 4, 3, 3, &err) == MRGI_OK);
  for (int y = 0; y < 3; ++y)
  {
    for (int x = 0; x < 4; ++x)
    {
      float* t = lightTexture.pixels + 3 * (y * 4 + x);
      t[0] = 0.25f * static_cast<float>(x + 1);
      t[1] = 0.3f * static_cast<float>(y + 1);
      t[2] = (x + y) % 2 ? 1.0f : 0.1f;
    }
  }
  for (const int twoSided : { 0, 1 })
  {
    mrgi_area_light light{};
    light.center[0] = bounds[0] + 0.45 * ext[0];
    light.center[1] = bounds[2] + 0.97 * ext[1];
    light.center[2] = bounds[4] + 0.55 * ext[2];
    light.edge_u[0] = 0.3 * ext[0];
    light.edge_v[2] = 0.25 * std::fmax(ext[2], 1e-3 * ext[0]);
    light.color[0] = light.color[1] = light.color[2] = 1.0;
    light.intensity = 3.0;
    light.texture = &lightTexture;
    light.two_sided = twoSided;
    MRGI_TEST_CHECK(mrgi_area_light_check(&light, &err) == MRGI_OK);
    mrgi_area_light_texture_pyramid pyramid{};
    MRGI_TEST_CHECK(mrgi_area_light_texture_pyramid_create(&pyramid, &lightTexture, &err) == MRGI_OK);
    std::vector<mrgi_area_light_sample> samples(64);
    int32_t sampleCount = 0;
    MRGI_TEST_CHECK(mrgi_area_light_make_samples(&light, &pyramid, 64, 1, 7u, samples.data(), 64,
                      &sampleCount, &err) == MRGI_OK);
    mrgi_area_light_uniforms uniforms;
    MRGI_TEST_CHECK(mrgi_area_light_uniforms_init(&light, &pyramid, &uniforms, &err) == MRGI_OK);
    mrgi_area_light_texture_pyramid_destroy(&pyramid);
    vtkNew<vtkTextureObject> sampleTexture;
    sampleTexture->SetContext(glWindow);
    MRGI_TEST_CHECK(sampleTexture->Create2DFromRaw(MRGI_AREA_LIGHT_SAMPLE_TEXELS,
      static_cast<unsigned int>(sampleCount), 4, VTK_FLOAT,
      const_cast<float*>(mrgi_area_light_sample_texture_data(samples.data()))));
    vtkMRGIAreaLightTerm term;
    term.Samples = sampleTexture;
    term.SampleCount = sampleCount;
    term.Light = &uniforms;
    MRGI_TEST_CHECK(gather->GatherAreaLight(frame, gpu, term, gpu->GetStencilTexture()));
    vtkNew<vtkFloatArray> gpuX;
    MRGI_TEST_CHECK(gather->ReadIrradiance(window, gpuX));
    double xnum = 0, xden = 0;
    size_t xleaks = 0, lit = 0;
    for (size_t t = 0; t < texels; ++t)
    {
      if (!mask[t])
      {
        for (int k = 0; k < 3; ++k)
        {
          xleaks += gpuX->GetValue(4 * t + k) != 0.0;
        }
        continue;
      }
      // The shader's transform: P = M p, N = normalize(mat3(M) n), in float.
      float P[3], N[3];
      for (int r = 0; r < 3; ++r)
      {
        P[r] = viewToWorld[12 + r];
        N[r] = 0.0f;
        for (int k = 0; k < 3; ++k)
        {
          P[r] += viewToWorld[4 * k + r] * receiverP[4 * t + k];
          N[r] += viewToWorld[4 * k + r] * receiverN[4 * t + k];
        }
      }
      float X[3] = { 0.0f, 0.0f, 0.0f };
      if (receiverP[4 * t + 3] > 0.0f)
      {
        mrgi_area_light_diffuse(&uniforms, samples.data(), sampleCount, P, N, X);
      }
      lit += X[0] + X[1] + X[2] > 0.0f;
      for (int k = 0; k < 3; ++k)
      {
        const double g = gpuX->GetValue(4 * t + k);
        MRGI_TEST_CHECK(std::isfinite(g));
        xnum += (g - X[k]) * (g - X[k]);
        xden += double(X[k]) * X[k];
      }
    }
    const double areaError = xden > 0 ? std::sqrt(xnum / xden) : std::sqrt(xnum);
    std::printf("  area light (%s, %d samples): %zu lit texels, relative RMS %.3g against the C twin; "
                "unselected texels written: %zu\n",
      twoSided ? "two-sided" : "one-sided", sampleCount, lit, areaError, xleaks);
    MRGI_TEST_CHECK(areaError < 1e-4 && xleaks == 0);
    MRGI_TEST_CHECK(W * H < 16 || lit > 0);
    sampleTexture->ReleaseGraphicsResources(window);
  }
  mrgi_image_destroy(&lightTexture);

  gather->ReleaseGraphicsResources(window);
  upsample->ReleaseGraphicsResources(window);
  gpu->ReleaseGraphicsResources(window);
  renderer->SetPass(nullptr);
  pass->ReleaseGraphicsResources(window);
  return 0;
}
}

int main()
{
  const double off = INFINITY;
  const Case cases[] = {
    { "cornell-spot", 97, 61, false, 4.0, 0.25, 0, true },
    { "cornell", 128, 128, false, 4.0, 0.25, 0, false },
    { "scaling", 131, 89, false, 4.0, 0.25, 1, true },
    { "scaling", 80, 120, true, 2.0, 0.1, 0, true },
    { "cornell-spot", 64, 48, false, 0.0, 0.0, 0, true },  // every texel refines: full resolution
    { "cornell-spot", 64, 48, false, off, off, 0, true },  // nothing refines: coarsest level
    { "cornell-spot", 33, 17, true, 4.0, 0.25, 0, true },
    { "cornell-spot", 1, 1, false, 4.0, 0.25, 0, true },
    // Viewports away from the window's origin (level 0 reads the G-buffer
    // normal at the offset: mrgiLevel0Normal).
    { "cornell-spot", 120, 90, false, 4.0, 0.25, 0, true, 0.3, 0.2 },
    { "scaling", 97, 71, true, 2.0, 0.1, 1, false, 0.5, 0.0 },
  };
  for (const Case& c : cases)
  {
    RunCase(c);
  }
  return 0;
}
