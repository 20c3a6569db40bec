#version 330 core
// Lit surfel discs (surfel_shade.glsl). With the section plane on (see surfel.vert): fragments
// on the cut side are discarded, and a splat facing away from the camera is drawn as the cap.
// With SPLAT_POINTS (see surfel.vert): the fragment belongs to a point sprite; the pixel's view
// ray is cut with the splat's plane (surfel_geometry.glsl), which gives the disc's coordinates and
// the depth written.

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
uniform float splatRadius;  // in cells
#else
in vec2 vCorner;
in vec3 vToEye;
in vec3 vWorld;
#endif

// Outside the #ifdef (an include within a block left out would shift the log's line numbers).
#include "surfel_geometry.glsl"
#include "surfel_shade.glsl"

out vec4 fragColor;

void main() {
#ifdef SPLAT_POINTS
  vec2 ndc = (gl_FragCoord.xy - viewportRect.xy) / viewportRect.zw * 2.0 - 1.0;
  vec3 world;
  float depth;
  if (!rayOnDisc(ndc, vCenter, vPlaneNormal, vAxis, splatRadius * cellSize, world, depth))
    discard;
  gl_FragDepth = depth;
  vec3 toEye = ortho ? -viewForward : normalize(eye - world);
#else
  vec2 corner = vCorner;
  vec3 world = vWorld;
  vec3 toEye = vToEye;
  if (dot(corner, corner) > 1.0) discard;
#endif
  vec4 colour;
  if (!shadeSurfel(world, toEye, vNormal, vColor, vSelected, vFacing, false, colour)) discard;
  fragColor = colour;
}
