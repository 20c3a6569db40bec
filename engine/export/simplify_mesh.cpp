#include "engine/export/simplify_mesh.h"

// OpenMesh's VectorT leaves its default-constructed coordinates unset by design, which GCC's
// -Wmaybe-uninitialized reports from inside OpenMesh's property arrays.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Decimater/DecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModBaseT.hh>
#include <OpenMesh/Tools/Decimater/ModNormalFlippingT.hh>
#include <OpenMesh/Tools/Decimater/ModQuadricT.hh>
#include <OpenMesh/Tools/Decimater/Observer.hh>

#include <glm/vec4.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <functional>
#include <mutex>
#include <vector>

#include "engine/geometry/triangle_distance.h"
#include "engine/util/hash.h"
#include "engine/util/parallel_for.h"
#include "engine/util/timer.h"

namespace strata {
namespace {

struct Traits : OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
  using Normal = OpenMesh::Vec3d;
  VertexAttributes(OpenMesh::Attributes::Status);
  EdgeAttributes(OpenMesh::Attributes::Status);
  HalfedgeAttributes(OpenMesh::Attributes::Status | OpenMesh::Attributes::PrevHalfedge);
  FaceAttributes(OpenMesh::Attributes::Status | OpenMesh::Attributes::Normal);
};
using Mesh = OpenMesh::TriMesh_ArrayKernelT<Traits>;
using Decimater = OpenMesh::Decimater::DecimaterT<Mesh>;
using Points = std::vector<glm::dvec3>;

glm::dvec3 toGlm(const OpenMesh::Vec3d& p) {
  return {p[0], p[1], p[2]};
}

// The deviation bound, as OpenMesh's ModHausdorffT but with the points of removed vertices
// loadable (they are carried from the chunks into the final pass) and a point-triangle distance
// that is robust for degenerate triangles. Every face keeps the original vertices it covers; a
// collapse is legal only if every point around the removed vertex stays within the tolerance
// of one of the faces that replace the old ones.
constexpr int kBackSteps = 6;

template <class MeshT>
class ModDeviationT : public OpenMesh::Decimater::ModBaseT<MeshT> {
 public:
  DECIMATING_MODULE(ModDeviationT, MeshT, Deviation);
  explicit ModDeviationT(MeshT& mesh) : Base(mesh, true), mesh_(mesh) {
    mesh_.add_property(points_);
  }
  ~ModDeviationT() override { mesh_.remove_property(points_); }
  void setTolerance(double tolerance) { tolerance2_ = tolerance * tolerance; }
  // The unsimplified surface: near(p) is true when p lies within the tolerance of it.
  void setSurface(const std::function<bool(const glm::dvec3&)>* near) { near_ = near; }
  Points& points(typename MeshT::FaceHandle f) { return mesh_.property(points_, f); }

  void initialize() override {}  // points are loaded by the caller, or start empty

  float collapse_priority(const CollapseInfo& ci) override {
    faces_.clear();
    tested_.clear();
    for (const auto f : mesh_.vf_range(ci.v0)) {
      if (f != ci.fl && f != ci.fr) faces_.push_back(f);
      const Points& p = mesh_.property(points_, f);
      tested_.insert(tested_.end(), p.begin(), p.end());
    }
    tested_.push_back(toGlm(ci.p0));
    mesh_.set_point(ci.v0, ci.p1);  // simulate the collapse
    bool ok = true;
    for (const glm::dvec3& p : tested_) {
      bool near = false;
      for (const auto f : faces_)
        if (distance2(p, f) <= tolerance2_) {
          near = true;
          break;
        }
      if (!near) {
        ok = false;
        break;
      }
    }
    // The other way: the new faces stay near the unsimplified surface, tested on a grid of
    // points at most twice the tolerance apart (at most kBackSteps per edge; the corners are
    // vertices of it).
    if (ok && near_)
      for (const auto f : faces_) {
        auto v = mesh_.cfv_begin(f);
        const glm::dvec3 a = toGlm(mesh_.point(*v)), b = toGlm(mesh_.point(*++v)),
                         c = toGlm(mesh_.point(*++v));
        const double longest2 =
            std::max({glm::dot(b - a, b - a), glm::dot(c - b, c - b), glm::dot(a - c, a - c)});
        const int n = int(std::clamp(std::ceil(std::sqrt(longest2 / (9.0 * tolerance2_))), 2.0,
                                     double(kBackSteps)));
        for (int i = 0; ok && i <= n; ++i)
          for (int j = 0; i + j <= n; ++j) {
            if ((i == 0 && j == 0) || i == n || j == n) continue;  // a corner
            const glm::dvec3 p = a + (b - a) * (double(i) / n) + (c - a) * (double(j) / n);
            if (!(*near_)(p)) {
              ok = false;
              break;
            }
          }
        if (!ok) break;
      }
    mesh_.set_point(ci.v0, ci.p0);
    return ok ? float(Base::LEGAL_COLLAPSE) : float(Base::ILLEGAL_COLLAPSE);
  }

  void postprocess_collapse(const CollapseInfo& ci) override {
    faces_.clear();
    tested_.clear();
    auto take = [&](typename MeshT::FaceHandle f) {
      Points& p = mesh_.property(points_, f);
      tested_.insert(tested_.end(), p.begin(), p.end());
      p.clear();
    };
    for (const auto f : mesh_.vf_range(ci.v1)) {
      faces_.push_back(f);
      take(f);
    }
    if (faces_.empty()) return;
    if (ci.fl.is_valid()) take(ci.fl);
    if (ci.fr.is_valid()) take(ci.fr);
    tested_.push_back(toGlm(ci.p0));
    for (const glm::dvec3& p : tested_) {  // each to the face nearest to it
      double best = INFINITY;
      auto nearest = faces_.front();
      for (const auto f : faces_) {
        const double d = distance2(p, f);
        if (d < best) {
          best = d;
          nearest = f;
        }
      }
      mesh_.property(points_, nearest).push_back(p);
    }
  }

 private:
  double distance2(const glm::dvec3& p, typename MeshT::FaceHandle f) const {
    auto v = mesh_.cfv_begin(f);
    const glm::dvec3 a = toGlm(mesh_.point(*v)), b = toGlm(mesh_.point(*++v)),
                     c = toGlm(mesh_.point(*++v));
    return pointTriangleDistanceSquared(p, a, b, c);
  }

  MeshT& mesh_;
  double tolerance2_ = 0.0;
  const std::function<bool(const glm::dvec3&)>* near_ = nullptr;
  OpenMesh::FPropHandleT<Points> points_;
  std::vector<typename MeshT::FaceHandle> faces_;
  Points tested_;
};

// Keeps the seams between chunks as they were: a vertex on a seam is locked, and a collapse
// onto one may not join it to another seam vertex it was not joined to (two chunks could make
// the same new edge, and the stitched mesh would hold it four times).
template <class MeshT>
class ModSeamT : public OpenMesh::Decimater::ModBaseT<MeshT> {
 public:
  DECIMATING_MODULE(ModSeamT, MeshT, Seam);
  explicit ModSeamT(MeshT& mesh) : Base(mesh, true), mesh_(mesh) {}
  void setSeam(OpenMesh::VPropHandleT<uint8_t> seam) { seam_ = seam; }

  float collapse_priority(const CollapseInfo& ci) override {
    if (!mesh_.property(seam_, ci.v1)) return float(Base::LEGAL_COLLAPSE);
    for (const auto w : mesh_.vv_range(ci.v0))
      if (w != ci.v1 && w != ci.vl && w != ci.vr && mesh_.property(seam_, w))
        return float(Base::ILLEGAL_COLLAPSE);
    return float(Base::LEGAL_COLLAPSE);
  }

 private:
  MeshT& mesh_;
  OpenMesh::VPropHandleT<uint8_t> seam_;
};

// The collapses of all pieces, reported as one fraction that never goes back.
struct CollapseCount {
  std::mutex mutex;
  size_t collapses = 0;
  double reported = 0.0;
};

// Reports collapses as progress and stops the decimater on a cancel.
class ProgressObserver : public OpenMesh::Decimater::Observer {
 public:
  ProgressObserver(Progress& progress, CollapseCount& count, size_t expected, double from,
                   double to)
      : Observer(1024),
        progress_(progress),
        count_(count),
        expected_(std::max<size_t>(expected, 1)),
        from_(from),
        to_(to) {}
  void notify(size_t) override {
    // How many collapses an export allows is not known beforehand (most lose 80-95% of their
    // vertices): the fraction approaches `to` and never goes back.
    std::lock_guard<std::mutex> lock(count_.mutex);
    count_.collapses += 1024;
    const double fraction =
        from_ + (to_ - from_) * std::min(0.99, double(count_.collapses) / double(expected_));
    if (fraction <= count_.reported || progress_.cancelled()) return;
    count_.reported = fraction;
    progress_.report("simplify", fraction);
  }
  bool abort() const override { return progress_.cancelled(); }

 private:
  Progress& progress_;
  CollapseCount& count_;
  size_t expected_;
  double from_, to_;
};

// A triangle mesh in OpenMesh, with each vertex's index in the export and each face's leaf.
struct Piece {
  Mesh mesh;
  OpenMesh::VPropHandleT<uint32_t> original;
  OpenMesh::VPropHandleT<uint8_t> seam;
  OpenMesh::FPropHandleT<uint32_t> leaf;
  Piece() {
    mesh.add_property(original);
    mesh.add_property(seam);
    mesh.add_property(leaf);
  }
};

// Builds a piece from `triangles` (indices into `positions`), with `isSeam` vertices locked.
// A seam vertex whose triangles in this piece form several fans gets one copy per fan (it never
// moves, and the copies are one vertex again once stitched). False when a face cannot be added
// (the mesh is not a 2-manifold).
bool buildPiece(Piece& piece, const std::vector<glm::dvec3>& positions,
                const std::vector<std::array<uint32_t, 3>>& allTriangles,
                const std::vector<uint32_t>& triangles, const std::vector<uint32_t>& leaves,
                const std::vector<uint8_t>& isSeam, Progress& progress) {
  std::vector<uint32_t> used;
  used.reserve(triangles.size() * 3 / 2);
  for (uint32_t t : triangles)
    for (uint32_t v : allTriangles[t]) used.push_back(v);
  std::sort(used.begin(), used.end());
  used.erase(std::unique(used.begin(), used.end()), used.end());
  Mesh& m = piece.mesh;
  m.reserve(used.size(), triangles.size() * 3 / 2 + 16, triangles.size());
  auto addVertex = [&](uint32_t v) {
    const glm::dvec3& p = positions[v];
    const auto h = m.add_vertex({p.x, p.y, p.z});
    m.property(piece.original, h) = v;
    m.property(piece.seam, h) = isSeam.empty() ? 0 : isSeam[v];
    if (m.property(piece.seam, h)) m.status(h).set_locked(true);
    return h;
  };
  std::vector<Mesh::VertexHandle> handles;
  handles.reserve(used.size());
  for (uint32_t v : used) handles.push_back(addVertex(v));
  auto local = [&](uint32_t v) {
    return handles[size_t(std::lower_bound(used.begin(), used.end(), v) - used.begin())];
  };
  for (size_t k = 0; k < triangles.size(); ++k) {
    if ((k & 0xffff) == 0) progress.check();
    const auto& tri = allTriangles[triangles[k]];
    Mesh::VertexHandle corner[3] = {local(tri[0]), local(tri[1]), local(tri[2])};
    auto face = m.add_face(corner[0], corner[1], corner[2]);
    if (!face.is_valid()) {  // fans meeting at a seam vertex: fresh copies of the seam corners
      for (auto& c : corner)
        if (m.property(piece.seam, c)) c = addVertex(m.property(piece.original, c));
      face = m.add_face(corner[0], corner[1], corner[2]);
      if (!face.is_valid()) return false;
    }
    m.property(piece.leaf, face) = leaves.empty() ? 0u : leaves[triangles[k]];
  }
  return true;
}

// Marks sharp edges and edges between leaves as features, their vertices as feature vertices,
// and locks the vertices where features meet or end (they keep their place).
void markFeatures(Piece& piece) {
  Mesh& mesh = piece.mesh;
  mesh.update_face_normals();
  const double cosFeature = std::cos(kFeatureAngleDegrees * M_PI / 180.0);
  std::vector<uint8_t> featureEdges(mesh.n_vertices(), 0);
  for (const auto e : mesh.edges()) {
    const auto f0 = mesh.face_handle(mesh.halfedge_handle(e, 0));
    const auto f1 = mesh.face_handle(mesh.halfedge_handle(e, 1));
    if (!f0.is_valid() || !f1.is_valid()) continue;  // a seam: its vertices are locked
    const bool sharp = (mesh.normal(f0) | mesh.normal(f1)) < cosFeature;
    if (!sharp && mesh.property(piece.leaf, f0) == mesh.property(piece.leaf, f1)) continue;
    mesh.status(e).set_feature(true);
    for (int side = 0; side < 2; ++side) {
      const auto v = mesh.to_vertex_handle(mesh.halfedge_handle(e, side));
      mesh.status(v).set_feature(true);
      featureEdges[size_t(v.idx())] = uint8_t(std::min(featureEdges[size_t(v.idx())] + 1, 3));
    }
  }
  for (const auto v : mesh.vertices())
    if (featureEdges[size_t(v.idx())] != 0 && featureEdges[size_t(v.idx())] != 2)
      mesh.status(v).set_locked(true);
}

// Runs the decimater on `piece` until no collapse is legal; `points` (may be null) are the
// original vertices each face covers so far, in face order. Leaves the carried points of every
// face (deleted ones included) in `carried`, indexed by face.
void decimatePiece(Piece& piece, double tolerance,
                   const std::function<bool(const glm::dvec3&)>& near, bool seams,
                   const std::vector<Points>* points, std::vector<Points>* carried,
                   Progress& progress, CollapseCount& collapses, size_t expected, double from,
                   double to) {
  Decimater decimater(piece.mesh);
  OpenMesh::Decimater::ModQuadricT<Mesh>::Handle quadric;
  ModDeviationT<Mesh>::Handle deviation;
  OpenMesh::Decimater::ModNormalFlippingT<Mesh>::Handle flipping;
  ModSeamT<Mesh>::Handle seam;
  decimater.add(quadric);
  decimater.add(deviation);
  decimater.add(flipping);
  if (seams) decimater.add(seam);
  decimater.module(quadric).unset_max_err();  // the priority only; the bound is the deviation's
  decimater.module(deviation).setTolerance(tolerance);
  decimater.module(deviation).setSurface(&near);
  decimater.module(flipping).set_max_normal_deviation(kMaxNormalTurnDegrees);
  if (seams) decimater.module(seam).setSeam(piece.seam);
  decimater.initialize();
  if (points)
    for (const auto f : piece.mesh.faces())
      decimater.module(deviation).points(f) = (*points)[size_t(f.idx())];
  ProgressObserver observer(progress, collapses, expected, from, to);
  decimater.set_observer(&observer);
  decimater.decimate(0);
  decimater.set_observer(nullptr);
  progress.check();
  carried->assign(piece.mesh.n_faces(), {});
  for (const auto f : piece.mesh.all_faces())
    if (!piece.mesh.status(f).deleted())
      (*carried)[size_t(f.idx())] = std::move(decimater.module(deviation).points(f));
}

// The unsimplified surface for "is this point within the tolerance of it": triangles bucketed
// by the cells of a uniform grid that their boxes, grown by the tolerance, overlap; cells found
// through an open-addressing table. Immutable after construction; any number of threads.
class NearSurface {
 public:
  NearSurface(const std::vector<glm::dvec3>& positions,
              const std::vector<std::array<uint32_t, 3>>& triangles, double tolerance)
      : positions_(positions), triangles_(triangles), tolerance2_(tolerance * tolerance) {
    const Bounds bounds = meshBounds(TriangleMeshView{positions, triangles});
    double edges = 0.0;
    for (const auto& t : triangles) edges += glm::length(positions[t[1]] - positions[t[0]]);
    // Cells about a triangle across: a triangle lands in a few cells, a cell holds a few dozen.
    cell_ = std::max(edges / double(std::max<size_t>(triangles.size(), 1)), 2.0 * tolerance);
    origin_ = bounds.min - glm::dvec3(tolerance + cell_);
    spheres_.resize(triangles.size());
    std::vector<std::pair<uint64_t, uint32_t>> pairs;
    pairs.reserve(triangles.size() * 4);
    for (uint32_t t = 0; t < triangles.size(); ++t) {
      Bounds box;
      for (uint32_t v : triangles[t]) box.include(positions[v]);
      const glm::dvec3 centre = box.center();
      const double reach = 0.5 * glm::length(box.size()) + tolerance;
      spheres_[t] = glm::dvec4(centre, reach * reach);
      const glm::ivec3 lo = cellOf(box.min - glm::dvec3(tolerance));
      const glm::ivec3 hi = cellOf(box.max + glm::dvec3(tolerance));
      for (int z = lo.z; z <= hi.z; ++z)
        for (int y = lo.y; y <= hi.y; ++y)
          for (int x = lo.x; x <= hi.x; ++x) pairs.emplace_back(key({x, y, z}), t);
    }
    std::sort(pairs.begin(), pairs.end());
    items_.resize(pairs.size());
    size_t cells = 0;
    for (size_t k = 0; k < pairs.size(); ++k) {
      items_[k] = pairs[k].second;
      if (k == 0 || pairs[k].first != pairs[k - 1].first) ++cells;
    }
    size_t slots = 16;
    while (slots < 2 * cells) slots *= 2;
    table_.assign(slots, Slot{});
    for (size_t k = 0; k < pairs.size();) {
      size_t end = k;
      while (end < pairs.size() && pairs[end].first == pairs[k].first) ++end;
      size_t slot = avalanche64(pairs[k].first) & (slots - 1);
      while (table_[slot].end != 0) slot = (slot + 1) & (slots - 1);
      table_[slot] = {pairs[k].first, uint32_t(k), uint32_t(end)};
      k = end;
    }
  }

  bool near(const glm::dvec3& p) const {
    const uint64_t k = key(cellOf(p));
    const size_t mask = table_.size() - 1;
    for (size_t slot = avalanche64(k) & mask; table_[slot].end != 0; slot = (slot + 1) & mask) {
      if (table_[slot].key != k) continue;
      for (uint32_t i = table_[slot].begin; i < table_[slot].end; ++i) {
        const glm::dvec4& sphere = spheres_[items_[i]];
        const glm::dvec3 d = p - glm::dvec3(sphere);
        if (glm::dot(d, d) > sphere.w) continue;  // beyond the box's sphere grown by the tolerance
        const auto& t = triangles_[items_[i]];
        if (pointTriangleDistanceSquared(p, positions_[t[0]], positions_[t[1]], positions_[t[2]]) <=
            tolerance2_)
          return true;
      }
      return false;
    }
    return false;
  }

 private:
  struct TriangleMeshView {
    const std::vector<glm::dvec3>& positions;
    const std::vector<std::array<uint32_t, 3>>& triangles;
  };
  static Bounds meshBounds(const TriangleMeshView& mesh) {
    Bounds b;
    for (const auto& p : mesh.positions) b.include(p);
    return b;
  }
  struct Slot {
    uint64_t key = 0;
    uint32_t begin = 0, end = 0;  // end == 0: empty
  };
  glm::ivec3 cellOf(const glm::dvec3& p) const {
    return glm::ivec3(glm::floor((p - origin_) / cell_));
  }
  static uint64_t key(const glm::ivec3& c) {
    return (uint64_t(uint32_t(c.x) & 0x1fffff) << 42) | (uint64_t(uint32_t(c.y) & 0x1fffff) << 21) |
           uint64_t(uint32_t(c.z) & 0x1fffff);
  }

  const std::vector<glm::dvec3>& positions_;
  const std::vector<std::array<uint32_t, 3>>& triangles_;
  double tolerance2_;
  double cell_ = 1.0;
  glm::dvec3 origin_{0.0};
  std::vector<glm::dvec4>
      spheres_;  // per triangle: its box's centre, (half diagonal + tolerance)^2
  std::vector<uint32_t> items_;
  std::vector<Slot> table_;
};

constexpr int kMaxChunks = 64;

}  // namespace

SimplifyReport simplifyMesh(ExportMesh* mesh, double tolerance, Progress& progress,
                            size_t trianglesPerChunk) {
  Stopwatch clock;
  SimplifyReport report;
  report.tolerance = tolerance;
  report.trianglesBefore = mesh->mesh.triangles.size();
  report.trianglesAfter = report.trianglesBefore;
  if (mesh->mesh.triangles.empty() || !(tolerance > 0.0)) return report;
  progress.report("simplify", 0.0);
  // OpenMesh prints every face it cannot add; buildPiece handles those (copies of seam vertices,
  // or a refusal in the report).
  omerr().disable();
  const auto& positions = mesh->mesh.positions;
  const auto& triangles = mesh->mesh.triangles;
  const size_t count = triangles.size();
  trianglesPerChunk = std::max<size_t>(trianglesPerChunk, 1);
  const int chunks =
      int(std::clamp<size_t>((count + trianglesPerChunk / 2) / trianglesPerChunk, 1, kMaxChunks));
  CollapseCount collapses;
  // The unsimplified surface, for the deviation's other way.
  const NearSurface surface(positions, triangles, tolerance);
  const std::function<bool(const glm::dvec3&)> near = [&](const glm::dvec3& p) {
    return surface.near(p);
  };

  const size_t expected = positions.size() * 9 / 10;

  // Pass 1: the chunks, their seams locked, in parallel.
  std::vector<uint32_t> chunkOf(count, 0);
  std::vector<uint8_t> isSeam;
  std::vector<Points> points;  // per face of the stitched mesh
  std::vector<std::array<uint32_t, 3>> stitched;
  std::vector<uint32_t> stitchedLeaf;
  if (chunks > 1) {
    const Bounds bounds = meshBounds(mesh->mesh);
    const glm::dvec3 size = bounds.size();
    const int axis = size.x >= size.y && size.x >= size.z ? 0 : size.y >= size.z ? 1 : 2;
    std::vector<uint32_t> order(count);
    for (size_t t = 0; t < count; ++t) order[t] = uint32_t(t);
    auto key = [&](uint32_t t) {
      const auto& tri = triangles[t];
      return positions[tri[0]][axis] + positions[tri[1]][axis] + positions[tri[2]][axis];
    };
    std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
      const double ka = key(a), kb = key(b);
      return ka < kb || (ka == kb && a < b);
    });
    std::vector<std::vector<uint32_t>> members(static_cast<size_t>(chunks));
    for (size_t k = 0; k < count; ++k) {
      const uint32_t c = uint32_t(k * size_t(chunks) / count);
      chunkOf[order[k]] = c;
      members[c].push_back(order[k]);
    }
    order = {};
    std::vector<uint32_t> owner(positions.size(), UINT32_MAX);
    isSeam.assign(positions.size(), 0);
    for (size_t t = 0; t < count; ++t)
      for (uint32_t v : triangles[t]) {
        if (owner[v] == UINT32_MAX)
          owner[v] = chunkOf[t];
        else if (owner[v] != chunkOf[t])
          isSeam[v] = 1;
      }
    std::vector<Piece> pieces(static_cast<size_t>(chunks));
    std::vector<std::vector<Points>> carried(static_cast<size_t>(chunks));
    std::atomic<bool> built{true};
    parallelFor(0, chunks, 1, [&](int64_t first, int64_t last) {
      for (int64_t c = first; c < last; ++c) {
        Piece& piece = pieces[size_t(c)];
        if (!buildPiece(piece, positions, triangles, members[size_t(c)], mesh->triangleLeaf, isSeam,
                        progress)) {
          built = false;
          return;
        }
        members[size_t(c)] = {};
        markFeatures(piece);
        decimatePiece(piece, tolerance, near, true, nullptr, &carried[size_t(c)], progress,
                      collapses, expected, 0.02, 0.8);
      }
    });
    if (!built) {
      report.refused = true;
      report.refusedWhy = "the mesh is not a 2-manifold OpenMesh can hold";
      report.seconds = clock.seconds();
      return report;
    }
    for (size_t c = 0; c < pieces.size(); ++c) {
      const Mesh& m = pieces[c].mesh;
      for (const auto f : m.faces()) {
        std::array<uint32_t, 3> tri{};
        int k = 0;
        for (const auto v : m.fv_range(f)) tri[k++] = m.property(pieces[c].original, v);
        stitched.push_back(tri);
        stitchedLeaf.push_back(m.property(pieces[c].leaf, f));
        points.push_back(std::move(carried[c][size_t(f.idx())]));
      }
      pieces[c] = Piece();
    }
  } else {
    stitched = triangles;
    stitchedLeaf = mesh->triangleLeaf;
  }

  // Pass 2: the whole mesh, seams free, the chunks' points carried.
  std::vector<uint32_t> all(stitched.size());
  for (size_t t = 0; t < all.size(); ++t) all[t] = uint32_t(t);
  Piece whole;
  if (!buildPiece(whole, positions, stitched, all, stitchedLeaf, {}, progress)) {
    report.refused = true;
    report.refusedWhy = "the mesh is not a 2-manifold OpenMesh can hold";
    report.seconds = clock.seconds();
    return report;
  }
  all = {};
  stitched = {};
  stitchedLeaf = {};
  markFeatures(whole);
  std::vector<Points> carried;
  decimatePiece(whole, tolerance, near, false, chunks > 1 ? &points : nullptr, &carried, progress,
                collapses, expected, chunks > 1 ? 0.8 : 0.02, 0.98);
  carried = {};
  points = {};
  whole.mesh.garbage_collection();

  ExportMesh simplified;
  simplified.leaves = mesh->leaves;
  simplified.unit = mesh->unit;
  const Mesh& m = whole.mesh;
  simplified.mesh.positions.reserve(m.n_vertices());
  for (const auto v : m.vertices()) simplified.mesh.positions.push_back(toGlm(m.point(v)));
  simplified.mesh.triangles.reserve(m.n_faces());
  simplified.triangleLeaf.reserve(m.n_faces());
  for (const auto f : m.faces()) {
    std::array<uint32_t, 3> tri{};
    int k = 0;
    for (const auto v : m.fv_range(f)) tri[k++] = uint32_t(v.idx());
    simplified.mesh.triangles.push_back(tri);
    simplified.triangleLeaf.push_back(m.property(whole.leaf, f));
  }
  report.measured =
      measureDeviation(mesh->mesh, simplified.mesh, kSampleSpacingPerTolerance * tolerance,
                       8.0 * tolerance, progress, "simplify");
  *mesh = std::move(simplified);
  report.trianglesAfter = mesh->mesh.triangles.size();
  report.seconds = clock.seconds();
  progress.report("simplify", 1.0);
  return report;
}

}  // namespace strata
