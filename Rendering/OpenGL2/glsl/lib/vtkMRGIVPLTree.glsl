// MRGI: the HISR VPL-tree traversal of one receiver (nichols-shopf-wyman-2009
// section 3.5), for the tree gather (vtkMRGIGatherFS.glsl with
// MRGI_GATHER_TREE). The contract, step by step, is
// mrgi_vpl_tree_gather.h section 2; its C twin mrgi_vpl_tree_gather()
// follows the same order. Needs vtkMRGIVPLIrradiance.glsl (the per-node term).
//
// The tree texture (mrgi_vpl_tree_gather.h section 3): record k's texel t
// at (MRGI_VPL_TEXELS * (k % MRGI_VPL_TREE_RECORDS_PER_ROW) + t,
// k / MRGI_VPL_TREE_RECORDS_PER_ROW); records coarse levels first
// (mrgi_vpl_tree.h section 2); R_P in the normal texel's w.
uniform sampler2D mrgiTreeNodes;
uniform int mrgiTreeRootFirst;  // global index of this batch's first root (view-major)
uniform int mrgiTreeRootCount;  // roots in this batch (mrgi_vpl_tree_roots_per_batch())
uniform int mrgiTreeLevels;     // L + 1: the roots are level L
uniform int mrgiTreeLevelFirst[MRGI_MULTIRES_MAX_LEVELS]; // first record of each level
uniform int mrgiTreeSide;       // T: level i is (T >> i) x (T >> i) nodes per view
uniform float mrgiTreeThreshold; // tau >= 0 (>= 1: the roots only)

vec4 mrgiTreeTexel(int k, int t)
{
  return texelFetch(mrgiTreeNodes, ivec2(MRGI_VPL_TEXELS * (k % MRGI_VPL_TREE_RECORDS_PER_ROW) + t,
    k / MRGI_VPL_TREE_RECORDS_PER_ROW), 0);
}

// E of this batch's roots at receiver (P, N) (world space), and the nodes
// used as VPLs. The depth-first order of the contract's explicit stack
// (children pop in scan order (2x, 2y), (2x+1, 2y), (2x, 2y+1),
// (2x+1, 2y+1)) follows from the quadtree's indexing alone, so the stack is
// implicit: after a node that is not refined, the next one is the next
// sibling of the nearest ancestor-or-self that is not a last child (bit j
// of x & y is set when the ancestor j levels up is one), or the next root.
// Same nodes, same order, same sums as a stack, without a per-invocation
// array (which llvmpipe keeps in memory). One loop iteration per node
// visited: at most mrgiTreeRootCount * N_sub, the batch's budget.
vec3 mrgiVPLTreeIrradiance(vec3 P, vec3 N, out int used)
{
  int rootLevel = mrgiTreeLevels - 1;
  int rootSide = mrgiTreeSide >> rootLevel;
  int root = mrgiTreeRootFirst; // global index r = (v * w_L + y) * w_L + x
  int rootEnd = mrgiTreeRootFirst + mrgiTreeRootCount;
  int level = rootLevel;
  int view = root / (rootSide * rootSide);
  int x = root % rootSide;
  int y = (root / rootSide) % rootSide;
  vec3 E = vec3(0.0);
  used = 0;
#ifdef MRGI_INDIRECT_ISM
  float rootVisibility = -1.0; // V of the current root at P; -1: not yet
#endif
  while (root < rootEnd)
  {
    int w = mrgiTreeSide >> level;
    int k = mrgiTreeLevelFirst[level] + (view * w + y) * w + x;
    bool refine = false;
    // 1. Zero flux: every descendant has zero flux too.
    vec4 flux = mrgiTreeTexel(k, MRGI_VPL_TEXEL_FLUX);
    if (flux.r != 0.0 || flux.g != 0.0 || flux.b != 0.0)
    {
      vec4 position = mrgiTreeTexel(k, MRGI_VPL_TEXEL_POSITION);
      vec4 normal = mrgiTreeTexel(k, MRGI_VPL_TEXEL_NORMAL);
      float radius = normal.w; // R_P
      vec3 d = position.xyz - P;
      // 2. The bounding sphere wholly behind the receiver's plane: exact cull.
      if (dot(N, d) + radius > 0.0)
      {
        // 3. Refine while the form-factor bound B_P = A_P / (pi d_min^2 + A_P)
        // exceeds tau (section 1; B_P = 0 for A_P = 0).
        float area = position.w;
        float dMin = max(0.0, length(d) - radius);
        float bound = area > 0.0 ? area / (MRGI_PI * dMin * dMin + area) : 0.0;
        refine = level > 0 && bound > mrgiTreeThreshold;
        if (!refine)
        {
          // 4. P as one VPL: the cache gather's term on its record.
#ifdef MRGI_INDIRECT_ISM
          // Weighted by root r's ISM (tile r), looked up from root r's
          // record: ISMs exist per root only (mrgi_vpl_tree_gather.h
          // section 4); computed once per root, at its first term > 0.
          vec3 term = mrgiVPLRecordIrradiance(position, normal.xyz, flux.rgb, P, N);
          if (term != vec3(0.0))
          {
            if (rootVisibility < 0.0)
            {
              int rk = mrgiTreeLevelFirst[rootLevel] + root;
              rootVisibility = mrgiISMVisibility(root, mrgiTreeTexel(rk, MRGI_VPL_TEXEL_POSITION).xyz,
                mrgiTreeTexel(rk, MRGI_VPL_TEXEL_NORMAL).xyz, P);
            }
            term *= rootVisibility;
          }
          E += term;
#elif defined(MRGI_INDIRECT_VOXELS)
          // One march per node used as a VPL, to the node's own position
          // and normal (mrgi_vpl_tree_gather.h section 4).
          vec3 term = mrgiVPLRecordIrradiance(position, normal.xyz, flux.rgb, P, N);
          if (term != vec3(0.0)) { term *= mrgiVPLVoxelVisibility(position.xyz, normal.xyz); }
          E += term;
#else
          E += mrgiVPLRecordIrradiance(position, normal.xyz, flux.rgb, P, N);
#endif
          ++used;
        }
      }
    }
    if (refine)
    {
      // The first child, (2x, 2y) one level down.
      --level;
      x *= 2;
      y *= 2;
      continue;
    }
    // Climb past the last children: `up` trailing ones of x & y (the
    // lowest zero bit of x & y isolated, then its exponent).
    int last = x & y;
    int up = int(log2(float((last + 1) & ~last)) + 0.5);
    if (up >= rootLevel - level)
    {
      // This root's subtree is done: the next root.
      ++root;
#ifdef MRGI_INDIRECT_ISM
      rootVisibility = -1.0;
#endif
      level = rootLevel;
      view = root / (rootSide * rootSide);
      x = root % rootSide;
      y = (root / rootSide) % rootSide;
      continue;
    }
    level += up;
    x >>= up;
    y >>= up;
    // The next sibling in scan order.
    if ((x & 1) == 0)
    {
      ++x;
    }
    else
    {
      --x;
      ++y;
    }
  }
  return E;
}
