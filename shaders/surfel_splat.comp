#version 430 core
// Splats rasterized by compute (ViewportRenderer's compute kind): one invocation a splat finds
// the pixels of its disc as surfel.frag's points do (each pixel's view ray cut with the splat's
// plane: surfel_geometry.glsl) and keeps, per pixel, the nearest depth (pass 0) and then the
// lowest index of the splats at that depth (pass 1, after a memory barrier). Culled and cut as
// surfel.vert and surfel.frag cull and cut. surfel_resolve.frag then lights each pixel's splat.
// Why: a GPU that runs its graphics stages on a few of its units (the H100 and H200 do) draws
// millions of small splats at several nanoseconds each, where its compute units take a fraction.
//
// Images: depthImage (r32ui, the view's pixels, cleared to 0xffffffff) holds the nearest depth
// in [0, 1] rounded to the 24-bit depth buffer's steps (round(depth * (2^24 - 1)) / (2^24 - 1),
// as float bits, which order as the floats do: none is negative; surfel_resolve.frag writes
// that float as it is, which the depth buffer keeps exactly), so that splats at
// depths that buffer cannot tell apart tie and the first in the buffer wins, as the quads' depth
// test (GL_LESS) decides: with the floats' full precision instead, two parts' coincident faces
// showed a speckle of both in a section's cap; idImage (r32ui, cleared to 0xffffffff) the
// splat's index in the buffer.

layout(local_size_x = 64) in;

// engine/ldi/splats.h: Splat, 5 words each (position x, y, z as float bits, octahedral normal,
// leaf id << 2 | ray axis).
layout(std430, binding = 0) readonly buffer SplatWords {
  uint splatWords[];
};
layout(r32ui, binding = 0) uniform coherent uimage2D depthImage;
layout(r32ui, binding = 1) uniform coherent uimage2D idImage;

uniform uint firstSplat;   // the splats drawn: firstSplat + k * splatStride, k < splatCount
uniform uint splatCount;
uniform uint splatStride;
uniform int pass;          // 0: depths, 1: indices
uniform ivec2 viewSize;    // pixels of the view (the images' size)
uniform int maxFootprint;  // pixels across a splat's box at most (the renderer's bound)
uniform vec3 eye;          // camera position (perspective)
uniform vec3 viewForward;  // camera forward direction (orthographic)
uniform bool ortho;
uniform float cellSize;     // h, scene units
uniform float splatRadius;  // in cells, across the ray axis
uniform bool sectionOn;
uniform vec4 sectionPlane;  // unit normal (xyz) and offset (w), scene units

#include "surfel_geometry.glsl"

void main() {
  uint k = gl_GlobalInvocationID.x;
  if (k >= splatCount) return;
  uint index = firstSplat + k * splatStride;
  uint base = index * 5u;
  vec3 position = vec3(uintBitsToFloat(splatWords[base]), uintBitsToFloat(splatWords[base + 1u]),
                       uintBitsToFloat(splatWords[base + 2u]));
  vec3 n = decodeOctahedral(splatWords[base + 3u]);
  int axis = int(splatWords[base + 4u] & 3u);
  vec3 toEye = ortho ? -viewForward : normalize(eye - position);
  float facing = dot(n, toEye);
  bool cull = sectionOn ? dot(sectionPlane.xyz, position) - sectionPlane.w >
                              2.0 * splatRadius * cellSize
                        : facing < -0.25;
  if (cull) return;
  vec3 planeNormal = splatPlaneNormal(n, axis);
  float radius = splatRadius * cellSize;
  vec4 centre;
  vec2 extent;
  if (!splatExtent(position, planeNormal, axis, radius, centre, extent)) return;
  // The pixels whose centres may lie in the quad's box (a pixel of margin for rounding).
  vec2 size = vec2(viewSize);
  vec2 at = (centre.xy / centre.w * 0.5 + 0.5) * size;  // pixels from the view's corner
  vec2 reach = extent * 0.5 * size + 1.0;
  if (any(greaterThan(abs(at), size + reach + 1.0))) return;  // far outside (and not NaN below)
  ivec2 lo = max(ivec2(floor(at - reach)), ivec2(0));
  ivec2 hi = min(ivec2(ceil(at + reach)), viewSize - 1);
  hi = min(hi, lo + maxFootprint);
  for (int y = lo.y; y <= hi.y; ++y)
    for (int x = lo.x; x <= hi.x; ++x) {
      vec2 ndc = (vec2(x, y) + 0.5) / size * 2.0 - 1.0;
      vec3 world;
      float depth;
      if (!rayOnDisc(ndc, position, planeNormal, axis, radius, world, depth)) continue;
      if (sectionOn && dot(sectionPlane.xyz, world) > sectionPlane.w) continue;
      uint bits = floatBitsToUint(round(depth * 16777215.0) / 16777215.0);
      if (pass == 0) {
        imageAtomicMin(depthImage, ivec2(x, y), bits);
      } else if (imageLoad(depthImage, ivec2(x, y)).x == bits) {
        imageAtomicMin(idImage, ivec2(x, y), index);
      }
    }
}
