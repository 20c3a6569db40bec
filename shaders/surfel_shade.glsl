// Included (GlProgram: #include "surfel_shade.glsl") by the shaders that colour a surfel's
// pixel: surfel.frag and surfel_resolve.frag. Lit discs: a key light and a fill light fixed to
// the camera, ambient, a little specular; the selection is tinted. Output is gamma-encoded (the
// window is not sRGB). With the section plane on, pixels on the cut side are cut away, and a
// splat facing away from the camera is drawn as the cap: the leaf's colour, flat-lit by the
// plane's normal, with a faint hatch on the plane.

#ifndef SURFEL_SHADE_GLSL
#define SURFEL_SHADE_GLSL

uniform vec3 keyLight;   // unit direction towards the light, world space
uniform vec3 fillLight;
uniform bool sectionOn;
uniform vec4 sectionPlane;  // unit normal (xyz) and offset (w), scene units
uniform vec3 eye;
uniform vec3 viewForward;
uniform bool ortho;
uniform float cellSize;   // h, scene units
uniform vec4 ghostColor;  // a > 0: a ghost (a part that cuts or intersects), translucent, no cap

vec3 gammaEncode(vec3 linear) {
  return pow(clamp(linear, 0.0, 1.0), vec3(1.0 / 2.2));
}

// Where the view ray through this fragment (at `world`) meets the section plane.
vec3 onSectionPlane(vec3 world) {
  vec3 dir = ortho ? viewForward : normalize(world - eye);
  vec3 origin = ortho ? world : eye;
  float denom = dot(sectionPlane.xyz, dir);
  if (abs(denom) < 1e-6) return world;
  return origin + dir * ((sectionPlane.w - dot(sectionPlane.xyz, origin)) / denom);
}

// The colour of the disc's pixel at `world` (scene units), seen along `toEye` (unit, towards
// the eye), of a surfel with normal `normal` (any length), leaf colour `color` (linear),
// `selected` (> 0.5: tinted) and `facing` (dot of its normal with the direction to the eye at
// the surfel: < 0 faces away). False where the pixel is not drawn: cut away by the section
// plane (unless `kept`: the cut was decided before), or a ghost's back.
bool shadeSurfel(vec3 world, vec3 toEye, vec3 normal, vec3 color, float selected, float facing,
                 bool kept, out vec4 colour) {
  colour = vec4(0.0);
  if (ghostColor.a > 0.0) {
    if (sectionOn && dot(sectionPlane.xyz, world) > sectionPlane.w) return false;
    if (facing < 0.0) return false;
    vec3 gn = normalize(normal);
    float lit = 0.45 + 0.55 * max(dot(gn, keyLight), 0.0);
    float edge = pow(1.0 - max(dot(gn, toEye), 0.0), 2.0);  // outlines read through the tint
    colour = vec4(gammaEncode(ghostColor.rgb * lit), min(1.0, ghostColor.a + 0.5 * edge));
    return true;
  }
  vec3 base = color;
  if (selected > 0.5) base = mix(base, vec3(1.0, 0.55, 0.12), 0.45);
  if (sectionOn) {
    if (!kept && dot(sectionPlane.xyz, world) > sectionPlane.w) return false;
    if (facing < 0.0) {
      // The cap: lit as the plane (its normal turned to the viewer), hatched every 8 cells.
      vec3 eyeDir = ortho ? -viewForward : normalize(eye - world);
      vec3 pn = dot(sectionPlane.xyz, eyeDir) >= 0.0 ? sectionPlane.xyz : -sectionPlane.xyz;
      vec3 c = onSectionPlane(world);
      float hatch = step(0.5, fract((c.x + c.y + c.z) / (8.0 * cellSize)));
      float light = 0.35 + 0.45 * max(dot(pn, keyLight), 0.0) + 0.15 * max(dot(pn, fillLight), 0.0);
      colour = vec4(gammaEncode(base * light * (0.82 + 0.18 * hatch)), 1.0);
      return true;
    }
  }
  vec3 n = normalize(normal);
  float key = max(dot(n, keyLight), 0.0);
  float fill = max(dot(n, fillLight), 0.0);
  float rim = pow(1.0 - max(dot(n, toEye), 0.0), 3.0);
  vec3 h = normalize(keyLight + toEye);
  float spec = pow(max(dot(n, h), 0.0), 48.0);
  vec3 linear = base * (0.18 + 0.72 * key + 0.25 * fill) + vec3(0.18 * spec) + 0.12 * rim * base;
  if (selected > 0.5) linear += vec3(0.35, 0.16, 0.02) * rim;
  colour = vec4(gammaEncode(linear), 1.0);
  return true;
}

#endif  // SURFEL_SHADE_GLSL
