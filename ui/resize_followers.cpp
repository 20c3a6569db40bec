#include "ui/resize_followers.h"

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <cmath>
#include <unordered_set>

#include "engine/document/commands.h"
#include "engine/document/roles.h"
#include "engine/geometry/transform.h"
#include "ui/scene_queries.h"

namespace strata::ui {
namespace {

// A part whose box changed: the resized part (each face moved as far as it did) or a part that
// moved whole (rigid: every face as far as its box).
struct Mover {
  NodeId id = 0;
  Bounds was, now;
  bool rigid = false;
};

// How far the face of `m`'s box on `side` (0 low, 1 high) of world axis `axis` moved, as a world
// vector: along the axis for the resized part, the whole motion for a part that moved.
glm::dvec3 faceMotion(const Mover& m, int axis, int side) {
  if (m.rigid) return m.now.min - m.was.min;
  glm::dvec3 v(0.0);
  v[axis] = side ? m.now.max[axis] - m.was.max[axis] : m.now.min[axis] - m.was.min[axis];
  return v;
}

struct Leaf {
  NodePtr node;
  VisibleLeaf at;
};

// Where leaf `leaf` rests on a face of `m`'s old box: that face's motion; none otherwise.
bool restsOn(const Leaf& leaf, const Mover& m, const NodePtr& root, glm::dvec3* motion) {
  const glm::dmat4 world = leaf.at.parentWorld * leaf.node->transform.matrix();
  const glm::dvec3 bottom = glm::dvec3(world * glm::dvec4(ownBottom(leaf.node, root), 1.0));
  const glm::dvec3 down = glm::dvec3(world * glm::dvec4(0.0, 0.0, -1.0, 0.0));
  if (glm::length(down) == 0.0) return false;
  const double tolerance = 1e-4 * std::max(m.was.longestSide(), leaf.at.box.longestSide());
  const double aligned = std::cos(glm::radians(2.0));
  for (int a = 0; a < 3; ++a) {
    bool within = true;
    for (int k = 0; k < 3; ++k)
      if (k != a && (bottom[k] < m.was.min[k] - tolerance || bottom[k] > m.was.max[k] + tolerance))
        within = false;
    if (!within) continue;
    for (int side = 0; side < 2; ++side) {
      const double face = side ? m.was.max[a] : m.was.min[a];
      if (std::fabs(bottom[a] - face) > tolerance) continue;
      // Its down points into the face: against the face's outward normal.
      const double into = (side ? -down[a] : down[a]) / glm::length(down);
      if (into < aligned) continue;
      *motion = faceMotion(m, a, side);
      return true;
    }
  }
  return false;
}

// The bases cutter `id` acts on: the first child of each difference on its path from the root
// where the path goes through a later child.
std::vector<NodeId> basesCutBy(const NodePtr& root, NodeId id) {
  std::vector<const Node*> path;
  std::vector<NodeId> bases;
  if (!pathToNode(root, id, &path)) return bases;
  for (size_t i = 0; i + 1 < path.size(); ++i) {
    const Node& parent = *path[i];
    for (size_t c = 0; c < parent.children.size(); ++c)
      if (parent.children[c].get() == path[i + 1] &&
          childRole(parent, static_cast<int>(c)) == ChildRole::Cut)
        bases.push_back(parent.children.front()->id);
  }
  return bases;
}

// The world motion of a cutter with box `box` so that it keeps its place against the movers it
// acts on (resizeFollowers' rules), as a diagonal affine map; identity where nothing changes.
struct CutterMotion {
  glm::dmat4 map{1.0};
  bool lengthened = false;
  bool moved = false;
};
CutterMotion cutterMotion(const Bounds& box, const std::vector<const Mover*>& movers) {
  glm::dvec3 low = box.min, high = box.max, shift(0.0);
  bool lengthen[3] = {false, false, false}, shifted[3] = {false, false, false};
  for (const Mover* m : movers) {
    const double tolerance = 1e-4 * std::max(m->was.longestSide(), box.longestSide());
    bool overlaps = true;
    for (int a = 0; a < 3; ++a)
      overlaps =
          overlaps &&
          std::min(box.max[a], m->was.max[a]) - std::max(box.min[a], m->was.min[a]) > tolerance;
    if (!overlaps) continue;
    for (int a = 0; a < 3; ++a) {
      const bool fromLow = box.min[a] <= m->was.min[a] + tolerance;
      const bool pastHigh = box.max[a] >= m->was.max[a] - tolerance;
      if (fromLow && pastHigh) {  // through, face to face: still through where the box grew
        if (m->now.min[a] < box.min[a] - tolerance) {
          low[a] = std::min(low[a], m->now.min[a] - std::max(m->was.min[a] - box.min[a], 0.0));
          lengthen[a] = true;
        }
        if (m->now.max[a] > box.max[a] + tolerance) {
          high[a] = std::max(high[a], m->now.max[a] + std::max(box.max[a] - m->was.max[a], 0.0));
          lengthen[a] = true;
        }
        continue;
      }
      if (shifted[a]) continue;  // the first part it acts on places it
      shifted[a] = true;
      const double wasSize = m->was.max[a] - m->was.min[a];
      if (m->rigid)
        shift[a] = m->now.min[a] - m->was.min[a];
      else if (pastHigh)  // crosses the high face only
        shift[a] = m->now.max[a] - m->was.max[a];
      else if (fromLow)  // crosses the low face only
        shift[a] = m->now.min[a] - m->was.min[a];
      else if (wasSize > 0.0)  // inside: at the same fraction of the box
        shift[a] = m->now.min[a] +
                   (box.center()[a] - m->was.min[a]) / wasSize * (m->now.max[a] - m->now.min[a]) -
                   box.center()[a];
    }
  }
  CutterMotion out;
  for (int a = 0; a < 3; ++a) {
    if (lengthen[a]) {
      const double scale = (high[a] - low[a]) / (box.max[a] - box.min[a]);
      out.map[a][a] = scale;
      out.map[3][a] = low[a] - box.min[a] * scale;
      out.lengthened = true;
    } else if (shift[a] != 0.0) {
      out.map[3][a] = shift[a];
      out.moved = true;
    }
  }
  return out;
}

}  // namespace

ResizeFollowing resizeFollowers(const NodePtr& before, const NodePtr& after, NodeId id,
                                const std::vector<NodeId>& excluded) {
  ResizeFollowing following;
  std::vector<ResizeFollower>& out = following.followers;
  if (!findNode(before, id) || !findNode(after, id) || removesMaterial(before, id))
    return following;
  Mover resized{id, selectionBounds(before, {id}), selectionBounds(after, {id}), false};
  if (resized.was.empty() || resized.now.empty()) return following;
  std::vector<Leaf> leaves;
  forEachVisibleLeaf(before, [&](const NodePtr& leaf, const VisibleLeaf& at) {
    leaves.push_back({leaf, at});
  });
  std::unordered_set<NodeId> settled(excluded.begin(), excluded.end());
  settled.insert(id);
  const auto leftOut = [&](NodeId leaf) {
    return settled.count(leaf) > 0 || isInSubtree(before, id, leaf);
  };

  // The parts resting on the resized part, and on those, breadth first.
  std::vector<Mover> movers{resized};
  for (size_t i = 0; i < movers.size(); ++i)
    for (const Leaf& leaf : leaves) {
      glm::dvec3 motion;
      if (leaf.at.removes || leftOut(leaf.node->id) || !restsOn(leaf, movers[i], before, &motion) ||
          glm::length(motion) == 0.0)
        continue;
      settled.insert(leaf.node->id);
      Transform t = leaf.node->transform;
      t.translate += glm::dvec3(glm::inverse(leaf.at.parentWorld) * glm::dvec4(motion, 0.0));
      out.push_back({leaf.node->id, t, ResizeFollower::Why::RestsOn});
      Bounds moved = leaf.at.box;
      moved.min += motion;
      moved.max += motion;
      movers.push_back({leaf.node->id, leaf.at.box, moved, true});
    }

  // The cutters of the parts that changed.
  for (const Leaf& cutter : leaves) {
    if (!cutter.at.removes || leftOut(cutter.node->id)) continue;
    const std::vector<NodeId> bases = basesCutBy(before, cutter.node->id);
    std::vector<const Mover*> actedOn;
    for (const Mover& m : movers)
      for (NodeId base : bases)
        if (isInSubtree(before, base, m.id)) {
          actedOn.push_back(&m);
          break;
        }
    if (actedOn.empty()) continue;
    const CutterMotion motion = cutterMotion(cutter.at.box, actedOn);
    if (!motion.lengthened && !motion.moved) continue;
    const Transform& was = cutter.node->transform;
    bool exact = true;
    const Transform t = transformNear(
        glm::inverse(cutter.at.parentWorld) * motion.map * cutter.at.parentWorld * was.matrix(),
        was, &exact);
    if (!exact) {
      following.leftTurned.push_back(cutter.node->id);
      continue;
    }
    out.push_back(
        {cutter.node->id, t,
         motion.lengthened ? ResizeFollower::Why::CutsThrough : ResizeFollower::Why::CutsInto});
  }

  // Parts left where they were that the part now covers.
  const auto inside = [&](const Bounds& b, const Bounds& in) {
    const double tolerance = 1e-4 * in.longestSide();
    for (int a = 0; a < 3; ++a)
      if (b.min[a] < in.min[a] - tolerance || b.max[a] > in.max[a] + tolerance) return false;
    return true;
  };
  for (const Leaf& leaf : leaves)
    if (!leaf.at.removes && !leftOut(leaf.node->id) && inside(leaf.at.box, resized.now) &&
        !inside(leaf.at.box, resized.was))
      following.buried.push_back(leaf.node->id);
  return following;
}

std::vector<FollowMessage> resizeFollowingMessages(const NodePtr& root, NodeId id,
                                                   const ResizeFollowing& following) {
  using Why = ResizeFollower::Why;
  const auto named = [&](NodeId of) {
    const NodePtr n = findNode(root, of);
    return n ? "\"" + (n->name.empty() ? nodeLabel(*n) : n->name) + "\"" : std::string("a part");
  };
  const std::pair<Why, const char*> clauses[] = {
      {Why::RestsOn, "moved with it"},
      {Why::CutsThrough, "lengthened to stay through it"},
      {Why::CutsInto, "moved with its face"},
  };
  std::string text;
  for (const auto& [why, said] : clauses) {
    std::vector<std::string> names;
    for (const ResizeFollower& f : following.followers)
      if (f.why == why) names.push_back(named(f.id));
    if (names.empty()) continue;
    std::string list;
    const size_t shown = names.size() > 3 ? 2 : names.size();
    for (size_t i = 0; i < shown; ++i)
      list += (i == 0 ? "" : i + 1 == shown && shown == names.size() ? " and " : ", ") + names[i];
    if (shown < names.size()) list += " and " + std::to_string(names.size() - shown) + " more";
    text += (text.empty() ? "" : "; ") + list + " " + said;
  }
  std::vector<FollowMessage> out;
  if (!text.empty()) out.push_back({false, named(id) + " changed size: " + text});
  for (NodeId left : following.leftTurned)
    out.push_back({true, named(left) + " cuts " + named(id) +
                             " but is turned against the scene's axes: it was left as it was "
                             "(check that it still goes through)"});
  for (NodeId under : following.buried)
    out.push_back({true, named(under) + " now lies inside " + named(id) +
                             " and no longer shows: it did not rest on it, so it stayed where it "
                             "was (Ctrl+Z undoes the change)"});
  return out;
}

}  // namespace strata::ui
