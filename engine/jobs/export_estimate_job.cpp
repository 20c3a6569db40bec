#include "engine/jobs/triangle_estimate_job.h"

#include "engine/util/error.h"

namespace strata {

TriangleEstimateJob::TriangleEstimateJob(std::shared_ptr<const Scene> scene,
                                         const std::string& path, int resolution,
                                         double simplifyCells,
                                         std::function<std::shared_ptr<Backend>()> makeBackend)
    : scene_(scene),
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

}  // namespace strata
