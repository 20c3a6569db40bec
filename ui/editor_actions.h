// What the editor's menus, shortcuts, panels and tests do to the document: each action is one
// undo step (or none), reports a refusal as an error message instead of throwing, and keeps the
// selection meaningful. No GL; the UI thread.
#pragma once

#include <string>
#include <vector>

#include "ui/editor_state.h"

namespace strata::ui {

NodeId primarySelection(const EditorState& state);
bool isSelected(const EditorState& state, NodeId id);
// Selects `id` alone, or toggles it in the selection when `extend`.
void selectNode(EditorState& state, NodeId id, bool extend = false);
void clearSelection(EditorState& state);
// Shift+click in the outliner: adds every node from the primary selection to `id` in the order
// of `rows`, the rows the outliner shows (a collapsed operation's parts are not among them),
// where both are among them, else in tree order (`id` becomes the primary); selects `id` alone
// when nothing is selected.
void selectRange(EditorState& state, NodeId id, const std::vector<NodeId>& rows = {});
// Drops ids that are no longer in the document (after undo, delete, open).
void pruneSelection(EditorState& state);
// Remembers the selection at the document's current revision (the editor calls it once a frame,
// before input changes either); undo and redo select what was selected in the state they return
// to (the parts of a group whose making is undone, not nothing).
void rememberSelection(EditorState& state);

// New parts land on the primary selection (the root when none) with the editor's place mode:
// they add, cut or intersect as the mode says and no existing part changes its role
// (engine/document/roles.h); the log says what the new part does. Each is one undo step.

// The modifier bits dropMode reads (GLFW's: shift 1, control 2, alt 4).
constexpr int kDropIntersect = 1, kDropCut = 2, kDropAdd = 4;
// The mode a drop onto `target` (0 = the root) uses with the modifier keys held: Ctrl cuts,
// Shift intersects, Alt adds; without one, an existing node `dragged` keeps what it does to the
// result (modeKeepingEffect: its role's mode, or the other where its material was taken away and
// would not be there, or the reverse) and a new part from the palette (dragged 0) takes the
// palette's mode.
PlaceMode dropMode(const EditorState& state, int mods, NodeId dragged = 0, NodeId target = 0);
// What a part placed onto `target` (0 = the root) with `mode` would do, for tooltips ("cuts
// from \"bracket\""), or, for an existing node `dragged`, what it would do once moved there. Sets
// *refused (when given) and returns the reason when the drop would be refused.
std::string placementSentence(const EditorState& state, NodeId target, PlaceMode mode,
                              NodeId dragged = 0, bool* refused = nullptr);

// Adds a primitive sized to the scene (about a quarter of its extent, 1 in an empty scene),
// centred on the top of what it is placed onto (the primary selection, else the scene; at the
// origin in an empty scene) so that the change shows; selects it. One undo step.
NodeId addPrimitive(EditorState& state, NodeKind kind);
// Adds an empty operation the same way.
NodeId addOperation(EditorState& state, NodeKind kind);
// Adds a primitive as addPrimitive does, placed at `placement` (a palette item dropped in the
// viewport): its bounds centred on the point, or resting on the ground plane.
NodeId addPrimitiveAt(EditorState& state, NodeKind kind, const Placement& placement);
// Adds a mesh file as addPrimitive does, with the import options (unit, up axis) and optional
// placement.
NodeId importMesh(EditorState& state, const PendingImport& import);
// A palette item dropped onto outliner row `target` (0: empty space, the root) with `mode`.
// kImportMeshItem opens the file dialog for it.
void dropPaletteItem(EditorState& state, int item, NodeId target, PlaceMode mode);

void deleteSelection(EditorState& state);
void duplicateSelection(EditorState& state);
// The clipboard: copies of the selected subtrees (a node inside another selected one goes with
// it). Cut is copy, then delete (one undo step). Paste places the copies onto the primary
// selection (the root when none), each doing what its original did when copied (a cutter's
// copy cuts), selects them; one undo step.
void copySelection(EditorState& state);
void cutSelection(EditorState& state);
void pasteClipboard(EditorState& state);
// Adds an instance of each selected node (a live copy that follows every edit of the original,
// with its own transform; it starts where the original is) right after it in its parent, and
// selects the instances. One undo step. The root cannot be instanced.
void instanceSelection(EditorState& state);
// Hides the selection, or shows it when every selected node is hidden.
void toggleSelectionHidden(EditorState& state);
void groupSelection(EditorState& state, NodeKind kind);
// What Ctrl+G groups the selection as, keeping what its parts do: an intersection where they
// all intersect (a union of them keeps what either keeps, which is more), else a union.
NodeKind groupKindKeepingRoles(const EditorState& state);
// Where alignSelection meets the active part's bounds on an axis.
enum class AlignEdge { Min, Centre, Max };
// Moves every selected part but the active (primary) one along world `axis` (0 x, 1 y, 2 z) so
// that its bounds' min, centre or max meets the active part's; a part inside another selected
// one moves with it only. One undo step.
void alignSelection(EditorState& state, int axis, AlignEdge edge);
// Moves every selected part (a part inside another selected one with it) along z so that it
// rests on the ground plane z = 0. One undo step.
void dropSelectionToGround(EditorState& state);
void setSelectionOperation(EditorState& state, NodeKind kind);
void renameNode(EditorState& state, NodeId id, const std::string& name);
// Drag and drop in the outliner: node `dragged` onto row `target` (0: empty space, the root)
// with `mode` (movePart in roles.h: every other part keeps its role); the log says what it does
// now. One undo step, named `label` (Edit > Undo "move"; "role" for the inspector's role).
void dropNode(EditorState& state, NodeId dragged, NodeId target, PlaceMode mode,
              const std::string& label = "move");
// An outliner drop of `dragged` onto `target` with the drop modifiers `mods` held (dropMode):
// where `dragged` is one of several selected rows, every selected part no other selected part
// holds moves, each with its own dropMode, in tree order, as one undo step (refused whole,
// nothing moved, where one move is refused); else dropNode.
void dropNodes(EditorState& state, NodeId dragged, NodeId target, int mods);
// Node `id` made to do what `mode` says (add, cut, intersect) where it is: moved onto its own
// parent with that mode (dropNode), or in a modifier or pattern made to cut or intersect its
// siblings there (changeRole in roles.h), so that every other part keeps its role; the log says
// what it does now. Refused, with the reason in the log, for the root and a difference's base
// (whose role is its place). Nothing happens where it already does that. One undo step.
void setRole(EditorState& state, NodeId id, PlaceMode mode);
// What setRole(id, mode) would make the part do, for the artist before the click: where it is
// moved onto its parent (placementSentence), or inside a modifier or pattern what it cuts or
// intersects there ("cuts \"sphere 4\" inside \"shell 5\" ...", changeRole in roles.h).
std::string roleChangeSentence(const EditorState& state, NodeId id, PlaceMode mode);
// Whether a part made to do `mode` inside `parent` (setRole) also becomes its opening: a cutter in
// a shell that has none, so that the hollow reaches out where it cuts (a drain hole, a mouth:
// an artist's cutter inside a shell made a closed pocket, the wall following the cut).
bool opensTheShell(const Node& parent, PlaceMode mode);
// Why setRole(id, mode) would be refused ("" where it would take, or where the part already does
// that): the root, a base, or a part that would land doing what it did (the only child of its
// operation goes back there).
std::string roleChangeRefusal(const EditorState& state, NodeId id, PlaceMode mode);
// The operation node `id` lies in (nullptr for the root or a node not in the tree).
const Node* parentOf(const EditorState& state, NodeId id);
void setResolution(EditorState& state, int resolution);

void undo(EditorState& state);
void redo(EditorState& state);

// Files. Each returns false (with a message) when it failed.
void newDocument(EditorState& state);
// A scene in state.bundledScenesFolder opens as an untitled copy (openTemplate), and says so.
bool openDocument(EditorState& state, const std::string& path);
// Opens a scene as a new, untitled document (the bundled demo: saving asks where, never
// overwriting the original). Mesh paths become absolute so that they resolve from anywhere.
bool openTemplate(EditorState& state, const std::string& path);
// False without a message when the document has no path yet (the caller asks for one).
bool saveDocument(EditorState& state);
bool saveDocumentAs(EditorState& state, const std::string& path);
// The recovery question's answers, for the first of state.recoveryOffers: recovered (it becomes
// the document, its file forgotten), discarded (moved aside, kept: recovery_slots.h), or left
// for a later start. Each then asks about the next offer, if any.
bool recoverDocument(EditorState& state);
void discardRecovery(EditorState& state);
void postponeRecovery(EditorState& state);
// The document's folder, absolute, with a trailing '/' ("" for an untitled document).
std::string documentFolder(const EditorState& state);
// The folder the file dialogs start in: the document's, else the last export's (of this run,
// else of an earlier one), else the user's home (never where the editor happened to be started),
// with a trailing '/'; "" where none is known (the dialog then shows the working folder).
std::string dialogFolder(const EditorState& state);
// What Save as offers: the document's own path, else in dialogFolder the name of the file an
// untitled copy was opened from (a copy of flange_patterns was offered "untitled.strata.json":
// an artist's test), else "untitled.strata.json".
std::string saveAsSuggestion(const EditorState& state);
// Where the import dialog opens: the folder the last mesh was chosen from while it exists
// (meshes live apart from scenes: an artist walked back to them at every import), else
// dialogFolder.
std::string importFolder(const EditorState& state);
// Keeps the import dialog's folder, unit and up axis for the next run (importSettingsPath); a
// failure to write them is a warning in the log.
void rememberImportChoices(EditorState& state);
// The file an export of the document is offered: the last export's of the same document, else
// the document's name beside it with .stl, or in the last export's folder (of this run, else of
// an earlier one) where the document's own takes no file; an untitled one's "part.stl" in the
// last export's folder (of this run, else of an earlier one), else dialogFolder.
std::string exportSuggestion(const EditorState& state);
// The document as the menu bar names it: its file's name, " *" when unsaved; an untitled copy of
// a template names it ("untitled (a copy of demo.strata.json) *").
std::string documentLabel(const EditorState& state);
// The window's title: "Strata — " and documentLabel.
std::string windowTitle(const EditorState& state);
// The folder of an earlier run's last export (EditorState::rememberedExportFolder) with a
// trailing '/', while it exists; else "".
std::string rememberedExportFolder(const EditorState& state);
// The part a palette drop on the surface of leaf `picked` goes onto: the leaf, or where its
// surface is a cutter's or an intersector's the operation whose material it bounds, or the
// pattern it lies in (0 when `picked` is not in the tree).
NodeId dropTargetFor(const NodePtr& root, NodeId picked);
// Starts the background export of the current document to `path` at `resolution`.
// Exports the document in the background (ExportJob); `insist` exports a job whose estimate
// does not fit anyway.
void startExport(EditorState& state, const std::string& path, int resolution,
                 double simplifyCells = 0.0, bool insist = false);
// What a cancel after the write leaves (ExportStatus::cancelledAfterWrite), for the log and the
// Export window alike.
inline constexpr const char* exportCancelledAfterWriteText =
    "the new file is in place and whole, but was not checked (export again to check it)";
// What a cancel before the write leaves, for the log and the Export window alike: "cancelled;
// nothing was written", and where a file was there already, that it is as it was.
std::string exportCancelledText(const ExportStatus& s);
// Once the export has ended, says how in the log, once (written and checked, failed, cancelled):
// the status bar showed "exporting ..." long after. Called every frame (the Export window).
void logExportEnd(EditorState& state);

// Runs `body`, turning strata::Error into an error message; returns whether it succeeded.
// `topic` (may be empty): what the body sets ("resolution", "scale"); its error carries it, and
// a later success on the same topic settles earlier errors of it (LogLine::topic).
bool guarded(EditorState& state, const std::function<void()>& body, const std::string& topic = "");

}  // namespace strata::ui
