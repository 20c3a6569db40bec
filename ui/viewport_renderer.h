// Draws the 3D view: background gradient, ground grid, the root's surfels as lit oriented
// splats, and overlay lines (selection box, gizmo). Owns every GL object it uses; restores the
// GL state it changes that ImGui's backend relies on (blend, depth, cull, viewport, program).
//
// Threads: the UI thread, with the GL context current. Constructing throws strata::Error when
// a shader fails.
#pragma once

#include <epoxy/gl.h>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <algorithm>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "engine/ldi/grid.h"
#include "engine/ldi/splats.h"
#include "ui/gl_program.h"
#include "ui/pixel_rect.h"
#include "ui/splat_primitive.h"

namespace strata::ui {

struct LineVertex {
  float position[3];
  uint8_t color[4];  // gamma-encoded RGBA
};
LineVertex lineVertex(const glm::dvec3& p, const glm::vec4& color);

// Per leaf id: its colour (linear RGB) and whether it is selected.
struct LeafStyleTable {
  std::vector<glm::vec3> color;  // indexed by leaf id
  std::vector<uint8_t> selected;
};

struct ViewportFrame {
  glm::dmat4 viewProjection{1.0};
  glm::dvec3 eye{0.0};
  glm::dvec3 forward{0.0, 0.0, -1.0};
  glm::dvec3 up{0.0, 0.0, 1.0};
  bool ortho = false;
  int x = 0, y = 0, width = 1, height = 1;  // GL viewport, pixels, origin bottom-left
  // Section plane: when on, what lies where dot(sectionNormal, p) > sectionOffset is cut away
  // and the cut is capped.
  bool sectionOn = false;
  glm::dvec3 sectionNormal{0.0, 0.0, 1.0};  // unit
  double sectionOffset = 0.0;               // scene units
};

// What a pixel of the viewport shows.
struct PickHit {
  uint32_t leaf = 0;
  glm::dvec3 position{0.0};  // world, scene units
  bool cap = false;          // on the section plane's cap (position on the plane)
  // The surface's unit normal there, facing the viewer (from the depths of the pixels around
  // it that show the same part; the plane's at a cap); none where too few pixels show it.
  std::optional<glm::dvec3> normal;
};

// What the splat buffer holds beside the splats: their grid's cell size h (scene units), where
// their levels of detail end (engine/ldi/splats.h: SplatLevels), and the box they lie in (scene
// units), from which a view works out the level it needs.
struct SplatShape {
  double cellSize = 1.0;
  SplatLevels levels;
  glm::dvec3 lo{0.0}, hi{0.0};
};

// The shape of `splats` made on `grid`: its h, the splats' levels, the grid's box.
SplatShape splatShapeOf(const Grid& grid, const SplatResource& splats);

class RenderTarget;

// What a draw of splats is for (ViewportRenderer::drawSplatRange): a whole image of a level
// (timed, for the automatic choice of kind), a share of one drawn over frames, or the coarse
// image of a moving view (every k-th splat, large discs).
enum class SplatDraw { WholeImage, Share, Coarse };

class ViewportRenderer {
 public:
  ViewportRenderer();
  ~ViewportRenderer();
  ViewportRenderer(const ViewportRenderer&) = delete;
  ViewportRenderer& operator=(const ViewportRenderer&) = delete;

  // The splat instance buffer. Its storage holds splatCapacity() splats; reserveSplats
  // reallocates it (glBufferData) to hold `count`, keeping some room to grow, and returns
  // whether it did (a CUDA-GL registration of the buffer must then be renewed).
  GLuint splatBuffer() const { return splatBuffer_; }
  size_t splatCapacity() const { return splatCapacity_; }
  bool reserveSplats(size_t count);
  // Whether reserveSplats(count) would keep the buffer as it is.
  bool splatBufferFits(size_t count) const;
  static constexpr size_t kMinSplatCapacity = 1024;
  // Host upload of `count` splats.
  void uploadSplats(const Splat* splats, size_t count, const SplatShape& shape);
  // The first `count` splats of GL buffer `source` copied into the splat buffer by the GPU
  // (glCopyBufferSubData: no host bytes touched in the frame; ui/mapped_splat_slots.h).
  void copySplats(GLuint source, size_t count, const SplatShape& shape);
  // A host upload spread over frames: the splats go into a second buffer, at most `maxBytes`
  // a call of stageSplats, while the first keeps drawing the last result; commitStagedSplats
  // then makes the second the one drawn (and the first the next staging buffer). `splats` must
  // stay the same array from the call that starts at 0 to the commit. Returns how many of the
  // `count` splats are in the second buffer now (from `done`).
  size_t stageSplats(const Splat* splats, size_t count, size_t done, size_t maxBytes);
  void commitStagedSplats(size_t count, const SplatShape& shape);
  // After the buffer was filled on the device (CUDA-GL interop): draw `count` splats.
  void setSplatCount(size_t count, const SplatShape& shape);
  void setLeafStyles(const LeafStyleTable& styles);
  size_t splatCount() const { return splatCount_; }
  size_t splatBytes() const { return splatCount_ * sizeof(Splat); }

  // Ghosts: splats of parts that cut (red) or intersect (violet), drawn translucent over the
  // result (depth-tested against it, not written, not pickable). A layer's splats come in runs,
  // one per ghost, each drawn with the cell size of the lattice it was made on (`runs[layer]`:
  // counts adding up to the layer's splats, cell sizes in scene units, 0: the result's; none:
  // the whole layer at the result's). Replaces the previous ghosts; empty vectors draw none.
  struct GhostRun {
    size_t count = 0;
    double cellSize = 0.0;
    bool operator==(const GhostRun& o) const { return count == o.count && cellSize == o.cellSize; }
  };
  void setGhosts(const std::vector<Splat>& cutting, const std::vector<Splat>& intersecting,
                 const std::vector<GhostRun> runs[2] = nullptr);
  size_t ghostCount() const { return ghosts_[0].count + ghosts_[1].count; }

  // Lines drawn over the background only, under every splat and ghost: the ground grid, which is
  // then never seen across a solid's face (above the ground or below it). Kept until replaced.
  void setBackdrop(std::vector<LineVertex> lines) { backdrop_ = std::move(lines); }

  // `lines` are depth-tested against the surfels (section outline, boxes); `overlay` is drawn on
  // top (gizmo); `overlayTriangles` too (gizmo handles), as a triangle list. All splats of the
  // view's level of detail (detailLevel), at once: screenshots and headless renders.
  void draw(const ViewportFrame& frame, const std::vector<LineVertex>& lines,
            const std::vector<LineVertex>& overlay,
            const std::vector<LineVertex>& overlayTriangles);

  // The editor's view, within a frame budget. The scene (background, splats, ghosts, `lines`) is
  // drawn into an off-screen image that is redrawn only when the view (camera, size, section) or
  // what is shown (splats, colours, selection, ghosts, lines) changes, and copied to the window
  // each frame with the overlay on top. When the view changes and the splats are more than the
  // frame's share, an image at half resolution with every k-th splat (k prime, each splat
  // larger to cover) is shown at once; the full image is then drawn a share a frame and shown
  // when complete. A new content seen from a view at rest (an edit) is drawn whole when its
  // splats cost at most kFirstImageMs, else first from a coarser level at full resolution and
  // then refined the same way. The share follows `lastFrameMs` (the previous frame's whole
  // time) toward kTargetFrameMs.
  void drawCached(const ViewportFrame& frame, const std::vector<LineVertex>& lines,
                  const std::vector<LineVertex>& overlay,
                  const std::vector<LineVertex>& overlayTriangles, double lastFrameMs);
  // Whether the window's pixels at `frame` already show what drawCached would draw with these
  // arguments: the last drawCached left its complete image there (not a coarse or partial one)
  // with the same view, content, lines and overlay, and nothing was drawn into the window by
  // draw since. A caller whose window keeps its back buffer (window_redraw.h) may then leave
  // the view as it is and call skipFrame instead of drawCached.
  bool windowShows(const ViewportFrame& frame, const std::vector<LineVertex>& lines,
                   const std::vector<LineVertex>& overlay,
                   const std::vector<LineVertex>& overlayTriangles) const;
  // A frame that keeps the view's pixels as they are (windowShows): the frame budget follows
  // `lastFrameMs` (the previous frame's whole time) as drawCached would, and this frame draws
  // no splats.
  void skipFrame(double lastFrameMs);
  // Draws the window's view again within `clip` (window pixels), as the last drawCached left
  // it: its complete image and `overlay` on top. Only where windowShows(frame, ..., overlay,
  // overlayTriangles) holds; the scissor test is off on return.
  void repaintWindow(const ViewportFrame& frame, const std::vector<LineVertex>& overlay,
                     const std::vector<LineVertex>& overlayTriangles, const PixelRect& clip);
  // The splats about to be given (uploadSplats, setSplatCount, commitStagedSplats) show the same
  // parts as those shown, at another resolution: where their image cannot be drawn whole at once
  // from the view shown at rest, the complete image shown stays until the new one is (a first
  // or coarse image of the new splats showed the parts worse for seconds: an artist raised the
  // preview's resolution). Taken by the next new content drawCached draws.
  void holdShownImage() { holdShownImage_ = true; }
  // The full image is still being drawn: the frame loop must keep frames coming.
  bool refining() const { return refining_; }
  // The view shows the coarse image (half resolution, every k-th splat) while it refines.
  bool showsCoarseImage() const { return refining_ && !refineOverShown_; }
  // How splats are drawn (ui/splat_primitive.h). Points because a GPU's draw of millions of
  // splats is bound by vertex work (four vertices a quad); quads where sprites would not fit.
  void setSplatPrimitive(SplatPrimitive primitive) { primitive_ = primitive; }
  // Splats drawn so far as points, as quads and by compute (each drawn splat counted once per
  // draw).
  size_t pointsDrawn() const { return drawn_[int(SplatKind::Points)]; }
  size_t quadsDrawn() const { return drawn_[int(SplatKind::Quads)]; }
  size_t computedDrawn() const { return drawn_[int(SplatKind::Compute)]; }
  // Whether this context draws splats by compute (GL 4.4 and the programs built); else why not.
  bool computeReady() const { return computeReady_; }
  const std::string& computeProblem() const { return computeProblem_; }
  // By compute, splats whose sprites' bound (spriteBoundPx, loose: a splat of 6 px gets 77) is
  // at most this many pixels (a splat's pixels are one invocation's loop); quads or points where
  // they could be larger (close-ups). Automatic's timing weighs what the loops cost.
  static constexpr double kMaxComputeFootprintPx = 128.0;
  // Automatic picks by measurement: which is cheaper depends on where the driver spends its time
  // (a GPU: vertices, where points save three of four, and where its graphics stages run on few
  // of its units, as on the H100 and H200, compute; a software rasterizer: fragments, where the
  // points' depth written per fragment costs more) and on the splats' size on screen.
  // Whole images' draws (kTimedDrawSplats or more) are timed with GL_TIME_ELAPSED, read back
  // frames later without waiting; each kind is drawn until it has a time, then the cheapest,
  // and another again every kRetryEvery times (views change what each costs). Whole draws,
  // not slices of one: on the H200 a slice of points drawn after quads timed 8.5 ns a splat,
  // whole draws of points 3.6 (a pipelined GPU's timer spans what is still in flight).
  static constexpr size_t kTimedDrawSplats = 2000;
  // The most splats drawn at once, in place of a frame's share, to time a kind that has no time
  // yet (drawCached's refinement): a frame of at most 20 ms at 5 ns a splat.
  static constexpr size_t kCalibrationSplats = size_t(1) << 22;
  static constexpr int kRetryEvery = 32;
  // The measured GPU time per splat of each kind in nanoseconds (0: not measured yet).
  double nsPerSplat(SplatPrimitive kind) const;
  // Tests: takes `ns` as the measured time per splat of `kind` (Quads, Points or Compute), as
  // if read back from a timed draw.
  void assumeNsPerSplat(SplatPrimitive kind, double ns);
  // Times of draws of one kind.
  struct KindTiming {
    double nsPerSplat = 0.0;             // nsSum / splatSum; 0 before the first
    double nsSum = 0.0, splatSum = 0.0;  // timed draws, each older one weighing 0.7 as much
    GLuint query = 0;                    // GL_TIME_ELAPSED
    bool pending = false;                // query holds a draw not read back yet
    size_t splats = 0;                   // of that draw
    int reads = 0;                       // times read back
  };
  // Whether the driver's timer queries are taken to measure a draw's whole work (not on a
  // software rasterizer, which then draws quads in Automatic); tests may say so either way.
  bool timersTrusted() const { return timersTrusted_; }
  void trustTimers(bool trusted) { timersTrusted_ = trusted; }
  // Level of detail: splats whose rays are at most this many pixels apart where the splats come
  // nearest to the camera show the surface as every splat would (a finer lattice adds only
  // splats drawn over each other within a pixel).
  static constexpr double kMaxSplatSpacingPx = 1.0;
  // The coarsest level (engine/ldi/splats.h: SplatLevels) whose rays, 2^L h apart, are at most
  // kMaxSplatSpacingPx apart on screen at the splats' box's nearest depth in `frame`; 0 when
  // the camera is within that box's depth range or the level holds no splats.
  // At most `level` (0: every splat, a reference to compare the levels with).
  int detailLevel(const ViewportFrame& frame) const;
  void limitDetailLevel(int level) { maxDetailLevel_ = level; }
  // The level the last full image was drawn at (drawCached, draw), and its splat count.
  int drawnLevel() const { return drawnLevel_; }
  size_t drawnLevelSplats() const { return drawnLevel_ < 0 ? 0 : levelEnd(drawnLevel_); }
  // Splats of the coarse image drawn a frame now (drawCached), for the status bar.
  size_t splatsPerFrame() const { return splatsPerFrame_; }
  // Tests: the splats a frame of the coarse image and of the full one (see splatsPerFrame_).
  void setFrameShares(size_t coarse, size_t full) {
    splatsPerFrame_ = std::max<size_t>(1, coarse);
    fullShare_ = std::max<size_t>(1, full);
  }
  static constexpr double kTargetFrameMs = 12.0;
  // The fewest splats a frame either share shrinks to.
  static constexpr size_t kMinShare = 4000;
  // The coarse image's reduction (2: half the view's width and height; 4: a quarter). It turns
  // to 4 once a coarse frame at the fewest splats (kMinShare) still takes longer than
  // kTargetFrameMs: its cost is then the pixels the discs fill (the discs widen as the share
  // shrinks, so fewer splats fill as many pixels), which only a smaller image reduces: a
  // software GL driver (Mesa llvmpipe at 1024 cells: 9 ms of coarse drawing at a half, 4.3 at
  // a quarter). Back to 2 when a coarse frame at 4 takes less than a quarter of the target
  // (where even four times its pixels would fit).
  int coarseShrink() const { return coarseShrink_; }
  // An edit's first image: drawn from the finest level whose splats cost at most this long at
  // the measured cost per splat (the frame's target: the frame bringing the result stays one
  // frame); the view's level follows over the next frames. Not less: where the view's level
  // fits in a frame, a coarser first image only delays it (measured on the H200 at 1024 cells
  // with a quarter frame: the first image 30% sooner, every splat twice as late).
  static constexpr double kFirstImageMs = kTargetFrameMs;

  // The leaf and point that pixel (px, py) of `frame`'s viewport shows (pixels from its
  // bottom-left corner), rendered into an off-screen id buffer; nothing when it shows no splat.
  // Leaves the bound framebuffer and viewport as they were.
  std::optional<PickHit> pick(const ViewportFrame& frame, int px, int py);
  // The pick ids (leaf + 1, the top bit on a cap; 0: nothing) and depths of the pixel rectangle
  // (x0, y0, width, height) of a frame's viewport, with what turns them into world points.
  struct PickWindow {
    int x0 = 0, y0 = 0, width = 0, height = 0;
    std::vector<uint32_t> ids;
    std::vector<float> depths;
    glm::dmat4 toWorld{1.0};
    int frameWidth = 1, frameHeight = 1;
    glm::dvec3 sectionNormal{0.0, 0.0, 1.0};
    double sectionOffset = 0.0;
    size_t index(int x, int y) const { return size_t(y - y0) * size_t(width) + size_t(x - x0); }
    uint32_t idAt(int x, int y) const {
      return x < x0 || y < y0 || x >= x0 + width || y >= y0 + height ? 0u : ids[index(x, y)];
    }
    // The world point of pixel (x, y) at NDC depth `ndcDepth`.
    glm::dvec3 unproject(int x, int y, double ndcDepth) const;
    // The surface point the pixel shows (a cap's: on the section plane); none where none.
    std::optional<glm::dvec3> pointAt(int x, int y) const;
    // Where pixel (x, y)'s line of sight meets the section plane (any pixel, shown or not).
    glm::dvec3 onSectionPlane(int x, int y) const;
    // The edge of the section's cap nearest to pixel (px, py) within `radius` pixels: between a
    // cap pixel and a neighbour (across or along) that shows no cap, the middle of their points
    // on the section plane (the cap's side as drawn, to half a pixel); none where the window
    // holds no such pair. For the measure tool: a wall measured across the cap (measure_tool.h).
    std::optional<glm::dvec3> capEdgeNear(int px, int py, double radius) const;
  };
  // The pixels of the square of `radius` pixels around (px, py), clipped to the view: what each
  // shows (PickWindow::pointAt). One pass for many questions: whether a snap point lies on the
  // surface the view shows (measure_tool.h). Empty (width 0) when nothing is drawn.
  PickWindow shownAround(const ViewportFrame& frame, int px, int py, int radius);
  // The leaves shown in the pixel rectangle [x0, x1) x [y0, y1) of `frame`'s viewport (from its
  // bottom-left corner; corners in any order), sorted, once each: box selection.
  std::vector<uint32_t> pickLeaves(const ViewportFrame& frame, int x0, int y0, int x1, int y1);

 private:
  void drawLines(const std::vector<LineVertex>& vertices, GLenum mode);
  // Clears the bound target's viewport and draws the background gradient.
  void drawBackground(const ViewportFrame& f);
  // Splats [first, first + count * stride) of the instance buffer, every `stride`-th, with the
  // disc radius `radius` cells, lit for `f`, as points, quads or by compute (preferredKind; the
  // coarse image as quads; a whole image now and then as the other kind, timed). Into the bound
  // target's current viewport.
  void drawSplatRange(const ViewportFrame& f, size_t first, size_t count, size_t stride,
                      float radius, SplatDraw what);
  // The splats' box's nearest depth along the view (its corners' least), scene units.
  double nearestDepth(const ViewportFrame& f) const;
  // Pixels per scene unit across the view where the splats' box comes nearest to the camera;
  // infinity when the camera is within the box's depth range.
  double nearestPixelsPerUnit(const ViewportFrame& f) const;
  // The splats of level `level` and coarser: the first levelEnd(level) of the buffer.
  size_t levelEnd(int level) const;
  void drawGhosts(const ViewportFrame& f);
  // The key of the view the scene image shows: camera, viewport, section and lines.
  uint64_t viewKey(const ViewportFrame& f, const std::vector<LineVertex>& lines) const;
  // drawCached's and skipFrame's start: the splats a frame follow the last frame's time (the
  // splats it drew against what it took), and this frame has drawn none yet.
  void followFrameTime(double lastFrameMs);
  // The key of the window's pixels drawn by drawCached with these arguments (never 0).
  uint64_t windowKeyFor(const ViewportFrame& f, const std::vector<LineVertex>& lines,
                        const std::vector<LineVertex>& overlay,
                        const std::vector<LineVertex>& overlayTriangles) const;
  // The overlay over the view, within `clip` (window pixels; empty: the whole view).
  void drawOverlay(const ViewportFrame& f, const std::vector<LineVertex>& overlay,
                   const std::vector<LineVertex>& overlayTriangles, const PixelRect& clip = {});
  // Draws the leaf ids of the pixels in the rectangle into the pick framebuffer (left bound, with
  // scissoring on) and readies it for glReadPixels; false when the framebuffer is incomplete.
  bool drawPickIds(const ViewportFrame& frame, int x, int y, int width, int height);
  // Draws the ids into the rectangle and reads them back; false when there is nothing to draw.
  // Leaves the bound framebuffer and viewport as they were.
  bool readPickWindow(const ViewportFrame& frame, int x0, int y0, int width, int height,
                      PickWindow* out);
  // Binds `program` and sets the uniforms surfel.vert needs (which the compute kind's programs
  // read too), the leaf texture on unit 0 and the splat vertex array.
  void useSurfelProgram(const GlProgram& program, const ViewportFrame& f);
  // The kinds of draw (timing_, drawn_): quads (four vertices a splat), points (one vertex, the
  // disc cut per fragment), compute (surfel_splat.comp and surfel_resolve.frag).
  enum class SplatKind { Quads = 0, Points = 1, Compute = 2 };
  static constexpr int kSplatKinds = 3;
  // Whether splats of `radius` cells can be drawn as `kind` in `f` (points: every sprite within
  // the driver's largest point; compute: computeReady and every box within
  // kMaxComputeFootprintPx).
  bool kindFits(const ViewportFrame& f, float radius, SplatKind kind) const;
  // The kind a whole image of splats of `radius` cells is drawn as in `f` (setSplatPrimitive;
  // Automatic: a kind that fits and has no time yet, else the cheapest measured), before
  // drawSplatRange's retries.
  SplatKind preferredKind(const ViewportFrame& f, float radius) const;
  // Whether every kind that fits in `f` has been timed.
  bool everyFittingKindTimed(const ViewportFrame& f, float radius) const;
  // Whether every splat's sprite of `radius` cells fits the driver's largest point in `f`.
  bool pointsFit(const ViewportFrame& f, float radius) const;
  // A bound on the sprites' size in pixels (infinity where a splat may reach the eye's plane).
  double spriteBoundPx(const ViewportFrame& f, float radius) const;
  // drawSplatRange's draw of one kind, timed into `timer` (marked pending) when given; leaves
  // the vertex array and buffer bound.
  void drawSplatsAs(const ViewportFrame& f, SplatKind kind, size_t first, size_t count,
                    size_t stride, float radius, KindTiming* timer);
  // drawSplatsAs by compute: the splats' nearest depths and then their indices per pixel of the
  // current viewport (computeDepth_, computeIds_), then each pixel lit through the depth test.
  void drawSplatsComputed(const ViewportFrame& f, size_t first, size_t count, size_t stride,
                          float radius, KindTiming* timer);

  // A splat instance buffer with its vertex array (corners + instances).
  struct SplatLayer {
    GLuint vao = 0, buffer = 0;
    size_t count = 0;
  };
  void makeSplatLayer(GLuint* vao, GLuint* buffer);

  GlProgram surfelProgram_;
  GlProgram pointProgram_;  // surfel.vert + surfel.frag with SPLAT_POINTS
  GlProgram pickProgram_;
  GlProgram lineProgram_;
  GlProgram backgroundProgram_;
  GlProgram computeProgram_;  // surfel_splat.comp, where computeReady_
  GlProgram resolveProgram_;  // surfel_resolve.vert + .frag
  bool computeReady_ = false;
  std::string computeProblem_;
  double maxStorageBlockBytes_ = 0.0;         // GL_MAX_SHADER_STORAGE_BLOCK_SIZE
  GLuint computeDepth_ = 0, computeIds_ = 0;  // r32ui, the viewport's size when last drawn
  int computeWidth_ = 0, computeHeight_ = 0;
  GLuint surfelVao_ = 0, cornerBuffer_ = 0, splatBuffer_ = 0;
  GLuint stagingVao_ = 0, stagingBuffer_ = 0;  // stageSplats' buffer, and a VAO to draw it
  size_t stagingCapacity_ = 0;
  GLuint lineVao_ = 0, lineBuffer_ = 0;
  GLuint emptyVao_ = 0;
  GLuint pointVao_ = 0;           // the splat buffer's attributes, one vertex per splat
  float maxPointSize_ = 1.0f;     // pixels, the driver's largest
  GLint maxAttribStride_ = 2048;  // bytes, the driver's largest vertex attribute stride
  SplatPrimitive primitive_ = SplatPrimitive::Automatic;
  size_t drawn_[kSplatKinds] = {};  // splats drawn as each kind so far
  // Whole images' times of each kind (see kTimedDrawSplats), by SplatKind.
  KindTiming timing_[kSplatKinds];
  // The timer of a whole image's draw of `count` splats of `kind` (marked pending), or none.
  KindTiming* timerFor(SplatKind kind, size_t count);
  int retryAfterReads_ = kRetryEvery;  // another kind again once the drawn one has as many
  bool timersTrusted_ = true;          // see timersTrusted()
  // Reads the pending timer queries back when the GPU has them (never waits).
  void collectTiming();
  // The level of an edit's first image in `f` (kFirstImageMs): buildLevel_ or coarser, as the
  // measured cost per splat allows; buildLevel_ before any measurement and where the timers
  // are not trusted (the frames' share then decides between a whole image and the coarse one).
  int firstImageLevel(const ViewportFrame& f) const;
  SplatLayer ghosts_[2];              // cutting, intersecting
  std::vector<LineVertex> backdrop_;  // setBackdrop
  GLuint leafTexture_ = 0;
  int leafTextureWidth_ = 1;
  int leafCount_ = 1;
  size_t splatCount_ = 0;
  size_t splatCapacity_ = 0;
  size_t lineCapacity_ = 0;
  double cellSize_ = 1.0;
  SplatShape shape_;
  int buildLevel_ = 0;                     // the level building_ is drawn at
  int drawnLevel_ = -1;                    // of the last full image; -1 before one
  int maxDetailLevel_ = kSplatLevels - 1;  // limitDetailLevel
  GLuint pickFramebuffer_ = 0, pickIds_ = 0, pickDepth_ = 0;
  int pickWidth_ = 0, pickHeight_ = 0;

  // drawCached's images: the coarse one (reduced, coarseShrink), the full one shown and the full
  // one being drawn.
  uint64_t contentVersion_ = 1;  // bumped by every change of splats, colours or ghosts
  uint64_t splatsVersion_ = 1;   // bumped by every change of splats or colours (not ghosts)
  std::unique_ptr<RenderTarget> coarse_, shown_, building_;
  // The last complete image of the view's level of detail, of the splats alone, without ghosts
  // and lines (colour and depth), and the view (lines left out) and splats it shows: a
  // change of the lines or the ghosts alone (a measurement placed, a selection's box, a ghost
  // finished after its result) draws them over a copy of it, instead of all the splats again.
  std::unique_ptr<RenderTarget> plain_;
  std::optional<LeafStyleTable> styles_;  // the last setLeafStyles' table
  std::vector<Splat> ghostSplats_[2];     // the last setGhosts' layers
  std::vector<GhostRun> ghostRuns_[2];    // and their runs, one per ghost
  uint64_t plainKey_ = 0;
  uint64_t shownKey_ = 0;          // what shown_ (or coarse_, while refining) holds
  uint64_t windowKey_ = 0;         // what the window shows (windowShows); 0: unknown
  uint64_t shownView_ = 0;         // its view alone (viewKey)
  uint64_t buildingPlainKey_ = 0;  // the splats and view (no lines) of the image being built
  bool refining_ = false;          // building_ is being drawn for shownKey_
  bool refineOverShown_ = false;   // meanwhile shown_ holds a first image (else coarse_ is shown)
  bool holdShownImage_ = false;    // holdShownImage
  size_t buildDone_ = 0;           // splats drawn into building_ so far
  // Splats a frame: of the coarse image (every k-th, reduced resolution) and at full resolution
  // (whole images and the refining shares). Safe starts for a software GL driver; each grows
  // 1.5x a frame while frames are quick.
  size_t splatsPerFrame_ = 30000;
  size_t fullShare_ = 30000;
  int coarseShrink_ = 2;       // see coarseShrink()
  bool lastDrawFull_ = false;  // the last drawCached's splats were at full resolution
  double uploadMsThisFrame_ = 0.0, uploadMsLastFrame_ = 0.0;  // host uploads, by frame
  size_t drewSplatsLastFrame_ = 0;  // splats the last drawCached drew (what its time bought)
};

// An off-screen colour + depth target for rendering the viewport alone (headless renders,
// tests). Restores the previous framebuffer binding in read().
class RenderTarget {
 public:
  RenderTarget(int width, int height);  // throws strata::Error when incomplete
  ~RenderTarget();
  RenderTarget(const RenderTarget&) = delete;
  RenderTarget& operator=(const RenderTarget&) = delete;
  void bind();
  GLuint framebuffer() const { return framebuffer_; }
  // RGBA8 pixels, top row first (width * height * 4 bytes). Unbinds the target.
  std::vector<uint8_t> read();
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  int width_, height_;
  GLuint framebuffer_ = 0, color_ = 0, depth_ = 0;
};

// Reads the default framebuffer's back buffer (the whole window), top row first.
std::vector<uint8_t> readWindowPixels(int width, int height);

}  // namespace strata::ui
