// MRGI visibility masks: bit helpers shared by the visibility pyramid
// (vtkMRGIVisibilityPyramidFS.glsl) and the incremental stencil
// (vtkMRGIIncrementalStencilFS.glsl). No main, no #version.

// mrgi_voxel_popcount(): SWAR (GLSL 1.50 has no bitCount).
uint mrgiVisPopcount(uint v)
{
  v = v - ((v >> 1u) & 0x55555555u);
  v = (v & 0x33333333u) + ((v >> 2u) & 0x33333333u);
  v = (v + (v >> 4u)) & 0x0F0F0F0Fu;
  return (v * 0x01010101u) >> 24u;
}
