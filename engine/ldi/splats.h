// Splats: what the editor's viewport draws of an LDI. Every surfel once, on the axis its normal
// is most aligned with (onDominantAxis, ALGORITHM.md §6), as a compact record for a GL instance
// buffer. The per-surfel math (splatOf, splatRayLevel) is shared with the CUDA twin
// (gpu/ldi/splats.cu), so both backends produce the same splats, bit for bit and in the same
// order: level of detail (coarsest first, see SplatLevels), then axis, then ray, then depth
// along the ray.
#pragma once

#include <cstdint>
#include <memory>
#include <mutex>
#include <vector>

#include "engine/ldi/ldi.h"
#include "engine/ldi/shared_math.h"

namespace strata {

// One splat: 20 bytes, laid out for glVertexAttrib(I)Pointer (see shaders/surfel.vert).
struct Splat {
  float position[3];  // world, scene units
  uint32_t normal;    // octahedral, as in Surfel
  uint32_t leafAxis;  // leaf id << 2 | axis of the ray it lies on
};
static_assert(sizeof(Splat) == 20, "tightly packed splat");

STRATA_HD uint32_t splatLeaf(const Splat& s) {
  return s.leafAxis >> 2;
}

// The lattice of one grid as plain numbers (what a device kernel can take by value).
struct SplatFrame {
  double origin[3];
  double h;
  int64_t first[3];
  int64_t raysU[3];  // per axis: rays along that axis's u direction
};
SplatFrame splatFrame(const Grid& grid);

// The splat of surfel `s` on ray `ray` of `axis`: its world position (grid.h: origin + h times
// the global node line and the depth, in double) rounded to float.
STRATA_HD Splat splatOf(const SplatFrame& f, int axis, int64_t ray, const Surfel& s) {
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  double p[3];
  p[axis] = f.origin[axis] + f.h * double(s.depth);
  p[u] = f.origin[u] + f.h * double(f.first[u] + ray % f.raysU[axis]);
  p[v] = f.origin[v] + f.h * double(f.first[v] + ray / f.raysU[axis]);
  Splat out;
  out.position[0] = float(p[0]);
  out.position[1] = float(p[1]);
  out.position[2] = float(p[2]);
  out.normal = s.normal;
  out.leafAxis = (surfelLeaf(s.tag) << 2) | uint32_t(axis);
  return out;
}

// Levels of detail as prefixes of one array. A ray is of level L when both of its global lattice
// indices across the axis are multiples of 2^L (at most kSplatLevels - 1). Splats of higher
// levels come first, so the first end[L] splats are those of the rays 2^L h apart: drawn with
// discs 2^L times as wide, they cover the same surface with a sixteenth or a quarter of the
// splats (what a viewer draws where a cell is smaller than a pixel). end[0] is every splat.
constexpr int kSplatLevels = 3;
struct SplatLevels {
  uint64_t end[kSplatLevels] = {};
  // Splats in no particular order: every one at level 0, none at the coarser levels.
  static SplatLevels flat(uint64_t count) {
    SplatLevels l;
    l.end[0] = count;
    return l;
  }
};

// The level of ray `ray` of `axis` (see SplatLevels).
STRATA_HD int splatRayLevel(const SplatFrame& f, int axis, int64_t ray) {
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  const int64_t across = (f.first[u] + ray % f.raysU[axis]) | (f.first[v] + ray / f.raysU[axis]);
  int level = 0;
  while (level + 1 < kSplatLevels && (across & ((int64_t(2) << level) - 1)) == 0) ++level;
  return level;
}

// Whether surfel `s` of `axis` becomes a splat.
STRATA_HD bool surfelMakesSplat(const Surfel& s, int axis) {
  float n[3];
  decodeNormal(s.normal, n);
  return onDominantAxis(n, axis);
}

// The splats of `ldi`, on the host (any thread), coarsest level first; *levels (when given)
// says where each level ends.
std::vector<Splat> buildSplats(const Ldi& ldi, SplatLevels* levels = nullptr);

// Splats owned by a backend, wherever it keeps them (host memory for the CPU backend, device
// memory for CUDA, where the editor copies them into a GL buffer without a trip through the
// host). Immutable once made; may be released on any thread.
class SplatResource {
 public:
  virtual ~SplatResource() = default;
  virtual size_t count() const = 0;
  size_t bytes() const { return count() * sizeof(Splat); }
  // Where the levels of detail end in the array (SplatLevels).
  virtual SplatLevels levels() const = 0;
  // The splats in host memory, or null when they live elsewhere.
  virtual const Splat* hostData() const = 0;
  // Copies all count() splats into `out` (host memory).
  virtual void copyToHost(Splat* out) const = 0;
};
using SplatsHandle = std::shared_ptr<const SplatResource>;

// The box of the splats' positions (empty for none): a result's extent as its surfels sample it,
// within a small part of a cell (a flat face exactly; a curved extreme to the nearest ray).
// Copies device splats to the host first. Any thread.
Bounds splatBounds(const SplatResource& splats);

// Host arrays of splats kept for reuse: a new array of millions of splats taken from fresh memory
// costs more in the kernel's zeroing of its pages than the copy that fills it (the preview
// worker's host copies of device splats, 40 MB a result at 1024 cells). Keeps at most
// kKept arrays. Threads: any (a result is released on the UI thread, arrays taken on the
// worker's).
class SplatArrayPool {
 public:
  static constexpr size_t kKept = 2;
  // An array of `count` splats (contents unspecified): a kept one when one is large enough.
  std::vector<Splat> take(size_t count);
  // Keeps `splats` for a later take (or drops it when kKept are kept).
  void give(std::vector<Splat>&& splats);

 private:
  std::mutex mutex_;
  std::vector<std::vector<Splat>> kept_;
};

// Splats in host memory.
class HostSplats : public SplatResource {
 public:
  // Splats of buildSplats with its levels, or in any order (every splat at level 0).
  explicit HostSplats(std::vector<Splat> splats)
      : splats_(std::move(splats)), levels_(SplatLevels::flat(splats_.size())) {}
  HostSplats(std::vector<Splat> splats, const SplatLevels& levels)
      : splats_(std::move(splats)), levels_(levels) {}
  // With `pool`: the array goes back to it when this is released.
  HostSplats(std::vector<Splat> splats, const SplatLevels& levels,
             std::shared_ptr<SplatArrayPool> pool)
      : splats_(std::move(splats)), levels_(levels), pool_(std::move(pool)) {}
  ~HostSplats() override {
    if (!pool_) return;
    try {
      pool_->give(std::move(splats_));
    } catch (...) {  // out of memory keeping it: the array is freed instead
    }
  }
  HostSplats(const HostSplats&) = delete;
  HostSplats& operator=(const HostSplats&) = delete;
  size_t count() const override { return splats_.size(); }
  SplatLevels levels() const override { return levels_; }
  const Splat* hostData() const override { return splats_.data(); }
  void copyToHost(Splat* out) const override;
  const std::vector<Splat>& splats() const { return splats_; }

 private:
  std::vector<Splat> splats_;
  SplatLevels levels_;
  std::shared_ptr<SplatArrayPool> pool_;
};

}  // namespace strata
