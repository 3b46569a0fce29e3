// mrgiRenderOptions: mrgi-render's command line. One table (OptionTable in
// mrgiRenderOptionTable.cxx) gives every option's names, value form, help text and handler;
// both the parser and `--help` are built from it.
//
// The command line is a contract users script against: options are only ever
// added, never renamed.
#ifndef mrgiRenderOptions_h
#define mrgiRenderOptions_h

#include "vtkMRGIPass.h"     // For the area-light defaults
#include "vtkSmartPointer.h" // For vtkSmartPointer

#include "mrgi_exposure.h" // For MRGI_EXPOSURE_KEY
#include "mrgi_ism_atlas.h" // For MRGI_ISM_DEFAULT_PUSH_PULL_LEVELS
#include "mrgi_reference.h" // For the ground truth's defaults
#include "mrgi_ssao.h"      // For MRGI_SSAO_DEFAULT_KERNEL_SIZE
#include "mrgi_ssgi.h"      // For MRGI_SSGI_DEFAULT_SAMPLES

#include <cmath>
#include <string>
#include <vector>

class vtkLight;
class vtkMRGIAreaLight;

namespace mrgirender
{
// Largest window side --aa ssaa:N may render (GL_MAX_TEXTURE_SIZE of
// llvmpipe and of common GPUs is 16384; MRGI's buffers are window-sized).
constexpr int MRGI_SSAA_MAX_SIDE = 16384;

// What the command line asks for; defaults as --help states them.
struct Options
{
  std::string Scene;
  std::vector<std::string> Outputs;
  bool Half = false;
  int Width = 512;
  int Height = 512;
  double Background[3] = { 0, 0, 0 };
  bool HasPosition = false, HasFocal = false, HasUp = false, HasAngle = false;
  double Position[3], Focal[3], Up[3], Angle = 30;
  bool AutoCamera = false;
  bool Parallel = false;
  std::vector<std::string> Lights;
  double LightIntensity = 1.0;
  bool HasLightIntensity = false;
  long long Triangles = 100000;
  long long Objects = 64;
  long long Seed = 1;
  bool Timings = false;
  long long Frames = 1;
  // Frame-budget tuner (vtkMRGIFrameBudget): 0 = off.
  double FrameBudget = 0.0;
  double ErrorBudget = 0.0;
  bool Calibrate = false;
  bool Interactive = false;
  std::string Backend; // empty: MRGI_BACKEND, else automatic
  bool Quiet = false;
  bool AllowEmpty = false;
  bool GI = true;
  bool Multires = true; // Balanced whenever indirect light is on
  long long Preset = 1;
  double SurfaceDetail = 0.0;
  bool SSAO = false;
  long long SSAOSamples = MRGI_SSAO_DEFAULT_KERNEL_SIZE;
  double SSAORadius = 0.5;
  bool HasSSAORadius = false; // else 2% of the scene's diagonal
  double SSAOBias = 0.01;
  bool HasSSAOBias = false; // else radius / 50
  bool SSAOBlur = false;
  bool SSGI = false;
  long long SSGISamples = MRGI_SSGI_DEFAULT_SAMPLES;
  double SSGIRadius = 0.5;
  bool HasSSGIRadius = false; // else 10% of the scene's diagonal
  bool SSAOMultires = false; // --ssao-resolution multires
  bool SSGIMultires = false; // --ssgi-resolution multires
  // --screen-space-preset (-1: none); a knob given explicitly overrides it.
  long long ScreenSpacePreset = -1;
  bool HasSSAOSamples = false, HasShadowKernel = false, HasSSGISamples = false;
  bool HasSSAOResolution = false, HasShadowResolution = false, HasSSGIResolution = false;
  // NaN / -1: not given, the preset's value stands.
  double DepthThreshold = std::nan("");
  double NormalThreshold = std::nan("");
  long long FinestLevel = -1;
  bool MaskUpsampling = false;
  bool Splatting = false;
  std::vector<std::string> AreaLights;
  bool AreaLightsOn = true;
  bool AreaLightTwoSided = false;
  long long AreaLightSamples = 256;
  int AreaLightVisibility = vtkMRGIPass::VisibilityIncremental;
  long long VoxelSize = 0; // 0: automatic (vtkMRGIVoxelization::AutomaticVoxelSize)
  int VoxelOffset = 0;     // vtkMRGIVoxelization::OffsetAlongRayMode
  int VoxelSlices = 0;     // vtkMRGIVoxelization::NumberOfSlices; 0: the pass's (256)
  bool AreaLightSpecular = true;
  int AreaLightSpecularResolution = vtkMRGIPass::SpecularFullResolution;
  bool VisibilityInterleave = false;
  bool IncrementalStencil = true;
  bool HasSpecular = false;
  double SpecularCoefficient = 0.0;
  double SpecularPower = 1.0;
  int DirectShadows = -1; // not given: soft with indirect light, off without
  long long ShadowKernel = MRGI_DIRECT_SHADOW_DEFAULT_SIDE;
  double ShadowLightRadius = 0.0; // 0: automatic
  bool ShadowMultires = false;    // --shadow-resolution multires
  long long VPLs = 256;
  int VPLSelection = 0; // vtkMRGIVPLSelection::SelectionMode (grid, importance, clusters, tree, brsm)
  double ClusterDepthThreshold = std::nan(""); // not given: the selection's default
  double ClusterNormalThreshold = std::nan("");
  double TreeThreshold = std::nan(""); // not given: MRGI_VPL_TREE_DEFAULT_THRESHOLD
  long long RSMSize = 256;
  int IndirectVisibility = 0;   // vtkMRGIIndirectLight::VisibilityModes (off, ism, voxel)
  int Refinement = -1;          // vtkMRGIIndirectLight::RefinementModes; -1: the pass's default
  double IlluminationThreshold = std::nan(""); // not given: the stage's default (0.1)
  int IlluminationMetric = -1;  // MRGI_INCREMENTAL_ILLUMINATION_*; -1: the stage's default
  long long ISMPointsPerVPL = 256;
  long long ISMTileSize = 32;
  int ISMPointMode = 2;         // vtkMRGIImperfectShadowMaps::PointModes (adaptive8)
  long long ISMLazyFrames = 8;
  double ISMBias = std::nan(""); // not given: MRGI_ISM_DEFAULT_RELATIVE_BIAS
  bool ISMFiltering = true;
  double ISMTexelBias = std::nan(""); // not given: MRGI_ISM_DEFAULT_TEXEL_BIAS
  double ISMMaxTexelAngle = std::nan(""); // not given: MRGI_ISM_DEFAULT_MAX_TEXEL_ANGLE
  long long ISMPushPullLevels = MRGI_ISM_DEFAULT_PUSH_PULL_LEVELS;
  double IndirectStrength = 1.0;
  bool IndirectOnly = false;
  bool ToneMapping = false;
  // --exposure: a fixed EV, or automatic (Reinhard's key value).
  bool AutoExposure = true;
  double Exposure = 0.0;
  double ExposureKey = MRGI_EXPOSURE_KEY;
  // --aa: off, fxaa, or supersampling by SSAAFactor per axis.
  enum AntiAliasingMode
  {
    AAOff = 0,
    AAFXAA = 1,
    AASSAA = 2
  };
  int AntiAliasing = AAFXAA;
  int SSAAFactor = 1;
  bool Reference = false;
  bool ReferenceVisibility = true;
  bool ReferenceShadows = true;
  int ReferencePixel = 0; // vtkMRGIReferenceRenderer::PixelFilterType
  double ReferenceError = MRGI_REFERENCE_DEFAULT_TARGET;
  double ReferencePercentile = MRGI_REFERENCE_DEFAULT_PERCENTILE;
  long long ReferencePasses = MRGI_REFERENCE_DEFAULT_MAX_PASSES;
  bool ReferenceProgress = false; // per-pass lines even when stderr is no terminal
  // Staging of data files (vtkMRGIStaging); built-in scenes are never staged.
  bool Stage = true;
  int StageUp = -1; // vtkMRGIStaging::UpAxis
  bool StageGround = true;
  int StageKeyLight = 1; // vtkMRGIStaging::KeyLightType
  double StageFill = 0.8;
  bool HasIso = false;
  double Iso = 0.0;
  std::string StagingOptions; // the staging options given, for a note when unused
};

// Parses argv into `o`; returns -1 to go on, else the exit code (0 after
// --help / --version, 2 with the error printed).
int ParseArguments(int argc, char* argv[], Options& o);

// Prints "mrgi-render: error: MESSAGE" and returns 2 (the usage exit code).
int Fail(const std::string& message);

// Whether `s` ends with `extension`, ignoring case.
bool EndsWith(const std::string& s, const char* extension);

// An --area-light / --light value into a light; false with `why` on error.
bool ParseAreaLight(const std::string& spec, vtkMRGIAreaLight* light, std::string& why);
bool ParseLight(const std::string& spec, vtkSmartPointer<vtkLight>& light, std::string& why);
}

#endif
