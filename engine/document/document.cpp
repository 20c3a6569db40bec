#include "engine/document/document.h"

#include <atomic>
#include <cmath>
#include <filesystem>

#include "engine/document/commands.h"
#include "engine/document/expansion.h"
#include "engine/util/error.h"
#include "engine/util/limits.h"

namespace strata {
namespace {
namespace fs = std::filesystem;

// A revision no document of this process has had (see Document::revision).
uint64_t freshRevision() {
  static std::atomic<uint64_t> next{1};
  return next.fetch_add(1);
}

std::string folderOf(const std::string& path) {
  return path.empty() ? std::string() : fs::path(path).parent_path().string();
}

// Whether two trees have the same nodes in the same places with the same kinds and transforms:
// all a move (movePart) can change. A move that lands a part where it was gives a new tree of
// the same shape: no edit.
bool sameShape(const NodePtr& a, const NodePtr& b) {
  if (a == b) return true;
  if (!a || !b || a->id != b->id || a->kind != b->kind || !(a->transform == b->transform) ||
      a->children.size() != b->children.size())
    return false;
  for (size_t i = 0; i < a->children.size(); ++i)
    if (!sameShape(a->children[i], b->children[i])) return false;
  return true;
}
}  // namespace

Document::Document() {
  Scene scene;
  auto root = std::make_shared<Node>(*makeOperationNode(NodeKind::Union, 1, {}));
  root->name = "scene";
  scene.root = root;
  state_ = DocumentState{std::make_shared<const Scene>(std::move(scene)), freshRevision()};
  savedRevision_ = state_.revision;
}

Document::Document(Scene scene, std::string path) : path_(std::move(path)) {
  if (!scene.root) throw Error("a document needs a root node");
  scene.root = absoluteMeshPaths(scene.root, folderOf(path_));
  state_ = DocumentState{std::make_shared<const Scene>(std::move(scene)), freshRevision()};
  savedRevision_ = state_.revision;
}

NodeId Document::nextId() const {
  return maxNodeId(root()) + 1;
}

std::string Document::name() const {
  return path_.empty() ? "untitled" : fs::path(path_).filename().string();
}

std::string Document::title() const {
  return dirty() ? name() + " *" : name();
}

void Document::apply(const std::string& label, const NodePtr& newRoot) {
  if (!newRoot) throw Error("an edit must leave a root node");
  if (newRoot == root()) return;  // nothing changed: no undo step
  Scene next = scene();
  next.root = newRoot;
  if (!next.measurements.empty())
    next.measurements = followResizedParts(
        root(), newRoot, pinPointsOfRemovedParts(root(), newRoot, next.measurements));
  history_.record(state_, label);
  resolutionStepOpen_ = false;
  state_ = DocumentState{std::make_shared<const Scene>(std::move(next)), freshRevision()};
}

void Document::applyMeasurements(const std::string& label, std::vector<Measurement> measurements) {
  if (measurements == scene().measurements) return;
  if (measurements.size() > kMaxMeasurements)
    throw Error("a scene holds at most " + std::to_string(kMaxMeasurements) + " measurements");
  for (const Measurement& m : measurements) {
    if (m.points.size() < 2 || m.points.size() > 3)
      throw Error("a measurement has two points (a distance) or three (an angle)");
    for (const MeasurePoint& p : m.points)
      if (!std::isfinite(p.local.x) || !std::isfinite(p.local.y) || !std::isfinite(p.local.z))
        throw Error("a measured point is not a finite position");
    for (const MeasurePoint& p : m.points)
      if (p.node != 0 && !findNode(root(), p.node))
        throw Error("a measured point lies on node " + std::to_string(p.node) +
                    ", which is not in the scene");
  }
  Scene next = scene();
  next.measurements = std::move(measurements);
  history_.record(state_, label);
  resolutionStepOpen_ = false;
  state_ = DocumentState{std::make_shared<const Scene>(std::move(next)), freshRevision()};
}

NodeId Document::parentForAdd(NodeId parent, int* index) const {
  if (parent == 0) parent = root()->id;
  NodePtr target = findNode(root(), parent);
  if (!target) throw Error("there is no node with id " + std::to_string(parent));
  if (isOperation(target->kind) || target == root()) return parent;
  NodeLocation where;
  locateNode(root(), parent, &where);
  *index = where.index + 1;
  return where.parent->id;
}

NodeId Document::addNode(NodeKind kind, NodeId parent, int index) {
  NodeId id = nextId();
  NodePtr node = isOperation(kind) ? makeOperationNode(kind, id, {}) : makePrimitiveNode(kind, id);
  return addSubtree(node, parent, index);
}

NodeId Document::addSubtree(const NodePtr& node, NodeId parent, int index) {
  NodeId id = nextId();
  NodePtr fresh = withFreshIds(node, id);
  NodeId target = parentForAdd(parent, &index);
  std::string label =
      "add " + (fresh->name.empty() ? std::string(kindLabel(fresh->kind)) : fresh->name);
  if (!isOperation(root()->kind) && target == root()->id) {
    // A leaf root: wrap it and the new node in a union.
    NodeId unionId = maxNodeId(fresh) + 1;
    auto top =
        std::make_shared<Node>(*makeOperationNode(NodeKind::Union, unionId, {root(), fresh}));
    top->name = "scene";
    apply(label, top);
    return id;
  }
  // An instance in it must find its target here (a cut instance whose target went since).
  NodePtr result = insertChild(root(), target, index, fresh);
  checkInstances(result);
  apply(label, result);
  return id;
}

NodeId Document::place(const NodePtr& node, NodeId target, PlaceMode mode, std::string* sentence) {
  const NodeId id = nextId();
  NodePtr fresh = withFreshIds(node, id);
  if (target == 0) target = root()->id;
  const PlacePlan plan = planPlacement(root(), target, mode);
  NodePtr result = placePart(root(), plan, fresh, maxNodeId(fresh) + 1);
  checkInstances(result);
  apply("add " + (fresh->name.empty() ? std::string(kindLabel(fresh->kind)) : fresh->name), result);
  if (sentence) *sentence = plan.sentence;
  return id;
}

void Document::moveOnto(NodeId id, NodeId target, PlaceMode mode, const std::string& label) {
  if (target == 0) target = root()->id;
  const NodePtr moved = movePart(root(), id, target, mode, nextId());
  if (sameShape(root(), moved)) return;  // dropped where it was: no undo step
  apply(label, moved);
}

void Document::remove(NodeId id) {
  NodePtr node = findNode(root(), id);
  apply("delete " + (node ? node->name : std::string()), removeNode(root(), id));
}

NodeId Document::duplicate(NodeId id) {
  NodeId copy = 0;
  NodePtr result = duplicateNode(root(), id, nextId(), &copy);
  apply("duplicate", result);
  return copy;
}

void Document::setMesh(NodeId id, std::shared_ptr<const TriangleMesh> mesh, const std::string& hash,
                       bool open) {
  NodePtr node = findNode(root(), id);
  if (!node || node->kind != NodeKind::Mesh)
    throw Error("there is no mesh node with id " + std::to_string(id));
  apply(open ? "take as an open mesh" : "read the mesh again", editNode(root(), id, [&](Node& n) {
          n.mesh = std::move(mesh);
          n.meshHash = hash;
          n.meshOpen = open;
          n.meshProblem.clear();
          n.meshRefusedAsOpen = false;
        }));
}

void Document::rename(NodeId id, const std::string& name) {
  NodePtr node = findNode(root(), id);
  if (node && node->name == name) return;  // no change, no undo step
  apply("rename", editNode(root(), id, [&](Node& n) { n.name = name; }));
}

void Document::setTransform(NodeId id, const Transform& given) {
  validateTransform(given);
  // A zero is +0 (a snapped move of -0.0 read "-0" in the inspector: an artist's test).
  Transform transform = given;
  transform.translate += glm::dvec3(0.0);
  transform.rotateDegrees += glm::dvec3(0.0);
  NodePtr node = findNode(root(), id);
  if (node && node->transform == transform) return;
  // What an undo takes back, named ("undone: transform" whichever it was: an artist's test).
  std::string label = "transform";
  if (node) {
    const Transform& t = node->transform;
    const bool moved = t.translate != transform.translate;
    const bool turned = t.rotateDegrees != transform.rotateDegrees;
    const bool scaled = t.scale != transform.scale;
    if (moved + turned + scaled == 1) label = moved ? "position" : turned ? "rotation" : "scale";
  }
  apply(label, editNode(root(), id, [&](Node& n) { n.transform = transform; }));
}

void Document::setColor(NodeId id, const glm::vec3& color) {
  for (int i = 0; i < 3; ++i)
    if (!(color[i] >= 0.0f && color[i] <= 1.0f)) throw Error("colour components must be in [0, 1]");
  NodePtr node = findNode(root(), id);
  if (node && node->color == color) return;
  apply("colour", editNode(root(), id, [&](Node& n) { n.color = color; }));
}

void Document::setParams(NodeId id, const PrimitiveParams& params) {
  NodePtr node = findNode(root(), id);
  if (!node) throw Error("there is no node with id " + std::to_string(id));
  if (!isPrimitive(node->kind))
    throw Error(std::string("a ") + kindName(node->kind) + " node has no primitive parameters");
  validateParams(node->kind, params);
  if (node->params == params) return;
  // The parameter changed, named ("size", "top radius"); "parameters" where several did.
  std::string label = "parameters";
  int changed = 0;
  if (const PrimitiveInfo* info = primitiveInfo(node->kind))
    for (const PrimitiveParam& p : info->params)
      if ((p.scalar && node->params.*p.scalar != params.*p.scalar) ||
          (p.vector && node->params.*p.vector != params.*p.vector))
        label = p.label, ++changed;
  if (node->params.segments != params.segments) label = "segments", ++changed;
  if (changed != 1) label = "parameters";
  apply(label, editNode(root(), id, [&](Node& n) { n.params = params; }));
}

void Document::setAmount(NodeId id, double amount) {
  NodePtr node = findNode(root(), id);
  if (!node) throw Error("there is no node with id " + std::to_string(id));
  if (modifierOf(node->kind) == Modifier::None)
    throw Error(std::string("a ") + kindName(node->kind) + " node has no distance");
  checkModifierAmount(node->kind, amount, nodeLabel(*node));
  if (node->amount == amount) return;
  apply(nodeKindInfo(node->kind).amountKey,
        editNode(root(), id, [&](Node& n) { n.amount = amount; }));
}

void Document::setOpening(NodeId id, NodeId opening) {
  NodePtr node = findNode(root(), id);
  if (!node) throw Error("there is no node with id " + std::to_string(id));
  if (node->kind != NodeKind::Shell)
    throw Error(std::string("a ") + kindName(node->kind) + " node has no opening");
  if (opening != 0 && (opening == id || !findNode(node, opening)))
    throw Error("node " + std::to_string(opening) + " is not a part inside shell '" + node->name +
                "'");
  if (node->opening == opening) return;
  apply("opening", editNode(root(), id, [&](Node& n) { n.opening = opening; }));
}

void Document::setPattern(NodeId id, const PatternParams& pattern) {
  NodePtr node = findNode(root(), id);
  if (!node) throw Error("there is no node with id " + std::to_string(id));
  const Pattern kind = patternOf(node->kind);
  const std::string who = nodeLabel(*node);
  if (kind == Pattern::None) throw Error(who + " makes no copies (only arrays and mirrors do)");
  checkPattern(kind, pattern, who);
  if (node->pattern == pattern) return;
  NodePtr edited = editNode(root(), id, [&](Node& n) { n.pattern = pattern; });
  checkExpansion(edited, scene().settings.maxLeaves);
  apply(patternChangeLabel(node->pattern, pattern, kind), edited);
}

void Document::setVisible(NodeId id, bool visible) {
  NodePtr node = findNode(root(), id);
  if (node && node->visible == visible) return;
  apply(visible ? "show" : "hide", editNode(root(), id, [&](Node& n) { n.visible = visible; }));
}

void Document::setResolution(int resolution) {
  if (resolution < kMinResolution || resolution > kMaxResolution)
    throw Error("resolution must be from " + std::to_string(kMinResolution) + " to " +
                std::to_string(kMaxResolution));
  if (scene().settings.resolution == resolution) return;
  // Saved with the document, so an undo step of its own (changes in a row, with no other step,
  // undo or redo between them, one step: a slider's drag, the - and + buttons, a double-click
  // that types a value); the other steps' undo and redo keep it
  // (withCurrentResolution), as a setting of the view.
  if (!resolutionStepOpen_ || history_.undoLabel() != kResolutionStep)
    history_.record(state_, kResolutionStep);
  resolutionStepOpen_ = true;
  Scene next = scene();
  next.settings.resolution = resolution;
  state_ = DocumentState{std::make_shared<const Scene>(std::move(next)), freshRevision()};
}

DocumentState Document::withCurrentResolution(DocumentState restored) {
  const int resolution = scene().settings.resolution;
  if (restored.scene->settings.resolution == resolution) return restored;
  Scene next = *restored.scene;
  next.settings.resolution = resolution;
  return DocumentState{std::make_shared<const Scene>(std::move(next)), freshRevision()};
}

void Document::move(NodeId id, NodeId parent, int index) {
  apply("move", moveNode(root(), id, parent, index));
}

void Document::moveToTop(NodeId id) {
  apply("move", moveNodeToTop(root(), id, nextId()));
}

NodeId Document::group(const std::vector<NodeId>& ids, NodeKind kind) {
  NodeId id = nextId();
  apply(std::string("group as ") + kindLabel(kind), groupNodes(root(), ids, kind, id));
  return id;
}

void Document::setOperation(NodeId id, NodeKind kind) {
  apply(std::string("make ") + kindLabel(kind), setOperationKind(root(), id, kind));
}

void Document::cancelInteraction() {
  if (std::optional<DocumentState> before = history_.cancelInteraction()) state_ = *before;
  resolutionStepOpen_ = false;
}

bool Document::undo() {
  if (!history_.canUndo()) return false;
  const bool resolution = history_.undoLabel() == kResolutionStep;
  resolutionStepOpen_ = false;
  DocumentState restored = history_.undo(state_);
  state_ = resolution ? std::move(restored) : withCurrentResolution(std::move(restored));
  return true;
}

bool Document::redo() {
  if (!history_.canRedo()) return false;
  const bool resolution = history_.redoLabel() == kResolutionStep;
  resolutionStepOpen_ = false;
  DocumentState restored = history_.redo(state_);
  state_ = resolution ? std::move(restored) : withCurrentResolution(std::move(restored));
  return true;
}

}  // namespace strata
