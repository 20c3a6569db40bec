// Included (GlProgram: #include "surfel_geometry.glsl") by the shaders that read splats
// (engine/ldi/splats.h: Splat) and find their discs: surfel.vert, surfel.frag with SPLAT_POINTS,
// surfel_splat.comp and surfel_resolve.frag. A splat's disc lies in the plane through its
// surfel across its normal with the ray-axis component kept away from 0 (surfel.vert's lifted
// quad), and is the disc of `radius` around the surfel measured across the ray axis (the quad's
// inscribed disc).

#ifndef SURFEL_GEOMETRY_GLSL
#define SURFEL_GEOMETRY_GLSL

uniform mat4 viewProjection;  // scene units to clip space
// The view ray through NDC (x, y): from rayOrigin0 + x rayOriginX + y rayOriginY (the near
// plane) along rayDir0 + x rayDirX + y rayDirY (any length), scene units.
uniform vec3 rayOrigin0, rayOriginX, rayOriginY;
uniform vec3 rayDir0, rayDirX, rayDirY;

float snorm16(uint bits) {
  int v = int(bits);
  if (v >= 32768) v -= 65536;
  return float(v) / 32767.0;
}

// A splat's unit normal from its octahedral encoding (2 x snorm16).
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

// The normal of the splat's plane: `n` with its ray-axis component kept away from 0 (a lift of
// at most 1 / 0.3 per unit across the axis).
vec3 splatPlaneNormal(vec3 n, int axis) {
  float na = n[axis];
  vec3 planeNormal = n;
  planeNormal[axis] = abs(na) < 0.3 ? sign(na + 1e-6) * 0.3 : na;
  return planeNormal;
}

// The projection of the splat's lifted quad (of half-side `radius` scene units across the ray
// axis, around `center`): its centre's clip position and the corners' largest distance from it
// in NDC along x and y; false where the quad crosses the eye's plane (a splat the near plane
// would clip). The quad holds the disc, so the box of that extent around the centre holds
// every pixel of it. (The corners' box is tighter than a bound of the sphere through them,
// which cost 8-14% more per splat drawn as points on the H200 and 4 times more under Mesa.)
bool splatExtent(vec3 center, vec3 planeNormal, int axis, float radius, out vec4 centre,
                 out vec2 extent) {
  int u = (axis + 1) % 3;
  int v = (axis + 2) % 3;
  centre = viewProjection * vec4(center, 1.0);
  extent = vec2(0.0);
  bool behind = centre.w <= 0.0;
  for (int k = 0; k < 4; ++k) {
    vec2 c = vec2((k & 1) == 0 ? -radius : radius, (k & 2) == 0 ? -radius : radius);
    vec3 offset = vec3(0.0);
    offset[u] = c.x;
    offset[v] = c.y;
    offset[axis] = -(planeNormal[u] * c.x + planeNormal[v] * c.y) / planeNormal[axis];
    vec4 q = viewProjection * vec4(center + offset, 1.0);
    behind = behind || q.w <= 0.0;
    extent = max(extent, abs(q.xy / q.w - centre.xy / centre.w));
  }
  return !behind;
}

// Where the view ray through `ndc` meets the disc of `radius` (scene units) of the splat at
// `center` (plane normal `planeNormal`, ray axis `axis`), and that point's window depth in [0, 1]
// (the default depth range); false where it misses the disc or lies outside the depth range.
bool rayOnDisc(vec2 ndc, vec3 center, vec3 planeNormal, int axis, float radius, out vec3 world,
               out float depth) {
  world = center;
  depth = 1.0;
  vec3 origin = rayOrigin0 + ndc.x * rayOriginX + ndc.y * rayOriginY;
  vec3 dir = rayDir0 + ndc.x * rayDirX + ndc.y * rayDirY;
  float denom = dot(planeNormal, dir);
  if (abs(denom) < 1e-9) return false;  // the ray runs along the plane
  world = origin + dir * (dot(planeNormal, center - origin) / denom);
  vec3 fromCenter = world - center;
  vec2 corner = vec2(fromCenter[(axis + 1) % 3], fromCenter[(axis + 2) % 3]) / radius;
  if (dot(corner, corner) > 1.0) return false;
  vec4 clip = viewProjection * vec4(world, 1.0);
  float ndcDepth = clip.z / clip.w;
  if (!(abs(ndcDepth) <= 1.0)) return false;  // outside the depth range (a quad would be clipped)
  depth = 0.5 * ndcDepth + 0.5;
  return true;
}

#endif  // SURFEL_GEOMETRY_GLSL
