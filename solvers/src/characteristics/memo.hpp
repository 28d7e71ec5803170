#pragma once
// The material functions a crossing in a linearly degenerate body needs, remembered.
//
// In a linearly degenerate body the Riemann invariants are carried by the fronts, never
// made: a crossing's star state takes J+ from its left and J− from its right, so a bar
// ringing between its ends visits the same few states again and again. The Ψ of a stretch,
// the stretch of a Ψ and the characteristic speeds of a state are pure functions, so a small
// direct-mapped table of the last values asked for returns bit for bit what the material
// would compute, without its logarithms, square roots and exponentials.
#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "rigidity/material.hpp"
#include "rigidity/solvers/riemann.hpp"

namespace rigidity::characteristics {

class MaterialMemo {
 public:
  /// Tables of `slots` entries each (a power of two): a scene of a few segments visits few
  /// states, and clearing a thousand slots would cost it more than its whole solve.
  explicit MaterialMemo(std::size_t slots) : mask_(slots - 1), psi_(slots), stretch_(slots), speeds_(slots) {}

  /// m.riemann_psi(s)
  double psi(const Material& m, Stretch s) {
    PsiSlot& slot = psi_[index(&m, s.log(), 0.0, 0)];
    if (slot.material != &m || slot.log_s != s.log()) slot = PsiSlot{&m, s.log(), m.riemann_psi(s)};
    return slot.psi;
  }

  /// m.stretch_at_psi(psi)
  Solved<Stretch> stretch_at_psi(const Material& m, double psi) {
    StretchSlot& slot = stretch_[index(&m, psi, 1.0, 1)];
    if (slot.material != &m || slot.psi != psi) slot = StretchSlot{&m, psi, m.stretch_at_psi(psi)};
    return slot.stretch;
  }

  /// Ψ at the stretch where m parts (its cavitation pressure); not ok if it has none there.
  Solved<double> parting_psi(const Material& m) {
    PartingSlot& slot = parting_[(reinterpret_cast<std::uintptr_t>(&m) >> 4) & (kPartingSlots - 1)];
    if (slot.material != &m) {
      const Solved<Stretch> parting = m.stretch_at_pressure(m.cavitation_pressure());
      slot = PartingSlot{&m, parting.ok() ? Solved<double>{m.riemann_psi(parting.value), Status::ok}
                                          : Solved<double>::failure(parting.status)};
    }
    return slot.psi;
  }

  /// characteristic_speeds(m, state, family)
  FrontSpeeds speeds(const Material& m, const State& state, int family) {
    SpeedSlot& slot = speeds_[index(&m, state.rapidity, state.stretch.log(), family)];
    if (slot.material != &m || slot.family != family || slot.rapidity != state.rapidity ||
        slot.log_s != state.stretch.log()) {
      slot = SpeedSlot{&m, family, state.rapidity, state.stretch.log(), characteristic_speeds(m, state, family)};
    }
    return slot.speeds;
  }

 private:
  struct PsiSlot {
    const Material* material = nullptr;
    double log_s = 0.0, psi = 0.0;
  };
  struct StretchSlot {
    const Material* material = nullptr;
    double psi = 0.0;
    Solved<Stretch> stretch{Stretch{}, Status::ok};
  };
  struct SpeedSlot {
    const Material* material = nullptr;
    int family = 0;
    double rapidity = 0.0, log_s = 0.0;
    FrontSpeeds speeds{};
  };

  static constexpr std::size_t kPartingSlots = 8;
  struct PartingSlot {
    const Material* material = nullptr;
    Solved<double> psi{0.0, Status::ok};
  };

  [[nodiscard]] std::size_t index(const Material* m, double a, double b, int family) const {
    std::uint64_t h = std::bit_cast<std::uint64_t>(a) * 0x9E3779B97F4A7C15ULL;
    h ^= std::bit_cast<std::uint64_t>(b) * 0xC2B2AE3D27D4EB4FULL;
    h ^= reinterpret_cast<std::uintptr_t>(m) * 0x165667B19E3779F9ULL;
    h += static_cast<std::uint64_t>(family + 1);
    h ^= h >> 29;
    return static_cast<std::size_t>(h) & mask_;
  }

  std::size_t mask_;
  std::vector<PsiSlot> psi_;
  std::vector<StretchSlot> stretch_;
  std::vector<SpeedSlot> speeds_;
  std::array<PartingSlot, kPartingSlots> parting_{};
};

}  // namespace rigidity::characteristics
