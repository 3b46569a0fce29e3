/**
 * @file mrgiGatherTestScene.h
 * @brief The scene the GPU gather parity tests share (TestMRGITreeGather,
 *        TestMRGIIndirectVisibility): the built-in Cornell box lit by its
 *        spot, rendered once through vtkMRGIPass, its G-buffer and RSM read
 *        back for the C twins, a frame context for driving vtkMRGIGather
 *        alone, and the relative-RMS comparison of GPU and twin irradiance.
 */
#ifndef mrgiGatherTestScene_h
#define mrgiGatherTestScene_h

#include "mrgiTestUtilities.h"
#include "vtkCamera.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMRGIFrameContext.h"
#include "vtkMRGIPass.h"
#include "vtkMRGIReflectiveShadowMapPass.h"
#include "vtkMRGISceneBuilder.h"
#include "vtkMath.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkPointData.h"
#include "vtkRenderStepsPass.h"
#include "vtkRenderer.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include "mrgi_gather.h"
#include "mrgi_multires.h"
#include "mrgi_vpl_tree.h"

#include <cmath>
#include <vector>

namespace mrgigather
{
inline float* Floats(vtkImageData* image)
{
  return vtkFloatArray::SafeDownCast(image->GetPointData()->GetScalars())->GetPointer(0);
}

inline bool ReadTexture(vtkTextureObject* t, std::vector<float>& rgba)
{
  rgba.assign(4 * static_cast<size_t>(t->GetWidth()) * t->GetHeight(), 0.0f);
  t->Activate();
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glGetTexImage(GL_TEXTURE_2D, 0, GL_RGBA, GL_FLOAT, rgba.data());
  t->Deactivate();
  return glGetError() == GL_NO_ERROR;
}

inline vtkSmartPointer<vtkTextureObject> Target(vtkOpenGLRenderWindow* window, int w, int h)
{
  vtkNew<vtkTextureObject> t;
  t->SetContext(window);
  t->SetInternalFormat(GL_RGBA32F);
  t->SetFormat(GL_RGBA);
  t->SetDataType(GL_FLOAT);
  MRGI_TEST_CHECK(t->Allocate2D(w, h, 4, VTK_FLOAT));
  return t.Get();
}

// Relative RMS of GPU E (RGBA, `gpu[4 * index(t)]`) against the twin's E
// (RGB) over the receivers `use` selects; also checks alpha 1 there.
struct Comparison
{
  double Num = 0.0, Den = 0.0;
  size_t Compared = 0, BadAlpha = 0;
  void Add(const float* g, const float* c)
  {
    for (int k = 0; k < 3; ++k)
    {
      MRGI_TEST_CHECK(std::isfinite(g[k]));
      Num += (double(g[k]) - c[k]) * (double(g[k]) - c[k]);
      Den += double(c[k]) * c[k];
    }
    BadAlpha += g[3] != 1.0f;
    ++Compared;
  }
  double Error() const { return Den > 0 ? std::sqrt(Num / Den) : std::sqrt(Num); }
};

struct Scene
{
  vtkSmartPointer<vtkRenderWindow> Window;
  vtkOpenGLRenderWindow* GL = nullptr;
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkRenderStepsPass> Steps;
  vtkNew<vtkMRGIPass> Pass;
  vtkNew<vtkImageData> Position, Normal, Albedo;
  vtkMRGIFrameContext Frame;
  float WorldToView[16];
  mrgi_vpl_tree Tree{};
  int W = 0, H = 0;

  // `point`: the spot becomes a point light (cone 90 degrees): six cube views.
  Scene(int width, int height, int rsmSize, bool point = false)
  {
    this->Window = mrgitest::HeadlessWindow(width, height);
    this->GL = vtkOpenGLRenderWindow::SafeDownCast(this->Window);
    this->Window->AddRenderer(this->Renderer);
    vtkNew<vtkMRGISceneBuilder> builder;
    builder->SetScene("cornell-spot");
    MRGI_TEST_CHECK(builder->Build(this->Renderer));
    if (point)
    {
      vtkLightCollection* lights = this->Renderer->GetLights();
      lights->InitTraversal();
      while (vtkLight* light = lights->GetNextItem())
      {
        light->SetConeAngle(90.0);
      }
    }
    this->Pass->SetDelegatePass(this->Steps);
    this->Pass->SetIndirectMode(vtkMRGIPass::IndirectFull);
    this->Pass->SetNumberOfVPLs(256);
    this->Pass->SetRSMResolution(rsmSize);
    this->Renderer->SetPass(this->Pass);
    this->Window->Render();
    MRGI_TEST_CHECK(this->Pass->GetIndirectComputed());
    MRGI_TEST_CHECK(
      this->Pass->GetGBuffer(this->Window, this->Position, this->Normal, this->Albedo));
    const int* vp = this->Pass->GetViewport();
    this->W = vp[2];
    this->H = vp[3];
    const double* v2w = this->Pass->GetLastViewToWorld();
    Frame.Window = this->GL;
    Frame.Renderer = this->Renderer;
    Frame.Position = this->Pass->GetPositionTexture();
    Frame.Normal = this->Pass->GetNormalTexture();
    Frame.Albedo = this->Pass->GetAlbedoTexture();
    std::copy(vp, vp + 4, Frame.Viewport);
    for (int k = 0; k < 16; ++k)
    {
      Frame.ViewToWorld[k] = static_cast<float>(v2w[k]);
      Frame.ViewToWorldDouble[k] = v2w[k];
    }
    mrgitest::WorldToViewColumnMajor(v2w, this->WorldToView);
    this->BuildTree();
  }

  ~Scene()
  {
    mrgi_vpl_tree_destroy(&this->Tree);
    this->Renderer->SetPass(nullptr);
    this->Pass->ReleaseGraphicsResources(this->Window);
  }

  // The tree of the read-back RSM (one spot view), the camera rebuilt from
  // the RSM pass's matrices (as TestMRGIClusters). With `lightEverything`,
  // every valid texel gets flux = its area (radiosity 1), so that no node is
  // skipped for zero flux and a receiver that culls no node above level 0
  // visits every node of every root (the loop budget of a batch, in full).
  void BuildTree(bool lightEverything = false)
  {
    mrgi_vpl_tree_destroy(&this->Tree);
    vtkMRGIReflectiveShadowMapPass* rsm = this->Pass->GetReflectiveShadowMapPass();
    const int views = rsm->GetNumberOfViews();
    const size_t S = static_cast<size_t>(rsm->GetResolution());
    MRGI_TEST_CHECK(views >= 1 && views <= MRGI_RSM_MAX_VIEWS);
    // The views one after another, as mrgi_rsm holds them.
    std::vector<float> position(4 * S * S * views), normal(position.size()), flux(position.size());
    std::vector<mrgi_rsm_view_camera> cameras(static_cast<size_t>(views));
    for (int v = 0; v < views; ++v)
    {
      vtkNew<vtkImageData> p, n, f;
      MRGI_TEST_CHECK(rsm->ReadView(this->Window, v, p, n, f));
      const size_t first = 4 * S * S * static_cast<size_t>(v);
      std::copy(Floats(p), Floats(p) + 4 * S * S, position.begin() + first);
      std::copy(Floats(n), Floats(n) + 4 * S * S, normal.begin() + first);
      std::copy(Floats(f), Floats(f) + 4 * S * S, flux.begin() + first);
      double worldToView[16], projection[16];
      MRGI_TEST_CHECK(rsm->GetViewWorldToView(v, worldToView));
      MRGI_TEST_CHECK(rsm->GetViewProjection(v, projection));
      MRGI_TEST_CHECK(rsm->GetViewPerspective(v));
      mrgi_rsm_view_camera& camera = cameras[static_cast<size_t>(v)];
      for (int i = 0; i < 16; ++i)
      {
        camera.world_to_view[i] = static_cast<float>(worldToView[(i % 4) * 4 + i / 4]); // transpose
      }
      camera.projection.parallel = 0;
      camera.projection.view_angle_deg =
        2.0 * std::atan(1.0 / projection[5]) * 180.0 / vtkMath::Pi();
      camera.projection.parallel_scale = 1.0;
    }
    if (lightEverything)
    {
      for (size_t t = 0; 4 * t < position.size(); ++t)
      {
        if (position[4 * t + 3] > MRGI_VALID_THRESHOLD)
        {
          flux[4 * t] = flux[4 * t + 1] = flux[4 * t + 2] = flux[4 * t + 3];
        }
      }
    }
    const mrgi_rsm map = { static_cast<int32_t>(S), views, position.data(), normal.data(),
      flux.data() };
    mrgi_error err;
    if (mrgi_vpl_tree_build(&map, cameras.data(), &this->Tree, &err) != MRGI_OK)
    {
      MRGI_TEST_FAIL("mrgi_vpl_tree_build: %s", err.message);
    }
  }

};
} // namespace mrgigather

#endif
