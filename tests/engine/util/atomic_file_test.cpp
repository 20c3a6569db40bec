// Atomic writes (engine/util/atomic_file.h) against hostile folders and faults: links planted at
// the target and at the temporary names, concurrent writers (threads and processes), failing
// writers, failed renames in a set, leftovers of dead and live writers, and the signal path.
#include "engine/util/atomic_file.h"

#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "engine/util/error.h"

namespace strata {
namespace {
namespace fs = std::filesystem;

// A fresh folder of this test's own (tests run in parallel processes), removed afterwards.
class AtomicFileDir : public testing::Test {
 protected:
  void SetUp() override {
    const auto* info = testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::path(testing::TempDir()) / ("strata_atomic_" + std::string(info->test_suite_name()) +
                                           "_" + info->name() + "_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    setAtomicFileTestHooks({});
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  fs::path dir_;
};

void writeText(const std::string& path, const std::string& text) {
  writeFileAtomically(path, [&](std::ostream& out) { out << text; });
}

// Writes `text` plainly (not atomically): the files the tests plant.
void plant(const std::string& path, const std::string& text) {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  ASSERT_NE(f, nullptr) << path;
  std::fwrite(text.data(), 1, text.size(), f);
  std::fclose(f);
}

bool isLink(const std::string& path) {
  struct stat st;
  return ::lstat(path.c_str(), &st) == 0 && S_ISLNK(st.st_mode);
}

bool existsNoFollow(const std::string& path) {
  struct stat st;
  return ::lstat(path.c_str(), &st) == 0;
}

// The name writes use, as documented: ".<name>.strata-<pid>-<16 hex digits>.tmp" (or ".old").
std::string temporaryName(const std::string& folder, const std::string& name, long pid,
                          uint64_t random, const char* suffix = ".tmp") {
  char hex[17];
  std::snprintf(hex, sizeof(hex), "%016llx", static_cast<unsigned long long>(random));
  return folder + "/." + name + ".strata-" + std::to_string(pid) + "-" + hex + suffix;
}

// A pid that ran and no longer does (a child that exited and was reaped).
pid_t deadPid() {
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  int status = 0;
  ::waitpid(child, &status, 0);
  return child;
}

// A whole file of the concurrency tests: "<writer> <iteration>\n" then 256 KiB of one letter
// chosen by the writer.
std::string wholeFile(int writer, int iteration) {
  std::string text = std::to_string(writer) + " " + std::to_string(iteration) + "\n";
  text.append(256 * 1024, char('a' + writer));
  return text;
}

bool isWhole(const std::string& text) {
  int writer = -1, iteration = -1;
  if (std::sscanf(text.c_str(), "%d %d", &writer, &iteration) != 2) return false;
  return writer >= 0 && writer < 26 && text == wholeFile(writer, iteration);
}

// ---- one file ---------------------------------------------------------------------------------

TEST_F(AtomicFileDir, WritesReplacesAndLeavesNoTemporaryFile) {
  const std::string out = path("out.txt");
  writeText(out, "one");
  EXPECT_EQ(readWholeFile(out), "one");
  writeText(out, "two");
  EXPECT_EQ(readWholeFile(out), "two");
  EXPECT_TRUE(temporaryFilesOf(out).empty());
  EXPECT_EQ(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()), 1);
}

// Whether a file can be written at a path is known before the work whose end writes it: a missing
// folder, a folder nobody may create files in (/proc: not even root), and a good one (the probe
// leaves nothing behind); a device is written through, never refused.
TEST_F(AtomicFileDir, AFolderThatCannotTakeTheFileIsSaidBeforehand) {
  EXPECT_EQ(cannotWriteAt(path("part.stl")), "");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()), 0)
      << "the probe was left behind";
  EXPECT_NE(cannotWriteAt(path("missing/part.stl")).find("does not exist"), std::string::npos);
  EXPECT_NE(cannotWriteAt("/proc/strata-part.stl").find("cannot create a file in /proc"),
            std::string::npos)
      << cannotWriteAt("/proc/strata-part.stl");
  EXPECT_EQ(cannotWriteAt("/dev/null"), "");
}

TEST_F(AtomicFileDir, NewFilesFollowTheUmaskAndReplacedFilesKeepTheirPermissions) {
  const std::string out = path("mode.txt");
  const mode_t mask = ::umask(022);
  writeText(out, "one");
  struct stat st;
  ASSERT_EQ(::stat(out.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 0777, 0644u);
  ASSERT_EQ(::chmod(out.c_str(), 0600), 0);
  writeText(out, "two");
  ASSERT_EQ(::stat(out.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 0777, 0600u);
  ::umask(mask);
}

// A user's link at the output (out.stl -> prints/v3.stl) stays a link: the file it leads to is
// replaced, atomically, with the permissions it had; a chain of links, relative links and a link
// to a file not made yet lead to theirs.
TEST_F(AtomicFileDir, ALinkAtTheTargetIsKeptAndTheFileItLeadsToIsReplaced) {
  fs::create_directory(path("prints"));
  const std::string real = path("prints/v3.txt");
  plant(real, "old");
  ASSERT_EQ(::chmod(real.c_str(), 0640), 0);
  const std::string out = path("out.txt");
  fs::create_symlink("prints/v3.txt", out);  // relative to the link's folder
  writeText(out, "new");
  EXPECT_TRUE(isLink(out));
  EXPECT_EQ(fs::read_symlink(out).string(), "prints/v3.txt");
  EXPECT_EQ(readWholeFile(real), "new");
  struct stat st;
  ASSERT_EQ(::stat(real.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 0777, 0640u);
  EXPECT_TRUE(temporaryFilesOf(out).empty());
  EXPECT_EQ(committedFiles().back(), out);  // what the caller named

  const std::string chain = path("chain.txt");  // chain -> out -> prints/v3.txt
  fs::create_symlink(out, chain);
  writeText(chain, "through two");
  EXPECT_TRUE(isLink(chain));
  EXPECT_TRUE(isLink(out));
  EXPECT_EQ(readWholeFile(real), "through two");

  const std::string pending = path("pending.txt");  // a link to a file not written yet
  fs::create_symlink(path("prints/v4.txt"), pending);
  writeText(pending, "made");
  EXPECT_TRUE(isLink(pending));
  EXPECT_EQ(readWholeFile(path("prints/v4.txt")), "made");

  // A set (an OBJ and its MTL) through links; two names of one file in a set are refused.
  const std::string mtl = path("out.mtl");
  fs::create_symlink(path("prints/v3.mtl"), mtl);
  writeFilesAtomically({{out, [](std::ostream& o) { o << "set"; }},
                        {mtl, [](std::ostream& o) { o << "set companion"; }}});
  EXPECT_TRUE(isLink(out));
  EXPECT_TRUE(isLink(mtl));
  EXPECT_EQ(readWholeFile(real), "set");
  EXPECT_EQ(readWholeFile(path("prints/v3.mtl")), "set companion");
  EXPECT_THROW(writeFilesAtomically({{out, [](std::ostream& o) { o << "a"; }},
                                     {real, [](std::ostream& o) { o << "b"; }}}),
               Error);
  EXPECT_EQ(readWholeFile(real), "set");
}

// Links that lead nowhere a file can be: a loop, a folder, a missing folder. Each is an error
// naming a path, and nothing is changed.
TEST_F(AtomicFileDir, LinksThatLeadNowhereAreRefusedByName) {
  const std::string a = path("a.txt"), b = path("b.txt");
  fs::create_symlink(b, a);
  fs::create_symlink(a, b);
  try {
    writeText(a, "x");
    ADD_FAILURE() << "a loop of links was written";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(a), std::string::npos) << e.what();
  }
  EXPECT_TRUE(isLink(a));
  EXPECT_TRUE(isLink(b));

  const std::string toFolder = path("folder.txt");
  fs::create_directory(path("sub"));
  fs::create_symlink(path("sub"), toFolder);
  EXPECT_THROW(writeText(toFolder, "x"), Error);
  EXPECT_TRUE(fs::is_directory(path("sub")));
  EXPECT_TRUE(fs::is_empty(path("sub")));

  const std::string toMissing = path("missing.txt");
  fs::create_symlink(path("no/such/folder/file.txt"), toMissing);
  try {
    writeText(toMissing, "x");
    ADD_FAILURE() << "written into a missing folder";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("no/such/folder/file.txt"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(isLink(toMissing));
}

// In a sticky folder that everyone may write (as /tmp), a link that another user planted at the
// output is not followed (fs.protected_symlinks' rule): the write is refused by name and the
// file it leads to is untouched. Needs root (to give the link to another user); skipped otherwise.
TEST_F(AtomicFileDir, ALinkPlantedByAnotherUserInASharedFolderIsNotFollowed) {
  if (::geteuid() != 0) GTEST_SKIP() << "needs root to make a link owned by another user";
  const std::string shared = path("shared");
  fs::create_directory(shared);
  ASSERT_EQ(::chmod(shared.c_str(), 01777), 0);
  const std::string victim = path("victim.txt");
  plant(victim, "precious");
  const std::string out = shared + "/out.txt";
  fs::create_symlink(victim, out);
  ASSERT_EQ(::lchown(out.c_str(), 12345, 12345), 0);
  try {
    writeText(out, "new");
    ADD_FAILURE() << "written through another user's link";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("another user"), std::string::npos) << e.what();
  }
  EXPECT_EQ(readWholeFile(victim), "precious");
  EXPECT_TRUE(isLink(out));
  // A link of the folder's owner (another user) is followed, as the kernel follows it.
  ASSERT_EQ(::chown(shared.c_str(), 12345, 12345), 0);
  writeText(out, "new");
  EXPECT_EQ(readWholeFile(victim), "new");
}

// /dev/stdout is a link into /proc: what the descriptor has open (a shell's `>` file) is written
// through, appended, never replaced by a renamed temporary (which would leave the process writing
// to an unlinked file); an export, read back to check it, refuses such a path by name.
TEST_F(AtomicFileDir, ALinkIntoProcIsWrittenThroughNotReplaced) {
  const std::string file = path("stdout.txt");
  plant(file, "before\n");
  const int fd = ::open(file.c_str(), O_WRONLY | O_APPEND);
  ASSERT_GE(fd, 0);
  const std::string link = path("out.txt");  // as /dev/stdout -> /proc/self/fd/1
  fs::create_symlink("/proc/self/fd/" + std::to_string(fd), link);
  struct stat before;
  ASSERT_EQ(::stat(file.c_str(), &before), 0);
  writeText(link, "report\n");
  struct stat after;
  ASSERT_EQ(::stat(file.c_str(), &after), 0);
  EXPECT_EQ(after.st_ino, before.st_ino) << "the file was replaced";
  EXPECT_EQ(readWholeFile(file), "before\nreport\n");
  EXPECT_TRUE(isLink(link));
  EXPECT_NE(notAFileToReadBack(link).find("descriptor"), std::string::npos);
  EXPECT_EQ(resolvedOutputPath(link), link);
  ::close(fd);
}

// Links (to a file, and dangling) at the old fixed name, at names without the random part, and
// at the exact names the next writes will try: each is skipped, none is followed or removed.
TEST_F(AtomicFileDir, LinksPlantedAtTemporaryNamesAreNeverFollowed) {
  const std::string victim = path("victim.txt");
  plant(victim, "precious");
  const std::string nowhere = path("created-through-a-link");
  const std::string out = path("out.txt");
  const std::string companion = path("out.mtl");
  plant(out, "old");
  plant(companion, "old companion");

  // Every name a write creates (temporary or backup) tries random parts 1, 2, ... 12, all
  // planted, before 13.
  int calls = 0;
  AtomicFileTestHooks hooks;
  hooks.random = [&calls] { return uint64_t(calls++ % 13 + 1); };
  setAtomicFileTestHooks(hooks);
  std::vector<std::string> planted;
  auto plantLink = [&](const std::string& at) {
    fs::create_symlink(planted.size() % 2 ? victim : nowhere, at);
    planted.push_back(at);
  };
  for (const std::string& target : {std::string("out.txt"), std::string("out.mtl")}) {
    plantLink(path(target + ".tmp"));
    plantLink(path("." + target + ".tmp"));
    for (uint64_t r = 1; r <= 12; ++r) {
      plantLink(temporaryName(dir_.string(), target, ::getpid(), r, ".tmp"));
      plantLink(temporaryName(dir_.string(), target, ::getpid(), r, ".old"));
    }
  }

  writeText(out, "new");  // one file
  EXPECT_EQ(readWholeFile(out), "new");
  writeFilesAtomically({{out, [](std::ostream& o) { o << "set"; }},  // a set, with backups
                        {companion, [](std::ostream& o) { o << "set companion"; }}});
  EXPECT_EQ(readWholeFile(out), "set");
  EXPECT_EQ(readWholeFile(companion), "set companion");
  EXPECT_EQ(calls, 5 * 13);  // 1 + 2 temporary files and 2 backups, each after 12 planted names

  EXPECT_EQ(readWholeFile(victim), "precious");
  EXPECT_FALSE(existsNoFollow(nowhere));
  for (const std::string& link : planted) EXPECT_TRUE(isLink(link)) << link;  // a live pid's
}

TEST_F(AtomicFileDir, AFailingWriterLeavesThePreviousFileAndNoTemporaryFile) {
  const std::string out = path("out.txt");
  writeText(out, "previous");
  EXPECT_THROW(writeFileAtomically(out,
                                   [](std::ostream& o) {
                                     o << std::string(1 << 20, 'x');
                                     throw Error("the writer failed");
                                   }),
               Error);
  EXPECT_THROW(writeFileAtomically(out,
                                   [](std::ostream& o) {
                                     o << "partial";
                                     throw Cancelled();
                                   }),
               Cancelled);
  try {
    writeFileAtomically(out, [](std::ostream& o) { o.setstate(std::ios::badbit); });
    ADD_FAILURE() << "a stream gone bad must fail the write";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(out), std::string::npos) << e.what();
  }
  EXPECT_EQ(readWholeFile(out), "previous");
  EXPECT_TRUE(temporaryFilesOf(out).empty());
}

TEST_F(AtomicFileDir, ErrorsNameThePathAndLeaveNothing) {
  const std::string missing = path("no/such/folder/out.txt");
  try {
    writeText(missing, "x");
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(missing), std::string::npos) << e.what();
  }
  const std::string folder = path("a-folder");
  fs::create_directory(folder);
  try {
    writeText(folder, "x");
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(folder), std::string::npos) << e.what();
  }
  EXPECT_TRUE(fs::is_directory(folder));
  EXPECT_TRUE(temporaryFilesOf(folder).empty());
  EXPECT_THROW(writeText(dir_.string() + "/", "x"), Error);
}

TEST_F(AtomicFileDir, LongNamesStayWithinTheFileSystemsLimit) {
  const std::string out = path(std::string(250, 'n'));
  writeText(out, "long");
  EXPECT_EQ(readWholeFile(out), "long");
  EXPECT_TRUE(temporaryFilesOf(out).empty());
}

// ---- concurrency ------------------------------------------------------------------------------

TEST_F(AtomicFileDir, ConcurrentThreadsLeaveOneWholeFileAndReadersNeverSeeLess) {
  const std::string out = path("shared.txt");
  writeText(out, wholeFile(0, 0));
  std::atomic<bool> done{false};
  std::atomic<int> broken{0};
  std::thread reader([&] {
    while (!done.load())
      if (!isWhole(readWholeFile(out))) broken.fetch_add(1);
  });
  std::vector<std::thread> writers;
  for (int w = 1; w <= 4; ++w)
    writers.emplace_back([&, w] {
      for (int i = 0; i < 20; ++i) writeText(out, wholeFile(w, i));
    });
  for (auto& t : writers) t.join();
  done.store(true);
  reader.join();
  EXPECT_EQ(broken.load(), 0);
  EXPECT_TRUE(isWhole(readWholeFile(out)));
  EXPECT_TRUE(temporaryFilesOf(out).empty());
}

TEST_F(AtomicFileDir, ConcurrentProcessesLeaveOneWholeFile) {
  const std::string out = path("shared.txt");
  std::vector<pid_t> children;
  for (int w = 0; w < 3; ++w) {
    const pid_t child = ::fork();
    if (child == 0) {
      try {
        for (int i = 0; i < 20; ++i) writeText(out, wholeFile(w, i));
      } catch (...) {
        ::_exit(1);
      }
      ::_exit(0);
    }
    children.push_back(child);
  }
  for (pid_t child : children) {
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  }
  EXPECT_TRUE(isWhole(readWholeFile(out)));
  EXPECT_TRUE(temporaryFilesOf(out).empty());
}

// ---- leftovers --------------------------------------------------------------------------------

TEST_F(AtomicFileDir, LeftoversOfDeadWritersAreRemovedAndNothingElse) {
  const std::string out = path("out.txt");
  const pid_t dead = deadPid();
  ASSERT_NE(::kill(dead, 0), 0);
  const std::string folder = dir_.string();
  const std::vector<std::string> stale = {
      temporaryName(folder, "out.txt", dead, 0x0123456789abcdefull, ".tmp"),
      temporaryName(folder, "out.txt", dead, 0xfedcba9876543210ull, ".old")};
  const std::vector<std::string> kept = {
      temporaryName(folder, "out.txt", ::getpid(), 1, ".tmp"),   // a live writer (this one)
      temporaryName(folder, "out.txt", ::getppid(), 2, ".old"),  // another live process
      temporaryName(folder, "other.txt", dead, 3, ".tmp"),       // another target's
      path("out.txt.tmp"),
      path(".out.txt.tmp"),
      path(".out.txt.strata-" + std::to_string(dead) + "-0123456789ABCDEF.tmp"),  // upper case
      path(".out.txt.strata-" + std::to_string(dead) + "-0123456789abcde.tmp"),   // 15 digits
      path(".out.txt.strata-" + std::to_string(dead) + "-0123456789abcdef.tmpx"),
      path(".out.txt.strata-0-0123456789abcdef.tmp"),  // pid 0 is no process
      path(".out.txt.strata--1-0123456789abcdef.tmp"),
      path(".out.txt.strata-" + std::to_string(dead) + "x-0123456789abcdef.tmp")};
  for (const auto& p : stale) plant(p, "left by a killed writer");
  for (const auto& p : kept) plant(p, "not a leftover");
  const std::string victim = path("victim.txt");
  plant(victim, "precious");
  const std::string staleLink = temporaryName(folder, "out.txt", dead, 4, ".tmp");
  fs::create_symlink(victim, staleLink);

  EXPECT_EQ(temporaryFilesOf(out).size(), 5u);  // 2 stale, the link, 2 live
  writeText(out, "new");
  for (const auto& p : stale) EXPECT_FALSE(existsNoFollow(p)) << p;
  for (const auto& p : kept) EXPECT_TRUE(existsNoFollow(p)) << p;
  EXPECT_FALSE(existsNoFollow(staleLink));  // the link removed, what it pointed to kept
  EXPECT_EQ(readWholeFile(victim), "precious");
  EXPECT_EQ(readWholeFile(out), "new");
}

TEST_F(AtomicFileDir, AFolderNamedLikeALeftoverIsNotRemoved) {
  const std::string out = path("out.txt");
  const std::string folder = temporaryName(dir_.string(), "out.txt", deadPid(), 5, ".tmp");
  fs::create_directory(folder);
  plant(folder + "/inside", "kept");
  writeText(out, "new");
  EXPECT_EQ(readWholeFile(folder + "/inside"), "kept");
}

// ---- sets -------------------------------------------------------------------------------------

TEST_F(AtomicFileDir, ASetReplacesEveryFile) {
  const std::string main = path("part.obj");
  const std::string companion = path("part.mtl");
  plant(main, "old main");
  writeFilesAtomically({{main, [](std::ostream& o) { o << "main"; }},
                        {companion, [](std::ostream& o) { o << "companion"; }}});
  EXPECT_EQ(readWholeFile(main), "main");
  EXPECT_EQ(readWholeFile(companion), "companion");
  EXPECT_TRUE(temporaryFilesOf(main).empty());
  EXPECT_TRUE(temporaryFilesOf(companion).empty());
  EXPECT_THROW(writeFilesAtomically({{main, [](std::ostream&) {}}, {main, [](std::ostream&) {}}}),
               Error);
}

// The main file (replaced last) cannot be replaced: a folder stands at its path. The companion
// already replaced is put back, the one that did not exist is removed again.
TEST_F(AtomicFileDir, AFailedRenamePutsBackEveryFileAlreadyReplaced) {
  const std::string main = path("part.obj");
  const std::string existing = path("part.mtl");
  const std::string fresh = path("part.txt");
  const std::string victim = path("victim.txt");
  const std::string linked = path("linked.txt");
  fs::create_directory(main);
  plant(existing, "old companion");
  plant(victim, "precious");
  fs::create_symlink(victim, linked);
  try {
    writeFilesAtomically({{main, [](std::ostream& o) { o << "main"; }},
                          {existing, [](std::ostream& o) { o << "new companion"; }},
                          {linked, [](std::ostream& o) { o << "new linked"; }},
                          {fresh, [](std::ostream& o) { o << "new fresh"; }}});
    ADD_FAILURE() << "a folder cannot be replaced by a file";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(main), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("no file was replaced"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(fs::is_directory(main));
  EXPECT_EQ(readWholeFile(existing), "old companion");
  EXPECT_TRUE(isLink(linked));
  EXPECT_EQ(fs::read_symlink(linked).string(), victim);
  EXPECT_EQ(readWholeFile(victim), "precious");
  EXPECT_FALSE(existsNoFollow(fresh));
  for (const auto& p : {main, existing, linked, fresh})
    EXPECT_TRUE(temporaryFilesOf(p).empty()) << p;
}

TEST_F(AtomicFileDir, AFailingWriterInASetReplacesNothing) {
  const std::string main = path("part.obj");
  const std::string companion = path("part.mtl");
  plant(main, "old main");
  plant(companion, "old companion");
  EXPECT_THROW(
      writeFilesAtomically({{main, [](std::ostream& o) { o << "main"; }},
                            {companion, [](std::ostream&) { throw Error("the writer failed"); }}}),
      Error);
  EXPECT_EQ(readWholeFile(main), "old main");
  EXPECT_EQ(readWholeFile(companion), "old companion");
  EXPECT_TRUE(temporaryFilesOf(main).empty());
  EXPECT_TRUE(temporaryFilesOf(companion).empty());
}

// Sets commit under an flock(2) of their folder (as documented): a reader holding it sees both
// files from one writer, and the last writer's set is what remains.
TEST_F(AtomicFileDir, ConcurrentSetsEndAsOneWritersWholeSet) {
  const std::string main = path("part.obj");
  const std::string companion = path("part.mtl");
  auto set = [&](const std::string& text) {
    writeFilesAtomically({{main, [&](std::ostream& o) { o << text; }},
                          {companion, [&](std::ostream& o) { o << text; }}});
  };
  set("initial");
  std::atomic<bool> done{false};
  std::atomic<int> mixed{0}, looks{0};
  std::thread reader([&] {
    while (!done.load()) {
      const int folder = ::open(dir_.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
      ASSERT_GE(folder, 0);
      ASSERT_EQ(::flock(folder, LOCK_SH), 0);
      if (readWholeFile(main) != readWholeFile(companion)) mixed.fetch_add(1);
      looks.fetch_add(1);
      ::close(folder);
    }
  });
  std::vector<std::thread> writers;
  for (int w = 0; w < 4; ++w)
    writers.emplace_back([&, w] {
      for (int i = 0; i < 100; ++i) set(std::to_string(w) + " " + std::to_string(i));
    });
  for (auto& t : writers) t.join();
  done.store(true);
  reader.join();
  EXPECT_EQ(mixed.load(), 0) << "of " << looks.load();
  EXPECT_EQ(readWholeFile(main), readWholeFile(companion));
  EXPECT_TRUE(temporaryFilesOf(main).empty());
  EXPECT_TRUE(temporaryFilesOf(companion).empty());
}

// Where the file system has no hard links (FAT), the previous versions are kept as copies: a
// regular file (its permissions too) and a link are put back just the same.
TEST_F(AtomicFileDir, WithoutHardLinksBackupsAreCopiesAndPutBackTheSame) {
  AtomicFileTestHooks hooks;
  hooks.refuseHardLinks = true;
  setAtomicFileTestHooks(hooks);
  const std::string main = path("part.obj");
  const std::string existing = path("part.mtl");
  const std::string victim = path("victim.txt");
  const std::string linked = path("linked.txt");
  plant(existing, std::string(300000, 'm'));
  ASSERT_EQ(::chmod(existing.c_str(), 0640), 0);
  plant(victim, "precious");
  fs::create_symlink(victim, linked);
  fs::create_directory(main);
  EXPECT_THROW(writeFilesAtomically({{main, [](std::ostream& o) { o << "main"; }},
                                     {existing, [](std::ostream& o) { o << "new"; }},
                                     {linked, [](std::ostream& o) { o << "new"; }}}),
               Error);
  EXPECT_EQ(readWholeFile(existing), std::string(300000, 'm'));
  struct stat st;
  ASSERT_EQ(::stat(existing.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 0777, 0640u);
  EXPECT_TRUE(isLink(linked));
  EXPECT_EQ(readWholeFile(victim), "precious");
  for (const auto& p : {main, existing, linked}) EXPECT_TRUE(temporaryFilesOf(p).empty()) << p;

  fs::remove(main);
  writeFilesAtomically({{main, [](std::ostream& o) { o << "main"; }},
                        {existing, [](std::ostream& o) { o << "new"; }}});
  EXPECT_EQ(readWholeFile(main), "main");
  EXPECT_EQ(readWholeFile(existing), "new");
  EXPECT_TRUE(temporaryFilesOf(existing).empty());
}

// Single-file writers do not take the folder's lock; a set writing the same paths meanwhile still
// succeeds (its backup of a file replaced under it is taken again).
TEST_F(AtomicFileDir, SetsAndSingleWritersOfTheSamePathsBothSucceed) {
  const std::string main = path("part.obj");
  const std::string companion = path("part.mtl");
  writeText(main, "initial");
  writeText(companion, "initial");
  std::atomic<int> failures{0};
  std::vector<std::thread> writers;
  for (int w = 0; w < 4; ++w)
    writers.emplace_back([&, w] {
      for (int i = 0; i < 100; ++i) {
        const std::string text = std::to_string(w) + " " + std::to_string(i);
        try {
          if (w % 2)
            writeText(w == 1 ? main : companion, text);
          else
            writeFilesAtomically({{main, [&](std::ostream& o) { o << text; }},
                                  {companion, [&](std::ostream& o) { o << text; }}});
        } catch (const std::exception& e) {
          failures.fetch_add(1);
          ADD_FAILURE() << e.what();
        }
      }
    });
  for (auto& t : writers) t.join();
  EXPECT_EQ(failures.load(), 0);
  EXPECT_TRUE(temporaryFilesOf(main).empty());
  EXPECT_TRUE(temporaryFilesOf(companion).empty());
}

// ---- the signal path --------------------------------------------------------------------------

// In a child (abandoning is for good): a signal handler's abandonAtomicWritesForExit() in the
// middle of a write removes its temporary file and refuses new ones; the old file stays.
TEST_F(AtomicFileDir, AbandoningRemovesTheFilesInFlightAndRefusesNewOnes) {
  const std::string out = path("out.txt");
  plant(out, "previous");
  const pid_t child = ::fork();
  if (child == 0) {
    int code = 1;
    try {
      writeFileAtomically(out, [&](std::ostream& o) {
        o << "half";
        o.flush();
        if (temporaryFilesOf(out).size() != 1) ::_exit(2);
        abandonAtomicWritesForExit();
        if (!temporaryFilesOf(out).empty()) ::_exit(3);
        ::_exit(4);  // as the handler would, before the write could finish
      });
    } catch (...) {
    }
    ::_exit(code);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 4);
  EXPECT_EQ(readWholeFile(out), "previous");
  EXPECT_TRUE(temporaryFilesOf(out).empty());

  const pid_t refusing = ::fork();
  if (refusing == 0) {
    abandonAtomicWritesForExit();
    try {
      writeText(out, "after");
    } catch (const Cancelled&) {
      ::_exit(5);
    } catch (...) {
    }
    ::_exit(6);
  }
  ASSERT_EQ(::waitpid(refusing, &status, 0), refusing);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 5);
  EXPECT_EQ(readWholeFile(out), "previous");
}

// A child forked while the parent writes (the editor's file dialog forks) and ending from a
// signal handler leaves the parent's temporary file alone.
TEST_F(AtomicFileDir, AForkedChildAbandoningLeavesItsParentsWriteAlone) {
  const std::string out = path("out.txt");
  writeFileAtomically(out, [&](std::ostream& o) {
    o << "parent";
    const pid_t child = ::fork();
    if (child == 0) {
      abandonAtomicWritesForExit();
      ::_exit(0);
    }
    int status = 0;
    ::waitpid(child, &status, 0);
    EXPECT_EQ(temporaryFilesOf(out).size(), 1u);
  });
  EXPECT_EQ(readWholeFile(out), "parent");
}

}  // namespace
}  // namespace strata

namespace strata {
namespace {

// Input files are checked before they are read: devices and folders are refused at once, and a
// file over the limit is refused naming its size and the option that raises the limit.
// A report written to /dev/stdout or a FIFO, as root, renamed a file over the device or the pipe
// (over /dev/stdout for the whole system): a device, a pipe or a link to one is written through,
// in place; /dev/full's refusal is an error; files written together refuse them; an export, read
// back to check it, is told why it cannot go there.
TEST_F(AtomicFileDir, DevicesAndPipesAreWrittenThroughNeverReplaced) {
  const std::string fifo = path("pipe.json");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  std::string read;
  std::thread reader([&] {
    std::FILE* f = std::fopen(fifo.c_str(), "rb");
    ASSERT_NE(f, nullptr);
    char buffer[256];
    size_t n;
    while ((n = std::fread(buffer, 1, sizeof(buffer), f)) > 0) read.append(buffer, n);
    std::fclose(f);
  });
  writeText(fifo, "through the pipe");
  reader.join();
  EXPECT_EQ(committedFiles().back(), fifo);  // what a cancel during a check says was written
  EXPECT_EQ(read, "through the pipe");
  struct stat st;
  ASSERT_EQ(::stat(fifo.c_str(), &st), 0);
  EXPECT_TRUE(S_ISFIFO(st.st_mode)) << "the pipe was replaced";
  const std::string link = path("null.json");
  ASSERT_EQ(::symlink("/dev/null", link.c_str()), 0);
  writeText(link, "nothing");
  EXPECT_TRUE(isLink(link));
  ASSERT_EQ(::stat("/dev/null", &st), 0);
  EXPECT_TRUE(S_ISCHR(st.st_mode));
  if (::stat("/dev/full", &st) == 0 && S_ISCHR(st.st_mode)) {
    try {
      writeText("/dev/full", "no room");
      ADD_FAILURE() << "/dev/full took it";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("/dev/full: cannot write"), std::string::npos)
          << e.what();
    }
    ASSERT_EQ(::stat("/dev/full", &st), 0);
    EXPECT_TRUE(S_ISCHR(st.st_mode));
  }
  EXPECT_THROW(writeFilesAtomically({{path("a.obj"), [](std::ostream& o) { o << "a"; }},
                                     {link, [](std::ostream& o) { o << "b"; }}}),
               Error);
  EXPECT_FALSE(fs::exists(path("a.obj")));
  EXPECT_NE(notAFileToReadBack(link).find("not a regular file"), std::string::npos);
  EXPECT_NE(notAFileToReadBack(fifo).find("not a regular file"), std::string::npos);
  EXPECT_EQ(notAFileToReadBack(path("new.stl")), "");
  plant(path("old.stl"), "old");
  EXPECT_EQ(notAFileToReadBack(path("old.stl")), "");
}

TEST(ReadWholeFile, RefusesDevicesFoldersAndFilesOverTheLimit) {
  auto message = [](const std::string& path) {
    try {
      readWholeFile(path);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("(read)");
  };
  EXPECT_NE(message("/dev/zero").find("/dev/zero: is a device"), std::string::npos);
  EXPECT_NE(message(testing::TempDir()).find("is a folder"), std::string::npos);
  const std::string file = testing::TempDir() + "/strata_limit_test.txt";
  writeFileAtomically(file, [](std::ostream& out) { out << std::string(3000, 'x'); });
  const uint64_t saved = maxInputFileBytes();
  setMaxInputFileBytes(3000);
  EXPECT_EQ(readWholeFile(file).size(), 3000u);
  setMaxInputFileBytes(2999);
  const std::string m = message(file);
  setMaxInputFileBytes(saved);
  EXPECT_NE(m.find("larger than the limit"), std::string::npos) << m;
  EXPECT_NE(m.find("--max-file-size"), std::string::npos) << m;
  std::remove(file.c_str());
}

// The export reads back its own file with the limit lifted on its thread alone.
TEST(ReadWholeFile, LiftedLimitHoldsOnThisThreadOnly) {
  const std::string file = testing::TempDir() + "/strata_lifted_test.txt";
  writeFileAtomically(file, [](std::ostream& out) { out << std::string(3000, 'x'); });
  const uint64_t saved = maxInputFileBytes();
  setMaxInputFileBytes(100);
  size_t liftedSize = 0;
  bool otherThreadRefused = false;
  {
    const InputLimitLifted lifted;
    liftedSize = readWholeFile(file).size();
    std::thread other([&] {
      try {
        readWholeFile(file);
      } catch (const Error&) {
        otherThreadRefused = true;
      }
    });
    other.join();
  }
  bool refusedAfter = false;
  try {
    readWholeFile(file);
  } catch (const Error&) {
    refusedAfter = true;
  }
  setMaxInputFileBytes(saved);
  std::remove(file.c_str());
  EXPECT_EQ(liftedSize, 3000u);
  EXPECT_TRUE(otherThreadRefused);
  EXPECT_TRUE(refusedAfter);
}

}  // namespace
}  // namespace strata
