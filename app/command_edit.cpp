// `strata edit` and `strata render`: the editor (ui/) on the backend chosen here. Compiled in
// every build; without the editor (STRATA_HAS_EDITOR unset) both say so and edit falls back to
// the command line.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "app/cli_common.h"
#include "app/commands.h"
#include "app/editor_commands.h"
#include "engine/document/commands.h"
#include "engine/eval/evaluator.h"
#include "engine/io/mesh_formats.h"
#include "engine/io/recovery_slots.h"
#include "engine/io/scene_file.h"
#include "engine/io/user_files.h"
#include "engine/ldi/grid.h"
#include "engine/util/error.h"
#include "engine/util/parallel_for.h"
#include "engine/util/timer.h"
#if defined(STRATA_HAS_EDITOR)
#include "app/cuda_gl_splat_copier.h"
#include "app/cuda_host_pinning.h"
#include "ui/editor.h"
#include "ui/editor_actions.h"
#include "ui/gl_window.h"
#include "ui/headless_gl.h"
#include "ui/png_file.h"
#include "ui/scene_render.h"
#endif

namespace strata {
namespace {

std::vector<std::string> editorValuedOptions() {
  std::vector<std::string> valued = kValuedOptions;
  for (const char* o :
       {"--width", "--height", "--screenshot", "--view", "--measure-latency", "--move-leaf",
        "--section", "--measure-frames", "--select", "--splats", "--edit-wait"})
    valued.push_back(o);
  return valued;
}

std::vector<std::string> editorFlagOptions() {
  std::vector<std::string> flags = kFlagOptions;
  flags.push_back("--no-interop");
  flags.push_back("--no-pinning");
  flags.push_back("--ortho");
  flags.push_back("--ghosts");
  flags.push_back("--drag");
  return flags;
}

// Without an editor: the command line's evaluation of the same scene, with the options it takes.
int fallBackToEval(const std::string& scene, const CliArgs& args, const std::string& why) {
  std::fprintf(stderr, "strata: cannot open the editor: %s\n", why.c_str());
  std::fprintf(stderr, "strata: evaluating %s on the command line instead\n", scene.c_str());
  std::vector<std::string> evalArgs{scene};
  for (const char* o : {"--backend", "--threads", "--resolution"})
    if (args.has(o)) evalArgs.insert(evalArgs.end(), {o, args.text(o, "")});
  return runEval(evalArgs);
}

#if defined(STRATA_HAS_EDITOR)
// The leaf named `name` (or the last leaf of the tree when empty) in `node`'s subtree.
NodePtr findLeaf(const NodePtr& node, const std::string& name) {
  if (!node) return nullptr;
  NodePtr found;
  if (!isOperation(node->kind) && (name.empty() || node->name == name)) found = node;
  for (const auto& c : node->children)
    if (NodePtr f = findLeaf(c, name)) found = f;
  return found;
}

// `--select "NAME[,NAME...]"`: selects the nodes with those names (each must exist).
void selectByNames(ui::EditorState& state, const std::string& list) {
  if (list.empty()) return;
  size_t start = 0;
  while (start <= list.size()) {
    const size_t comma = std::min(list.find(',', start), list.size());
    const std::string name = list.substr(start, comma - start);
    NodeId found = 0;
    for (NodeId id : treeOrder(state.document.root()))
      if (findNode(state.document.root(), id)->name == name) found = id;
    if (!found) throw Error("--select: no node named '" + name + "'");
    state.selection.push_back(found);
    start = comma + 1;
  }
}

// `strata edit SCENE --measure-latency N [--move-leaf NAME]`: N times, moves a leaf by a small
// step through the document (as a drag's release would) and runs frames until the window shows
// the surfels of that edit at the scene's resolution and the view's level of detail; prints each
// time from the edit to the end of that frame (buffers swapped, GL finished), and the median; and
// the same to the end of the frame that first showed the edit's result (a coarser level where
// the view's would take long: ViewportRenderer::kFirstImageMs).
// With `drag`, the N moves are one drag (the hand held on the part, as the gizmo holds it): each
// move's time is to the first frame that shows its result, whatever its resolution (a draft:
// PreviewWorker), printed with that resolution; then the release, to the full result on screen.
int measureDrag(ui::Editor& editor, NodePtr leaf, int count, double step) {
  Document& document = editor.state().document;
  const int full = document.scene().settings.resolution;
  std::vector<double> ms;
  int fullSteps = 0;
  editor.holdDrag(true);
  document.beginInteraction();
  for (int k = 0; k < count; ++k) {
    Transform t = leaf->transform;
    t.translate.x += (k % 2 == 0 ? step : -step);
    Stopwatch clock;
    document.setTransform(leaf->id, t);
    leaf = findNode(document.root(), leaf->id);
    const uint64_t revision = document.revision();
    int frames = 0;
    for (;;) {
      editor.frame();
      ++frames;
      const auto& p = editor.state().preview;
      if (p && p->tag == revision) break;
      if (clock.seconds() > 60.0) throw Error("a drag's move did not reach the screen within 60 s");
    }
    ms.push_back(clock.seconds() * 1e3);
    const auto& shown = *editor.state().preview;
    fullSteps += shown.resolution == full;
    std::printf(
        "drag move %d: %.1f ms to the screen at %d cells (engine %.1f + splats %.1f ms, "
        "%d frames)\n",
        k + 1, ms.back(), shown.resolution, shown.stats.seconds * 1e3, shown.splatSeconds * 1e3,
        frames);
    std::fflush(stdout);
  }
  Stopwatch release;
  document.endInteraction();
  editor.holdDrag(false);
  const uint64_t revision = document.revision();
  for (;;) {
    editor.frame();
    const auto& p = editor.state().preview;
    if (p && p->tag == revision && !p->coarse && editor.viewSettled()) break;
    if (release.seconds() > 60.0) throw Error("the drag's full result did not arrive in 60 s");
  }
  const double releaseMs = release.seconds() * 1e3;
  std::sort(ms.begin(), ms.end());
  std::printf(
      "drag: median %.1f ms, worst %.1f ms a move over %d moves of '%s', %d of them at the full "
      "%d cells; released: the full result settled on screen %.1f ms later (%s)\n",
      ms[ms.size() / 2], ms.back(), count, leaf->name.c_str(), fullSteps, full, releaseMs,
      editor.state().backendDescription.c_str());
  return 0;
}

int measureLatency(ui::Editor& editor, int count, const std::string& leafName, bool drag) {
  NodePtr leaf = findLeaf(editor.state().document.root(), leafName);
  if (!leaf) throw Error("--move-leaf: no leaf named '" + leafName + "'");
  if (!editor.waitForPreview(600.0)) throw Error("the first evaluation did not finish");
  for (int i = 0; i < 3; ++i) editor.frame();
  const double step = Evaluator::gridFor(editor.state().document.scene(), 0).h * 0.37;
  if (drag) return measureDrag(editor, leaf, count, step);
  std::vector<double> ms, firstMs;
  const size_t pointsBefore = editor.splatsDrawnAsPoints();
  const size_t quadsBefore = editor.splatsDrawnAsQuads();
  const size_t computedBefore = editor.splatsDrawnByCompute();
  for (int k = 0; k < count; ++k) {
    Transform t = leaf->transform;
    t.translate.x += (k % 2 == 0 ? step : -step);
    Stopwatch clock;
    editor.state().document.setTransform(leaf->id, t);
    leaf = findNode(editor.state().document.root(), leaf->id);
    const uint64_t revision = editor.state().document.revision();
    // Where the time goes: the engine's passes (evaluation and splats, as the results report
    // them), the transfer of the full result into GL, and the frames drawn meanwhile.
    int frames = 0, framesAfterResult = 0;
    std::string firstImage;  // what the first frame with the result showed
    double resultAtMs = -1.0;
    std::string frameTimes;  // the UI thread's time of each frame from the one that took the result
    for (;;) {
      editor.frame();
      ++frames;
      const auto& p = editor.state().preview;
      if (p && p->tag == revision && !p->coarse) {
        if (resultAtMs < 0.0) resultAtMs = clock.seconds() * 1e3;
        if (++framesAfterResult == 1) {  // the frame that brought the result to the screen
          firstMs.push_back(clock.seconds() * 1e3);
          firstImage = editor.showsCoarseImage()
                           ? "a coarse image"
                           : "level of detail " + std::to_string(editor.shownDetailLevel());
        }
        char t[96];
        const auto& parts = editor.state().frameParts;
        std::snprintf(t, sizeof t, "%s%.1f (build %.1f, view %.1f, panels %.1f, present %.1f)",
                      frameTimes.empty() ? "" : " ", editor.state().frameMs, parts.build,
                      parts.view, parts.panels, parts.present);
        frameTimes += t;
        if (editor.viewSettled()) break;
      }
      if (clock.seconds() > 60.0) throw Error("an edit did not reach the screen within 60 s");
    }
    ms.push_back(clock.seconds() * 1e3);
    const auto& shown = *editor.state().preview;
    std::printf(
        "edit %d: %.1f ms from the edit to its surfels on screen (first image at %.1f ms, %s; "
        "full result in the UI at %.1f ms: engine %.1f + splats %.1f ms, transfer "
        "%.1f ms; %d frames, %d from the result on, taking %s ms)\n",
        k + 1, ms.back(), firstMs.back(), firstImage.c_str(), resultAtMs, shown.stats.seconds * 1e3,
        shown.splatSeconds * 1e3, editor.state().uploadMs, frames, framesAfterResult,
        frameTimes.c_str());
    std::fflush(stdout);  // each edit's line as it comes (a long run may be stopped)
  }
  std::sort(ms.begin(), ms.end());
  std::sort(firstMs.begin(), firstMs.end());
  std::printf(
      "first image: median %.1f ms, best %.1f ms, worst %.1f ms (the edit's result on screen; a "
      "coarser image first where the view's level costs more than %.0f ms to draw)\n",
      firstMs[firstMs.size() / 2], firstMs.front(), firstMs.back(),
      ui::ViewportRenderer::kFirstImageMs);
  std::printf(
      "latency: median %.1f ms, best %.1f ms, worst %.1f ms over %d edits of '%s' (%s; %zu "
      "splats, %zu drawn at level of detail %d; over the edits %zu splats drawn as points, %zu "
      "as quads, %zu by compute; measured %.2f ns a splat as points, %.2f as quads, %.2f by "
      "compute)\n",
      ms[ms.size() / 2], ms.front(), ms.back(), count, leaf->name.c_str(),
      editor.state().backendDescription.c_str(), editor.state().preview->splatCount(),
      editor.shownSplats(), editor.shownDetailLevel(), editor.splatsDrawnAsPoints() - pointsBefore,
      editor.splatsDrawnAsQuads() - quadsBefore, editor.splatsDrawnByCompute() - computedBefore,
      editor.splatNanoseconds(ui::SplatPrimitive::Points),
      editor.splatNanoseconds(ui::SplatPrimitive::Quads),
      editor.splatNanoseconds(ui::SplatPrimitive::Compute));
  std::printf("splats reach GL by %s; %zu results were copied straight into mapped GL buffers\n",
              editor.state().splatTransfer.c_str(), editor.resultsInMappedBuffers());
  return 0;
}
#endif

#if defined(STRATA_HAS_EDITOR)
// `strata edit SCENE --measure-frames SECONDS [--resolution N]`: once the scene is shown, runs
// the editor's frame loop for SECONDS while the engine thread evaluates the scene (at N), and
// prints how long the UI thread took per frame (events, panels, splat transfer, drawing; not the
// idle wait) while the evaluation was running: the UI must keep 60 frames a second (16.7 ms)
// whatever the engine does.
int measureFrames(ui::Editor& editor, double seconds, int resolution) {
  ui::EditorState& state = editor.state();
  // As a user would: the scene opened and shown first (the window's first frames compile
  // shaders and make its images; they are not frames of the engine at work), then the
  // resolution raised.
  {
    Stopwatch opening;
    editor.waitForPreview(30.0);
    while (!editor.viewSettled() && opening.seconds() < 30.0) editor.frame();
    for (int k = 0; k < 3; ++k) editor.frame();
  }
  if (resolution > 0) ui::setResolution(state, resolution);
  // Every frame turns the camera a little, as a user orbiting would: first while the engine
  // evaluates the new resolution, then, once its result is shown, for as long again.
  std::vector<double> busy, orbiting;
  Stopwatch clock;
  int frames = 0;
  double busySeconds = 0.0, idleSince = -1.0, worstUploadMs = 0.0;
  while (true) {
    const double before = clock.seconds();
    editor.camera().orbit(3.0, 0.0);
    editor.frame();
    ++frames;
    worstUploadMs = std::max(worstUploadMs, state.uploadMs);
    if (state.worker.busy) {
      busy.push_back(state.frameMs);
      busySeconds += clock.seconds() - before;
      idleSince = -1.0;  // a pause between the coarse and the full pass is not the end
    } else {
      if (idleSince < 0.0) idleSince = before;
      orbiting.push_back(state.frameMs);
    }
    if (clock.seconds() > seconds && idleSince >= 0.0 && clock.seconds() - idleSince > 3.0) break;
    if (clock.seconds() > 10.0 * seconds + 60.0) break;
  }
  if (busy.empty()) throw Error("--measure-frames: the evaluation finished before a frame ran");
  auto report = [&](const char* what, std::vector<double> ms) {
    if (ms.empty()) return;
    std::sort(ms.begin(), ms.end());
    auto quantile = [&](double q) { return ms[std::min(ms.size() - 1, size_t(q * ms.size()))]; };
    std::printf(
        "%s: %zu frames; UI thread per frame: median %.2f ms, 99%% %.2f ms, worst %.2f ms\n", what,
        ms.size(), quantile(0.5), quantile(0.99), ms.back());
  };
  std::printf("resolution %d (%s), %d frames in all, %.1f s evaluating\n",
              state.document.scene().settings.resolution, state.backendDescription.c_str(), frames,
              busySeconds);
  std::printf("largest splat transfer of a result: %.1f ms\n", worstUploadMs);
  report("orbiting while evaluating", busy);
  report("orbiting the result", orbiting);
  // The camera at rest: the view's full image is drawn a share a frame until it is complete
  // (under a software rasteriser at 1024 cells, hundreds of frames), then the floor: frames
  // where only the panels may change (a hand on the mouse over the panels), the view kept.
  std::vector<double> refining, still;
  Stopwatch settling;
  while (!editor.viewSettled() && settling.seconds() < 60.0) {
    editor.frame();
    refining.push_back(state.frameMs);
  }
  report("at rest, refining the view's full image", refining);
  if (!editor.viewSettled())
    std::printf("the view's full image was not complete after 60 s: the still frames refine it\n");
  for (int i = 0; i < 60; ++i) {
    editor.frame();
    still.push_back(state.frameMs);
  }
  report("still (panels and the cached view)", still);
  std::printf(
      "splats drawn as points %zu, as quads %zu, by compute %zu; measured %.2f ns a splat as "
      "points, %.2f as quads, %.2f by compute\n",
      editor.splatsDrawnAsPoints(), editor.splatsDrawnAsQuads(), editor.splatsDrawnByCompute(),
      editor.splatNanoseconds(ui::SplatPrimitive::Points),
      editor.splatNanoseconds(ui::SplatPrimitive::Quads),
      editor.splatNanoseconds(ui::SplatPrimitive::Compute));
  return 0;
}

// Sets the editor's backend maker (--backend, --threads) and, for the CUDA backend, the CUDA-GL
// interop copier of its splats (--no-interop: the host upload path, for comparison).
void chooseEditorBackend(const CliArgs& args, ui::EditorOptions* options) {
  if (args.has("--threads")) setWorkerCount(args.integer("--threads", 0, 1, 1024));
  std::string name = args.text("--backend", "auto");
  BackendChoice first = chooseBackend(name);  // fails early, with the reason, for a bad name
  std::fprintf(stderr, "%s\n", first.why.c_str());
  auto spare = std::make_shared<std::shared_ptr<Backend>>(first.backend);
  options->makeBackend = [name, spare]() -> std::shared_ptr<Backend> {
    if (*spare) return std::move(*spare);  // the first caller gets the one made above
    return chooseBackend(name).backend;
  };
  if (first.cuda && !args.has("--no-interop")) options->makeSplatCopier = makeCudaGlSplatCopier;
  // The host path's mapped buffers page-locked for the worker's copies (--no-pinning: not, for
  // comparison).
  if (first.cuda && !args.has("--no-pinning")) options->pinHostMemory = makeCudaHostPinning();
}

// --section AXIS[:AT][:flip], e.g. "y:0.4": the section plane across AXIS at the fraction AT
// of the scene's bounds (default 0.5), cutting away the upper side (the lower with ":flip").
ui::SectionState parseSection(const CliArgs& args) {
  if (!args.has("--section")) return {};
  const std::string text = args.text("--section", "");
  std::vector<std::string> parts;
  size_t start = 0;
  for (;;) {
    size_t colon = text.find(':', start);
    parts.push_back(text.substr(start, colon - start));
    if (colon == std::string::npos) break;
    start = colon + 1;
  }
  const std::string usage =
      "--section: expected AXIS[:AT][:flip] with AXIS x, y or z and AT in "
      "[0, 1], e.g. y:0.4; got '" +
      text + "'";
  if (parts[0].size() != 1 || parts[0][0] < 'x' || parts[0][0] > 'z') throw Error(usage);
  ui::SectionState section;
  section.on = true;
  section.axis = parts[0][0] - 'x';
  for (size_t i = 1; i < parts.size(); ++i) {
    if (parts[i] == "flip") {
      section.flip = true;
      continue;
    }
    char* end = nullptr;
    section.startFraction = std::strtod(parts[i].c_str(), &end);
    if (parts[i].empty() || *end != '\0' ||
        !(section.startFraction >= 0.0 && section.startFraction <= 1.0))
      throw Error(usage);
  }
  return section;
}

ui::SplatPrimitive parseSplats(const CliArgs& args) {
  const std::string word = args.text("--splats", "auto");
  if (auto primitive = ui::parseSplatPrimitive(word)) return *primitive;
  throw Error("--splats: unknown way to draw splats '" + word +
              "' (expected auto, points, quads or compute)");
}

ui::AxisView parseView(const std::string& view, bool* iso) {
  *iso = false;
  if (view == "front") return ui::AxisView::Front;
  if (view == "back") return ui::AxisView::Back;
  if (view == "right") return ui::AxisView::Right;
  if (view == "left") return ui::AxisView::Left;
  if (view == "top") return ui::AxisView::Top;
  if (view == "bottom") return ui::AxisView::Bottom;
  if (view != "iso")
    throw Error("--view: unknown view '" + view +
                "' (expected iso, front, back, right, left, top or bottom)");
  *iso = true;
  return ui::AxisView::Front;
}
#endif

}  // namespace

// What `strata edit` does without a user: a screenshot or a measurement. Each needs a window,
// and none reads or writes the user's files (recovery, recent files, panel sizes).
const char* const kBatchOptions[] = {"--screenshot", "--measure-frames", "--measure-latency"};

bool looksLikeScenePath(const std::string& arg) {
  return arg.size() > 5 && arg.compare(arg.size() - 5, 5, ".json") == 0;
}

int runEdit(const std::vector<std::string>& argv) {
  return runGuarded([&] {
    CliArgs args(argv, editorValuedOptions(), editorFlagOptions());
    if (args.positional().size() > 1)
      throw Error("usage: strata edit [SCENE.strata.json] [--backend B] [--screenshot FILE]");
    if (!args.positional().empty() && args.positional()[0].empty())
      throw Error("edit: the scene's file name is empty (strata edit [SCENE.strata.json])");
    const std::string scene = args.positional().empty() ? demoScenePath() : args.positional()[0];
#if !defined(STRATA_HAS_EDITOR)
    return fallBackToEval(scene, args,
                          "this build has no editor (GLFW, libepoxy or Dear ImGui were missing "
                          "when it was built; see .ci/deps --editor)");
#else
    std::string why;
    if (!ui::editorDisplayAvailable(&why)) {
      // What only a window can do is an error without one, not an evaluation that exits 0.
      for (const char* windowOnly : kBatchOptions)
        if (args.has(windowOnly))
          throw Error(std::string("strata edit ") + windowOnly + " needs a window, and " + why +
                      (std::string(windowOnly) == "--screenshot"
                           ? "; `strata render SCENE -o FILE.png` draws the same view without one"
                           : ""));
      return fallBackToEval(scene, args, why);
    }
    ui::EditorOptions options;
    options.scenePath = scene;
    options.sceneAsTemplate = args.positional().empty();  // the demo: never saved over
    options.bundledScenesFolder = std::filesystem::path(demoScenePath()).parent_path().string();
    chooseEditorBackend(args, &options);
    options.splatPrimitive = parseSplats(args);
    options.editResultWaitSeconds = args.number("--edit-wait", 8.0, 0.0, 1000.0) / 1000.0;
    options.width = args.integer("--width", 1600, 320, 8192);
    options.height = args.integer("--height", 1000, 240, 8192);
    // A size asked for is kept (screenshots, measurements); the default fits the screen.
    options.fitScreen = !args.has("--width") && !args.has("--height");
    const std::string screenshot = args.text("--screenshot", "");
    // A screenshot or a measurement is a batch run: it neither reads nor writes the user's
    // recovery file, recent files or panel sizes (a measurement's edit left a recovery file
    // that the user's next session offered, and its prompt then sat over every later
    // measurement).
    bool batch = false;
    for (const char* option : kBatchOptions) batch = batch || args.has(option);
    if (!batch) {
      options.recentFilesPath = defaultRecentFilesPath();
      if (!userConfigDir().empty()) {
        options.layoutPath = userConfigDir() + "/layout.txt";
        options.exportSettingsPath = userConfigDir() + "/export.txt";
        options.importSettingsPath = userConfigDir() + "/import.txt";
      }
      options.recoveryDir = defaultRecoveryDir();
      options.legacyRecoveryPath = defaultRecoveryPath();  // the one file of earlier versions
    }
    ui::Editor editor(options);
    editor.state().section = parseSection(args);
    selectByNames(editor.state(), args.text("--select", ""));
    editor.state().showAllGhosts = args.has("--ghosts");
    // --resolution: the document opened (an undoable change of its resolution) and each new one
    // are previewed at it (it was read by the measurements only, and silently dropped
    // otherwise). --measure-frames raises it itself once the scene is shown.
    if (args.has("--resolution") && !args.has("--measure-frames")) {
      const int resolution = args.integer("--resolution", 0, kMinResolution, kMaxResolution);
      editor.state().newDocumentResolution = resolution;
      const int own = editor.state().document.scene().settings.resolution;
      if (own != resolution) {
        ui::setResolution(editor.state(), resolution);
        ui::logInfo(editor.state(), "previewed at " + std::to_string(resolution) +
                                        " cells (--resolution; Ctrl+Z goes back to the file's " +
                                        std::to_string(own) + ")");
      }
    }
    if (args.has("--measure-frames"))
      return measureFrames(editor, args.number("--measure-frames", 10.0, 0.1, 3600.0),
                           args.has("--resolution")
                               ? args.integer("--resolution", 0, kMinResolution, kMaxResolution)
                               : 0);
    if (args.has("--measure-latency")) {
      return measureLatency(editor, args.integer("--measure-latency", 10, 1, 1000),
                            args.text("--move-leaf", ""), args.has("--drag"));
    }
    if (screenshot.empty()) return editor.run();
    // Documentation screenshots: the whole window once the preview has settled.
    editor.waitForPreview(600.0);
    for (int i = 0; i < 3; ++i) editor.frame();  // ImGui settles its layout in a frame or two
    int width = 0, height = 0;
    std::vector<uint8_t> pixels = editor.screenshot(&width, &height);
    ui::writePng(screenshot, width, height, pixels);
    std::fprintf(stderr, "strata: wrote %s (%d x %d)\n", screenshot.c_str(), width, height);
    return 0;
#endif
  });
}

int runRender(const std::vector<std::string>& argv) {
  return runGuarded([&] {
    CliArgs args(argv, editorValuedOptions(), editorFlagOptions());
    const std::string output = args.text("-o", args.text("--output", ""));
    if (args.positional().size() != 1 || output.empty())
      throw Error(
          "usage: strata render SCENE.strata.json -o shot.png [--width W] [--height H] "
          "[--resolution N] [--view iso|front|right|top|...] [--ortho] [--section AXIS[:AT]]");
    if (lowerExtension(output) != "png")
      throw Error(output + ": render writes PNG; use a .png name");
    const int width = args.integer("--width", 1280, 16, 8192);
    const int height = args.integer("--height", 800, 16, 8192);
#if !defined(STRATA_HAS_EDITOR)
    (void)width;
    (void)height;
    throw Error("this build has no editor, so it cannot render (see .ci/deps --editor)");
    return 1;
#else
    bool iso = true;
    ui::AxisView view = parseView(args.text("--view", "iso"), &iso);
    ui::SceneRenderOptions options;
    options.width = width;
    options.height = height;
    if (!iso) options.view = view;
    options.ortho = args.has("--ortho");
    options.section = parseSection(args);
    options.splatPrimitive = parseSplats(args);
    if (args.has("--resolution"))
      options.resolution = args.integer("--resolution", 0, kMinResolution, kMaxResolution);
    const std::string scenePath = args.positional()[0];
    Scene scene = loadScene(scenePath);  // a bad file fails here with its message
    if (args.has("--threads")) setWorkerCount(args.integer("--threads", 0, 1, 1024));
    BackendChoice backend = chooseBackend(args.text("--backend", "auto"));
    std::fprintf(stderr, "%s\n", backend.why.c_str());
    // A GL context without a window (EGL) where there is one; else an invisible window, which
    // needs a display.
    std::unique_ptr<ui::HeadlessGl> headless;
    std::unique_ptr<ui::GlWindow> window;
    std::string context;
    try {
      headless = std::make_unique<ui::HeadlessGl>();
      context = headless->description();
    } catch (const Error& e) {
      std::string why;
      if (!ui::displayAvailable(&why))
        throw Error(std::string("strata render: ") + e.what() + "; and no window either: " + why);
      window = std::make_unique<ui::GlWindow>(64, 64, "strata render", false);
      context = "invisible window: " + window->description() + " (" + e.what() + ")";
    }
    std::fprintf(stderr, "strata: rendering with %s\n", context.c_str());
    Progress progress;
    ui::SceneRender render = ui::renderScene(scene, scenePath, backend.backend, options, progress);
    ui::writePng(output, width, height, render.pixels);
    std::printf(
        "wrote %s (%d x %d, %zu splats at resolution %d, %zu drawn as %s at level of detail %d, "
        "evaluated in %.0f ms)\n",
        output.c_str(), width, height, render.splats, render.resolution, render.splatsDrawn,
        render.drawnAsPoints ? "points" : "quads", render.detailLevel,
        render.evaluateSeconds * 1e3);
    return 0;
#endif
  });
}

}  // namespace strata
