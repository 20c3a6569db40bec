// The backend interface: where LDIs are computed and kept. The CPU backend (cpu_backend.h) is
// the reference; the CUDA backend (gpu/) implements the same interface and keeps its LDIs on
// the device. The engine passes handles, never arrays: data stays where it was computed, and a
// copy to the host happens only in download().
//
// Threads: a backend is used by one thread at a time (the evaluator's); handles are immutable
// and may be shared with, and released on, any thread.
#pragma once

#include <glm/mat4x4.hpp>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "engine/contour/contour_tile.h"
#include "engine/geometry/mesh.h"
#include "engine/kinds/node_kind.h"
#include "engine/ldi/ldi.h"
#include "engine/ldi/splats.h"
#include "engine/util/progress.h"

namespace strata {

// An LDI owned by a backend. Immutable once made.
class LdiResource {
 public:
  virtual ~LdiResource() = default;
  virtual const Grid& grid() const = 0;
  virtual size_t surfelCount() const = 0;
  virtual size_t bytes() const = 0;  // memory held, on whatever memory the backend uses
};
using LdiHandle = std::shared_ptr<const LdiResource>;

// One leaf to sample: `mesh` (borrowed for the call) placed by `objectToWorld`, its surfels
// tagged `leafId`.
struct LeafToSample {
  const TriangleMesh* mesh = nullptr;
  glm::dmat4 objectToWorld{1.0};
  uint32_t leafId = 0;
};

class Backend {
 public:
  virtual ~Backend() = default;
  // "cpu (2 threads)", "cuda (NVIDIA H100 80GB HBM3)".
  virtual std::string description() const = 0;
  virtual LdiHandle sampleMesh(const TriangleMesh& mesh, const glm::dmat4& objectToWorld,
                               const Grid& grid, uint32_t leafId, Progress& progress) = 0;
  // Many leaves at once: result k is what sampleMesh makes of leaves[k]. The evaluator hands
  // every leaf an evaluation must sample to one call, so a backend whose cost is per call (the
  // CUDA one: launches and waits) samples them in one pass. The default calls sampleMesh on
  // each in turn.
  virtual std::vector<LdiHandle> sampleMeshes(const std::vector<LeafToSample>& leaves,
                                              const Grid& grid, Progress& progress);
  virtual LdiHandle combine(RayOp op, const std::vector<LdiHandle>& children, const Grid& grid,
                            Progress& progress) = 0;
  virtual LdiHandle empty(const Grid& grid) = 0;
  virtual LdiMeasure measure(const LdiHandle& ldi, Progress& progress) = 0;
  // A host copy (or view) of the LDI, every axis whole (see AxisLdi).
  virtual std::shared_ptr<const Ldi> download(const LdiHandle& ldi) = 0;
  // Dual contouring of one tile (see engine/contour/contour_tile.h) of `root`, an LDI on the
  // tile's window grid. The default downloads the LDI and contours it on the CPU, keeping the
  // node planes for the next tile (hostContourArrays_).
  virtual TileContour contourTile(const LdiHandle& root, const glm::ivec3& globalCells,
                                  const glm::ivec3& begin, const glm::ivec3& end,
                                  Progress& progress);
  // The rays of `window` (a window within ldi's grid, on its lattice) with their whole lists
  // (engine/ldi/ldi.h: cropLdi; the CUDA twin gives the same bits): a tile's part of an LDI
  // evaluated on a larger window (a tiled export of modifiers, contour_scene.h).
  virtual LdiHandle crop(const LdiHandle& ldi, const Grid& window, Progress& progress) = 0;
  // The same LDI on another window of its lattice (engine/ldi/ldi.h: rewindowLdi), for an
  // evaluation whose grid moved around a cached node that lies within both windows; nullptr
  // where the backend cannot (the default), and the evaluator computes the node again.
  virtual LdiHandle rewindow(const LdiHandle& ldi, const Grid& window);
  // `ldi`'s solid grown (distance > 0) or shrunk (distance < 0) by |distance| scene units, on
  // its grid (engine/ldi/offset_ldi.h; the CUDA twin gives the same bits). The default throws
  // strata::Error: a backend that cannot offset says so.
  virtual LdiHandle offset(const LdiHandle& ldi, double distance, Progress& progress);
  // `ldi` changed by a modifier (engine/kinds/node_kinds.h: offset, shell, round, fillet) by
  // `amount` scene units, on the LDI's grid: composed from offset() and combine(), the same on
  // every backend.
  // For a shell, `wallOf` (on the same grid) is the solid whose inward offset is taken away,
  // when it is not `ldi` itself: the solid without the shell's opening (Node::opening).
  LdiHandle modify(Modifier modifier, double amount, const LdiHandle& ldi, Progress& progress,
                   const LdiHandle& wallOf = nullptr);
  // Whether offset() works here. Where it does not, the editor's preview and exports evaluate
  // scenes holding a modifier on a CPU backend instead, and say so.
  virtual bool evaluatesModifiers() const { return false; }
  // Bytes of the memory this backend keeps its LDIs and contours in that it could still take
  // now (0 = unknown). Sizes export tiles (contour_scene.h). The default: the host's
  // (availableMemoryBytes, engine/util/memory.h).
  virtual uint64_t memoryAvailable() const;
  // Whether LDIs (LdiResource::bytes) take host memory (true) or the device's (false).
  virtual bool keepsLdisOnHost() const { return true; }
  // Bytes per node of its grid window that an offset holds at once in that memory (sizes the
  // tiles of exports with modifiers): the CPU's kHostOffsetBytesPerNode by default
  // (engine/ldi/offset_math.h).
  virtual uint64_t offsetBytesPerNode() const;
  // The splats of `ldi` (engine/ldi/splats.h), made and kept where the backend keeps its LDIs.
  // The default downloads the LDI and builds them on the host.
  virtual SplatsHandle splats(const LdiHandle& ldi, Progress& progress);
  // Releases what contourTile keeps for the next tile (after an export's last tile, so that its
  // merge does not hold them).
  void releaseContourArrays() { hostContourArrays_ = TileSides(); }

 private:
  // The default contourTile's node planes, kept from tile to tile while the backend lives (an
  // export's tiles, one after another on one backend); released with it.
  TileSides hostContourArrays_;
};

}  // namespace strata
