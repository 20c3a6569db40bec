#include "app/cli_common.h"

#include <cstdint>
#include <new>

#include "engine/util/atomic_file.h"
#include "engine/util/error.h"
#include "engine/util/parallel_for.h"

namespace strata {

const std::vector<std::string> kValuedOptions = {
    "--resolution", "--report",  "-o",     "--output",     "--backend",    "--threads",
    "--margin",     "--surfels", "--tile", "--unit-scale", "--max-leaves", "--max-file-size"};
const std::vector<std::string> kFlagOptions = {"--quiet", "-q", "--nodes", "--allow-open"};

int runGuarded(const std::function<int()>& body) {
  try {
    return body();
  } catch (const Cancelled&) {
    std::fprintf(stderr, "\nstrata: cancelled; nothing was written\n");
    return 130;
  } catch (const Error& e) {
    std::fprintf(stderr, "strata: error: %s\n", e.what());
    return 1;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "strata: error: out of memory; try a lower --resolution or --tile\n");
    return 1;
  }
}

bool quietRequested(const CliArgs& args) {
  return args.has("--quiet") || args.has("-q");
}

BackendChoice setUpBackend(const CliArgs& args) {
  if (args.has("--threads")) setWorkerCount(args.integer("--threads", 0, 1, 1024));
  BackendChoice choice = chooseBackend(args.text("--backend", "auto"));
  if (!quietRequested(args)) std::fprintf(stderr, "%s\n", choice.why.c_str());
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

void applyInputLimits(const CliArgs& args) {
  if (!args.has("--max-file-size")) return;
  const std::string text = args.text("--max-file-size", "");
  size_t used = 0;
  unsigned long long value = 0;
  try {
    value = std::stoull(text, &used);
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
    throw Error("--max-file-size: expected a size such as 800M, 16G or 2000000000, got '" + text +
                "'");
  setMaxInputFileBytes(uint64_t(value) << shift);
}

void applySceneLimits(const CliArgs& args, Scene* scene) {
  if (args.has("--max-leaves"))
    scene->settings.maxLeaves = uint64_t(args.integer("--max-leaves", 0, 1, INT32_MAX));
}

}  // namespace strata
