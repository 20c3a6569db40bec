#version 330 core
// The panels' pixels: the vertex colour times the font atlas (a white texel for fills).
in vec2 vUv;
in vec4 vColour;
uniform sampler2D atlas;
out vec4 fragColour;
void main() {
  fragColour = vColour * texture(atlas, vUv);
}
