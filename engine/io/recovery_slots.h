// Crash recovery with several editors at once: each running editor writes its autosave into a
// slot of its own in the recovery folder ($XDG_DATA_HOME/strata/recovery, by default
// ~/.local/share/strata/recovery), "<pid>-<n>.strata.json" with its ".origin" (user_files.h:
// writeRecoveryFile) and a ".lock" that the editor holds locked (flock(2), exclusive) for as long
// as it runs. A clean exit removes its slot. A recovery file whose lock nobody holds (its editor
// crashed, or was killed; the kernel lets go of a dead process's locks) or that has no lock (the
// single file of earlier versions) is an orphan: its work is offered at the next start.
// Every editor used one file before: a second editor overwrote the first one's autosave, offered
// it as a crash while the first still ran, deleted it on a clean exit or on a Discard (an
// artist's test).
//
// Threads: any; each object's files are its own. Errors: strata::Error naming the file.
#pragma once

#include <memory>
#include <string>
#include <vector>

namespace strata {

// The recovery folder from XDG_DATA_HOME or HOME; "" when neither is set.
std::string defaultRecoveryDir();

// This editor's slot: claimed and locked by the constructor (the folder created), released by
// the destructor, which removes the slot's files (a clean end: nothing to recover). The
// recovery file itself is written by writeRecoveryFile(…, path()).
class RecoverySlot {
 public:
  explicit RecoverySlot(const std::string& dir);
  ~RecoverySlot();
  RecoverySlot(const RecoverySlot&) = delete;
  RecoverySlot& operator=(const RecoverySlot&) = delete;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  int lock_ = -1;
};

// An orphaned recovery file, locked by this process while the offer lives (so that an editor
// started meanwhile does not offer it too); dropping the offer leaves the file for a later start.
struct RecoveryOffer {
  std::string path;
  std::shared_ptr<int> lock;  // the lock file's descriptor, closed when the last copy goes
};

// The orphans of `dir`, newest first, each claimed, and the file of earlier versions at
// `legacyPath` where it exists ("": none). Unreadable entries are skipped. Never throws.
std::vector<RecoveryOffer> claimOrphanedRecoveries(const std::string& dir,
                                                   const std::string& legacyPath = "");

// Recovered: the file, its origin and its lock removed. Never throws.
void forgetRecovery(const RecoveryOffer& offer);

// How many discarded recovery files are kept.
constexpr int kKeptDiscards = 5;
// Discarded: moved into `dir`/discarded as "<time>-<name>" (the newest kKeptDiscards kept, older
// ones removed), not deleted, so that a misclick keeps the work; its lock removed. Returns the
// path it now has ("" where it could not be moved: then it stays an orphan, offered again).
std::string discardRecovery(const RecoveryOffer& offer, const std::string& dir);

}  // namespace strata
