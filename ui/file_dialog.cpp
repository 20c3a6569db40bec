#include "ui/file_dialog.h"

#include <fcntl.h>
#include <imgui.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <thread>
#include <vector>

#include "engine/io/mesh_formats.h"
#include "engine/util/atomic_file.h"

namespace strata::ui {
namespace {

bool programInstalled(const char* name) {
  std::string command = std::string("command -v ") + name + " >/dev/null 2>&1";
  return std::system(command.c_str()) == 0;
}

std::string shellQuote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

bool isMeshDialog(DialogPurpose p) {
  return p == DialogPurpose::Export || p == DialogPurpose::ImportMesh;
}

// Mesh dialogs list the formats of the table in engine/io/mesh_formats.h: import the readable
// ones, export the writable ones.
MeshAccess meshAccess(DialogPurpose p) {
  return p == DialogPurpose::Export ? MeshAccess::Write : MeshAccess::Read;
}

// "*.stl *.obj ..." for a list of extensions.
std::string patterns(const std::vector<std::string>& extensions) {
  std::string text;
  for (const std::string& ext : extensions) text += (text.empty() ? "*." : " *.") + ext;
  return text;
}

// All meshes first, then one filter per format, named by its label.
std::string zenityFilter(DialogPurpose p) {
  if (!isMeshDialog(p)) return "--file-filter='Strata scenes | *.strata.json *.json'";
  const MeshAccess access = meshAccess(p);
  std::string filters =
      "--file-filter=" + shellQuote("Meshes | " + patterns(meshExtensions(access)));
  for (const MeshFormat& format : meshFormats()) {
    if (!format.supports(access)) continue;
    filters += " --file-filter=" +
               shellQuote(std::string(format.label) + " | " + patterns(format.extensions));
  }
  return filters;
}

std::string kdialogFilter(DialogPurpose p) {
  if (!isMeshDialog(p)) return "'*.strata.json *.json|Strata scenes'";
  return shellQuote(patterns(meshExtensions(meshAccess(p))) + "|Meshes");
}

bool saving(DialogPurpose p) {
  return p == DialogPurpose::SaveAs || p == DialogPurpose::Export;
}

}  // namespace

const char* dialogTitle(DialogPurpose purpose) {
  switch (purpose) {
    case DialogPurpose::Open:
      return "Open scene";
    case DialogPurpose::SaveAs:
      return "Save scene as";
    case DialogPurpose::Export:
      return "Export mesh";
    case DialogPurpose::ImportMesh:
      return "Import mesh";
  }
  return "File";
}

FileDialog::FileDialog() {
  const char* forced = std::getenv("STRATA_FILE_DIALOG");  // "built-in" to skip the tools
  forcedBuiltIn_ = forced && std::strcmp(forced, "built-in") == 0;
}

FileDialog::~FileDialog() {
  if (!external_) return;
  std::lock_guard<std::mutex> lock(external_->mutex);
  if (!external_->done && external_->pid > 0) kill(external_->pid, SIGTERM);
  // The helper thread holds its own reference to the shared state; it reaps the child and ends.
}

void FileDialog::open(DialogPurpose purpose, const std::string& suggestion) {
  if (open_) return;
  if (tool_.empty()) {
    tool_ = forcedBuiltIn_                ? "built-in"
            : programInstalled("zenity")  ? "zenity"
            : programInstalled("kdialog") ? "kdialog"
                                          : "built-in";
  }
  open_ = true;
  purpose_ = purpose;
  hasChosen_ = false;
  selectAll_ = true;  // a refusal in an earlier dialog does not carry over
  missingFolder_.clear();
  if (tool_ == "built-in") {
    std::snprintf(field_, sizeof(field_), "%s", suggestion.c_str());
    const bool scene = suggestion.size() >= 12 &&
                       suggestion.compare(suggestion.size() - 12, 12, ".strata.json") == 0;
    suggestedExtension_ =
        scene ? ".strata.json" : std::filesystem::path(suggestion).extension().string();
    justOpened_ = true;
    focusField_ = true;
    listError_.clear();
    replacing_.clear();
    return;
  }
  std::string command;
  if (tool_ == "zenity") {
    command = "zenity --file-selection --title=" + shellQuote(dialogTitle(purpose)) + " " +
              zenityFilter(purpose) + (saving(purpose) ? " --save --confirm-overwrite" : "") +
              (suggestion.empty() ? "" : " --filename=" + shellQuote(suggestion));
  } else {
    command = std::string("kdialog ") +
              (saving(purpose) ? "--getsavefilename " : "--getopenfilename ") +
              shellQuote(suggestion.empty() ? "." : suggestion) + " " + kdialogFilter(purpose) +
              " --title " + shellQuote(dialogTitle(purpose));
  }
  startExternal(command);
}

void FileDialog::startExternal(const std::string& command) {
  auto state = std::make_shared<External>();
  external_ = state;
  int fds[2];
  pid_t pid = -1;
  if (pipe(fds) == 0) {
    pid = fork();
    if (pid == 0) {
      close(fds[0]);
      dup2(fds[1], 1);
      int devnull = ::open("/dev/null", O_WRONLY);
      if (devnull >= 0) dup2(devnull, 2);
      execl("/bin/sh", "sh", "-c", command.c_str(), static_cast<char*>(nullptr));
      _exit(127);
    }
    close(fds[1]);
    if (pid < 0) close(fds[0]);
  }
  if (pid < 0) {  // no process: the dialog closes as cancelled
    std::lock_guard<std::mutex> lock(state->mutex);
    state->done = true;
    return;
  }
  state->pid = pid;
  std::thread([state, fd = fds[0]] {
    std::string out;
    char buffer[4096];
    ssize_t n;
    while ((n = read(fd, buffer, sizeof(buffer))) > 0) out.append(buffer, size_t(n));
    close(fd);
    waitpid(state->pid, nullptr, 0);
    while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
    {
      std::lock_guard<std::mutex> lock(state->mutex);
      state->output = out;
      state->done = true;
    }
    glfwPostEmptyEvent();  // the editor sleeps in glfwWaitEvents: wake it for the result
  }).detach();
}

void FileDialog::draw() {
  if (!open_) return;
  if (tool_ != "built-in") {
    std::lock_guard<std::mutex> lock(external_->mutex);
    if (external_->done) {
      open_ = false;
      if (!external_->output.empty()) {
        chosen_ = external_->output;
        hasChosen_ = true;
      }
    }
    return;
  }
  // The built-in browser: a folder's listing (folders first, then the files this dialog
  // takes), a path field that a click on a file fills and Enter or Open accepts. Its popup id
  // is its own: the import options that follow an import share no id with it.
  const std::string title = std::string(dialogTitle(purpose_)) + "###strata file browser";
  if (justOpened_) {
    ImGui::OpenPopup(title.c_str());
    justOpened_ = false;
    listFolder(folderOf(field_));
  }
  ImGui::SetNextWindowSize(ImVec2(680, 520), ImGuiCond_Appearing);
  if (!ImGui::BeginPopupModal(title.c_str(), nullptr, ImGuiWindowFlags_NoSavedSettings)) {
    open_ = false;  // closed from outside
    return;
  }
  if (ImGui::Button("Up")) listFolder(std::filesystem::path(folder_).parent_path().string());
  ImGui::SameLine();
  ImGui::TextDisabled("%s", folder_.c_str());
  const float footer =
      ImGui::GetFrameHeightWithSpacing() *
      (3.0f + (listError_.empty() ? 0.0f : 1.5f) + (replacing_.empty() ? 0.0f : 1.5f));
  ImGui::BeginChild("##listing", ImVec2(0, -footer), true);
  std::string enter;  // a folder double-clicked (entered after the loop)
  bool accept = false;
  for (const Entry& e : entries_) {
    const std::string label = (e.folder ? "[folder]  " : "") + e.name;
    const bool selected = !e.folder && field_ == (std::filesystem::path(folder_) / e.name).string();
    if (ImGui::Selectable(label.c_str(), selected, ImGuiSelectableFlags_AllowDoubleClick)) {
      if (e.folder) {
        if (ImGui::IsMouseDoubleClicked(0))
          enter = (std::filesystem::path(folder_) / e.name).string();
      } else {
        std::snprintf(field_, sizeof(field_), "%s",
                      (std::filesystem::path(folder_) / e.name).string().c_str());
        accept = ImGui::IsMouseDoubleClicked(0);
      }
    }
  }
  if (entries_.empty())
    ImGui::TextDisabled("(no folders or %s here)", isMeshDialog(purpose_) ? "meshes" : "scenes");
  ImGui::EndChild();
  if (!enter.empty()) listFolder(enter);
  if (!listError_.empty()) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.5f, 0.45f, 1.0f));
    ImGui::TextWrapped("%s", listError_.c_str());
    ImGui::PopStyleColor();
  }
  // A file saved into a folder that does not exist: the folder made on request, then shown;
  // Save (or Enter) then writes there.
  if (!missingFolder_.empty() && !listError_.empty()) {
    const std::string folder = missingFolder_;
    if (ImGui::Button("Create folder")) {
      std::error_code made;
      std::filesystem::create_directories(folder, made);
      missingFolder_.clear();
      if (made) {
        listError_ = "cannot create " + folder + ": " + made.message();
      } else {
        listFolder(folder);
        focusField_ = true;
      }
    }
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("Create %s", folder.c_str());
  }
  ImGui::SetNextItemWidth(-1);
  // Focused with its text selected when the dialog opens (and on each click into it): what is
  // typed replaces the suggested name instead of joining it.
  if (focusField_) {
    ImGui::SetKeyboardFocusHere();
    focusField_ = false;
  }
  // After a refusal the field takes the keyboard with the path as typed, not selected: it is
  // corrected, not typed again (selectAll_ comes back once the field is left).
  const bool typed = ImGui::InputText(
      "##path", field_, sizeof(field_),
      ImGuiInputTextFlags_EnterReturnsTrue | (selectAll_ ? ImGuiInputTextFlags_AutoSelectAll : 0));
  if (ImGui::IsItemEdited()) {  // the refusal's button and the replace question named the old path
    missingFolder_.clear();
    replacing_.clear();
  }
  if (ImGui::IsItemDeactivated()) selectAll_ = true;
  if (!replacing_.empty()) {  // asked once: the same path again replaces it
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.75f, 0.3f, 1.0f));
    ImGui::TextWrapped("%s exists: Replace (or Enter) writes over it", replacing_.c_str());
    ImGui::PopStyleColor();
  }
  const char* label = !saving(purpose_) ? "Open" : replacing_.empty() ? "Save" : "Replace";
  bool ok = ImGui::Button(label, ImVec2(100, 0)) || typed || accept;
  ImGui::SameLine();
  const bool cancel = ImGui::Button("Cancel", ImVec2(100, 0)) ||
                      ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape));
  ImGui::SameLine();
  ImGui::TextDisabled(forcedBuiltIn_ ? "" : "(zenity or kdialog give the desktop's browser)");
  // A folder typed into the field (a name alone: in the folder shown) is entered, not chosen.
  std::error_code ec;
  if (ok && field_[0] != '\0') {
    std::filesystem::path typed(field_);
    if (typed.is_relative()) typed = std::filesystem::path(folder_) / typed;
    if (std::filesystem::is_directory(typed, ec)) {
      listFolder(typed.lexically_normal().string());
      ok = false;
    }
  }
  if (ok && field_[0] != '\0') {
    const ResolvedPath resolved = resolveDialogPath(field_, folder_, saving(purpose_),
                                                    suggestedExtension_, acceptedExtensions());
    listError_ = resolved.error;
    missingFolder_ = resolved.missingFolder;
    ok = resolved.error.empty();
    // Refused: the field keeps the keyboard, so that the path can be corrected at once.
    if (!ok) {
      focusField_ = true;
      selectAll_ = false;
    }
    // Saving over a file asks first (as the desktop's dialogs do): once for each path.
    if (ok && saving(purpose_) && replacing_ != resolved.path &&
        std::filesystem::exists(resolved.path, ec)) {
      replacing_ = resolved.path;
      focusField_ = true;  // Enter again replaces
      ok = false;
    }
    if (ok) {
      replacing_.clear();
      chosen_ = resolved.path;
      hasChosen_ = true;
      open_ = false;
      ImGui::CloseCurrentPopup();
    }
  } else if (cancel) {
    replacing_.clear();
    open_ = false;
    ImGui::CloseCurrentPopup();
  }
  ImGui::EndPopup();
}

ResolvedPath resolveDialogPath(const std::string& field, const std::string& folder, bool saving,
                               const std::string& extension,
                               const std::vector<std::string>& accepted) {
  namespace fs = std::filesystem;
  ResolvedPath r;
  fs::path path(field);
  if (path.is_relative()) path = fs::path(folder) / path;
  path = path.lexically_normal();
  std::error_code ec;
  if (field.empty() || path.filename().empty() || path.filename() == "." ||
      path.filename() == "..") {
    r.error = "type a file name" + std::string(field.empty() ? "" : " after the folder");
    return r;
  }
  if (saving && !extension.empty()) {
    // Unless it ends in an extension the dialog takes, the suggested one is added
    // ("bracket_v1.2" becomes "bracket_v1.2.stl"; "name." becomes "name.stl").
    std::string name = path.filename().string();
    while (!name.empty() && name.back() == '.') name.pop_back();
    std::string typed = fs::path(name).extension().string();
    for (char& ch : typed) ch = char(std::tolower(static_cast<unsigned char>(ch)));
    const bool known = typed.size() > 1 && std::find(accepted.begin(), accepted.end(),
                                                     typed.substr(1)) != accepted.end();
    if (!known) name += extension;
    path.replace_filename(name);
  }
  const fs::path parent = path.parent_path();
  if (saving && !fs::is_directory(parent, ec)) {
    r.error = "the folder " + parent.string() + " does not exist: choose another, or create it";
    if (!fs::exists(parent, ec)) r.missingFolder = parent.string();
  } else if (saving && fs::is_directory(path, ec))
    r.error = path.string() + " is a folder: type a file name";
  else if (const std::string why = saving ? cannotWriteAt(path.string()) : ""; !why.empty())
    // A folder that takes no file (read-only, not ours): said here, where another can be
    // chosen, not by a failed save or export after the dialog closed (an artist's test).
    r.error = why + ": choose another folder";
  else if (!saving && !fs::is_regular_file(path, ec))
    r.error = (fs::is_directory(path, ec) ? path.string() + " is a folder, not a file"
                                          : "there is no file " + path.string());
  else
    r.path = path.string();
  return r;
}

std::vector<std::string> FileDialog::acceptedExtensions() const {
  if (isMeshDialog(purpose_)) return meshExtensions(meshAccess(purpose_));
  return {"json"};  // scenes: .strata.json (and .json)
}

std::string FileDialog::folderOf(const std::string& suggestion) const {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (suggestion.empty()) return fs::current_path(ec).string();
  fs::path p = fs::absolute(suggestion, ec);
  if (fs::is_directory(p, ec)) return p.string();
  if (fs::is_directory(p.parent_path(), ec)) return p.parent_path().string();
  return fs::current_path(ec).string();
}

void FileDialog::listFolder(const std::string& folder) {
  namespace fs = std::filesystem;
  entries_.clear();
  listError_.clear();
  missingFolder_.clear();
  std::error_code ec;
  fs::path dir = fs::absolute(folder.empty() ? "." : folder, ec).lexically_normal();
  // "/a/b/" is the folder "/a/b" (Up from it only dropped the slash: an artist pressed it twice).
  if (!dir.has_filename() && dir != dir.root_path()) dir = dir.parent_path();
  // The path field follows the folder shown, keeping a file name typed or suggested (it kept
  // the first folder while the listing moved on, and Open took that).
  const fs::path before(field_);
  std::error_code typeError;
  const std::string name = before.has_filename() && !fs::is_directory(before, typeError)
                               ? before.filename().string()
                               : std::string();
  folder_ = dir.string();
  std::snprintf(field_, sizeof(field_), "%s", (dir / name).string().c_str());
  std::vector<std::string> extensions;
  if (isMeshDialog(purpose_)) extensions = meshExtensions(meshAccess(purpose_));
  fs::directory_iterator it(dir, fs::directory_options::skip_permission_denied, ec);
  if (ec) {
    listError_ = "cannot list " + folder_ + ": " + ec.message();
    return;
  }
  for (; it != fs::directory_iterator(); it.increment(ec)) {
    if (ec) break;
    const std::string name = it->path().filename().string();
    if (name.empty() || name[0] == '.') continue;  // hidden files
    std::error_code typeError;
    const bool folder = it->is_directory(typeError);
    if (!folder) {
      std::string lower = name;
      for (char& c : lower) c = char(std::tolower(static_cast<unsigned char>(c)));
      bool wanted = false;
      if (extensions.empty()) {
        wanted = lower.size() > 5 && lower.compare(lower.size() - 5, 5, ".json") == 0;
      } else {
        for (const std::string& ext : extensions)
          wanted = wanted ||
                   (lower.size() > ext.size() + 1 &&
                    lower.compare(lower.size() - ext.size() - 1, ext.size() + 1, "." + ext) == 0);
      }
      if (!wanted) continue;
    }
    entries_.push_back(Entry{name, folder});
  }
  std::sort(entries_.begin(), entries_.end(), [](const Entry& a, const Entry& b) {
    return a.folder != b.folder ? a.folder : a.name < b.name;
  });
}

bool FileDialog::takeResult(std::string* path) {
  if (!hasChosen_) return false;
  hasChosen_ = false;
  *path = chosen_;
  return true;
}

}  // namespace strata::ui
