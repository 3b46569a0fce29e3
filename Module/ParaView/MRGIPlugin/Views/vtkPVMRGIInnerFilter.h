/**
 * @file    vtkPVMRGIInnerFilter.h
 * @brief   Internal: how the plugin's point-cloud proxies run MRGI's own
 *          filters (vtkMRGIPointCloudNormals, vtkMRGISurfels), which live
 *          in a module the plugin does not wrap for client-server.
 *
 * The inner filter gets a shallow copy of the input, so that it never
 * holds (or modifies) ParaView's pipeline object. On bad input the inner
 * filter reports the problem itself; its executive would add a second,
 * generic error ("returned failure"): an observer takes that one, so that
 * ParaView shows the useful message once. Not wrapped, not installed.
 */
#ifndef vtkPVMRGIInnerFilter_h
#define vtkPVMRGIInnerFilter_h

class vtkPolyData;
class vtkPolyDataAlgorithm;

namespace vtkPVMRGIInnerFilter
{
/** Run `inner` (configured) on a shallow copy of `input`; `output` shares its result. */
void Run(vtkPolyDataAlgorithm* inner, vtkPolyData* input, vtkPolyData* output);
}

#endif
