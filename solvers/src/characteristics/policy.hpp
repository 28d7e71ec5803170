#pragma once
// The front tracker's resolution policy: the thresholds that set how finely it resolves waves
// and droplets, and the rules that steer them as it runs. The tracker asks them; the
// mechanics that use them (merges, fans, cracks, light pieces) are the tracker's.
#include <algorithm>
#include <cmath>
#include <vector>

#include "ledger.hpp"
#include "rigidity/scene.hpp"

namespace rigidity::characteristics {

/// How finely the front tracker resolves its waves and droplets. Every threshold follows one
/// resolution: the tolerance, unless the droplets of a spray have booked more than it
/// (at_droplet). Two controllers steer on top of it: what a merge may cost, by the live fronts
/// (after_interaction), and the droplet length of each body, by its pieces (at_crack).
class ResolutionPolicy {
 public:
  /// A rarefaction fan is split into steps of this many √tolerance in Ψ. The samples
  /// reconstruct the fan linearly between its steps (Tracker::reconstruct), which misses it by
  /// its curvature, second order in the step: an L1 error of about δ² per unit length for
  /// steps δ (measured on the crossed fan of bench/second_order.py: error ≈ 1.2 δ² at t = 3),
  /// which the bound books at about twice that: steps of 0.7 √tolerance put the bound of a
  /// scene of fans near the tolerance.
  static constexpr double kFanStepPerRootTolerance = 0.7;
  /// The widest fan step, in Ψ, and the most the fan's characteristic speed (in the labels) may
  /// change across one of its steps, relative to itself: the reconstruction's error is second
  /// order in the step while the speeds change little across one (a few percent); coarser steps
  /// meet shocks and each other as the jumps they are, at first order (measured on the random
  /// gas-bar scenes of the bound tests, and on a Murnaghan bar whose sound is ten times slower).
  static constexpr double kMaxFanStep = 0.02;
  static constexpr double kMaxSpeedStep = 0.04;
  /// A fan is split into at least this many steps where steps of 2 × the resolution would make
  /// as many: a line through fewer steps reconstructs little of it, and a shock that overtakes a
  /// fan of one or two steps is displaced by the whole fan at once.
  static constexpr int kMinFanSteps = 4;
  /// A merge of two neighbouring fronts may cost at most this fraction of the resolution's L1
  /// budget (resolution × natural length of all bodies): thousands of merges fit in it.
  static constexpr double kMergeFraction = 1.0;
  /// Live fronts per body beyond which merges may cost more (see after_interaction):
  /// kFrontsPerBody / resolution, at least kMinFrontsPerBody. At the cap the bound grows as
  /// 1/fronts and the work as fronts².
  static constexpr double kFrontsPerBody = 0.25;
  static constexpr double kMinFrontsPerBody = 100.0;
  /// While the live fronts exceed their cap, what a merge may cost grows by this factor per
  /// interaction; once they are below kMergeRelease × the cap it falls back by as much. Merges
  /// then hold the fronts near the cap at the least cost that does it.
  static constexpr double kMergeSteering = 1.002;
  static constexpr double kMergeRelease = 0.9;
  /// The most a merge may cost, as a multiple of its cost while fronts are few.
  static constexpr double kMergeCeiling = 1e4;
  /// Fronts of light pieces cost O(1) per crossing time each, not O(fronts): they have a cap
  /// of their own, this many times the others', and merges steered by it.
  static constexpr double kLightCap = 10.0;
  /// Pieces per body beyond which droplets grow (see at_crack): kPiecesPerBody / tolerance, at
  /// least kMinPiecesPerBody and at most kMaxPiecesPerBody. A spray's error does not fall with
  /// the tolerance (see kDropletBalance), so a finer one buys it no more pieces, only work: at
  /// 10⁻⁶, 20 000 pieces a body let random scenes with a spray crack 1–3 million times in
  /// 20 s to reach t ≈ 1–3 of 10; 100 let them end in 0.4–5.4 s, their bounds as chaotic.
  static constexpr double kPiecesPerBody = 0.02;
  static constexpr double kMinPiecesPerBody = 8.0;
  static constexpr double kMaxPiecesPerBody = 100.0;
  /// While a body's pieces exceed their cap, its droplet scale grows by this factor per crack;
  /// once they are below kDropletRelease × the cap it falls back by as much, never below 1. It
  /// grows to at most kWidestDroplet / (the cap × the resolution) (or 1, if that is less): a
  /// droplet is then at most that fraction of the length the body's pieces would each have at
  /// the cap.
  static constexpr double kDropletSteering = 1.02;
  static constexpr double kDropletRelease = 0.5;
  static constexpr double kWidestDroplet = 0.5;
  /// A spray's waves may book up to this multiple of what its droplets book before their
  /// resolution stops coarsening, by kResolutionStep per droplet (see at_droplet). The
  /// droplets' error does not fall as the resolution is refined (random seed 141: 0.049 at 0.01,
  /// 0.070 at 0.001), so waves resolved far below it buy little.
  static constexpr double kDropletBalance = 3.0;
  /// The coarsest a spray may make the resolution of waves and droplets (see at_droplet).
  static constexpr double kCoarsestResolution = 0.005;
  static constexpr double kResolutionStep = 1.1;

  /// The width in Ψ of a fan step at `resolution`.
  [[nodiscard]] static double fan_step_for(double resolution) {
    return std::min(kMaxFanStep, kFanStepPerRootTolerance * std::sqrt(resolution));
  }

  /// The thresholds of the scene's tolerance, for its bodies and the interfaces and contacts
  /// between and within them.
  explicit ResolutionPolicy(const Scene& scene);

  // ---- what the tracker asks ----------------------------------------------------------------
  /// The strength |ΔJ| below which an interface or contact emits no wave.
  [[nodiscard]] double weak_wave() const { return weak_; }
  /// The strength below which two fronts of one family merging emit no reflection.
  [[nodiscard]] double weak_merging() const { return weak_merging_; }
  /// The width in Ψ of the steps of a new rarefaction fan.
  [[nodiscard]] double fan_step() const { return fan_step_; }
  /// The steps a new fan of `span` in Ψ is split into, its family's characteristic speed (in
  /// the labels) going from `speed_outer` to `speed_star`: steps of fan_step(), at least
  /// kMinFanSteps where steps of 2 × the resolution would make as many, and enough that the
  /// speed changes by at most kMaxSpeedStep of itself across one. In double: span / tolerance
  /// overflows an int for tolerances of 1e-11.
  [[nodiscard]] double fan_steps(double span, double speed_outer, double speed_star) const;
  /// The largest L1 error (strength × distance) a merge of fronts on the node list may make now.
  [[nodiscard]] double merge_limit() const { return merge_; }
  /// The same for a merge of fronts of a light piece.
  [[nodiscard]] double light_merge_limit() const { return merge_light_; }
  /// Live fronts per body beyond which merges may cost more.
  [[nodiscard]] double front_cap() const { return front_cap_; }
  /// The label distance from a free end of `body` (of natural length `natural_length`) within
  /// which a crack would leave a droplet: the resolution × the body's droplet scale × its length.
  [[nodiscard]] double droplet_limit(int body, double natural_length) const {
    return resolution_ * droplet_scale_[body] * natural_length;
  }

  // ---- the controllers ----------------------------------------------------------------------
  /// After each interaction, with the live fronts (`live_fronts` in all, `light_fronts` of them
  /// in light pieces, which `light_bodies` bodies are): a solution that grows rough (a pulse
  /// scattered by many contacts into more and more waves) cannot be held to a fixed L1 error by
  /// a bounded number of fronts. Work is bounded first: while more fronts live than front_cap()
  /// per body, the cost a merge may have grows by kMergeSteering per interaction, and falls
  /// back towards its cost while fronts are few once they are fewer than kMergeRelease × the
  /// cap. Fronts of light pieces are held to their own cap (kLightCap). The bound reports what
  /// it cost.
  void after_interaction(long live_fronts, long light_fronts, double light_bodies) {
    steer(merge_, static_cast<double>(live_fronts - light_fronts), (bodies_ - light_bodies) * front_cap_);
    steer(merge_light_, static_cast<double>(light_fronts), kLightCap * light_bodies * front_cap_);
  }
  /// At each droplet, with the errors booked so far: a spray's droplets (a chaotic sequence of
  /// collisions that knock pieces off) book an error that does not fall with the tolerance,
  /// while resolving the waves around them to the tolerance costs ~1/tolerance² per crossing.
  /// While the waves have booked (merges and fan steps) less than kDropletBalance × what the
  /// droplets have, the resolution of waves and droplets coarsens by kResolutionStep (no
  /// coarser than kCoarsestResolution); once they have booked more, it refines by as much (no
  /// finer than the tolerance). The waves' share of the bound then follows the droplets'. What
  /// the splits of waves have grown the carried errors by (ErrorLedger::scattered: most of it at
  /// the cracks a spray's waves set off, each displacing waves far stronger than itself) counts
  /// with the droplets, as error already committed that a finer resolution of the waves to come
  /// does not take back. It grows with what the waves made too, so where the spray's scattering
  /// grows errors by more than a third the resolution goes to its coarsest: a switch more than
  /// a balance.
  void at_droplet(const ErrorLedger& ledger);
  /// At each crack inside a piece of `body`, which has `pieces` pieces: a spray that keeps more
  /// pieces than its cap alive (kPiecesPerBody / tolerance within its bounds; each collision
  /// of unequal rigid-fluid pieces knocks a new one off) is held to that many by letting the
  /// body's droplet length grow (see kDropletSteering); it falls back once the pieces are
  /// fewer. The bound reports what it cost.
  void at_crack(int body, int pieces);

  // ---- what the run reports ---------------------------------------------------------------
  /// The coarsest resolution the run took (wave_resolution): the tolerance, unless a spray
  /// coarsened it.
  [[nodiscard]] double coarsest_resolution() const { return coarsest_resolution_; }
  /// The widest fan step the run took (fan_step_max).
  [[nodiscard]] double widest_fan_step() const { return widest_fan_step_; }

 private:
  /// Sets every threshold that follows the resolution.
  void set_resolution(double r);
  /// Steers what a merge may cost by the fronts it holds against their cap.
  void steer(double& merge, double fronts, double cap) const {
    if (fronts > cap) {
      merge = std::min(merge * kMergeSteering, kMergeCeiling * merge_base_);
    } else if (merge > merge_base_ && fronts < kMergeRelease * cap) {
      merge = std::max(merge_base_, merge / kMergeSteering);
    }
  }

  double finest_ = 0.0;        ///< the resolution the scene asks for (SolverDecl::wave_resolution)
  double bodies_ = 0.0;        ///< bodies of the scene
  double total_length_ = 0.0;  ///< natural length of all bodies
  int places_ = 1;             ///< interfaces and contacts among which weak_ shares its budget
  double resolution_ = 0.0;
  double coarsest_resolution_ = 0.0;
  double weak_ = 0.0, weak_merging_ = 0.0;
  double fan_step_ = 0.0, widest_fan_step_ = 0.0;
  double merge_base_ = 0.0;   ///< largest L1 error (strength × distance) of a merge while fronts are few
  double merge_ = 0.0;        ///< the same now: raised while the live fronts exceed front_cap_
  double merge_light_ = 0.0;  ///< the same for light pieces
  double front_cap_ = 0.0;    ///< per body
  double piece_cap_ = 0.0;    ///< per body
  /// Per body: the droplet length as a multiple of the resolution × its natural length.
  std::vector<double> droplet_scale_;
};

}  // namespace rigidity::characteristics
