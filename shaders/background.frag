#version 330 core
// Vertical gradient behind the scene (gamma-encoded colours).
in float vHeight;
uniform vec3 bottomColor;
uniform vec3 topColor;
out vec4 fragColor;
void main() { fragColor = vec4(mix(bottomColor, topColor, clamp(vHeight, 0.0, 1.0)), 1.0); }
