#pragma once
/// An independent reference for a cascade of `rigid_fluid` pieces between two walls: bars
/// of a material with e = ρ00 + p in compression (c_s = c = 1) that carries no tension,
/// followed event by event in closed form. Written from the laws alone; it shares no code
/// with solvers/ (nor with exact/riemann.hpp: every wave here is a jump).
///
/// With c_s = 1 every characteristic runs at exactly ±1 in the lab, whatever the state, so in
/// each piece the Riemann invariants J± = φ ± Ψ (Ψ = −ln s) are carried unchanged along
/// x ∓ t = const: J+ to the right, J− to the left. The line is an ordered list of points —
/// walls (fixed), jumps (speed ±1) and edges (a free end or a contact of two pieces, moving
/// with the material, v = tanh φ) — and between each two a region: vacuum or a uniform state
/// (J+, J−) of one piece. Points move at constant speed until two of them meet; a meeting (or
/// a cluster of them at one instant and place) is resolved from the states on its two sides:
///
///   wall | matter       φ = 0: Ψ = ∓J (kept on the wall if Ψ ≥ 0, else the end leaves it free)
///   matter | vacuum     free end, p = 0: Ψ = 0, φ = the arriving invariant
///   matter | matter     one material: the star (J+_L, J−_R); Ψ* < 0 cracks it (two free ends)
///   (two bodies)        p* continuous at the contact: Ψ_L(p*) + Ψ_R(p*) = J+_L − J−_R with
///                       Ψ_i(p) = ½ ln(1 + 2p/ρ_i) (p = (ρ/2)(e^{2Ψ} − 1)); < 0 parts them
///
/// Pieces of one body that meet again are one piece (they share the material, so the contact
/// is no interface). Templated on the arithmetic: run in double and long double to see the
/// round-off.

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace rigidity::exact {

struct CascadeBody {
  std::string name;
  double rest_density;
  double position;  ///< lab x of the left end at t = 0
  double length;    ///< natural length (unstrained at t = 0)
  double velocity;
};

template <class Real>
struct CascadePiece {
  int body = 0;
  Real x_left = 0, x_right = 0;
  Real labels = 0;         ///< natural length
  Real velocity_mean = 0;  ///< weighted by labels (rest mass)
  Real momentum = 0, energy = 0;
};

template <class Real>
struct CascadeEvent {
  Real t = 0, x = 0;
  std::string kind;  ///< contact | separation | cavitation | rejoin
  std::vector<int> bodies;
};

template <class Real>
class LightCascade {
 public:
  LightCascade(std::vector<CascadeBody> bodies, double wall_left, double wall_right) : bodies_(std::move(bodies)) {
    points_.push_back({Kind::wall, Real(wall_left), 0, 0});
    regions_.push_back(Region{});
    for (std::size_t b = 0; b < bodies_.size(); ++b) {
      const CascadeBody& body = bodies_[b];
      const Real phi = std::atanh(Real(body.velocity));
      const Real x0 = Real(body.position), x1 = x0 + Real(body.length) / std::cosh(phi);
      points_.push_back({Kind::edge, x0, 0, std::tanh(phi)});
      regions_.push_back(Region{true, static_cast<int>(b), next_piece_++, phi, phi});
      points_.push_back({Kind::edge, x1, 0, std::tanh(phi)});
      regions_.push_back(Region{});
    }
    points_.push_back({Kind::wall, Real(wall_right), 0, 0});
  }

  /// Follow the cascade to t_end (at most max_events meetings).
  void run(Real t_end, long max_events = 1000000) {
    const Real eps = 256 * std::numeric_limits<Real>::epsilon();
    while (events_resolved_ < max_events) {
      Real t_next = t_end;
      std::vector<Real> meet(points_.size() - 1, std::numeric_limits<Real>::infinity());
      for (std::size_t i = 0; i + 1 < points_.size(); ++i) {
        const Point &a = points_[i], &b = points_[i + 1];
        if (a.speed <= b.speed) continue;
        meet[i] = std::max(now_, now_ + (b.at(now_) - a.at(now_)) / (a.speed - b.speed));
        t_next = std::min(t_next, meet[i]);
      }
      if (t_next >= t_end) break;
      now_ = t_next;
      // Clusters: runs of neighbours meeting now; resolved right to left so indices hold.
      for (std::size_t i = points_.size() - 1; i-- > 0;) {
        if (meet[i] > now_ + eps) continue;
        std::size_t first = i;
        while (first > 0 && meet[first - 1] <= now_ + eps) --first;
        resolve(first, i + 1);
        ++events_resolved_;
        i = first;
      }
    }
    now_ = t_end;
  }

  [[nodiscard]] long events_resolved() const { return events_resolved_; }
  [[nodiscard]] const std::vector<CascadeEvent<Real>>& events() const { return events_; }

  /// The pieces at the current time, left to right.
  [[nodiscard]] std::vector<CascadePiece<Real>> pieces() const {
    std::vector<CascadePiece<Real>> out;
    int current = -1;
    for (std::size_t k = 0; k + 1 < points_.size(); ++k) {
      const Region& r = regions_[k];
      if (!r.matter) {
        current = -1;
        continue;
      }
      const Real x0 = points_[k].at(now_), x1 = points_[k + 1].at(now_);
      if (current != r.piece) {
        out.push_back({r.body, x0, x0, 0, 0, 0, 0});
        current = r.piece;
      }
      CascadePiece<Real>& p = out.back();
      const Real phi = (r.jp + r.jm) / 2, psi = (r.jp - r.jm) / 2;
      const Real s = std::exp(-psi), g = std::cosh(phi), rho = Real(bodies_[r.body].rest_density);
      const Real pressure = rho / 2 * (1 / (s * s) - 1), w = rho + 2 * pressure;  // e = ρ + p
      const Real labels = (x1 - x0) * g / s;                                      // dx/dX = s/γ
      p.x_right = x1;
      p.labels += labels;
      p.velocity_mean += labels * std::tanh(phi);
      p.momentum += labels * w * s * std::sinh(phi);
      p.energy += labels * (w * g * g - pressure) * s / g;
    }
    for (CascadePiece<Real>& p : out) p.velocity_mean /= p.labels;
    return out;
  }

 private:
  enum class Kind { wall, jump, edge };
  struct Point {
    Kind kind;
    Real x0, t0, speed;
    [[nodiscard]] Real at(Real t) const { return x0 + speed * (t - t0); }
  };
  struct Region {
    bool matter = false;
    int body = -1, piece = -1;
    Real jp = 0, jm = 0;
    [[nodiscard]] Real phi() const { return (jp + jm) / 2; }
    [[nodiscard]] Real psi() const { return (jp - jm) / 2; }
  };
  static Region state(const Region& like, Real jp, Real jm) {
    Region r = like;
    r.jp = jp;
    r.jm = jm;
    return r;
  }

  void event(Real x, const char* kind, std::vector<int> bodies) {
    events_.push_back({now_, x, kind, std::move(bodies)});
  }

  /// Points first..last (inclusive) meet now: replace them, and the regions between them and
  /// next to them, by the waves of the Riemann problem between the states on either side.
  void resolve(std::size_t first, std::size_t last) {
    Real x = 0;
    bool had_vacuum = false;
    for (std::size_t i = first; i <= last; ++i) {
      x += points_[i].at(now_);
      if (i < last && !regions_[i].matter) had_vacuum = true;
    }
    x /= Real(last - first + 1);
    const bool wall_left = first == 0, wall_right = last + 1 == points_.size();
    if (wall_left && wall_right) throw std::runtime_error("light cascade: the walls met");
    const Region L = wall_left ? Region{} : regions_[first - 1];
    const Region R = wall_right ? Region{} : regions_[last];

    // The new points P and the regions G: G.front() replaces the region left of the cluster
    // (none at a wall), G.back() the one right of it; the rest lie between new points.
    std::vector<Point> P;
    std::vector<Region> G;
    if (!wall_left) G.push_back(L);
    auto add = [&](Kind kind, Real speed, const Region& after) {
      P.push_back({kind, x, now_, speed});
      G.push_back(after);
    };
    // The C− wave into L towards the star `s` (J+ is carried: s.jp == L.jp), or none.
    auto left_wave = [&](const Region& s) {
      if (s.jm != L.jm)
        add(Kind::jump, -1, s);
      else
        G.back() = s;
    };
    auto right_wave = [&](const Region& s) {
      if (s.jp != R.jp)
        add(Kind::jump, 1, R);
      else
        G.back() = s;
    };
    auto free_end = [&](const Region& s) { return std::tanh(s.phi()); };

    if (wall_left || wall_right) {
      const Region& M = wall_left ? R : L;
      if (!M.matter) throw std::runtime_error("light cascade: vacuum at a wall");
      // φ = 0 on the wall: Ψ = −J− (left wall) or J+ (right wall); it carries no tension.
      const Real arriving = wall_left ? M.jm : M.jp;
      const Real psi = wall_left ? -arriving : arriving;
      const bool leaves = psi < 0;
      Region star = leaves ? state(M, arriving, arriving)
                           : (wall_left ? state(M, -arriving, arriving) : state(M, arriving, -arriving));
      if (!leaves && had_vacuum) event(x, "contact", {M.body});
      if (leaves && !had_vacuum) event(x, "separation", {M.body});
      if (wall_left) {
        add(Kind::wall, 0, leaves ? Region{} : star);
        if (leaves) add(Kind::edge, free_end(star), star);
        right_wave(star);
      } else {
        left_wave(star);
        if (leaves) add(Kind::edge, free_end(star), Region{});
        P.push_back({Kind::wall, x, now_, 0});
      }
    } else if (L.matter && !R.matter) {  // a right free end: Ψ = 0
      const Region s = state(L, L.jp, L.jp);
      left_wave(s);
      add(Kind::edge, free_end(s), R);
    } else if (!L.matter && R.matter) {  // a left free end
      const Region s = state(R, R.jm, R.jm);
      add(Kind::edge, free_end(s), s);
      right_wave(s);
    } else if (!L.matter && !R.matter) {
      throw std::runtime_error("light cascade: a piece vanished");
    } else {
      const Real dj = L.jp - R.jm;  // 2Ψ* if one material
      if (dj < 0) {                 // tension: a crack, or two bodies part
        const bool one_piece = L.body == R.body && L.piece == R.piece;
        if (!had_vacuum)
          event(x, one_piece ? "cavitation" : "separation",
                L.body == R.body ? std::vector<int>{L.body} : std::vector<int>{L.body, R.body});
        const Region left = state(L, L.jp, L.jp);
        Region right = state(R, R.jm, R.jm);
        if (one_piece) {
          right.piece = next_piece_++;
          relabel(R.piece, right.piece, last);
        }
        left_wave(left);
        add(Kind::edge, free_end(left), Region{});
        add(Kind::edge, free_end(right), right);
        right_wave(right);
      } else if (L.body == R.body) {  // one material: the star (J+_L, J−_R)
        if (L.piece != R.piece) {
          event(x, "rejoin", {L.body});
          relabel(R.piece, L.piece, last);
        }
        const Region s = state(L, L.jp, R.jm);
        left_wave(s);
        Region r = R;
        r.piece = L.piece;
        if (s.jp != R.jp)
          add(Kind::jump, 1, r);
        else
          G.back() = s;
      } else {  // two bodies in contact: Ψ_L(p) + Ψ_R(p) = dj
        if (had_vacuum) event(x, "contact", {L.body, R.body});
        const Real a = 2 / Real(bodies_[L.body].rest_density), b = 2 / Real(bodies_[R.body].rest_density);
        // (1 + a p)(1 + b p) = e^{2 dj}:  a b p² + (a + b) p − (e^{2 dj} − 1) = 0
        const Real q = std::expm1(2 * dj);
        const Real p = 2 * q / ((a + b) + std::sqrt((a + b) * (a + b) + 4 * a * b * q));
        const Real psi_l = std::log1p(a * p) / 2, psi_r = std::log1p(b * p) / 2;
        const Real phi = (L.jp - psi_l + R.jm + psi_r) / 2;  // both sides' φ*, averaged
        const Region left = state(L, L.jp, phi - psi_l), right = state(R, phi + psi_r, R.jm);
        left_wave(left);
        add(Kind::edge, std::tanh(phi), right);
        right_wave(right);
      }
    }
    // Splice: points first..last become P; regions from (first − 1 or first) to (last or
    // last − 1) become G.
    const std::size_t r0 = wall_left ? first : first - 1, r1 = wall_right ? last - 1 : last;
    if (G.size() + (last - first + 1) != P.size() + (r1 + 1 - r0))
      throw std::runtime_error("light cascade: bad splice");
    points_.erase(points_.begin() + static_cast<long>(first), points_.begin() + static_cast<long>(last) + 1);
    points_.insert(points_.begin() + static_cast<long>(first), P.begin(), P.end());
    regions_.erase(regions_.begin() + static_cast<long>(r0), regions_.begin() + static_cast<long>(r1) + 1);
    regions_.insert(regions_.begin() + static_cast<long>(r0), G.begin(), G.end());
  }

  /// Regions of piece `from` from point index `start` on to the right, up to that piece's end.
  void relabel(int from, int to, std::size_t start) {
    for (std::size_t k = start; k < regions_.size(); ++k) {
      if (!regions_[k].matter || regions_[k].piece != from) break;
      regions_[k].piece = to;
    }
  }

  std::vector<CascadeBody> bodies_;
  std::vector<Point> points_;
  std::vector<Region> regions_;  ///< regions_[k] between points_[k] and points_[k + 1]
  std::vector<CascadeEvent<Real>> events_;
  Real now_ = 0;
  int next_piece_ = 0;
  long events_resolved_ = 0;
};

}  // namespace rigidity::exact
