#include "engine/io/document_files.h"

#include <filesystem>

#include "engine/document/commands.h"
#include "engine/io/mesh_io.h"
#include "engine/io/scene_file.h"
#include "engine/util/error.h"

namespace strata {
namespace fs = std::filesystem;

Document openDocument(const std::string& path, std::vector<std::string>* warnings) {
  SceneLoadReport report;
  Scene scene = loadScene(path, &report, {}, MissingMeshes::Keep);
  if (warnings) warnings->insert(warnings->end(), report.warnings.begin(), report.warnings.end());
  return Document(std::move(scene), path);
}

void saveDocument(Document& document) {
  if (document.path().empty()) throw Error("the document has no file yet; use Save As");
  saveDocumentAs(document, document.path());
}

void saveDocumentAs(Document& document, const std::string& path) {
  if (path.empty()) throw Error("no file name given");
  Scene out = document.scene();
  out.root = relativeMeshPaths(out.root, fs::path(path).parent_path().string());
  std::error_code ec;
  if (fs::exists(path, ec)) {
    fs::copy_file(path, path + ".bak", fs::copy_options::overwrite_existing, ec);
    if (ec) throw Error(path + ".bak: cannot keep the previous version: " + ec.message());
  }
  saveScene(out, path);
  document.markSaved(path);
}

NodeId importMeshFile(Document& document, const std::string& file, NodeId target, PlaceMode mode,
                      const Transform& transform, std::string* sentence) {
  auto mesh = std::make_shared<const TriangleMesh>(readMeshFile(file));
  const std::string hash = hashFile(file);
  const std::string stored = fs::absolute(file).lexically_normal().generic_string();
  return document.addMesh(std::move(mesh), stored, hash, target, mode, transform, sentence);
}

}  // namespace strata
