#pragma once
// Helpers shared by the scene loader's tests.

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "rigidity/scene.hpp"
#include "rigidity/scene_loader.hpp"

namespace rigidity::test {

/// |a − b| <= rel·|b|
inline ::testing::AssertionResult close_relative(double a, double b, double rel = 1.0e-15) {
  if (std::abs(a - b) <= rel * std::abs(b)) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << a << " differs from " << b << " by " << std::abs(a - b) / std::abs(b)
                                       << " (relative), more than " << rel;
}

/// Loads text as a scene, failing the test (with the loader's message) if it is refused.
inline Scene load_ok(const std::string& text, const std::vector<std::string>& overrides = {}) {
  try {
    return load_scene_string(text, "<test>", overrides);
  } catch (const InputError& e) {
    ADD_FAILURE() << "refused: " << e.what() << "\n--- scene ---\n" << text;
    throw;
  }
}

/// Every field of two scenes is identical (bit for bit), except where they were read from.
inline void expect_same_scene(const Scene& a, const Scene& b) {
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.units, b.units);
  EXPECT_EQ(a.plugins, b.plugins);
  ASSERT_EQ(a.materials.size(), b.materials.size());
  for (const auto& [name, m] : a.materials) {
    ASSERT_EQ(b.materials.count(name), 1u) << name;
    const MaterialDecl& n = b.materials.at(name);
    EXPECT_EQ(m.name, n.name);
    EXPECT_EQ(m.model, n.model);
    EXPECT_EQ(m.material->rest_density(), n.material->rest_density()) << name;
    EXPECT_EQ(m.material->model(), n.material->model());
    for (double s : {0.5, 1.0, 2.0})  // same law, same parameters
      EXPECT_EQ(m.material->sound_speed(Stretch::from_value(s)), n.material->sound_speed(Stretch::from_value(s)));
  }
  ASSERT_EQ(a.bodies.size(), b.bodies.size());
  for (std::size_t i = 0; i < a.bodies.size(); ++i) {
    const BodyDecl& x = a.bodies[i];
    const BodyDecl& y = b.bodies[i];
    EXPECT_EQ(x.name, y.name);
    EXPECT_EQ(x.position, y.position);
    ASSERT_EQ(x.segments.size(), y.segments.size());
    for (std::size_t k = 0; k < x.segments.size(); ++k) {
      EXPECT_EQ(x.segments[k].length, y.segments[k].length);
      EXPECT_EQ(x.segments[k].rapidity, y.segments[k].rapidity);
      EXPECT_EQ(x.segments[k].stretch.log(), y.segments[k].stretch.log());
      EXPECT_EQ(x.segments[k].material, y.segments[k].material);
    }
  }
  for (const auto& [p, q] : {std::pair{&a.left, &b.left}, std::pair{&a.right, &b.right}}) {
    EXPECT_EQ(p->type, q->type);
    EXPECT_EQ(p->bonded, q->bonded);
    EXPECT_EQ(p->position, q->position);
    EXPECT_EQ(p->piston.times, q->piston.times);
    EXPECT_EQ(p->piston.rapidities, q->piston.rapidities);
  }
  EXPECT_EQ(a.solver.method, b.solver.method);
  EXPECT_EQ(a.solver.tolerance, b.solver.tolerance);
  EXPECT_EQ(a.solver.max_fronts, b.solver.max_fronts);
  EXPECT_EQ(a.solver.cells, b.solver.cells);
  EXPECT_EQ(a.solver.order, b.solver.order);
  EXPECT_EQ(a.solver.cfl, b.solver.cfl);
  EXPECT_EQ(a.solver.flux, b.solver.flux);
  EXPECT_EQ(a.t_end, b.t_end);
  ASSERT_EQ(a.outputs.probes.size(), b.outputs.probes.size());
  for (std::size_t i = 0; i < a.outputs.probes.size(); ++i) {
    const ProbeDecl& p = a.outputs.probes[i];
    const ProbeDecl& q = b.outputs.probes[i];
    EXPECT_EQ(p.name, q.name);
    EXPECT_EQ(p.body, q.body);
    EXPECT_EQ(p.X, q.X);
    EXPECT_EQ(p.quantities, q.quantities);
    EXPECT_EQ(p.every, q.every);
  }
  ASSERT_EQ(a.outputs.snapshots.size(), b.outputs.snapshots.size());
  for (std::size_t i = 0; i < a.outputs.snapshots.size(); ++i) {
    const SnapshotDecl& p = a.outputs.snapshots[i];
    const SnapshotDecl& q = b.outputs.snapshots[i];
    EXPECT_EQ(p.times, q.times);
    EXPECT_EQ(p.quantities, q.quantities);
    EXPECT_EQ(p.samples, q.samples);
    EXPECT_EQ(p.bodies, q.bodies);
  }
  EXPECT_EQ(a.outputs.fronts, b.outputs.fronts);
  EXPECT_EQ(a.resolved_yaml(), b.resolved_yaml());
}

/// Loads `text`, reloads its resolved_yaml, and expects the same scene both times.
inline void expect_round_trip(const std::string& text) {
  const Scene first = load_ok(text);
  SCOPED_TRACE("resolved:\n" + first.resolved_yaml());
  const Scene second = load_ok(first.resolved_yaml());
  expect_same_scene(first, second);
}

}  // namespace rigidity::test
