#include "ui/viewport_renderer.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstring>
#include <string>

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>
#include <glm/matrix.hpp>

#include "engine/util/error.h"
#include "engine/util/timer.h"

namespace strata::ui {
namespace {

uint8_t toByte(float c) {
  return uint8_t(std::lround(std::clamp(c, 0.0f, 1.0f) * 255.0f));
}

// Camera-fixed lights: key from the upper left and slightly behind the viewer, fill from the
// lower right.
glm::vec3 cameraLight(const ViewportFrame& f, double right, double up, double back) {
  glm::dvec3 r = glm::normalize(glm::cross(f.forward, f.up));
  return glm::vec3(glm::normalize(r * right + f.up * up - f.forward * back));
}

// NDC per scene unit across the view (x, y) at view depth 1 (perspective) or anywhere
// (orthographic): the projections of unit steps right and up from the point in front of the eye.
glm::dvec2 projectionScale(const ViewportFrame& f) {
  const glm::dvec3 right = glm::normalize(glm::cross(f.forward, f.up));
  const glm::dvec3 up = glm::normalize(glm::cross(right, f.forward));
  const glm::dvec3 at = f.eye + f.forward;
  auto ndc = [&](const glm::dvec3& p) {
    const glm::dvec4 c = f.viewProjection * glm::dvec4(p, 1.0);
    return glm::dvec2(c) / c.w;
  };
  const glm::dvec2 centre = ndc(at);
  return glm::dvec2(std::abs(ndc(at + right).x - centre.x), std::abs(ndc(at + up).y - centre.y));
}

// The splat attributes (1: position, 2: normal, 3: leaf and axis) of the bound vertex array, from
// the bound GL_ARRAY_BUFFER: splats `strideBytes` apart from byte `base`.
void pointSplatAttributes(GLsizei strideBytes, size_t base) {
  glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, strideBytes,
                        reinterpret_cast<void*>(base + offsetof(Splat, position)));
  glVertexAttribIPointer(2, 1, GL_UNSIGNED_INT, strideBytes,
                         reinterpret_cast<void*>(base + offsetof(Splat, normal)));
  glVertexAttribIPointer(3, 1, GL_UNSIGNED_INT, strideBytes,
                         reinterpret_cast<void*>(base + offsetof(Splat, leafAxis)));
}

std::vector<uint8_t> flipRows(std::vector<uint8_t> pixels, int width, int height) {
  const size_t row = size_t(width) * 4;
  std::vector<uint8_t> tmp(row);
  for (int y = 0; y < height / 2; ++y) {
    uint8_t* a = pixels.data() + size_t(y) * row;
    uint8_t* b = pixels.data() + size_t(height - 1 - y) * row;
    std::memcpy(tmp.data(), a, row);
    std::memcpy(a, b, row);
    std::memcpy(b, tmp.data(), row);
  }
  return pixels;
}

}  // namespace

LineVertex lineVertex(const glm::dvec3& p, const glm::vec4& c) {
  return LineVertex{{float(p.x), float(p.y), float(p.z)},
                    {toByte(c.r), toByte(c.g), toByte(c.b), toByte(c.a)}};
}

ViewportRenderer::ViewportRenderer()
    : surfelProgram_("surfel.vert", "surfel.frag"),
      pointProgram_("surfel.vert", "surfel.frag", "#define SPLAT_POINTS\n"),
      pickProgram_("surfel.vert", "surfel_pick.frag"),
      lineProgram_("line.vert", "line.frag"),
      backgroundProgram_("background.vert", "background.frag") {
  // Surfels: a unit quad per instance plus the instance buffer.
  const float corners[] = {-1.f, -1.f, 1.f, -1.f, -1.f, 1.f, 1.f, 1.f};
  glGenBuffers(1, &cornerBuffer_);
  glBindBuffer(GL_ARRAY_BUFFER, cornerBuffer_);
  glBufferData(GL_ARRAY_BUFFER, sizeof(corners), corners, GL_STATIC_DRAW);
  makeSplatLayer(&surfelVao_, &splatBuffer_);
  makeSplatLayer(&stagingVao_, &stagingBuffer_);
  for (SplatLayer& ghost : ghosts_) makeSplatLayer(&ghost.vao, &ghost.buffer);

  glGenVertexArrays(1, &lineVao_);
  glBindVertexArray(lineVao_);
  glGenBuffers(1, &lineBuffer_);
  glBindBuffer(GL_ARRAY_BUFFER, lineBuffer_);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(LineVertex),
                        reinterpret_cast<void*>(offsetof(LineVertex, position)));
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 4, GL_UNSIGNED_BYTE, GL_TRUE, sizeof(LineVertex),
                        reinterpret_cast<void*>(offsetof(LineVertex, color)));

  glGenVertexArrays(1, &emptyVao_);
  glGenVertexArrays(1, &pointVao_);
  glBindVertexArray(pointVao_);
  for (GLuint attribute = 1; attribute <= 3; ++attribute) glEnableVertexAttribArray(attribute);
  glBindVertexArray(0);
  GLfloat pointSizes[2] = {1.0f, 1.0f};
  glGetFloatv(GL_POINT_SIZE_RANGE, pointSizes);
  maxPointSize_ = std::max(1.0f, pointSizes[1]);
  glEnable(GL_PROGRAM_POINT_SIZE);
  // GL 4.4 names the limit (at least 2048 bytes); older contexts have no query and none below.
  if (epoxy_gl_version() >= 44) glGetIntegerv(GL_MAX_VERTEX_ATTRIB_STRIDE, &maxAttribStride_);
  for (KindTiming& t : timing_) glGenQueries(1, &t.query);
  // Splats by compute where the context has compute shaders (4.3) and glClearTexImage (4.4),
  // and the driver builds the programs; quads and points otherwise.
  if (epoxy_gl_version() >= 44) {
    GLint64 blockBytes = 0;
    glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &blockBytes);
    maxStorageBlockBytes_ = double(blockBytes);
    try {
      computeProgram_ = GlProgram::compute("surfel_splat.comp");
      resolveProgram_ = GlProgram("surfel_resolve.vert", "surfel_resolve.frag");
      computeReady_ = true;
    } catch (const Error& e) {
      computeProblem_ = e.what();
    }
  } else {
    computeProblem_ = "the GL context is older than 4.4";
  }
  // Software rasterizers queue a draw's pixels for worker threads after the timer query has
  // ended: their times count little of the work (Mesa llvmpipe timed points at 1 ns a splat
  // against 215 for quads, then drew points 2-4 times slower than quads). There, Automatic
  // draws quads, which they fill fastest (no depth written per fragment).
  const auto* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  const std::string name = renderer ? renderer : "";
  for (const char* software : {"llvmpipe", "softpipe", "SwiftShader", "swrast", "Software"})
    if (name.find(software) != std::string::npos) timersTrusted_ = false;
  glBindBuffer(GL_ARRAY_BUFFER, 0);

  glGenTextures(1, &leafTexture_);
  glBindTexture(GL_TEXTURE_2D, leafTexture_);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  const uint8_t grey[4] = {204, 204, 204, 0};
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, 1, 1, 0, GL_RGBA, GL_UNSIGNED_BYTE, grey);
  glBindTexture(GL_TEXTURE_2D, 0);
}

void ViewportRenderer::makeSplatLayer(GLuint* vao, GLuint* buffer) {
  glGenVertexArrays(1, vao);
  glBindVertexArray(*vao);
  glBindBuffer(GL_ARRAY_BUFFER, cornerBuffer_);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 0, nullptr);
  glGenBuffers(1, buffer);
  glBindBuffer(GL_ARRAY_BUFFER, *buffer);
  pointSplatAttributes(sizeof(Splat), 0);
  for (GLuint attribute = 1; attribute <= 3; ++attribute) {  // one splat per instance
    glEnableVertexAttribArray(attribute);
    glVertexAttribDivisor(attribute, 1);
  }
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}

void ViewportRenderer::setGhosts(const std::vector<Splat>& cutting,
                                 const std::vector<Splat>& intersecting,
                                 const std::vector<GhostRun> given[2]) {
  const std::vector<Splat>* layers[2] = {&cutting, &intersecting};
  std::vector<GhostRun> runs[2];
  for (int i = 0; i < 2; ++i) {
    if (given) runs[i] = given[i];
    size_t counted = 0;
    for (const GhostRun& run : runs[i]) counted += run.count;
    if (counted != layers[i]->size()) runs[i] = {GhostRun{layers[i]->size(), 0.0}};
  }
  // The same ghosts (a new result of an edit that changed no part): the image stands.
  auto same = [](const std::vector<Splat>& a, const std::vector<Splat>& b) {
    return a.size() == b.size() &&
           (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(Splat)) == 0);
  };
  if (same(cutting, ghostSplats_[0]) && same(intersecting, ghostSplats_[1]) &&
      runs[0] == ghostRuns_[0] && runs[1] == ghostRuns_[1])
    return;
  ghostSplats_[0] = cutting;
  ghostSplats_[1] = intersecting;
  ghostRuns_[0] = std::move(runs[0]);
  ghostRuns_[1] = std::move(runs[1]);
  for (int i = 0; i < 2; ++i) {
    ghosts_[i].count = layers[i]->size();
    if (layers[i]->empty()) continue;
    glBindBuffer(GL_ARRAY_BUFFER, ghosts_[i].buffer);
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(layers[i]->size() * sizeof(Splat)), layers[i]->data(),
                 GL_DYNAMIC_DRAW);
  }
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  ++contentVersion_;
}

ViewportRenderer::~ViewportRenderer() {
  coarse_.reset();
  shown_.reset();
  building_.reset();
  if (pickFramebuffer_) {
    glDeleteFramebuffers(1, &pickFramebuffer_);
    GLuint targets[] = {pickIds_, pickDepth_};
    glDeleteRenderbuffers(2, targets);
  }
  glDeleteTextures(1, &leafTexture_);
  GLuint computeImages[] = {computeDepth_, computeIds_};
  glDeleteTextures(2, computeImages);
  for (KindTiming& t : timing_) glDeleteQueries(1, &t.query);
  GLuint buffers[] = {cornerBuffer_,     splatBuffer_,      lineBuffer_,
                      ghosts_[0].buffer, ghosts_[1].buffer, stagingBuffer_};
  glDeleteBuffers(6, buffers);
  GLuint vaos[] = {surfelVao_,     lineVao_,    emptyVao_, ghosts_[0].vao,
                   ghosts_[1].vao, stagingVao_, pointVao_};
  glDeleteVertexArrays(7, vaos);
}

bool ViewportRenderer::splatBufferFits(size_t count) const {
  // Grows when needed; shrinks only from a large buffer that is mostly unused, so that
  // alternating coarse and full previews do not reallocate (and re-register with CUDA) each time.
  constexpr size_t kShrinkAbove = size_t(1) << 22;  // splats (80 MiB)
  return splatCapacity_ > 0 && count <= splatCapacity_ &&
         (splatCapacity_ <= kShrinkAbove || count * 4 >= splatCapacity_);
}

bool ViewportRenderer::reserveSplats(size_t count) {
  if (splatBufferFits(count)) return false;
  const size_t capacity = std::max(kMinSplatCapacity, count + count / 4);
  glBindBuffer(GL_ARRAY_BUFFER, splatBuffer_);
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(capacity * sizeof(Splat)), nullptr, GL_DYNAMIC_DRAW);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  splatCapacity_ = capacity;
  return true;
}

void ViewportRenderer::uploadSplats(const Splat* splats, size_t count, const SplatShape& shape) {
  Stopwatch clock;
  reserveSplats(count);
  if (count > 0) {
    glBindBuffer(GL_ARRAY_BUFFER, splatBuffer_);
    glBufferSubData(GL_ARRAY_BUFFER, 0, GLsizeiptr(count * sizeof(Splat)), splats);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
  }
  setSplatCount(count, shape);
  uploadMsThisFrame_ += clock.seconds() * 1000.0;
}

void ViewportRenderer::copySplats(GLuint source, size_t count, const SplatShape& shape) {
  Stopwatch clock;
  reserveSplats(count);
  if (count > 0) {
    glBindBuffer(GL_COPY_READ_BUFFER, source);
    glBindBuffer(GL_COPY_WRITE_BUFFER, splatBuffer_);
    glCopyBufferSubData(GL_COPY_READ_BUFFER, GL_COPY_WRITE_BUFFER, 0, 0,
                        GLsizeiptr(count * sizeof(Splat)));
    glBindBuffer(GL_COPY_READ_BUFFER, 0);
    glBindBuffer(GL_COPY_WRITE_BUFFER, 0);
  }
  setSplatCount(count, shape);
  uploadMsThisFrame_ += clock.seconds() * 1000.0;
}

size_t ViewportRenderer::stageSplats(const Splat* splats, size_t count, size_t done,
                                     size_t maxBytes) {
  Stopwatch clock;
  glBindBuffer(GL_ARRAY_BUFFER, stagingBuffer_);
  if (done == 0 && stagingCapacity_ < count) {
    const size_t capacity = std::max(kMinSplatCapacity, count + count / 4);
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(capacity * sizeof(Splat)), nullptr, GL_DYNAMIC_DRAW);
    stagingCapacity_ = capacity;
  }
  const size_t n = std::min(count - done, std::max<size_t>(1, maxBytes / sizeof(Splat)));
  if (n > 0)
    glBufferSubData(GL_ARRAY_BUFFER, GLintptr(done * sizeof(Splat)), GLsizeiptr(n * sizeof(Splat)),
                    splats + done);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  uploadMsThisFrame_ += clock.seconds() * 1000.0;
  return done + n;
}

void ViewportRenderer::commitStagedSplats(size_t count, const SplatShape& shape) {
  std::swap(surfelVao_, stagingVao_);
  std::swap(splatBuffer_, stagingBuffer_);
  std::swap(splatCapacity_, stagingCapacity_);
  setSplatCount(count, shape);
}

void ViewportRenderer::setSplatCount(size_t count, const SplatShape& shape) {
  splatCount_ = std::min(count, splatCapacity_);
  shape_ = shape;
  cellSize_ = shape.cellSize;
  ++contentVersion_;
  ++splatsVersion_;
}

SplatShape splatShapeOf(const Grid& grid, const SplatResource& splats) {
  SplatShape shape;
  shape.cellSize = grid.h;
  shape.levels = splats.levels();
  const Bounds box = grid.bounds();
  if (!box.empty()) {
    shape.lo = box.min;
    shape.hi = box.max;
  }
  return shape;
}

size_t ViewportRenderer::levelEnd(int level) const {
  if (level <= 0) return splatCount_;
  return std::min<size_t>(splatCount_, size_t(shape_.levels.end[level]));
}

double ViewportRenderer::nearestDepth(const ViewportFrame& f) const {
  double nearest = 1e300;
  for (int c = 0; c < 8; ++c) {
    const glm::dvec3 corner((c & 1) ? shape_.hi.x : shape_.lo.x,
                            (c & 2) ? shape_.hi.y : shape_.lo.y,
                            (c & 4) ? shape_.hi.z : shape_.lo.z);
    nearest = std::min(nearest, glm::dot(corner - f.eye, f.forward));
  }
  return nearest;
}

double ViewportRenderer::nearestPixelsPerUnit(const ViewportFrame& f) const {
  // Pixels per scene unit across the view at depth 1 (perspective) or anywhere (orthographic).
  const glm::dvec2 scale = projectionScale(f);
  const double perUnit = std::max(scale.y * 0.5 * f.height, scale.x * 0.5 * f.width);
  if (f.ortho) return std::isfinite(perUnit) ? perUnit : HUGE_VAL;
  const double nearest = nearestDepth(f);
  if (!(nearest > 0.0)) return HUGE_VAL;  // the camera is within the box's depth range
  const double pixelsPerUnit = perUnit / nearest;
  return std::isfinite(pixelsPerUnit) ? pixelsPerUnit : HUGE_VAL;
}

int ViewportRenderer::detailLevel(const ViewportFrame& f) const {
  if (splatCount_ == 0 || shape_.levels.end[1] == 0) return 0;
  const double pixelsPerUnit = nearestPixelsPerUnit(f);
  if (!std::isfinite(pixelsPerUnit) || pixelsPerUnit <= 0.0) return 0;
  int level = 0;
  while (level < maxDetailLevel_ && level + 1 < kSplatLevels && shape_.levels.end[level + 1] > 0 &&
         std::ldexp(shape_.cellSize, level + 1) * pixelsPerUnit <= kMaxSplatSpacingPx)
    ++level;
  return level;
}

double ViewportRenderer::spriteBoundPx(const ViewportFrame& f, float radius) const {
  // The quad's corners lie at most `reach` from the surfel (radius * sqrt(2 + 2 / 0.3^2) cells:
  // lifted onto the tangent plane, surfel.vert), so no corner comes nearer the eye than the
  // box's nearest depth less reach. A point at depth d and NDC x lies at projScale.x x_view / d;
  // moving it by reach moves it by at most reach (projScale.x + |NDC x|) / (d - reach), |NDC x|
  // at most 1 for a splat whose sprite shows (plus the margin drawSplatsAs adds); the same
  // across y. The sprite spans twice that, plus the shader's pixel of margin.
  const double reach = double(radius) * shape_.cellSize * std::sqrt(2.0 + 2.0 / (0.3 * 0.3));
  const glm::dvec2 scale = projectionScale(f);
  const glm::dvec2 pixelsPerNdc(0.5 * f.width, 0.5 * f.height);
  double perUnit = 0.0;  // pixels per scene unit of offset, the worst across x and y
  if (f.ortho) {
    perUnit = std::max(scale.x * pixelsPerNdc.x, scale.y * pixelsPerNdc.y);
  } else {
    const double depth = nearestDepth(f) - reach;
    if (!(depth > 0.0)) return HUGE_VAL;  // a splat may reach the eye's plane
    constexpr double kNdcReach = 1.5;     // |NDC| of a centre whose sprite still shows, bound
    perUnit =
        std::max((scale.x + kNdcReach) * pixelsPerNdc.x, (scale.y + kNdcReach) * pixelsPerNdc.y) /
        depth;
  }
  const double sprite = 2.0 * reach * perUnit + 2.0;
  return std::isfinite(sprite) ? sprite : HUGE_VAL;
}

bool ViewportRenderer::pointsFit(const ViewportFrame& f, float radius) const {
  return spriteBoundPx(f, radius) <= double(maxPointSize_);
}

bool ViewportRenderer::kindFits(const ViewportFrame& f, float radius, SplatKind kind) const {
  switch (kind) {
    case SplatKind::Points:
      return pointsFit(f, radius);
    case SplatKind::Compute:
      // The splats are read as one shader storage block, which the driver bounds (the spec's
      // least is 16 MiB; Mesa's and older NVIDIA drivers' 128 MiB: 6.7 M splats).
      return computeReady() && double(splatCount_) * sizeof(Splat) <= maxStorageBlockBytes_ &&
             spriteBoundPx(f, radius) <= kMaxComputeFootprintPx;
    default:
      return true;
  }
}

ViewportRenderer::SplatKind ViewportRenderer::preferredKind(const ViewportFrame& f,
                                                            float radius) const {
  switch (primitive_) {
    case SplatPrimitive::Quads:
      return SplatKind::Quads;
    case SplatPrimitive::Points:
      return pointsFit(f, radius) ? SplatKind::Points : SplatKind::Quads;
    case SplatPrimitive::Compute:
      return kindFits(f, radius, SplatKind::Compute) ? SplatKind::Compute : SplatKind::Quads;
    case SplatPrimitive::Automatic:
      break;
  }
  if (!timersTrusted_) return SplatKind::Quads;
  // Automatic: each kind that fits until it has a time (points, compute, quads; not again
  // while its timer is still in flight, which would draw it untimed), then the cheapest
  // (drawSplatRange retries the others now and then).
  for (SplatKind kind : {SplatKind::Points, SplatKind::Compute, SplatKind::Quads})
    if (kindFits(f, radius, kind) && timing_[int(kind)].reads == 0 && !timing_[int(kind)].pending)
      return kind;
  std::optional<SplatKind> best;  // the cheapest kind measured (untimed ones have no cost)
  for (SplatKind kind : {SplatKind::Quads, SplatKind::Points, SplatKind::Compute})
    if (kindFits(f, radius, kind) && timing_[int(kind)].reads > 0 &&
        (!best || timing_[int(kind)].nsPerSplat < timing_[int(*best)].nsPerSplat))
      best = kind;
  return best.value_or(SplatKind::Quads);
}

bool ViewportRenderer::everyFittingKindTimed(const ViewportFrame& f, float radius) const {
  for (int k = 0; k < kSplatKinds; ++k)
    if (kindFits(f, radius, SplatKind(k)) && timing_[k].reads == 0) return false;
  return true;
}

int ViewportRenderer::firstImageLevel(const ViewportFrame& f) const {
  int level = buildLevel_;
  // Not from a software rasterizer's timers, which count little of a draw's work (and under
  // load read anything: a test of the window's image saw a coarser first image now and then).
  if (!timersTrusted_) return level;
  const double ns = timing_[int(preferredKind(f, float(1 << level)))].nsPerSplat;
  if (ns <= 0.0) return level;  // not measured yet: the view's level
  while (level + 1 < kSplatLevels && shape_.levels.end[level + 1] > 0 &&
         double(levelEnd(level)) * ns * 1e-6 > kFirstImageMs)
    ++level;
  return level;
}

double ViewportRenderer::nsPerSplat(SplatPrimitive kind) const {
  switch (kind) {
    case SplatPrimitive::Quads:
      return timing_[int(SplatKind::Quads)].nsPerSplat;
    case SplatPrimitive::Points:
      return timing_[int(SplatKind::Points)].nsPerSplat;
    case SplatPrimitive::Compute:
      return timing_[int(SplatKind::Compute)].nsPerSplat;
    default:
      return 0.0;
  }
}

void ViewportRenderer::assumeNsPerSplat(SplatPrimitive kind, double ns) {
  const SplatKind k = kind == SplatPrimitive::Points    ? SplatKind::Points
                      : kind == SplatPrimitive::Compute ? SplatKind::Compute
                                                        : SplatKind::Quads;
  KindTiming& t = timing_[int(k)];
  t.nsPerSplat = ns;
  t.nsSum = ns * 1e6;
  t.splatSum = 1e6;
  t.reads = std::max(t.reads, 1);
}

namespace {

// The view rays of surfel_geometry.glsl (rayOnDisc) for `viewProjection`: near-plane points and
// directions, affine in NDC (x, y), the directions scaled alike (their length does not matter)
// to keep floats well within range.
void setViewRays(const GlProgram& program, const glm::dmat4& viewProjection) {
  const glm::dmat4 toWorld = glm::inverse(viewProjection);
  auto unproject = [&](double x, double y, double z) {
    const glm::dvec4 p = toWorld * glm::dvec4(x, y, z, 1.0);
    return glm::dvec3(p) / p.w;
  };
  const glm::dvec3 near0 = unproject(0, 0, -1), nearX = unproject(1, 0, -1) - near0,
                   nearY = unproject(0, 1, -1) - near0;
  const glm::dvec3 dir0 = unproject(0, 0, 1) - near0;
  const glm::dvec3 dirX = unproject(1, 0, 1) - near0 - nearX - dir0;
  const glm::dvec3 dirY = unproject(0, 1, 1) - near0 - nearY - dir0;
  const double scale = 1.0 / std::max(1e-300, glm::length(dir0));
  program.set("rayOrigin0", glm::vec3(near0));
  program.set("rayOriginX", glm::vec3(nearX));
  program.set("rayOriginY", glm::vec3(nearY));
  program.set("rayDir0", glm::vec3(dir0 * scale));
  program.set("rayDirX", glm::vec3(dirX * scale));
  program.set("rayDirY", glm::vec3(dirY * scale));
}

// Reads `t`'s query when the GPU has it (never waits): its time joins the sums, older draws
// fading, so that a large draw weighs more than a small one, whose fixed cost (a draw's setup,
// tens of microseconds) would read as splats' cost. True when it was read.
bool readTiming(ViewportRenderer::KindTiming& t) {
  if (!t.pending) return false;
  GLint available = 0;
  glGetQueryObjectiv(t.query, GL_QUERY_RESULT_AVAILABLE, &available);
  if (!available) return false;
  GLuint64 ns = 0;
  glGetQueryObjectui64v(t.query, GL_QUERY_RESULT, &ns);
  t.pending = false;
  t.nsSum = 0.7 * t.nsSum + double(ns);
  t.splatSum = 0.7 * t.splatSum + double(t.splats);
  t.nsPerSplat = t.splatSum > 0.0 ? t.nsSum / t.splatSum : 0.0;
  ++t.reads;
  return true;
}

}  // namespace

void ViewportRenderer::collectTiming() {
  for (KindTiming& t : timing_) readTiming(t);
}

void ViewportRenderer::setLeafStyles(const LeafStyleTable& styles) {
  // The same colours and selection (an edit that changed no part's look: a measurement, a
  // name): the image stands.
  if (styles_ && styles.color == styles_->color && styles.selected == styles_->selected) return;
  styles_ = styles;
  const int count = std::max<int>(1, int(styles.color.size()));
  const int width = std::min(count, 1024);
  const int height = (count + width - 1) / width;
  std::vector<uint8_t> texels(size_t(width) * size_t(height) * 4, 0);
  for (size_t i = 0; i < styles.color.size(); ++i) {
    texels[i * 4 + 0] = toByte(styles.color[i].r);
    texels[i * 4 + 1] = toByte(styles.color[i].g);
    texels[i * 4 + 2] = toByte(styles.color[i].b);
    texels[i * 4 + 3] = i < styles.selected.size() && styles.selected[i] ? 255 : 0;
  }
  glBindTexture(GL_TEXTURE_2D, leafTexture_);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE,
               texels.data());
  glBindTexture(GL_TEXTURE_2D, 0);
  leafTextureWidth_ = width;
  leafCount_ = count;
  ++contentVersion_;
  ++splatsVersion_;
}

void ViewportRenderer::drawLines(const std::vector<LineVertex>& vertices, GLenum mode) {
  if (vertices.empty()) return;
  glBindVertexArray(lineVao_);
  glBindBuffer(GL_ARRAY_BUFFER, lineBuffer_);
  if (vertices.size() > lineCapacity_) {
    lineCapacity_ = vertices.size() * 2;
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(lineCapacity_ * sizeof(LineVertex)), nullptr,
                 GL_STREAM_DRAW);
  }
  glBufferSubData(GL_ARRAY_BUFFER, 0, GLsizeiptr(vertices.size() * sizeof(LineVertex)),
                  vertices.data());
  glDrawArrays(mode, 0, GLsizei(vertices.size()));
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}

void ViewportRenderer::drawBackground(const ViewportFrame& f) {
  glViewport(f.x, f.y, f.width, f.height);
  glEnable(GL_SCISSOR_TEST);
  glScissor(f.x, f.y, f.width, f.height);
  glClearColor(0.16f, 0.17f, 0.19f, 1.0f);
  glClearDepth(1.0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glDisable(GL_CULL_FACE);
  glDisable(GL_BLEND);
  glDisable(GL_DEPTH_TEST);  // the gradient writes no depth
  backgroundProgram_.use();
  backgroundProgram_.set("bottomColor", glm::vec3(0.13f, 0.14f, 0.16f));
  backgroundProgram_.set("topColor", glm::vec3(0.30f, 0.32f, 0.36f));
  glBindVertexArray(emptyVao_);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  if (!backdrop_.empty()) {  // setBackdrop: no depth, so everything drawn next covers it
    lineProgram_.use();
    lineProgram_.set("viewProjection", glm::mat4(f.viewProjection));
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    drawLines(backdrop_, GL_LINES);
    glDisable(GL_BLEND);
  }
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
}

void ViewportRenderer::drawSplatRange(const ViewportFrame& f, size_t first, size_t count,
                                      size_t stride, float radius, SplatDraw what) {
  if (count == 0) return;
  collectTiming();
  // The coarse image of a moving view: quads, whose large discs points would draw only where
  // their centres lie in the view (a point is clipped by its vertex).
  SplatKind kind = what == SplatDraw::Coarse ? SplatKind::Quads : preferredKind(f, radius);
  const bool whole = what == SplatDraw::WholeImage;
  const bool automatic = primitive_ == SplatPrimitive::Automatic && timersTrusted_;
  // Automatic tries a kind on whole images only, where it is timed: a share of an image drawn
  // over frames goes as quads until every kind that fits has a time. (Timing shares instead was
  // tried: a compute draw's fixed cost, its images cleared and the view's pixels resolved, made
  // shares of 30,000 splats time 6.5-19 ns a splat on the H200 against 0.4-1.0 for whole
  // images, and Automatic then kept the slower kinds.)
  if (!whole && automatic && !everyFittingKindTimed(f, radius)) kind = SplatKind::Quads;
  if (whole && automatic && everyFittingKindTimed(f, radius) &&
      timing_[int(kind)].reads >= retryAfterReads_) {
    // Another kind again, once every kRetryEvery times of the one drawn: the one timed least.
    const int drawnReads = timing_[int(kind)].reads;
    std::optional<SplatKind> retry;
    // Not a kind this draw would make a hitch of: where a whole image was allowed for the
    // cheapest kind's time (a moving view, drawCached), a dearer kind may take many frames.
    for (int k = 0; k < kSplatKinds; ++k)
      if (SplatKind(k) != kind && kindFits(f, radius, SplatKind(k)) && !timing_[k].pending &&
          double(count) * timing_[k].nsPerSplat * 1e-6 <= kTargetFrameMs &&
          (!retry || timing_[k].reads < timing_[int(*retry)].reads))
        retry = SplatKind(k);
    if (retry) {
      kind = *retry;
      retryAfterReads_ = drawnReads + kRetryEvery;
    }
  }
  drawSplatsAs(f, kind, first, count, stride, radius, whole ? timerFor(kind, count) : nullptr);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  glBindTexture(GL_TEXTURE_2D, 0);
}

ViewportRenderer::KindTiming* ViewportRenderer::timerFor(SplatKind kind, size_t count) {
  // Timed: whole images' draws (every splat of a level from the buffer's start; draws of other
  // ranges, such as the refinement's shares, hold other mixes of splats far apart and close
  // together, which cost differently, and a compute draw's fixed cost weighs on a small one),
  // of kTimedDrawSplats or more, one a kind at a time.
  KindTiming& t = timing_[int(kind)];
  if (t.pending || count < kTimedDrawSplats) return nullptr;
  t.splats = count;
  t.pending = true;
  return &t;
}

void ViewportRenderer::drawSplatsAs(const ViewportFrame& f, SplatKind kind, size_t first,
                                    size_t count, size_t stride, float radius, KindTiming* timer) {
  if (count == 0) {
    if (timer) timer->pending = false;
    return;
  }
  if (kind == SplatKind::Compute) {
    drawSplatsComputed(f, first, count, stride, radius, timer);
    return;
  }
  const bool points = kind == SplatKind::Points;
  const GlProgram& program = points ? pointProgram_ : surfelProgram_;
  useSurfelProgram(program, f);
  program.set("keyLight", cameraLight(f, -0.5, 0.8, 0.6));
  program.set("fillLight", cameraLight(f, 0.7, -0.3, 0.4));
  program.set("ghostColor", glm::vec4(0.0f));
  program.set("splatRadius", radius);
  GLint viewport[4] = {0, 0, 1, 1};
  GLint scissorBox[4] = {0, 0, 1, 1};
  GLboolean scissorOn = GL_FALSE;
  if (points) {
    // A point is clipped by its vertex: one whose centre lies just outside the view would leave
    // its visible part undrawn. The viewport grows by half the largest sprite on each side, the
    // projection shrinks to match (the view maps to the same pixels), and the scissor keeps the
    // drawing to the view.
    glGetIntegerv(GL_VIEWPORT, viewport);
    glGetIntegerv(GL_SCISSOR_BOX, scissorBox);
    scissorOn = glIsEnabled(GL_SCISSOR_TEST);
    GLint maxDims[2] = {16384, 16384};
    glGetIntegerv(GL_MAX_VIEWPORT_DIMS, maxDims);
    const double bound = std::min(spriteBoundPx(f, radius), double(maxPointSize_));
    GLint margin = GLint(std::ceil(0.5 * bound)) + 1;
    if (viewport[2] + 2 * margin > maxDims[0] || viewport[3] + 2 * margin > maxDims[1]) margin = 0;
    glm::dmat4 widen(1.0);
    widen[0][0] = double(viewport[2]) / double(viewport[2] + 2 * margin);
    widen[1][1] = double(viewport[3]) / double(viewport[3] + 2 * margin);
    const glm::dmat4 viewProjection = widen * f.viewProjection;
    if (!scissorOn) {
      glEnable(GL_SCISSOR_TEST);
      glScissor(viewport[0], viewport[1], viewport[2], viewport[3]);
    }
    glViewport(viewport[0] - margin, viewport[1] - margin, viewport[2] + 2 * margin,
               viewport[3] + 2 * margin);
    program.set("viewProjection", glm::mat4(viewProjection));
    program.set("viewportRect",
                glm::vec4(float(viewport[0] - margin), float(viewport[1] - margin),
                          float(viewport[2] + 2 * margin), float(viewport[3] + 2 * margin)));
    program.set("maxPointSize", maxPointSize_);
    setViewRays(program, viewProjection);
    glBindVertexArray(pointVao_);
  }
  glBindBuffer(GL_ARRAY_BUFFER, splatBuffer_);
  // Within the driver's limit (callers keep to it): a refused stride would leave the last
  // pointers in place, and the draw would read what they point at.
  assert(stride * sizeof(Splat) <= size_t(maxAttribStride_));
  const GLsizei bytes = GLsizei(stride * sizeof(Splat));
  const size_t base = first * sizeof(Splat);
  pointSplatAttributes(bytes, base);
  if (timer) glBeginQuery(GL_TIME_ELAPSED, timer->query);
  if (points) {
    glDrawArrays(GL_POINTS, 0, GLsizei(count));
    drawn_[int(SplatKind::Points)] += count;
    glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
    if (!scissorOn) {
      glScissor(scissorBox[0], scissorBox[1], scissorBox[2], scissorBox[3]);
      glDisable(GL_SCISSOR_TEST);
    }
  } else {
    glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, GLsizei(count));
    drawn_[int(SplatKind::Quads)] += count;
    // Back to every splat from the first, as pick() and the CUDA-GL copier expect.
    if (first != 0 || stride != 1) pointSplatAttributes(sizeof(Splat), 0);
  }
  if (timer) glEndQuery(GL_TIME_ELAPSED);
}

void ViewportRenderer::drawSplatsComputed(const ViewportFrame& f, size_t first, size_t count,
                                          size_t stride, float radius, KindTiming* timer) {
  GLint viewport[4] = {0, 0, 1, 1};
  glGetIntegerv(GL_VIEWPORT, viewport);
  const int width = std::max(1, viewport[2]), height = std::max(1, viewport[3]);
  if (computeWidth_ != width || computeHeight_ != height) {
    for (GLuint* texture : {&computeDepth_, &computeIds_}) {
      if (*texture) glDeleteTextures(1, texture);
      glGenTextures(1, texture);
      glBindTexture(GL_TEXTURE_2D, *texture);
      glTexStorage2D(GL_TEXTURE_2D, 1, GL_R32UI, width, height);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    }
    glBindTexture(GL_TEXTURE_2D, 0);
    computeWidth_ = width;
    computeHeight_ = height;
  }
  if (timer) glBeginQuery(GL_TIME_ELAPSED, timer->query);
  const GLuint none = 0xffffffffu;
  glClearTexImage(computeDepth_, 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &none);
  glClearTexImage(computeIds_, 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &none);
  glBindBufferRange(GL_SHADER_STORAGE_BUFFER, 0, splatBuffer_, 0,
                    GLsizeiptr(std::max<size_t>(1, splatCount_) * sizeof(Splat)));
  glBindImageTexture(0, computeDepth_, 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
  glBindImageTexture(1, computeIds_, 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
  // What the splats' discs, culling and colours read, in both programs: surfel.vert's uniforms
  // (and the leaf texture on unit 0), the disc's radius and the view rays.
  auto setView = [&](const GlProgram& program) {
    useSurfelProgram(program, f);
    program.set("splatRadius", radius);
    setViewRays(program, f.viewProjection);
  };
  setView(computeProgram_);
  computeProgram_.set("viewSize", glm::ivec2(width, height));
  computeProgram_.set("maxFootprint", int(kMaxComputeFootprintPx) + 2);
  computeProgram_.set("splatStride", unsigned(stride));
  // At most kMaxGroups groups a dispatch (GL guarantees 65,535 along x).
  constexpr size_t kGroupSize = 64, kMaxGroups = 65535;
  for (int pass = 0; pass < 2; ++pass) {
    computeProgram_.set("pass", pass);
    for (size_t done = 0; done < count; done += kGroupSize * kMaxGroups) {
      const size_t n = std::min(count - done, kGroupSize * kMaxGroups);
      computeProgram_.set("firstSplat", unsigned(first + done * stride));
      computeProgram_.set("splatCount", unsigned(n));
      glDispatchCompute(GLuint((n + kGroupSize - 1) / kGroupSize), 1, 1);
    }
    // Pass 1 reads pass 0's depths; the resolve fetches both images; the next draw's clears
    // follow these passes' image writes.
    glMemoryBarrier(pass == 0 ? GL_SHADER_IMAGE_ACCESS_BARRIER_BIT
                              : GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
  }
  // Each pixel's splat lit and written with its depth, through the depth test.
  setView(resolveProgram_);
  resolveProgram_.set("keyLight", cameraLight(f, -0.5, 0.8, 0.6));
  resolveProgram_.set("fillLight", cameraLight(f, 0.7, -0.3, 0.4));
  resolveProgram_.set("ghostColor", glm::vec4(0.0f));
  resolveProgram_.set("viewportRect", glm::vec4(float(viewport[0]), float(viewport[1]),
                                                float(width), float(height)));
  resolveProgram_.set("depthImage", 1);
  resolveProgram_.set("idImage", 2);
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_2D, computeDepth_);
  glActiveTexture(GL_TEXTURE2);
  glBindTexture(GL_TEXTURE_2D, computeIds_);
  glActiveTexture(GL_TEXTURE0);
  glBindVertexArray(emptyVao_);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  if (timer) glEndQuery(GL_TIME_ELAPSED);
  drawn_[int(SplatKind::Compute)] += count;
  glActiveTexture(GL_TEXTURE2);
  glBindTexture(GL_TEXTURE_2D, 0);
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_2D, 0);
  glActiveTexture(GL_TEXTURE0);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, 0);
  glBindVertexArray(surfelVao_);
}

void ViewportRenderer::drawGhosts(const ViewportFrame& f) {
  if (ghostCount() == 0) return;
  useSurfelProgram(surfelProgram_, f);
  surfelProgram_.set("keyLight", cameraLight(f, -0.5, 0.8, 0.6));
  surfelProgram_.set("fillLight", cameraLight(f, 0.7, -0.3, 0.4));
  // Over the result: translucent, hidden where the result is in front.
  const glm::vec4 tints[2] = {glm::vec4(1.0f, 0.32f, 0.26f, 0.3f),
                              glm::vec4(0.62f, 0.45f, 1.0f, 0.3f)};
  glEnable(GL_BLEND);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  glDepthMask(GL_FALSE);
  for (int i = 0; i < 2; ++i) {
    if (ghosts_[i].count == 0) continue;
    surfelProgram_.set("ghostColor", tints[i]);
    glBindVertexArray(ghosts_[i].vao);
    glBindBuffer(GL_ARRAY_BUFFER, ghosts_[i].buffer);
    // Each ghost's run with its own lattice's splat size (a ghost carried from a coarse pass
    // beside one of the fine lattice: the fine one was drawn as scattered dots, or the coarse
    // one as blobs); the runs' splats start where the attributes point.
    size_t first = 0;
    for (const GhostRun& run : ghostRuns_[i]) {
      if (run.count == 0) continue;
      surfelProgram_.set("cellSize", float(run.cellSize > 0.0 ? run.cellSize : cellSize_));
      pointSplatAttributes(sizeof(Splat), first * sizeof(Splat));
      glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, GLsizei(run.count));
      first += run.count;
    }
    pointSplatAttributes(sizeof(Splat), 0);
  }
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  surfelProgram_.set("ghostColor", glm::vec4(0.0f));
  surfelProgram_.set("cellSize", float(cellSize_));
  glDepthMask(GL_TRUE);
  glDisable(GL_BLEND);
  glBindTexture(GL_TEXTURE_2D, 0);
}

void ViewportRenderer::drawOverlay(const ViewportFrame& f, const std::vector<LineVertex>& overlay,
                                   const std::vector<LineVertex>& overlayTriangles,
                                   const PixelRect& clip) {
  glViewport(f.x, f.y, f.width, f.height);
  glEnable(GL_SCISSOR_TEST);
  const PixelRect view{f.x, f.y, f.x + f.width, f.y + f.height};
  const PixelRect r = clip.empty() ? view : clip.intersect(view);
  glScissor(r.x0, r.y0, std::max(0, r.x1 - r.x0), std::max(0, r.y1 - r.y0));
  lineProgram_.use();
  lineProgram_.set("viewProjection", glm::mat4(f.viewProjection));
  glEnable(GL_BLEND);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  glDisable(GL_DEPTH_TEST);
  drawLines(overlayTriangles, GL_TRIANGLES);
  drawLines(overlay, GL_LINES);
  glBindVertexArray(0);
  glUseProgram(0);
  glDisable(GL_SCISSOR_TEST);
}

namespace {

// FNV-1a of `bytes` bytes at `data`, continuing from `h` (the keys of what a view shows).
uint64_t fnv1a(uint64_t h, const void* data, size_t bytes) {
  const auto* p = static_cast<const uint8_t*>(data);
  for (size_t i = 0; i < bytes; ++i) h = (h ^ p[i]) * 1099511628211ull;
  return h;
}

}  // namespace

void ViewportRenderer::draw(const ViewportFrame& f, const std::vector<LineVertex>& lines,
                            const std::vector<LineVertex>& overlay,
                            const std::vector<LineVertex>& overlayTriangles) {
  windowKey_ = 0;  // drawn another way than drawCached's
  drawBackground(f);
  if (splatCount_ > 0) {
    const int level = detailLevel(f);
    drawSplatRange(f, 0, levelEnd(level), 1, float(1 << level), SplatDraw::WholeImage);
    drawnLevel_ = level;
  }
  drawGhosts(f);
  lineProgram_.use();
  lineProgram_.set("viewProjection", glm::mat4(f.viewProjection));
  glEnable(GL_BLEND);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  glDepthMask(GL_FALSE);
  drawLines(lines, GL_LINES);
  glDepthMask(GL_TRUE);
  drawOverlay(f, overlay, overlayTriangles);
  glDisable(GL_DEPTH_TEST);
}

uint64_t ViewportRenderer::windowKeyFor(const ViewportFrame& f,
                                        const std::vector<LineVertex>& lines,
                                        const std::vector<LineVertex>& overlay,
                                        const std::vector<LineVertex>& overlayTriangles) const {
  uint64_t h = viewKey(f, lines) ^ (contentVersion_ * 0x9e3779b97f4a7c15ull);
  for (const std::vector<LineVertex>* v : {&overlay, &overlayTriangles}) {
    const size_t count = v->size();
    h = fnv1a(fnv1a(h, v->data(), count * sizeof(LineVertex)), &count, sizeof(count));
  }
  return h | 1;
}

bool ViewportRenderer::windowShows(const ViewportFrame& f, const std::vector<LineVertex>& lines,
                                   const std::vector<LineVertex>& overlay,
                                   const std::vector<LineVertex>& overlayTriangles) const {
  return windowKey_ != 0 && !refining_ &&
         windowKey_ == windowKeyFor(f, lines, overlay, overlayTriangles);
}

void ViewportRenderer::repaintWindow(const ViewportFrame& f, const std::vector<LineVertex>& overlay,
                                     const std::vector<LineVertex>& overlayTriangles,
                                     const PixelRect& clip) {
  const PixelRect r = clip.intersect({f.x, f.y, f.x + f.width, f.y + f.height});
  if (!shown_ || r.empty()) return;
  GLint window = 0;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &window);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, shown_->framebuffer());
  glEnable(GL_SCISSOR_TEST);  // a blit is scissored too
  glScissor(r.x0, r.y0, r.x1 - r.x0, r.y1 - r.y0);
  glBlitFramebuffer(0, 0, shown_->width(), shown_->height(), f.x, f.y, f.x + f.width,
                    f.y + f.height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, GLuint(window));
  drawOverlay(f, overlay, overlayTriangles, r);
  glDisable(GL_DEPTH_TEST);
}

void ViewportRenderer::followFrameTime(double lastFrameMs) {
  // The share follows the frame time: scaled by target / time from the splats the last frame
  // drew, when they were at least half a share (a small draw, such as a coarse result of a few
  // thousand splats, costs mostly the frame's base and says little about splats). An upload in
  // the last frame is not drawing.
  const double drawMs = lastFrameMs - uploadMsLastFrame_;
  uploadMsLastFrame_ = uploadMsThisFrame_;
  uploadMsThisFrame_ = 0.0;
  // Two shares, one per kind of drawing, since a splat drawn at full resolution costs far more
  // than one of the coarse image: mixing them made the share swing between a cheap coarse frame
  // and a full one many times dearer.
  if (drawMs > 0.0 && drewSplatsLastFrame_ > 0) {
    const double factor = std::clamp(kTargetFrameMs / drawMs, 0.5, 1.5);
    size_t& share = lastDrawFull_ ? fullShare_ : splatsPerFrame_;
    // A coarse frame over the target at the fewest splats is bound by the pixels it fills.
    if (!lastDrawFull_ && share <= kMinShare && drawMs > kTargetFrameMs) coarseShrink_ = 4;
    // Back to half only where a half image would fit even if the whole frame were pixels to
    // fill (4 times as many): otherwise it would turn again within frames.
    if (!lastDrawFull_ && coarseShrink_ > 2 && drawMs < 0.25 * kTargetFrameMs) coarseShrink_ = 2;
    if (drewSplatsLastFrame_ >= share / 2)
      share = std::clamp<size_t>(size_t(double(drewSplatsLastFrame_) * factor), kMinShare,
                                 size_t(1) << 26);
  }
  drewSplatsLastFrame_ = 0;
}

void ViewportRenderer::skipFrame(double lastFrameMs) {
  followFrameTime(lastFrameMs);  // the last frame may have drawn: its time counts
}

uint64_t ViewportRenderer::viewKey(const ViewportFrame& f,
                                   const std::vector<LineVertex>& lines) const {
  uint64_t h = 1469598103934665603ull;
  auto mix = [&](const void* data, size_t bytes) { h = fnv1a(h, data, bytes); };
  mix(&f.viewProjection, sizeof(f.viewProjection));
  mix(&f.eye, sizeof(f.eye));
  const int ints[6] = {f.x, f.y, f.width, f.height, f.ortho ? 1 : 0, f.sectionOn ? 1 : 0};
  mix(ints, sizeof(ints));
  mix(&f.sectionNormal, sizeof(f.sectionNormal));
  mix(&f.sectionOffset, sizeof(f.sectionOffset));
  if (!lines.empty()) mix(lines.data(), lines.size() * sizeof(LineVertex));
  if (!backdrop_.empty()) mix(backdrop_.data(), backdrop_.size() * sizeof(LineVertex));
  return h | 1;  // never 0 (nothing shown)
}

namespace {

size_t nextPrime(size_t n) {
  if (n <= 2) return 2;
  for (size_t k = n | 1;; k += 2) {
    bool prime = true;
    for (size_t d = 3; d * d <= k && prime; d += 2) prime = k % d != 0;
    if (prime) return k;
  }
}

// The largest prime not above n (1 for n < 2).
size_t largestPrimeAtMost(size_t n) {
  for (size_t k = n; k >= 2; --k) {
    bool prime = true;
    for (size_t d = 2; d * d <= k && prime; ++d) prime = k % d != 0;
    if (prime) return k;
  }
  return 1;
}

// Makes `target` a width x height off-screen image (kept when it already is one).
void ensureTarget(std::unique_ptr<RenderTarget>* target, int width, int height) {
  if (*target && (*target)->width() == width && (*target)->height() == height) return;
  target->reset();
  *target = std::make_unique<RenderTarget>(width, height);
}

}  // namespace

void ViewportRenderer::drawCached(const ViewportFrame& f, const std::vector<LineVertex>& lines,
                                  const std::vector<LineVertex>& overlay,
                                  const std::vector<LineVertex>& overlayTriangles,
                                  double lastFrameMs) {
  followFrameTime(lastFrameMs);
  GLint window = 0;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &window);
  // The image's own frame: the same view, at the image's origin.
  ViewportFrame local = f;
  local.x = local.y = 0;
  // What is shown: the view (camera, size, section, lines) and the content (splats, colours,
  // ghosts). A new content seen from a view at rest (an edit's result) is drawn whole at once
  // when that fits about two and a half frames' share (a fast GPU: one frame from the edit to
  // the screen); a moving view keeps to the share.
  const uint64_t view = viewKey(local, lines);
  const bool viewMoved = view != shownView_;
  const uint64_t key = view ^ (contentVersion_ * 0x9e3779b97f4a7c15ull);
  shownView_ = view;
  size_t allowed = viewMoved ? fullShare_ : fullShare_ * 5 / 2;
  // Where the GPU's measured time per splat says that a whole image of the view's level costs
  // at most half the frame's target, it is drawn whole, a moving view's too, whatever share the
  // frames have taught so far (which a view in motion, drawing coarse images, never raises).
  if (timersTrusted_) {
    const double ns = timing_[int(preferredKind(local, float(1 << detailLevel(local))))].nsPerSplat;
    if (ns > 0.0) allowed = std::max(allowed, size_t(0.5 * kTargetFrameMs * 1e6 / ns));
  }
  const RenderTarget* show = nullptr;
  bool showCoarse = false;

  auto drawLinesInto = [&](const ViewportFrame& frame) {
    lineProgram_.use();
    lineProgram_.set("viewProjection", glm::mat4(frame.viewProjection));
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    glDepthMask(GL_FALSE);
    drawLines(lines, GL_LINES);
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
  };

  // The image of the splats alone (no ghosts, no lines), kept when one is complete
  // (copyImage: colour and depth): a change of the lines or the ghosts alone (a measurement
  // placed, a selection's box, a ghost finished after its result) draws them over a copy of it,
  // instead of all the splats again (a software GL driver refined the whole image again).
  const uint64_t plainKey =
      viewKey(local, {}) ^ (splatsVersion_ * 0x9e3779b97f4a7c15ull) ^ 0x5bd1e995ull;
  auto copyImage = [&](const RenderTarget& from, RenderTarget& to) {
    glBindFramebuffer(GL_READ_FRAMEBUFFER, from.framebuffer());
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, to.framebuffer());
    glDisable(GL_SCISSOR_TEST);
    glBlitFramebuffer(0, 0, from.width(), from.height(), 0, 0, to.width(), to.height(),
                      GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT, GL_NEAREST);
  };
  auto keepPlain = [&](RenderTarget& complete) {
    ensureTarget(&plain_, f.width, f.height);
    copyImage(complete, *plain_);
    plainKey_ = plainKey;
    complete.bind();
  };

  // The lines or the ghosts changed while the image of the same splats is being built: the
  // build goes on (it draws them when complete) instead of starting again from a coarse image.
  if (key != shownKey_ && refining_ && plainKey == buildingPlainKey_) shownKey_ = key;
  if (key != shownKey_ && !refining_ && plain_ && plainKey == plainKey_ && shown_ &&
      plain_->width() == f.width && plain_->height() == f.height) {
    // Only the lines or the ghosts changed: the complete image of the splats, and over it the
    // ghosts (a few splats: all of them) and the lines.
    shownKey_ = key;
    copyImage(*plain_, *shown_);
    shown_->bind();
    glViewport(0, 0, f.width, f.height);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    drawGhosts(local);
    drawLinesInto(local);
    drewSplatsLastFrame_ = 0;
    show = shown_.get();
  } else if (key != shownKey_ && !(refining_ && plainKey == buildingPlainKey_)) {
    shownKey_ = key;
    buildingPlainKey_ = plainKey;
    buildDone_ = 0;
    // The full image's splats: those of the level of detail the view needs.
    buildLevel_ = detailLevel(local);
    // A new content (an edit's result) seen from a view at rest: the first image from coarser
    // levels where the view's level costs more than kFirstImageMs (firstImageLevel).
    const int firstLevel = viewMoved ? buildLevel_ : firstImageLevel(local);
    const size_t first = levelEnd(firstLevel);
    // The same parts at another resolution (holdShownImage), at rest, too many splats for one
    // frame: the image shown stays while the new one is built.
    const bool hold = holdShownImage_ && !viewMoved && shown_ && (!refining_ || refineOverShown_) &&
                      shown_->width() == f.width && shown_->height() == f.height &&
                      levelEnd(buildLevel_) > allowed;
    holdShownImage_ = false;
    if (hold) {
      refining_ = true;
      refineOverShown_ = true;
      drewSplatsLastFrame_ = 0;
      show = shown_.get();
    } else if (first <= allowed) {
      // The full image at once, or a first image at a coarser level at full resolution (discs
      // as wide as their rays are apart) refined to the view's level over the next frames.
      ensureTarget(&shown_, f.width, f.height);
      shown_->bind();
      drawBackground(local);
      drawSplatRange(local, 0, first, 1, float(1 << firstLevel), SplatDraw::WholeImage);
      // Kept for a change of the lines or ghosts alone (an orbit's frames too: the image they
      // stop on is the one a ghost or a selection changes next; a copy on the GPU).
      if (firstLevel == buildLevel_) keepPlain(*shown_);
      drawGhosts(local);
      drawLinesInto(local);
      refining_ = firstLevel != buildLevel_;
      refineOverShown_ = refining_;
      drawnLevel_ = firstLevel;
      drewSplatsLastFrame_ = first;
      lastDrawFull_ = true;
      show = shown_.get();
    } else {
      // A share of the splats at reduced resolution now; the full image over the next frames.
      // Half resolution; a quarter when the share is so small that each splat stands for many,
      // or when the pixels filled set the cost (coarseShrink_): a software GL driver.
      // Every k-th splat of a level, k no larger than the driver's largest attribute stride
      // allows (a larger one is refused, and the draw would read other splats or none): from a
      // coarser level where the view's would need a larger k.
      const size_t maxStride = std::max<size_t>(1, size_t(maxAttribStride_) / sizeof(Splat));
      int coarseLevel = buildLevel_;
      while (coarseLevel + 1 < kSplatLevels && shape_.levels.end[coarseLevel + 1] > 0 &&
             levelEnd(coarseLevel) > splatsPerFrame_ * maxStride)
        ++coarseLevel;
      const size_t pool = levelEnd(coarseLevel);
      const size_t ratio = (pool + splatsPerFrame_ - 1) / splatsPerFrame_;
      const size_t stride =
          ratio <= 1 ? 1 : std::min(nextPrime(ratio), largestPrimeAtMost(maxStride));
      const int shrink = stride > 64 ? 4 : coarseShrink_;
      ViewportFrame half = local;
      half.width = std::max(1, f.width / shrink);
      half.height = std::max(1, f.height / shrink);
      ensureTarget(&coarse_, half.width, half.height);
      coarse_->bind();
      drawBackground(half);
      const size_t drawn = (pool + stride - 1) / stride;
      // Discs a little larger than the sampling's spacing: no holes.
      drawSplatRange(half, 0, drawn, stride,
                     1.25f * float(1 << coarseLevel) * float(std::sqrt(double(stride))),
                     SplatDraw::Coarse);
      drawGhosts(half);
      drawLinesInto(half);
      refining_ = true;
      refineOverShown_ = false;
      drewSplatsLastFrame_ = drawn;
      lastDrawFull_ = false;
      show = coarse_.get();
      showCoarse = true;
    }
  } else if (refining_) {
    ensureTarget(&building_, f.width, f.height);
    building_->bind();
    if (buildDone_ == 0) drawBackground(local);
    glViewport(0, 0, f.width, f.height);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    const size_t full = levelEnd(buildLevel_);
    const size_t rest = full - std::min(full, buildDone_);
    size_t count = std::min(fullShare_, rest);
    SplatDraw what = SplatDraw::Share;
    // Automatic learns a kind's cost from whole draws only (drawSplatRange): while a kind has
    // no time yet, the rest of the image is drawn at once, timed, as that kind (once a kind, at
    // most kCalibrationSplats), so that a view whose images are drawn a share a frame learns
    // them too.
    const float radius = float(1 << buildLevel_);
    if (primitive_ == SplatPrimitive::Automatic && timersTrusted_ &&
        !everyFittingKindTimed(local, radius) && rest >= kTimedDrawSplats &&
        rest <= kCalibrationSplats) {
      count = rest;
      what = SplatDraw::WholeImage;
    }
    drawSplatRange(local, buildDone_, count, 1, radius, what);
    buildDone_ += count;
    // A calibration's draw says nothing of the share a frame (it may be far larger): the share
    // stays as it is.
    drewSplatsLastFrame_ = what == SplatDraw::WholeImage ? 0 : count;
    lastDrawFull_ = true;
    if (buildDone_ >= full) {
      keepPlain(*building_);
      drawGhosts(local);
      drawLinesInto(local);
      std::swap(shown_, building_);
      refining_ = false;
      drawnLevel_ = buildLevel_;
      show = shown_.get();
    } else if (refineOverShown_) {
      show = shown_.get();  // the first image, until the view's level is complete
    } else {
      show = coarse_.get();
      showCoarse = true;
    }
  } else {
    show = shown_.get();
  }

  // Into the window: the image, then the overlay.
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, GLuint(window));
  if (show) {
    glBindFramebuffer(GL_READ_FRAMEBUFFER, show->framebuffer());
    glDisable(GL_SCISSOR_TEST);
    glBlitFramebuffer(0, 0, show->width(), show->height(), f.x, f.y, f.x + f.width, f.y + f.height,
                      GL_COLOR_BUFFER_BIT, showCoarse ? GL_LINEAR : GL_NEAREST);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, GLuint(window));
  }
  drawOverlay(f, overlay, overlayTriangles);
  glDisable(GL_DEPTH_TEST);
  // The window now holds the complete image (until the view or the content changes), or one
  // that a later frame replaces.
  windowKey_ = show != nullptr && show == shown_.get() && !refining_ && !showCoarse
                   ? windowKeyFor(f, lines, overlay, overlayTriangles)
                   : 0;
}

void ViewportRenderer::useSurfelProgram(const GlProgram& program, const ViewportFrame& f) {
  program.use();
  program.set("viewProjection", glm::mat4(f.viewProjection));
  program.set("eye", glm::vec3(f.eye));
  program.set("viewForward", glm::vec3(f.forward));
  program.set("ortho", f.ortho ? 1 : 0);
  program.set("cellSize", float(cellSize_));
  program.set("splatRadius", 1.0f);
  program.set("leafTexture", 0);
  program.set("leafTextureWidth", leafTextureWidth_);
  program.set("leafCount", leafCount_);
  program.set("sectionOn", f.sectionOn ? 1 : 0);
  program.set("sectionPlane", glm::vec4(glm::vec3(f.sectionNormal), float(f.sectionOffset)));
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, leafTexture_);
  glBindVertexArray(surfelVao_);
}

bool ViewportRenderer::drawPickIds(const ViewportFrame& f, int x, int y, int width, int height) {
  if (!pickFramebuffer_ || pickWidth_ != f.width || pickHeight_ != f.height) {
    if (!pickFramebuffer_) {
      glGenFramebuffers(1, &pickFramebuffer_);
      glGenRenderbuffers(1, &pickIds_);
      glGenRenderbuffers(1, &pickDepth_);
    }
    glBindRenderbuffer(GL_RENDERBUFFER, pickIds_);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_R32UI, f.width, f.height);
    glBindRenderbuffer(GL_RENDERBUFFER, pickDepth_);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, f.width, f.height);
    glBindRenderbuffer(GL_RENDERBUFFER, 0);
    glBindFramebuffer(GL_FRAMEBUFFER, pickFramebuffer_);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, pickIds_);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, pickDepth_);
    pickWidth_ = f.width;
    pickHeight_ = f.height;
  }
  glBindFramebuffer(GL_FRAMEBUFFER, pickFramebuffer_);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) return false;
  glViewport(0, 0, f.width, f.height);
  glEnable(GL_SCISSOR_TEST);
  glScissor(x, y, width, height);  // only the pixels read are drawn
  const GLuint none[4] = {0, 0, 0, 0};
  glClearBufferuiv(GL_COLOR, 0, none);
  glClearDepth(1.0);
  glClear(GL_DEPTH_BUFFER_BIT);
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  useSurfelProgram(pickProgram_, f);
  glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, GLsizei(splatCount_));
  glBindTexture(GL_TEXTURE_2D, 0);
  glBindVertexArray(0);
  glUseProgram(0);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadBuffer(GL_COLOR_ATTACHMENT0);
  return true;
}

std::vector<uint32_t> ViewportRenderer::pickLeaves(const ViewportFrame& f, int x0, int y0, int x1,
                                                   int y1) {
  const int left = std::clamp(std::min(x0, x1), 0, f.width);
  const int right = std::clamp(std::max(x0, x1), 0, f.width);
  const int bottom = std::clamp(std::min(y0, y1), 0, f.height);
  const int top = std::clamp(std::max(y0, y1), 0, f.height);
  x0 = left, x1 = right, y0 = bottom, y1 = top;
  std::vector<uint32_t> leaves;
  if (splatCount_ == 0 || x1 <= x0 || y1 <= y0) return leaves;
  GLint previousFramebuffer = 0, previousViewport[4] = {0, 0, 1, 1};
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &previousFramebuffer);
  glGetIntegerv(GL_VIEWPORT, previousViewport);
  if (drawPickIds(f, x0, y0, x1 - x0, y1 - y0)) {
    std::vector<GLuint> ids(size_t(x1 - x0) * size_t(y1 - y0));
    glReadPixels(x0, y0, x1 - x0, y1 - y0, GL_RED_INTEGER, GL_UNSIGNED_INT, ids.data());
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
    for (GLuint id : ids)
      if (id > 0) leaves.push_back((id & 0x7fffffffu) - 1);
    std::sort(leaves.begin(), leaves.end());
    leaves.erase(std::unique(leaves.begin(), leaves.end()), leaves.end());
  }
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_DEPTH_TEST);
  glBindFramebuffer(GL_FRAMEBUFFER, GLuint(previousFramebuffer));
  glViewport(previousViewport[0], previousViewport[1], previousViewport[2], previousViewport[3]);
  return leaves;
}

bool ViewportRenderer::readPickWindow(const ViewportFrame& f, int x0, int y0, int w, int h,
                                      PickWindow* out) {
  if (splatCount_ == 0 || w <= 0 || h <= 0) return false;
  GLint previousFramebuffer = 0, previousViewport[4] = {0, 0, 1, 1};
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &previousFramebuffer);
  glGetIntegerv(GL_VIEWPORT, previousViewport);
  const bool drawn = drawPickIds(f, x0, y0, w, h);
  if (drawn) {
    out->x0 = x0, out->y0 = y0, out->width = w, out->height = h;
    out->ids.assign(size_t(w) * size_t(h), 0);
    out->depths.assign(out->ids.size(), 1.0f);
    glReadPixels(x0, y0, w, h, GL_RED_INTEGER, GL_UNSIGNED_INT, out->ids.data());
    glReadPixels(x0, y0, w, h, GL_DEPTH_COMPONENT, GL_FLOAT, out->depths.data());
    out->toWorld = glm::inverse(f.viewProjection);
    out->frameWidth = f.width, out->frameHeight = f.height;
    out->sectionNormal = f.sectionNormal, out->sectionOffset = f.sectionOffset;
  }
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_DEPTH_TEST);
  glBindFramebuffer(GL_FRAMEBUFFER, GLuint(previousFramebuffer));
  glViewport(previousViewport[0], previousViewport[1], previousViewport[2], previousViewport[3]);
  return drawn;
}

glm::dvec3 ViewportRenderer::PickWindow::unproject(int x, int y, double ndcDepth) const {
  const glm::dvec4 ndc((x + 0.5) / frameWidth * 2.0 - 1.0, (y + 0.5) / frameHeight * 2.0 - 1.0,
                       ndcDepth, 1.0);
  const glm::dvec4 world = toWorld * ndc;
  return glm::dvec3(world) / world.w;
}

std::optional<glm::dvec3> ViewportRenderer::PickWindow::pointAt(int x, int y) const {
  const uint32_t id = idAt(x, y);
  if (id == 0) return std::nullopt;
  if ((id & 0x80000000u) == 0) return unproject(x, y, double(depths[index(x, y)]) * 2.0 - 1.0);
  const glm::dvec3 a = unproject(x, y, -1.0), b = unproject(x, y, 1.0);
  if (std::fabs(glm::dot(sectionNormal, b - a)) <= 1e-12)
    return unproject(x, y, double(depths[index(x, y)]) * 2.0 - 1.0);
  return onSectionPlane(x, y);  // a cap: where the pixel's ray meets the section plane
}

glm::dvec3 ViewportRenderer::PickWindow::onSectionPlane(int x, int y) const {
  const glm::dvec3 a = unproject(x, y, -1.0), b = unproject(x, y, 1.0);
  const double denom = glm::dot(sectionNormal, b - a);
  if (std::fabs(denom) <= 1e-12) return a;  // seen edge-on: the plane is a line on screen
  return a + (b - a) * ((sectionOffset - glm::dot(sectionNormal, a)) / denom);
}

std::optional<glm::dvec3> ViewportRenderer::PickWindow::capEdgeNear(int px, int py,
                                                                    double radius) const {
  const auto isCap = [&](int x, int y) { return (idAt(x, y) & 0x80000000u) != 0; };
  std::optional<glm::dvec3> best;
  double bestDistance = radius;
  for (int y = y0; y < y0 + height; ++y)
    for (int x = x0; x < x0 + width; ++x) {
      if (!isCap(x, y)) continue;
      for (const glm::ivec2 d :
           {glm::ivec2(1, 0), glm::ivec2(-1, 0), glm::ivec2(0, 1), glm::ivec2(0, -1)}) {
        const int nx = x + d.x, ny = y + d.y;
        if (nx < x0 || ny < y0 || nx >= x0 + width || ny >= y0 + height || isCap(nx, ny)) continue;
        const double distance = std::hypot(x + 0.5 * d.x - px, y + 0.5 * d.y - py);
        if (distance > bestDistance) continue;
        bestDistance = distance;
        best = 0.5 * (onSectionPlane(x, y) + onSectionPlane(nx, ny));
      }
    }
  return best;
}

std::optional<PickHit> ViewportRenderer::pick(const ViewportFrame& f, int px, int py) {
  if (px < 0 || py < 0 || px >= f.width || py >= f.height) return {};
  // The pixel and a window around it (clipped to the view): the window's depths give the
  // surface's normal there.
  constexpr int kNormalRadius = 4;
  const int x0 = std::max(0, px - kNormalRadius), y0 = std::max(0, py - kNormalRadius);
  const int x1 = std::min(f.width - 1, px + kNormalRadius);
  const int y1 = std::min(f.height - 1, py + kNormalRadius);
  PickWindow window;
  if (!readPickWindow(f, x0, y0, x1 - x0 + 1, y1 - y0 + 1, &window)) return {};
  const uint32_t leafPlusOne = window.idAt(px, py);
  if (leafPlusOne == 0) return {};
  PickHit h;
  h.cap = (leafPlusOne & 0x80000000u) != 0;
  h.leaf = (leafPlusOne & 0x7fffffffu) - 1;
  h.position = *window.pointAt(px, py);
  const glm::dvec3 toEye = f.ortho ? -f.forward : f.eye - h.position;
  if (h.cap) {
    h.normal = glm::dot(f.sectionNormal, toEye) >= 0.0 ? f.sectionNormal : -f.sectionNormal;
    return h;
  }
  // The surface's normal from the same part's depths across the window: the cross product of
  // the spans between the farthest pixels on each side, facing the viewer.
  auto point = [&](int x, int y, glm::dvec3* out) {
    if (window.idAt(x, y) != leafPlusOne) return false;
    *out = *window.pointAt(x, y);
    return true;
  };
  glm::dvec3 left = h.position, right = h.position, down = h.position, up = h.position;
  bool any[4] = {false, false, false, false};
  for (int k = kNormalRadius; k >= 1 && !any[0]; --k) any[0] = point(px - k, py, &left);
  for (int k = kNormalRadius; k >= 1 && !any[1]; --k) any[1] = point(px + k, py, &right);
  for (int k = kNormalRadius; k >= 1 && !any[2]; --k) any[2] = point(px, py - k, &down);
  for (int k = kNormalRadius; k >= 1 && !any[3]; --k) any[3] = point(px, py + k, &up);
  const glm::dvec3 n = glm::cross(right - left, up - down);
  if ((any[0] || any[1]) && (any[2] || any[3]) && glm::length(n) > 0.0) {
    const glm::dvec3 unit = glm::normalize(n);
    h.normal = glm::dot(unit, toEye) >= 0.0 ? unit : -unit;
  }
  return h;
}

ViewportRenderer::PickWindow ViewportRenderer::shownAround(const ViewportFrame& f, int px, int py,
                                                           int radius) {
  PickWindow window;
  const int x0 = std::max(0, px - radius), y0 = std::max(0, py - radius);
  const int x1 = std::min(f.width - 1, px + radius), y1 = std::min(f.height - 1, py + radius);
  if (x1 < x0 || y1 < y0 || !readPickWindow(f, x0, y0, x1 - x0 + 1, y1 - y0 + 1, &window))
    return PickWindow();
  return window;
}

RenderTarget::RenderTarget(int width, int height) : width_(width), height_(height) {
  glGenFramebuffers(1, &framebuffer_);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  glGenRenderbuffers(1, &color_);
  glBindRenderbuffer(GL_RENDERBUFFER, color_);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, color_);
  glGenRenderbuffers(1, &depth_);
  glBindRenderbuffer(GL_RENDERBUFFER, depth_);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, width, height);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_);
  GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glBindRenderbuffer(GL_RENDERBUFFER, 0);
  if (status != GL_FRAMEBUFFER_COMPLETE)
    throw Error("cannot render off-screen at " + std::to_string(width) + " x " +
                std::to_string(height) + " (framebuffer status " + std::to_string(status) + ")");
}

RenderTarget::~RenderTarget() {
  glDeleteFramebuffers(1, &framebuffer_);
  GLuint buffers[] = {color_, depth_};
  glDeleteRenderbuffers(2, buffers);
}

void RenderTarget::bind() {
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
}

std::vector<uint8_t> RenderTarget::read() {
  std::vector<uint8_t> pixels(size_t(width_) * size_t(height_) * 4);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer_);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  return flipRows(std::move(pixels), width_, height_);
}

std::vector<uint8_t> readWindowPixels(int width, int height) {
  std::vector<uint8_t> pixels(size_t(width) * size_t(height) * 4);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  glReadBuffer(GL_BACK);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
  return flipRows(std::move(pixels), width, height);
}

}  // namespace strata::ui
