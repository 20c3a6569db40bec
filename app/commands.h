// The subcommands of the `strata` command line. Each returns the process exit code:
// 0 success, 1 failure (message printed), 3 written but failed the watertight check,
// 130 cancelled.
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace strata {

int runEval(const std::vector<std::string>& args);
int runBoolean(const std::vector<std::string>& args);
int runExport(const std::vector<std::string>& args);
// `strata offset|shell|round A [B...]`: the meshes' union under a modifier (node_kinds.h).
int runModifier(const std::string& command, const std::vector<std::string>& args);
// `strata batch FILE [--keep-going] [-q]`: the command lines of FILE, each run by `runOne` (the
// dispatcher of main.cpp) in this process (command_batch.cpp). Exit code: 0 when every job
// succeeded, else the first failing job's (a cancelled one's ends the batch at once).
int runBatch(const std::vector<std::string>& args,
             const std::function<int(const std::vector<std::string>&)>& runOne);

// The bundled demo scene (assets/scenes/demo.strata.json), located from STRATA_ASSETS or the
// source tree this binary was built from.
std::string demoScenePath();

}  // namespace strata
