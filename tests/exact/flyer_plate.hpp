#pragma once
/// The symmetric flyer-plate impact of a light-speed material (`rigid`, `rigid_fluid`) in
/// closed form: when and where the two release waves meet inside the target, which is where
/// the rigid fluid spalls (docs/materials.md: it carries no tension).
///
/// A flyer of natural length l_f at velocity +v, its left end at x_f, and a target of natural
/// length l_t at −v, its left end at x_t > x_f + l_f/γ, both unstrained at t = 0. Every front
/// of these materials moves at ±1 in the lab (c_s = 1: λ± = (v ± 1)/(1 ± v) = ±1). The
/// collision stops both at the contact (the star state of a symmetric impact is at rest), so
/// the contact point stays where the bodies met:
///
///   contact   t_c = (x_t − x_f − l_f/γ)/(2v),  x_c = x_t − v t_c
///   flyer     the front runs left from (t_c, x_c) at −1 and meets the rear x_f + v t at
///             t_1 = (x_c + t_c − x_f)/(1 + v); the release (flyer unstrained at −v) runs
///             right at +1 and reaches the contact at t_2 = t_1 + x_c − (x_f + v t_1), then
///             crosses into the target unchanged (the star of that meeting is again
///             unstrained at −v, at p = 0);
///   target    the front runs right at +1 and meets the rear x_t + l_t/γ − v t at
///             t_3 = (x_t + l_t/γ − x_c + t_c)/(1 + v); the release (target unstrained at
///             +v) runs left at −1;
///   meeting   x_c + (t − t_2) = x_r − (t − t_3), x_r = x_t + l_t/γ − v t_3:
///             t_s = (x_r − x_c + t_2 + t_3)/2.
///
/// Valid while the flyer's release enters the target before the target's release reaches
/// the contact (`valid`).

#include <cmath>

namespace rigidity::exact {

struct FlyerPlateMeeting {
  double t_contact = 0.0;
  double x_contact = 0.0;
  double t_meet = 0.0;  ///< the release waves meet: the target goes into tension here
  double x_meet = 0.0;
  bool valid = false;
};

inline FlyerPlateMeeting symmetric_flyer_plate(double x_f, double l_f, double x_t, double l_t, double v) {
  const double inverse_gamma = std::sqrt((1.0 - v) * (1.0 + v));
  FlyerPlateMeeting out;
  out.t_contact = (x_t - x_f - l_f * inverse_gamma) / (2.0 * v);
  out.x_contact = x_t - v * out.t_contact;
  const double t1 = (out.x_contact + out.t_contact - x_f) / (1.0 + v);
  const double t2 = t1 + out.x_contact - (x_f + v * t1);
  const double rear_t = x_t + l_t * inverse_gamma;
  const double t3 = (rear_t - out.x_contact + out.t_contact) / (1.0 + v);
  const double x_r = rear_t - v * t3;
  out.t_meet = 0.5 * (x_r - out.x_contact + t2 + t3);
  out.x_meet = out.x_contact + (out.t_meet - t2);
  // The flyer's release must enter the target before the target's release reaches the contact.
  out.valid = t2 < t3 + (x_r - out.x_contact) && out.x_meet > out.x_contact && out.x_meet < x_r;
  return out;
}

}  // namespace rigidity::exact
