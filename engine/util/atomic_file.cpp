#include "engine/util/atomic_file.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <mutex>
#include <sstream>
#include <utility>

#include "engine/util/error.h"
#include "engine/util/temporary_files.h"

namespace strata {
namespace {
using namespace atomic_detail;

std::string errorText(int error) {
  return std::strerror(error);
}

// ---- Writing ----------------------------------------------------------------------------------

// An output buffer over a file descriptor that remembers the first write error (errno value).
class DescriptorBuffer : public std::streambuf {
 public:
  explicit DescriptorBuffer(int fd) : fd_(fd), buffer_(new char[kSize]) {
    setp(buffer_.get(), buffer_.get() + kSize);
  }
  int error() const { return error_; }

 protected:
  int_type overflow(int_type ch) override {
    if (!drain()) return traits_type::eof();
    if (!traits_type::eq_int_type(ch, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(ch);
      pbump(1);
    }
    return traits_type::not_eof(ch);
  }
  std::streamsize xsputn(const char* data, std::streamsize n) override {
    if (n < kSize) return std::streambuf::xsputn(data, n);
    if (!drain() || !writeAll(data, static_cast<size_t>(n))) return 0;
    return n;
  }
  int sync() override { return drain() ? 0 : -1; }

 private:
  static constexpr std::streamsize kSize = 1 << 16;

  bool drain() {
    const size_t n = static_cast<size_t>(pptr() - pbase());
    if (n > 0 && !writeAll(pbase(), n)) return false;
    setp(buffer_.get(), buffer_.get() + kSize);
    return true;
  }
  bool writeAll(const char* data, size_t n) {
    while (n > 0 && error_ == 0) {
      const ssize_t written = ::write(fd_, data, n);
      if (written < 0 && errno == EINTR) continue;
      if (written <= 0) {
        error_ = written < 0 ? errno : EIO;
        break;
      }
      data += written;
      n -= static_cast<size_t>(written);
      startWriteback(static_cast<uint64_t>(written));
    }
    return error_ == 0;
  }

  // Starts the disk's writing of every whole kWritebackBytes written so far while the rest is
  // still being made (Linux: sync_file_range, which does not wait), so that the fsync at the end
  // waits for the last stretch only instead of the whole file. Best effort: the fsync is what
  // makes the file durable.
  void startWriteback(uint64_t written) {
#if defined(__linux__)
    constexpr uint64_t kWritebackBytes = uint64_t(8) << 20;
    total_ += written;
    if (total_ - started_ < kWritebackBytes) return;
    const uint64_t end = total_ / kWritebackBytes * kWritebackBytes;
    ::sync_file_range(fd_, off_t(started_), off_t(end - started_), SYNC_FILE_RANGE_WRITE);
    started_ = end;
#else
    (void)written;
#endif
  }

  int fd_;
  uint64_t total_ = 0, started_ = 0;  // bytes written; bytes whose writeback was started
  std::unique_ptr<char[]> buffer_;
  int error_ = 0;
};

// Closes a descriptor unless handed over.
struct Descriptor {
  int fd = -1;
  Descriptor() = default;
  Descriptor(const Descriptor&) = delete;
  Descriptor& operator=(const Descriptor&) = delete;
  ~Descriptor() {
    if (fd >= 0) ::close(fd);
  }
  // Closes and reports close's error (0 when none).
  int close() {
    const int result = ::close(fd);
    fd = -1;
    return result == 0 ? 0 : errno;
  }
};

int createExclusive(const std::string& name, mode_t mode, Descriptor* out) {
  const int fd = ::open(name.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, mode);
  if (fd < 0) return errno;
  out->fd = fd;
  return 0;
}

void syncAndClose(Descriptor& file, const std::string& path) {
  if (::fsync(file.fd) != 0) throw Error(path + ": cannot flush to disk: " + errorText(errno));
  if (const int error = file.close()) throw Error(path + ": cannot write: " + errorText(error));
}

// Writes `file` into a fresh temporary file next to it, synced and closed.
std::unique_ptr<OwnedFile> writeTemporary(const Target& target, const AtomicFileWrite& file) {
  struct stat old;
  const bool replacesRegular = ::lstat(target.path.c_str(), &old) == 0 && S_ISREG(old.st_mode);
  Descriptor out;
  int error = 0;
  std::unique_ptr<OwnedFile> temporary = OwnedFile::create(
      target, Kind::Temporary,
      [&](const std::string& name) { return createExclusive(name, 0666, &out); }, &error);
  if (!temporary) throw Error(target.path + ": cannot write: " + errorText(error));
  if (replacesRegular) ::fchmod(out.fd, old.st_mode & 0777);  // best effort (FAT cannot)
  DescriptorBuffer buffer(out.fd);
  std::ostream stream(&buffer);
  file.write(stream);
  stream.flush();
  if (buffer.error()) throw Error(target.path + ": cannot write: " + errorText(buffer.error()));
  if (!stream) throw Error(target.path + ": write failed");
  syncAndClose(out, target.path);
  return temporary;
}

// ---- Sets -------------------------------------------------------------------------------------

void syncFolder(const std::string& folder) {
  const int fd = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  ::fsync(fd);  // best effort: the rename has happened; some file systems cannot sync folders
  ::close(fd);
}

// flock(2) on every distinct folder of a set, in (device, inode) order. Where the file system
// refuses (NFS without write access, ...), the set goes unserialised.
class FolderLocks {
 public:
  explicit FolderLocks(const std::vector<Target>& targets) {
    std::vector<std::pair<std::pair<dev_t, ino_t>, int>> folders;
    for (const Target& target : targets) {
      const int fd = ::open(target.folderToOpen().c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
      struct stat st;
      if (fd < 0) continue;
      if (::fstat(fd, &st) != 0) {
        ::close(fd);
        continue;
      }
      const auto key = std::make_pair(st.st_dev, st.st_ino);
      if (std::any_of(folders.begin(), folders.end(),
                      [&](const auto& f) { return f.first == key; })) {
        ::close(fd);
        continue;
      }
      folders.push_back({key, fd});
    }
    std::sort(folders.begin(), folders.end());
    for (const auto& folder : folders) {
      while (::flock(folder.second, LOCK_EX) != 0 && errno == EINTR) {
      }
      fds_.push_back(folder.second);
    }
  }
  FolderLocks(const FolderLocks&) = delete;
  FolderLocks& operator=(const FolderLocks&) = delete;
  ~FolderLocks() {
    for (int fd : fds_) ::close(fd);  // releases the lock
  }

 private:
  std::vector<int> fds_;
};

bool noHardLinks(int error) {
  return error == EPERM || error == EMLINK || error == ENOTSUP || error == EOPNOTSUPP ||
         error == ENOSYS || error == EXDEV;
}

// A copy of the regular file or link at `target`, for file systems without hard links.
std::unique_ptr<OwnedFile> copyAsBackup(const Target& target, const struct stat& old) {
  int error = 0;
  if (S_ISLNK(old.st_mode)) {
    std::string destination(static_cast<size_t>(old.st_size) + 1, '\0');
    const ssize_t n = ::readlink(target.path.c_str(), &destination[0], destination.size());
    if (n < 0 || static_cast<size_t>(n) >= destination.size())
      throw Error(target.path + ": cannot keep the previous version: cannot read the link");
    destination.resize(static_cast<size_t>(n));
    auto backup = OwnedFile::create(
        target, Kind::Backup,
        [&](const std::string& name) {
          return ::symlink(destination.c_str(), name.c_str()) == 0 ? 0 : errno;
        },
        &error);
    if (!backup)
      throw Error(target.path + ": cannot keep the previous version: " + errorText(error));
    return backup;
  }
  if (!S_ISREG(old.st_mode))
    throw Error(target.path + ": cannot keep the previous version: not a regular file");
  Descriptor in;
  in.fd = ::open(target.path.c_str(), O_RDONLY | O_NOFOLLOW | O_CLOEXEC);
  if (in.fd < 0)
    throw Error(target.path + ": cannot read the previous version: " + errorText(errno));
  Descriptor out;
  auto backup = OwnedFile::create(
      target, Kind::Backup,
      [&](const std::string& name) { return createExclusive(name, old.st_mode & 0777, &out); },
      &error);
  if (!backup) throw Error(target.path + ": cannot keep the previous version: " + errorText(error));
  std::unique_ptr<char[]> chunk(new char[1 << 16]);
  DescriptorBuffer copy(out.fd);
  for (;;) {
    const ssize_t n = ::read(in.fd, chunk.get(), 1 << 16);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw Error(target.path + ": cannot read the previous version: " + errorText(errno));
    if (n == 0) break;
    copy.sputn(chunk.get(), n);
  }
  if (copy.pubsync() != 0 || copy.error())
    throw Error(target.path + ": cannot keep the previous version: " + errorText(copy.error()));
  syncAndClose(out, backup->path());
  return backup;
}

// The previous version of `target` under a backup name (null when there is none, or when it is
// a folder, which no rename can replace).
std::unique_ptr<OwnedFile> keepPreviousVersion(const Target& target) {
  int error = 0;
  // linkat fails with ENOENT when a writer outside this set's lock replaces the target meanwhile
  // (the old inode's last link is gone): look again.
  for (int attempt = 0; attempt < 100; ++attempt) {
    struct stat old;
    if (::lstat(target.path.c_str(), &old) != 0) {
      if (errno == ENOENT) return nullptr;
      throw Error(target.path + ": cannot replace the file: " + errorText(errno));
    }
    if (S_ISDIR(old.st_mode)) return nullptr;
    auto backup = OwnedFile::create(
        target, Kind::Backup,
        [&](const std::string& name) {
          if (hardLinksRefusedForTesting()) return EPERM;  // as FAT answers
          // linkat without AT_SYMLINK_FOLLOW links a symbolic link itself.
          return ::linkat(AT_FDCWD, target.path.c_str(), AT_FDCWD, name.c_str(), 0) == 0 ? 0
                                                                                         : errno;
        },
        &error);
    if (backup) return backup;
    if (noHardLinks(error)) return copyAsBackup(target, old);
    if (error != ENOENT) break;
  }
  throw Error(target.path + ": cannot keep the previous version: " + errorText(error));
}

// Whether `path` names (through links too) something other than a regular file or a folder: a
// device, a pipe or a socket.
bool namesSpecialFile(const std::string& path) {
  struct stat st;
  return ::stat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode) && !S_ISDIR(st.st_mode);
}

// `file` written in place into the device, pipe or socket its path names, or (`append`) at the
// end of what a process's descriptor has open (/dev/stdout redirected to a file).
void writeThrough(const AtomicFileWrite& file, bool append = false) {
  Descriptor out;
  out.fd = ::open(file.path.c_str(), O_WRONLY | O_CLOEXEC | O_NOCTTY | (append ? O_APPEND : 0));
  if (out.fd < 0) throw Error(file.path + ": cannot write: " + errorText(errno));
  DescriptorBuffer buffer(out.fd);
  std::ostream stream(&buffer);
  file.write(stream);
  stream.flush();
  if (buffer.error()) throw Error(file.path + ": cannot write: " + errorText(buffer.error()));
  if (!stream) throw Error(file.path + ": write failed");
  if (const int error = out.close()) throw Error(file.path + ": cannot write: " + errorText(error));
}

// The end of the chain of links at `path` itself, and whether the chain reaches into /proc.
struct LinkChain {
  std::string target;
  // A link into /proc (/dev/stdout, /dev/fd/1: a process's descriptors): it names what a
  // descriptor has open, not a place for a file (a temporary renamed over the file a shell's
  // `>` opened would leave the process writing to an unlinked file). `target` is then `path`.
  bool throughProcess = false;
};

// See resolvedOutputPath in atomic_file.h. Links are read into a buffer grown until it holds
// them (/proc's links report a size of 64, whatever their length).
LinkChain followTargetLinks(const std::string& path) {
  LinkChain chain;
  std::string current = path;
  for (int hop = 0; hop < 40; ++hop) {
    struct stat link;
    if (::lstat(current.c_str(), &link) != 0 || !S_ISLNK(link.st_mode)) {
      chain.target = current;
      return chain;
    }
    const size_t slash = current.rfind('/');
    const std::string folder = slash == std::string::npos ? "" : current.substr(0, slash + 1);
    struct stat shared;
    if (::stat(folder.empty() ? "." : folder.c_str(), &shared) == 0 &&
        (shared.st_mode & S_ISVTX) != 0 && (shared.st_mode & S_IWOTH) != 0 &&
        link.st_uid != ::geteuid() && link.st_uid != shared.st_uid)
      throw Error(current +
                  ": a symbolic link of another user in a shared folder; not followed (write "
                  "to another name)");
    std::string destination(std::max<size_t>(size_t(link.st_size), 64) + 1, '\0');
    ssize_t n = 0;
    for (;;) {
      n = ::readlink(current.c_str(), &destination[0], destination.size());
      if (n < 0) throw Error(current + ": cannot read the symbolic link: " + errorText(errno));
      if (size_t(n) < destination.size()) break;
      destination.resize(destination.size() * 2);
    }
    if (n == 0) throw Error(current + ": an empty symbolic link");
    destination.resize(static_cast<size_t>(n));
    current = destination[0] == '/' ? destination : folder + destination;
    if (current.compare(0, 6, "/proc/") == 0) {
      chain.target = path;
      chain.throughProcess = true;
      return chain;
    }
  }
  throw Error(path + ": " + errorText(ELOOP));
}

}  // namespace

std::string notAFileToReadBack(const std::string& path) {
  bool throughProcess = false;
  try {
    throughProcess = followTargetLinks(path).throughProcess;
  } catch (const Error&) {
    // the write says why
  }
  if (throughProcess)
    return "a process's descriptor (such as /dev/stdout), not a file: an export is read back "
           "to check it; write it to a file";
  if (!namesSpecialFile(path)) return "";
  return "not a regular file (a device, a pipe or a socket): an export is read back to check "
         "it; write it to a file";
}

std::string cannotWriteAt(const std::string& path) {
  if (!notAFileToReadBack(path).empty()) return "";  // a device or a pipe: written through
  std::string folder;
  try {
    folder = std::filesystem::path(followTargetLinks(path).target).parent_path().string();
  } catch (const Error& e) {
    return e.what();
  }
  if (folder.empty()) folder = ".";
  struct stat st {};
  if (::stat(folder.c_str(), &st) != 0 || !S_ISDIR(st.st_mode))
    return "the folder " + folder + " does not exist";
  static std::atomic<unsigned> next{0};
  const std::string probe =
      folder + "/.strata-probe-" + std::to_string(::getpid()) + "-" + std::to_string(next++);
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
  // A folder that exists but answers "no such file" to a new one (/proc, /sys) says so in words.
  if (fd < 0)
    return "cannot create a file in " + folder + ": " +
           (errno == ENOENT ? std::string("it takes no new files") : std::strerror(errno));
  ::close(fd);
  ::unlink(probe.c_str());
  return "";
}

std::string resolvedOutputPath(const std::string& path) {
  return followTargetLinks(path).target;
}

namespace {
std::mutex g_committedMutex;
std::vector<std::string> g_committed;  // guarded by g_committedMutex

void noteCommitted(const std::string& path) {
  std::lock_guard<std::mutex> lock(g_committedMutex);
  g_committed.push_back(path);
}
}  // namespace

void writeFilesAtomically(const std::vector<AtomicFileWrite>& files) {
  // The links first (a planted one is refused before anything is opened through it), then what
  // they lead to: a device, a pipe, a socket or a process's descriptor is written through.
  std::vector<LinkChain> chains;
  for (const AtomicFileWrite& file : files) {
    splitTarget(file.path);  // refuses a path that names no file, before any link is read
    chains.push_back(followTargetLinks(file.path));
  }
  const auto special = [&](size_t i) {
    return chains[i].throughProcess || namesSpecialFile(files[i].path);
  };
  if (files.size() == 1 && special(0)) {
    writeThrough(files[0], chains[0].throughProcess && !namesSpecialFile(files[0].path));
    noteCommitted(files[0].path);
    return;
  }
  for (size_t i = 0; i < files.size(); ++i)
    if (special(i))
      throw Error(files[i].path +
                  ": not a regular file (a device, a pipe, a socket or a process's descriptor): "
                  "files written together go to regular files");
  std::vector<Target> targets;
  for (size_t i = 0; i < files.size(); ++i) {
    const AtomicFileWrite& file = files[i];
    const std::string& target = chains[i].target;
    for (const Target& t : targets)
      if (t.path == target) throw Error(file.path + ": listed twice in one atomic write");
    targets.push_back(splitTarget(target));
  }
  std::vector<std::unique_ptr<OwnedFile>> temporaries;
  for (size_t i = 0; i < files.size(); ++i) {
    removeLeftovers(targets[i]);
    temporaries.push_back(writeTemporary(targets[i], files[i]));
  }

  if (files.size() == 1) {
    {
      RenameSection section;
      if (::rename(temporaries[0]->path().c_str(), targets[0].path.c_str()) != 0)
        throw Error(targets[0].path + ": cannot replace the file: " + errorText(errno));
      temporaries[0]->release();
    }
    noteCommitted(files[0].path);
    syncFolder(targets[0].folderToOpen());
    return;
  }

  FolderLocks locks(targets);
  std::vector<std::unique_ptr<OwnedFile>> backups;
  for (const Target& target : targets) backups.push_back(keepPreviousVersion(target));
  {
    // Renamed last to first; `renamed` counts from the last.
    RenameSection section;
    const size_t n = targets.size();
    size_t renamed = 0;
    int error = 0;
    for (; renamed < n; ++renamed) {
      const size_t i = n - 1 - renamed;
      if (::rename(temporaries[i]->path().c_str(), targets[i].path.c_str()) != 0) {
        error = errno;
        break;
      }
      temporaries[i]->release();
    }
    if (renamed < n) {
      std::string message =
          targets[n - 1 - renamed].path + ": cannot replace the file: " + errorText(error);
      std::string notRestored;
      for (size_t i = n - renamed; i < n; ++i) {
        const std::string& path = targets[i].path;
        if (backups[i]) {
          if (::rename(backups[i]->path().c_str(), path.c_str()) == 0) {
            backups[i]->release();
          } else {
            notRestored += "; " + path + " could not be put back (" + errorText(errno) +
                           "; its previous version is " + backups[i]->path() + ")";
            backups[i]->release();  // left for the user; a later write of the path removes it
          }
        } else if (::unlink(path.c_str()) != 0 && errno != ENOENT) {
          notRestored += "; the new " + path + " could not be removed (" + errorText(errno) + ")";
        }
      }
      throw Error(message + (notRestored.empty() ? "; no file was replaced" : notRestored));
    }
  }
  noteCommitted(files[0].path);  // the set's main file (an OBJ, not its MTL), as named
  std::vector<std::string> synced;
  for (const Target& target : targets) {
    if (std::find(synced.begin(), synced.end(), target.folderToOpen()) != synced.end()) continue;
    synced.push_back(target.folderToOpen());
    syncFolder(synced.back());
  }
}

void writeFileAtomically(const std::string& path, const std::function<void(std::ostream&)>& write) {
  writeFilesAtomically({AtomicFileWrite{path, write}});
}

std::vector<std::string> committedFiles() {
  std::lock_guard<std::mutex> lock(g_committedMutex);
  return g_committed;
}

std::vector<std::string> temporaryFilesOf(const std::string& path) {
  std::string target = path;
  try {
    target = followTargetLinks(path).target;
  } catch (const Error&) {
    // a link that cannot be followed: the files named after the link itself
  }
  return leftoversOf(splitTarget(target));
}

namespace {
std::atomic<uint64_t> g_maxInputFileBytes{kDefaultMaxInputFileBytes};

std::string sizeText(uint64_t bytes) {
  char text[32];
  if (bytes >= (uint64_t(1) << 30))
    std::snprintf(text, sizeof(text), "%.1f GiB", double(bytes) / double(uint64_t(1) << 30));
  else if (bytes >= (uint64_t(1) << 20))
    std::snprintf(text, sizeof(text), "%.1f MiB", double(bytes) / double(1 << 20));
  else
    std::snprintf(text, sizeof(text), "%llu bytes", static_cast<unsigned long long>(bytes));
  return text;
}

const char* fileTypeName(mode_t mode) {
  if (S_ISDIR(mode)) return "a folder";
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
  if (S_ISCHR(mode) || S_ISBLK(mode)) return "a device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

Error tooLargeFile(const std::string& path, uint64_t size, uint64_t limit) {
  return Error(path + ": the file is " + sizeText(size) + ", larger than the limit of " +
               sizeText(limit) + "; raise it with --max-file-size (e.g. --max-file-size 16G)");
}

}  // namespace

thread_local bool t_inputLimitLifted = false;

InputLimitLifted::InputLimitLifted() : previous_(t_inputLimitLifted) {
  t_inputLimitLifted = true;
}
InputLimitLifted::~InputLimitLifted() {
  t_inputLimitLifted = previous_;
}
bool InputLimitLifted::active() {
  return t_inputLimitLifted;
}

uint64_t maxInputFileBytes() {
  if (t_inputLimitLifted) return ~uint64_t(0) >> 1;
  return g_maxInputFileBytes.load();
}

void setMaxInputFileBytes(uint64_t bytes) {
  g_maxInputFileBytes.store(bytes);
}

InputFile::InputFile(const std::string& path) : path_(path) {
  // O_NONBLOCK: opening a FIFO must not wait for a writer; it is refused below.
  fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd_ < 0) throw Error(path + ": cannot open: " + std::strerror(errno));
  struct stat st {};
  const bool statted = ::fstat(fd_, &st) == 0;
  const int statError = errno;
  if (!statted || !S_ISREG(st.st_mode)) {
    ::close(fd_);
    if (!statted) throw Error(path + ": cannot read: " + std::strerror(statError));
    throw Error(path + ": is " + fileTypeName(st.st_mode) + "; Strata reads regular files only");
  }
  size_ = uint64_t(st.st_size);
  const uint64_t limit = maxInputFileBytes();
  if (size_ > limit) {
    ::close(fd_);
    throw tooLargeFile(path, size_, limit);
  }
  ::fcntl(fd_, F_SETFL, ::fcntl(fd_, F_GETFL) & ~O_NONBLOCK);
}

InputFile::~InputFile() {
  ::close(fd_);
}

void InputFile::readExactly(char* to, size_t n) {
  size_t done = 0;
  while (done < n) {
    const ssize_t got = ::read(fd_, to + done, n - done);
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) throw Error(path_ + ": read failed: " + std::strerror(errno));
    if (got == 0) throw Error(path_ + ": the file ended early (it changed while it was read)");
    done += size_t(got);
  }
}

std::string readWholeFile(const std::string& path) {
  InputFile file(path);
  const int fd = file.descriptor();
  const uint64_t limit = maxInputFileBytes();
  auto tooLarge = [&](uint64_t size) { return tooLargeFile(path, size, limit); };
  std::string bytes;
  bytes.resize(size_t(file.size()));
  size_t done = 0;
  for (;;) {  // the file may change while it is read: read to its end, within the limit
    if (done == bytes.size()) {
      // Full: is there more? Probe with a byte before growing, so that the usual case (the
      // file as large as fstat said) never allocates and touches a second buffer.
      char probe;
      const ssize_t more = ::read(fd, &probe, 1);
      if (more == 0) break;
      if (more < 0 && errno == EINTR) continue;
      if (more < 0) throw Error(path + ": read failed: " + std::strerror(errno));
      if (bytes.size() >= limit) throw tooLarge(limit + 1);
      bytes.resize(std::min<uint64_t>(limit, std::max<uint64_t>(4096, bytes.size() * 2)));
      bytes[done++] = probe;
      continue;
    }
    const ssize_t got = ::read(fd, &bytes[done], bytes.size() - done);
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) throw Error(path + ": read failed: " + std::strerror(errno));
    if (got == 0) break;
    done += size_t(got);
  }
  bytes.resize(done);
  return bytes;
}

}  // namespace strata
