#include "rigidity/json_writer.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <stdexcept>

#include "rigidity/errors.hpp"

namespace rigidity {

JsonWriter::JsonWriter(std::string document) : document_(std::move(document)) {}

JsonWriter& JsonWriter::begin_object(JsonLayout layout) {
  begin_container(false, layout);
  return *this;
}
JsonWriter& JsonWriter::end_object() {
  end_container(false);
  return *this;
}
JsonWriter& JsonWriter::begin_array(JsonLayout layout) {
  begin_container(true, layout);
  return *this;
}
JsonWriter& JsonWriter::end_array() {
  end_container(true);
  return *this;
}

JsonWriter& JsonWriter::key(std::string_view name) {
  if (scopes_.empty() || scopes_.back().is_array || key_pending_)
    throw std::logic_error(document_ + ": a key is only allowed for the next member of an object");
  Scope& scope = scopes_.back();
  if (scope.count > 0) out_ += ',';
  if (scope.on_one_line) {
    if (scope.count > 0) out_ += ' ';
  } else {
    newline_and_indent(scopes_.size());
  }
  ++scope.count;
  scope.key.assign(name);
  append_json_string(out_, name);
  out_ += ": ";
  key_pending_ = true;
  return *this;
}

JsonWriter& JsonWriter::text(std::string_view value) {
  begin_value();
  append_json_string(out_, value);
  return *this;
}

JsonWriter& JsonWriter::number(double value) {
  if (!std::isfinite(value)) {
    const char* what = std::isnan(value) ? "nan" : (value > 0 ? "inf" : "-inf");
    throw NumericalError(document_ + ": " + path() + " is " + what + " (no NaN or inf is ever written)");
  }
  begin_value();
  append_shortest(out_, value);
  return *this;
}

JsonWriter& JsonWriter::integer(long long value) {
  begin_value();
  std::array<char, 24> buffer{};
  const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
  out_.append(buffer.data(), result.ptr);
  return *this;
}

JsonWriter& JsonWriter::boolean(bool value) {
  begin_value();
  out_ += value ? "true" : "false";
  return *this;
}

JsonWriter& JsonWriter::null() {
  begin_value();
  out_ += "null";
  return *this;
}

std::string JsonWriter::take() {
  if (!scopes_.empty() || key_pending_ || out_.empty())
    throw std::logic_error(document_ + ": JSON document taken before it was complete");
  out_ += '\n';
  return std::move(out_);
}

// Writes what separates this value from the previous one: nothing after a key,
// ", " within a one-line array, ",\n  " within a block array.
void JsonWriter::begin_value() {
  if (key_pending_) {
    key_pending_ = false;
    return;
  }
  if (scopes_.empty()) {
    if (!out_.empty()) throw std::logic_error(document_ + ": a JSON document holds a single value");
    return;
  }
  Scope& scope = scopes_.back();
  if (!scope.is_array) throw std::logic_error(document_ + ": an object member needs a key");
  if (scope.count > 0) out_ += scope.on_one_line ? ", " : ",";
  if (!scope.on_one_line) newline_and_indent(scopes_.size());
  ++scope.count;
}

void JsonWriter::begin_container(bool is_array, JsonLayout layout) {
  begin_value();
  const bool inside_one_line = !scopes_.empty() && scopes_.back().on_one_line;
  scopes_.push_back(Scope{is_array, inside_one_line || layout == JsonLayout::line, 0, {}});
  out_ += is_array ? '[' : '{';
}

void JsonWriter::end_container(bool is_array) {
  if (scopes_.empty() || scopes_.back().is_array != is_array || key_pending_)
    throw std::logic_error(document_ + ": unbalanced JSON " + (is_array ? "array" : "object"));
  const Scope scope = scopes_.back();
  scopes_.pop_back();
  if (scope.count > 0 && !scope.on_one_line) newline_and_indent(scopes_.size());
  out_ += is_array ? ']' : '}';
}

void JsonWriter::newline_and_indent(std::size_t depth) {
  out_ += '\n';
  out_.append(2 * depth, ' ');
}

// Where the next value goes, as "bodies[0].energy".
std::string JsonWriter::path() const {
  std::string out;
  for (std::size_t i = 0; i < scopes_.size(); ++i) {
    const Scope& scope = scopes_[i];
    if (scope.is_array) {
      // Enclosing arrays have counted the element being written; the innermost not yet.
      const long index = i + 1 < scopes_.size() ? scope.count - 1 : scope.count;
      out += '[' + std::to_string(index) + ']';
    } else if (scope.count > 0) {
      if (!out.empty()) out += '.';
      out += scope.key;
    }
  }
  return out.empty() ? std::string("the document") : out;
}

void append_json_string(std::string& out, std::string_view value) {
  static constexpr char kHex[] = "0123456789abcdef";
  out += '"';
  for (const char c : value) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\b': out += "\\b"; break;
      case '\f': out += "\\f"; break;
      case '\n': out += "\\n"; break;
      case '\r': out += "\\r"; break;
      case '\t': out += "\\t"; break;
      default: {
        const auto byte = static_cast<unsigned char>(c);
        if (byte < 0x20) {
          out += "\\u00";
          out += kHex[byte >> 4];
          out += kHex[byte & 0xF];
        } else {
          out += c;
        }
      }
    }
  }
  out += '"';
}

void append_shortest(std::string& out, double value) {
  if (value == 0.0) value = 0.0;  // -0 is written as 0
  std::array<char, 32> buffer{};  // the longest shortest form, "-2.2250738585072014e-308", has 24
  const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
  out.append(buffer.data(), result.ptr);
}

}  // namespace rigidity
