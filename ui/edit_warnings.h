// What an edit did to the parts that the artist may not have meant, for the log: a cutter that no
// longer reaches the part it cut (moved off it, or the part moved away from its holes: a base
// plate moved alone left its mounting holes behind, cutting nothing), an intersection whose
// parts no longer meet. The tree is plain engine data, no GL; the hook reads the editor's state
// on the UI thread.
#pragma once

#include <string>
#include <vector>

#include "engine/document/node.h"

namespace strata::ui {

struct EditorState;

// The contacts the change from `before` to `after` broke, one sentence each, in tree order of
// `after`: for each visible difference, each visible cutter one of whose parts' world boxes
// overlapped one of its base's in `before`, where none does in `after` ("\"bolt hole\" no longer
// reaches \"body\": it cuts nothing now"; the parts of a union are its children, any other node
// is one part, an array with all its copies); for each visible intersection, where its visible
// children's boxes had a common overlap in `before` and have none now ("\"i\" is empty now: its
// parts no longer meet"). Boxes that do not overlap hold parts that cannot meet, so what is said
// is so; parts whose boxes still overlap may not meet either, and are not judged. Nodes absent
// from `before` (new) are left out.
std::vector<std::string> contactsLost(const NodePtr& before, const NodePtr& after);

// Once a frame on the UI thread: where the document changed since the last settled tree (no drag
// under way), logs contactsLost as warnings. Undo and redo, and a document opened or made new,
// only take the tree as the new settled one.
void warnLostContacts(EditorState& state);

}  // namespace strata::ui
