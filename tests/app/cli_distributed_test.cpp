// `mpirun -np N strata export ... --distributed` end to end: the file of three processes is the
// file of one, byte for byte; a process killed halfway ends the job with an error naming it and
// leaves the file that was at the output path as it was. Skips, saying why, where Open MPI
// (mpirun) or the plugin (a build without libopenmpi-dev) is missing.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

namespace {

struct ShellRun {
  int code = -1;
  std::string output;  // stdout and stderr together
};

ShellRun shell(const std::string& command) {
  ShellRun run;
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (!pipe) return run;
  char buffer[4096];
  size_t n;
  while ((n = fread(buffer, 1, sizeof(buffer), pipe)) > 0) run.output.append(buffer, n);
  const int status = pclose(pipe);
  run.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return run;
}

std::string bytesOf(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string temp(const std::string& name) {
  return testing::TempDir() + "/strata_distributed_cli_" + name;
}

// The plugin lives beside the binary (dist/CMakeLists.txt).
std::string pluginPath() {
  const std::string binary = STRATA_BINARY;
  return binary.substr(0, binary.rfind('/')) + "/libstrata_mpi.so";
}

// Open MPI refuses root without these (CI runs as root); its libraries keep allocations until
// exit, which LeakSanitizer would report in the sanitizer build.
const char* kMpiEnvironment =
    "env OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 "
    "OMPI_MCA_rmaps_base_oversubscribe=1 "
    "ASAN_OPTIONS=detect_leaks=0 ";

std::string scene() {
  return std::string(STRATA_ASSETS) + "/scenes/demo.strata.json";
}

class DistributedCli : public testing::Test {
 protected:
  void SetUp() override {
    if (shell("command -v mpirun").code != 0)
      GTEST_SKIP() << "mpirun not found (Debian: openmpi-bin; .ci/deps installs it)";
    if (access(pluginPath().c_str(), F_OK) != 0)
      GTEST_SKIP() << "built without MPI: " << pluginPath() << " is missing (libopenmpi-dev)";
  }
};

TEST_F(DistributedCli, ThreeProcessesWriteTheFileOfOne) {
  const std::string one = temp("one.stl"), three = temp("three.stl");
  std::remove(three.c_str());
  const std::string args = " export " + scene() + " --resolution 120 --tile 32 --backend cpu ";
  const ShellRun single = shell(std::string(STRATA_BINARY) + args + "-q -o " + one);
  ASSERT_EQ(single.code, 0) << single.output;
  const ShellRun group = shell(std::string(kMpiEnvironment) + "mpirun -np 3 --oversubscribe " +
                               STRATA_BINARY + args + "--distributed -o " + three);
  ASSERT_EQ(group.code, 0) << group.output;
  EXPECT_NE(group.output.find("3 processes: every tile in"), std::string::npos) << group.output;
  EXPECT_NE(group.output.find("process 2 of 3 contoured"), std::string::npos) << group.output;
  const std::string a = bytesOf(one), b = bytesOf(three);
  ASSERT_GT(a.size(), 10000u);
  EXPECT_TRUE(a == b) << "the three processes' file differs from the one process's";
  // Process 0 writing the file in pieces as the slabs of tiles come in: the same bytes.
  const std::string streamed = temp("three_streamed.stl");
  std::remove(streamed.c_str());
  const ShellRun pieces = shell(std::string(kMpiEnvironment) + "mpirun -np 3 --oversubscribe " +
                                STRATA_BINARY + args + "--distributed --stream -o " + streamed);
  ASSERT_EQ(pieces.code, 0) << pieces.output;
  EXPECT_NE(pieces.output.find("passed the watertight check"), std::string::npos) << pieces.output;
  EXPECT_TRUE(a == bytesOf(streamed)) << "the streamed file differs from the one process's";
  // And as PLY (its vertices numbered on process 0 before the faces are written).
  const std::string onePly = temp("one.ply"), threePly = temp("three_streamed.ply");
  std::remove(threePly.c_str());
  ASSERT_EQ(shell(std::string(STRATA_BINARY) + args + "-q -o " + onePly).code, 0);
  const ShellRun ply = shell(std::string(kMpiEnvironment) + "mpirun -np 3 --oversubscribe " +
                             STRATA_BINARY + args + "--distributed --stream -o " + threePly);
  ASSERT_EQ(ply.code, 0) << ply.output;
  EXPECT_TRUE(bytesOf(onePly) == bytesOf(threePly)) << "the streamed PLY differs";
}

TEST_F(DistributedCli, AProcessKilledHalfwayEndsTheJobAndLeavesTheOldFile) {
  const std::string path = temp("killed.stl");
  {
    std::ofstream old(path, std::ios::binary);
    old << "the good file from before";
  }
  const ShellRun group = shell(
      std::string(kMpiEnvironment) + "mpirun -np 3 --oversubscribe -x STRATA_TEST_KILL_PROCESS=1 " +
      STRATA_BINARY + " export " + scene() +
      " --resolution 120 --tile 32 --backend cpu --distributed -q -o " + path);
  EXPECT_NE(group.code, 0) << group.output;
  EXPECT_NE(group.output.find("rank 1"), std::string::npos) << group.output;
  EXPECT_NE(group.output.find("signal 9"), std::string::npos) << group.output;
  EXPECT_EQ(bytesOf(path), "the good file from before");
  const ShellRun streamed = shell(
      std::string(kMpiEnvironment) + "mpirun -np 3 --oversubscribe -x STRATA_TEST_KILL_PROCESS=1 " +
      STRATA_BINARY + " export " + scene() +
      " --resolution 120 --tile 32 --backend cpu --distributed --stream -q -o " + path);
  EXPECT_NE(streamed.code, 0) << streamed.output;
  EXPECT_EQ(bytesOf(path), "the good file from before");
}

}  // namespace
