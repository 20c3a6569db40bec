#include "ui/scene_render.h"

#include <algorithm>

#include "engine/eval/evaluator.h"
#include "engine/util/timer.h"
#include "ui/scene_queries.h"
#include "ui/viewport.h"
#include "ui/viewport_renderer.h"

namespace strata::ui {

SceneRender renderScene(const Scene& scene, const std::string& scenePath,
                        const std::shared_ptr<Backend>& backend, const SceneRenderOptions& options,
                        Progress& progress) {
  SceneRender out;
  EditorState state;  // what the viewport reads: the document, grid and section settings
  state.document = Document(scene, scenePath);
  state.showGrid = options.grid;
  state.section = options.section;

  Stopwatch clock;
  Evaluator evaluator(backend);
  EvalOptions eval;
  eval.resolution = options.resolution;
  EvalResult result = evaluator.evaluate(scene, eval, progress);
  SplatsHandle splats = backend->splats(result.root, progress);
  out.evaluateSeconds = clock.seconds();
  out.resolution = result.grid.cells.x > 0
                       ? (options.resolution > 0 ? options.resolution : scene.settings.resolution)
                       : 0;
  out.splats = splats->count();

  ViewportRenderer renderer;
  if (const Splat* host = splats->hostData()) {
    renderer.uploadSplats(host, splats->count(), splatShapeOf(result.grid, *splats));
  } else {
    std::vector<Splat> copy(splats->count());
    splats->copyToHost(copy.data());
    renderer.uploadSplats(copy.data(), copy.size(), splatShapeOf(result.grid, *splats));
  }
  renderer.setLeafStyles(leafStyles(scene.root, {}));
  if (options.everySplat) renderer.limitDetailLevel(0);
  renderer.setSplatPrimitive(options.splatPrimitive);

  Viewport viewport;
  if (options.view) viewport.camera.setAxisView(*options.view);
  viewport.camera.ortho = options.ortho;
  viewport.viewAll(state);
  RenderTarget target(options.width, options.height);
  target.bind();
  ViewRect rect;
  rect.width = options.width;
  rect.height = options.height;
  viewport.draw(renderer, state, rect, options.height, 1.0);
  out.pixels = target.read();
  out.detailLevel = std::max(0, renderer.drawnLevel());
  out.splatsDrawn = renderer.drawnLevelSplats();
  out.drawnAsPoints = renderer.pointsDrawn() > 0;
  out.drawnByCompute = renderer.computedDrawn() > 0;
  return out;
}

}  // namespace strata::ui
