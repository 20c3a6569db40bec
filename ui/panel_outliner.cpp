// The scene tree (outliner) and the palette.
#include <imgui.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <string>

#include "engine/document/commands.h"
#include "engine/document/roles.h"
#include "engine/io/mesh_formats.h"
#include "engine/kinds/primitives.h"
#include "ui/editor_actions.h"
#include "ui/panels.h"
#include "ui/scene_queries.h"
#include "ui/text_fit.h"
#include "ui/theme.h"

namespace strata::ui {
namespace {

constexpr const char* kPayload = "STRATA_NODE";

struct PendingDrop {
  NodeId dragged = 0;
  NodeId target = 0;
  bool valid = false;
  int paletteItem = 0;  // with paletteDrop: what was dropped from the palette onto `target`
  bool paletteDrop = false;
  PlaceMode mode = PlaceMode::Add;
  int mods = 0;  // the drop modifiers held (heldDropModifiers)
  // What the part being dragged would do where it hovers now (shown by the drag source's
  // tooltip the next frame); empty when it hovers no target.
  std::string hint;
  bool hintRefused = false;
};

// The hint the drag tooltip shows: set by the target hovered last frame (sources and targets
// are drawn in tree order, so a source above its target would otherwise miss it).
std::string gShownHint;
bool gShownHintRefused = false;

// The rows the outliner shows, in order (a collapsed operation's parts are not among them):
// those drawn this frame, and last frame's, which a Shift+click selects a range of.
std::vector<NodeId> gRowsDrawn, gRowsShown;
// A selected row pressed among several selected: selected alone when released without a drag.
NodeId gPressedRow = 0;

}  // namespace

int heldDropModifiers() {
  const ImGuiIO& io = ImGui::GetIO();
  return (io.KeyShift ? kDropIntersect : 0) | (io.KeyCtrl ? kDropCut : 0) |
         (io.KeyAlt ? kDropAdd : 0);
}

namespace {

// The drop target of the last item (a row, or the empty space: target 0): says what the
// dragged node or palette item would do there, with the modifiers held now, and accepts it
// unless it would be refused (a refused target is not highlighted).
void dropTarget(const EditorState& state, NodeId target, PendingDrop* drop) {
  const ImGuiPayload* payload = ImGui::GetDragDropPayload();
  if (!payload) return;
  NodeId dragged = 0;
  if (payload->IsDataType(kPayload)) std::memcpy(&dragged, payload->Data, sizeof(NodeId));
  const PlaceMode mode = dropMode(state, heldDropModifiers(), dragged, target);
  bool refused = false;
  const std::string sentence = placementSentence(state, target, mode, dragged, &refused);
  drop->hint = refused ? "can't drop here: " + sentence : sentence;
  drop->hintRefused = refused;
  if (refused) return;
  if (const ImGuiPayload* p = ImGui::AcceptDragDropPayload(kPayload)) {
    std::memcpy(&drop->dragged, p->Data, sizeof(NodeId));
    drop->target = target;
    drop->valid = true;
    drop->mode = mode;
    drop->mods = heldDropModifiers();
  }
  if (const ImGuiPayload* p = ImGui::AcceptDragDropPayload(kPalettePayload)) {
    std::memcpy(&drop->paletteItem, p->Data, sizeof(int));
    drop->target = target;
    drop->paletteDrop = true;
    drop->mode = mode;
  }
}

// The drag tooltip's second part: what the part would do where it hovers.
void dragHint() {
  if (gShownHint.empty()) {
    ImGui::TextDisabled(
        "drop on a row: a hole stays a hole and a solid takes no material away, its role "
        "changed where the place needs it (Ctrl: cut, Shift: intersect, Alt: add)");
    return;
  }
  ImGui::PushTextWrapPos(ImGui::GetFontSize() * 24.0f);
  if (gShownHintRefused)
    ImGui::TextColored(ImVec4(1.0f, 0.5f, 0.45f, 1.0f), "%s", gShownHint.c_str());
  else
    ImGui::TextUnformatted(gShownHint.c_str());
  ImGui::TextDisabled("Ctrl: cut  Shift: intersect  Alt: add");
  ImGui::PopTextWrapPos();
}

// A child's role in its parent, as a short word coloured by what its material does to the
// result (`removes`: removesMaterial, roles.h): red where it is taken away, so that a part that
// adds to a cutter does not look like one that adds material; such a part reads "cut".
// The badge's word ("" for the root, which has none) and colour.
const char* roleBadgeWord(ChildRole role, bool removes, ImVec4* colour) {
  const ImVec4 red(1.0f, 0.45f, 0.42f, 1.0f);
  *colour = removes ? red : ImVec4(0.6f, 0.62f, 0.66f, 1.0f);
  switch (role) {
    case ChildRole::Add:
      // Inside a cutter (a hole of a circular array that cuts): its material is taken away, and
      // the word says so ("add" in red was read as adding material: an artist's test); the
      // tooltip says it adds to the cutter.
      *colour = removes ? red : ImVec4(0.5f, 0.85f, 0.55f, 1.0f);
      return removes ? "cut" : "add";
    case ChildRole::Cut:
      *colour = removes ? red : ImVec4(0.5f, 0.85f, 0.55f, 1.0f);
      return "cut";
    case ChildRole::Intersect:
      *colour = ImVec4(0.75f, 0.6f, 1.0f, 1.0f);
      return "intersect";
    case ChildRole::Root:
      return "";
    default:
      return "base";
  }
}

// Drawn ending at `x` (window coordinates), on the row's line.
void roleBadge(ChildRole role, bool removes, float x) {
  ImVec4 colour;
  const char* word = roleBadgeWord(role, removes, &colour);
  if (!*word) return;
  ImGui::SameLine(x - ImGui::CalcTextSize(word).x);
  ImGui::TextColored(colour, "%s", word);
}

// Operations are coloured by the Boolean they apply; leaves are grey.
ImVec4 kindColor(NodeKind kind) {
  const NodeKindInfo& info = nodeKindInfo(kind);
  if (info.role != KindRole::Operation) return ImVec4(0.7f, 0.72f, 0.76f, 1.0f);
  switch (info.rayOp) {
    case RayOp::Union:
      return ImVec4(0.45f, 0.78f, 1.0f, 1.0f);
    case RayOp::Intersection:
      return ImVec4(0.75f, 0.6f, 1.0f, 1.0f);
    default:
      return ImVec4(1.0f, 0.45f, 0.42f, 1.0f);
  }
}

void contextMenu(EditorState& state, const NodePtr& node) {
  if (!ImGui::BeginPopupContextItem()) return;
  if (!isSelected(state, node->id)) selectNode(state, node->id);
  contextMenuItems(state, node);
  ImGui::EndPopup();
}

}  // namespace

void contextMenuItems(EditorState& state, const NodePtr& node) {
  ImGui::TextDisabled("%s %s", kindGlyph(node->kind), node->name.c_str());
  ImGui::Separator();
  if (ImGui::MenuItem("Rename", "F2")) state.renaming = node->id;
  if (ImGui::MenuItem(node->visible ? "Hide" : "Show", "H")) toggleSelectionHidden(state);
  if (ImGui::MenuItem("Duplicate", "Ctrl+D")) duplicateSelection(state);
  if (ImGui::MenuItem("Instance", "Alt+D")) instanceSelection(state);
  if (ImGui::MenuItem("Delete", "Del")) deleteSelection(state);
  ImGui::Separator();
  if (ImGui::BeginMenu("Group as")) {
    for (NodeKind k : operationKinds()) {
      const std::string label = std::string(kindGlyph(k)) + " " + kindLabel(k);
      if (ImGui::MenuItem(label.c_str())) groupSelection(state, k);
    }
    ImGui::EndMenu();
  }
  // The part's role where it is (setRole), each with what it would do; not for the root or a
  // difference's base, whose role is their place.
  const Node* parent = parentOf(state, node->id);
  const ChildRole role = parent ? roleOf(state.document.root(), node->id) : ChildRole::Root;
  if (parent && role != ChildRole::Base && ImGui::BeginMenu("Role")) {
    for (PlaceMode mode : {PlaceMode::Add, PlaceMode::Cut, PlaceMode::Intersect}) {
      const bool current = modeKeepingRole(role) == mode;
      const char* word = mode == PlaceMode::Add   ? "adds"
                         : mode == PlaceMode::Cut ? "cuts"
                                                  : "intersects";
      const std::string refusal = current ? "" : roleChangeRefusal(state, node->id, mode);
      if (ImGui::MenuItem(word, nullptr, current, refusal.empty()) && !current)
        setRole(state, node->id, mode);
      if (!current && ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) {
        const std::string says =
            refusal.empty() ? "it " + roleChangeSentence(state, node->id, mode) : refusal;
        ImGui::SetTooltip("%s", says.c_str());
      }
    }
    ImGui::EndMenu();
  }
  if (isOperation(node->kind) && ImGui::BeginMenu("Operation")) {
    for (NodeKind k : operationKinds())
      if (ImGui::MenuItem(kindLabel(k), nullptr, node->kind == k)) setSelectionOperation(state, k);
    ImGui::EndMenu();
  }
  ImGui::Separator();
  if (ImGui::MenuItem("Frame", "F")) state.requestFrameSelected = true;
}

namespace {

void renameField(EditorState& state, const NodePtr& node) {
  static char buffer[256];
  static NodeId editing = 0;
  if (editing != node->id) {
    std::snprintf(buffer, sizeof(buffer), "%s", node->name.c_str());
    editing = node->id;
    ImGui::SetKeyboardFocusHere();
  }
  ImGui::SetNextItemWidth(-1);
  bool enter =
      ImGui::InputText("##rename", buffer, sizeof(buffer),
                       ImGuiInputTextFlags_EnterReturnsTrue | ImGuiInputTextFlags_AutoSelectAll);
  if (enter || ImGui::IsItemDeactivated()) {
    if (!ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape)) && node->name != buffer)
      renameNode(state, node->id, buffer);
    state.renaming = 0;
    editing = 0;
  }
}

// Chains: an operation nested in one of the same associative kind (a union in a union, an
// intersection in an intersection) means the same flattened, so a chain of them (three or more
// deep, such as a scaffold's 27 nested unions) is shown at one indent: its links as thin rows,
// their children beside each other. Shorter nestings are groups the artist made: shown as trees.
bool sameAssociativeKind(const Node& parent, const Node& child) {
  const RayOp op = nodeKindInfo(parent.kind).rayOp;
  return isOperation(parent.kind) && child.kind == parent.kind &&
         (op == RayOp::Union || op == RayOp::Intersection);
}

// Whether `node` continues a chain at least `depth` links below it.
bool chainBelow(const Node& node, int depth) {
  if (depth <= 0) return true;
  for (const auto& c : node.children)
    if (sameAssociativeKind(node, *c) && chainBelow(*c, depth - 1)) return true;
  return false;
}

// `removes`: whether the node's material is taken away from the result (an odd number of
// cutters from the root to it, itself included: removesMaterial, roles.h).
void nodeRow(EditorState& state, const NodePtr& node, ChildRole role, bool removes,
             PendingDrop* drop, bool chained = false) {
  const bool isRoot = role == ChildRole::Root;
  ImGui::PushID(static_cast<int>(node->id));
  gRowsDrawn.push_back(node->id);
  const bool leaf = node->children.empty();
  ImGuiTreeNodeFlags flags = ImGuiTreeNodeFlags_OpenOnArrow | ImGuiTreeNodeFlags_SpanAvailWidth |
                             ImGuiTreeNodeFlags_DefaultOpen | ImGuiTreeNodeFlags_FramePadding;
  if (leaf || chained) flags |= ImGuiTreeNodeFlags_Leaf | ImGuiTreeNodeFlags_NoTreePushOnOpen;
  if (chained) flags &= ~ImGuiTreeNodeFlags_FramePadding;  // a thin row
  if (isSelected(state, node->id)) flags |= ImGuiTreeNodeFlags_Selected;

  // Visibility toggle at the right edge.
  const float right = ImGui::GetContentRegionMax().x;
  const ImVec2 rowStart = ImGui::GetCursorPos();

  // Revealing a part picked in the view: every row above it open.
  const bool reveal = state.revealInOutliner != 0;
  if (reveal && !leaf && !chained && state.revealInOutliner != node->id &&
      findNode(node, state.revealInOutliner))
    ImGui::SetNextItemOpen(true);

  bool open;
  float clipRight = 1e9f;
  bool kindShown = isOperation(node->kind) && !chained;  // the kind word after the name
  if (state.renaming == node->id) {
    open = ImGui::TreeNodeEx("##node", flags | ImGuiTreeNodeFlags_AllowItemOverlap, "%s",
                             kindGlyph(node->kind));
    ImGui::SameLine();
    renameField(state, node);
  } else {
    // The name (and the operation's kind) end where this row's role badge begins, right-aligned
    // before the eye (the root has none); the full name is in the row's tooltip. The room of
    // the widest badge, kept on every row, cut "bolt circle" to "bol\u2026" with the room of
    // "intersect" empty beside it (an artist's test).
    ImVec4 unused;
    const char* badge = roleBadgeWord(role, removes, &unused);
    const float badgeColumn =
        (*badge ? ImGui::CalcTextSize(badge).x + ImGui::GetStyle().ItemSpacing.x : 0.0f) +
        ImGui::GetFrameHeight() + ImGui::GetStyle().ItemSpacing.x;
    clipRight = ImGui::GetWindowPos().x + right - badgeColumn;
    ImGui::PushClipRect(ImVec2(ImGui::GetWindowPos().x, -1e9f), ImVec2(clipRight, 1e9f), true);
    // A mesh whose file could not be read when the scene opened: amber, marked, and said why on
    // hover (meshMissing).
    const bool missing = meshMissing(*node);
    if (!node->visible) ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(0.5f, 0.5f, 0.52f, 1.0f));
    if (chained) ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(0.55f, 0.6f, 0.68f, 1.0f));
    if (missing) ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.72f, 0.3f, 1.0f));
    // A name too long for the column ends in an ellipsis (the operation's kind word after it
    // keeps its room); the row's tooltip has it whole.
    const std::string prefix = std::string(kindGlyph(node->kind)) + (chained ? "  \u2026 " : "  ");
    const std::string suffix = missing ? " (missing)" : node->meshOpen ? " (open)" : "";
    const float textStart = ImGui::GetCursorScreenPos().x + ImGui::GetFontSize() +
                            2.0f * ImGui::GetStyle().FramePadding.x;
    // The operation's kind word after the name where both fit; where the name would be cut, the
    // name has the room (its glyph and the inspector say the kind): in a narrow panel "bolt
    // circle" read "\u2026" beside a whole "circular array" (an artist's test).
    const std::string& shownName = node->name.empty() ? std::string("(unnamed)") : node->name;
    const float nameRoomAlone =
        clipRight - textStart - ImGui::CalcTextSize((prefix + suffix).c_str()).x;
    float kindRoom =
        isOperation(node->kind) && !chained
            ? ImGui::CalcTextSize(kindLabel(node->kind)).x + ImGui::GetStyle().ItemSpacing.x
            : 0.0f;
    if (ImGui::CalcTextSize(shownName.c_str()).x > nameRoomAlone - kindRoom) kindRoom = 0.0f;
    kindShown = kindRoom > 0.0f;
    const float nameRoom = nameRoomAlone - kindRoom;
    const std::string name = fitWithEllipsis(
        shownName, nameRoom, [](const std::string& s) { return ImGui::CalcTextSize(s.c_str()).x; });
    open = ImGui::TreeNodeEx("##node", flags | ImGuiTreeNodeFlags_AllowItemOverlap, "%s",
                             (prefix + name + suffix).c_str());
    if (missing) ImGui::PopStyleColor();
    if (chained) ImGui::PopStyleColor();
    if (!node->visible) ImGui::PopStyleColor();
    ImGui::PopClipRect();
    if (ImGui::IsItemClicked(0) && !ImGui::IsItemToggledOpen()) {
      const ImGuiIO& io = ImGui::GetIO();
      if (io.KeyShift)
        selectRange(state, node->id, gRowsShown);
      else if (!io.KeyCtrl && state.selection.size() > 1 && isSelected(state, node->id))
        gPressedRow = node->id;  // a drag takes the whole selection; a click, this row alone
      else
        selectNode(state, node->id, io.KeyCtrl);
    }
    if (reveal && state.revealInOutliner == node->id) {
      if (!ImGui::IsItemVisible()) ImGui::SetScrollHereY(0.5f);
      state.revealInOutliner = 0;
    }
    if (gPressedRow == node->id && ImGui::IsMouseReleased(0)) {
      if (ImGui::IsItemHovered() && !ImGui::GetDragDropPayload()) selectNode(state, node->id);
      gPressedRow = 0;
    }
    if (ImGui::IsItemHovered() && ImGui::IsMouseDoubleClicked(0)) state.renaming = node->id;
    if (!isRoot && ImGui::BeginDragDropSource()) {
      NodeId id = node->id;
      ImGui::SetDragDropPayload(kPayload, &id, sizeof(id));
      const size_t moving = isSelected(state, id)
                                ? outermostSelected(state.document.root(), state.selection).size()
                                : 1;
      if (moving > 1)
        ImGui::Text("%s %s and %zu more selected", kindGlyph(node->kind), node->name.c_str(),
                    moving - 1);
      else
        ImGui::Text("%s %s", kindGlyph(node->kind), node->name.c_str());
      dragHint();
      ImGui::EndDragDropSource();
    }
    if (ImGui::BeginDragDropTarget()) {
      dropTarget(state, node->id, drop);
      ImGui::EndDragDropTarget();
    }
    if (ImGui::IsItemHovered() && !ImGui::GetDragDropPayload() && !isRoot) {
      // Inside a cutter (the parity of the cutters above differs from its own role's) the
      // material goes the other way than the role says.
      const bool ownCut = role == ChildRole::Cut;
      const char* inside =
          removes == ownCut ? ""
          : ownCut
              ? "\ninside a cutter: where it lies that cutter cuts nothing (it adds no material)"
              : "\ninside a cutter: its material is taken away (a hole, not a solid)";
      // Why, where loading said (an open mesh read as "could not be read": an artist's test).
      const std::string missingNote =
          !meshMissing(*node) ? ""
          : node->meshRefusedAsOpen
              ? "\nnot taken: " + node->meshProblem +
                    "\nnothing of it is evaluated; the inspector can take "
                    "it as an open mesh"
              : "\nits file could not be read: " +
                    (node->meshProblem.empty() ? "\"" + node->meshPath + "\"" : node->meshProblem) +
                    "\nnothing of it is evaluated; put the file back and "
                    "open the scene again, or delete the node";
      // What it does to what: "bunny adds to 'mirror 10'" (a bare "bunny adds" said to what not).
      std::vector<const Node*> path;
      std::string within;
      if (pathToNode(state.document.root(), node->id, &path) && path.size() >= 2) {
        const Node& parent = *path[path.size() - 2];
        const std::string parentName = "'" + (parent.name.empty() ? "(unnamed)" : parent.name) +
                                       "' (" + kindLabel(parent.kind) + ")";
        within = role == ChildRole::Add         ? " to " + parentName
                 : role == ChildRole::Cut       ? " from the base of " + parentName
                 : role == ChildRole::Intersect ? " the rest of " + parentName
                                                : " of " + parentName;
      }
      // Wrapped: a reader's error runs long (it ran off the screen).
      ImGui::BeginTooltip();
      ImGui::PushTextWrapPos(ImGui::GetFontSize() * 40.0f);
      ImGui::Text("%s %s%s%s%s%s", node->name.empty() ? "(unnamed)" : node->name.c_str(),
                  role == ChildRole::Base ? "is the base" : rolePhrase(role), within.c_str(),
                  role == ChildRole::Base ? ": the cutters beside it cut it" : "", inside,
                  missingNote.c_str());
      ImGui::PopTextWrapPos();
      ImGui::EndTooltip();
    }
    // The root: its whole name (cut in a narrow panel) and what it is.
    if (ImGui::IsItemHovered() && !ImGui::GetDragDropPayload() && isRoot)
      ImGui::SetTooltip("%s (%s): the scene's result, the one the view shows and export writes",
                        node->name.empty() ? "(unnamed)" : node->name.c_str(),
                        kindLabel(node->kind));
    contextMenu(state, node);
  }
  if (kindShown) {
    ImGui::SameLine();
    ImGui::PushClipRect(ImVec2(ImGui::GetWindowPos().x, -1e9f), ImVec2(clipRight, 1e9f), true);
    ImGui::TextColored(kindColor(node->kind), "%s", kindLabel(node->kind));
    ImGui::PopClipRect();
  }
  roleBadge(role, removes, right - ImGui::GetFrameHeight() - ImGui::GetStyle().ItemSpacing.x);
  ImGui::SameLine(right - ImGui::GetFrameHeight());
  ImGui::SetCursorPosY(rowStart.y);
  ImGui::PushStyleColor(ImGuiCol_Button, ImVec4(0, 0, 0, 0));
  if (ImGui::Button(visibleGlyph(node->visible), ImVec2(ImGui::GetFrameHeight(), 0))) {
    guarded(state, [&] { state.document.setVisible(node->id, !node->visible); });
  }
  ImGui::PopStyleColor();
  if (ImGui::IsItemHovered()) ImGui::SetTooltip(node->visible ? "Hide" : "Show");

  if ((open || chained) && !leaf) {
    for (size_t i = 0; i < node->children.size(); ++i) {
      const NodePtr& child = node->children[i];
      const bool link = sameAssociativeKind(*node, *child) && (chained || chainBelow(*child, 2));
      const ChildRole childRoleHere = childRole(*node, static_cast<int>(i));
      nodeRow(state, child, childRoleHere, removes != (childRoleHere == ChildRole::Cut), drop,
              link);
    }
    if (!chained) ImGui::TreePop();
  }
  ImGui::PopID();
}

// A palette button `width` wide showing `label` whole or, where the panel is too narrow for it,
// shortened with an ellipsis (it was cut mid-letter at 870 pixels: an artist's test); `id` keeps
// it the same button either way. True when clicked. `*shortened` says whether it was.
bool fittedButton(const std::string& label, const char* id, float width, bool* shortened) {
  const float room = width - 2.0f * ImGui::GetStyle().FramePadding.x;
  const std::string shown = fitWithEllipsis(
      label, room, [](const std::string& s) { return ImGui::CalcTextSize(s.c_str()).x; });
  *shortened = shown != label;
  return ImGui::Button((shown + "##" + id).c_str(), ImVec2(width, 0));
}

// The last palette button as a drag source of `item`.
void paletteDragSource(EditorState& state, int item, const char* label) {
  if (ImGui::BeginDragDropSource()) {
    ImGui::SetDragDropPayload(kPalettePayload, &item, sizeof(item));
    ImGui::Text("%s", label);
    if (gShownHint.empty()) {
      // Over the view (or anywhere but a tree row): what a drop there does (onto the part under
      // the pointer, else onto the selection, with the palette's mode or the key held), said
      // before the release as a row's drop says it (it said only where to drop).
      const NodeId under = state.paletteDropPart;
      const NodePtr part = under ? findNode(state.document.root(), under) : nullptr;
      const std::string does = placementSentence(state, part ? under : primarySelection(state),
                                                 dropMode(state, heldDropModifiers()));
      if (part)
        ImGui::Text("on \"%s\": it %s", part->name.c_str(), does.c_str());
      else
        ImGui::Text("on the ground: it %s", does.c_str());
      ImGui::TextDisabled("on a part's surface or tree row: onto that part");
    } else {
      dragHint();
    }
    ImGui::EndDragDropSource();
  }
}

}  // namespace

float paletteRowsHeight() {
  const int rows = int((primitiveTable().size() + 2) / 3);
  return float(std::max(0, rows - 2) + 2) * ImGui::GetFrameHeightWithSpacing();
}

float paletteHeightFor(const PanelLayout& layout) {
  return layout.paletteHeight + layout.paletteRows;
}

void drawOutliner(EditorState& state, const PanelLayout& layout) {
  const ImGuiViewport* vp = ImGui::GetMainViewport();
  const float paletteHeight = paletteHeightFor(layout);
  ImGui::SetNextWindowPos(ImVec2(vp->Pos.x, vp->Pos.y + layout.menuHeight));
  ImGui::SetNextWindowSize(ImVec2(
      layout.leftWidth, vp->Size.y - layout.menuHeight - layout.statusHeight - paletteHeight));
  ImGui::Begin("Scene", nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                   ImGuiWindowFlags_NoBringToFrontOnFocus);
  PendingDrop drop;
  const NodePtr root = state.document.root();  // this frame's snapshot
  gRowsShown.swap(gRowsDrawn);
  gRowsDrawn.clear();
  if (root) nodeRow(state, root, ChildRole::Root, false, &drop);
  state.revealInOutliner = 0;  // done, or its row is not drawn (inside a chain shown compactly)
  // Empty space below the tree: a drop here places the node onto the root.
  ImVec2 avail = ImGui::GetContentRegionAvail();
  ImGui::InvisibleButton("##empty", ImVec2(std::max(avail.x, 1.0f), std::max(avail.y, 24.0f)));
  if (ImGui::IsItemClicked(0)) clearSelection(state);
  if (ImGui::BeginDragDropTarget()) {
    dropTarget(state, 0, &drop);
    ImGui::EndDragDropTarget();
  }
  ImGui::End();
  gShownHint = drop.hint;
  gShownHintRefused = drop.hintRefused;
  if (ImGui::IsMouseReleased(0)) gPressedRow = 0;  // its row handled the release, or is gone
  if (drop.valid) dropNodes(state, drop.dragged, drop.target, drop.mods);
  if (drop.paletteDrop) dropPaletteItem(state, drop.paletteItem, drop.target, drop.mode);
}

void drawPalette(EditorState& state, const PanelLayout& layout) {
  const ImGuiViewport* vp = ImGui::GetMainViewport();
  const float height = paletteHeightFor(layout);
  ImGui::SetNextWindowPos(ImVec2(vp->Pos.x, vp->Pos.y + vp->Size.y - layout.statusHeight - height));
  ImGui::SetNextWindowSize(ImVec2(layout.leftWidth, height));
  ImGui::Begin("Add", nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                   ImGuiWindowFlags_NoBringToFrontOnFocus);
  // The mode new parts are placed with, and what a click would do now.
  const PlaceMode modes[] = {PlaceMode::Add, PlaceMode::Cut, PlaceMode::Intersect};
  const char* modeTips[] = {"New parts add material", "New parts cut (subtract)",
                            "New parts intersect: only what they share remains"};
  for (int i = 0; i < 3; ++i) {
    if (i) ImGui::SameLine();
    if (ImGui::RadioButton(placeModeName(modes[i]), state.placeMode == modes[i]))
      state.placeMode = modes[i];
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", modeTips[i]);
  }
  const std::string sentence = placementSentence(state, primarySelection(state), state.placeMode);
  // Two lines, always: the buttons below must not move when the sentence grows (a click aimed
  // at one would land on another).
  const float top = ImGui::GetCursorPosY();
  ImGui::PushTextWrapPos(0.0f);
  ImGui::TextDisabled("a new part %s", sentence.c_str());
  ImGui::PopTextWrapPos();
  const float twoLines = 2.0f * ImGui::GetTextLineHeightWithSpacing();
  if (ImGui::GetCursorPosY() < top + twoLines) ImGui::SetCursorPosY(top + twoLines);
  const float w = (ImGui::GetContentRegionAvail().x - 2 * ImGui::GetStyle().ItemSpacing.x) / 3.0f;
  const int count = int(primitiveTable().size());
  const int lastRowStart = (count - 1) / 3 * 3;  // a short last row shares the whole width
  const float lastWidth = (ImGui::GetContentRegionAvail().x -
                           float(count - lastRowStart - 1) * ImGui::GetStyle().ItemSpacing.x) /
                          float(count - lastRowStart);
  int column = 0;
  for (const PrimitiveInfo& primitive : primitiveTable()) {
    const bool lastRow = column >= lastRowStart;
    if (column++ % 3) ImGui::SameLine();
    char label[64];
    std::snprintf(label, sizeof(label), "%s %s", kindGlyph(primitive.kind), primitive.label);
    bool shortened = false;
    if (fittedButton(label, primitive.label, lastRow ? lastWidth : w, &shortened))
      addPrimitive(state, primitive.kind);
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("%s%s%s", shortened ? primitive.label : "", shortened ? "\n\n" : "",
                        primitive.summary);
    paletteDragSource(state, int(primitive.kind), label);
  }
  const std::string importLabel = std::string(kindGlyph(NodeKind::Mesh)) + " Import mesh...";
  bool importShortened = false;
  if (fittedButton(importLabel, "import", ImGui::GetContentRegionAvail().x, &importShortened)) {
    state.importPlacement.reset();
    state.dialog.open(DialogPurpose::ImportMesh, importFolder(state));
  }
  if (ImGui::IsItemHovered()) {
    std::string formats;  // from the one table of formats
    for (const MeshFormat& format : meshFormats())
      if (format.supports(MeshAccess::Read))
        formats += (formats.empty() ? "" : ", ") + std::string(format.label);
    ImGui::SetTooltip("%sA closed mesh file (%s); asks its unit and up axis",
                      importShortened ? "Import mesh\n\n" : "", formats.c_str());
  }
  paletteDragSource(state, kImportMeshItem, importLabel.c_str());
  ImGui::Separator();
  // One set of operation buttons: with a selection they apply to it (the selection is put in the
  // new operation in its place, each part keeping what it does), as an artist expects of
  // "round" with a part selected; Shift, or nothing selected, adds an empty one as the palette
  // adds parts.
  const bool wraps = !state.selection.empty() && !ImGui::GetIO().KeyShift;
  ImGui::TextDisabled(wraps                     ? "operation on the selection (Shift: empty)"
                      : state.selection.empty() ? "empty operation"
                                                : "empty operation (Shift held)");
  const std::vector<NodeKind> ops = operationKinds();
  // Three to a row: the Booleans, then the modifiers, then the patterns.
  const std::vector<bool> rowStarts = operationRowStarts(ops, 3);
  for (size_t i = 0; i < ops.size(); ++i) {
    if (!rowStarts[i]) ImGui::SameLine();
    char id[32];
    std::snprintf(id, sizeof(id), "op%zu", i);
    bool shortened = false;
    if (fittedButton(kindLabel(ops[i]), id, w, &shortened)) {
      if (wraps)
        groupSelection(state, ops[i]);
      else
        addOperation(state, ops[i]);
    }
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip(
          wraps ? "%s%s%s\n\nPuts the selected parts in a new %s in the first one's place, each "
                  "keeping what it does (add or cut).\nShift+click: an empty %s instead."
                : "%s%s%s\n\nAdds an empty %s (then drop parts into it).%s",
          shortened ? kindLabel(ops[i]) : "", shortened ? "\n\n" : "", nodeKindInfo(ops[i]).summary,
          kindLabel(ops[i]),
          wraps                     ? kindLabel(ops[i])
          : state.selection.empty() ? "\nSelect parts first to apply it to them."
                                    : "");
  }
  ImGui::End();
}

}  // namespace strata::ui
