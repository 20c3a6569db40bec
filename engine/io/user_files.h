// The editor's files outside any document: the recent-files list and the crash-recovery copy.
//
//   recent files:  $XDG_CONFIG_HOME/strata/recent.txt (default ~/.config/strata/recent.txt),
//                  one absolute path per line, most recent first, at most kMaxRecentFiles
//   recovery file: a scene file an editor writes while it has unsaved changes and removes on a
//                  clean exit, so that finding one at start means an editor ended without saving.
//                  Each running editor has one of its own (recovery_slots.h: slots in
//                  $XDG_DATA_HOME/strata/recovery); earlier versions shared
//                  $XDG_DATA_HOME/strata/recovery.strata.json (defaultRecoveryPath), still offered.
//                  Its companion "<recovery>.origin" holds the path of the document it was made
//                  from ("" for an untitled one). Mesh paths in it are absolute, so it loads from
//                  its own folder.
//
// Threads: any. The recent-files list is not locked (the last writer wins).
#pragma once

#include <string>
#include <vector>

#include "engine/document/document.h"

namespace strata {

constexpr size_t kMaxRecentFiles = 10;

// The folders, from XDG_CONFIG_HOME / XDG_DATA_HOME or HOME; "" when neither is set.
std::string userConfigDir();
std::string userDataDir();
std::string defaultRecentFilesPath();
std::string defaultRecoveryPath();

// Reads the list (missing file: empty list; unreadable lines are skipped).
std::vector<std::string> readRecentFiles(const std::string& listPath);
// Puts `file` first (made absolute, duplicates removed), trims to kMaxRecentFiles and writes the
// list atomically, creating its folder. Returns the new list. Throws strata::Error.
std::vector<std::string> addRecentFile(const std::string& listPath, const std::string& file);

// Writes the document's current scene and its origin atomically, as one set (both or neither;
// engine/util/atomic_file.h). Throws strata::Error.
void writeRecoveryFile(const Document& document, const std::string& recoveryPath);
// The same from a scene and the path of the document it belongs to ("" = never saved): what a
// background thread writes from a snapshot of the document (a Scene's nodes are immutable).
void writeRecoveryFile(const Scene& scene, const std::string& documentPath,
                       const std::string& recoveryPath);
// True when a recovery file exists.
bool recoveryFileExists(const std::string& recoveryPath);
// Loads it as a modified document belonging to its origin file (if it had one). Throws
// strata::Error for a damaged file.
Document readRecoveryFile(const std::string& recoveryPath,
                          std::vector<std::string>* warnings = nullptr);
// What a recovery file is of, for the question at start: the document it was made from ("" for
// an untitled one) and when it was written (local time, "2026-11-23 06:12"; "" when unknown).
// Never throws.
struct RecoveryInfo {
  std::string origin;
  std::string writtenAt;
};
RecoveryInfo describeRecoveryFile(const std::string& recoveryPath);

// Removes the recovery file and its companion (a clean exit). Never throws.
void removeRecoveryFile(const std::string& recoveryPath);

}  // namespace strata
