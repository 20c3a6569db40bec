#include "engine/eval/evaluator.h"

#include <glm/geometric.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>
#include <glm/vector_relational.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <string>
#include <unordered_set>

#include "engine/document/commands.h"
#include "engine/document/expansion.h"
#include "engine/document/measurement.h"
#include "engine/geometry/mesh_world_bounds.h"
#include "engine/kinds/primitives.h"
#include "engine/ldi/offset_math.h"
#include "engine/util/error.h"
#include "engine/util/hash.h"
#include "engine/util/memory.h"
#include "engine/util/timer.h"

namespace strata {
namespace {

constexpr int kDepthGuard = 4096;  // recursion guard (scene files are limited far below)
// Chordal error of automatic tessellation, in cells.
constexpr double kAutoChordErrorCells = 0.02;

enum Stage { kTessellate, kSample, kBoolean, kMeasure, kStageCount };
const char* const kStageNames[kStageCount] = {"tessellate", "sample", "boolean", "measure"};

double largestScale(const glm::dmat4& m) {
  double s = 0.0;
  for (int c = 0; c < 3; ++c) s = std::max(s, glm::length(glm::dvec3(m[c])));
  return s;
}

void hashGrid(Hasher& h, const Grid& grid) {
  h.add(grid.origin.x).add(grid.origin.y).add(grid.origin.z).add(grid.h);
  h.add(grid.cells.x).add(grid.cells.y).add(grid.cells.z);
  h.add(grid.first.x).add(grid.first.y).add(grid.first.z);
}

// Nodes' LDIs are keyed on the grid's lattice, not its window: an LDI computed on one window
// serves another of the same lattice when the node lies within both (Evaluator::onGrid).
void hashLattice(Hasher& h, const Grid& grid) {
  h.add(grid.origin.x).add(grid.origin.y).add(grid.origin.z).add(grid.h);
}

// The primitive's parameters in the cache key, as its table entry lists them.
void hashPrimitiveParams(Hasher& h, NodeKind kind, const PrimitiveParams& p) {
  for (const PrimitiveParam& param : primitiveInfo(kind)->params) {
    if (param.scalar) h.add(p.*param.scalar);
    if (param.vector) h.add((p.*param.vector).x).add((p.*param.vector).y).add((p.*param.vector).z);
  }
}

// Where an operation places its children, in its frame: a pattern's copies (checked), else the
// identity alone.
std::vector<glm::dmat4> placementsOf(const Node& node) {
  const Pattern pattern = patternOf(node.kind);
  if (pattern == Pattern::None) return {glm::dmat4(1.0)};
  // Nothing to place: no copies listed.
  if (std::none_of(node.children.begin(), node.children.end(),
                   [](const NodePtr& c) { return c->visible; }))
    return {};
  checkPattern(pattern, node.pattern, nodeLabel(node));
  return patternPlacements(pattern, node.pattern);
}

// A mesh's or a primitive's world bounds (empty for a mesh not loaded).
Bounds leafBounds(const Node& node, const glm::dmat4& world) {
  Bounds b;
  if (node.kind == NodeKind::Mesh) return meshWorldBounds(node.mesh, world);
  if (isPrimitive(node.kind)) return primitiveWorldBounds(node.kind, node.params, world);
  return b;
}

Bounds boundsOf(const NodePtr& node, const NodePtr& root, const glm::dmat4& parentWorld,
                bool asInstance, int depth) {
  Bounds b;
  if (!node || depth > kDepthGuard || (!node->visible && !asInstance)) return b;
  glm::dmat4 world = parentWorld * node->transform.matrix();
  if (node->kind == NodeKind::Instance)
    return boundsOf(findNode(root, node->instanceOf), root, world, true, depth + 1);
  if (!isOperation(node->kind)) return leafBounds(*node, world);
  bool first = true;
  const RayOp op = nodeKindInfo(node->kind).rayOp;
  // A hidden base leaves its difference empty (its cutters never become the base).
  if (op == RayOp::Difference && !node->children.empty() && !node->children[0]->visible) return b;
  for (const glm::dmat4& placement : placementsOf(*node)) {  // patterns: every copy
    for (const auto& child : node->children) {
      if (!child->visible) continue;
      Bounds cb = boundsOf(child, root, world * placement, false, depth + 1);
      if (op == RayOp::Union) {
        b.include(cb);
      } else if (op == RayOp::Intersection) {
        b = first ? cb : b.intersected(cb);
      } else if (first) {
        b = cb;  // difference: the first visible child
      }
      first = false;
    }
  }
  // A modifier may reach beyond its children (an offset grows, a fillet grows before it
  // shrinks): room for it.
  const double growth = modifierGrowth(node->kind, node->amount);
  if (growth > 0.0 && !b.empty()) {
    b.min -= glm::dvec3(growth);
    b.max += glm::dvec3(growth);
  }
  return b;
}

// A part thinner than this fraction of its width is flat: a sheet, its thickness rounding.
constexpr double kFlatPart = 1e-9;

// Numbers a leaf's placement must keep: a finite, invertible world transform whose scales neither
// underflow nor overflow, and a size that the coordinates' precision can still represent.
// Throws strata::Error naming the leaf.
void checkLeafPlacement(const Node& node, const glm::dmat4& world, const Bounds& bounds) {
  const std::string who = nodeLabel(node);
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(world[c][r]))
        throw Error(who +
                    ": its world transform overflows (nested scales or translations "
                    "multiply past 1e308)");
  const double det = glm::determinant(glm::dmat3(world));
  if (!(std::abs(det) > 1e-300) || !std::isfinite(det)) {
    char text[64];
    std::snprintf(text, sizeof(text), "%.3g", det);
    throw Error(who +
                ": its world transform is singular or underflows (the nested scales "
                "multiply to a volume factor of " +
                text + ")");
  }
  if (!(bounds.min.x <= bounds.max.x)) return;  // no points (empty() also holds for flat boxes)
  const glm::dvec3 size = bounds.max - bounds.min;
  const glm::dvec3 far = glm::max(glm::abs(bounds.min), glm::abs(bounds.max));
  bool finite = true;
  for (int a = 0; a < 3; ++a) finite = finite && std::isfinite(size[a]) && std::isfinite(far[a]);
  if (!finite) throw Error(who + ": its coordinates overflow");
  const double widest = std::max({size.x, size.y, size.z});
  for (int a = 0; a < 3; ++a) {
    // A single sheet (an open mesh that is a flat surface, say) whose width is representable:
    // evaluated (it encloses nothing) and said to be flat (smallerThanCellWarning). It was
    // refused as "its size of 0 cannot be represented", which read as a precision problem and
    // stopped the whole scene.
    if (size[a] <= kFlatPart * widest && far[a] * 1e-12 < widest) continue;
    if (!(size[a] > far[a] * 1e-12)) {  // fewer than ~4500 doubles across the part
      char text[120];
      std::snprintf(text, sizeof(text), "%.3g from the origin along %c, where its size of %.3g",
                    far[a], "xyz"[a], size[a]);
      throw Error(who + " lies " + text + " cannot be represented in double precision");
    }
  }
}

// How thick a leaf whose own box (in its frame) is `local` is where `world` places it: the least
// distance between opposite faces of that box carried into the world (a parallelepiped, turned,
// scaled or sheared), so that a thin plate turned 45 degrees, whose world box is as deep as it is
// wide, is still as thin as it is (an artist's turned 0.3 mm shim was exported in strips without
// a word). Infinity for an empty box; 0 for a flat one.
double placedThickness(const Bounds& local, const glm::dmat4& world) {
  if (local.empty()) return std::numeric_limits<double>::infinity();
  const glm::dvec3 size = local.size();
  const glm::dvec3 edge[3] = {glm::dvec3(world[0]) * size.x, glm::dvec3(world[1]) * size.y,
                              glm::dvec3(world[2]) * size.z};
  const double volume = std::fabs(glm::dot(edge[0], glm::cross(edge[1], edge[2])));
  double thickness = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a) {
    const double face = glm::length(glm::cross(edge[(a + 1) % 3], edge[(a + 2) % 3]));
    if (face > 0.0) thickness = std::min(thickness, volume / face);
  }
  return thickness;
}

// "part 'X' (0.001 mm across) is smaller than a cell (0.01 mm); ..." (`unit`: the scene's
// unitSymbol) when the leaf's largest extent (of its world bounds) is below the cell size h, so
// that it may vanish or break up at this resolution; "... is only 1.4 cells thick ..." when its
// thickness (the least of its world bounds' sizes and `placed`, its placedThickness) is below
// 2 h; "" otherwise.
std::string smallerThanCellWarning(const Node& node, const Bounds& bounds, double placed, double h,
                                   const char* unit) {
  if (bounds.empty()) return "";
  const glm::dvec3 size = bounds.size();
  const double extent = std::max({size.x, size.y, size.z});
  const double thickness = std::min({size.x, size.y, size.z, placed});
  // A sheet, flat but for rounding (an imported plane turned +Y up lay 6e-16 thick): "only
  // 1.8e-15 cells thick; about 2.2e+15x the resolution" said nothing useful (an artist's test).
  if (extent > 0.0 && thickness <= kFlatPart * extent)
    return nodeLabel(node) +
           " is flat (no thickness): it encloses no volume and adds nothing to the result";
  if (extent >= h && thickness < 2.0 * h) {
    // Big enough to show, too thin to keep its shape: say by how much the resolution must grow
    // for it to be four cells thick.
    // The factor whole from 10 on: "4.4e+02x" read as a formula (an artist's test).
    const double factor = 4.0 * h / std::max(thickness, 1e-300);
    char times[48];
    std::snprintf(times, sizeof(times), factor >= 10.0 ? "%.0f" : "%.2g", factor);
    char text[280];
    std::snprintf(text, sizeof(text),
                  " is only %.2g cells thick (%.3g %s; a cell is %.3g %s): its shape is lost at "
                  "this resolution; about %s times the resolution makes it 4 cells thick",
                  thickness / h, thickness, unit, h, unit, times);
    return nodeLabel(node) + text;
  }
  if (extent >= h) return "";
  char text[200];
  std::snprintf(text, sizeof(text),
                " (%.3g %s across) is smaller than a cell (%.3g %s): it may vanish at this "
                "resolution; raise the resolution to see it",
                extent, unit, h, unit);
  return nodeLabel(node) + text;
}

// What is said of a mesh node kept without its file (meshMissing).
std::string missingMeshWarning(const Node& node) {
  return "mesh node '" + node.name + "' has no mesh (its file \"" + node.meshPath +
         "\" could not be read): nothing of it is evaluated";
}

// Calls `leaf` with every visible leaf under `node` (instances and pattern copies each once)
// and its world matrix; `parentWorld` is node's parent's, `asInstance` says node is reached
// through an instance (which shows it even where it is hidden). The one walk of the leaves as
// placed: the small parts' warnings, the fallback grid and the far part's warning use it.
void forEachVisibleLeaf(const NodePtr& node, const NodePtr& root, const glm::dmat4& parentWorld,
                        bool asInstance, int depth,
                        const std::function<void(const Node&, const glm::dmat4&)>& leaf) {
  if (!node || depth > kDepthGuard || (!node->visible && !asInstance)) return;
  const glm::dmat4 world = parentWorld * node->transform.matrix();
  if (node->kind == NodeKind::Instance) {
    forEachVisibleLeaf(findNode(root, node->instanceOf), root, world, true, depth + 1, leaf);
  } else if (isOperation(node->kind)) {
    for (const glm::dmat4& placement : placementsOf(*node))
      for (const auto& c : node->children)
        forEachVisibleLeaf(c, root, world * placement, false, depth + 1, leaf);
  } else {
    leaf(*node, world);
  }
}

// smallerThanCellWarning (or missingMeshWarning) of every visible leaf of the scene `root`,
// each sentence once, into *out.
void collectSmallParts(const NodePtr& root, double h, const char* unit,
                       std::vector<std::string>* out) {
  forEachVisibleLeaf(
      root, root, glm::dmat4(1.0), false, 0, [&](const Node& node, const glm::dmat4& world) {
        const std::string w =
            meshMissing(node)
                ? missingMeshWarning(node)
                : smallerThanCellWarning(node, leafBounds(node, world),
                                         placedThickness(leafBounds(node, glm::dmat4(1.0)), world),
                                         h, unit);
        if (!w.empty() && std::find(out->begin(), out->end(), w) == out->end()) out->push_back(w);
      });
}

// Bounds of everything visible in the scene `root`, whatever the operations: the fallback grid
// of a scene whose result is empty (so that the evaluation still runs and reports an empty
// result).
Bounds allLeafBounds(const NodePtr& root) {
  Bounds out;
  forEachVisibleLeaf(
      root, root, glm::dmat4(1.0), true, 0,
      [&](const Node& node, const glm::dmat4& world) { out.include(leafBounds(node, world)); });
  return out;
}

}  // namespace

struct Evaluator::Context {
  const Scene* scene = nullptr;
  Grid grid;
  Progress* progress = nullptr;
  EvalResult* result = nullptr;
  StageStats stages[kStageCount];
  int total = 1;
  int done = 0;
  std::unordered_map<uint64_t, NodeId> firstLeafWithContent;  // leaf content key -> leaf id
  std::unordered_set<NodeId> keep;                            // EvalOptions::keep
  double skipModifiersUnderCells = 0.0;                       // EvalOptions'
  std::unordered_set<NodeId> applyModifiers;                  // EvalOptions'
  int insideInstance = 0;  // > 0 while visiting an instance's target

  // The first walk only collects the leaves to sample (sampleMeshes takes them in one call);
  // the second finds every leaf's LDI cached and combines.
  bool collecting = false;
  struct PendingLeaf {
    uint64_t key = 0;
    std::shared_ptr<const TriangleMesh> mesh;
    glm::dmat4 world{1.0};
    uint32_t leafId = 0;
    std::string warning;
  };
  std::vector<PendingLeaf> pending;
  std::unordered_set<uint64_t> pendingKeys;
  // Keys sampled by this evaluation and not visited yet by the second walk: its first visit of
  // each is reported as computed, with its share of the batch's time.
  std::unordered_map<uint64_t, double> sampledNow;
  // Primitives tessellated by this evaluation, by kind, parameters and segments.
  std::unordered_map<uint64_t, std::shared_ptr<const TriangleMesh>> tessellations;

  void finishStage(Stage s, double seconds, uint64_t surfels) {
    stages[s].seconds += seconds;
    stages[s].surfels += surfels;
    stages[s].peakBytes = peakResidentBytes();
    stages[s].runs += 1;
  }
  void warn(const std::string& warning) {
    if (warning.empty()) return;
    auto& list = result->warnings;
    if (std::find(list.begin(), list.end(), warning) == list.end()) list.push_back(warning);
  }
  // Progress units a modifier's visit counts for (see evaluate): its passes over the whole
  // lattice outweigh a leaf's sampling or a Boolean (one unit each) by about the grid's layers.
  int modifierUnits = 1;
  void nodeDone(int units = 1) {
    done += units;
    progress->report("evaluate", double(done) / double(total));
  }
};

// What a modifier node that left nothing of its (non-empty) parts did.
std::string emptiedByModifier(const Node& node, const char* unit) {
  char amount[48];
  std::snprintf(amount, sizeof(amount), "%.4g %s", std::fabs(node.amount), unit);
  char twice[48];
  std::snprintf(twice, sizeof(twice), "%.4g %s", 2.0 * std::fabs(node.amount), unit);
  const std::string who = nodeLabel(node) + " ";
  switch (modifierOf(node.kind)) {
    case Modifier::Round:
      return who + "left nothing of its parts: a round of radius " + amount +
             " removes every wall thinner than " + twice + "; a smaller radius keeps them";
    case Modifier::Offset:
      return who + "left nothing of its parts: shrinking by " + amount +
             " removes every part thinner than " + twice;
    case Modifier::Shell:
      return who + "left nothing of its parts: a wall of " + amount +
             " is thinner than the cell size; raise the resolution or the thickness";
    default:
      return who + "left nothing of its parts";
  }
}

const char* outcomeName(NodeOutcome outcome) {
  switch (outcome) {
    case NodeOutcome::Computed:
      return "computed";
    case NodeOutcome::Cached:
      return "cached";
    case NodeOutcome::PassThrough:
      return "pass-through";
    case NodeOutcome::Merged:
      return "merged";
    default:
      return "empty";
  }
}

Evaluator::Evaluator(std::shared_ptr<Backend> backend) : backend_(std::move(backend)) {}

// Thrown by evaluateCached's walk where a node would be computed.
struct Evaluator::NotCached {};

namespace {

// The halo (modifierHaloCells) of `node`'s subtree: its visible children, and what instances
// stand for whether shown or not (as the evaluation visits them); `depth` guards against
// instance cycles as the evaluation does.
int64_t haloCells(const NodePtr& node, const NodePtr& root, double h, int depth) {
  if (!node) return 0;
  if (depth > kDepthGuard) throw Error("the tree is too deep to evaluate (instance cycle?)");
  if (node->kind == NodeKind::Instance)
    return haloCells(findNode(root, node->instanceOf), root, h, depth + 1);
  int64_t below = 0;
  for (const auto& c : node->children)
    if (c->visible) below = std::max(below, haloCells(c, root, h, depth + 1));
  const ModifierReach reach = modifierReach(node->kind, node->amount);
  if (reach.offsets == 0) return below;
  // Amounts are checked where the node is evaluated; a halo beyond any grid is clamped there.
  const double cells = std::isfinite(reach.distance) ? std::ceil(reach.distance / h) : 1e9;
  return below + int64_t(std::min(cells, 1e9)) + int64_t(reach.offsets) * kOffsetHaloCells;
}

}  // namespace

bool withinWithRoom(const Bounds& content, const Grid& grid) {
  const Bounds window = grid.bounds();
  const glm::dvec3 room(2.0 * grid.h);
  return glm::all(glm::greaterThanEqual(content.min - room, window.min)) &&
         glm::all(glm::lessThanEqual(content.max + room, window.max));
}

bool hasModifier(const NodePtr& root) {
  return haloCells(root, root, 1.0, 0) > 0;  // every modifier's halo is at least one offset's
}

int modifierHaloCells(const NodePtr& root, double h) {
  return int(std::min<int64_t>(haloCells(root, root, h, 0), 1 << 30));
}

Bounds nodeBounds(const NodePtr& node, const NodePtr& root, const glm::dmat4& parentWorld) {
  return boundsOf(node, root, parentWorld, false, 0);
}

namespace {

// Scenes whose volume and area doubles can measure: extents and distances from the origin up to
// 1e100 units, extents down to 1e-100 (a box of 1e308 measured an infinite volume, one of
// 1e-300 a volume of 0, and both evaluated "successfully").
constexpr double kMaxSceneUnits = 1e100;
constexpr double kMinSceneExtent = 1e-100;

void checkSceneSize(const Bounds& b) {
  if (b.empty()) return;
  const glm::dvec3 size = b.size();
  const double extent = std::max({size.x, size.y, size.z});
  const double far = std::max({std::fabs(b.min.x), std::fabs(b.min.y), std::fabs(b.min.z),
                               std::fabs(b.max.x), std::fabs(b.max.y), std::fabs(b.max.z)});
  char text[160];
  if (!std::isfinite(extent) || !std::isfinite(far) || extent > kMaxSceneUnits ||
      far > kMaxSceneUnits) {
    std::snprintf(text, sizeof(text),
                  "the scene spans %.3g units at up to %.3g from the origin: more than 1e100, "
                  "where its volume and area cannot be measured; scale it down",
                  extent, far);
    throw Error(text);
  }
  if (extent < kMinSceneExtent) {
    std::snprintf(text, sizeof(text),
                  "the scene spans %.3g units: less than 1e-100, where its volume and area "
                  "cannot be measured; scale it up",
                  extent);
    throw Error(text);
  }
}

}  // namespace

namespace {
// A hidden root hides everything (the format: hidden nodes take no part), as a hidden child
// does; it was evaluated as shown.
void refuseHiddenRoot(const Scene& scene) {
  if (scene.root && !scene.root->visible)
    throw Error("the scene is empty: its root, " + nodeLabel(*scene.root) +
                ", is hidden, so nothing is visible to evaluate");
}

// "" where the scene has no bounds of its own or its parts lie within them; else what the bounds
// cut off (a box of 1 x 1 x 1.2 in bounds 1 x 1 x 1 was cut flat without a word: a numbers
// check), for EvalResult::warnings.
std::string boundsCutWarning(const Scene& scene) {
  if (!scene.settings.hasBounds || !scene.root) return "";
  const Bounds parts = boundsOf(scene.root, scene.root, glm::dmat4(1.0), true, 0);
  const Bounds& box = scene.settings.bounds;
  if (parts.empty()) return "";
  const double slack = 1e-9 * glm::length(box.size());
  std::string sides;
  for (int a = 0; a < 3; ++a) {
    char text[96];
    if (parts.min[a] < box.min[a] - slack) {
      std::snprintf(text, sizeof(text), "%s%c down to %.4g (the bounds start at %.4g)",
                    sides.empty() ? "" : ", ", "xyz"[a], parts.min[a], box.min[a]);
      sides += text;
    }
    if (parts.max[a] > box.max[a] + slack) {
      std::snprintf(text, sizeof(text), "%s%c up to %.4g (the bounds end at %.4g)",
                    sides.empty() ? "" : ", ", "xyz"[a], parts.max[a], box.max[a]);
      sides += text;
    }
  }
  if (sides.empty()) return "";
  return "the scene's own bounds (settings.bounds) cut its parts, which reach " + sides +
         ": the result is cut flat there; widen the bounds or remove them";
}
// "" unless one leaf far from the rest stretches the scene's grid: where the grid's longest side
// is at least 4 times what the rest of the scene needs and twice the leaf's own (every cell 4 times
// as large: an artist's sphere at x = 120 doubled the cell, and a position typed as 1e9 emptied the
// view, the warnings blaming the parts that had become smaller than a cell); then which leaf, and
// by how much. Leaves are taken within the scene's bounds (a cutter beyond its part stretches
// nothing).
std::string farPartWarning(const Scene& scene) {
  if (scene.settings.hasBounds || !scene.root) return "";
  const Bounds all = boundsOf(scene.root, scene.root, glm::dmat4(1.0), true, 0);
  if (all.empty()) return "";
  std::vector<std::pair<const Node*, Bounds>> leaves;
  forEachVisibleLeaf(scene.root, scene.root, glm::dmat4(1.0), false, 0,
                     [&](const Node& node, const glm::dmat4& world) {
                       leaves.push_back({&node, leafBounds(node, world)});
                     });
  for (auto& leaf : leaves) leaf.second = leaf.second.intersected(all);
  leaves.erase(std::remove_if(leaves.begin(), leaves.end(),
                              [](const auto& leaf) { return leaf.second.empty(); }),
               leaves.end());
  const size_t n = leaves.size();
  if (n < 2) return "";
  std::vector<Bounds> before(n + 1), after(n + 1);  // the union of the leaves before / after i
  for (size_t i = 0; i < n; ++i) {
    before[i + 1] = before[i];
    before[i + 1].include(leaves[i].second);
    after[n - 1 - i] = after[n - i];
    after[n - 1 - i].include(leaves[n - 1 - i].second);
  }
  // The leaf without which the grid shrinks most, and the next most: one part far from the rest
  // is said, not two (or more) far apart, which the scene means to hold (parts laid out on a
  // print bed), where no one of them alone stretches the grid.
  const double whole = all.longestSide();
  size_t far = n;
  double rest = whole, next = whole;
  for (size_t i = 0; i < n; ++i) {
    Bounds others = before[i];
    others.include(after[i + 1]);
    if (others.empty()) continue;
    const double side = others.longestSide();
    if (side < rest) {
      next = rest;
      rest = side;
      far = i;
    } else if (side < next) {
      next = side;
    }
  }
  if (far == n || !(rest > 0.0) || whole < 4.0 * rest || whole >= 2.0 * next) return "";
  // Far, not large: the grid is mostly the space between it and the rest (a large part holding
  // a small one stretches nothing).
  if (2.0 * leaves[far].second.longestSide() > whole) return "";
  const char* unit = unitSymbol(scene.settings.unit);
  char text[320];
  std::snprintf(text, sizeof(text),
                " lies far from the rest of the scene: the grid spans %.4g %s to hold it where the "
                "rest spans %.4g %s, so every cell is %.3gx as large and the rest that much "
                "coarser; move it closer, or hide it while working on the rest",
                whole, unit, rest, unit, whole / rest);
  return nodeLabel(*leaves[far].first) + text;
}
}  // namespace

std::vector<std::string> Evaluator::smallPartWarnings(const Scene& scene, int resolution) {
  std::vector<std::string> out;
  if (!scene.root) return out;
  const Grid grid = gridFor(scene, resolution);
  collectSmallParts(scene.root, grid.h, unitSymbol(scene.settings.unit), &out);
  // First: it says why the others are small (evaluate puts it first too).
  const std::string far = farPartWarning(scene);
  if (!far.empty()) out.insert(out.begin(), far);
  return out;
}

Grid Evaluator::gridFor(const Scene& scene, int resolution) {
  int n = resolution > 0 ? resolution : scene.settings.resolution;
  refuseHiddenRoot(scene);
  checkExpansion(scene.root, scene.settings.maxLeaves);  // before any walk through instances
  if (scene.settings.hasBounds) {
    checkSceneSize(scene.settings.bounds);
    return makeGridExact(scene.settings.bounds, n);
  }
  Bounds b = boundsOf(scene.root, scene.root, glm::dmat4(1.0), true, 0);
  if (b.empty()) b = allLeafBounds(scene.root);
  checkSceneSize(b);
  return makeGrid(b, n, scene.settings.margin);
}

Grid Evaluator::previewGridFor(const Scene& scene, int resolution, const Grid* previous) {
  const Grid ideal = gridFor(scene, resolution);
  if (scene.settings.hasBounds) return ideal;
  const int n = resolution > 0 ? resolution : scene.settings.resolution;
  const Bounds wanted = ideal.bounds();
  if (previous && previous->h <= ideal.h * kLatticeSlack &&
      previous->h * kLatticeSlack >= ideal.h) {
    Grid g = *previous;
    bool fits = true;
    for (int a = 0; a < 3; ++a) {
      const double lo = std::floor((wanted.min[a] - g.origin[a]) / g.h + 1e-9);
      const double hi = std::ceil((wanted.max[a] - g.origin[a]) / g.h - 1e-9);
      fits = fits && lo >= 0.0 && hi <= 4.0 * n && hi > lo;
      if (!fits) break;
      g.first[a] = int(lo);
      g.cells[a] = int(hi - lo);
    }
    if (fits) return g;
  }
  Grid fresh = ideal;
  const int room = n / 4;
  fresh.origin -= glm::dvec3(room) * ideal.h;
  fresh.first = glm::ivec3(room);
  return fresh;
}

uint64_t Evaluator::meshHash(const std::shared_ptr<const TriangleMesh>& mesh) {
  auto it = meshHashes_.find(mesh.get());
  if (it != meshHashes_.end() && !it->second.mesh.expired() && it->second.mesh.lock() == mesh)
    return it->second.hash;
  Hasher h;
  h.bytes(mesh->positions.data(), mesh->positions.size() * sizeof(glm::dvec3));
  h.bytes(mesh->triangles.data(), mesh->triangles.size() * sizeof(mesh->triangles[0]));
  uint64_t digest = h.digest();
  // Forget memos of meshes that are gone, so the table does not grow without bound.
  for (auto m = meshHashes_.begin(); m != meshHashes_.end();)
    m = m->second.mesh.expired() ? meshHashes_.erase(m) : std::next(m);
  meshHashes_[mesh.get()] = MeshHashMemo{mesh, digest};
  return digest;
}

Evaluator::Visit Evaluator::visitLeaf(const NodePtr& node, const glm::dmat4& world, Context& ctx) {
  // The leaf's content: what it samples to, whoever it is.
  Hasher content;
  content.add(uint8_t(node->kind));
  const glm::dmat4& m = world;
  content.bytes(glm::value_ptr(m), sizeof(double) * 16);
  hashLattice(content, ctx.grid);
  int segments = 0;
  if (node->kind == NodeKind::Mesh) {
    if (!node->mesh) throw Error("mesh node '" + node->name + "' has no mesh loaded");
    content.add(meshHash(node->mesh));
  } else {
    const PrimitiveParams& p = node->params;
    segments = p.segments > 0 ? p.segments
                              : autoSegments(primitiveRadius(node->kind, p) * largestScale(world),
                                             kAutoChordErrorCells * ctx.grid.h);
    hashPrimitiveParams(content, node->kind, p);
    content.add(segments);
  }
  // Identical leaves (same content, same place) share one LDI, tagged with the first of them in
  // tree order: a thousand copies of a part cost one sampling, and the Booleans below see equal
  // keys and drop the duplicates. Keyed with that leaf's id, so a cached LDI is reused only
  // while its tag names a leaf of the scene being evaluated.
  const NodeId leafId = ctx.firstLeafWithContent.emplace(content.digest(), node->id).first->second;
  Hasher key;
  key.add(content.digest()).add(leafId);
  Visit v;
  v.key = key.digest();
  // Collecting, a leaf not cached is prepared for the batch; in the second walk every leaf is
  // cached (one that was not collected, should the walks ever differ, is sampled alone now).
  auto hit = cache_.find(v.key);
  if (hit != cache_.end() &&
      !onGrid(hit->second, ctx.grid, [&] { return leafBounds(*node, world); })) {
    cache_.erase(hit);  // computed on a window that clipped it, or this one clips it
    hit = cache_.end();
  }
  if (hit == cache_.end() && ctx.pendingKeys.insert(v.key).second) {
    std::shared_ptr<const TriangleMesh> mesh = node->mesh;
    if (node->kind != NodeKind::Mesh) {
      // Copies of a primitive (instances, patterns) share one tessellation.
      Hasher shape;
      shape.add(uint8_t(node->kind));
      hashPrimitiveParams(shape, node->kind, node->params);
      shape.add(segments);
      std::shared_ptr<const TriangleMesh>& made = ctx.tessellations[shape.digest()];
      if (!made) {
        Stopwatch tessellate;
        made =
            std::make_shared<TriangleMesh>(tessellatePrimitive(node->kind, node->params, segments));
        ctx.finishStage(kTessellate, tessellate.seconds(), 0);
      }
      mesh = made;
    }
    if (mesh->triangles.empty()) {
      // A mesh node kept without its file (meshMissing: MissingMeshes::Keep): nothing, on any
      // backend, and said.
      cache_[v.key] = CacheEntry{backend_->empty(ctx.grid), generation_, missingMeshWarning(*node)};
      hit = cache_.find(v.key);
    } else {
      const Bounds bounds = meshWorldBounds(mesh, world);
      checkLeafPlacement(*node, world, bounds);
      if (onlyCached_) throw NotCached{};
      ctx.pending.push_back(Context::PendingLeaf{
          v.key, mesh, world, uint32_t(leafId),
          smallerThanCellWarning(*node, bounds,
                                 placedThickness(meshWorldBounds(mesh, glm::dmat4(1.0)), world),
                                 ctx.grid.h, unitSymbol(ctx.scene->settings.unit))});
    }
  }
  if (ctx.collecting) return v;
  if (hit == cache_.end()) {
    sampleCollected(ctx);
    hit = cache_.find(v.key);
    if (hit == cache_.end()) throw Error("internal: leaf '" + node->name + "' was not sampled");
  }
  NodeRecord record{node->id, node->name, kindName(node->kind), NodeOutcome::Cached, 0.0, 0};
  hit->second.generation = generation_;
  v.ldi = hit->second.ldi;
  ctx.warn(hit->second.warning);
  auto now = ctx.sampledNow.find(v.key);
  if (now != ctx.sampledNow.end()) {
    record.outcome = NodeOutcome::Computed;
    record.seconds = now->second;
    ctx.sampledNow.erase(now);
    ++ctx.result->computed;
  } else {
    ++ctx.result->reused;
  }
  record.surfels = v.ldi->surfelCount();
  ctx.result->nodes.push_back(record);
  ctx.nodeDone();
  return v;
}

void Evaluator::sampleCollected(Context& ctx) {
  if (ctx.pending.empty()) return;
  // In groups of about an eighth of the triangles (at least a million a group), so that the
  // progress moves while big leaves are sampled; a small scene is one call.
  uint64_t triangles = 0;
  for (const auto& p : ctx.pending) triangles += p.mesh->triangles.size();
  const uint64_t perGroup = std::max<uint64_t>(triangles / 8, 1000000);
  ctx.total += int(std::min<size_t>(ctx.pending.size(), 1u << 30));  // a unit per leaf sampled
  Stopwatch sample;
  uint64_t surfels = 0;
  size_t first = 0;
  while (first < ctx.pending.size()) {
    std::vector<LeafToSample> leaves;
    uint64_t groupTriangles = 0;
    size_t end = first;
    for (; end < ctx.pending.size() && (end == first || groupTriangles < perGroup); ++end) {
      const auto& p = ctx.pending[end];
      leaves.push_back(LeafToSample{p.mesh.get(), p.world, p.leafId});
      groupTriangles += p.mesh->triangles.size();
    }
    const std::vector<LdiHandle> ldis = backend_->sampleMeshes(leaves, ctx.grid, *ctx.progress);
    for (size_t k = 0; k < ldis.size(); ++k) {
      const auto& p = ctx.pending[first + k];
      cache_[p.key] = CacheEntry{ldis[k], generation_, p.warning};
      surfels += ldis[k]->surfelCount();
    }
    ctx.done += int(ldis.size());
    ctx.progress->report("evaluate", double(ctx.done) / double(ctx.total));
    first = end;
  }
  const double seconds = sample.seconds();
  for (const auto& p : ctx.pending) ctx.sampledNow[p.key] = seconds / double(ctx.pending.size());
  ctx.finishStage(kSample, seconds, surfels);
  ctx.stages[kSample].runs += int(ctx.pending.size()) - 1;
  ctx.pending.clear();
}

// Equal keys mean equal LDIs: A op A = A for union and intersection, and subtracting A twice
// subtracts it once. Drops the repeats (keeping order); returns false when the result is empty
// without work (a difference whose base is among its cutters: A - A).
bool Evaluator::dropDuplicateOperands(RayOp op, std::vector<Visit>* operands) {
  std::unordered_set<uint64_t> seen;
  std::vector<Visit> kept;
  for (size_t i = 0; i < operands->size(); ++i) {
    const Visit& o = (*operands)[i];
    if (op == RayOp::Difference && i > 0 && o.key == (*operands)[0].key) return false;
    if (seen.insert(o.key).second) kept.push_back(o);
  }
  *operands = std::move(kept);
  return true;
}

bool Evaluator::onGrid(CacheEntry& entry, const Grid& grid,
                       const std::function<Bounds()>& content) {
  const Grid& had = entry.ldi->grid();
  if (had == grid) return true;
  const Bounds b = content();
  if (b.empty() ? entry.ldi->surfelCount() > 0
                : !(withinWithRoom(b, had) && withinWithRoom(b, grid)))
    return false;
  LdiHandle moved = backend_->rewindow(entry.ldi, grid);
  if (!moved) return false;
  entry.ldi = std::move(moved);
  return true;
}

LdiHandle Evaluator::cachedOr(uint64_t key, const Grid& grid,
                              const std::function<Bounds()>& content, NodeRecord& record,
                              const std::function<LdiHandle()>& compute) {
  auto hit = cache_.find(key);
  if (hit != cache_.end() && !onGrid(hit->second, grid, content)) {
    cache_.erase(hit);
    hit = cache_.end();
  }
  if (hit != cache_.end()) {
    hit->second.generation = generation_;
    record.outcome = NodeOutcome::Cached;
    return hit->second.ldi;
  }
  if (onlyCached_) throw NotCached{};
  LdiHandle ldi = compute();
  record.outcome = NodeOutcome::Computed;
  cache_[key] = CacheEntry{ldi, generation_, {}};
  return ldi;
}

namespace {
// Whether operation `node` (visible, or an instance's target) joins the Boolean `op` of its
// parent as an operand of the given role (Evaluator::collectOperands): a union into a union, an
// intersection into an intersection, a difference as the base of a difference, a union as a
// cutter of one; never a modifier, a pattern or a node kept for its own LDI, nor one without a
// visible child (it evaluates to nothing, which for an intersection is not the same as no
// operand) or, for a difference, with a hidden base.
bool mergeable(const Node& node, RayOp op, bool asCutter, const std::unordered_set<NodeId>& keep) {
  if (!isOperation(node.kind) || node.kind == NodeKind::Instance ||
      modifierOf(node.kind) != Modifier::None || patternOf(node.kind) != Pattern::None ||
      keep.count(node.id))
    return false;
  if (std::none_of(node.children.begin(), node.children.end(),
                   [](const NodePtr& c) { return c->visible; }))
    return false;
  const RayOp own = nodeKindInfo(node.kind).rayOp;
  if (op != RayOp::Difference) return own == op;
  if (asCutter) return own == RayOp::Union;
  return own == RayOp::Difference && node.children[0]->visible;
}
}  // namespace

void Evaluator::collectOperands(const NodePtr& node, RayOp op, const glm::dmat4& world, int depth,
                                Context& ctx, std::vector<Visit>* operands) {
  const RayOp own = nodeKindInfo(node->kind).rayOp;
  bool first = true;
  for (const auto& c : node->children) {
    if (!c->visible) continue;
    // In a merged difference its own base leads and its cutters follow as cutters; in a
    // merged union or intersection every part keeps the role the node had in the collector.
    const bool asCutter =
        op == RayOp::Difference && (own == RayOp::Difference ? !first : operands->size() > 0);
    first = false;
    NodePtr target = c;
    glm::dmat4 targetWorld = world * c->transform.matrix();
    const bool instance = c->kind == NodeKind::Instance;
    if (instance) {
      target = findNode(ctx.scene->root, c->instanceOf);
      if (target) targetWorld = targetWorld * target->transform.matrix();
    }
    if (!target || depth + 1 > kDepthGuard || !mergeable(*target, op, asCutter, ctx.keep)) {
      operands->push_back(visit(c, world, depth + 1, ctx));
      continue;
    }
    ctx.progress->check();
    ctx.insideInstance += instance ? 1 : 0;
    collectOperands(target, op, targetWorld, depth + (instance ? 2 : 1), ctx, operands);
    ctx.insideInstance -= instance ? 1 : 0;
    if (!ctx.collecting) {
      ctx.result->nodes.push_back(NodeRecord{target->id, target->name, kindName(target->kind),
                                             NodeOutcome::Merged, 0.0, 0});
      ctx.nodeDone();
    }
  }
}

Evaluator::Visit Evaluator::visit(const NodePtr& node, const glm::dmat4& parentWorld, int depth,
                                  Context& ctx) {
  const bool instance = node->kind == NodeKind::Instance;
  ctx.insideInstance += instance ? 1 : 0;
  Visit v = visitNode(node, parentWorld, depth, ctx);
  ctx.insideInstance -= instance ? 1 : 0;
  if (!ctx.collecting && ctx.insideInstance == 0 && !ctx.keep.empty() && ctx.keep.count(node->id))
    ctx.result->kept.push_back(KeptLdi{node->id, v.ldi});
  return v;
}

Evaluator::Visit Evaluator::visitNode(const NodePtr& node, const glm::dmat4& parentWorld, int depth,
                                      Context& ctx) {
  if (depth > kDepthGuard) throw Error("the tree is too deep to evaluate (instance cycle?)");
  ctx.progress->check();
  glm::dmat4 world = parentWorld * node->transform.matrix();
  if (node->kind == NodeKind::Instance) {
    NodePtr target = findNode(ctx.scene->root, node->instanceOf);
    if (!target)
      throw Error("instance '" + node->name + "' refers to missing node id " +
                  std::to_string(node->instanceOf));
    return visit(target, world, depth + 1, ctx);  // the target's own flag is ignored
  }
  if (!isOperation(node->kind)) return visitLeaf(node, world, ctx);

  // Hidden children take no part, except that a hidden base leaves a difference empty: its
  // first cutter never becomes the base (roles.h).
  const RayOp op = nodeKindInfo(node->kind).rayOp;
  const bool hiddenBase =
      op == RayOp::Difference && !node->children.empty() && !node->children[0]->visible;
  std::vector<Visit> children;
  const std::vector<glm::dmat4> placements = placementsOf(*node);
  for (size_t k = 0; k < placements.size(); ++k) {
    // A pattern's copies are reached as instances are: their LDIs are not kept. The first
    // placement is the one the editor shows the children at (patterns.h: firstPlacement): kept.
    const int copy = k == 0 ? 0 : 1;
    ctx.insideInstance += copy;
    if (!hiddenBase) collectOperands(node, op, world * placements[k], depth, ctx, &children);
    ctx.insideInstance -= copy;
  }
  // Collecting leaves: a shell's walls without its opening hold the same leaves.
  if (ctx.collecting) return Visit{};
  // Empty operands decide some results without a Boolean.
  std::vector<Visit> operands;
  bool resultEmpty = children.empty();
  for (size_t i = 0; i < children.size(); ++i) {
    bool empty = children[i].ldi->surfelCount() == 0;
    if (op == RayOp::Intersection && empty) resultEmpty = true;
    if (op == RayOp::Difference && i == 0 && empty) resultEmpty = true;
    if (!empty) operands.push_back(children[i]);
  }
  resultEmpty = resultEmpty || !dropDuplicateOperands(op, &operands);
  NodeRecord record{node->id, node->name, kindName(node->kind), NodeOutcome::Computed, 0.0, 0};
  // Where the node's result can lie (a cached one computed on another window is kept when it
  // lies within both: onGrid).
  auto content = [&] { return boundsOf(node, ctx.scene->root, parentWorld, true, depth); };
  Visit v;
  if (resultEmpty || operands.empty()) {
    Hasher key;
    key.add(uint8_t(0xEE));
    hashGrid(key, ctx.grid);
    v.key = key.digest();
    // One empty LDI per grid, kept like any result .
    auto hit = cache_.find(v.key);
    if (hit != cache_.end()) {
      hit->second.generation = generation_;
      v.ldi = hit->second.ldi;
    } else {
      v.ldi = backend_->empty(ctx.grid);
      cache_[v.key] = CacheEntry{v.ldi, generation_, {}};
    }
    record.outcome = NodeOutcome::Empty;
  } else if (operands.size() == 1) {
    // A single operand (the others empty, or the only child) is the result itself.
    v = operands[0];
    record.outcome = NodeOutcome::PassThrough;
  } else {
    Hasher key;
    key.add(uint8_t(node->kind));
    hashLattice(key, ctx.grid);
    for (const auto& c : operands) key.add(c.key);
    v.key = key.digest();
    v.ldi = cachedOr(v.key, ctx.grid, content, record, [&] {
      std::vector<LdiHandle> inputs;
      for (const auto& c : operands) inputs.push_back(c.ldi);
      Stopwatch watch;
      LdiHandle out = backend_->combine(op, inputs, ctx.grid, *ctx.progress);
      record.seconds = watch.seconds();
      ctx.finishStage(kBoolean, record.seconds, out->surfelCount());
      return out;
    });
  }
  const Modifier modifier = modifierOf(node->kind);
  const bool skipped = modifier != Modifier::None &&
                       std::abs(node->amount) < ctx.skipModifiersUnderCells * ctx.grid.h &&
                       !ctx.applyModifiers.count(node->id);
  if (skipped) {
    const std::string name = nodeLabel(*node);
    auto& list = ctx.result->skippedModifiers;
    if (std::find(list.begin(), list.end(), name) == list.end()) list.push_back(name);
  }
  if (modifier != Modifier::None && !skipped && v.ldi->surfelCount() > 0 &&
      !(modifier == Modifier::Offset && node->amount == 0.0)) {
    // The children's union, changed by the modifier: keyed on it, the kind and the amount.
    checkModifierAmount(node->kind, node->amount, nodeLabel(*node));
    Hasher key;
    key.add(uint8_t(0xA0)).add(uint8_t(node->kind)).add(node->amount).add(v.key);
    // A shell's opening: the wall follows the children without the opening part.
    LdiHandle wallOf;
    if (modifier == Modifier::Shell) {
      if (NodePtr without = withoutOpening(node)) {
        const Visit wall = visit(without, parentWorld, depth, ctx);
        key.add(uint8_t(0x0B)).add(wall.key);
        wallOf = wall.ldi;
      }
    }
    hashLattice(key, ctx.grid);
    v.key = key.digest();
    const LdiHandle united = v.ldi;
    v.ldi = cachedOr(v.key, ctx.grid, content, record, [&] {
      Stopwatch watch;
      // The modifier's own progress ("modify", over its offsets' passes) moves the evaluation's
      // bar within this node's step: a round at high resolution is most of an evaluation.
      Progress within(ctx.progress, [&ctx](const std::string&, double f) {
        ctx.progress->report(
            "evaluate", (double(ctx.done) + std::clamp(f, 0.0, 1.0) * double(ctx.modifierUnits)) /
                            double(ctx.total));
      });
      LdiHandle out = backend_->modify(modifier, node->amount, united, within, wallOf);
      record.seconds += watch.seconds();
      ctx.result->modifySeconds += watch.seconds();
      ctx.finishStage(kBoolean, watch.seconds(), out->surfelCount());
      return out;
    });
    // A modifier that leaves nothing of its parts says why (an artist's 3 mm round of a part
    // with 3 mm walls emptied it, and only the inspector's grey note had said it could). Only
    // where this evaluation's grid holds the whole node: in an export's tile that holds a piece
    // of it, nothing left there says nothing of the rest.
    if (v.ldi->surfelCount() == 0) {
      const Bounds whole = boundsOf(node, ctx.scene->root, parentWorld, false, depth);
      const Bounds window = ctx.grid.bounds();
      if (!whole.empty() && glm::all(glm::greaterThanEqual(whole.min, window.min)) &&
          glm::all(glm::lessThanEqual(whole.max, window.max)))
        ctx.warn(emptiedByModifier(*node, unitSymbol(ctx.scene->settings.unit)));
    }
  }
  if (record.outcome == NodeOutcome::Cached) ++ctx.result->reused;
  if (record.outcome == NodeOutcome::Computed) ++ctx.result->computed;
  record.surfels = v.ldi->surfelCount();
  ctx.result->nodes.push_back(record);
  ctx.nodeDone(modifier != Modifier::None ? ctx.modifierUnits : 1);
  return v;
}

EvalResult Evaluator::evaluate(const Scene& scene, const EvalOptions& options, Progress& progress) {
  if (!scene.root) throw Error("the scene has no root node");
  return evaluateOn(scene, gridFor(scene, options.resolution), progress, options);
}

std::optional<EvalResult> Evaluator::evaluateCached(const Scene& scene, const Grid& grid,
                                                    Progress& progress,
                                                    const EvalOptions& options) {
  const uint64_t generation = generation_;
  onlyCached_ = true;
  try {
    EvalResult result = evaluateOn(scene, grid, progress, options);
    onlyCached_ = false;
    return result;
  } catch (const NotCached&) {
    onlyCached_ = false;
    generation_ = generation;  // as if it had not run: the cache keeps what it kept
    return std::nullopt;
  } catch (...) {
    onlyCached_ = false;
    generation_ = generation;
    throw;
  }
}

EvalResult Evaluator::evaluateOn(const Scene& scene, const Grid& grid, Progress& progress,
                                 const EvalOptions& options) {
  if (!scene.root) throw Error("the scene has no root node");
  refuseHiddenRoot(scene);
  Stopwatch total;
  EvalResult result;
  result.backend = backend_->description();
  ++generation_;
  Context ctx;
  ctx.scene = &scene;
  ctx.grid = grid;
  ctx.progress = &progress;
  ctx.result = &result;
  ctx.keep.insert(options.keep.begin(), options.keep.end());
  ctx.skipModifiersUnderCells = options.skipModifiersUnderCells;
  ctx.applyModifiers.insert(options.applyModifiers.begin(), options.applyModifiers.end());
  const TreeExpansion expansion = checkExpansion(scene.root, scene.settings.maxLeaves);
  // A unit of progress a node visit (and a leaf sampled, added as they are collected), but a
  // modifier's visit as many as half the grid's layers: its passes run over every lattice node,
  // where a leaf's sampling follows its rays (an offset at 768 cells took two thirds of the
  // bone scaffold's evaluation, and the bar sat at 33% through it: an artist's test).
  const uint64_t lattice =
      uint64_t(grid.cells.x + 1) * uint64_t(grid.cells.y + 1) * uint64_t(grid.cells.z + 1);
  const uint64_t longest = uint64_t(std::max({grid.cells.x, grid.cells.y, grid.cells.z}) + 1);
  ctx.modifierUnits = int(std::clamp<uint64_t>(lattice / (2 * longest * longest), 1, 4096));
  ctx.total =
      int(std::min<uint64_t>(expansion.nodes + std::min<uint64_t>(expansion.modifiers, 1u << 20) *
                                                   uint64_t(ctx.modifierUnits - 1),
                             1u << 30)) +
      1;
  for (int s = 0; s < kStageCount; ++s) ctx.stages[s].name = kStageNames[s];
  result.grid = ctx.grid;

  // The node evaluated: the root, or the one asked for alone, placed as the tree places it.
  NodePtr start = scene.root;
  glm::dmat4 startWorld(1.0);
  int startDepth = 0;
  if (options.alone != 0) {
    std::vector<const Node*> path;
    start = findNode(scene.root, options.alone);
    if (!start || !pathToNode(scene.root, options.alone, &path))
      throw Error("node #" + std::to_string(options.alone) + " is not in the scene");
    startWorld = parentWorldMatrix(scene.root, options.alone);
    startDepth = int(path.size()) - 1;
  }
  // First every leaf to sample, in one call to the backend; then the tree.
  ctx.collecting = true;
  visit(start, startWorld, startDepth, ctx);
  ctx.collecting = false;
  sampleCollected(ctx);
  Visit root = visit(start, startWorld, startDepth, ctx);
  result.root = root.ldi;
  result.rootKey = root.key;
  if (options.alone == 0) ctx.warn(boundsCutWarning(scene));
  // First: it says why parts are smaller than a cell (the empty result's hint quotes the first).
  if (const std::string far = options.alone == 0 ? farPartWarning(scene) : std::string();
      !far.empty() &&
      std::find(result.warnings.begin(), result.warnings.end(), far) == result.warnings.end())
    result.warnings.insert(result.warnings.begin(), far);
  Stopwatch measure;
  if (options.measureRoot)
    result.measure = backend_->measure(root.ldi, progress);
  else
    result.measure.surfels = root.ldi->surfelCount();
  ctx.finishStage(kMeasure, measure.seconds(), 0);
  ctx.nodeDone();

  // Keep what this and the previous evaluation used (so toggling between two states, such as a
  // coarse preview and its refinement, stays cached); drop the rest.
  for (auto it = cache_.begin(); it != cache_.end();)
    it = it->second.generation + 1 < generation_ ? cache_.erase(it) : std::next(it);
  for (const auto& entry : cache_) result.cacheBytes += entry.second.ldi->bytes();
  for (int s = 0; s < kStageCount; ++s) result.stages.push_back(ctx.stages[s]);
  result.seconds = total.seconds();
  result.peakBytes = peakResidentBytes();
  return result;
}

}  // namespace strata
