// `strata eval SCENE` and `strata boolean OP A B...`: evaluate a CSG tree on the LDI engine and
// report per stage. `boolean` with -o exports the result as a watertight mesh (see
// command_export.cpp); --surfels writes the root's surfels as a point cloud.
#include <algorithm>
#include <cstdlib>
#include <map>

#include "app/cli_common.h"
#include "app/command_export.h"
#include "app/commands.h"
#include "app/eval_report.h"
#include "app/scene_from_meshes.h"
#include "app/terminal_progress.h"
#include "engine/document/commands.h"
#include "engine/document/expansion.h"
#include "engine/eval/evaluator.h"
#include "engine/export/fallback.h"
#include "engine/io/mesh_formats.h"
#include "engine/io/point_cloud.h"
#include "engine/io/scene_file.h"
#include "engine/util/atomic_file.h"
#include "engine/util/error.h"

namespace strata {
namespace {

void collectColors(const NodePtr& node, std::map<uint32_t, glm::vec3>* colors) {
  if (!node) return;
  (*colors)[node->id] = node->color;
  for (const auto& c : node->children) collectColors(c, colors);
}

// "out.stl|.obj|.ply|.3mf" for usage lines: `stem` and every writable mesh extension.
std::string outputAlternatives(const std::string& stem) {
  std::string text = stem;
  for (const std::string& ext : meshExtensions(MeshAccess::Write))
    text += (text == stem ? "." : "|.") + ext;
  return text;
}

// Evaluates `scene`, prints the report, writes the optional report and surfel cloud.
int evaluateAndReport(const Scene& scene, const CliArgs& args, ReportContext context) {
  BackendChoice choice = setUpBackend(args);
  EvalOptions options;
  options.resolution = args.integer("--resolution", 0, kMinResolution, kMaxResolution);
  context.unit = scene.settings.unit;
  context.treeDepth = treeDepth(scene.root);

  {
    Progress probe;
    JobEstimate estimate;
    namingInput(context.input, {}, [&] {
      estimate = estimateEvaluation(scene, options.resolution, choice.backend, probe);
    });
    tellOrRefuseEstimate(
        estimate, args,
        "evaluation of " + context.input + " at " +
            std::to_string(std::max(estimate.grid.cells.x,
                                    std::max(estimate.grid.cells.y, estimate.grid.cells.z))) +
            " cells",
        "");
  }
  Evaluator evaluator(choice.backend);
  TerminalProgress terminal(quietRequested(args));
  std::shared_ptr<Backend> used;
  EvalResult result;
  namingInput(context.input, {}, [&] {
    result = evaluateWithFallback(
        evaluator, scene, options, terminal.progress(),
        [&](const std::string& line) {
          terminal.finish();
          std::fprintf(stderr, "strata: %s\n", line.c_str());
          context.warnings.push_back(line);
        },
        &used);
  });
  for (const auto& w : result.warnings) {
    terminal.finish();
    printWarning(w);
    context.warnings.push_back(w);
  }
  Backend& backend = used ? *used : *choice.backend;
  const std::string surfels = args.text("--surfels", "");
  if (!surfels.empty()) {
    if (lowerExtension(surfels) != "ply")
      throw Error(surfels + ": --surfels writes a PLY point cloud; use a .ply file name");
    std::map<uint32_t, glm::vec3> colors;
    collectColors(scene.root, &colors);
    auto ldi = backend.download(result.root);
    context.outputPoints = writePointCloudPly(*ldi, surfels, [&](uint32_t leaf) {
      auto it = colors.find(leaf);
      return it == colors.end() ? glm::vec3(0.8f) : it->second;
    });
    context.output = surfels;
  }
  terminal.finish();
  std::fputs(formatReportText(result, context, args.has("--nodes")).c_str(), stdout);
  if (args.has("--report")) {
    std::string json = formatReportJson(result, context);
    writeFileAtomically(args.text("--report", ""), [&](std::ostream& out) { out << json; });
  }
  return 0;
}

Scene loadSceneFromArgs(const CliArgs& args, const std::string& path,
                        std::vector<std::string>* warnings) {
  applyInputLimits(args);
  SceneLoadReport load;
  MeshReadOptions meshOptions;
  meshOptions.allowOpen = args.has("--allow-open");
  Scene scene = loadScene(path, &load, meshOptions);
  applySceneLimits(args, &scene);
  // A scene too large to expand, or too large or small to measure, refused here, naming the
  // file (gridFor checks both).
  try {
    Evaluator::gridFor(scene, 0);
  } catch (const Error& e) {
    throw Error(path + ": " + e.what());
  }
  for (const auto& w : load.warnings) {
    printWarning(w);
    warnings->push_back(w);
  }
  return scene;
}

}  // namespace

std::string demoScenePath() {
  if (const char* env = std::getenv("STRATA_ASSETS"))
    return std::string(env) + "/scenes/demo.strata.json";
  return std::string(STRATA_SOURCE_ASSETS) + "/scenes/demo.strata.json";
}

int runEval(const std::vector<std::string>& argv) {
  return runGuarded([&] {
    CliArgs args(argv, kValuedOptions, kFlagOptions);
    startBackendEarly(args);
    if (args.positional().size() != 1)
      throw Error(
          "usage: strata eval SCENE.strata.json [--resolution N] [--report FILE] "
          "[--surfels points.ply]");
    if (args.has("-o") || args.has("--output"))
      throw Error("eval does not write meshes; use strata export SCENE -o FILE");
    ReportContext context;
    context.input = args.positional()[0];
    Scene scene = loadSceneFromArgs(args, context.input, &context.warnings);
    return evaluateAndReport(scene, args, context);
  });
}

namespace {
// The end of `boolean`, `offset`, `shell` and `round`: the scene built from mesh files (`what`
// of `files`) exported with -o, else evaluated; either way reported.
int runMeshScene(Scene& scene, const CliArgs& args, const std::string& what,
                 const std::vector<std::string>& files, const std::vector<std::string>& warnings) {
  applySceneLimits(args, &scene);
  for (const auto& w : warnings) printWarning(w);
  std::string input = what + " of";
  for (const auto& f : files) input += " " + f;
  if (args.has("-o") || args.has("--output")) return exportAndReport(scene, args, input, warnings);
  ReportContext context;
  context.input = input;
  context.warnings = warnings;
  return evaluateAndReport(scene, args, context);
}
}  // namespace

int runBoolean(const std::vector<std::string>& argv) {
  return runGuarded([&] {
    CliArgs args(argv, kValuedOptions, kFlagOptions);
    startBackendEarly(args);
    const auto& pos = args.positional();
    if (pos.size() < 3)
      throw Error(
          "usage: strata boolean union|intersection|difference A B [C...] "
          "[--resolution N] [-o " +
          outputAlternatives("out") + "] [--report FILE]");
    applyInputLimits(args);
    MeshReadOptions meshOptions;
    meshOptions.allowOpen = args.has("--allow-open");
    meshOptions.unitScale = args.number("--unit-scale", 1.0, 1e-9, 1e9);
    std::vector<std::string> warnings;
    std::vector<std::string> files(pos.begin() + 1, pos.end());
    Scene scene = sceneFromMeshFiles(pos[0], files, meshOptions,
                                     args.number("--margin", 0.05, 0.0, 10.0), &warnings);
    return runMeshScene(scene, args, pos[0], files, warnings);
  });
}

int runModifier(const std::string& command, const std::vector<std::string>& argv) {
  return runGuarded([&] {
    CliArgs args(argv, kValuedOptions, kFlagOptions);
    startBackendEarly(args);
    const auto& files = args.positional();
    NodeKind kind = NodeKind::Offset;
    std::string option = "--distance";
    if (command == "shell") {
      kind = NodeKind::Shell;
      option = "--thickness";
    } else if (command == "round") {
      const bool fillet = args.has("--fillet");
      if (fillet == args.has("--radius"))
        throw Error(
            "round: give --radius R (round convex edges) or --fillet R (fill concave "
            "edges and seams), one of them");
      kind = fillet ? NodeKind::Fillet : NodeKind::Round;
      option = fillet ? "--fillet" : "--radius";
    }
    if (files.empty() || !args.has(option))
      throw Error("usage: strata " + command + " A [B...] " + option + " VALUE" +
                  (kind == NodeKind::Shell ? " [--opening C]" : "") + " [--resolution N] [-o " +
                  outputAlternatives("out") + "] [--report FILE] [--backend auto|cpu|cuda]");
    if (args.has("--opening") && kind != NodeKind::Shell)
      throw Error(command + ": --opening applies to shell only");
    const double amount = args.number(option, 0.0, -1e300, 1e300);
    applyInputLimits(args);
    MeshReadOptions meshOptions;
    meshOptions.allowOpen = args.has("--allow-open");
    meshOptions.unitScale = args.number("--unit-scale", 1.0, 1e-9, 1e9);
    std::vector<std::string> warnings;
    // With --opening C: the shell of (the union minus C), open where C cuts it.
    std::vector<std::string> meshes = files;
    if (args.has("--opening")) meshes.push_back(args.text("--opening", ""));
    Scene scene = sceneFromMeshFiles("union", meshes, meshOptions,
                                     args.number("--margin", 0.05, 0.0, 10.0), &warnings);
    checkModifierAmount(kind, amount, command + " " + option);
    NodePtr solid = scene.root;
    NodeId opening = 0;
    if (args.has("--opening")) {
      NodePtr cutter = solid->children.back();
      auto body = std::make_shared<Node>(*solid);
      body->children.pop_back();
      solid = makeOperationNode(NodeKind::Difference, NodeId(meshes.size() + 3), {body, cutter});
      opening = cutter->id;
    }
    auto modifier =
        std::make_shared<Node>(*makeOperationNode(kind, NodeId(meshes.size() + 2), {solid}));
    modifier->name = kindName(kind);
    modifier->amount = amount;
    modifier->opening = opening;
    scene.root = modifier;
    std::string what = std::string(kindName(kind)) + " " + args.text(option, "");
    if (opening) what += " open where " + meshes.back() + " cuts it,";
    return runMeshScene(scene, args, what, files, warnings);
  });
}

int runExport(const std::vector<std::string>& argv) {
  return runGuarded([&] {
    CliArgs args(argv, kValuedOptions, kFlagOptions);
    startBackendEarly(args);
    if (args.positional().size() != 1 || !(args.has("-o") || args.has("--output")))
      throw Error("usage: strata export SCENE.strata.json -o " + outputAlternatives("part") +
                  " [--resolution N] [--tile N] [--report FILE]");
    std::vector<std::string> warnings;
    Scene scene = loadSceneFromArgs(args, args.positional()[0], &warnings);
    return exportAndReport(scene, args, args.positional()[0], warnings);
  });
}

}  // namespace strata
