// What else changes when a part's size changes: the parts resting on it, the parts built into it
// (a hub standing through a plate, a rounded edge along it) and the cutters through or into it.
// A base plate made thicker grew from the ground, burying the ribs that stood on it and the hub
// that stood through it, and leaving its mounting holes blind, without a word (artists' tests).
// Plain engine types, no GL; any thread (the trees are immutable).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "engine/document/node.h"
#include "engine/kinds/primitives.h"

namespace strata::ui {

struct ResizeFollower {
  enum class Why {
    Moved,      // moved as far as the face it rests on or lies in (or the part it belongs to)
    Stretched,  // its ends moved with the faces it passes: lengthened or shortened with it
  };
  NodeId id = 0;
  Transform transform;                    // its transform for `after` (its parent's frame)
  std::optional<PrimitiveParams> params;  // its parameters where the stretch went into them
  Why why = Why::Moved;
  bool cuts = false;  // it takes material away (a hole, a pocket)
};

// Part `id` changed size from the tree `before` to `after` (a size or a radius typed, a scale;
// `after` already keeps it where it rested, keptResting; nothing else changed between the two).
// What follows it, each with its transform (and parameters) for `after`: its own in `before`
// changed (a gizmo drag asks from the tree where the drag began, every frame). All in world
// boxes, along each world axis, the "faces" being those of the part's world box:
// - Resting: a visible leaf that adds material whose own bottom (the middle of the bottom of its
//   own box, the side a part dropped on a surface sets on it) lay on a face (within a
//   ten-thousandth of the larger box's size), its own -z pointing into it (within 2 degrees):
//   moved as far as that face, along its axis.
// - Built in: a visible leaf that adds material, overlaps the part's box and lies within it
//   along at least one axis, and reaches past both ends of it along one axis at most (the hub,
//   within the plate's length and width, past it along z; not the plate when the hub is resized:
//   it reaches past the hub along x and y; not the plate a boss is sunk into):
//   along each axis where it passes both faces, its ends move as far as the faces they pass (the
//   hub still stands as far out of the plate's top); where it crosses one face, it moves as far
//   as that face; within the box, it stays.
// - Cutters: a visible leaf on the cut side of a difference whose base holds the part, overlapping
//   its box: the same as a part built in (a hole through stays through, passing each face by as
//   much as before; a pocket moves with its face).
// A part that follows is followed in turn by what rests on it or is built into it, and by its
// cutters (a cap on a pedestal on a plate made thicker; an o-ring around the pedestal; a hole
// through the hub). A part that moved whole takes what lies in it along whole.
// A lengthening goes into the part's parameters where its own axis lies along the world axis and
// it has a length there (a box's size, a cylinder's height), else into its scale.
// Nothing where `id` takes material away (a cutter resized) or shows nothing. Parts in
// `excluded` (the rest of a selection changed by the same edit) and inside `id` are left out.
struct ResizeFollowing {
  std::vector<ResizeFollower> followers;
  // Parts that would follow but cannot exactly: turned other than by quarter turns against the
  // world (a stretch along a world axis would shear them), or in a pattern whose copies, each
  // following these rules from its own box, would not all be moved so by one change of the part.
  // Left as they were.
  std::vector<NodeId> leftAlone;
  // Parts that add material, follow nothing and now lie inside the part's box (within a
  // ten-thousandth of its size), where they did not before. Left as they are, for the log.
  std::vector<NodeId> buried;
};
ResizeFollowing resizeFollowers(const NodePtr& before, const NodePtr& after, NodeId id,
                                const std::vector<NodeId>& excluded = {});

// A primitive scaled (the gizmo's scale of one part) as a change of its size instead, where its
// parameters can hold it: `now` (its transform, scaled from `start`'s) gets `start`'s scale
// back and `params` the size that scale gave (a box's size; a cylinder's or cone's radius where
// x and y scale alike, and height; a sphere's or torus's radii where all three do; a capsule's
// radius and length). A rounded box's corners stayed round when its size was typed and turned
// oval when the gizmo scaled it (an artist's test). A relation the new size breaks is fitted as
// the inspector fits it (fitPrimitiveRelations: a rounded box made thinner than twice its
// corners' radius gets a smaller radius), what was fitted in `fitted` (when given). False
// (nothing changed) where the scale cannot be held so: a part turned by it (a mirroring), a
// circle made an ellipse, or a size its parameters refuse.
bool scaleIntoSize(const Node& start, Transform* now, PrimitiveParams* params,
                   std::vector<FittedParam>* fitted = nullptr);

// What the log says of parameters fitted to a change of part `n`'s `changed` (a parameter's label,
// "size"), lengths in `unit` ("mm", or "" for none): "\"base plate\": corner radius made 1.999 mm
// to fit the size (rounded box; undo gives the old one back)". `dragging`: said at the first
// frame of a drag that fitted it, whose value the drag goes on changing: "made smaller ... as
// the size is dragged (... it comes back as the size does ...)".
std::string fittedParamsMessage(const Node& n, const std::vector<FittedParam>& fitted,
                                const std::string& changed, const std::string& unit,
                                bool dragging = false);

// What the log says of `following` for part `id` (names as in `root`), in order: "\"base
// plate\" changed size: \"rib\" moved with it; \"hub\" resized with it; \"mounting hole\" and
// \"slot\" kept through it" (up to three names a clause, else two and "and N
// more"), then a warning for each part left alone and each part buried. None when nothing
// followed.
struct FollowMessage {
  bool warning = false;
  std::string text;
};
std::vector<FollowMessage> resizeFollowingMessages(const NodePtr& root, NodeId id,
                                                   const ResizeFollowing& following);

}  // namespace strata::ui
