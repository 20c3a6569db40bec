#include "engine/document/expansion.h"

#include <algorithm>
#include <unordered_map>
#include <vector>

#include "engine/util/error.h"
#include "engine/util/limits.h"

namespace strata {
namespace {

uint64_t saturatingAdd(uint64_t a, uint64_t b) {
  return a > kSaturated - b ? kSaturated : a + b;
}

uint64_t saturatingMultiply(uint64_t a, uint64_t b) {
  if (a == 0 || b == 0) return 0;
  return a > kSaturated / b ? kSaturated : a * b;
}

// One visit state: a node, reached directly or through an instance (which shows hidden nodes).
struct StateKey {
  const Node* node;
  bool viaInstance;
  bool operator==(const StateKey& o) const {
    return node == o.node && viaInstance == o.viaInstance;
  }
};
struct StateHash {
  size_t operator()(const StateKey& k) const {
    return std::hash<const Node*>()(k.node) * 2 + size_t(k.viaInstance);
  }
};

class ExpansionCounter {
 public:
  explicit ExpansionCounter(const NodePtr& root) { indexIds(root); }

  TreeExpansion run(const NodePtr& root) {
    if (!root) return result_;
    Totals totals = visit({root.get(), true});
    result_.leaves = totals.leaves;
    result_.nodes = totals.nodes;
    result_.modifiers = totals.modifiers;
    result_.depth = totals.depth;
    return result_;
  }

 private:
  struct Totals {
    uint64_t leaves = 0;
    uint64_t nodes = 0;
    int depth = 0;
    uint64_t modifiers = 0;
  };
  struct Frame {
    StateKey key;
    size_t next = 0;  // next edge to follow
    Totals sum;
  };

  void indexIds(const NodePtr& root) {
    std::vector<const Node*> stack;
    if (root) stack.push_back(root.get());
    while (!stack.empty()) {
      const Node* n = stack.back();
      stack.pop_back();
      byId_.emplace(n->id, n);
      for (const auto& c : n->children) stack.push_back(c.get());
    }
  }

  // The edges of a state: an instance's target (shown even when hidden), or the children.
  size_t edgeCount(const Node& n) const {
    return n.kind == NodeKind::Instance ? 1 : n.children.size();
  }
  const Node* edge(const Node& n, size_t i) {
    if (n.kind != NodeKind::Instance) return n.children[i].get();
    auto it = byId_.find(n.instanceOf);
    if (it == byId_.end()) result_.missingTarget = true;
    return it == byId_.end() ? nullptr : it->second;
  }

  // Iterative post-order walk with memoised totals per state.
  Totals visit(StateKey start) {
    std::vector<Frame> stack{Frame{start, 0, {}}};
    active_[start] = true;
    Totals last;
    while (!stack.empty()) {
      Frame& top = stack.back();
      const Node& n = *top.key.node;
      if (top.next < edgeCount(n)) {
        const Node* child = edge(n, top.next++);
        if (!child) continue;
        StateKey key{child, n.kind == NodeKind::Instance};
        if (auto done = memo_.find(key); done != memo_.end()) {
          accumulate(top, key, done->second);
        } else if (active_[key]) {
          result_.cycle = true;
        } else {
          active_[key] = true;
          stack.push_back(Frame{key, 0, {}});
        }
        continue;
      }
      last = finish(top);
      memo_[top.key] = last;
      active_[top.key] = false;
      StateKey key = top.key;
      stack.pop_back();
      if (!stack.empty()) accumulate(stack.back(), key, last);
    }
    return last;
  }

  static void accumulate(Frame& parent, const StateKey& child, const Totals& t) {
    parent.sum.depth = std::max(parent.sum.depth, t.depth);
    // Hidden children take no part (an instance's target is shown whatever its flag).
    if (!child.viaInstance && !child.node->visible) return;
    parent.sum.leaves = saturatingAdd(parent.sum.leaves, t.leaves);
    parent.sum.nodes = saturatingAdd(parent.sum.nodes, t.nodes);
    parent.sum.modifiers = saturatingAdd(parent.sum.modifiers, t.modifiers);
  }

  static Totals finish(const Frame& f) {
    const Node& n = *f.key.node;
    if (n.kind == NodeKind::Instance) return f.sum;  // the target's totals, as evaluated
    if (!isOperation(n.kind)) return {1, 1, 1, 0};
    const uint64_t own = modifierOf(n.kind) != Modifier::None ? 1 : 0;
    if (n.kind == NodeKind::Shell && n.opening != 0) {
      // A shell with an opening evaluates its children twice: as they are, and without the
      // opening for its wall (evaluator.cpp; an upper bound, most of it from the cache).
      return {saturatingAdd(f.sum.leaves, f.sum.leaves),
              saturatingAdd(saturatingAdd(f.sum.nodes, f.sum.nodes), 2), f.sum.depth + 1,
              saturatingAdd(saturatingAdd(f.sum.modifiers, f.sum.modifiers), own)};
    }
    const uint64_t copies = patternCopies(patternOf(n.kind), n.pattern);
    // A pattern visits its children once per copy; its copies count as visits even when it
    // holds nothing (they are listed).
    return {saturatingMultiply(f.sum.leaves, copies),
            saturatingAdd(saturatingMultiply(std::max<uint64_t>(f.sum.nodes, 1), copies), 1),
            f.sum.depth + 1, saturatingAdd(saturatingMultiply(f.sum.modifiers, copies), own)};
  }

  std::unordered_map<NodeId, const Node*> byId_;
  std::unordered_map<StateKey, Totals, StateHash> memo_;
  std::unordered_map<StateKey, bool, StateHash> active_;
  TreeExpansion result_;
};

}  // namespace

TreeExpansion measureExpansion(const NodePtr& root) {
  return ExpansionCounter(root).run(root);
}

std::string countText(uint64_t count) {
  if (count == kSaturated) return "more than 10^19";
  std::string digits = std::to_string(count), out;
  for (size_t i = 0; i < digits.size(); ++i) {
    if (i && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out;
}

TreeExpansion checkExpansion(const NodePtr& root, uint64_t maxLeaves) {
  TreeExpansion e = measureExpansion(root);
  if (e.cycle) throw Error("an instance refers to one of its own ancestors (an instance cycle)");
  if (e.missingTarget) throw Error("an instance refers to a node that is not in the scene");
  if (e.depth > kMaxTreeDepth)
    throw Error("the tree is " + countText(uint64_t(e.depth)) +
                " levels deep through its instances; at most " + std::to_string(kMaxTreeDepth) +
                " are evaluated");
  if (e.leaves > maxLeaves)
    throw Error("the scene expands to " + countText(e.leaves) +
                " visible leaves through its instances, more than the limit of " +
                countText(maxLeaves) +
                "; raise it with --max-leaves N (or the scene setting \"maxLeaves\") if you "
                "mean it");
  return e;
}

}  // namespace strata
