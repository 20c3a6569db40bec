#version 330 core
// Picking (with surfel.vert): the id of the leaf each pixel shows, plus one (0 = nothing), into
// an R32UI target, with bit 31 set where the pixel shows the section's cap; the depth buffer
// gives the point (for a cap: the reader intersects the view ray with the plane). Same disc and
// section cuts as surfel.frag, so what is picked is what is seen (a cap picks the leaf whose
// solid it cuts).

in vec2 vCorner;
in vec3 vWorld;
in float vFacing;
flat in uint vLeaf;

uniform bool sectionOn;
uniform vec4 sectionPlane;

out uint pickedLeaf;

void main() {
  if (dot(vCorner, vCorner) > 1.0) discard;
  if (sectionOn && dot(sectionPlane.xyz, vWorld) > sectionPlane.w) discard;
  bool cap = sectionOn && vFacing < 0.0;
  pickedLeaf = (vLeaf + 1u) | (cap ? 0x80000000u : 0u);
}
