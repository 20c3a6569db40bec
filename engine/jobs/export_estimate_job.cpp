#include "engine/jobs/export_estimate_job.h"

#include <cctype>
#include <filesystem>

#include "engine/util/error.h"

namespace strata {

ExportEstimateJob::ExportEstimateJob(std::shared_ptr<const Scene> scene, const std::string& path,
                                     int resolution, double simplifyCells,
                                     std::function<std::shared_ptr<Backend>()> makeBackend)
    : scene_(scene),
      path_(path),
      resolution_(resolution),
      simplifyCells_(simplifyCells),
      job_([scene = std::move(scene), path, resolution, simplifyCells,
            makeBackend = std::move(makeBackend)](Progress& progress) {
        if (!makeBackend) throw Error("no backend to estimate with");
        const std::shared_ptr<Backend> backend = makeBackend();
        DialogEstimate out;
        out.triangles =
            estimateExportTriangles(*scene, resolution, simplifyCells, backend, progress);
        ContourOptions options;
        options.resolution = resolution;
        out.job = estimateExport(*scene, options, path, backend, progress, kProbeAbove,
                                 simplifyCells, &out.triangles);
        return out;
      }) {}

namespace {

// The extension of `path`, lower case: ".stl".
std::string lowerExtension(const std::string& path) {
  std::string e = std::filesystem::path(path).extension().string();
  for (char& c : e) c = char(std::tolower(static_cast<unsigned char>(c)));
  return e;
}

}  // namespace

std::optional<JobEstimate> ExportEstimateJob::estimateOf(const std::shared_ptr<const Scene>& scene,
                                                         const std::string& path, int resolution,
                                                         double simplifyCells) const {
  if (!countOf(scene, resolution, simplifyCells) || lowerExtension(path) != lowerExtension(path_))
    return std::nullopt;
  const JobEstimate e = jobEstimate();
  if (!e.probed) return std::nullopt;
  return e;
}

}  // namespace strata
