#include "engine/jobs/part_measure_job.h"

#include "engine/document/commands.h"
#include "engine/eval/evaluator.h"
#include "engine/util/error.h"

namespace strata {

Scene partScene(const Scene& scene, NodeId id) {
  std::vector<const Node*> path;
  if (!scene.root || !pathToNode(scene.root, id, &path))
    throw Error("there is no node with id " + std::to_string(id));
  // The part, visible, under a union per ancestor carrying that ancestor's transform.
  auto part = std::make_shared<Node>(*path.back());
  part->visible = true;
  NodePtr placed = part;
  for (size_t i = path.size() - 1; i-- > 0;) {
    auto holder = std::make_shared<Node>();
    holder->id = path[i]->id;
    holder->name = path[i]->name;
    holder->kind = NodeKind::Union;
    holder->transform = path[i]->transform;
    // A mirror that drops its original shows the part as its image (patterns.h:
    // firstPlacement): measured there.
    if (patternOf(path[i]->kind) == Pattern::Mirror && !path[i]->pattern.keepOriginal) {
      holder->kind = NodeKind::Mirror;
      holder->pattern = path[i]->pattern;
    }
    holder->children = {placed};
    placed = holder;
  }
  auto rest = std::make_shared<Node>(*scene.root);
  rest->visible = false;
  auto root = std::make_shared<Node>();
  root->id = 0;  // never looked up: the part and the hidden tree keep their own ids
  root->name = "part";
  root->kind = NodeKind::Union;
  root->children = {placed, rest};
  Scene out;
  out.settings = scene.settings;
  out.settings.hasBounds = false;  // the part's own box
  out.root = root;
  return out;
}

PartMeasureJob::PartMeasureJob(std::shared_ptr<const Scene> scene, NodeId id, int resolution,
                               std::function<std::shared_ptr<Backend>()> makeBackend)
    : id_(id),
      job_([scene = std::move(scene), id, resolution,
            makeBackend = std::move(makeBackend)](Progress& progress) {
        if (!makeBackend) throw Error("no backend to measure with");
        Evaluator evaluator(makeBackend());
        EvalOptions options;
        options.resolution = resolution;
        const EvalResult r = evaluator.evaluate(partScene(*scene, id), options, progress);
        return PartMeasure{r.measure, r.grid.h};
      }) {}

}  // namespace strata
