#include "engine/export/simplify_mesh.h"

// OpenMesh's VectorT leaves its default-constructed coordinates unset by design, which GCC's
// -Wmaybe-uninitialized reports from inside OpenMesh's property arrays.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Decimater/CollapseInfoT.hh>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <mutex>
#include <queue>
#include <vector>

#include "engine/geometry/triangle_distance.h"
#include "engine/geometry/triangle_grid.h"
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
using Points = std::vector<glm::dvec3>;

glm::dvec3 toGlm(const OpenMesh::Vec3d& p) {
  return {p[0], p[1], p[2]};
}

// The collapses of all pieces, reported as one fraction that never goes back.
struct CollapseCount {
  std::mutex mutex;
  size_t collapses = 0;
  double reported = 0.0;  // the stage's fraction last reported (never goes back)
  // This attempt's share of the stage's bar (simplifyMesh may try again, tighter).
  double spanFrom = 0.0, spanTo = 1.0;
  double at(double fraction) const { return spanFrom + (spanTo - spanFrom) * fraction; }
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
// False when a face cannot be added: the mesh is not a 2-manifold, or (a chunk) OpenMesh could
// not join the fans a seam vertex has in it.
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
    const auto face = m.add_face(corner[0], corner[1], corner[2]);
    if (!face.is_valid()) return false;
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

// The sum of squared distances to a set of planes (Garland and Heckbert's error quadric):
// q(p) = p.A.p + 2 b.p + c, A symmetric.
struct Quadric {
  double a[6] = {0, 0, 0, 0, 0, 0};  // xx xy xz yy yz zz
  double b[3] = {0, 0, 0};
  double c = 0.0;
  Quadric() = default;
  Quadric(const OpenMesh::Vec3d& n, double d)  // the plane n.p + d = 0, |n| = 1
      : a{n[0] * n[0], n[0] * n[1], n[0] * n[2], n[1] * n[1], n[1] * n[2], n[2] * n[2]},
        b{n[0] * d, n[1] * d, n[2] * d},
        c(d * d) {}
  Quadric& operator+=(const Quadric& o) {
    for (int i = 0; i < 6; ++i) a[i] += o.a[i];
    for (int i = 0; i < 3; ++i) b[i] += o.b[i];
    c += o.c;
    return *this;
  }
  double evaluate(const OpenMesh::Vec3d& p) const {
    const double x = p[0], y = p[1], z = p[2];
    return a[0] * x * x + 2 * a[1] * x * y + 2 * a[2] * x * z + a[3] * y * y + 2 * a[4] * y * z +
           a[5] * z * z + 2 * (b[0] * x + b[1] * y + b[2] * z) + c;
  }
};

constexpr int kBackSteps = 6;

// Edge collapses until none is allowed, cheapest quadric error first (Garland and Heckbert, onto
// the remaining vertex). Each vertex offers its cheapest collapse that its flags allow (locked,
// features, boundaries); the rules are tested only when a collapse is due, on the mesh as it is
// then: the topology rules of OpenMesh's decimater, the seams between chunks, no face normal
// turning by more than kMaxNormalTurnDegrees, then the deviation. A refused collapse is not
// offered again until the vertex's neighbourhood changes.
class Collapser {
 public:
  Collapser(Piece& piece, double tolerance, const TriangleGrid& surface, bool seams)
      : piece_(piece),
        m_(piece.mesh),
        tolerance_(tolerance),
        tolerance2_(tolerance * tolerance),
        sampleSpacing_(3.0 * tolerance),
        surface_(surface),
        seams_(seams),
        minCos_(std::cos(kMaxNormalTurnDegrees * M_PI / 180.0)) {
    quadric_.assign(m_.n_vertices(), Quadric());
    for (const auto f : m_.faces()) {
      auto v = m_.cfv_begin(f);
      const auto a = *v, b = *++v, c = *++v;
      OpenMesh::Vec3d n = (m_.point(b) - m_.point(a)) % (m_.point(c) - m_.point(a));
      const double area = n.norm();
      if (!(area > 0.0)) continue;
      n /= area;
      const Quadric q(n, -(n | m_.point(a)));
      for (const auto u : {a, b, c}) quadric_[size_t(u.idx())] += q;
    }
    points_.assign(m_.n_faces(), {});
    version_.assign(m_.n_vertices(), 0);
    touched_.assign(m_.n_vertices(), 0);
    // Epochs are drawn from one clock, so that no two vertices ever share one: a refusal stamp
    // stays with its halfedge when a collapse hands the halfedge to another vertex, and must
    // not match that vertex's epoch.
    epoch_.resize(m_.n_vertices());
    for (auto& e : epoch_) e = ++clock_;
    refusedAt_.assign(m_.n_halfedges(), 0);
    target_.assign(m_.n_vertices(), Mesh::HalfedgeHandle());
  }

  // The unsimplified points each face covers so far (by face index), from an earlier pass.
  void loadPoints(std::vector<Points>&& points) { points_ = std::move(points); }
  // A first pass covers, besides the vertices it removes, the centre of every face and the
  // midpoint of every edge (kept by the face on its halfedge 0's side): the unsimplified
  // surface sampled about half a triangle apart.
  void coverFaceCentresAndEdgeMidpoints() {
    for (const auto f : m_.faces()) {
      auto it = m_.cfv_begin(f);
      const glm::dvec3 a = toGlm(m_.point(*it)), b = toGlm(m_.point(*++it)),
                       c = toGlm(m_.point(*++it));
      points_[size_t(f.idx())].push_back((a + b + c) / 3.0);
    }
    for (const auto e : m_.edges()) {
      const auto h = m_.halfedge_handle(e, 0);
      auto f = m_.face_handle(h);
      if (!f.is_valid()) f = m_.face_handle(m_.halfedge_handle(e, 1));
      if (!f.is_valid()) continue;
      points_[size_t(f.idx())].push_back(0.5 * (toGlm(m_.point(m_.from_vertex_handle(h))) +
                                                toGlm(m_.point(m_.to_vertex_handle(h)))));
    }
  }
  // The same after run(), by face index (deleted faces hold none).
  std::vector<Points> takePoints() { return std::move(points_); }
  // Clears `settled` (per vertex) where a collapse changed a vertex's faces.
  void unsettleTouched(std::vector<uint8_t>& settled) const {
    for (size_t i = 0; i < touched_.size() && i < settled.size(); ++i)
      if (touched_[i]) settled[i] = 0;
  }

  void run(Progress& progress, CollapseCount& count, size_t expected, double from, double to) {
    for (const auto v : m_.vertices()) offer(v);
    size_t pops = 0, collapses = 0;
    std::vector<Mesh::VertexHandle> support;
    while (!heap_.empty()) {
      const Entry e = heap_.top();
      heap_.pop();
      const Mesh::VertexHandle v(int(e.vertex));
      if (e.version != version_[e.vertex] || m_.status(v).deleted()) continue;
      if ((++pops & 1023) == 0) {
        progress.check();
        report(progress, count, collapses, expected, from, to);
        collapses = 0;
      }
      const Mesh::HalfedgeHandle h = target_[e.vertex];
      const CollapseInfo ci(m_, h);
      if (!allowed(ci) || !deviationKept(ci)) {
        refusedAt_[size_t(h.idx())] = epoch_[e.vertex];
        offer(v);
        continue;
      }
      support.clear();
      for (const auto w : m_.vv_range(ci.v0))
        if (w != ci.v1) support.push_back(w);
      m_.collapse(h);
      ++collapses;
      afterCollapse(ci);
      support.push_back(ci.v1);
      for (const auto w : support) {
        epoch_[size_t(w.idx())] = ++clock_;
        offer(w);
      }
    }
    report(progress, count, collapses, expected, from, to);
  }

 private:
  using CollapseInfo = OpenMesh::Decimater::CollapseInfoT<Mesh>;
  // Cheapest error first; among equal errors (a flat region: all zero) the shortest edge, so
  // that flat regions coarsen evenly instead of one fan sweeping across them (which would carry
  // ever more covered points along, quadratic in the region's size); then the vertex index.
  struct Entry {
    double priority;
    double length2;
    uint32_t vertex, version;
    bool operator>(const Entry& o) const {
      if (priority != o.priority) return priority > o.priority;
      if (length2 != o.length2) return length2 > o.length2;
      return vertex > o.vertex;
    }
  };

  void report(Progress& progress, CollapseCount& count, size_t collapses, size_t expected,
              double from, double to) {
    std::lock_guard<std::mutex> lock(count.mutex);
    count.collapses += collapses;
    // How many collapses an export allows is not known beforehand (most lose 80-95% of their
    // vertices): the fraction approaches `to` and never goes back.
    const double fraction =
        count.at(from + (to - from) * std::min(0.99, double(count.collapses) /
                                                         double(std::max<size_t>(expected, 1))));
    if (fraction <= count.reported || progress.cancelled()) return;
    count.reported = fraction;
    progress.report("simplify", fraction);
  }

  // Puts v's cheapest allowed collapse on the heap (or none).
  void offer(Mesh::VertexHandle v) {
    const size_t i = size_t(v.idx());
    ++version_[i];
    if (m_.status(v).deleted() || m_.status(v).locked()) return;
    double best = INFINITY, bestLength2 = INFINITY;
    Mesh::HalfedgeHandle bestHalfedge;
    for (const auto h : m_.voh_range(v)) {
      if (refusedAt_[size_t(h.idx())] == epoch_[i]) continue;
      const CollapseInfo ci(m_, h);
      if (!flagsAllow(ci)) continue;
      Quadric q = quadric_[i];
      q += quadric_[size_t(ci.v1.idx())];
      const double cost = q.evaluate(ci.p1);
      const double length2 = (ci.p1 - ci.p0).sqrnorm();
      if (cost < best || (cost == best && length2 < bestLength2)) {
        best = cost;
        bestLength2 = length2;
        bestHalfedge = h;
      }
    }
    if (!bestHalfedge.is_valid()) return;
    target_[i] = bestHalfedge;
    heap_.push({best, bestLength2, uint32_t(i), version_[i]});
  }

  // The flags (locked, features, boundaries; as OpenMesh's BaseDecimaterT::is_collapse_legal):
  // what offer() tests.
  bool flagsAllow(const CollapseInfo& ci) const {
    if (m_.status(ci.v0).locked()) return false;
    if (m_.status(ci.v0).feature() && !m_.status(m_.edge_handle(ci.v0v1)).feature()) return false;
    if (m_.is_boundary(ci.v0) && (!m_.is_boundary(ci.v1) || (ci.vl.is_valid() && ci.vr.is_valid())))
      return false;
    return m_.cw_rotated_halfedge_handle(m_.cw_rotated_halfedge_handle(ci.v0v1)) != ci.v0v1;
  }

  // The flags, then the folds (arithmetic on the ring), then OpenMesh's link test: what a
  // collapse must pass when it is due.
  bool allowed(const CollapseInfo& ci) const {
    if (!flagsAllow(ci)) return false;
    // No face around v0 turns by more than the limit (or loses its area).
    for (const auto f : m_.vf_range(ci.v0)) {
      if (f == ci.fl || f == ci.fr) continue;
      auto it = m_.cfv_begin(f);
      OpenMesh::Vec3d p[3];
      for (auto& q : p) {
        q = *it == ci.v0 ? ci.p1 : m_.point(*it);
        ++it;
      }
      OpenMesh::Vec3d n = (p[1] - p[0]) % (p[2] - p[0]);
      const double length = n.norm();
      if (!(length > 0.0) || (m_.normal(f) | n) < minCos_ * length) return false;
    }
    if (!m_.is_collapse_ok(ci.v0v1)) return false;
    if (ci.vl.is_valid() && ci.vr.is_valid() && m_.find_halfedge(ci.vl, ci.vr).is_valid() &&
        m_.valence(ci.vl) == 3 && m_.valence(ci.vr) == 3)
      return false;  // a tetrahedron would collapse flat
    // A seam vertex may not be joined to another seam vertex it was not joined to: two chunks
    // could make the same new edge, and the stitched mesh would hold it four times.
    if (seams_ && m_.property(piece_.seam, ci.v1))
      for (const auto w : m_.vv_range(ci.v0))
        if (w != ci.v1 && w != ci.vl && w != ci.vr && m_.property(piece_.seam, w)) return false;
    return true;
  }

  // Face f, with `moved` (when valid) at `to`, prepared for distance queries: once per face,
  // not once per point tested against it (the circulator and the triangle's own arithmetic cost
  // more than the point's).
  TriangleDistance shapeOf(Mesh::FaceHandle f, Mesh::VertexHandle moved,
                           const glm::dvec3& to) const {
    glm::dvec3 c[3];
    auto it = m_.cfv_begin(f);
    for (auto& q : c) {
      q = *it == moved ? to : toGlm(m_.point(*it));
      ++it;
    }
    return TriangleDistance(c[0], c[1], c[2]);
  }

  // The costly rules, on the mesh as it would be: every unsimplified point covered by the faces
  // around v0 (and v0 itself) lies within the tolerance of the faces that replace them, and
  // those faces stay within it of the unsimplified surface on a grid of points at most
  // sampleSpacing_ apart (at most kBackSteps per edge; their corners are vertices of it). What
  // it finds is what afterCollapse applies, if the collapse goes ahead: which points stay on
  // their face (stays_) and the nearest new face of each that moves (moves_, in the order
  // afterCollapse gathers them). A changed face is the same face after the collapse, with v1 at
  // p1 in place of v0.
  bool deviationKept(const CollapseInfo& ci) {
    changed_.clear();
    shapes_.clear();
    const glm::dvec3 p1 = toGlm(ci.p1);
    for (const auto f : m_.vf_range(ci.v0))
      if (f != ci.fl && f != ci.fr) {
        changed_.push_back(f);
        shapes_.push_back(shapeOf(f, ci.v0, p1));
      }
    if (changed_.empty()) return false;
    stays_.clear();
    moves_.clear();
    // The nearest changed face (the first of equals) if within the tolerance, else -1.
    auto nearest = [&](const glm::dvec3& p) {
      double best = INFINITY;
      uint32_t which = 0;
      for (uint32_t k = 0; k < shapes_.size(); ++k) {
        const double d = shapes_[k].squared(p);
        if (d < best) {
          best = d;
          which = k;
        }
      }
      return best <= tolerance2_ ? int64_t(which) : int64_t(-1);
    };
    auto move = [&](const glm::dvec3& p) {
      const int64_t k = nearest(p);
      if (k < 0) return false;
      moves_.push_back(uint32_t(k));
      return true;
    };
    // Each covered point is within the tolerance of its own face: test that face first.
    for (size_t k = 0; k < changed_.size(); ++k)
      for (const glm::dvec3& p : points_[size_t(changed_[k].idx())]) {
        const bool stays = shapes_[k].squared(p) <= tolerance2_;
        stays_.push_back(stays ? 1 : 0);
        if (!stays && !move(p)) return false;
      }
    for (const auto f : {ci.fl, ci.fr})
      if (f.is_valid())
        for (const glm::dvec3& p : points_[size_t(f.idx())])
          if (!move(p)) return false;
    if (!move(toGlm(ci.p0))) return false;
    for (const TriangleDistance& shape : shapes_)
      if (!faceNearSurface(shape)) return false;
    return true;
  }

  // Whether a face lies within the tolerance of the unsimplified surface on a grid of points at
  // most sampleSpacing_ apart (at most kBackSteps per edge; its corners are tested by the
  // caller or are vertices of the surface).
  bool faceNearSurface(const TriangleDistance& shape) {
    const glm::dvec3 c[3] = {shape.corner(0), shape.corner(1), shape.corner(2)};
    const double longest =
        std::sqrt(std::max({glm::dot(c[1] - c[0], c[1] - c[0]), glm::dot(c[2] - c[1], c[2] - c[1]),
                            glm::dot(c[0] - c[2], c[0] - c[2])}));
    const double steps = std::ceil(longest / sampleSpacing_);
    const int n = steps >= 2.0 ? int(std::min(steps, double(kBackSteps))) : 2;
    for (int i = 0; i <= n; ++i)
      for (int j = 0; i + j <= n; ++j) {
        if ((i == 0 && j == 0) || i == n || j == n) continue;  // a corner
        if (!surface_.within(
                c[0] + (c[1] - c[0]) * (double(i) / n) + (c[2] - c[0]) * (double(j) / n),
                tolerance_, &hint_))
          return false;
      }
    return true;
  }

 public:
  // Moves each vertex that is not locked (free, or inside a feature line: on a sharp edge or a
  // seam between leaves the chords cut inside just as well) along its normal by the mean signed
  // distance of the unsimplified points its faces cover, so that the surface runs through
  // them rather than along their chords (a collapse keeps a vertex where it was: on a curved
  // surface the faces cut inside it, and the volume shrinks). A move is kept only if every rule
  // still holds around the vertex (no face turning by more than the limit, every covered vertex
  // within the tolerance of the faces around it, the faces near the unsimplified surface, the
  // moved vertex itself within the tolerance of it). In vertex order, each move seeing the ones
  // before it.
  // `settled` (per vertex, may be null): vertices to leave (relocated before, faces unchanged).
  void relocate(Progress& progress, const std::vector<uint8_t>* settled) {
    for (const auto v : m_.vertices()) {
      if ((v.idx() & 4095) == 0) progress.check();
      if (m_.status(v).locked() || (settled && (*settled)[size_t(v.idx())])) continue;
      double sum = 0.0;
      size_t count = 0;
      OpenMesh::Vec3d normal(0.0, 0.0, 0.0);
      for (const auto f : m_.vf_range(v)) {
        const OpenMesh::Vec3d n = m_.normal(f);
        const glm::dvec3 nf = toGlm(n), a = toGlm(m_.point(*m_.cfv_begin(f)));
        for (const glm::dvec3& p : points_[size_t(f.idx())]) sum += glm::dot(nf, p - a);
        count += points_[size_t(f.idx())].size();
        normal += n;
      }
      const double length = normal.norm();
      if (count == 0 || !(length > 0.0)) continue;
      const double delta = std::clamp(sum / double(count), -tolerance_, tolerance_);
      const OpenMesh::Vec3d from = m_.point(v), to = from + normal * (delta / length);
      if (!surface_.within(toGlm(to), tolerance_)) continue;
      m_.set_point(v, to);
      if (ringKept(v)) {
        for (const auto f : m_.vf_range(v)) m_.set_normal(f, m_.calc_face_normal(f));
      } else {
        m_.set_point(v, from);
      }
    }
  }

 private:
  // After moving v: the rules around it (see relocate()).
  bool ringKept(Mesh::VertexHandle v) {
    for (const auto f : m_.vf_range(v)) {
      const OpenMesh::Vec3d n = m_.calc_face_normal(f);
      if (!(n.norm() > 0.0) || (m_.normal(f) | n) < minCos_) return false;
      const TriangleDistance shape = shapeOf(f, Mesh::VertexHandle(), glm::dvec3(0.0));
      for (const glm::dvec3& p : points_[size_t(f.idx())])
        if (shape.squared(p) > tolerance2_) return false;
      if (!faceNearSurface(shape)) return false;
    }
    return true;
  }

  // The points of the faces that changed (changed_) stay on their face where deviationKept
  // found them within the tolerance of it; the others, those of the two deleted faces and the
  // removed vertex go to the nearest changed face it found (moves_, in this order).
  void afterCollapse(const CollapseInfo& ci) {
    quadric_[size_t(ci.v1.idx())] += quadric_[size_t(ci.v0.idx())];
    touched_[size_t(ci.v1.idx())] = 1;
    for (const auto u : m_.vv_range(ci.v1)) touched_[size_t(u.idx())] = 1;
    for (const auto f : m_.vf_range(ci.v1)) m_.set_normal(f, m_.calc_face_normal(f));
    tested_.clear();
    size_t next = 0;  // into stays_
    for (const auto f : changed_) {
      Points& own = points_[size_t(f.idx())];
      size_t kept = 0;
      for (const glm::dvec3& p : own) {
        if (stays_[next++])
          own[kept++] = p;
        else
          tested_.push_back(p);
      }
      own.resize(kept);
    }
    for (const auto f : {ci.fl, ci.fr})
      if (f.is_valid()) {
        Points& gone = points_[size_t(f.idx())];
        tested_.insert(tested_.end(), gone.begin(), gone.end());
        gone = Points();
      }
    tested_.push_back(toGlm(ci.p0));
    for (size_t k = 0; k < tested_.size(); ++k)
      points_[size_t(changed_[moves_[k]].idx())].push_back(tested_[k]);
  }

  Piece& piece_;
  Mesh& m_;
  double tolerance_;
  double tolerance2_;
  double sampleSpacing_;
  const TriangleGrid& surface_;
  bool seams_;
  double minCos_;
  std::vector<Quadric> quadric_;
  std::vector<Points> points_;
  std::vector<uint32_t> version_;
  std::vector<uint8_t> touched_;             // per vertex: its faces changed by a collapse
  std::vector<uint64_t> epoch_, refusedAt_;  // refusedAt_: the epoch of the refusal, 0 none
  uint64_t clock_ = 0;
  std::vector<Mesh::HalfedgeHandle> target_;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> heap_;
  // Scratch of deviationKept, read by afterCollapse (see there).
  std::vector<Mesh::FaceHandle> changed_;
  std::vector<TriangleDistance> shapes_;
  std::vector<uint8_t> stays_;
  std::vector<uint32_t> moves_;
  Points tested_;
  // The unsimplified triangle that faceNearSurface last found near (see TriangleGrid::within).
  uint32_t hint_ = UINT32_MAX;
};

constexpr size_t kMaxChunks = 256;

// The key a triangle is placed in a slab by: the sum of its corners' coordinates on `axis`.
double slabKey(const std::vector<glm::dvec3>& positions, const std::array<uint32_t, 3>& tri,
               int axis) {
  return positions[tri[0]][axis] + positions[tri[1]][axis] + positions[tri[2]][axis];
}

// The working mesh of an attempt between passes: triangles (indices into `positions`, which
// relocations move), their leaves and the unsimplified points each covers (empty before the
// first pass).
struct Working {
  std::vector<glm::dvec3> positions;
  std::vector<std::array<uint32_t, 3>> triangles;
  std::vector<uint32_t> leaf;
  std::vector<Points> points;
  std::vector<uint8_t> settled;  // per position: relocated, and its faces unchanged since
};

// One parallel pass over slabs along `axis` split at `bounds` (slabKey values, ascending: a
// triangle goes to the slab of the bounds at or below its key), each collapsed on one thread with
// the vertices two slabs share locked, then relocated. False when a slab cannot be built (a seam
// vertex OpenMesh cannot hold): `w` is then unchanged.
bool slabPass(Working& w, int axis, const std::vector<double>& bounds, double tolerance,
              const TriangleGrid& surface, Progress& progress, CollapseCount& collapses,
              size_t expected, double from, double to) {
  const size_t count = w.triangles.size();
  const size_t slabs = bounds.size() + 1;
  std::vector<uint32_t> slabOf(count);
  std::vector<std::vector<uint32_t>> members(slabs);
  for (size_t t = 0; t < count; ++t) {
    const double key = slabKey(w.positions, w.triangles[t], axis);
    slabOf[t] = uint32_t(std::upper_bound(bounds.begin(), bounds.end(), key) - bounds.begin());
    members[slabOf[t]].push_back(uint32_t(t));
  }
  std::vector<uint32_t> owner(w.positions.size(), UINT32_MAX);
  std::vector<uint8_t> isSeam(w.positions.size(), 0);
  for (size_t t = 0; t < count; ++t)
    for (uint32_t v : w.triangles[t]) {
      if (owner[v] == UINT32_MAX)
        owner[v] = slabOf[t];
      else if (owner[v] != slabOf[t])
        isSeam[v] = 1;
    }
  owner = {};
  slabOf = {};
  std::vector<Piece> pieces(slabs);
  std::atomic<bool> built{true};
  parallelFor(0, int64_t(slabs), 1, [&](int64_t first, int64_t last) {
    for (int64_t c = first; c < last && built; ++c)
      if (!buildPiece(pieces[size_t(c)], w.positions, w.triangles, members[size_t(c)], w.leaf,
                      isSeam, progress))
        built = false;
  });
  if (!built) return false;
  std::vector<std::vector<Points>> carried(slabs);
  parallelFor(0, int64_t(slabs), 1, [&](int64_t first, int64_t last) {
    for (int64_t c = first; c < last; ++c) {
      Piece& piece = pieces[size_t(c)];
      markFeatures(piece);
      Collapser collapser(piece, tolerance, surface, true);
      if (w.points.empty()) {
        collapser.coverFaceCentresAndEdgeMidpoints();
      } else {  // the piece's faces were added in members' order
        std::vector<Points> own(members[size_t(c)].size());
        for (size_t k = 0; k < own.size(); ++k) own[k] = std::move(w.points[members[size_t(c)][k]]);
        collapser.loadPoints(std::move(own));
      }
      collapser.run(progress, collapses, expected, from, to);
      collapser.relocate(progress, nullptr);
      carried[size_t(c)] = collapser.takePoints();
    }
  });
  Working next;
  next.positions = std::move(w.positions);
  next.settled.assign(next.positions.size(), 0);
  for (size_t c = 0; c < slabs; ++c) {
    const Piece& piece = pieces[c];
    const Mesh& m = piece.mesh;
    for (const auto v : m.vertices()) {
      const uint32_t o = m.property(piece.original, v);
      next.positions[o] = toGlm(m.point(v));  // a seam vertex is locked: the same in every slab
      if (!m.status(v).locked()) next.settled[o] = 1;
    }
    for (const auto f : m.faces()) {
      std::array<uint32_t, 3> tri{};
      int k = 0;
      for (const auto v : m.fv_range(f)) tri[k++] = m.property(piece.original, v);
      next.triangles.push_back(tri);
      next.leaf.push_back(m.property(piece.leaf, f));
      next.points.push_back(std::move(carried[c][size_t(f.idx())]));
    }
    pieces[c] = Piece();
  }
  w = std::move(next);
  return true;
}

// One attempt: `original` simplified by the collapse rules within `tolerance` (scene units) into
// `*out`, the bar's span from `collapses`; false when the mesh is not a 2-manifold OpenMesh can
// hold (then `*out` is unspecified). `surface`: `original`'s triangles, reach >= tolerance.
// `*closed`: whether the mesh has no boundary (the measurement's flat-region bound needs it).
// With more than one chunk's worth of triangles: slabs in parallel, then slabs shifted by half
// a slab (the first pass's seams inside them) in parallel, then the whole mesh with what is left.
bool simplifyOnce(const ExportMesh& original, double tolerance, const TriangleGrid& surface,
                  size_t trianglesPerChunk, Progress& progress, CollapseCount& collapses,
                  ExportMesh* out, bool* closed) {
  const size_t count = original.mesh.triangles.size();
  trianglesPerChunk = std::max<size_t>(trianglesPerChunk, 1);
  const size_t chunks =
      std::clamp<size_t>((count + trianglesPerChunk / 2) / trianglesPerChunk, 1, kMaxChunks);
  const size_t expected = original.mesh.positions.size() * 9 / 10;

  auto unsimplified = [&original] {
    Working w;
    w.positions = original.mesh.positions;
    w.triangles = original.mesh.triangles;
    w.leaf = original.triangleLeaf;
    return w;
  };
  Working w = unsimplified();
  if (chunks > 1) {
    const Bounds box = meshBounds(original.mesh);
    const glm::dvec3 size = box.size();
    const int axis = size.x >= size.y && size.x >= size.z ? 0 : size.y >= size.z ? 1 : 2;
    std::vector<double> keys(count);
    for (size_t t = 0; t < count; ++t) keys[t] = slabKey(w.positions, w.triangles[t], axis);
    std::sort(keys.begin(), keys.end());
    std::vector<double> bounds, shifted;  // equal counts; then halfway between those
    for (size_t k = 1; k < chunks; ++k) bounds.push_back(keys[k * count / chunks]);
    for (size_t k = 0; k < chunks; ++k) {
      const double below = k == 0 ? keys.front() : bounds[k - 1];
      const double above = k + 1 == chunks ? keys.back() : bounds[k];
      shifted.push_back(0.5 * (below + above));
    }
    keys = {};
    if (slabPass(w, axis, bounds, tolerance, surface, progress, collapses, expected, 0.02, 0.6))
      slabPass(w, axis, shifted, tolerance, surface, progress, collapses, expected, 0.6, 0.8);
    // else a seam vertex OpenMesh could not take: the whole mesh at once.
  }

  // The whole mesh, seams free, the slabs' points carried.
  std::vector<uint32_t> all(w.triangles.size());
  for (size_t t = 0; t < all.size(); ++t) all[t] = uint32_t(t);
  Piece whole;
  bool builtWhole = buildPiece(whole, w.positions, w.triangles, all, w.leaf, {}, progress);
  if (!builtWhole && !w.points.empty()) {  // the slabs did not stitch into a 2-manifold
    w = unsimplified();
    all.resize(w.triangles.size());
    for (size_t t = 0; t < all.size(); ++t) all[t] = uint32_t(t);
    whole = Piece();
    builtWhole = buildPiece(whole, w.positions, w.triangles, all, w.leaf, {}, progress);
  }
  if (!builtWhole) return false;
  all = {};
  // Collapses keep the boundary: the result is closed when the input is.
  *closed = true;
  for (const auto h : whole.mesh.halfedges())
    if (whole.mesh.is_boundary(h)) {
      *closed = false;
      break;
    }
  markFeatures(whole);
  {
    Collapser collapser(whole, tolerance, surface, false);
    const bool carried = !w.points.empty();
    if (carried)
      collapser.loadPoints(std::move(w.points));
    else
      collapser.coverFaceCentresAndEdgeMidpoints();
    collapser.run(progress, collapses, expected, carried ? 0.8 : 0.02, 0.88);
    // Relocated by a slab and untouched since: not again.
    std::vector<uint8_t> settled(whole.mesh.n_vertices(), 0);
    if (!w.settled.empty())
      for (const auto v : whole.mesh.vertices())
        settled[size_t(v.idx())] = w.settled[whole.mesh.property(whole.original, v)];
    collapser.unsettleTouched(settled);
    collapser.relocate(progress, &settled);
  }
  w = Working();
  whole.mesh.garbage_collection();

  ExportMesh& simplified = *out;
  simplified = ExportMesh();
  simplified.leaves = original.leaves;
  simplified.unit = original.unit;
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
  return true;
}

}  // namespace

SimplifyReport simplifyMesh(ExportMesh* mesh, double tolerance, Progress& progress,
                            size_t trianglesPerChunk, double firstAttemptTolerance) {
  Stopwatch clock;
  SimplifyReport report;
  report.tolerance = tolerance;
  report.trianglesBefore = mesh->mesh.triangles.size();
  report.trianglesAfter = report.trianglesBefore;
  if (mesh->mesh.triangles.empty() || !(tolerance > 0.0)) return report;
  progress.report("simplify", 0.0);
  // OpenMesh prints every face it cannot add; buildPiece reports those (the chunks then give way
  // to the whole mesh at once, or the report says why nothing was done).
  omerr().disable();
  // The unsimplified surface, for the rules' back-check and the measurement.
  const TriangleGrid surface(mesh->mesh.positions, mesh->mesh.triangles,
                             kMeasureReachPerTolerance * tolerance, &progress);
  CollapseCount collapses;
  double within = firstAttemptTolerance * tolerance;
  ExportMesh simplified;
  for (int attempt = 0;; ++attempt) {
    // Each attempt a shrinking share of the bar: 0-0.85, 0.85-0.95, 0.95-0.99, 0.99-1.
    static constexpr double kSpans[kMaxSimplifyAttempts + 1] = {0.0, 0.85, 0.95, 0.99, 1.0};
    collapses.spanFrom = kSpans[attempt];
    collapses.spanTo = kSpans[attempt + 1];
    collapses.collapses = 0;
    bool closed = false;
    if (!simplifyOnce(*mesh, within, surface, trianglesPerChunk, progress, collapses, &simplified,
                      &closed)) {
      report.refused = true;
      report.refusedWhy = "the mesh is not a 2-manifold OpenMesh can hold";
      break;
    }
    report.attempts = attempt + 1;
    report.rulesTolerance = within;
    Stopwatch measuring;
    report.measured = measureDeviation(mesh->mesh, simplified.mesh, closed,
                                       kMeasureAccuracyPerTolerance * tolerance, surface.reach(),
                                       kMeasureEnoughPerTolerance * tolerance, progress, "simplify",
                                       &surface, collapses.at(0.9), collapses.at(1.0));
    report.measureSeconds += measuring.seconds();
    if (attempt == 0) report.firstAttemptBound = report.measured.bound();
    if (report.measured.bound() <= tolerance && !report.measured.capped) {
      *mesh = std::move(simplified);
      report.trianglesAfter = mesh->mesh.triangles.size();
      break;
    }
    if (attempt + 1 == kMaxSimplifyAttempts) {
      report.refused = true;
      report.refusedWhy = "no attempt kept within the bound (the mesh is left as it was)";
      break;
    }
    // Tighter by what the last attempt overshot, and by at least a fifth.
    within *= std::min(0.8, 0.95 * tolerance / report.measured.bound());
  }
  report.seconds = clock.seconds();
  progress.report("simplify", 1.0);
  return report;
}

}  // namespace strata
