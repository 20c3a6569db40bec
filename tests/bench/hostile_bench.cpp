// hostile_bench: how the cost of hostile inputs grows with their size (tests/README.md lists
// the families). For each family it builds inputs of growing size in memory, runs them through
// the same code the command line runs (readers, scene parser, expansion check, CPU evaluation),
// and prints a markdown table: size, seconds, peak memory of the row, and the growth exponent
// k of time ~ size^k against the row before. The bound every family must hold is n log n:
// k <= 1.3 once the times are large enough to measure (above 50 ms).
//
// Each row runs in a forked child, so its peak memory is its own, and a row that fails or
// takes over --limit seconds prints that instead of ending the table.
//
// usage: strata_hostile_bench [--quick] [--limit SECONDS]   (--quick: the two smallest sizes)
// Results are recorded in tests/bench/RESULTS.md.
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "engine/document/expansion.h"
#include "engine/eval/cpu_backend.h"
#include "engine/eval/evaluator.h"
#include "engine/io/mesh_io.h"
#include "engine/io/scene_file.h"
#include "engine/util/error.h"
#include "engine/util/timer.h"
#include "tests/fuzz/fuzz_entries.h"

namespace strata {
namespace {

// A scene file whose root unites `n` unit boxes at distinct places.
std::string distinctBoxesScene(int n) {
  std::string s = R"({"format":"strata-scene","version":1,"settings":{"resolution":256},)"
                  R"("root":{"id":1,"type":"union","children":[)";
  uint64_t seed = 12345;
  auto next = [&] {
    seed = seed * 6364136223846793005ull + 1442695040888963407ull;
    return double(seed >> 11) / double(1ull << 53) * 100.0 - 50.0;
  };
  for (int i = 0; i < n; ++i) {
    char node[256];
    std::snprintf(node, sizeof(node),
                  R"(%s{"id":%d,"type":"box","size":[0.5,0.5,0.5],)"
                  R"("transform":{"translate":[%.4f,%.4f,%.4f]}})",
                  i ? "," : "", i + 2, next(), next(), next());
    s += node;
  }
  return s + "]}}";
}

// A scene whose instances double `levels` times: level k unites two instances of level k-1.
std::string doublingScene(int levels) {
  std::string s = R"({"format":"strata-scene","version":1,"root":{"id":1,"type":"union",)"
                  R"("children":[{"id":2,"type":"box","visible":false})";
  int id = 3;
  for (int k = 0; k < levels; ++k) {
    const int below = k == 0 ? 2 : id - 3;
    s += ",{\"id\":" + std::to_string(id) +
         ",\"type\":\"union\",\"visible\":" + (k + 1 == levels ? "true" : "false") +
         ",\"children\":[{\"id\":" + std::to_string(id + 1) +
         ",\"type\":\"instance\",\"of\":" + std::to_string(below) +
         "},{\"id\":" + std::to_string(id + 2) +
         ",\"type\":\"instance\",\"of\":" + std::to_string(below) +
         R"(,"transform":{"translate":[1,0,0]}}]})";
    id += 3;
  }
  return s + "]}}";
}

// A 3MF model placing one cube `n` times at the same place (a build item per placement).
std::string coincidentPlacementsModel(int n) {
  std::string s = R"(<?xml version="1.0" encoding="UTF-8"?><model unit="millimeter" )"
                  R"(xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02"><resources>)"
                  R"(<object id="1" type="model"><mesh><vertices>)";
  for (int i = 0; i < 8; ++i)
    s += "<vertex x=\"" + std::to_string(i & 1) + "\" y=\"" + std::to_string((i >> 1) & 1) +
         "\" z=\"" + std::to_string(i >> 2) + "\"/>";
  s += "</vertices><triangles>";
  const int t[12][3] = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                        {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  for (const auto& tri : t)
    s += "<triangle v1=\"" + std::to_string(tri[0]) + "\" v2=\"" + std::to_string(tri[1]) +
         "\" v3=\"" + std::to_string(tri[2]) + "\"/>";
  s += "</triangles></mesh></object></resources><build>";
  for (int i = 0; i < n; ++i) s += "<item objectid=\"1\"/>";
  return s + "</build></model>";
}

// A binary STL of a closed torus of about `triangles` triangles.
std::string torusStl(int triangles) {
  const int n = int(std::sqrt(triangles / 2.0));
  std::string s(80, '\0');
  const uint32_t count = uint32_t(2 * n * n);
  s.append(reinterpret_cast<const char*>(&count), 4);
  auto p = [&](int i, int j, float* out) {
    const double a = 2 * M_PI * (i % n) / n, b = 2 * M_PI * (j % n) / n;
    out[0] = float((10 + 3 * std::cos(b)) * std::cos(a));
    out[1] = float((10 + 3 * std::cos(b)) * std::sin(a));
    out[2] = float(3 * std::sin(b));
  };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      float c[4][3];
      p(i, j, c[0]);
      p(i + 1, j, c[1]);
      p(i + 1, j + 1, c[2]);
      p(i, j + 1, c[3]);
      const int tris[2][3] = {{0, 1, 2}, {0, 2, 3}};
      for (const auto& tri : tris) {
        float record[12] = {0};
        for (int k = 0; k < 3; ++k)
          for (int q = 0; q < 3; ++q) record[3 + 3 * k + q] = c[tri[k]][q];
        s.append(reinterpret_cast<const char*>(record), sizeof(record));
        s.append(2, '\0');
      }
    }
  return s;
}

EvalResult evaluateText(const std::string& text) {
  Scene scene = parseScene(text, "bench.strata.json", "/nonexistent");
  checkExpansion(scene.root, scene.settings.maxLeaves);
  Evaluator evaluator(std::make_shared<CpuBackend>());
  Progress progress;
  return evaluator.evaluate(scene, EvalOptions{}, progress);
}

struct Family {
  const char* name;
  const char* unit;
  std::vector<int> sizes;
  std::function<std::string(int)> run;  // returns what happened, in a few words
};

std::vector<Family> families() {
  return {
      {"union of distinct boxes, 256 cells",
       "boxes",
       {1000, 10000, 100000},
       [](int n) {
         const EvalResult r = evaluateText(distinctBoxesScene(n));
         return std::to_string(r.measure.surfels) + " surfels";
       }},
      {"instances doubling (refused by the leaf limit)",
       "levels",
       {10, 20, 40},
       [](int n) {
         try {
           evaluateText(doublingScene(n));
           return std::string("evaluated");
         } catch (const Error&) {
           return std::string("refused");
         }
       }},
      {"3MF: one cube placed n times at one place",
       "placements",
       {10000, 100000, 1000000},
       [](int n) {
         try {
           readMeshBytes("bench.3mf", fuzz::packageModel(coincidentPlacementsModel(n)));
           return std::string("read");
         } catch (const Error&) {
           return std::string("refused (not manifold)");
         }
       }},
      {"binary STL torus, read and prepared",
       "triangles",
       {1000000, 4000000, 16000000},
       [](int n) {
         const TriangleMesh m = readMeshBytes("bench.stl", torusStl(n));
         return std::to_string(m.triangles.size()) + " triangles";
       }},
  };
}

double peakMiB() {
  struct rusage usage {};
  getrusage(RUSAGE_SELF, &usage);
  return double(usage.ru_maxrss) / 1024.0;
}

}  // namespace
}  // namespace strata

int main(int argc, char** argv) {
  using namespace strata;
  bool quick = false;
  int limit = 600;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--quick") == 0)
      quick = true;
    else if (std::strcmp(argv[i], "--limit") == 0 && i + 1 < argc)
      limit = std::atoi(argv[++i]);
    else {
      std::fprintf(stderr, "usage: strata_hostile_bench [--quick] [--limit SECONDS]\n");
      return 2;
    }
  }
  bool allBounded = true;
  for (const Family& family : families()) {
    std::printf(
        "\n### %s\n\n| %s | seconds | peak MiB | growth k | outcome |\n|---:|---:|---:|---:|---|\n",
        family.name, family.unit);
    std::fflush(stdout);
    double previousSeconds = 0.0;
    int previousSize = 0;
    size_t count = quick ? std::min<size_t>(2, family.sizes.size()) : family.sizes.size();
    for (size_t k = 0; k < count; ++k) {
      const int n = family.sizes[k];
      int pipe[2];
      if (::pipe(pipe) != 0) return 1;
      const pid_t child = fork();
      if (child == 0) {
        ::close(pipe[0]);
        alarm(unsigned(limit));
        Stopwatch clock;
        std::string outcome;
        try {
          outcome = family.run(n);
        } catch (const std::exception& e) {
          outcome = std::string("error: ") + e.what();
        }
        char line[512];
        std::snprintf(line, sizeof(line), "%.4f %.1f %s", clock.seconds(), peakMiB(),
                      outcome.c_str());
        if (::write(pipe[1], line, std::strlen(line)) < 0) _exit(1);
        _exit(0);
      }
      ::close(pipe[1]);
      char buffer[512] = {0};
      ssize_t got = ::read(pipe[0], buffer, sizeof(buffer) - 1);
      ::close(pipe[0]);
      int status = 0;
      waitpid(child, &status, 0);
      if (got <= 0) {
        std::printf("| %d | > %d | | | did not finish (signal %d) |\n", n, limit,
                    WIFSIGNALED(status) ? WTERMSIG(status) : 0);
        allBounded = false;
        break;
      }
      double seconds = 0.0, mib = 0.0;
      int used = 0;
      std::sscanf(buffer, "%lf %lf %n", &seconds, &mib, &used);
      std::string growth = "";
      if (previousSize > 0 && previousSeconds > 0.05 && seconds > 0.05) {
        const double kk = std::log(seconds / previousSeconds) / std::log(double(n) / previousSize);
        char text[32];
        std::snprintf(text, sizeof(text), "%.2f%s", kk, kk > 1.3 ? " (over n log n)" : "");
        growth = text;
        if (kk > 1.3) allBounded = false;
      }
      std::printf("| %d | %.3f | %.0f | %s | %s |\n", n, seconds, mib, growth.c_str(),
                  buffer + used);
      std::fflush(stdout);
      previousSeconds = seconds;
      previousSize = n;
    }
  }
  std::printf("\n%s\n", allBounded ? "every family within n log n" : "SOME FAMILY GROWS FASTER");
  return allBounded ? 0 : 1;
}
