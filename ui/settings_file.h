// The editor's settings files ($XDG_CONFIG_HOME/strata/layout.txt, export.txt, import.txt): one
// "name value" line a setting, read and written here for all of them. A file that is missing or
// damaged reads as no lines; each reader keeps its defaults for what it does not find.
//
// Threads: the UI thread (any thread; no state).
#pragma once

#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace strata::ui {

// Calls visit(name, value) for each line of `path` that has a name, a space and a value (the
// rest of the line, spaces included).
void readSettingLines(
    const std::string& path,
    const std::function<void(const std::string& name, const std::string& value)>& visit);

// A setting's value as a finite number; false where it is not one.
bool settingNumber(const std::string& value, double* out);

// Writes `lines` (name, value) atomically, creating the folder; a value holding a line break is
// left out (it could not be read back as one line). Throws strata::Error.
void writeSettingLines(const std::string& path,
                       const std::vector<std::pair<std::string, std::string>>& lines);

}  // namespace strata::ui
