// Questions the editor asks of the document tree: world matrices, bounds, leaf colours and
// selection. Plain engine types, no GL; any thread (the tree is immutable).
#pragma once

#include <glm/mat4x4.hpp>

#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "engine/document/measurement.h"
#include "engine/document/node.h"
#include "engine/document/scene.h"
#include "engine/geometry/mesh.h"
#include "engine/kinds/patterns.h"
#include "ui/viewport_renderer.h"

namespace strata::ui {

// Object-to-world matrix of the node's parent (engine/document/measurement.h).
using strata::nodeWorldMatrix;
using strata::parentWorldMatrix;

// World bounds of the visible result of each selected node (empty when nothing is visible).
Bounds selectionBounds(const NodePtr& root, const std::vector<NodeId>& selection);
// Whether selectionBounds of these nodes is their result's extent, not only a bound of it:
// false where a cutter, an intersection, a shrinking offset, a round, a fillet or a circular
// array may leave less, or a turn other than quarter turns (on a node or above it) makes the box
// of a turned part larger than the part. Conservative: false may be said of a tight box.
bool selectionBoundsTight(const NodePtr& root, const std::vector<NodeId>& selection);
// World bounds of the whole visible scene; falls back to every leaf when the result is empty.
Bounds sceneBounds(const NodePtr& root);

// Calls visit(leaf, where it is) for every visible leaf (every node that is not an operation)
// that shows something, in tree order: its world box, the world matrix of its parent (through
// the patterns above it as they show it first, firstPlacement) and whether its material is taken
// away (removesMaterial: an odd number of cutters on its path). Hidden nodes and all below them
// are left out.
struct VisibleLeaf {
  Bounds box;
  glm::dmat4 parentWorld{1.0};
  bool removes = false;
};
void forEachVisibleLeaf(const NodePtr& root,
                        const std::function<void(const NodePtr&, const VisibleLeaf&)>& visit);

// The top of the parts standing under the point (x, y) of the ground: the highest top of the
// boxes of the visible parts that add material (removesMaterial false) whose box holds the
// point; none where no such part lies under it. A new part with nothing selected rested on the
// top of the whole scene's box, 10 mm above the box under it where a sphere beside the box rose
// higher (an artist's test).
std::optional<double> topOfPartsUnder(const NodePtr& root, glm::dvec2 xy);

// Per leaf id, its colour and whether it lies under a selected node (following instances).
LeafStyleTable leafStyles(const NodePtr& root, const std::vector<NodeId>& selection);

// A gizmo drag with several nodes selected: what every other selected node's transform becomes
// when the primary node `primary` gets `primaryNow` in the tree `start` (the tree when the drag
// began). They follow the primary's world motion about its origin: each gets D * (its world
// matrix in `start`), D taking the primary's world matrix in `start` to its new one, turned back
// into a Transform (transformNear: exact for moves and turns; a scale along the primary's
// axes of a node turned against them is its nearest scale and turn, and the node is added to
// `sheared` when not null). Left out: nodes inside another selected node (they move with it)
// and nodes holding or held by the primary.
std::vector<std::pair<NodeId, Transform>> followingTransforms(
    const NodePtr& start, const std::vector<NodeId>& selection, NodeId primary,
    const Transform& primaryNow, std::vector<NodeId>* sheared = nullptr);

// What every selected node's transform becomes when the world motion `motion` (a matrix applied
// to world points) moves the whole selection of the tree `start`: motion * (its world matrix in
// `start`), turned back into a Transform keeping the node's rotation where it can
// (transformNear). Nodes inside another selected node (they move with it) are left out.
// `sheared` (when not null) gets the nodes the motion would shear (a turned part stretched along
// another axis): their Transform is the nearest one, not the motion's.
std::vector<std::pair<NodeId, Transform>> movedSelection(const NodePtr& start,
                                                         const std::vector<NodeId>& selection,
                                                         const glm::dmat4& motion,
                                                         std::vector<NodeId>* sheared = nullptr);
// The selected nodes not inside another selected node.
size_t independentSelectionCount(const NodePtr& root, const std::vector<NodeId>& selection);
// Those nodes, in the selection's order: what a move, a duplicate or an inspector edit of the
// selection changes (the rest follow the node that holds them).
std::vector<NodeId> outermostSelected(const NodePtr& root, const std::vector<NodeId>& selection);
// The outermost selected node holding `id` (tree edges), or `id` itself where none does: what
// the gizmo and the inspector's transform act on for the active part `id`.
NodeId selectedHolder(const NodePtr& root, const std::vector<NodeId>& selection, NodeId id);

// The middle of the bottom of leaf `node`'s own box, in its own frame (its own transform left
// out): the side a part placed on a surface turns towards it (its own -z).
glm::dvec3 ownBottom(const NodePtr& node, const NodePtr& root);

// A part resting on something whose shape was changed from the tree `before` to `after` (a
// size, a radius typed in the inspector) stays on it. On the ground (the bottom of its world
// bounds at z = 0, within a millionth of its size): moved along the world's z so that its bottom
// is at 0 again. On another part (a leaf that adds material, where the middle of the bottom of
// its own box, the side a part dropped on a surface sets on it, lay in the box of a visible part
// that adds material, within a ten-thousandth of the larger box's size): moved so that that
// point stays where it was, the part growing from it.
// A change of its shape parameters or of its own scale (about its origin, a box's middle) alike;
// a part mirrored by the change (a scale that changed sign) is kept on the ground only.
// Its transform in `after` as it is where it rested on nothing, takes material away or shows
// nothing. A box 10 high made 20 high sank 5 into the ground, made 4 floated 3 above it; a 20 mm
// block dropped on a plate and made 6 mm floated 7 mm above it (artists' tests).
struct Rest {
  bool moved = false;     // the transform returned differs from `after`'s
  bool onGround = false;  // it rested on the ground
  NodeId on = 0;          // else the part it rested on (0: none)
};
Transform keptResting(const NodePtr& before, const NodePtr& after, NodeId id, Rest* rest = nullptr);

// Where a mirror's plane goes, placed from its parts (the inspector's "plane at" buttons): back
// through the mirror's origin, through the middle of its parts, or at their low or high side
// along the mirror's axis (the image then touches the original there: model one half, mirror it
// at its cut face). A new mirror's plane passes through its parent's origin, often far from the
// parts (an artist's test).
enum class MirrorPlaneAt { Origin, PartsCentre, PartsLowSide, PartsHighSide };
// The parameters of mirror `id` with its plane's point along its axis moved there (the other
// coordinates of the point kept); the parts' box is taken in the mirror's frame. Unchanged where
// `id` is not a mirror or its parts show nothing.
PatternParams mirrorPlaneAt(const NodePtr& root, NodeId id, MirrorPlaneAt where);

// Where a circular array's axis goes, placed from its neighbours (the inspector's "axis
// through" buttons): what its copies go round is usually what they cut or join (bolt holes round
// a flange), whose middle the artist had to read off and type (an artist's test). The
// neighbours: for a cutter or an intersector (of a difference or an intersection), the base it
// acts on; otherwise its visible siblings. None where it has no parent or they show nothing.
struct CircularAxisPlace {
  PatternParams params;  // the array's parameters with the axis through their middle
  std::string around;    // "union 'body'", "box 'hub' and 2 more" (nodeLabel): for the tooltip
  // How far the middle of the array's parts lies from its axis, before and after (scene units,
  // the array's frame): the parts stay where they are, so the ring's radius changes with the axis
  // (an artist moved the axis and the holes' pitch circle shrank without a word).
  double radiusBefore = 0.0, radiusAfter = 0.0;
};
// The parameters of circular array `id` with its axis's point moved to the middle of its
// neighbours' box, taken in the array's frame (the coordinate along its axis kept).
std::optional<CircularAxisPlace> circularAxisThroughNeighbours(const NodePtr& root, NodeId id);

// A point picked on leaf `leaf`'s surface, whose normal there lies along an axis (within 2
// degrees), moved along that axis onto the face of the leaf's world box on the normal's side
// (the other side for a cutter, whose surface faces into the hole) where it lies within a
// ten-thousandth of the box's size of it, and the normal then turned onto the axis; `point` and
// `normal` as they are otherwise. A pick reads the depth buffer: a part dropped on a plate's top
// at z = 8 landed at 8.00002 and showed "18…" for its centre, and resized it no longer rested on
// the plate; the normal, from the depths around the point, came out 0.5 degrees off the plate's
// and a box dropped there stood tilted, its corners 0.2 mm in and out of the plate (artists'
// tests). A face turned by less than 2 degrees from an axis meets its box's face along an edge
// only: a point picked in it lies off the box's face and is left as picked.
struct FaceSnap {
  glm::dvec3 point;
  glm::dvec3 normal;
};
FaceSnap snappedToBoxFace(const NodePtr& root, NodeId leaf, const glm::dvec3& point,
                          const glm::dvec3& normal);

// A round length near `approximate`: 1, 2 or 5 times a power of ten.
double niceLength(double approximate);

// The spacing of the ground grid drawn under a scene with these bounds (an eighth of its
// largest extent, rounded by niceLength; an empty scene's: an eighth of `emptySpan`, what its
// view spans: emptySceneSpan in import_options.h). The move snap follows it.
double groundGridStep(const Bounds& scene, double emptySpan = 10.0);

// "mm", "cm", "m", "in" for a scene's unit name (engine/document/scene.h).
using strata::unitSymbol;

}  // namespace strata::ui
