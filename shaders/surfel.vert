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

layout(location = 0) in vec2 corner;          // per vertex: (+-1, +-1)
layout(location = 1) in vec3 surfelPosition;  // per instance: world position, scene units
layout(location = 2) in uint surfelNormal;    // per instance: octahedral normal, 2 x snorm16
layout(location = 3) in uint surfelLeafAxis;  // per instance: leaf id << 2 | ray axis

uniform mat4 viewProjection;
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
out vec2 vCorner;
out float vSelected;
out vec3 vToEye;
out vec3 vWorld;        // the fragment's world position, scene units
out float vFacing;      // dot(normal, direction to the eye): < 0 faces away
flat out uint vLeaf;

float snorm16(uint bits) {
  int v = int(bits);
  if (v >= 32768) v -= 65536;
  return float(v) / 32767.0;
}

vec3 decodeOctahedral(uint bits) {
  float x = snorm16(bits & 0xffffu);
  float y = snorm16(bits >> 16);
  float z = 1.0 - abs(x) - abs(y);
  if (z < 0.0) {
    float ox = (1.0 - abs(y)) * (x >= 0.0 ? 1.0 : -1.0);
    float oy = (1.0 - abs(x)) * (y >= 0.0 ? 1.0 : -1.0);
    x = ox;
    y = oy;
  }
  return normalize(vec3(x, y, z));
}

void main() {
  vec3 n = decodeOctahedral(surfelNormal);
  int axis = int(surfelLeafAxis & 3u);
  uint leaf = surfelLeafAxis >> 2;
  int u = (axis + 1) % 3;
  int v = (axis + 2) % 3;

  vec3 toEye = ortho ? -viewForward : normalize(eye - surfelPosition);
  vToEye = toEye;
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

  float du = corner.x * splatRadius * cellSize;
  float dv = corner.y * splatRadius * cellSize;
  vec3 offset = vec3(0.0);
  offset[u] = du;
  offset[v] = dv;
  float na = n[axis];
  offset[axis] = -(n[u] * du + n[v] * dv) / (abs(na) < 0.3 ? sign(na + 1e-6) * 0.3 : na);

  vWorld = surfelPosition + offset;
  vLeaf = leaf;
  gl_Position = viewProjection * vec4(vWorld, 1.0);
  int entry = min(int(leaf), leafCount - 1);  // texelFetch outside the texture is undefined
  ivec2 texel = ivec2(entry % leafTextureWidth, entry / leafTextureWidth);
  vec4 leafData = texelFetch(leafTexture, texel, 0);
  vColor = leafData.rgb;
  vSelected = leafData.a;
  vNormal = n;
  vCorner = corner;
}
