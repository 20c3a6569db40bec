// strata_gpu_bench: the CUDA backend beside the CPU backend on the same host, in one run.
// Prints a markdown table per scene: full evaluation (sample, Boolean), the update after one
// leaf moves, watertight export (download + contour), peak device memory, and the ratio to
// the paper's figures (depth-28 scaffold at 512^3: 1.7 s, 600 MB on a GTX 480).
//
// Then a table of offsets (the armadillo grown by 2% and 10% of its diagonal), CUDA beside CPU,
// with a check that both give the same bits.
//
// usage: strata_gpu_bench [--resolutions 256,512,1024,2048] [--cpu-max 1024]
//                         [--offset-cpu-max 512] [--assets DIR] [--data DIR]
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

#include "engine/eval/cpu_backend.h"
#include "engine/export/contour_scene.h"
#include "engine/geometry/mesh_check.h"
#include "engine/io/mesh_io.h"
#include "engine/io/scene_file.h"
#include "engine/util/error.h"
#include "engine/util/memory.h"
#include "engine/util/parallel_for.h"
#include "engine/util/timer.h"
#include "gpu/cuda_backend.h"
#include "gpu/util/device_memory.h"

namespace {
using namespace strata;

std::vector<int> parseList(const std::string& s) {
  std::vector<int> out;
  std::stringstream in(s);
  std::string item;
  while (std::getline(in, item, ',')) out.push_back(std::atoi(item.c_str()));
  return out;
}

// A mesh leaf.
NodePtr meshNode(NodeId id, const char* name, std::shared_ptr<const TriangleMesh> mesh) {
  auto leaf = std::make_shared<Node>();
  leaf->id = id;
  leaf->kind = NodeKind::Mesh;
  leaf->name = name;
  leaf->mesh = std::move(mesh);
  return leaf;
}

// The id of the first node called name in the subtree (0 where there is none).
NodeId idNamed(const Node& node, const std::string& name) {
  if (node.name == name) return node.id;
  for (const NodePtr& child : node.children)
    if (NodeId id = idNamed(*child, name)) return id;
  return 0;
}

struct Bench {
  std::string name;
  Scene scene;
  NodeId movedLeaf;  // the leaf moved for the update measurement
};

// Replaces the node with id `id` by a copy moved by `delta` (a new root; everything else shared).
NodePtr moved(const NodePtr& node, NodeId id, const glm::dvec3& delta) {
  if (node->id == id) {
    auto copy = std::make_shared<Node>(*node);
    copy->transform.translate += delta;
    return copy;
  }
  bool changed = false;
  std::vector<NodePtr> children;
  for (const auto& c : node->children) {
    children.push_back(moved(c, id, delta));
    changed = changed || children.back() != c;
  }
  if (!changed) return node;
  auto copy = std::make_shared<Node>(*node);
  copy->children = children;
  return copy;
}

double stageSeconds(const EvalResult& r, const char* name) {
  for (const auto& s : r.stages)
    if (s.name == name) return s.seconds;
  return 0.0;
}

struct Row {
  double sample = 0, boolean = 0, full = 0, update = 0, download = 0, contour = 0, exportTotal = 0;
  uint64_t surfels = 0, triangles = 0, deviceBytes = 0, hostBytes = 0;
  bool watertight = false;
};

Row run(const Bench& b, const std::shared_ptr<Backend>& backend, int resolution, bool gpu) {
  Row row;
  Progress progress;
  EvalOptions options;
  options.resolution = resolution;
  if (gpu) resetDevicePeak();
  {
    Evaluator warm(backend);  // first-use costs (context, pools, page faults) out of the timing
    warm.evaluate(b.scene, options, progress);
  }
  Evaluator evaluator(backend);
  Stopwatch full;
  EvalResult r = evaluator.evaluate(b.scene, options, progress);
  row.full = full.seconds();
  row.sample = stageSeconds(r, "sample");
  row.boolean = stageSeconds(r, "boolean");
  row.surfels = r.measure.surfels;
  // One leaf moves: only its path to the root is recomputed.
  Scene edited = b.scene;
  edited.root = moved(b.scene.root, b.movedLeaf,
                      glm::dvec3(0.37 * Evaluator::gridFor(b.scene, resolution).h));
  Stopwatch update;
  evaluator.evaluate(edited, options, progress);
  row.update = update.seconds();
  // Watertight export of the edited scene at the same resolution (whole grid when it fits in
  // one tile of 1024, tiles of 512 beyond).
  Stopwatch download;
  auto host = backend->download(evaluator.evaluate(edited, options, progress).root);
  row.download = download.seconds();
  ContourReport report;
  Stopwatch exportTime;
  ExportMesh mesh =
      contourScene(edited, evaluator, ContourOptions{resolution, resolution <= 1024 ? 1024 : 512},
                   progress, &report);
  row.exportTotal = exportTime.seconds();
  row.contour = report.contourSeconds + report.mergeSeconds;
  row.triangles = mesh.mesh.triangles.size();
  MeshCheck check = checkMesh(mesh.mesh);
  row.watertight = check.watertight();
  if (gpu) row.deviceBytes = devicePeakBytes();
  row.hostBytes = peakResidentBytes();
  return row;
}

// Offsets: `mesh` alone grown by `fraction` of its diagonal, on one backend. Offset alone
// (Backend::offset on the sampled mesh, after one warm-up call) and the whole evaluation of the
// offset node (sampling included); `bits` receives the result for comparison across backends.
struct OffsetRow {
  double distanceCells = 0, offset = 0, full = 0;
  uint64_t surfels = 0, deviceBytes = 0;
};

OffsetRow runOffset(const std::shared_ptr<TriangleMesh>& mesh, int resolution, double fraction,
                    const std::shared_ptr<Backend>& backend, bool gpu,
                    std::shared_ptr<const Ldi>* bits) {
  Bounds bounds = meshBounds(*mesh);
  const double distance = fraction * glm::length(bounds.size());
  NodePtr leaf = meshNode(2, "mesh", mesh);
  auto root = std::make_shared<Node>();
  root->id = 1;
  root->kind = NodeKind::Offset;
  root->amount = distance;
  root->children = {leaf};
  Scene scene;
  scene.root = leaf;
  scene.settings.margin = fraction * 1.8;  // room for the growth, as strata_bench's table 4
  EvalOptions options;
  options.resolution = resolution;
  Progress progress;
  OffsetRow row;
  Evaluator evaluator(backend);
  // The grid of the offset scene (it grows the leaf's bounds by the distance).
  Scene offsetScene = scene;
  offsetScene.root = root;
  const Grid grid = Evaluator::gridFor(offsetScene, resolution);
  row.distanceCells = distance / grid.h;
  LdiHandle sampled = backend->sampleMesh(*mesh, glm::dmat4(1.0), grid, 2, progress);
  if (gpu) resetDevicePeak();
  backend->offset(sampled, distance, progress);  // warm-up
  Stopwatch alone;
  LdiHandle grown = backend->offset(sampled, distance, progress);
  row.offset = alone.seconds();
  if (gpu) row.deviceBytes = devicePeakBytes();
  row.surfels = grown->surfelCount();
  *bits = backend->download(grown);
  grown.reset();
  sampled.reset();
  Stopwatch full;
  evaluator.evaluate(offsetScene, options, progress);
  row.full = full.seconds();
  return row;
}

bool sameBits(const Ldi& a, const Ldi& b) {
  if (!(a.grid == b.grid)) return false;
  for (int axis = 0; axis < 3; ++axis) {
    if (a.axes[axis].offsets != b.axes[axis].offsets) return false;
    const auto& x = a.axes[axis].surfels;
    const auto& y = b.axes[axis].surfels;
    if (x.size() != y.size() ||
        (!x.empty() && std::memcmp(x.data(), y.data(), x.size() * sizeof(Surfel)) != 0))
      return false;
  }
  return true;
}

void offsetTable(const std::string& data, const std::shared_ptr<Backend>& cuda,
                 const std::shared_ptr<Backend>& cpu, const std::vector<int>& resolutions,
                 int cpuMax) {
  auto arm = std::make_shared<TriangleMesh>(readMeshFile(data + "/armadillo.obj"));
  std::printf(
      "### Offsets: the armadillo grown by 2%% and 10%% of its diagonal (targets on the H200: "
      "15 ms and 50 ms at 512)\n\n");
  std::printf(
      "| res | grown by | distance (cells) | backend | offset alone | full eval (sample + "
      "offset) | surfels | peak device MiB | bits equal the CPU's |\n");
  std::printf("|---:|---:|---:|---|---:|---:|---:|---:|---|\n");
  for (int res : resolutions) {
    if (res > 1024) continue;  // 37 bytes per node: 2048^3 does not fit one GPU in one piece
    for (double fraction : {0.02, 0.10}) {
      try {
        std::shared_ptr<const Ldi> onGpu, onCpu;
        OffsetRow g = runOffset(arm, res, fraction, cuda, true, &onGpu);
        std::string equal = "not run (cpu above --cpu-max)";
        OffsetRow c;
        const bool withCpu = res <= cpuMax;
        if (withCpu) {
          c = runOffset(arm, res, fraction, cpu, false, &onCpu);
          equal = sameBits(*onGpu, *onCpu) ? "yes" : "NO";
        }
        std::printf("| %d | %.0f%% | %.1f | cuda | %.1f | %.1f | %llu | %llu | %s |\n", res,
                    fraction * 100.0, g.distanceCells, g.offset * 1e3, g.full * 1e3,
                    static_cast<unsigned long long>(g.surfels),
                    static_cast<unsigned long long>(g.deviceBytes / 1048576), equal.c_str());
        if (withCpu)
          std::printf("| %d | %.0f%% | %.1f | cpu | %.1f | %.1f | %llu | - | |\n", res,
                      fraction * 100.0, c.distanceCells, c.offset * 1e3, c.full * 1e3,
                      static_cast<unsigned long long>(c.surfels));
      } catch (const std::exception& e) {
        std::printf("| %d | %.0f%% | | | failed: %s |\n", res, fraction * 100.0, e.what());
      }
      std::fflush(stdout);
    }
  }
  std::printf("\n");
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<int> resolutions = {256, 512, 1024, 2048};
  int cpuMax = 1024, offsetCpuMax = 512;
  std::string assets = STRATA_ASSETS, data = STRATA_TEST_DATA;
  for (int i = 1; i + 1 < argc; i += 2) {
    std::string k = argv[i];
    if (k == "--resolutions")
      resolutions = parseList(argv[i + 1]);
    else if (k == "--cpu-max")
      cpuMax = std::atoi(argv[i + 1]);
    else if (k == "--offset-cpu-max")
      offsetCpuMax = std::atoi(argv[i + 1]);
    else if (k == "--assets")
      assets = argv[i + 1];
    else if (k == "--data")
      data = argv[i + 1];
  }
  std::string why;
  if (!cudaDeviceAvailable(&why)) {
    std::printf("strata_gpu_bench: no CUDA device (%s)\n", why.c_str());
    return 1;
  }
  auto cuda = makeCudaBackend();
  auto cpu = std::make_shared<CpuBackend>();

  std::vector<Bench> benches;
  {
    Bench pair;
    pair.name = "armadillo - bunny";
    auto arm = std::make_shared<TriangleMesh>(readMeshFile(data + "/armadillo.obj"));
    auto bunny = std::make_shared<TriangleMesh>(readMeshFile(data + "/bunny.obj"));
    NodePtr a = meshNode(2, "armadillo", arm);
    auto c = std::make_shared<Node>(*meshNode(3, "bunny", bunny));
    c->transform.scale = glm::dvec3(6.0);
    c->transform.translate = {0, 10, 20};
    auto root = std::make_shared<Node>();
    root->id = 1;
    root->kind = NodeKind::Difference;
    root->children = {a, c};
    pair.scene.root = root;
    pair.movedLeaf = 3;
    benches.push_back(pair);
  }
  {
    // The paper's Fig. 1 scene: the femur minus its inward offset, and the offset intersected
    // with 27 tiles of a strut lattice. The update moves the middle tile.
    Bench scaffold;
    scaffold.name = "bone scaffold (depth 29: true offset, 27 lattice tiles)";
    scaffold.scene = loadScene(assets + "/scenes/bone_scaffold.strata.json");
    scaffold.movedLeaf = idNamed(*scaffold.scene.root, "cell 111");
    if (scaffold.movedLeaf == 0) throw Error("bone_scaffold.strata.json: no node \"cell 111\"");
    benches.push_back(scaffold);
  }
  {
    // The scene measured before the offset existed (kept for comparison): the offset faked by
    // a copy scaled by 0.8, cells of three struts and a ball. The update moves the copy.
    Bench scaffold;
    scaffold.name = "bone scaffold of scaled copies (depth 30)";
    scaffold.scene = loadScene(assets + "/scenes/bone_scaffold_scaled_copy.strata.json");
    scaffold.movedLeaf = 0;  // the offset mesh (the cortical shell's second child)
    for (const auto& c : scaffold.scene.root->children)
      if (c->name == "cortical shell") scaffold.movedLeaf = c->children[1]->id;
    if (scaffold.movedLeaf == 0)
      throw Error("bone_scaffold_scaled_copy.strata.json: no cortical shell");
    benches.push_back(scaffold);
  }

  std::printf("strata_gpu_bench: %s vs %s; times in ms\n\n", cuda->description().c_str(),
              cpu->description().c_str());
  for (const auto& b : benches) {
    std::printf("### %s\n\n", b.name.c_str());
    std::printf(
        "| res | backend | sample | Boolean | full eval | update (1 leaf) | download | "
        "contour+merge | export total | triangles | watertight | surfels | peak device "
        "MiB | peak host MiB |\n");
    std::printf("|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---|---:|---:|---:|\n");
    for (int res : resolutions) {
      for (int g = 1; g >= 0; --g) {
        if (!g && res > cpuMax) continue;
        try {
          Row r = run(b, g ? cuda : std::shared_ptr<Backend>(cpu), res, g);
          std::printf(
              "| %d | %s | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f | %llu | %s | "
              "%llu | %s | %.0f |\n",
              res, g ? "cuda" : "cpu", r.sample * 1e3, r.boolean * 1e3, r.full * 1e3,
              r.update * 1e3, r.download * 1e3, r.contour * 1e3, r.exportTotal * 1e3,
              static_cast<unsigned long long>(r.triangles), r.watertight ? "yes" : "NO",
              static_cast<unsigned long long>(r.surfels),
              g ? std::to_string(int(r.deviceBytes / 1048576)).c_str() : "-",
              double(r.hostBytes) / 1048576.0);
          if (g && res == 512 && b.name.find("scaffold") != std::string::npos)
            std::printf(
                "|  | vs paper | | | %.0fx faster than 1.7 s | | | | | | | | %.2fx of 600 MB | |\n",
                1.7 / r.full, double(r.deviceBytes) / (600.0 * 1048576.0));
        } catch (const std::exception& e) {
          std::printf("| %d | %s | failed: %s |\n", res, g ? "cuda" : "cpu", e.what());
        }
        std::fflush(stdout);
      }
    }
    std::printf("\n");
  }
  offsetTable(data, cuda, cpu, resolutions, offsetCpuMax);
  return 0;
}
