/**
 * @file    vtkMRGIFileReaders.h
 * @brief   Internal (MRGI::RenderingIO): the reader vtkMRGISceneBuilder
 *          uses for a data file, chosen by its extension, after the core's
 *          structure check of its format.
 *
 * .ply (mrgi_ply_check.h, vtkPLYReader), .obj (mrgi_obj_check.h,
 * vtkOBJReader), .stl (vtkSTLReader), .vtk (mrgi_vtk_check.h,
 * vtkGenericDataObjectReader), .vtp .vtu .vti .vts .vtr .vtm
 * (mrgi_xml_check.h, vtkXMLGenericDataObjectReader), .las and .laz
 * (vtkMRGILASReader, which refuses LAZ by its header), .pcd
 * (vtkMRGIPCDReader, where MRGI::RenderingPCL is built). glTF is not a
 * reader but an importer: IsGLTF() tells the builder to import it.
 * Not wrapped, not installed.
 */
#ifndef vtkMRGIFileReaders_h
#define vtkMRGIFileReaders_h

#include "vtkAlgorithm.h"    // For vtkSmartPointer<vtkAlgorithm>
#include "vtkSmartPointer.h" // For vtkSmartPointer

#include <string> // For std::string

namespace vtkMRGIFileReaders
{
/** Whether `path` ends with `extension` (case-insensitive, and longer than it). */
bool EndsWith(const std::string& path, const char* extension);

/** Whether `path` names a glTF file (.gltf, .glb). */
bool IsGLTF(const std::string& path);

/**
 * A reader for `path` with its file name set, or nullptr with `why` (a line
 * naming the file or quoting the format check, as the builder reports it):
 * an unknown extension, a file its format's structure check refuses, or
 * .pcd in a build without MRGI's PCL module. Does not read the file.
 */
vtkSmartPointer<vtkAlgorithm> MakeReader(const std::string& path, std::string& why);
}

#endif
