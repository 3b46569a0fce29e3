// Screen-space voxelization (nichols-penmatsa-wyman-2010 section 3.3),
// geometry stage: the triangle's eye-depth range [dmin, dmax] as flat
// varyings (mrgi_voxel.h section 5), so that the fragment stage can clamp its
// conservative depth interval to depths the triangle really has; without the
// clamp an obliquely seen face grows a "skirt" in front of and behind it.
// gl_in[].gl_Position holds the eye-space vertex (see the vertex stage).
layout(triangles) in;
layout(triangle_strip, max_vertices = 3) out;

// Eye -> clip; near and far are the voxel range's, so clipping drops what
// lies outside [near, far] (the fragment stage tests it again exactly).
uniform mat4 mrgiProjection;

out float mrgiDepthGS;
flat out float mrgiDepthMinGS;
flat out float mrgiDepthMaxGS;

void main()
{
  // Linear eye depth d = -z_eye (mrgi_voxel.h section 2).
  float d0 = -gl_in[0].gl_Position.z;
  float d1 = -gl_in[1].gl_Position.z;
  float d2 = -gl_in[2].gl_Position.z;
  float dmin = min(d0, min(d1, d2));
  float dmax = max(d0, max(d1, d2));
  for (int i = 0; i < 3; ++i)
  {
    gl_Position = mrgiProjection * gl_in[i].gl_Position;
    mrgiDepthGS = -gl_in[i].gl_Position.z;
    // Flat values come from the provoking vertex: every vertex carries them.
    mrgiDepthMinGS = dmin;
    mrgiDepthMaxGS = dmax;
    EmitVertex();
  }
  EndPrimitive();
}
