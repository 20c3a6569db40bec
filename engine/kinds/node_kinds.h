// Every node kind, described once: its name in files and on the command line, its role, its
// icon, the Boolean an operation applies ray by ray, and the scene-file fields it accepts.
// The document, the evaluator (and through it both backends), scene files and the editor read
// this table instead of switching on kinds. Primitive entries come from primitives.h.
#pragma once

#include <string>
#include <vector>

#include "engine/kinds/node_kind.h"
#include "engine/kinds/primitives.h"
#include "engine/ldi/shared_math.h"

namespace strata {

enum class KindRole : uint8_t {
  Operation,  // n-ary, combines its children with `rayOp`
  Primitive,  // a leaf tessellated from parameters (`primitive`)
  Mesh,       // a leaf holding an imported mesh
  Instance,   // a leaf standing for another node of the document
};

struct NodeKindInfo {
  NodeKind kind;
  const char* name;  // "union", "box", ...
  KindRole role;
  const char* glyph;                         // UTF-8 icon (see PrimitiveInfo::glyph for the ranges)
  const char* asciiGlyph;                    // where the font lacks it
  const char* summary;                       // one line for tooltips
  RayOp rayOp = RayOp::Union;                // operations only
  std::vector<std::string> fields;           // scene-file fields besides the common ones
  const PrimitiveInfo* primitive = nullptr;  // primitives only
  Modifier modifier = Modifier::None;        // modifiers only (role Operation, rayOp Union)
  const char* amountKey = nullptr;           // modifiers: the amount's scene-file field
  double defaultAmount = 0.0;                // modifiers: of a new node, in scene units
  Pattern pattern = Pattern::None;           // patterns only (role Operation, rayOp Union)
  const char* label = nullptr;               // for people, where it differs from `name`
};

// The modifier of `kind` (Modifier::None for every other kind).
Modifier modifierOf(NodeKind kind);
// How far a modifier's result may reach beyond its children's bounds (scene units, >= 0).
double modifierGrowth(NodeKind kind, double amount);
// The offsets a modifier applies (Backend::modify) and their summed distance (scene units, >= 0):
// its result at a point depends on its children within that distance (plus each offset's band,
// engine/ldi/offset_math.h: kOffsetHaloCells).
struct ModifierReach {
  int offsets = 0;
  double distance = 0.0;
};
ModifierReach modifierReach(NodeKind kind, double amount);
// Throws strata::Error (naming `who`) when `amount` is not valid for the modifier `kind`.
void checkModifierAmount(NodeKind kind, double amount, const std::string& who);

// The pattern of `kind` (Pattern::None for every other kind).
Pattern patternOf(NodeKind kind);

// Every kind: operations, then primitives in palette order, then mesh and instance.
const std::vector<NodeKindInfo>& nodeKindTable();
// The entry of `kind` (every NodeKind has one).
const NodeKindInfo& nodeKindInfo(NodeKind kind);

bool isOperation(NodeKind kind);
bool isPrimitive(NodeKind kind);
// Lower-case name used in files and on the command line ("union", "box", ...).
const char* kindName(NodeKind kind);
// For people: a primitive's label ("rounded box"), a kind's label ("circular array"), else the
// name ("union").
const char* kindLabel(NodeKind kind);
// Inverse of kindName; returns false for unknown names.
bool kindFromName(const std::string& name, NodeKind* kind);
// The operations, in the order the editor offers them.
std::vector<NodeKind> operationKinds();

}  // namespace strata
