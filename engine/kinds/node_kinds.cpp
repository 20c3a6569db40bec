#include "engine/kinds/node_kinds.h"

#include <cmath>

#include "engine/util/error.h"

namespace strata {
namespace {

std::vector<NodeKindInfo> buildTable() {
  std::vector<NodeKindInfo> table = {
      {NodeKind::Union,
       "union",
       KindRole::Operation,
       "\u222A",
       "U",
       "Union: everything any child covers",
       RayOp::Union,
       {"children"}},
      {NodeKind::Difference,
       "difference",
       KindRole::Operation,
       "\u2212",
       "-",
       "Difference: the first child minus all the others",
       RayOp::Difference,
       {"children"}},
      {NodeKind::Intersection,
       "intersection",
       KindRole::Operation,
       "\u2229",
       "&",
       "Intersection: only what every child covers",
       RayOp::Intersection,
       {"children"}},
      {NodeKind::Offset,
       "offset",
       KindRole::Operation,
       "\u25CC",
       "O",
       "Offset: the children grown (distance > 0) or shrunk (< 0) by a distance",
       RayOp::Union,
       {"children", "distance"},
       nullptr,
       Modifier::Offset,
       "distance",
       0.1},
      {NodeKind::Shell,
       "shell",
       KindRole::Operation,
       "\u25CE",
       "S",
       "Shell: a wall of the given thickness inside the children's surface",
       RayOp::Union,
       {"children", "thickness", "opening"},
       nullptr,
       Modifier::Shell,
       "thickness",
       0.1},
      {NodeKind::Round,
       "round",
       KindRole::Operation,
       "\u25E0",
       "R",
       "Round: convex edges of the children rounded with a radius",
       RayOp::Union,
       {"children", "radius"},
       nullptr,
       Modifier::Round,
       "radius",
       0.1},
      {NodeKind::Fillet,
       "fillet",
       KindRole::Operation,
       "\u25E1",
       "F",
       "Fillet: concave edges and the seams between the children filled with a radius",
       RayOp::Union,
       {"children", "radius"},
       nullptr,
       Modifier::Fillet,
       "radius",
       0.1},
      {NodeKind::Array,
       "array",
       KindRole::Operation,
       "\u2237",
       "#",
       "Array: copies of the children along one, two or three axes (counts and steps)",
       RayOp::Union,
       {"children", "counts", "step"},
       nullptr,
       Modifier::None,
       nullptr,
       0.0,
       Pattern::Array},
      {NodeKind::CircularArray,
       "circularArray",
       KindRole::Operation,
       "\u21BB",
       "@",
       "Circular array: copies of the children around an axis (count, axis, angle, centre)",
       RayOp::Union,
       {"children", "count", "axis", "angle", "center"},
       nullptr,
       Modifier::None,
       nullptr,
       0.0,
       Pattern::Circular,
       "circular array"},
      {NodeKind::Mirror,
       "mirror",
       KindRole::Operation,
       "\u2194",
       "|",
       "Mirror: the children and their mirror image across a plane (or the image alone)",
       RayOp::Union,
       {"children", "axis", "center", "keep"},
       nullptr,
       Modifier::None,
       nullptr,
       0.0,
       Pattern::Mirror},
  };
  for (const PrimitiveInfo& p : primitiveTable()) {
    std::vector<std::string> fields;
    for (const PrimitiveParam& param : p.params) fields.push_back(param.key);
    fields.push_back("segments");
    NodeKindInfo info{p.kind,    p.name,       KindRole::Primitive, p.glyph, p.asciiGlyph,
                      p.summary, RayOp::Union, std::move(fields),   &p};
    table.push_back(std::move(info));
  }
  table.push_back({NodeKind::Mesh,
                   "mesh",
                   KindRole::Mesh,
                   "\u25C6",
                   "M",
                   "An imported closed triangle mesh",
                   RayOp::Union,
                   {"path", "hash", "open"}});
  table.push_back({NodeKind::Instance,
                   "instance",
                   KindRole::Instance,
                   "\u21B3",
                   ">",
                   "A live copy of another node, with its own transform",
                   RayOp::Union,
                   {"of"}});
  return table;
}

}  // namespace

const std::vector<NodeKindInfo>& nodeKindTable() {
  static const std::vector<NodeKindInfo> table = buildTable();
  return table;
}

const NodeKindInfo& nodeKindInfo(NodeKind kind) {
  for (const NodeKindInfo& info : nodeKindTable())
    if (info.kind == kind) return info;
  static const NodeKindInfo unknown{kind,         "unknown", KindRole::Mesh, "?", "?", "",
                                    RayOp::Union, {},        nullptr};
  return unknown;
}

bool isOperation(NodeKind kind) {
  return nodeKindInfo(kind).role == KindRole::Operation;
}

bool isPrimitive(NodeKind kind) {
  return nodeKindInfo(kind).role == KindRole::Primitive;
}

const char* kindName(NodeKind kind) {
  return nodeKindInfo(kind).name;
}

const char* kindLabel(NodeKind kind) {
  const NodeKindInfo& info = nodeKindInfo(kind);
  return info.primitive ? info.primitive->label : info.label ? info.label : info.name;
}

bool kindFromName(const std::string& name, NodeKind* kind) {
  for (const NodeKindInfo& info : nodeKindTable()) {
    if (name == info.name) {
      *kind = info.kind;
      return true;
    }
  }
  return false;
}

Modifier modifierOf(NodeKind kind) {
  return nodeKindInfo(kind).modifier;
}

Pattern patternOf(NodeKind kind) {
  return nodeKindInfo(kind).pattern;
}

double modifierGrowth(NodeKind kind, double amount) {
  switch (modifierOf(kind)) {
    case Modifier::Offset:
      return amount > 0.0 ? amount : 0.0;
    case Modifier::Fillet:  // grown by the radius before it shrinks back
      return amount;
    default:
      return 0.0;
  }
}

ModifierReach modifierReach(NodeKind kind, double amount) {
  const double a = std::abs(amount);
  switch (modifierOf(kind)) {
    case Modifier::Offset:
    case Modifier::Shell:  // one offset, by -amount
      return ModifierReach{1, a};
    case Modifier::Round:  // two offsets, by -amount then amount
    case Modifier::Fillet:
      return ModifierReach{2, 2.0 * a};
    case Modifier::None:
      break;
  }
  return ModifierReach{};
}

void checkModifierAmount(NodeKind kind, double amount, const std::string& who) {
  const NodeKindInfo& info = nodeKindInfo(kind);
  if (info.modifier == Modifier::None) return;
  if (!std::isfinite(amount))
    throw Error(who + ": its " + info.amountKey + " is not a finite number");
  if (info.modifier != Modifier::Offset && !(amount > 0.0))
    throw Error(who + ": its " + info.amountKey + " must be greater than 0");
}

std::vector<NodeKind> operationKinds() {
  std::vector<NodeKind> kinds;
  for (const NodeKindInfo& info : nodeKindTable())
    if (info.role == KindRole::Operation) kinds.push_back(info.kind);
  return kinds;
}

}  // namespace strata
