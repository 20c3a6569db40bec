// `strata render`: a scene's preview as the editor's viewport draws it (surfel splats coloured by
// leaf, ground grid, section plane), rendered off-screen into pixels, with no window and no
// ImGui. The caller makes a GL context current first (HeadlessGl, or a GlWindow where EGL is
// missing).
//
// Threads: the thread with the GL context current.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "engine/document/scene.h"
#include "engine/eval/backend.h"
#include "engine/util/progress.h"
#include "ui/camera.h"
#include "ui/editor_state.h"
#include "ui/splat_primitive.h"

namespace strata::ui {

struct SceneRenderOptions {
  int width = 1280, height = 800;  // pixels
  std::optional<AxisView> view;    // none: the editor's default three-quarter view
  bool ortho = false;
  int resolution = 0;  // 0: the scene's
  SectionState section;
  bool grid = true;
  // Every splat, whatever the view's level of detail needs (ViewportRenderer::detailLevel).
  bool everySplat = false;
  SplatPrimitive splatPrimitive = SplatPrimitive::Automatic;
};

struct SceneRender {
  std::vector<uint8_t> pixels;  // width * height RGBA, top row first
  size_t splats = 0;
  size_t splatsDrawn = 0;  // those of the level of detail drawn
  int detailLevel = 0;
  bool drawnAsPoints = false;   // the splats were drawn as points
  bool drawnByCompute = false;  // the splats were drawn by compute (neither: quads)
  int resolution = 0;
  double evaluateSeconds = 0.0;
};

// Evaluates `scene` on `backend` (its splats copied to the host if the backend keeps them
// elsewhere) and renders it. Throws strata::Error (evaluation, GL) and Cancelled.
SceneRender renderScene(const Scene& scene, const std::string& scenePath,
                        const std::shared_ptr<Backend>& backend, const SceneRenderOptions& options,
                        Progress& progress);

}  // namespace strata::ui
