// The inspector: the selected node's name, visibility, colour, transform and parameters. With
// several nodes selected, the fields they share edit all of them (a value that differs is shown
// with "~"): transforms change each by the same amount, the rest set the same value. A widget
// that is held (a drag, a colour picker) makes one undo step from activation to deactivation, for
// every node it changes; a number typed into a field is applied when the field is left
// (typed_value.h), not per keystroke.
#include <imgui.h>
#include <imgui_internal.h>  // ImGuiItemFlags_MixedValue: a mixed checkbox

#include <glm/vector_relational.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "engine/document/commands.h"
#include "engine/document/measurement.h"
#include "engine/document/roles.h"
#include "engine/io/document_files.h"
#include "engine/kinds/primitives.h"
#include "engine/util/error.h"
#include "ui/editor_actions.h"
#include "ui/import_options.h"
#include "ui/panels.h"
#include "ui/resize_followers.h"
#include "ui/resize_gesture.h"
#include "ui/scene_queries.h"
#include "ui/text_fit.h"
#include "ui/theme.h"
#include "ui/typed_value.h"

namespace strata::ui {
namespace {

// The topic of a primitive's parameters' errors: they are often relations between two of them
// (a rounded box's radius against its size), so that a later good value of either settles one.
constexpr const char* kParamsTopic = "parameters";

// The width of `text` in the current font (pixels), for fittedNumberFormat.
float textWidth(const std::string& text) {
  return ImGui::CalcTextSize(text.c_str()).x;
}

// The format of length fields: the number and the scene's unit ("%.4g mm"), set per frame.
std::string gLengthFormat = "%.4g";
std::string gLengthUnit;  // the scene's unit, for lengths typed with a unit (commitTypedValue)

// Brackets an edit made by the last ImGui item in begin/end interaction and applies it.
void edited(EditorState& state, bool changed, const std::function<void()>& apply,
            const std::string& topic = "") {
  if (ImGui::IsItemActivated()) state.document.beginInteraction();
  // A unit typed with the number is said before what applying it says (a refusal of "0 cm" was
  // followed, and hidden, by "typed 0 cm is 0 mm").
  if (changed)
    if (const std::string converted = takeUnitConversion(); !converted.empty())
      logInfo(state, "typed " + converted);
  if (changed) guarded(state, apply, topic);
  if (ImGui::IsItemDeactivated()) state.document.endInteraction();
}

// Three drag fields (x, y, z) on one row; each is its own item, so activation is exact.
// A component marked in `mixed` differs across the selection: it shows the primary node's value
// with a "~" in front.
// `apply` gets the new value, the component changed, and whether a number was typed into a
// field the selection differs on: every selected part then takes that number (a drag, or a
// number typed where all agree, moves each by as much; typing 5 into "~-9.65" shifted the parts
// by 14.65 each: an artist's test).
struct VecEdit {
  int component = 0;
  bool setsAll = false;
};
bool dragVec3(EditorState& state, const char* label, glm::dvec3* value, double speed,
              const std::function<void(const glm::dvec3&, VecEdit)>& apply, const char* format,
              const glm::bvec3& mixed = glm::bvec3(false), const char* topic = nullptr,
              const char* mixedDrag = "moves every one by as much",
              const double* dragMinimum = nullptr) {
  const ImVec4 colors[3] = {
      {0.93f, 0.35f, 0.35f, 1.0f}, {0.5f, 0.82f, 0.35f, 1.0f}, {0.38f, 0.6f, 1.0f, 1.0f}};
  ImGui::PushID(label);
  float labelWidth = 80.0f;  // "move mm" and the fields of every row aligned
  const float spacing = ImGui::GetStyle().ItemInnerSpacing.x;
  float w = (ImGui::GetContentRegionAvail().x - labelWidth - 2 * spacing) / 3;
  // The number with its unit in each field where the widest number the format writes fits with
  // it ("0.003149 mm" cut to "0.003149 m" read as metres); else the unit once, after the row's
  // label, and the numbers shorter where even they do not fit. Decided by the fields' width, not
  // by the values, so that the row keeps its look while a value is dragged.
  const std::string withUnit = format;
  const size_t space = withUnit.find(' ');
  std::string number = withUnit.substr(0, space);
  const std::string unit = space == std::string::npos ? "" : withUnit.substr(space + 1);
  const bool anyMixed = mixed.x || mixed.y || mixed.z;
  auto fits = [&](const char* f) {
    const float room = w - 2 * ImGui::GetStyle().FramePadding.x;
    for (const double widest : {-0.000123456789, -123456789.0, -1234.56789}) {
      char text[64];
      text[0] = '~';
      ImFormatString(text + 1, sizeof(text) - 1, f, widest);
      if (ImGui::CalcTextSize(anyMixed ? text : text + 1).x > room) return false;
    }
    return true;
  };
  std::string fieldFormat = withUnit;
  if (!unit.empty() && !fits(withUnit.c_str())) {
    // The label column widens for "rotate deg" rather than run into the first field.
    const std::string labelWithUnit = std::string(label) + " " + unit;
    const float wanted =
        ImGui::CalcTextSize(labelWithUnit.c_str()).x + 2 * ImGui::GetStyle().ItemSpacing.x;
    if (wanted > labelWidth) {
      w -= (wanted - labelWidth) / 3;
      labelWidth = wanted;
    }
    fieldFormat = fits(number.c_str()) ? number : "%.3g";
    ImGui::TextUnformatted(labelWithUnit.c_str());
  } else {
    ImGui::TextUnformatted(label);
  }
  ImGui::SameLine(labelWidth);
  bool any = false;
  for (int i = 0; i < 3; ++i) {
    if (i) ImGui::SameLine(0, ImGui::GetStyle().ItemInnerSpacing.x);
    ImGui::PushID(i);
    ImGui::SetNextItemWidth(w);
    ImGui::PushStyleColor(ImGuiCol_Text, colors[i]);
    glm::dvec3 next = *value;
    // As many digits as the field has room for (fittedNumberFormat).
    const float room =
        w - 2 * ImGui::GetStyle().FramePadding.x - (mixed[i] ? ImGui::CalcTextSize("~").x : 0.0f);
    const std::string marked = fittedNumberFormat(fieldFormat, next[i], room, textWidth);
    const std::string shown = mixed[i] ? std::string("~") + marked : marked;
    // A drag stops at `dragMinimum` (a size dragged to nothing), where a number typed under it
    // is refused by `apply`, saying so: a drag past it warned every frame (an artist's test).
    bool changed = ImGui::DragScalar("##c", ImGuiDataType_Double, &next[i], float(speed),
                                     dragMinimum, nullptr, shown.c_str());
    changed = dragFromItsStart(changed, (*value)[i], &next[i], speed, dragMinimum);
    changed = commitTypedValue(changed, &next[i], sceneUnitMetres(unit) > 0.0 ? unit : "");
    const VecEdit edit{i, changed && mixed[i] && lastCommitWasTyped()};
    ImGui::PopStyleColor();  // the tooltips below in the usual colour
    if (mixed[i] && ImGui::IsItemHovered())
      ImGui::SetTooltip(
          "differs across the selection: dragging %s, a number typed sets every "
          "one to it",
          mixedDrag);
    else if (ImGui::IsItemHovered() && !ImGui::IsItemActive()) {
      // A field too narrow for the number shows it rounded (-26.5 for the gizmo's -26.480444:
      // an artist's test): the whole number on hover.
      char text[64];
      ImFormatString(text, sizeof(text), marked.c_str(), next[i]);
      if (std::strtod(text, nullptr) != next[i]) {
        ImFormatString(text, sizeof(text), "%.10g", next[i]);
        ImGui::SetTooltip("%s%s%s (double-click to type)", text, unit.empty() ? "" : " ",
                          unit.c_str());
      }
    }
    edited(
        state, changed, [&] { apply(next, edit); }, topic ? topic : label);
    if (changed) *value = next;
    any = any || changed;
    ImGui::PopID();
  }
  ImGui::PopID();
  return any;
}

// A value under a parameter's minimum (a size of -5 typed) is refused, not clamped to a part too
// small to see: the field goes back to the value it had, and the log says why.
void refuseBelowMinimum(EditorState& state, const char* label, double minimum) {
  logWarning(state, std::string(label) +
                        (minimum > 0.0 ? " must be greater than 0" : " must be 0 or more") +
                        ": the value is kept");
}

// Part `id` changed in size (its parameters or its scale) from the tree `before`: where it rested
// on the ground or on another part it is moved back onto it, the parts resting on it and the
// cutters through or into it follow (followResize; `sameEdit`: the other parts the edit changed,
// left to it), all worked out from where the gesture began (a drag of the field, or a value
// typed: the document's open interaction), and the log says so once per gesture.
void reseatResting(EditorState& state, const NodePtr& before, NodeId id,
                   const std::vector<NodeId>& sameEdit = {}) {
  // One gesture while the document's interaction is open; an edit outside one is its own.
  static ResizeGesture gesture;
  if (const NodePtr start = state.document.interactionStart())
    gesture.begin(start, state.document.interactionsBegun());
  else
    gesture = ResizeGesture(before);
  // The rest of the selection changes by the same edit (a size typed for two plates): not
  // followers of one another.
  std::vector<NodeId> changedToo = sameEdit;
  changedToo.insert(changedToo.end(), state.selection.begin(), state.selection.end());
  ResizeStep step = followResize(state.document, gesture, id, changedToo);
  const ResizeFollowing& following = step.following;
  Rest& rest = step.rest;
  if (!rest.moved && following.followers.empty() && following.leftAlone.empty() &&
      following.buried.empty())
    return;
  // Once a gesture, not every frame of it; again where a part joins those that follow (a hole
  // the plate grew past in a later frame of the drag).
  const bool sameDrag = gesture.said.count(id) > 0;
  std::vector<NodeId>& saidFollowers = gesture.said[id];
  bool joined = false;
  for (const ResizeFollower& f : following.followers)
    if (std::find(saidFollowers.begin(), saidFollowers.end(), f.id) == saidFollowers.end()) {
      saidFollowers.push_back(f.id);
      joined = true;
    }
  if (sameDrag && !joined) return;
  const NodePtr root = state.document.root();
  const auto named = [&](NodeId of) {
    const NodePtr n = findNode(root, of);
    return n ? quotedName(*n) : std::string("a part");
  };
  if (sameDrag) rest.moved = false;  // said at the gesture's first frame
  if (rest.moved && (rest.onGround || !rest.on))
    logInfo(state,
            named(id) + " rested on the ground and stays on it (its position along z moved)");
  else if (rest.moved)
    logInfo(state, named(id) + " rested on " + named(rest.on) +
                       " and stays on it (it grows from its base; its position moved)");
  for (const FollowMessage& m : resizeFollowingMessages(root, id, following))
    (m.warning ? logWarning : logInfo)(state, m.text);
}

// The parameters part `n` gets from `set` changing its parameter `param`: its other parameters as
// the gesture began (a drag of the field, or a value typed), where a relation the change broke is
// fitted (fitPrimitiveRelations: a thinner rounded box gets a smaller corner radius, and gets its
// radius back as it thickens again in the same drag), said once a gesture and part.
// What changedParams fitted, said by setParamsKeptResting once the change is set, after what
// followed it: said first, the status bar showed the followers' line and the fit went unseen (an
// artist's test).
std::string gFitToSay;

PrimitiveParams changedParams(EditorState& state, const Node& n, const PrimitiveParam& param,
                              const std::function<void(PrimitiveParams&)>& set) {
  gFitToSay.clear();
  const NodePtr start = state.document.interactionStart();
  const NodePtr was = start ? findNode(start, n.id) : nullptr;
  PrimitiveParams q = was && was->kind == n.kind ? was->params : n.params;
  set(q);
  const std::vector<FittedParam> fitted = fitPrimitiveRelations(n.kind, &q, param.key);
  static std::pair<uint64_t, std::vector<NodeId>> said;  // per gesture: the parts said
  const bool interacting = state.document.interacting();
  const uint64_t gesture = interacting ? state.document.interactionsBegun() : 0;
  if (said.first != gesture || !interacting) said = {gesture, {}};
  // Said where the change will be taken: a change refused for another reason (a size of 0)
  // fits nothing.
  const auto valid = [&] {
    try {
      validatePrimitiveParams(n.kind, q);
      return true;
    } catch (const Error&) {
      return false;
    }
  };
  if (!fitted.empty() &&
      std::find(said.second.begin(), said.second.end(), n.id) == said.second.end() && valid()) {
    said.second.push_back(n.id);
    gFitToSay = fittedParamsMessage(n, fitted, param.label, gLengthUnit, !lastCommitWasTyped());
  }
  return q;
}

// Sets a part's shape parameters, the part kept where it rests (reseatResting).
void setParamsKeptResting(EditorState& state, NodeId id, const PrimitiveParams& params) {
  const NodePtr before = state.document.root();
  state.document.setParams(id, params);
  reseatResting(state, before, id);
  if (!gFitToSay.empty()) logInfo(state, gFitToSay);
  gFitToSay.clear();
}

// A positive length parameter.
void lengthField(EditorState& state, const NodePtr& node, const std::vector<NodePtr>& nodes,
                 const PrimitiveParam& param, double speed, double minimum) {
  const char* label = param.label;
  double PrimitiveParams::*field = param.scalar;
  PrimitiveParams p = node->params;
  bool mixed = false;
  for (const NodePtr& n : nodes) mixed = mixed || n->params.*field != p.*field;
  ImGui::TextUnformatted(label);
  ImGui::SameLine(110.0f);
  ImGui::SetNextItemWidth(-1);
  double value = p.*field;
  bool changed = ImGui::DragScalar(
      (std::string("##") + label).c_str(), ImGuiDataType_Double, &value, float(speed), &minimum,
      nullptr,
      ((mixed ? "~" : "") +
       fittedNumberFormat(gLengthFormat, value,
                          ImGui::CalcItemWidth() - 2 * ImGui::GetStyle().FramePadding.x -
                              (mixed ? ImGui::CalcTextSize("~").x : 0.0f),
                          textWidth))
          .c_str());
  changed = dragFromItsStart(changed, p.*field, &value, speed, &minimum);
  changed = commitTypedValue(changed, &value, gLengthUnit);
  if (mixed && ImGui::IsItemHovered())
    ImGui::SetTooltip("differs across the selection; a change sets every one to the same value");
  edited(
      state, changed,
      [&] {
        if (value < minimum) return refuseBelowMinimum(state, label, minimum);
        for (const NodePtr& n : nodes)
          setParamsKeptResting(
              state, n->id,
              changedParams(state, *n, param, [&](PrimitiveParams& q) { q.*field = value; }));
      },
      kParamsTopic);
}

// The primitive's parameters, as its table entry lists them.
// For every selected node of the primary's kind (the caller checks that all are): a change
// sets the same value on each.
void primitiveParams(EditorState& state, const NodePtr& node, const std::vector<NodePtr>& nodes,
                     double speed) {
  const PrimitiveInfo* info = primitiveInfo(node->kind);
  if (!info) return;
  const PrimitiveParams p = node->params;
  for (const PrimitiveParam& param : info->params) {
    const double minimum = param.minimum == ParamMinimum::Positive ? 1e-6 : 0.0;
    if (param.scalar) lengthField(state, node, nodes, param, speed, minimum);
    if (param.vector) {
      glm::dvec3 value = p.*param.vector;
      dragVec3(
          state, param.label, &value, speed,
          [&](const glm::dvec3& v, VecEdit) {
            if (glm::any(glm::lessThan(v, glm::dvec3(minimum))))
              return refuseBelowMinimum(state, param.label, minimum);
            for (const NodePtr& n : nodes)
              setParamsKeptResting(state, n->id,
                                   changedParams(state, *n, param,
                                                 [&](PrimitiveParams& q) { q.*param.vector = v; }));
          },
          gLengthFormat.c_str(), glm::bvec3(false), kParamsTopic, "moves every one by as much",
          &minimum);
    }
  }
  if (info->usesSegments) {
    ImGui::TextUnformatted("segments");
    ImGui::SameLine(110.0f);
    ImGui::SetNextItemWidth(-1);
    int segments = p.segments;
    bool changed = ImGui::DragInt("##segments", &segments, 0.5f, 0, kMaxSegments,
                                  segments == 0 ? "automatic" : "%d");
    changed = commitTypedValue(changed, &segments);
    edited(state, changed, [&] {
      for (const NodePtr& n : nodes) {
        PrimitiveParams q = n->params;
        q.segments = segments > 0 && segments < 3 ? 3 : segments;
        state.document.setParams(n->id, q);
      }
    });
  }
}

// The selected nodes, the primary (inspected) one last.
using NodeList = std::vector<NodePtr>;

// What the (one) selected part does in its parent, and the other roles on offer: each says what
// the part would do before it is picked (setRole: moved onto its parent with that mode).
void nodeRole(EditorState& state, const Node& node, size_t selected) {
  const Node* parent = parentOf(state, node.id);
  if (!parent || selected != 1) return;
  const ChildRole role = roleOf(state.document.root(), node.id);
  ImGui::TextUnformatted("role");
  ImGui::SameLine(90.0f);
  if (role == ChildRole::Base) {
    ImGui::TextDisabled("base of %s", parent->name.c_str());
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip(
          "What the parts beside it cut. Drag it elsewhere, or another part onto it,\n"
          "to change what it does.");
    return;
  }
  const PlaceMode current = modeKeepingRole(role);
  // A part that adds to a cutter (a bolt hole in the circular array that cuts) takes material
  // away: its role reads so, as its row's word in the tree does ("cut" in the tree beside
  // "adds" here: an artist's test).
  const bool addsToACutter =
      role == ChildRole::Add && removesMaterial(state.document.root(), node.id);
  const std::string shown = addsToACutter ? "adds to a cutter (cuts)" : roleWord(role);
  ImGui::SetNextItemWidth(-1);
  if (!ImGui::BeginCombo("##role", shown.c_str())) {
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip(
          "What it does in %s%s; pick another role here (or drag the row with\n"
          "Ctrl: cut, Shift: intersect, Alt: add)",
          parent->name.empty() ? "its parent" : parent->name.c_str(),
          addsToACutter ? ", which cuts: its material is taken away" : "");
    return;
  }
  for (PlaceMode mode : {PlaceMode::Add, PlaceMode::Cut, PlaceMode::Intersect}) {
    const char* word = mode == PlaceMode::Add   ? "adds"
                       : mode == PlaceMode::Cut ? "cuts"
                                                : "intersects";
    const std::string refusal = roleChangeRefusal(state, node.id, mode);
    const bool chosen = ImGui::Selectable(word, mode == current,
                                          refusal.empty() ? 0 : ImGuiSelectableFlags_Disabled);
    if (mode != current && ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) {
      const std::string says =
          refusal.empty() ? "it " + roleChangeSentence(state, node.id, mode) : refusal;
      ImGui::SetTooltip("%s", says.c_str());
    }
    if (chosen && mode != current) setRole(state, node.id, mode);
  }
  ImGui::EndCombo();
}

// The kind, id, name, visibility, colour and role of `node`; visibility and colour for all
// `nodes`.
void nodeIdentity(EditorState& state, const NodePtr& node, const NodeList& nodes) {
  ImGui::Text("%s  %s", kindGlyph(node->kind), kindLabel(node->kind));
  ImGui::SameLine();
  ImGui::TextDisabled(
      "id %u%s", node->id,
      nodes.size() > 1 ? ("   (" + std::to_string(nodes.size()) + " selected)").c_str() : "");

  // Name: committed when the field is left or Enter is pressed. The primary node's only.
  static char name[256];
  static NodeId nameOf = 0;
  if (nameOf != node->id || !ImGui::IsAnyItemActive())
    std::snprintf(name, sizeof(name), "%s", node->name.c_str()), nameOf = node->id;
  ImGui::SetNextItemWidth(-1);
  ImGui::InputTextWithHint("##name", "name", name, sizeof(name));
  if (nodes.size() > 1 && ImGui::IsItemHovered())
    ImGui::SetTooltip("Renames the active part only (the one last clicked), not the %zu selected",
                      nodes.size());
  if (ImGui::IsItemDeactivatedAfterEdit() && node->name != name) renameNode(state, node->id, name);

  bool visible = node->visible;
  bool mixedVisible = false, mixedColor = false;
  for (const NodePtr& n : nodes) {
    mixedVisible = mixedVisible || n->visible != node->visible;
    mixedColor = mixedColor || n->color != node->color;
  }
  ImGui::PushItemFlag(ImGuiItemFlags_MixedValue, mixedVisible);
  const bool toggled = ImGui::Checkbox("visible", &visible);
  ImGui::PopItemFlag();
  if (toggled) {
    state.document.beginInteraction();
    for (const NodePtr& n : nodes)
      guarded(state, [&] { state.document.setVisible(n->id, visible); });
    state.document.endInteraction();
  }
  ImGui::SameLine();
  glm::vec3 color = node->color;
  bool colorChanged = ImGui::ColorEdit3(mixedColor ? "colour (mixed)" : "colour", &color.x,
                                        ImGuiColorEditFlags_NoInputs);
  edited(state, colorChanged, [&] {
    for (const NodePtr& n : nodes)
      state.document.setColor(n->id, glm::clamp(color, glm::vec3(0.0f), glm::vec3(1.0f)));
  });
  nodeRole(state, *node, nodes.size());
}

// The selection's size as placed: the extent of its result along the scene's axes, scale and
// turn included (an artist scaling a 20 mm box by 1.5 saw 20 mm and 1.5, never the 30 mm it
// prints at); "within" where that box is only a bound of it (a cut part, a fillet: an artist's
// re-test saw a filleted part "span" twice the radius more than it did). Kept between frames
// for the same tree and selection (a mesh's vertices are gone through once).
void placedSize(const EditorState& state) {
  static std::weak_ptr<const Node> lastRoot;
  static std::vector<NodeId> lastSelection;
  static Bounds lastBounds;
  static bool lastTight = false;
  const NodePtr& root = state.document.root();
  if (lastRoot.lock() != root || lastSelection != state.selection) {
    lastBounds = selectionBounds(root, state.selection);
    lastTight = selectionBoundsTight(root, state.selection);
    lastRoot = root;
    lastSelection = state.selection;
  }
  if (lastBounds.empty()) return;
  const glm::dvec3 size = lastBounds.size();
  ImGui::TextDisabled("%s %.4g x %.4g x %.4g %s, as placed", lastTight ? "spans" : "within", size.x,
                      size.y, size.z, gLengthUnit.c_str());
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(lastTight
                          ? "What the selection's result spans along the scene's x, y and z, as "
                            "placed (scale and turn included): the size it exports at"
                          : "A box along the scene's x, y and z that holds the selection's result "
                            "as placed: a cut, an intersection, a shrinking offset, a round, a "
                            "fillet or a turn leaves the part smaller than it (measure with M)");
}

// Where the fields' numbers are measured from, under them, where that is not the world's frame:
// an artist's box moved into a shell at z = 8 read its z change from 26 to 18 without having
// moved, the fields being in the shell's frame.
void parentFrameNote(const EditorState& state, const Node& shown) {
  const NodePtr& root = state.document.root();
  const glm::dmat4 parentWorld = parentWorldMatrix(root, shown.id);
  if (parentWorld == glm::dmat4(1.0)) return;
  const Node* parent = parentOf(state, shown.id);
  const glm::dvec3 origin(parentWorld[3]);
  const auto zero = [](double v) { return std::fabs(v) < 5e-13 ? 0.0 : v; };
  ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
  ImGui::TextWrapped("in the frame of %s (its origin at %.4g, %.4g, %.4g %s)",
                     parent ? nodeLabel(*parent).c_str() : "its parent", zero(origin.x),
                     zero(origin.y), zero(origin.z), gLengthUnit.c_str());
  ImGui::PopStyleColor();
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(
        "Move, rotate and scale are measured in the frame of the group that holds the part\n"
        "(its position, turn and scale): the same place in the world reads differently\n"
        "once the part is inside another group. \"spans\" below is in the scene's axes.");
}

// Which components of `field` differ from the primary node's across `nodes`.
// What a modifier takes away or fills besides its edges, said under its amount: an artist
// expects "round 3 mm" to round edges, not to remove every wall thinner than 6 mm.
void modifierLimit(Modifier modifier, double amount) {
  char twice[48];
  std::snprintf(twice, sizeof(twice), gLengthFormat.c_str(), 2.0 * std::fabs(amount));
  std::string text;
  if (modifier == Modifier::Round)
    text = std::string("Walls, ribs and pins thinner than ") + twice +
           " (twice the radius) vanish: what a ball of that radius cannot reach from inside "
           "is taken away.";
  else if (modifier == Modifier::Fillet)
    text = std::string("Gaps, slots and holes narrower than ") + twice +
           " (twice the radius) are filled.";
  else if (modifier == Modifier::Offset && amount < 0.0)
    text = std::string("Parts thinner than ") + twice + " vanish when shrunk.";
  else if (modifier == Modifier::Offset && amount > 0.0)
    text = std::string("Gaps narrower than ") + twice + " close when grown.";
  if (text.empty()) return;
  ImGui::PushTextWrapPos(0.0f);
  ImGui::TextDisabled("%s", text.c_str());
  ImGui::PopTextWrapPos();
}

glm::bvec3 mixedComponents(const NodeList& nodes, glm::dvec3 Transform::*field) {
  glm::bvec3 mixed(false);
  const glm::dvec3 first = nodes.back()->transform.*field;
  for (const NodePtr& n : nodes)
    for (int i = 0; i < 3; ++i) mixed[i] = mixed[i] || (n->transform.*field)[i] != first[i];
  return mixed;
}

// Move, rotate and scale of the primary node, applied to every selected node by as much: a
// move or turn adds the same amount to each, a scale multiplies each by the same factor.
// `speed` is the drag step in scene units.
void nodeTransform(EditorState& state, const NodePtr& node, const NodeList& nodes, double speed) {
  if (ImGui::CollapsingHeader("Transform", ImGuiTreeNodeFlags_DefaultOpen)) {
    Transform t = node->transform;
    // Each node from its own current transform, changed as the shown node's field changed.
    // A node inside another selected node moves with it, not on its own as well (`node`, the
    // one shown, is the active part or the selected group holding it: never inside another).
    auto applyAll = [&](const std::function<Transform(const Transform&)>& change) {
      for (const NodePtr& n : nodes) {
        bool nested = false;
        for (const NodePtr& other : nodes)
          if (other != n && isInSubtree(state.document.root(), other->id, n->id)) nested = true;
        if (!nested) state.document.setTransform(n->id, change(n->transform));
      }
    };
    dragVec3(
        state, "move", &t.translate, speed,
        [&](const glm::dvec3& v, VecEdit edit) {
          const glm::dvec3 delta = v - node->transform.translate;
          applyAll([&](Transform n) {
            // A value equal to the one shown takes the new one as it is: 6.2 moved by the drag's
            // difference to 6.3 came out 6.300000000000001 (and was saved so).
            if (edit.setsAll || n.translate == node->transform.translate)
              n.translate[edit.component] = v[edit.component];
            else
              n.translate += delta;
            return n;
          });
        },
        gLengthFormat.c_str(), mixedComponents(nodes, &Transform::translate));
    dragVec3(
        state, "rotate", &t.rotateDegrees, 0.5,
        [&](const glm::dvec3& v, VecEdit edit) {
          const glm::dvec3 delta = v - node->transform.rotateDegrees;
          applyAll([&](Transform n) {
            if (edit.setsAll || n.rotateDegrees == node->transform.rotateDegrees)
              n.rotateDegrees[edit.component] = v[edit.component];
            else
              n.rotateDegrees += delta;
            return n;
          });
        },
        "%.2f\u00B0", mixedComponents(nodes, &Transform::rotateDegrees), nullptr,
        "turns every one by as much");
    dragVec3(
        state, "scale", &t.scale, 0.005,
        [&](const glm::dvec3& v, VecEdit edit) {
          for (int i = 0; i < 3; ++i)
            if (v[i] == 0.0 && node->transform.scale[i] != 0.0)
              throw Error(std::string("scale ") + "xyz"[i] +
                          " cannot be 0: a part scaled to nothing has no volume (a negative "
                          "scale mirrors it)");
          glm::dvec3 factor(1.0);
          for (int i = 0; i < 3; ++i)
            if (v[i] != 0.0 && node->transform.scale[i] != 0.0)
              factor[i] = v[i] / node->transform.scale[i];
          if (state.uniformScale)  // the component changed sets the factor of all three
            for (int i = 0; i < 3; ++i)
              if (factor[i] != 1.0) factor = glm::dvec3(factor[i]);
          // Scaled about its own origin (a box's middle), a part resting on the ground or on
          // another part would sink into it or float off it: it is kept on it, as a size typed.
          const NodePtr before = state.document.root();
          applyAll([&](Transform n) {
            const int c = edit.component;
            if (edit.setsAll && state.uniformScale && n.scale[c] != 0.0)
              n.scale *= v[c] / n.scale[c];  // that axis to the number, the others in proportion
            else if (edit.setsAll)
              n.scale[c] = v[c];
            else
              n.scale *= factor;
            return n;
          });
          std::vector<NodeId> scaled;  // those applyAll scaled (not the nested ones)
          for (const NodePtr& n : nodes) {
            const NodePtr was = findNode(before, n->id),
                          now = findNode(state.document.root(), n->id);
            if (was && now && was->transform.scale != now->transform.scale) scaled.push_back(n->id);
          }
          for (const NodePtr& n : nodes) {
            const NodePtr was = findNode(before, n->id),
                          now = findNode(state.document.root(), n->id);
            if (was && now && was->transform.scale != now->transform.scale)
              reseatResting(state, before, n->id, scaled);
          }
        },
        "%.4g", mixedComponents(nodes, &Transform::scale), nullptr, "scales every one by as much");
    if (ImGui::SmallButton(nodes.size() > 1 ? "reset all" : "reset")) {
      state.document.beginInteraction();
      guarded(state, [&] { applyAll([](const Transform&) { return Transform(); }); });
      state.document.endInteraction();
    }
    ImGui::SameLine();
    ImGui::Checkbox("uniform scale", &state.uniformScale);
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("A scale typed or dragged on one axis scales all three by as much");
  }
}

// What the node's kind adds: primitive parameters, the operation, the mesh file, the target.
// The parts strictly inside `node` (tree order, not through instances), each with its depth.
void partsInside(const NodePtr& node, int depth, std::vector<std::pair<NodePtr, int>>* out) {
  for (const NodePtr& c : node->children) {
    out->push_back({c, depth});
    partsInside(c, depth + 1, out);
  }
}

// A shell's opening: none, or a part inside it whose cut the wall does not follow.
void shellOpeningField(EditorState& state, const NodePtr& shell) {
  ImGui::TextUnformatted("opening");
  ImGui::SameLine(110.0f);
  ImGui::SetNextItemWidth(-1);
  const NodePtr current = findNode(shell, shell->opening);
  std::string preview = "none (closed wall)";
  if (shell->opening != 0) preview = current ? current->name : "(a part no longer inside: closed)";
  if (ImGui::BeginCombo("##opening", preview.c_str())) {
    if (ImGui::Selectable("none (closed wall)", shell->opening == 0))
      guarded(state, [&] { state.document.setOpening(shell->id, 0); });
    std::vector<std::pair<NodePtr, int>> parts;
    partsInside(shell, 0, &parts);
    for (const auto& [part, depth] : parts) {
      ImGui::PushID(int(part->id));
      // A part that adds to the shell's parts opens nothing: said in the list.
      const std::string label = std::string(size_t(2 * depth), ' ') + part->name +
                                (removesMaterial(shell, part->id) ? "" : "  (adds: opens nothing)");
      if (ImGui::Selectable(label.c_str(), part->id == shell->opening))
        guarded(state, [&] { state.document.setOpening(shell->id, part->id); });
      ImGui::PopID();
    }
    ImGui::EndCombo();
  }
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(
        "A part inside the shell where the wall opens: the wall follows the shell's children "
        "as they would be without it, so where it cuts them the hollow reaches the outside "
        "(a drain hole, a mouth)");
  if (shell->opening != 0 && current && !shellOpening(shell)) {
    ImGui::TextDisabled("the opening is hidden: the wall is closed");
  } else if (shell->opening != 0 && current && !removesMaterial(shell, current->id)) {
    // An artist chose a part that adds (a cylinder added on top of the sphere) and got a solid
    // plug on a closed wall: the wall opens only where the opening cuts the shell's parts.
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.8f, 0.3f, 1.0f));
    ImGui::TextWrapped(
        "\"%s\" adds to the shell's parts, so the wall stays closed: an opening must cut them "
        "(drag its row onto the part it should open with Ctrl held: it then cuts that part)",
        current->name.c_str());
    ImGui::PopStyleColor();
  }
}

// Sets one field of every selected pattern's copies (all of the primary's kind).
void setPatternField(EditorState& state, const NodeList& nodes,
                     const std::function<void(PatternParams&)>& change) {
  for (const NodePtr& n : nodes) {
    PatternParams p = n->pattern;
    change(p);
    state.document.setPattern(n->id, p);
  }
}

// A whole number of copies from 1 to kMaxPatternCount, "~" when the selection differs.
void countField(EditorState& state, const NodeList& nodes, const char* label, float width,
                int value, bool mixed, const std::function<void(PatternParams&, int)>& set) {
  ImGui::PushID(label);
  ImGui::SetNextItemWidth(width);
  // A drag stays within the range; a number typed outside it is set to the nearest end and said
  // (0 became 1 and 200000 became 10000 without a word).
  const bool changed = commitTypedValue(
      ImGui::DragInt("##n", &value, 0.1f, 1, kMaxPatternCount, mixed ? "~%d" : "%d"), &value);
  if (changed && (value < 1 || value > kMaxPatternCount)) {
    const int typed = value;
    value = std::clamp(value, 1, kMaxPatternCount);
    logWarning(state, std::string(label) + " " + std::to_string(typed) + ": a pattern makes 1 to " +
                          std::to_string(kMaxPatternCount) + " copies; set to " +
                          std::to_string(value));
  }
  edited(state, changed,
         [&] { setPatternField(state, nodes, [&](PatternParams& p) { set(p, value); }); });
  ImGui::PopID();
}

// Three radio buttons x, y, z for an axis.
void axisField(EditorState& state, const NodeList& nodes, const char* label, const char* tip,
               int axis) {
  ImGui::PushID(label);
  ImGui::TextUnformatted(label);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", tip);
  for (int a = 0; a < 3; ++a) {
    ImGui::SameLine(a == 0 ? 110.0f : 0.0f);
    if (ImGui::RadioButton(axisName(a), axis == a)) {
      state.document.beginInteraction();
      guarded(state, [&] { setPatternField(state, nodes, [&](PatternParams& p) { p.axis = a; }); });
      state.document.endInteraction();
    }
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", tip);
  }
  ImGui::PopID();
}

// A pattern's copies (array, circular array, mirror), in the node's frame.
void patternFields(EditorState& state, const NodePtr& node, const NodeList& nodes, double speed) {
  const Pattern pattern = patternOf(node->kind);
  const PatternParams& p = node->pattern;
  auto mixedVec = [&](glm::dvec3 PatternParams::*field) {
    glm::bvec3 mixed(false);
    for (const NodePtr& n : nodes)
      for (int i = 0; i < 3; ++i) mixed[i] = mixed[i] || (n->pattern.*field)[i] != (p.*field)[i];
    return mixed;
  };
  auto vecField = [&](const char* label, glm::dvec3 PatternParams::*field) {
    glm::dvec3 value = p.*field;
    const glm::dvec3 before = value;
    dragVec3(
        state, label, &value, speed,
        [&](const glm::dvec3& next, VecEdit edit) {
          // Each node's own value moved by as much as the primary's, or set to a typed one.
          setPatternField(state, nodes, [&](PatternParams& q) {
            if (edit.setsAll || q.*field == before)
              (q.*field)[edit.component] = next[edit.component];
            else
              q.*field = q.*field + (next - before);
          });
        },
        gLengthFormat.c_str(), mixedVec(field));
  };
  if (pattern == Pattern::Array) {
    ImGui::TextUnformatted("counts");
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("Copies along x, y and z of the array's frame (1 = no repeat)");
    ImGui::SameLine(72.0f);
    const float spacing = ImGui::GetStyle().ItemInnerSpacing.x;
    const float w = (ImGui::GetContentRegionAvail().x - 2 * spacing) / 3;
    for (int a = 0; a < 3; ++a) {
      bool mixed = false;
      for (const NodePtr& n : nodes) mixed = mixed || n->pattern.counts[a] != p.counts[a];
      if (a) ImGui::SameLine(0, spacing);
      countField(state, nodes, axisName(a), w, p.counts[a], mixed,
                 [a](PatternParams& q, int n) { q.counts[a] = n; });
    }
    vecField("step", &PatternParams::step);
    // Copies along an axis whose step is 0 lie on top of each other: say so (an artist's array
    // of 2 along y with a step of 0 showed 5 copies, not 10, without a word).
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.8f, 0.35f, 1.0f));
    for (int a = 0; a < 3; ++a)
      if (p.counts[a] > 1 && p.step[a] == 0.0)
        ImGui::TextWrapped("%d copies along %s lie on top of each other: its step is 0",
                           p.counts[a], axisName(a));
    ImGui::PopStyleColor();
  } else if (pattern == Pattern::Circular) {
    bool mixedCount = false, mixedAngle = false;
    for (const NodePtr& n : nodes) {
      mixedCount = mixedCount || n->pattern.count != p.count;
      mixedAngle = mixedAngle || n->pattern.angle != p.angle;
    }
    ImGui::TextUnformatted("count");
    ImGui::SameLine(110.0f);
    countField(state, nodes, "count", -1.0f, p.count, mixedCount,
               [](PatternParams& q, int n) { q.count = n; });
    axisField(state, nodes, "axis", "The axis the copies turn about (of the array's frame)",
              p.axis);
    ImGui::TextUnformatted("angle");
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip(
          "360: spaced evenly around; less: the first and last copies this far apart");
    ImGui::SameLine(110.0f);
    ImGui::SetNextItemWidth(-1);
    double angle = p.angle;
    const double lo = -360.0, hi = 360.0;
    const bool changed = commitTypedValue(
        ImGui::DragScalar("##angle", ImGuiDataType_Double, &angle, 0.5f, &lo, &hi,
                          mixedAngle ? "~%.4g deg" : "%.4g deg", ImGuiSliderFlags_AlwaysClamp),
        &angle);
    edited(state, changed, [&] {
      if (angle == 0.0) return;  // no copies on top of each other
      setPatternField(state, nodes, [&](PatternParams& q) { q.angle = angle; });
    });
    vecField("centre", &PatternParams::center);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("A point of the axis (the array's frame)");
    // The axis placed from what the copies go round, each selected array from its own
    // (circularAxisThroughNeighbours), or back through the array's origin.
    ImGui::TextUnformatted("axis through");
    ImGui::SameLine(110.0f);
    const auto placeAxes = [&](const std::function<PatternParams(const NodePtr&)>& placed) {
      state.document.beginInteraction();
      guarded(state, [&] {
        for (const NodePtr& n : nodes) state.document.setPattern(n->id, placed(n));
      });
      state.document.endInteraction();
      state.revealSelection = true;  // copies now lying out of view are shown
    };
    if (ImGui::SmallButton("origin"))
      placeAxes([&](const NodePtr& n) {
        PatternParams q = n->pattern;
        q.center = glm::dvec3(0.0);
        return q;
      });
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("The axis through the array's origin");
    ImGui::SameLine();
    // Kept between frames for the same tree and array (its neighbours' boxes: a mesh's vertices
    // are gone through), as the selection's size is.
    static std::weak_ptr<const Node> aroundRoot;
    static NodeId aroundOf = 0;
    static std::optional<CircularAxisPlace> aroundKept;
    if (aroundRoot.lock() != state.document.root() || aroundOf != node->id) {
      aroundKept = circularAxisThroughNeighbours(state.document.root(), node->id);
      aroundRoot = state.document.root();
      aroundOf = node->id;
    }
    const std::optional<CircularAxisPlace> around = aroundKept;
    ImGui::BeginDisabled(!around);
    // What the click will do to the ring, said before and after it: the parts stay, so the
    // ring's radius follows the axis (it changed without a word: an artist's test).
    const char* unit = unitSymbol(state.document.scene().settings.unit);
    // `done`: said after the click (the log), else before it (the tooltip).
    const auto ringText = [&](const CircularAxisPlace& place, bool done) {
      char text[200];
      if (place.params.center == node->pattern.center)
        std::snprintf(text, sizeof(text),
                      "the axis already passes through it (the copies %.4g %s from it)",
                      place.radiusAfter, unit);
      else
        std::snprintf(text, sizeof(text),
                      done ? "the parts stayed where they were: the copies circle it %.4g %s from "
                             "it (they were %.4g %s from the axis)"
                           : "the parts stay where they are: the copies will circle it %.4g %s "
                             "from it (they are %.4g %s from the axis now)",
                      place.radiusAfter, unit, place.radiusBefore, unit);
      return std::string(text);
    };
    if (ImGui::SmallButton("what it goes round")) {
      const std::string said = around ? ringText(*around, true) : "";
      placeAxes([&](const NodePtr& n) {
        const std::optional<CircularAxisPlace> place =
            circularAxisThroughNeighbours(state.document.root(), n->id);
        return place ? place->params : n->pattern;
      });
      if (around)
        logInfo(state, "the axis of " + nodeLabel(*node) + " through the middle of " +
                           around->around + ": " + said);
    }
    ImGui::EndDisabled();
    if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) {
      ImGui::BeginTooltip();
      ImGui::PushTextWrapPos(ImGui::GetFontSize() * 32.0f);
      ImGui::TextUnformatted(
          around ? ("The axis through the middle of " + around->around +
                    " (what a cutter cuts; else the parts beside it): " + ringText(*around, false))
                       .c_str()
                 : "Nothing beside the array to go round (it has no parent, or its neighbours "
                   "show nothing)");
      ImGui::PopTextWrapPos();
      ImGui::EndTooltip();
    }
  } else if (pattern == Pattern::Mirror) {
    axisField(state, nodes, "across",
              "The mirror plane's normal: x mirrors left to right across the yz plane", p.axis);
    vecField("centre", &PatternParams::center);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("A point of the mirror plane");
    // The plane placed from the parts, each selected mirror from its own (mirrorPlaneAt).
    const char* axis = axisName(std::clamp(p.axis, 0, 2));
    const struct {
      MirrorPlaneAt where;
      std::string label, tip;
    } places[] = {
        {MirrorPlaneAt::Origin, "origin", "The plane through the mirror's origin"},
        {MirrorPlaneAt::PartsLowSide, std::string("-") + axis + " side",
         std::string("The plane at the parts' lowest ") + axis +
             ": the image touches them there (model one half, mirror it at its cut face)"},
        {MirrorPlaneAt::PartsCentre, "middle",
         "The plane through the middle of the parts: the image overlaps them"},
        {MirrorPlaneAt::PartsHighSide, std::string("+") + axis + " side",
         std::string("The plane at the parts' highest ") + axis + ": the image touches them there"},
    };
    ImGui::TextUnformatted("plane at");
    // On the label's row while they fit the panel, then on the next rows under the fields.
    const ImGuiStyle& style = ImGui::GetStyle();
    float right = 0.0f;  // where the last button ended, in window coordinates
    for (size_t k = 0; k < std::size(places); ++k) {
      const float width = ImGui::CalcTextSize(places[k].label.c_str()).x + 2 * style.FramePadding.x;
      const float maxX = ImGui::GetWindowContentRegionMax().x;
      if (k == 0)
        ImGui::SameLine(110.0f);
      else if (right + style.ItemSpacing.x + width <= maxX)
        ImGui::SameLine();
      else
        ImGui::SetCursorPosX(110.0f);
      if (ImGui::SmallButton(places[k].label.c_str())) {
        state.document.beginInteraction();
        guarded(state, [&] {
          for (const NodePtr& n : nodes)
            state.document.setPattern(n->id,
                                      mirrorPlaneAt(state.document.root(), n->id, places[k].where));
        });
        state.document.endInteraction();
        state.revealSelection = true;  // the image, where it now lies out of view, is shown
      }
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", places[k].tip.c_str());
      right = ImGui::GetItemRectMax().x - ImGui::GetWindowPos().x;
    }
    bool keep = p.keepOriginal;
    bool mixed = false;
    for (const NodePtr& n : nodes) mixed = mixed || n->pattern.keepOriginal != keep;
    if (mixed) ImGui::PushItemFlag(ImGuiItemFlags_MixedValue, true);
    if (ImGui::Checkbox("keep the original", &keep)) {
      state.document.beginInteraction();
      guarded(state, [&] {
        setPatternField(state, nodes, [&](PatternParams& q) { q.keepOriginal = keep; });
      });
      state.document.endInteraction();
    }
    if (mixed) ImGui::PopItemFlag();
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("On: the children and their image (symmetry). Off: the image alone");
  }
  const uint64_t copies = patternCopies(pattern, p);
  ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyle().Colors[ImGuiCol_TextDisabled]);
  ImGui::TextWrapped("%llu copies of the children, each following every edit",
                     static_cast<unsigned long long>(copies));
  ImGui::PopStyleColor();
}

void nodeKindSections(EditorState& state, const NodePtr& node, const NodeList& nodes,
                      double speed) {
  bool sameKind = true;
  for (const NodePtr& n : nodes) sameKind = sameKind && n->kind == node->kind;
  if (!sameKind) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyle().Colors[ImGuiCol_TextDisabled]);
    ImGui::TextWrapped("Parts of different kinds: their shapes are edited one at a time.");
    ImGui::PopStyleColor();
    return;
  }
  if (isPrimitive(node->kind) && ImGui::CollapsingHeader("Shape", ImGuiTreeNodeFlags_DefaultOpen))
    primitiveParams(state, node, nodes, speed);

  if (isOperation(node->kind) &&
      ImGui::CollapsingHeader("Operation", ImGuiTreeNodeFlags_DefaultOpen)) {
    // Booleans on one row, modifiers on the next, patterns on the third.
    const std::vector<NodeKind> ops = operationKinds();
    const std::vector<bool> rowStarts = operationRowStarts(ops, 4);
    for (size_t i = 0; i < ops.size(); ++i) {
      const NodeKind op = ops[i];
      if (!rowStarts[i]) ImGui::SameLine();
      // The selection's operations become `op` (a pattern spaced for what it holds).
      if (ImGui::RadioButton(kindLabel(op), node->kind == op)) setSelectionOperation(state, op);
      if (ImGui::IsItemHovered()) {
        // What the click would do to the children's roles, before it is made.
        const std::string changes = op == node->kind ? "" : roleChangesOfKind(*node, op);
        ImGui::SetTooltip("%s%s%s", nodeKindInfo(op).summary, changes.empty() ? "" : "\n",
                          changes.c_str());
      }
    }
    ImGui::TextDisabled("%zu %s%s", node->children.size(),
                        node->children.size() == 1 ? "child" : "children",
                        node->kind == NodeKind::Difference ? "; the first minus the others" : "");
    if (const char* key = nodeKindInfo(node->kind).amountKey) {
      // A modifier's distance, thickness or radius: dragged, the preview follows.
      ImGui::TextUnformatted(key);
      ImGui::SameLine(110.0f);
      ImGui::SetNextItemWidth(-1);
      double amount = node->amount;
      const bool signedAmount = modifierOf(node->kind) == Modifier::Offset;
      // Dragged by a percent of the amount a pixel, stopping at zero (amountDrag).
      static double dragSign = 0.0;  // the amount's sign where the running drag began
      const bool dragging =
          ImGui::GetActiveID() == ImGui::GetID("##amount") && ImGui::IsMouseDown(0);
      if (!dragging) dragSign = node->amount > 0.0 ? 1.0 : node->amount < 0.0 ? -1.0 : 0.0;
      const AmountDrag drag =
          amountDrag(node->amount, signedAmount, dragging ? dragSign : 0.0, speed * 0.005);
      const bool changed = commitTypedValue(
          ImGui::DragScalar("##amount", ImGuiDataType_Double, &amount, float(drag.speed), &drag.lo,
                            &drag.hi, gLengthFormat.c_str(), ImGuiSliderFlags_AlwaysClamp),
          &amount, gLengthUnit);
      if (ImGui::IsItemHovered())
        ImGui::SetTooltip("%s", signedAmount ? "Grows the children (> 0) or shrinks them (< 0)"
                                             : nodeKindInfo(node->kind).summary);
      edited(state, changed, [&] {
        for (const NodePtr& n : nodes) state.document.setAmount(n->id, amount);
      });
      modifierLimit(modifierOf(node->kind), node->amount);
    }
    if (node->kind == NodeKind::Shell && nodes.size() == 1) shellOpeningField(state, node);
    if (patternOf(node->kind) != Pattern::None) patternFields(state, node, nodes, speed);
  }

  if (node->kind == NodeKind::Mesh &&
      ImGui::CollapsingHeader("Mesh", ImGuiTreeNodeFlags_DefaultOpen)) {
    ImGui::TextWrapped("file: %s", node->meshPath.c_str());
    ImGui::TextDisabled("%s", node->meshHash.c_str());
    if (node->mesh)
      ImGui::Text("%zu triangles, %zu vertices", node->mesh->triangles.size(),
                  node->mesh->positions.size());
    if (node->meshOpen) {
      ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.8f, 0.3f, 1.0f));
      ImGui::TextWrapped(
          "open mesh, taken as it is: its inside is guessed where rays pass its "
          "holes, so what it makes may leak");
      ImGui::PopStyleColor();
    }
    // Kept without its mesh: why, and for an open one the choice the import dialog offers.
    if (meshMissing(*node) && !node->meshProblem.empty()) {
      ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.5f, 0.45f, 1.0f));
      ImGui::TextWrapped("not in the result: %s", node->meshProblem.c_str());
      ImGui::PopStyleColor();
      // The button is drawn for one selected node only; its tooltip with it (it was attached to
      // the line above when several were selected).
      if (node->meshRefusedAsOpen && nodes.size() == 1) {
        if (ImGui::Button("take it as an open mesh")) {
          const NodeId id = node->id;
          guarded(state, [&] {
            acceptOpenMesh(state.document, id);
            logInfo(state, nodeLabel(*node) +
                               " taken as an open mesh: its inside is guessed where rays pass "
                               "its holes (the scene marks it open)");
          });
        }
        if (ImGui::IsItemHovered())
          ImGui::SetTooltip(
              "Read the file again and take it although it is not closed, as the "
              "import dialog's \"import it anyway\" does");
      }
    }
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
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                   ImGuiWindowFlags_NoBringToFrontOnFocus);
  const NodeId id = primarySelection(state);
  const NodePtr node = id ? findNode(state.document.root(), id) : nullptr;
  if (!node) {
    ImGui::TextDisabled("Nothing selected.");
    ImGui::TextDisabled("Click a part in the viewport or a row");
    ImGui::TextDisabled("in the scene tree.");
    ImGui::End();
    return;
  }
  NodeList nodes;  // every selected node still in the tree, the primary last
  for (NodeId selected : state.selection)
    if (NodePtr n = findNode(state.document.root(), selected); n && selected != id)
      nodes.push_back(n);
  nodes.push_back(node);
  gLengthFormat = std::string("%.4g ") + unitSymbol(state.document.scene().settings.unit);
  gLengthUnit = unitSymbol(state.document.scene().settings.unit);
  ImGui::PushID(static_cast<int>(node->id));
  nodeIdentity(state, node, nodes);
  // Drag speeds follow the scene's size.
  Bounds b = sceneBounds(state.document.root());
  double extent = b.empty() ? 1.0 : std::max({b.size().x, b.size().y, b.size().z});
  double speed = std::max(extent * 0.002, 1e-6);

  // The transform of the active part, or of the selected group that holds it (the part moves
  // with the group: editing both would move it twice).
  const NodeId holderId = selectedHolder(state.document.root(), state.selection, id);
  const NodePtr holder = holderId == id ? node : findNode(state.document.root(), holderId);
  const auto nameOf = [](const Node& n) {
    return n.name.empty() ? std::string(kindName(n.kind)) : n.name;
  };
  if (holder && holder != node) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
    ImGui::TextWrapped("transform of %s, which holds %s", nameOf(*holder).c_str(),
                       nameOf(*node).c_str());
    ImGui::PopStyleColor();
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip(
          "Both are selected: the fields move, turn and scale the group, and the part with it");
  }
  NodeList outer;  // the selected nodes no other selected node holds, the shown one last
  for (NodeId other : outermostSelected(state.document.root(), state.selection))
    if (other != holderId)
      if (NodePtr n = findNode(state.document.root(), other)) outer.push_back(n);
  outer.push_back(holder ? holder : node);
  nodeTransform(state, outer.back(), outer, speed);
  parentFrameNote(state, *outer.back());
  placedSize(state);
  nodeKindSections(state, node, nodes, speed);
  ImGui::PopID();
  ImGui::End();
}

}  // namespace strata::ui
