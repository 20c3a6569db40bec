#include "app/command_export.h"

#include "app/cli_common.h"
#include "app/export_report.h"
#include "app/terminal_progress.h"
#include "engine/export/export_scene.h"
#include "engine/io/mesh_formats.h"
#include "engine/util/atomic_file.h"
#include "engine/util/error.h"

namespace strata {

int exportAndReport(const Scene& scene, const CliArgs& args, const std::string& input,
                    const std::vector<std::string>& warnings) {
  const std::string output = args.text("-o", args.text("--output", ""));
  if (!meshFormatFor(output, MeshAccess::Write))
    throw Error(output + ": unknown export format '" + lowerExtension(output) + "' (expected " +
                meshExtensionList(MeshAccess::Write) + ")");
  BackendChoice choice = setUpBackend(args);
  ExportOptions options;
  options.resolution = args.integer("--resolution", 0, kMinResolution, kMaxResolution);
  options.tileCells = args.integer("--tile", 0, 8, kMaxTileCells);  // 0: sized to memory
  options.simplifyCells = args.number("--simplify", 0.0, 0.0, 8.0);

  {
    Progress probe;
    const JobEstimate estimate = estimateExport(scene, options, output, choice.backend, probe);
    const glm::ivec3 c = estimate.grid.cells;
    tellOrRefuseEstimate(estimate, args,
                         "export of " + input + " at " +
                             std::to_string(std::max(c.x, std::max(c.y, c.z))) + " cells",
                         output);
  }
  ExportSummary summary;
  summary.input = input;
  summary.output = output;
  summary.unit = scene.settings.unit;
  summary.backend = choice.backend->description();
  summary.warnings = warnings;
  {
    TerminalProgress terminal(quietRequested(args));
    summary.result = exportScene(scene, output, options, choice.backend, terminal.progress(),
                                 [&](const std::string& line) {
                                   terminal.finish();
                                   std::fprintf(stderr, "strata: %s\n", line.c_str());
                                 });
  }
  for (const auto& line : summary.result.notices) summary.warnings.push_back(line);
  for (const auto& line : summary.result.contour.warnings) {
    std::fprintf(stderr, "strata: warning: %s\n", line.c_str());
    summary.warnings.push_back(line);
  }
  std::fputs(formatExportText(summary).c_str(), stdout);
  if (args.has("--report")) {
    std::string json = formatExportJson(summary);
    writeFileAtomically(args.text("--report", ""), [&](std::ostream& out) { out << json; });
  }
  return summary.result.passed() ? 0 : 3;
}

}  // namespace strata
