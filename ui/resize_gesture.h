// One frame of a gesture that resizes parts (a size field of the inspector dragged or typed, the
// gizmo's scale of one part): the part kept where it rested and what follows it
// (resize_followers.h), both worked out from the tree where the gesture began, not from the last
// frame. Asked frame by frame, a plate dragged thicker past a block floating over it and back
// caught the block and took it down onto its top (a review): the block did not follow when the
// drag began, so it must not follow in any frame of it.
// Threads: UI thread only (it edits the document).
#pragma once

#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include "engine/document/document.h"
#include "ui/resize_followers.h"
#include "ui/scene_queries.h"

namespace strata::ui {

// What a gesture has done so far; the caller keeps one per gesture (begin() at its start).
struct ResizeGesture {
  ResizeGesture() = default;
  // An edit of its own (no interaction open): it begins from `tree`.
  explicit ResizeGesture(NodePtr tree) : start(std::move(tree)) {}

  NodePtr start;  // the tree where the gesture began (immutable; shared)
  // What followed each part the gesture resized, as its last frame set it.
  std::map<NodeId, ResizeFollowing> following;
  // The parts the log has named for each part resized (for the caller's messages: said once a
  // gesture, again where a part joins those that follow).
  std::map<NodeId, std::vector<NodeId>> said;

  uint64_t serial = 0;  // the caller's name for the gesture (Document::interactionsBegun)

  // Starts afresh from `tree` unless the gesture `serial` already began from it.
  void begin(const NodePtr& tree, uint64_t gestureSerial);
};

// What one frame did to part `id`.
struct ResizeStep {
  Rest rest;                  // where `id` rested in `start`, and whether it was moved back onto it
  ResizeFollowing following;  // what follows it now
  bool firstFrame = true;     // the gesture's first frame for `id`
};

// Part `id` has been resized in `document` (its parameters or its scale set for this frame).
// Moves it back onto what it rested on in `gesture.start` (keptResting), sets on each part that
// follows it (resizeFollowers from `gesture.start`; `excluded`: the other parts the same edit
// changed) its transform and its parameters (those the stretch went into, else its own in
// `start`), and puts back as they were in `start` the parts that followed `id` in an earlier
// frame and no longer do (unless another part the gesture resizes has them among its followers:
// a selection of two plates). Throws what Document's setters throw (strata::Error).
ResizeStep followResize(Document& document, ResizeGesture& gesture, NodeId id,
                        const std::vector<NodeId>& excluded);

}  // namespace strata::ui
