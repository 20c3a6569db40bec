#version 330 core
// Surfel splats: one instanced quad per surfel of the root LDI, lying in the surfel's tangent
// plane. The quad is built in the plane across the surfel's ray axis (where rays are h apart)
// and lifted onto the tangent plane, so neighbouring splats of one axis meet without gaps
// whatever the slope; the disc cut from it (surfel.frag) covers the ray's cell.
//
// Section plane: with sectionOn, everything where dot(sectionPlane.xyz, p) > sectionPlane.w is
// cut away (per fragment, in surfel.frag), and splats facing away from the camera are kept: where
// the nearest remaining splat faces away, the view ray is inside the solid at the plane, and the
// fragment shader draws the cap there.
//
// With SPLAT_POINTS defined (ViewportRenderer's point program): one point per surfel instead of
// a quad of four vertices (the draw is bound by vertex work on a GPU), sized to cover the lifted
// quad's projection; surfel.frag then casts the pixel's view ray onto the same tangent plane and
// writes that depth, so the disc seen is the quad's disc.

layout(location = 0) in vec2 corner;          // per vertex: (+-1, +-1)
layout(location = 1) in vec3 surfelPosition;  // per instance: world position, scene units
layout(location = 2) in uint surfelNormal;    // per instance: octahedral normal, 2 x snorm16
layout(location = 3) in uint surfelLeafAxis;  // per instance: leaf id << 2 | ray axis

uniform vec3 eye;         // camera position (perspective)
uniform vec3 viewForward; // camera forward direction (orthographic)
uniform bool ortho;
uniform float cellSize;   // h, scene units
uniform float splatRadius;  // in cells, across the ray axis
uniform sampler2D leafTexture;  // per leaf id: rgb colour (linear), a = 1 when selected
uniform int leafTextureWidth;
uniform int leafCount;  // entries in leafTexture; a newer document may have fewer leaves
uniform bool sectionOn;
uniform vec4 sectionPlane;  // unit normal (xyz) and offset (w), scene units

out vec3 vNormal;
out vec3 vColor;
out float vSelected;
out float vFacing;      // dot(normal, direction to the eye): < 0 faces away
flat out uint vLeaf;
#include "surfel_geometry.glsl"
#ifdef SPLAT_POINTS
uniform vec4 viewportRect;  // the GL viewport: x, y, width, height in pixels
uniform float maxPointSize;  // pixels; the renderer draws quads where splats would need more
flat out vec3 vCenter;       // the surfel's position, scene units
flat out vec3 vPlaneNormal;  // the lifted quad's plane: dot(vPlaneNormal, p - vCenter) = 0
flat out int vAxis;          // the ray axis
#else
out vec2 vCorner;
out vec3 vToEye;
out vec3 vWorld;        // the fragment's world position, scene units
#endif

void main() {
  vec3 n = decodeOctahedral(surfelNormal);
  int axis = int(surfelLeafAxis & 3u);
  uint leaf = surfelLeafAxis >> 2;
  int u = (axis + 1) % 3;
  int v = (axis + 2) % 3;

  vec3 toEye = ortho ? -viewForward : normalize(eye - surfelPosition);
  vFacing = dot(n, toEye);
  bool cull = sectionOn
                  // wholly on the cut side
                  ? dot(sectionPlane.xyz, surfelPosition) - sectionPlane.w >
                        2.0 * splatRadius * cellSize
                  // clearly facing away: hidden by the front of the closed surface
                  : vFacing < -0.25;
  if (cull) {
    gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
    return;
  }

  // The quad lies in the plane through the surfel whose normal is n with its ray-axis component
  // kept away from 0 (a lift of at most 1 / 0.3 per unit across the axis).
  vec3 planeNormal = splatPlaneNormal(n, axis);
  float radius = splatRadius * cellSize;
#ifdef SPLAT_POINTS
  vec4 centre;
  vec2 extent;
  if (!splatExtent(surfelPosition, planeNormal, axis, radius, centre, extent)) {
    // crosses the eye's plane: left out, as the near plane would clip it
    gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
    return;
  }
  gl_Position = centre;
  // NDC spans 2 across the viewport: extent * size / 2 pixels each side, plus a pixel of margin.
  gl_PointSize = min(maxPointSize, max(extent.x * viewportRect.z, extent.y * viewportRect.w) + 2.0);
  vCenter = surfelPosition;
  vPlaneNormal = planeNormal;
  vAxis = axis;
#else
  vToEye = toEye;
  float du = corner.x * radius;
  float dv = corner.y * radius;
  vec3 offset = vec3(0.0);
  offset[u] = du;
  offset[v] = dv;
  offset[axis] = -(planeNormal[u] * du + planeNormal[v] * dv) / planeNormal[axis];
  vWorld = surfelPosition + offset;
  gl_Position = viewProjection * vec4(vWorld, 1.0);
  vCorner = corner;
#endif
  vLeaf = leaf;
  int entry = min(int(leaf), leafCount - 1);  // texelFetch outside the texture is undefined
  ivec2 texel = ivec2(entry % leafTextureWidth, entry / leafTextureWidth);
  vec4 leafData = texelFetch(leafTexture, texel, 0);
  vColor = leafData.rgb;
  vSelected = leafData.a;
  vNormal = n;
}
