#include "ui/file_dialog.h"

#include <fcntl.h>
#include <imgui.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <thread>
#include <vector>

#include "engine/io/mesh_formats.h"

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
  if (tool_ == "built-in") {
    std::snprintf(field_, sizeof(field_), "%s", suggestion.c_str());
    justOpened_ = true;
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
  const char* title = dialogTitle(purpose_);
  if (justOpened_) {
    ImGui::OpenPopup(title);
    justOpened_ = false;
  }
  ImGui::SetNextWindowSize(ImVec2(620, 0), ImGuiCond_Appearing);
  if (ImGui::BeginPopupModal(title, nullptr, ImGuiWindowFlags_NoSavedSettings)) {
    ImGui::TextUnformatted(
        forcedBuiltIn_ ? "Path:" : "Path (no zenity or kdialog found for a file browser):");
    if (ImGui::IsWindowAppearing()) ImGui::SetKeyboardFocusHere();
    ImGui::SetNextItemWidth(-1);
    bool enter =
        ImGui::InputText("##path", field_, sizeof(field_), ImGuiInputTextFlags_EnterReturnsTrue);
    bool ok = ImGui::Button(saving(purpose_) ? "Save" : "Open", ImVec2(100, 0)) || enter;
    ImGui::SameLine();
    bool cancel = ImGui::Button("Cancel", ImVec2(100, 0)) ||
                  ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape));
    if (ok && field_[0] != '\0') {
      chosen_ = field_;
      hasChosen_ = true;
      open_ = false;
      ImGui::CloseCurrentPopup();
    } else if (cancel) {
      open_ = false;
      ImGui::CloseCurrentPopup();
    }
    ImGui::EndPopup();
  } else {
    open_ = false;  // closed from outside
  }
}

bool FileDialog::takeResult(std::string* path) {
  if (!hasChosen_) return false;
  hasChosen_ = false;
  *path = chosen_;
  return true;
}

}  // namespace strata::ui
