/**
 * @file vtkMRGIIndirectVisibility.h
 * @brief The visibility term of the VPL gathers (indirect shadows): none,
 *        imperfect shadow maps (ritschel-et-al-2011) or the screen-space
 *        voxels of the area lights (nichols-penmatsa-wyman-2010 3.3, fed
 *        the VPLs instead of area-light samples).
 *
 * vtkMRGIPass fills one per frame and passes it to the VPL gathers of
 * vtkMRGIGather (cache, full, stenciled and tree); a default-constructed
 * one (NoVisibility) gathers without visibility, as before. A plain struct:
 * nothing is owned, the stages never keep it.
 *
 * - ISMVisibility: `ISMAtlas` is the push-pulled depth atlas of
 *   vtkMRGIImperfectShadowMaps::Update() for THIS frame's VPL cache: tile l
 *   belongs to VPL l of the cache (for the tree gather: to root l, and every
 *   node of root l's subtree is tested with root l's tile, from root l's
 *   position; see vtkMRGIGather). Lookup: mrgi_ism_visibility.h.
 * - VoxelVisibility: `Voxels` was voxelized this frame from the G-buffer; every VPL
 *   term is weighted by the voxel march from the receiver to the VPL
 *   (mrgi_voxel_march.h), occluders the camera does not see are missed.
 *   C twins: mrgi_gather_full_visibility(), mrgi_vpl_tree_gather_visibility().
 *   The GPU gathers draw the VPLs (tree: roots) in batches that fit
 *   llvmpipe's loop budget (vtkMRGIGatherVisibility); splatting refuses it.
 *   Documentation: IndirectLight.md, "Indirect visibility".
 */
#ifndef vtkMRGIIndirectVisibility_h
#define vtkMRGIIndirectVisibility_h

#include "mrgi_ism_atlas.h"      // For mrgi_ism_atlas_layout
#include "mrgi_ism_visibility.h" // For mrgi_ism_lookup_params

class vtkMRGIVoxelization;
class vtkTextureObject;

struct vtkMRGIIndirectVisibility
{
  enum Modes
  {
    NoVisibility = 0,
    ISMVisibility = 1,
    VoxelVisibility = 2
  };
  int Mode = NoVisibility;

  ///@{
  /** ISM: the R32F atlas texture (mrgi_ism_atlas.h layout), its layout, the lookup parameters. */
  vtkTextureObject* ISMAtlas = nullptr;
  mrgi_ism_atlas_layout ISMLayout = { 0, 0, 0, 0, 0, 0 };
  mrgi_ism_lookup_params ISMLookup = { MRGI_ISM_DEFAULT_RELATIVE_BIAS, MRGI_ISM_DEFAULT_TEXEL_BIAS, 1,
    MRGI_ISM_DEFAULT_MAX_TEXEL_ANGLE };
  ///@}

  /** Voxels: voxelized this frame (the receivers' eye space). */
  vtkMRGIVoxelization* Voxels = nullptr;
};

#endif
