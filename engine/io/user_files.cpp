#include "engine/io/user_files.h"

#include <sys/stat.h>

#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "engine/document/commands.h"
#include "engine/io/scene_file.h"
#include "engine/util/atomic_file.h"
#include "engine/util/error.h"

namespace strata {
namespace {
namespace fs = std::filesystem;

std::string xdgDir(const char* variable, const char* fallbackUnderHome) {
  if (const char* v = std::getenv(variable); v && *v) return std::string(v) + "/strata";
  if (const char* home = std::getenv("HOME"); home && *home)
    return std::string(home) + "/" + fallbackUnderHome + "/strata";
  return "";
}

void makeFolderFor(const std::string& file) {
  fs::path folder = fs::path(file).parent_path();
  if (folder.empty()) return;
  std::error_code ec;
  fs::create_directories(folder, ec);
  if (ec) throw Error(folder.string() + ": cannot create the folder: " + ec.message());
}

std::string originPath(const std::string& recoveryPath) {
  return recoveryPath + ".origin";
}
}  // namespace

std::string userConfigDir() {
  return xdgDir("XDG_CONFIG_HOME", ".config");
}
std::string userDataDir() {
  return xdgDir("XDG_DATA_HOME", ".local/share");
}

std::string defaultRecentFilesPath() {
  std::string dir = userConfigDir();
  return dir.empty() ? "" : dir + "/recent.txt";
}

std::string defaultRecoveryPath() {
  std::string dir = userDataDir();
  return dir.empty() ? "" : dir + "/recovery.strata.json";
}

std::vector<std::string> readRecentFiles(const std::string& listPath) {
  std::vector<std::string> files;
  std::ifstream in(listPath);
  std::string line;
  while (std::getline(in, line) && files.size() < kMaxRecentFiles)
    if (!line.empty() && line[0] == '/') files.push_back(line);
  return files;
}

std::vector<std::string> addRecentFile(const std::string& listPath, const std::string& file) {
  std::string absolute = fs::absolute(file).lexically_normal().string();
  std::vector<std::string> files{absolute};
  for (const auto& f : readRecentFiles(listPath))
    if (f != absolute && files.size() < kMaxRecentFiles) files.push_back(f);
  makeFolderFor(listPath);
  writeFileAtomically(listPath, [&](std::ostream& out) {
    for (const auto& f : files) out << f << "\n";
  });
  return files;
}

void writeRecoveryFile(const Document& document, const std::string& recoveryPath) {
  writeRecoveryFile(document.scene(), document.path(), recoveryPath);
}

void writeRecoveryFile(const Scene& scene, const std::string& documentPath,
                       const std::string& recoveryPath) {
  makeFolderFor(recoveryPath);
  std::string json;
  try {
    json = sceneToJson(scene);  // mesh paths are absolute (Document)
  } catch (const Error& e) {
    throw Error(recoveryPath + ": " + e.what());
  }
  // The document's path from the root: the editor that recovers it may start in another
  // folder (a relative one would name, or overwrite, another file there).
  std::error_code error;
  const fs::path absolute = documentPath.empty() ? fs::path() : fs::absolute(documentPath, error);
  const std::string origin = documentPath.empty() ? ""
                             : error              ? documentPath
                                                  : absolute.lexically_normal().string();
  // One set: a recovery file never sits beside the origin of another document.
  writeFilesAtomically(
      {{recoveryPath, [&](std::ostream& out) { out << json; }},
       {originPath(recoveryPath), [&](std::ostream& out) { out << origin << "\n"; }}});
}

bool recoveryFileExists(const std::string& recoveryPath) {
  std::error_code ec;
  return !recoveryPath.empty() && fs::exists(recoveryPath, ec);
}

Document readRecoveryFile(const std::string& recoveryPath, std::vector<std::string>* warnings) {
  SceneLoadReport report;
  Scene scene = loadScene(recoveryPath, &report, {}, MissingMeshes::Keep);
  if (warnings) warnings->insert(warnings->end(), report.warnings.begin(), report.warnings.end());
  std::string origin;
  std::ifstream in(originPath(recoveryPath));
  std::getline(in, origin);
  Document document(std::move(scene), origin);
  document.markDirty();
  return document;
}

RecoveryInfo describeRecoveryFile(const std::string& recoveryPath) {
  RecoveryInfo info;
  std::ifstream in(originPath(recoveryPath));
  std::getline(in, info.origin);
  struct stat st {};
  if (::stat(recoveryPath.c_str(), &st) == 0) {
    std::tm local{};
    const std::time_t when = st.st_mtime;
    if (localtime_r(&when, &local)) {
      char text[32];
      if (std::strftime(text, sizeof(text), "%Y-%m-%d %H:%M", &local)) info.writtenAt = text;
    }
  }
  return info;
}

void removeRecoveryFile(const std::string& recoveryPath) {
  if (recoveryPath.empty()) return;
  std::error_code ec;
  fs::remove(recoveryPath, ec);
  fs::remove(originPath(recoveryPath), ec);
}

}  // namespace strata
