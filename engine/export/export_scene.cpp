#include "engine/export/export_scene.h"

#include <stdlib.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <system_error>

#include "engine/io/mesh_io.h"
#include "engine/io/mesh_writers.h"
#include "engine/util/error.h"
#include "engine/util/timer.h"

namespace strata {
namespace {

namespace fs = std::filesystem;

// A private folder beside `target` that a file is written into before it replaces `target`.
// Removed with everything in it unless commit() moved the files out.
class StagedFile {
 public:
  explicit StagedFile(const std::string& target) : target_(target) {
    const size_t slash = target.find_last_of('/');
    targetFolder_ = slash == std::string::npos ? "" : target.substr(0, slash + 1);
    name_ = slash == std::string::npos ? target : target.substr(slash + 1);
    std::string pattern = targetFolder_ + "." + name_ + ".export-XXXXXX";
    if (!::mkdtemp(pattern.data())) throw Error(target + ": cannot write: " + std::strerror(errno));
    folder_ = pattern;
  }
  ~StagedFile() {
    std::error_code ignored;
    if (!folder_.empty()) fs::remove_all(folder_, ignored);
  }
  StagedFile(const StagedFile&) = delete;
  StagedFile& operator=(const StagedFile&) = delete;

  // Where to write: the target's file name inside the staging folder (so that an OBJ names
  // its MTL as it will be named beside the target).
  std::string path() const { return folder_ + "/" + name_; }

  // `message` with the staging folder replaced by the target's.
  std::string namingTarget(std::string message) const {
    const std::string staged = folder_ + "/";
    for (size_t at = message.find(staged); at != std::string::npos;
         at = message.find(staged, at + targetFolder_.size()))
      message.replace(at, staged.size(), targetFolder_);
    return message;
  }

  // Renames every staged file beside the target, companions (an OBJ's MTL) first and the target
  // itself last, then removes the staging folder.
  void commit() {
    std::vector<std::string> names;
    std::error_code ec;
    for (fs::directory_iterator it(folder_, ec), end; !ec && it != end; it.increment(ec))
      names.push_back(it->path().filename().string());
    if (ec) throw Error(target_ + ": cannot list the staged files: " + ec.message());
    std::sort(names.begin(), names.end());
    std::stable_partition(names.begin(), names.end(),
                          [&](const std::string& n) { return n != name_; });
    for (const std::string& n : names) {
      const std::string to = targetFolder_ + n;
      if (std::rename((folder_ + "/" + n).c_str(), to.c_str()) != 0)
        throw Error(to + ": cannot replace the file: " + std::strerror(errno));
    }
    fs::remove(folder_, ec);
    folder_.clear();
  }

 private:
  std::string target_;
  std::string targetFolder_;  // "" or ending in '/'
  std::string name_;
  std::string folder_;  // the staging folder; "" once committed
};

// Runs `step`, rethrowing its strata::Error with the target's path in place of the staged one.
template <typename Step>
auto namingTarget(const StagedFile& staged, Step&& step) -> decltype(step()) {
  try {
    return step();
  } catch (const Error& e) {
    throw Error(staged.namingTarget(e.what()));
  }
}

}  // namespace

ExportReport exportScene(const Scene& scene, const std::string& path, const ContourOptions& options,
                         std::shared_ptr<Backend> backend, Progress& progress,
                         const FallbackNotice& notice) {
  ExportReport report;
  ExportMesh mesh;
  {
    Evaluator evaluator(std::move(backend));
    mesh = contourWithFallback(scene, evaluator, options, progress, &report.contour,
                               [&](const std::string& line) {
                                 report.notices.push_back(line);
                                 if (notice) notice(line);
                               });
  }  // the evaluator's cached LDIs go before the file is written
  StagedFile staged(path);
  Stopwatch write;
  namingTarget(staged, [&] { writeMeshFile(staged.path(), mesh, &progress); });
  report.writeSeconds = write.seconds();
  mesh = ExportMesh();

  progress.report("check", 0.0);
  Stopwatch check;
  TriangleMesh written = namingTarget(staged, [&] { return readMeshFileRaw(staged.path()); });
  progress.report("check", 0.5);
  report.check = checkMesh(written);
  report.checkSeconds = check.seconds();
  progress.report("check", 1.0);
  staged.commit();
  return report;
}

}  // namespace strata
