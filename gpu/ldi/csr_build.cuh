// Building device LDIs from per-ray lists, for all three axes at once.
//
// Kernels of the CUDA backend work on the concatenated rays of the three axes (global ray
// index R in [0, rays(0) + rays(1) + rays(2))), so each step is one launch and the host waits
// for the device only where it must learn a size. This file holds that ray space and the final
// split of a concatenated CSR into the three axes of a DeviceLdi.
#pragma once

#include <cuda_runtime.h>

#include <memory>
#include <vector>

#include "gpu/ldi/device_ldi.h"

namespace strata {

// The three axes' rays, concatenated: every ray of the grid, or of a window per axis (the ray
// (i, j) of axis a is base[a] + (i - u0[a]) + (j - v0[a]) * raysU[a]).
struct RaySpace {
  int64_t base[4];  // first global ray of each axis; base[3] = total rays
  int raysU[3];     // rays along u per axis (of the window)
  int u0[3], v0[3];

  RaySpace() : base{0, 0, 0, 0}, raysU{0, 0, 0}, u0{0, 0, 0}, v0{0, 0, 0} {}  // no rays
  explicit RaySpace(const Grid& grid) {
    base[0] = 0;
    for (int a = 0; a < 3; ++a) {
      base[a + 1] = base[a] + grid.rayCount(a);
      raysU[a] = grid.raysU(a);
      u0[a] = v0[a] = 0;
    }
  }
  explicit RaySpace(const RayWindow windows[3]) {
    base[0] = 0;
    for (int a = 0; a < 3; ++a) {
      base[a + 1] = base[a] + windows[a].rayCount();
      raysU[a] = windows[a].uCount;
      u0[a] = windows[a].u0;
      v0[a] = windows[a].v0;
    }
  }
  // The concatenated index of ray (i, j) of `axis` (inside the axis's window).
  __host__ __device__ int64_t rayOf(int axis, int i, int j) const {
    return base[axis] + int64_t(i - u0[axis]) + int64_t(j - v0[axis]) * raysU[axis];
  }
  __host__ __device__ int64_t total() const { return base[3]; }
  __host__ __device__ int axisOf(int64_t ray) const {
    return ray < base[1] ? 0 : (ray < base[2] ? 1 : 2);
  }
};

// Every function here queues its work on `stream` (and allocates its scratch there); the
// device pointers it takes must be valid for work on that stream.

// In-place exclusive scan of `count` 64-bit values; returns nothing (no host wait).
void exclusiveScanAsync(uint64_t* data, int64_t count, const DeviceStream& stream);

// Reads `n` values at the given device addresses into host memory, with one wait.
void readBack(const uint64_t* const* addresses, uint64_t* values, int n,
              const DeviceStream& stream);

// Writes counts[R] widened to 64 bits into wide[R] (and 0 at wide[total]).
void widenCounts(const uint32_t* counts, int64_t total, uint64_t* wide, const DeviceStream& stream);

// Where each axis's surfels start on the device: ray R of axis a writes its list at
// surfels[a] + (wide[R] - wide[space.base[a]]), wide being the scan allocateAxes was given.
struct AxisSurfelTargets {
  Surfel* surfels[3];
  uint64_t total;  // surfels of all three axes
};

// Given `wide`, the exclusive scan of per-ray surfel counts over `space` (total + 1 values, on
// the device), reads the three axis totals back (one wait), allocates out's axes on
// out->stream() and writes their offsets; the surfels are left to the caller. Throws
// strata::Error (naming `what`) when an axis exceeds 2^32 surfels.
AxisSurfelTargets allocateAxes(const RaySpace& space, const uint64_t* wide, DeviceLdi* out,
                               const char* what);

// Given per-ray counts (concatenated rays) and each ray's start in a scratch buffer, builds the
// three axes of `out`: scans the counts, reads the three axis totals back (one wait), and
// copies each ray's list to its place, allocating out's buffers on out->stream() (the one the
// work is queued on). Throws strata::Error when an axis exceeds 2^32 surfels.
void buildAxes(const RaySpace& space, const uint32_t* counts, const Surfel* scratch,
               const uint64_t* scratchOffsets, DeviceLdi* out, const char* what);

// Rays of several LDIs, one after the other: LDI k's ray space (its axes, whole or windowed)
// starts at global ray first[k]; `total` rays in all.
struct RaySpaces {
  std::vector<RaySpace> spaces;
  std::vector<int64_t> first;
  int64_t total = 0;
  void add(const RaySpace& space) {
    spaces.push_back(space);
    first.push_back(total);
    total += space.total();
  }
};

// buildAxes for many LDIs at once (outs[k] over spaces.spaces[k]; all on one stream, that of
// outs[0]): one scan, one wait for all their axis sizes, one copy launch. scratch may be null
// when every count is 0.
void buildAxesOfMany(const RaySpaces& spaces, const uint32_t* counts, const Surfel* scratch,
                     const uint64_t* scratchOffsets, const std::vector<DeviceLdi*>& outs,
                     const char* what);

// `ldi` itself when every axis is whole, else a copy with whole axes (offsets for every ray of
// the grid), made on `stream` and complete on return: for the steps that index rays of the
// grid directly (splats, contouring).
std::shared_ptr<const DeviceLdi> wholeOnDevice(const std::shared_ptr<const DeviceLdi>& ldi,
                                               const DeviceStream& stream);

// The rays of `window` (within ldi's grid, on its lattice) with their whole lists: the CUDA
// twin of cropLdi (engine/ldi/ldi.h), the same bits. Made on `stream`, complete on return.
// Throws strata::Error for a window outside the grid.
std::shared_ptr<const DeviceLdi> cropOnDevice(const std::shared_ptr<const DeviceLdi>& ldi,
                                              const Grid& window, const DeviceStream& stream);

// The same lists on another window of ldi's lattice, empty where ldi has no ray: the CUDA twin
// of rewindowLdi (engine/ldi/ldi.h), the same lists. Made on `stream`, complete on return.
// Throws strata::Error for a window on another lattice.
std::shared_ptr<const DeviceLdi> rewindowOnDevice(const std::shared_ptr<const DeviceLdi>& ldi,
                                                  const Grid& window, const DeviceStream& stream);

inline unsigned blocksFor(int64_t items, unsigned threads) {
  int64_t blocks = (items + threads - 1) / threads;
  return unsigned(blocks < 1 ? 1 : (blocks > 0x7fffffff ? 0x7fffffff : blocks));
}

}  // namespace strata
