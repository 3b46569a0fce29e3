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
// used as VPLs. One loop iteration per node popped: the loop runs at most
// mrgiTreeRootCount * N_sub times, the budget the batch was sized for (a
// stack entry is record * MRGI_MULTIRES_MAX_LEVELS + level).
vec3 mrgiVPLTreeIrradiance(vec3 P, vec3 N, out int used)
{
  int stack[MRGI_VPL_TREE_STACK_SIZE];
  int top = 0;
  int root = mrgiTreeRootFirst;
  int rootEnd = mrgiTreeRootFirst + mrgiTreeRootCount;
  int rootLevel = mrgiTreeLevels - 1;
  vec3 E = vec3(0.0);
  used = 0;
  while (top > 0 || root < rootEnd)
  {
    int entry;
    if (top > 0)
    {
      entry = stack[--top];
    }
    else
    {
      // Roots in increasing global index r = (v * w_L + y) * w_L + x.
      entry = (mrgiTreeLevelFirst[rootLevel] + root) * MRGI_MULTIRES_MAX_LEVELS + rootLevel;
      ++root;
    }
    int level = entry % MRGI_MULTIRES_MAX_LEVELS;
    int k = entry / MRGI_MULTIRES_MAX_LEVELS;
    // 1. Zero flux: every descendant has zero flux too.
    vec4 flux = mrgiTreeTexel(k, MRGI_VPL_TEXEL_FLUX);
    if (flux.r == 0.0 && flux.g == 0.0 && flux.b == 0.0)
    {
      continue;
    }
    vec4 position = mrgiTreeTexel(k, MRGI_VPL_TEXEL_POSITION);
    vec4 normal = mrgiTreeTexel(k, MRGI_VPL_TEXEL_NORMAL);
    float radius = normal.w; // R_P
    vec3 d = position.xyz - P;
    // 2. The bounding sphere wholly behind the receiver's plane: exact cull.
    if (dot(N, d) + radius <= 0.0)
    {
      continue;
    }
    // 3. Refine while the form-factor bound B_P = A_P / (pi d_min^2 + A_P)
    // exceeds tau (section 1; B_P = 0 for A_P = 0).
    if (level > 0)
    {
      float area = position.w;
      float dMin = max(0.0, length(d) - radius);
      float bound = area > 0.0 ? area / (MRGI_PI * dMin * dMin + area) : 0.0;
      if (bound > mrgiTreeThreshold)
      {
        // Children of (x, y) at level - 1, pushed so that (2x, 2y) pops first.
        int w = mrgiTreeSide >> level;
        int local = k - mrgiTreeLevelFirst[level];
        int view = local / (w * w);
        int y = (local / w) % w;
        int x = local % w;
        int cw = 2 * w;
        int child = level - 1;
        int base = mrgiTreeLevelFirst[child] + (view * cw + 2 * y) * cw + 2 * x;
        stack[top++] = (base + cw + 1) * MRGI_MULTIRES_MAX_LEVELS + child;
        stack[top++] = (base + cw) * MRGI_MULTIRES_MAX_LEVELS + child;
        stack[top++] = (base + 1) * MRGI_MULTIRES_MAX_LEVELS + child;
        stack[top++] = base * MRGI_MULTIRES_MAX_LEVELS + child;
        continue;
      }
    }
    // 4. P as one VPL: the cache gather's term on its record.
    E += mrgiVPLRecordIrradiance(position, normal.xyz, flux.rgb, P, N);
    ++used;
  }
  return E;
}
