// The scene tree (outliner) and the palette.
#include <imgui.h>

#include <algorithm>
#include <cstdint>
#include <cstring>

#include "engine/document/commands.h"
#include "engine/kinds/primitives.h"
#include "ui/editor_actions.h"
#include "ui/panels.h"
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
};

// Accepts a palette item over the last item (a row, or the empty space: target 0).
void acceptPaletteItem(NodeId target, PendingDrop* drop) {
  if (const ImGuiPayload* p = ImGui::AcceptDragDropPayload(kPalettePayload)) {
    std::memcpy(&drop->paletteItem, p->Data, sizeof(int));
    drop->target = target;
    drop->paletteDrop = true;
  }
}

// The palette's height: its default, plus a row of buttons for every three primitives beyond six.
float paletteHeightFor(const PanelLayout& layout) {
  const int rows = int((primitiveTable().size() + 2) / 3);
  return layout.paletteHeight + float(std::max(0, rows - 2)) * ImGui::GetFrameHeightWithSpacing();
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
      const std::string label = std::string(kindGlyph(k)) + " " + kindName(k);
      if (ImGui::MenuItem(label.c_str())) groupSelection(state, k);
    }
    ImGui::EndMenu();
  }
  if (isOperation(node->kind) && ImGui::BeginMenu("Operation")) {
    for (NodeKind k : operationKinds())
      if (ImGui::MenuItem(kindName(k), nullptr, node->kind == k)) setSelectionOperation(state, k);
    ImGui::EndMenu();
  }
  ImGui::Separator();
  if (ImGui::MenuItem("Frame", "F")) state.requestFrameSelected = true;
  ImGui::EndPopup();
}

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

void nodeRow(EditorState& state, const NodePtr& node, bool isRoot, PendingDrop* drop) {
  ImGui::PushID(static_cast<int>(node->id));
  const bool leaf = node->children.empty();
  ImGuiTreeNodeFlags flags = ImGuiTreeNodeFlags_OpenOnArrow | ImGuiTreeNodeFlags_SpanAvailWidth |
                             ImGuiTreeNodeFlags_DefaultOpen | ImGuiTreeNodeFlags_FramePadding;
  if (leaf) flags |= ImGuiTreeNodeFlags_Leaf | ImGuiTreeNodeFlags_NoTreePushOnOpen;
  if (isSelected(state, node->id)) flags |= ImGuiTreeNodeFlags_Selected;

  // Visibility toggle at the right edge.
  const float right = ImGui::GetContentRegionMax().x;
  const ImVec2 rowStart = ImGui::GetCursorPos();

  bool open;
  if (state.renaming == node->id) {
    open = ImGui::TreeNodeEx("##node", flags | ImGuiTreeNodeFlags_AllowItemOverlap, "%s",
                             kindGlyph(node->kind));
    ImGui::SameLine();
    renameField(state, node);
  } else {
    if (!node->visible) ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(0.5f, 0.5f, 0.52f, 1.0f));
    open = ImGui::TreeNodeEx("##node", flags | ImGuiTreeNodeFlags_AllowItemOverlap, "%s  %s",
                             kindGlyph(node->kind),
                             node->name.empty() ? "(unnamed)" : node->name.c_str());
    if (!node->visible) ImGui::PopStyleColor();
    if (ImGui::IsItemClicked(0) && !ImGui::IsItemToggledOpen())
      selectNode(state, node->id, ImGui::GetIO().KeyCtrl || ImGui::GetIO().KeyShift);
    if (ImGui::IsItemHovered() && ImGui::IsMouseDoubleClicked(0)) state.renaming = node->id;
    if (!isRoot && ImGui::BeginDragDropSource()) {
      NodeId id = node->id;
      ImGui::SetDragDropPayload(kPayload, &id, sizeof(id));
      ImGui::Text("%s %s", kindGlyph(node->kind), node->name.c_str());
      ImGui::EndDragDropSource();
    }
    if (ImGui::BeginDragDropTarget()) {
      if (const ImGuiPayload* p = ImGui::AcceptDragDropPayload(kPayload)) {
        std::memcpy(&drop->dragged, p->Data, sizeof(NodeId));
        drop->target = node->id;
        drop->valid = true;
      }
      acceptPaletteItem(node->id, drop);
      ImGui::EndDragDropTarget();
    }
    contextMenu(state, node);
  }
  if (isOperation(node->kind)) {
    ImGui::SameLine();
    ImGui::TextColored(kindColor(node->kind), "%s", kindLabel(node->kind));
  }
  ImGui::SameLine(right - ImGui::GetFrameHeight());
  ImGui::SetCursorPosY(rowStart.y);
  ImGui::PushStyleColor(ImGuiCol_Button, ImVec4(0, 0, 0, 0));
  if (ImGui::Button(visibleGlyph(node->visible), ImVec2(ImGui::GetFrameHeight(), 0))) {
    guarded(state, [&] { state.document.setVisible(node->id, !node->visible); });
  }
  ImGui::PopStyleColor();
  if (ImGui::IsItemHovered()) ImGui::SetTooltip(node->visible ? "Hide" : "Show");

  if (open && !leaf) {
    for (const auto& child : node->children) nodeRow(state, child, false, drop);
    ImGui::TreePop();
  }
  ImGui::PopID();
}

// The last palette button as a drag source of `item`.
void paletteDragSource(int item, const char* label) {
  if (ImGui::BeginDragDropSource()) {
    ImGui::SetDragDropPayload(kPalettePayload, &item, sizeof(item));
    ImGui::Text("%s", label);
    ImGui::TextDisabled("drop on a surface, the ground, or a tree row");
    ImGui::EndDragDropSource();
  }
}

}  // namespace

void drawOutliner(EditorState& state, const PanelLayout& layout) {
  const ImGuiViewport* vp = ImGui::GetMainViewport();
  const float paletteHeight = paletteHeightFor(layout);
  ImGui::SetNextWindowPos(ImVec2(vp->Pos.x, vp->Pos.y + layout.menuHeight));
  ImGui::SetNextWindowSize(ImVec2(
      layout.leftWidth, vp->Size.y - layout.menuHeight - layout.statusHeight - paletteHeight));
  ImGui::Begin("Scene", nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse);
  PendingDrop drop;
  const NodePtr root = state.document.root();  // this frame's snapshot
  if (root) nodeRow(state, root, true, &drop);
  // Empty space below the tree: a drop here moves the node to the top level.
  ImVec2 avail = ImGui::GetContentRegionAvail();
  ImGui::InvisibleButton("##empty", ImVec2(std::max(avail.x, 1.0f), std::max(avail.y, 24.0f)));
  if (ImGui::IsItemClicked(0)) clearSelection(state);
  if (ImGui::BeginDragDropTarget()) {
    if (const ImGuiPayload* p = ImGui::AcceptDragDropPayload(kPayload)) {
      std::memcpy(&drop.dragged, p->Data, sizeof(NodeId));
      drop.target = 0;
      drop.valid = true;
    }
    acceptPaletteItem(0, &drop);
    ImGui::EndDragDropTarget();
  }
  ImGui::End();
  if (drop.valid) dropNode(state, drop.dragged, drop.target);
  if (drop.paletteDrop) {
    if (drop.target == 0) clearSelection(state);
    dropPaletteItem(state, drop.paletteItem, drop.target);
  }
}

void drawPalette(EditorState& state, const PanelLayout& layout) {
  const ImGuiViewport* vp = ImGui::GetMainViewport();
  const float height = paletteHeightFor(layout);
  ImGui::SetNextWindowPos(ImVec2(vp->Pos.x, vp->Pos.y + vp->Size.y - layout.statusHeight - height));
  ImGui::SetNextWindowSize(ImVec2(layout.leftWidth, height));
  ImGui::Begin("Add", nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse);
  NodeId target = primarySelection(state);
  NodePtr targetNode = target ? findNode(state.document.root(), target) : nullptr;
  ImGui::TextDisabled("click: add %s %s (or drag)",
                      targetNode && !isOperation(targetNode->kind) ? "beside" : "to",
                      targetNode ? targetNode->name.c_str() : "the root");
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
    if (ImGui::Button(label, ImVec2(lastRow ? lastWidth : w, 0)))
      addPrimitive(state, primitive.kind);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", primitive.summary);
    paletteDragSource(int(primitive.kind), label);
  }
  const std::string importLabel = std::string(kindGlyph(NodeKind::Mesh)) + " Import mesh...";
  if (ImGui::Button(importLabel.c_str(), ImVec2(-1, 0))) {
    state.importPlacement.reset();
    state.dialog.open(DialogPurpose::ImportMesh, "");
  }
  paletteDragSource(kImportMeshItem, importLabel.c_str());
  ImGui::Separator();
  ImGui::TextDisabled("empty operation");
  const std::vector<NodeKind> ops = operationKinds();
  for (size_t i = 0; i < ops.size(); ++i) {
    if (i) ImGui::SameLine();
    char label[64];
    std::snprintf(label, sizeof(label), "%s##add%zu", kindName(ops[i]), i);
    if (ImGui::Button(label, ImVec2(w, 0))) addOperation(state, ops[i]);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", nodeKindInfo(ops[i]).summary);
  }
  ImGui::TextDisabled("group selection as");
  ImGui::BeginDisabled(state.selection.empty());
  for (size_t i = 0; i < ops.size(); ++i) {
    if (i) ImGui::SameLine();
    char label[64];
    std::snprintf(label, sizeof(label), "%s %s##group%zu", kindGlyph(ops[i]), kindName(ops[i]), i);
    if (ImGui::Button(label, ImVec2(w, 0))) groupSelection(state, ops[i]);
  }
  ImGui::EndDisabled();
  ImGui::End();
}

}  // namespace strata::ui
