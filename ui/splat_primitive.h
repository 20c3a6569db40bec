// How the viewport draws its splats (ViewportRenderer::setSplatPrimitive).
#pragma once

#include <optional>
#include <string>

namespace strata::ui {

// Automatic: one point per splat where every splat's sprite fits in the driver's largest point,
// quads elsewhere (close-ups). Quads or Points: that kind alone (points only where they fit).
enum class SplatPrimitive { Automatic, Quads, Points };

// "auto", "quads" or "points"; nothing for another word.
std::optional<SplatPrimitive> parseSplatPrimitive(const std::string& word);

}  // namespace strata::ui
