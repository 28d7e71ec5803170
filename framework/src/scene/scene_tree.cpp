#include "scene_tree.hpp"

#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/parser.h>

#include <istream>
#include <map>
#include <streambuf>

namespace rigidity::detail {

// ---- reading ---------------------------------------------------------------------------

namespace {
const SceneTree::Node& node_of(const SceneTree* tree, int index) { return tree->node(index); }
}  // namespace

bool TreeValue::is_null() const { return defined() && node_of(tree_, index_).kind == SceneTree::Kind::null; }
bool TreeValue::is_scalar() const { return defined() && node_of(tree_, index_).kind == SceneTree::Kind::scalar; }
bool TreeValue::is_list() const { return defined() && node_of(tree_, index_).kind == SceneTree::Kind::list; }
bool TreeValue::is_map() const { return defined() && node_of(tree_, index_).kind == SceneTree::Kind::map; }
bool TreeValue::is_plain() const { return is_scalar() && node_of(tree_, index_).plain; }

std::string_view TreeValue::text() const {
  return defined() ? tree_->text(node_of(tree_, index_)) : std::string_view{};
}

const YAML::Mark& TreeValue::mark() const {
  static const YAML::Mark none = YAML::Mark::null_mark();
  return defined() ? node_of(tree_, index_).mark : none;
}

std::size_t TreeValue::size() const {
  if (!defined()) return 0;
  const SceneTree::Node& n = node_of(tree_, index_);
  return n.kind == SceneTree::Kind::list ? n.count : n.kind == SceneTree::Kind::map ? n.count / 2 : 0;
}

TreeValue TreeValue::item(std::size_t i) const { return {tree_, tree_->child(node_of(tree_, index_), i)}; }
TreeValue TreeValue::key(std::size_t entry) const { return {tree_, tree_->child(node_of(tree_, index_), 2 * entry)}; }
TreeValue TreeValue::value(std::size_t entry) const {
  return {tree_, tree_->child(node_of(tree_, index_), 2 * entry + 1)};
}

TreeValue TreeValue::operator[](std::string_view name) const {
  if (!is_map()) return {};
  for (std::size_t e = 0; e < size(); ++e) {
    const TreeValue k = key(e);
    if (k.is_scalar() && k.text() == name) return value(e);
  }
  return {};
}

// ---- building from the parser's events ---------------------------------------------------

/// Receives the parser's events and appends each value to the tree as it comes: a value
/// opens in its parent's list of children (pending until the parent closes, then copied
/// into children_ in one piece).
class TreeBuilder final : public YAML::EventHandler {
 public:
  TreeBuilder(SceneTree& tree, std::size_t max_values, int max_depth)
      : tree_(tree), max_values_(max_values), max_depth_(max_depth) {}

  int documents = 0;

  void OnDocumentStart(const YAML::Mark& mark) override {
    if (++documents == 1) tree_.document_mark_ = mark;
    if (documents == 2) throw TreeLimit{mark, "a scene file holds one YAML document; a second one starts here"};
  }
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark& mark, YAML::anchor_t anchor) override {
    SceneTree::Node n;
    n.mark = mark;
    place(n, anchor);
  }
  void OnAlias(const YAML::Mark& mark, YAML::anchor_t anchor) override {
    count(mark);
    attach(anchors_.at(anchor));  // the parser refuses an alias of an unknown anchor
  }
  void OnScalar(const YAML::Mark& mark, const std::string& tag, YAML::anchor_t anchor,
                const std::string& value) override {
    SceneTree::Node n;
    n.kind = SceneTree::Kind::scalar;
    n.plain = tag == "?" || tag == "tag:yaml.org,2002:float" || tag == "tag:yaml.org,2002:int";
    n.text_begin = static_cast<std::uint32_t>(tree_.text_.size());
    n.text_size = static_cast<std::uint32_t>(value.size());
    tree_.text_ += value;
    n.mark = mark;
    place(n, anchor);
  }
  void OnSequenceStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t anchor,
                       YAML::EmitterStyle::value) override {
    open(SceneTree::Kind::list, mark, anchor);
  }
  void OnSequenceEnd() override { close(); }
  void OnMapStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t anchor,
                  YAML::EmitterStyle::value) override {
    open(SceneTree::Kind::map, mark, anchor);
  }
  void OnMapEnd() override { close(); }

 private:
  void count(const YAML::Mark& mark) {
    if (++values_ > max_values_)
      throw TreeLimit{mark, "too many values: a scene holds at most " + std::to_string(max_values_)};
  }
  int place(const SceneTree::Node& n, YAML::anchor_t anchor) {
    count(n.mark);
    const int index = tree_.add_node(n);
    if (anchor != YAML::NullAnchor) anchors_[anchor] = index;
    attach(index);
    return index;
  }
  void attach(int index) {
    if (depth_ == 0) {
      if (tree_.root_ < 0) tree_.root_ = index;
      return;
    }
    pending_[static_cast<std::size_t>(depth_ - 1)].push_back(index);
  }
  void open(SceneTree::Kind kind, const YAML::Mark& mark, YAML::anchor_t anchor) {
    SceneTree::Node n;
    n.kind = kind;
    n.mark = mark;
    const int index = place(n, anchor);
    if (++depth_ > max_depth_)
      throw TreeLimit{mark, "nesting deeper than " + std::to_string(max_depth_) + " levels: not a scene"};
    if (pending_.size() < static_cast<std::size_t>(depth_)) pending_.emplace_back();
    pending_[static_cast<std::size_t>(depth_ - 1)].clear();
    open_.push_back(index);
  }
  void close() {
    std::vector<int>& items = pending_[static_cast<std::size_t>(depth_ - 1)];
    SceneTree::Node& n = tree_.nodes_[static_cast<std::size_t>(open_.back())];
    n.first = static_cast<std::uint32_t>(tree_.children_.size());
    n.count = static_cast<std::uint32_t>(items.size());
    tree_.children_.insert(tree_.children_.end(), items.begin(), items.end());
    open_.pop_back();
    --depth_;
  }

  SceneTree& tree_;
  std::size_t max_values_;
  int max_depth_;
  std::size_t values_ = 0;
  int depth_ = 0;
  std::vector<std::vector<int>> pending_;  ///< children of each open container, by depth
  std::vector<int> open_;                  ///< the open containers
  std::map<YAML::anchor_t, int> anchors_;
};

namespace {
/// Reads a text in place: the parser takes a stream, and a scene of megabytes need not be
/// copied into one.
class ViewBuffer final : public std::streambuf {
 public:
  explicit ViewBuffer(std::string_view text) {
    char* begin = const_cast<char*>(text.data());  // read only: the get area is never written
    setg(begin, begin, begin + text.size());
  }
};
}  // namespace

SceneTree SceneTree::parse(std::string_view text, std::size_t max_values, int max_depth) {
  SceneTree tree;
  tree.text_.reserve(text.size() / 2);
  ViewBuffer view(text);
  std::istream stream(&view);
  YAML::Parser parser(stream);
  TreeBuilder builder(tree, max_values, max_depth);
  while (parser.HandleNextDocument(builder)) {
  }
  if (tree.root_ < 0) tree.root_ = tree.add_node(Node{});  // no document: a null value
  // Capacity grown by doubling is up to half unused: give it back before the values are
  // checked (the checked values are the larger part of what loading holds).
  tree.nodes_.shrink_to_fit();
  tree.children_.shrink_to_fit();
  tree.text_.shrink_to_fit();
  return tree;
}

TreeValue SceneTree::empty_map() {
  static const SceneTree tree = [] {
    SceneTree t;
    t.root_ = t.add_map();
    return t;
  }();
  return tree.root();
}

// ---- changes ---------------------------------------------------------------------------

static_assert(sizeof(SceneTree::Node) <= 32,
              "a value of the tree stays 32 bytes: a scene of 10^6 values fits in 32 MB");

int SceneTree::add_node(Node n) {
  nodes_.push_back(n);
  return static_cast<int>(nodes_.size()) - 1;
}

int SceneTree::add_map() {
  Node n;
  n.kind = Kind::map;
  return add_node(n);
}

int SceneTree::add_list() {
  Node n;
  n.kind = Kind::list;
  return add_node(n);
}

int SceneTree::graft(const SceneTree& other, int from) {
  // Aliases make the other tree a graph; each of its values is copied once.
  std::map<int, int> copied;
  const auto copy = [&](const auto& self, int index) -> int {
    if (const auto it = copied.find(index); it != copied.end()) return it->second;
    Node n = other.node(index);
    if (n.kind == Kind::scalar) {
      const std::string_view t = other.text(n);
      n.text_begin = static_cast<std::uint32_t>(text_.size());
      text_ += t;
    }
    const int here = add_node(n);
    copied[index] = here;
    std::vector<int> children;
    for (std::uint32_t k = 0; k < n.count; ++k) children.push_back(self(self, other.children_[n.first + k]));
    nodes_[static_cast<std::size_t>(here)].first = static_cast<std::uint32_t>(children_.size());
    children_.insert(children_.end(), children.begin(), children.end());
    return here;
  };
  return copy(copy, from);
}

void SceneTree::set_item(int list, std::size_t i, int value) {
  children_[nodes_[static_cast<std::size_t>(list)].first + i] = value;
}

void SceneTree::set_value(int map, std::size_t entry, int value) {
  children_[nodes_[static_cast<std::size_t>(map)].first + 2 * entry + 1] = value;
}

void SceneTree::add_entry(int map, std::string_view key, int value) {
  Node k;
  k.kind = Kind::scalar;
  k.plain = true;
  k.text_begin = static_cast<std::uint32_t>(text_.size());
  k.text_size = static_cast<std::uint32_t>(key.size());
  text_ += key;
  const int key_index = add_node(k);
  // The map's children move to the end, where there is room for one more entry.
  Node& m = nodes_[static_cast<std::size_t>(map)];
  const std::vector<int> old(children_.begin() + m.first, children_.begin() + m.first + m.count);
  m.first = static_cast<std::uint32_t>(children_.size());
  children_.insert(children_.end(), old.begin(), old.end());
  children_.push_back(key_index);
  children_.push_back(value);
  m.count += 2;
}

void SceneTree::set_items(int list, const std::vector<int>& items) {
  Node& n = nodes_[static_cast<std::size_t>(list)];
  n.first = static_cast<std::uint32_t>(children_.size());
  n.count = static_cast<std::uint32_t>(items.size());
  children_.insert(children_.end(), items.begin(), items.end());
}

void SceneTree::null_to_map(int index) {
  Node& n = nodes_[static_cast<std::size_t>(index)];
  n.kind = Kind::map;
  n.count = 0;
}

}  // namespace rigidity::detail
