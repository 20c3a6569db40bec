// Small helpers to build documents in tests without scene files.
#pragma once

#include <initializer_list>
#include <memory>
#include <string>

#include "engine/document/scene.h"
#include "engine/eval/cpu_backend.h"
#include "engine/eval/evaluator.h"

namespace strata::test {

// Leaves and operations with fresh ids (ids count up per process).
NodePtr box(glm::dvec3 size, glm::dvec3 at = glm::dvec3(0.0));
NodePtr sphere(double radius, glm::dvec3 at = glm::dvec3(0.0));
NodePtr cylinder(double radius, double height, glm::dvec3 at = glm::dvec3(0.0),
                 glm::dvec3 rotateDegrees = glm::dvec3(0.0));
NodePtr torus(double major, double minor, glm::dvec3 at = glm::dvec3(0.0));
NodePtr meshLeaf(std::shared_ptr<const TriangleMesh> mesh, glm::dvec3 at = glm::dvec3(0.0));
NodePtr op(NodeKind kind, std::initializer_list<NodePtr> children);
// An offset, shell, round or fillet node of `amount` scene units over the children.
NodePtr modifier(NodeKind kind, double amount, std::initializer_list<NodePtr> children);
NodePtr withTransform(const NodePtr& node, const Transform& transform);

Scene makeScene(NodePtr root, int resolution, double margin = 0.05);
Scene makeSceneInBox(NodePtr root, int resolution, glm::dvec3 min, glm::dvec3 max);

// Evaluates on a fresh CPU evaluator.
EvalResult evaluateCpu(const Scene& scene);

// tests/data and assets/: the source tree's, or $STRATA_TEST_DATA / $STRATA_ASSETS when set
// (binaries carried to another machine, such as the GPU device, find their data there).
std::string testDataDir();
std::string assetsDir();

// Reads a mesh from tests/data (checked and prepared).
std::shared_ptr<const TriangleMesh> dataMesh(const std::string& file);
// `mesh` with every `every`-th triangle left out (its last of each run): an open mesh with
// holes, as a scan taken with --allow-open or marked open.
std::shared_ptr<const TriangleMesh> withHoles(const TriangleMesh& mesh, size_t every);

}  // namespace strata::test
