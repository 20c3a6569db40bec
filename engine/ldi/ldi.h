// Layered depth images on the host: for each of the three axes, every ray's surfels sorted by
// depth, stored as key-data pairs compacted into CSR (per-ray offsets + one surfel array).
// Memory grows with the surface, not the volume, and there is no layer limit.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include "engine/ldi/grid.h"
#include "engine/ldi/shared_math.h"
#include "engine/util/host_array.h"

namespace strata {

// The rays of one axis that an AxisLdi stores: (u0 + i, v0 + j) for i < uCount, j < vCount,
// in the grid's ray coordinates (see grid.h); local ray i + j * uCount.
struct RayWindow {
  int u0 = 0, v0 = 0, uCount = 0, vCount = 0;

  int64_t rayCount() const { return int64_t(uCount) * vCount; }
  bool empty() const { return uCount <= 0 || vCount <= 0; }
  bool contains(int i, int j) const {
    return i >= u0 && j >= v0 && i < u0 + uCount && j < v0 + vCount;
  }
};

// The surfels of one axis. A whole axis (whole == true, what every consumer but the CPU
// backend's combine sees; see wholeLdi) has offsets for all rayCount(axis) rays: the surfels of
// ray r are surfels[offsets[r] .. offsets[r + 1]). A windowed axis (whole == false, made by the
// CPU backend for solids small against the grid, so that 100,000 small leaves do not each pay
// for every ray of the grid) has offsets only for the rays of `window`, indexed by local ray;
// the other rays have no surfels. Either way each list is sorted by depth, alternating enter /
// exit, starting with an enter (a "clean" list).
struct AxisLdi {
  bool whole = true;
  RayWindow window;  // meaningful when !whole
  std::vector<uint32_t> offsets;
  HostArray<Surfel> surfels;  // resize leaves new surfels unwritten: every site writes them all

  size_t bytes() const {
    return offsets.capacity() * sizeof(uint32_t) + surfels.capacity() * sizeof(Surfel);
  }
};

struct Ldi {
  Grid grid;
  std::array<AxisLdi, 3> axes;

  size_t surfelCount() const {
    return axes[0].surfels.size() + axes[1].surfels.size() + axes[2].surfels.size();
  }
  size_t bytes() const { return axes[0].bytes() + axes[1].bytes() + axes[2].bytes(); }
};

// An LDI with no surfels on the grid (windowed axes of no rays: a few bytes whatever the grid).
std::shared_ptr<Ldi> makeEmptyLdi(const Grid& grid);

// The window of every ray of `axis` of the grid.
RayWindow wholeWindow(const Grid& grid, int axis);

// `ldi` itself when every axis is whole, else a copy with whole axes.
std::shared_ptr<const Ldi> wholeLdi(std::shared_ptr<const Ldi> ldi);

// The rays of `window` (a window on `ldi`'s lattice, within its grid) with their whole lists:
// what a consumer of the window reads of them (a ray's surfels beyond the window count for its
// parity, as a sampled ray's clipped ones do). Every axis of the result is whole.
std::shared_ptr<Ldi> cropLdi(const std::shared_ptr<const Ldi>& ldi, const Grid& window);

// The same lists on another window of `ldi`'s lattice (same origin and h; throws strata::Error
// otherwise): rays of `window` that `ldi`'s grid holds keep their lists, the others are empty,
// rays of `ldi` outside `window` are dropped. Exactly what evaluating on `window` gives when the
// solid lies within both windows (the editor's preview keeps its LDIs when the scene's grid
// grows or shrinks around them: Evaluator). Axes stay windowed where they were and fit.
std::shared_ptr<Ldi> rewindowLdi(const std::shared_ptr<const Ldi>& ldi, const Grid& window);

// Where ray (i, j) of `axis` of `window` lies among the rays of `grid` (same lattice, window
// within the grid): its index there is i + di + (j + dj) * grid.raysU(axis). Throws
// strata::Error when the window does not lie within the grid.
struct RayShift {
  int di = 0, dj = 0;
  // The index in the grid of the window's ray `ray` (window rays raysU across; grid rays fromU).
  STRATA_HD int64_t source(int64_t ray, int raysU, int fromU) const {
    return (ray % raysU + di) + (ray / raysU + dj) * int64_t(fromU);
  }
};
RayShift rayShift(const Grid& grid, const Grid& window, int axis);

// Stores `axis` (built for the rays of `window`) whole when the window covers more than half of
// the grid's rays (the offsets of the other rays cost little then, and consumers read it
// directly), windowed otherwise.
void settleAxisWindow(const Grid& grid, int axisIndex, const RayWindow& window, AxisLdi* axis);

// Volume and area of the solid an LDI describes, in scene units.
//   volume: per axis, the summed inside length of all rays times h^2; the three axes averaged
//   area:   each surfel stands for h^2 / |n|_1 of surface (the three axes together sample a
//           patch with normal n at density |n|_1 / h^2)
//   thinnestWall: the thinnest wall any ray crosses (shared_math.h: rayThinnestWall), scene
//           units, +infinity when none; thinnestAt: the middle of that wall, world coordinates.
//           An estimate at the grid's resolution: spans under half a cell are not judged.
struct LdiMeasure {
  double volume = 0.0;
  std::array<double, 3> axisVolume{0.0, 0.0, 0.0};
  double area = 0.0;
  size_t surfels = 0;
  double thinnestWall = std::numeric_limits<double>::infinity();
  glm::dvec3 thinnestAt{0.0};
};
// The world point at `depth` on the stored ray `ray` of axis `axis` of an LDI on `grid` (rays
// of a windowed axis count within its window).
glm::dvec3 rayPoint(const Grid& grid, int axis, bool whole, const RayWindow& window, int64_t ray,
                    double depth);
LdiMeasure measureLdi(const Ldi& ldi);

// Throws strata::Error when a surfel count no longer fits the 32-bit offsets.
void checkSurfelCount(uint64_t count, const char* what);

}  // namespace strata
