// Rest steps (component.h): a state at rest is kept over long spans at no
// cost, and a state that only looks at rest (an unstable equilibrium a
// rounding away, slow drift) is integrated as usual.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <utility>

#include <Eigen/Dense>

#include "core/pipeline/pipeline.h"
#include "tests/solver/simulate_checked.h"

namespace asgard {
namespace {

pipeline::Run Simulate(const std::string& text, double rtol = 1e-8, double atol = 1e-10) {
  return testing::SimulateChecked(text, rtol, atol);
}

// A ball on an exact joint at a point `len` above (θ = 0, hanging) or below
// it (θ = π, standing on it), turned by `theta`.
std::string Pendulum(double theta, double finish) {
  const double len = 1.0, s = std::sin(theta), c = std::cos(theta);
  char text[1024];
  std::snprintf(text, sizeof text,
                "shape_set ball -desc {-sub {-pos {0 0 0} -sphere 0.1}}\n"
                "body p -shape ball -mass 1 -init_pos {%.17g %.17g 0}\n"
                "link -body1 p -offset1 {%.17g %.17g 0} -x 0 -y 0 -z 0\n"
                "force -body p -y -9.81 -gravitational 1\n"
                "simulator -finish %g -collisions 0\n",
                len * s, -len * c, -len * s, len * c, finish);
  return text;
}

TEST(RestSteps, APendulumHangingAtRestCostsOneStepHoweverLongTheRun) {
  for (double finish : {10.0, 1000.0}) {
    const pipeline::Run run = Simulate(Pendulum(0.0, finish));
    const solver::Counters c = run.simulation->totals();
    // The joint force balances gravity to rounding (refined against K), so
    // every rate vanishes exactly: one rest step reaches the end.
    EXPECT_EQ(c.steps, 1) << "finish " << finish;
    EXPECT_EQ(c.rest_steps, 1);
    EXPECT_EQ(c.jacobian_evaluations, 0);
    const int v = run.equations->bodies[run.equations->FindBody("p")].first_var;
    EXPECT_EQ(run.simulation->Value(v + physics::kY, finish), -1.0);
    EXPECT_EQ(run.simulation->Value(v + physics::kDy, 0.5 * finish), 0.0);
  }
}

// Pendulums of other masses and lengths, and chains of two, three and five
// (a block solve of their joints), hanging straight down, cost one rest
// step. A pendulum's joint force cancels its weight to the last bit, however
// 1/m and the arm round (a mass of 5 on an arm of 3 rounded
// 1/m + c L² − c L² away from 1/m); a chain's rates are a cancellation of
// the weight of the bodies below, tested against the rounding of its terms.
TEST(RestSteps, PendulumsAndChainsOfAnyMassHangingAtRestCostOneStep) {
  auto hanging = [](int links, double mass, double len0) {
    std::string text = "shape_set ball -desc {-sub {-pos {0 0 0} -sphere 0.5}}\n";
    double y = 0;
    for (int i = 0; i < links; ++i) {
      const double len = len0 + 0.5 * i;
      const std::string name = "b" + std::to_string(i);
      char body[256];
      std::snprintf(body, sizeof body, "body %s -shape ball -mass %.17g -init_pos {0 %.17g 0}\n",
                    name.c_str(), mass + i, y - len);
      text += body;
      text += "force -body " + name + " -y -9.81 -gravitational 1\n";
      char link[256];
      if (i == 0)
        std::snprintf(link, sizeof link, "link -body1 b0 -offset1 {0 %.17g 0} -x 0 -y 0 -z 0\n",
                      len);
      else
        std::snprintf(link, sizeof link,
                      "link -body1 %s -offset1 {0 %.17g 0} -body2 b%d -offset2 {0 0 0}\n",
                      name.c_str(), len, i - 1);
      text += link;
      y -= len;
    }
    return text + "simulator -finish 100 -collisions 0\n";
  };
  for (const int links : {1, 2, 3, 5})
    for (const double mass : {1.0, 3.0, 5.0, 0.7})
      for (const double len : {1.0, 1.5, 3.0}) {
        const pipeline::Run run = Simulate(hanging(links, mass, len));
        const solver::Counters c = run.simulation->totals();
        EXPECT_EQ(c.steps, 1) << links << " links, mass " << mass << ", length " << len;
        EXPECT_EQ(c.rest_steps, 1) << links << " links, mass " << mass << ", length " << len;
      }
}

TEST(RestSteps, AnInvertedPendulumARoundingAwayFromUpFallsAsTheLinearizationSays) {
  // A physical pendulum (a ball of radius r = 0.1, I = 2/5 m r², on a point
  // L = 1 from its centre): θ̈ = g L / (L² + 2/5 r²) sin θ near the top, so
  // θ(t) = θ₀ cosh(λ t) while θ is small.
  // Its rates at t = 0 are tiny (g θ₀ ≈ 1e-8) but not zero, and J·f is not:
  // the second-order probe must refuse to keep it standing.
  const double theta0 = 1e-9, pi = std::acos(-1.0);
  // Tolerances far below x (which grows from 1e-9 to 1e-5): the comparison
  // is with the motion, not with the integration error.
  const pipeline::Run run = Simulate(Pendulum(pi + theta0, 3.0), 1e-10, 1e-18);
  const int v = run.equations->bodies[run.equations->FindBody("p")].first_var;
  const double lambda = std::sqrt(9.81 / (1.0 + 0.4 * 0.1 * 0.1));
  for (double t : {1.0, 2.0, 3.0}) {
    const double x = run.simulation->Value(v + physics::kX, t);
    const double expect = -std::sin(theta0 * std::cosh(lambda * t));  // x = L sin(π + θ)
    // θ ≤ 1e-5 here: the linearization's error is O(θ²) relative, far below
    // the 1e-4 asked; the run's own error, amplified by e^(λt) ≈ 1e4 at
    // most from a local 1e-10, stays below it too.
    EXPECT_NEAR(x, expect, 1e-4 * std::abs(expect)) << "t=" << t;
  }
  EXPECT_EQ(run.simulation->totals().rest_steps, 0);
}

TEST(RestSteps, ABallDriftingSlowlyIsNotFrozen) {
  // A constant velocity of 1e-12 moves x by 1e-9 over 1000 s, ten times the
  // absolute tolerance: x must follow it (its velocity component, whose
  // rate is exactly zero, rests).
  const pipeline::Run run = Simulate(
      "shape_set ball -desc {-sub {-pos {0 0 0} -sphere 0.1}}\n"
      "body b -shape ball -mass 1 -init_pos {0 0 0} -init_dpos {1e-12 0 0}\n"
      "simulator -finish 1000 -collisions 0\n");
  const int v = run.equations->bodies[run.equations->FindBody("b")].first_var;
  EXPECT_NEAR(run.simulation->Value(v + physics::kX, 1000.0), 1e-9, 1e-21);
  EXPECT_NEAR(run.simulation->Value(v + physics::kX, 400.0), 4e-10, 1e-21);
  // The ball is one component (per-body fusion) in free flight: exact
  // ballistic steps, never kept at rest.
  EXPECT_GT(run.simulation->totals().ballistic_steps, 0);
  EXPECT_EQ(run.simulation->totals().rest_steps, 0);
  // Every component: a handful of steps for the whole run.
  for (int c = 0; c < run.simulation->component_count(); ++c)
    EXPECT_LE(run.simulation->component(c).counters().steps, 12) << c;
}

TEST(RestSteps, AJumpIntoARestingComponentRestartsItFromTheJump) {
  // A ball at rest on a pendulum's path: the swing hits it, and the ball's
  // resting velocity components must take the impulse at the impact time.
  const pipeline::Run run = Simulate(
      "shape_set ball -desc {-sub {-pos {0 0 0} -sphere 0.25}}\n"
      "body p -shape ball -mass 1 -init_pos {-1 0 0}\n"
      "link -body1 p -offset1 {1 0 0} -x 0 -y 0 -z 0\n"
      "force -body p -y -9.81 -gravitational 1\n"
      "body q -shape ball -mass 1 -init_pos {0.5 -1 0} -restitution 1\n"
      "simulator -finish 2 -collisions 1\n");
  ASSERT_TRUE(run.collisions);
  ASSERT_FALSE(run.collisions->impacts().empty());
  const double t_hit = run.collisions->impacts().front().t;
  const int v = run.equations->bodies[run.equations->FindBody("q")].first_var;
  EXPECT_EQ(run.simulation->Value(v + physics::kDx, 0.5 * t_hit), 0.0);
  EXPECT_GT(run.simulation->Value(v + physics::kDx, t_hit + 1e-3), 0.5);
  // After the hit the ball moves: x grows.
  EXPECT_GT(run.simulation->Value(v + physics::kX, 2.0), 0.5 + 1e-3);
}

}  // namespace
}  // namespace asgard

namespace asgard {
namespace {

// n balls of radius 0.2, `body` writing ball i's lines, collisions off unless asked.
template <typename Body>
std::string FreeBalls(int n, double finish, Body body, bool collisions = false) {
  std::string text = "shape_set ball -desc {-sub {-pos {0 0 0} -sphere 0.2}}\n";
  for (int i = 0; i < n; ++i) {
    char line[256];
    body(i, line, sizeof line);
    text += line;
  }
  return text + "simulator -finish " + std::to_string(finish) + " -collisions " +
         (collisions ? "1" : "0") + "\n";
}

// Free flight under constant forces (BallisticStep): x + v t + a t²/2 over
// the whole run in one exact step per component, at every time a reader
// asks for (the Hermite interpolant of a quadratic is the quadratic).
TEST(BallisticSteps, FreeBallsCostOneStepEachAndFollowTheirParabolas) {
  const int n = 200;
  const std::string text = FreeBalls(n, 100.0, [](int i, char* line, size_t size) {
    std::snprintf(line, size,
                  "body b%d -shape ball -mass 2 -init_pos {%d 0 %d} -init_dpos {%g %g 0.5}\n"
                  "force -body b%d -x 0 -y -9.81 -z %g -gravitational 1\n",
                  i, 3 * (i % 20), 3 * (i / 20), 0.01 * (i + 1), 1.0 + 0.1 * i, i, -0.5 * (i % 3));
  });
  const pipeline::Run run = Simulate(text);
  const solver::Counters c = run.simulation->totals();
  // One component per ball (its axes and its rotation at rest, fused) and
  // one exact step each.
  EXPECT_EQ(run.simulation->component_count(), n);
  EXPECT_EQ(c.steps, n);
  EXPECT_EQ(c.ballistic_steps, n);
  EXPECT_EQ(c.rest_steps, 0);
  for (int i = 0; i < n; i += 37) {
    const int v = run.equations->bodies[run.equations->FindBody("b" + std::to_string(i))].first_var;
    const double vx = 0.01 * (i + 1), vy = 1.0 + 0.1 * i, az = -0.5 * (i % 3);
    for (double t : {0.0, 0.37, 13.0, 61.5, 100.0}) {
      const double y = vy * t - 0.5 * 9.81 * t * t;
      // Rounding only: the terms reach 5e4, an ulp of which is 7e-12, and the
      // interpolation weights add a few more (1e-10 is 14 such ulps).
      EXPECT_NEAR(run.simulation->Value(v + physics::kX, t), 3 * (i % 20) + vx * t, 1e-10);
      EXPECT_NEAR(run.simulation->Value(v + physics::kY, t), y, 1e-10);
      EXPECT_NEAR(run.simulation->Value(v + physics::kZ, t),
                  3 * (i / 20) + 0.5 * t + 0.5 * az * t * t, 1e-10);
      EXPECT_NEAR(run.simulation->Value(v + physics::kDy, t), vy - 9.81 * t, 1e-12);
    }
  }
}

// A force that depends on time or on the state is not constant: the mode is
// integrated as usual (and still accurately).
TEST(BallisticSteps, ForcesThatVaryAreIntegratedNotExtrapolated) {
  const pipeline::Run run = Simulate(
      "shape_set ball -desc {-sub {-pos {0 0 0} -sphere 0.2}}\n"
      "body b -shape ball -mass 1\n"
      "force -body b -x {cos(t)} -y {-b.y} -z 0\n"
      "body c -shape ball -mass 1 -init_pos {0 5 0} -init_dpos {0 1 0}\n"
      "simulator -finish 3 -collisions 0\n");
  const solver::Counters c = run.simulation->totals();
  const int b = run.equations->bodies[run.equations->FindBody("b")].first_var;
  // x'' = cos t from rest: x = 1 − cos t.
  EXPECT_NEAR(run.simulation->Value(b + physics::kX, 3.0), 1.0 - std::cos(3.0), 1e-6);
  EXPECT_GT(c.explicit_steps, 10);
  // Each ball is one component.  c (no force, constant velocity) is
  // ballistic: one step.  b's x is driven by cos t, so its whole component
  // (with y, a spring at its equilibrium, and z and the rotation at rest)
  // is integrated, never kept at rest nor extrapolated.
  EXPECT_EQ(run.simulation->component_count(), 2);
  EXPECT_EQ(c.ballistic_steps, 1);
  EXPECT_EQ(c.rest_steps, 0);
  EXPECT_EQ(run.simulation->Value(b + physics::kY, 3.0), 0.0);
}

// Issue target: 1000 free-flying balls (no collisions) cost fewer than two
// steps each.  Fused, a ball under gravity with its spin at rest is one
// component that takes one exact step to the end; a ball that spins (about
// a fixed axis: no torque, isotropic inertia) turns exactly too, in steps
// as long as the playback interpolant follows the turn: a phase |ω|h/2 of
// at most φ = (tol / 8e-5)^(1/5) = 0.4164 for tol = rtol + atol (component.cc,
// kSpinInterpolation), so 2 rad/s for 10 s take ⌈10 / 0.4164⌉ = 25 steps.
TEST(BallisticSteps, AThousandFreeBallsCostFewerThanTwoStepsEach) {
  const int n = 1000;
  const std::string text = FreeBalls(n, 10.0, [](int i, char* line, size_t size) {
    std::snprintf(line, size,
                  "body b%d -shape ball -mass 1 -init_pos {%d 0 %d} -init_dpos {0.1 %g 0.2}%s\n"
                  "force -body b%d -x 0 -y -9.81 -z 0 -gravitational 1\n",
                  i, 3 * (i % 32), 3 * (i / 32), 1.0 + 0.01 * i,
                  i == 0 ? " -init_drot {0 0 2}" : "", i);
  });
  const pipeline::Run run = Simulate(text, 1e-6, 1e-9);
  const solver::Counters c = run.simulation->totals();
  EXPECT_EQ(run.simulation->component_count(), n);
  EXPECT_LT(c.steps, 2 * n);
  EXPECT_EQ(c.ballistic_steps, c.steps);
  EXPECT_LE(c.steps, n - 1 + 25);
  // The spinning ball: its spin about z (isotropic, so constant) turns it
  // by 2t, q = (cos t, 0, 0, sin t); its centre flies as the others do.
  // Between samples each of q's rows is off by at most the interpolant's
  // error, tol = 1e-6 + 1e-9 (above), which turns the angle atan2(q_z, q_w)
  // by at most √2 tol.
  const int v = run.equations->bodies[run.equations->FindBody("b0")].first_var;
  for (double t : {0.3, 1.0, 2.71, 5.0, 7.77, 10.0}) {
    const double qw = run.simulation->Value(v + physics::kQw, t);
    const double qz = run.simulation->Value(v + physics::kQz, t);
    EXPECT_NEAR(qw, std::cos(t), 1.001e-6) << t;
    EXPECT_NEAR(qz, std::sin(t), 1.001e-6) << t;
    EXPECT_NEAR(std::atan2(qz, qw), std::remainder(t, 2 * std::acos(-1.0)), 1.5e-6) << t;
    EXPECT_NEAR(run.simulation->Value(v + physics::kY, t), t - 0.5 * 9.81 * t * t, 1e-9) << t;
  }
}

// A cube and a ball spinning about a skew axis, without torque, keep their
// angular velocity (isotropic inertia): their orientation is
// q(t) = (cos(|ω|t/2), sin(|ω|t/2) ω/|ω|) from the identity, exactly at each
// step and to the interpolant's bound between steps (tol = rtol + atol per
// row, above), every step ballistic.  A brick of unequal sides precesses:
// its angular velocity's rates are not zero, and it is integrated.
TEST(BallisticSteps, ACubeAndABallTurnExactlyAboutAnyAxisAndABrickIsIntegrated) {
  const std::string text =
      "shape_set cube -desc {-sub {-box {1 1 1}}}\n"
      "shape_set brick -desc {-sub {-box {1 2 3}}}\n"
      "shape_set ball -desc {-sub {-pos {0 0 0} -sphere 0.5}}\n"
      "body cube -shape cube -mass 1 -init_pos {0 0 0} -init_drot {1 2 3}\n"
      "body ball -shape ball -mass 2 -init_pos {5 0 0} -init_dpos {0 3 0} -init_drot {-2 0.5 1}\n"
      "body brick -shape brick -mass 1 -init_pos {10 0 0} -init_drot {1 2 3}\n"
      "force -body cube -y -9.81 -gravitational 1\n"
      "force -body ball -y -9.81 -gravitational 1\n"
      "force -body brick -y -9.81 -gravitational 1\n"
      "simulator -finish 10 -collisions 0\n";
  const pipeline::Run run = Simulate(text, 1e-6, 1e-9);
  const double tol = 1e-6 + 1e-9;
  for (const auto& [name, w] : {std::pair<std::string, Eigen::Vector3d>{"cube", {1, 2, 3}},
                                {"ball", {-2, 0.5, 1}}}) {
    const int v = run.equations->bodies[run.equations->FindBody(name)].first_var;
    const solver::Counters& c = run.simulation->component(run.simulation->component_of(v)).counters();
    EXPECT_EQ(c.ballistic_steps, c.steps) << name;
    // At most a phase |ω|h/2 of 0.4164 per step (the test above).
    EXPECT_LE(c.steps, std::ceil(0.5 * w.norm() * 10.0 / 0.4164) + 1) << name;
    for (double t : {0.0, 0.1, 1.234, 3.0, 6.66, 9.99, 10.0}) {
      const double half = 0.5 * w.norm() * t;
      const Eigen::Vector4d q(std::cos(half), std::sin(half) * w.x() / w.norm(),
                              std::sin(half) * w.y() / w.norm(), std::sin(half) * w.z() / w.norm());
      for (int i = 0; i < 4; ++i)
        EXPECT_NEAR(run.simulation->Value(v + physics::kQw + i, t), q[i], tol)
            << name << " t " << t << " row " << i;
      for (int i = 0; i < 3; ++i)  // constant, up to the interpolation weights' rounding
        EXPECT_DOUBLE_EQ(run.simulation->Value(v + physics::kW1 + i, t), w[i]) << name << " t " << t;
    }
  }
  const int brick = run.equations->bodies[run.equations->FindBody("brick")].first_var;
  const solver::Counters& c =
      run.simulation->component(run.simulation->component_of(brick + physics::kQw)).counters();
  EXPECT_GT(c.explicit_steps, 0);
  EXPECT_EQ(c.ballistic_steps, 0);
}

// The same with collisions on: the collision monitor reads and writes fused
// bodies (pipeline.cc fuses them now that the monitor reads every value
// before a response cuts a component back), so 1000 balls that never meet
// still cost one exact step each, the monitor's windows notwithstanding
// (a step is not cut at a window's end).
TEST(BallisticSteps, AThousandFreeBallsWithCollisionsOnCostFewerThanTwoStepsEach) {
  const int n = 1000;
  const std::string text = FreeBalls(
      n, 10.0,
      [](int i, char* line, size_t size) {
        std::snprintf(line, size,
                      "body b%d -shape ball -mass 1 -init_pos {%d 0 %d} -init_dpos {0.1 %g 0.2}\n"
                      "force -body b%d -x 0 -y -9.81 -z 0 -gravitational 1\n",
                      i, 3 * (i % 32), 3 * (i / 32), 1.0 + 0.01 * i, i);
      },
      /*collisions=*/true);
  const pipeline::Run run = Simulate(text, 1e-6, 1e-9);
  ASSERT_TRUE(run.collisions);
  EXPECT_EQ(run.collisions->counters().impacts, 0);  // 3 apart, moving in step sideways
  const solver::Counters c = run.simulation->totals();
  EXPECT_EQ(run.simulation->component_count(), n);
  EXPECT_LT(c.steps, 2 * n);
  // Each flies its parabola: exact up to the rounding of terms of size ~500.
  for (int i : {0, 999}) {
    const int v = run.equations->bodies[run.equations->FindBody("b" + std::to_string(i))].first_var;
    for (double t : {1.0, 5.0, 10.0})
      EXPECT_NEAR(run.simulation->Value(v + physics::kY, t),
                  (1.0 + 0.01 * i) * t - 0.5 * 9.81 * t * t, 1e-9)
          << i << " " << t;
  }
}

}  // namespace
}  // namespace asgard
