// Voxel visibility in the GPU VPL gathers (issue 13 part 4): vtkMRGIGather's
// full, stenciled and tree gathers with vtkMRGIIndirectVisibility::VoxelVisibility
// (one march per receiver and VPL through the screen-space voxels,
// nichols-penmatsa-wyman-2010 3.3.1, vtkMRGIVoxelMarch.glsl) against their C
// twins mrgi_gather_full_visibility() and mrgi_vpl_tree_gather_visibility()
// on the read-back G-buffer and voxels. Scene: the built-in Cornell box lit
// by its spot (RSM 64: 256 tree roots, which are also the VPL cache here);
// its two blocks shadow the VPLs. Default voxels and march (128 x 128, 256
// steps): 28 VPLs per draw, 1 tree root per draw (three levels: 21 nodes
// each), so every gather runs in several additive draws. Without them
// (all 256 VPLs in one draw) llvmpipe's loop budget drops marches: the full
// gather's relative RMS was 0.021, 606 receivers differing (measured).
// 1. Full cache gather, full tree gather (tau 0.05), stenciled cache and
//    stenciled tree gathers: relative RMS against the twin below Bound. The
//    march is binary: a ray whose step middle or clip parameter lies within
//    float rounding of a voxel boundary may answer differently (the VPL's
//    eye-space position is float on the GPU, double rounded to float in the
//    twin); the count of receivers that differ by more than 1e-4 of the
//    mean E is printed (0 here).
// 2. The shadows darken every gather (< 0.98 of the unshadowed sum).
// 3. Errors: no voxelization, one never run, a tree whose root subtree needs
//    more marches than one draw allows.
#include "mrgiPassSceneFixture.h"
#include "mrgiVoxelTestUtilities.h"

#include "vtkCamera.h"
#include "vtkCommand.h"
#include "vtkMRGIFrameContext.h"
#include "vtkMRGIGather.h"
#include "vtkMRGIIndirectVisibility.h"
#include "vtkMRGIMultiresolution.h"
#include "vtkMRGIVoxelization.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkTextureObject.h"
#include "vtkUnsignedCharArray.h"
#include "vtk_glew.h"

#include "mrgi_gather.h"
#include "mrgi_multires.h"
#include "mrgi_voxel_march.h"
#include "mrgi_vpl_tree.h"
#include "mrgi_vpl_tree_gather.h"

#include <cmath>
#include <cstdio>
#include <vector>

namespace
{
// Relative RMS bound of the GPU against the C twin: the gather parity
// tolerance (TestMRGITreeGather). Measured 1.0e-7..2.2e-7 with no receiver
// differing: no march answered differently here. A binary march that did
// would move one VPL term of one receiver, about 1/256 of its E.
constexpr double Bound = 1e-4;
constexpr int VPLs = 256;

float* Floats(vtkImageData* image)
{
  return vtkFloatArray::SafeDownCast(image->GetPointData()->GetScalars())->GetPointer(0);
}

vtkSmartPointer<vtkTextureObject> Texture(vtkOpenGLRenderWindow* window, int w, int h,
  const void* data = nullptr)
{
  vtkNew<vtkTextureObject> t;
  t->SetContext(window);
  t->SetInternalFormat(GL_RGBA32F);
  t->SetFormat(GL_RGBA);
  t->SetDataType(GL_FLOAT);
  MRGI_TEST_CHECK(data ? t->Create2DFromRaw(w, h, 4, VTK_FLOAT, const_cast<void*>(data))
                       : t->Allocate2D(w, h, 4, VTK_FLOAT));
  return t.Get();
}

std::vector<float> Read(vtkTextureObject* t)
{
  std::vector<float> rgba(4 * static_cast<size_t>(t->GetWidth()) * t->GetHeight(), 0.0f);
  t->Activate();
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glGetTexImage(GL_TEXTURE_2D, 0, GL_RGBA, GL_FLOAT, rgba.data());
  t->Deactivate();
  MRGI_TEST_CHECK(glGetError() == GL_NO_ERROR);
  return rgba;
}

// GPU E (RGBA) against the twin's (RGB): relative RMS, receivers that differ
// by more than 1e-4 of the mean, GPU and twin sums.
struct Comparison
{
  double Num = 0.0, Den = 0.0, Gpu = 0.0, Twin = 0.0;
  size_t Compared = 0, BadAlpha = 0, Differ = 0;
  std::vector<double> Diffs;
  void Add(const float* g, const float* c)
  {
    double d2 = 0.0;
    for (int k = 0; k < 3; ++k)
    {
      MRGI_TEST_CHECK(std::isfinite(g[k]));
      d2 += (double(g[k]) - c[k]) * (double(g[k]) - c[k]);
      Den += double(c[k]) * c[k];
      Gpu += g[k];
      Twin += c[k];
    }
    Num += d2;
    Diffs.push_back(std::sqrt(d2));
    BadAlpha += g[3] != 1.0f;
    ++Compared;
  }
  bool Report(const char* what)
  {
    const double mean = Compared ? Twin / (3.0 * Compared) : 0.0;
    for (double d : Diffs)
    {
      Differ += d > 1e-4 * mean;
    }
    const double rms = Den > 0 ? std::sqrt(Num / Den) : std::sqrt(Num);
    std::printf("%-34s %5zu receivers, relative RMS %.3g, %zu differ, GPU/twin sum %.6f\n", what,
      Compared, rms, Differ, Twin > 0 ? Gpu / Twin : 0.0);
    return Compared > 0 && BadAlpha == 0 && rms < Bound;
  }
};

struct Fixture
{
  mrgitest::PassScene Scene{ 72, 56, "cornell-spot" };
  vtkOpenGLRenderWindow* GL = nullptr;
  vtkNew<vtkImageData> Position, Normal, Albedo;
  vtkMRGIFrameContext Frame;
  float WorldToView[16];
  mrgi_vpl_tree Tree{};
  int W = 0, H = 0;
  vtkNew<vtkMRGIVoxelization> Voxelization;
  vtkNew<vtkTypeUInt32Array> Words;
  mrgi_voxel_view View{};

  Fixture()
  {
    vtkMRGIPass* pass = this->Scene.Pass;
    pass->SetIndirectMode(vtkMRGIPass::IndirectFull);
    pass->SetNumberOfVPLs(VPLs);
    pass->SetRSMResolution(64);
    this->Scene.Window->Render();
    this->GL = vtkOpenGLRenderWindow::SafeDownCast(this->Scene.Window);
    MRGI_TEST_CHECK(pass->GetIndirectComputed());
    MRGI_TEST_CHECK(pass->GetGBuffer(this->GL, this->Position, this->Normal, this->Albedo));
    const int* vp = pass->GetViewport();
    this->W = vp[2];
    this->H = vp[3];
    const double* v2w = pass->GetLastViewToWorld();
    this->Frame.Window = this->GL;
    this->Frame.Renderer = this->Scene.Renderer;
    this->Frame.Position = pass->GetPositionTexture();
    this->Frame.Normal = pass->GetNormalTexture();
    this->Frame.Albedo = pass->GetAlbedoTexture();
    std::copy(vp, vp + 4, this->Frame.Viewport);
    for (int k = 0; k < 16; ++k)
    {
      this->Frame.ViewToWorld[k] = static_cast<float>(v2w[k]);
      this->Frame.ViewToWorldDouble[k] = v2w[k];
    }
    mrgitest::WorldToViewColumnMajor(v2w, this->WorldToView);
    mrgitest::SpotRSMView rsm(pass, this->GL);
    mrgi_error err;
    if (mrgi_vpl_tree_build(&rsm.Map, &rsm.Camera, &this->Tree, &err) != MRGI_OK)
    {
      MRGI_TEST_FAIL("mrgi_vpl_tree_build: %s", err.message);
    }
    MRGI_TEST_CHECK(mrgi_vpl_tree_root_count(&this->Tree) == VPLs);
    // The voxels of the same camera, over the scene's depth range.
    double range[2];
    mrgitest::DepthRange(mrgitest::SceneTriangles(this->Scene.Renderer), range);
    this->Voxelization->SetVoxelSide(MRGI_VOXEL_DEFAULT_SIZE);
    this->Voxelization->SetMaxSteps(MRGI_VOXEL_DEFAULT_MAX_STEPS);
    MRGI_TEST_CHECK(this->Voxelization->Voxelize(this->Scene.Renderer, range[0], range[1]));
    double worldToView[16];
    this->View = mrgitest::ReadVoxelView(this->Voxelization, this->GL, this->Words, worldToView);
    for (int k = 0; k < 16; ++k)
    {
      MRGI_TEST_CHECK(
        std::abs(worldToView[k] - this->WorldToView[k]) <= 1e-5 * (1.0 + std::abs(worldToView[k])));
    }
  }

  ~Fixture()
  {
    mrgi_vpl_tree_destroy(&this->Tree);
    this->Scene.Renderer->SetPass(nullptr);
    this->Scene.Pass->ReleaseGraphicsResources(this->Scene.Window);
    this->Voxelization->ReleaseGraphicsResources(this->Scene.Window);
  }

  mrgi_gather_visibility Twin(bool voxels) const
  {
    mrgi_gather_visibility c{};
    c.mode = voxels ? MRGI_GATHER_VISIBILITY_VOXELS : MRGI_GATHER_VISIBILITY_NONE;
    c.voxels = &this->View;
    return c;
  }

  // The twin on `receivers` (eye space): cache gather (tree null) or tree.
  void RunTwin(const mrgi_gather_receivers& receivers, const vtkMRGIVPLTreeTerm* tree,
    bool voxels, mrgi_image& out) const
  {
    const mrgi_gather_visibility cv = this->Twin(voxels);
    mrgi_error err;
    const mrgi_status status = tree
      ? mrgi_vpl_tree_gather_visibility(&receivers, &this->Tree, tree->Threshold,
          this->WorldToView, &cv, &out, nullptr, nullptr, &err)
      : mrgi_gather_full_visibility(
          &receivers, this->Tree.nodes, VPLs, this->WorldToView, &cv, &out, nullptr, &err);
    if (status != MRGI_OK)
    {
      MRGI_TEST_FAIL("C twin: %s", err.message);
    }
  }
};

vtkMRGIIndirectVisibility Voxels(vtkMRGIVoxelization* voxelization)
{
  vtkMRGIIndirectVisibility v;
  v.Mode = vtkMRGIIndirectVisibility::VoxelVisibility;
  v.Voxels = voxelization;
  return v;
}

// The full gathers at every valid pixel; returns the twin's sum of E.
double Full(Fixture& f, vtkMRGIGather* gather, vtkTextureObject* cache,
  const vtkMRGIVPLTreeTerm* tree, const vtkMRGIIndirectVisibility& v, const char* what)
{
  const int winW = f.Scene.Window->GetSize()[0], winH = f.Scene.Window->GetSize()[1];
  vtkSmartPointer<vtkTextureObject> irradiance = Texture(f.GL, winW, winH);
  vtkSmartPointer<vtkTextureObject> indirect = Texture(f.GL, winW, winH);
  MRGI_TEST_CHECK(tree ? gather->GatherFullTree(f.Frame, *tree, 1.0, irradiance, indirect, v)
                       : gather->GatherFull(f.Frame, cache, VPLs, 1.0, irradiance, indirect, v));
  const std::vector<float> gpu = Read(irradiance);
  irradiance->ReleaseGraphicsResources(f.Scene.Window);
  indirect->ReleaseGraphicsResources(f.Scene.Window);
  const mrgi_gather_receivers receivers = { f.W, f.H, Floats(f.Position), Floats(f.Normal) };
  mrgi_image cE{};
  f.RunTwin(receivers, tree, v.Mode == vtkMRGIIndirectVisibility::VoxelVisibility, cE);
  Comparison c;
  for (int y = 0; y < f.H; ++y)
  {
    for (int x = 0; x < f.W; ++x)
    {
      const size_t p = static_cast<size_t>(y) * f.W + x;
      if (Floats(f.Position)[4 * p + 3] > MRGI_VALID_THRESHOLD)
      {
        const size_t g =
          static_cast<size_t>(y + f.Frame.Viewport[1]) * winW + x + f.Frame.Viewport[0];
        c.Add(gpu.data() + 4 * g, cE.pixels + 3 * p);
      }
    }
  }
  mrgi_image_destroy(&cE);
  MRGI_TEST_CHECK(c.Report(what));
  return c.Twin;
}

// The stenciled gathers at the texels the buffer selects; returns the twin's sum.
double Stenciled(Fixture& f, vtkMRGIGather* gather, vtkTextureObject* cache,
  const vtkMRGIVPLTreeTerm* tree, const vtkMRGIIndirectVisibility& v, const char* what)
{
  vtkNew<vtkMRGIMultiresolution> buffer;
  buffer->SetPreset(vtkMRGIMultiresolution::PresetBalanced);
  vtkCamera* camera = f.Scene.Renderer->GetActiveCamera();
  mrgi_multires_projection projection = { 0, camera->GetViewAngle(), camera->GetParallelScale() };
  float ab[2];
  MRGI_TEST_CHECK(mrgi_multires_pixel_size_coefficients(&projection, f.H, ab, nullptr) == MRGI_OK);
  const int* vp = f.Frame.Viewport;
  MRGI_TEST_CHECK(
    buffer->Update(f.GL, f.Frame.Position, f.Frame.Normal, vp[0], vp[1], f.W, f.H, ab[0], ab[1]));
  MRGI_TEST_CHECK(buffer->BuildReceivers(f.GL, f.Frame.Position, f.Frame.Normal, vp[0], vp[1]));
  MRGI_TEST_CHECK(tree ? gather->GatherVPLTree(f.Frame, buffer, *tree, v)
                       : gather->GatherVPLs(f.Frame, buffer, cache, VPLs, v));
  vtkNew<vtkFloatArray> gpuE, gpuP, gpuN;
  MRGI_TEST_CHECK(gather->ReadIrradiance(f.Scene.Window, gpuE));
  MRGI_TEST_CHECK(buffer->ReadReceivers(f.Scene.Window, gpuP, gpuN));
  vtkNew<vtkUnsignedCharArray> mask;
  MRGI_TEST_CHECK(buffer->ReadSelection(f.Scene.Window, mask, true));
  mrgi_multires_layout layout;
  MRGI_TEST_CHECK(buffer->GetLayout(&layout));
  const size_t texels = static_cast<size_t>(layout.total_width) * layout.total_height;
  std::vector<float> P(4 * texels, 0.0f), N(4 * texels, 0.0f);
  for (size_t t = 0; t < texels; ++t)
  {
    if (mask->GetValue(static_cast<vtkIdType>(t)))
    {
      std::copy(gpuP->GetPointer(4 * t), gpuP->GetPointer(4 * t) + 4, P.data() + 4 * t);
      std::copy(gpuN->GetPointer(4 * t), gpuN->GetPointer(4 * t) + 4, N.data() + 4 * t);
    }
  }
  const mrgi_gather_receivers flat = { layout.total_width, layout.total_height, P.data(), N.data() };
  mrgi_image cE{};
  f.RunTwin(flat, tree, v.Mode == vtkMRGIIndirectVisibility::VoxelVisibility, cE);
  Comparison c;
  for (size_t t = 0; t < texels; ++t)
  {
    if (mask->GetValue(static_cast<vtkIdType>(t)) && P[4 * t + 3] > MRGI_VALID_THRESHOLD)
    {
      c.Add(gpuE->GetPointer(4 * t), cE.pixels + 3 * t);
    }
  }
  mrgi_image_destroy(&cE);
  MRGI_TEST_CHECK(c.Report(what));
  buffer->ReleaseGraphicsResources(f.Scene.Window);
  return c.Twin;
}

void CheckErrors(Fixture& f, vtkMRGIGather* gather, vtkTextureObject* cache,
  const vtkMRGIVPLTreeTerm& term)
{
  const int winW = f.Scene.Window->GetSize()[0], winH = f.Scene.Window->GetSize()[1];
  vtkSmartPointer<vtkTextureObject> irradiance = Texture(f.GL, winW, winH);
  vtkSmartPointer<vtkTextureObject> indirect = Texture(f.GL, winW, winH);
  vtkNew<mrgitest::ErrorCatcher> errors;
  gather->AddObserver(vtkCommand::ErrorEvent, errors);
  MRGI_TEST_CHECK(
    !gather->GatherFull(f.Frame, cache, VPLs, 1.0, irradiance, indirect, Voxels(nullptr)));
  MRGI_TEST_CHECK(errors->Caught("voxelization is missing"));
  vtkNew<vtkMRGIVoxelization> never;
  MRGI_TEST_CHECK(
    !gather->GatherFull(f.Frame, cache, VPLs, 1.0, irradiance, indirect, Voxels(never)));
  MRGI_TEST_CHECK(errors->Caught("no voxels"));
  // 3 levels (21 nodes a root). A march takes at most the voxel buffer's
  // side + 2 steps (mrgi_voxel_step_bound()): at 4096 steps the 128^2
  // buffer still allows 57 marches a draw, a 1024^2 one 7.
  f.Voxelization->SetMaxSteps(MRGI_VOXEL_MAX_STEPS);
  MRGI_TEST_CHECK(mrgi_voxel_samples_per_batch(f.Voxelization->GetMarchStepBound()) >= 21);
  MRGI_TEST_CHECK(gather->GatherFullTree(
    f.Frame, term, 1.0, irradiance, indirect, Voxels(f.Voxelization)));
  double range[2];
  mrgitest::DepthRange(mrgitest::SceneTriangles(f.Scene.Renderer), range); // as the fixture
  f.Voxelization->SetVoxelSide(1024);
  MRGI_TEST_CHECK(f.Voxelization->Voxelize(f.Scene.Renderer, range[0], range[1]));
  MRGI_TEST_CHECK(mrgi_voxel_samples_per_batch(f.Voxelization->GetMarchStepBound()) < 21);
  MRGI_TEST_CHECK(!gather->GatherFullTree(
    f.Frame, term, 1.0, irradiance, indirect, Voxels(f.Voxelization)));
  MRGI_TEST_CHECK(errors->Caught("subtree of 21 nodes"));
  f.Voxelization->SetMaxSteps(MRGI_VOXEL_DEFAULT_MAX_STEPS);
  f.Voxelization->SetVoxelSide(MRGI_VOXEL_DEFAULT_SIZE);
  MRGI_TEST_CHECK(f.Voxelization->Voxelize(f.Scene.Renderer, range[0], range[1]));
  gather->RemoveObserver(errors);
  irradiance->ReleaseGraphicsResources(f.Scene.Window);
  indirect->ReleaseGraphicsResources(f.Scene.Window);
}
}

int main()
{
  vtkNew<vtkMRGIGather> gather;
  {
    Fixture f;
    // Several draws per gather (the batching is exercised).
    MRGI_TEST_CHECK(mrgi_voxel_samples_per_batch(MRGI_VOXEL_DEFAULT_MAX_STEPS) < VPLs);
    vtkSmartPointer<vtkTextureObject> cache = Texture(f.GL, MRGI_VPL_TEXELS, VPLs, f.Tree.nodes);
    vtkNew<vtkTextureObject> nodes;
    MRGI_TEST_CHECK(vtkMRGIGather::UploadVPLTree(f.GL, &f.Tree, nodes));
    vtkMRGIVPLTreeTerm term;
    term.Nodes = nodes;
    term.Tree = &f.Tree;
    term.Threshold = 0.05;
    const vtkMRGIIndirectVisibility none;
    const vtkMRGIIndirectVisibility voxels = Voxels(f.Voxelization);

    // 1. and 2.
    double lit = Full(f, gather, cache, nullptr, none, "full, none");
    double shadowed = Full(f, gather, cache, nullptr, voxels, "full, voxels");
    std::printf("  shadowed / unshadowed: %.3f\n", shadowed / lit);
    MRGI_TEST_CHECK(shadowed < 0.98 * lit);
    lit = Full(f, gather, nullptr, &term, none, "full tree tau 0.05, none");
    shadowed = Full(f, gather, nullptr, &term, voxels, "full tree tau 0.05, voxels");
    std::printf("  shadowed / unshadowed: %.3f\n", shadowed / lit);
    MRGI_TEST_CHECK(shadowed < 0.98 * lit);
    lit = Stenciled(f, gather, cache, nullptr, none, "stenciled, none");
    shadowed = Stenciled(f, gather, cache, nullptr, voxels, "stenciled, voxels");
    std::printf("  shadowed / unshadowed: %.3f\n", shadowed / lit);
    MRGI_TEST_CHECK(shadowed < 0.98 * lit);
    lit = Stenciled(f, gather, nullptr, &term, none, "stenciled tree tau 0.05, none");
    shadowed = Stenciled(f, gather, nullptr, &term, voxels, "stenciled tree tau 0.05, voxels");
    std::printf("  shadowed / unshadowed: %.3f\n", shadowed / lit);
    MRGI_TEST_CHECK(shadowed < 0.98 * lit);

    // 3. Errors.
    CheckErrors(f, gather, cache, term);
    cache->ReleaseGraphicsResources(f.Scene.Window);
    nodes->ReleaseGraphicsResources(f.Scene.Window);
    gather->ReleaseGraphicsResources(f.Scene.Window);
  }
  return EXIT_SUCCESS;
}
