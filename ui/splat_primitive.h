// How the viewport draws its splats (ViewportRenderer::setSplatPrimitive).
#pragma once

#include <optional>
#include <string>

namespace strata::ui {

// Automatic: whichever of points, quads and compute the renderer's timing of whole images finds
// cheapest (ViewportRenderer::kTimedDrawSplats), quads on software rasterizers and wherever a
// sprite could exceed the driver's largest point (close-ups). Quads, Points or Compute: that
// kind alone (points and compute only where they fit and, for compute, where the GL context
// has compute shaders; quads elsewhere).
enum class SplatPrimitive { Automatic, Quads, Points, Compute };

// "auto", "quads", "points" or "compute"; nothing for another word.
std::optional<SplatPrimitive> parseSplatPrimitive(const std::string& word);

}  // namespace strata::ui
