// Evaluation of a scene's CSG tree into the root's LDI, with a content-keyed cache.
//
// Chains of the same Boolean are flattened (union(union(a, b), c) is union(a, b, c); a difference
// whose base is a difference, or whose cutter is a union, one difference): one Boolean instead
// of one per level, so a deep tree costs what its parts do, not its depth (the paper's depth-28
// scaffold: 56 Booleans become 4). Nodes merged so have no LDI of their own (NodeOutcome::Merged);
// a node kept (EvalOptions::keep), a modifier or a pattern is never merged.
//
// Every node's LDI is cached under a key made of its content: kind and parameters, the world
// transform (for leaves), the mesh's content hash, the grid's lattice (origin and cell size, not
// its window: see onGrid), and the keys of its children. After
// one leaf changes, only the nodes on its path to the root get new keys and are recomputed; the
// result reports what was computed and what was reused. The tree is walked twice: once to
// collect the leaves not cached, which the backend samples in one call (sampleMeshes), then to
// combine.
//
// Threads: an Evaluator is used by one thread at a time. The Scene it reads is immutable.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "engine/document/scene.h"
#include "engine/eval/backend.h"
#include "engine/util/progress.h"

namespace strata {

struct EvalOptions {
  int resolution = 0;  // cells along the longest side; 0 = the scene's setting
  // Nodes whose own LDIs the result keeps (EvalResult::kept), e.g. the cutters the editor draws
  // as ghosts. A node reached only through instances is not kept.
  std::vector<NodeId> keep;
  // Modifiers (offset, shell, round, fillet) whose |amount| is under this many cells of the grid
  // are passed through: their children's union stands for them, unchanged, and each is named in
  // EvalResult::skippedModifiers. For a coarse preview, whose cells cannot resolve such an
  // amount (a 1 mm round on cells of 1.1 mm tears 3 mm walls apart), so that it shows the parts
  // whole until the full pass comes. 0: every modifier applies (exports, the full preview).
  double skipModifiersUnderCells = 0.0;
  // Modifiers applied whatever skipModifiersUnderCells says: the ones being edited (a coarse
  // draft of a drag on a round's radius showed the parts unrounded, whatever the radius: an
  // artist's test).
  std::vector<NodeId> applyModifiers;
  // Whether EvalResult::measure holds the root's volume, area and thinnest wall (a pass over its
  // surfels); without, only its surfel count (an export's tiles, which read nothing else).
  bool measureRoot = true;
  // When not 0: only this node is evaluated, alone (not combined with its siblings or parents),
  // placed as the tree shows it (parentWorldMatrix: its parents' transforms and the patterns'
  // first placements), instances resolved in the whole scene; EvalResult::root is its LDI. For
  // the editor's ghosts of cutters that reach beyond the result's grid. Throws strata::Error
  // where the scene holds no such node (reached without instances).
  NodeId alone = 0;
};

// A node's own LDI, before its parent combined it (world space, on the evaluation's grid).
struct KeptLdi {
  NodeId id = 0;
  LdiHandle ldi;
};

// Totals of one stage of the pipeline over all nodes of an evaluation.
struct StageStats {
  std::string name;        // "tessellate", "sample", "boolean", "measure"
  double seconds = 0.0;    // wall time spent in the stage
  uint64_t surfels = 0;    // surfels produced by the stage
  uint64_t peakBytes = 0;  // process peak resident memory when the stage last ended
  int runs = 0;            // nodes the stage ran for
};

// What happened to one node.
enum class NodeOutcome : uint8_t {
  Computed,     // sampled or combined now
  Cached,       // taken from the cache
  PassThrough,  // an operation with one non-empty operand: that operand's LDI, no work
  Empty,        // an operation whose result is empty without work (e.g. nothing visible)
  Merged,       // an operation combined in its parent's Boolean (Evaluator: flattened chains)
};
const char* outcomeName(NodeOutcome outcome);

struct NodeRecord {
  NodeId id = 0;
  std::string name;
  std::string kind;
  NodeOutcome outcome = NodeOutcome::Computed;
  double seconds = 0.0;  // time spent computing this node alone (0 unless Computed)
  uint64_t surfels = 0;
};

struct EvalResult {
  Grid grid;
  LdiHandle root;
  LdiMeasure measure;  // volume and area of the root, from its LDI
  std::vector<StageStats> stages;
  std::vector<NodeRecord> nodes;  // in evaluation order (children before parents)
  std::vector<KeptLdi> kept;      // of EvalOptions::keep that were evaluated, evaluation order
  int computed = 0;               // nodes with outcome Computed
  int reused = 0;                 // nodes with outcome Cached
  double seconds = 0.0;
  // Of `seconds`, the modifiers' own (offset, shell, round, fillet nodes computed): work that
  // grows with the grid's nodes, not with the surface as the rest does (job_estimate.h).
  double modifySeconds = 0.0;
  uint64_t peakBytes = 0;   // process peak resident memory after the evaluation
  uint64_t cacheBytes = 0;  // LDI memory held by the cache after the evaluation
  std::string backend;
  // Said once each, for the user: parts smaller than a cell (named), ...
  std::vector<std::string> warnings;
  // Modifiers passed through (EvalOptions::skipModifiersUnderCells), as "round 'rim'".
  std::vector<std::string> skippedModifiers;
  // The root's content key: equal keys (on one grid) mean the same root LDI, surfel for surfel
  // (the editor keeps its splats when an edit changed nothing they show: a measurement, a name).
  uint64_t rootKey = 0;
};

class Evaluator {
 public:
  explicit Evaluator(std::shared_ptr<Backend> backend);

  // Evaluates the visible tree. Throws strata::Error (e.g. an empty scene) or Cancelled.
  EvalResult evaluate(const Scene& scene, const EvalOptions& options, Progress& progress);
  // The same on an explicit grid, e.g. one tile (a window) of the scene's grid
  // (options.resolution is not read).
  EvalResult evaluateOn(const Scene& scene, const Grid& grid, Progress& progress,
                        const EvalOptions& options = {});

  // evaluateOn where the cache holds every node it needs (on this grid, or on another window of
  // its lattice that onGrid moves); nothing, computing nothing, where a node would have to be
  // sampled, combined or modified. For the editor: an edit that changed no part (a measurement,
  // a rename, an undo back to a state just shown) is shown at once, with no coarse pass first.
  std::optional<EvalResult> evaluateCached(const Scene& scene, const Grid& grid, Progress& progress,
                                           const EvalOptions& options = {});

  // The grid an evaluation at `resolution` (0 = the scene's) would use.
  static Grid gridFor(const Scene& scene, int resolution);
  // What an evaluation at `resolution` would say of visible parts too small or too thin for its
  // cells (the warnings it gives them: "... is only 1.1 cells thick ...") and of mesh nodes kept
  // without their file, each once, from the parts' bounds alone, nothing evaluated: said before
  // an export at its own resolution runs.
  // Throws what gridFor throws.
  static std::vector<std::string> smallPartWarnings(const Scene& scene, int resolution);
  // The grid of an interactive preview at `resolution` that follows `previous` (the last one
  // of that resolution; null for none): gridFor's window on the lattice of `previous` while its
  // cells stay within kLatticeSlack of gridFor's size and its window can start at a node of
  // index >= 0 (and below resolution * 4), else gridFor's grid on a lattice of its own whose
  // window starts at node resolution / 4 on every axis (room for the scene to move toward -x,
  // -y, -z). An edit that moves, grows or shrinks the scene then keeps the LDIs of the parts it
  // left alone (onGrid) instead of sampling the whole tree again. Scenes with explicit bounds
  // get gridFor's grid.
  static Grid previewGridFor(const Scene& scene, int resolution, const Grid* previous);
  static constexpr double kLatticeSlack = 1.125;

  void clearCache() { cache_.clear(); }
  size_t cacheEntries() const { return cache_.size(); }
  Backend& backend() { return *backend_; }

 private:
  struct CacheEntry {
    LdiHandle ldi;
    uint64_t generation = 0;  // the last evaluation that used it
    std::string warning;      // what sampling this leaf warned about ("" for none)
  };
  struct Context;
  struct NotCached;
  struct Visit {
    LdiHandle ldi;
    uint64_t key = 0;
  };
  // Visits a node whose visibility the caller has checked (instances show hidden targets), and
  // keeps its LDI when asked (EvalOptions::keep).
  Visit visit(const NodePtr& node, const glm::dmat4& parentWorld, int depth, Context& ctx);
  Visit visitNode(const NodePtr& node, const glm::dmat4& parentWorld, int depth, Context& ctx);
  // The operands of operation `node` (of Boolean `op`, placed by `world`), appended to
  // *operands: its visible children visited, except that a child operation that can join this
  // Boolean (mergeable) gives its own operands instead (a chain of unions is one union of all
  // their parts, a difference of a difference one difference, a union of cutters its parts as
  // cutters), and is recorded as Merged. `asBase`: node is the base of the difference that
  // collects (its own cutters follow the base).
  void collectOperands(const NodePtr& node, RayOp op, const glm::dmat4& world, int depth,
                       Context& ctx, std::vector<Visit>* operands);
  // The LDI cached under `key` (kept for this generation) on `grid` (onGrid), or what compute()
  // makes, cached under it; record.outcome says which. `content` gives the node's bounds.
  LdiHandle cachedOr(uint64_t key, const Grid& grid, const std::function<Bounds()>& content,
                     NodeRecord& record, const std::function<LdiHandle()>& compute);
  // Whether `entry` serves `grid`: computed on it, or on another window of the same lattice and
  // moved onto this one (Backend::rewindow) because the node's `content` bounds lie within both
  // windows with room to spare, so that neither clipped it: what evaluating it here would give.
  bool onGrid(CacheEntry& entry, const Grid& grid, const std::function<Bounds()>& content);
  Visit visitLeaf(const NodePtr& node, const glm::dmat4& world, Context& ctx);
  // Samples the leaves the collecting walk found (Backend::sampleMeshes) into the cache.
  void sampleCollected(Context& ctx);
  static bool dropDuplicateOperands(RayOp op, std::vector<Visit>* operands);
  uint64_t meshHash(const std::shared_ptr<const TriangleMesh>& mesh);

  std::shared_ptr<Backend> backend_;
  bool onlyCached_ = false;  // evaluateCached: any computation throws NotCached instead
  std::unordered_map<uint64_t, CacheEntry> cache_;
  uint64_t generation_ = 0;
  struct MeshHashMemo {
    std::weak_ptr<const TriangleMesh> mesh;
    uint64_t hash;
  };
  std::unordered_map<const TriangleMesh*, MeshHashMemo> meshHashes_;
};

// Whether `content` lies within `grid`'s window with two cells (kGuardCells) to spare on every
// side: what evaluating there does not clip (an offset reads beyond a surface: the node where its
// sign changes and the gradient's neighbour).
bool withinWithRoom(const Bounds& content, const Grid& grid);

// Whether the tree under `root` holds a modifier (offset, shell, round, fillet) that takes part:
// visible, or stood for by an instance (modifierHaloCells > 0).
bool hasModifier(const NodePtr& root);

// The cells (of size h) by which a tile's window must grow on every side for its evaluation to
// hold, inside the window, exactly what the whole grid's does: a modifier reads its children
// around each point up to its reach away (modifierReach, plus kOffsetHaloCells per offset,
// engine/ldi/offset_math.h), and modifiers nested on one path add up. 0 without modifiers;
// instances followed.
int modifierHaloCells(const NodePtr& root, double h);

// World-space bounds of a node's visible result (union: all children; intersection: the
// overlap of the children's; difference: the first child's). Empty when nothing is visible.
Bounds nodeBounds(const NodePtr& node, const NodePtr& root, const glm::dmat4& parentWorld);

}  // namespace strata
