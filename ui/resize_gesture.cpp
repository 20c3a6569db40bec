#include "ui/resize_gesture.h"

#include <algorithm>

#include "engine/kinds/node_kinds.h"

namespace strata::ui {

void ResizeGesture::begin(const NodePtr& tree, uint64_t gestureSerial) {
  if (start == tree && serial == gestureSerial) return;
  start = tree;
  serial = gestureSerial;
  following.clear();
  said.clear();
}

ResizeStep followResize(Document& document, ResizeGesture& gesture, NodeId id,
                        const std::vector<NodeId>& excluded) {
  ResizeStep step;
  const NodePtr& start = gesture.start;
  const Transform t = keptResting(start, document.root(), id, &step.rest);
  if (step.rest.moved) document.setTransform(id, t);
  step.following = resizeFollowers(start, document.root(), id, excluded);
  for (const ResizeFollower& f : step.following.followers) {
    document.setTransform(f.id, f.transform);
    // Its parameters for this frame, from where the gesture began: a stretch one frame put into
    // them and the next into the scale counted twice (a review).
    if (f.params)
      document.setParams(f.id, *f.params);
    else if (const NodePtr at = findNode(start, f.id); at && isPrimitive(at->kind))
      document.setParams(f.id, at->params);
  }
  const auto earlier = gesture.following.find(id);
  step.firstFrame = earlier == gesture.following.end();
  // Whether another part the gesture resizes has `part` among its followers (this frame's, or
  // the last one's where it comes later in this frame): that one places it.
  const auto followsAnother = [&](NodeId part) {
    for (const auto& [other, following] : gesture.following)
      if (other != id)
        for (const ResizeFollower& f : following.followers)
          if (f.id == part) return true;
    return false;
  };
  if (!step.firstFrame) {
    const std::vector<ResizeFollower>& now = step.following.followers;
    for (const ResizeFollower& was : earlier->second.followers)
      if (std::none_of(now.begin(), now.end(),
                       [&](const ResizeFollower& f) { return f.id == was.id; }) &&
          !followsAnother(was.id))
        if (const NodePtr at = findNode(start, was.id)) {
          document.setTransform(was.id, at->transform);
          if (isPrimitive(at->kind)) document.setParams(was.id, at->params);
        }
  }
  gesture.following[id] = step.following;
  return step;
}

}  // namespace strata::ui
