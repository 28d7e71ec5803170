#include "scene_text.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>

namespace rigidity::detail {

std::string format_number(double v) {
  if (v == 0.0) return "0";  // also -0
  std::array<char, 64> buffer{};
  const auto [end, ec] = std::to_chars(buffer.data(), buffer.data() + buffer.size(), v);
  if (ec != std::errc()) return "nan";
  // "1e+08" → "1e8", "1e-07" → "1e-7": shorter, and still exactly v.
  std::string text(buffer.data(), end);
  const std::size_t e = text.find('e');
  if (e == std::string::npos) return text;
  std::string exponent = text.substr(e + 1);
  const bool negative = exponent.front() == '-';
  if (exponent.front() == '+' || negative) exponent.erase(0, 1);
  exponent.erase(0, std::min(exponent.find_first_not_of('0'), exponent.size() - 1));
  return text.substr(0, e + 1) + (negative ? "-" : "") + exponent;
}

namespace {

bool is_digit(char c) { return c >= '0' && c <= '9'; }

/// Length of a run of digits starting at i.
std::size_t digits(std::string_view s, std::size_t i) {
  std::size_t n = 0;
  while (i + n < s.size() && is_digit(s[i + n])) ++n;
  return n;
}

bool is_non_finite_word(std::string_view s) {
  if (!s.empty() && (s[0] == '+' || s[0] == '-')) s.remove_prefix(1);
  if (!s.empty() && s[0] == '.') s.remove_prefix(1);
  std::string lower;
  for (char c : s) lower += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return lower == "inf" || lower == "infinity" || lower == "nan";
}

}  // namespace

NumberLiteral parse_number(std::string_view text) {
  if (is_non_finite_word(text)) return {NumberSyntax::non_finite, 0.0};
  // [-+]? ( \. [0-9]+ | [0-9]+ ( \. [0-9]* )? ) ( [eE] [-+]? [0-9]+ )?
  std::size_t i = 0;
  if (i < text.size() && (text[i] == '+' || text[i] == '-')) ++i;
  const std::size_t mantissa_start = i;
  const std::size_t integer_digits = digits(text, i);
  i += integer_digits;
  std::size_t fraction_digits = 0;
  if (i < text.size() && text[i] == '.') {
    ++i;
    fraction_digits = digits(text, i);
    i += fraction_digits;
  }
  if (integer_digits == 0 && fraction_digits == 0) return {};
  if (i < text.size() && (text[i] == 'e' || text[i] == 'E')) {
    ++i;
    if (i < text.size() && (text[i] == '+' || text[i] == '-')) ++i;
    const std::size_t exponent_digits = digits(text, i);
    if (exponent_digits == 0) return {};
    i += exponent_digits;
  }
  if (i != text.size()) return {};

  double value = 0.0;
  const char* first = text.data() + mantissa_start;
  const auto [end, ec] = std::from_chars(first, text.data() + text.size(), value);
  if (ec == std::errc::result_out_of_range) {
    // Overflow is not finite; underflow (1e-400) reads as zero, as a physicist expects.
    const std::size_t e = text.find_first_of("eE");
    const bool negative_exponent = e != std::string_view::npos && e + 1 < text.size() && text[e + 1] == '-';
    if (!negative_exponent) return {NumberSyntax::non_finite, 0.0};
    value = 0.0;
  } else if (ec != std::errc() || end != text.data() + text.size()) {
    return {};
  }
  if (!std::isfinite(value)) return {NumberSyntax::non_finite, 0.0};
  return {NumberSyntax::finite, text[0] == '-' ? -value : value};
}

int parse_boolean(std::string_view text) {
  if (text == "true" || text == "True" || text == "TRUE") return 1;
  if (text == "false" || text == "False" || text == "FALSE") return 0;
  return -1;
}

bool needs_quotes(std::string_view text) {
  if (text.empty() || std::isspace(static_cast<unsigned char>(text.front())) ||
      std::isspace(static_cast<unsigned char>(text.back())))
    return true;
  static constexpr std::string_view kLookAlikes[] = {
      "~",  "null", "Null", "NULL", "y",   "Y",   "n",   "N",    "yes",  "Yes",  "YES",   "no",    "No",
      "NO", "on",   "On",   "ON",   "off", "Off", "OFF", "true", "True", "TRUE", "false", "False", "FALSE"};
  for (std::string_view w : kLookAlikes)
    if (text == w) return true;
  return parse_number(text).syntax != NumberSyntax::invalid;
}

std::string quoted(std::string_view text) {
  constexpr std::size_t kLongest = 60;
  std::string shown;
  for (char c : text.substr(0, kLongest)) {
    const auto u = static_cast<unsigned char>(c);
    if (u < 0x20 || u == 0x7f) {
      static constexpr char kHex[] = "0123456789abcdef";
      shown += "\\x";
      shown += kHex[u >> 4];
      shown += kHex[u & 0xf];
    } else {
      shown += c;
    }
  }
  if (text.size() > kLongest) shown += "...";
  return "'" + shown + "'";
}

std::string join(const std::vector<std::string>& words, std::string_view separator) {
  std::string out;
  for (const std::string& w : words) {
    if (!out.empty()) out += separator;
    out += w;
  }
  return out;
}

}  // namespace rigidity::detail
