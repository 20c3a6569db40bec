// ProcessGroup over MPI (see README.md): the plugin's one entry point is
// strataOpenMpiProcessGroup, looked up by app/process_group_plugin.cpp.
#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <cstring>
#include <deque>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "engine/util/process_group.h"

namespace strata {
namespace {

constexpr size_t kChunk = size_t(1) << 30;  // MPI counts are int
constexpr int kChunkTag = 1024;             // tags of the chunks after a header

void check(int status, const char* what) {
  if (status == MPI_SUCCESS) return;
  char text[MPI_MAX_ERROR_STRING];
  int length = 0;
  MPI_Error_string(status, text, &length);
  throw std::runtime_error(std::string("MPI: ") + what + ": " + std::string(text, size_t(length)));
}

// Every MPI call is made under mutex_ (MPI_THREAD_SERIALIZED): by the thread that uses the
// group and, for posted messages, by a delivery thread that tests them until they complete
// (MPI moves a large message only while some call of the process drives it, and the thread
// that uses the group is busy contouring between its calls). Messages are only ever started by
// the thread that uses the group, in the order given, so MPI's ordering between two processes
// holds for sent and posted messages alike. With only MPI_THREAD_FUNNELED, posting sends at
// once.
class MpiProcessGroup : public ProcessGroup {
 public:
  explicit MpiProcessGroup(bool deliveryThread) {
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
    // Errors come back as codes (check above) instead of ending the job without a word.
    MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
    MPI_Comm host;
    if (MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &host) ==
        MPI_SUCCESS) {
      MPI_Comm_rank(host, &rankOnHost_);
      MPI_Comm_free(&host);
    }
    if (deliveryThread) delivery_ = std::thread([this] { deliver(); });
  }
  ~MpiProcessGroup() override {
    try {
      flush();
    } catch (const std::exception&) {
      // MPI_Finalize below reports what is still pending.
    }
    if (delivery_.joinable()) {
      {
        std::lock_guard<std::mutex> lock(mutex_);
        stopping_ = true;
      }
      changed_.notify_all();
      delivery_.join();
    }
    MPI_Finalize();
  }

  int rank() const override { return rank_; }
  int size() const override { return size_; }
  int rankOnHost() const override { return rankOnHost_; }
  std::string description() const override {
    char version[MPI_MAX_LIBRARY_VERSION_STRING];
    int length = 0;
    std::lock_guard<std::mutex> lock(mutex_);
    MPI_Get_library_version(version, &length);
    std::string v(version, size_t(length));
    v = v.substr(0, v.find_first_of(",\n"));
    return "MPI (" + v + "), " + std::to_string(size_) + " processes";
  }

  void send(int to, int tag, const void* data, size_t bytes) override {
    const uint64_t size = bytes;
    std::lock_guard<std::mutex> lock(mutex_);
    check(MPI_Send(&size, 8, MPI_BYTE, to, tag, MPI_COMM_WORLD), "send");
    const auto* p = static_cast<const uint8_t*>(data);
    for (size_t at = 0; at < bytes; at += kChunk) {
      const int n = int(std::min(kChunk, bytes - at));
      check(MPI_Send(p + at, n, MPI_BYTE, to, kChunkTag, MPI_COMM_WORLD), "send");
    }
  }

  using ProcessGroup::post;
  void post(int to, int tag, const void* data, size_t bytes,
            std::shared_ptr<const void> owner) override {
    if (!delivery_.joinable()) {
      send(to, tag, data, bytes);
      return;
    }
    auto message = std::make_unique<Posted>();
    message->size = bytes;
    message->owner = std::move(owner);
    {
      std::lock_guard<std::mutex> lock(mutex_);
      throwIfFailed();
      MPI_Request request;
      check(MPI_Isend(&message->size, 8, MPI_BYTE, to, tag, MPI_COMM_WORLD, &request), "post");
      message->requests.push_back(request);
      const auto* p = static_cast<const uint8_t*>(data);
      for (size_t at = 0; at < bytes; at += kChunk) {
        const int n = int(std::min(kChunk, bytes - at));
        // MPI_Isend takes a non-const buffer in older headers; it only reads it.
        check(MPI_Isend(const_cast<uint8_t*>(p + at), n, MPI_BYTE, to, kChunkTag, MPI_COMM_WORLD,
                        &request),
              "post");
        message->requests.push_back(request);
      }
      posted_.push_back(std::move(message));
    }
    changed_.notify_all();
  }

  void flush() override {
    std::unique_lock<std::mutex> lock(mutex_);
    changed_.wait(lock, [&] { return posted_.empty() || !failed_.empty(); });
    throwIfFailed();
  }

  void receiveInto(int from, int tag, void* data, size_t bytes) override {
    std::unique_lock<std::mutex> lock(mutex_);
    for (;;) {
      int flag = 0;
      check(MPI_Iprobe(from, tag, MPI_COMM_WORLD, &flag, MPI_STATUS_IGNORE), "probe");
      if (flag) break;
      lock.unlock();  // not a blocking probe: the delivery thread needs the lock meanwhile
      std::this_thread::sleep_for(std::chrono::microseconds(100));
      lock.lock();
    }
    uint64_t size = 0;
    check(MPI_Recv(&size, 8, MPI_BYTE, from, tag, MPI_COMM_WORLD, MPI_STATUS_IGNORE), "receive");
    if (size != bytes)
      throw std::runtime_error("MPI: process " + std::to_string(from) + " sent " +
                               std::to_string(size) + " bytes where " + std::to_string(bytes) +
                               " were expected");
    auto* p = static_cast<uint8_t*>(data);
    for (size_t at = 0; at < bytes; at += kChunk) {
      const int n = int(std::min(kChunk, bytes - at));
      check(MPI_Recv(p + at, n, MPI_BYTE, from, kChunkTag, MPI_COMM_WORLD, MPI_STATUS_IGNORE),
            "receive");
    }
  }

  bool receive(Message* out, bool wait) override {
    MPI_Status status;
    std::unique_lock<std::mutex> lock(mutex_);
    for (;;) {
      int flag = 0;
      check(MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &status), "probe");
      if (flag) break;
      if (!wait) return false;
      // Not a blocking probe: the delivery thread needs the lock meanwhile.
      lock.unlock();
      std::this_thread::sleep_for(std::chrono::microseconds(100));
      lock.lock();
    }
    // Messages from one rank arrive in order, so what a probe finds first is a header.
    const int source = status.MPI_SOURCE, tag = status.MPI_TAG;
    uint64_t size = 0;
    check(MPI_Recv(&size, 8, MPI_BYTE, source, tag, MPI_COMM_WORLD, MPI_STATUS_IGNORE), "receive");
    out->source = source;
    out->tag = tag;
    out->bytes.resize(size);
    for (size_t at = 0; at < size; at += kChunk) {
      const int n = int(std::min<uint64_t>(kChunk, size - at));
      check(MPI_Recv(out->bytes.data() + at, n, MPI_BYTE, source, kChunkTag, MPI_COMM_WORLD,
                     MPI_STATUS_IGNORE),
            "receive");
    }
    return true;
  }

  void abort(int code) override {
    std::lock_guard<std::mutex> lock(mutex_);  // the delivery thread may be in a call
    MPI_Abort(MPI_COMM_WORLD, code);
  }

 private:
  struct Posted {
    uint64_t size = 0;                  // the header, sent first
    std::shared_ptr<const void> owner;  // keeps the bytes until they are delivered
    std::vector<MPI_Request> requests;
  };

  void throwIfFailed() const {
    if (!failed_.empty()) throw std::runtime_error(failed_);
  }

  // The delivery thread: tests the posted messages (oldest first) until each completes, then
  // releases it; sleeps while none is pending.
  void deliver() {
    std::unique_lock<std::mutex> lock(mutex_);
    for (;;) {
      changed_.wait(lock, [&] { return stopping_ || !posted_.empty(); });
      if (posted_.empty()) return;  // stopping
      while (!posted_.empty() && failed_.empty()) {
        Posted& oldest = *posted_.front();
        int done = 0;
        const int status = MPI_Testall(int(oldest.requests.size()), oldest.requests.data(), &done,
                                       MPI_STATUSES_IGNORE);
        if (status != MPI_SUCCESS) {
          try {
            check(status, "delivering a posted message");
          } catch (const std::exception& e) {
            failed_ = e.what();
          }
        } else if (done) {
          posted_.pop_front();
          continue;
        }
        break;
      }
      changed_.notify_all();
      if (!failed_.empty()) return;
      if (!posted_.empty()) {
        lock.unlock();
        std::this_thread::sleep_for(std::chrono::microseconds(100));
        lock.lock();
      }
    }
  }

  int rank_ = 0, size_ = 1, rankOnHost_ = 0;
  mutable std::mutex mutex_;  // every MPI call; posted_, failed_, stopping_
  std::condition_variable changed_;
  std::deque<std::unique_ptr<Posted>> posted_;
  std::string failed_;  // a posted message's error, thrown by the next post or flush
  bool stopping_ = false;
  std::thread delivery_;
};

}  // namespace
}  // namespace strata

// Initialises MPI (SERIALIZED, else FUNNELED: posts then send at once) and returns the group of
// MPI_COMM_WORLD, or null with the reason in error (at most errorSize bytes, terminated).
extern "C" __attribute__((visibility("default"))) strata::ProcessGroup* strataOpenMpiProcessGroup(
    int* argc, char*** argv, char* error, size_t errorSize) {
  int provided = 0;
  if (MPI_Init_thread(argc, argv, MPI_THREAD_SERIALIZED, &provided) != MPI_SUCCESS) {
    std::snprintf(error, errorSize, "MPI_Init_thread failed");
    return nullptr;
  }
  if (provided < MPI_THREAD_FUNNELED) {
    std::snprintf(error, errorSize, "the MPI library offers no MPI_THREAD_FUNNELED");
    MPI_Finalize();
    return nullptr;
  }
  try {
    return new strata::MpiProcessGroup(provided >= MPI_THREAD_SERIALIZED);
  } catch (const std::exception& e) {
    std::snprintf(error, errorSize, "%s", e.what());
    return nullptr;
  }
}
