#pragma once
/// A minimal JSON writer for rigidity's outputs (summary.json, `rigidity materials
/// --json`). It writes valid JSON or throws: strings are escaped, numbers are written
/// in the shortest form that reads back to the same double, and a NaN or inf is a
/// NumericalError naming the document and the path of the value ("summary.json:
/// bodies[0].energy is nan").
///
///   JsonWriter json("summary.json");
///   json.begin_object();
///   json.key("t_end").number(1.5);
///   json.key("bodies").begin_array(JsonLayout::line).text("bar").end_array();
///   json.end_object();
///   std::string text = json.take();

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace rigidity {

/// block: one member per line, indented; line: the whole container on one line.
enum class JsonLayout { block, line };

class JsonWriter {
 public:
  /// `document` names the output in error messages.
  explicit JsonWriter(std::string document);

  JsonWriter& begin_object(JsonLayout layout = JsonLayout::block);
  JsonWriter& end_object();
  JsonWriter& begin_array(JsonLayout layout = JsonLayout::block);
  JsonWriter& end_array();

  /// The key of the next member. \pre inside an object, no key pending
  JsonWriter& key(std::string_view name);

  JsonWriter& text(std::string_view value);
  /// \throws NumericalError if value is not finite
  JsonWriter& number(double value);
  JsonWriter& integer(long long value);
  JsonWriter& boolean(bool value);
  JsonWriter& null();

  /// The document, ending in a newline. \pre every container closed
  [[nodiscard]] std::string take();

 private:
  struct Scope {
    bool is_array = false;
    bool on_one_line = false;
    long count = 0;
    std::string key;  ///< the current member's key (objects)
  };
  void begin_value();
  void begin_container(bool is_array, JsonLayout layout);
  void end_container(bool is_array);
  void newline_and_indent(std::size_t depth);
  [[nodiscard]] std::string path() const;

  std::string document_;
  std::string out_;
  std::vector<Scope> scopes_;
  bool key_pending_ = false;
};

/// Appends `value` as a JSON string literal (quotes included, escaped).
void append_json_string(std::string& out, std::string_view value);

/// Appends the shortest decimal form of `value` that reads back exactly (std::to_chars);
/// -0 is written as 0. \pre value is finite
void append_shortest(std::string& out, double value);

}  // namespace rigidity
