// Scene files (*.strata.json): the documented, versioned JSON format described in
// engine/io/SCENE_FORMAT.md.
//
// Loading validates everything: unknown fields, wrong types, values out of range, duplicate
// ids, instance cycles and absurd depth all throw strata::Error naming the file and the JSON
// location ("scene.strata.json: /root/children/2/transform/scale: expected 3 numbers").
// Referenced meshes are read with readMeshFile (paths relative to the scene file's folder).
#pragma once

#include <string>
#include <vector>

#include "engine/document/scene.h"
#include "engine/io/mesh_io.h"
#include "engine/util/limits.h"

namespace strata {

// 2: offset, shell, round and fillet nodes. Version 1 files read unchanged.
// 3: a shell's opening (the `opening` member).
// 4: patterns: array, circularArray and mirror nodes.
// 5: a mesh accepted although it is open (the mesh's `open` member).
constexpr int kSceneFormatVersion = 5;

struct SceneLoadReport {
  std::vector<std::string> warnings;  // e.g. a mesh whose content hash changed since saving
};

// What loading does with a mesh file that cannot be read (missing, moved, damaged).
enum class MissingMeshes {
  Refuse,  // the scene is refused, naming the file (the command line: a batch must not guess)
  Keep,    // the node is kept with its path and recorded hash but an empty mesh (nothing of it
           // is evaluated), and a warning says so: the editor opens the rest of the work
};

// Reads and validates a scene file, loading the meshes it references.
Scene loadScene(const std::string& path, SceneLoadReport* report = nullptr,
                const MeshReadOptions& meshOptions = {},
                MissingMeshes missing = MissingMeshes::Refuse);

// Parses scene JSON text. `sourceName` is used in messages; mesh paths resolve against
// `baseDir`.
Scene parseScene(const std::string& text, const std::string& sourceName, const std::string& baseDir,
                 SceneLoadReport* report = nullptr, const MeshReadOptions& meshOptions = {},
                 MissingMeshes missing = MissingMeshes::Refuse);

// Serialises a scene; mesh paths are written as stored in the nodes.
std::string sceneToJson(const Scene& scene);

// Writes atomically (engine/util/atomic_file.h): to a temporary file of its own beside `path`
// (created exclusively, never through a link), synced, then renamed over `path`; a failure
// leaves `path` as it was and no temporary file. Throws strata::Error naming the path.
void saveScene(const Scene& scene, const std::string& path);

// The content hash that mesh nodes record ("fnv1a64:" + 16 hex digits, see formatContentHash)
// of the file's bytes. Throws strata::Error naming the path when it cannot be read.
std::string hashFile(const std::string& path);

}  // namespace strata
