#include "app/scene_from_meshes.h"

#include "engine/util/error.h"

namespace strata {

Scene sceneFromMeshFiles(const std::string& operation, const std::vector<std::string>& files,
                         const MeshReadOptions& options, double margin,
                         std::vector<std::string>* warnings) {
  NodeKind kind;
  if (!kindFromName(operation, &kind) || !isOperation(kind) || modifierOf(kind) != Modifier::None)
    throw Error("boolean: unknown operation '" + operation +
                "' (expected union, intersection or difference)");
  static const glm::vec3 kPalette[] = {{0.85f, 0.55f, 0.3f}, {0.3f, 0.6f, 0.85f},
                                       {0.45f, 0.8f, 0.4f},  {0.85f, 0.4f, 0.6f},
                                       {0.7f, 0.7f, 0.35f},  {0.5f, 0.45f, 0.85f}};
  auto root = std::make_shared<Node>();
  root->id = 1;
  root->kind = kind;
  root->name = operation;
  for (size_t i = 0; i < files.size(); ++i) {
    MeshReadReport report;
    auto leaf = std::make_shared<Node>();
    leaf->id = NodeId(i + 2);
    leaf->kind = NodeKind::Mesh;
    leaf->name = files[i].substr(files[i].find_last_of('/') + 1);
    leaf->meshPath = files[i];
    leaf->color = kPalette[i % 6];
    leaf->mesh = std::make_shared<TriangleMesh>(readMeshFile(files[i], options, &report));
    for (const auto& w : report.warnings) warnings->push_back(w);
    root->children.push_back(leaf);
  }
  Scene scene;
  scene.root = root;
  scene.settings.resolution = 256;
  scene.settings.margin = margin;
  return scene;
}

}  // namespace strata
