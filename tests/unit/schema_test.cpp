// The scene schema (engine/scene/schema): `loom schema` prints every key; the schema is a consistent tree.
#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>
#include <string>

#include "engine/scene/schema.hpp"

namespace loom {

TEST(PrintSchema, ListsEveryKeyWithTypeAndDefault) {
  std::ostringstream os;
  print_schema(os, false);
  const std::string s = os.str();
  ASSERT_FALSE(scene_schema().empty());
  for (const KeySpec& k : scene_schema()) {
    // The key's block starts a line: "path\n    type: ...\n    default: ...".
    const std::string head = k.path + "\n    type: ";
    std::size_t p = 0;
    if (s.compare(0, head.size(), head) != 0) {
      const auto found = s.find("\n" + head);
      ASSERT_NE(found, std::string::npos) << k.path;
      p = found + 1;
    }
    const std::string block = s.substr(p, s.find('\n', s.find("default:", p)) - p);
    if (k.required) {
      EXPECT_NE(block.find(k.unless.empty() ? "(required)" : "(required unless " + k.unless + ")"), std::string::npos) << block;
    } else if (!k.default_value.empty()) {
      EXPECT_NE(block.find("default: " + k.default_value), std::string::npos) << block;
    }
  }
}

TEST(PrintSchema, MarkdownTableHasOneRowPerKey) {
  std::ostringstream os;
  print_schema(os, true);
  const std::string s = os.str();
  for (const KeySpec& k : scene_schema()) EXPECT_NE(s.find("\n| `" + k.path + "` |"), std::string::npos) << k.path;
  // One line per key after the header and separator, each with four cells: a '|' inside a cell must be
  // escaped ("\\|"), or the row would split.
  std::istringstream in(s);
  int rows = 0;
  for (std::string line; std::getline(in, line); ++rows) {
    int bars = 0;
    for (std::size_t i = 0; i < line.size(); ++i) bars += line[i] == '|' && (i == 0 || line[i - 1] != '\\');
    EXPECT_EQ(bars, 5) << line;
  }
  EXPECT_EQ(rows, int(scene_schema().size()) + 2);
}

TEST(SceneSchema, EveryKeyHangsUnderADeclaredTable) {
  for (const KeySpec& k : scene_schema()) {
    const auto dot = k.path.rfind('.');
    if (dot == std::string::npos) continue;
    std::string parent = k.path.substr(0, dot);
    const bool entry = parent.size() > 2 && parent.compare(parent.size() - 2, 2, "[]") == 0;
    if (entry) parent.resize(parent.size() - 2);
    const KeySpec* p = find_key_spec(parent);
    ASSERT_NE(p, nullptr) << k.path;
    EXPECT_EQ(p->kind, entry ? ValueKind::table_array : ValueKind::table) << k.path;
  }
}

TEST(SceneSchema, KeysAreUniqueAndFindable) {
  for (const KeySpec& k : scene_schema()) {
    EXPECT_EQ(find_key_spec(k.path), &k) << k.path;
    EXPECT_FALSE(k.doc.empty()) << k.path;
  }
  EXPECT_EQ(find_key_spec("time.no_such_key"), nullptr);
}

TEST(SceneSchema, ChoiceDefaultsAreAmongTheChoices) {
  for (const KeySpec& k : scene_schema())
    if (k.kind == ValueKind::choice && !k.default_value.empty()) {
      EXPECT_NE(std::find(k.choices.begin(), k.choices.end(), k.default_value), k.choices.end()) << k.path;
    }
}

TEST(KeySpec, RangeText) {
  KeySpec k;
  EXPECT_EQ(k.range_text(), "");
  EXPECT_EQ(KeySpec(k).above(0).range_text(), "> 0");
  EXPECT_EQ(KeySpec(k).at_least(1).range_text(), ">= 1");
  EXPECT_EQ(KeySpec(k).above(-1).below(0.5).range_text(), "in (-1, 0.5)");
  EXPECT_EQ(KeySpec(k).at_least(0).at_most(0.45).range_text(), "in [0, 0.45]");
}

}  // namespace loom
