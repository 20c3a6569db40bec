// Limits a user meets, in one place: what a scene, a command line option or the editor may ask
// for. Messages that refuse a value name the limit.
#pragma once

namespace strata {

// Cells along the longest side of an evaluation grid.
constexpr int kMinResolution = 8;
constexpr int kMaxResolution = 16384;

}  // namespace strata
