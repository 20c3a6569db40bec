#version 330 core
// Lit surfel discs: a key light and a fill light fixed to the camera, ambient, a little
// specular; the selection is tinted. Output is gamma-encoded (the window is not sRGB).

in vec3 vNormal;
in vec3 vColor;
in vec2 vCorner;
in float vSelected;
in vec3 vToEye;

uniform vec3 keyLight;   // unit direction towards the light, world space
uniform vec3 fillLight;

out vec4 fragColor;

void main() {
  if (dot(vCorner, vCorner) > 1.0) discard;
  vec3 n = normalize(vNormal);
  vec3 base = vColor;
  if (vSelected > 0.5) base = mix(base, vec3(1.0, 0.55, 0.12), 0.45);
  float key = max(dot(n, keyLight), 0.0);
  float fill = max(dot(n, fillLight), 0.0);
  float rim = pow(1.0 - max(dot(n, vToEye), 0.0), 3.0);
  vec3 h = normalize(keyLight + vToEye);
  float spec = pow(max(dot(n, h), 0.0), 48.0);
  vec3 linear = base * (0.18 + 0.72 * key + 0.25 * fill) + vec3(0.18 * spec) + 0.12 * rim * base;
  if (vSelected > 0.5) linear += vec3(0.35, 0.16, 0.02) * rim;
  fragColor = vec4(pow(clamp(linear, 0.0, 1.0), vec3(1.0 / 2.2)), 1.0);
}
