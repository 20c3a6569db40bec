#version 330 core
// Dear ImGui's vertices (ui/panel_renderer.h): position in display pixels, texture coordinate
// in the font atlas, colour as four normalised bytes.
layout(location = 0) in vec2 position;
layout(location = 1) in vec2 uv;
layout(location = 2) in vec4 colour;
uniform mat4 projection;  // display pixels to clip space
out vec2 vUv;
out vec4 vColour;
void main() {
  vUv = uv;
  vColour = colour;
  gl_Position = projection * vec4(position, 0.0, 1.0);
}
