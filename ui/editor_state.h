// Everything the editor's panels read and change, apart from GL objects: the document, the
// selection, the preview shown, messages, the jobs and dialogs in progress, and requests the
// panels leave for the frame loop (view all, quit, ...).
//
// Threads: the UI thread only. What other threads produce arrives as finished values
// (PreviewResult, ExportStatus).
#pragma once

#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "engine/document/document.h"
#include "engine/eval/backend.h"
#include "engine/io/recovery_slots.h"
#include "engine/jobs/background_job.h"
#include "engine/jobs/export_estimate_job.h"
#include "engine/jobs/export_job.h"
#include "engine/jobs/part_measure_job.h"
#include "engine/jobs/preview_worker.h"
#include "ui/file_dialog.h"
#include "ui/gizmo.h"
#include "ui/measure_tool.h"

namespace strata::ui {

enum class LogLevel { Info, Warning, Error };
struct LogLine {
  LogLevel level = LogLevel::Info;
  std::string text;
  double time = 0.0;       // seconds since the editor started
  bool dismissed = false;  // an error stays in the status bar until clicked
  // What an error was about (guarded's topic: "resolution", "scale"): a later success on the
  // same topic settles it (a refused 100000 cells no longer shows once 512 is applied).
  std::string topic;
};

// Something that replaces the document, held back while the user decides about unsaved changes.
struct PendingReplace {
  enum Kind { New, Open, Quit } kind = New;
  std::string path;
};

// The section plane of the viewport: cuts the preview across axis `axis` (0 x, 1 y, 2 z) at
// `at` (scene units along that axis), removing the upper side (the lower with `flip`), and caps
// the cut. Until it is placed (`at` unset) it lies at the fraction `startFraction` of the scene's
// bounds; the editor places it there when it is first shown, so that it stays where it is when
// parts move (sectionAt). A view setting: not part of the document.
struct SectionState {
  bool on = false;
  int axis = 0;
  std::optional<double> at;
  double startFraction = 0.5;
  bool flip = false;
};

// Where a node added by dragging from the palette goes: centred on `point` (world, scene units),
// or, `onGround`, resting on the ground plane z = 0 below `point`.
struct Placement {
  glm::dvec3 point{0.0};
  bool onGround = false;
  // The surface's normal at the point (world, unit): a part dropped there turns its own +z to it.
  std::optional<glm::dvec3> normal;
  // The part whose surface the point is on (0: the ground): a part dropped there goes onto it,
  // as a drop on its tree row does (dropped on the ground: onto the selection).
  NodeId part = 0;
};

// A mesh file chosen for import, waiting for its options in the import dialog.
struct PendingImport {
  std::string path;
  int unit = 0;    // index into importUnits() (import_options.h); 0 = scene units
  int upAxis = 0;  // 0: +Z up (as written), 1: +Y up (turned so that +Y becomes +Z)
  std::optional<Placement> placement;
  // Taken although it is not a closed oriented surface (the dialog's box, offered only for such
  // a mesh): the leaf is marked open (Node::meshOpen) and the scene file keeps the choice.
  bool acceptOpen = false;
};

// What the import dialog learns of its file off the UI thread: its extent as the file has it,
// and what keeps it from being a closed oriented surface ("" where it is one).
struct ImportProbe {
  Bounds bounds;
  std::string openProblem;
};

// A key press as the window system reported it (GLFW key code and modifier bits).
struct KeyPress {
  int key = 0;
  int mods = 0;  // GLFW_MOD_SHIFT 1, GLFW_MOD_CONTROL 2, GLFW_MOD_ALT 4
};

struct EditorState {
  Document document;
  // The tree as it last settled (no drag under way) and its revision: what warnLostContacts
  // (edit_warnings.h) compares the next settled tree with; null after a document was opened or
  // made new. historyRevision: the revision the last undo or redo left (not judged).
  NodePtr contactsRoot;
  uint64_t contactsRevision = ~uint64_t(0);
  uint64_t historyRevision = ~uint64_t(0);
  std::vector<NodeId> selection;  // the primary (inspected, gizmo) node is the last
  // The selection last seen at each document revision (rememberSelection, once a frame): undo
  // and redo bring back the selection of the state they return to.
  std::map<uint64_t, std::vector<NodeId>> selectionAtRevision;
  // What new parts from the palette do where they land (the palette's mode; Ctrl while
  // dropping cuts, Shift intersects, Alt adds): see engine/document/roles.h. Moved and pasted
  // parts keep their own role instead, unless a modifier picks another.
  PlaceMode placeMode = PlaceMode::Add;
  // Copied subtrees (Ctrl+C / Ctrl+X), each with the mode that keeps the role it had when
  // copied; pasted with fresh ids by Ctrl+V.
  struct CopiedPart {
    NodePtr part;
    PlaceMode mode = PlaceMode::Add;  // of its role in its parent
    glm::dvec3 worldOrigin{0.0};      // where its origin was in the world when copied
    // Where it was in the tree when copied: its parent (id and kind; 0 for the root) and its
    // place among the parent's children. A cut part pastes back there, in the role it had.
    NodeId parent = 0;
    NodeKind parentKind = NodeKind::Union;
    int index = -1;
    bool removes = false;  // its material was taken away from the result (a hole)
  };
  std::vector<CopiedPart> clipboard;
  int pastes = 0;  // pasted since the clipboard was filled: each paste lands a step further
  bool clipboardFromCut = false;  // its parts were cut (not in the scene): pasted where they were
  std::function<std::shared_ptr<Backend>()> makeBackend;  // a fresh backend per thread

  // Files outside the document.
  std::string recentFilesPath;  // "" = no recent-files list
  std::vector<std::string> recentFiles;
  std::string recoveryPath;  // this editor's autosave (its recovery slot); "" = no autosave
  std::string recoveryDir;   // the recovery folder, where discarded work is kept
  // Work of editors that ended without saving (the newest first), offered one at a time.
  std::vector<RecoveryOffer> recoveryOffers;
  bool offerRecovery = false;  // !recoveryOffers.empty(): the question is up

  // Preview.
  std::shared_ptr<const PreviewResult> preview;  // shown in the viewport
  // The warnings of the last full pass shown (Editor::pumpPreview): what the panels list while a
  // drag shows drafts, whose own warnings quote their coarser cells (an artist read "a cell is
  // 2.1 mm" of a 0.4 mm scene); empty with no preview.
  std::vector<std::string> fullPassWarnings;
  std::string previewError;  // of the newest evaluation, "" when it worked
  // The preview runs at this many cells instead of the document's resolution, which would not
  // fit in memory (previewResolutionFor); 0 when it runs at the document's.
  int previewCappedAt = 0;
  PreviewStatus worker;
  std::string backendDescription;
  std::string glDescription;
  double frameMs = 0.0;
  // Where the last frame's time went (ms, CPU time on the UI thread up to each step, GL calls
  // queued not waited on but where a step waits): building the panels (input, ImGui), the view,
  // the panels' drawing, the present (swap, or the partial present).
  struct FrameParts {
    double build = 0.0, view = 0.0, panels = 0.0, present = 0.0;
  } frameParts;
  // How splats reach GL: "CUDA-GL interop" or "host upload (...why)"; the last transfer.
  std::string splatTransfer = "host upload";
  double uploadMs = 0.0;
  size_t uploadedBytes = 0;

  // Viewport settings.
  GizmoMode gizmoMode = GizmoMode::Move;
  // With several parts selected, what the gizmo turns and scales them about: the centre of the
  // selection's box (world axes), or the active part's origin (its axes; the others follow).
  bool pivotAtSelectionCentre = true;
  GizmoSnap snap;
  bool snapFollowsGrid = true;  // snap.step is the ground grid's spacing (groundGridStep)
  // The height of the world the view shows at the point it orbits (scene units), set by the
  // viewport each frame: new parts in an empty scene are sized from it.
  double viewExtent = 0.0;
  bool showGrid = true;
  // The inspector's scale: a change to one component scales all three by the same factor.
  bool uniformScale = false;
  // Ghosts (translucent parts that cut or intersect): those of the selection always, all of
  // them with this toggle (View > Ghosts of all cutters, G).
  bool showAllGhosts = false;
  // The resolution `strata edit --resolution N` asked for: each new document (File > New) is
  // previewed at it; 0 = a new document's own (SceneSettings).
  int newDocumentResolution = 0;
  SectionState section;
  bool showDiagnostics = false;
  MeasureTool measure;  // M: distances and angles on the preview (measure_tool.h)
  // Diagnostics: the selected part measured alone in the background; older jobs cancelled and
  // kept until they have stopped (never joined on the UI thread while running).
  std::unique_ptr<PartMeasureJob> partMeasure;
  // What the job measured: the part and its ancestors below the root (shared nodes: the same
  // pointers while nothing on that path changed), and the root's transform.
  std::vector<const Node*> partMeasurePath;
  Transform partMeasureRootTransform;
  std::vector<std::unique_ptr<PartMeasureJob>> retiredPartMeasures;

  // Jobs and dialogs.
  std::unique_ptr<ExportJob> exportJob;
  bool exportEndLogged = false;  // its end said in the log (the status bar showed "exporting")
  // An export refused before it started (its folder takes no file): shown in the export window
  // with why and a way to choose another file, not only in the status bar (an artist's test).
  struct ExportNotStarted {
    std::string path, why;
  };
  std::optional<ExportNotStarted> exportNotStarted;
  // The export dialog (panel_modals.cpp): open while a path waits for its options. The choices
  // are the export's own (not the preview's resolution) and stay for the next export.
  std::optional<std::string> pendingExportPath;
  // The last export's file (absolute) and the document it was of: the next export of that
  // document is offered the same place, not the document's folder again.
  std::string lastExportPath, lastExportDocument;
  // The folder of the last document that had a file, when another replaced it (File > New,
  // Open): where an untitled document's dialogs start (dialogFolder).
  std::string lastDocumentFolder;
  // The folder of the last export of an earlier run (export.txt): where an untitled document's
  // first export is offered, and a document's whose own folder cannot be written to.
  std::string rememberedExportFolder;
  // The file an untitled document was opened as a copy of (the bundled demo): the window's title
  // names it (a bare "untitled" said nothing of the demo on screen: an artist's test); "" else.
  std::string templateName;
  // The folder of the scenes shipped with Strata: one opened from there (File > Open, Recent, the
  // command line) opens as an untitled copy, as the demo does, so that saving never edits the
  // shipped file (an artist's Ctrl+S changed the bundled example for every later user); "" none.
  std::string bundledScenesFolder;
  int exportResolution = 0;  // cells along the longest side; 0: the document's, until chosen
  bool exportSimplify = false;
  float exportSimplifyCells = 0.25f;
  std::string exportSettingsPath;  // where those choices are kept between runs ("" = not kept)
  std::unique_ptr<ExportEstimateJob> exportEstimate;  // the dialog's triangle counts
  // Estimates cancelled (the choice changed, the dialog closed) and not yet finished: dropped
  // once done(), so that the UI never joins a running one.
  std::vector<std::unique_ptr<ExportEstimateJob>> retiredEstimates;
  FileDialog dialog;
  std::optional<PendingReplace> pendingReplace;  // asking about unsaved changes
  bool askingQuitDuringExport = false;           // asking whether to cancel a running export
  // A save over a file changed on disk since (engine/io/document_files.h: changedOnDisk) asks
  // first: what changed, and what to do once it is overwritten.
  std::string overwriteQuestion;
  std::optional<PendingReplace> afterOverwrite;
  std::optional<PendingReplace> afterSaveAs;  // to do once the Save As being asked succeeds
  NodeId renaming = 0;                        // outliner row being renamed
  NodeId viewContextMenu = 0;  // a part right-clicked in the view: its menu is to open
  // The part under the pointer while a palette item is dragged over the view (0: the ground, or
  // not over the view): what a drop there goes onto, said before the release.
  NodeId paletteDropPart = 0;
  std::optional<PendingImport> pendingImport;  // the import dialog is open for it
  std::optional<Placement> importPlacement;    // for the mesh being chosen (palette drag)
  // The file the import dialog is open for, read and checked off the UI thread (its path).
  std::unique_ptr<BackgroundJob<ImportProbe>> importSizeJob;
  std::string importSizePath;
  // The shown result's extent (Diagnostics), from its splats off the UI thread (a device copy
  // waits on the splats' stream); a new one starts once the last is done, never joined running.
  std::unique_ptr<BackgroundJob<Bounds>> resultBoundsJob;
  std::weak_ptr<const SplatResource> resultBoundsOf;  // the splats resultBoundsJob measures
  // The export dialog's grid (Evaluator::gridFor; or why there is none) and its parts too small
  // or thin for its cells (Evaluator::smallPartWarnings), for the document revision and
  // resolution in exportGridFor.
  Grid exportGrid;
  std::string exportNoGrid;
  std::vector<std::string> exportSmallParts;
  std::pair<uint64_t, int> exportGridFor{~uint64_t(0), 0};
  int lastImportUnit = 0;  // the import dialog's last choices
  int lastImportUpAxis = 0;
  std::string lastImportFolder;  // where the last mesh was chosen from (importFolder)
  // A part picked in the view: the outliner opens the rows above it and scrolls its row into view
  // (it stayed where it was, the part's row out of sight: an artist's test); 0 once done.
  NodeId revealInOutliner = 0;
  std::string importSettingsPath;  // where those three are kept between runs ("" = not kept)

  // Requests to the frame loop.
  bool requestViewAll = false;
  bool requestFrameSelected = false;
  // An edit added the selection (a new part, a copy, a paste): the view shows it where it lies
  // out of view (Viewport::revealSelection; an artist's part added beside a zoomed-in detail
  // landed off screen without a word).
  bool revealSelection = false;
  int requestAxisView = -1;  // an AxisView (camera.h) from the View menu; -1 none
  bool requestToggleOrtho = false;
  bool showShortcuts = false;  // the shortcut sheet (F1, Help menu)
  // The viewport's gizmo drag (set by the editor each frame before the shortcuts), and Escape's
  // request to call it off (the viewport restores what the drag moved, with no undo step).
  bool gizmoDragging = false;
  bool cancelGizmoDrag = false;
  // A panel's field dragged with the mouse (set by the editor each frame before the shortcuts;
  // Dear ImGui holds the keyboard then), and the request of Ctrl+Z, redo or Escape to call its
  // drag off (the editor lets the field go and restores what the drag changed, with no undo step).
  bool fieldDragHeld = false;
  bool cancelFieldDrag = false;
  bool quitNow = false;

  // This frame's key presses, collected from GLFW as they happened: ImGui 1.86 samples key
  // state once a frame, so a tap shorter than a frame would be lost to IsKeyPressed.
  std::vector<KeyPress> keyPresses;

  std::deque<LogLine> log;
  double now = 0.0;  // seconds since start, set each frame
};

// --- messages ---
void logInfo(EditorState& state, const std::string& text);
void logWarning(EditorState& state, const std::string& text);
void logError(EditorState& state, const std::string& text);

// True when `key` was pressed this frame with exactly the modifiers `mods` (shift, control and
// alt bits; other bits such as caps lock are ignored).
bool keyPressed(const EditorState& state, int key, int mods = 0);

}  // namespace strata::ui
