// Limits a user meets, in one place: what a scene, a command line option or the editor may ask
// for. Messages that refuse a value name the limit.
#pragma once

#include <cstddef>
#include <cstdint>

namespace strata {

// Cells along the longest side of an evaluation grid.
constexpr int kMinResolution = 8;
constexpr int kMaxResolution = 16384;

// Levels of a CSG tree, counted through instances (a leaf alone has depth 1).
constexpr int kMaxTreeDepth = 512;

// Visible leaves an evaluation may visit, counted through instances, unless the user raises it
// (`--max-leaves N`, or the scene setting "maxLeaves").
constexpr uint64_t kDefaultMaxLeaves = 100000;
// The most a scene file may set it to (2^24, about 16.8 million: a file read from anywhere must
// not lift its own guard into hours of work; the 2^40 it took before let an 8 KB scene of
// doubled instances run for hours; a file asking more is held to it, with a warning). The
// command line (`--max-leaves`, the user's own choice) may go to 2^31 - 1.
constexpr int64_t kMaxLeavesSetting = int64_t(1) << 24;

// Measurements a scene may hold (engine/document/measurement.h).
constexpr size_t kMaxMeasurements = 10000;

}  // namespace strata
