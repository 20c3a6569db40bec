#include "engine/document/history.h"

namespace strata {

void History::record(const DocumentState& before, const std::string& label) {
  if (depth_ > 0 && recordedInInteraction_) {
    redo_.clear();
    return;
  }
  if (depth_ > 0) {
    redoBeforeInteraction_ = std::move(redo_);
    oldestBeforeInteraction_.reset();
  }
  redo_.clear();
  undo_.push_back(Step{before, label});
  if (depth_ > 0) recordedInInteraction_ = true;
  if (undo_.size() > limit_) {
    if (depth_ > 0) oldestBeforeInteraction_ = undo_.front();
    undo_.erase(undo_.begin());
  }
}

DocumentState History::undo(const DocumentState& current) {
  depth_ = 0;
  recordedInInteraction_ = false;
  redoBeforeInteraction_.clear();
  oldestBeforeInteraction_.reset();
  Step step = undo_.back();
  undo_.pop_back();
  redo_.push_back(Step{current, step.label});
  return step.state;
}

DocumentState History::redo(const DocumentState& current) {
  depth_ = 0;
  recordedInInteraction_ = false;
  redoBeforeInteraction_.clear();
  oldestBeforeInteraction_.reset();
  Step step = redo_.back();
  redo_.pop_back();
  undo_.push_back(Step{current, step.label});
  return step.state;
}

void History::beginInteraction() {
  if (depth_++ == 0) {
    recordedInInteraction_ = false;
    // Numbered across the process, not per history: a document opened anew starts a history
    // whose first drag must not take the number of the last one's (UI thread only).
    static uint64_t begun = 0;
    interactionsBegun_ = ++begun;
  }
}

void History::endInteraction() {
  if (depth_ == 0) return;
  if (--depth_ == 0) {
    recordedInInteraction_ = false;
    redoBeforeInteraction_.clear();
    oldestBeforeInteraction_.reset();
  }
}

std::optional<DocumentState> History::cancelInteraction() {
  const bool recorded = depth_ > 0 && recordedInInteraction_ && !undo_.empty();
  depth_ = 0;
  recordedInInteraction_ = false;
  std::vector<Step> redo = std::move(redoBeforeInteraction_);
  std::optional<Step> oldest = std::move(oldestBeforeInteraction_);
  redoBeforeInteraction_.clear();
  oldestBeforeInteraction_.reset();
  if (!recorded) return std::nullopt;
  DocumentState before = undo_.back().state;
  undo_.pop_back();
  redo_ = std::move(redo);
  if (oldest) undo_.insert(undo_.begin(), std::move(*oldest));
  return before;
}

void History::clear() {
  undo_.clear();
  redo_.clear();
  depth_ = 0;
  recordedInInteraction_ = false;
}

}  // namespace strata
