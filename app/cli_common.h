// What the subcommands share: the option lists, error handling, and setup from options.
#pragma once

#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "app/backend_choice.h"
#include "app/cli_args.h"
#include "engine/document/scene.h"
#include "engine/export/job_estimate.h"

namespace strata {

extern const std::vector<std::string> kValuedOptions;
extern const std::vector<std::string> kFlagOptions;

// Runs `body`, turning errors into a message on stderr and an exit code: strata::Error and
// bad_alloc give 1, Cancelled gives 130.
int runGuarded(const std::function<int()>& body);

// Starts a command of a batch (strata batch) as if it were a process of its own: the worker
// count, the input limits and the warnings printed back to their defaults, the files written
// before it not its own. A single command needs no call. Main thread.
void beginCommand();

// Runs `body`; a strata::Error whose message does not begin with one of `named` (the files the
// command reads and writes, as "FILE: ...") is rethrown as "INPUT: message", so that every
// error of a command names a file (an error deep in the engine names none: "the tree is too
// deep", a device out of memory).
void namingInput(const std::string& input, const std::vector<std::string>& named,
                 const std::function<void()>& body);

// Starts choosing the backend of --backend (and applies --threads) while the command goes on
// to read its inputs (startChoosingBackend): at the top of a command that later calls
// setUpBackend. Not with --distributed (the process's GPU is known only once MPI has started).
void startBackendEarly(const CliArgs& args);
// Applies --threads and picks the backend from --backend (printing the choice unless quiet).
BackendChoice setUpBackend(const CliArgs& args);
// The same, printing the choice unless `quiet`; processOnHost: see chooseBackend.
BackendChoice setUpBackend(const CliArgs& args, bool quiet, int processOnHost = 0);

bool quietRequested(const CliArgs& args);

// Warnings a command prints in full; past them, one line says more follow (a scene of 2,000
// copies printed 2,001 lines of one warning). The report's JSON keeps every one.
constexpr size_t kWarningsShown = 20;
// Prints `line` as "strata: warning: ..." on stderr while fewer than kWarningsShown were printed
// by this process, then one line that says the rest are not shown. Any thread.
void printWarning(const std::string& line);
// The summary's warning lines ("warning   ..."), the first kWarningsShown and a count of the rest.
std::string warningLines(const std::vector<std::string>& warnings);

// Applies --max-file-size (bytes, or with K, M, G, T) and --max-triangles to every file read
// from now on. Call it before reading any input.
void applyInputLimits(const CliArgs& args);

// Applies --max-leaves to the scene's settings (engine/document/expansion.h).
void applySceneLimits(const CliArgs& args, Scene* scene);

// The memory a job may use: --max-memory, else what the machine has available.
uint64_t jobMemoryBytes(const CliArgs& args);

// Before a long job: refuses (strata::Error naming the job, the need and what is available) a
// job whose estimate does not fit in the memory available (or --max-memory) or, writing
// `outputPath`, on its disk, unless --force; prints the estimate of a job worth telling about
// (estimateWorthTelling) or forced, unless --quiet. `job` names it: "export of part.strata.json at
// 4096 cells". `otherWay` (may be empty): a further way on that the refusal names (", or write
// it in pieces with --stream, ...").
void tellOrRefuseEstimate(const JobEstimate& estimate, const CliArgs& args, const std::string& job,
                          const std::string& outputPath, const std::string& otherWay = "");

// "mm" for "millimetre" and the other units scene files name; anything else unchanged.
std::string unitAbbreviation(const std::string& unit);

}  // namespace strata
