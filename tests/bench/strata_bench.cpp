// strata_bench: prints markdown tables of the Boolean "mesh minus a copy of itself shifted by
// (0.3, 0.2, 0.1) of its size" on the CPU backend, for real meshes at several resolutions:
//   1. sampling and Boolean times, surfels, LDI memory and peak memory;
//   2. the watertight export of the same Boolean (contourScene, tiled dual contouring): stage
//      times, triangles, whether the result is closed, manifold and oriented, peak memory;
//   4. (after 3) the mesh alone grown by 2% and 10% of its diagonal: offsetLdi's time;
//   3. when built with OpenVDB: the same Boolean through OpenVDB (mesh to narrow-band level set
//      with Strata's cell size, CSG difference, volume to mesh), the same columns;
//   5. (after 4) the same offsets through OpenSCAD's minkowski() with a sphere, where an
//      `openscad` binary is found (Debian's `openscad`; bench only), each capped in time.
// Each row runs in a forked child process, so its peak resident memory is its own, and a row
// that fails or crashes prints its error instead of ending the table.
//
// usage: strata_bench [--meshes bunny,armadillo] [--resolutions 256,512,1024] [--threads N]
//                     [--tile N] [--no-export] [--no-openvdb] [--openvdb-max-resolution 1024]
//                     [--openscad PATH|none] [--openscad-timeout 600] [--openscad-fn 16]
// --resolutions applies to every table; without it table 1 uses 256,512,1024 and tables 2 and 3
// use 256..2048 for the armadillo and 256..1024 for other meshes.
// The results and the command that made them are recorded in tests/bench/RESULTS.md.
#include <sys/wait.h>
#include <unistd.h>
#include <glm/geometric.hpp>

#include <cerrno>
#include <csignal>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "engine/eval/cpu_backend.h"
#include "engine/eval/evaluator.h"
#include "engine/export/contour_scene.h"
#include "engine/geometry/mesh_check.h"
#include "engine/io/mesh_io.h"
#include "engine/io/mesh_writers.h"
#include "engine/ldi/offset_ldi.h"
#include "engine/util/error.h"
#include "engine/util/memory.h"
#include "engine/util/parallel_for.h"
#include "engine/util/timer.h"

#ifdef STRATA_BENCH_OPENVDB
#include <openvdb/openvdb.h>
#include <openvdb/tools/Composite.h>
#include <openvdb/tools/MeshToVolume.h>
#include <openvdb/tools/VolumeToMesh.h>
#include <tbb/global_control.h>
#endif

namespace {
using namespace strata;

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream in(s);
  std::string item;
  while (std::getline(in, item, ','))
    if (!item.empty()) out.push_back(item);
  return out;
}

std::string format(const char* fmt, ...) __attribute__((format(printf, 1, 2)));
std::string format(const char* fmt, ...) {
  char line[512];
  va_list args;
  va_start(args, fmt);
  std::vsnprintf(line, sizeof(line), fmt, args);
  va_end(args);
  return line;
}

// Prints a markdown table header; each column is {title, width, right-aligned}. Rows print their
// cells with the same widths.
struct Column {
  const char* title;
  int width;
  bool right;
};
void printHeader(const std::vector<Column>& columns) {
  std::string titles = "|", rule = "|";
  for (const auto& c : columns) {
    titles += format(c.right ? " %*s |" : " %-*s |", c.width, c.title);
    rule += std::string(size_t(c.width) + (c.right ? 1 : 2), '-') + (c.right ? ":|" : "|");
  }
  std::printf("%s\n%s\n", titles.c_str(), rule.c_str());
}

double mib(uint64_t bytes) {
  return double(bytes) / 1048576.0;
}

std::shared_ptr<TriangleMesh> loadMesh(const std::string& name) {
  return std::make_shared<TriangleMesh>(
      readMeshFile(std::string(STRATA_TEST_DATA) + "/" + name + ".obj"));
}

// The shift of the second operand, in scene units.
glm::dvec3 shiftOf(const TriangleMesh& mesh) {
  return meshBounds(mesh).size() * glm::dvec3(0.3, 0.2, 0.1);
}

// The benchmark scene: the mesh minus a copy of itself shifted by shiftOf(mesh).
Scene benchScene(const std::shared_ptr<const TriangleMesh>& mesh, int resolution) {
  auto a = std::make_shared<Node>();
  a->id = 2;
  a->kind = NodeKind::Mesh;
  a->name = "mesh";
  a->mesh = mesh;
  auto c = std::make_shared<Node>(*a);
  c->id = 3;
  c->name = "shifted";
  c->transform.translate = shiftOf(*mesh);
  auto root = std::make_shared<Node>();
  root->id = 1;
  root->kind = NodeKind::Difference;
  root->children = {a, c};
  Scene scene;
  scene.root = root;
  scene.settings.resolution = resolution;
  return scene;
}

// "yes", or "no (...)" with what failed.
std::string watertightText(const MeshCheck& c) {
  if (c.watertight()) return "yes";
  std::string why;
  auto add = [&why](size_t n, const char* what) {
    if (n == 0) return;
    if (!why.empty()) why += ", ";
    why += std::to_string(n) + " " + what;
  };
  add(c.boundaryEdges, "open edges");
  add(c.nonManifoldEdges, "non-manifold edges");
  add(c.misorientedEdges, "misoriented edges");
  add(c.nonFiniteCoordinates, "non-finite coords");
  return "no (" + why + ")";
}

// Table 1: sampling and Boolean.
std::string sampleRow(const std::string& name, int resolution) {
  auto mesh = loadMesh(name);
  Scene scene = benchScene(mesh, resolution);
  Evaluator evaluator(std::make_shared<CpuBackend>());
  Progress progress;
  EvalResult r = evaluator.evaluate(scene, EvalOptions{}, progress);
  double sample = 0, boolean = 0;
  uint64_t sampled = 0;
  for (const auto& s : r.stages) {
    if (s.name == "sample") {
      sample = s.seconds;
      sampled = s.surfels;
    }
    if (s.name == "boolean") boolean = s.seconds;
  }
  return format("| %-9s | %5d | %9zu | %8.3f | %9.3f | %15llu | %14llu | %8.1f | %12.1f |",
                name.c_str(), resolution, mesh->triangles.size(), sample, boolean,
                static_cast<unsigned long long>(sampled),
                static_cast<unsigned long long>(r.measure.surfels), mib(r.cacheBytes),
                mib(peakResidentBytes()));
}

// Table 2: the watertight export by tiled dual contouring.
std::string exportRow(const std::string& name, int resolution, int tile) {
  auto mesh = loadMesh(name);
  Scene scene = benchScene(mesh, resolution);
  Evaluator evaluator(std::make_shared<CpuBackend>());
  Progress progress;
  ContourOptions options;
  options.tileCells = tile;
  ContourReport report;
  ExportMesh out = contourScene(scene, evaluator, options, progress, &report);
  // Peak memory of the export itself, before the check (which is not part of it) allocates.
  const uint64_t peak = peakResidentBytes();
  const MeshCheck check = checkMesh(out.mesh);
  const double total = report.evaluateSeconds + report.contourSeconds + report.mergeSeconds;
  return format(
      "| %-9s | %5d | %5d | %10.3f | %9.3f | %7.3f | %7.3f | %10zu | %10.4g | %-10s | %12.1f |",
      name.c_str(), resolution, report.tiles, report.evaluateSeconds, report.contourSeconds,
      report.mergeSeconds, total, out.mesh.triangles.size(), check.volume,
      watertightText(check).c_str(), mib(peak));
}

// `fraction` of the mesh's bounding-box diagonal: the growth of tables 4 and 5.
double diagonalFraction(const TriangleMesh& mesh, double fraction) {
  return fraction * glm::length(meshBounds(mesh).size());
}

// Table 4: the mesh alone grown by `fraction` of its diagonal (offsetLdi, engine/ldi/offset_ldi.h).
std::string offsetRow(const std::string& name, int resolution, double fraction) {
  auto mesh = loadMesh(name);
  const double distance = diagonalFraction(*mesh, fraction);
  auto leaf = std::make_shared<Node>();
  leaf->id = 1;
  leaf->kind = NodeKind::Mesh;
  leaf->mesh = mesh;
  Scene scene;
  scene.root = leaf;
  scene.settings.resolution = resolution;
  // Room for the growth: the grid's box is the mesh's grown by the distance (and its margin).
  scene.settings.margin = fraction * 1.8;
  Evaluator evaluator(std::make_shared<CpuBackend>());
  Progress progress;
  EvalResult r = evaluator.evaluate(scene, EvalOptions{}, progress);
  std::shared_ptr<const Ldi> ldi = evaluator.backend().download(r.root);
  Stopwatch clock;
  std::shared_ptr<Ldi> grown = offsetLdi(*ldi, distance, &progress);
  const double seconds = clock.seconds();
  return format("| %-9s | %5d | %8.1f%% | %9.1f | %9.3f | %14zu | %12.1f |", name.c_str(),
                resolution, fraction * 100.0, distance / ldi->grid.h, seconds, grown->surfelCount(),
                mib(peakResidentBytes()));
}

// Table 5: the mesh grown by `fraction` of its diagonal through OpenSCAD: minkowski() of the mesh
// (written as binary STL) with a sphere of that radius and `fn` segments, run as
// `timeout T openscad -o out.stl in.scad` in a fresh folder. The time is the command's wall time,
// including OpenSCAD's own import and export (its minkowski dominates by far).
std::string openScadRow(const std::string& name, double fraction, const std::string& openscad,
                        int timeoutSeconds, int fn) {
  auto mesh = loadMesh(name);
  const double distance = diagonalFraction(*mesh, fraction);
  char folderTemplate[] = "/tmp/strata_bench_openscad_XXXXXX";
  const char* folderName = mkdtemp(folderTemplate);
  if (!folderName) throw Error(std::string("mkdtemp: ") + std::strerror(errno));
  const std::string folder = folderName;
  {
    ExportMesh stl;  // binary STL through the project's own writer
    stl.mesh = *mesh;
    stl.triangleLeaf.assign(mesh->triangles.size(), 0);
    stl.leaves[0] = LeafStyle{name, glm::vec3(0.8f)};
    writeMeshFile(folder + "/mesh.stl", stl);
    FILE* scad = std::fopen((folder + "/grow.scad").c_str(), "w");
    if (!scad) throw Error("cannot write " + folder + "/grow.scad");
    std::fprintf(scad, "minkowski() {\n  import(\"mesh.stl\");\n  sphere(r = %.9g, $fn = %d);\n}\n",
                 distance, fn);
    std::fclose(scad);
  }
  const std::string command = "cd " + folder + " && timeout " + std::to_string(timeoutSeconds) +
                              " " + openscad + " -o out.stl grow.scad > log.txt 2>&1";
  Stopwatch clock;
  const int status = std::system(command.c_str());
  const double seconds = clock.seconds();
  const int code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::string outcome;
  if (code == 124) {
    outcome = format("| %-9s | %8.1f%% | %9d | > %7d | not finished in %d s (stopped) |",
                     name.c_str(), fraction * 100.0, fn, timeoutSeconds, timeoutSeconds);
  } else if (code != 0) {
    outcome = format("| %-9s | %8.1f%% | %9d | %9.1f | failed: exit status %d (%s/log.txt) |",
                     name.c_str(), fraction * 100.0, fn, seconds, code, folder.c_str());
    return outcome;  // the folder stays for the log
  } else {
    const TriangleMesh result = readMeshFileRaw(folder + "/out.stl");
    const MeshCheck check = checkMesh(result);
    outcome = format("| %-9s | %8.1f%% | %9d | %9.1f | %10zu | %10.4g | %-10s |", name.c_str(),
                     fraction * 100.0, fn, seconds, result.triangles.size(), check.volume,
                     watertightText(check).c_str());
  }
  if (std::system(("rm -rf " + folder).c_str()) != 0) outcome += " (" + folder + " left behind)";
  return outcome;
}

// The openscad binary to run: `requested` when given ("none": no table), else `openscad` on the
// PATH; empty when there is none.
std::string findOpenScad(const std::string& requested) {
  if (requested == "none") return "";
  if (!requested.empty()) return requested;
  if (std::system("command -v openscad > /dev/null 2>&1") == 0) return "openscad";
  return "";
}

#ifdef STRATA_BENCH_OPENVDB
// Table 3: the same Boolean through OpenVDB, on Strata's lattice (same cell size and origin).
std::string openVdbRow(const std::string& name, int resolution) {
  openvdb::initialize();
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, size_t(workerCount()));
  auto mesh = loadMesh(name);
  const Scene scene = benchScene(mesh, resolution);
  const Grid grid = Evaluator::gridFor(scene, resolution);
  auto xform = openvdb::math::Transform::createLinearTransform(grid.h);
  xform->postTranslate(openvdb::Vec3d(grid.origin.x, grid.origin.y, grid.origin.z));
  const float halfWidth = 3.0f;  // narrow band, in voxels

  Stopwatch toLevelSet;
  std::vector<openvdb::Vec3I> triangles(mesh->triangles.size());
  for (size_t t = 0; t < triangles.size(); ++t)
    triangles[t] =
        openvdb::Vec3I(mesh->triangles[t][0], mesh->triangles[t][1], mesh->triangles[t][2]);
  std::vector<openvdb::Vec3s> points(mesh->positions.size());
  for (size_t i = 0; i < points.size(); ++i)
    points[i] = openvdb::Vec3s(float(mesh->positions[i].x), float(mesh->positions[i].y),
                               float(mesh->positions[i].z));
  openvdb::FloatGrid::Ptr a =
      openvdb::tools::meshToLevelSet<openvdb::FloatGrid>(*xform, points, triangles, halfWidth);
  const glm::dvec3 shift = shiftOf(*mesh);
  for (size_t i = 0; i < points.size(); ++i)
    points[i] =
        openvdb::Vec3s(float(mesh->positions[i].x + shift.x), float(mesh->positions[i].y + shift.y),
                       float(mesh->positions[i].z + shift.z));
  openvdb::FloatGrid::Ptr b =
      openvdb::tools::meshToLevelSet<openvdb::FloatGrid>(*xform, points, triangles, halfWidth);
  const double levelSetSeconds = toLevelSet.seconds();

  Stopwatch csg;
  openvdb::tools::csgDifference(*a, *b);  // the result in a; b is emptied
  const double csgSeconds = csg.seconds();
  const uint64_t voxels = a->activeVoxelCount();

  Stopwatch toMesh;
  std::vector<openvdb::Vec3s> outPoints;
  std::vector<openvdb::Vec3I> outTriangles;
  std::vector<openvdb::Vec4I> outQuads;
  openvdb::tools::volumeToMesh(*a, outPoints, outTriangles, outQuads, 0.0, 0.0);
  const double meshSeconds = toMesh.seconds();
  const uint64_t peak = peakResidentBytes();

  // The check, as for Strata's export (not timed, not in the peak): quads split in two.
  a.reset();
  b.reset();
  TriangleMesh result;
  result.positions.reserve(outPoints.size());
  for (const auto& p : outPoints) result.positions.emplace_back(p.x(), p.y(), p.z());
  result.triangles.reserve(outTriangles.size() + 2 * outQuads.size());
  for (const auto& t : outTriangles) result.triangles.push_back({t.x(), t.y(), t.z()});
  for (const auto& q : outQuads) {
    result.triangles.push_back({q[0], q[1], q[2]});
    result.triangles.push_back({q[0], q[2], q[3]});
  }
  const MeshCheck check = checkMesh(result);
  const double total = levelSetSeconds + csgSeconds + meshSeconds;
  return format(
      "| %-9s | %5d | %8.3f | %7.3f | %9.3f | %7.3f | %13llu | %10zu | %10.4g | %-10s | "
      "%12.1f |",
      name.c_str(), resolution, levelSetSeconds, csgSeconds, meshSeconds, total,
      static_cast<unsigned long long>(voxels), result.triangles.size(), check.volume,
      watertightText(check).c_str(), mib(peak));
}
#endif

// Runs `row` in a child process and returns its line, or the row's failure.
std::string forkRow(const std::string& name, int resolution,
                    const std::function<std::string()>& row) {
  const std::string prefix = resolution > 0 ? format("| %-9s | %5d | ", name.c_str(), resolution)
                                            : format("| %-9s | ", name.c_str());
  std::fflush(stdout);
  int fds[2];
  if (pipe(fds) != 0) return prefix + "failed: pipe: " + std::strerror(errno) + " |";
  pid_t pid = fork();
  if (pid < 0) return prefix + "failed: fork: " + std::strerror(errno) + " |";
  if (pid == 0) {
    close(fds[0]);
    std::string line;
    try {
      line = row();
    } catch (const std::exception& e) {
      line = prefix + "failed: " + e.what() + " |";
    } catch (...) {
      line = prefix + "failed: unknown exception |";
    }
    const char* p = line.data();
    size_t left = line.size();
    while (left > 0) {
      ssize_t n = write(fds[1], p, left);
      if (n <= 0) break;
      p += n;
      left -= size_t(n);
    }
    _exit(0);
  }
  close(fds[1]);
  std::string out;
  char buffer[512];
  ssize_t n;
  while ((n = read(fds[0], buffer, sizeof(buffer))) > 0) out.append(buffer, size_t(n));
  close(fds[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  if (out.empty()) {
    if (WIFSIGNALED(status))
      out = prefix + "crashed: signal " + std::to_string(WTERMSIG(status)) + " (" +
            strsignal(WTERMSIG(status)) + ")" +
            (WTERMSIG(status) == SIGKILL ? ", out of memory?" : "") + " |";
    else
      out = prefix + "crashed: exit status " + std::to_string(WEXITSTATUS(status)) + " |";
  }
  return out;
}

std::vector<int> toInts(const std::vector<std::string>& items) {
  std::vector<int> out;
  for (const auto& s : items) out.push_back(std::atoi(s.c_str()));
  return out;
}

void usage() {
  std::fprintf(stderr,
               "usage: strata_bench [--meshes bunny,armadillo] [--resolutions 256,512,1024]\n"
               "                    [--threads N] [--tile N] [--no-export] [--no-openvdb]\n"
               "                    [--openvdb-max-resolution 1024] [--openscad PATH|none]\n"
               "                    [--openscad-timeout 600] [--openscad-fn 16]\n");
}
}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> meshes = {"bunny", "armadillo"};
  std::vector<int> resolutions;  // empty: the defaults of each table
  int tile = 0;                  // as the command line: sized to memory (exportTileCells)
  bool doExport = true;
  bool doOpenVdb = true;
  int openVdbMax = 1024;
  std::string openScadRequested;  // empty: `openscad` on the PATH, if any
  int openScadTimeout = 600;
  int openScadFn = 16;
  for (int i = 1; i < argc; ++i) {
    const std::string key = argv[i];
    const bool hasValue = i + 1 < argc;
    if (key == "--no-export")
      doExport = false;
    else if (key == "--no-openvdb")
      doOpenVdb = false;
    else if (key == "--help" || key == "-h") {
      usage();
      return 0;
    } else if (!hasValue) {
      std::fprintf(stderr, "option %s needs a value\n", argv[i]);
      usage();
      return 2;
    } else if (key == "--meshes")
      meshes = split(argv[++i]);
    else if (key == "--resolutions")
      resolutions = toInts(split(argv[++i]));
    else if (key == "--threads")
      setWorkerCount(std::atoi(argv[++i]));
    else if (key == "--tile")
      tile = std::atoi(argv[++i]);
    else if (key == "--openvdb-max-resolution")
      openVdbMax = std::atoi(argv[++i]);
    else if (key == "--openscad")
      openScadRequested = argv[++i];
    else if (key == "--openscad-timeout")
      openScadTimeout = std::atoi(argv[++i]);
    else if (key == "--openscad-fn")
      openScadFn = std::atoi(argv[++i]);
    else {
      std::fprintf(stderr, "unknown option %s\n", argv[i]);
      usage();
      return 2;
    }
  }
  auto tableResolutions = [&](const std::string& mesh, bool exportTable) {
    if (!resolutions.empty()) return resolutions;
    if (!exportTable) return std::vector<int>{256, 512, 1024};
    if (mesh == "armadillo") return std::vector<int>{256, 512, 1024, 2048};
    return std::vector<int>{256, 512, 1024};
  };

  std::printf(
      "strata_bench: mesh minus a copy of itself shifted by (0.3, 0.2, 0.1) of its size, "
      "CPU backend, %d threads, %u hardware threads\n\n",
      workerCount(), std::thread::hardware_concurrency());

  std::printf("### 1. Sampling and Boolean (Strata)\n\n");
  printHeader({{"mesh", 9, false},
               {"res", 5, true},
               {"triangles", 9, true},
               {"sample s", 8, true},
               {"boolean s", 9, true},
               {"sampled surfels", 15, true},
               {"result surfels", 14, true},
               {"LDIs MiB", 8, true},
               {"peak RSS MiB", 12, true}});
  for (const auto& m : meshes)
    for (int r : tableResolutions(m, false))
      std::printf("%s\n", forkRow(m, r, [&] { return sampleRow(m, r); }).c_str());

  if (doExport) {
    if (tile > 0)
      std::printf("\n### 2. Watertight export (Strata: contourScene, tiles of %d cells)\n\n", tile);
    else
      std::printf("\n### 2. Watertight export (Strata: contourScene, tiles sized to memory)\n\n");
    printHeader({{"mesh", 9, false},
                 {"res", 5, true},
                 {"tiles", 5, true},
                 {"evaluate s", 10, true},
                 {"contour s", 9, true},
                 {"merge s", 7, true},
                 {"total s", 7, true},
                 {"triangles", 10, true},
                 {"volume", 10, true},
                 {"watertight", 10, false},
                 {"peak RSS MiB", 12, true}});
    for (const auto& m : meshes)
      for (int r : tableResolutions(m, true))
        std::printf("%s\n", forkRow(m, r, [&] { return exportRow(m, r, tile); }).c_str());
    std::printf(
        "\nevaluate: sampling and Booleans of all tiles; contour: signs, vertices and "
        "quads; merge: stitching. Watertight: closed, manifold and oriented "
        "(checkMesh), not timed and not in the peak. Volume: signed volume of the "
        "output mesh.\n");
  }

  if (doOpenVdb) {
#ifdef STRATA_BENCH_OPENVDB
    std::printf("\n### 3. The same Boolean through OpenVDB %s\n\n",
                openvdb::getLibraryVersionString());
    printHeader({{"mesh", 9, false},
                 {"res", 5, true},
                 {"to SDF s", 8, true},
                 {"CSG s", 7, true},
                 {"to mesh s", 9, true},
                 {"total s", 7, true},
                 {"active voxels", 13, true},
                 {"triangles", 10, true},
                 {"volume", 10, true},
                 {"watertight", 10, false},
                 {"peak RSS MiB", 12, true}});
    bool capped = false;
    for (const auto& m : meshes)
      for (int r : tableResolutions(m, true)) {
        if (r > openVdbMax) {
          std::printf("| %-9s | %5d | skipped: above --openvdb-max-resolution %d |\n", m.c_str(), r,
                      openVdbMax);
          capped = true;
          continue;
        }
        std::printf("%s\n", forkRow(m, r, [&] { return openVdbRow(m, r); }).c_str());
      }
    std::printf(
        "\nto SDF: tools::meshToLevelSet of both operands (float grid, voxel size = "
        "Strata's cell h, same origin, narrow band 3 voxels); CSG: "
        "tools::csgDifference; to mesh: tools::volumeToMesh (isovalue 0, adaptivity 0), "
        "quads counted as 2 triangles. OpenVDB threads limited to %d (TBB "
        "global_control). Volume: signed volume of the output mesh (checkMesh); "
        "volumeToMesh winds its polygons inward, hence the sign.\n",
        workerCount());
    if (capped)
      std::printf(
          "Resolutions above %d were not run through OpenVDB "
          "(--openvdb-max-resolution).\n",
          openVdbMax);
#else
    (void)openVdbMax;
    std::printf(
        "\nOpenVDB was not available when strata_bench was built: no comparison "
        "(install libopenvdb-dev and reconfigure).\n");
#endif
  }
  std::printf(
      "\n### 4. Offsets (offsetLdi on the CPU: a distance transform, cost independent of "
      "the distance)\n\n");
  printHeader({{"mesh", 9, false},
               {"res", 5, true},
               {"distance", 9, true},
               {"cells", 9, true},
               {"offset s", 9, true},
               {"result surfels", 14, true},
               {"peak RSS MiB", 12, true}});
  for (const auto& m : meshes)
    for (int r : tableResolutions(m, false)) {
      if (r > 512) continue;  // 13 bytes a node of the grid: 1.7 GB at 512
      for (double fraction : {0.02, 0.10})
        std::printf("%s\n", forkRow(m, r, [&] { return offsetRow(m, r, fraction); }).c_str());
    }
  std::printf(
      "\ndistance: of the mesh's bounding-box diagonal; cells: the same in cells. "
      "Offset s: offsetLdi alone (sampling not included).\n");

  const std::string openscad = findOpenScad(openScadRequested);
  if (openscad.empty()) {
    std::printf(
        "\nNo openscad binary (apt-get install openscad, or --openscad PATH): no minkowski() "
        "comparison.\n");
    return 0;
  }
  std::printf("\n### 5. The same offsets through OpenSCAD's minkowski() with a sphere\n\n");
  printHeader({{"mesh", 9, false},
               {"distance", 9, true},
               {"sphere fn", 9, true},
               {"wall s", 9, true},
               {"triangles", 10, true},
               {"volume", 10, true},
               {"watertight", 10, false}});
  for (const auto& m : meshes)
    for (double fraction : {0.02, 0.10})
      std::printf("%s\n", forkRow(m, 0, [&] {
                            return openScadRow(m, fraction, openscad, openScadTimeout, openScadFn);
                          }).c_str());
  std::printf(
      "\n`timeout %d %s -o out.stl grow.scad` where grow.scad is minkowski() { import(mesh.stl); "
      "sphere(r = distance, $fn = fn); }: wall time of the whole command (one thread: OpenSCAD's "
      "CGAL path is sequential), stopped at %d s. Its result is the offset up to the sphere's "
      "polygonization; Strata's (table 4) is the exact Euclidean offset up to the cell size.\n",
      openScadTimeout, openscad.c_str(), openScadTimeout);

  return 0;
}
