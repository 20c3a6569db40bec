#include "ui/edit_warnings.h"

#include <algorithm>

#include "engine/document/commands.h"
#include "engine/document/roles.h"
#include "ui/editor_actions.h"
#include "ui/editor_state.h"
#include "ui/scene_queries.h"

namespace strata::ui {
namespace {

// Whether boxes `a` and `b` share a volume (not only a face: parts that touch take nothing from
// each other).
bool overlap(const Bounds& a, const Bounds& b) {
  if (a.empty() || b.empty()) return false;
  for (int k = 0; k < 3; ++k)
    if (std::min(a.max[k], b.max[k]) <= std::max(a.min[k], b.min[k])) return false;
  return true;
}

// The boxes of what `node` is made of: through unions, each part they join (a union's own box
// would span its parts and the gaps between them: a hole next to a plate, inside the box of
// the plate and the hub, cut nothing); any other node whole (an array's box holds its copies).
void partBoxes(const NodePtr& root, const NodePtr& node, std::vector<Bounds>* out) {
  if (!node || !node->visible) return;
  if (node->kind == NodeKind::Union) {
    for (const NodePtr& c : node->children) partBoxes(root, c, out);
    return;
  }
  const Bounds b = selectionBounds(root, {node->id});
  if (!b.empty()) out->push_back(b);
}

// Whether a part of `a` and a part of `b` (partBoxes) share a volume, in tree `root`.
bool reaches(const NodePtr& root, const NodePtr& a, const NodePtr& b) {
  std::vector<Bounds> as, bs;
  partBoxes(root, a, &as);
  partBoxes(root, b, &bs);
  for (const Bounds& x : as)
    for (const Bounds& y : bs)
      if (overlap(x, y)) return true;
  return false;
}

std::string named(const Node& n) {
  return quotedName(n);
}

// The common box of the visible children of `op` in `root` (empty where there is none).
Bounds commonBox(const NodePtr& root, const Node& op, bool* any) {
  Bounds common;
  *any = false;
  for (const NodePtr& c : op.children) {
    if (!c->visible) continue;
    const Bounds b = selectionBounds(root, {c->id});
    common = *any ? common.intersected(b) : b;
    *any = true;
  }
  return common;
}

}  // namespace

std::vector<std::string> contactsLost(const NodePtr& before, const NodePtr& after) {
  std::vector<std::string> out;
  if (!before || !after) return out;
  for (NodeId id : treeOrder(after)) {
    const NodePtr op = findNode(after, id);
    if (!op || !op->visible || !isOperation(op->kind) || op->children.empty() ||
        !findNode(before, id))
      continue;
    if (childRole(*op, 0) == ChildRole::Base) {
      const NodePtr& base = op->children.front();
      const NodePtr baseWas = findNode(before, base->id);
      if (!base->visible || !baseWas) continue;
      for (size_t c = 1; c < op->children.size(); ++c) {
        const NodePtr& cutter = op->children[c];
        const NodePtr cutterWas = findNode(before, cutter->id);
        if (!cutter->visible || childRole(*op, int(c)) != ChildRole::Cut || !cutterWas) continue;
        if (reaches(before, cutterWas, baseWas) && !reaches(after, cutter, base))
          out.push_back(named(*cutter) + " no longer reaches " + named(*base) +
                        ": it cuts nothing now (Ctrl+Z undoes the change)");
      }
    } else if (childRole(*op, 0) == ChildRole::Intersect) {
      const NodePtr was = findNode(before, id);
      bool anyWas = false, anyNow = false;
      const Bounds common = commonBox(before, *was, &anyWas);
      const Bounds now = commonBox(after, *op, &anyNow);
      const auto shared = [](const Bounds& b) { return overlap(b, b); };
      if (anyWas && anyNow && shared(common) && !shared(now))
        out.push_back(named(*op) +
                      " is empty now: its parts no longer meet (an intersection keeps only "
                      "what all of them share; Ctrl+Z undoes the change)");
    }
  }
  return out;
}

void warnLostContacts(EditorState& state) {
  const uint64_t revision = state.document.revision();
  if (revision == state.contactsRevision || state.document.interacting()) return;
  const NodePtr now = state.document.root();
  const bool judged = state.contactsRoot && revision != state.historyRevision;
  if (judged)
    for (const std::string& line : contactsLost(state.contactsRoot, now)) logWarning(state, line);
  state.contactsRoot = now;
  state.contactsRevision = revision;
}

}  // namespace strata::ui
