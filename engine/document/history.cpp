#include "engine/document/history.h"

namespace strata {

void History::record(const DocumentState& before, const std::string& label) {
  redo_.clear();
  if (depth_ > 0 && recordedInInteraction_) return;
  undo_.push_back(Step{before, label});
  if (depth_ > 0) recordedInInteraction_ = true;
  if (undo_.size() > limit_) undo_.erase(undo_.begin());
}

DocumentState History::undo(const DocumentState& current) {
  depth_ = 0;
  recordedInInteraction_ = false;
  Step step = undo_.back();
  undo_.pop_back();
  redo_.push_back(Step{current, step.label});
  return step.state;
}

DocumentState History::redo(const DocumentState& current) {
  depth_ = 0;
  recordedInInteraction_ = false;
  Step step = redo_.back();
  redo_.pop_back();
  undo_.push_back(Step{current, step.label});
  return step.state;
}

void History::beginInteraction() {
  if (depth_++ == 0) recordedInInteraction_ = false;
}

void History::endInteraction() {
  if (depth_ == 0) return;
  if (--depth_ == 0) recordedInInteraction_ = false;
}

std::optional<DocumentState> History::cancelInteraction() {
  const bool recorded = depth_ > 0 && recordedInInteraction_ && !undo_.empty();
  depth_ = 0;
  recordedInInteraction_ = false;
  if (!recorded) return std::nullopt;
  DocumentState before = undo_.back().state;
  undo_.pop_back();
  return before;
}

void History::clear() {
  undo_.clear();
  redo_.clear();
  depth_ = 0;
  recordedInInteraction_ = false;
}

}  // namespace strata
