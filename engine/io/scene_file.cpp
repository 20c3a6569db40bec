// Scene files on disk: loading (read, then parseScene), atomic saving, file content hashes.
// Parsing and validation are in scene_json_read.cpp, serialisation in scene_json_write.cpp.
#include "engine/io/scene_file.h"

#include <filesystem>
#include <ostream>
#include <string>

#include "engine/util/atomic_file.h"
#include "engine/util/error.h"
#include "engine/util/hash.h"

namespace strata {

Scene loadScene(const std::string& path, SceneLoadReport* report,
                const MeshReadOptions& meshOptions, MissingMeshes missing) {
  std::string text = readWholeFile(path);
  std::string baseDir = std::filesystem::path(path).parent_path().string();
  return parseScene(text, path, baseDir, report, meshOptions, missing);
}

void saveScene(const Scene& scene, const std::string& path) {
  std::string text;
  try {
    text = sceneToJson(scene);  // before touching the disk: a refused scene leaves no file
  } catch (const Error& e) {
    throw Error(path + ": " + e.what());
  }
  writeFileAtomically(path, [&text](std::ostream& out) { out << text; });
}

std::string hashFile(const std::string& path) {
  std::string bytes = readWholeFile(path);
  Hasher hasher;
  hasher.bytes(bytes.data(), bytes.size());
  return formatContentHash(hasher.digest());
}

}  // namespace strata
