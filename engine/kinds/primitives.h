// The primitive leaves, one table entry each: name, icon, parameters with their ranges and
// units, defaults, local bounds, automatic level of detail and tessellation. Scene files, the
// document's validation, the evaluator's cache keys and tessellation, and the editor's palette,
// inspector and outliner all iterate over this table; adding a primitive is one entry in
// primitives.cpp, its tessellation beside it, and its value in node_kind.h (CONTRIBUTING.md).
//
// Conventions: object coordinates, centred at the origin, axis along z; lengths in scene units.
// Meshes are closed, consistently oriented outward, without degenerate triangles.
#pragma once

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <string>
#include <vector>

#include "engine/geometry/mesh.h"
#include "engine/kinds/node_kind.h"
#include "engine/kinds/primitive_params.h"

namespace strata {

// Segments around the circumference for a primitive whose largest radius, after its world
// transform, is `worldRadius` scene units, such that the chordal error stays below
// `maxError` scene units. Clamped to [12, kMaxAutoSegments].
int autoSegments(double worldRadius, double maxError);
constexpr int kMaxAutoSegments = 1024;
// The most segments a primitive may ask for explicitly (scene files, the inspector).
constexpr int kMaxSegments = 4096;

// The smallest value a parameter takes.
enum class ParamMinimum : uint8_t {
  Positive,     // > 0
  NonNegative,  // >= 0
};

// One parameter: a length, or three lengths along x, y, z. Exactly one of `scalar` and
// `vector` is set.
struct PrimitiveParam {
  const char* key;    // scene-file field, e.g. "topRadius"
  const char* label;  // for people, e.g. "top radius"
  double PrimitiveParams::*scalar = nullptr;
  glm::dvec3 PrimitiveParams::*vector = nullptr;
  ParamMinimum minimum = ParamMinimum::Positive;
};

// A constraint between parameters that failed: what to say, and the parameters involved (a
// message about a file names the first of them the file sets, else the last).
struct ParamProblem {
  std::string message;
  std::vector<const char*> keys;
};

// A primitive's solid as the convex hull of at most two pieces, each a centre plus the Minkowski
// sum of an axis-aligned box, a disc in the plane z = centre.z and a ball (object units): a box,
// a ball, a cylinder (a segment plus a disc), a cone (the hull of its two end discs), a torus (a
// disc plus a ball), a capsule, a rounded box (a smaller box plus a ball). Exact enough to give
// the solid's extent in every direction, so its bounds under any transform (primitiveWorldBounds)
// are those of the solid, not of its local box turned (a sphere turned 45 degrees kept a box 41%
// too wide).
struct HullPiece {
  glm::dvec3 centre{0.0};
  glm::dvec3 box{0.0};  // half sizes
  double disc = 0.0;    // radius
  double ball = 0.0;    // radius
};
struct PrimitiveHull {
  HullPiece pieces[2];
  int count = 1;
};

struct PrimitiveInfo {
  NodeKind kind;
  const char* name;        // in files and on the command line: "box", "roundedBox"
  const char* label;       // for people: "box", "rounded box"
  const char* glyph;       // UTF-8 icon (from U+2190..U+21FF or U+2500..U+25FF, which the
                           // editor's font carries)
  const char* asciiGlyph;  // where the font lacks it
  const char* summary;     // one line for tooltips
  std::vector<PrimitiveParam> params;
  bool usesSegments;         // shown in the inspector; every primitive's file may carry one
  PrimitiveParams defaults;  // a new primitive of size about 1
  // Largest radius in object units, for automatic segments (0: not curved).
  double (*radius)(const PrimitiveParams&);
  // The solid's hull (its bounds in any frame: primitiveWorldBounds).
  PrimitiveHull (*hull)(const PrimitiveParams&);
  // Constraints between parameters (each alone in range); nullptr or "" message: none failed.
  ParamProblem (*relations)(const PrimitiveParams&);
  // Where the artist's change of the parameter `changedKey` broke a relation: the relation's
  // other parameters brought within it (fitPrimitiveRelations). False where it cannot (the
  // change is then refused). nullptr: no relation can be fitted.
  bool (*fitRelations)(PrimitiveParams&, const std::string& changedKey);
  // The mesh, for parameters that passed validation, with `segments` >= 3 around.
  TriangleMesh (*tessellate)(const PrimitiveParams&, int segments);
};

// Every primitive, in palette order.
const std::vector<PrimitiveInfo>& primitiveTable();
// The entry of `kind`; nullptr when `kind` is not a primitive.
const PrimitiveInfo* primitiveInfo(NodeKind kind);

// Checks every parameter of `kind` (ranges, relations, segments). Throws strata::Error
// "<label> must be ..." for the first that fails, or when `kind` is not a primitive.
void validatePrimitiveParams(NodeKind kind, const PrimitiveParams& params);

// Where `params` (valid parameters of `kind` with `changedKey` just changed by the artist) break
// a relation, the relation's other parameters made to fit, as near to what they were as the
// relation allows, at 4 significant digits (what a length field shows, so that the number shown
// is the number kept): a rounded box made thinner than twice its corners' radius gets a smaller
// radius, a torus's major radius made smaller than its minor one a smaller minor radius (both
// were refused: an artist's test). The parameter changed is never touched. Returns the
// parameters changed with their new values: none where the relations held, or where no fit
// exists (a cone's two radii both 0), left to validatePrimitiveParams to refuse.
struct FittedParam {
  const char* label;  // for people: "corner radius"
  double value;
};
std::vector<FittedParam> fitPrimitiveRelations(NodeKind kind, PrimitiveParams* params,
                                               const std::string& changedKey);

// The primitive's mesh in object coordinates with `segments` segments around (at least 3 are
// used). Validates first (throws strata::Error for a non-primitive kind or invalid parameters).
TriangleMesh tessellatePrimitive(NodeKind kind, const PrimitiveParams& params, int segments);

// The largest radius of the primitive in object units (0 for a box): what autoSegments needs,
// times the transform's largest scale.
double primitiveRadius(NodeKind kind, const PrimitiveParams& params);
// The primitive's local bounds; empty for a non-primitive kind.
Bounds primitiveLocalBounds(NodeKind kind, const PrimitiveParams& params);
// The bounds of the primitive's solid placed by the affine `objectToWorld` (its hull's extent
// along each world axis: exact for the solid, and so containing its tessellation, whose
// vertices lie on it); empty for a non-primitive kind.
Bounds primitiveWorldBounds(NodeKind kind, const PrimitiveParams& params,
                            const glm::dmat4& objectToWorld);

// Every length parameter of `kind` multiplied by `factor` (> 0); segments kept.
PrimitiveParams scaledPrimitiveParams(NodeKind kind, const PrimitiveParams& params, double factor);

}  // namespace strata
