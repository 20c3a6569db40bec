// The files an atomic write (engine/util/atomic_file.h) creates beside its target, temporary
// files and backups: their names, the removal of what dead writers left, and the registry through
// which a signal handler removes the ones in flight (abandonAtomicWritesForExit). Internal to
// engine/util/atomic_file.cpp; the contracts are documented in atomic_file.h.
#pragma once

#include <signal.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace strata {
namespace atomic_detail {

// A target path split into its folder ("" for the current one, else ending in '/') and name.
struct Target {
  std::string path;
  std::string folder;
  std::string name;
  std::string folderToOpen() const { return folder.empty() ? "." : folder; }
};

// Throws strata::Error when `path` names no file ("", "dir/", ".", "..").
Target splitTarget(const std::string& path);

enum class Kind { Temporary, Backup };  // ".tmp" and ".old"

// Removes the temporary and backup files of `target` whose writer no longer runs.
void removeLeftovers(const Target& target);

// The temporary and backup files of `target` by name, of any process (full paths, sorted).
std::vector<std::string> leftoversOf(const Target& target);

// True while a test makes backups act as on a file system without hard links.
bool hardLinksRefusedForTesting();

struct Slot;

// A file system entry this process created at a fresh name next to a target, registered for
// abandonAtomicWritesForExit. Removed by the destructor unless release() said it was renamed (or
// must stay).
class OwnedFile {
 public:
  // Creates an entry at a fresh name with create(name) (returning 0 or an errno value), trying
  // other names while the name exists (EEXIST: a file or link is there, never followed). Returns
  // null and sets *error for any other failure. Throws Cancelled once the process is exiting.
  static std::unique_ptr<OwnedFile> create(const Target& target, Kind kind,
                                           const std::function<int(const std::string&)>& create,
                                           int* error);
  OwnedFile(const OwnedFile&) = delete;
  OwnedFile& operator=(const OwnedFile&) = delete;
  ~OwnedFile();
  const std::string& path() const { return path_; }
  void release();

 private:
  explicit OwnedFile(std::string path);
  void settle();
  void freeSlot();

  std::string path_;
  Slot* slot_ = nullptr;
  bool released_ = false;
};

// Renames run inside one: SIGINT, SIGTERM and SIGHUP are blocked in this thread, and a handler
// on another thread waits for it before removing files (so a set is never left half renamed).
// Throws Cancelled once the process is exiting.
class RenameSection {
 public:
  RenameSection();
  RenameSection(const RenameSection&) = delete;
  RenameSection& operator=(const RenameSection&) = delete;
  ~RenameSection() { leave(); }

 private:
  void leave();
  sigset_t previous_;
  bool left_ = false;
};

}  // namespace atomic_detail
}  // namespace strata
