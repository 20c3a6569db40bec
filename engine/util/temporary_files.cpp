#include "engine/util/temporary_files.h"

#include <dirent.h>
#include <pthread.h>
#include <sys/random.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstring>
#include <mutex>
#include <random>
#include <utility>

#include "engine/util/atomic_file.h"
#include "engine/util/error.h"

namespace strata {
namespace atomic_detail {

// ---- Names ------------------------------------------------------------------------------------
//
// ".<name>.strata-<pid>-<16 hex digits>.tmp" (temporary) or ".old" (backup), beside the target.

namespace {

const char* suffixOf(Kind kind) {
  return kind == Kind::Temporary ? ".tmp" : ".old";
}

constexpr size_t kMaxNameBytes = 255;  // NAME_MAX of Linux file systems
constexpr size_t kRandomDigits = 16;

// ".<name>.strata-": what every temporary and backup file name of the target begins with. The
// name is shortened so that the longest file name (a 10-digit pid) stays within kMaxNameBytes.
std::string namePrefix(const std::string& name) {
  const size_t fixed = 1 + std::strlen(".strata-") + 10 + 1 + kRandomDigits + 4;
  return "." + name.substr(0, kMaxNameBytes - fixed) + ".strata-";
}

// The pid in `entry` when it is "<prefix><pid>-<16 lower-case hex digits>.tmp" or ".old";
// 0 for any other name.
pid_t ownerOf(const std::string& entry, const std::string& prefix) {
  if (entry.size() <= prefix.size() || entry.compare(0, prefix.size(), prefix) != 0) return 0;
  size_t at = prefix.size();
  long long pid = 0;
  const size_t digitsBegin = at;
  while (at < entry.size() && entry[at] >= '0' && entry[at] <= '9' && at - digitsBegin < 10)
    pid = pid * 10 + (entry[at++] - '0');
  if (at == digitsBegin || pid <= 0 || pid > INT_MAX) return 0;
  if (at >= entry.size() || entry[at++] != '-') return 0;
  for (size_t i = 0; i < kRandomDigits; ++i, ++at) {
    if (at >= entry.size()) return 0;
    const char c = entry[at];
    if (!((c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'))) return 0;
  }
  const std::string rest = entry.substr(at);
  if (rest != suffixOf(Kind::Temporary) && rest != suffixOf(Kind::Backup)) return 0;
  return static_cast<pid_t>(pid);
}

std::mutex g_hooksMutex;
AtomicFileTestHooks g_hooks;

uint64_t nameRandom() {
  {
    std::lock_guard<std::mutex> lock(g_hooksMutex);
    if (g_hooks.random) return g_hooks.random();
  }
  uint64_t value = 0;
  if (::getrandom(&value, sizeof(value), 0) == static_cast<ssize_t>(sizeof(value))) return value;
  static std::atomic<uint64_t> counter{0};
  thread_local std::mt19937_64 engine(std::random_device{}());
  return engine() ^ counter.fetch_add(0x9E3779B97F4A7C15ull);
}

std::string freshName(const Target& target, Kind kind) {
  char random[kRandomDigits + 1];
  std::snprintf(random, sizeof(random), "%016llx", static_cast<unsigned long long>(nameRandom()));
  return target.folder + namePrefix(target.name) + std::to_string(::getpid()) + "-" + random +
         suffixOf(kind);
}

}  // namespace

Target splitTarget(const std::string& path) {
  const size_t slash = path.rfind('/');
  Target t;
  t.path = path;
  t.folder = slash == std::string::npos ? "" : path.substr(0, slash + 1);
  t.name = slash == std::string::npos ? path : path.substr(slash + 1);
  if (t.name.empty() || t.name == "." || t.name == "..") throw Error(path + ": not a file name");
  return t;
}

void removeLeftovers(const Target& target) {
  DIR* dir = ::opendir(target.folderToOpen().c_str());
  if (!dir) return;
  const std::string prefix = namePrefix(target.name);
  while (const dirent* entry = ::readdir(dir)) {
    const pid_t pid = ownerOf(entry->d_name, prefix);
    if (pid <= 0) continue;
    if (::kill(pid, 0) == 0 || errno != ESRCH) continue;  // alive, or not ours to judge (EPERM)
    ::unlinkat(::dirfd(dir), entry->d_name, 0);           // never a folder: unlinkat refuses
  }
  ::closedir(dir);
}

std::vector<std::string> leftoversOf(const Target& target) {
  std::vector<std::string> found;
  DIR* dir = ::opendir(target.folderToOpen().c_str());
  if (!dir) return found;
  const std::string prefix = namePrefix(target.name);
  while (const dirent* entry = ::readdir(dir))
    if (ownerOf(entry->d_name, prefix) > 0) found.push_back(target.folder + entry->d_name);
  ::closedir(dir);
  std::sort(found.begin(), found.end());
  return found;
}

bool hardLinksRefusedForTesting() {
  std::lock_guard<std::mutex> lock(g_hooksMutex);
  return g_hooks.refuseHardLinks;
}

// ---- Files in flight, as a signal handler sees them -------------------------------------------
//
// Each file this process creates (temporary or backup) holds a slot while it exists under its
// own name. abandonAtomicWritesForExit() removes the files of the slots in state kOpen. States:
//   kFree -> kClaimed (a writer, path being copied) -> kCreating (path complete; the file may
//   exist) -> kOpen (it exists) -> kFree (renamed or removed by the writer),
//   and kOpen -> kCleaning (the handler removes it; the slot stays taken until exit).
// A writer stores kCreating and then reads g_closing; the handler stores g_closing and then
// reads the states (both sequentially consistent), so a file is either never created or seen.

namespace {
enum SlotState : int { kFree, kClaimed, kCreating, kOpen, kCleaning };
constexpr int kSlots = 64;
constexpr size_t kSlotPathBytes = 4096;
}  // namespace

struct Slot {
  std::atomic<int> state{kFree};
  pid_t owner = 0;  // the process that registered it (a forked child leaves its parent's alone)
  char path[kSlotPathBytes] = {};
};
static_assert(std::atomic<int>::is_always_lock_free, "slot states must be lock-free");
static_assert(std::atomic<bool>::is_always_lock_free, "g_closing must be lock-free");

namespace {
Slot g_slots[kSlots];
std::atomic<bool> g_closing{false};  // set by abandonAtomicWritesForExit: no new files
std::atomic<int> g_renaming{0};      // threads inside a RenameSection
}  // namespace

std::unique_ptr<OwnedFile> OwnedFile::create(const Target& target, Kind kind,
                                             const std::function<int(const std::string&)>& create,
                                             int* error) {
  for (int attempt = 0; attempt < 100; ++attempt) {
    std::unique_ptr<OwnedFile> file(new OwnedFile(freshName(target, kind)));
    const int result = create(file->path_);
    if (result == 0) {
      file->settle();
      return file;
    }
    file->released_ = true;  // nothing of ours is there
    if (result != EEXIST && result != ELOOP && result != EINTR) {
      *error = result;
      return nullptr;
    }
  }
  *error = EEXIST;
  return nullptr;
}

OwnedFile::OwnedFile(std::string path) : path_(std::move(path)) {
  if (g_closing.load()) throw Cancelled();
  if (path_.size() < kSlotPathBytes) {
    for (Slot& slot : g_slots) {
      int expected = kFree;
      if (slot.state.compare_exchange_strong(expected, kClaimed)) {
        slot_ = &slot;
        break;
      }
    }
  }
  // Without a slot (64 files in flight, or a path of 4 KiB) a signal can leave the file behind,
  // as SIGKILL does; the next write of the target removes it.
  if (slot_) {
    std::memcpy(slot_->path, path_.c_str(), path_.size() + 1);
    slot_->owner = ::getpid();
    slot_->state.store(kCreating);
  }
  if (g_closing.load()) {
    freeSlot();
    throw Cancelled();
  }
}

OwnedFile::~OwnedFile() {
  if (!released_) ::unlink(path_.c_str());
  freeSlot();
}

void OwnedFile::release() {
  released_ = true;
  freeSlot();
}

void OwnedFile::settle() {
  if (!slot_) return;
  int expected = kCreating;
  slot_->state.compare_exchange_strong(expected, kOpen);
}

void OwnedFile::freeSlot() {
  if (!slot_) return;
  int state = slot_->state.load();
  while (state != kCleaning && !slot_->state.compare_exchange_weak(state, kFree)) {
  }
  slot_ = nullptr;
}

RenameSection::RenameSection() {
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGINT);
  sigaddset(&set, SIGTERM);
  sigaddset(&set, SIGHUP);
  pthread_sigmask(SIG_BLOCK, &set, &previous_);
  g_renaming.fetch_add(1);
  if (g_closing.load()) {
    leave();
    throw Cancelled();
  }
}

void RenameSection::leave() {
  if (left_) return;
  left_ = true;
  g_renaming.fetch_sub(1);
  pthread_sigmask(SIG_SETMASK, &previous_, nullptr);
}

}  // namespace atomic_detail

void abandonAtomicWritesForExit() noexcept {
  using namespace atomic_detail;
  g_closing.store(true);
  timespec deadline;
  clock_gettime(CLOCK_MONOTONIC, &deadline);
  deadline.tv_sec += 1;
  // Sleeps a millisecond; false once the deadline has passed.
  auto wait = [&deadline]() {
    timespec now;
    clock_gettime(CLOCK_MONOTONIC, &now);
    if (now.tv_sec > deadline.tv_sec ||
        (now.tv_sec == deadline.tv_sec && now.tv_nsec >= deadline.tv_nsec))
      return false;
    const timespec step{0, 1000000};
    nanosleep(&step, nullptr);
    return true;
  };
  while (g_renaming.load() > 0 && wait()) {
  }
  const pid_t self = ::getpid();
  for (Slot& slot : g_slots) {
    // A file being created right now is waited for; one only claimed never will be (its writer
    // reads g_closing after claiming). The wait ends at the deadline when the creating thread
    // is the one this handler interrupted.
    while (slot.state.load() == kCreating && slot.owner == self && wait()) {
    }
    int expected = kOpen;
    if (slot.state.compare_exchange_strong(expected, kCleaning) && slot.owner == self)
      ::unlink(slot.path);
  }
}

void setAtomicFileTestHooks(AtomicFileTestHooks hooks) {
  std::lock_guard<std::mutex> lock(atomic_detail::g_hooksMutex);
  atomic_detail::g_hooks = std::move(hooks);
}

}  // namespace strata
