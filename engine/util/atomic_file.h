// Writing files so that readers never see half of one: the content goes to "<path>.tmp" in
// the same folder, is flushed to disk, and is renamed over `path`. On any failure (including
// Cancelled thrown by `write`) the temporary file is removed and `path` is left untouched.
#pragma once

#include <functional>
#include <ostream>
#include <string>

namespace strata {

// Calls write(stream) and commits the result atomically. Throws strata::Error naming the path
// when the file cannot be written; rethrows whatever `write` throws.
void writeFileAtomically(const std::string& path, const std::function<void(std::ostream&)>& write);

// Reads a whole file. Throws strata::Error naming the path when it cannot be read.
std::string readWholeFile(const std::string& path);

}  // namespace strata
