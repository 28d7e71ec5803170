#include "rigidity/errors.hpp"

namespace rigidity {

std::string SourceLocation::str() const {
  std::string out = file.empty() ? std::string("<input>") : file;
  if (line > 0) {
    out.append(1, ':').append(std::to_string(line));
    if (column > 0) out.append(1, ':').append(std::to_string(column));
  }
  return out;
}

namespace {
std::string format_input_error(const SourceLocation& where, const std::string& key, const std::string& message) {
  std::string out = where.str() + ": error: ";
  if (!key.empty()) out += "key '" + key + "': ";
  return out + message;
}
}  // namespace

InputError::InputError(SourceLocation where, std::string key, std::string message)
    : std::runtime_error(format_input_error(where, key, message)),
      where_(std::move(where)),
      key_(std::move(key)),
      message_(std::move(message)) {}

}  // namespace rigidity
