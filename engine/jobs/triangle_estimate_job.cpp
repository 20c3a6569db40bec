#include "engine/jobs/triangle_estimate_job.h"

#include "engine/util/error.h"

namespace strata {

TriangleEstimateJob::TriangleEstimateJob(std::shared_ptr<const Scene> scene, int resolution,
                                         double simplifyCells,
                                         std::function<std::shared_ptr<Backend>()> makeBackend)
    : scene_(scene),
      resolution_(resolution),
      simplifyCells_(simplifyCells),
      job_([scene = std::move(scene), resolution, simplifyCells,
            makeBackend = std::move(makeBackend)](Progress& progress) {
        if (!makeBackend) throw Error("no backend to estimate with");
        return estimateExportTriangles(*scene, resolution, simplifyCells, makeBackend(), progress);
      }) {}

}  // namespace strata
