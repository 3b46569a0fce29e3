#include "vtkMRGIVPLSelection.h"
#include "vtkMRGIFrameContext.h"

#include "vtkFloatArray.h"
#include "vtkMRGIBRSMInversion.h"
#include "vtkMRGIGather.h"
#include "vtkMRGIReflectiveShadowMapPass.h"
#include "vtkMRGIResourceStatistics.h"
#include "vtkMRGIShaderUtilities.h"
#include "vtkMath.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLQuadHelper.h"
#include "vtkOpenGLRenderUtilities.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"

#include "vtkMRGIBRSM.h"
#include "vtkMRGIVPLTreeTexture.h"
#include "vtkMRGIViewSamples.h"

#include "vtkMRGIVPLGridFS.h"

#include "mrgi_brsm_importance.h"
#include "mrgi_brsm_temporal.h"
#include "mrgi_vpl.h"
#include "mrgi_vpl_clusters.h"
#include "mrgi_vpl_tree.h"
#include "mrgi_vpl_tree_gather.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

#include <map>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkMRGIVPLSelection);

// The header's clamp range is the core's.
static_assert(MRGI_BRSM_MIN_TEMPORAL_WEIGHT == 0.001, "BRSMTemporalWeight clamp range");
static_assert(MRGI_BRSM_MAX_VIEW_SAMPLES == 1024, "BRSMSamplesPerTexel clamp range");

struct vtkMRGIVPLSelection::Internals
{
  vtkTextureObject* Texture = nullptr;
  vtkOpenGLFramebufferObject* FrameBuffer = nullptr;
  vtkOpenGLQuadHelper* GridQuad = nullptr;
  vtkOpenGLQuadHelper* RowsQuad = nullptr;
  vtkTextureObject* RowSums = nullptr; // grid stage 0 outputs, G x S
  vtkTextureObject* RowBest = nullptr;
  vtkTextureObject* TreeTexture = nullptr; // Tree mode: node records (mrgi_vpl_tree_gather.h 3)
  mrgi_vpl_tree Tree = {};                 // Tree mode: node_count 0 when there is none
  int Count = 0;
  vtkMTimeType SourceTime = 0;
  vtkMTimeType SettingsTime = 0;
  vtkMRGIBRSM::ViewSamples View; // BRSM mode: the view samples of the selection
  vtkMRGIViewSamples OwnSamples;  // BRSM mode without a shared read-back
  const vtkMRGIViewSamples* ViewSource = nullptr; // where View came from
  long long ViewSourceStamp = -1;                 // its content stamp then
  vtkIdType ViewStamp = 0;        // bumped whenever View changes
  vtkIdType SourceViewStamp = 0;  // ViewStamp of the cache
  vtkMRGIBRSMInversion* Inversion = nullptr; // BRSM mode, texel VPLs: the GPU inversion
  // BRSM mode: each light's pdf of the previous selection (the temporal
  // blend's history, mrgi_brsm_temporal.h), indexed by light.
  std::vector<std::vector<float>> BRSMHistory;
};

//------------------------------------------------------------------------------
void vtkMRGIVPLSelection::ResetBRSMHistory()
{
  if (this->Internal->BRSMHistory.empty())
  {
    return;
  }
  this->Internal->BRSMHistory.clear();
  // The cached VPLs were drawn from the blended pdf: the next frame selects
  // again, from its own pdf alone, even if nothing else changed. Without
  // this, a reset before an unchanged frame took effect one frame late,
  // where the view moved, and that frame jumped (temporal_flicker.py).
  this->Modified();
}

//------------------------------------------------------------------------------
vtkMRGIVPLSelection::vtkMRGIVPLSelection()
  : Internal(new Internals)
{
  mrgi_vpl_cluster_params defaults;
  mrgi_vpl_cluster_params_default(&defaults);
  this->ClusterDepthThreshold = defaults.depth_threshold;
  this->ClusterNormalThreshold = defaults.normal_threshold;
  this->ClusterFinestLevel = defaults.finest_level;
  this->TreeThreshold = MRGI_VPL_TREE_DEFAULT_THRESHOLD;
  this->BRSMTemporalWeight = MRGI_BRSM_DEFAULT_TEMPORAL_WEIGHT;
  this->BRSMFluxShare = MRGI_BRSM_DEFAULT_FLUX_SHARE;
  this->BRSMSamplesPerTexel = MRGI_BRSM_DEFAULT_SAMPLES_PER_TEXEL;
}

//------------------------------------------------------------------------------
vtkMRGIVPLSelection::~vtkMRGIVPLSelection()
{
  if (this->Internal->Texture || this->Internal->FrameBuffer || this->Internal->GridQuad ||
    this->Internal->RowsQuad || this->Internal->RowSums || this->Internal->RowBest ||
    this->Internal->TreeTexture || this->Internal->Inversion)
  {
    vtkErrorMacro("GL resources should have been freed in ReleaseGraphicsResources().");
  }
  if (this->Internal->Texture)
  {
    this->Internal->Texture->Delete();
  }
  if (this->Internal->FrameBuffer)
  {
    this->Internal->FrameBuffer->Delete();
  }
  for (vtkTextureObject* t : { this->Internal->RowSums, this->Internal->RowBest })
  {
    if (t)
    {
      t->Delete();
    }
  }
  delete this->Internal->GridQuad;
  delete this->Internal->RowsQuad;
  if (this->Internal->Inversion)
  {
    this->Internal->Inversion->ReleaseGraphicsResources(nullptr);
    this->Internal->Inversion->Delete();
  }
  this->ReleaseTree(nullptr);
}

//------------------------------------------------------------------------------
void vtkMRGIVPLSelection::ReleaseTree(vtkWindow* w)
{
  if (this->Internal->TreeTexture)
  {
    if (w)
    {
      this->Internal->TreeTexture->ReleaseGraphicsResources(w);
    }
    this->Internal->TreeTexture->Delete();
    this->Internal->TreeTexture = nullptr;
  }
  mrgi_vpl_tree_destroy(&this->Internal->Tree);
}

//------------------------------------------------------------------------------
void vtkMRGIVPLSelection::ReleaseGraphicsResources(vtkWindow* w)
{
  if (this->Internal->GridQuad)
  {
    this->Internal->GridQuad->ReleaseGraphicsResources(w);
    delete this->Internal->GridQuad;
    this->Internal->GridQuad = nullptr;
  }
  if (this->Internal->Inversion)
  {
    this->Internal->Inversion->ReleaseGraphicsResources(w);
    this->Internal->Inversion->Delete();
    this->Internal->Inversion = nullptr;
  }
  if (this->Internal->RowsQuad)
  {
    this->Internal->RowsQuad->ReleaseGraphicsResources(w);
    delete this->Internal->RowsQuad;
    this->Internal->RowsQuad = nullptr;
  }
  for (vtkTextureObject** t : { &this->Internal->RowSums, &this->Internal->RowBest })
  {
    if (*t)
    {
      (*t)->ReleaseGraphicsResources(w);
      (*t)->Delete();
      *t = nullptr;
    }
  }
  if (this->Internal->FrameBuffer)
  {
    this->Internal->FrameBuffer->ReleaseGraphicsResources(w);
    this->Internal->FrameBuffer->Delete();
    this->Internal->FrameBuffer = nullptr;
  }
  if (this->Internal->Texture)
  {
    this->Internal->Texture->ReleaseGraphicsResources(w);
    this->Internal->Texture->Delete();
    this->Internal->Texture = nullptr;
  }
  this->ReleaseTree(w);
  this->Internal->OwnSamples.Invalidate(); // the G-buffer it was read from is gone
  this->Internal->Count = 0;
  this->Internal->SourceTime = 0;
}

//------------------------------------------------------------------------------
vtkTextureObject* vtkMRGIVPLSelection::GetVPLTexture() const
{
  return this->Internal->Count > 0 ? this->Internal->Texture : nullptr;
}

int vtkMRGIVPLSelection::GetVPLCount() const
{
  return this->Internal->Count;
}

vtkTextureObject* vtkMRGIVPLSelection::GetTreeTexture() const
{
  return this->Internal->Tree.node_count > 0 ? this->Internal->TreeTexture : nullptr;
}

vtkIdType vtkMRGIVPLSelection::GetNumberOfTreeNodes() const
{
  return static_cast<vtkIdType>(this->Internal->Tree.node_count);
}

const mrgi_vpl_tree* vtkMRGIVPLSelection::GetTree() const
{
  return this->Internal->Tree.node_count > 0 ? &this->Internal->Tree : nullptr;
}

vtkMRGIVPLTreeTerm vtkMRGIVPLSelection::GetTreeTerm() const
{
  vtkMRGIVPLTreeTerm term;
  term.Nodes = this->GetTreeTexture();
  term.Tree = this->GetTree();
  term.Threshold = this->TreeThreshold;
  return term;
}

//------------------------------------------------------------------------------
bool vtkMRGIVPLSelection::ReadVPLs(vtkOpenGLRenderWindow* window, vtkFloatArray* vpls)
{
  vtkTextureObject* texture = this->GetVPLTexture();
  std::vector<float> rgba;
  if (!window || !vpls || !texture || !vtkMRGIShaderUtilities::ReadTextureRGBA(window, texture, rgba))
  {
    vtkErrorMacro("no VPLs to read back");
    return false;
  }
  const int count = this->Internal->Count;
  vpls->SetNumberOfComponents(MRGI_VPL_FLOATS);
  vpls->SetNumberOfTuples(count);
  std::copy(rgba.begin(), rgba.begin() + static_cast<long>(MRGI_VPL_FLOATS) * count, vpls->GetPointer(0));
  return true;
}

bool vtkMRGIVPLSelection::ReadTreeTexture(vtkOpenGLRenderWindow* window, vtkFloatArray* records)
{
  vtkTextureObject* texture = this->GetTreeTexture();
  std::vector<float> rgba;
  if (!window || !records || !texture ||
    !vtkMRGIShaderUtilities::ReadTextureRGBA(window, texture, rgba))
  {
    vtkErrorMacro("no VPL tree texture to read back");
    return false;
  }
  records->SetNumberOfComponents(MRGI_VPL_FLOATS);
  records->SetNumberOfTuples(static_cast<vtkIdType>(rgba.size() / MRGI_VPL_FLOATS));
  std::copy(rgba.begin(), rgba.end(), records->GetPointer(0));
  return true;
}

//------------------------------------------------------------------------------
namespace
{
// Read back the RSM views `views` into one mrgi_rsm's arrays (view order).
bool ReadViews(vtkOpenGLRenderWindow* window, vtkMRGIReflectiveShadowMapPass* rsm,
  const std::vector<int>& views, std::vector<float>& position, std::vector<float>& normal,
  std::vector<float>& flux)
{
  const int size = rsm->GetResolution();
  const size_t texels = static_cast<size_t>(size) * static_cast<size_t>(size) * 4;
  position.resize(texels * views.size());
  normal.resize(texels * views.size());
  flux.resize(texels * views.size());
  std::vector<float> scratch;
  for (size_t i = 0; i < views.size(); ++i)
  {
    const long at = static_cast<long>(i * texels);
    if (!vtkMRGIShaderUtilities::ReadTextureRGBA(window, rsm->GetPositionTexture(views[i]), scratch))
      return false;
    std::copy(scratch.begin(), scratch.end(), position.begin() + at);
    if (!vtkMRGIShaderUtilities::ReadTextureRGBA(window, rsm->GetNormalTexture(views[i]), scratch))
      return false;
    std::copy(scratch.begin(), scratch.end(), normal.begin() + at);
    if (!vtkMRGIShaderUtilities::ReadTextureRGBA(window, rsm->GetFluxTexture(views[i]), scratch))
      return false;
    std::copy(scratch.begin(), scratch.end(), flux.begin() + at);
  }
  return true;
}

// The light-space camera of RSM view `view` (mrgi_vpl_tree.h section 1): the
// RSM pass's row-major world -> view matrix, column-major as floats, and the
// projection's field of view (perspective: P[1][1] = 1 / tan(fov/2)) or
// half extent (orthographic: P[1][1] = 1 / parallel scale).
bool ViewCamera(vtkMRGIReflectiveShadowMapPass* rsm, int view, mrgi_rsm_view_camera& camera)
{
  double worldToView[16];
  double projection[16];
  if (!rsm->GetViewWorldToView(view, worldToView) || !rsm->GetViewProjection(view, projection) ||
    !(projection[5] > 0.0))
  {
    return false;
  }
  for (int row = 0; row < 4; ++row)
  {
    for (int col = 0; col < 4; ++col)
    {
      camera.world_to_view[col * 4 + row] = static_cast<float>(worldToView[row * 4 + col]);
    }
  }
  camera.projection.parallel = rsm->GetViewPerspective(view) ? 0 : 1;
  camera.projection.view_angle_deg =
    camera.projection.parallel ? 90.0 : 2.0 * std::atan(1.0 / projection[5]) * 180.0 / vtkMath::Pi();
  camera.projection.parallel_scale = camera.projection.parallel ? 1.0 / projection[5] : 1.0;
  return true;
}
}

//------------------------------------------------------------------------------
bool vtkMRGIVPLSelection::ReadLight(vtkOpenGLRenderWindow* window,
  vtkMRGIReflectiveShadowMapPass* rsm, const std::vector<int>& views, const char* what,
  mrgi_rsm_view_camera* cameras, std::vector<float>& position, std::vector<float>& normal,
  std::vector<float>& flux)
{
  if (views.empty() || views.size() > MRGI_RSM_MAX_VIEWS)
  {
    vtkErrorMacro(<< what << ": " << views.size() << " RSM views, the C core takes 1.."
                  << MRGI_RSM_MAX_VIEWS << " (MRGI_RSM_MAX_VIEWS) in one map");
    return false;
  }
  for (size_t i = 0; i < views.size(); ++i)
  {
    if (!ViewCamera(rsm, views[i], cameras[i]))
    {
      vtkErrorMacro(<< what << ": RSM view " << views[i] << " has no camera");
      return false;
    }
  }
  if (!ReadViews(window, rsm, views, position, normal, flux))
  {
    vtkErrorMacro(<< what << ": could not read back the RSM views");
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
void vtkMRGIVPLSelection::SetTreeThreshold(double threshold)
{
  // No Modified(): the tree does not depend on tau (see the header).
  this->TreeThreshold = threshold < 0.0 ? 0.0 : threshold;
}

//------------------------------------------------------------------------------
int vtkMRGIVPLSelection::SelectTree(
  vtkOpenGLRenderWindow* window, vtkMRGIReflectiveShadowMapPass* rsm, std::vector<mrgi_vpl>& roots)
{
  roots.clear();
  mrgi_vpl_tree_destroy(&this->Internal->Tree); // the texture stays for the next upload
  const int size = rsm->GetResolution();
  if (size > MRGI_VPL_TREE_GATHER_MAX_RSM_SIZE)
  {
    vtkErrorMacro(<< "VPL tree: the RSM has " << size << " texels per side, the tree gather takes at most "
                  << MRGI_VPL_TREE_GATHER_MAX_RSM_SIZE
                  << " (MRGI_VPL_TREE_GATHER_MAX_RSM_SIZE); no tree, no indirect light");
    return 0;
  }
  // Every view of every light in one tree: the views are independent
  // patches, each with its own camera (mrgi_vpl_tree.h section 2).
  std::vector<int> views(static_cast<size_t>(rsm->GetNumberOfViews()));
  for (size_t v = 0; v < views.size(); ++v)
  {
    views[v] = static_cast<int>(v);
  }
  mrgi_rsm_view_camera cameras[MRGI_RSM_MAX_VIEWS];
  std::vector<float> position, normal, flux;
  if (!this->ReadLight(window, rsm, views, "VPL tree", cameras, position, normal, flux))
  {
    return 0;
  }
  const mrgi_rsm map = { size, static_cast<int32_t>(views.size()), position.data(), normal.data(),
    flux.data() };
  mrgi_vpl_tree& tree = this->Internal->Tree;
  mrgi_error err;
  if (mrgi_vpl_tree_build(&map, cameras, &tree, &err) != MRGI_OK)
  {
    vtkErrorMacro(<< "VPL tree: " << err.message);
    return 0;
  }

  // The texture (mrgi_vpl_tree_gather.h section 3): records row-major,
  // MRGI_VPL_TREE_RECORDS_PER_ROW per row, zero records after the last; the
  // tree gather's own upload, so that the layout has one implementation.
  if (!this->Internal->TreeTexture)
  {
    this->Internal->TreeTexture = vtkTextureObject::New();
  }
  std::string error;
  if (!vtkMRGIVPLTreeTexture::Upload(window, &tree, this->Internal->TreeTexture, error))
  {
    vtkErrorMacro(<< "VPL tree: " << error << "; no tree, no indirect light");
    this->ReleaseTree(window);
    return 0;
  }

  // The flat cache: the roots (level L, records 0..V w_L^2 - 1), pads cleared (mrgi_vpl.h).
  const int32_t rootCount = mrgi_vpl_tree_root_count(&tree);
  roots.assign(tree.nodes, tree.nodes + rootCount);
  for (mrgi_vpl& root : roots)
  {
    root.pad0 = 0.0f;
    root.pad1 = 0.0f;
  }
  return rootCount;
}

//------------------------------------------------------------------------------
int vtkMRGIVPLSelection::SelectClusters(vtkOpenGLRenderWindow* window,
  vtkMRGIReflectiveShadowMapPass* rsm, const std::vector<std::vector<int>>& lights,
  std::vector<mrgi_vpl>& vpls)
{
  vpls.clear();
  this->ClusterRefinementsCapped = 0;
  mrgi_vpl_cluster_params params;
  mrgi_vpl_cluster_params_default(&params);
  params.depth_threshold = this->ClusterDepthThreshold;
  params.normal_threshold = this->ClusterNormalThreshold;
  params.finest_level = this->ClusterFinestLevel;
  params.max_count = MRGI_VPL_CLUSTER_MAX / static_cast<int>(lights.size());
  std::vector<float> position, normal, flux;
  std::vector<mrgi_vpl> light(static_cast<size_t>(params.max_count));
  for (const std::vector<int>& views : lights)
  {
    mrgi_rsm_view_camera cameras[MRGI_RSM_MAX_VIEWS];
    if (!this->ReadLight(window, rsm, views, "VPL clusters", cameras, position, normal, flux))
    {
      return 0;
    }
    const mrgi_rsm map = { rsm->GetResolution(), static_cast<int32_t>(views.size()),
      position.data(), normal.data(), flux.data() };
    mrgi_vpl_cluster_info info;
    mrgi_error err;
    if (mrgi_vpl_select_clusters(&map, cameras, &params, light.data(), params.max_count, &info,
          &err) != MRGI_OK)
    {
      vtkErrorMacro(<< "VPL clusters: " << err.message);
      vpls.clear();
      return 0;
    }
    this->ClusterRefinementsCapped += info.capped;
    vpls.insert(vpls.end(), light.begin(), light.begin() + info.vpl_count);
  }
  return static_cast<int>(vpls.size());
}

//------------------------------------------------------------------------------
int vtkMRGIVPLSelection::Update(vtkOpenGLRenderWindow* window, vtkMRGIReflectiveShadowMapPass* rsm)
{
  if (!window || !rsm)
  {
    return 0;
  }
  const int views = rsm->GetNumberOfViews();
  if (views == 0 || this->NumberOfVPLs == 0)
  {
    this->ReleaseTree(window);
    this->Internal->Count = 0;
    return 0;
  }
  if (this->Internal->Texture && rsm->GetContentTime() == this->Internal->SourceTime &&
    this->GetMTime() == this->Internal->SettingsTime &&
    (this->Mode != BRSM || this->Internal->ViewStamp == this->Internal->SourceViewStamp))
  {
    return this->Internal->Count; // RSMs and settings unchanged
  }

  // Views per light, in view order (the RSM pass keeps a light's views together).
  std::map<int, std::vector<int>> lightViews;
  std::vector<int> lightOrder;
  for (int v = 0; v < views; ++v)
  {
    const int light = rsm->GetViewLight(v);
    if (lightViews.find(light) == lightViews.end())
    {
      lightOrder.push_back(light);
    }
    lightViews[light].push_back(v);
  }
  const int size = rsm->GetResolution();
  std::vector<mrgi_vpl> clusters; // Clusters: the clusters; Tree: the roots
  if (this->Mode == Tree)
  {
    if (this->SelectTree(window, rsm, clusters) == 0)
    {
      return this->Internal->Count = 0;
    }
  }
  else
  {
    this->ReleaseTree(window);
  }
  if (this->Mode == Clusters)
  {
    std::vector<std::vector<int>> lights;
    for (int light : lightOrder)
    {
      lights.push_back(lightViews[light]);
    }
    if (this->SelectClusters(window, rsm, lights, clusters) == 0)
    {
      return this->Internal->Count = 0;
    }
  }
  const int perLight = std::max(MRGI_VPL_MIN_COUNT, this->NumberOfVPLs / static_cast<int>(lightOrder.size()));

  // Rows each light gets.
  struct Block
  {
    int Light;
    int FirstRow;
    int Rows;
    int GridSide;
  };
  std::vector<Block> blocks;
  int rows = 0;
  for (int light : lightOrder)
  {
    const int lightViewCount = static_cast<int>(lightViews[light].size());
    int side = 0, count = perLight;
    if (this->Mode == Grid)
    {
      mrgi_error err;
      if (mrgi_vpl_grid_layout(perLight, lightViewCount, size, &side, &count, &err) != MRGI_OK)
      {
        vtkErrorMacro(<< "VPL grid: " << err.message);
        this->Internal->Count = 0;
        return 0;
      }
    }
    blocks.push_back({ light, rows, count, side });
    rows += count;
  }
  if (this->Mode == Clusters || this->Mode == Tree)
  {
    rows = static_cast<int>(clusters.size()); // a variable count, not NumberOfVPLs
  }

  vtkTextureObject*& texture = this->Internal->Texture;
  if (!texture)
  {
    texture = vtkTextureObject::New();
    texture->SetContext(window);
    texture->SetFormat(GL_RGBA);
    texture->SetInternalFormat(GL_RGBA32F);
    texture->SetDataType(GL_FLOAT);
    texture->SetMinificationFilter(vtkTextureObject::Nearest);
    texture->SetMagnificationFilter(vtkTextureObject::Nearest);
    texture->Allocate2D(MRGI_VPL_TEXELS, rows, 4, VTK_FLOAT);
    vtkMRGIResourceStatistics::RecordTextureAllocation(MRGI_VPL_TEXELS, rows, 16);
  }
  vtkMRGIShaderUtilities::ResizeTexture(texture, MRGI_VPL_TEXELS, rows);

  if (this->Mode == Clusters || this->Mode == Tree)
  {
    texture->Bind();
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, MRGI_VPL_TEXELS, rows, GL_RGBA, GL_FLOAT,
      mrgi_vpl_texture_data(clusters.data()));
    texture->Deactivate();
  }
  else if (this->Mode == FluxImportance || this->Mode == BRSM)
  {
    // Read the maps back and let the C core sample them; upload the records.
    // BRSM texel VPLs: the C core builds the float CDF, the GPU inverts it
    // (vtkMRGIBRSMInversion) into the rows after the upload.
    struct Inversion
    {
      const Block* Rows;
      std::vector<float> CDF, Samples;
    };
    std::vector<Inversion> inversions;
    std::vector<mrgi_vpl> vpls(static_cast<size_t>(rows));
    for (const Block& block : blocks)
    {
      const std::vector<int>& v = lightViews[block.Light];
      std::vector<float> position, normal, flux;
      if (!ReadViews(window, rsm, v, position, normal, flux))
      {
        return this->Internal->Count = 0;
      }
      const mrgi_rsm map = { size, static_cast<int32_t>(v.size()), position.data(), normal.data(),
        flux.data() };
      const vtkTypeUInt64 seed = this->Seed + static_cast<vtkTypeUInt64>(block.Light);
      if (this->Mode == BRSM)
      {
        vtkMRGIBRSM::Settings settings;
        settings.FluxShare = this->BRSMFluxShare;
        settings.SamplesPerTexel = this->BRSMSamplesPerTexel;
        settings.Blur = this->BRSMBlur;
        settings.InterTexel = this->BRSMInterTexel;
        settings.TemporalWeight = this->BRSMTemporalWeight;
        std::vector<std::vector<float>>& histories = this->Internal->BRSMHistory;
        histories.resize(std::max(histories.size(), static_cast<size_t>(block.Light) + 1));
        std::vector<float>* history = &histories[static_cast<size_t>(block.Light)];
        std::string error;
        if (!settings.InterTexel)
        {
          inversions.push_back({ &block, {}, {} });
          if (!vtkMRGIBRSM::PrepareInversion(map, this->Internal->View, settings, block.Rows,
                seed, // fixed: the same VPLs for the same inputs
                history, inversions.back().CDF, inversions.back().Samples, error))
          {
            vtkErrorMacro(<< error);
            return this->Internal->Count = 0;
          }
          continue;
        }
        if (!vtkMRGIBRSM::Select(map, this->Internal->View, settings, block.Rows,
              seed, // fixed: the same VPLs for the same inputs
              history, vpls.data() + block.FirstRow, error))
        {
          vtkErrorMacro(<< error);
          return this->Internal->Count = 0;
        }
        continue;
      }
      mrgi_error err;
      if (mrgi_vpl_select_importance(&map, block.Rows, seed,
            nullptr, 0, vpls.data() + block.FirstRow, block.Rows, nullptr, &err) != MRGI_OK)
      {
        vtkErrorMacro(<< "VPL importance sampling: " << err.message);
        return this->Internal->Count = 0;
      }
    }
    texture->Bind();
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, MRGI_VPL_TEXELS, rows, GL_RGBA, GL_FLOAT,
      mrgi_vpl_texture_data(vpls.data()));
    texture->Deactivate();
    for (const Inversion& inversion : inversions)
    {
      if (!this->Internal->Inversion)
      {
        this->Internal->Inversion = vtkMRGIBRSMInversion::New();
      }
      std::vector<vtkMRGIBRSMInversion::View> viewTextures;
      for (int v : lightViews[inversion.Rows->Light])
      {
        viewTextures.push_back(
          { rsm->GetPositionTexture(v), rsm->GetNormalTexture(v), rsm->GetFluxTexture(v) });
      }
      std::string error;
      if (!this->Internal->Inversion->Invert(window, size, viewTextures, inversion.CDF, inversion.Samples,
            inversion.Rows->Rows, texture, inversion.Rows->FirstRow, error))
      {
        vtkErrorMacro(<< error);
        return this->Internal->Count = 0;
      }
    }
  }
  else
  {
    // Two stages (vtkMRGIVPLGridFS.glsl): rows of each block column, then blocks.
    auto ready = [&](vtkOpenGLQuadHelper*& quad, const char* stage) -> vtkShaderProgram* {
      if (!quad)
      {
        const std::string body = std::string("#define MRGI_GRID_STAGE ") + stage + "\n" + vtkMRGIVPLGridFS;
        quad = new vtkOpenGLQuadHelper(window,
          vtkOpenGLRenderUtilities::GetFullScreenQuadVertexShader().c_str(),
          vtkMRGIShaderUtilities::FullScreenShader(body.c_str()).c_str(), "");
      }
      else
      {
        window->GetShaderCache()->ReadyShaderProgram(quad->Program);
      }
      return (quad->Program && quad->Program->GetCompiled()) ? quad->Program : nullptr;
    };
    vtkShaderProgram* rowsProgram = ready(this->Internal->RowsQuad, "0");
    vtkShaderProgram* program = ready(this->Internal->GridQuad, "1");
    if (!rowsProgram || !program)
    {
      vtkErrorMacro("could not build the VPL selection shader");
      return this->Internal->Count = 0;
    }
    int maxSide = 1;
    for (const Block& block : blocks)
    {
      maxSide = std::max(maxSide, block.GridSide);
    }
    for (vtkTextureObject** t : { &this->Internal->RowSums, &this->Internal->RowBest })
    {
      if (!*t)
      {
        *t = vtkTextureObject::New();
        (*t)->SetContext(window);
        (*t)->SetFormat(GL_RGBA);
        (*t)->SetInternalFormat(GL_RGBA32F);
        (*t)->SetDataType(GL_FLOAT);
        (*t)->SetMinificationFilter(vtkTextureObject::Nearest);
        (*t)->SetMagnificationFilter(vtkTextureObject::Nearest);
        (*t)->Allocate2D(maxSide, size, 4, VTK_FLOAT);
        vtkMRGIResourceStatistics::RecordTextureAllocation(maxSide, size, 16);
      }
      vtkMRGIShaderUtilities::ResizeTexture(*t, maxSide, size);
    }
    vtkTextureObject* rowSums = this->Internal->RowSums;
    vtkTextureObject* rowBest = this->Internal->RowBest;
    if (!this->Internal->FrameBuffer)
    {
      this->Internal->FrameBuffer = vtkOpenGLFramebufferObject::New();
      this->Internal->FrameBuffer->SetContext(window);
    }
    vtkOpenGLState* ostate = window->GetState();
    vtkOpenGLState::ScopedglEnableDisable blend(ostate, GL_BLEND);
    vtkOpenGLState::ScopedglEnableDisable depth(ostate, GL_DEPTH_TEST);
    vtkOpenGLState::ScopedglEnableDisable scissor(ostate, GL_SCISSOR_TEST);
    vtkOpenGLState::ScopedglViewport viewport(ostate);
    ostate->vtkglDisable(GL_BLEND);
    ostate->vtkglDisable(GL_DEPTH_TEST);
    ostate->vtkglDisable(GL_SCISSOR_TEST);
    vtkOpenGLFramebufferObject* fbo = this->Internal->FrameBuffer;
    fbo->SaveCurrentBindingsAndBuffers();
    fbo->Bind();
    for (const Block& block : blocks)
    {
      const std::vector<int>& v = lightViews[block.Light];
      for (size_t i = 0; i < v.size(); ++i)
      {
        const int first = block.FirstRow + static_cast<int>(i) * block.GridSide * block.GridSide;
        vtkTextureObject* position = rsm->GetPositionTexture(v[i]);
        vtkTextureObject* normal = rsm->GetNormalTexture(v[i]);
        vtkTextureObject* flux = rsm->GetFluxTexture(v[i]);
        position->Activate();
        normal->Activate();
        flux->Activate();

        // Stage 0: one fragment per (block column, RSM row).
        window->GetShaderCache()->ReadyShaderProgram(rowsProgram);
        fbo->AddColorAttachment(0, rowSums);
        fbo->AddColorAttachment(1, rowBest);
        vtkMRGIShaderUtilities::SelectDrawBuffers(fbo, 2);
        rowsProgram->SetUniformi("mrgiRSMPosition", position->GetTextureUnit());
        rowsProgram->SetUniformi("mrgiRSMNormal", normal->GetTextureUnit());
        rowsProgram->SetUniformi("mrgiRSMFlux", flux->GetTextureUnit());
        rowsProgram->SetUniformi("mrgiRSMSize", size);
        rowsProgram->SetUniformi("mrgiGridSide", block.GridSide);
        ostate->vtkglViewport(0, 0, block.GridSide, size);
        this->Internal->RowsQuad->Render();

        // Stage 1: one fragment per VPL texel.
        fbo->RemoveColorAttachments(2);
        fbo->AddColorAttachment(0, texture);
        vtkMRGIShaderUtilities::SelectDrawBuffers(fbo, 1);
        window->GetShaderCache()->ReadyShaderProgram(program);
        rowSums->Activate();
        rowBest->Activate();
        program->SetUniformi("mrgiRSMPosition", position->GetTextureUnit());
        program->SetUniformi("mrgiRSMNormal", normal->GetTextureUnit());
        program->SetUniformi("mrgiRowSums", rowSums->GetTextureUnit());
        program->SetUniformi("mrgiRowBest", rowBest->GetTextureUnit());
        program->SetUniformi("mrgiRSMSize", size);
        program->SetUniformi("mrgiGridSide", block.GridSide);
        program->SetUniformi("mrgiFirstVPL", first);
        ostate->vtkglViewport(0, first, MRGI_VPL_TEXELS, block.GridSide * block.GridSide);
        this->Internal->GridQuad->Render();
        rowBest->Deactivate();
        rowSums->Deactivate();
        fbo->RemoveColorAttachments(1);
        flux->Deactivate();
        normal->Deactivate();
        position->Deactivate();
      }
    }
    fbo->UnBind();
    fbo->RestorePreviousBindingsAndBuffers();
  }

  this->Internal->Count = rows;
  this->Internal->SourceTime = rsm->GetContentTime();
  this->Internal->SettingsTime = this->GetMTime();
  this->Internal->SourceViewStamp = this->Internal->ViewStamp;
  ++this->NumberOfSelections;
  return rows;
}

//------------------------------------------------------------------------------
void vtkMRGIVPLSelection::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  static const char* const modes[] = { "Grid", "FluxImportance", "Clusters", "Tree", "BRSM" };
  os << indent << "Mode: " << modes[this->Mode] << "\n";
  os << indent << "ClusterDepthThreshold: " << this->ClusterDepthThreshold << "\n";
  os << indent << "ClusterNormalThreshold: " << this->ClusterNormalThreshold << "\n";
  os << indent << "ClusterFinestLevel: " << this->ClusterFinestLevel << "\n";
  os << indent << "ClusterRefinementsCapped: " << this->ClusterRefinementsCapped << "\n";
  os << indent << "TreeThreshold: " << this->TreeThreshold << "\n";
  os << indent << "BRSMFluxShare: " << this->BRSMFluxShare << "\n";
  os << indent << "BRSMSamplesPerTexel: " << this->BRSMSamplesPerTexel << "\n";
  os << indent << "BRSMBlur: " << this->BRSMBlur << "\n";
  os << indent << "BRSMInterTexel: " << this->BRSMInterTexel << "\n";
  os << indent << "BRSMTemporalWeight: " << this->BRSMTemporalWeight << "\n";
  os << indent << "NumberOfViewSamples: " << this->GetNumberOfViewSamples() << "\n";
  os << indent << "NumberOfTreeNodes: " << this->GetNumberOfTreeNodes() << "\n";
  os << indent << "NumberOfVPLs: " << this->NumberOfVPLs << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "VPLCount: " << this->Internal->Count << "\n";
  os << indent << "NumberOfSelections: " << this->NumberOfSelections << "\n";
}

//------------------------------------------------------------------------------
int vtkMRGIVPLSelection::Update(vtkOpenGLRenderWindow* window,
  vtkMRGIReflectiveShadowMapPass* rsm, const vtkMRGIFrameContext& frame,
  vtkMRGIViewSamples* shared)
{
  if (this->Mode == BRSM && frame.Position)
  {
    this->UpdateViewSamples(frame, shared ? *shared : this->Internal->OwnSamples);
  }
  return this->Update(window, rsm);
}

//------------------------------------------------------------------------------
void vtkMRGIVPLSelection::UpdateViewSamples(
  const vtkMRGIFrameContext& frame, vtkMRGIViewSamples& samples)
{
  // A fixed jitter (from Seed, not the frame): the same G-buffer gives the
  // same samples, hence the same VPLs (no temporal noise).
  std::string error;
  Internals& in = *this->Internal;
  if (!samples.Update(frame, vtkMRGIViewSamples::Surfaces, this->Seed ^ 0x5851F42D4C957F2Dull, error))
  {
    vtkErrorMacro(<< error << "; BRSM falls back to flux importance");
    if (!in.View.Samples.empty() || in.ViewSource)
    {
      ++in.ViewStamp; // samples lost: flux importance from now on
    }
    in.View = vtkMRGIBRSM::ViewSamples();
    in.ViewSource = nullptr;
    return;
  }
  if (in.ViewSource != &samples || in.ViewSourceStamp != samples.GetContentStamp())
  {
    in.View = samples.GetSurfaces();
    in.ViewSource = &samples;
    in.ViewSourceStamp = samples.GetContentStamp();
    ++in.ViewStamp; // new samples: the cache is stale in BRSM mode
  }
}

//------------------------------------------------------------------------------
int vtkMRGIVPLSelection::GetNumberOfViewSamples() const
{
  return static_cast<int>(this->Internal->View.Samples.size() / MRGI_BRSM_VIEW_SAMPLE_FLOATS);
}
