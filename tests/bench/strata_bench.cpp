// strata_bench: prints a table of sampling and Boolean times, surfels and peak memory for real
// meshes at several resolutions, on the CPU backend. Each row runs in a forked child process,
// so its peak resident memory is its own.
//
// usage: strata_bench [--meshes bunny,armadillo] [--resolutions 256,512,1024] [--threads N]
// The results and the command that made them are recorded in tests/bench/RESULTS.md.
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "engine/eval/cpu_backend.h"
#include "engine/eval/evaluator.h"
#include "engine/io/mesh_io.h"
#include "engine/util/memory.h"
#include "engine/util/parallel_for.h"
#include "engine/util/timer.h"

namespace {
using namespace strata;

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream in(s);
  std::string item;
  while (std::getline(in, item, ',')) out.push_back(item);
  return out;
}

// The benchmark scene: the mesh minus a copy of itself shifted by (0.3, 0.2, 0.1) of its size.
Scene benchScene(const std::shared_ptr<const TriangleMesh>& mesh, int resolution) {
  Bounds b = meshBounds(*mesh);
  auto a = std::make_shared<Node>();
  a->id = 2;
  a->kind = NodeKind::Mesh;
  a->name = "mesh";
  a->mesh = mesh;
  auto c = std::make_shared<Node>(*a);
  c->id = 3;
  c->name = "shifted";
  c->transform.translate = b.size() * glm::dvec3(0.3, 0.2, 0.1);
  auto root = std::make_shared<Node>();
  root->id = 1;
  root->kind = NodeKind::Difference;
  root->children = {a, c};
  Scene scene;
  scene.root = root;
  scene.settings.resolution = resolution;
  return scene;
}

std::string runRow(const std::string& name, int resolution) {
  auto mesh = std::make_shared<TriangleMesh>(
      readMeshFile(std::string(STRATA_TEST_DATA) + "/" + name + ".obj"));
  Scene scene = benchScene(mesh, resolution);
  Evaluator evaluator(std::make_shared<CpuBackend>());
  Progress progress;
  EvalResult r = evaluator.evaluate(scene, EvalOptions{}, progress);
  double sample = 0, boolean = 0;
  uint64_t sampled = 0;
  for (const auto& s : r.stages) {
    if (s.name == "sample") {
      sample = s.seconds;
      sampled = s.surfels;
    }
    if (s.name == "boolean") boolean = s.seconds;
  }
  char line[256];
  std::snprintf(line, sizeof(line),
                "| %-9s | %5d | %7zu | %8.3f | %8.3f | %12llu | %12llu | %9.1f | %9.1f |", name.c_str(),
                resolution, mesh->triangles.size(), sample, boolean,
                static_cast<unsigned long long>(sampled),
                static_cast<unsigned long long>(r.measure.surfels),
                double(r.cacheBytes) / 1048576.0, double(peakResidentBytes()) / 1048576.0);
  return line;
}

// Runs one row in a child process and returns its line (or the failure).
std::string forkRow(const std::string& name, int resolution) {
  int fds[2];
  if (pipe(fds) != 0) return "pipe failed";
  pid_t pid = fork();
  if (pid == 0) {
    close(fds[0]);
    std::string line;
    try {
      line = runRow(name, resolution);
    } catch (const std::exception& e) {
      line = "| " + name + " | " + std::to_string(resolution) + " | failed: " + e.what();
    }
    ssize_t ignored = write(fds[1], line.data(), line.size());
    (void)ignored;
    _exit(0);
  }
  close(fds[1]);
  std::string out;
  char buffer[512];
  ssize_t n;
  while ((n = read(fds[0], buffer, sizeof(buffer))) > 0) out.append(buffer, size_t(n));
  close(fds[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  if (out.empty()) out = "| " + name + " | " + std::to_string(resolution) + " | crashed";
  return out;
}
}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> meshes = {"bunny", "armadillo"};
  std::vector<std::string> resolutions = {"256", "512", "1024"};
  for (int i = 1; i + 1 < argc; i += 2) {
    std::string key = argv[i];
    if (key == "--meshes") meshes = split(argv[i + 1]);
    else if (key == "--resolutions") resolutions = split(argv[i + 1]);
    else if (key == "--threads") setWorkerCount(std::atoi(argv[i + 1]));
    else {
      std::fprintf(stderr, "unknown option %s\n", argv[i]);
      return 2;
    }
  }
  std::printf("strata_bench: mesh minus a shifted copy of itself, CPU backend, %d threads, "
              "%u hardware threads\n\n",
              workerCount(), std::thread::hardware_concurrency());
  std::printf("| mesh      |   res | triangles | sample s | boolean s | sampled surfels | result "
              "surfels | LDIs MiB | peak RSS MiB |\n");
  std::printf("|-----------|------:|----------:|---------:|----------:|----------------:|-------"
              "-------:|---------:|-------------:|\n");
  for (const auto& m : meshes)
    for (const auto& r : resolutions) {
      std::printf("%s\n", forkRow(m, std::atoi(r.c_str())).c_str());
      std::fflush(stdout);
    }
  return 0;
}
