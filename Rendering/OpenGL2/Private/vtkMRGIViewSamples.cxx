#include "vtkMRGIViewSamples.h"

#include "vtkMRGIFrameContext.h"
#include "vtkMRGIShaderUtilities.h"

#include "vtkCamera.h"
#include "vtkMatrix4x4.h"
#include "vtkProp.h"
#include "vtkPropCollection.h"
#include "vtkRenderer.h"
#include "vtkTextureObject.h"

#include "mrgi_brsm_importance.h"
#include "mrgi_buffers.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

static_assert(vtkMRGIViewSamples::SurfaceSide * vtkMRGIViewSamples::SurfaceSide <=
    MRGI_BRSM_MAX_VIEW_SAMPLES,
  "the BRSM sample grid must fit MRGI_BRSM_MAX_VIEW_SAMPLES");

namespace
{
// What the G-buffer's content depends on (see the header's "Cache").
std::vector<double> FrameKey(const vtkMRGIFrameContext& frame)
{
  std::vector<double> key(frame.Viewport, frame.Viewport + 4);
  key.insert(key.end(), frame.ViewToWorldDouble, frame.ViewToWorldDouble + 16);
  for (vtkTextureObject* t : { frame.Position, frame.Normal, frame.Albedo })
  {
    key.push_back(t ? static_cast<double>(t->GetHandle()) : -1.0);
    key.push_back(t ? static_cast<double>(t->GetMTime()) : -1.0);
  }
  vtkRenderer* renderer = frame.Renderer;
  vtkCamera* camera = renderer ? renderer->GetActiveCamera() : nullptr;
  key.push_back(camera ? static_cast<double>(camera->GetMTime()) : -1.0);
  if (renderer)
  {
    vtkPropCollection* props = renderer->GetViewProps();
    vtkCollectionSimpleIterator it;
    props->InitTraversal(it);
    while (vtkProp* prop = props->GetNextProp(it))
    {
      if (prop->GetVisibility())
      {
        key.push_back(static_cast<double>(reinterpret_cast<std::uintptr_t>(prop)));
        key.push_back(static_cast<double>(prop->GetRedrawMTime()));
      }
    }
  }
  return key;
}

// Eye-space point or direction (w = 1 or 0) of pixel p to world space.
void ToWorld(const double* m, const float* p, double w, double out[3])
{
  for (int row = 0; row < 3; ++row)
  {
    out[row] = m[row] * p[0] + m[4 + row] * p[1] + m[8 + row] * p[2] + w * m[12 + row];
  }
}
}

//------------------------------------------------------------------------------
void vtkMRGIViewSamples::Invalidate()
{
  this->Key.clear();
  this->Held = 0;
  this->PositionSamples.clear();
  this->SurfaceSamples = vtkMRGIBRSM::ViewSamples();
}

//------------------------------------------------------------------------------
bool vtkMRGIViewSamples::Update(
  const vtkMRGIFrameContext& frame, int needs, std::uint64_t seed, std::string& error)
{
  const int w = frame.Viewport[2], h = frame.Viewport[3];
  const bool surfaces = (needs & Surfaces) != 0;
  if (!frame.Window || !frame.Position || (surfaces && (!frame.Normal || !frame.Albedo)) || w < 1 ||
    h < 1)
  {
    this->Invalidate();
    error = "view samples need the frame's G-buffer (position, and for BRSM normal and albedo)";
    return false;
  }
  std::vector<double> key = FrameKey(frame);
  const bool sameSeed = !surfaces || seed == this->SurfaceSeed;
  if (key == this->Key && (this->Held & needs) == needs && sameSeed)
  {
    return true; // the G-buffer's inputs did not change: nothing read
  }
  needs |= Positions | (key == this->Key && sameSeed ? this->Held : 0); // positions come free
  this->Invalidate();

  // One read-back of what is needed (positions always).
  const size_t pixels = static_cast<size_t>(w) * static_cast<size_t>(h) * 4;
  const int x0 = frame.Viewport[0], y0 = frame.Viewport[1];
  this->Position.resize(pixels);
  bool read = vtkMRGIShaderUtilities::ReadTextureRegion(
    frame.Window, frame.Position, x0, y0, w, h, 4, this->Position.data());
  if (read && (needs & Surfaces))
  {
    this->Normal.resize(pixels);
    this->Albedo.resize(pixels);
    read = vtkMRGIShaderUtilities::ReadTextureRegion(
             frame.Window, frame.Normal, x0, y0, w, h, 4, this->Normal.data()) &&
      vtkMRGIShaderUtilities::ReadTextureRegion(
        frame.Window, frame.Albedo, x0, y0, w, h, 4, this->Albedo.data());
  }
  ++this->ReadBacks;
  if (!read)
  {
    error = "cannot read the G-buffer back for the view samples";
    return false;
  }
  const double* m = frame.ViewToWorldDouble; // column-major eye -> world

  // Positions: the regular grid (RIHKS11 5.2).
  const int stride = std::max(
    1, static_cast<int>(std::ceil(std::sqrt(static_cast<double>(w) * h / MaxPositions))));
  for (int y = stride / 2; y < h; y += stride)
  {
    for (int x = stride / 2; x < w; x += stride)
    {
      const float* p = &this->Position[4 * (static_cast<size_t>(y) * w + x)];
      if (!(p[3] > MRGI_VALID_THRESHOLD) || !std::isfinite(p[0]) || !std::isfinite(p[1]) ||
        !std::isfinite(p[2]))
      {
        continue;
      }
      double world[3];
      ToWorld(m, p, 1.0, world);
      this->PositionSamples.insert(this->PositionSamples.end(), world, world + 3);
    }
  }

  // Surfaces: the fixed jittered grid (BRSM, RIHKS11 4).
  if (needs & Surfaces)
  {
    vtkMRGIBRSM::ViewSamples& out = this->SurfaceSamples;
    const int side = SurfaceSide;
    out.Samples.assign(static_cast<size_t>(side) * side * MRGI_BRSM_VIEW_SAMPLE_FLOATS, 0.0f);
    for (int j = 0; j < side; ++j)
    {
      for (int i = 0; i < side; ++i)
      {
        const std::uint64_t k = static_cast<std::uint64_t>(j) * side + i;
        const double px = (i + mrgi_brsm_hash01(seed, 2 * k)) * w / side;
        const double py = (j + mrgi_brsm_hash01(seed, 2 * k + 1)) * h / side;
        const int x = std::min(w - 1, static_cast<int>(px));
        const int y = std::min(h - 1, static_cast<int>(py));
        const size_t p = (static_cast<size_t>(y) * w + x) * 4;
        float* s = out.Samples.data() + k * MRGI_BRSM_VIEW_SAMPLE_FLOATS;
        double world[3], normal[3];
        ToWorld(m, &this->Position[p], 1.0, world);
        ToWorld(m, &this->Normal[p], 0.0, normal);
        for (int row = 0; row < 3; ++row)
        {
          s[row] = static_cast<float>(world[row]);
          s[4 + row] = static_cast<float>(normal[row]);
          s[8 + row] = this->Albedo[p + row];
        }
        s[3] = static_cast<float>(x + 0.5);
        s[7] = static_cast<float>(y + 0.5);
        s[11] = this->Position[p + 3] > MRGI_VALID_THRESHOLD ? 1.0f : 0.0f;
      }
    }
    vtkCamera* camera = frame.Renderer ? frame.Renderer->GetActiveCamera() : nullptr;
    if (camera)
    {
      vtkMatrix4x4* rowMajor = camera->GetCompositeProjectionTransformMatrix(
        static_cast<double>(w) / static_cast<double>(h), -1.0, 1.0);
      for (int row = 0; row < 4; ++row)
      {
        for (int col = 0; col < 4; ++col)
        {
          out.WorldToClip[col * 4 + row] = static_cast<float>(rowMajor->GetElement(row, col));
        }
      }
      out.HasCamera = true;
    }
    out.Width = w;
    out.Height = h;
  }
  this->Key.swap(key);
  this->Held = needs;
  this->SurfaceSeed = seed;
  return true;
}
