#pragma once
// A scene's YAML as the loader reads it: one compact tree, built in the single pass
// yaml-cpp's parser makes over the text (its event API), with the guards against hostile
// input applied as the values arrive, and the mark (line, column) of every value for error
// messages. A value is 32 bytes and its text lives in one buffer, so a scene of 10⁵
// segments costs tens of megabytes, not hundreds. Internal to the scene loader.

#include <yaml-cpp/mark.h>

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace rigidity::detail {

class SceneTree;

/// One value of a SceneTree, or none (the value of a key a map does not have).
class TreeValue {
 public:
  TreeValue() = default;
  TreeValue(const SceneTree* tree, int index) : tree_(tree), index_(index) {}

  [[nodiscard]] bool defined() const { return tree_ != nullptr && index_ >= 0; }
  [[nodiscard]] bool is_null() const;
  [[nodiscard]] bool is_scalar() const;
  [[nodiscard]] bool is_list() const;
  [[nodiscard]] bool is_map() const;
  /// A plain scalar, or one tagged !!int or !!float: what may be a number or a boolean
  /// (quoted text is a string).
  [[nodiscard]] bool is_plain() const;
  /// The text of a scalar.
  [[nodiscard]] std::string_view text() const;
  [[nodiscard]] const YAML::Mark& mark() const;
  /// Items of a list, entries of a map, else 0.
  [[nodiscard]] std::size_t size() const;
  [[nodiscard]] TreeValue item(std::size_t i) const;
  [[nodiscard]] TreeValue key(std::size_t entry) const;
  [[nodiscard]] TreeValue value(std::size_t entry) const;
  /// The value of the first entry whose key is `name`, or none.
  [[nodiscard]] TreeValue operator[](std::string_view name) const;
  [[nodiscard]] int index() const { return index_; }

 private:
  const SceneTree* tree_ = nullptr;
  int index_ = -1;
};

class SceneTree {
 public:
  enum class Kind : std::uint8_t { null, scalar, list, map };
  struct Node {
    Kind kind = Kind::null;
    bool plain = false;
    std::uint32_t text_begin = 0, text_size = 0;  ///< a scalar's text in text_
    std::uint32_t first = 0, count = 0;           ///< children_[first, first + count): items, or key, value pairs
    YAML::Mark mark = YAML::Mark::null_mark();
  };

  /// The tree of `text`, a YAML text of at most one document (none: a null root). Guards:
  /// at most max_values values (aliases counted once) and max_depth levels of nesting, one
  /// document. \throws TreeLimit past a guard; YAML::Exception on a syntax error
  static SceneTree parse(std::string_view text, std::size_t max_values, int max_depth);

  /// An empty map: the value of an absent map key whose own defaults apply.
  static TreeValue empty_map();

  [[nodiscard]] TreeValue root() const { return {this, root_}; }
  /// Where the document starts (null if there is none).
  [[nodiscard]] const YAML::Mark& document_mark() const { return document_mark_; }
  [[nodiscard]] TreeValue at(int index) const { return {this, index}; }
  [[nodiscard]] const Node& node(int index) const { return nodes_[static_cast<std::size_t>(index)]; }
  [[nodiscard]] std::string_view text(const Node& n) const { return {text_.data() + n.text_begin, n.text_size}; }
  [[nodiscard]] int child(const Node& n, std::size_t k) const { return children_[n.first + k]; }

  // ---- changes, for --set overrides ----
  /// Copies the value `from` of another tree into this one; returns its index here.
  int graft(const SceneTree& other, int from);
  int add_map();
  int add_list();
  /// Replaces item i of a list, or the value of entry i of a map, by `value`.
  void set_item(int list, std::size_t i, int value);
  void set_value(int map, std::size_t entry, int value);
  /// Appends the entry key: value to a map (the key has no mark: it is not in the file).
  void add_entry(int map, std::string_view key, int value);
  /// Replaces the items of a list.
  void set_items(int list, const std::vector<int>& items);
  /// Makes a null value an empty map, in place (every reference to it sees the map).
  void null_to_map(int index);

 private:
  friend class TreeBuilder;
  int add_node(Node n);
  std::vector<Node> nodes_;
  std::string text_;
  std::vector<int> children_;
  int root_ = -1;
  YAML::Mark document_mark_ = YAML::Mark::null_mark();
};

/// A guard of SceneTree::parse was passed: where, and which.
struct TreeLimit {
  YAML::Mark mark;
  std::string message;
};

}  // namespace rigidity::detail
