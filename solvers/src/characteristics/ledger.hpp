// The error ledger of the front tracker: every L1 error it books for its approximations.
#pragma once

#include <cmath>

namespace rigidity::characteristics {

/// Every L1 error the front tracker books for its approximations (in the labels: |δφ| + |δΨ|
/// times natural length; the bound divides by the bodies' natural length), by kind, and where
/// it is now. Some errors stay where they were booked: a weak wave held back at an interface
/// or a contact (defects), droplets kept with their piece. The others travel with the waves they
/// were made on (Node::carried, LightFront::carried): what a merge or a smooth step's
/// approximation makes is handed to the wave that carries it on (the book methods return it),
/// scattering at an interface or an end grows or shrinks it with the waves it splits into, and
/// a wave that ends with no successor leaves it here as lost. So at every instant the waves
/// carry exactly carried() of it: Tracker::validate checks that they do.
class ErrorLedger {
 public:
  /// A smooth step's error (a fan step's, a reconstruction's, a staircase's), made now; for
  /// the wave that carries it on.
  double book_fan(double error) {
    fans_ += error;
    return error;
  }
  /// A merge of fronts; for the merged front.
  double book_merge(double error) {
    merges_ += error;
    return error;
  }
  /// A weak wave held back at an interface or a contact (or a front off its curve): stays.
  void book_defect(double error) { defects_ += error; }
  /// A droplet kept with its piece: stays.
  void book_droplet(double error) { droplets_ += error; }
  /// What a wave held back booked while held, leaving now with the waves that go on; for them.
  double release(double error) {
    released_ += error;
    return error;
  }
  /// Errors `carried` handed on `ratio` times over where a wave splits or waves meet
  /// (scattering grows them above 1, label speeds shrink them below); for the outgoing waves.
  double scale(double carried, double ratio) {
    if (ratio > 1.0) {
      scattered_ += carried * (ratio - 1.0);
    } else {
      shrunk_ += carried * (1.0 - ratio);
    }
    return carried * ratio;
  }
  /// What a wave carried as it ended with no wave to hand it to: it stays in the bound.
  void lose(double carried) { lost_ += carried; }

  /// What the waves alive carry between them.
  [[nodiscard]] double carried() const { return merges_ + fans_ + released_ + scattered_ - shrunk_ - lost_; }
  /// Everything that has gone onto or off the waves: the scale of carried()'s round-off.
  [[nodiscard]] double flow() const { return merges_ + fans_ + released_ + scattered_ + shrunk_ + lost_; }
  /// What the waves alive carry (`carried_alive`, summed over them) with what those that ended
  /// carried: all the errors made on waves, grown and shrunk as they scattered.
  [[nodiscard]] double on_waves(double carried_alive) const { return carried_alive + lost_; }
  /// The error booked up to now: what stays where it was booked, what the waves took
  /// (`on_waves`), and what the smooth steps and jumps alive book at this instant (`alive`).
  [[nodiscard]] double booked(double on_waves, double alive) const {
    return (defects_ - released_) + alive + on_waves + droplets_;
  }

  [[nodiscard]] double fans() const { return fans_; }
  [[nodiscard]] double merges() const { return merges_; }
  [[nodiscard]] double defects() const { return defects_; }
  [[nodiscard]] double droplets() const { return droplets_; }
  [[nodiscard]] double lost() const { return lost_; }
  /// What scattering grew the carried errors by (see ResolutionPolicy::at_droplet).
  [[nodiscard]] double scattered() const { return scattered_; }
  /// Every total finite and non-negative.
  [[nodiscard]] bool sound() const {
    for (const double v : {fans_, merges_, defects_, droplets_, released_, scattered_, shrunk_, lost_})
      if (!(v >= 0.0) || !std::isfinite(v)) return false;
    return true;
  }

 private:
  double fans_ = 0.0, merges_ = 0.0, defects_ = 0.0, droplets_ = 0.0;
  double released_ = 0.0, scattered_ = 0.0, shrunk_ = 0.0, lost_ = 0.0;
};

}  // namespace rigidity::characteristics
