#pragma once
/// Status values for numerical kernels: hot loops return these, never throw, and
/// never hand back an unconverged iterate as if it were an answer.

#include <string_view>

namespace rigidity {

enum class Status {
  ok,
  out_of_range,   ///< the requested value lies outside what the material can reach
  no_bracket,     ///< a root could not be bracketed
  not_converged,  ///< an iteration stopped before meeting its tolerance
};

[[nodiscard]] constexpr std::string_view to_string(Status s) {
  switch (s) {
    case Status::ok: return "ok";
    case Status::out_of_range: return "out of range";
    case Status::no_bracket: return "no bracket";
    case Status::not_converged: return "not converged";
  }
  return "unknown";
}

/// A value with the status of the computation that produced it; value is meaningful only if ok().
template <class T>
struct Solved {
  T value{};
  Status status = Status::ok;
  [[nodiscard]] constexpr bool ok() const { return status == Status::ok; }
  [[nodiscard]] static constexpr Solved failure(Status s) { return Solved{T{}, s}; }
};

}  // namespace rigidity
