// A file path for a test to write: `name` in a folder of its own under the test temporary
// directory (created), no file there yet (removed). Header-only; any thread.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace strata::test {

inline std::string freshPath(const std::string& folder, const std::string& name) {
  const std::filesystem::path dir = std::filesystem::path(testing::TempDir()) / folder;
  std::filesystem::create_directories(dir);
  const std::filesystem::path path = dir / name;
  std::filesystem::remove(path);
  return path.string();
}

}  // namespace strata::test
