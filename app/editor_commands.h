// The subcommands that open a window: the editor and headless renders of its viewport. Each
// returns the process exit code (0 success, 1 failure with a message).
#pragma once

#include <string>
#include <vector>

namespace strata {

// `strata`, `strata SCENE.strata.json`, `strata edit [SCENE] [--backend B] [--threads N]
// [--screenshot FILE --width W --height H]`: opens the editor on the scene (the demo scene when
// none is given). Without a display (or in a build without the editor) it says so and evaluates
// the scene on the command line instead, as `strata eval` does.
int runEdit(const std::vector<std::string>& args);

// `strata render SCENE -o shot.png [--width W] [--height H] [--resolution N] [--view V]
// [--ortho] [--section AXIS[:AT][:flip]]`: the editor's viewport of the whole scene, rendered
// headless through EGL (an invisible window where EGL is missing) and written as PNG.
// V: iso (default), front, back, right, left, top, bottom.
int runRender(const std::vector<std::string>& args);

// True when `arg` names a scene file (ends in .json), so `strata FILE` opens it in the editor.
bool looksLikeScenePath(const std::string& arg);

}  // namespace strata
