// Choosing a file: zenity or kdialog when installed (a child process read by a helper thread,
// so the editor keeps drawing; the tool is looked for at the first open()), otherwise a built-in
// ImGui browser: the folder's listing (folders, then the files the dialog takes: scenes, or the
// mesh formats it reads or writes), a path field, Up, double-click to enter or choose.
//
// Threads: the UI thread; the helper thread only waits for the child process and its output,
// in state it shares (not the dialog object), then wakes the UI (glfwPostEmptyEvent). A dialog
// destroyed while the child runs kills it.
#pragma once

#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace strata::ui {

enum class DialogPurpose { Open, SaveAs, Export, ImportMesh };

// What the built-in browser's path field means: a name alone lies in `folder`; a file saved
// whose name does not end in one of `accepted` (extensions without the dot: "stl") gets
// `extension` (the suggested name's, as ".stl"; none when empty); a file saved must go into a
// folder that exists and not be a folder, a file opened must be an existing file. `error` says
// why not (and `path` is then empty); `missingFolder`, where a file saved names a folder that
// does not exist, is that folder (the dialog offers to create it).
struct ResolvedPath {
  std::string path;
  std::string error;
  std::string missingFolder;
};
ResolvedPath resolveDialogPath(const std::string& field, const std::string& folder, bool saving,
                               const std::string& extension,
                               const std::vector<std::string>& accepted);

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

 private:
  // What the helper thread shares with the dialog: the child's pid and, once it exited, its
  // output.
  struct External {
    std::mutex mutex;
    int pid = 0;
    bool done = false;
    std::string output;
  };
  void startExternal(const std::string& command);

  std::string tool_;  // "zenity", "kdialog" or "built-in"; "" until the first open()
  bool forcedBuiltIn_ = false;
  bool open_ = false;
  DialogPurpose purpose_ = DialogPurpose::Open;
  char field_[1024] = {};
  bool justOpened_ = false;
  bool focusField_ = false;         // the path field takes the keyboard on the next frame
  bool selectAll_ = true;           // ... with its text selected (not after a refusal)
  std::string suggestedExtension_;  // ".stl": given to a name saved without one
  std::string replacing_;           // an existing file the user was asked about replacing
  std::string chosen_;
  bool hasChosen_ = false;
  std::shared_ptr<External> external_;  // of the running native dialog

  // The built-in browser's folder and listing.
  struct Entry {
    std::string name;
    bool folder = false;
  };
  std::string folderOf(const std::string& suggestion) const;
  void listFolder(const std::string& folder);
  std::vector<std::string> acceptedExtensions() const;
  std::string folder_;
  std::vector<Entry> entries_;
  std::string listError_;
  std::string missingFolder_;  // named by the last path refused for it (ResolvedPath)
};

// "Open scene", "Save scene as", ... for titles and labels.
const char* dialogTitle(DialogPurpose purpose);

}  // namespace strata::ui
