#include "tests/support/scene_builder.h"

#include <atomic>
#include <cstdlib>

#include "engine/io/mesh_io.h"

namespace strata::test {
namespace {
std::atomic<NodeId> g_nextId{1};

std::shared_ptr<Node> leaf(NodeKind kind, glm::dvec3 at) {
  auto n = std::make_shared<Node>();
  n->id = g_nextId++;
  n->kind = kind;
  n->name = std::string(kindName(kind)) + std::to_string(n->id);
  n->transform.translate = at;
  return n;
}
}  // namespace

NodePtr box(glm::dvec3 size, glm::dvec3 at) {
  auto n = leaf(NodeKind::Box, at);
  n->params.size = size;
  return n;
}

NodePtr sphere(double radius, glm::dvec3 at) {
  auto n = leaf(NodeKind::Sphere, at);
  n->params.radius = radius;
  return n;
}

NodePtr cylinder(double radius, double height, glm::dvec3 at, glm::dvec3 rotateDegrees) {
  auto n = leaf(NodeKind::Cylinder, at);
  n->params.radius = radius;
  n->params.height = height;
  n->transform.rotateDegrees = rotateDegrees;
  return n;
}

NodePtr torus(double major, double minor, glm::dvec3 at) {
  auto n = leaf(NodeKind::Torus, at);
  n->params.majorRadius = major;
  n->params.minorRadius = minor;
  return n;
}

NodePtr meshLeaf(std::shared_ptr<const TriangleMesh> mesh, glm::dvec3 at) {
  auto n = leaf(NodeKind::Mesh, at);
  n->mesh = std::move(mesh);
  return n;
}

NodePtr op(NodeKind kind, std::initializer_list<NodePtr> children) {
  auto n = leaf(kind, glm::dvec3(0.0));
  n->children.assign(children.begin(), children.end());
  return n;
}

NodePtr modifier(NodeKind kind, double amount, std::initializer_list<NodePtr> children) {
  auto n = std::make_shared<Node>(*op(kind, children));
  n->amount = amount;
  return n;
}

NodePtr withTransform(const NodePtr& node, const Transform& transform) {
  auto n = std::make_shared<Node>(*node);
  n->transform = transform;
  return n;
}

Scene makeScene(NodePtr root, int resolution, double margin) {
  Scene s;
  s.root = std::move(root);
  s.settings.resolution = resolution;
  s.settings.margin = margin;
  return s;
}

Scene makeSceneInBox(NodePtr root, int resolution, glm::dvec3 min, glm::dvec3 max) {
  Scene s = makeScene(std::move(root), resolution);
  s.settings.hasBounds = true;
  s.settings.bounds.min = min;
  s.settings.bounds.max = max;
  return s;
}

EvalResult evaluateCpu(const Scene& scene) {
  Evaluator evaluator(std::make_shared<CpuBackend>());
  Progress progress;
  return evaluator.evaluate(scene, EvalOptions{}, progress);
}

std::string testDataDir() {
  const char* env = std::getenv("STRATA_TEST_DATA");
  return env ? env : STRATA_TEST_DATA;
}

std::string assetsDir() {
  const char* env = std::getenv("STRATA_ASSETS");
  return env ? env : STRATA_ASSETS;
}

std::shared_ptr<const TriangleMesh> dataMesh(const std::string& file) {
  return std::make_shared<TriangleMesh>(readMeshFile(testDataDir() + "/" + file));
}

std::shared_ptr<const TriangleMesh> withHoles(const TriangleMesh& mesh, size_t every) {
  auto open = std::make_shared<TriangleMesh>(mesh);
  open->triangles.clear();
  for (size_t t = 0; t < mesh.triangles.size(); ++t)
    if (t % every != every - 1) open->triangles.push_back(mesh.triangles[t]);
  return open;
}

}  // namespace strata::test
