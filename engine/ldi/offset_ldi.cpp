// See offset_ldi.h.
#include "engine/ldi/offset_ldi.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "engine/util/error.h"
#include "engine/util/parallel_for.h"

namespace strata {
namespace {

constexpr float kFar = std::numeric_limits<float>::infinity();

// The window's nodes: per axis cells + 1, index x + nx * (y + ny * z).
struct NodeLattice {
  int64_t n[3];
  int64_t stride[3];
  int64_t count;
  explicit NodeLattice(const Grid& g) {
    for (int a = 0; a < 3; ++a) n[a] = int64_t(g.cells[a]) + 1;
    stride[0] = 1;
    stride[1] = n[0];
    stride[2] = n[0] * n[1];
    count = n[0] * n[1] * n[2];
  }
  // The first node of the line along `axis` through window coordinates (i, j) on u, v.
  int64_t lineStart(int axis, int64_t i, int64_t j) const {
    return i * stride[(axis + 1) % 3] + j * stride[(axis + 2) % 3];
  }
};

// Scratch of one lower-envelope pass over a line of up to n samples.
struct Envelope {
  std::vector<float> f;
  std::vector<uint32_t> leafIn;
  std::vector<int64_t> v;
  std::vector<double> z;
  explicit Envelope(int64_t n) : f(size_t(n)), leafIn(size_t(n)), v(size_t(n)), z(size_t(n) + 1) {}
};

// d[q] = min_i (q - i)^2 + d[i] over the line's n samples (stride apart, spacing one cell), with
// each sample's leaf following its minimiser. Samples at kFar take no part.
void lowerEnvelope(float* d, uint32_t* leaf, int64_t stride, int64_t n, Envelope& e) {
  int64_t k = -1;
  for (int64_t q = 0; q < n; ++q) {
    e.f[size_t(q)] = d[q * stride];
    e.leafIn[size_t(q)] = leaf[q * stride];
    if (e.f[size_t(q)] == kFar) continue;
    const double fq = double(e.f[size_t(q)]) + double(q) * double(q);
    double s = -std::numeric_limits<double>::infinity();
    while (k >= 0) {
      const int64_t p = e.v[size_t(k)];
      s = (fq - (double(e.f[size_t(p)]) + double(p) * double(p))) / (2.0 * double(q - p));
      if (s > e.z[size_t(k)]) break;
      --k;
    }
    ++k;
    e.v[size_t(k)] = q;
    e.z[size_t(k)] = k == 0 ? -std::numeric_limits<double>::infinity() : s;
  }
  if (k < 0) return;  // no sample on this line: every node stays far
  const int64_t last = k;
  k = 0;
  for (int64_t q = 0; q < n; ++q) {
    while (k < last && e.z[size_t(k + 1)] < double(q)) ++k;
    const int64_t p = e.v[size_t(k)];
    const double dq = double(q - p);
    d[q * stride] = float(dq * dq + double(e.f[size_t(p)]));
    leaf[q * stride] = e.leafIn[size_t(p)];
  }
}

// Step 1 for `axis`: each node's squared distance (cells^2) along its line to the nearest surfel
// of that line, and that surfel's leaf; for axis 0 also whether the node is inside.
void seedAlongAxis(const Ldi& ldi, const NodeLattice& lat, int axis, float* d, uint32_t* leaf,
                   uint8_t* inside, Progress* progress) {
  const Grid& g = ldi.grid;
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  const AxisLdi& a = ldi.axes[size_t(axis)];
  const int64_t raysU = lat.n[u], rays = lat.n[u] * lat.n[v];
  parallelFor(0, rays, 256, [&](int64_t begin, int64_t end) {
    if (progress) progress->check();
    for (int64_t ray = begin; ray < end; ++ray) {
      const int64_t start = lat.lineStart(axis, ray % raysU, ray / raysU);
      const Surfel* s = a.surfels.data() + a.offsets[size_t(ray)];
      const int64_t count = int64_t(a.offsets[size_t(ray) + 1]) - int64_t(a.offsets[size_t(ray)]);
      int64_t next = 0;  // the first surfel deeper than the node
      for (int64_t k = 0; k < lat.n[axis]; ++k) {
        const double depth = double(g.first[axis] + k);
        while (next < count && double(s[next].depth) <= depth) ++next;
        double best = kFar;
        uint32_t bestLeaf = 0;
        if (next > 0) {
          best = depth - double(s[next - 1].depth);
          bestLeaf = surfelLeaf(s[next - 1].tag);
        }
        if (next < count && double(s[next].depth) - depth < best) {
          best = double(s[next].depth) - depth;
          bestLeaf = surfelLeaf(s[next].tag);
        }
        const int64_t node = start + k * lat.stride[axis];
        d[node] = best == double(kFar) ? kFar : float(best * best);
        leaf[node] = bestLeaf;
        if (inside) inside[node] = next > 0 && surfelEnters(s[next - 1].tag) ? 1 : 0;
      }
    }
  });
}

// Step 2 along `axis` for every line of the lattice.
void envelopeAlongAxis(const NodeLattice& lat, int axis, float* d, uint32_t* leaf,
                       Progress* progress) {
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  const int64_t linesU = lat.n[u], lines = lat.n[u] * lat.n[v];
  parallelFor(0, lines, 256, [&](int64_t begin, int64_t end) {
    if (progress) progress->check();
    Envelope e(lat.n[axis]);
    for (int64_t line = begin; line < end; ++line) {
      const int64_t start = lat.lineStart(axis, line % linesU, line / linesU);
      lowerEnvelope(d + start, leaf + start, lat.stride[axis], lat.n[axis], e);
    }
  });
}

// sd's gradient at node (x, y, z), central differences (one-sided at the window's faces).
void gradientAt(const NodeLattice& lat, const float* sd, const int64_t p[3], double out[3]) {
  const int64_t node = p[0] * lat.stride[0] + p[1] * lat.stride[1] + p[2] * lat.stride[2];
  for (int a = 0; a < 3; ++a) {
    const int64_t lo = p[a] > 0 ? 1 : 0, hi = p[a] + 1 < lat.n[a] ? 1 : 0;
    if (lo + hi == 0) {
      out[a] = 0.0;
      continue;
    }
    out[a] = (double(sd[node + hi * lat.stride[a]]) - double(sd[node - lo * lat.stride[a]])) /
             double(lo + hi);
  }
}

}  // namespace

std::shared_ptr<Ldi> offsetLdi(const Ldi& input, double distance, Progress* progress) {
  const std::shared_ptr<const Ldi> whole =
      wholeLdi(std::shared_ptr<const Ldi>(std::shared_ptr<const Ldi>(), &input));
  const Ldi& ldi = *whole;
  const Grid& g = ldi.grid;
  if (!std::isfinite(distance)) throw Error("offset distance is not a finite number");
  const NodeLattice lat(g);
  const double offsetCells = distance / g.h;

  // Steps 1 and 2: the smallest over the three axes' samplings.
  std::vector<float> best(size_t(lat.count), kFar), d(size_t(lat.count));
  std::vector<uint32_t> bestLeaf(size_t(lat.count), 0), leaf(size_t(lat.count));
  std::vector<uint8_t> inside(size_t(lat.count), 0);
  for (int axis = 0; axis < 3; ++axis) {
    seedAlongAxis(ldi, lat, axis, d.data(), leaf.data(), axis == 0 ? inside.data() : nullptr,
                  progress);
    envelopeAlongAxis(lat, (axis + 1) % 3, d.data(), leaf.data(), progress);
    envelopeAlongAxis(lat, (axis + 2) % 3, d.data(), leaf.data(), progress);
    parallelFor(0, lat.count, 1 << 16, [&](int64_t begin, int64_t end) {
      for (int64_t i = begin; i < end; ++i)
        if (d[size_t(i)] < best[size_t(i)]) {
          best[size_t(i)] = d[size_t(i)];
          bestLeaf[size_t(i)] = leaf[size_t(i)];
        }
    });
  }
  // Signed distance in cells (reusing d): negative inside; far everywhere without a surface.
  float* sd = d.data();
  parallelFor(0, lat.count, 1 << 16, [&](int64_t begin, int64_t end) {
    for (int64_t i = begin; i < end; ++i) {
      const float m = std::sqrt(best[size_t(i)]);
      sd[i] = inside[size_t(i)] ? -m : m;
    }
  });
  std::vector<float>().swap(best);

  // Step 3: each ray's crossings of sd = offset, counted, then written.
  auto result = std::make_shared<Ldi>();
  result->grid = g;
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    const int64_t raysU = lat.n[u], rays = lat.n[u] * lat.n[v];
    const int64_t n = lat.n[axis], step = lat.stride[axis];
    // The solid of the offset at node k of a line: sd - offset < 0.
    auto in = [&](int64_t node) { return double(sd[node]) - offsetCells < 0.0; };
    AxisLdi& out = result->axes[size_t(axis)];
    out.whole = true;
    std::vector<uint64_t> counts(size_t(rays) + 1, 0);
    parallelFor(0, rays, 1024, [&](int64_t begin, int64_t end) {
      if (progress) progress->check();
      for (int64_t ray = begin; ray < end; ++ray) {
        const int64_t start = lat.lineStart(axis, ray % raysU, ray / raysU);
        bool previous = false;
        uint64_t c = 0;
        for (int64_t k = 0; k < n; ++k) {
          const bool now = in(start + k * step);
          c += now != previous ? 1 : 0;
          previous = now;
        }
        counts[size_t(ray)] = c + (previous ? 1 : 0);
      }
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
      for (int64_t ray = begin; ray < end; ++ray) {
        const int64_t i = ray % raysU, j = ray / raysU;
        const int64_t start = lat.lineStart(axis, i, j);
        Surfel* s = out.surfels.data() + out.offsets[size_t(ray)];
        bool previous = false;
        for (int64_t k = 0; k <= n; ++k) {
          const bool now = k < n && in(start + k * step);
          if (now == previous) continue;
          previous = now;
          Surfel& x = *s++;
          if (k == 0 || k == n) {  // cut at the window's face
            const int64_t node = start + (k == 0 ? 0 : n - 1) * step;
            x.depth = float(g.first[axis] + (k == 0 ? 0 : n - 1));
            float normal[3] = {0.0f, 0.0f, 0.0f};
            normal[axis] = now ? -1.0f : 1.0f;
            x.normal = encodeNormal(normal[0], normal[1], normal[2]);
            x.tag = makeSurfelTag(bestLeaf[size_t(node)], now);
            continue;
          }
          const int64_t a = start + (k - 1) * step, b = start + k * step;
          const double fa = double(sd[a]) - offsetCells, fb = double(sd[b]) - offsetCells;
          const double t = std::clamp(fa / (fa - fb), 0.0, 1.0);
          x.depth = float(double(g.first[axis] + k - 1) + t);
          int64_t pa[3], pb[3];
          pa[axis] = k - 1;
          pb[axis] = k;
          pa[u] = pb[u] = i;
          pa[v] = pb[v] = j;
          double ga[3], gb[3];
          gradientAt(lat, sd, pa, ga);
          gradientAt(lat, sd, pb, gb);
          float normal[3];
          for (int c = 0; c < 3; ++c) normal[c] = float(ga[c] + t * (gb[c] - ga[c]));
          const float length =
              std::sqrt(normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]);
          if (length > 0.0f) {
            for (float& c : normal) c /= length;
          } else {
            normal[0] = normal[1] = normal[2] = 0.0f;
            normal[axis] = now ? -1.0f : 1.0f;
          }
          x.normal = encodeNormal(normal[0], normal[1], normal[2]);
          x.tag = makeSurfelTag(bestLeaf[size_t(t < 0.5 ? a : b)], now);
        }
      }
    });
  }
  return result;
}

}  // namespace strata
