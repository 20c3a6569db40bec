#version 430 core
// A full-screen triangle from gl_VertexID (no vertex buffer), for surfel_resolve.frag.
void main() {
  vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2)) * 2.0 - 1.0;
  gl_Position = vec4(p, 0.0, 1.0);
}
