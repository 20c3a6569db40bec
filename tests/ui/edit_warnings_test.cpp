// What an edit did that the artist may not have meant (ui/edit_warnings.h): a cutter moved off
// the part it cut, a part moved away from its holes, an intersection whose parts no longer meet.
#include "ui/edit_warnings.h"

#include <gtest/gtest.h>

#include "engine/document/commands.h"
#include "tests/support/scene_builder.h"
#include "ui/editor_actions.h"
#include "ui/editor_state.h"

namespace strata::ui {
namespace {

using test::box;
using test::cylinder;
using test::op;
using test::sphere;

NodePtr withName(const NodePtr& node, const std::string& name) {
  auto named = std::make_shared<Node>(*node);
  named->name = name;
  return named;
}

NodePtr moved(const NodePtr& root, NodeId id, glm::dvec3 by) {
  return editNode(root, id, [&](Node& n) { n.transform.translate += by; });
}

// A plate with a hole through it: the hole moved off the plate cuts nothing, said once, naming
// both; moved within it, or back onto it, nothing is said.
TEST(ContactsLost, ACutterMovedOffItsBaseIsSaid) {
  const NodePtr plate = withName(box({40.0, 20.0, 4.0}), "plate");
  const NodePtr hole = withName(cylinder(2.0, 10.0), "hole");
  const NodePtr root = op(NodeKind::Difference, {plate, hole});
  const NodePtr away = moved(root, hole->id, {100.0, 0.0, 0.0});
  EXPECT_EQ(contactsLost(root, away),
            std::vector<std::string>{
                "\"hole\" no longer reaches \"plate\": it cuts nothing now (Ctrl+Z undoes the "
                "change)"});
  EXPECT_TRUE(contactsLost(root, moved(root, hole->id, {15.0, 5.0, 0.0})).empty());
  EXPECT_TRUE(contactsLost(away, root).empty());  // back onto it
  // The plate moved away from its hole: the same.
  EXPECT_EQ(contactsLost(root, moved(root, plate->id, {0.0, 0.0, 50.0})).size(), 1u);
  // Touching only (a face in common) takes nothing away: said too.
  EXPECT_EQ(contactsLost(root, moved(root, hole->id, {22.0, 0.0, 0.0})).size(), 1u);
}

// Judged part by part through unions: a hole through a plate that is joined with a far block
// (the union's box spans the hole's new place) is said once the plate moves away from it.
TEST(ContactsLost, TheBaseIsJudgedByItsPartsNotByItsUnionsBox) {
  const NodePtr plate = box({40.0, 20.0, 4.0});
  const NodePtr block = box({10.0, 10.0, 10.0}, {100.0, 0.0, 0.0});
  const NodePtr hole = cylinder(2.0, 10.0, {60.0, 0.0, 0.0});
  const NodePtr plateAt60 = moved(op(NodeKind::Union, {plate, block}), plate->id, {60.0, 0, 0});
  const NodePtr root = op(NodeKind::Difference, {plateAt60, hole});
  const NodePtr back = moved(root, plate->id, {-60.0, 0.0, 0.0});
  EXPECT_EQ(contactsLost(root, back).size(), 1u);
}

// An intersection whose parts are moved apart is empty: said. New parts, hidden cutters and
// hidden bases are not judged.
TEST(ContactsLost, AnIntersectionMovedApartIsSaidAndNewOrHiddenPartsAreNot) {
  const NodePtr a = sphere(5.0), b = sphere(5.0, {6.0, 0.0, 0.0});
  const NodePtr both = withName(op(NodeKind::Intersection, {a, b}), "lens");
  const std::vector<std::string> said = contactsLost(both, moved(both, b->id, {20.0, 0.0, 0.0}));
  ASSERT_EQ(said.size(), 1u);
  EXPECT_EQ(said[0].rfind("\"lens\" is empty now", 0), 0u) << said[0];

  const NodePtr plate = box({40.0, 20.0, 4.0});
  const NodePtr hole = cylinder(2.0, 10.0);
  const NodePtr root = op(NodeKind::Difference, {plate, hole});
  const NodePtr hidden = editNode(root, hole->id, [](Node& n) { n.visible = false; });
  EXPECT_TRUE(contactsLost(hidden, moved(hidden, hole->id, {100.0, 0.0, 0.0})).empty());
  const NodePtr fresh = cylinder(2.0, 10.0, {100.0, 0.0, 0.0});
  const NodePtr added = editNode(root, root->id, [&](Node& n) { n.children.push_back(fresh); });
  EXPECT_TRUE(contactsLost(root, added).empty());
}

// In the editor: said once when the edit settles, not while a drag is under way, and not for an
// undo that takes the cutter off again.
TEST(ContactsLost, TheEditorSaysItOnceAnEditSettlesAndNotForUndo) {
  EditorState state;
  const NodePtr plateNode = box({40.0, 20.0, 4.0});
  const NodePtr holeNode = cylinder(2.0, 10.0);
  Scene scene = state.document.scene();
  scene.root = op(NodeKind::Difference, {plateNode, holeNode});
  state.document = Document(scene);
  const NodeId hole = holeNode->id;
  warnLostContacts(state);  // the settled tree
  const auto warnings = [&] {
    size_t n = 0;
    for (const LogLine& line : state.log)
      n += line.level == LogLevel::Warning &&
           line.text.find("no longer reaches") != std::string::npos;
    return n;
  };
  Transform far = findNode(state.document.root(), hole)->transform;
  far.translate.x += 1000.0;
  state.document.beginInteraction();
  state.document.setTransform(hole, far);
  warnLostContacts(state);
  EXPECT_EQ(warnings(), 0u) << "not during a drag";
  state.document.endInteraction();
  warnLostContacts(state);
  EXPECT_EQ(warnings(), 1u);
  warnLostContacts(state);
  EXPECT_EQ(warnings(), 1u) << "once";
  undo(state);
  warnLostContacts(state);
  redo(state);
  warnLostContacts(state);
  EXPECT_EQ(warnings(), 1u) << "undo and redo are not judged";
}

}  // namespace
}  // namespace strata::ui
