#pragma once
/// Typed errors of rigidity and the exit status each maps to (SPEC §4).
///
///   InputError        exit 2  the scene (or a command-line argument) is invalid
///   InadmissibleError exit 3  the scene is valid but has no classical solution
///   NumericalError    exit 1  a numerical method failed (never reported as a number)
///
/// A run that stops early writes its outputs up to the time it reached, with status
/// `stopped` (a budget: exit 1) or `interrupted` (Ctrl-C: exit 130, as a shell
/// reports a command ended by SIGINT).

#include <stdexcept>
#include <string>

namespace rigidity {

/// Where something stands in an input file; line and column are 1-based, 0 if unknown.
struct SourceLocation {
  std::string file;
  int line = 0;
  int column = 0;

  /// "FILE:LINE:COL" (or "FILE" when line is unknown).
  [[nodiscard]] std::string str() const;
};

/// An invalid input. what() is the full diagnostic "FILE:LINE:COL: error: key 'k': message".
class InputError : public std::runtime_error {
 public:
  InputError(SourceLocation where, std::string key, std::string message);
  [[nodiscard]] const SourceLocation& where() const noexcept { return where_; }
  [[nodiscard]] const std::string& key() const noexcept { return key_; }
  [[nodiscard]] const std::string& message() const noexcept { return message_; }

 private:
  SourceLocation where_;
  std::string key_;
  std::string message_;
};

/// A physically inadmissible situation (e.g. a `hooke` impact at v >= V).
class InadmissibleError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A numerical method that did not deliver (a root find that did not converge, ...).
class NumericalError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Exit status of the command line for each error kind.
inline constexpr int kExitOk = 0;
inline constexpr int kExitInternal = 1;
inline constexpr int kExitInvalidInput = 2;
inline constexpr int kExitInadmissible = 3;
inline constexpr int kExitStopped = 1;        ///< a budget reached; outputs up to the time reached
inline constexpr int kExitInterrupted = 130;  ///< Ctrl-C; outputs up to the time reached
inline constexpr int kExitTerminated = 143;   ///< SIGTERM (kill, timeout, a batch time limit); likewise

}  // namespace rigidity
