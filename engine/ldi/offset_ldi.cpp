// See offset_ldi.h.
#include "engine/ldi/offset_ldi.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "engine/ldi/offset_math.h"
#include "engine/util/error.h"
#include "engine/util/large_array.h"
#include "engine/util/parallel_for.h"

namespace strata {
namespace {

OffsetLattice latticeOf(const Grid& g) {
  const int cells[3] = {g.cells.x, g.cells.y, g.cells.z};
  const int first[3] = {g.first.x, g.first.y, g.first.z};
  return makeOffsetLattice(cells, first);
}

// The passes across the layout (along y and z) take their lines in blocks of up to kLineBlock
// whose nodes are neighbours in memory (consecutive lines along the lattice's fast coordinate,
// OffsetLattice::lineCoords), gathered into line-major buffers and scattered back: each cache
// line is then read and written once per block instead of once per line (one line at a time,
// the gathers and scatters were a third of a round's time at 512 cells). The per-line math
// runs on the buffers unchanged, so every value is the same.
constexpr int64_t kLineBlock = 16;

// Calls body(t, count, start, lineStep) for the consecutive blocks of lines [begin, end) along
// `axis`: lines t .. t + count - 1, the first starting at node `start`, each `lineStep` nodes
// after the one before. A block ends where the fast coordinate's row ends.
template <typename Body>
void forLineBlocks(const OffsetLattice& lat, int axis, int64_t begin, int64_t end, Body&& body) {
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  const int fast = lat.stride[v] < lat.stride[u] ? v : u;
  const int64_t row = lat.n[fast], lineStep = lat.stride[fast];
  for (int64_t t = begin; t < end;) {
    const int64_t last = std::min({end, (t / row + 1) * row, t + kLineBlock});
    int64_t i, j;
    lat.lineCoords(axis, t, &i, &j);
    body(t, int(last - t), lat.lineStart(axis, i, j), lineStep);
    t = last;
  }
}

// Lines `count` of a block (see forLineBlocks; `step` between a line's nodes, n nodes each)
// from the lattice array `lattice` into the line-major `lines` (count x n), and back.
template <typename T>
void gatherLines(const T* lattice, int64_t start, int64_t lineStep, int64_t step, int64_t n,
                 int count, T* lines) {
  if (step == 1) {
    for (int l = 0; l < count; ++l)
      std::copy(lattice + start + l * lineStep, lattice + start + l * lineStep + n, lines + l * n);
    return;
  }
  for (int64_t q = 0; q < n; ++q) {
    const T* node = lattice + start + q * step;
    for (int l = 0; l < count; ++l) lines[l * n + q] = node[l * lineStep];
  }
}
template <typename T>
void scatterLines(const T* lines, int64_t start, int64_t lineStep, int64_t step, int64_t n,
                  int count, T* lattice) {
  if (step == 1) {
    for (int l = 0; l < count; ++l)
      std::copy(lines + l * n, lines + (l + 1) * n, lattice + start + l * lineStep);
    return;
  }
  for (int64_t q = 0; q < n; ++q) {
    T* node = lattice + start + q * step;
    for (int l = 0; l < count; ++l) node[l * lineStep] = lines[l * n + q];
  }
}

// Step 1 for `axis`: each node's squared distance (cells^2) along its line to the nearest surfel
// of that line, and that surfel's leaf; for axis 0 also whether the node is inside.
void seedAlongAxis(const Ldi& ldi, const OffsetLattice& lat, int axis, float bandSquared, float* d,
                   uint32_t* leaf, uint8_t* inside, Progress* progress) {
  const AxisLdi& a = ldi.axes[size_t(axis)];
  const int64_t raysU = lat.n[(axis + 1) % 3], rays = lat.lineCount(axis);
  const int64_t n = lat.n[axis], step = lat.stride[axis];
  parallelFor(0, rays, 256, [&](int64_t begin, int64_t end) {
    if (progress) progress->check();
    const size_t block = size_t(kLineBlock * n);
    std::vector<float> dLines(block);
    std::vector<uint32_t> leafLines(block);
    std::vector<uint8_t> insideLines(inside ? block : 0);
    forLineBlocks(
        lat, axis, begin, end, [&](int64_t t, int count, int64_t start, int64_t lineStep) {
          for (int l = 0; l < count; ++l) {
            int64_t i, j;
            lat.lineCoords(axis, t + l, &i, &j);
            const int64_t ray = i + j * raysU;
            const uint32_t from = a.offsets[size_t(ray)];
            offsetSeedLine(a.surfels.data() + from,
                           int64_t(a.offsets[size_t(ray) + 1]) - int64_t(from), lat.first[axis], n,
                           1, bandSquared, dLines.data() + l * n, leafLines.data() + l * n,
                           inside ? insideLines.data() + l * n : nullptr);
          }
          scatterLines(dLines.data(), start, lineStep, step, n, count, d);
          scatterLines(leafLines.data(), start, lineStep, step, n, count, leaf);
          if (inside) scatterLines(insideLines.data(), start, lineStep, step, n, count, inside);
        });
  });
}

// Step 2 along `axis` for every line of the lattice: the envelope of d (and its leaves) into out
// (which may be d itself: each block of lines is copied first); with onlySmaller, out keeps its
// value where that is smaller (offsetEnvelopeLine).
void envelopeAlongAxis(const OffsetLattice& lat, int axis, float bandSquared, const float* d,
                       const uint32_t* leaf, float* out, uint32_t* outLeaf, bool onlySmaller,
                       Progress* progress) {
  const int64_t lines = lat.lineCount(axis), n = lat.n[axis];
  const int64_t step = lat.stride[axis];
  parallelFor(0, lines, 256, [&](int64_t begin, int64_t end) {
    if (progress) progress->check();
    const size_t block = size_t(kLineBlock * n);
    std::vector<float> in(block), outLines(block);
    std::vector<uint32_t> inLeaf(block), outLeafLines(block);
    std::vector<int32_t> v(static_cast<size_t>(n));
    std::vector<double> z(static_cast<size_t>(n));
    forLineBlocks(lat, axis, begin, end, [&](int64_t, int count, int64_t start, int64_t lineStep) {
      gatherLines(d, start, lineStep, step, n, count, in.data());
      gatherLines(leaf, start, lineStep, step, n, count, inLeaf.data());
      if (onlySmaller) {  // the values the envelope keeps where they are smaller
        gatherLines(out, start, lineStep, step, n, count, outLines.data());
        gatherLines(outLeaf, start, lineStep, step, n, count, outLeafLines.data());
      }
      for (int l = 0; l < count; ++l)
        offsetEnvelopeLine(in.data() + l * n, inLeaf.data() + l * n, 1, outLines.data() + l * n,
                           outLeafLines.data() + l * n, 1, n, lat.first[axis], v.data(), z.data(),
                           1, bandSquared, onlySmaller);
      scatterLines(outLines.data(), start, lineStep, step, n, count, out);
      scatterLines(outLeafLines.data(), start, lineStep, step, n, count, outLeaf);
    });
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
  // Left uninitialised (the passes below write every node before reading it: the x seeds every
  // d, leaf and inside flag, the first envelope every best), touched first by the parallel
  // passes, in huge pages where the system offers them (the passes along z stride by a layer).
  const size_t nodes = size_t(lat.count);
  LargeArray<float> best(nodes), d(nodes);
  LargeArray<uint32_t> bestLeaf(nodes), leaf(nodes);
  LargeArray<uint8_t> inside(nodes);
  float *bd = best.get(), *dd = d.get();
  uint32_t *bl = bestLeaf.get(), *dl = leaf.get();
  // Progress "offset": a step for each of the eight passes below and each axis written.
  int stepsDone = 0;
  const auto stepDone = [&] {
    if (progress) progress->report("offset", double(++stepsDone) / 11.0);
  };
  // best = Ez Sx (and the inside flags, from the x rays).
  seedAlongAxis(ldi, lat, 0, band, dd, dl, inside.get(), progress);
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
  float* sd = d.get();
  parallelFor(0, lat.count, 1 << 16, [&](int64_t begin, int64_t end) {
    for (int64_t i = begin; i < end; ++i)
      sd[i] = offsetSignedDistance(best[size_t(i)], inside[size_t(i)]);
  });
  best.reset();

  // Step 3: each ray's crossings of sd = offset, counted, then written.
  auto result = std::make_shared<Ldi>();
  result->grid = g;
  for (int axis = 0; axis < 3; ++axis) {
    const int64_t raysU = lat.n[(axis + 1) % 3], rays = lat.lineCount(axis);
    AxisLdi& out = result->axes[size_t(axis)];
    out.whole = true;
    std::vector<uint32_t> counts(size_t(rays), 0);
    const int64_t n = lat.n[axis];
    parallelFor(0, rays, 1024, [&](int64_t begin, int64_t end) {
      if (progress) progress->check();
      // A block's lines of sd, gathered, are a lattice of their own: line l starts at l * n,
      // its nodes one apart, the same values in the same order as on the whole lattice.
      std::vector<float> lines(size_t(kLineBlock * n));
      OffsetLattice block = lat;
      block.stride[axis] = 1;
      block.stride[(axis + 1) % 3] = n;
      block.stride[(axis + 2) % 3] = 0;
      forLineBlocks(lat, axis, begin, end, [&](int64_t t, int count, int64_t start, int64_t step) {
        gatherLines(sd, start, step, lat.stride[axis], n, count, lines.data());
        for (int l = 0; l < count; ++l) {
          int64_t i, j;
          lat.lineCoords(axis, t + l, &i, &j);
          counts[size_t(i + j * raysU)] =
              offsetRayCount(block, lines.data(), axis, l, 0, offsetCells);
        }
      });
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
      for (int64_t t = begin; t < end; ++t) {
        int64_t i, j;
        lat.lineCoords(axis, t, &i, &j);
        const int64_t ray = i + j * raysU;
        if (counts[size_t(ray)] == 0) continue;  // no crossing: nothing to write
        offsetWriteRay(lat, sd, bestLeaf.get(), axis, i, j, offsetCells,
                       out.surfels.data() + out.offsets[size_t(ray)]);
      }
    });
    stepDone();
  }
  return result;
}

}  // namespace strata
