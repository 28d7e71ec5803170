// The scene loader's YAML tree (framework/src/scene/scene_tree.hpp): one value per value of
// the text, marks where the values are, aliases shared, the guards, and the changes --set
// overrides make. The loader's behaviour on whole scenes is checked in the other scene tests.
#include "../../framework/src/scene/scene_tree.hpp"

#include <gtest/gtest.h>

#include <string>

namespace rigidity::detail {
namespace {

TEST(SceneTree, HoldsEachValueOnceWithItsMark) {
  std::string text = "segments:\n";
  for (int i = 0; i < 1000; ++i) text += "  - {length: 1, velocity: \"0.5\", stretch: ~}\n";
  const SceneTree tree = SceneTree::parse(text, 100000, 64);
  const TreeValue root = tree.root();
  ASSERT_TRUE(root.is_map());
  ASSERT_EQ(root.size(), 1u);
  const TreeValue segments = root["segments"];
  ASSERT_TRUE(segments.is_list());
  ASSERT_EQ(segments.size(), 1000u);
  const TreeValue last = segments.item(999);
  ASSERT_TRUE(last.is_map());
  EXPECT_EQ(last.size(), 3u);
  EXPECT_EQ(last["length"].text(), "1");
  EXPECT_TRUE(last["length"].is_plain());
  EXPECT_EQ(last["velocity"].text(), "0.5");
  EXPECT_FALSE(last["velocity"].is_plain()) << "quoted text is a string, not a number";
  EXPECT_TRUE(last["stretch"].is_null());
  EXPECT_FALSE(last["material"].defined());
  // Marks count from 0: the last segment is on the 1001st line, its "velocity" in the 17th
  // column and its value in the 27th.
  EXPECT_EQ(last.key(1).mark().line, 1000);
  EXPECT_EQ(last.key(1).mark().column, 16);
  EXPECT_EQ(last["velocity"].mark().column, 26);
}

TEST(SceneTree, AnAliasIsTheValueItNames) {
  const SceneTree tree = SceneTree::parse("a: &shared {x: 1}\nb: *shared\n", 100, 64);
  EXPECT_EQ(tree.root()["a"].index(), tree.root()["b"].index());
  EXPECT_EQ(tree.root()["b"]["x"].text(), "1");
}

TEST(SceneTree, RefusesWhatIsNotASceneAtTheValueThatCrossesTheLine) {
  std::string deep = "a: ";
  for (int i = 0; i < 70; ++i) deep += "[";
  try {
    (void)SceneTree::parse(deep, 1000, 64);
    FAIL() << "nesting deeper than the limit was accepted";
  } catch (const TreeLimit& e) {
    EXPECT_EQ(e.mark.line, 0);  // on the line of the brackets (the parser reads ahead of the one it reports)
    EXPECT_GT(e.mark.column, 3);
    EXPECT_NE(e.message.find("nesting deeper than 64"), std::string::npos);
  }
  EXPECT_THROW((void)SceneTree::parse("[1, 2, 3, 4]", 4, 64), TreeLimit);  // five values with the list
  EXPECT_NO_THROW((void)SceneTree::parse("[1, 2, 3, 4]", 5, 64));
  try {
    (void)SceneTree::parse("a: 1\n---\nb: 2\n", 100, 64);
    FAIL() << "a second document was accepted";
  } catch (const TreeLimit& e) {
    EXPECT_EQ(e.mark.line, 1);
  }
  EXPECT_TRUE(SceneTree::parse("", 100, 64).root().is_null());
}

TEST(SceneTree, OverridesChangeTheTreeInPlace) {
  SceneTree tree = SceneTree::parse("time: {end: 2}\nlist: [1, 2, 3]\nempty:\n", 100, 64);
  const SceneTree value = SceneTree::parse("{end: 5, start: 1}", 100, 64);
  const int grafted = tree.graft(value, value.root().index());
  tree.set_value(tree.root().index(), 0, grafted);
  EXPECT_EQ(tree.root()["time"]["end"].text(), "5");
  EXPECT_EQ(tree.root()["time"]["start"].text(), "1");
  const TreeValue list = tree.root()["list"];
  tree.set_items(list.index(), {list.item(2).index(), list.item(0).index()});
  ASSERT_EQ(tree.root()["list"].size(), 2u);
  EXPECT_EQ(tree.root()["list"].item(0).text(), "3");
  const int empty = tree.root()["empty"].index();
  tree.null_to_map(empty);
  tree.add_entry(empty, "new", tree.graft(value, value.root().index()));
  EXPECT_EQ(tree.root()["empty"]["new"]["start"].text(), "1");
  EXPECT_FALSE(tree.root()["empty"].key(0).mark().line >= 0) << "a key the file does not have has no mark";
  tree.add_entry(tree.root().index(), "added", tree.add_map());
  EXPECT_EQ(tree.root().size(), 4u);
  EXPECT_EQ(tree.root()["time"]["end"].text(), "5") << "entries keep their values when the map grows";
}

}  // namespace
}  // namespace rigidity::detail
