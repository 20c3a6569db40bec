// Writing files so that nothing is ever lost or half-seen: a reader finds the old file or the
// whole new one, never a mixture or a truncated file.
//
// How one file is written (POSIX; Linux is what is tested):
//   1. Leftovers of killed writers of the same target are removed (see "Leftovers").
//   2. A temporary file of its own is created in the target's folder,
//        "<folder>/.<name>.strata-<pid>-<16 hex digits, random>.tmp"
//      with open(O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC): it never opens an existing
//      file and never follows a link planted at its name (it tries another random name). Its
//      mode is 0666 less the umask, or the permission bits of the regular file it replaces.
//      (<name> is shortened when the whole name would exceed 255 bytes.)
//   3. `write` fills it through a std::ostream (on Linux the disk's writeback of each 8 MB is
//      started as the next is written, so the fsync waits for the last stretch only); it is
//      fsync'ed and closed.
//   4. It is renamed over the target (rename(2)) and the folder is fsync'ed (best effort: some
//      file systems cannot, and the rename has happened by then).
// On any failure, or when `write` throws (Cancelled included), the temporary file is removed and
// the target is untouched.
//
// A symbolic link at the target itself is kept: the file it leads to (through a chain of links;
// a link to nothing yet: the path it names) is what is written and replaced, the same way, in
// that file's folder (resolvedOutputPath). In a sticky folder that everyone may write (/tmp), a
// link owned by neither this user nor the folder's owner is refused by name, as the kernel's
// fs.protected_symlinks refuses to follow it; elsewhere links are followed whoever made them (a
// folder others may write is theirs to plant links in, as for any program that writes through a
// link). A link into /proc (/dev/stdout, /dev/fd/N) is written through, appended to what the
// descriptor has open. Links among the folders above are followed. Errors name the file written.
//
// Concurrent writers of one path (threads or processes) each write their own temporary file;
// the last rename wins and leaves one writer's whole file.
//
// Several files that belong together (OBJ + MTL; a scene and its companion) are written with
// writeFilesAtomically: every temporary file is written first, then the targets are replaced,
// the main file (the first) last, the previous version of each kept meanwhile as a backup (a hard
// link, or a copy where the file system has none) named like a temporary file with ".old" for
// ".tmp". A failed rename puts back every target already replaced (or removes it when it did not
// exist) and the error says so; on success the backups are removed. Strata writers of sets
// serialise their renames on an flock(2) of the folder (where the file system supports it), so
// concurrent sets to the same paths end as one writer's whole set.
//
// Leftovers: a writer killed by SIGKILL (or a crash, or a power cut) leaves its temporary or
// backup files behind; the target keeps its previous version (a set killed in the middle of
// its renames may be half replaced). Every write removes the temporary and backup files of the
// same target whose names match the pattern above exactly and whose pid no longer runs
// (kill(pid, 0) fails with ESRCH). Nothing else is ever removed: not other names, not the files
// of a live process. (A folder shared by several hosts or pid namespaces, e.g. over NFS, could
// see another host's live writer as dead; its rename then fails and it reports the error.)
//
// Signals: a process that exits from a signal handler calls abandonAtomicWritesForExit() first
// (app/signal_cancellation.h does), so that SIGINT, SIGTERM and SIGHUP leave no temporary file.
// Renames run with SIGINT, SIGTERM and SIGHUP blocked in the renaming thread.
//
// Threads: every function may be called from any thread, concurrently.
#pragma once

#include <cstdint>
#include <functional>
#include <ostream>
#include <string>
#include <vector>

namespace strata {

// Calls write(stream) and commits the result atomically. Throws strata::Error naming the path
// when the file cannot be written or replaced; rethrows whatever `write` throws.
// A path that names a device, a pipe or a socket (itself or through links: /dev/stdout,
// /dev/null, a FIFO) is written through, in place, never replaced by a file (as root, a
// rename over /dev/stdout replaced it for the whole system); a failed write (/dev/full) throws.
// A set of several files refuses such paths.
void writeFileAtomically(const std::string& path, const std::function<void(std::ostream&)>& write);
// Why `path` cannot take a file that is read back after it is written (an export's check): it
// names a device, a pipe, a socket or a process's descriptor ("" where it names a regular file,
// a link to one, or nothing yet).
std::string notAFileToReadBack(const std::string& path);
// Why no file can be written at `path` ("" where one can): its folder is missing, or a file cannot
// be created in it (read-only, no permission, full of inodes); found by creating and removing a
// probe file there, as the atomic write's temporary file will be. Asked before long work whose
// end is a write (an export found a read-only folder only after all its work).
std::string cannotWriteAt(const std::string& path);
// The file a write of `path` replaces: the end of the chain of links at `path` itself (`path`
// where it is no link, or leads into /proc). Throws strata::Error as a write would (a loop, a
// link another user planted in a shared folder). For files named after it (an OBJ's MTL).
std::string resolvedOutputPath(const std::string& path);

// One file of a set that is committed together.
struct AtomicFileWrite {
  std::string path;
  std::function<void(std::ostream&)> write;
};

// Writes every file of `files` (distinct paths) to its temporary file, in order, then replaces
// the targets in reverse order, all or none (see above): the first file is the main one, which
// refers to the others (the OBJ before its MTL) and is replaced last. Throws strata::Error naming
// the path that failed (and any target that could not be put back); rethrows whatever a `write`
// throws. Nothing is replaced unless every `write` succeeded.
void writeFilesAtomically(const std::vector<AtomicFileWrite>& files);

// Every path this process has written so far (committed, in order; of a set, its main file):
// what a command cancelled after its file was in place (during its check) says it wrote.
std::vector<std::string> committedFiles();

// The temporary and backup files in `path`'s folder that belong to `path` by their name, of any
// process, live or dead (full paths, sorted). For tests and diagnostics.
std::vector<std::string> temporaryFilesOf(const std::string& path);

// For a process about to end from a signal handler: refuses new temporary files (a writer that
// tries throws Cancelled), waits up to about a second for renames in progress to finish, and
// removes the temporary and backup files this process has open. Async-signal-safe; never throws;
// call it only right before _exit. A forked child's call leaves its parent's files alone.
void abandonAtomicWritesForExit() noexcept;

// A regular file opened for reading front to back, with readWholeFile's refusals (not a
// regular file; larger than maxInputFileBytes()). For files read in pieces, never held whole.
// Owns its descriptor; one thread at a time.
class InputFile {
 public:
  explicit InputFile(const std::string& path);
  ~InputFile();
  InputFile(const InputFile&) = delete;
  InputFile& operator=(const InputFile&) = delete;

  // The size when opened (fstat).
  uint64_t size() const { return size_; }
  // Reads exactly n bytes from where the last read ended. Throws strata::Error naming the path
  // when it cannot, or when the file ends first (it shrank while read).
  void readExactly(char* to, size_t n);
  int descriptor() const { return fd_; }

 private:
  std::string path_;
  int fd_ = -1;
  uint64_t size_ = 0;
};

// Reads a whole regular file of at most maxInputFileBytes() bytes. Throws strata::Error naming
// the path when it cannot be read, is not a regular file (a FIFO, a device such as /dev/zero,
// a folder: refused without blocking on them), or is larger than the limit (the message says
// the size and how to raise the limit).
std::string readWholeFile(const std::string& path);

// The largest file readWholeFile reads (default kDefaultMaxInputFileBytes), and the largest
// uncompressed part of a 3MF package; process-wide, set by the command line's --max-file-size.
// Any thread.
uint64_t maxInputFileBytes();
void setMaxInputFileBytes(uint64_t bytes);

// While alive, lifts the input limits on this thread alone (this size limit and the readers'
// triangle limit, maxInputTriangles in engine/io/mesh_io.h): for reading back a file Strata has
// just written itself (the export's check), which no input limit should refuse.
class InputLimitLifted {
 public:
  InputLimitLifted();
  ~InputLimitLifted();
  InputLimitLifted(const InputLimitLifted&) = delete;
  InputLimitLifted& operator=(const InputLimitLifted&) = delete;

  // Whether one is alive on the calling thread.
  static bool active();

 private:
  bool previous_;
};
constexpr uint64_t kDefaultMaxInputFileBytes = uint64_t(4) << 30;  // 4 GiB

// For tests: stand-ins for what a test cannot otherwise control. Process-wide; a test sets them
// and restores the defaults ({}) when done.
struct AtomicFileTestHooks {
  // The random part of temporary and backup names (empty: the system's random numbers), so a
  // test can plant files at the names a write is going to try.
  std::function<uint64_t()> random;
  // Backups as on a file system without hard links (FAT): copies of the previous version.
  bool refuseHardLinks = false;
};
void setAtomicFileTestHooks(AtomicFileTestHooks hooks);

}  // namespace strata
