// The editor: a window with the scene tree, palette, inspector, status bar and a live surfel
// viewport, over an engine thread that evaluates the document in the background.
//
// app/ constructs it (with the backend chosen there) and calls run(); tests and `strata render`
// drive it frame by frame, wait for the preview and read pixels back.
//
// Threads: construct, use and destroy on the main thread (GLFW and GL). The engine worker and
// export jobs run on their own threads and hand back finished, immutable results.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "engine/eval/backend.h"
#include "engine/jobs/background_job.h"
#include "ui/camera.h"
#include "ui/device_splat_copier.h"
#include "ui/editor_state.h"
#include "ui/mapped_splat_slots.h"
#include "ui/panels.h"
#include "ui/viewport_renderer.h"

namespace strata::ui {

struct EditorOptions {
  std::string scenePath;         // opened at start; "" = a new, empty document
  bool sceneAsTemplate = false;  // open scenePath as an untitled copy (the bundled demo)
  // The shipped scenes' folder: any scene there opens as an untitled copy (EditorState's).
  std::string bundledScenesFolder;
  // Makes a backend; called once for the preview worker and once per export.
  std::function<std::shared_ptr<Backend>()> makeBackend;
  // Optional: copies the backend's device splats into GL (CUDA-GL interop). Without it, or when
  // it cannot attach to this GL context, splats take the host upload path.
  std::function<std::unique_ptr<DeviceSplatCopier>()> makeSplatCopier;
  // Optional: page-locks the mapped GL buffers that the host path's copies of device splats go
  // into (ui/mapped_splat_slots.h), making each copy one DMA.
  PinHostMemory pinHostMemory;
  bool visible = true;  // false: an invisible window for off-screen rendering
  int width = 1600, height = 1000;
  bool fitScreen = false;       // shrink the window to the screen's work area where it is larger
  std::string recentFilesPath;  // "" = none
  std::string layoutPath;       // the panel sizes remembered between runs; "" = the defaults
  // Crash recovery (engine/io/recovery_slots.h): this editor autosaves into a slot of its own in
  // recoveryDir and offers the slots no running editor owns, with the single file of earlier
  // versions at legacyRecoveryPath. "" = no autosave and no recovery offer.
  std::string recoveryDir;
  std::string legacyRecoveryPath;
  std::string exportSettingsPath;  // the export dialog's choices between runs; "" = not kept
  std::string importSettingsPath;  // the import dialog's folder, unit, up axis; "" = not kept
  // A change is written for recovery once it has rested autosaveRestSeconds (a crash then loses
  // seconds of work, not minutes; a burst of edits is written once), and at least every
  // autosaveSeconds while edits keep coming. Written on a thread of its own.
  double autosaveRestSeconds = 1.0;
  double autosaveSeconds = 30.0;
  // Tests: every frame takes at least this long (a slow machine), to show that input made
  // during a slow frame is still handled.
  double slowFrameSeconds = 0.0;
  int coarseResolution = 96;  // of previews while dragging
  // A frame that sends an edit to the engine is built (panels, input) while the engine works,
  // then waits up to this long for the edit's result before drawing the view, so that on a fast
  // engine the edit reaches the screen in that frame.
  double editResultWaitSeconds = 0.008;
  SplatPrimitive splatPrimitive = SplatPrimitive::Automatic;  // how the viewport draws splats
};

// True when a window can be opened (see gl_window.h); otherwise false with the reason.
bool editorDisplayAvailable(std::string* why);

class Editor {
 public:
  // Opens the window, GL and ImGui, starts the engine worker and opens options.scenePath (an
  // unreadable scene is reported in the editor and a new document is shown instead). Throws
  // strata::Error when no window can be opened.
  explicit Editor(EditorOptions options);
  ~Editor();
  Editor(const Editor&) = delete;
  Editor& operator=(const Editor&) = delete;

  // Runs frames until the window is closed (asking about unsaved changes). Returns 0.
  int run();
  // One frame: events, preview results, panels, viewport, present. Returns false once the editor
  // should close.
  bool frame();

  EditorState& state() { return *state_; }
  Camera& camera();
  // The window's client area on the screen (pixels from the screen's top-left corner).
  void windowOrigin(int* x, int* y) const;
  // Waits (polling the worker, no drawing) until the viewport shows the current document at its
  // full resolution, or it failed, or `timeoutSeconds` passed. Returns whether it is shown.
  bool waitForPreview(double timeoutSeconds);
  // Whether the window's view shows the full image of the current preview (every splat of the
  // view's level of detail; not a coarse image of a moving view, or one still being refined).
  bool viewSettled() const;
  // The level of detail of the view's last full image (ViewportRenderer::detailLevel) and the
  // splats it drew.
  int shownDetailLevel() const;
  size_t shownSplats() const;
  // The view shows its coarse image while the full one is drawn (ViewportRenderer).
  bool showsCoarseImage() const;
  // Splats drawn so far as points, as quads and by compute (ViewportRenderer::pointsDrawn,
  // quadsDrawn, computedDrawn).
  size_t splatsDrawnAsPoints() const;
  size_t splatsDrawnAsQuads() const;
  size_t splatsDrawnByCompute() const;
  // The GPU time per splat measured for each kind (ViewportRenderer::nsPerSplat).
  double splatNanoseconds(SplatPrimitive kind) const;
  // Whether a result is being uploaded over several frames (shown once all of it is there).
  bool uploading() const { return staging_ != nullptr; }
  // The ghosts' splats the view draws (ViewportRenderer::ghostCount).
  size_t shownGhostSplats() const;
  // Results whose device splats the worker copied straight into a mapped GL buffer and the
  // frame copied from there on the GPU, so far (MappedSplatSlots::copiedCount).
  size_t resultsInMappedBuffers() const;
  // The longest the last frame() waited for events before drawing, in seconds (0: it only
  // polled): frames keep coming at once while the view refines or a result uploads.
  double lastWaitSeconds() const { return lastWaitSeconds_; }
  // Holds the hand on the scene as a gizmo drag does, for `--measure-latency --drag`: while
  // held, previews are requested as a drag's (drafts, PreviewWorker) and the document's
  // interaction (one undo step) stays open.
  void holdDrag(bool held) { dragHeld_ = held; }
  // Points the camera at the whole scene.
  void viewAll();
  // Renders the 3D view alone (no panels) off-screen: width * height * 4 RGBA bytes, top row
  // first.
  std::vector<uint8_t> renderViewport(int width, int height);
  // What renderViewport(width, height) shows at pixel (x, y) from its top-left corner: the leaf
  // and the point (the click-to-select and drop-from-palette query).
  std::optional<PickHit> pickViewport(int width, int height, double x, double y);
  // Where a palette item dropped at pixel (x, y) of that view goes.
  Placement placementInViewport(int width, int height, double x, double y);
  // Draws one whole frame (panels included) and reads it back: the window's pixels.
  std::vector<uint8_t> screenshot(int* width, int* height);

 private:
  struct Gl;
  void pumpPreview();
  // Sends the worker what the document needs now; returns whether a request went out.
  bool requestPreviewIfNeeded();
  void applyResult(std::shared_ptr<const PreviewResult> result);
  // A large host upload goes over several frames (ViewportRenderer::stageSplats) while the last
  // result stays drawn: one more share of it, and the result shown once all is there.
  void stageMore();
  // Bytes of splats one frame uploads: about kUploadMsPerFrame at the rate measured so far.
  size_t uploadChunkBytes() const;
  // Puts the result's splats into the renderer's buffer: device to device through the copier,
  // or a host upload. Falls back to the host path for good when the copier fails.
  void transferSplats(const PreviewResult& result);
  void dropCopier(const std::string& why);
  // The host path: the worker copies device splats into mapped GL buffers where GL can map
  // them for good (MappedSplatSlots), and the frame copies those on the GPU.
  void lendMappedBuffers();
  // Frees and grows the mapped buffers; stops lending them if one cannot be mapped.
  void maintainMappedBuffers();
  void updateLeafStyles();
  // Gives the renderer the ghosts of the selection (or all) from the shown result.
  void updateGhosts();
  void autosave();
  void drawFrame(std::vector<uint8_t>* capture, int* width, int* height);
  // Takes the worker's newest result, if any, and shows it (unless it is for a scene emptied
  // since). Returns whether one was taken.
  bool takeResult();
  // In a frame that sent an edit (awaitUntil_ set): waits, until awaitUntil_, for the result of
  // the revision sent (any: a coarse one ends the wait too) and takes it; the panels built
  // before it are redrawn by the next frame. Returns the seconds spent waiting (not taking).
  double awaitEditResult();

  EditorOptions options_;
  // Counts the worker's results (its onResult, on the worker's thread) for awaitEditResult.
  struct ResultSignal;
  std::shared_ptr<ResultSignal> resultSignal_;
  double awaitUntil_ = 0.0;      // glfwGetTime() until which this frame awaits its edit's result
  uint64_t awaitFromCount_ = 0;  // the signal's count when the edit was sent
  bool panelsStale_ = false;     // a result was taken after the panels were built
  std::unique_ptr<EditorState> state_;
  std::unique_ptr<Gl> gl_;
  std::unique_ptr<PreviewWorker> worker_;
  // What the worker was last asked for.
  uint64_t requestedRevision_ = ~uint64_t(0);
  int requestedResolution_ = 0;
  int wantedResolution_ = 0;    // the document's resolution when the cap was made
  bool capFromResult_ = false;  // the cap was scaled from a full result
  int cappedResolution_ = 0;    // what the preview evaluates (previewResolutionFor)
  bool requestedInteractive_ = false;
  bool dragHeld_ = false;         // holdDrag
  bool requestedGhosts_ = false;  // the last request asked for every ghost candidate's splats
  // Whether the selection has ghosts, worked out when the document or the selection changes.
  uint64_t ghostWantRevision_ = ~uint64_t(0);
  std::vector<NodeId> ghostWantSelection_;
  bool selectionHasGhosts_ = false;
  bool requestedEmpty_ = false;
  // Leaf colours and selection last given to the renderer.
  uint64_t styledRevision_ = ~uint64_t(0);
  std::vector<NodeId> styledSelection_;
  // Ghosts last given to the renderer: of which result, selection and toggle.
  std::weak_ptr<const PreviewResult> ghostedResult_;
  std::vector<NodeId> ghostedSelection_;
  bool ghostedAll_ = false;
  std::shared_ptr<const PreviewResult> staging_;  // being uploaded (stageMore), not shown yet
  size_t stagedSplats_ = 0;
  double stagingMs_ = 0.0;
  double uploadBytesPerMs_ = 0.0;  // host upload rate seen (0: not measured yet)
  double lastAutosave_ = 0.0;
  double activeUntil_ = 0.0;  // draw without waiting for events until then (seconds)
  bool wasWorking_ = false;   // the engine or an export worked at the last frame (frame())
  // The document's revision and when it last changed (glfwGetTime seconds): a drag whose scene
  // has not changed for kDragRestSeconds is sent as a calm request (requestPreviewIfNeeded).
  uint64_t restRevision_ = ~uint64_t(0);
  double revisionChangedAt_ = 0.0;
  static constexpr double kDragRestSeconds = 0.3;
  double lastWaitSeconds_ = 0.0;  // frame()'s wait for events (lastWaitSeconds)
  uint64_t autosavedRevision_ = 0;
  uint64_t seenRevision_ = 0;  // the document's revision when autosave() last looked
  double changedAt_ = 0.0;     // when that revision was first seen (seconds)
  uint64_t autosavingRevision_ = 0;
  bool recoveryWritten_ = false;                      // a recovery file of this session's may exist
  std::unique_ptr<RecoverySlot> recoverySlot_;        // this editor's, removed on a clean exit
  std::unique_ptr<BackgroundJob<bool>> autosaveJob_;  // writing autosavingRevision_
  double startTime_ = 0.0;
  PanelLayout layout_;  // the panels' sizes (splitters), read from options_.layoutPath
};

}  // namespace strata::ui
