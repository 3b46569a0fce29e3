/**
 * @file vtkMRGIViewSamples.h
 * @brief Internal: the view samples of one frame, read back from the
 *        G-buffer once and shared by the stages that need them: the
 *        adaptive imperfect shadow map points (RIHKS11 5.2, world
 *        positions) and BRSM importance (RIHKS11 4, position, normal,
 *        albedo). Not wrapped, not installed.
 *
 * vtkMRGIIndirectLight owns one and passes it to vtkMRGIVPLSelection and
 * vtkMRGIImperfectShadowMaps as an argument; a stage driven alone (tests)
 * uses one of its own.
 *
 * ## Cache
 * The samples depend on the G-buffer, which depends on the camera, the
 * viewport and the visible props. Update() keeps a key of those (the
 * viewport, eye -> world, the active camera's MTime, each visible prop's
 * redraw MTime, the G-buffer textures) and reads back only when the key
 * changed or the caller needs attachments not read yet. A hit reads
 * nothing (GetNumberOfReadBacks() counts the misses).
 *
 * ## Patterns (fixed, frame-independent)
 * - Positions: a regular grid of stride ceil(sqrt(w h / MaxPositions))
 *   pixels, at the cells' centres; valid samples only (<= MaxPositions).
 * - Surfaces (BRSM): SurfaceSide x SurfaceSide samples, one per cell of a
 *   regular grid, jittered inside its cell by mrgi_brsm_hash01(seed, .)
 *   (paper-specs 2.1). The jitter depends on the seed only, never on the
 *   frame: a static view gives the same samples every frame, and a moving
 *   one moves them with the surfaces (no temporal noise from re-jittering).
 *   Background pixels become invalid samples.
 */
#ifndef vtkMRGIViewSamples_h
#define vtkMRGIViewSamples_h

#include "vtkMRGIBRSM.h" // For vtkMRGIBRSM::ViewSamples

#include <cstdint> // For uint64_t
#include <string>  // For std::string
#include <vector>  // For std::vector

struct vtkMRGIFrameContext;

class vtkMRGIViewSamples
{
public:
  /** What a caller needs (flags). */
  enum Needs
  {
    Positions = 1, ///< world positions on the regular grid (adaptive ISM points)
    Surfaces = 2   ///< jittered position, normal, albedo samples (BRSM)
  };
  /** Most position samples (RIHKS11 5.2's "few thousand"). */
  static constexpr int MaxPositions = 4096;
  /** Side of the BRSM sample grid: MRGI_BRSM_MAX_VIEW_SAMPLES = 32 x 32. */
  static constexpr int SurfaceSide = 32;

  vtkMRGIViewSamples() = default;

  /**
   * Bring the samples up to date with `frame` for `needs`, the surface
   * pattern jittered by `seed` (ignored without Surfaces). Reads the G-buffer back only on a miss
   * (see the file comment). False, with `error`, when the G-buffer is
   * missing or cannot be read; the samples are then empty.
   */
  bool Update(const vtkMRGIFrameContext& frame, int needs, std::uint64_t seed, std::string& error);

  /** World xyz of the valid position samples (3 doubles each). */
  const std::vector<double>& GetPositions() const { return this->PositionSamples; }

  /** The BRSM samples and the camera's world -> clip for the guide. */
  const vtkMRGIBRSM::ViewSamples& GetSurfaces() const { return this->SurfaceSamples; }

  /** G-buffer read-backs so far (cache misses). */
  long long GetNumberOfReadBacks() const { return this->ReadBacks; }

  /** Bumped at every read-back: consumers key their caches on it. */
  long long GetContentStamp() const { return this->ReadBacks; }

  /** Forget the samples (the next Update() reads back). */
  void Invalidate();

private:
  std::vector<double> Key;
  int Held = 0; // the Needs read for Key
  std::uint64_t SurfaceSeed = 0;
  long long ReadBacks = 0;
  std::vector<double> PositionSamples;
  vtkMRGIBRSM::ViewSamples SurfaceSamples;
  std::vector<float> Position, Normal, Albedo; // read-back scratch, kept for reuse

  vtkMRGIViewSamples(const vtkMRGIViewSamples&) = delete;
  void operator=(const vtkMRGIViewSamples&) = delete;
};

#endif
