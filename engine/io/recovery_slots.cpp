// See recovery_slots.h.
#include "engine/io/recovery_slots.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <ctime>
#include <filesystem>

#include "engine/io/user_files.h"
#include "engine/util/error.h"

namespace strata {
namespace {
namespace fs = std::filesystem;

constexpr const char* kExtension = ".strata.json";

std::string lockPath(const std::string& recoveryPath) {
  return recoveryPath + ".lock";
}

// Opens (creating) `path` and takes its exclusive lock without waiting: the descriptor, or -1
// where another process holds it (or the file cannot be opened).
int tryLock(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0600);
  if (fd < 0) return -1;
  int result;
  while ((result = ::flock(fd, LOCK_EX | LOCK_NB)) != 0 && errno == EINTR) {
  }
  if (result != 0) {
    ::close(fd);
    return -1;
  }
  return fd;
}

bool endsWith(const std::string& s, const std::string& end) {
  return s.size() >= end.size() && s.compare(s.size() - end.size(), end.size(), end) == 0;
}

// The offer of `path` where its lock is free (claimed: held from now on); none otherwise.
bool claim(const std::string& path, std::vector<RecoveryOffer>* offers) {
  const int fd = tryLock(lockPath(path));
  if (fd < 0) return false;
  std::error_code ec;
  if (!fs::exists(path, ec)) {  // gone meanwhile (its finder recovered it)
    ::close(fd);
    return false;
  }
  offers->push_back(RecoveryOffer{path, std::shared_ptr<int>(new int(fd), [](int* d) {
                                    ::close(*d);
                                    delete d;
                                  })});
  return true;
}

fs::file_time_type writtenAt(const std::string& path) {
  std::error_code ec;
  const auto t = fs::last_write_time(path, ec);
  return ec ? fs::file_time_type::min() : t;
}

}  // namespace

std::string defaultRecoveryDir() {
  const std::string dir = userDataDir();
  return dir.empty() ? "" : dir + "/recovery";
}

RecoverySlot::RecoverySlot(const std::string& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw Error(dir + ": cannot create the recovery folder: " + ec.message());
  // A name no other process uses: this process's id and a count (a process may hold several:
  // tests), skipping names whose lock someone holds or whose file an orphan left.
  static std::atomic<int> next{0};
  for (int attempt = 0; attempt < 1000; ++attempt) {
    const std::string path =
        (fs::path(dir) / (std::to_string(::getpid()) + "-" + std::to_string(next++) + kExtension))
            .string();
    if (fs::exists(path, ec)) continue;  // an orphan of an earlier process with this id
    const int fd = tryLock(lockPath(path));
    if (fd < 0) continue;
    // Still the file at that name: another editor clearing stale locks may have removed it
    // between its creation and the lock (this editor would then hold a lock nobody sees).
    struct stat held {
    }, named{};
    if (::fstat(fd, &held) != 0 || ::stat(lockPath(path).c_str(), &named) != 0 ||
        held.st_ino != named.st_ino || held.st_dev != named.st_dev) {
      ::close(fd);
      continue;
    }
    path_ = path;
    lock_ = fd;
    return;
  }
  throw Error(dir + ": no free recovery slot (1000 names tried)");
}

RecoverySlot::~RecoverySlot() {
  removeRecoveryFile(path_);
  std::error_code ec;
  fs::remove(lockPath(path_), ec);  // while still held: no other process takes it meanwhile
  ::close(lock_);
}

std::vector<RecoveryOffer> claimOrphanedRecoveries(const std::string& dir,
                                                   const std::string& legacyPath) {
  std::vector<RecoveryOffer> offers;
  std::error_code ec;
  if (!dir.empty() && fs::is_directory(dir, ec)) {
    std::vector<std::string> staleLocks;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
      const std::string path = it->path().string();
      std::error_code entry;  // its own: the iteration's stops the loop
      if (endsWith(path, std::string(kExtension) + ".lock") &&
          !fs::exists(path.substr(0, path.size() - 5), entry))
        staleLocks.push_back(path);
      if (!it->is_regular_file(entry) || !endsWith(path, kExtension)) continue;
      claim(path, &offers);
    }
    // The locks of editors that ended without a recovery file to leave (killed with nothing
    // unsaved): removed where nobody holds them.
    for (const std::string& lock : staleLocks) {
      const int fd = tryLock(lock);
      if (fd < 0) continue;
      fs::remove(lock, ec);
      ::close(fd);
    }
  }
  if (!legacyPath.empty() && fs::exists(legacyPath, ec)) claim(legacyPath, &offers);
  std::stable_sort(offers.begin(), offers.end(),
                   [](const RecoveryOffer& a, const RecoveryOffer& b) {
                     return writtenAt(a.path) > writtenAt(b.path);
                   });
  return offers;
}

void forgetRecovery(const RecoveryOffer& offer) {
  removeRecoveryFile(offer.path);
  std::error_code ec;
  fs::remove(lockPath(offer.path), ec);
}

std::string discardRecovery(const RecoveryOffer& offer, const std::string& dir) {
  const fs::path kept = fs::path(dir) / "discarded";
  std::error_code ec;
  fs::create_directories(kept, ec);
  if (ec) return "";
  char stamp[32] = "";
  const std::time_t now = std::time(nullptr);
  std::tm local{};
  if (localtime_r(&now, &local)) std::strftime(stamp, sizeof(stamp), "%Y%m%d-%H%M%S", &local);
  const std::string name = std::string(stamp) + "-" + fs::path(offer.path).filename().string();
  const fs::path to = kept / name;
  fs::rename(offer.path, to, ec);
  if (ec) return "";
  fs::rename(offer.path + ".origin", to.string() + ".origin", ec);
  fs::remove(lockPath(offer.path), ec);
  // The newest kKeptDiscards (names start with their time).
  std::vector<std::string> discarded;
  for (fs::directory_iterator it(kept, ec), end; !ec && it != end; it.increment(ec))
    if (endsWith(it->path().string(), kExtension)) discarded.push_back(it->path().string());
  std::sort(discarded.begin(), discarded.end(), std::greater<>());
  for (size_t i = size_t(kKeptDiscards); i < discarded.size(); ++i) {
    fs::remove(discarded[i], ec);
    fs::remove(discarded[i] + ".origin", ec);
  }
  return to.string();
}

}  // namespace strata
