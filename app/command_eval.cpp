// `strata eval SCENE` and `strata boolean OP A B...`: evaluate a CSG tree on the LDI engine and
// report per stage; -o writes the root's surfels as a point cloud.
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <map>

#include "app/backend_choice.h"
#include "app/cli_args.h"
#include "app/commands.h"
#include "app/eval_report.h"
#include "app/terminal_progress.h"
#include "engine/eval/evaluator.h"
#include "engine/io/mesh_io.h"
#include "engine/io/point_cloud.h"
#include "engine/io/scene_file.h"
#include "engine/util/atomic_file.h"
#include "engine/util/error.h"
#include "engine/util/parallel_for.h"

namespace strata {
namespace {

const std::vector<std::string> kValued = {"--resolution", "--report", "-o", "--output",
                                          "--backend", "--threads", "--margin", "--unit-scale"};
const std::vector<std::string> kFlags = {"--quiet", "-q", "--nodes", "--allow-open"};

void collectColors(const NodePtr& node, std::map<uint32_t, glm::vec3>* colors) {
  if (!node) return;
  (*colors)[node->id] = node->color;
  for (const auto& c : node->children) collectColors(c, colors);
}

std::string lowercase(std::string s) {
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// Evaluates `scene`, prints the report, writes the optional outputs.
int evaluateAndReport(const Scene& scene, const CliArgs& args, ReportContext context) {
  if (args.has("--threads")) setWorkerCount(args.integer("--threads", 0, 1, 1024));
  BackendChoice choice = chooseBackend(args.text("--backend", "auto"));
  const bool quiet = args.has("--quiet") || args.has("-q");
  if (!quiet) std::fprintf(stderr, "%s\n", choice.why.c_str());
  EvalOptions options;
  options.resolution = args.integer("--resolution", 0, kMinResolution, kMaxResolution);
  context.unit = scene.settings.unit;
  context.treeDepth = treeDepth(scene.root);

  Evaluator evaluator(choice.backend);
  TerminalProgress terminal(quiet);
  EvalResult result = evaluator.evaluate(scene, options, terminal.progress());
  std::string output = args.text("-o", args.text("--output", ""));
  if (!output.empty()) {
    std::string ext = lowercase(output.substr(output.find_last_of('.') + 1));
    if (ext != "ply")
      throw Error(output + ": until watertight export lands, -o writes the surfels as a PLY "
                           "point cloud; use a .ply file name");
    std::map<uint32_t, glm::vec3> colors;
    collectColors(scene.root, &colors);
    auto ldi = choice.backend->download(result.root);
    context.outputPoints = writePointCloudPly(*ldi, output, [&](uint32_t leaf) {
      auto it = colors.find(leaf);
      return it == colors.end() ? glm::vec3(0.8f) : it->second;
    });
    context.output = output;
  }
  terminal.finish();
  std::fputs(formatReportText(result, context, args.has("--nodes")).c_str(), stdout);
  if (args.has("--report")) {
    std::string path = args.text("--report", "");
    std::string json = formatReportJson(result, context);
    writeFileAtomically(path, [&](std::ostream& out) { out << json; });
  }
  return 0;
}

template <typename F>
int guarded(F&& body) {
  try {
    return body();
  } catch (const Cancelled&) {
    std::fprintf(stderr, "\nstrata: cancelled; nothing was written\n");
    return 130;
  } catch (const Error& e) {
    std::fprintf(stderr, "strata: error: %s\n", e.what());
    return 1;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "strata: error: out of memory; try a lower --resolution\n");
    return 1;
  }
}

}  // namespace

std::string demoScenePath() {
  if (const char* env = std::getenv("STRATA_ASSETS"))
    return std::string(env) + "/scenes/demo.strata.json";
  return std::string(STRATA_SOURCE_ASSETS) + "/scenes/demo.strata.json";
}

int runEval(const std::vector<std::string>& argv) {
  return guarded([&] {
    CliArgs args(argv, kValued, kFlags);
    if (args.positional().size() != 1)
      throw Error("usage: strata eval SCENE.strata.json [--resolution N] [--report FILE] "
                  "[-o points.ply]");
    const std::string path = args.positional()[0];
    SceneLoadReport load;
    MeshReadOptions meshOptions;
    meshOptions.allowOpen = args.has("--allow-open");
    Scene scene = loadScene(path, &load, meshOptions);
    ReportContext context;
    context.input = path;
    context.warnings = load.warnings;
    for (const auto& w : load.warnings) std::fprintf(stderr, "strata: warning: %s\n", w.c_str());
    return evaluateAndReport(scene, args, context);
  });
}

int runBoolean(const std::vector<std::string>& argv) {
  return guarded([&] {
    CliArgs args(argv, kValued, kFlags);
    const auto& pos = args.positional();
    if (pos.size() < 3)
      throw Error("usage: strata boolean union|intersection|difference A B [C...] "
                  "[--resolution N] [-o out.ply] [--report FILE]");
    NodeKind kind;
    if (!kindFromName(pos[0], &kind) || !isOperation(kind))
      throw Error("boolean: unknown operation '" + pos[0] +
                  "' (expected union, intersection or difference)");
    MeshReadOptions meshOptions;
    meshOptions.allowOpen = args.has("--allow-open");
    meshOptions.unitScale = args.number("--unit-scale", 1.0, 1e-9, 1e9);
    auto root = std::make_shared<Node>();
    root->id = 1;
    root->kind = kind;
    root->name = pos[0];
    ReportContext context;
    context.input = pos[0] + " of";
    static const glm::vec3 palette[] = {{0.85f, 0.55f, 0.3f}, {0.3f, 0.6f, 0.85f},
                                        {0.45f, 0.8f, 0.4f},  {0.85f, 0.4f, 0.6f},
                                        {0.7f, 0.7f, 0.35f},  {0.5f, 0.45f, 0.85f}};
    for (size_t i = 1; i < pos.size(); ++i) {
      MeshReadReport report;
      auto leaf = std::make_shared<Node>();
      leaf->id = NodeId(i + 1);
      leaf->kind = NodeKind::Mesh;
      leaf->name = pos[i];
      leaf->meshPath = pos[i];
      leaf->color = palette[(i - 1) % 6];
      leaf->mesh = std::make_shared<TriangleMesh>(readMeshFile(pos[i], meshOptions, &report));
      for (const auto& w : report.warnings) {
        std::fprintf(stderr, "strata: warning: %s\n", w.c_str());
        context.warnings.push_back(w);
      }
      root->children.push_back(leaf);
      context.input += " " + pos[i];
    }
    Scene scene;
    scene.root = root;
    scene.settings.resolution = 256;
    scene.settings.margin = args.number("--margin", 0.05, 0.0, 10.0);
    return evaluateAndReport(scene, args, context);
  });
}

}  // namespace strata
