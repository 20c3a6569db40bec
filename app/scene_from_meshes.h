// The scene `strata boolean OP A B...` evaluates: one n-ary operation over mesh files.
#pragma once

#include <string>
#include <vector>

#include "engine/document/scene.h"
#include "engine/io/mesh_io.h"

namespace strata {

// Reads every file (strict; warnings appended to `warnings`) and builds union / intersection /
// difference (first minus the rest) of them, leaves coloured from a fixed palette.
Scene sceneFromMeshFiles(const std::string& operation, const std::vector<std::string>& files,
                         const MeshReadOptions& options, double margin,
                         std::vector<std::string>* warnings);

}  // namespace strata
