// Screen-space voxelization (nichols-penmatsa-wyman-2010 section 3.3), vertex
// stage: object -> eye space only. The projection happens in the geometry
// stage, which needs the eye depths of all three vertices first.
//
// vertexMC is the actor's point minus a per-geometry centre (float VBOs keep
// precision for data far from the origin); mrgiModelView folds the centre,
// the actor matrix and the camera's view matrix (computed in double).
in vec3 vertexMC;
uniform mat4 mrgiModelView;

void main()
{
  gl_Position = mrgiModelView * vec4(vertexMC, 1.0);
}
