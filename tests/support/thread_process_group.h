// A ProcessGroup of threads for tests: process k is the k-th of makeThreadGroup(n)'s groups,
// each used from its own thread. Messages go through per-process mailboxes; abort() makes every
// process's next or current receive throw GroupAborted.
#pragma once

#include <algorithm>
#include <condition_variable>
#include <cstring>
#include <deque>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

#include "engine/util/process_group.h"

namespace strata {

struct GroupAborted : std::runtime_error {
  GroupAborted() : std::runtime_error("the group was aborted") {}
};

namespace detail {
struct ThreadGroupShared {
  std::mutex mutex;
  std::condition_variable arrived;
  std::vector<std::deque<ProcessGroup::Message>> mailboxes;
  bool aborted = false;
};
}  // namespace detail

class ThreadProcessGroup : public ProcessGroup {
 public:
  ThreadProcessGroup(std::shared_ptr<detail::ThreadGroupShared> shared, int rank)
      : shared_(std::move(shared)), rank_(rank) {}
  int rank() const override { return rank_; }
  int size() const override { return int(shared_->mailboxes.size()); }
  int rankOnHost() const override { return rank_; }
  std::string description() const override {
    return "threads, " + std::to_string(size()) + " processes";
  }
  void send(int to, int tag, const void* data, size_t bytes) override {
    Message m;
    m.source = rank_;
    m.tag = tag;
    const auto* p = static_cast<const uint8_t*>(data);
    m.bytes.assign(p, p + bytes);
    std::lock_guard<std::mutex> lock(shared_->mutex);
    shared_->mailboxes[size_t(to)].push_back(std::move(m));
    shared_->arrived.notify_all();
  }
  using ProcessGroup::post;
  void post(int to, int tag, const void* data, size_t bytes, std::shared_ptr<const void>) override {
    send(to, tag, data, bytes);  // copied: delivered at once
  }
  void receiveInto(int from, int tag, void* data, size_t bytes) override {
    std::unique_lock<std::mutex> lock(shared_->mutex);
    auto& box = shared_->mailboxes[size_t(rank_)];
    auto match = [&] {
      return std::find_if(box.begin(), box.end(),
                          [&](const Message& m) { return m.source == from && m.tag == tag; });
    };
    shared_->arrived.wait(lock, [&] { return shared_->aborted || match() != box.end(); });
    if (shared_->aborted) throw GroupAborted();
    auto it = match();
    if (it->bytes.size() != bytes)
      throw std::runtime_error("receiveInto: the message has " + std::to_string(it->bytes.size()) +
                               " bytes, not " + std::to_string(bytes));
    if (bytes) std::memcpy(data, it->bytes.data(), bytes);
    box.erase(it);
  }
  void flush() override {}  // a post is delivered at once
  bool receive(Message* out, bool wait) override {
    std::unique_lock<std::mutex> lock(shared_->mutex);
    auto& box = shared_->mailboxes[size_t(rank_)];
    if (wait) shared_->arrived.wait(lock, [&] { return shared_->aborted || !box.empty(); });
    if (shared_->aborted) throw GroupAborted();
    if (box.empty()) return false;
    *out = std::move(box.front());
    box.pop_front();
    return true;
  }
  void abort(int) override {
    {
      std::lock_guard<std::mutex> lock(shared_->mutex);
      shared_->aborted = true;
      shared_->arrived.notify_all();
    }
    throw GroupAborted();
  }

 private:
  std::shared_ptr<detail::ThreadGroupShared> shared_;
  int rank_;
};

inline std::vector<std::unique_ptr<ProcessGroup>> makeThreadGroup(int processes) {
  auto shared = std::make_shared<detail::ThreadGroupShared>();
  shared->mailboxes.resize(size_t(processes));
  std::vector<std::unique_ptr<ProcessGroup>> groups;
  for (int k = 0; k < processes; ++k)
    groups.push_back(std::make_unique<ThreadProcessGroup>(shared, k));
  return groups;
}

}  // namespace strata
