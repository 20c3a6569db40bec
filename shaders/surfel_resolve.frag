#version 430 core
// The pixels of splats rasterized by compute (surfel_splat.comp): each pixel of the viewport
// whose idImage names a splat is lit as surfel.frag lights a point's pixel (the same disc point
// from the pixel's view ray, surfel_shade.glsl) and written with the depth depthImage holds, so
// that the depth test merges it with what the target holds (an image drawn over frames) and
// what is drawn next (ghosts, lines) is hidden behind it. depthImage holds depths on the 24-bit
// buffer's steps (surfel_splat.comp), which the depth buffer keeps as they are. The section cut
// was decided there: a pixel kept is not cut again here (a recomputed point a rounding away
// could fall on the cut side and leave a hole).

// engine/ldi/splats.h: Splat, 5 words each.
layout(std430, binding = 0) readonly buffer SplatWords {
  uint splatWords[];
};
uniform usampler2D depthImage;  // r32ui, as surfel_splat.comp left them
uniform usampler2D idImage;
uniform vec4 viewportRect;      // the GL viewport: x, y, width, height in pixels
uniform float splatRadius;      // in cells
uniform sampler2D leafTexture;  // per leaf id: rgb colour (linear), a = 1 when selected
uniform int leafTextureWidth;
uniform int leafCount;

#include "surfel_geometry.glsl"
#include "surfel_shade.glsl"

out vec4 fragColor;

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy - viewportRect.xy);
  uint index = texelFetch(idImage, pixel, 0).x;
  if (index == 0xffffffffu) discard;
  uint base = index * 5u;
  vec3 position = vec3(uintBitsToFloat(splatWords[base]), uintBitsToFloat(splatWords[base + 1u]),
                       uintBitsToFloat(splatWords[base + 2u]));
  vec3 n = decodeOctahedral(splatWords[base + 3u]);
  uint leafAxis = splatWords[base + 4u];
  int axis = int(leafAxis & 3u);
  int entry = min(int(leafAxis >> 2), leafCount - 1);
  vec4 leafData = texelFetch(leafTexture, ivec2(entry % leafTextureWidth, entry / leafTextureWidth), 0);
  float facing = dot(n, ortho ? -viewForward : normalize(eye - position));
  vec2 ndc = (gl_FragCoord.xy - viewportRect.xy) / viewportRect.zw * 2.0 - 1.0;
  vec3 world;
  float depth;
  rayOnDisc(ndc, position, splatPlaneNormal(n, axis), axis, splatRadius * cellSize, world, depth);
  gl_FragDepth = uintBitsToFloat(texelFetch(depthImage, pixel, 0).x);  // on a 24-bit step
  vec3 toEye = ortho ? -viewForward : normalize(eye - world);
  vec4 colour;
  if (!shadeSurfel(world, toEye, n, leafData.rgb, leafData.a, facing, true, colour)) discard;
  fragColor = colour;
}
