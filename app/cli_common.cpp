#include "app/cli_common.h"

#include "engine/io/mesh_io.h"
#include "engine/util/memory.h"

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <new>

#include "engine/util/atomic_file.h"
#include "engine/util/error.h"
#include "engine/util/parallel_for.h"

namespace strata {

const std::vector<std::string> kValuedOptions = {
    "--resolution", "--report",        "-o",           "--output",        "--backend",
    "--threads",    "--margin",        "--surfels",    "--tile",          "--unit-scale",
    "--max-leaves", "--max-file-size", "--max-memory", "--max-triangles", "--distance",
    "--thickness",  "--radius",        "--fillet",     "--opening",       "--simplify",
    "--gpus"};
const std::vector<std::string> kFlagOptions = {
    "--quiet", "-q", "--nodes", "--allow-open", "--force", "--distributed", "--stream"};

namespace {
// Where this command began (beginCommand): the files committed and warnings printed before it
// belong to earlier commands of a batch.
size_t g_committedBefore = 0;
std::atomic<size_t> g_warningsPrinted{0};
}  // namespace

void beginCommand() {
  g_committedBefore = committedFiles().size();
  g_warningsPrinted = 0;
  setWorkerCount(0);
  setMaxInputFileBytes(kDefaultMaxInputFileBytes);
  setMaxInputTriangles(kDefaultMaxInputTriangles);
}

int runGuarded(const std::function<int()>& body) {
  try {
    return body();
  } catch (const Cancelled&) {
    // A cancel once the file was in place (during its check) leaves it: said, not denied.
    std::vector<std::string> written = committedFiles();
    written.erase(written.begin(),
                  written.begin() + std::ptrdiff_t(std::min(g_committedBefore, written.size())));
    if (written.empty())
      std::fprintf(stderr, "\nstrata: cancelled; nothing was written\n");
    else
      std::fprintf(stderr, "\nstrata: cancelled after %s was written; its check did not finish\n",
                   written.back().c_str());
    return 130;
  } catch (const Error& e) {
    std::fprintf(stderr, "strata: error: %s\n", e.what());
    return 1;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "strata: error: out of memory; try a lower --resolution or --tile\n");
    return 1;
  }
}

void namingInput(const std::string& input, const std::vector<std::string>& named,
                 const std::function<void()>& body) {
  try {
    body();
  } catch (const Error& e) {
    const std::string message = e.what();
    const auto begins = [&](const std::string& file) {
      return !file.empty() && message.compare(0, file.size() + 1, file + ":") == 0;
    };
    if (begins(input) || std::any_of(named.begin(), named.end(), begins)) throw;
    throw Error(input + ": " + message);
  }
}

void printWarning(const std::string& line) {
  const size_t n = g_warningsPrinted++;
  if (n < kWarningsShown)
    std::fprintf(stderr, "strata: warning: %s\n", line.c_str());
  else if (n == kWarningsShown)
    std::fprintf(stderr,
                 "strata: more warnings follow: not shown here (the summary counts them, "
                 "--report's JSON holds them all)\n");
}

std::string warningLines(const std::vector<std::string>& warnings) {
  std::string out;
  for (size_t i = 0; i < warnings.size() && i < kWarningsShown; ++i)
    out += "warning   " + warnings[i] + "\n";
  if (warnings.size() > kWarningsShown)
    out += "warning   and " + std::to_string(warnings.size() - kWarningsShown) +
           " more (all in --report's JSON)\n";
  return out;
}

bool quietRequested(const CliArgs& args) {
  return args.has("--quiet") || args.has("-q");
}

void startBackendEarly(const CliArgs& args) {
  if (args.has("--threads")) setWorkerCount(args.integer("--threads", 0, 1, 1024));
  if (!args.has("--distributed")) startChoosingBackend(args.text("--backend", "auto"));
}

BackendChoice setUpBackend(const CliArgs& args) {
  return setUpBackend(args, quietRequested(args));
}

BackendChoice setUpBackend(const CliArgs& args, bool quiet, int processOnHost) {
  if (args.has("--threads")) setWorkerCount(args.integer("--threads", 0, 1, 1024));
  BackendChoice choice = chooseBackend(args.text("--backend", "auto"), processOnHost);
  if (!quiet) std::fprintf(stderr, "%s\n", choice.why.c_str());
  return choice;
}

std::string unitAbbreviation(const std::string& unit) {
  if (unit == "millimetre" || unit == "millimeter") return "mm";
  if (unit == "centimetre" || unit == "centimeter") return "cm";
  if (unit == "metre" || unit == "meter") return "m";
  if (unit == "inch") return "in";
  if (unit == "foot") return "ft";
  if (unit == "micron" || unit == "micrometre" || unit == "micrometer") return "um";
  return unit;
}

namespace {
// A size option: bytes, or with K, M, G, T (powers of 1024).
uint64_t sizeOption(const CliArgs& args, const std::string& option) {
  const std::string text = args.text(option, "");
  size_t used = 0;
  unsigned long long value = 0;
  try {
    // stoull takes "-5" as 2^64 - 5: only digits are a size.
    if (!text.empty() && text[0] >= '0' && text[0] <= '9') value = std::stoull(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  std::string unit = text.substr(used);
  int shift = unit == "" || unit == "B" ? 0
              : unit == "K"             ? 10
              : unit == "M"             ? 20
              : unit == "G"             ? 30
              : unit == "T"             ? 40
                                        : -1;
  if (used == 0 || shift < 0 || value == 0 || value > (~0ull >> shift))
    throw Error(option + ": expected a size such as 800M, 16G or 2000000000, got '" + text + "'");
  return uint64_t(value) << shift;
}
}  // namespace

void applyInputLimits(const CliArgs& args) {
  if (args.has("--max-file-size")) setMaxInputFileBytes(sizeOption(args, "--max-file-size"));
  if (args.has("--max-triangles"))
    setMaxInputTriangles(uint64_t(args.integer("--max-triangles", 0, 1, INT32_MAX)));
}

void applySceneLimits(const CliArgs& args, Scene* scene) {
  if (args.has("--max-leaves"))
    scene->settings.maxLeaves = uint64_t(args.integer("--max-leaves", 0, 1, INT32_MAX));
}

uint64_t jobMemoryBytes(const CliArgs& args) {
  return args.has("--max-memory") ? sizeOption(args, "--max-memory") : availableMemoryBytes();
}

void tellOrRefuseEstimate(const JobEstimate& estimate, const CliArgs& args, const std::string& job,
                          const std::string& outputPath, const std::string& otherWay) {
  const uint64_t memory = jobMemoryBytes(args);
  const std::string refusal =
      estimateRefusal(estimate, memory, outputPath.empty() ? 0 : freeDiskBytesForFile(outputPath));
  const bool force = args.has("--force");
  if (!refusal.empty() && !force)
    throw Error(job + " " + refusal + " (estimate: " + describeEstimate(estimate) +
                "). Lower --resolution" + otherWay + ", or run it anyway with --force");
  if (!refusal.empty() || (estimateWorthTelling(estimate) && !quietRequested(args)))
    std::fprintf(stderr, "strata: estimate for %s: %s%s\n", job.c_str(),
                 describeEstimate(estimate).c_str(),
                 refusal.empty() ? "" : (" -- " + refusal + "; going on (--force)").c_str());
}

}  // namespace strata
