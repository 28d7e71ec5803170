// The front tracker's resolution policy: its thresholds set from the scene, and the rules that
// steer them at droplets and cracks.
#include "policy.hpp"

#include <algorithm>
#include <cmath>

namespace rigidity::characteristics {

ResolutionPolicy::ResolutionPolicy(const Scene& scene)
    : finest_(scene.solver.wave_resolution()), bodies_(static_cast<double>(scene.bodies.size())) {
  // The threshold of weak waves: each interface or contact holding back a wave weaker than
  // `weak_` adds at most weak_ × (the speeds of the waves on its two sides, ~1) per unit time
  // to the L1 error; over the time light takes to cross the bodies' natural length, for every
  // such place, that is about half the tolerance's budget. The thresholds do not depend on
  // time.end, so that the work per unit time does not either: a run much longer than that
  // crossing time reports a bound that grows with it.
  int places = 0;
  for (const BodyDecl& b : scene.bodies) {
    total_length_ += b.natural_length();
    for (std::size_t k = 1; k < b.segments.size(); ++k)
      places += b.segments[k].material != b.segments[k - 1].material ? 1 : 0;
  }
  places += static_cast<int>(scene.bodies.size()) - 1;
  places_ = std::max(1, places);
  droplet_scale_.assign(scene.bodies.size(), 1.0);
  set_resolution(finest_);
  piece_cap_ = std::clamp(kPiecesPerBody / finest_, kMinPiecesPerBody, kMaxPiecesPerBody);
}

void ResolutionPolicy::set_resolution(double r) {
  // Merges and the reflections of merging fronts come more often the finer the resolution
  // (as fan steps, their number grows as 1/resolution): what each may cost falls as its
  // square, so that their sum falls with the resolution.
  resolution_ = r;
  coarsest_resolution_ = std::max(coarsest_resolution_, r);
  merge_base_ = kMergeFraction * r * r * total_length_;
  merge_ = std::max(merge_, merge_base_);
  merge_light_ = std::max(merge_light_, merge_base_);
  weak_merging_ = 0.5 * r * r;
  weak_ = 0.5 * r / places_;
  fan_step_ = fan_step_for(r);
  widest_fan_step_ = std::max(widest_fan_step_, fan_step_);
  front_cap_ = std::max(kMinFrontsPerBody, kFrontsPerBody / r);  // per body
}

double ResolutionPolicy::fan_steps(double span, double speed_outer, double speed_star) const {
  const double least = std::min<double>(kMinFanSteps, std::floor(span / (2.0 * resolution_)));
  const double by_speed = std::ceil(std::abs(speed_star - speed_outer) /
                                    (kMaxSpeedStep * std::max(std::abs(speed_outer), std::abs(speed_star))));
  return std::max({std::floor(span / fan_step_), least, by_speed});
}

void ResolutionPolicy::at_droplet(const ErrorLedger& ledger) {
  double r = ledger.merges() + ledger.fans() < kDropletBalance * (ledger.droplets() + ledger.scattered())
                 ? std::min(kCoarsestResolution, kResolutionStep * resolution_)
                 : resolution_ / kResolutionStep;
  r = std::max(r, finest_);
  if (r != resolution_) set_resolution(r);
}

void ResolutionPolicy::at_crack(int body, int pieces) {
  const double max_scale = kWidestDroplet / (piece_cap_ * resolution_);
  double& scale = droplet_scale_[body];
  if (pieces > piece_cap_) {
    scale = std::min(scale * kDropletSteering, std::max(1.0, max_scale));
  } else if (scale > 1.0 && pieces < kDropletRelease * piece_cap_) {
    scale = std::max(1.0, scale / kDropletSteering);
  }
}

}  // namespace rigidity::characteristics
