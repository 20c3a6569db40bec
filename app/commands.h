// The subcommands of the `strata` command line. Each returns the process exit code:
// 0 success, 1 failure (message printed), 3 written but failed the watertight check,
// 130 cancelled.
#pragma once

#include <string>
#include <vector>

namespace strata {

int runEval(const std::vector<std::string>& args);
int runBoolean(const std::vector<std::string>& args);
int runExport(const std::vector<std::string>& args);
// `strata offset|shell|round A [B...]`: the meshes' union under a modifier (node_kinds.h).
int runModifier(const std::string& command, const std::vector<std::string>& args);

// The bundled demo scene (assets/scenes/demo.strata.json), located from STRATA_ASSETS or the
// source tree this binary was built from.
std::string demoScenePath();

}  // namespace strata
