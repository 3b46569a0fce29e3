// Indirect shadows in the VPL gathers (issue 13 part 3): the GPU gathers of
// vtkMRGIGather with ISM visibility (vtkMRGIIndirectVisibility,
// vtkMRGIISMLookup.glsl) against their C twins mrgi_gather_full_visibility()
// and mrgi_vpl_tree_gather_visibility(), on the built-in Cornell box lit by
// its spot (RSM 64: the 16 x 16 grid VPLs and tree roots). The ISM atlas is
// built with the C core: the G-buffer's valid pixels (world space) are the
// point set; every VPL draws every point (mrgi_ism_point_texel, nearest
// wins), then mrgi_ism_push_pull; uploaded as R32F.
// 1. Full cache gather, stenciled cache gather, full and stenciled tree
//    gathers (tau 0.05), PCF on and off: relative RMS against the twin
//    below 1e-4 (measured about 2.5e-7: float vs double moved no lookup
//    that mattered here), and the shadows darken both gathers;
// 2. visibility None gives the old gathers bit for bit, and ISM with an
//    empty atlas too (every V is exactly 1); a real atlas darkens;
// 3. errors name the problem: atlas missing, a layout of another VPL count,
//    an atlas texture of another size, voxel visibility without voxels and splatting
//    refused.
#include "mrgiTestUtilities.h"

#include "vtkCamera.h"
#include "vtkCommand.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMRGIFrameContext.h"
#include "vtkMRGIGather.h"
#include "vtkMRGIIndirectVisibility.h"
#include "vtkMRGIMultiresolution.h"
#include "vtkMRGIPass.h"
#include "vtkMRGIReflectiveShadowMapPass.h"
#include "vtkMRGISceneBuilder.h"
#include "vtkMRGIVPLSelection.h"
#include "vtkMath.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkPointData.h"
#include "vtkRenderStepsPass.h"
#include "vtkRenderer.h"
#include "vtkTextureObject.h"
#include "vtkUnsignedCharArray.h"
#include "vtk_glew.h"

#include "mrgi_gather.h"
#include "mrgi_ism_atlas.h"
#include "mrgi_ism_visibility.h"
#include "mrgi_multires.h"
#include "mrgi_vpl_tree.h"
#include "mrgi_vpl_tree_gather.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <vector>

#include "mrgiGatherTestScene.h"

using namespace mrgigather;

namespace
{

// Relative RMS bound of the GPU against the C twin with visibility.
constexpr double Bound = 1e-4; // the gather parity tolerance (TestMRGITreeGather)

struct Atlas
{
  mrgi_ism_atlas_layout Layout{};
  std::vector<float> Depth;
  vtkNew<vtkTextureObject> Texture;
};

// The atlas of `vpls` (world space) over the G-buffer's valid pixels, or
// an empty one (every texel MRGI_ISM_EMPTY_DEPTH).
void BuildAtlas(Scene& s, const mrgi_vpl* vpls, int count, bool empty, Atlas& atlas)
{
  MRGI_TEST_CHECK(mrgi_ism_atlas_layout_make(count, 32, &atlas.Layout, nullptr) == MRGI_OK);
  atlas.Depth.assign(static_cast<size_t>(atlas.Layout.width) * atlas.Layout.height,
    MRGI_ISM_EMPTY_DEPTH);
  const double* v2w = s.Pass->GetLastViewToWorld();
  const float* P = Floats(s.Position);
  for (int p = 0; !empty && p < s.W * s.H; ++p)
  {
    if (!(P[4 * p + 3] > MRGI_VALID_THRESHOLD))
    {
      continue;
    }
    double x[3];
    for (int r = 0; r < 3; ++r) // v2w is column-major: element (r, c) at v2w[4 c + r]
    {
      x[r] = v2w[r] * P[4 * p] + v2w[4 + r] * P[4 * p + 1] + v2w[8 + r] * P[4 * p + 2] +
        v2w[12 + r];
    }
    for (int j = 0; j < count; ++j)
    {
      const double pos[3] = { vpls[j].position[0], vpls[j].position[1], vpls[j].position[2] };
      const double nor[3] = { vpls[j].normal[0], vpls[j].normal[1], vpls[j].normal[2] };
      const double len = std::sqrt(nor[0] * nor[0] + nor[1] * nor[1] + nor[2] * nor[2]);
      if (!(len > 0.0))
      {
        continue;
      }
      const double n[3] = { nor[0] / len, nor[1] / len, nor[2] / len };
      int64_t texel;
      float z;
      if (mrgi_ism_point_texel(&atlas.Layout, j, pos, n, x, &texel, &z) &&
        z < atlas.Depth[static_cast<size_t>(texel)])
      {
        atlas.Depth[static_cast<size_t>(texel)] = z;
      }
    }
  }
  std::vector<float> scratch(mrgi_ism_push_pull_scratch_size(&atlas.Layout));
  MRGI_TEST_CHECK(mrgi_ism_push_pull(&atlas.Layout, atlas.Depth.data(),
                    MRGI_ISM_MAX_PUSH_PULL_LEVELS, scratch.data(), scratch.size(), nullptr) == MRGI_OK);
  atlas.Texture->SetContext(s.GL);
  atlas.Texture->SetInternalFormat(GL_R32F);
  atlas.Texture->SetFormat(GL_RED);
  atlas.Texture->SetDataType(GL_FLOAT);
  MRGI_TEST_CHECK(atlas.Texture->Create2DFromRaw(
    atlas.Layout.width, atlas.Layout.height, 1, VTK_FLOAT, atlas.Depth.data()));
}

vtkMRGIIndirectVisibility ISM(const Atlas& atlas, int pcf)
{
  vtkMRGIIndirectVisibility v;
  v.Mode = vtkMRGIIndirectVisibility::ISMVisibility;
  v.ISMAtlas = atlas.Texture;
  v.ISMLayout = atlas.Layout;
  mrgi_ism_lookup_params_default(&v.ISMLookup);
  v.ISMLookup.pcf = pcf;
  return v;
}

mrgi_gather_visibility CVisibility(const Atlas& atlas, const vtkMRGIIndirectVisibility& v)
{
  mrgi_gather_visibility c{};
  c.mode = v.Mode == vtkMRGIIndirectVisibility::ISMVisibility ? MRGI_GATHER_VISIBILITY_ISM
                                                               : MRGI_GATHER_VISIBILITY_NONE;
  c.ism_layout = &atlas.Layout;
  c.ism_depth = atlas.Depth.data();
  c.ism_lookup = v.ISMLookup;
  return c;
}

// The VPL cache as a texture (MRGI_VPL_TEXELS RGBA32F texels per VPL, one row each).
vtkSmartPointer<vtkTextureObject> VPLTexture(vtkOpenGLRenderWindow* window, const mrgi_vpl* vpls,
  int count)
{
  vtkNew<vtkTextureObject> t;
  t->SetContext(window);
  t->SetInternalFormat(GL_RGBA32F);
  t->SetFormat(GL_RGBA);
  t->SetDataType(GL_FLOAT);
  MRGI_TEST_CHECK(t->Create2DFromRaw(MRGI_VPL_TEXELS, count, 4, VTK_FLOAT,
    const_cast<void*>(static_cast<const void*>(vpls))));
  return t.Get();
}

// The full-resolution gathers (cache: `tree` null) at every valid pixel.
// Returns the GPU image (window-sized RGBA).
std::vector<float> Full(Scene& s, vtkMRGIGather* gather, vtkTextureObject* cache,
  const vtkMRGIVPLTreeTerm* tree, const vtkMRGIIndirectVisibility& v, const Atlas& atlas,
  const char* what, bool compare = true)
{
  const int winW = s.Window->GetSize()[0], winH = s.Window->GetSize()[1];
  vtkSmartPointer<vtkTextureObject> irradiance = Target(s.GL, winW, winH);
  vtkSmartPointer<vtkTextureObject> indirect = Target(s.GL, winW, winH);
  MRGI_TEST_CHECK(tree ? gather->GatherFullTree(s.Frame, *tree, 1.0, irradiance, indirect, v)
                       : gather->GatherFull(s.Frame, cache, 256, 1.0, irradiance, indirect, v));
  std::vector<float> gpu;
  MRGI_TEST_CHECK(ReadTexture(irradiance, gpu));
  irradiance->ReleaseGraphicsResources(s.Window);
  indirect->ReleaseGraphicsResources(s.Window);
  if (!compare)
  {
    return gpu;
  }
  mrgi_gather_receivers receivers = { s.W, s.H, Floats(s.Position), Floats(s.Normal) };
  const mrgi_gather_visibility cv = CVisibility(atlas, v);
  mrgi_image cE{};
  mrgi_error err;
  const mrgi_status status = tree
    ? mrgi_vpl_tree_gather_visibility(
        &receivers, &s.Tree, tree->Threshold, s.WorldToView, &cv, &cE, nullptr, nullptr, &err)
    : mrgi_gather_full_visibility(
        &receivers, s.Tree.nodes, 256, s.WorldToView, &cv, &cE, nullptr, &err);
  if (status != MRGI_OK)
  {
    MRGI_TEST_FAIL("C twin: %s", err.message);
  }
  Comparison c;
  for (int y = 0; y < s.H; ++y)
  {
    for (int x = 0; x < s.W; ++x)
    {
      const size_t p = static_cast<size_t>(y) * s.W + x;
      if (Floats(s.Position)[4 * p + 3] > MRGI_VALID_THRESHOLD)
      {
        const size_t g =
          static_cast<size_t>(y + s.Frame.Viewport[1]) * winW + x + s.Frame.Viewport[0];
        c.Add(gpu.data() + 4 * g, cE.pixels + 3 * p);
      }
    }
  }
  mrgi_image_destroy(&cE);
  std::printf("%s: %zu receivers, relative RMS %.3g against the twin\n", what, c.Compared,
    c.Error());
  MRGI_TEST_CHECK(c.Compared > 0 && c.BadAlpha == 0 && c.Error() < Bound);
  return gpu;
}

// The stenciled gathers at the texels the buffer selects.
void Stenciled(Scene& s, vtkMRGIGather* gather, vtkTextureObject* cache,
  const vtkMRGIVPLTreeTerm* tree, const vtkMRGIIndirectVisibility& v, const Atlas& atlas,
  const char* what)
{
  vtkNew<vtkMRGIMultiresolution> buffer;
  buffer->SetPreset(vtkMRGIMultiresolution::PresetBalanced);
  vtkCamera* camera = s.Renderer->GetActiveCamera();
  mrgi_multires_projection projection = { 0, camera->GetViewAngle(), camera->GetParallelScale() };
  float ab[2];
  mrgi_error err;
  MRGI_TEST_CHECK(mrgi_multires_pixel_size_coefficients(&projection, s.H, ab, &err) == MRGI_OK);
  const int* vp = s.Frame.Viewport;
  MRGI_TEST_CHECK(
    buffer->Update(s.GL, s.Frame.Position, s.Frame.Normal, vp[0], vp[1], s.W, s.H, ab[0], ab[1]));
  MRGI_TEST_CHECK(buffer->BuildReceivers(s.GL, s.Frame.Position, s.Frame.Normal, vp[0], vp[1]));
  MRGI_TEST_CHECK(tree ? gather->GatherVPLTree(s.Frame, buffer, *tree, v)
                       : gather->GatherVPLs(s.Frame, buffer, cache, 256, v));
  vtkNew<vtkFloatArray> gpuE, gpuP, gpuN;
  MRGI_TEST_CHECK(gather->ReadIrradiance(s.Window, gpuE));
  MRGI_TEST_CHECK(buffer->ReadReceivers(s.Window, gpuP, gpuN));
  vtkNew<vtkUnsignedCharArray> mask;
  MRGI_TEST_CHECK(buffer->ReadSelection(s.Window, mask, true));
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
  mrgi_gather_receivers flat = { layout.total_width, layout.total_height, P.data(), N.data() };
  const mrgi_gather_visibility cv = CVisibility(atlas, v);
  mrgi_image cE{};
  const mrgi_status status = tree
    ? mrgi_vpl_tree_gather_visibility(
        &flat, &s.Tree, tree->Threshold, s.WorldToView, &cv, &cE, nullptr, nullptr, &err)
    : mrgi_gather_full_visibility(&flat, s.Tree.nodes, 256, s.WorldToView, &cv, &cE, nullptr, &err);
  if (status != MRGI_OK)
  {
    MRGI_TEST_FAIL("C twin: %s", err.message);
  }
  Comparison c;
  for (size_t t = 0; t < texels; ++t)
  {
    if (mask->GetValue(static_cast<vtkIdType>(t)) && P[4 * t + 3] > MRGI_VALID_THRESHOLD)
    {
      c.Add(gpuE->GetPointer(4 * t), cE.pixels + 3 * t);
    }
  }
  mrgi_image_destroy(&cE);
  std::printf("%s: %zu selected receivers, relative RMS %.3g against the twin\n", what,
    c.Compared, c.Error());
  MRGI_TEST_CHECK(c.Compared > 0 && c.BadAlpha == 0 && c.Error() < Bound);
  buffer->ReleaseGraphicsResources(s.Window);
}

double Sum(const std::vector<float>& rgba)
{
  double sum = 0.0;
  for (size_t t = 0; 4 * t < rgba.size(); ++t)
  {
    sum += rgba[4 * t] + rgba[4 * t + 1] + rgba[4 * t + 2];
  }
  return sum;
}

void CheckErrors(Scene& s, vtkMRGIGather* gather, vtkTextureObject* cache, const Atlas& atlas,
  const Atlas& small)
{
  const int winW = s.Window->GetSize()[0], winH = s.Window->GetSize()[1];
  vtkSmartPointer<vtkTextureObject> irradiance = Target(s.GL, winW, winH);
  vtkSmartPointer<vtkTextureObject> indirect = Target(s.GL, winW, winH);
  vtkNew<mrgitest::ErrorCatcher> errors;
  gather->AddObserver(vtkCommand::ErrorEvent, errors);
  vtkMRGIIndirectVisibility v = ISM(atlas, 1);
  v.ISMAtlas = nullptr;
  MRGI_TEST_CHECK(!gather->GatherFull(s.Frame, cache, 256, 1.0, irradiance, indirect, v));
  MRGI_TEST_CHECK(errors->Caught("atlas is missing"));
  v = ISM(small, 1); // 16 tiles for 256 VPLs
  MRGI_TEST_CHECK(!gather->GatherFull(s.Frame, cache, 256, 1.0, irradiance, indirect, v));
  MRGI_TEST_CHECK(errors->Caught("16 tiles"));
  v = ISM(atlas, 1);
  v.ISMAtlas = small.Texture; // the texture of another layout
  MRGI_TEST_CHECK(!gather->GatherFull(s.Frame, cache, 256, 1.0, irradiance, indirect, v));
  MRGI_TEST_CHECK(errors->Caught("atlas texture"));
  v = ISM(atlas, 1);
  v.ISMLookup.texel_bias = -1.0f;
  MRGI_TEST_CHECK(!gather->GatherFull(s.Frame, cache, 256, 1.0, irradiance, indirect, v));
  MRGI_TEST_CHECK(errors->Caught("texel bias"));
  vtkMRGIIndirectVisibility voxels;
  voxels.Mode = vtkMRGIIndirectVisibility::VoxelVisibility;
  MRGI_TEST_CHECK(!gather->GatherFull(s.Frame, cache, 256, 1.0, irradiance, indirect, voxels));
  MRGI_TEST_CHECK(errors->Caught("voxelization is missing")); // TestMRGIVoxelVPLVisibility: with voxels
  vtkNew<vtkMRGIMultiresolution> buffer;
  gather->SetGatherModeToSplatting();
  MRGI_TEST_CHECK(!gather->GatherVPLs(s.Frame, buffer, cache, 256, ISM(atlas, 1)));
  MRGI_TEST_CHECK(errors->Caught("splatting"));
  gather->SetGatherModeToStenciled();
  gather->RemoveObserver(errors);
  irradiance->ReleaseGraphicsResources(s.Window);
  indirect->ReleaseGraphicsResources(s.Window);
}
}

int main()
{
  vtkNew<vtkMRGIGather> gather;
  {
    Scene s(72, 56, 64);
    MRGI_TEST_CHECK(mrgi_vpl_tree_root_count(&s.Tree) == 256);
    // The roots are the cache (vtkMRGIVPLSelection's Tree mode): tile r = root r.
    vtkSmartPointer<vtkTextureObject> cache = VPLTexture(s.GL, s.Tree.nodes, 256);
    vtkNew<vtkTextureObject> nodes;
    MRGI_TEST_CHECK(vtkMRGIGather::UploadVPLTree(s.GL, &s.Tree, nodes));
    vtkMRGIVPLTreeTerm term;
    term.Nodes = nodes;
    term.Tree = &s.Tree;
    term.Threshold = 0.05;
    Atlas atlas, empty, small;
    BuildAtlas(s, s.Tree.nodes, 256, false, atlas);
    BuildAtlas(s, s.Tree.nodes, 256, true, empty);
    BuildAtlas(s, s.Tree.nodes, 16, true, small);

    // 2. None: the old gathers bit for bit; ISM with an empty atlas too.
    const vtkMRGIIndirectVisibility none;
    const std::vector<float> old = Full(s, gather, cache, nullptr, none, atlas, "", false);
    std::vector<float> plain;
    {
      const int winW = s.Window->GetSize()[0], winH = s.Window->GetSize()[1];
      vtkSmartPointer<vtkTextureObject> irradiance = Target(s.GL, winW, winH);
      vtkSmartPointer<vtkTextureObject> indirect = Target(s.GL, winW, winH);
      MRGI_TEST_CHECK(gather->GatherFull(s.Frame, cache, 256, 1.0, irradiance, indirect));
      MRGI_TEST_CHECK(ReadTexture(irradiance, plain));
      irradiance->ReleaseGraphicsResources(s.Window);
      indirect->ReleaseGraphicsResources(s.Window);
    }
    MRGI_TEST_CHECK(old == plain);
    const std::vector<float> unshadowed =
      Full(s, gather, cache, nullptr, ISM(empty, 1), empty, "full, ISM of nothing");
    MRGI_TEST_CHECK(unshadowed == plain);
    std::printf("None and an empty ISM give the old full gather bit for bit\n");
    const std::vector<float> treePlain = Full(s, gather, nullptr, &term, none, atlas, "", false);
    MRGI_TEST_CHECK(
      Full(s, gather, nullptr, &term, ISM(empty, 1), empty, "full tree, ISM of nothing") ==
      treePlain);

    // 1. Parity with the twins, PCF on and off.
    for (int pcf = 1; pcf >= 0; --pcf)
    {
      char what[64];
      std::snprintf(what, sizeof(what), "full, ISM, pcf %d", pcf);
      const std::vector<float> shadowed = Full(s, gather, cache, nullptr, ISM(atlas, pcf), atlas, what);
      std::printf("  shadowed / unshadowed irradiance: %.3f\n", Sum(shadowed) / Sum(plain));
      MRGI_TEST_CHECK(Sum(shadowed) < 0.98 * Sum(plain));
      std::snprintf(what, sizeof(what), "full tree tau 0.05, ISM, pcf %d", pcf);
      const std::vector<float> treeShadowed =
        Full(s, gather, nullptr, &term, ISM(atlas, pcf), atlas, what);
      std::printf("  tree: shadowed / unshadowed irradiance: %.3f\n",
        Sum(treeShadowed) / Sum(treePlain));
      MRGI_TEST_CHECK(Sum(treeShadowed) < 0.98 * Sum(treePlain));
      std::snprintf(what, sizeof(what), "stenciled, ISM, pcf %d", pcf);
      Stenciled(s, gather, cache, nullptr, ISM(atlas, pcf), atlas, what);
      std::snprintf(what, sizeof(what), "stenciled tree tau 0.05, ISM, pcf %d", pcf);
      Stenciled(s, gather, nullptr, &term, ISM(atlas, pcf), atlas, what);
    }
    // 3. Errors.
    CheckErrors(s, gather, cache, atlas, small);
    cache->ReleaseGraphicsResources(s.Window);
    nodes->ReleaseGraphicsResources(s.Window);
    atlas.Texture->ReleaseGraphicsResources(s.Window);
    empty.Texture->ReleaseGraphicsResources(s.Window);
    small.Texture->ReleaseGraphicsResources(s.Window);
    gather->ReleaseGraphicsResources(s.Window);
  }
  return EXIT_SUCCESS;
}
