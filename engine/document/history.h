// Undo and redo as whole-document snapshots. A snapshot is a shared, immutable Scene, so keeping
// one per step costs only the nodes an edit copied (the path to the root), not the document.
//
// Coalescing: between beginInteraction() and endInteraction() (a drag in the viewport, a
// slider held down in the inspector) only the first edit records a step, so the whole gesture
// undoes at once.
//
// Threads: UI thread only.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "engine/document/scene.h"

namespace strata {

// One state of the document: the scene and a revision number that identifies it (used to tell
// whether the document differs from what was last saved).
struct DocumentState {
  std::shared_ptr<const Scene> scene;
  uint64_t revision = 0;
};

class History {
 public:
  explicit History(size_t limit = 500) : limit_(limit) {}

  // Records that `before` is about to be replaced by an edit called `label`: it becomes the
  // state undo returns to, and the redo steps are dropped. Inside an interaction only the first
  // edit records; later ones extend that step.
  void record(const DocumentState& before, const std::string& label);

  bool canUndo() const { return !undo_.empty(); }
  bool canRedo() const { return !redo_.empty(); }
  // The label of the step undo or redo would revert or repeat ("" when none).
  std::string undoLabel() const { return undo_.empty() ? "" : undo_.back().label; }
  std::string redoLabel() const { return redo_.empty() ? "" : redo_.back().label; }

  // Returns the state to restore and remembers `current` for the opposite direction. Ends any
  // open interaction first. Call only when canUndo() / canRedo().
  DocumentState undo(const DocumentState& current);
  DocumentState redo(const DocumentState& current);

  // Interactions nest; the step closes when the outermost one ends.
  void beginInteraction();
  void endInteraction();
  // Ends every open interaction and forgets its step: returns the state before its first edit
  // (to restore), or nothing when it recorded none. The history is then as it was before the
  // interaction: the redo steps its first edit dropped, and the oldest step the limit dropped,
  // come back (a drag cancelled with Escape emptied redo: an artist's test).
  std::optional<DocumentState> cancelInteraction();
  bool interacting() const { return depth_ > 0; }
  // The state before the open interaction's first edit (where a drag began), or null when no
  // interaction is open or it has recorded no edit yet. Valid until the next call that changes
  // the history.
  // The number of the last interaction begun (outermost ones; numbered across all histories of
  // the process, 0 before the first): tells one drag from the next that began from the same
  // state (a drag, an undo, and a drag again), in this document or another.
  uint64_t interactionsBegun() const { return interactionsBegun_; }
  const DocumentState* interactionStart() const {
    return depth_ > 0 && recordedInInteraction_ && !undo_.empty() ? &undo_.back().state : nullptr;
  }

  void clear();
  size_t undoSteps() const { return undo_.size(); }
  size_t redoSteps() const { return redo_.size(); }

 private:
  struct Step {
    DocumentState state;
    std::string label;
  };
  std::vector<Step> undo_;
  std::vector<Step> redo_;
  size_t limit_;
  int depth_ = 0;
  uint64_t interactionsBegun_ = 0;
  bool recordedInInteraction_ = false;
  // What the open interaction's first edit dropped: the redo steps, and the oldest undo step
  // where the limit was reached. Given back by cancelInteraction, forgotten when it ends.
  std::vector<Step> redoBeforeInteraction_;
  std::optional<Step> oldestBeforeInteraction_;
};

}  // namespace strata
