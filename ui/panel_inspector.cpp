// The inspector: the selected node's name, visibility, colour, transform and parameters. A
// widget that is held (a drag, a colour picker) makes one undo step from activation to
// deactivation.
#include <imgui.h>

#include <algorithm>
#include <cstdio>

#include "engine/document/commands.h"
#include "engine/kinds/primitives.h"
#include "ui/editor_actions.h"
#include "ui/panels.h"
#include "ui/scene_queries.h"
#include "ui/theme.h"

namespace strata::ui {
namespace {

// Brackets an edit made by the last ImGui item in begin/end interaction and applies it.
void edited(EditorState& state, bool changed, const std::function<void()>& apply) {
  if (ImGui::IsItemActivated()) state.document.beginInteraction();
  if (changed) guarded(state, apply);
  if (ImGui::IsItemDeactivated()) state.document.endInteraction();
}

// Three drag fields (x, y, z) on one row; each is its own item, so activation is exact.
bool dragVec3(EditorState& state, const char* label, glm::dvec3* value, double speed,
              const std::function<void(const glm::dvec3&)>& apply, const char* format) {
  const ImVec4 colors[3] = {
      {0.93f, 0.35f, 0.35f, 1.0f}, {0.5f, 0.82f, 0.35f, 1.0f}, {0.38f, 0.6f, 1.0f, 1.0f}};
  ImGui::PushID(label);
  ImGui::TextUnformatted(label);
  const float labelWidth = 72.0f;
  ImGui::SameLine(labelWidth);
  const float w = (ImGui::GetContentRegionAvail().x - 2 * ImGui::GetStyle().ItemInnerSpacing.x) / 3;
  bool any = false;
  for (int i = 0; i < 3; ++i) {
    if (i) ImGui::SameLine(0, ImGui::GetStyle().ItemInnerSpacing.x);
    ImGui::PushID(i);
    ImGui::SetNextItemWidth(w);
    ImGui::PushStyleColor(ImGuiCol_Text, colors[i]);
    glm::dvec3 next = *value;
    bool changed = ImGui::DragScalar("##c", ImGuiDataType_Double, &next[i], float(speed), nullptr,
                                     nullptr, format);
    ImGui::PopStyleColor();
    edited(state, changed, [&] { apply(next); });
    if (changed) *value = next;
    any = any || changed;
    ImGui::PopID();
  }
  ImGui::PopID();
  return any;
}

// A positive length parameter.
void lengthField(EditorState& state, const NodePtr& node, const char* label,
                 double PrimitiveParams::*field, double speed, double minimum) {
  PrimitiveParams p = node->params;
  ImGui::TextUnformatted(label);
  ImGui::SameLine(110.0f);
  ImGui::SetNextItemWidth(-1);
  double value = p.*field;
  bool changed = ImGui::DragScalar((std::string("##") + label).c_str(), ImGuiDataType_Double,
                                   &value, float(speed), &minimum, nullptr, "%.4g");
  edited(state, changed, [&] {
    p.*field = std::max(value, minimum);
    state.document.setParams(node->id, p);
  });
}

// The primitive's parameters, as its table entry lists them.
void primitiveParams(EditorState& state, const NodePtr& node, double speed) {
  const PrimitiveInfo* info = primitiveInfo(node->kind);
  if (!info) return;
  const PrimitiveParams p = node->params;
  for (const PrimitiveParam& param : info->params) {
    const double minimum = param.minimum == ParamMinimum::Positive ? 1e-6 : 0.0;
    if (param.scalar) lengthField(state, node, param.label, param.scalar, speed, minimum);
    if (param.vector) {
      glm::dvec3 value = p.*param.vector;
      dragVec3(
          state, param.label, &value, speed,
          [&](const glm::dvec3& v) {
            PrimitiveParams q = p;
            q.*param.vector = glm::max(v, glm::dvec3(minimum));
            state.document.setParams(node->id, q);
          },
          "%.4g");
    }
  }
  if (info->usesSegments) {
    ImGui::TextUnformatted("segments");
    ImGui::SameLine(110.0f);
    ImGui::SetNextItemWidth(-1);
    int segments = p.segments;
    bool changed = ImGui::DragInt("##segments", &segments, 0.5f, 0, kMaxSegments,
                                  segments == 0 ? "automatic" : "%d");
    edited(state, changed, [&] {
      PrimitiveParams q = p;
      q.segments = segments > 0 && segments < 3 ? 3 : segments;
      state.document.setParams(node->id, q);
    });
  }
}

// The kind, id, name, visibility and colour of `node`.
void nodeIdentity(EditorState& state, const NodePtr& node) {
  ImGui::Text("%s  %s", kindGlyph(node->kind), kindLabel(node->kind));
  ImGui::SameLine();
  ImGui::TextDisabled("id %u%s", node->id,
                      state.selection.size() > 1
                          ? ("   (" + std::to_string(state.selection.size()) + " selected)").c_str()
                          : "");

  // Name: committed when the field is left or Enter is pressed.
  static char name[256];
  static NodeId nameOf = 0;
  if (nameOf != node->id || !ImGui::IsAnyItemActive())
    std::snprintf(name, sizeof(name), "%s", node->name.c_str()), nameOf = node->id;
  ImGui::SetNextItemWidth(-1);
  ImGui::InputTextWithHint("##name", "name", name, sizeof(name));
  if (ImGui::IsItemDeactivatedAfterEdit() && node->name != name) renameNode(state, node->id, name);

  bool visible = node->visible;
  if (ImGui::Checkbox("visible", &visible))
    guarded(state, [&] { state.document.setVisible(node->id, visible); });
  ImGui::SameLine();
  glm::vec3 color = node->color;
  bool colorChanged = ImGui::ColorEdit3("colour", &color.x, ImGuiColorEditFlags_NoInputs);
  edited(state, colorChanged, [&] {
    state.document.setColor(node->id, glm::clamp(color, glm::vec3(0.0f), glm::vec3(1.0f)));
  });
}

// Move, rotate and scale of `node`; `speed` is the drag step in scene units.
void nodeTransform(EditorState& state, const NodePtr& node, double speed) {
  if (ImGui::CollapsingHeader("Transform", ImGuiTreeNodeFlags_DefaultOpen)) {
    Transform t = node->transform;
    auto applyTransform = [&](const Transform& next) {
      state.document.setTransform(node->id, next);
    };
    dragVec3(
        state, "move", &t.translate, speed,
        [&](const glm::dvec3& v) {
          Transform n = node->transform;
          n.translate = v;
          applyTransform(n);
        },
        "%.4g");
    dragVec3(
        state, "rotate", &t.rotateDegrees, 0.5,
        [&](const glm::dvec3& v) {
          Transform n = node->transform;
          n.rotateDegrees = v;
          applyTransform(n);
        },
        "%.2f\u00B0");
    dragVec3(
        state, "scale", &t.scale, 0.005,
        [&](const glm::dvec3& v) {
          Transform n = node->transform;
          n.scale = v;
          for (int i = 0; i < 3; ++i)
            if (n.scale[i] == 0.0) n.scale[i] = node->transform.scale[i];
          applyTransform(n);
        },
        "%.4g");
    if (ImGui::SmallButton("reset")) guarded(state, [&] { applyTransform(Transform()); });
  }
}

// What the node's kind adds: primitive parameters, the operation, the mesh file, the target.
void nodeKindSections(EditorState& state, const NodePtr& node, double speed) {
  if (isPrimitive(node->kind) && ImGui::CollapsingHeader("Shape", ImGuiTreeNodeFlags_DefaultOpen))
    primitiveParams(state, node, speed);

  if (isOperation(node->kind) &&
      ImGui::CollapsingHeader("Operation", ImGuiTreeNodeFlags_DefaultOpen)) {
    bool first = true;
    for (NodeKind op : operationKinds()) {
      if (!first) ImGui::SameLine();
      first = false;
      if (ImGui::RadioButton(kindName(op), node->kind == op))
        guarded(state, [&] { state.document.setOperation(node->id, op); });
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", nodeKindInfo(op).summary);
    }
    ImGui::TextDisabled("%zu children%s", node->children.size(),
                        node->kind == NodeKind::Difference ? "; the first minus the others" : "");
  }

  if (node->kind == NodeKind::Mesh &&
      ImGui::CollapsingHeader("Mesh", ImGuiTreeNodeFlags_DefaultOpen)) {
    ImGui::TextWrapped("file: %s", node->meshPath.c_str());
    ImGui::TextDisabled("%s", node->meshHash.c_str());
    if (node->mesh)
      ImGui::Text("%zu triangles, %zu vertices", node->mesh->triangles.size(),
                  node->mesh->positions.size());
  }
  if (node->kind == NodeKind::Instance) {
    NodePtr target = findNode(state.document.root(), node->instanceOf);
    ImGui::Text("instance of %s (id %u)", target ? target->name.c_str() : "?", node->instanceOf);
  }
}

}  // namespace

void drawInspector(EditorState& state, const PanelLayout& layout) {
  const ImGuiViewport* vp = ImGui::GetMainViewport();
  ImGui::SetNextWindowPos(
      ImVec2(vp->Pos.x + vp->Size.x - layout.rightWidth, vp->Pos.y + layout.menuHeight));
  ImGui::SetNextWindowSize(
      ImVec2(layout.rightWidth,
             vp->Size.y - layout.menuHeight - layout.statusHeight - layout.previewHeight));
  ImGui::Begin("Inspector", nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse);
  const NodeId id = primarySelection(state);
  const NodePtr node = id ? findNode(state.document.root(), id) : nullptr;
  if (!node) {
    ImGui::TextDisabled("Nothing selected.");
    ImGui::TextDisabled("Click a part in the viewport or a row");
    ImGui::TextDisabled("in the scene tree.");
    ImGui::End();
    return;
  }
  ImGui::PushID(static_cast<int>(node->id));
  nodeIdentity(state, node);
  // Drag speeds follow the scene's size.
  Bounds b = sceneBounds(state.document.root());
  double extent = b.empty() ? 1.0 : std::max({b.size().x, b.size().y, b.size().z});
  double speed = std::max(extent * 0.002, 1e-6);

  nodeTransform(state, node, speed);
  nodeKindSections(state, node, speed);
  ImGui::PopID();
  ImGui::End();
}

}  // namespace strata::ui
