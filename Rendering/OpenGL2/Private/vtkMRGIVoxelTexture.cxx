#include "vtk_glew.h"

#include "vtkMRGIVoxelTexture.h"

#include "vtkMRGIResourceStatistics.h"
#include "vtkMRGIShaderUtilities.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkTextureObject.h"
#include "vtkTypeUInt32Array.h"

#include "mrgi_voxel.h"

#include <algorithm>
#include <sstream>
#include <vector>

namespace
{
std::string GLErrorText(GLenum error)
{
  std::ostringstream text;
  text << "OpenGL error 0x" << std::hex << error;
  return text.str();
}
}

//------------------------------------------------------------------------------
vtkMRGIVoxelTexture::~vtkMRGIVoxelTexture()
{
  vtkMRGIShaderUtilities::ReleaseTexture(this->Texture, nullptr);
}

//------------------------------------------------------------------------------
bool vtkMRGIVoxelTexture::Ensure(
  vtkOpenGLRenderWindow* window, int width, int height, int layers, std::string& problem)
{
  if (this->Texture && this->Size[0] == width && this->Size[1] == height &&
    this->Size[2] == layers)
  {
    return true;
  }
  this->Release(window);
  GLint maxBuffers = 0, maxAttachments = 0, maxSize = 0;
  glGetIntegerv(GL_MAX_DRAW_BUFFERS, &maxBuffers);
  glGetIntegerv(GL_MAX_COLOR_ATTACHMENTS, &maxAttachments);
  glGetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &maxSize);
  if (layers > std::min(maxBuffers, maxAttachments))
  {
    problem = std::to_string(MRGI_VOXEL_LAYER_SLICES * layers) + " slices need " +
      std::to_string(layers) + " render targets, and this OpenGL draws into at most " +
      std::to_string(std::min(maxBuffers, maxAttachments)) +
      "; use fewer slices (SetNumberOfSlices)";
    return false;
  }
  if (width > maxSize || height > maxSize)
  {
    problem = "the " + std::to_string(width) + " x " + std::to_string(height) +
      " voxel buffer exceeds this OpenGL's largest 3D texture (" + std::to_string(maxSize) +
      " per side); use a smaller voxel size";
    return false;
  }
  vtkTextureObject* t = vtkTextureObject::New();
  t->SetContext(window);
  t->SetInternalFormat(GL_RGBA32UI);
  t->SetFormat(GL_RGBA_INTEGER);
  t->SetDataType(GL_UNSIGNED_INT);
  t->SetMinificationFilter(vtkTextureObject::Nearest);
  t->SetMagnificationFilter(vtkTextureObject::Nearest);
  t->SetWrapS(vtkTextureObject::ClampToEdge);
  t->SetWrapT(vtkTextureObject::ClampToEdge);
  t->SetWrapR(vtkTextureObject::ClampToEdge);
  if (!t->Allocate3D(static_cast<unsigned int>(width), static_cast<unsigned int>(height),
        static_cast<unsigned int>(layers), 4, VTK_UNSIGNED_INT))
  {
    problem = "could not allocate the " + std::to_string(width) + " x " + std::to_string(height) +
      " x " + std::to_string(layers) + " RGBA32UI voxel texture";
    t->Delete();
    return false;
  }
  this->Texture = t;
  this->Size[0] = width;
  this->Size[1] = height;
  this->Size[2] = layers;
  vtkMRGIResourceStatistics::RecordTextureAllocation(width, height, 16 * layers);
  return true;
}

//------------------------------------------------------------------------------
void vtkMRGIVoxelTexture::Release(vtkWindow* w)
{
  vtkMRGIShaderUtilities::ReleaseTexture(this->Texture, w);
  this->Size[0] = this->Size[1] = this->Size[2] = 0;
}

//------------------------------------------------------------------------------
void vtkMRGIVoxelTexture::AttachLayers() const
{
  // vtkOpenGLFramebufferObject attaches no layers of a 3D texture.
  for (int l = 0; l < this->Size[2]; ++l)
  {
    glFramebufferTextureLayer(GL_DRAW_FRAMEBUFFER, static_cast<GLenum>(GL_COLOR_ATTACHMENT0 + l),
      this->Texture->GetHandle(), 0, l);
  }
}

void vtkMRGIVoxelTexture::DetachLayers() const
{
  for (int l = 0; l < this->Size[2]; ++l)
  {
    glFramebufferTextureLayer(
      GL_DRAW_FRAMEBUFFER, static_cast<GLenum>(GL_COLOR_ATTACHMENT0 + l), 0, 0, 0);
  }
}

//------------------------------------------------------------------------------
bool vtkMRGIVoxelTexture::Read(
  const mrgi_voxel_grid& grid, vtkTypeUInt32Array* voxels, std::string& problem) const
{
  const int layers = mrgi_voxel_layers(&grid);
  const int words = mrgi_voxel_pixel_words(&grid);
  const size_t pixels = static_cast<size_t>(grid.width) * static_cast<size_t>(grid.height);
  std::vector<GLuint> texels(mrgi_voxel_buffer_words(&grid));
  // Every layer at once, layer after layer.
  this->Texture->Activate();
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glGetTexImage(GL_TEXTURE_3D, 0, GL_RGBA_INTEGER, GL_UNSIGNED_INT, texels.data());
  this->Texture->Deactivate();
  const GLenum error = glGetError();
  if (error != GL_NO_ERROR)
  {
    problem = GLErrorText(error);
    return false;
  }
  voxels->SetNumberOfComponents(words);
  voxels->SetNumberOfTuples(static_cast<vtkIdType>(pixels));
  vtkTypeUInt32* target = voxels->GetPointer(0);
  for (size_t p = 0; p < pixels; ++p)
  {
    for (int l = 0; l < layers; ++l)
    {
      const GLuint* texel =
        texels.data() + (static_cast<size_t>(l) * pixels + p) * MRGI_VOXEL_CHANNELS;
      std::copy(texel, texel + MRGI_VOXEL_CHANNELS, target + p * words + MRGI_VOXEL_CHANNELS * l);
    }
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkMRGIVoxelTexture::Write(
  const mrgi_voxel_grid& grid, vtkTypeUInt32Array* voxels, std::string& problem) const
{
  const int layers = mrgi_voxel_layers(&grid);
  const int words = mrgi_voxel_pixel_words(&grid);
  const size_t pixels = static_cast<size_t>(grid.width) * static_cast<size_t>(grid.height);
  // A pixel's layers together -> one image per layer.
  std::vector<GLuint> texels(pixels * static_cast<size_t>(words));
  const vtkTypeUInt32* source = voxels->GetPointer(0);
  for (size_t p = 0; p < pixels; ++p)
  {
    for (int l = 0; l < layers; ++l)
    {
      std::copy(source + p * words + MRGI_VOXEL_CHANNELS * l,
        source + p * words + MRGI_VOXEL_CHANNELS * (l + 1),
        texels.data() + (static_cast<size_t>(l) * pixels + p) * MRGI_VOXEL_CHANNELS);
    }
  }
  this->Texture->Activate();
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glTexSubImage3D(GL_TEXTURE_3D, 0, 0, 0, 0, grid.width, grid.height, layers, GL_RGBA_INTEGER,
    GL_UNSIGNED_INT, texels.data());
  this->Texture->Deactivate();
  const GLenum error = glGetError();
  if (error != GL_NO_ERROR)
  {
    problem = GLErrorText(error);
    return false;
  }
  return true;
}
