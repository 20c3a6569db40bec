// An editable document: the current Scene (an immutable snapshot), its undo history, the file
// it belongs to and whether it differs from that file.
//
// Every command builds a new tree with the pure edits of commands.h and makes it current as one
// undo step; a command that is refused throws strata::Error and leaves the document unchanged.
// New nodes get ids from maxNodeId + 1, so ids stay unique and are never reused while a node
// with that id exists.
//
// Threads: UI thread only. snapshot() hands out the current Scene, which any thread may keep and
// read (an evaluation in the background, an export) while the document moves on.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "engine/document/history.h"
#include "engine/document/roles.h"
#include "engine/document/scene.h"

namespace strata {

class Document {
 public:
  // A new, empty, never saved document: a union root named "scene".
  Document();
  // A document over an existing scene; `path` is the file it came from ("" = none).
  //
  // Mesh paths: in memory every mesh leaf's path is absolute (relative ones in `scene` are
  // resolved against the folder of `path`, or the working directory), so that no edit, undo or
  // Save As can make a path point elsewhere. Only the file written by saveAs holds them relative
  // to its own folder (where the mesh lies inside it).
  explicit Document(Scene scene, std::string path = "");

  const Scene& scene() const { return *state_.scene; }
  const NodePtr& root() const { return state_.scene->root; }
  std::shared_ptr<const Scene> snapshot() const { return state_.scene; }
  // Changes with every edit, undo and redo; equal revisions mean equal documents. Unique across
  // all documents of the process, so that a new or opened document never repeats the revision
  // of the one it replaces (the editor keys its caches on it).
  uint64_t revision() const { return state_.revision; }
  NodeId nextId() const;

  const std::string& path() const { return path_; }
  bool dirty() const { return state_.revision != savedRevision_; }
  // The file's name ("untitled" when none), with " *" when there are unsaved changes.
  std::string title() const;
  // The file's name ("untitled" before the first save), without title()'s unsaved mark.
  std::string name() const;

  // --- commands (each one undo step) ---------------------------------------------------------
  // Makes `root` current as one undo step named `label`. The other commands go through here.
  void apply(const std::string& label, const NodePtr& root);
  // Replaces the measurements (measurement.h) as one undo step; none is kept when nothing
  // changes. Throws strata::Error for a measurement of fewer than 2 or more than 3 points, or a
  // point on a node that is not in the tree.
  void applyMeasurements(const std::string& label, std::vector<Measurement> measurements);

  // Adds a new primitive (default parameters) or operation under `parent` (0 = the root; a leaf
  // parent adds beside it instead, after it in its own parent) at `index` (< 0 = at the end).
  // Returns the new node's id.
  NodeId addNode(NodeKind kind, NodeId parent = 0, int index = -1);
  // Adds `node` (a subtree from elsewhere, e.g. a mesh leaf) with fresh ids; returns its id.
  NodeId addSubtree(const NodePtr& node, NodeId parent = 0, int index = -1);
  // Adds `node` (a subtree from elsewhere: a new primitive, a mesh leaf, a pasted copy) with
  // fresh ids onto `target` (0 = the root) with `mode` (roles.h): it does what the mode says and
  // no existing part changes its role. Returns the new node's id; *sentence (when given) says
  // what it does.
  NodeId place(const NodePtr& node, NodeId target, PlaceMode mode, std::string* sentence = nullptr);
  // Drag and drop with roles: moves node `id` onto `target` (0 = the root) with `mode`
  // (movePart in roles.h); no undo step where that leaves every node where it was. `label`
  // names the undo step ("role" where the move changes a part's role in place).
  void moveOnto(NodeId id, NodeId target, PlaceMode mode, const std::string& label = "move");

  void remove(NodeId id);
  NodeId duplicate(NodeId id);
  void rename(NodeId id, const std::string& name);
  void setTransform(NodeId id, const Transform& transform);
  void setColor(NodeId id, const glm::vec3& color);
  void setParams(NodeId id, const PrimitiveParams& params);
  // A modifier's distance, thickness or radius (Node::amount); checked as the kind requires.
  void setAmount(NodeId id, double amount);
  // A shell's opening (Node::opening): a part inside the shell, or 0 for a closed wall.
  void setOpening(NodeId id, NodeId opening);
  // A pattern's copies (Node::pattern); checked as the kind requires, and refused when the
  // scene would exceed its leaf limit (engine/document/expansion.h).
  void setPattern(NodeId id, const PatternParams& pattern);
  // A mesh leaf's content read again (engine/io's acceptOpenMesh): its mesh, the file's content
  // hash and whether it is taken open; its problem cleared. One undo step.
  void setMesh(NodeId id, std::shared_ptr<const TriangleMesh> mesh, const std::string& hash,
               bool open);
  void setVisible(NodeId id, bool visible);
  // The preview's resolution: saved with the document, so an undo step (kResolutionStep) of its
  // own, changes in a row one step; the other steps' undo and redo keep the resolution set last,
  // as a view setting. Throws strata::Error outside kMinResolution .. kMaxResolution.
  static constexpr const char* kResolutionStep = "resolution";
  void setResolution(int resolution);
  // Drag and drop: under `parent` before child `index`; never into the node's own subtree.
  void move(NodeId id, NodeId parent, int index = -1);
  // Drag and drop on empty space (see moveNodeToTop).
  void moveToTop(NodeId id);
  // Returns the new operation's id.
  NodeId group(const std::vector<NodeId>& ids, NodeKind kind);
  void setOperation(NodeId id, NodeKind kind);

  // --- history -------------------------------------------------------------------------------
  bool canUndo() const { return history_.canUndo(); }
  bool canRedo() const { return history_.canRedo(); }
  std::string undoLabel() const { return history_.undoLabel(); }
  std::string redoLabel() const { return history_.redoLabel(); }
  bool undo();
  bool redo();
  // A drag or a held widget: every edit until endInteraction() is one undo step.
  void beginInteraction() { history_.beginInteraction(); }
  void endInteraction() { history_.endInteraction(); }
  // Ends a drag that was called off (Escape): the document is as it was before it, with no undo
  // step for it.
  void cancelInteraction();
  bool interacting() const { return history_.interacting(); }
  // The tree where the open interaction began (before its first edit), or null when none is
  // open or it has changed nothing yet: a drag's every frame can be worked out from it.
  // interactionsBegun() tells one interaction from the next.
  uint64_t interactionsBegun() const { return history_.interactionsBegun(); }
  NodePtr interactionStart() const {
    const DocumentState* start = history_.interactionStart();
    return start ? start->scene->root : nullptr;
  }

  // --- files (read and written by engine/io/document_files.h) ---------------------------------
  // The document now belongs to `path` and is clean (it was just written there).
  void markSaved(const std::string& path) {
    path_ = path;
    savedRevision_ = state_.revision;
    resolutionStepOpen_ = false;  // a change after a save is a step of its own
  }
  // Makes the document belong to `path` without writing (e.g. after recovering it).
  void setPath(const std::string& path) { path_ = path; }
  // Marks the current state as modified (e.g. a recovered document that was never saved).
  void markDirty() { savedRevision_ = ~uint64_t(0); }
  // Its file as it was when last opened or saved here (document_files.h stamps and compares it),
  // so that a save over a file another editor or program wrote since can ask first.
  struct FileStamp {
    bool known = false;
    int64_t modifiedNs = 0;
    uint64_t size = 0;
    bool operator==(const FileStamp& o) const {
      return known == o.known && modifiedNs == o.modifiedNs && size == o.size;
    }
  };
  const FileStamp& fileStamp() const { return fileStamp_; }
  void setFileStamp(const FileStamp& stamp) { fileStamp_ = stamp; }

 private:
  NodeId parentForAdd(NodeId parent, int* index) const;
  // A state restored by undo or redo, with the resolution set last (setResolution).
  DocumentState withCurrentResolution(DocumentState restored);

  DocumentState state_;
  History history_;
  // The last change was the resolution's (setResolution): the next one extends its step.
  bool resolutionStepOpen_ = false;
  std::string path_;
  uint64_t savedRevision_ = 0;
  FileStamp fileStamp_;
};

}  // namespace strata
