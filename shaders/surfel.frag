#version 330 core
// Lit surfel discs: a key light and a fill light fixed to the camera, ambient, a little
// specular; the selection is tinted. Output is gamma-encoded (the window is not sRGB).
// With the section plane on (see surfel.vert): fragments on the cut side are discarded, and a
// splat facing away from the camera is drawn as the cap: the leaf's colour, flat-lit by the
// plane's normal, with a faint hatch on the plane.
// With SPLAT_POINTS (see surfel.vert): the fragment belongs to a point sprite; the pixel's view
// ray is cut with the splat's plane, which gives the disc's coordinates and the depth written.

in vec3 vNormal;
in vec3 vColor;
in float vSelected;
in float vFacing;
flat in uint vLeaf;
#ifdef SPLAT_POINTS
flat in vec3 vCenter;
flat in vec3 vPlaneNormal;
flat in int vAxis;
uniform vec4 viewportRect;  // the GL viewport: x, y, width, height in pixels
uniform mat4 viewProjection;
uniform float splatRadius;  // in cells
// The view ray through NDC (x, y): from rayOrigin0 + x rayOriginX + y rayOriginY (the near
// plane) along rayDir0 + x rayDirX + y rayDirY (any length), scene units.
uniform vec3 rayOrigin0, rayOriginX, rayOriginY;
uniform vec3 rayDir0, rayDirX, rayDirY;
#else
in vec2 vCorner;
in vec3 vToEye;
in vec3 vWorld;
#endif

uniform vec3 keyLight;   // unit direction towards the light, world space
uniform vec3 fillLight;
uniform bool sectionOn;
uniform vec4 sectionPlane;
uniform vec3 eye;
uniform vec3 viewForward;
uniform bool ortho;
uniform float cellSize;
uniform vec4 ghostColor;  // a > 0: a ghost (a part that cuts or intersects), translucent, no cap

out vec4 fragColor;

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

void main() {
#ifdef SPLAT_POINTS
  vec2 ndc = (gl_FragCoord.xy - viewportRect.xy) / viewportRect.zw * 2.0 - 1.0;
  vec3 origin = rayOrigin0 + ndc.x * rayOriginX + ndc.y * rayOriginY;
  vec3 dir = rayDir0 + ndc.x * rayDirX + ndc.y * rayDirY;
  float denom = dot(vPlaneNormal, dir);
  if (abs(denom) < 1e-9) discard;  // the ray runs along the plane
  vec3 world = origin + dir * (dot(vPlaneNormal, vCenter - origin) / denom);
  vec3 fromCenter = world - vCenter;
  vec2 corner = vec2(fromCenter[(vAxis + 1) % 3], fromCenter[(vAxis + 2) % 3]) /
                (splatRadius * cellSize);
  if (dot(corner, corner) > 1.0) discard;
  vec4 clip = viewProjection * vec4(world, 1.0);
  float ndcDepth = clip.z / clip.w;
  if (!(abs(ndcDepth) <= 1.0)) discard;  // outside the depth range (the quad would be clipped)
  gl_FragDepth = 0.5 * (gl_DepthRange.diff * ndcDepth + gl_DepthRange.near + gl_DepthRange.far);
  vec3 toEye = ortho ? -viewForward : normalize(eye - world);
#else
  vec2 corner = vCorner;
  vec3 world = vWorld;
  vec3 toEye = vToEye;
  if (dot(corner, corner) > 1.0) discard;
#endif
  if (ghostColor.a > 0.0) {
    if (sectionOn && dot(sectionPlane.xyz, world) > sectionPlane.w) discard;
    if (vFacing < 0.0) discard;
    vec3 gn = normalize(vNormal);
    float lit = 0.45 + 0.55 * max(dot(gn, keyLight), 0.0);
    float edge = pow(1.0 - max(dot(gn, toEye), 0.0), 2.0);  // outlines read through the tint
    fragColor = vec4(gammaEncode(ghostColor.rgb * lit), min(1.0, ghostColor.a + 0.5 * edge));
    return;
  }
  vec3 base = vColor;
  if (vSelected > 0.5) base = mix(base, vec3(1.0, 0.55, 0.12), 0.45);
  if (sectionOn) {
    if (dot(sectionPlane.xyz, world) > sectionPlane.w) discard;
    if (vFacing < 0.0) {
      // The cap: lit as the plane (its normal turned to the viewer), hatched every 8 cells.
      vec3 eyeDir = ortho ? -viewForward : normalize(eye - world);
      vec3 pn = dot(sectionPlane.xyz, eyeDir) >= 0.0 ? sectionPlane.xyz : -sectionPlane.xyz;
      vec3 c = onSectionPlane(world);
      float hatch = step(0.5, fract((c.x + c.y + c.z) / (8.0 * cellSize)));
      float light = 0.35 + 0.45 * max(dot(pn, keyLight), 0.0) + 0.15 * max(dot(pn, fillLight), 0.0);
      fragColor = vec4(gammaEncode(base * light * (0.82 + 0.18 * hatch)), 1.0);
      return;
    }
  }
  vec3 n = normalize(vNormal);
  float key = max(dot(n, keyLight), 0.0);
  float fill = max(dot(n, fillLight), 0.0);
  float rim = pow(1.0 - max(dot(n, toEye), 0.0), 3.0);
  vec3 h = normalize(keyLight + toEye);
  float spec = pow(max(dot(n, h), 0.0), 48.0);
  vec3 linear = base * (0.18 + 0.72 * key + 0.25 * fill) + vec3(0.18 * spec) + 0.12 * rim * base;
  if (vSelected > 0.5) linear += vec3(0.35, 0.16, 0.02) * rim;
  fragColor = vec4(gammaEncode(linear), 1.0);
}
