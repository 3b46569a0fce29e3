#include "vtkMRGIResourceStatistics.h"

#include "vtkObjectFactory.h"

#include <atomic>

vtkStandardNewMacro(vtkMRGIResourceStatistics);

namespace
{
// Process-wide on purpose: textures are allocated by stages that know no
// pass (vtkMRGIShaderUtilities, the G-buffer), and a count per window would
// need every stage to carry it.
std::atomic<vtkTypeInt64> TextureAllocations{ 0 };
std::atomic<vtkTypeInt64> TextureBytes{ 0 };
}

//------------------------------------------------------------------------------
vtkTypeInt64 vtkMRGIResourceStatistics::GetNumberOfTextureAllocations()
{
  return TextureAllocations.load();
}

//------------------------------------------------------------------------------
vtkTypeInt64 vtkMRGIResourceStatistics::GetTextureBytesAllocated()
{
  return TextureBytes.load();
}

//------------------------------------------------------------------------------
void vtkMRGIResourceStatistics::RecordTextureAllocation(int w, int h, int bytesPerTexel)
{
  ++TextureAllocations;
  if (w > 0 && h > 0 && bytesPerTexel > 0)
  {
    TextureBytes += static_cast<vtkTypeInt64>(w) * h * bytesPerTexel;
  }
}

//------------------------------------------------------------------------------
void vtkMRGIResourceStatistics::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "NumberOfTextureAllocations: " << GetNumberOfTextureAllocations() << "\n";
  os << indent << "TextureBytesAllocated: " << GetTextureBytesAllocated() << "\n";
}
