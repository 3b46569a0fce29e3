#include "vtkMRGIFileReaders.h"

#include "vtkGenericDataObjectReader.h"
#include "vtkMRGILASReader.h"
#include "vtkOBJReader.h"
#include "vtkPLYReader.h"
#include "vtkSTLReader.h"
#include "vtkXMLGenericDataObjectReader.h"

#include "mrgi_error.h"
#include "mrgi_obj_check.h"
#include "mrgi_ply_check.h"
#include "mrgi_vtk_check.h"
#include "mrgi_xml_check.h"

// PCD files are read by vtkMRGIPCDReader (MRGI::RenderingPCL overrides it
// with PCL's reader); until that class is in this tree, .pcd is refused with
// the same message its base class gives.
#if __has_include("vtkMRGIPCDReader.h")
#include "vtkMRGIPCDReader.h"
#define MRGI_HAVE_PCD_READER 1
#endif

#include <cstring>
#include <strings.h>

//------------------------------------------------------------------------------
bool vtkMRGIFileReaders::EndsWith(const std::string& path, const char* extension)
{
  const size_t e = std::strlen(extension);
  return path.size() > e && strcasecmp(path.c_str() + path.size() - e, extension) == 0;
}

//------------------------------------------------------------------------------
bool vtkMRGIFileReaders::IsGLTF(const std::string& path)
{
  return EndsWith(path, ".gltf") || EndsWith(path, ".glb");
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkAlgorithm> vtkMRGIFileReaders::MakeReader(
  const std::string& path, std::string& why)
{
  mrgi_error err;
  if (EndsWith(path, ".ply"))
  {
    // VTK's PLY reader crashes on some malformed headers and accepts
    // truncated bodies: check the structure first.
    if (mrgi_ply_check(path.c_str(), nullptr, &err) != MRGI_OK)
    {
      why = err.message;
      return nullptr;
    }
    auto r = vtkSmartPointer<vtkPLYReader>::New();
    r->SetFileName(path.c_str());
    return r;
  }
  if (EndsWith(path, ".obj"))
  {
    // VTK's OBJ reader indexes with the face indices unchecked.
    if (mrgi_obj_check(path.c_str(), nullptr, &err) != MRGI_OK)
    {
      why = err.message;
      return nullptr;
    }
    auto r = vtkSmartPointer<vtkOBJReader>::New();
    r->SetFileName(path.c_str());
    return r;
  }
  if (EndsWith(path, ".stl"))
  {
    auto r = vtkSmartPointer<vtkSTLReader>::New();
    r->SetFileName(path.c_str());
    return r;
  }
  if (EndsWith(path, ".vtk"))
  {
    // VTK's legacy readers trust declared counts, sizes and cell types.
    if (mrgi_vtk_check(path.c_str(), nullptr, &err) != MRGI_OK)
    {
      why = err.message;
      return nullptr;
    }
    auto r = vtkSmartPointer<vtkGenericDataObjectReader>::New();
    r->SetFileName(path.c_str());
    return r;
  }
  if (EndsWith(path, ".vtp") || EndsWith(path, ".vtu") || EndsWith(path, ".vti") ||
    EndsWith(path, ".vts") || EndsWith(path, ".vtr") || EndsWith(path, ".vtm"))
  {
    // VTK's XML readers allocate what the attributes declare.
    if (mrgi_xml_check(path.c_str(), &err) != MRGI_OK)
    {
      why = err.message;
      return nullptr;
    }
    auto r = vtkSmartPointer<vtkXMLGenericDataObjectReader>::New();
    r->SetFileName(path.c_str());
    return r;
  }
  if (EndsWith(path, ".las") || EndsWith(path, ".laz"))
  {
    // LAZ goes through the LAS reader too: the core recognizes compression
    // by the header (not the name) and says "compressed LAZ is not supported".
    auto r = vtkSmartPointer<vtkMRGILASReader>::New();
    r->SetFileName(path.c_str());
    return r;
  }
  if (EndsWith(path, ".pcd"))
  {
#ifdef MRGI_HAVE_PCD_READER
    vtkSmartPointer<vtkMRGIPCDReader> r;
    r.TakeReference(vtkMRGIPCDReader::New()); // the PCL override where MRGI::RenderingPCL is built
    r->SetFileName(path.c_str());
    return r;
#else
    why = "cannot read '" + path +
      "': reading PCD needs MRGI's PCL module (MRGI::RenderingPCL), which this build lacks";
    return nullptr;
#endif
  }
  why = "cannot read '" + path +
    "': unknown extension (known: .vtp .vtu .vti .vts .vtr .vtm .vtk .ply .obj .stl "
    ".gltf .glb .las .pcd)";
  return nullptr;
}
