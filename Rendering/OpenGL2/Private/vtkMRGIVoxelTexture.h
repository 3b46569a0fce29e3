/**
 * @class   vtkMRGIVoxelTexture
 * @brief   Internal: vtkMRGIVoxelization's voxel buffer on the GPU, a
 *          GL_TEXTURE_3D of RGBA32UI with one depth layer per 128 slices
 *          (mrgi_voxel.h section 1), its layers as the render targets of one
 *          draw, and its read-back in the core's storage.
 *
 * A 3D texture, not a 2D array: vtkTextureObject allocates no array
 * textures, and ParaView's VTK asserts on such a target when it binds one.
 * Layer l is attached as draw buffer l of the bound draw framebuffer
 * (glFramebufferTextureLayer), so one voxelization draw writes every layer
 * (NPW10 3.3: more bits through more render targets); the march reads it as
 * a usampler3D. The GPU holds one image per layer, the core a pixel's 4 L
 * words together: Read() and Write() convert.
 *
 * GL objects live in the context current at Ensure(); the owner releases
 * them there (Release(window)) or forgets them when that context is gone
 * (Release(nullptr)). Not wrapped, not installed.
 */
#ifndef vtkMRGIVoxelTexture_h
#define vtkMRGIVoxelTexture_h

#include <string> // For std::string

class vtkOpenGLRenderWindow;
class vtkTextureObject;
class vtkTypeUInt32Array;
class vtkWindow;
struct mrgi_voxel_grid;

class vtkMRGIVoxelTexture
{
public:
  vtkMRGIVoxelTexture() = default;
  /** Forgets the texture without GL calls: release it first. */
  ~vtkMRGIVoxelTexture();

  /**
   * A width x height x layers texture in `window`'s current context:
   * the one held when its size matches, else a new one (the old one is
   * released). False, with `problem` naming the limit or the failure, for
   * more layers than the context draws into at once or a side beyond its
   * largest 3D texture; nothing is held then.
   */
  bool Ensure(vtkOpenGLRenderWindow* window, int width, int height, int layers,
    std::string& problem);

  /** Free the texture in `w`'s context (w current), or forget it when `w` is null. */
  void Release(vtkWindow* w);

  /** The texture (nearest filtering, clamped), or nullptr. */
  vtkTextureObject* GetTexture() const { return this->Texture; }

  /** Attach layer l as GL_COLOR_ATTACHMENT0 + l of the bound draw framebuffer, l < layers. */
  void AttachLayers() const;
  /** Detach what AttachLayers() attached. */
  void DetachLayers() const;

  /**
   * The texture's words in mrgi_voxel.h's storage for `grid` (its size and
   * layers): `voxels` gets S / 32 components and VW VH tuples. The
   * texture's context must be current. False, with `problem`, on a GL error.
   */
  bool Read(const mrgi_voxel_grid& grid, vtkTypeUInt32Array* voxels, std::string& problem) const;

  /** Replace the texture's words by `voxels` (Read()'s layout); false, with `problem`, on a GL error. */
  bool Write(const mrgi_voxel_grid& grid, vtkTypeUInt32Array* voxels, std::string& problem) const;

private:
  vtkTextureObject* Texture = nullptr;
  int Size[3] = { 0, 0, 0 }; // width, height, layers

  vtkMRGIVoxelTexture(const vtkMRGIVoxelTexture&) = delete;
  void operator=(const vtkMRGIVoxelTexture&) = delete;
};

#endif
