#pragma once
/// Typed errors of rigidity and the exit status each maps to (docs/cli.md).
///
///   InputError        exit 2  the scene (or a command-line argument) is invalid
///   InadmissibleError exit 3  the scene is valid but has no classical solution
///   NumericalError    exit 1  a numerical method failed (never reported as a number)
///
/// A run that stops early writes its outputs up to the time it reached, with status
/// `stopped` (a budget: exit 1), `interrupted` (Ctrl-C: exit 130, as a shell
/// reports a command ended by SIGINT) or `inadmissible` (a state with no classical
/// solution met during the run, e.g. a material crushed to zero length: exit 3).

#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

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

/// Where and how a run met a state with no classical solution, in natural units (NaN where
/// not known): the Riemann problem of two sides (or a side and a wall) whose solution would
/// take a material out of its admissible range.
struct Inadmissibility {
  static constexpr double kUnknown = std::numeric_limits<double>::quiet_NaN();
  double t = kUnknown, x = kUnknown;  ///< the interaction's place
  double relative_speed = kUnknown;   ///< |speed| of the left side relative to the right (or the wall) [c]
  double psi_needed = kUnknown;       ///< the Ψ the limiting side would need
  double psi_limit = kUnknown;        ///< its material's limit: Ψ_max (crushed), Ψ_min (in_tension)
  bool in_tension = false;            ///< pulled out of its range, not crushed
  std::string material;               ///< the limiting material's model

  /// At time t and place x, nothing else known.
  [[nodiscard]] static Inadmissibility at(double t, double x = kUnknown) {
    Inadmissibility where;
    where.t = t;
    where.x = x;
    return where;
  }

  /// How far beyond its limit the material would be taken, in Ψ (>= 0; NaN if not known).
  [[nodiscard]] double margin() const { return in_tension ? psi_limit - psi_needed : psi_needed - psi_limit; }
};

/// A physically inadmissible situation (e.g. a `hooke` impact at v >= V).
class InadmissibleError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
  InadmissibleError(const std::string& what, Inadmissibility where)
      : std::runtime_error(what), where_(std::move(where)) {}
  /// Where a run met it, if it was met during a run (not found from the scene alone).
  [[nodiscard]] const std::optional<Inadmissibility>& where() const noexcept { return where_; }

 private:
  std::optional<Inadmissibility> where_;
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
