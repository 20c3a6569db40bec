#include "ui/splat_primitive.h"

namespace strata::ui {

std::optional<SplatPrimitive> parseSplatPrimitive(const std::string& word) {
  if (word == "auto") return SplatPrimitive::Automatic;
  if (word == "quads") return SplatPrimitive::Quads;
  if (word == "points") return SplatPrimitive::Points;
  if (word == "compute") return SplatPrimitive::Compute;
  return std::nullopt;
}

}  // namespace strata::ui
