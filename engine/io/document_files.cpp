#include "engine/io/document_files.h"

#include <sys/stat.h>

#include <ctime>
#include <filesystem>

#include "engine/document/commands.h"
#include "engine/geometry/mesh_world_bounds.h"
#include "engine/io/mesh_io.h"
#include "engine/io/scene_file.h"
#include "engine/util/error.h"

namespace strata {
namespace fs = std::filesystem;

Document openDocument(const std::string& path, std::vector<std::string>* warnings) {
  SceneLoadReport report;
  Scene scene = loadScene(path, &report, {}, MissingMeshes::Keep);
  if (warnings) warnings->insert(warnings->end(), report.warnings.begin(), report.warnings.end());
  // The editor asks the meshes' bounds on every edit: their trees built now, with the loading.
  std::vector<const Node*> stack{scene.root.get()};
  while (!stack.empty()) {
    const Node* node = stack.back();
    stack.pop_back();
    if (!node) continue;
    prepareMeshWorldBounds(node->mesh);
    for (const NodePtr& child : node->children) stack.push_back(child.get());
  }
  Document document(std::move(scene), path);
  document.setFileStamp(fileStampOf(path));
  return document;
}

Document::FileStamp fileStampOf(const std::string& path) {
  Document::FileStamp stamp;
  struct stat st {};
  if (path.empty() || ::stat(path.c_str(), &st) != 0) return stamp;
  stamp.known = true;
  stamp.modifiedNs = int64_t(st.st_mtim.tv_sec) * 1000000000 + int64_t(st.st_mtim.tv_nsec);
  stamp.size = uint64_t(st.st_size);
  return stamp;
}

std::string changedOnDisk(const Document& document) {
  const Document::FileStamp& was = document.fileStamp();
  if (document.path().empty() || !was.known) return "";
  const Document::FileStamp now = fileStampOf(document.path());
  if (now == was) return "";
  if (!now.known) return "";  // deleted or moved away: a save puts it back, overwriting nothing
  char when[32] = "";
  const std::time_t t = std::time_t(now.modifiedNs / 1000000000);
  std::tm local{};
  if (localtime_r(&t, &local)) std::strftime(when, sizeof(when), "%Y-%m-%d %H:%M:%S", &local);
  return document.path() + " was written by another editor or program since it was opened or " +
         "saved here (at " + when + ", " + std::to_string(now.size) + " bytes)";
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
  document.setFileStamp(fileStampOf(path));
}

namespace {
// A mesh file as a document's leaf holds it: read and checked (open ones too with `acceptOpen`,
// then `open` says whether it is), with the file's content hash.
struct LeafMesh {
  std::shared_ptr<const TriangleMesh> mesh;
  std::string hash;
  bool open = false;
};
LeafMesh readLeafMesh(const std::string& file, bool acceptOpen) {
  MeshReadOptions options;
  options.allowOpen = acceptOpen;
  MeshReadReport report;
  LeafMesh read;
  read.mesh = std::make_shared<const TriangleMesh>(readMeshFile(file, options, &report));
  prepareMeshWorldBounds(read.mesh);  // the editor asks its bounds on every edit
  read.hash = hashFile(file);
  read.open = !report.openProblem.empty();
  return read;
}
}  // namespace

void acceptOpenMesh(Document& document, NodeId id) {
  const NodePtr node = findNode(document.root(), id);
  if (!node || node->kind != NodeKind::Mesh)
    throw Error("there is no mesh node with id " + std::to_string(id));
  LeafMesh read = readLeafMesh(node->meshPath, true);
  document.setMesh(id, std::move(read.mesh), read.hash, read.open);
}

NodeId importMeshFile(Document& document, const std::string& file, NodeId target, PlaceMode mode,
                      const Transform& transform, std::string* sentence, bool acceptOpen) {
  LeafMesh read = readLeafMesh(file, acceptOpen);
  const std::string stored = fs::absolute(file).lexically_normal().generic_string();
  auto node = std::make_shared<Node>(*makeMeshNode(
      1, fs::path(file).stem().string(), std::move(read.mesh), stored, read.hash, read.open));
  node->transform = transform;
  return document.place(node, target, mode, sentence);
}

}  // namespace strata
