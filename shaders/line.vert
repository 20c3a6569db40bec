#version 330 core
// Coloured lines and triangles in world space: the ground grid, the gizmo, the selection box.
layout(location = 0) in vec3 position;
layout(location = 1) in vec4 color;  // gamma-encoded RGBA
uniform mat4 viewProjection;
out vec4 vColor;
void main() {
  gl_Position = viewProjection * vec4(position, 1.0);
  vColor = color;
}
