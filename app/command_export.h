// Watertight export from the command line: contour, write atomically, re-read and check.
#pragma once

#include <string>
#include <vector>

#include "app/cli_args.h"
#include "engine/document/scene.h"

namespace strata {

// Exports `scene` to the -o path in the format its extension names, prints the export report
// (and writes it as JSON with --report). Returns 0, or 3 when the written file fails the check.
int exportAndReport(const Scene& scene, const CliArgs& args, const std::string& input,
                    const std::vector<std::string>& warnings);

}  // namespace strata
