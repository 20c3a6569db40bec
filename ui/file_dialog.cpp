#include "ui/file_dialog.h"

#include <imgui.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>

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

const char* zenityFilter(DialogPurpose p) {
  switch (p) {
    case DialogPurpose::Open:
    case DialogPurpose::SaveAs:
      return "--file-filter='Strata scenes | *.strata.json *.json'";
    case DialogPurpose::Export:
      return "--file-filter='Meshes | *.stl *.obj *.ply *.3mf'";
    case DialogPurpose::ImportMesh:
      return "--file-filter='Meshes | *.obj *.stl *.ply *.off *.3mf'";
  }
  return "";
}

const char* kdialogFilter(DialogPurpose p) {
  switch (p) {
    case DialogPurpose::Open:
    case DialogPurpose::SaveAs:
      return "'*.strata.json *.json|Strata scenes'";
    case DialogPurpose::Export:
      return "'*.stl *.obj *.ply *.3mf|Meshes'";
    case DialogPurpose::ImportMesh:
      return "'*.obj *.stl *.ply *.off *.3mf|Meshes'";
  }
  return "''";
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
  if (forced && std::strcmp(forced, "built-in") == 0)
    tool_ = "built-in";
  else if (programInstalled("zenity"))
    tool_ = "zenity";
  else if (programInstalled("kdialog"))
    tool_ = "kdialog";
  else
    tool_ = "built-in";
}

FileDialog::~FileDialog() {
  if (helper_.joinable()) helper_.detach();  // a native dialog left open dies with the process
}

void FileDialog::open(DialogPurpose purpose, const std::string& suggestion) {
  if (open_) return;
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
  if (helper_.joinable()) helper_.join();
  helperDone_ = false;
  helper_ = std::thread([this, command] { runExternal(command + " 2>/dev/null"); });
}

void FileDialog::runExternal(std::string command) {
  std::string out;
  if (FILE* pipe = popen(command.c_str(), "r")) {
    char buffer[4096];
    size_t n;
    while ((n = fread(buffer, 1, sizeof(buffer), pipe)) > 0) out.append(buffer, n);
    pclose(pipe);
  }
  while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
  std::lock_guard<std::mutex> lock(mutex_);
  helperResult_ = out;
  helperDone_ = true;
}

void FileDialog::draw() {
  if (!open_) return;
  if (tool_ != "built-in") {
    if (helperDone_) {
      helper_.join();
      std::lock_guard<std::mutex> lock(mutex_);
      open_ = false;
      if (!helperResult_.empty()) {
        chosen_ = helperResult_;
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
    ImGui::TextUnformatted("Path (no zenity or kdialog found for a file browser):");
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
