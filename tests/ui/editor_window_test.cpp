// The editor end to end, in a real (invisible) window: build scenes through the UI layer's
// actions, let the engine thread evaluate them, render the viewport off-screen and check the
// silhouettes in the pixels. Needs a display: starts Xvfb itself when DISPLAY is unset, and skips
// (saying why) when it cannot.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <thread>

#include "engine/document/commands.h"
#include "engine/eval/cpu_backend.h"
#include "engine/eval/evaluator.h"
#include "engine/io/scene_file.h"
#include "engine/io/user_files.h"
#include "tests/support/gated_backend.h"
#include "tests/support/off_host_splats_backend.h"
#include "ui/editor.h"
#include "ui/editor_actions.h"
#include "ui/png_file.h"
#include "ui/scene_queries.h"

#if defined(STRATA_HAVE_XTEST)
#include <X11/Xlib.h>
#include <X11/extensions/XTest.h>
#include <X11/keysym.h>
#endif

namespace strata::ui {
namespace {

// Starts a private Xvfb when no display is named; stops it at the end of the test program.
class DisplayEnvironment : public testing::Environment {
 public:
  void SetUp() override {
    const char* display = std::getenv("DISPLAY");
    if (display && *display) return;
    if (std::system("command -v Xvfb >/dev/null 2>&1") != 0) {
      why_ = "DISPLAY is unset and Xvfb is not installed (.ci/deps --editor installs it)";
      return;
    }
    // Xvfb picks a free display number itself and writes it to the pipe once it accepts clients
    // (-displayfd), so parallel test programs never race for a number.
    int fds[2];
    if (pipe(fds) != 0) {
      why_ = "DISPLAY is unset and no pipe for Xvfb";
      return;
    }
    pid_t pid = fork();
    if (pid == 0) {
      prctl(PR_SET_PDEATHSIG, SIGTERM);  // never outlive the tests
      close(fds[0]);
      int devnull = open("/dev/null", O_RDWR);
      dup2(devnull, 1);
      dup2(devnull, 2);
      std::string fd = std::to_string(fds[1]);
      // -noreset: no server reset (and refused connections) when the last window closes.
      execlp("Xvfb", "Xvfb", "-displayfd", fd.c_str(), "-screen", "0", "1280x800x24", "-nolisten",
             "tcp", "-noreset", static_cast<char*>(nullptr));
      _exit(127);
    }
    close(fds[1]);
    std::string number;
    char c;
    while (read(fds[0], &c, 1) == 1 && c != '\n') number += c;
    close(fds[0]);
    if (pid > 0 && !number.empty()) {
      server_ = pid;
      setenv("DISPLAY", (":" + number).c_str(), 1);
    } else if (pid > 0) {
      kill(pid, SIGTERM);
      waitpid(pid, nullptr, 0);
    }
    if (server_ == 0) why_ = "DISPLAY is unset and Xvfb did not start";
  }
  void TearDown() override {
    if (server_ > 0) {
      kill(server_, SIGTERM);
      waitpid(server_, nullptr, 0);
    }
  }
  static const std::string& why() { return why_; }

 private:
  pid_t server_ = 0;
  static std::string why_;
};
std::string DisplayEnvironment::why_;
testing::Environment* const g_display = testing::AddGlobalTestEnvironment(new DisplayEnvironment);

#define REQUIRE_DISPLAY()                                                        \
  do {                                                                           \
    std::string why;                                                             \
    if (!editorDisplayAvailable(&why))                                           \
      GTEST_SKIP() << "no display: " << why << " " << DisplayEnvironment::why(); \
  } while (0)

EditorOptions testOptions() {
  EditorOptions o;
  o.makeBackend = [] { return std::make_shared<CpuBackend>(); };
  o.visible = false;
  o.width = 1280;
  o.height = 800;
  return o;  // no recent files, no recovery file
}

struct Pixel {
  int r, g, b;
};
Pixel at(const std::vector<uint8_t>& image, int width, int x, int y) {
  const uint8_t* p = &image[(size_t(y) * size_t(width) + size_t(x)) * 4];
  return {p[0], p[1], p[2]};
}
bool reddish(Pixel p) {
  return p.r > p.g + 60 && p.r > p.b + 60;
}
bool bluish(Pixel p) {
  return p.b > p.r + 50 && p.b > p.g + 20;
}

// A sphere from the palette, coloured red (two undo steps); its id, 0 when it failed.
NodeId addRedSphere(EditorState& state) {
  const NodeId sphere = addPrimitive(state, NodeKind::Sphere);
  if (sphere == 0) return 0;
  const bool coloured =
      guarded(state, [&] { state.document.setColor(sphere, glm::vec3(0.9f, 0.1f, 0.1f)); });
  return coloured ? sphere : 0;
}

TEST(EditorWindow, SphereSilhouetteAppearsAndUndoRemovesIt) {
  REQUIRE_DISPLAY();
  Editor editor(testOptions());
  EditorState& state = editor.state();
  ASSERT_NE(addRedSphere(state), 0u);
  setResolution(state, 48);
  clearSelection(state);  // no selection tint, no gizmo
  state.showGrid = false;
  ASSERT_TRUE(editor.waitForPreview(60.0)) << state.previewError;
  EXPECT_GT(state.preview->splatCount(), 100u);
  EXPECT_EQ(state.splatTransfer, "host upload");  // the CPU backend: no interop to try
  editor.camera().setAxisView(AxisView::Front);
  editor.viewAll();

  const int w = 240, h = 200;
  std::vector<uint8_t> image = editor.renderViewport(w, h);
  ASSERT_EQ(image.size(), size_t(w) * h * 4);
  EXPECT_TRUE(reddish(at(image, w, w / 2, h / 2)));
  for (auto [x, y] : {std::pair{2, 2}, {w - 3, 2}, {2, h - 3}, {w - 3, h - 3}})
    EXPECT_FALSE(reddish(at(image, w, x, y))) << "corner " << x << "," << y;
  // The silhouette is a centred disc: its extent is about the same across and down.
  int minX = w, maxX = -1, minY = h, maxY = -1, count = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      if (reddish(at(image, w, x, y))) {
        minX = std::min(minX, x), maxX = std::max(maxX, x);
        minY = std::min(minY, y), maxY = std::max(maxY, y);
        ++count;
      }
  ASSERT_GT(count, 0);
  const double dx = maxX - minX + 1, dy = maxY - minY + 1;
  EXPECT_NEAR(dx / dy, 1.0, 0.1);
  EXPECT_NEAR((minX + maxX) * 0.5, w * 0.5, 3.0);
  EXPECT_NEAR((minY + maxY) * 0.5, h * 0.5, 3.0);
  EXPECT_NEAR(count / (3.14159265 * dx * dy / 4.0), 1.0, 0.08);  // a filled disc, no holes

  // A whole frame with every panel draws without trouble.
  int fw = 0, fh = 0;
  std::vector<uint8_t> frame = editor.screenshot(&fw, &fh);
  EXPECT_GT(fw, 0);
  EXPECT_EQ(frame.size(), size_t(fw) * size_t(fh) * 4);

  // Undo the colour and the add: the viewport empties.
  undo(state);  // resolution
  undo(state);  // colour
  undo(state);  // add
  EXPECT_TRUE(state.document.root()->children.empty());
  ASSERT_TRUE(editor.waitForPreview(60.0)) << state.previewError;
  std::vector<uint8_t> empty = editor.renderViewport(w, h);
  EXPECT_FALSE(reddish(at(empty, w, w / 2, h / 2)));
  redo(state);
  redo(state);
  ASSERT_TRUE(editor.waitForPreview(60.0)) << state.previewError;
  EXPECT_TRUE(reddish(at(editor.renderViewport(w, h), w, w / 2, h / 2)));
}

// A change is written for recovery once it has rested a moment, not minutes later (an artist's
// kill -9 fifty seconds after an edit lost it when the only trigger was every two minutes), on
// a thread of its own; saved or undone back to the saved state, the file goes.
TEST(EditorWindow, AnEditIsWrittenForRecoveryOnceItHasRested) {
  REQUIRE_DISPLAY();
  const std::string folder = ::testing::TempDir() + "/strata_autosave_rest";
  std::filesystem::remove_all(folder);
  EditorOptions o = testOptions();
  o.recoveryDir = folder;
  o.autosaveRestSeconds = 0.3;
  o.autosaveSeconds = 3600.0;  // only the rest can trigger it here
  Editor editor(o);
  EditorState& state = editor.state();
  const auto framesFor = [&](double seconds, const std::function<bool()>& until) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    while (std::chrono::steady_clock::now() < end) {
      editor.frame();
      if (until && until()) return true;
    }
    return false;
  };
  const std::string slot = state.recoveryPath;  // this editor's own file in the folder
  ASSERT_EQ(std::filesystem::path(slot).parent_path(), std::filesystem::path(folder));
  const auto written = [&] { return std::filesystem::exists(slot); };
  ASSERT_NE(addPrimitive(state, NodeKind::Sphere), 0u);
  ASSERT_TRUE(state.document.dirty());
  ASSERT_TRUE(framesFor(20.0, written)) << "not written within 20 s of the edit";
  const Document recovered = readRecoveryFile(slot);
  ASSERT_EQ(recovered.root()->children.size(), 1u);
  EXPECT_EQ(recovered.root()->children[0]->kind, NodeKind::Sphere);
  // Back to the saved (empty) state: nothing to recover.
  undo(state);
  EXPECT_FALSE(state.document.dirty());
  EXPECT_TRUE(framesFor(20.0, [&] { return !written(); })) << "the recovery file stayed";
  std::filesystem::remove_all(folder);
}

// The frame that sends an edit to the engine builds its panels while the engine works and waits
// for the result only before drawing the view: the edit is on screen at the end of that frame,
// here where the engine takes a second (a gate held that long: far more than the editor's usual
// wait, so the wait is long here; long enough that the frame is waiting when it opens, even on a
// loaded machine under a sanitizer), and the next frame, which redraws the panels built before
// the result came, follows without waiting for input.
TEST(EditorWindow, AnEditIsShownByTheFrameThatSentIt) {
  REQUIRE_DISPLAY();
  auto gated = std::make_shared<test::GatedBackend>();
  EditorOptions o = testOptions();
  o.makeBackend = [gated] { return gated; };
  o.editResultWaitSeconds = 30.0;
  Editor editor(o);
  EditorState& state = editor.state();
  const NodeId sphere = addPrimitive(state, NodeKind::Sphere);
  ASSERT_NE(sphere, 0u);
  setResolution(state, 32);
  ASSERT_TRUE(editor.waitForPreview(60.0)) << state.previewError;
  for (int i = 0; i < 3; ++i) editor.frame();
  const double x0 = findNode(state.document.root(), sphere)->transform.translate.x;
  Transform moved = findNode(state.document.root(), sphere)->transform;
  moved.translate.x += 0.3;
  gated->close();
  ASSERT_TRUE(guarded(state, [&] { state.document.setTransform(sphere, moved); }));
  const uint64_t revision = state.document.revision();
  std::thread opener([&] {
    if (gated->waitUntilHeld()) std::this_thread::sleep_for(std::chrono::seconds(1));
    gated->open();
  });
  editor.frame();
  opener.join();
  ASSERT_TRUE(state.preview);
  EXPECT_EQ(state.preview->tag, revision) << "the edit's result was not shown by its frame";
  editor.frame();
  EXPECT_EQ(editor.lastWaitSeconds(), 0.0) << "the panels built before the result waited";
  undo(state);
  ASSERT_TRUE(editor.waitForPreview(60.0)) << state.previewError;
  EXPECT_EQ(findNode(state.document.root(), sphere)->transform.translate.x, x0);
}

// A result too large for one frame's upload goes up in shares over several frames, while the
// last one stays on screen; then it is shown whole (the sphere's pixels, every splat).
TEST(EditorWindow, LargeResultsAreUploadedOverSeveralFramesWhileTheLastStaysShown) {
  REQUIRE_DISPLAY();
  Editor editor(testOptions());
  EditorState& state = editor.state();
  ASSERT_NE(addRedSphere(state), 0u);
  setResolution(state, 32);  // a small first result: one upload
  clearSelection(state);
  ASSERT_TRUE(editor.waitForPreview(60.0)) << state.previewError;
  ASSERT_FALSE(editor.uploading());
  const PreviewResult* small = state.preview.get();
  setResolution(state, 400);  // about 340,000 splats, 7 MB: more than a first frame's share
  bool sawUpload = false;
  for (int frame = 0; frame < 20000 && !(state.preview.get() != small && !editor.uploading());
       ++frame) {
    const bool wasUploading = editor.uploading();
    editor.frame();
    if (wasUploading) {  // the frame loop kept frames coming: no wait for events (a mouse move)
      EXPECT_EQ(editor.lastWaitSeconds(), 0.0) << "a frame waited while a result was uploading";
    }
    if (editor.uploading()) {
      sawUpload = true;
      EXPECT_EQ(state.preview.get(), small) << "the last result stays shown meanwhile";
    }
  }
  EXPECT_TRUE(sawUpload);
  ASSERT_NE(state.preview.get(), small);
  ASSERT_TRUE(editor.waitForPreview(60.0)) << state.previewError;
  EXPECT_EQ(state.preview->resolution, 400);
  EXPECT_EQ(state.uploadedBytes, state.preview->splatCount() * sizeof(Splat));
  editor.camera().setAxisView(AxisView::Front);
  editor.viewAll();
  const int w = 240, h = 200;
  const std::vector<uint8_t> image = editor.renderViewport(w, h);
  int red = 0;  // the disc (about 17,000 pixels; its centre is the highlight)
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) red += reddish(at(image, w, x, y)) ? 1 : 0;
  EXPECT_GT(red, 12000);
  EXPECT_FALSE(reddish(at(image, w, 2, 2)));
  undo(state);  // resolution 400
  undo(state);  // resolution 32
  undo(state);  // colour
  undo(state);  // add
  EXPECT_TRUE(state.document.root()->children.empty());
}

// A red sphere moved six times along x, then seen from the front at 64 cells; the moves' results
// that went through mapped GL buffers (copied from one on the GPU) in *mapped.
std::vector<uint8_t> movedSphereImage(EditorOptions options, size_t* mapped) {
  Editor editor(std::move(options));
  EditorState& state = editor.state();
  const NodeId sphere = addRedSphere(state);
  EXPECT_NE(sphere, 0u);
  setResolution(state, 64);
  clearSelection(state);
  EXPECT_TRUE(editor.waitForPreview(60.0)) << state.previewError;
  const double step = 0.37 * Evaluator::gridFor(state.document.scene(), 0).h;
  const size_t before = editor.resultsInMappedBuffers();
  for (int k = 0; k < 6; ++k) {
    Transform t = findNode(state.document.root(), sphere)->transform;
    t.translate.x += step;  // each result unlike every earlier one
    state.document.setTransform(sphere, t);
    EXPECT_TRUE(editor.waitForPreview(60.0)) << state.previewError;
  }
  editor.camera().setAxisView(AxisView::Front);
  editor.viewAll();
  std::vector<uint8_t> image = editor.renderViewport(240, 200);
  *mapped = editor.resultsInMappedBuffers() - before;
  for (int k = 0; k < 6 + 3; ++k) undo(state);  // the moves, the resolution, colour and add
  EXPECT_TRUE(state.document.root()->children.empty());
  return image;
}

TEST(EditorWindow, DeviceSplatsGoStraightIntoMappedBuffersAndLookAsUploaded) {
  REQUIRE_DISPLAY();
  size_t mapped = 0, uploaded = 0;
  const std::vector<uint8_t> host = movedSphereImage(testOptions(), &uploaded);
  EXPECT_EQ(uploaded, 0u) << "host splats are uploaded as they are";
  EditorOptions options = testOptions();
  options.makeBackend = [] { return std::make_shared<test::OffHostSplatsBackend>(); };
  const std::vector<uint8_t> device = movedSphereImage(options, &mapped);
  // The first result takes the worker's arrays; the buffers then grow for the next, and each
  // of the six moves' results goes through one of the three (each lent twice, at least one
  // after the GPU's copy from it).
  EXPECT_EQ(mapped, 6u) << "results copied straight into mapped GL buffers";
  ASSERT_EQ(device.size(), host.size());
  size_t differ = 0;
  for (size_t i = 0; i < host.size(); ++i) differ += device[i] != host[i];
  EXPECT_EQ(differ, 0u) << "the same pixels as the host upload";
  int red = 0;
  for (int y = 0; y < 200; ++y)
    for (int x = 0; x < 240; ++x) red += reddish(at(device, 240, x, y)) ? 1 : 0;
  EXPECT_GT(red, 10000);
}

// A change of the ghosts alone (shown with G, or finished after the result they belong to)
// draws them over the kept image of the splats: not one splat is drawn again (the whole image
// was drawn again, under a software GL driver a coarse image refined over a second).
TEST(EditorWindow, AChangeOfTheGhostsAloneDrawsNoSplatAgain) {
  REQUIRE_DISPLAY();
  Editor editor(testOptions());
  EditorState& state = editor.state();
  const NodeId block = addPrimitive(state, NodeKind::Box);
  state.placeMode = PlaceMode::Cut;
  ASSERT_NE(addPrimitive(state, NodeKind::Cylinder), 0u);
  state.placeMode = PlaceMode::Add;
  ASSERT_TRUE(findNode(state.document.root(), block));
  clearSelection(state);
  setResolution(state, 48);
  ASSERT_TRUE(editor.waitForPreview(60.0)) << state.previewError;
  const auto drawn = [&] {
    return editor.splatsDrawnAsPoints() + editor.splatsDrawnAsQuads() +
           editor.splatsDrawnByCompute();
  };
  const auto settle = [&] {
    for (int i = 0; i < 2000 && !(editor.viewSettled() && !editor.uploading()); ++i) editor.frame();
    for (int i = 0; i < 3; ++i) editor.frame();
  };
  settle();
  const size_t before = drawn();
  ASSERT_GT(before, 0u);
  const std::shared_ptr<const PreviewResult> shown = state.preview;
  state.showAllGhosts = true;
  for (int i = 0; i < 2000 && !(state.preview && !state.preview->ghosts.empty()); ++i)
    editor.frame();
  ASSERT_TRUE(state.preview && !state.preview->ghosts.empty()) << "no ghost came";
  EXPECT_NE(state.preview, shown);
  EXPECT_EQ(state.preview->splats, shown->splats) << "the same splats";
  settle();
  EXPECT_GT(editor.shownGhostSplats(), 0u) << "the ghosts reached the view";
  EXPECT_EQ(drawn(), before) << "the splats were drawn again for a change of the ghosts";
  state.showAllGhosts = false;
  settle();
  EXPECT_EQ(editor.shownGhostSplats(), 0u);
  EXPECT_EQ(drawn(), before);
  undo(state);  // resolution
  undo(state);  // cutter
  undo(state);  // box
  EXPECT_TRUE(state.document.root()->children.empty());
}

TEST(EditorWindow, DifferenceShowsTheHoleFromAbove) {
  REQUIRE_DISPLAY();
  Editor editor(testOptions());
  EditorState& state = editor.state();
  NodeId block = addPrimitive(state, NodeKind::Box);
  clearSelection(state);
  NodeId hole = addPrimitive(state, NodeKind::Cylinder);
  ASSERT_TRUE(guarded(state, [&] {
    PrimitiveParams box;
    box.size = glm::dvec3(4.0, 4.0, 1.0);
    state.document.setParams(block, box);
    PrimitiveParams cylinder;
    cylinder.radius = 1.0;
    cylinder.height = 3.0;
    state.document.setParams(hole, cylinder);
    state.document.setColor(block, glm::vec3(0.1f, 0.3f, 0.95f));
  }));
  state.selection = {block, hole};
  groupSelection(state, NodeKind::Difference);
  clearSelection(state);
  setResolution(state, 64);
  state.showGrid = false;
  ASSERT_TRUE(editor.waitForPreview(60.0)) << state.previewError;
  editor.camera().setAxisView(AxisView::Top);
  editor.camera().ortho = true;
  editor.viewAll();
  const int w = 200, h = 200;
  std::vector<uint8_t> image = editor.renderViewport(w, h);
  EXPECT_FALSE(bluish(at(image, w, w / 2, h / 2))) << "the hole";
  // Halfway between the hole's rim (radius 1) and the block's edge (2): the block's top.
  // viewAll frames the bounding sphere; locate the block's extent in the row instead.
  int left = -1, right = -1;
  for (int x = 0; x < w; ++x)
    if (bluish(at(image, w, x, h / 2))) {
      if (left < 0) left = x;
      right = x;
    }
  ASSERT_GE(left, 0);
  const double cx = (left + right) * 0.5, half = (right - left) * 0.5;
  EXPECT_NEAR(cx, w * 0.5, 3.0);
  EXPECT_TRUE(bluish(at(image, w, int(cx + half * 0.75), h / 2)));
  EXPECT_FALSE(bluish(at(image, w, int(cx + half * 0.3), h / 2)));  // inside the hole
}

// The first and last pixel of row `y` where `match` holds (-1, -1 when none does).
struct Span {
  int first = -1, last = -1;
  double centre() const { return (first + last) * 0.5 + 0.5; }
};
template <typename Match>
Span spanInRow(const std::vector<uint8_t>& image, int width, int y, Match match) {
  Span span;
  for (int x = 0; x < width; ++x)
    if (match(at(image, width, x, y))) {
      if (span.first < 0) span.first = x;
      span.last = x;
    }
  return span;
}

// A red sphere (radius 0.5) at the origin and a blue unit box at x = 3, evaluated at 48, no
// grid, nothing selected; look() renders it 320 x 200 from an axis.
// Grouping the selection as a modifier (the palette's "group selection as round"): one undo
// step, a radius from the parts' size (3% of the largest side), the preview rounds them.
TEST(EditorWindow, GroupAsRoundIsOneUndoStepWithARadiusFromTheParts) {
  REQUIRE_DISPLAY();
  Editor editor(testOptions());
  EditorState& state = editor.state();
  NodeId block = addPrimitive(state, NodeKind::Box);
  ASSERT_TRUE(guarded(state, [&] {
    PrimitiveParams box;
    box.size = glm::dvec3(10.0, 10.0, 4.0);
    state.document.setParams(block, box);
  }));
  setResolution(state, 64);
  ASSERT_TRUE(editor.waitForPreview(60.0)) << state.previewError;
  const double plain = state.preview->stats.measure.volume;
  const std::string before = sceneToJson(state.document.scene());
  state.selection = {block};
  groupSelection(state, NodeKind::Round);
  ASSERT_EQ(state.selection.size(), 1u);
  NodePtr round = findNode(state.document.root(), state.selection[0]);
  ASSERT_TRUE(round);
  EXPECT_EQ(round->kind, NodeKind::Round);
  EXPECT_DOUBLE_EQ(round->amount, 0.3);  // 3% of 10
  ASSERT_TRUE(editor.waitForPreview(60.0)) << state.previewError;
  EXPECT_LT(state.preview->stats.measure.volume, plain - 0.1);  // its edges were rounded
  undo(state);
  EXPECT_EQ(sceneToJson(state.document.scene()), before);
}

// Grouping the selection as each pattern: one undo step, copies spaced from the parts' size
// (an array: 3 along x, a quarter of their width apart; a mirror across x keeping the
// original), the preview's volume multiplied by the disjoint copies; switching an array to a
// circular array respaces it; every step undoes.
TEST(EditorWindow, GroupAsAPatternIsOneUndoStepSpacedFromTheParts) {
  REQUIRE_DISPLAY();
  Editor editor(testOptions());
  EditorState& state = editor.state();
  NodeId block = addPrimitive(state, NodeKind::Box);
  ASSERT_TRUE(guarded(state, [&] {
    PrimitiveParams box;
    box.size = glm::dvec3(8.0, 4.0, 4.0);
    state.document.setParams(block, box);
    Transform t;
    t.translate = glm::dvec3(10.0, 0.0, 0.0);  // off the mirror plane and the circle's axis
    state.document.setTransform(block, t);
  }));
  setResolution(state, 128);
  ASSERT_TRUE(editor.waitForPreview(60.0)) << state.previewError;
  const double one = 8.0 * 4.0 * 4.0;
  // The LDI's volume of n copies: within half a cell of their surface (area 160 each) of n x 128.
  auto expectCopies = [&](int n) {
    const double h = state.preview->stats.grid.h;
    EXPECT_NEAR(state.preview->stats.measure.volume, n * one, 0.5 * n * 160.0 * h) << n;
  };
  expectCopies(1);
  const std::string before = sceneToJson(state.document.scene());
  state.selection = {block};
  groupSelection(state, NodeKind::Array);
  NodePtr array = findNode(state.document.root(), state.selection.at(0));
  ASSERT_TRUE(array && array->kind == NodeKind::Array);
  EXPECT_EQ(array->pattern.counts, glm::ivec3(3, 1, 1));
  EXPECT_DOUBLE_EQ(array->pattern.step.x, 10.0);  // 1.25 x 8
  ASSERT_TRUE(editor.waitForPreview(60.0)) << state.previewError;
  expectCopies(3);
  PatternParams grid = array->pattern;
  grid.counts = glm::ivec3(2, 2, 1);
  state.document.setPattern(array->id, grid);
  setSelectionOperation(state, NodeKind::CircularArray);
  array = findNode(state.document.root(), array->id);
  EXPECT_EQ(array->pattern.count, 6);
  ASSERT_TRUE(editor.waitForPreview(60.0)) << state.previewError;
  expectCopies(6);  // at radius 10 they are disjoint
  // Back to an array: its 2 x 2 as it was (3 copies again, an artist's test), and back to a
  // circular array: its 6.
  setSelectionOperation(state, NodeKind::Array);
  EXPECT_EQ(findNode(state.document.root(), array->id)->pattern.counts, glm::ivec3(2, 2, 1));
  setSelectionOperation(state, NodeKind::CircularArray);
  EXPECT_EQ(findNode(state.document.root(), array->id)->pattern.count, 6);
  for (int i = 0; i < 5; ++i) undo(state);
  EXPECT_EQ(sceneToJson(state.document.scene()), before);

  state.selection = {block};
  groupSelection(state, NodeKind::Mirror);
  NodePtr mirror = findNode(state.document.root(), state.selection.at(0));
  ASSERT_TRUE(mirror && mirror->kind == NodeKind::Mirror);
  EXPECT_TRUE(mirror->pattern.keepOriginal);
  ASSERT_TRUE(editor.waitForPreview(60.0)) << state.previewError;
  expectCopies(2);
  const Bounds shown = selectionBounds(state.document.root(), {mirror->id});
  EXPECT_NEAR(shown.min.x, -14.0, 1e-9);
  EXPECT_NEAR(shown.max.x, 14.0, 1e-9);
  undo(state);
  EXPECT_EQ(sceneToJson(state.document.scene()), before);
}

class SphereAndBox : public testing::Test {
 protected:
  static constexpr int w = 320, h = 200;
  void SetUp() override {
    REQUIRE_DISPLAY();
    editor = std::make_unique<Editor>(testOptions());
    EditorState& state = editor->state();
    sphere = addPrimitive(state, NodeKind::Sphere);
    clearSelection(state);
    box = addPrimitive(state, NodeKind::Box);
    ASSERT_TRUE(guarded(state, [&] {
      PrimitiveParams cube;
      cube.size = glm::dvec3(1.0);
      state.document.setParams(box, cube);
      state.document.setTransform(sphere, Transform());  // centred on the origin (the views')
      state.document.setColor(sphere, glm::vec3(0.9f, 0.1f, 0.1f));
      state.document.setColor(box, glm::vec3(0.1f, 0.3f, 0.95f));
      Transform t;
      t.translate = glm::dvec3(3.0, 0.0, 0.0);
      state.document.setTransform(box, t);
    }));
    clearSelection(state);
    setResolution(state, 48);
    state.showGrid = false;
    ASSERT_TRUE(editor->waitForPreview(60.0)) << state.previewError;
    cellSize = state.preview->stats.grid.h;
  }
  std::vector<uint8_t> look(AxisView view, bool ortho) {
    editor->camera().setAxisView(view);
    editor->camera().ortho = ortho;
    editor->viewAll();
    return editor->renderViewport(w, h);
  }
  std::unique_ptr<Editor> editor;
  NodeId sphere = 0, box = 0;
  double cellSize = 0.0;
};

TEST_F(SphereAndBox, PickingReadsTheLeafAndThePointUnderTheCursor) {
  const std::vector<uint8_t> image = look(AxisView::Front, false);  // looking along +y
  const Span redSpan = spanInRow(image, w, h / 2, reddish);
  const Span blueSpan = spanInRow(image, w, h / 2, bluish);
  ASSERT_GE(redSpan.first, 0);
  ASSERT_GE(blueSpan.first, 0);
  const int redX = redSpan.first + 6, blueX = blueSpan.last - 6;  // inside each silhouette
  std::optional<PickHit> red = editor->pickViewport(w, h, redX + 0.5, h / 2 + 0.5);
  ASSERT_TRUE(red);
  EXPECT_EQ(red->leaf, sphere);
  EXPECT_FALSE(red->cap);
  EXPECT_NEAR(glm::length(red->position), 0.5, 1.5 * cellSize);  // on the sphere
  EXPECT_LT(red->position.y, 0.0);                               // its front
  std::optional<PickHit> blue = editor->pickViewport(w, h, blueX + 0.5, h / 2 + 0.5);
  ASSERT_TRUE(blue);
  EXPECT_EQ(blue->leaf, box);
  EXPECT_NEAR(blue->position.y, -0.5, 1.5 * cellSize);  // the box's front face
  EXPECT_FALSE(editor->pickViewport(w, h, 2.5, 2.5)) << "a corner shows no surface";
}

TEST_F(SphereAndBox, SectionPlaneCutsAndCapsTheSolid) {
  EditorState& state = editor->state();
  // Look from +y at the sphere's back; the plane y = 0 keeps the half towards -y.
  const std::vector<uint8_t> whole = look(AxisView::Back, true);
  const Span red = spanInRow(whole, w, h / 2, reddish);
  ASSERT_GE(red.first, 0);
  const double sphereX = red.centre();
  std::optional<PickHit> back = editor->pickViewport(w, h, sphereX, h / 2 + 0.5);
  ASSERT_TRUE(back);
  EXPECT_NEAR(back->position.y, 0.5, 1.5 * cellSize);  // the sphere's back
  EXPECT_FALSE(back->cap);

  state.section.on = true;
  state.section.axis = 1;
  state.section.at = 0.0;  // scene units
  std::optional<PickHit> cap = editor->pickViewport(w, h, sphereX, h / 2 + 0.5);
  ASSERT_TRUE(cap);
  EXPECT_TRUE(cap->cap);
  EXPECT_EQ(cap->leaf, sphere);
  EXPECT_NEAR(cap->position.y, 0.0, 1e-6);  // on the plane
  const std::vector<uint8_t> cut = editor->renderViewport(w, h);
  EXPECT_TRUE(reddish(at(cut, w, int(sphereX), h / 2))) << "the cap has the leaf's colour";
  // The cap is filled: every pixel inside the cut disc (radius 0.5, less a cell) is red.
  const double pixelsPerUnit = (red.last - red.first + 1) / 1.0;
  const int r = int((0.5 - cellSize) * pixelsPerUnit);
  int holes = 0, inside = 0;
  for (int dy = -r; dy <= r; ++dy)
    for (int dx = -r; dx <= r; ++dx)
      if (dx * dx + dy * dy <= r * r) {
        ++inside;
        holes += reddish(at(cut, w, int(sphereX) + dx, h / 2 + dy)) ? 0 : 1;
      }
  EXPECT_GT(inside, 100);
  EXPECT_EQ(holes, 0);
  // Flipped, the plane keeps the far half: the view shows its outside, not a cap.
  state.section.flip = true;
  std::optional<PickHit> far = editor->pickViewport(w, h, sphereX, h / 2 + 0.5);
  ASSERT_TRUE(far);
  EXPECT_FALSE(far->cap);
  EXPECT_NEAR(far->position.y, 0.5, 1.5 * cellSize);
}

TEST_F(SphereAndBox, PaletteDropLandsOnTheSurfaceOrTheGround) {
  EditorState& state = editor->state();
  const std::vector<uint8_t> image = look(AxisView::Top, true);  // looking down -z
  const Span blue = spanInRow(image, w, h / 2, bluish);
  ASSERT_GE(blue.first, 0);
  // On the box's top face (z = 0.5).
  Placement top = editor->placementInViewport(w, h, blue.centre(), h / 2 + 0.5);
  EXPECT_FALSE(top.onGround);
  EXPECT_NEAR(top.point.z, 0.5, 1.5 * cellSize);
  EXPECT_NEAR(top.point.x, 3.0, 0.25);  // within the box's top (half width 0.5)
  EXPECT_NEAR(top.point.y, 0.0, 0.25);
  // Beside everything: the ground plane z = 0.
  Placement ground = editor->placementInViewport(w, h, 4.5, 4.5);
  EXPECT_TRUE(ground.onGround);
  EXPECT_EQ(ground.point.z, 0.0);
  NodeId cone = addPrimitiveAt(state, NodeKind::Cone, ground);
  const Bounds b = selectionBounds(state.document.root(), {cone});
  EXPECT_NEAR(b.min.z, 0.0, 1e-9);
  EXPECT_NEAR(b.center().x, ground.point.x, 1e-9);
  EXPECT_NEAR(b.center().y, ground.point.y, 1e-9);
}

#if defined(STRATA_HAVE_XTEST)
// Input made while frames are slow (250 ms each, as on a loaded software-GL machine), through the
// X server as a user's hand would make it (XTest): a Ctrl+Z tapped within one frame undoes, a
// double-click on a tree row within one frame starts renaming it, and a box drag pressed, moved
// and released within one frame selects what it covers. Each must be handled, once.
class XInput {
 public:
  XInput() : display_(XOpenDisplay(nullptr)) {}
  ~XInput() {
    if (display_) XCloseDisplay(display_);
  }
  bool ok() const { return display_ != nullptr; }
  void move(int x, int y) {
    XTestFakeMotionEvent(display_, -1, x, y, 0);
    XFlush(display_);
  }
  void button(bool down) {
    XTestFakeButtonEvent(display_, 1, down ? True : False, 0);
    XFlush(display_);
  }
  void key(KeySym symbol, bool down) {
    XTestFakeKeyEvent(display_, XKeysymToKeycode(display_, symbol), down ? True : False, 0);
    XFlush(display_);
  }

 private:
  Display* display_;
};

// Runs frames until `done` or 5 s.
bool framesUntil(Editor& editor, const std::function<bool()>& done) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (std::chrono::steady_clock::now() < end) {
    editor.frame();
    if (done()) return true;
  }
  return false;
}

TEST(EditorWindow, ClicksKeysAndDoubleClicksDuringSlowFramesAreAllHandled) {
  REQUIRE_DISPLAY();
  XInput input;
  if (!input.ok()) GTEST_SKIP() << "cannot open the display for XTest";
  EditorOptions options = testOptions();
  options.visible = true;
  options.slowFrameSeconds = 0.25;
  Editor editor(options);
  EditorState& state = editor.state();
  int wx = 0, wy = 0;
  editor.windowOrigin(&wx, &wy);
  input.move(wx + 700, wy + 400);  // keys go where the pointer is (no window manager)
  for (int i = 0; i < 3; ++i) editor.frame();

  // A Ctrl+Z tapped between two frames.
  const NodeId box = addPrimitive(state, NodeKind::Box);
  ASSERT_TRUE(findNode(state.document.root(), box));
  editor.frame();
  input.key(XK_Control_L, true);
  input.key(XK_z, true);
  input.key(XK_z, false);
  input.key(XK_Control_L, false);
  EXPECT_TRUE(framesUntil(editor, [&] { return !findNode(state.document.root(), box); }))
      << "the Ctrl+Z made during a slow frame was lost";

  // A double-click on the tree's first row (the root), both clicks within one frame.
  input.move(wx + 90, wy + 66);
  editor.frame();
  for (int click = 0; click < 2; ++click) {
    input.button(true);
    input.button(false);
  }
  const NodeId root = state.document.root()->id;
  EXPECT_TRUE(framesUntil(editor, [&] { return state.renaming == root; }))
      << "the double-click made during a slow frame was not seen as one";
  input.key(XK_Escape, true);
  input.key(XK_Escape, false);
  framesUntil(editor, [&] { return state.renaming == 0; });

  // A box drag across the view, pressed, moved and released within one frame: it selects the
  // parts it covers (two boxes side by side).
  addPrimitive(state, NodeKind::Box);
  clearSelection(state);
  ASSERT_TRUE(editor.waitForPreview(60.0));
  for (int i = 0; i < 3; ++i) editor.frame();
  input.move(wx + 340, wy + 60);
  editor.frame();
  input.button(true);
  for (int step = 1; step <= 8; ++step) input.move(wx + 340 + step * 110, wy + 60 + step * 85);
  input.button(false);
  const bool selected = framesUntil(editor, [&] { return !state.selection.empty(); });
  if (!selected) {
    int w = 0, h = 0;
    auto px = editor.screenshot(&w, &h);
    writePng("/tmp/slowframes.png", w, h, px);
  }
  EXPECT_TRUE(selected) << "the box drag made during a slow frame selected nothing; window at "
                        << wx << ", " << wy
                        << "; last message: " << (state.log.empty() ? "" : state.log.back().text)
                        << " (the window is in /tmp/slowframes.png)";

  // A click on the inspector's name field, Ctrl+A and a new name typed, all within one frame:
  // the keys reach the field after the click that activates it (they used to go first: Ctrl+A
  // did nothing and the typed text was appended to the old name).
  const NodeId named = state.document.root()->children.at(0)->id;
  state.selection = {named};
  for (int i = 0; i < 2; ++i) editor.frame();
  input.move(wx + 1120, wy + 85);
  editor.frame();
  input.button(true);
  input.button(false);
  input.key(XK_Control_L, true);
  input.key(XK_a, true);
  input.key(XK_a, false);
  input.key(XK_Control_L, false);
  for (KeySym k : {XK_h, XK_o, XK_l, XK_e, XK_Return}) {
    input.key(k, true);
    input.key(k, false);
  }
  const bool renamed =
      framesUntil(editor, [&] { return findNode(state.document.root(), named)->name == "hole"; });
  if (!renamed) {
    int w = 0, h = 0;
    auto px = editor.screenshot(&w, &h);
    writePng("/tmp/slowframes_name.png", w, h, px);
  }
  EXPECT_TRUE(renamed) << "named '" << findNode(state.document.root(), named)->name
                       << "' (the window is in /tmp/slowframes_name.png)";
}
#endif

}  // namespace
}  // namespace strata::ui
