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
// VW, VH: clip -> voxel pixel coordinates (the viewport transform).
uniform vec2 mrgiVoxelViewport;

out float mrgiDepthGS;
flat out float mrgiDepthMinGS;
flat out float mrgiDepthMaxGS;
// The triangle for the per-pixel clamp (mrgi_voxel_triangle_pixel_range()):
// per vertex voxel pixel u, v, linear depth d and clip w.
flat out vec3 mrgiTriUGS;
flat out vec3 mrgiTriVGS;
flat out vec3 mrgiTriDGS;
flat out vec3 mrgiTriWGS;

void main()
{
  // Linear eye depth d = -z_eye (mrgi_voxel.h section 2).
  float d0 = -gl_in[0].gl_Position.z;
  float d1 = -gl_in[1].gl_Position.z;
  float d2 = -gl_in[2].gl_Position.z;
  float dmin = min(d0, min(d1, d2));
  float dmax = max(d0, max(d1, d2));
  vec4 c[3];
  vec3 tu, tv, tw;
  for (int i = 0; i < 3; ++i)
  {
    c[i] = mrgiProjection * gl_in[i].gl_Position;
    tw[i] = c[i].w;
    tu[i] = (c[i].x / c[i].w + 1.0) * 0.5 * mrgiVoxelViewport.x;
    tv[i] = (c[i].y / c[i].w + 1.0) * 0.5 * mrgiVoxelViewport.y;
  }
  for (int i = 0; i < 3; ++i)
  {
    gl_Position = c[i];
    mrgiTriUGS = tu;
    mrgiTriVGS = tv;
    mrgiTriDGS = vec3(d0, d1, d2);
    mrgiTriWGS = tw;
    mrgiDepthGS = -gl_in[i].gl_Position.z;
    // Flat values come from the provoking vertex: every vertex carries them.
    mrgiDepthMinGS = dmin;
    mrgiDepthMaxGS = dmax;
    EmitVertex();
  }
  EndPrimitive();
}
