// ProcessGroup over MPI (see README.md): the plugin's one entry point is
// strataOpenMpiProcessGroup, looked up by app/process_group_plugin.cpp.
#include <mpi.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>

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

class MpiProcessGroup : public ProcessGroup {
 public:
  MpiProcessGroup() {
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
  }
  ~MpiProcessGroup() override { MPI_Finalize(); }

  int rank() const override { return rank_; }
  int size() const override { return size_; }
  int rankOnHost() const override { return rankOnHost_; }
  std::string description() const override {
    char version[MPI_MAX_LIBRARY_VERSION_STRING];
    int length = 0;
    MPI_Get_library_version(version, &length);
    std::string v(version, size_t(length));
    v = v.substr(0, v.find_first_of(",\n"));
    return "MPI (" + v + "), " + std::to_string(size_) + " processes";
  }

  void send(int to, int tag, const void* data, size_t bytes) override {
    const uint64_t size = bytes;
    check(MPI_Send(&size, 8, MPI_BYTE, to, tag, MPI_COMM_WORLD), "send");
    const auto* p = static_cast<const uint8_t*>(data);
    for (size_t at = 0; at < bytes; at += kChunk) {
      const int n = int(std::min(kChunk, bytes - at));
      check(MPI_Send(p + at, n, MPI_BYTE, to, kChunkTag, MPI_COMM_WORLD), "send");
    }
  }

  bool receive(Message* out, bool wait) override {
    MPI_Status status;
    if (wait) {
      check(MPI_Probe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &status), "probe");
    } else {
      int flag = 0;
      check(MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &status), "probe");
      if (!flag) return false;
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

  void abort(int code) override { MPI_Abort(MPI_COMM_WORLD, code); }

 private:
  int rank_ = 0, size_ = 1, rankOnHost_ = 0;
};

}  // namespace
}  // namespace strata

// Initialises MPI (FUNNELED) and returns the group of MPI_COMM_WORLD, or null with the reason
// in error (at most errorSize bytes, terminated).
extern "C" __attribute__((visibility("default"))) strata::ProcessGroup* strataOpenMpiProcessGroup(
    int* argc, char*** argv, char* error, size_t errorSize) {
  int provided = 0;
  if (MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS) {
    std::snprintf(error, errorSize, "MPI_Init_thread failed");
    return nullptr;
  }
  if (provided < MPI_THREAD_FUNNELED) {
    std::snprintf(error, errorSize, "the MPI library offers no MPI_THREAD_FUNNELED");
    MPI_Finalize();
    return nullptr;
  }
  try {
    return new strata::MpiProcessGroup();
  } catch (const std::exception& e) {
    std::snprintf(error, errorSize, "%s", e.what());
    return nullptr;
  }
}
