#include "engine/jobs/part_measure_job.h"

#include <exception>
#include <new>

#include "engine/document/commands.h"
#include "engine/eval/evaluator.h"
#include "engine/util/error.h"
#include "engine/util/thread_priority.h"

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
    : scene_(std::move(scene)), id_(id) {
  thread_ = std::thread([this, resolution, makeBackend = std::move(makeBackend)] {
    lowerThisThreadPriority();
    PartMeasure measured;
    std::string error;
    try {
      if (!makeBackend) throw Error("no backend to measure with");
      Evaluator evaluator(makeBackend());
      EvalOptions options;
      options.resolution = resolution;
      const EvalResult r = evaluator.evaluate(partScene(*scene_, id_), options, progress_);
      measured.measure = r.measure;
      measured.h = r.grid.h;
    } catch (const Cancelled&) {
      error = "cancelled";
    } catch (const Error& e) {
      error = e.what();
    } catch (const std::bad_alloc&) {
      error = "out of memory";
    } catch (const std::exception& e) {
      error = std::string("unexpected error: ") + e.what();
    } catch (...) {
      error = "unexpected error";
    }
    {
      std::lock_guard<std::mutex> lock(mutex_);
      result_ = measured;
      error_ = error;
    }
    done_.store(true, std::memory_order_release);
  });
}

PartMeasureJob::~PartMeasureJob() {
  progress_.cancel();
  thread_.join();
}

PartMeasure PartMeasureJob::result() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return result_;
}

std::string PartMeasureJob::error() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return error_;
}

}  // namespace strata
