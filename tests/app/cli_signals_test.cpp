// The `strata` command line under signals (app/signal_cancellation.h): SIGTERM, SIGINT and
// SIGHUP end it cleanly with 128 + the signal's number, keep the previous files and leave no
// temporary file, while a mesh loads as while an export writes; what a SIGKILL leaves behind is
// removed by the next export of the same file. No timing is asserted: the tests wait for what
// the process does (a temporary file appearing, a FIFO opened), and stop it to look.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include "engine/util/atomic_file.h"

extern char** environ;

namespace strata {
namespace {
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

const std::string kDemo = std::string(STRATA_ASSETS) + "/scenes/demo.strata.json";
constexpr auto kPatience = std::chrono::seconds(300);  // generous: sanitizer builds, busy hosts

// A running `strata`, stdout and stderr into a log file.
class Strata {
 public:
  Strata(const std::vector<std::string>& args, const std::string& log) : log_(log) {
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&actions, 1, 2);
    std::vector<std::string> all{STRATA_BINARY};
    all.insert(all.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (auto& a : all) argv.push_back(&a[0]);
    argv.push_back(nullptr);
    if (posix_spawn(&pid_, STRATA_BINARY, &actions, nullptr, argv.data(), environ) != 0) pid_ = -1;
    posix_spawn_file_actions_destroy(&actions);
  }
  ~Strata() {
    if (running()) {
      ::kill(pid_, SIGKILL);
      finish();
    }
  }
  pid_t pid() const { return pid_; }
  bool running() {
    if (pid_ < 0 || done_) return false;
    if (::waitpid(pid_, &status_, WNOHANG) == pid_) done_ = true;
    return !done_;
  }
  // The exit code, or 1000 + the signal that ended it.
  int finish() {
    if (pid_ < 0) return -1;
    if (!done_ && ::waitpid(pid_, &status_, 0) == pid_) done_ = true;
    return WIFEXITED(status_) ? WEXITSTATUS(status_) : 1000 + WTERMSIG(status_);
  }
  std::string output() const {
    std::error_code ec;
    return fs::exists(log_, ec) ? readWholeFile(log_) : "";
  }

 private:
  std::string log_;
  pid_t pid_ = -1;
  int status_ = 0;
  bool done_ = false;
};

// Polls `condition` until it holds (true) or `process` has ended or patience ran out (false).
bool waitUntil(Strata& process, const std::function<bool()>& condition) {
  const auto end = Clock::now() + kPatience;
  while (Clock::now() < end) {
    if (condition()) return true;
    if (!process.running()) return false;
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
  return false;
}

class CliSignals : public testing::Test {
 protected:
  void SetUp() override {
    const auto* info = testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::path(testing::TempDir()) /
           ("strata_cli_signals_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  static void plant(const std::string& path, const std::string& text) {
    writeFileAtomically(path, [&](std::ostream& out) { out << text; });
  }

  fs::path dir_;
};

// Starts an OBJ export of the demo scene over "old" files and stops it (SIGSTOP) while it
// writes the OBJ: the OBJ's temporary file exists and the MTL's does not yet (it is written
// after). Retries at higher resolutions when the export was too quick to catch. Returns the
// stopped process, or null.
std::unique_ptr<Strata> stopWhileWritingObj(const std::string& obj, const std::string& mtl,
                                            const std::string& log) {
  for (const char* resolution : {"256", "384", "512"}) {
    writeFileAtomically(obj, [](std::ostream& out) { out << "old obj"; });
    writeFileAtomically(mtl, [](std::ostream& out) { out << "old mtl"; });
    auto process = std::make_unique<Strata>(
        std::vector<std::string>{"export", kDemo, "--resolution", resolution, "--backend", "cpu",
                                 "-q", "-o", obj},
        log);
    auto writingObj = [&] {
      return !temporaryFilesOf(obj).empty() && temporaryFilesOf(mtl).empty();
    };
    if (!waitUntil(*process, writingObj)) continue;
    ::kill(process->pid(), SIGSTOP);
    // Stopped: nothing changes now. Still writing the OBJ?
    bool stopped = false;
    for (int i = 0; i < 1000 && !stopped; ++i) {
      char state = 0;
      if (std::FILE* f =
              std::fopen(("/proc/" + std::to_string(process->pid()) + "/stat").c_str(), "r")) {
        std::fscanf(f, "%*d %*s %c", &state);
        std::fclose(f);
      }
      stopped = state == 'T';
      if (!stopped) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    if (stopped && writingObj()) return process;
    ::kill(process->pid(), SIGKILL);
    process->finish();
  }
  return nullptr;
}

TEST_F(CliSignals, SigtermWhileAnExportWritesKeepsThePreviousFilesAndLeavesNoTemporary) {
  const std::string obj = path("part.obj");
  const std::string mtl = path("part.mtl");
  auto process = stopWhileWritingObj(obj, mtl, path("log.txt"));
  ASSERT_TRUE(process) << "never caught strata writing " << obj;
  ::kill(process->pid(), SIGTERM);
  ::kill(process->pid(), SIGCONT);
  EXPECT_EQ(process->finish(), 143) << process->output();
  EXPECT_NE(process->output().find("cancelled"), std::string::npos) << process->output();
  EXPECT_EQ(readWholeFile(obj), "old obj");
  EXPECT_EQ(readWholeFile(mtl), "old mtl");
  EXPECT_TRUE(temporaryFilesOf(obj).empty());
  EXPECT_TRUE(temporaryFilesOf(mtl).empty());
}

TEST_F(CliSignals, SigkillLeavesATemporaryFileTheNextExportRemoves) {
  const std::string obj = path("part.obj");
  const std::string mtl = path("part.mtl");
  auto process = stopWhileWritingObj(obj, mtl, path("log.txt"));
  ASSERT_TRUE(process) << "never caught strata writing " << obj;
  ::kill(process->pid(), SIGKILL);
  EXPECT_EQ(process->finish(), 1000 + SIGKILL);
  EXPECT_EQ(readWholeFile(obj), "old obj");
  EXPECT_EQ(readWholeFile(mtl), "old mtl");
  ASSERT_EQ(temporaryFilesOf(obj).size(), 1u);  // what SIGKILL leaves

  Strata next({"export", kDemo, "--resolution", "32", "-q", "-o", obj}, path("next.txt"));
  ASSERT_EQ(next.finish(), 0) << next.output();
  EXPECT_TRUE(temporaryFilesOf(obj).empty());
  EXPECT_TRUE(temporaryFilesOf(mtl).empty());
  EXPECT_NE(readWholeFile(obj).find("mtllib part.mtl"), std::string::npos);
}

// A FIFO (or a device such as /dev/zero) as a mesh is refused at once, without blocking on it.
TEST_F(CliSignals, AFifoAsAMeshIsRefusedWithoutBlocking) {
  const std::string fifo = path("slow.obj");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const std::string out = path("out.stl");
  plant(out, "old stl");
  Strata process({"boolean", "union", fifo, std::string(STRATA_TEST_DATA) + "/bunny.obj",
                  "--resolution", "32", "-q", "-o", out},
                 path("log.txt"));
  EXPECT_EQ(process.finish(), 1) << process.output();
  EXPECT_NE(process.output().find("slow.obj: is a FIFO"), std::string::npos) << process.output();
  EXPECT_EQ(readWholeFile(out), "old stl");
}

// True when `pid` has `file` open (it is reading it).
bool hasOpen(pid_t pid, const std::string& file) {
  std::error_code ec;
  const fs::path want = fs::canonical(file, ec);
  for (const auto& fd : fs::directory_iterator("/proc/" + std::to_string(pid) + "/fd", ec)) {
    std::error_code linkError;
    if (fs::read_symlink(fd.path(), linkError) == want) return true;
  }
  return false;
}

// The bytes `pid` has read so far (rchar of /proc/PID/io: every read(2), not only the disk's);
// 0 where it cannot be told.
uint64_t bytesRead(pid_t pid) {
  std::ifstream io("/proc/" + std::to_string(pid) + "/io");
  std::string key;
  uint64_t value = 0;
  while (io >> key >> value)
    if (key == "rchar:") return value;
  return 0;
}

// A large mesh: once strata has it open it is loading it; each signal then ends the command
// cleanly, whether it lands in the load or, on a fast machine, in the evaluation after it.
TEST_F(CliSignals, SignalsWhileAMeshLoadsEndItCleanly) {
  const std::string big = path("big.obj");
  writeFileAtomically(big, [](std::ostream& obj) {
    for (int t = 0; t < 200000; ++t) {  // disjoint closed tetrahedra
      const double x = 3.0 * (t % 1000), y = 3.0 * (t / 1000);
      obj << "v " << x << ' ' << y << " 0\nv " << x + 1 << ' ' << y << " 0\nv " << x << ' ' << y + 1
          << " 0\nv " << x << ' ' << y << " 1\n";
      const int v = 4 * t + 1;
      obj << "f " << v << ' ' << v + 2 << ' ' << v + 1 << "\nf " << v << ' ' << v + 1 << ' '
          << v + 3 << "\nf " << v << ' ' << v + 3 << ' ' << v + 2 << "\nf " << v + 1 << ' ' << v + 2
          << ' ' << v + 3 << '\n';
    }
  });
  const std::string out = path("out.stl");
  plant(out, "old stl");
  for (const auto& [sig, code] :
       {std::pair(SIGINT, 130), std::pair(SIGTERM, 143), std::pair(SIGHUP, 129)}) {
    Strata process({"boolean", "union", big, std::string(STRATA_TEST_DATA) + "/bunny.obj",
                    "--resolution", "512", "-q", "-o", out},
                   path("log.txt"));
    // Open, or read already and being parsed (the read itself lasts a few milliseconds: on a
    // loaded machine the polls missed it, and the command ran to its end).
    const uint64_t size = fs::file_size(big);
    const bool reading = waitUntil(
        process, [&] { return hasOpen(process.pid(), big) || bytesRead(process.pid()) >= size; });
    ASSERT_TRUE(reading) << process.output();
    ::kill(process.pid(), sig);
    EXPECT_EQ(process.finish(), code) << sig << ": " << process.output();
    EXPECT_NE(process.output().find("cancelled"), std::string::npos) << process.output();
    EXPECT_EQ(readWholeFile(out), "old stl");
    EXPECT_TRUE(temporaryFilesOf(out).empty());
  }
}

}  // namespace
}  // namespace strata
