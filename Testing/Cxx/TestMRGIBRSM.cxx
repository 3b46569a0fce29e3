// BRSM VPL sampling on the GPU (ritschel-et-al-2011 section 4.1; issue 13
// part 5): vtkMRGIBRSMInversion against its C twin (mrgi_brsm_cdf_float.h).
// 1. Random RSMs (1 and 6 views, random importance with zero runs, several
//    seeds and VPL counts): the GPU picks (texel x, stacked row r and the
//    fractions fx, fy, p) equal mrgi_brsm_cdf_float_invert()'s bit for bit
//    (mismatches counted, none allowed); the texel VPL records equal
//    mrgi_brsm_float_vpl()'s within 1e-6 relative (positions and normals
//    bit for bit).
// 2. The real RSM of the Cornell box's spot light (mrgiPassSceneFixture.h),
//    random importance: the same checks; then BRSM mode in the pass with
//    texel VPLs (BRSMInterTexel off, the GPU path): every VPL sits on a
//    usable RSM texel (position and normal bit for bit), flux finite >= 0.
// 3. Ties (integer weights, u W exactly on CDF values, u = 1): bit for bit.
//    Bad input: zero importance everywhere gives W = 0: the C twin picks
//    nothing and the GPU writes all-zero records (no NaN); a short CDF or
//    a bad count is refused with an error naming it, nothing drawn.
#include "mrgiPassSceneFixture.h"
#include "mrgiTestUtilities.h"

#include "vtkMRGIBRSMInversion.h"
#include "vtkMRGIVPLSelection.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include "mrgi_brsm_cdf_float.h"
#include "mrgi_brsm_importance.h"
#include "mrgi_vpl.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>
#include <string>
#include <vector>

namespace
{
std::vector<float> ReadTexture(vtkTextureObject* t)
{
  std::vector<float> rgba(4 * static_cast<size_t>(t->GetWidth()) * t->GetHeight(), 0.0f);
  t->Activate();
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glGetTexImage(GL_TEXTURE_2D, 0, GL_RGBA, GL_FLOAT, rgba.data());
  t->Deactivate();
  MRGI_TEST_CHECK(glGetError() == GL_NO_ERROR);
  return rgba;
}

vtkSmartPointer<vtkTextureObject> FloatTexture(vtkOpenGLRenderWindow* gl, int w, int h, const float* data)
{
  auto t = vtkSmartPointer<vtkTextureObject>::New();
  t->SetContext(gl);
  t->SetInternalFormat(GL_RGBA32F);
  t->SetFormat(GL_RGBA);
  t->SetDataType(GL_FLOAT);
  t->SetMinificationFilter(vtkTextureObject::Nearest);
  t->SetMagnificationFilter(vtkTextureObject::Nearest);
  MRGI_TEST_CHECK(t->Create2DFromRaw(static_cast<unsigned int>(w), static_cast<unsigned int>(h), 4,
    VTK_FLOAT, const_cast<float*>(data)));
  return t;
}

/** Random weights: zero runs (whole columns and stretches), exact ties, a wide range. */
std::vector<float> RandomWeights(size_t n, std::mt19937& rng)
{
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<float> w(n);
  for (size_t i = 0; i < n; ++i)
  {
    const float r = u(rng);
    w[i] = r < 0.3f ? 0.0f : (r < 0.4f ? 1.0f : std::pow(10.0f, 4.0f * u(rng) - 2.0f));
  }
  return w;
}

struct Counts
{
  size_t Picks = 0, PickMismatches = 0, RecordMismatches = 0;
};

/** Run the GPU inversion on `views` for `weights` and compare with the C twin. */
void Compare(vtkOpenGLRenderWindow* gl, const mrgi_rsm& rsm,
  const std::vector<vtkMRGIBRSMInversion::View>& views, const std::vector<float>& weights,
  int count, uint64_t seed, Counts& counts, const std::vector<float>* given = nullptr)
{
  mrgi_error err;
  std::vector<double> cdf(mrgi_brsm_cdf_count(&rsm));
  MRGI_TEST_CHECK(mrgi_brsm_cdf_build(&rsm, weights.data(), weights.size(), cdf.data(), cdf.size(),
                    nullptr, &err) == MRGI_OK);
  std::vector<float> fcdf(mrgi_brsm_cdf_float_count(&rsm)), samples(2 * static_cast<size_t>(count));
  MRGI_TEST_CHECK(mrgi_brsm_cdf_to_float(&rsm, cdf.data(), cdf.size(), fcdf.data(), fcdf.size(),
                    &err) == MRGI_OK);
  MRGI_TEST_CHECK(
    mrgi_brsm_sample_values(count, seed, samples.data(), samples.size(), &err) == MRGI_OK);
  if (given)
  {
    samples = *given;
  }

  const int first = 3; // not row 0: the row offset is exercised
  std::vector<float> zeros(4 * MRGI_VPL_TEXELS * static_cast<size_t>(count + first + 2), -7.0f);
  vtkSmartPointer<vtkTextureObject> target = FloatTexture(gl, MRGI_VPL_TEXELS, count + first + 2, zeros.data());
  vtkNew<vtkMRGIBRSMInversion> inversion;
  std::string error;
  inversion->WritePicksOn();
  MRGI_TEST_CHECK(inversion->Invert(gl, rsm.size, views, fcdf, samples, count, target, first, error));
  const std::vector<float> picks = ReadTexture(target);
  inversion->WritePicksOff();
  MRGI_TEST_CHECK(inversion->Invert(gl, rsm.size, views, fcdf, samples, count, target, first, error));
  const std::vector<float> records = ReadTexture(target);
  inversion->ReleaseGraphicsResources(gl);

  const int S = rsm.size;
  for (int k = 0; k < count; ++k)
  {
    mrgi_brsm_pick pick = { 0, 0, 0, 0.0f, 0.0f, 0.0f };
    const int picked = mrgi_brsm_cdf_float_invert(&rsm, fcdf.data(), samples[2 * k], samples[2 * k + 1], &pick);
    const float* g = picks.data() + 4 * MRGI_VPL_TEXELS * static_cast<size_t>(first + k);
    const float want[6] = { static_cast<float>(pick.x), static_cast<float>(pick.view * S + pick.y),
      pick.fx, pick.fy, pick.pdf, static_cast<float>(picked) };
    const float got[6] = { g[0], g[1], g[2], g[3], g[4], g[5] };
    ++counts.Picks;
    if (std::memcmp(want, got, sizeof(want)) != 0)
    {
      if (counts.PickMismatches < 5)
      {
        std::printf("pick %d: C (%g %g %.9g %.9g p %.9g %g) GPU (%g %g %.9g %.9g p %.9g %g)\n", k,
          want[0], want[1], want[2], want[3], want[4], want[5], got[0], got[1], got[2], got[3],
          got[4], got[5]);
      }
      ++counts.PickMismatches;
    }
    mrgi_vpl twin;
    if (picked)
    {
      mrgi_brsm_float_vpl(&rsm, &pick, count, &twin);
    }
    else
    {
      std::memset(&twin, 0, sizeof(twin));
    }
    const float* r = records.data() + 4 * MRGI_VPL_TEXELS * static_cast<size_t>(first + k);
    const float* t = mrgi_vpl_texture_data(&twin);
    bool same = true;
    for (int i = 0; i < 4 * MRGI_VPL_TEXELS; ++i)
    {
      MRGI_TEST_CHECK(std::isfinite(r[i]));
      const bool exact = i < 3 || (i >= 4 && i < 8); // position xyz, normal xyzw
      const float tolerance = exact ? 0.0f : 1e-6f * std::fabs(t[i]);
      same = same && std::fabs(r[i] - t[i]) <= tolerance;
    }
    counts.RecordMismatches += same ? 0 : 1;
  }
  // Rows outside first..first+count-1 untouched.
  for (int row : { 0, first - 1, first + count, first + count + 1 })
  {
    MRGI_TEST_CHECK(records[4 * MRGI_VPL_TEXELS * static_cast<size_t>(row)] == -7.0f);
  }
}

void RandomRSMs()
{
  mrgitest::SceneWindow scene(32, 32, "cornell-spot");
  scene.Window->Render(); // a context
  vtkOpenGLRenderWindow* gl = vtkOpenGLRenderWindow::SafeDownCast(scene.Window);
  std::mt19937 rng(1234);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  Counts counts;
  for (int V : { 1, 6 })
  {
    const int S = V == 1 ? 32 : 12;
    const size_t texels = static_cast<size_t>(V) * S * S;
    std::vector<float> position(4 * texels), normal(4 * texels), flux(4 * texels);
    for (size_t t = 0; t < texels; ++t)
    {
      for (int k = 0; k < 3; ++k)
      {
        position[4 * t + k] = u(rng);
        normal[4 * t + k] = u(rng);
        flux[4 * t + k] = 0.5f + 0.5f * u(rng);
      }
      position[4 * t + 3] = u(rng) > -0.8f ? 1.0f : 0.0f; // 10% invalid
      normal[4 * t + 3] = 0.0f;
      flux[4 * t + 3] = 0.01f + 0.005f * u(rng);
    }
    std::vector<vtkSmartPointer<vtkTextureObject>> keep;
    std::vector<vtkMRGIBRSMInversion::View> views;
    for (int v = 0; v < V; ++v)
    {
      const size_t o = 4 * static_cast<size_t>(v) * S * S;
      vtkMRGIBRSMInversion::View view;
      keep.push_back(FloatTexture(gl, S, S, position.data() + o));
      view.Position = keep.back();
      keep.push_back(FloatTexture(gl, S, S, normal.data() + o));
      view.Normal = keep.back();
      keep.push_back(FloatTexture(gl, S, S, flux.data() + o));
      view.Flux = keep.back();
      views.push_back(view);
    }
    const mrgi_rsm rsm = { S, V, position.data(), normal.data(), flux.data() };
    for (int count : { 1, 37, 256 })
    {
      for (uint64_t seed : { 1ull, 99ull })
      {
        Compare(gl, rsm, views, RandomWeights(texels, rng), count, seed, counts);
      }
    }
  }
  std::printf("random RSMs: %zu picks, %zu pick mismatches, %zu record mismatches\n", counts.Picks,
    counts.PickMismatches, counts.RecordMismatches);
  MRGI_TEST_CHECK(counts.Picks > 1000);
  MRGI_TEST_CHECK(counts.PickMismatches == 0);
  MRGI_TEST_CHECK(counts.RecordMismatches == 0);
}

void CornellRSM()
{
  mrgitest::PassScene scene(48, 40, "cornell-spot");
  vtkMRGIPass* pass = scene.Pass;
  pass->SetIndirectMode(vtkMRGIPass::IndirectFull);
  pass->SetNumberOfVPLs(64);
  pass->SetRSMResolution(32);
  pass->SetVPLSelectionMode(vtkMRGIVPLSelection::BRSM);
  pass->GetVPLSelection()->SetBRSMInterTexel(false);
  scene.Window->Render();
  vtkOpenGLRenderWindow* gl = vtkOpenGLRenderWindow::SafeDownCast(scene.Window);
  mrgitest::SpotRSMView rsm(pass, scene.Window);
  vtkMRGIReflectiveShadowMapPass* maps = pass->GetReflectiveShadowMapPass();
  vtkMRGIBRSMInversion::View view;
  view.Position = maps->GetPositionTexture(0);
  view.Normal = maps->GetNormalTexture(0);
  view.Flux = maps->GetFluxTexture(0);
  std::mt19937 rng(77);
  Counts counts;
  const size_t texels = static_cast<size_t>(rsm.Map.size) * rsm.Map.size;
  for (uint64_t seed : { 3ull, 4ull, 5ull })
  {
    Compare(gl, rsm.Map, { view }, RandomWeights(texels, rng), 200, seed, counts);
  }
  // Flux importance (the weights BRSM mode has without view samples).
  std::vector<float> weights(texels, 0.0f);
  mrgi_error err;
  MRGI_TEST_CHECK(mrgi_brsm_mix(&rsm.Map, 1.0, weights.data(), texels, &err) == MRGI_OK);
  Compare(gl, rsm.Map, { view }, weights, 256, 11u, counts);
  std::printf("Cornell RSM: %zu picks, %zu pick mismatches, %zu record mismatches\n", counts.Picks,
    counts.PickMismatches, counts.RecordMismatches);
  MRGI_TEST_CHECK(counts.PickMismatches == 0);
  MRGI_TEST_CHECK(counts.RecordMismatches == 0);

  // BRSM mode (texel VPLs: the GPU path) in the pass.
  const std::vector<mrgi_vpl> vpls = mrgitest::ReadVPLs(pass, scene.Window);
  MRGI_TEST_CHECK(vpls.size() == 64);
  int onTexel = 0, lit = 0;
  for (const mrgi_vpl& v : vpls)
  {
    for (int k = 0; k < 3; ++k)
    {
      MRGI_TEST_CHECK(std::isfinite(v.flux[k]) && v.flux[k] >= 0.0f);
    }
    lit += v.flux[0] + v.flux[1] + v.flux[2] > 0.0f;
    for (size_t t = 0; t < texels; ++t)
    {
      if (mrgi_rsm_texel_usable(&rsm.Map, static_cast<int64_t>(t)) &&
        std::memcmp(v.position, rsm.Map.position + 4 * t, sizeof(v.position)) == 0 &&
        std::memcmp(v.normal, rsm.Map.normal + 4 * t, sizeof(v.normal)) == 0)
      {
        ++onTexel;
        break;
      }
    }
  }
  std::printf("BRSM mode: %d of 64 VPLs on a usable texel, %d lit\n", onTexel, lit);
  MRGI_TEST_CHECK(onTexel == 64);
  MRGI_TEST_CHECK(lit > 32);
}

void BadInput()
{
  mrgitest::SceneWindow scene(32, 32, "cornell-spot");
  scene.Window->Render();
  vtkOpenGLRenderWindow* gl = vtkOpenGLRenderWindow::SafeDownCast(scene.Window);
  const int S = 8, count = 16;
  std::vector<float> data(4 * S * S, 1.0f);
  vtkSmartPointer<vtkTextureObject> map = FloatTexture(gl, S, S, data.data());
  const std::vector<vtkMRGIBRSMInversion::View> views = { { map, map, map } };
  const mrgi_rsm rsm = { S, 1, data.data(), data.data(), data.data() };
  Counts counts;
  Compare(gl, rsm, views, std::vector<float>(S * S, 0.0f), count, 5u, counts);
  MRGI_TEST_CHECK(counts.PickMismatches == 0 && counts.RecordMismatches == 0);
  // Ties: integer weights (zero columns and rows among them) and samples
  // with u W exactly on CDF values: "first c > t" must not become ">=".
  std::vector<float> weights(S * S, 1.0f), tied;
  for (int t = 0; t < S * S; ++t)
  {
    // Column 2 and row 5 zero, row 0 and column 0 doubled: column totals 16
    // and 8, W = 64, so u = j / 8 and i / 8 land exactly on CDF entries.
    const int x = t % S, y = t / S;
    weights[static_cast<size_t>(t)] =
      (x == 2 || y == 5) ? 0.0f : (y == 0 ? 2.0f : 1.0f) * (x == 0 ? 2.0f : 1.0f);
  }
  for (int j = 0; j <= S; ++j)
  {
    for (int i = 0; i < S; ++i)
    {
      tied.push_back(static_cast<float>(j) / S);
      tied.push_back(static_cast<float>(i) / S);
    }
  }
  const int tiedCount = static_cast<int>(tied.size() / 2);
  Compare(gl, rsm, views, weights, tiedCount, 1u, counts, &tied);
  std::printf("ties: %zu picks, %zu pick mismatches, %zu record mismatches\n", counts.Picks,
    counts.PickMismatches, counts.RecordMismatches);
  MRGI_TEST_CHECK(counts.PickMismatches == 0 && counts.RecordMismatches == 0);
  mrgi_brsm_pick pick;
  std::vector<float> zero(mrgi_brsm_cdf_float_count(&rsm), 0.0f);
  MRGI_TEST_CHECK(mrgi_brsm_cdf_float_invert(&rsm, zero.data(), 0.5f, 0.5f, &pick) == 0);

  std::vector<float> samples(2 * count, 0.5f), fill(4 * MRGI_VPL_TEXELS * count, -7.0f);
  vtkSmartPointer<vtkTextureObject> target = FloatTexture(gl, MRGI_VPL_TEXELS, count, fill.data());
  vtkNew<vtkMRGIBRSMInversion> inversion;
  std::string error;
  MRGI_TEST_CHECK(!inversion->Invert(gl, S, views, std::vector<float>(5, 1.0f), samples, count,
    target, 0, error));
  std::printf("short CDF: %s\n", error.c_str());
  MRGI_TEST_CHECK(error.find("float CDF") != std::string::npos);
  MRGI_TEST_CHECK(!inversion->Invert(gl, S, views, zero, samples, count + 1, target, 0, error));
  std::printf("bad count: %s\n", error.c_str());
  MRGI_TEST_CHECK(error.find("sample values") != std::string::npos);
  MRGI_TEST_CHECK(!inversion->Invert(gl, S, views, zero, samples, count, target, 1, error));
  std::printf("rows: %s\n", error.c_str());
  MRGI_TEST_CHECK(ReadTexture(target)[0] == -7.0f); // nothing drawn
  inversion->ReleaseGraphicsResources(gl);
  mrgi_error err;
  MRGI_TEST_CHECK(mrgi_brsm_sample_values(0, 1u, samples.data(), samples.size(), &err) != MRGI_OK);
  MRGI_TEST_CHECK(std::strstr(err.message, "count") != nullptr);
}
}

int main(int argc, char* argv[])
{
  return mrgitest::RunCases(argc, argv,
    { MRGI_TEST_CASE(RandomRSMs), MRGI_TEST_CASE(CornellRSM), MRGI_TEST_CASE(BadInput) });
}
