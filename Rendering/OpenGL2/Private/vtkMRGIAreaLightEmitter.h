/**
 * @class   vtkMRGIAreaLightEmitter
 * @brief   Internal: what draws a vtkMRGIAreaLight's emitter: its actor, the
 *          quad and picture pipeline sources behind it, and the actors that
 *          share them.
 *
 * The light owns one (made on the first vtkMRGIAreaLight::GetGeometryActor())
 * and forwards GetGeometryActor() and ShareGeometryActor() here; their
 * documentation is the behaviour. The emitter does not know the light's
 * class: the light pushes its look (UpdateActor(), on every Modified()) and
 * answers two questions at render time (SetLight()), through functions that
 * hold it weakly. The light owns the emitter, while a renderer may keep the
 * actor after the light is gone: the actor then draws nothing.
 *
 * Behind the actor: a polydata source of the light's quad (the light's
 * MakeGeometry(), regenerated when the light's own properties change, not
 * when only its texture image does) and, for a textured light, an image
 * source of its display picture (vtkMRGIAreaLightUtilities::
 * EncodeDisplayPicture(), as an 8-bit sRGB vtkTexture, regenerated when the
 * light or its texture image changes: the next video frame). Not wrapped,
 * not installed.
 *
 * @sa vtkMRGIAreaLight
 */
#ifndef vtkMRGIAreaLightEmitter_h
#define vtkMRGIAreaLightEmitter_h

#include "vtkObject.h"

#include <functional> // For std::function
#include <memory>     // For std::unique_ptr

class vtkActor;
class vtkPolyData;
struct mrgi_image;

class vtkMRGIAreaLightEmitter : public vtkObject
{
public:
  static vtkMRGIAreaLightEmitter* New();
  vtkTypeMacro(vtkMRGIAreaLightEmitter, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /** The picture to show, with the light's radiance scale. */
  struct Picture
  {
    const mrgi_image* Image = nullptr; // the core's float RGB image; nullptr: none
    double Intensity = 0.0;
    double Color[3] = { 0.0, 0.0, 0.0 };
  };

  /** Fills the quad (false: an invalid light or no light, nothing drawn). */
  using QuadFunction = std::function<bool(vtkPolyData* quad)>;
  /** The picture of the light's texture (Image nullptr: none, or no light). */
  using PictureFunction = std::function<Picture()>;

  /**
   * The light (held weakly; vtkObject::GetMTime() of it drives the quad,
   * its own GetMTime(), which includes its texture image, the picture) and
   * how to ask it for its quad and picture. Set once, before GetActor().
   */
  void SetLight(vtkObject* light, QuadFunction quad, PictureFunction picture);

  /** The emitter's actor, made on the first call; UpdateActor() gives it the light's look. */
  vtkActor* GetActor();

  /** What UpdateActor() shows. */
  struct Look
  {
    bool Visible = true;
    bool Textured = false; // show the picture (else Intensity * Color)
    bool TwoSided = false;
    double Intensity = 1.0; // non-finite or negative values show as 0
    double Color[3] = { 1.0, 1.0, 1.0 };
  };

  /**
   * Bring the actor (made if needed) and the shared actors' texture in
   * step with the light's look: visibility, colour, texture, back face.
   */
  void UpdateActor(const Look& look);

  /** vtkMRGIAreaLight::ShareGeometryActor(): `actor` becomes a second view. */
  void ShareActor(vtkActor* actor);

  /**
   * The emitter quad of vtkMRGIAreaLight::MakeGeometry() for a checked
   * light (Center, full edges EdgeU and EdgeV): 4 corners counter-clockwise
   * seen from the emitting side, one polygon, point normals and texture
   * coordinates. Replaces what `quad` held.
   */
  static void MakeQuad(
    const double center[3], const double edgeU[3], const double edgeV[3], vtkPolyData* quad);

protected:
  vtkMRGIAreaLightEmitter();
  ~vtkMRGIAreaLightEmitter() override;

private:
  vtkMRGIAreaLightEmitter(const vtkMRGIAreaLightEmitter&) = delete;
  void operator=(const vtkMRGIAreaLightEmitter&) = delete;

  struct vtkInternals;
  std::unique_ptr<vtkInternals> Internals;
};

#endif
