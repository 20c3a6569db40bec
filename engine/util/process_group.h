// A group of cooperating processes that exchange byte messages: the ranks of an MPI job
// (dist/mpi_process_group.cpp, loaded by the app only for --distributed), or threads standing
// in for them in tests. The engine sees this interface only, never MPI.
//
// Threads: each process uses its group from one thread (the MPI group may deliver posted
// messages from a thread of its own: MPI_THREAD_SERIALIZED).
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace strata {

class ProcessGroup {
 public:
  struct Message {
    int source = -1;
    int tag = 0;
    std::vector<uint8_t> bytes;
  };

  virtual ~ProcessGroup() = default;
  virtual int rank() const = 0;  // this process, 0 .. size() - 1
  virtual int size() const = 0;
  // This process's number among the group's processes on its host (0 ..): processes of one
  // host spread over its GPUs by it.
  virtual int rankOnHost() const = 0;
  // "MPI (Open MPI v4.1.4), 3 processes": for reports.
  virtual std::string description() const = 0;
  // Sends `bytes` bytes (any size) to process `to` with `tag` (>= 0, < 1024); returns once the
  // buffer may be reused. Messages from one process to another arrive in the order sent.
  virtual void send(int to, int tag, const void* data, size_t bytes) = 0;
  // Starts sending the `bytes` bytes at `data` to process `to` with `tag` and returns at once;
  // `owner` keeps them alive and unchanged until they are delivered, when the group lets it go
  // (a transport that cannot deliver in the background sends them before returning). Messages
  // from one process to another, sent or posted, arrive in the order they were given.
  virtual void post(int to, int tag, const void* data, size_t bytes,
                    std::shared_ptr<const void> owner) = 0;
  // The same for a byte array the group takes over.
  void post(int to, int tag, std::vector<uint8_t> bytes) {
    auto owner = std::make_shared<const std::vector<uint8_t>>(std::move(bytes));
    post(to, tag, owner->data(), owner->size(), owner);
  }
  // Returns once every message posted by this process was delivered; call it before this
  // process leaves the group.
  virtual void flush() = 0;
  // The next message from any process: false when none has arrived and !wait; with wait,
  // blocks until one does.
  virtual bool receive(Message* out, bool wait) = 0;
  // Receives the next message from process `from` with `tag` into the `bytes` bytes at `data`
  // (no copy in between: for large arrays whose size an earlier message gave); blocks until it
  // arrives. Throws std::runtime_error when it has another size.
  virtual void receiveInto(int from, int tag, void* data, size_t bytes) = 0;
  // Ends every process of the group now with `code` (the launcher reports it). Does not return
  // for MPI; in tests it throws GroupAborted on every process.
  virtual void abort(int code) = 0;
};

}  // namespace strata
