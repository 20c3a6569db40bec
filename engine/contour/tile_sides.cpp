#include "engine/contour/tile_sides.h"

#include <algorithm>
#include <atomic>
#include <cmath>

#include "engine/util/parallel_for.h"

namespace strata {
namespace {

// Slices (node layers along z) per parallel chunk.
constexpr int kSlicesPerChunk = 8;

// Bit i of the result: the parity of bits 0..i of x.
inline uint64_t prefixParity(uint64_t x) {
  x ^= x << 1;
  x ^= x << 2;
  x ^= x << 4;
  x ^= x << 8;
  x ^= x << 16;
  x ^= x << 32;
  return x;
}

// The first window node along an axis that counts a surfel at `depth` (rayVote: a node counts
// the surfels at or before its depth, float(first + node) >= depth), clamped to [0, nodes]
// (nodes: none does). Exact: grid depths are integers well below 2^24.
inline int firstCountingNode(float depth, int first, int nodes) {
  const float c = std::ceil(depth) - float(first);
  if (!(c > 0.0f)) return c == c ? 0 : nodes;
  return c >= float(nodes) ? nodes : int(c);
}

inline void flipBit(uint64_t* words, int64_t bit) {
  words[bit >> 6] ^= uint64_t(1) << (bit & 63);
}

// Bits of a row's words for the nodes i in [0, count) that satisfy pred(i).
template <typename Pred>
std::vector<uint64_t> rowMask(int64_t words, int count, Pred pred) {
  std::vector<uint64_t> m(size_t(words), 0);
  for (int i = 0; i < count; ++i)
    if (pred(i)) m[size_t(i >> 6)] |= uint64_t(1) << (i & 63);
  return m;
}

// The z rays' toggles, bucketed by the first slice (node layer) they count for: for slice k,
// bits[start[k] .. start[k + 1]) are the bit addresses (j * 64 * rowWords + i) of the z rays
// whose parity changes between slice k - 1 and k (slice 0: every surfel at or below it).
struct ZToggles {
  std::vector<uint32_t> start;
  std::vector<uint32_t> bits;
};

ZToggles bucketZToggles(const TileView& t) {
  const int nx = t.cells[0] + 1, ny = t.cells[1] + 1, nz = t.cells[2] + 1;
  const uint32_t* offsets = t.offsets[2];
  const Surfel* surfels = t.surfels[2];
  ZToggles z;
  z.start.assign(size_t(nz) + 2, 0);
  const int64_t rays = int64_t(nx) * ny;
  for (int64_t r = 0; r < rays; ++r)
    for (uint32_t s = offsets[r]; s < offsets[r + 1]; ++s)
      ++z.start[size_t(firstCountingNode(surfels[s].depth, t.first[2], nz)) + 1];
  for (size_t k = 1; k < z.start.size(); ++k) z.start[k] += z.start[k - 1];
  z.bits.resize(z.start[size_t(nz)]);  // surfels beyond the last slice count for none
  std::vector<uint32_t> cursor(z.start.begin(), z.start.end() - 1);
  for (int64_t r = 0; r < rays; ++r) {
    const int i = int(r % nx), j = int(r / nx);
    const uint32_t bit = uint32_t(int64_t(j) * 64 * t.rowWords + i);
    for (uint32_t s = offsets[r]; s < offsets[r + 1]; ++s) {
      const int k = firstCountingNode(surfels[s].depth, t.first[2], nz);
      if (k < nz) z.bits[cursor[size_t(k)]++] = bit;
    }
  }
  return z;
}

void applyZToggles(const ZToggles& z, int slice, uint64_t* plane) {
  for (uint32_t b = z.start[size_t(slice)]; b < z.start[size_t(slice) + 1]; ++b)
    flipBit(plane, z.bits[b]);
}

// The node bit planes: per slab of slices, z votes from the plane at its first slice, y votes
// from the slice's toggles, x votes per row.
uint64_t decideNodes(const TileView& t, const ZToggles& z, TileSides* sides, Progress* progress) {
  const int nx = t.cells[0] + 1, ny = t.cells[1] + 1, nz = t.cells[2] + 1;
  const int64_t words = t.rowWords, planeWords = words * ny;
  const int chunks = (nz + kSlicesPerChunk - 1) / kSlicesPerChunk;
  // The z votes' plane at each chunk's first slice.
  std::vector<uint64_t> snapshots(size_t(planeWords) * size_t(chunks), 0);
  {
    std::vector<uint64_t> plane(size_t(planeWords), 0);
    for (int c = 0; c < chunks; ++c) {
      const int from = c == 0 ? 0 : (c - 1) * kSlicesPerChunk + 1;
      for (int k = from; k <= c * kSlicesPerChunk; ++k) applyZToggles(z, k, plane.data());
      std::copy(plane.begin(), plane.end(), snapshots.begin() + planeWords * c);
    }
  }
  const std::vector<uint64_t> valid = rowMask(words, nx, [](int) { return true; });
  const std::vector<uint64_t> xFace = rowMask(words, nx, [&](int i) {
    const int g = t.first[0] + i;
    return g == 0 || g == t.globalCells[0];
  });
  const uint32_t* yOffsets = t.offsets[1];
  const Surfel* ySurfels = t.surfels[1];
  const uint32_t* xOffsets = t.offsets[0];
  const Surfel* xSurfels = t.surfels[0];
  std::atomic<uint64_t> disagreements{0};
  parallelFor(0, chunks, 1, [&](int64_t cb, int64_t ce) {
    std::vector<uint64_t> zPlane, yToggles(static_cast<size_t>(planeWords)),
        yRow(static_cast<size_t>(words)), xRow(static_cast<size_t>(words));
    uint64_t local = 0;
    for (int64_t c = cb; c < ce; ++c) {
      if (progress) progress->check();
      zPlane.assign(snapshots.begin() + planeWords * c, snapshots.begin() + planeWords * (c + 1));
      const int kEnd = std::min(nz, int(c + 1) * kSlicesPerChunk);
      for (int k = int(c) * kSlicesPerChunk; k < kEnd; ++k) {
        if (k != int(c) * kSlicesPerChunk) applyZToggles(z, k, zPlane.data());
        // y rays of this slice: ray k + i * nz (tileRay), toggles at the row they start at.
        std::fill(yToggles.begin(), yToggles.end(), 0);
        for (int i = 0; i < nx; ++i) {
          const int64_t ray = k + int64_t(i) * nz;
          for (uint32_t s = yOffsets[ray]; s < yOffsets[ray + 1]; ++s) {
            const int j = firstCountingNode(ySurfels[s].depth, t.first[1], ny);
            if (j < ny) flipBit(yToggles.data() + words * j, i);
          }
        }
        std::fill(yRow.begin(), yRow.end(), 0);
        const int gz = t.first[2] + k;
        const bool zFace = gz == 0 || gz == t.globalCells[2];
        for (int j = 0; j < ny; ++j) {
          const uint64_t* toggles = yToggles.data() + words * j;
          for (int64_t w = 0; w < words; ++w) yRow[size_t(w)] ^= toggles[w];
          // x ray j + k * ny (tileRay): its parity along the row.
          std::fill(xRow.begin(), xRow.end(), 0);
          const int64_t ray = j + int64_t(k) * ny;
          for (uint32_t s = xOffsets[ray]; s < xOffsets[ray + 1]; ++s) {
            const int i = firstCountingNode(xSurfels[s].depth, t.first[0], nx);
            if (i < nx) flipBit(xRow.data(), i);
          }
          uint64_t carry = 0;
          for (int64_t w = 0; w < words; ++w) {
            const uint64_t p = prefixParity(xRow[size_t(w)]) ^ carry;
            xRow[size_t(w)] = p;
            carry = uint64_t(0) - (p >> 63);
          }
          const int gy = t.first[1] + j;
          const bool rowFace = zFace || gy == 0 || gy == t.globalCells[1];
          const uint64_t* zRow = zPlane.data() + words * j;
          uint64_t* inside = sides->insideBits.get() + nodeRow(t, j, k);
          uint64_t* unanimous = sides->unanimousBits.get() + nodeRow(t, j, k);
          for (int64_t w = 0; w < words; ++w) {
            const uint64_t x = xRow[size_t(w)], y = yRow[size_t(w)], zz = zRow[w];
            const uint64_t v = valid[size_t(w)];
            const uint64_t agree = ~((x ^ y) | (x ^ zz)) & v;
            const uint64_t majority = (x & y) | (x & zz) | (y & zz);
            inside[w] = rowFace ? 0 : (majority & v & ~xFace[size_t(w)]);
            unanimous[w] = agree;
            local += uint64_t(__builtin_popcountll(v & ~agree));
          }
        }
      }
    }
    disagreements += local;
  });
  return disagreements.load();
}

// The boundary cells (corners not all on one side) of each cell layer, in increasing index,
// with their masks.
void findBoundaryCells(const TileView& t, TileSides* sides, Progress* progress) {
  const int cx = t.cells[0], cy = t.cells[1], cz = t.cells[2];
  const int64_t words = t.rowWords;
  const std::vector<uint64_t> cellValid = rowMask(words, cx, [](int) { return true; });
  const int chunks = (cz + kSlicesPerChunk - 1) / kSlicesPerChunk;
  std::vector<std::vector<uint32_t>> cells(static_cast<size_t>(chunks));
  std::vector<std::vector<uint8_t>> masks(static_cast<size_t>(chunks));
  parallelFor(0, chunks, 1, [&](int64_t cb, int64_t ce) {
    for (int64_t c = cb; c < ce; ++c) {
      if (progress) progress->check();
      std::vector<uint32_t>& found = cells[size_t(c)];
      std::vector<uint8_t>& foundMasks = masks[size_t(c)];
      const int kEnd = std::min(cz, int(c + 1) * kSlicesPerChunk);
      for (int k = int(c) * kSlicesPerChunk; k < kEnd; ++k)
        for (int j = 0; j < cy; ++j) {
          const uint64_t* a = t.insideBits + nodeRow(t, j, k);
          const uint64_t* b = a + words;
          const uint64_t* d = t.insideBits + nodeRow(t, j, k + 1);
          const uint64_t* e = d + words;
          const int64_t row = tileCell(t, 0, j, k);
          uint64_t all = a[0] & b[0] & d[0] & e[0], any = a[0] | b[0] | d[0] | e[0];
          for (int64_t w = 0; w < words; ++w) {
            uint64_t nextAll = 0, nextAny = 0;
            if (w + 1 < words) {
              nextAll = a[w + 1] & b[w + 1] & d[w + 1] & e[w + 1];
              nextAny = a[w + 1] | b[w + 1] | d[w + 1] | e[w + 1];
            }
            // Cell i joins nodes i and i + 1 of the four rows.
            const uint64_t cellAll = all & ((all >> 1) | (nextAll << 63));
            const uint64_t cellAny = any | (any >> 1) | (nextAny << 63);
            uint64_t mixed = cellAny & ~cellAll & cellValid[size_t(w)];
            while (mixed) {
              const int i = int(w * 64 + __builtin_ctzll(mixed));
              mixed &= mixed - 1;
              found.push_back(uint32_t(row + i));
              foundMasks.push_back(cellMaskFromNodes(t, i, j, k));
            }
            all = nextAll;
            any = nextAny;
          }
        }
    }
  });
  size_t total = 0;
  for (const auto& c : cells) total += c.size();
  sides->boundary.clear();
  sides->boundary.reserve(total);
  sides->boundaryMasks.clear();
  sides->boundaryMasks.reserve(total);
  for (size_t c = 0; c < cells.size(); ++c) {
    sides->boundary.insert(sides->boundary.end(), cells[c].begin(), cells[c].end());
    sides->boundaryMasks.insert(sides->boundaryMasks.end(), masks[c].begin(), masks[c].end());
  }
}

}  // namespace

void decideTileSides(TileView* view, TileSides* sides, Progress* progress) {
  TileView& t = *view;
  t.rowWords = nodeRowWords(t.cells[0]);
  const size_t planes = size_t(t.rowWords) * size_t(t.cells[1] + 1) * size_t(t.cells[2] + 1);
  if (sides->planeCapacity < planes) {  // every word of a tile's planes written by decideNodes
    sides->insideBits.reset();          // the old planes gone before the new ones come
    sides->unanimousBits.reset();
    sides->insideBits.reset(new uint64_t[planes]);
    sides->unanimousBits.reset(new uint64_t[planes]);
    sides->planeCapacity = planes;
  }
  const ZToggles z = bucketZToggles(t);
  sides->disagreements = decideNodes(t, z, sides, progress);
  t.insideBits = sides->insideBits.get();
  t.unanimousBits = sides->unanimousBits.get();
  findBoundaryCells(t, sides, progress);
  t.boundary = sides->boundary.data();
  t.boundaryMasks = sides->boundaryMasks.data();
  t.boundaryCount = int64_t(sides->boundary.size());
}

}  // namespace strata
