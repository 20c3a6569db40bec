// Choosing a file: zenity or kdialog when installed (run on a helper thread, so the editor keeps
// drawing), otherwise an ImGui window with a path field.
//
// Threads: the UI thread; the helper thread only runs the external program.
#pragma once

#include <atomic>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

namespace strata::ui {

enum class DialogPurpose { Open, SaveAs, Export, ImportMesh };

class FileDialog {
 public:
  FileDialog();
  ~FileDialog();
  FileDialog(const FileDialog&) = delete;
  FileDialog& operator=(const FileDialog&) = delete;

  // Opens a dialog (replacing none: ignored while one is open). `suggestion` is the initial
  // path or folder.
  void open(DialogPurpose purpose, const std::string& suggestion);
  bool isOpen() const { return open_; }
  DialogPurpose purpose() const { return purpose_; }
  // Draws the ImGui fallback when it is the one in use. Call once per frame.
  void draw();
  // When the user has chosen, returns true once with the path in *path; a cancelled dialog
  // closes without returning a path.
  bool takeResult(std::string* path);
  // "zenity", "kdialog" or "built-in".
  const std::string& tool() const { return tool_; }

 private:
  void runExternal(std::string command);

  std::string tool_;
  bool open_ = false;
  DialogPurpose purpose_ = DialogPurpose::Open;
  char field_[1024] = {};
  bool justOpened_ = false;
  std::string chosen_;
  bool hasChosen_ = false;
  std::thread helper_;
  std::mutex mutex_;
  std::atomic<bool> helperDone_{false};
  std::string helperResult_;
};

// "Open scene", "Save scene as", ... for titles and labels.
const char* dialogTitle(DialogPurpose purpose);

}  // namespace strata::ui
