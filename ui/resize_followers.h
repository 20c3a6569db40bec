// What else moves when a part's size changes: the parts resting on it and the cutters through or
// into it. A base plate made thicker grew from the ground, burying the ribs that stood on it and
// leaving its mounting holes blind, without a word (an artist's test). Plain engine types, no
// GL; any thread (the trees are immutable).
#pragma once

#include <string>
#include <vector>

#include "engine/document/node.h"

namespace strata::ui {

struct ResizeFollower {
  enum class Why {
    RestsOn,      // rests on the resized part (or on a part that moved): moved with it
    CutsThrough,  // went through it from face to face: lengthened to stay through
    CutsInto,     // a pocket, a notch or a hole inside it: moved with its face (or the part)
  };
  NodeId id = 0;
  Transform transform;  // its transform in `after` (its parent's frame)
  Why why = Why::RestsOn;
};

// Part `id` changed size from the tree `before` to `after` (a size or a radius typed, a scale;
// `after` already keeps it where it rested, keptResting; nothing else changed between the two).
// What follows it, each with its transform for `after` (its transform in `before` moved: a gizmo
// drag asks from the tree where the drag began, every frame), in tree order:
// - Parts resting on it: a visible leaf that adds material whose own bottom (the middle of the
//   bottom of its own box, the side a part dropped on a surface sets on it) lay on a face of the
//   part's world box (within a ten-thousandth of the larger box's size), its own -z pointing into
//   that face (within 2 degrees): moved along the face's axis as far as the face moved. Parts
//   resting on a part that moved move as far, and so on.
// - Cutters of it and of the parts that moved (a visible leaf on the cut side of a difference
//   whose base holds the part) whose box overlaps the part's box, along each world axis: where
//   the cutter went through the box from face to face and the box now passes it, lengthened on
//   that side by as much as it passed the face before (a hole through stays through; one that
//   still passes is left); where it crossed one face only (a pocket, a notch), moved as far as
//   that face; inside the box, moved to the same fraction of it. A part that moved takes the
//   cutters in it along.
// Nothing where `id` takes material away (a cutter resized) or shows nothing. Parts in
// `excluded` (the rest of a selection changed by the same edit) and inside `id` are left out.
struct ResizeFollowing {
  std::vector<ResizeFollower> followers;
  // Cutters turned other than by quarter turns against the world, which a lengthening along a
  // world axis would shear: left as they were.
  std::vector<NodeId> leftTurned;
  // Parts that add material, rest on nothing that moved and now lie inside the part's box
  // (within a ten-thousandth of its size), where they did not before: a hub standing on the
  // ground beside a plate made thicker than it is tall. Left as they are, for the log to say.
  std::vector<NodeId> buried;
};
ResizeFollowing resizeFollowers(const NodePtr& before, const NodePtr& after, NodeId id,
                                const std::vector<NodeId>& excluded = {});

// What the log says of `following` for part `id` (names as in `root`), in order: "\"base
// plate\" changed size: \"rib\" moved with it; \"mounting hole\" and \"slot\" lengthened to stay
// through it; \"pocket\" moved with its face" (up to three names a clause, else two and "and N
// more"), then a warning for each cutter left turned and each part buried. None when nothing
// followed.
struct FollowMessage {
  bool warning = false;
  std::string text;
};
std::vector<FollowMessage> resizeFollowingMessages(const NodePtr& root, NodeId id,
                                                   const ResizeFollowing& following);

}  // namespace strata::ui
