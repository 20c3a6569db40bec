#include "app/command_export.h"

#include "app/cli_common.h"
#include "app/export_report.h"
#include "app/process_group_plugin.h"
#include "app/terminal_progress.h"
#include "engine/export/distributed_export.h"
#include "engine/export/export_scene.h"
#include "engine/export/streamed_export.h"
#include "engine/io/mesh_formats.h"
#include "engine/util/atomic_file.h"
#include "engine/util/error.h"
#include "engine/util/parallel_for.h"

namespace strata {

namespace {

// The report of a finished export on stdout (and --report's JSON); the export's notices and
// warnings join the summary's. Returns the exit code: 0, or 3 when the file failed the check.
int printExportSummary(const CliArgs& args, ExportSummary& summary) {
  for (const auto& line : summary.result.notices) summary.warnings.push_back(line);
  for (const auto& line : summary.result.contour.warnings) {
    printWarning(line);
    summary.warnings.push_back(line);
  }
  std::fputs(formatExportText(summary).c_str(), stdout);
  if (args.has("--report")) {
    std::string json = formatExportJson(summary);
    writeFileAtomically(args.text("--report", ""), [&](std::ostream& out) { out << json; });
  }
  return summary.result.passed() ? 0 : 3;
}

// What a stopped process says of its file: process 0 stopped during its check (streamed, the file
// is in place before the check) wrote it.
std::string writtenOrNot() {
  const std::vector<std::string> written = committedFiles();
  return written.empty() ? "nothing was written"
                         : written.back() + " was written; its check did not finish";
}

// The export's part on this process of an MPI job (mpirun ... --distributed): process 0 reports
// as a single-process export does, the others say what they did (unless quiet). A failure on any
// process ends them all (ProcessGroup::abort), after this one says why.
int exportDistributed(const Scene& scene, const CliArgs& args, const std::string& output,
                      const ExportOptions& options, BackendChoice choice, ProcessGroup& group,
                      ExportSummary summary) {
  const bool root = group.rank() == 0;
  const std::string who =
      "process " + std::to_string(group.rank()) + " of " + std::to_string(group.size());
  // mpirun binds each process to a core or two by default: process 0 would then merge, write and
  // check the whole mesh on those (several times slower: tests/gpu/RESULTS.md, sixteenth
  // session). Said, with the remedy; the binding is the launcher's to choose.
  if (root && usableCores() < onlineCores())
    std::fprintf(stderr,
                 "strata: warning: process 0 may run on %d of the %d cores here (mpirun binds "
                 "processes to cores unless told not to): the merge, write and check of the whole "
                 "mesh run on those; start mpirun with --bind-to none\n",
                 usableCores(), onlineCores());
  try {
    DistributedShare share;
    std::vector<std::string> notices;
    {
      TerminalProgress terminal(!root || quietRequested(args));
      summary.result = exportSceneDistributed(
          scene, output, options, choice.backend, group, terminal.progress(), &share,
          [&](const std::string& line) {
            terminal.finish();
            std::fprintf(stderr, "strata: %s: %s\n", who.c_str(), line.c_str());
            notices.push_back(line);
          });
    }
    summary.result.notices = notices;
    char seconds[32];
    std::snprintf(seconds, sizeof(seconds), "%.3f", share.seconds);
    if (!root) {
      if (!quietRequested(args))
        std::fprintf(stderr, "strata: %s contoured %d of %d tiles on %s in %s s\n", who.c_str(),
                     share.ownTiles, share.tiles, choice.backend->description().c_str(), seconds);
      return 0;
    }
    char all[32];
    std::snprintf(all, sizeof(all), "%.3f", share.allTilesSeconds);
    summary.distributed = group.description() + ": every tile in " + all +
                          " s (evaluate and contour above: summed over the processes); process 0 " +
                          std::to_string(share.ownTiles) + " of " + std::to_string(share.tiles) +
                          " tiles in " + seconds + " s";
    if (options.streamed)
      summary.distributed += "; process 0 held the tiles of at most " +
                             std::to_string(share.mostSlabsHeld) + " slabs at once";
    summary.processes = group.size();
    summary.distributedTilesSeconds = share.allTilesSeconds;
  } catch (const Cancelled&) {
    std::fprintf(stderr, "\nstrata: %s cancelled; ending every process, %s\n", who.c_str(),
                 writtenOrNot().c_str());
    group.abort(130);
    return 130;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "strata: error (%s): %s; ending every process, %s\n", who.c_str(),
                 e.what(), writtenOrNot().c_str());
    group.abort(1);
    return 1;
  }
  return printExportSummary(args, summary);
}

}  // namespace

int exportAndReport(const Scene& scene, const CliArgs& args, const std::string& input,
                    const std::vector<std::string>& warnings) {
  const std::string output = args.text("-o", args.text("--output", ""));
  if (!meshFormatFor(output, MeshAccess::Write))
    throw Error(output + ": unknown export format '" + lowerExtension(output) + "' (expected " +
                meshExtensionList(MeshAccess::Write) + ")");
  if (const std::string why = notAFileToReadBack(output); !why.empty())
    throw Error(output + ": " + why);
  // MPI starts first: each process then says only what is its to say.
  if (args.has("--distributed") && args.has("--gpus"))
    throw Error(
        "--gpus and --distributed: a distributed export runs one backend per process "
        "(the processes of a host take its GPUs in turn); start one process per GPU");
  // A folder that cannot take the file is said before the work (it was found after it). A
  // distributed export's processes may see other file systems: its first process writes.
  if (!args.has("--distributed"))
    if (const std::string why = cannotWriteAt(output); !why.empty())
      throw Error(output + ": " + why);
  std::unique_ptr<ProcessGroup> group;
  if (args.has("--distributed")) group = openMpiProcessGroup();
  const bool root = !group || group->rank() == 0;
  BackendChoice choice =
      setUpBackend(args, !root || quietRequested(args), group ? group->rankOnHost() : 0);
  ExportOptions options;
  options.resolution = args.integer("--resolution", 0, kMinResolution, kMaxResolution);
  options.tileCells = args.integer("--tile", 0, 8, kMaxTileCells);  // 0: sized to memory
  options.simplifyCells = args.number("--simplify", 0.0, 0.0, 8.0);
  const bool streamed = args.has("--stream");
  options.streamed = streamed;
  if (streamed) {
    const std::string refusal = streamedExportRefusal(output, options);
    if (!refusal.empty()) throw Error(output + ": " + refusal);
  }

  // One process: its tiles on every worker --gpus asks for (one a CUDA device by default).
  int perDevice = 1;
  std::vector<std::shared_ptr<Backend>> workers{choice.backend};
  if (!group)
    workers = exportWorkers(choice, args.text("--gpus", "all"), args.has("--gpus"), &perDevice);

  JobEstimate estimate;  // process 0's
  if (root) {
    Progress probe;
    // The tiling the export will pick: each worker's share of its device's memory.
    namingInput(input, {output}, [&] {
      estimate =
          estimateExport(scene, options, output, choice.backend, workersMemory(workers, perDevice),
                         probe, kProbeAbove, options.simplifyCells);
    });
    // Distributed: process 0 holds the tiles of the slabs the processes work in.
    const uint64_t held =
        group ? uint64_t(distributedSlabsAhead(group->size(), estimate.streamedTilesPerSlab) - 1) *
                    estimate.streamedSlabTileBytes
              : 0;
    const JobEstimate pieces = streamedEstimate(estimate, int(workers.size()), held);
    const uint64_t streamedPeak = pieces.peakBytes;
    if (streamed) estimate = pieces;
    const glm::ivec3 c = estimate.grid.cells;
    // Where the mesh would not fit but its pieces would: say so.
    std::string otherWay;
    if (!streamed && estimate.probed && streamedExportRefusal(output, options).empty() &&
        estimate.peakBytes > jobMemoryBytes(args) && streamedPeak <= jobMemoryBytes(args))
      otherWay = ", write it in pieces with --stream (about " + bytesText(double(streamedPeak)) +
                 " of memory and a " + bytesText(double(estimate.scratchBytes)) +
                 " scratch file beside it)";
    tellOrRefuseEstimate(estimate, args,
                         "export of " + input + " at " +
                             std::to_string(std::max(c.x, std::max(c.y, c.z))) + " cells",
                         output, otherWay);
  }
  ExportSummary summary;
  summary.input = input;
  summary.output = output;
  summary.unit = scene.settings.unit;
  summary.backend = choice.backend->description();
  summary.warnings = warnings;
  if (group) return exportDistributed(scene, args, output, options, choice, *group, summary);
  if (workers.size() > 1)
    summary.backend += ", " + std::to_string(workers.size()) + " workers (--gpus), up to " +
                       std::to_string(perDevice) + " a device";
  if (streamed) summary.backend += ", streamed (--stream)";
  {
    TerminalProgress terminal(quietRequested(args));
    const FallbackNotice notice = [&](const std::string& line) {
      terminal.finish();
      std::fprintf(stderr, "strata: %s\n", line.c_str());
    };
    namingInput(input, {output}, [&] {
      summary.result = streamed ? exportSceneStreamed(scene, output, options, workers, perDevice,
                                                      terminal.progress(), notice)
                                : exportScene(scene, output, options, workers, perDevice,
                                              terminal.progress(), notice);
    });
  }
  // Bodies the cells alone joined or parted (a contact or a gap thinner than a cell).
  const glm::ivec3 cells = summary.result.contour.grid.cells;
  if (const std::string bodies = bodiesDifferSentence(
          estimate, std::max(cells.x, std::max(cells.y, cells.z)), summary.result.check.components);
      !bodies.empty())
    summary.result.contour.warnings.push_back(bodies);
  return printExportSummary(args, summary);
}

}  // namespace strata
