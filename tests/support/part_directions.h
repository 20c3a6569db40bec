// Which way each part of a scene moves the result's volume: the ground truth that the role tests
// (duplicate, place, move) compare volumes against.
#pragma once

#include <map>
#include <set>

#include "engine/document/node.h"

namespace strata::test {

// For every visible part of the tree under root: the signs with which the part, where it stands,
// can change the result's volume against the tree without it (+1: it can only add material, -1:
// it can only remove some). A part reached along several paths (inside a subtree that instances
// refer to, or under a shell, which is not monotone) gets every sign of every path; a part with
// both signs has no direction, and volume tests must skip it. Parts only reached through an
// instance of a hidden template count with the instance's signs; hidden parts are not listed.
std::map<NodeId, std::set<int>> partDirections(const NodePtr& root);

}  // namespace strata::test
