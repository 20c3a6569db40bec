// Questions the editor asks of the document tree: world matrices, bounds, leaf colours and
// selection. Plain engine types, no GL; any thread (the tree is immutable).
#pragma once

#include <glm/mat4x4.hpp>

#include <vector>

#include "engine/document/node.h"
#include "engine/geometry/mesh.h"
#include "ui/viewport_renderer.h"

namespace strata::ui {

// Object-to-world matrix of the node's parent (identity for the root).
glm::dmat4 parentWorldMatrix(const NodePtr& root, NodeId id);

// World bounds of the visible result of each selected node (empty when nothing is visible).
Bounds selectionBounds(const NodePtr& root, const std::vector<NodeId>& selection);
// World bounds of the whole visible scene; falls back to every leaf when the result is empty.
Bounds sceneBounds(const NodePtr& root);

// Per leaf id, its colour and whether it lies under a selected node (following instances).
LeafStyleTable leafStyles(const NodePtr& root, const std::vector<NodeId>& selection);

// A round length near `approximate`: 1, 2 or 5 times a power of ten.
double niceLength(double approximate);

}  // namespace strata::ui
