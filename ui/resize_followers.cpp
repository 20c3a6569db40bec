#include "ui/resize_followers.h"

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/matrix.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <unordered_map>
#include <unordered_set>

#include "engine/document/commands.h"
#include "engine/document/roles.h"
#include "engine/eval/evaluator.h"
#include "engine/geometry/transform.h"
#include "engine/kinds/patterns.h"
#include "engine/util/error.h"
#include "ui/scene_queries.h"

namespace strata::ui {
namespace {

// A part whose box changed: the resized part or one that followed it (each face moved as far
// as it did), or one that moved whole (rigid: every face as far as its box; what lies within it
// moves along).
struct Mover {
  NodeId id = 0;
  Bounds was, now;
  bool rigid = false;
};

double lowMotion(const Mover& m, int a) {
  return m.now.min[a] - m.was.min[a];
}
double highMotion(const Mover& m, int a) {
  return m.now.max[a] - m.was.max[a];
}

// How far the face of `m`'s box on `side` (0 low, 1 high) of world axis `axis` moved, as a world
// vector: along the axis, or the whole motion for a part that moved whole.
glm::dvec3 faceMotion(const Mover& m, int axis, int side) {
  if (m.rigid) return m.now.min - m.was.min;
  glm::dvec3 v(0.0);
  v[axis] = side ? highMotion(m, axis) : lowMotion(m, axis);
  return v;
}

struct Leaf {
  NodePtr node;
  VisibleLeaf at;
};

double toleranceOf(const Bounds& a, const Bounds& b) {
  return 1e-4 * std::max(a.longestSide(), b.longestSide());
}

// Whether boxes `a` and `b` share more than `tolerance` along every axis.
bool overlaps(const Bounds& a, const Bounds& b, double tolerance) {
  for (int k = 0; k < 3; ++k)
    if (std::min(a.max[k], b.max[k]) - std::max(a.min[k], b.min[k]) <= tolerance) return false;
  return true;
}

// Whether `box` lies within `in` along at least one axis: a part built into `in`, not one `in`
// is built into (the plate under a boss sunk into it holds the boss on every axis).
bool withinAlongAnAxis(const Bounds& box, const Bounds& in, double tolerance) {
  for (int k = 0; k < 3; ++k)
    if (box.min[k] >= in.min[k] - tolerance && box.max[k] <= in.max[k] + tolerance) return true;
  return false;
}

// Whether `box` reaches past both ends of `in` along two axes or more: `in` is built into it
// (a hub through a plate, the plate reaching past the hub along x and y), not the other way:
// the plate grew with the hub's radius (a review).
bool holdsAlongTwoAxes(const Bounds& box, const Bounds& in, double tolerance) {
  int axes = 0;
  for (int k = 0; k < 3; ++k)
    axes += box.min[k] < in.min[k] - tolerance && box.max[k] > in.max[k] + tolerance ? 1 : 0;
  return axes >= 2;
}

// Where leaf `leaf` rests on a face of `m`'s old box: that face's motion; none otherwise.
bool restsOn(const Leaf& leaf, const Mover& m, const NodePtr& root, glm::dvec3* motion) {
  const glm::dmat4 world = leaf.at.parentWorld * leaf.node->transform.matrix();
  const glm::dvec3 bottom = glm::dvec3(world * glm::dvec4(ownBottom(leaf.node, root), 1.0));
  const glm::dvec3 down = glm::dvec3(world * glm::dvec4(0.0, 0.0, -1.0, 0.0));
  if (glm::length(down) == 0.0) return false;
  const double tolerance = toleranceOf(m.was, leaf.at.box);
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

// The world motion of a part with box `box` built into (or cutting) the movers `movers`, as a
// diagonal affine map of world points, along each axis from the first mover it overlaps that
// places it there: passing both faces, its ends move with them; crossing one, it moves with it;
// within the box, it stays (it moves whole with a part that moved whole).
struct Motion {
  glm::dmat4 map{1.0};
  bool stretched = false;
  bool moved = false;
};
Motion attachedMotion(const Bounds& box, const std::vector<const Mover*>& movers) {
  glm::dvec3 low = box.min, high = box.max, shift(0.0);
  bool ends[3] = {false, false, false}, shifted[3] = {false, false, false};
  for (const Mover* m : movers) {
    const double tolerance = toleranceOf(m->was, box);
    if (!overlaps(box, m->was, tolerance)) continue;
    for (int a = 0; a < 3; ++a) {
      if (ends[a] || shifted[a]) continue;  // the first part it belongs to places it
      const bool fromLow = box.min[a] <= m->was.min[a] + tolerance;
      const bool pastHigh = box.max[a] >= m->was.max[a] - tolerance;
      if (fromLow && pastHigh) {
        low[a] = box.min[a] + lowMotion(*m, a);
        high[a] = box.max[a] + highMotion(*m, a);
        ends[a] = true;
        continue;
      }
      if (pastHigh)
        shift[a] = highMotion(*m, a);
      else if (fromLow)
        shift[a] = lowMotion(*m, a);
      else if (m->rigid)
        shift[a] = lowMotion(*m, a);
      else
        continue;  // within the box: it stays (a later part may place it)
      shifted[a] = true;
    }
  }
  Motion out;
  for (int a = 0; a < 3; ++a) {
    if (ends[a]) {
      const double length = box.max[a] - box.min[a];
      const double scale = length > 0.0 ? (high[a] - low[a]) / length : 1.0;
      out.map[a][a] = scale;
      out.map[3][a] = low[a] - box.min[a] * scale;
      if (scale != 1.0)
        out.stretched = true;
      else if (out.map[3][a] != 0.0)
        out.moved = true;
    } else if (shifted[a] && shift[a] != 0.0) {
      out.map[3][a] = shift[a];
      out.moved = true;
    }
  }
  return out;
}

Bounds mapped(const glm::dmat4& map, const Bounds& b) {
  Bounds out;
  out.include(glm::dvec3(map * glm::dvec4(b.min, 1.0)));
  out.include(glm::dvec3(map * glm::dvec4(b.max, 1.0)));
  return out;
}

// The world matrices of the parent of leaf `id` for each copy the patterns above it make (tree
// edges, at most 4096), the one forEachVisibleLeaf gives first.
std::vector<glm::dmat4> copyParents(const NodePtr& root, NodeId id) {
  std::vector<const Node*> path;
  if (!pathToNode(root, id, &path)) return {};
  std::vector<glm::dmat4> parents{glm::dmat4(1.0)};
  for (size_t i = 0; i + 1 < path.size(); ++i) {
    const Node& node = *path[i];
    std::vector<glm::dmat4> placements{glm::dmat4(1.0)};
    const Pattern pattern = patternOf(node.kind);
    if (pattern != Pattern::None) {
      try {
        checkPattern(pattern, node.pattern, nodeLabel(node));
        placements = patternPlacements(pattern, node.pattern);
      } catch (const Error&) {
        placements = {firstPlacement(pattern, node.pattern)};
      }
    }
    std::vector<glm::dmat4> next;
    for (const glm::dmat4& p : parents)
      for (const glm::dmat4& place : placements)
        if (next.size() < 4096) next.push_back(p * node.transform.matrix() * place);
    parents = std::move(next);
  }
  return parents;
}

bool nearlyEqual(const glm::dmat4& a, const glm::dmat4& b) {
  double largest = 1.0, difference = 0.0;
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) {
      largest = std::max({largest, std::fabs(a[c][r]), std::fabs(b[c][r])});
      difference = std::max(difference, std::fabs(a[c][r] - b[c][r]));
    }
  return difference <= 1e-9 * largest;
}

// A stretch along one of the part's own axes moved from its scale into its parameters, where
// it has a length along that axis (a box's size, a cylinder's, cone's or capsule's height along
// its z): the inspector then shows the part's new size, not a scale (an artist's test).
bool stretchIntoParams(const Node& node, const Transform& was, Transform* now,
                       PrimitiveParams* params) {
  int k = -1;
  for (int c = 0; c < 3; ++c)
    if (now->scale[c] != was.scale[c]) {
      if (k >= 0) return false;
      k = c;
    }
  if (k < 0 || was.scale[k] == 0.0) return false;
  const double f = now->scale[k] / was.scale[k];
  if (!(f > 0.0) || !std::isfinite(f)) return false;
  PrimitiveParams p = node.params;
  switch (node.kind) {
    case NodeKind::Box:
      p.size[k] *= f;
      break;
    case NodeKind::RoundedBox:
      p.size[k] *= f;
      if (2.0 * p.radius >= std::min({p.size.x, p.size.y, p.size.z})) return false;
      break;
    case NodeKind::Cylinder:
    case NodeKind::Cone:
      if (k != 2) return false;
      p.height *= f;
      break;
    case NodeKind::Capsule: {  // its length is height + 2 radius
      if (k != 2) return false;
      const double height = f * (p.height + 2.0 * p.radius) - 2.0 * p.radius;
      if (height < 0.0) return false;
      p.height = height;
      break;
    }
    default:
      return false;
  }
  now->scale[k] = was.scale[k];
  *params = p;
  return true;
}

// Leaf `leaf` moved by the world map `map`: its transform (and parameters) for it, where the map
// holds as a move, turn and scale of it and every copy of it (a pattern's) moves as
// `copyMotion` says a copy with that box should: a mirrored rib moves the other way, which the
// leaf's own change gives it.
bool placedBy(const NodePtr& root, const Leaf& leaf, const glm::dmat4& map,
              const std::function<glm::dmat4(const Bounds&)>& copyMotion, ResizeFollower* out) {
  const Transform& was = leaf.node->transform;
  const glm::dmat4 parent = leaf.at.parentWorld;
  bool exact = true;
  Transform now = transformNear(glm::inverse(parent) * map * parent * was.matrix(), was, &exact);
  if (!exact) return false;
  for (const glm::dmat4& copy : copyParents(root, leaf.node->id)) {
    if (nearlyEqual(copy, parent)) continue;  // the leaf itself
    const glm::dmat4 wanted = copyMotion(nodeBounds(leaf.node, root, copy));
    if (!nearlyEqual(copy * now.matrix(), wanted * copy * was.matrix())) return false;
  }
  PrimitiveParams params;
  if (stretchIntoParams(*leaf.node, was, &now, &params)) out->params = params;
  out->id = leaf.node->id;
  out->transform = now;
  return true;
}

}  // namespace

ResizeFollowing resizeFollowers(const NodePtr& before, const NodePtr& after, NodeId id,
                                const std::vector<NodeId>& excluded) {
  ResizeFollowing following;
  std::vector<ResizeFollower>& out = following.followers;
  if (!findNode(before, id) || !findNode(after, id) || removesMaterial(before, id))
    return following;
  const Mover resized{id, selectionBounds(before, {id}), selectionBounds(after, {id}), false};
  if (resized.was.empty() || resized.now.empty()) return following;
  std::vector<Leaf> leaves;
  forEachVisibleLeaf(before, [&](const NodePtr& leaf, const VisibleLeaf& at) {
    leaves.push_back({leaf, at});
  });
  std::unordered_set<NodeId> settled(excluded.begin(), excluded.end());
  settled.insert(id);
  // Once a call, not a walk from the root per leaf and mover (a drag asks every frame).
  std::unordered_set<NodeId> underResized;
  for (NodeId n : treeOrder(findNode(before, id))) underResized.insert(n);
  const auto leftOut = [&](NodeId leaf) {
    return settled.count(leaf) > 0 || underResized.count(leaf) > 0;
  };
  // The ids under each base a cutter acts on, built when first asked.
  std::unordered_map<NodeId, std::unordered_set<NodeId>> underBase;
  const auto holds = [&](NodeId base, NodeId part) {
    auto it = underBase.find(base);
    if (it == underBase.end()) {
      std::unordered_set<NodeId> ids;
      for (NodeId n : treeOrder(findNode(before, base))) ids.insert(n);
      it = underBase.emplace(base, std::move(ids)).first;
    }
    return it->second.count(part) > 0;
  };

  // Leaf `leaf` follows by the world map `map`: a follower and a mover in turn, or left alone.
  std::vector<Mover> movers{resized};
  const auto follow = [&](const Leaf& leaf, const Motion& motion,
                          const std::function<glm::dmat4(const Bounds&)>& copyMotion) {
    settled.insert(leaf.node->id);
    ResizeFollower f;
    if (!placedBy(before, leaf, motion.map, copyMotion, &f)) {
      following.leftAlone.push_back(leaf.node->id);
      return;
    }
    f.why = motion.stretched ? ResizeFollower::Why::Stretched : ResizeFollower::Why::Moved;
    f.cuts = leaf.at.removes;
    out.push_back(f);
    if (!leaf.at.removes)
      movers.push_back(
          {leaf.node->id, leaf.at.box, mapped(motion.map, leaf.at.box), !motion.stretched});
  };

  // What rests on the resized part and what is built into it, then on and into those.
  for (size_t i = 0; i < movers.size(); ++i) {
    const Mover m = movers[i];  // `movers` grows below
    for (const Leaf& leaf : leaves) {
      glm::dvec3 motion;
      if (leaf.at.removes || leftOut(leaf.node->id) || !restsOn(leaf, m, before, &motion) ||
          glm::length(motion) == 0.0)
        continue;
      Motion moved;
      moved.map = glm::translate(glm::dmat4(1.0), motion);
      moved.moved = true;
      follow(leaf, moved, [&](const Bounds&) { return moved.map; });  // every copy alike
    }
    for (const Leaf& leaf : leaves) {
      const double tolerance = toleranceOf(m.was, leaf.at.box);
      if (leaf.at.removes || leftOut(leaf.node->id) || !overlaps(leaf.at.box, m.was, tolerance) ||
          !withinAlongAnAxis(leaf.at.box, m.was, tolerance) ||
          (!m.rigid && holdsAlongTwoAxes(leaf.at.box, m.was, tolerance)))
        continue;
      const Motion motion = attachedMotion(leaf.at.box, {&m});
      if (motion.stretched || motion.moved)
        follow(leaf, motion, [&](const Bounds& copy) { return attachedMotion(copy, {&m}).map; });
    }
  }

  // The cutters of the parts that changed.
  for (const Leaf& cutter : leaves) {
    if (!cutter.at.removes || leftOut(cutter.node->id)) continue;
    const std::vector<NodeId> bases = basesCutBy(before, cutter.node->id);
    std::vector<const Mover*> actedOn;
    for (const Mover& m : movers)
      for (NodeId base : bases)
        if (holds(base, m.id)) {
          actedOn.push_back(&m);
          break;
        }
    if (actedOn.empty()) continue;
    const Motion motion = attachedMotion(cutter.at.box, actedOn);
    if (motion.stretched || motion.moved)
      follow(cutter, motion, [&](const Bounds& copy) { return attachedMotion(copy, actedOn).map; });
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

bool scaleIntoSize(const Node& start, Transform* now, PrimitiveParams* params,
                   std::vector<FittedParam>* fitted) {
  if (fitted) fitted->clear();
  if (!isPrimitive(start.kind)) return false;
  glm::dvec3 f(1.0);
  for (int k = 0; k < 3; ++k) {
    if (start.transform.scale[k] == 0.0) return false;
    f[k] = now->scale[k] / start.transform.scale[k];
    if (!(f[k] > 0.0) || !std::isfinite(f[k])) return false;
  }
  const auto same = [](double a, double b) {
    return std::fabs(a - b) <= 1e-12 * std::max(1.0, std::fabs(a));
  };
  PrimitiveParams p = start.params;
  std::vector<FittedParam> fitParams;
  switch (start.kind) {
    case NodeKind::Box:
    case NodeKind::RoundedBox:
      p.size *= f;
      fitParams = fitPrimitiveRelations(start.kind, &p, "size");
      break;
    case NodeKind::Cylinder:
      if (!same(f.x, f.y)) return false;
      p.radius *= f.x;
      p.height *= f.z;
      break;
    case NodeKind::Cone:
      if (!same(f.x, f.y)) return false;
      p.radius *= f.x;
      p.topRadius *= f.x;
      p.height *= f.z;
      break;
    case NodeKind::Capsule: {  // its length is height + 2 radius
      if (!same(f.x, f.y)) return false;
      const double length = (p.height + 2.0 * p.radius) * f.z;
      p.radius *= f.x;
      p.height = length - 2.0 * p.radius;
      if (p.height < 0.0) return false;
      break;
    }
    case NodeKind::Sphere:
      if (!same(f.x, f.y) || !same(f.y, f.z)) return false;
      p.radius *= f.x;
      break;
    case NodeKind::Torus:
      if (!same(f.x, f.y) || !same(f.y, f.z)) return false;
      p.majorRadius *= f.x;
      p.minorRadius *= f.x;
      fitParams = fitPrimitiveRelations(start.kind, &p, "majorRadius");
      break;
    default:
      return false;
  }
  try {
    validateParams(start.kind, p);
  } catch (const Error&) {
    return false;
  }
  now->scale = start.transform.scale;
  *params = p;
  if (fitted) *fitted = fitParams;
  return true;
}

std::string fittedParamsMessage(const Node& n, const std::vector<FittedParam>& fitted,
                                const std::string& changed, const std::string& unit,
                                bool dragging) {
  std::string made;
  for (const FittedParam& f : fitted) {
    char number[32];
    std::snprintf(number, sizeof(number), "%.4g", f.value);  // as fitted: 4 digits
    made += (made.empty() ? "" : ", ") + std::string(f.label) + " made " +
            (dragging ? std::string("smaller") : number + (unit.empty() ? "" : " " + unit));
  }
  const PrimitiveInfo* info = primitiveInfo(n.kind);
  return quotedName(n) + ": " + made + " to fit the " + changed +
         (dragging ? " as it is dragged" : "") + " (" + (info ? info->label : "part") +
         (dragging ? "; it comes back as the " + changed + " does" : std::string()) +
         "; undo gives the old one back)";
}

std::vector<FollowMessage> resizeFollowingMessages(const NodePtr& root, NodeId id,
                                                   const ResizeFollowing& following) {
  using Why = ResizeFollower::Why;
  const auto named = [&](NodeId of) {
    const NodePtr n = findNode(root, of);
    return n ? quotedName(*n) : std::string("a part");
  };
  struct Clause {
    Why why;
    bool cuts;
    const char* said;
  };
  const Clause clauses[] = {
      {Why::Moved, false, "moved with it"},
      {Why::Stretched, false, "resized with it"},
      {Why::Stretched, true, "kept through it"},
      {Why::Moved, true, "moved with its face"},
  };
  std::string text;
  for (const Clause& clause : clauses) {
    std::vector<std::string> names;
    for (const ResizeFollower& f : following.followers)
      if (f.why == clause.why && f.cuts == clause.cuts) names.push_back(named(f.id));
    if (names.empty()) continue;
    std::string list;
    const size_t shown = names.size() > 3 ? 2 : names.size();
    for (size_t i = 0; i < shown; ++i)
      list += (i == 0 ? "" : i + 1 == shown && shown == names.size() ? " and " : ", ") + names[i];
    if (shown < names.size()) list += " and " + std::to_string(names.size() - shown) + " more";
    text += (text.empty() ? "" : "; ") + list + " " + clause.said;
  }
  std::vector<FollowMessage> out;
  if (!text.empty()) out.push_back({false, named(id) + " changed size: " + text});
  for (NodeId left : following.leftAlone)
    out.push_back({true, named(left) + " would follow " + named(id) +
                             " but was left as it was: it is turned against the scene's axes, "
                             "or its copies would not all move alike (check it)"});
  for (NodeId under : following.buried)
    out.push_back({true, named(under) + " now lies inside " + named(id) +
                             " and no longer shows: it did not rest on it, so it stayed where it "
                             "was (Ctrl+Z undoes the change)"});
  return out;
}

}  // namespace strata::ui
