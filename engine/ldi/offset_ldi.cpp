// See offset_ldi.h.
#include "engine/ldi/offset_ldi.h"

#include <cmath>
#include <vector>

#include "engine/ldi/offset_math.h"
#include "engine/util/error.h"
#include "engine/util/parallel_for.h"

namespace strata {
namespace {

OffsetLattice latticeOf(const Grid& g) {
  const int cells[3] = {g.cells.x, g.cells.y, g.cells.z};
  const int first[3] = {g.first.x, g.first.y, g.first.z};
  return makeOffsetLattice(cells, first);
}

// Step 1 for `axis`: each node's squared distance (cells^2) along its line to the nearest surfel
// of that line, and that surfel's leaf; for axis 0 also whether the node is inside.
void seedAlongAxis(const Ldi& ldi, const OffsetLattice& lat, int axis, float bandSquared, float* d,
                   uint32_t* leaf, uint8_t* inside, Progress* progress) {
  const int u = (axis + 1) % 3;
  const AxisLdi& a = ldi.axes[size_t(axis)];
  const int64_t raysU = lat.n[u], rays = lat.lineCount(axis);
  parallelFor(0, rays, 256, [&](int64_t begin, int64_t end) {
    if (progress) progress->check();
    for (int64_t ray = begin; ray < end; ++ray) {
      const int64_t start = lat.lineStart(axis, ray % raysU, ray / raysU);
      const uint32_t from = a.offsets[size_t(ray)];
      offsetSeedLine(a.surfels.data() + from, int64_t(a.offsets[size_t(ray) + 1]) - int64_t(from),
                     lat.first[axis], lat.n[axis], lat.stride[axis], bandSquared, d + start,
                     leaf + start, inside ? inside + start : nullptr);
    }
  });
}

// Step 2 along `axis` for every line of the lattice: the envelope of d (and its leaves) into out
// (which may be d itself: each line is copied first); with onlySmaller, out keeps its value
// where that is smaller (offsetEnvelopeLine).
void envelopeAlongAxis(const OffsetLattice& lat, int axis, float bandSquared, const float* d,
                       const uint32_t* leaf, float* out, uint32_t* outLeaf, bool onlySmaller,
                       Progress* progress) {
  const int u = (axis + 1) % 3;
  const int64_t linesU = lat.n[u], lines = lat.lineCount(axis), n = lat.n[axis];
  const int64_t step = lat.stride[axis];
  parallelFor(0, lines, 256, [&](int64_t begin, int64_t end) {
    if (progress) progress->check();
    std::vector<float> in(static_cast<size_t>(n));
    std::vector<uint32_t> inLeaf(static_cast<size_t>(n));
    std::vector<int32_t> v(static_cast<size_t>(n));
    std::vector<double> z(static_cast<size_t>(n));
    for (int64_t line = begin; line < end; ++line) {
      const int64_t start = lat.lineStart(axis, line % linesU, line / linesU);
      for (int64_t q = 0; q < n; ++q) {
        in[size_t(q)] = d[start + q * step];
        inLeaf[size_t(q)] = leaf[start + q * step];
      }
      offsetEnvelopeLine(in.data(), inLeaf.data(), 1, out + start, outLeaf + start, step, n,
                         lat.first[axis], v.data(), z.data(), 1, bandSquared, onlySmaller);
    }
  });
}

}  // namespace

std::shared_ptr<Ldi> offsetLdi(const Ldi& input, double distance, Progress* progress) {
  const std::shared_ptr<const Ldi> whole =
      wholeLdi(std::shared_ptr<const Ldi>(std::shared_ptr<const Ldi>(), &input));
  const Ldi& ldi = *whole;
  const Grid& g = ldi.grid;
  if (!std::isfinite(distance)) throw Error("offset distance is not a finite number");
  const OffsetLattice lat = latticeOf(g);
  const double offsetCells = distance / g.h;

  // Steps 1 and 2: the smallest over the three axes' samplings. The samples of the x rays need
  // envelopes along y and z, those of the y rays along z and x, those of the z rays along x and
  // y. An envelope is a min-plus convolution: it distributes over the minimum, so the x and z
  // rays share their y envelope: best = min(Ey(min(Ez Sx, Ex Sz)), Ez Ex Sy), five envelopes
  // instead of six, in the order the CUDA twin needs for its layouts (gpu/ldi/offset_ldi.cu runs
  // the same passes in the same order). Distances beyond the band are far (offsetBandSquared).
  const float band = offsetBandSquared(offsetCells);
  std::vector<float> best(size_t(lat.count)), d(size_t(lat.count));
  std::vector<uint32_t> bestLeaf(size_t(lat.count)), leaf(size_t(lat.count));
  std::vector<uint8_t> inside(size_t(lat.count), 0);
  float *bd = best.data(), *dd = d.data();
  uint32_t *bl = bestLeaf.data(), *dl = leaf.data();
  // Progress "offset": a step for each of the eight passes below and each axis written.
  int stepsDone = 0;
  const auto stepDone = [&] {
    if (progress) progress->report("offset", double(++stepsDone) / 11.0);
  };
  // best = Ez Sx (and the inside flags, from the x rays).
  seedAlongAxis(ldi, lat, 0, band, dd, dl, inside.data(), progress);
  stepDone();
  envelopeAlongAxis(lat, 2, band, dd, dl, bd, bl, false, progress);
  stepDone();
  // best = Ey min(best, Ex Sz).
  seedAlongAxis(ldi, lat, 2, band, dd, dl, nullptr, progress);
  stepDone();
  envelopeAlongAxis(lat, 0, band, dd, dl, bd, bl, true, progress);
  stepDone();
  envelopeAlongAxis(lat, 1, band, bd, bl, bd, bl, false, progress);
  stepDone();
  // best = min(best, Ez Ex Sy).
  seedAlongAxis(ldi, lat, 1, band, dd, dl, nullptr, progress);
  stepDone();
  envelopeAlongAxis(lat, 0, band, dd, dl, dd, dl, false, progress);
  stepDone();
  envelopeAlongAxis(lat, 2, band, dd, dl, bd, bl, true, progress);
  stepDone();
  // Signed distance in cells (reusing d): negative inside; far everywhere without a surface.
  float* sd = d.data();
  parallelFor(0, lat.count, 1 << 16, [&](int64_t begin, int64_t end) {
    for (int64_t i = begin; i < end; ++i)
      sd[i] = offsetSignedDistance(best[size_t(i)], inside[size_t(i)]);
  });
  std::vector<float>().swap(best);

  // Step 3: each ray's crossings of sd = offset, counted, then written.
  auto result = std::make_shared<Ldi>();
  result->grid = g;
  for (int axis = 0; axis < 3; ++axis) {
    const int64_t raysU = lat.n[(axis + 1) % 3], rays = lat.lineCount(axis);
    AxisLdi& out = result->axes[size_t(axis)];
    out.whole = true;
    std::vector<uint32_t> counts(size_t(rays), 0);
    parallelFor(0, rays, 1024, [&](int64_t begin, int64_t end) {
      if (progress) progress->check();
      for (int64_t ray = begin; ray < end; ++ray)
        counts[size_t(ray)] = offsetRayCount(lat, sd, axis, ray % raysU, ray / raysU, offsetCells);
    });
    uint64_t total = 0;
    out.offsets.resize(size_t(rays) + 1);
    for (int64_t ray = 0; ray < rays; ++ray) {
      out.offsets[size_t(ray)] = uint32_t(total);
      total += counts[size_t(ray)];
      checkSurfelCount(total, "the offset");
    }
    out.offsets[size_t(rays)] = uint32_t(total);
    out.surfels.resize(size_t(total));
    parallelFor(0, rays, 1024, [&](int64_t begin, int64_t end) {
      if (progress) progress->check();
      for (int64_t ray = begin; ray < end; ++ray)
        offsetWriteRay(lat, sd, bestLeaf.data(), axis, ray % raysU, ray / raysU, offsetCells,
                       out.surfels.data() + out.offsets[size_t(ray)]);
    });
    stepDone();
  }
  return result;
}

}  // namespace strata
