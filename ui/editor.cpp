#include "ui/editor.h"

#include "engine/util/memory.h"

#include <epoxy/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <imgui.h>
#include <imgui_internal.h>  // ClearActiveID: a field's drag called off by Ctrl+Z or Escape

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <filesystem>
#include <mutex>
#include <thread>

#include "engine/document/commands.h"
#include "engine/document/roles.h"
#include "engine/io/user_files.h"
#include "engine/util/error.h"
#include "engine/util/timer.h"
#include "ui/dialog_settings.h"
#include "ui/edit_warnings.h"
#include "ui/editor_actions.h"
#include "ui/gl_window.h"
#include "ui/input_queue.h"
#include "ui/panel_renderer.h"
#include "ui/panel_splitters.h"
#include "ui/panels.h"
#include "ui/scene_queries.h"
#include "ui/theme.h"
#include "ui/typed_value.h"
#include "ui/viewport.h"
#include "ui/viewport_renderer.h"
#include "ui/window_redraw.h"

namespace strata::ui {

struct Editor::ResultSignal {
  // Worker thread: a result was published.
  void notify() {
    {
      std::lock_guard<std::mutex> lock(mutex);
      ++published;
    }
    changed.notify_all();
  }
  uint64_t count() {
    std::lock_guard<std::mutex> lock(mutex);
    return published;
  }
  // UI thread: waits until more than `seen` results were published, for at most `seconds`.
  bool waitPast(uint64_t seen, double seconds) {
    std::unique_lock<std::mutex> lock(mutex);
    return changed.wait_for(lock, std::chrono::duration<double>(seconds),
                            [&] { return published > seen; });
  }
  std::mutex mutex;
  std::condition_variable changed;
  uint64_t published = 0;
};

namespace {
// Keys and typed characters, between GLFW and ImGui. ImGui 1.86 samples key state once a frame:
// a key pressed and released between two frames (a quick tap while frames are slow) would never
// be seen, by shortcuts or by text fields (Enter), and everything typed within one frame would
// land in it at once (characters typed after Ctrl+A are dropped while Ctrl is still down). So
// every key and character event waits in a queue with its time, and each frame takes them in
// order up to the release of a key it pressed (that release, and what follows, go to the next
// frame: every key is seen down once, a shortcut's modifier is up again before the text after
// it), and only those made before the first mouse button change the frames have not taken yet
// (InputQueue below): a click on a field followed at once by Ctrl+A and typing, or a value
// typed and Enter pressed right after a double-click, reach the field after the click that
// activates it, as they were made. (Keys went to ImGui at once while clicks waited: an artist's
// Ctrl+A did nothing and the name typed was appended, and a radius typed during a long
// evaluation was lost.) The presses also go to the shortcuts (EditorState::keyPresses).
GLFWkeyfun g_imguiKeyCallback = nullptr;
GLFWcharfun g_imguiCharCallback = nullptr;
std::vector<KeyPress> g_keyPresses;

struct KeyEvent {
  GLFWwindow* window;
  bool isChar;
  int key, scancode, action, mods;
  unsigned codepoint;
  double time;
};
std::deque<KeyEvent> g_keyEvents;

void onKey(GLFWwindow* window, int key, int scancode, int action, int mods) {
  g_keyEvents.push_back(KeyEvent{window, false, key, scancode, action, mods, 0, glfwGetTime()});
}
void onChar(GLFWwindow* window, unsigned codepoint) {
  g_keyEvents.push_back(KeyEvent{window, true, 0, 0, 0, 0, codepoint, glfwGetTime()});
}

// The mouse, between GLFW and ImGui: every button and cursor event queued with its time, taken
// by frames so that none is lost (input_queue.h). Replaces ImGui's own mouse button callback.
InputQueue g_input;
void onMouseButton(GLFWwindow*, int button, int action, int) {
  g_input.button(button, action == GLFW_PRESS, glfwGetTime());
}
void onCursor(GLFWwindow*, double x, double y) {
  g_input.cursor(x, y, glfwGetTime());
}

// What was typed into a number field that it does not take (letters, a unit): said once the
// frame has the state (Dear ImGui's number fields drop them without a word, so "5 mm" became 5
// and "0.5 in" 0.5 mm).
std::string g_notTyped;
unsigned g_notTypedIn = 0;  // the ImGui id of the field it was typed in

// At the start of a frame, before it takes the mouse: this frame's share of the key events. A
// key that typed a character needs no frame of its own (the character is the text; Ctrl+A and
// Enter type none), so typing goes on at full speed in slow frames.
void deliverKeyEvents() {
  const double before = g_input.firstButtonTime();  // +infinity: none pending
  std::vector<int> pressed, typed;
  int lastPressed = -1;
  while (!g_keyEvents.empty()) {
    const KeyEvent& k = g_keyEvents.front();
    if (k.time >= before) break;
    if (k.isChar) {
      if (lastPressed >= 0) typed.push_back(lastPressed);
      if (g_imguiCharCallback) {
        const size_t dropped = g_notTyped.size();
        g_imguiCharCallback(k.window, numberFieldCharacter(k.codepoint, &g_notTyped));
        if (g_notTyped.size() != dropped) g_notTypedIn = numberFieldBeingTyped();
      }
    } else {
      const auto in = [&](const std::vector<int>& keys) {
        return std::find(keys.begin(), keys.end(), k.key) != keys.end();
      };
      if (k.action == GLFW_RELEASE && in(pressed) && !in(typed))
        break;  // pressed in this frame, and seen only as down: released in the next
      if (k.action == GLFW_PRESS) {
        g_keyPresses.push_back(KeyPress{k.key, k.mods});
        pressed.push_back(k.key);
        lastPressed = k.key;
      }
      if (g_imguiKeyCallback) g_imguiKeyCallback(k.window, k.key, k.scancode, k.action, k.mods);
    }
    g_keyEvents.pop_front();
  }
}
}  // namespace

// The GL side: window, ImGui context and the viewport renderer, created and destroyed in order.
struct Editor::Gl {
  GlWindow window;
  ImGuiContext* imgui = nullptr;
  std::unique_ptr<ViewportRenderer> renderer;
  std::unique_ptr<DeviceSplatCopier> copier;  // null: host upload
  // The host path's mapped buffers (null: none); the worker holds their lender.
  std::unique_ptr<MappedSplatSlots> mapped;
  bool mappedShown = false;               // the status bar says they are used
  std::unique_ptr<PanelRenderer> panels;  // Dear ImGui's draw data in GL
  Viewport viewport;
  WindowRedraw redraw;  // what each frame redraws (window_redraw.h)
  Stopwatch frameClock;

  Gl(const EditorOptions& o)
      : window(o.width, o.height, "Strata", o.visible, o.fitScreen),
        redraw(window.presentsParts()) {
    renderer = std::make_unique<ViewportRenderer>();  // may throw: nothing else to undo yet
    renderer->setSplatPrimitive(o.splatPrimitive);
    IMGUI_CHECKVERSION();
    imgui = ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // the layout is fixed; nothing to remember
    float scale = 1.0f;
    glfwGetWindowContentScale(window.handle(), &scale, nullptr);
    applyTheme(scale > 0.5f ? scale : 1.0f);
    try {
      panels = std::make_unique<PanelRenderer>();  // after the theme's fonts: their atlas
    } catch (...) {
      ImGui::DestroyContext(imgui);
      throw;
    }
    ImGui_ImplGlfw_InitForOpenGL(window.handle(), true);
    g_imguiKeyCallback = glfwSetKeyCallback(window.handle(), onKey);  // in front of ImGui's
    g_imguiCharCallback = glfwSetCharCallback(window.handle(), onChar);
    glfwSetMouseButtonCallback(window.handle(), onMouseButton);  // instead of ImGui's
    glfwSetCursorPosCallback(window.handle(), onCursor);
    double x = 0.0, y = 0.0;
    glfwGetCursorPos(window.handle(), &x, &y);
    g_input = InputQueue();
    g_input.cursor(x, y, glfwGetTime());
  }
  ~Gl() {
    glfwSetKeyCallback(window.handle(), g_imguiKeyCallback);
    glfwSetCharCallback(window.handle(), g_imguiCharCallback);
    g_imguiKeyCallback = nullptr;
    g_imguiCharCallback = nullptr;
    g_keyEvents.clear();
    copier.reset();  // unregisters the buffer while it and the context exist
    mapped.reset();  // unmaps while the context exists (the worker and the results are gone)
    renderer.reset();
    panels.reset();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext(imgui);
  }
};

bool editorDisplayAvailable(std::string* why) {
  return displayAvailable(why);
}

Editor::Editor(EditorOptions options) : options_(std::move(options)) {
  if (!options_.makeBackend) throw Error("the editor needs a backend");
  state_ = std::make_unique<EditorState>();
  EditorState& s = *state_;
  s.makeBackend = options_.makeBackend;
  s.recentFilesPath = options_.recentFilesPath;
  s.bundledScenesFolder = options_.bundledScenesFolder;
  if (!options_.layoutPath.empty()) layout_ = readPanelLayout(options_.layoutPath, layout_);
  if (!options_.recoveryDir.empty()) {
    try {
      recoverySlot_ = std::make_unique<RecoverySlot>(options_.recoveryDir);
      s.recoveryPath = recoverySlot_->path();
      s.recoveryDir = options_.recoveryDir;
    } catch (const Error& e) {
      logWarning(s, std::string("no autosave: ") + e.what());
    }
    s.recoveryOffers = claimOrphanedRecoveries(options_.recoveryDir, options_.legacyRecoveryPath);
  }
  s.exportSettingsPath = options_.exportSettingsPath;
  if (!s.exportSettingsPath.empty()) {
    const ExportSettings kept = readExportSettings(
        s.exportSettingsPath, {s.exportResolution, s.exportSimplify, s.exportSimplifyCells, ""});
    s.exportResolution = kept.resolution;
    s.exportSimplify = kept.simplify;
    s.exportSimplifyCells = kept.simplifyCells;
    s.rememberedExportFolder = kept.folder;
  }
  s.importSettingsPath = options_.importSettingsPath;
  if (!s.importSettingsPath.empty()) {
    const ImportSettings kept = readImportSettings(s.importSettingsPath, {});
    s.lastImportFolder = kept.folder;
    s.lastImportUnit = kept.unit;
    s.lastImportUpAxis = kept.upAxis;
  }
  if (!s.recentFilesPath.empty()) s.recentFiles = readRecentFiles(s.recentFilesPath);
  s.offerRecovery = !s.recoveryOffers.empty();

  gl_ = std::make_unique<Gl>(options_);
  s.glDescription = gl_->window.description() + " (context " +
                    std::to_string(gl_->window.glMajor()) + "." +
                    std::to_string(gl_->window.glMinor()) + " core)";
  if (options_.makeSplatCopier) {
    // Interop only where it works: registering the splat buffer fails on GL that does not run
    // on the CUDA device (Mesa's llvmpipe, another GPU).
    try {
      gl_->copier = options_.makeSplatCopier();
      if (gl_->copier) {
        gl_->renderer->reserveSplats(1);
        gl_->copier->attach(gl_->renderer->splatBuffer());
        s.splatTransfer = gl_->copier->name();
      }
    } catch (const Error& e) {
      gl_->copier.reset();
      s.splatTransfer = std::string("host upload (") + e.what() + ")";
    }
  }
  resultSignal_ = std::make_shared<ResultSignal>();
  worker_ = std::make_unique<PreviewWorker>(options_.makeBackend(), options_.coarseResolution,
                                            [signal = resultSignal_] {
                                              signal->notify();
                                              glfwPostEmptyEvent();
                                            });
  worker_->setHostSplats(gl_->copier == nullptr);
  if (!gl_->copier) lendMappedBuffers();
  s.backendDescription = worker_->backendDescription();
  startTime_ = glfwGetTime();
  if (!options_.scenePath.empty()) {
    std::error_code ec;
    if (options_.sceneAsTemplate) {
      openTemplate(s, options_.scenePath);
    } else if (std::filesystem::exists(options_.scenePath, ec)) {
      openDocument(s, options_.scenePath);
    } else {
      s.document.setPath(options_.scenePath);  // a new scene, saved there
      logInfo(s, options_.scenePath + " does not exist yet: a new scene, saved there");
    }
  }
  gl_->viewport.viewAll(s);
  lastAutosave_ = 0.0;
}

Editor::~Editor() {
  state_->preview.reset();    // its splats may be device memory: free them while all is alive
  state_->exportJob.reset();  // cancel and join before the GL side goes
  worker_.reset();
  gl_.reset();
}

void Editor::viewAll() {
  gl_->viewport.viewAll(*state_);
}

void Editor::windowOrigin(int* x, int* y) const {
  glfwGetWindowPos(gl_->window.handle(), x, y);
}

Camera& Editor::camera() {
  return gl_->viewport.camera;
}

void Editor::dropCopier(const std::string& why) {
  EditorState& s = *state_;
  gl_->copier.reset();
  worker_->setHostSplats(true);
  s.splatTransfer = "host upload (" + why + ")";
  logWarning(s, "CUDA-GL interop failed, using the host upload path: " + why);
  lendMappedBuffers();
}

void Editor::lendMappedBuffers() {
  if (gl_->mapped || !MappedSplatSlots::supported()) return;
  gl_->mapped = std::make_unique<MappedSplatSlots>(options_.pinHostMemory);
  worker_->setHostSplatLender(gl_->mapped->lender());
}

void Editor::maintainMappedBuffers() {
  if (!gl_->mapped) return;
  EditorState& s = *state_;
  try {
    gl_->mapped->maintain();
  } catch (const Error& e) {
    worker_->setHostSplatLender(nullptr);  // the regions lent stay valid until given back
    s.splatTransfer = std::string("host upload (") + e.what() + ")";
    logWarning(s,
               std::string("host splats go through the worker's arrays from now on: ") + e.what());
    return;
  }
  if (gl_->mapped->made() && !gl_->mappedShown) {
    gl_->mappedShown = true;
    s.splatTransfer +=
        gl_->mapped->pinned() ? ", by DMA into mapped GL buffers" : ", into mapped GL buffers";
    if (!gl_->mapped->pinned())
      logInfo(s, "the mapped splat buffers are not page-locked: " + gl_->mapped->whyNotPinned());
  }
}

size_t Editor::resultsInMappedBuffers() const {
  return gl_->mapped ? gl_->mapped->copiedCount() : 0;
}

void Editor::transferSplats(const PreviewResult& result) {
  ViewportRenderer& renderer = *gl_->renderer;
  if (!result.splats || result.splats->count() == 0) {
    SplatShape none;
    none.cellSize = result.ok() ? result.stats.grid.h : 1.0;
    renderer.setSplatCount(0, none);
    return;
  }
  const SplatResource& splats = *result.splats;
  const SplatShape shape = splatShapeOf(result.stats.grid, splats);
  if (gl_->mapped && gl_->mapped->copyInto(renderer, splats, shape)) return;  // on the GPU
  if (const Splat* host = splats.hostData()) {
    renderer.uploadSplats(host, splats.count(), shape);
    return;
  }
  if (gl_->copier && gl_->copier->accepts(splats)) {
    try {
      if (!renderer.splatBufferFits(splats.count())) {
        gl_->copier->detach();  // no registration across a reallocation
        renderer.reserveSplats(splats.count());
        gl_->copier->attach(renderer.splatBuffer());
      }
      gl_->copier->copy(splats);
      renderer.setSplatCount(splats.count(), shape);
      return;
    } catch (const Error& e) {
      dropCopier(e.what());
    }
  }
  // Device splats and no way to copy them on the device: through the host, this once.
  std::vector<Splat> copy(splats.count());
  splats.copyToHost(copy.data());
  renderer.uploadSplats(copy.data(), copy.size(), shape);
}

size_t Editor::uploadChunkBytes() const {
  constexpr double kUploadMsPerFrame = 6.0;  // of a 16 ms frame, beside drawing and panels
  if (uploadBytesPerMs_ <= 0.0) return size_t(4) << 20;
  return size_t(
      std::clamp(uploadBytesPerMs_ * kUploadMsPerFrame, double(1 << 20), double(1 << 28)));
}

namespace {
// The full result `next` shows the parts of the result `shown` at another resolution: the
// preview's resolution changed, nothing else, or a drag's last draft (a coarse result of the
// same tree) is followed by the full result. The image shown may stay until next's is drawn:
// next's first image, from coarser levels of its splats, looked worse than the draft it
// replaced (gaps and specks for a second or two on a software GL driver: an artist's test).
bool sameRefinedParts(const PreviewResult* shown, const PreviewResult& next) {
  return shown && !next.coarse && shown->ok() && next.ok() && shown->scene && next.scene &&
         shown->scene->root == next.scene->root &&
         (shown->coarse || shown->resolution != next.resolution);
}
}  // namespace

void Editor::stageMore() {
  if (!staging_) return;
  EditorState& s = *state_;
  const SplatResource& splats = *staging_->splats;
  Stopwatch clock;
  const size_t before = stagedSplats_;
  stagedSplats_ = gl_->renderer->stageSplats(splats.hostData(), splats.count(), stagedSplats_,
                                             uploadChunkBytes());
  const double ms = clock.seconds() * 1000.0;
  stagingMs_ += ms;
  const size_t bytes = (stagedSplats_ - before) * sizeof(Splat);
  if (ms > 0.5 && bytes >= (size_t(1) << 20)) uploadBytesPerMs_ = double(bytes) / ms;
  if (stagedSplats_ < splats.count()) return;
  if (sameRefinedParts(s.preview.get(), *staging_)) gl_->renderer->holdShownImage();
  gl_->renderer->commitStagedSplats(splats.count(), splatShapeOf(staging_->stats.grid, splats));
  s.previewError = staging_->error;
  s.uploadMs = stagingMs_;
  s.uploadedBytes = gl_->renderer->splatBytes();
  s.preview = std::move(staging_);
}

void Editor::applyResult(std::shared_ptr<const PreviewResult> result) {
  EditorState& s = *state_;
  // The splats shown (an edit that changed no part: a measurement, a name): the image stays.
  if (!staging_ && s.preview && result->splats && result->splats == s.preview->splats) {
    s.previewError = result->error;
    s.preview = std::move(result);
    return;
  }
  // The same splats as the result being uploaded (its copy with the ghosts finished): it takes
  // that one's place, the upload going on where it was.
  if (staging_ && result->splats && result->splats == staging_->splats) {
    staging_ = std::move(result);
    return;
  }
  staging_.reset();  // a newer result replaces one still being uploaded
  // A host upload larger than a frame's share, with a result on screen to keep meanwhile (and
  // no CUDA-GL copier registered to the buffer drawn): over several frames.
  const Splat* host = result->splats ? result->splats->hostData() : nullptr;
  if (host && gl_->mapped && gl_->mapped->holds(*result->splats)) host = nullptr;  // a GPU copy
  if (host && s.preview && !gl_->copier &&
      result->splats->count() * sizeof(Splat) > uploadChunkBytes()) {
    staging_ = std::move(result);
    stagedSplats_ = 0;
    stagingMs_ = 0.0;
    stageMore();
    return;
  }
  s.previewError = result->error;
  if (sameRefinedParts(s.preview.get(), *result)) gl_->renderer->holdShownImage();
  Stopwatch upload;
  transferSplats(*result);
  s.uploadMs = upload.seconds() * 1000.0;
  s.uploadedBytes = gl_->renderer->splatBytes();
  // The rate of a large upload only: small ones say little.
  if (host && s.uploadMs > 0.5 && s.uploadedBytes >= (size_t(1) << 20))
    uploadBytesPerMs_ = double(s.uploadedBytes) / s.uploadMs;
  s.preview = std::move(result);
}

// Nothing visible to evaluate: no request; the viewport shows a hint instead.
static bool sceneHasVisibleLeaves(const NodePtr& node) {
  if (!node || !node->visible) return false;
  if (!isOperation(node->kind)) return true;
  for (const auto& c : node->children)
    if (sceneHasVisibleLeaves(c)) return true;
  return false;
}

bool Editor::requestPreviewIfNeeded() {
  EditorState& s = *state_;
  // A field held while a number is typed into it (ImGui's text input of a drag or slider) is
  // not a drag: the value shown is the one that stays until Enter, so it refines in full.
  const bool typing = ImGui::GetIO().WantTextInput;
  const uint64_t revision = s.document.revision();
  // A hand resting mid-drag (the button held, nothing changed for a moment) is calm: its scene
  // refines in full, and the drag's next motion is a draft again (the preview stayed at its
  // draft's 128 cells while the button was held: an artist's test).
  if (revision != restRevision_) {
    restRevision_ = revision;
    revisionChangedAt_ = glfwGetTime();
  }
  const bool resting = glfwGetTime() - revisionChangedAt_ >= kDragRestSeconds;
  const bool interactive =
      ((s.document.interacting() && !typing) || gl_->viewport.gizmoDragging() || dragHeld_) &&
      !resting;
  const int wanted = s.document.scene().settings.resolution;
  // The cap depends on what a full (not coarse) result cost. It is worked out when the wanted
  // resolution changes, and once more when the first full result arrives if there was none
  // before; never on every result, which would chase its own tail (each new cap a new pass).
  const bool fullShown = s.preview && s.preview->ok() && !s.preview->coarse;
  if (wanted != wantedResolution_ || (!capFromResult_ && fullShown)) {
    wantedResolution_ = wanted;
    capFromResult_ = fullShown;
    cappedResolution_ = previewResolutionFor(
        wanted, fullShown ? s.preview->resolution : 0, fullShown ? s.preview->stats.cacheBytes : 0,
        fullShown ? s.preview->stats.seconds : 0.0, availableMemoryBytes());
    s.previewCappedAt = cappedResolution_ < wanted ? cappedResolution_ : 0;
  }
  const int resolution = cappedResolution_;
  // Ghost splats are made for every candidate while any ghost is wanted, so that selecting
  // another part needs no new pass.
  if (revision != ghostWantRevision_ || s.selection != ghostWantSelection_) {
    ghostWantRevision_ = revision;
    ghostWantSelection_ = s.selection;
    selectionHasGhosts_ = !ghostsOf(s.document.root(), s.selection, false).empty();
  }
  const bool ghosts = s.showAllGhosts || selectionHasGhosts_;
  if (revision == requestedRevision_ && resolution == requestedResolution_ &&
      interactive == requestedInteractive_ && (ghosts == requestedGhosts_ || !ghosts))
    return false;
  requestedRevision_ = revision;
  requestedResolution_ = resolution;
  requestedInteractive_ = interactive;
  requestedGhosts_ = ghosts;
  if (!sceneHasVisibleLeaves(s.document.root())) {
    requestedEmpty_ = true;
    auto empty = std::make_shared<PreviewResult>();
    empty->tag = revision;
    empty->scene = s.document.snapshot();
    empty->resolution = resolution;
    applyResult(empty);
    worker_->cancel();  // an evaluation of an older scene is of no use now
    return false;
  }
  requestedEmpty_ = false;
  worker_->request(s.document.snapshot(), resolution, interactive, revision,
                   ghosts ? ghostCandidates(s.document.root()) : std::vector<NodeId>{},
                   s.selection);
  return true;
}

bool Editor::takeResult() {
  EditorState& s = *state_;
  auto result = worker_->takeResult();
  if (!result) return false;
  // A result for an emptied scene arrives late: ignore it.
  if (!(requestedEmpty_ && result->tag != s.document.revision())) applyResult(result);
  return true;
}

void Editor::pumpPreview() {
  EditorState& s = *state_;
  maintainMappedBuffers();
  stageMore();
  takeResult();
  if (!s.preview)
    s.fullPassWarnings.clear();
  else if (!s.preview->coarse && s.fullPassWarnings != s.preview->stats.warnings)
    s.fullPassWarnings = s.preview->stats.warnings;
  s.worker = worker_->status();
  requestPreviewIfNeeded();
}

double Editor::awaitEditResult() {
  if (awaitUntil_ <= 0.0) return 0.0;
  const double until = awaitUntil_;
  awaitUntil_ = 0.0;
  // Shown, or on its way over several frames (stageMore): no more to wait for.
  const auto arrived = [this] {
    const PreviewResult* p = staging_ ? staging_.get() : state_->preview.get();
    return p && p->tag == requestedRevision_;
  };
  double waited = 0.0;  // the waits only: taking a result is drawing's work (its upload)
  uint64_t seen = awaitFromCount_;
  while (!arrived()) {
    const double left = until - glfwGetTime();
    if (left <= 0.0) break;
    Stopwatch wait;
    const bool more = resultSignal_->waitPast(seen, left);
    waited += wait.seconds();
    if (!more) break;
    seen = resultSignal_->count();
    if (takeResult()) panelsStale_ = true;  // the status bar and panels show the last result
  }
  return waited;
}

bool Editor::waitForPreview(double timeoutSeconds) {
  Stopwatch clock;
  while (clock.seconds() < timeoutSeconds) {
    pumpPreview();
    const PreviewResult* p = state_->preview.get();
    // At the resolution asked of the worker: the document's, or its cap (previewResolutionFor).
    if (p && p->tag == state_->document.revision() && !p->coarse &&
        p->resolution == requestedResolution_)
      return p->error.empty();
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return false;
}

bool Editor::viewSettled() const {
  return !gl_->renderer->refining();
}

int Editor::shownDetailLevel() const {
  return gl_->renderer->drawnLevel();
}

size_t Editor::shownSplats() const {
  return gl_->renderer->drawnLevelSplats();
}

bool Editor::showsCoarseImage() const {
  return gl_->renderer->showsCoarseImage();
}

size_t Editor::shownGhostSplats() const {
  return gl_->renderer->ghostCount();
}

size_t Editor::splatsDrawnAsPoints() const {
  return gl_->renderer->pointsDrawn();
}

size_t Editor::splatsDrawnAsQuads() const {
  return gl_->renderer->quadsDrawn();
}

size_t Editor::splatsDrawnByCompute() const {
  return gl_->renderer->computedDrawn();
}

double Editor::splatNanoseconds(SplatPrimitive kind) const {
  return gl_->renderer->nsPerSplat(kind);
}

void Editor::updateLeafStyles() {
  EditorState& s = *state_;
  if (styledRevision_ == s.document.revision() && styledSelection_ == s.selection) return;
  styledRevision_ = s.document.revision();
  styledSelection_ = s.selection;
  gl_->renderer->setLeafStyles(leafStyles(s.document.root(), s.selection));
}

void Editor::updateGhosts() {
  EditorState& s = *state_;
  const PreviewResult* shown = s.preview.get();
  // The same result while it lives (not merely one at the same address: results now come in
  // quick succession, the ghosts' copy after its result).
  const bool sameResult = !ghostedResult_.expired() && ghostedResult_.lock() == s.preview;
  if (sameResult && s.selection == ghostedSelection_ && s.showAllGhosts == ghostedAll_) return;
  ghostedResult_ = s.preview;
  ghostedSelection_ = s.selection;
  ghostedAll_ = s.showAllGhosts;
  std::vector<Splat> layers[2];                     // cutting, intersecting
  std::vector<ViewportRenderer::GhostRun> runs[2];  // each ghost's splats and lattice
  if (shown && shown->scene) {
    const NodePtr& root = shown->scene->root;  // the tree the ghosts were evaluated from
    for (NodeId id : ghostsOf(root, s.selection, s.showAllGhosts)) {
      for (const GhostSplats& ghost : shown->ghosts) {
        if (ghost.id != id || !ghost.splats) continue;
        const int layer = roleOf(root, id) == ChildRole::Intersect ? 1 : 0;
        layers[layer].insert(layers[layer].end(), ghost.splats->splats().begin(),
                             ghost.splats->splats().end());
        runs[layer].push_back({ghost.splats->splats().size(), ghost.h});
      }
    }
  }
  gl_->renderer->setGhosts(layers[0], layers[1], runs);
}

void Editor::autosave() {
  EditorState& s = *state_;
  if (s.recoveryPath.empty() || s.offerRecovery) return;
  if (autosaveJob_) {
    if (!autosaveJob_->done()) return;
    const std::string error = autosaveJob_->error();
    if (error.empty())
      autosavedRevision_ = autosavingRevision_;
    else
      logWarning(s, "autosave failed: " + error);
    autosaveJob_.reset();
  }
  const uint64_t revision = s.document.revision();
  if (revision != seenRevision_) {
    seenRevision_ = revision;
    changedAt_ = s.now;
  }
  const bool overdue = s.now - lastAutosave_ >= options_.autosaveSeconds;
  if (!s.document.dirty()) {  // saved, or undone back to the saved state: nothing to recover
    if (recoveryWritten_ || overdue) {
      lastAutosave_ = s.now;
      recoveryWritten_ = false;
      removeRecoveryFile(s.recoveryPath);
    }
    return;
  }
  if (revision == autosavedRevision_) return;
  if (s.now - changedAt_ < options_.autosaveRestSeconds && !overdue) return;
  lastAutosave_ = s.now;
  autosavingRevision_ = revision;
  recoveryWritten_ = true;
  autosaveJob_ = std::make_unique<BackgroundJob<bool>>(
      [scene = s.document.scene(), origin = s.document.path(), path = s.recoveryPath](Progress&) {
        writeRecoveryFile(scene, origin, path);
        return true;
      });
}

namespace {
// Hints over the viewport: the empty-scene hint, the projection and the gizmo mode.
// `drawing`: the view still shows an earlier image while the result's is drawn (the renderer
// refines), said in the corner.
void drawViewportHints(const EditorState& s, const ViewRect& rect, const Camera& camera,
                       bool drawing) {
  const bool ortho = camera.ortho;
  ImDrawList* draw = ImGui::GetBackgroundDrawList();
  if (s.preview && s.preview->splatCount() == 0 && s.previewError.empty()) {
    // An empty tree, or parts whose result is empty (all hidden, cut away, or not overlapping
    // where they intersect): the hint says which, so that nothing looks lost.
    const NodePtr& root = s.document.root();
    const bool noParts = !root || (isOperation(root->kind) && root->children.empty());
    // Where the evaluation said why (a part smaller than a cell, a modifier that left nothing),
    // that is the hint: an artist's part of height 1e9 made every cell larger than the others,
    // and the generic causes misled.
    const std::vector<std::string>& warnings = s.preview->stats.warnings;
    const std::string text =
        noParts ? "Empty scene: add a primitive from the palette on the left."
        : !warnings.empty()
            ? "The result is empty: " + warnings.front() +
                  (warnings.size() > 1 ? " (and more: View > Diagnostics)" : "") +
                  " (Ctrl+Z undoes the last edit)."
            : "The result is empty: its parts are hidden, cut away or do not overlap where "
              "they intersect (Ctrl+Z undoes the last edit).";
    const char* hint = text.c_str();
    const float wrap = std::max(120.0f, float(rect.width) * 0.8f);
    const ImVec2 size = ImGui::CalcTextSize(hint, nullptr, false, wrap);
    const ImVec2 at(float(rect.x + (rect.width - size.x) * 0.5),
                    float(rect.y + rect.height * 0.5 - size.y * 0.5));
    // On a dark band, over the measurements' labels drawn before it (the text ran through a
    // label, unreadable: an artist's test).
    draw->AddRectFilled(ImVec2(at.x - 8, at.y - 5), ImVec2(at.x + size.x + 8, at.y + size.y + 5),
                        IM_COL32(20, 22, 26, 215), 4.0f);
    draw->AddText(ImGui::GetFont(), ImGui::GetFontSize(), at, IM_COL32(210, 210, 215, 235), hint,
                  nullptr, wrap);
  }
  char corner[160];
  const char* axisView = camera.axisViewName();
  std::snprintf(corner, sizeof(corner), "%s%s%s  \u00B7  %s%s", axisView, *axisView ? ", " : "",
                ortho ? "orthographic" : "perspective",
                s.gizmoMode == GizmoMode::Move     ? "move (W)"
                : s.gizmoMode == GizmoMode::Rotate ? "rotate (E)"
                                                   : "scale (R)",
                drawing ? "  \u00B7  drawing..." : "");
  // A dark outline under the light text: readable over light parts as over the background.
  for (const ImVec2 d : {ImVec2(1, 1), ImVec2(-1, 1), ImVec2(1, -1), ImVec2(-1, -1)})
    draw->AddText(ImVec2(float(rect.x + 10) + d.x, float(rect.y + 8) + d.y),
                  IM_COL32(20, 22, 26, 200), corner);
  draw->AddText(ImVec2(float(rect.x + 10), float(rect.y + 8)), IM_COL32(225, 225, 230, 230),
                corner);
  if (s.measure.active) {
    // What the next click does.
    const bool open = s.measure.open >= 0 && s.measure.openRevision == s.document.revision();
    std::string hint = s.measure.first ? "measure (M): click the second point"
                       : open ? "measure (M): click a third point for the angle, Esc to finish"
                              : "measure (M): click the first point; Esc leaves the tool";
    if (!s.measure.lastSnap.empty()) hint += "   (last point: " + s.measure.lastSnap + ")";
    // On a dark band: the yellow hint was unreadable over a light part.
    const ImVec2 at(float(rect.x + 10), float(rect.y + 26));
    const ImVec2 size = ImGui::CalcTextSize(hint.c_str());
    draw->AddRectFilled(ImVec2(at.x - 4, at.y - 1), ImVec2(at.x + size.x + 4, at.y + size.y + 1),
                        IM_COL32(20, 22, 26, 190), 3.0f);
    draw->AddText(at, IM_COL32(255, 226, 120, 235), hint.c_str());
  }
}

}  // namespace

void Editor::drawFrame(std::vector<uint8_t>* capture, int* width, int* height) {
  EditorState& s = *state_;
  GLFWwindow* window = gl_->window.handle();
  gl_->frameClock.restart();  // the status bar shows the previous frame's drawing time
  s.now = glfwGetTime() - startTime_;

  panelsStale_ = false;
  rememberSelection(s);  // before this frame's input changes it (undo brings it back)
  deliverKeyEvents();
  // Said once the field is left (or another is typed into: Tab), for the field it was typed in.
  if (const std::string converted = takeUnitConversion(); !converted.empty())
    logInfo(s, "typed " + converted);
  // A typing refused (two numbers apart, an expression that is no number): said.
  if (const std::string refused = takeTypedRefusal(); !refused.empty()) logWarning(s, refused);
  if (takeUnitConverted()) g_notTyped.clear();  // the letters were a unit, and converted
  if (!g_notTyped.empty()) {
    if (numberFieldBeingTyped() != g_notTypedIn) {
      logWarning(s, "\"" + g_notTyped +
                        "\" makes no sense of the number typed: the field kept its value "
                        "(lengths are in " +
                        unitSymbol(s.document.scene().settings.unit) +
                        "; a length field converts mm, cm, m, in or ft typed after the number; "
                        "angles are in degrees)");
      g_notTyped.clear();
    }
  }
  s.keyPresses.swap(g_keyPresses);
  g_keyPresses.clear();
  pumpPreview();
  handleDialogResult(s);

  ImGui_ImplGlfw_NewFrame();
  {
    // The mouse as this frame's share of the queued events left it (not as it is now).
    ImGuiIO& io = ImGui::GetIO();
    const InputQueue::Frame mouse = g_input.takeFrame();
    io.MousePos = ImVec2(float(mouse.x), float(mouse.y));
    bool doubleClicked = false;
    for (int b = 0; b < InputQueue::kButtons; ++b) {
      io.MouseDown[b] = mouse.down[b];
      doubleClicked = doubleClicked || mouse.doubleClicked[b];
    }
    // Double-clicks are the queue's decision, from the events' times (frames may be slow).
    io.MouseDoubleClickTime = doubleClicked ? 1e6f : 0.0f;
  }
  ImGui::NewFrame();

  PanelLayout& layout = layout_;
  layout.menuHeight = ImGui::GetFrameHeight();
  layout.statusHeight = ImGui::GetFrameHeight() + 8.0f;
  layout.paletteRows = paletteRowsHeight();
  clampLayout(layout, ImGui::GetIO().DisplaySize.x, ImGui::GetIO().DisplaySize.y);
  drawMainMenu(s);
  // The inspector before the outliner and the palette: a number being typed into one of its
  // fields is applied to the part it was typed for when a click on a row or a palette button
  // selects another (the field sees the click and is left before the selection changes).
  drawInspector(s, layout);
  drawOutliner(s, layout);
  drawPalette(s, layout);
  drawPreviewPanel(s, layout);
  drawStatusBar(s, layout);
  drawDiagnostics(s);
  if (drawSplitters(layout) && !options_.layoutPath.empty()) {
    try {
      writePanelLayout(options_.layoutPath, layout);
    } catch (const Error& e) {
      logWarning(s, std::string("panel sizes not remembered: ") + e.what());
    }
  }
  drawModals(s);
  drawShortcutSheet(s);
  s.dialog.draw();
  s.gizmoDragging = gl_->viewport.gizmoDragging();
  s.fieldDragHeld = !s.gizmoDragging && s.document.interacting() && ImGui::IsAnyItemActive() &&
                    !ImGui::GetIO().WantTextInput;
  handleShortcuts(s);
  if (s.cancelFieldDrag) {  // the field let go (it does not take the held button again)
    s.cancelFieldDrag = false;
    ImGui::ClearActiveID();
    s.document.cancelInteraction();
  }

  const ImGuiViewport* vp = ImGui::GetMainViewport();
  ViewRect rect;
  rect.x = layout.leftWidth;
  rect.y = layout.menuHeight;
  rect.width = std::max(1.0, double(vp->Size.x - layout.leftWidth - layout.rightWidth));
  rect.height = std::max(1.0, double(vp->Size.y - layout.menuHeight - layout.statusHeight));
  gl_->viewport.handleInput(s, rect);
  gl_->viewport.keepCameraOutside(s);
  warnLostContacts(s);
  if (s.requestAxisView >= 0) gl_->viewport.camera.setAxisView(AxisView(s.requestAxisView));
  if (s.requestToggleOrtho) gl_->viewport.toggleOrtho(s);
  s.requestAxisView = -1;
  s.requestToggleOrtho = false;
  if (s.requestViewAll) gl_->viewport.viewAll(s);
  if (s.requestFrameSelected) gl_->viewport.frameSelected(s);
  s.requestViewAll = s.requestFrameSelected = false;
  // A held widget that vanished (its node was deleted) must not leave the history coalescing.
  if (s.document.interacting() && !ImGui::IsAnyItemActive() && !gl_->viewport.gizmoDragging() &&
      !dragHeld_)
    s.document.endInteraction();

  gl_->viewport.drawAnnotations(s, rect);
  drawViewportHints(s, rect, gl_->viewport.camera, gl_->renderer->refining());
  ImGui::Render();
  const double builtAt = gl_->frameClock.seconds();
  const double awaitedSeconds = awaitEditResult();

  updateLeafStyles();
  updateGhosts();
  int fbWidth = 0, fbHeight = 0, winWidth = 1, winHeight = 1;
  glfwGetFramebufferSize(window, &fbWidth, &fbHeight);
  glfwGetWindowSize(window, &winWidth, &winHeight);
  const double pixelScale = winWidth > 0 ? double(fbWidth) / winWidth : 1.0;
  gl_->viewport.resolvePicks(*gl_->renderer, s, rect, pixelScale);
  updateLeafStyles();  // a pick may have changed the selection
  updateGhosts();
  const ImDrawData& drawData = *ImGui::GetDrawData();
  if (capture) {
    // Everything drawn at once (the window's depth included), every splat shown, and read.
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, fbWidth, fbHeight);
    glClearColor(kWindowBackground[0], kWindowBackground[1], kWindowBackground[2],
                 kWindowBackground[3]);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    gl_->viewport.draw(*gl_->renderer, s, rect, fbHeight, pixelScale, -1.0);
    gl_->panels->draw(drawData, fbWidth, fbHeight, {0, 0, fbWidth, fbHeight});
    *capture = readWindowPixels(fbWidth, fbHeight);
    *width = fbWidth;
    *height = fbHeight;
    gl_->window.present({{0, 0, fbWidth, fbHeight}}, fbWidth, fbHeight);
    gl_->redraw.invalidate();  // the next frame redraws everything
  } else {
    // The view within the frame budget, then the panels; where the window keeps its back
    // buffer, only the panels that changed (or that reach the view) and only those pixels sent.
    if (gl_->window.takeExposed()) gl_->redraw.invalidate();
    int x = 0, y = 0, w = 0, h = 0;
    viewPixels(rect, fbHeight, pixelScale, &x, &y, &w, &h);
    // A view that would draw what the window shows (a panel changed, not the view) is kept:
    // neither drawn nor sent, but where a changed panel reaches it.
    const bool viewShown = gl_->viewport.prepare(*gl_->renderer, s, rect, fbHeight, pixelScale);
    gl_->redraw.begin(drawData, fbWidth, fbHeight, {x, y, x + w, y + h}, viewShown);
    const double viewFrom = gl_->frameClock.seconds();
    if (gl_->redraw.viewKept()) {
      gl_->renderer->skipFrame(s.frameMs);
      for (const PixelRect& r : gl_->redraw.viewRepaints())
        gl_->viewport.repaintPrepared(*gl_->renderer, r);
    } else {
      gl_->viewport.drawPrepared(*gl_->renderer, s.frameMs);
    }
    const double panelsFrom = gl_->frameClock.seconds();
    gl_->redraw.drawPanels(*gl_->panels, drawData);
    const double presentFrom = gl_->frameClock.seconds();
    if (!gl_->window.present(gl_->redraw.rects(), fbWidth, fbHeight))
      gl_->redraw.invalidate();  // swapped: the back buffer's pixels are undefined
    const double presented = gl_->frameClock.seconds();
    s.frameParts = {builtAt * 1e3, (panelsFrom - viewFrom) * 1e3, (presentFrom - panelsFrom) * 1e3,
                    (presented - presentFrom) * 1e3};
  }
  if (options_.slowFrameSeconds > 0.0)
    std::this_thread::sleep_for(std::chrono::duration<double>(options_.slowFrameSeconds));
  s.frameMs = (gl_->frameClock.seconds() - awaitedSeconds) * 1000.0;  // drawing, not waiting

  gl_->window.setTitle(windowTitle(s));
  autosave();
}

bool Editor::frame() {
  // Idle: sleep until an event (input, a finished result) or a short timeout, so that a still
  // editor costs no CPU. Just after input: draw at once. While an evaluation or export runs:
  // redraw often enough to show progress, leaving the cores to the work.
  const ImGuiIO& io = ImGui::GetIO();
  bool input = io.MouseDelta.x != 0.0f || io.MouseDelta.y != 0.0f || io.MouseWheel != 0.0f ||
               io.InputQueueCharacters.Size > 0;
  for (bool down : io.MouseDown) input = input || down;
  for (bool down : io.KeysDown) input = input || down;
  // The viewport's full image is drawn a share a frame, and a large result uploaded a share a
  // frame: keep frames coming until it is shown.
  if (input || g_input.pending() || !g_keyEvents.empty() || gl_->renderer->refining() ||
      uploading())
    activeUntil_ = state_->now + 0.5;
  // An edit made since the last frame without input (a dialog's result, a script, a test) is
  // sent to the worker before sleeping: its result wakes the loop (glfwPostEmptyEvent).
  const uint64_t resultsBefore = resultSignal_->count();
  const bool requested = requestPreviewIfNeeded();
  const bool working =
      state_->worker.busy || (state_->exportJob && state_->exportJob->status().running);
  // Work just ended (an export's report, a result): frames keep coming a moment, so that the
  // windows sized by their content reach their size at once (an export's report was drawn cut
  // for its first half second: an artist's test).
  if (wasWorking_ && !working) activeUntil_ = state_->now + 0.5;
  wasWorking_ = working;
  if (requested && !input && options_.editResultWaitSeconds > 0.0) {
    // An edit just went to the engine and nothing else moves: a frame drawn now would show the
    // old result. This one is built while the engine works and waits for the new result just
    // before drawing the view (awaitEditResult): on a fast engine the edit then reaches the
    // screen in this frame instead of the next, and its wait overlaps building the panels.
    awaitUntil_ = glfwGetTime() + options_.editResultWaitSeconds;
    awaitFromCount_ = resultsBefore;
    lastWaitSeconds_ = 0.0;
  } else if (panelsStale_) {
    lastWaitSeconds_ = 0.0;  // the last frame's panels were built before its result came
  } else if (state_->now < activeUntil_)
    lastWaitSeconds_ = 0.0;
  else
    lastWaitSeconds_ = working ? 0.05 : 0.5;  // progress shows at 20 frames a second
  if (lastWaitSeconds_ > 0.0)
    glfwWaitEventsTimeout(lastWaitSeconds_);
  else
    glfwPollEvents();
  if (glfwWindowShouldClose(gl_->window.handle())) {
    glfwSetWindowShouldClose(gl_->window.handle(), GLFW_FALSE);
    requestQuit(*state_);
  }
  drawFrame(nullptr, nullptr, nullptr);
  return !state_->quitNow;
}

int Editor::run() {
  while (frame()) {
  }
  // A clean exit: nothing to recover next time (after an autosave still writing has finished):
  // this editor's slot goes; work offered and not answered stays for a later start.
  autosaveJob_.reset();
  recoverySlot_.reset();
  return 0;
}

std::vector<uint8_t> Editor::renderViewport(int width, int height) {
  RenderTarget target(width, height);
  target.bind();
  updateLeafStyles();
  updateGhosts();
  ViewRect rect;
  rect.width = width;
  rect.height = height;
  gl_->viewport.draw(*gl_->renderer, *state_, rect, height, 1.0);
  return target.read();
}

std::optional<PickHit> Editor::pickViewport(int width, int height, double x, double y) {
  ViewRect rect;
  rect.width = width;
  rect.height = height;
  return gl_->viewport.pickAt(*gl_->renderer, *state_, rect, glm::dvec2(x, y), 1.0);
}

Placement Editor::placementInViewport(int width, int height, double x, double y) {
  ViewRect rect;
  rect.width = width;
  rect.height = height;
  return gl_->viewport.placementAt(*gl_->renderer, *state_, rect, glm::dvec2(x, y), 1.0);
}

std::vector<uint8_t> Editor::screenshot(int* width, int* height) {
  std::vector<uint8_t> pixels;
  glfwPollEvents();
  drawFrame(&pixels, width, height);
  return pixels;
}

}  // namespace strata::ui
