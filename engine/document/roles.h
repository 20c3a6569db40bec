// What each part does in its parent, and where a new, pasted or moved part goes so that every
// existing part keeps doing what it did.
//
// A child's role follows from its parent's Boolean and its place: every child of a union adds,
// the first child of a difference is its base and the others cut it, every child of an
// intersection intersects. Scene files store the tree only; roles are read from it (files of
// every version mean what they meant).
//
// A part is placed onto a target node with a mode the artist chose (add, cut, intersect), and
// the rule is the same for adding, pasting and dropping:
//   1. the target is an operation of the mode's Boolean: the part becomes its last child (an
//      empty operation takes it as its first child); a part added onto a modifier or a pattern
//      (which unite their children, see unitesItsChildren) joins its children likewise, so that
//      the modifier changes it or the pattern repeats it: a row dropped onto a shell's row goes
//      into the shell, as into a folder (an artist's test saw it land beside the shell);
//   2. the target already plays the mode's role in its parent (a union's child for add, a
//      difference's cutter for cut, an intersection's child for intersect): the part goes right
//      after it, beside it;
//   3. otherwise the target is wrapped: a new operation of the mode's Boolean takes its place,
//      with the target as its first child and the part as its second.
// No rule reorders or removes an existing child, so no existing part changes its role.
//
// Threads: any; pure functions of immutable trees.
#pragma once

#include <string>
#include <vector>

#include "engine/document/node.h"

namespace strata {

enum class ChildRole {
  Root,       // the top of the tree
  Base,       // first child of a difference: what its cutters cut
  Add,        // child of a union
  Cut,        // later child of a difference
  Intersect,  // child of an intersection
};

// The role of child `index` of operation `parent`.
ChildRole childRole(const Node& parent, int index);
// The role of node `id` in its parent (Root for the root); throws strata::Error when absent.
ChildRole roleOf(const NodePtr& root, NodeId id);
// For people: "base", "adds", "cuts", "intersects" ("root" for the root).
const char* roleWord(ChildRole role);
// For sentences: "is the root", "is the base", "adds", "cuts", "intersects".
const char* rolePhrase(ChildRole role);
// What turning operation `op` into one of `kind` does to its children's roles, for the artist
// before the click ("\"hub\" and \"ribs\" will cut \"base plate\""); "" when no role changes.
std::string roleChangesOfKind(const Node& op, NodeKind kind);
// Whether node `id`'s material ends up taken away from the result: an odd number of cutters
// on its path from the root (itself included). Intersections count as keeping.
bool removesMaterial(const NodePtr& root, NodeId id);

// Ghosts (parts drawn translucent over the result, from their own LDIs): every visible node
// that cuts or intersects (its role in its parent), in tree order. A hidden node, or one under a
// hidden node, has none.
std::vector<NodeId> ghostCandidates(const NodePtr& root);
// The ghosts of a selection: what cuts or intersects each selected node (the cutters of every
// difference whose base holds it, the other children of every intersection that holds it), the
// selected nodes and the nodes holding them that cut or intersect themselves, and those inside
// the selected nodes. All of ghostCandidates with `all`. Tree order, no repeats.
std::vector<NodeId> ghostsOf(const NodePtr& root, const std::vector<NodeId>& selection, bool all);

// What the artist chose a new or moved part to do.
enum class PlaceMode { Add, Cut, Intersect };
// "add", "cut", "intersect".
const char* placeModeName(PlaceMode mode);
// The mode that keeps what a part does: cut for a cutter, intersect for a child of an
// intersection, add for the rest (a base or the root placed elsewhere adds). Moved and pasted
// parts keep their role unless the artist picks another.
PlaceMode modeKeepingRole(ChildRole role);
// The mode for placing a part onto `target` (in `root`, which does not hold the part) so that its
// material is taken away from the result exactly when `removes` says (removesMaterial where it
// was): `kept`, its role's mode, where that does (nothing else then changes), else add or cut.
// A part that added to a cutter (a countersink in a union of holes) pasted or dropped with its
// role's mode onto a part of the base became a peg where it was a hole (an artist's test).
// Intersecting parts keep `kept`; a target refused by every mode gives `kept` (the placement
// then says why).
PlaceMode modeKeepingEffect(const NodePtr& root, NodeId target, PlaceMode kept, bool removes);
// The instances that a move of node `moved` (the tree `before`, then `after`) changes: those of a
// part it leaves or joins, and those of itself where its own transform changed (it keeps its
// place in the world in a parent placed otherwise); for the artist before a drop is released:
// "; \"cross bore along y\" (an instance of \"cross bore\") changes with it" ("" for none). A part
// dragged out of a group that an instance repeats changed the instance too, without a word.
std::string instancesChangedNote(const NodePtr& before, const NodePtr& after, NodeId moved);
// What a move of node `moved` (the tree `before`, then `after`) stops it doing where it was,
// for the artist before a drop is released: "; it no longer cuts \"body\"", "; it no longer
// adds to \"ribs\", nor is repeated by it; \"ribs\" is left empty" ("" where it stays within its
// parent). A cutter dragged elsewhere took its hole out of the part it cut, and a solid dragged
// out of a mirror took its image, with a tooltip that named only where they went (an artist's
// test).
std::string leavesNote(const NodePtr& before, const NodePtr& after, NodeId moved);
// The operation kind whose Boolean the mode applies (from the kind table).
NodeKind operationKindFor(PlaceMode mode);

// Where a part placed onto `target` with `mode` goes (the rules above), and a sentence for the
// artist that says what it will do ("cuts from \"bracket\"", "adds to \"rounded plate\" in a new
// union"), shown before a drop is released.
struct PlacePlan {
  NodeId parent = 0;   // the operation receiving the part; 0 when wrapping
  int index = -1;      // before this child of `parent` (-1: at the end)
  NodeId wrapped = 0;  // the node a new operation takes the place of (rule 3)
  NodeKind wrapKind = NodeKind::Union;
  // Whether the part's material ends up taken away from the result (removesMaterial once
  // placed): a cutter, or a part that adds to or intersects a cutter.
  bool removesMaterial = false;
  std::string sentence;  // ends with what happens to the material when it is not what the
                         // mode says (a part that adds inside a cutter takes material away)
};
// Whether a part added onto a modifier or a pattern goes into it (rule 1: a drop, a paste or a
// palette click onto it) or is placed as onto any other part (a duplicate of the modifier lands
// beside it, not inside it).
enum class IntoUniting { Yes, No };
// Throws strata::Error when `target` is not in the tree.
PlacePlan planPlacement(const NodePtr& root, NodeId target, PlaceMode mode,
                        IntoUniting into = IntoUniting::Yes);

// Carries out `plan` for `part` (its ids new to the tree). A wrapping operation gets id
// `groupId` (unused in the tree and the part). Returns the new root.
NodePtr placePart(const NodePtr& root, const PlacePlan& plan, const NodePtr& part, NodeId groupId);

// Whether `op` unites its children and then changes or repeats the union as one solid (a
// modifier: offset, shell, round, fillet; a pattern: array, circular array, mirror).
bool unitesItsChildren(const Node& op);

// Node `id` made to do what `mode` says where it is, every other part keeping its role: moved
// onto its own parent with that mode (movePart), except where the parent unites its children
// (unitesItsChildren) and the part is to cut or intersect: there it acts on its siblings inside
// the parent, which then changes or repeats the result. The siblings (their union, id
// `groupId + 1`, where there are several) and the part become the two children of a new
// operation of the mode's Boolean (id `groupId`), the parent's only child; a shell's opening
// stays inside its shell, a pattern repeats the cut. Both ids must be unused. Throws
// strata::Error as movePart does, and for the only child of such a parent (nothing to act on).
NodePtr changeRole(const NodePtr& root, NodeId id, PlaceMode mode, NodeId groupId);

// Detaches node `id` and places it onto `target` with `mode`. Refused for the root, for a
// target inside the moved node, and when it would make an instance cycle. A moved base of a
// difference with cutters leaves an empty base behind (see removeKeepingRoles). The wrapping
// operation (when one is made) gets `groupId`, the empty base `groupId + 1`: both must be unused.
NodePtr movePart(const NodePtr& root, NodeId id, NodeId target, PlaceMode mode, NodeId groupId);

// The tree without node `id` (no instance checks: the caller moves or deletes it). When `id` is
// the base of a difference that has cutters, an empty union named "empty base" with id
// `placeholderId` takes its place: the cutters keep cutting nothing instead of the first of them
// becoming the base.
NodePtr removeKeepingRoles(const NodePtr& root, NodeId id, NodeId placeholderId);

}  // namespace strata
