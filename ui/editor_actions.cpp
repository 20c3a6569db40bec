#include "ui/editor_actions.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <limits>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/matrix.hpp>

#include "engine/document/commands.h"
#include "engine/document/roles.h"
#include "engine/eval/cpu_backend.h"
#include "engine/eval/evaluator.h"
#include "engine/io/document_files.h"
#include "engine/io/mesh_formats.h"
#include "engine/io/user_files.h"
#include "engine/jobs/part_measure_job.h"
#include "engine/kinds/primitives.h"
#include "engine/util/atomic_file.h"
#include "engine/util/error.h"
#include "ui/dialog_settings.h"
#include "ui/import_options.h"
#include "ui/panels.h"
#include "ui/scene_queries.h"

namespace strata::ui {
namespace {
namespace fs = std::filesystem;

void addLog(EditorState& state, LogLevel level, const std::string& text) {
  state.log.push_back(LogLine{level, text, state.now, false, ""});
  while (state.log.size() > 200) state.log.pop_front();
}

void rememberRecent(EditorState& state, const std::string& path) {
  if (state.recentFilesPath.empty()) return;
  try {
    state.recentFiles = addRecentFile(state.recentFilesPath, path);
  } catch (const Error& e) {
    logWarning(state, std::string("recent files: ") + e.what());
  }
}

// Errors shown so far are settled (the document they were about is saved or gone): they stay
// in the messages, no longer in the status bar.
void settleErrors(EditorState& state) {
  for (LogLine& line : state.log) line.dismissed = true;
}

void replaceDocument(EditorState& state, Document document) {
  settleErrors(state);
  if (const std::string folder = documentFolder(state); !folder.empty())
    state.lastDocumentFolder = folder;
  state.document = std::move(document);
  state.contactsRoot = nullptr;  // another document: nothing to compare with
  state.templateName.clear();
  state.selection.clear();
  state.preview.reset();
  state.previewError.clear();
  state.requestViewAll = true;
  state.section.at.reset();  // placed again in the middle of the new document's parts
  state.section.startFraction = 0.5;
  state.snapFollowsGrid = true;  // a move step typed was the other document's
  // The export dialog's resolution and simplification were chosen for the other document: this
  // one's first export starts from its own resolution, unsimplified (a quick Export after Ctrl+O
  // wrote a coarser, simplified mesh than the scene asks for: an artist's test). The tolerance
  // in cells, a preference, stays.
  state.exportResolution = 0;
  state.exportSimplify = false;
  // The palette's mode was chosen for the other document's parts: a new part adds again (after
  // Ctrl+O it was still "cut": an artist's re-test).
  state.placeMode = PlaceMode::Add;
}

// The size new parts get: a quarter of the scene's largest extent, or in an empty scene a
// quarter of what the view shows, rounded (niceLength); *from says which.
double sceneScale(const EditorState& state, std::string* from = nullptr) {
  const Bounds b = sceneBounds(state.document.root());
  if (!b.empty()) {
    const glm::dvec3 size = b.size();
    const double scene = niceLength(std::max({size.x, size.y, size.z}) / 4.0);
    // Zoomed in on a detail, a quarter of the view where that is less: a part a quarter of the
    // scene hid the detail it was added to (an artist's 125 mm torus over 20 mm spheres).
    const double view = state.viewExtent > 0.0 ? niceLength(state.viewExtent / 4.0) : scene;
    if (from) *from = view < scene ? "a quarter of the view" : "a quarter of the scene";
    return std::min(scene, view);
  }
  if (state.viewExtent > 0.0) {
    if (from) *from = "a quarter of the view";
    return niceLength(state.viewExtent / 4.0);
  }
  if (from) *from = "the default size";
  return 1.0;
}

// The scene's visible bounds without node `id` (what an imported part is placed beside).
Bounds sceneBoundsWithout(const EditorState& state, NodeId id) {
  try {
    return sceneBounds(removeNode(state.document.root(), id));
  } catch (const Error&) {
    return Bounds();
  }
}

// Moves the just-added node `id` so that its world bounds are centred on the placement's point
// (or rest on the ground below it). Part of the caller's interaction (one undo step).
void placeNode(EditorState& state, NodeId id, const Placement& placement) {
  NodePtr node = findNode(state.document.root(), id);
  if (!node) return;
  // A picked normal carries its surfel's encoding (about 0.005 degrees): one that close to an
  // axis is that axis, or a part dropped on a flat top got turns of -0.003 degrees ("-0.00").
  glm::dvec3 normal(0.0, 0.0, 1.0);
  if (placement.normal) {
    normal = glm::normalize(*placement.normal);
    for (int a = 0; a < 3; ++a)
      if (std::fabs(normal[a]) > std::cos(glm::radians(0.05))) {
        const double sign = normal[a] > 0.0 ? 1.0 : -1.0;
        normal = glm::dvec3(0.0);
        normal[a] = sign;
      }
  }
  if (placement.normal) {
    // Its own +z along the surface's normal (in its parent's frame), the turn about it kept.
    const glm::dmat3 parent(parentWorldMatrix(state.document.root(), id));
    const glm::dvec3 z = glm::normalize(glm::inverse(parent) * normal);
    const glm::dvec3 from(0.0, 0.0, 1.0);
    const double c = glm::dot(from, z);
    glm::dmat4 turn(1.0);
    if (c < 1.0 - 1e-12) {
      const glm::dvec3 axis =
          c > -1.0 + 1e-12 ? glm::normalize(glm::cross(from, z)) : glm::dvec3(1.0, 0.0, 0.0);
      turn = glm::rotate(glm::dmat4(1.0), std::acos(std::clamp(c, -1.0, 1.0)), axis);
    }
    Transform t = transformFromMatrix(turn * node->transform.matrix());
    t.translate = node->transform.translate;
    state.document.setTransform(id, t);
    node = findNode(state.document.root(), id);
  }
  const NodePtr& root = state.document.root();
  const Bounds b = selectionBounds(root, {id});
  if (b.empty()) return;
  glm::dvec3 delta = placement.point - b.center();
  if (placement.onGround) delta.z = placement.point.z - b.min.z;
  const ChildRole role = roleOf(root, id);
  if (placement.normal && role != ChildRole::Cut && role != ChildRole::Intersect) {
    // A part that adds material rests on the surface (centred on it, it sat half buried: an
    // artist's test): its own box's lowest corner along the normal on the surface, its centre
    // over the point. A cutter or an intersector stays centred on the point, half in.
    const Bounds own = nodeBounds(node, root, glm::inverse(node->transform.matrix()));
    if (!own.empty()) {
      const glm::dmat4 world = nodeWorldMatrix(root, id);
      double low = INFINITY;
      for (int k = 0; k < 8; ++k) {
        const glm::dvec3 corner(k & 1 ? own.max.x : own.min.x, k & 2 ? own.max.y : own.min.y,
                                k & 4 ? own.max.z : own.min.z);
        low = std::min(low, glm::dot(normal, glm::dvec3(world * glm::dvec4(corner, 1.0))));
      }
      const glm::dvec3 across = placement.point - glm::dvec3(world * glm::dvec4(own.center(), 1.0));
      delta = across - normal * glm::dot(across, normal) +
              normal * (glm::dot(placement.point, normal) - low);
    }
  }
  const glm::dmat4 toParent = glm::inverse(parentWorldMatrix(state.document.root(), id));
  Transform t = node->transform;
  t.translate += glm::dvec3(toParent * glm::dvec4(delta, 0.0));
  state.document.setTransform(id, t);
}

// The primitive node `addPrimitive` adds: sized to the scene (or the view); *sizeNote says how
// ("1 mm, a quarter of the scene").
// Dropped on a part (`sizeFrom`), at most a quarter of that part: a cutter sized to the scene
// swallowed the small part it was dropped on.
NodePtr newPrimitive(EditorState& state, NodeKind kind, std::string* sizeNote = nullptr,
                     NodeId sizeFrom = 0) {
  auto node = std::make_shared<Node>(*makePrimitiveNode(kind, state.document.nextId()));
  std::string from;
  double scale = sceneScale(state, &from);
  if (sizeFrom) {
    const Bounds part = selectionBounds(state.document.root(), {sizeFrom});
    if (!part.empty()) {
      const glm::dvec3 size = part.size();
      // The largest round length (1, 2 or 5 times a power of ten) of at most a quarter.
      const double most = std::max({size.x, size.y, size.z}) / 4.0;
      double quarter = 0.0;
      if (most > 0.0 && std::isfinite(most)) {
        const double power = std::pow(10.0, std::floor(std::log10(most)));
        for (const double m : {10.0, 5.0, 2.0, 1.0})
          if (quarter == 0.0 && m * power <= most * (1.0 + 1e-9)) quarter = m * power;
      }
      if (quarter > 0.0 && quarter < scale) {
        scale = quarter;
        from = "a quarter of " + nodeLabel(*findNode(state.document.root(), sizeFrom));
      }
    }
  }
  node->params = scaledPrimitiveParams(kind, node->params, scale);
  if (sizeNote) {
    char text[64];
    std::snprintf(text, sizeof(text), "%.4g %s", scale,
                  unitSymbol(state.document.scene().settings.unit));
    *sizeNote = std::string(text) + ", " + from;
  }
  return node;
}

std::string displayName(const Node& node) {
  return "\"" + (node.name.empty() ? std::string(kindName(node.kind)) : node.name) + "\"";
}

// Places a new part onto the primary selection with the place mode and says what it does.
// Places `node` onto `target` (0: the primary selection) with `mode`, saying what it does.
NodeId placeNew(EditorState& state, const NodePtr& node, PlaceMode mode,
                const std::string& note = "", NodeId target = 0) {
  std::string sentence;
  const NodeId id =
      state.document.place(node, target ? target : primarySelection(state), mode, &sentence);
  logInfo(state, displayName(*findNode(state.document.root(), id)) + " " + sentence +
                     (note.empty() ? "" : " (" + note + ")"));
  return id;
}

}  // namespace

void logInfo(EditorState& state, const std::string& text) {
  addLog(state, LogLevel::Info, text);
}
void logWarning(EditorState& state, const std::string& text) {
  addLog(state, LogLevel::Warning, text);
}
void logError(EditorState& state, const std::string& text) {
  addLog(state, LogLevel::Error, text);
}

bool keyPressed(const EditorState& state, int key, int mods) {
  for (const KeyPress& k : state.keyPresses)
    if (k.key == key && (k.mods & 7) == mods) return true;
  return false;
}

bool guarded(EditorState& state, const std::function<void()>& body, const std::string& topic) {
  try {
    body();
    if (!topic.empty())
      for (LogLine& line : state.log)
        if (line.topic == topic) line.dismissed = true;
    return true;
  } catch (const Error& e) {
    logError(state, e.what());
  } catch (const std::bad_alloc&) {
    logError(state, "out of memory");
  }
  if (!topic.empty()) state.log.back().topic = topic;
  return false;
}

NodeId primarySelection(const EditorState& state) {
  return state.selection.empty() ? 0 : state.selection.back();
}

bool isSelected(const EditorState& state, NodeId id) {
  return std::find(state.selection.begin(), state.selection.end(), id) != state.selection.end();
}

void selectNode(EditorState& state, NodeId id, bool extend) {
  if (!extend) {
    state.selection.assign(1, id);
    return;
  }
  auto it = std::find(state.selection.begin(), state.selection.end(), id);
  if (it != state.selection.end())
    state.selection.erase(it);
  else
    state.selection.push_back(id);
}

void clearSelection(EditorState& state) {
  state.selection.clear();
}

void selectRange(EditorState& state, NodeId id, const std::vector<NodeId>& rows) {
  const NodeId anchor = primarySelection(state);
  if (!anchor || !findNode(state.document.root(), anchor)) {
    selectNode(state, id);
    return;
  }
  // The rows shown where both ends are among them (a collapsed operation's parts are not),
  // else the whole tree's order.
  const bool shown = std::find(rows.begin(), rows.end(), anchor) != rows.end() &&
                     std::find(rows.begin(), rows.end(), id) != rows.end();
  const std::vector<NodeId> order = shown ? rows : treeOrder(state.document.root());
  const auto a = std::find(order.begin(), order.end(), anchor);
  const auto b = std::find(order.begin(), order.end(), id);
  if (a == order.end() || b == order.end()) return;
  const bool forward = a <= b;
  for (auto it = forward ? a : b; it != (forward ? b : a) + 1; ++it)
    if (*it != id && !isSelected(state, *it)) state.selection.push_back(*it);
  auto self = std::find(state.selection.begin(), state.selection.end(), id);
  if (self != state.selection.end()) state.selection.erase(self);
  state.selection.push_back(id);  // the primary
}

void pruneSelection(EditorState& state) {
  const NodePtr& root = state.document.root();
  state.selection.erase(std::remove_if(state.selection.begin(), state.selection.end(),
                                       [&](NodeId id) { return !findNode(root, id); }),
                        state.selection.end());
}

void rememberSelection(EditorState& state) {
  constexpr size_t kRemembered = 512;  // revisions; the oldest are forgotten first
  auto& remembered = state.selectionAtRevision;
  remembered[state.document.revision()] = state.selection;
  while (remembered.size() > kRemembered) remembered.erase(remembered.begin());
}

namespace {
// After undo or redo: the selection remembered at the revision returned to, where there is one.
void restoreSelection(EditorState& state) {
  const auto found = state.selectionAtRevision.find(state.document.revision());
  if (found != state.selectionAtRevision.end()) state.selection = found->second;
  pruneSelection(state);
}
}  // namespace

PlaceMode dropMode(const EditorState& state, int mods, NodeId dragged, NodeId target) {
  if (mods & kDropCut) return PlaceMode::Cut;
  if (mods & kDropIntersect) return PlaceMode::Intersect;
  if (mods & kDropAdd) return PlaceMode::Add;
  const NodePtr& root = state.document.root();
  if (dragged != 0 && findNode(root, dragged)) {
    const PlaceMode kept = modeKeepingRole(roleOf(root, dragged));
    if (dragged == root->id) return kept;
    // Judged on the tree without it, as movePart places it (ids past the tree's for what a
    // removal leaves behind).
    return modeKeepingEffect(removeKeepingRoles(root, dragged, state.document.nextId() + 1),
                             target ? target : root->id, kept, removesMaterial(root, dragged));
  }
  return state.placeMode;
}

std::string placementSentence(const EditorState& state, NodeId target, PlaceMode mode,
                              NodeId dragged, bool* refused) {
  const NodePtr& root = state.document.root();
  if (refused) *refused = false;
  try {
    if (target == 0) target = root->id;
    if (dragged == 0) return planPlacement(root, target, mode).sentence;
    const NodeId fresh = state.document.nextId();
    const NodePtr moved = movePart(root, dragged, target, mode, fresh);  // throws when refused
    std::string does =
        planPlacement(removeKeepingRoles(root, dragged, fresh + 1), target, mode).sentence +
        leavesNote(root, moved, dragged) + instancesChangedNote(root, moved, dragged);
    // A role that changes is said in words, with why: a part dropped without a modifier keeps
    // taking material away or not (dropMode), which there may need the other role (an artist
    // saw "adds" turn into "cuts" without a word of why).
    const ChildRole roleBefore = roleOf(root, dragged), roleAfter = roleOf(moved, dragged);
    if (roleBefore != ChildRole::Root && roleAfter != roleBefore &&
        !(roleBefore == ChildRole::Base && roleAfter == ChildRole::Add) &&
        !(roleBefore == ChildRole::Add && roleAfter == ChildRole::Base)) {
      const bool removes = removesMaterial(moved, dragged);
      does += std::string("; its role changes from \"") + roleWord(roleBefore) + "\" to \"" +
              roleWord(roleAfter) + "\"" +
              (removes == removesMaterial(root, dragged)
                   ? (removes ? ", so that it still takes material away"
                              : ", so that it still takes no material away")
                   : "");
    }
    // Within its own parent, keeping its role, a drop only changes its place among its
    // siblings (onto the sibling below: after it): say so, not only what it does.
    NodeLocation was, now;
    if (locateNode(root, dragged, &was) && locateNode(moved, dragged, &now) && was.parent &&
        now.parent && was.parent->id == now.parent->id &&
        childRole(*was.parent, was.index) == childRole(*now.parent, now.index)) {
      if (was.index == now.index) return "stays where it is (it " + does + ")";
      const std::string place =
          now.index > 0 ? "after " + displayName(*now.parent->children[size_t(now.index - 1)])
                        : "first";
      return "moves " + place + " in " + displayName(*now.parent) + ", its role unchanged (it " +
             does + ")";
    }
    return does;
  } catch (const Error& e) {
    if (refused) *refused = true;
    return e.what();
  }
}

NodeId addPrimitive(EditorState& state, NodeKind kind) {
  NodeId id = 0;
  // On the middle of the top of what it is placed onto (the selection, else the whole scene), so
  // that it shows: a part added at the origin inside another changed nothing to see. One that
  // adds material rests on that top, as a part dropped there does (centred on it, it sat half
  // sunk: an artist's test); a cutter or an intersector is centred on it. The first part of a
  // scene stands on the ground (z = 0) at the origin, as a printed part does on the bed
  // (centred on the origin, half of it was below the ground grid). One undo step.
  const NodeId target = primarySelection(state);
  const Bounds onto = target ? selectionBounds(state.document.root(), {target})
                             : sceneBounds(state.document.root());
  state.document.beginInteraction();
  guarded(state, [&] {
    std::string note;
    // Sized from what it goes onto where that is smaller (as a part dropped on it is).
    NodePtr node = newPrimitive(state, kind, &note, target);
    id = placeNew(state, node, state.placeMode, note);
    Placement at;
    if (!onto.empty()) {
      // Onto the selection: the top of its box. With nothing selected: the top of the parts
      // standing under the scene's middle, else the ground there.
      const std::optional<double> top =
          target ? std::optional<double>(onto.max.z)
                 : topOfPartsUnder(state.document.root(), glm::dvec2(onto.center()));
      at.point = glm::dvec3(onto.center().x, onto.center().y, top ? *top : 0.0);
      at.normal = glm::dvec3(0.0, 0.0, 1.0);  // the top's: a part that adds rests on it
      at.onGround = !top;
    } else {
      at.onGround = true;
    }
    placeNode(state, id, at);
    selectNode(state, id);
    state.revealSelection = true;
  });
  state.document.endInteraction();
  return id;
}

NodeId dropTargetFor(const NodePtr& root, NodeId picked) {
  std::vector<const Node*> path;
  if (!root || !pathToNode(root, picked, &path)) return 0;
  // The surface of a hole is its cutter's, of an intersection its intersector's: the material
  // around it is the operation's (a boss dropped on a hole's floor became a cutter).
  size_t at = path.size() - 1;
  while (at > 0) {
    const ChildRole role = roleOf(root, path[at]->id);
    if (role != ChildRole::Cut && role != ChildRole::Intersect) break;
    --at;
  }
  // Inside a pattern, every copy shows the same parts: the pattern itself (a drop on one copy
  // was repeated in all of them).
  for (size_t k = 0; k < at; ++k)
    if (patternOf(path[k]->kind) != Pattern::None) return path[k]->id;
  return path[at]->id;
}

NodeId addPrimitiveAt(EditorState& state, NodeKind kind, const Placement& placement) {
  NodeId id = 0;
  state.document.beginInteraction();
  guarded(state, [&] {
    std::string note;
    // Dropped on a part's surface: onto that part (dropped on the ground: onto the selection).
    const NodeId onto =
        placement.part && findNode(state.document.root(), placement.part) ? placement.part : 0;
    NodePtr node = newPrimitive(state, kind, &note, onto);
    id = placeNew(state, node, state.placeMode, note, onto);
    placeNode(state, id, placement);
    if (placement.normal) {
      // Components that print as zero are zero: "-0.00" read as a sign where none is.
      const auto shown = [](double v) { return std::fabs(v) < 0.005 ? 0.0 : v; };
      const auto at = [](double v) { return std::fabs(v) < 1e-9 ? 0.0 : v; };  // rounding dust
      // The contact point and the centre the inspector's move fields show (its translation in
      // its parent's frame): the status gave the point where the inspector showed the centre,
      // and the two read as a disagreement (an artist's test). The centre before the normal: a
      // narrow bar's ellipsis took it (an artist's re-test).
      const NodePtr placed = findNode(state.document.root(), id);
      const glm::dvec3 centre = placed ? placed->transform.translate : placement.point;
      const bool worldFrame = parentWorldMatrix(state.document.root(), id) == glm::dmat4(1.0);
      char text[240];
      std::snprintf(text, sizeof(text),
                    "placed touching the surface at (%.4g, %.4g, %.4g), its centre at (%.4g, "
                    "%.4g, %.4g)%s; its z turned to the surface's normal (%.2f, %.2f, %.2f)",
                    at(placement.point.x), at(placement.point.y), at(placement.point.z),
                    at(centre.x), at(centre.y), at(centre.z),
                    worldFrame ? "" : " in its parent's frame (as the inspector shows it)",
                    shown(placement.normal->x), shown(placement.normal->y),
                    shown(placement.normal->z));
      logInfo(state, text);
    }
    selectNode(state, id);
  });
  state.document.endInteraction();
  return id;
}

void dropPaletteItem(EditorState& state, int item, NodeId target, PlaceMode mode) {
  if (target)
    selectNode(state, target);
  else
    clearSelection(state);
  if (item == kImportMeshItem) {
    state.importPlacement.reset();
    state.dialog.open(DialogPurpose::ImportMesh, importFolder(state));
    return;
  }
  const PlaceMode saved = state.placeMode;
  state.placeMode = mode;
  addPrimitive(state, NodeKind(item));
  state.placeMode = saved;
}

namespace {
// A new modifier's distance from what it will hold (`bounds`: the grouped parts, or the scene):
// 3% of its largest side, to two significant digits; the kind's default when there is nothing.
// x (> 0) to two significant digits: the nearest such number, or the largest not above it.
double twoDigits(double x, bool down) {
  const double step = std::pow(10.0, std::floor(std::log10(x)) - 1.0);
  return std::max(step, (down ? std::floor(x / step) : std::round(x / step)) * step);
}

double modifierAmountFor(NodeKind kind, const Bounds& bounds) {
  if (bounds.empty()) return nodeKindInfo(kind).defaultAmount;
  const glm::dvec3 size = bounds.max - bounds.min;
  const double x = 0.03 * std::max({size.x, size.y, size.z});
  if (!(x > 0.0) || !std::isfinite(x)) return nodeKindInfo(kind).defaultAmount;
  return twoDigits(x, false);
}

// The thinnest wall of node `id`'s parts alone (partScene), measured on the CPU at 96 cells
// along them; +infinity where none was found (or the parts could not be evaluated). On the UI
// thread, once per press of a button: at 96 cells the armadillo and the bunny (80,000
// triangles) evaluate in 30 ms on two cores.
double thinnestWallOf(const EditorState& state, NodeId id) {
  try {
    const Scene part = partScene(state.document.scene(), id);
    Evaluator evaluator(std::make_shared<CpuBackend>());
    Progress progress;
    EvalOptions options;
    options.resolution = 96;
    return evaluator.evaluate(part, options, progress).measure.thinnestWall;
  } catch (const std::exception&) {
    return std::numeric_limits<double>::infinity();
  }
}

// The thinnest wall of the selected parts, each alone (a union of them is no thinner).
double thinnestWallOfSelection(const EditorState& state) {
  double wall = std::numeric_limits<double>::infinity();
  for (NodeId id : state.selection) wall = std::min(wall, thinnestWallOf(state, id));
  return wall;
}

// A new round's radius: modifierAmountFor's, but at most a quarter of the thinnest `wall` of
// the parts it will hold, so that every wall stays (a round of r removes walls thinner than 2r: an
// artist's first round of a 100 mm cup, 3 mm, took its 3 mm walls away). `why` says so.
double roundRadiusFor(const EditorState& state, double wall, double fromBox, std::string* why) {
  if (!std::isfinite(wall) || !(wall > 0.0) || fromBox <= 0.25 * wall) return fromBox;
  const double radius = twoDigits(0.25 * wall, true);
  char text[160];
  std::snprintf(text, sizeof(text),
                "radius %.4g %s: a quarter of the thinnest wall it holds (about %.3g), which it "
                "keeps",
                radius, unitSymbol(state.document.scene().settings.unit), wall);
  *why = text;
  return radius;
}

// A new pattern's copies from what it holds (`bounds`); an empty one is spaced for parts of
// the size new parts get (sceneScale).
PatternParams patternFor(const EditorState& state, NodeKind kind, const Bounds& bounds) {
  const glm::dvec3 held = bounds.empty() ? glm::dvec3(sceneScale(state)) : bounds.size();
  return defaultPattern(patternOf(kind), held);
}
}  // namespace

NodeId addOperation(EditorState& state, NodeKind kind) {
  NodeId id = 0;
  guarded(state, [&] {
    auto node = std::make_shared<Node>(*makeOperationNode(kind, state.document.nextId(), {}));
    if (modifierOf(kind) != Modifier::None)
      node->amount = modifierAmountFor(kind, sceneBounds(state.document.root()));
    if (patternOf(kind) != Pattern::None) node->pattern = patternFor(state, kind, Bounds());
    id = placeNew(state, node, state.placeMode);
    selectNode(state, id);
    state.revealSelection = true;
  });
  return id;
}

NodeId importMesh(EditorState& state, const PendingImport& import) {
  NodeId id = 0;
  std::string why;
  const double scale = importScale(import.unit, state.document.scene().settings.unit, &why);
  if (!why.empty()) logWarning(state, why);
  state.document.beginInteraction();
  guarded(state, [&] {
    std::string sentence;
    // Dropped on a part's surface: onto that part (else onto the selection).
    const NodeId onto = import.placement && import.placement->part &&
                                findNode(state.document.root(), import.placement->part)
                            ? import.placement->part
                            : primarySelection(state);
    id = importMeshFile(state.document, import.path, onto, state.placeMode,
                        importTransform(scale, import.upAxis), &sentence, import.acceptOpen);
    // Where it was dropped; otherwise resting on the ground beside the scene (right of it, a
    // tenth of its size away; at the origin in an empty scene), never inside another part or
    // around the camera. Then the view shows all of the scene, the new part with it (framing
    // the new part alone zoomed onto a 10 mm bunny and left the 100 mm part it was for out of
    // view), and says so.
    Placement where;
    if (import.placement) {
      where = *import.placement;
    } else {
      const Bounds others = sceneBoundsWithout(state, id);
      const Bounds own = selectionBounds(state.document.root(), {id});
      where.onGround = true;
      if (!others.empty() && !own.empty()) {
        const glm::dvec3 size = others.size();
        where.point =
            glm::dvec3(others.max.x + 0.1 * std::max({size.x, size.y, size.z}) + own.size().x * 0.5,
                       others.center().y, 0.0);
      }
    }
    placeNode(state, id, where);
    selectNode(state, id);
    state.requestViewAll = true;
    logInfo(state, "imported " + import.path + ": " +
                       displayName(*findNode(state.document.root(), id)) + " " + sentence +
                       " (the view shows the whole scene; F frames the new part)");
  });
  state.document.endInteraction();
  return id;
}

void deleteSelection(EditorState& state) {
  if (state.selection.empty()) return;
  // An empty base (left in a difference's first place where its base was cut or deleted, so
  // that its cutters do not become the base) would come back at once as another: said, not
  // removed (Delete seemed to do nothing: an artist's re-test).
  std::vector<NodeId> ids;
  for (NodeId id : state.selection) {
    NodeLocation at;
    const NodePtr node = findNode(state.document.root(), id);
    if (node && isOperation(node->kind) && node->children.empty() &&
        locateNode(state.document.root(), id, &at) && at.parent &&
        childRole(*at.parent, at.index) == ChildRole::Base && at.parent->children.size() > 1) {
      logWarning(state, displayName(*node) + " holds the base's place in " +
                            displayName(*at.parent) +
                            " (without a base its cutters would become one): put a part into it, "
                            "or delete " +
                            displayName(*at.parent));
      continue;
    }
    ids.push_back(id);
  }
  if (ids.empty()) return;
  // Said in the status bar (it kept the message before, as if Delete had done nothing).
  const NodePtr first = findNode(state.document.root(), ids[0]);
  const std::string what =
      ids.size() == 1 && first ? displayName(*first) : std::to_string(ids.size()) + " parts";
  const uint64_t before = state.document.revision();
  if (ids.size() == 1) {
    guarded(state, [&] { state.document.remove(ids[0]); });
  } else {
    // Several nodes: one undo step.
    state.document.beginInteraction();
    for (NodeId id : ids)
      if (findNode(state.document.root(), id)) guarded(state, [&] { state.document.remove(id); });
    state.document.endInteraction();
  }
  if (state.document.revision() != before)
    logInfo(state, "deleted " + what + " (Ctrl+Z brings it back)");
  pruneSelection(state);
}

void duplicateSelection(EditorState& state) {
  if (state.selection.empty()) return;
  // Each copy does what its original does (Document::duplicate) and sits one move-snap step
  // (the ground grid's spacing while the snap follows it) along world +x from it: a copy on top
  // of its original would change nothing that can be seen. Pressed again on the copies, the
  // steps add up to a row.
  const double step = state.snap.step;
  std::vector<NodeId> copies;
  int furthest = 1;  // grid steps from its original of the copy placed furthest
  state.document.beginInteraction();
  // A part inside another selected part is copied with it, once.
  for (NodeId id : outermostSelected(state.document.root(), state.selection))
    guarded(state, [&] {
      const NodeId copy = state.document.duplicate(id);
      copies.push_back(copy);
      const NodePtr& root = state.document.root();
      // A world move d is the local move P^-1 d, P the parent's object-to-world matrix.
      const glm::dvec3 local =
          glm::dvec3(glm::inverse(parentWorldMatrix(root, copy)) * glm::dvec4(step, 0, 0, 0));
      const NodePtr node = findNode(root, copy);
      Transform t = node->transform;
      t.translate += local;
      // Pressed again on the original, the next copy goes one step further than the copies
      // already there (it landed on the first copy, looking like one part).
      NodeLocation where;
      const NodePtr parent = locateNode(root, copy, &where) ? where.parent : nullptr;
      // The index among the parent's children of the sibling of the copy's kind at `at`, -1.
      const auto takenBy = [&](const glm::dvec3& at) {
        if (!parent) return -1;
        for (size_t i = 0; i < parent->children.size(); ++i) {
          const NodePtr& sibling = parent->children[i];
          if (sibling->id != copy && sibling->kind == node->kind &&
              glm::length(sibling->transform.translate - at) <= 1e-6 * glm::length(local))
            return int(i);
        }
        return -1;
      };
      int steps = 1, lastPassed = -1;
      for (int by; steps <= 1000 && (by = takenBy(t.translate)) >= 0; ++steps) {
        lastPassed = std::max(lastPassed, by);
        t.translate += local;
      }
      furthest = std::max(furthest, steps);
      state.document.setTransform(copy, t);
      // Listed after the copies it stepped past, as it sits after them in the row (it was listed
      // between its original and the first copy). Within its parent and past its original, so
      // its role stays: a base's copy shares a union with it, a cutter stays among the cutters.
      if (parent && lastPassed > where.index) {
        const int before = lastPassed + 1;
        state.document.move(copy, parent->id, before < int(parent->children.size()) ? before : -1);
      }
    });
  state.document.endInteraction();
  if (copies.empty()) return;
  state.selection = copies;
  state.revealSelection = true;
  char text[160];
  if (furthest == 1)
    std::snprintf(text, sizeof(text), "%s one grid step (%.4g %s) along +x from %s",
                  copies.size() == 1 ? "the copy sits" : "the copies sit", step,
                  unitSymbol(state.document.scene().settings.unit),
                  copies.size() == 1 ? "its original" : "their originals");
  else
    std::snprintf(text, sizeof(text),
                  "%s %d grid steps (%.4g %s each) along +x from %s, beside the copies there",
                  copies.size() == 1 ? "the copy sits" : "the copies sit up to", furthest, step,
                  unitSymbol(state.document.scene().settings.unit),
                  copies.size() == 1 ? "its original" : "their originals");
  logInfo(state, text);
}

void copySelection(EditorState& state) {
  if (state.selection.empty()) return;
  const NodePtr& root = state.document.root();
  std::vector<EditorState::CopiedPart> copied;
  // Tree order; a node inside another selected node goes with it.
  for (NodeId id : treeOrder(root)) {
    if (!isSelected(state, id)) continue;
    bool nested = false;
    for (NodeId other : state.selection)
      if (other != id && isInSubtree(root, other, id)) nested = true;
    if (nested) continue;
    EditorState::CopiedPart part{findNode(root, id), modeKeepingRole(roleOf(root, id)),
                                 glm::dvec3(nodeWorldMatrix(root, id) * glm::dvec4(0, 0, 0, 1))};
    part.removes = removesMaterial(root, id);
    NodeLocation at;
    if (locateNode(root, id, &at) && at.parent) {
      part.parent = at.parent->id;
      part.parentKind = at.parent->kind;
      part.index = at.index;
    }
    copied.push_back(part);
  }
  state.clipboard = copied;
  state.pastes = 0;
  state.clipboardFromCut = false;
  logInfo(state,
          "copied " + std::to_string(copied.size()) + (copied.size() == 1 ? " part" : " parts"));
}

void cutSelection(EditorState& state) {
  if (state.selection.empty()) return;
  // What the clipboard held: kept where nothing is cut (a refused cut filled it, and the next
  // paste put a copy of the part it had refused to cut: an artist's test).
  const std::vector<EditorState::CopiedPart> before = state.clipboard;
  const int pastesBefore = state.pastes;
  const bool fromCutBefore = state.clipboardFromCut;
  copySelection(state);
  deleteSelection(state);
  // What was removed (a root or a part an instance uses stays, with the delete's error): the
  // clipboard holds those alone.
  std::vector<EditorState::CopiedPart> cut;
  for (const EditorState::CopiedPart& part : state.clipboard)
    if (!findNode(state.document.root(), part.part->id)) cut.push_back(part);
  const size_t removed = cut.size();
  if (removed == 0) {
    state.clipboard = before;
    state.pastes = pastesBefore;
    state.clipboardFromCut = fromCutBefore;
    return;
  }
  state.clipboard = cut;
  state.clipboardFromCut = true;
  logInfo(state, "cut " + std::to_string(removed) + (removed == 1 ? " part" : " parts") +
                     " (Ctrl+V puts " + (removed == 1 ? "it" : "them") + " back where " +
                     (removed == 1 ? "it was" : "they were") + ")");
}

void pasteClipboard(EditorState& state) {
  if (state.clipboard.empty()) {
    logWarning(state, "nothing to paste: copy a part first (Ctrl+C)");
    return;
  }
  std::vector<NodeId> pasted;
  // A copy whose original is still in the scene lands one move-snap step further along world +x
  // with each paste (as Ctrl+D's copies): on top of its original it changed nothing to see (an
  // artist's test). A cut part (its original gone) lands where it was: a cut and paste moves it.
  const double step = state.snap.step * double(state.pastes + 1);
  // Ids are reused (a new part may take a cut one's): what the clipboard came from says.
  const bool originalThere = !state.clipboardFromCut;
  // The mode that makes a copy do where it lands (onto `onto`, else as placeNew places it) what
  // it did (a countersink copied from the holes cuts there too).
  const auto keepingEffect = [&](const EditorState::CopiedPart& copy, NodeId onto) {
    const NodeId target = onto ? onto : primarySelection(state);
    return modeKeepingEffect(state.document.root(), target ? target : state.document.root()->id,
                             copy.mode, copy.removes);
  };
  state.document.beginInteraction();
  guarded(state, [&] {
    for (const EditorState::CopiedPart& copy : state.clipboard) {
      // A cut part goes back under its parent, in its place there (and so its role), where that
      // parent is still in the scene: placed onto the selection, with nothing selected it cut the
      // whole scene (an artist's test).
      const NodePtr parent = originalThere || copy.parent == 0
                                 ? nullptr
                                 : findNode(state.document.root(), copy.parent);
      // In a difference the place is the role: the base goes back first (in place of the empty
      // base its cut left), a cutter after the base (never first: it would become the base).
      const bool difference = parent && parent->kind == NodeKind::Difference;
      const int count = parent ? int(parent->children.size()) : 0;
      const bool wasBase = difference && copy.index == 0;
      const int index = difference && !wasBase ? std::clamp(copy.index, 1, std::max(count, 1))
                                               : std::min(copy.index, count);
      NodeId id = 0;
      if (parent && parent->kind == copy.parentKind && isOperation(parent->kind) &&
          index <= count && (!difference || wasBase || count > 0)) {
        const NodePtr emptyBase = wasBase && count > 0 && isOperation(parent->children[0]->kind) &&
                                          parent->children[0]->children.empty()
                                      ? parent->children[0]
                                      : nullptr;
        id = state.document.addSubtree(copy.part, parent->id, index);
        if (emptyBase) state.document.remove(emptyBase->id);
        logInfo(state, displayName(*findNode(state.document.root(), id)) + " is back in " +
                           displayName(*parent) + ", in its place");
      } else if (originalThere) {
        // A copy beside its original: a name of its own, as Ctrl+D's copies; with nothing
        // selected onto the original (as Ctrl+D), not the whole scene (a hole's copy pasted with
        // nothing selected cut everything: an artist's re-test).
        auto named = std::make_shared<Node>(*copy.part);
        named->name = copyName(state.document.root(), copy.part->name);
        const NodePtr original = findNode(state.document.root(), copy.part->id);
        const NodeId onto = state.selection.empty() && original &&
                                    original->kind == copy.part->kind &&
                                    original->id != state.document.root()->id
                                ? original->id
                                : 0;
        id = placeNew(state, named, keepingEffect(copy, onto), "", onto);
      } else {
        id = placeNew(state, copy.part, keepingEffect(copy, 0));
      }
      pasted.push_back(id);
      const NodePtr& root = state.document.root();
      // Its origin moved to the original's, plus the step: a world move d is the local move
      // P^-1 d, P the parent's object-to-world matrix.
      const glm::dvec3 now = glm::dvec3(nodeWorldMatrix(root, id) * glm::dvec4(0, 0, 0, 1));
      const glm::dvec3 wanted = copy.worldOrigin + glm::dvec3(originalThere ? step : 0.0, 0, 0);
      if (wanted != now) {
        Transform t = findNode(root, id)->transform;
        t.translate +=
            glm::dvec3(glm::inverse(parentWorldMatrix(root, id)) * glm::dvec4(wanted - now, 0));
        state.document.setTransform(id, t);
      }
      // The next copy lands beside the first, not inside it.
      if (pasted.size() == 1) state.selection.assign(1, pasted[0]);
    }
  });
  state.document.endInteraction();
  if (pasted.empty()) return;
  state.selection = pasted;
  state.revealSelection = true;
  // After a cut's first paste, its part is back in place: later pastes are copies of it.
  if (state.clipboardFromCut)
    state.clipboardFromCut = false;
  else
    ++state.pastes;
  if (originalThere) {
    char text[112];
    std::snprintf(text, sizeof(text), "pasted %.4g %s along +x from the copied part%s", step,
                  unitSymbol(state.document.scene().settings.unit), pasted.size() == 1 ? "" : "s");
    logInfo(state, text);
  }
}

void instanceSelection(EditorState& state) {
  if (state.selection.empty()) return;
  std::vector<NodeId> instances;
  state.document.beginInteraction();
  for (NodeId id : state.selection) {
    guarded(state, [&] {
      NodePtr original = findNode(state.document.root(), id);
      NodeLocation where;
      if (!original || !locateNode(state.document.root(), id, &where) || !where.parent)
        throw Error("the root cannot be instanced: select a part of the tree");
      auto instance = std::make_shared<Node>();
      instance->kind = NodeKind::Instance;
      instance->instanceOf = id;
      instance->name = original->name + " instance";
      instance->color = original->color;
      instances.push_back(state.document.addSubtree(instance, where.parent->id, where.index + 1));
    });
  }
  state.document.endInteraction();
  if (!instances.empty()) {
    state.selection = instances;
    state.revealSelection = true;
  }
}

void toggleSelectionHidden(EditorState& state) {
  if (state.selection.empty()) return;
  bool allHidden = true;
  for (NodeId id : state.selection) {
    NodePtr n = findNode(state.document.root(), id);
    if (n && n->visible) allHidden = false;
  }
  state.document.beginInteraction();
  for (NodeId id : state.selection)
    guarded(state, [&] { state.document.setVisible(id, allHidden); });
  state.document.endInteraction();
}

NodeKind groupKindKeepingRoles(const EditorState& state) {
  const NodePtr& root = state.document.root();
  const std::vector<NodeId> parts = outermostSelected(root, state.selection);
  bool intersect = !parts.empty();
  for (NodeId id : parts)
    intersect = intersect && findNode(root, id) && roleOf(root, id) == ChildRole::Intersect;
  return intersect ? NodeKind::Intersection : NodeKind::Union;
}

void groupSelection(EditorState& state, NodeKind kind) {
  if (state.selection.empty()) return;
  const Bounds bounds = selectionBounds(state.document.root(), state.selection);
  const double wall = modifierOf(kind) == Modifier::Round ? thinnestWallOfSelection(state)
                                                          : std::numeric_limits<double>::infinity();
  state.document.beginInteraction();  // the group and its modifier's distance: one undo step
  guarded(state, [&] {
    NodeId id = state.document.group(state.selection, kind);
    // Said, so that an earlier refusal (of another grouping) does not read as this one's.
    if (const NodePtr made = findNode(state.document.root(), id))
      logInfo(state, "grouped " + std::to_string(made->children.size()) +
                         (made->children.size() == 1 ? " part" : " parts") + " as " +
                         displayName(*made));
    // A Boolean's or a modifier's origin is only where its gizmo turns and scales it: at the
    // centre of what it holds, its parts moved back by as much (nothing moves in the world). It
    // was the parent's origin, where a union wrapped around a part far from it had its gizmo (an
    // artist's test). A pattern keeps it: its copies are placed about it.
    if (patternOf(kind) == Pattern::None && !bounds.empty()) {
      const NodePtr& root = state.document.root();
      const glm::dvec3 centre =
          glm::dvec3(glm::inverse(parentWorldMatrix(root, id)) * glm::dvec4(bounds.center(), 1.0));
      const NodePtr group = findNode(root, id);
      // Not where an instance repeats one of its parts: the part's own transform would change,
      // and the copy would move with it (an artist's re-test: a bore's copy went astray).
      bool repeated = false;
      for (const NodePtr& child : group ? group->children : std::vector<NodePtr>{})
        repeated = repeated || instanceRepeating(root, child->id);
      if (group && !repeated && group->transform.matrix() == glm::dmat4(1.0)) {
        std::vector<std::pair<NodeId, Transform>> parts;
        for (const NodePtr& child : group->children) {
          Transform t = child->transform;
          t.translate -= centre;
          parts.push_back({child->id, t});
        }
        Transform at = group->transform;
        at.translate = centre;
        state.document.setTransform(id, at);
        for (const auto& [child, t] : parts) state.document.setTransform(child, t);
      }
    }
    if (modifierOf(kind) != Modifier::None) {
      double amount = modifierAmountFor(kind, bounds);
      std::string why;
      if (modifierOf(kind) == Modifier::Round) amount = roundRadiusFor(state, wall, amount, &why);
      state.document.setAmount(id, amount);
      if (!why.empty())
        logInfo(state, displayName(*findNode(state.document.root(), id)) + ": " + why);
    }
    if (patternOf(kind) != Pattern::None)
      state.document.setPattern(id, patternFor(state, kind, bounds));
    selectNode(state, id);
    // A pattern's copies lie about its origin (the parent's: a mirror of a part far from it lands
    // as far on the other side): the view shows them where they are out of it.
    if (patternOf(kind) != Pattern::None) state.revealSelection = true;
  });
  state.document.endInteraction();
}

namespace {

// Moves node `id` by `delta` in the world (its translation changed in its parent's frame).
void moveInWorld(EditorState& state, NodeId id, const glm::dvec3& delta) {
  NodePtr node = findNode(state.document.root(), id);
  if (!node || delta == glm::dvec3(0.0)) return;
  const glm::dmat4 toParent = glm::inverse(parentWorldMatrix(state.document.root(), id));
  Transform t = node->transform;
  t.translate += glm::dvec3(toParent * glm::dvec4(delta, 0.0));
  state.document.setTransform(id, t);
}

double edgeOf(const Bounds& b, int axis, AlignEdge edge) {
  return edge == AlignEdge::Min   ? b.min[axis]
         : edge == AlignEdge::Max ? b.max[axis]
                                  : b.center()[axis];
}
}  // namespace

void alignSelection(EditorState& state, int axis, AlignEdge edge) {
  const NodeId active = primarySelection(state);
  const Bounds target = selectionBounds(state.document.root(), {active});
  if (!active || target.empty()) return;
  state.document.beginInteraction();
  guarded(state, [&] {
    for (NodeId id : outermostSelected(state.document.root(), state.selection)) {
      // Not the active part, nor a group holding it (moving that would move the target too).
      NodePtr node = findNode(state.document.root(), id);
      if (id == active || (node && findNode(node, active))) continue;
      const Bounds b = selectionBounds(state.document.root(), {id});
      if (b.empty()) continue;
      glm::dvec3 delta(0.0);
      delta[axis] = edgeOf(target, axis, edge) - edgeOf(b, axis, edge);
      moveInWorld(state, id, delta);
    }
  });
  state.document.endInteraction();
}

void dropSelectionToGround(EditorState& state) {
  state.document.beginInteraction();
  guarded(state, [&] {
    for (NodeId id : outermostSelected(state.document.root(), state.selection)) {
      const Bounds b = selectionBounds(state.document.root(), {id});
      if (!b.empty()) moveInWorld(state, id, glm::dvec3(0.0, 0.0, -b.min.z));
    }
  });
  state.document.endInteraction();
}

void setSelectionOperation(EditorState& state, NodeKind kind) {
  state.document.beginInteraction();
  for (NodeId id : state.selection) {
    NodePtr n = findNode(state.document.root(), id);
    if (!n || !isOperation(n->kind)) continue;
    const Bounds held = selectionBounds(state.document.root(), {id});
    const std::string changes = roleChangesOfKind(*n, kind);
    guarded(state, [&] {
      state.document.setOperation(id, kind);
      if (!changes.empty())
        logInfo(state, displayName(*n) + " is a " + kindName(kind) + ": " + changes);
      // Becoming a pattern: copies spaced for what it holds, but what it had as another kind
      // of pattern kept (an array's 10 x 10 came back as 3 copies after a turn as a circular
      // array: an artist's test; undo had them).
      if (patternOf(kind) != Pattern::None && patternOf(n->kind) != patternOf(kind)) {
        const PatternParams fresh = patternFor(state, kind, held);
        PatternParams kept = n->pattern;
        const Pattern p = patternOf(kind);
        if (p == Pattern::Array && kept.counts == glm::ivec3(1)) {
          kept.counts = fresh.counts;
          kept.step = fresh.step;
        } else if (p == Pattern::Circular && kept.count <= 1) {
          kept.count = fresh.count;
          kept.angle = fresh.angle;
          kept.axis = fresh.axis;
          kept.center = fresh.center;
        } else if (p == Pattern::Mirror) {
          kept.axis = fresh.axis;  // a mirror's plane, for what it holds
          kept.center = fresh.center;
          kept.keepOriginal = fresh.keepOriginal;
        }
        state.document.setPattern(id, kept);
        state.revealSelection = true;  // its copies where they lie, out of view or not
      }
    });
  }
  state.document.endInteraction();
}

void renameNode(EditorState& state, NodeId id, const std::string& name) {
  guarded(state, [&] { state.document.rename(id, name); });
}

void dropNode(EditorState& state, NodeId dragged, NodeId target, PlaceMode mode,
              const std::string& label) {
  guarded(state, [&] {
    const std::string sentence = placementSentence(state, target, mode, dragged);
    const NodePtr before = state.document.root();
    state.document.moveOnto(dragged, target, mode, label);
    if (state.document.root() == before) return;  // dropped where it was
    if (NodePtr node = findNode(state.document.root(), dragged))
      logInfo(state, displayName(*node) + " " + sentence);
  });
}

void dropNodes(EditorState& state, NodeId dragged, NodeId target, int mods) {
  const NodePtr& root = state.document.root();
  std::vector<NodeId> moving = {dragged};
  if (isSelected(state, dragged)) moving = outermostSelected(root, state.selection);
  if (moving.size() <= 1) {
    // One moves: the dragged row, or the selected group holding it (as the gizmo moves it).
    const NodeId part = moving.empty() ? dragged : moving.front();
    dropNode(state, part, target, dropMode(state, mods, part, target));
    return;
  }
  // Several rows dragged at once: each moved onto the target keeping what it does (or taking
  // the modifier's role), in the tree's order, as one undo step; refused whole where one is.
  const std::vector<NodeId> order = treeOrder(root);
  std::sort(moving.begin(), moving.end(), [&](NodeId a, NodeId b) {
    return std::find(order.begin(), order.end(), a) < std::find(order.begin(), order.end(), b);
  });
  std::vector<std::pair<NodeId, PlaceMode>> moves;
  for (NodeId id : moving) moves.push_back({id, dropMode(state, mods, id, target)});
  const NodePtr before = root;
  state.document.beginInteraction();
  const bool moved = guarded(state, [&] {
    for (const auto& [id, mode] : moves) {
      if (target != 0 && isInSubtree(state.document.root(), id, target))
        throw Error(displayName(*findNode(state.document.root(), id)) +
                    " holds the part it was dropped on: nothing was moved");
      state.document.moveOnto(id, target, mode);
    }
  });
  if (!moved) {
    state.document.cancelInteraction();
    return;
  }
  state.document.endInteraction();
  if (state.document.root() == before) return;  // each dropped where it was
  const NodePtr onto = findNode(state.document.root(), target ? target : before->id);
  logInfo(state, std::to_string(moves.size()) + " parts moved onto " +
                     (onto ? displayName(*onto) : std::string("the scene")) +
                     ", each keeping what it does" + (mods ? " (or as the key held says)" : ""));
}

const Node* parentOf(const EditorState& state, NodeId id) {
  std::vector<const Node*> path;
  if (!pathToNode(state.document.root(), id, &path) || path.size() < 2) return nullptr;
  return path[path.size() - 2];
}

std::string roleChangeRefusal(const EditorState& state, NodeId id, PlaceMode mode) {
  const NodePtr& root = state.document.root();
  const NodePtr node = findNode(root, id);
  const Node* parent = parentOf(state, id);
  if (!node || !parent) return "the root has no role: it is the result";
  const ChildRole role = roleOf(root, id);
  if (role == ChildRole::Base)
    return displayName(*node) + " is the base of " + displayName(*parent) +
           ": what the parts beside it cut. Drag it elsewhere, or another part onto it, to "
           "change what it does";
  if (modeKeepingRole(role) == mode) return "";
  // Where it would land (an only child goes back where it was, doing what it did).
  try {
    const NodePtr after = changeRole(root, id, mode, state.document.nextId());
    if (modeKeepingRole(roleOf(after, id)) == mode) return "";
  } catch (const Error& e) {
    return e.what();
  }
  return displayName(*node) + " would still " + roleWord(role) + ": " + displayName(*parent) +
         (parent->children.size() == 1 ? " holds nothing else" : " leaves it no other place") +
         ". Drag it onto the part it should act on";
}

void setRole(EditorState& state, NodeId id, PlaceMode mode) {
  const std::string refusal = roleChangeRefusal(state, id, mode);
  if (!refusal.empty()) {
    logError(state, refusal);
    return;
  }
  const ChildRole role = roleOf(state.document.root(), id);
  if (modeKeepingRole(role) == mode) return;
  const Node* parent = parentOf(state, id);
  if (mode == PlaceMode::Add || !unitesItsChildren(*parent)) {
    dropNode(state, id, parent->id, mode, "role");
    return;
  }
  // In a modifier or a pattern it acts on its siblings there (changeRole); a cutter in a shell
  // without an opening becomes its opening too (opensTheShell), in the same undo step.
  guarded(state, [&] {
    const std::string sentence = roleChangeSentence(state, id, mode);
    NodePtr changed = changeRole(state.document.root(), id, mode, state.document.nextId());
    if (opensTheShell(*parent, mode))
      changed = editNode(changed, parent->id, [&](Node& shell) { shell.opening = id; });
    state.document.apply("role", changed);
    if (NodePtr node = findNode(state.document.root(), id))
      logInfo(state, displayName(*node) + " " + sentence);
  });
}

std::string roleChangeSentence(const EditorState& state, NodeId id, PlaceMode mode) {
  const Node* parent = parentOf(state, id);
  if (!parent) return "";
  if (mode == PlaceMode::Add || !unitesItsChildren(*parent))
    return placementSentence(state, parent->id, mode, id);
  std::vector<std::string> names;
  for (const NodePtr& child : parent->children)
    if (child->id != id) names.push_back(displayName(*child));
  const size_t count = names.size();
  std::string siblings = count > 3 ? std::to_string(count) + " parts" : "";
  for (size_t i = 0; count <= 3 && i < count; ++i)
    siblings += (i == 0 ? "" : i + 1 == count ? " and " : ", ") + names[i];
  return std::string(mode == PlaceMode::Cut ? "cuts " : "intersects ") + siblings + " inside " +
         displayName(*parent) + " (a new " + kindLabel(operationKindFor(mode)) + " there takes " +
         (count > 1 ? "them" : "it") + " and this part), which " +
         (opensTheShell(*parent, mode)
              ? "opens the shell's wall where it cuts (the shell's opening; \"none\" there keeps "
                "the wall closed, a pocket)"
          : patternOf(parent->kind) != Pattern::None ? "repeats the result"
                                                     : "changes the result");
}

bool opensTheShell(const Node& parent, PlaceMode mode) {
  return parent.kind == NodeKind::Shell && mode == PlaceMode::Cut && parent.opening == 0;
}

void setResolution(EditorState& state, int resolution) {
  guarded(
      state, [&] { state.document.setResolution(resolution); }, "resolution");
}

// Undo and redo say in the status line what they reverted or repeated: a step that changes
// nothing in view (a measurement off screen, a rename) must not look like a dead key.
namespace {
// Undo and redo while something is being dragged: a gizmo drag or a field dragged with the mouse
// is cancelled (as Escape does: everything it moved goes back), other drags are left to finish. An
// undo in the middle of a drag closed its undo step under it, and the drag went on recording a
// step a frame until the history held nothing else (an artist's test). True when it was one.
bool duringADrag(EditorState& state, const char* what) {
  if (state.gizmoDragging) {
    state.cancelGizmoDrag = true;
    logInfo(state, std::string(what) +
                       " during the drag: the drag is cancelled, everything it moved is back");
    return true;
  }
  if (state.fieldDragHeld) {
    state.cancelFieldDrag = true;
    logInfo(state, std::string(what) +
                       " during the drag: the drag is cancelled, the field's value is back");
    return true;
  }
  if (state.document.interacting()) {
    logWarning(state, std::string(what) + " waits until the drag under way ends");
    return true;
  }
  return false;
}
}  // namespace

void undo(EditorState& state) {
  if (duringADrag(state, "Ctrl+Z")) return;
  const std::string label = state.document.undoLabel();
  rememberSelection(state);  // what redo comes back to
  if (!state.document.undo()) {
    logInfo(state, "nothing to undo");
    return;
  }
  restoreSelection(state);
  state.historyRevision = state.document.revision();
  logInfo(state, "undone: " + label);
}

void redo(EditorState& state) {
  if (duringADrag(state, "Redo")) return;
  const std::string label = state.document.redoLabel();
  rememberSelection(state);
  if (!state.document.redo()) {
    logInfo(state, "nothing to redo");
    return;
  }
  restoreSelection(state);
  state.historyRevision = state.document.revision();
  logInfo(state, "redone: " + label);
}

void newDocument(EditorState& state) {
  if (state.newDocumentResolution > 0) {
    Scene scene = Document().scene();
    scene.settings.resolution = state.newDocumentResolution;
    replaceDocument(state, Document(std::move(scene)));
    logInfo(state, "new document, previewed at " + std::to_string(state.newDocumentResolution) +
                       " cells (--resolution)");
    return;
  }
  replaceDocument(state, Document());
  logInfo(state, "new document");
}

namespace {
// Whether `path` names a file directly inside the bundled scenes' folder (links and ".." resolved).
bool isBundledScene(const EditorState& state, const std::string& path) {
  if (state.bundledScenesFolder.empty()) return false;
  std::error_code ec;
  const fs::path folder = fs::weakly_canonical(state.bundledScenesFolder, ec);
  if (ec) return false;
  const fs::path file = fs::weakly_canonical(path, ec);
  return !ec && file.parent_path() == folder;
}
}  // namespace

bool openDocument(EditorState& state, const std::string& path) {
  if (isBundledScene(state, path) && !meshFormatFor(path, MeshAccess::Read))
    return openTemplate(state, path);
  return guarded(state, [&] {
    if (meshFormatFor(path, MeshAccess::Read))
      throw Error(path + ": a mesh, not a scene: File > Import mesh adds it to this scene");
    std::vector<std::string> warnings;
    Document doc = strata::openDocument(path, &warnings);
    replaceDocument(state, std::move(doc));
    for (const auto& w : warnings) logWarning(state, w);
    logInfo(state, "opened " + path);
    rememberRecent(state, path);
  });
}

bool openTemplate(EditorState& state, const std::string& path) {
  return guarded(state, [&] {
    std::vector<std::string> warnings;
    Document original = strata::openDocument(path, &warnings);  // mesh paths absolute
    replaceDocument(state, Document(original.scene()));
    state.templateName = std::filesystem::path(path).filename().string();
    for (const auto& w : warnings) logWarning(state, w);
    logInfo(state, "opened a copy of " + path +
                       (isBundledScene(state, path) ? ", an example shipped with Strata" : "") +
                       " (Save asks where to keep it)");
  });
}

bool saveDocument(EditorState& state) {
  if (state.document.path().empty()) return false;
  // Written since by another editor or program: asked first (its work was overwritten without a
  // word, only the one .bak keeping it: an artist's test).
  if (const std::string changed = changedOnDisk(state.document); !changed.empty()) {
    state.overwriteQuestion = changed;
    return false;
  }
  return saveDocumentAs(state, state.document.path());
}

bool saveDocumentAs(EditorState& state, const std::string& path) {
  return guarded(state, [&] {
    saveDocumentAs(state.document, path);
    settleErrors(state);
    logInfo(state, "saved " + path);
    rememberRecent(state, path);
  });
}

namespace {
// The offer answered: the next one (if any) is asked about next.
void nextRecoveryOffer(EditorState& state) {
  if (!state.recoveryOffers.empty()) state.recoveryOffers.erase(state.recoveryOffers.begin());
  state.offerRecovery = !state.recoveryOffers.empty();
}
}  // namespace

bool recoverDocument(EditorState& state) {
  if (state.recoveryOffers.empty()) return false;
  const RecoveryOffer offer = state.recoveryOffers.front();
  const bool recovered = guarded(state, [&] {
    std::vector<std::string> warnings;
    Document doc = readRecoveryFile(offer.path, &warnings);
    replaceDocument(state, std::move(doc));
    for (const auto& w : warnings) logWarning(state, w);
    logInfo(state,
            "recovered the unsaved work of an editor that ended without saving (its undo "
            "history was not kept: undo starts from here)");
  });
  // Read: the work is this editor's now (its own autosave keeps it). A damaged file is moved
  // aside with the discarded ones, where it can be mended and opened: left in place, it was
  // offered again at every start, to fail again.
  if (recovered) {
    forgetRecovery(offer);
  } else {
    // The reader's error and where the file went, in one line (the status bar showed the move
    // and "+1 earlier error"; the reason was only in Diagnostics: an artist's re-test).
    const std::string why = state.log.empty() ? std::string() : state.log.back().text;
    const std::string kept = discardRecovery(offer, state.recoveryDir);
    if (!kept.empty()) {
      state.log.back().dismissed = true;  // said again below, with where the file went
      logError(state, "the unsaved work could not be read back (" + why +
                          "); the file is kept as " + kept +
                          ", not offered again: mend it and File > Open it");
    }
  }
  nextRecoveryOffer(state);
  // The others are left for a later start (or another editor): recovering one of them here would
  // replace the document just recovered, unsaved.
  if (recovered && !state.recoveryOffers.empty()) {
    const size_t more = state.recoveryOffers.size();
    logInfo(state, std::to_string(more) +
                       (more == 1 ? " more unsaved document is" : " more unsaved documents are") +
                       " offered at the next start (or to another editor started now)");
    state.recoveryOffers.clear();
    state.offerRecovery = false;
  }
  return recovered;
}

void discardRecovery(EditorState& state) {
  if (state.recoveryOffers.empty()) return;
  const std::string kept = discardRecovery(state.recoveryOffers.front(), state.recoveryDir);
  if (!kept.empty())
    logInfo(state, "discarded the unsaved work; kept as " + kept + " (the last " +
                       std::to_string(kKeptDiscards) + " discarded are kept: File > Open it)");
  else
    logWarning(state, "the unsaved work could not be moved aside: it is offered again next time");
  nextRecoveryOffer(state);
}

void postponeRecovery(EditorState& state) {
  if (!state.recoveryOffers.empty()) {
    const std::string origin = describeRecoveryFile(state.recoveryOffers.front().path).origin;
    logInfo(state, "the unsaved work on " + (origin.empty() ? "an untitled document" : origin) +
                       " is offered again at the next start");
  }
  nextRecoveryOffer(state);
}

std::string documentFolder(const EditorState& state) {
  if (state.document.path().empty()) return "";
  // Absolute: the file dialog resolves a relative name in the folder it shows, which for a
  // document opened by a relative path would double that path.
  std::error_code error;
  const std::filesystem::path path =
      std::filesystem::absolute(std::filesystem::path(state.document.path()), error);
  return (error ? std::filesystem::path(state.document.path()) : path).parent_path().string() + "/";
}

std::string importFolder(const EditorState& state) {
  std::error_code missing;
  if (!state.lastImportFolder.empty() &&
      std::filesystem::is_directory(state.lastImportFolder, missing))
    return state.lastImportFolder + "/";
  return dialogFolder(state);
}

void rememberImportChoices(EditorState& state) {
  if (state.importSettingsPath.empty()) return;
  try {
    writeImportSettings(state.importSettingsPath,
                        {state.lastImportFolder, state.lastImportUnit, state.lastImportUpAxis});
  } catch (const std::exception& e) {
    logWarning(state, std::string("import options not remembered: ") + e.what());
  }
}

std::string saveAsSuggestion(const EditorState& state) {
  if (!state.document.path().empty()) return state.document.path();
  return dialogFolder(state) +
         (state.templateName.empty() ? std::string("untitled.strata.json") : state.templateName);
}

std::string dialogFolder(const EditorState& state) {
  const std::string own = documentFolder(state);
  if (!own.empty()) return own;
  // Untitled: the folder of the last scene saved or opened, in this run or an earlier one (the
  // recent files; a bundled example's copy, opened from the program's scenes/, is none of them:
  // an artist's Save opened there, not where they had last saved),
  std::error_code missing;
  for (const std::string& recent : state.recentFiles) {
    const std::filesystem::path folder = std::filesystem::path(recent).parent_path();
    if (!folder.empty() && std::filesystem::is_directory(folder, missing))
      return folder.string() + "/";
  }
  // else the folder of the document it replaced (File > New after working on a file),
  if (!state.lastDocumentFolder.empty() &&
      std::filesystem::is_directory(state.lastDocumentFolder, missing))
    return state.lastDocumentFolder;
  // else the last export's (of this run, else of an earlier one),
  if (!state.lastExportPath.empty())
    return std::filesystem::path(state.lastExportPath).parent_path().string() + "/";
  if (const std::string kept = rememberedExportFolder(state); !kept.empty()) return kept;
  // An untitled document's files go to the user's home, not wherever the editor was started
  // from (an artist's Save As opened in the program's own folder).
  std::error_code error;
  const char* home = std::getenv("HOME");
  if (home && *home && std::filesystem::is_directory(home, error)) return std::string(home) + "/";
  return "";
}

std::string rememberedExportFolder(const EditorState& state) {
  std::error_code missing;
  if (state.rememberedExportFolder.empty() ||
      !std::filesystem::is_directory(state.rememberedExportFolder, missing))
    return "";
  std::string folder = state.rememberedExportFolder;
  if (folder.back() != '/') folder += '/';
  return folder;
}

std::string documentLabel(const EditorState& state) {
  const Document& d = state.document;
  std::string name = d.name();
  if (d.path().empty() && !state.templateName.empty())
    name += " (a copy of " + state.templateName + ")";
  return name + (d.dirty() ? " *" : "");
}

std::string windowTitle(const EditorState& state) {
  return "Strata \u2014 " + documentLabel(state);
}

std::string exportSuggestion(const EditorState& state) {
  if (!state.lastExportPath.empty() && !state.document.path().empty() &&
      state.lastExportDocument == state.document.path())
    return state.lastExportPath;
  if (state.document.path().empty()) {
    // Untitled: the last export's folder (which may be another untitled document's, or an
    // earlier run's), a new name.
    if (!state.lastExportPath.empty())
      return (std::filesystem::path(state.lastExportPath).parent_path() / "part.stl").string();
    const std::string kept = rememberedExportFolder(state);
    return (kept.empty() ? dialogFolder(state) : kept) + "part.stl";
  }
  std::string name = std::filesystem::path(state.document.path()).filename().string();
  const std::string suffix = ".strata.json";
  if (name.size() > suffix.size() &&
      name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0)
    name = name.substr(0, name.size() - suffix.size());
  const std::string beside = documentFolder(state) + name + ".stl";
  // A document in a folder that takes no file (a bundled scene, a read-only share): the last
  // export's folder, where there is one.
  if (!cannotWriteAt(beside).empty()) {
    const std::string folder =
        !state.lastExportPath.empty()
            ? std::filesystem::path(state.lastExportPath).parent_path().string() + "/"
            : rememberedExportFolder(state);
    if (!folder.empty() && cannotWriteAt(folder + name + ".stl").empty())
      return folder + name + ".stl";
  }
  return beside;
}

void logExportEnd(EditorState& state) {
  if (!state.exportJob) return;
  const ExportStatus s = state.exportJob->status();
  if (s.running || !s.finished || state.exportEndLogged) return;
  state.exportEndLogged = true;
  if (s.succeeded && s.checkPassed()) {
    char text[96];
    std::snprintf(text, sizeof(text), ": written and checked, watertight, %zu triangles (%.1f s)",
                  s.check.triangles, s.seconds);
    logInfo(state, "exported " + s.path + text);
    for (const std::string& w : s.warnings) logWarning(state, "export: " + w);
  } else if (s.succeeded) {
    logWarning(state, "exported " + s.path + ", but its check FAILED (see the Export window)");
  } else if (s.cancelledAfterWrite) {
    logWarning(state, "export of " + s.path + " cancelled after the file was written: " +
                          exportCancelledAfterWriteText);
  } else if (s.cancelled) {
    logInfo(state, "export of " + s.path + " " + exportCancelledText(s));
  } else {
    logWarning(state,
               "export of " + s.path + (s.refused ? " not started: " : " failed: ") + s.error);
  }
}

std::string exportCancelledText(const ExportStatus& s) {
  return s.cancelledKeptFile
             ? "cancelled; nothing was written: the file that was there is as it was"
             : "cancelled; nothing was written";
}

void startExport(EditorState& state, const std::string& path, int resolution, double simplifyCells,
                 bool insist) {
  if (state.exportJob && state.exportJob->status().running) {
    logWarning(state, "an export is already running");
    return;
  }
  // Said now, not after the whole export, and in the export window (an artist's test of a
  // read-only folder).
  state.exportNotStarted.reset();
  if (const std::string why = cannotWriteAt(path); !why.empty()) {
    state.exportNotStarted = EditorState::ExportNotStarted{path, why};
    state.exportJob.reset();  // the last one ended (checked above): one window says this one
    logError(state, path + ": " + why);
  }
  if (!state.exportNotStarted)
    guarded(state, [&] {
      if (!state.makeBackend) throw Error("no backend to export with");
      ExportOptions options;
      options.resolution = resolution;
      options.simplifyCells = simplifyCells;
      ExportGuard guard;
      guard.insist = insist;
      // The dialog's count, where it was for this very choice: the export window says the same.
      if (state.exportEstimate) {
        guard.counted =
            state.exportEstimate->countOf(state.document.snapshot(), resolution, simplifyCells);
        // Its time and memory too, where it probed them: not probed again at Export.
        guard.estimated = state.exportEstimate->estimateOf(state.document.snapshot(), path,
                                                           resolution, simplifyCells);
      }
      state.exportJob = std::make_unique<ExportJob>(state.document.snapshot(), path, options,
                                                    state.makeBackend(), nullptr, guard);
      state.exportEndLogged = false;
      logInfo(state, "exporting " + path + " at resolution " + std::to_string(resolution) +
                         (simplifyCells > 0.0 ? ", simplified" : ""));
      std::error_code error;
      const std::filesystem::path absolute = std::filesystem::absolute(path, error);
      state.lastExportPath = error ? path : absolute.lexically_normal().string();
      state.lastExportDocument = state.document.path();
    });
  if (!state.exportSettingsPath.empty()) {  // the dialog opens with these choices next time
    try {
      const std::string folder =
          state.lastExportPath.empty()
              ? state.rememberedExportFolder
              : std::filesystem::path(state.lastExportPath).parent_path().string();
      writeExportSettings(
          state.exportSettingsPath,
          {resolution, simplifyCells > 0.0,
           simplifyCells > 0.0 ? float(simplifyCells) : state.exportSimplifyCells, folder});
      state.rememberedExportFolder = folder;
    } catch (const std::exception& e) {
      logWarning(state, std::string("export options not remembered: ") + e.what());
    }
  }
}

}  // namespace strata::ui
