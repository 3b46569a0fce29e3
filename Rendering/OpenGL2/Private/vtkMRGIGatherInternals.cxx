#include "vtk_glew.h"

#include "vtkMRGIGatherInternals.h"

#include "vtkMRGIShaderUtilities.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkTextureObject.h"

#include "mrgi_multires.h"

//------------------------------------------------------------------------------
bool vtkMRGIGatherInternals::Prepare(vtkOpenGLRenderWindow* window, const mrgi_multires_layout& layout)
{
  if (this->FlatIrradiance &&
    (this->FlatIrradiance->GetWidth() != static_cast<unsigned int>(layout.total_width) ||
      this->FlatIrradiance->GetHeight() != static_cast<unsigned int>(layout.total_height)))
  {
    vtkMRGIShaderUtilities::ReleaseTexture(this->FlatIrradiance, window);
  }
  if (!this->FlatIrradiance)
  {
    this->FlatIrradiance =
      vtkMRGIShaderUtilities::NewTexture(window, GL_RGBA32F, layout.total_width, layout.total_height);
  }
  this->GL.Prepare(window);
  return this->FlatIrradiance != nullptr;
}

//------------------------------------------------------------------------------
void vtkMRGIGatherInternals::AllocateQueries(vtkWindow* w, int levels)
{
  if (this->Queries.size() != static_cast<size_t>(levels))
  {
    this->ReleaseQueries(w);
    this->Queries.resize(static_cast<size_t>(levels));
    glGenQueries(levels, this->Queries.data());
  }
}

//------------------------------------------------------------------------------
void vtkMRGIGatherInternals::ReadQueries(int finest, int levels)
{
  for (int i = 0; i < levels; ++i)
  {
    GLuint passed = 0;
    if (i >= finest)
    {
      glGetQueryObjectuiv(this->Queries[static_cast<size_t>(i)], GL_QUERY_RESULT, &passed);
    }
    this->GatheredTexels[static_cast<size_t>(i)] = static_cast<long long>(passed);
  }
}

//------------------------------------------------------------------------------
void vtkMRGIGatherInternals::ReleaseQueries(vtkWindow* w)
{
  if (w && !this->Queries.empty())
  {
    glDeleteQueries(static_cast<GLsizei>(this->Queries.size()), this->Queries.data());
  }
  this->Queries.clear();
}

//------------------------------------------------------------------------------
void vtkMRGIGatherInternals::ReleaseSplats(vtkWindow* w)
{
  if (w && this->SplatArray)
  {
    glDeleteVertexArrays(1, &this->SplatArray);
  }
  if (w && this->SplatBuffer)
  {
    glDeleteBuffers(1, &this->SplatBuffer);
  }
  this->SplatArray = this->SplatBuffer = 0;
}
