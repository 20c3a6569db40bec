// How the viewport draws its splats (ViewportRenderer::setSplatPrimitive).
#pragma once

#include <optional>
#include <string>

namespace strata::ui {

// Automatic: whichever of points and quads the renderer's timing of whole images finds cheaper
// (ViewportRenderer::kTimedDrawSplats), quads on software rasterizers and wherever a sprite could
// exceed the driver's largest point (close-ups). Quads or Points: that kind alone (points only
// where they fit).
enum class SplatPrimitive { Automatic, Quads, Points };

// "auto", "quads" or "points"; nothing for another word.
std::optional<SplatPrimitive> parseSplatPrimitive(const std::string& word);

}  // namespace strata::ui
