// Exact joints and the per-component choice of method: accuracy against
// independent solutions, constraint drift, bounded cost for idle motion.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "core/physics/joints.h"
#include "core/pipeline/pipeline.h"
#include "tests/solver/reference_problems.h"
#include "tests/solver/simulate_checked.h"

namespace asgard {
namespace {

using physics::BodySlot;

pipeline::Run Simulate(
    const std::string& text, double rtol, double atol,
    solver::SolverOptions::Method method = solver::SolverOptions::Method::kAuto) {
  return testing::SimulateChecked(text, rtol, atol, method);
}

Eigen::Vector3d Position(const pipeline::Run& run, const std::string& body, double t) {
  const int b = run.equations->FindBody(body);
  const int v = run.equations->bodies[b].first_var;
  return {run.simulation->Value(v + physics::kX, t), run.simulation->Value(v + physics::kY, t),
          run.simulation->Value(v + physics::kZ, t)};
}

// The physical pendulum of reference_problems.h (a ball of radius 0.5, mass
// 1, whose point at distance L from its centre is held at the origin) with
// an exact joint, written with every digit so that the scene is exactly the
// one the reference solves.
std::string RigidPendulum(double length, double theta0, double finish) {
  char buf[512];
  const double sx = std::sin(theta0), cy = std::cos(theta0);
  std::snprintf(buf, sizeof buf,
                "body m -shape ball -mass 1 -init_pos {%.17g %.17g 0}\n"
                "link -body1 m -offset1 {%.17g %.17g 0} -x 0 -y 0 -z 0\n"
                "force -body m -x 0 -y -9.81 -z 0 -gravitational 1\n"
                "simulator -finish %.17g\n",
                length * sx, -length * cy, -length * sx, length * cy, finish);
  return std::string(testing::kBallShape) + buf;
}

// θ(t) of the same pendulum from its one-degree-of-freedom equation
// θ̈ = −(m g L / (I_cm + m L²)) sin θ, by classical RK4 at a step small
// enough that its error (∝ h⁴) is below 1e-12: an independent solution.
double PendulumAngle(double length, double theta0, double t) {
  const double c = 9.81 * length / (0.1 + length * length);
  double th = theta0, om = 0.0;
  const int n = static_cast<int>(std::ceil(t / 2e-4));
  const double h = t / n;
  auto acc = [c](double x) { return -c * std::sin(x); };
  for (int i = 0; i < n; ++i) {
    const double k1x = om, k1v = acc(th);
    const double k2x = om + 0.5 * h * k1v, k2v = acc(th + 0.5 * h * k1x);
    const double k3x = om + 0.5 * h * k2v, k3v = acc(th + 0.5 * h * k2x);
    const double k4x = om + h * k3v, k4v = acc(th + h * k3x);
    th += h / 6 * (k1x + 2 * k2x + 2 * k3x + k4x);
    om += h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
  }
  return th;
}

TEST(ExactJoint, PendulumFollowsItsOneDegreeOfFreedomSolution) {
  const double L = 2.0, theta0 = 1.0;
  for (double rtol : {1e-4, 1e-6, 1e-8}) {
    const pipeline::Run run = Simulate(RigidPendulum(L, theta0, 5.0), rtol, rtol);
    double worst = 0.0;
    for (double t = 0.0; t <= 5.0; t += 0.25) {
      const double th = PendulumAngle(L, theta0, t);
      const Eigen::Vector3d expect(L * std::sin(th), -L * std::cos(th), 0.0);
      worst = std::max(worst, (Position(run, "m", t) - expect).norm() / L);
    }
    // Error control is per step and relative: over ~2 periods the global
    // error stays within 10× the tolerance.
    EXPECT_LT(worst, 10 * rtol) << "rtol " << rtol;
    EXPECT_GT(run.simulation->totals().explicit_steps, 0) << "a rigid pendulum is not stiff";
  }
}

TEST(ExactJoint, ErrorFallsMonotonicallyWithTheTolerance) {
  const double L = 2.0, theta0 = 1.0;
  double previous = 1e300;
  for (double rtol : {1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8}) {
    const pipeline::Run run = Simulate(RigidPendulum(L, theta0, 5.0), rtol, rtol);
    double worst = 0.0;
    for (double t = 0.0; t <= 5.0; t += 0.1) {
      const double th = PendulumAngle(L, theta0, t);
      worst = std::max(
          worst,
          (Position(run, "m", t) - Eigen::Vector3d(L * std::sin(th), -L * std::cos(th), 0)).norm());
    }
    EXPECT_LT(worst, previous) << "rtol " << rtol;
    previous = worst;
  }
}

// A chain of n rods (boxes 1 × 0.2 × 0.2) hanging from the origin, released
// horizontally: joints exact, no damping anywhere, so energy is conserved.
std::string Chain(int n, double finish, bool closed_loop = false) {
  std::string s =
      "shape_set rod -desc {-sub {-pos {0 0 0} -vertices {{-0.5 -0.1 -0.1} {0.5 -0.1 -0.1} "
      "{-0.5 0.1 -0.1} {0.5 0.1 -0.1} {-0.5 -0.1 0.1} {0.5 -0.1 0.1} {-0.5 0.1 0.1} "
      "{0.5 0.1 0.1}}}}\n";
  for (int i = 0; i < n; ++i) {
    const std::string b = "r" + std::to_string(i);
    s += "body " + b + " -shape rod -mass 1 -init_pos {" + std::to_string(i + 0.5) + " 0 0}" +
         " -ct 0\n";
    s += "force -body " + b + " -x 0 -y -9.81 -z 0 -gravitational 1\n";
    if (i == 0)
      s += "link -body1 r0 -offset1 {-0.5 0 0} -x 0 -y 0 -z 0\n";
    else
      s += "link -body1 r" + std::to_string(i - 1) + " -offset1 {0.5 0 0} -body2 " + b +
           " -offset2 {-0.5 0 0}\n";
  }
  if (closed_loop)
    s += "link -body1 r" + std::to_string(n - 1) + " -offset1 {0.5 0 0} -x " + std::to_string(n) +
         " -y 0 -z 0\n";
  s += "simulator -finish " + std::to_string(finish) + "\n";
  return s;
}

double ChainEnergy(const pipeline::Run& run, int n, double t) {
  double e = 0.0;
  for (int i = 0; i < n; ++i) {
    const int b = run.equations->FindBody("r" + std::to_string(i));
    const auto& m = run.equations->bodies[b];
    const int v = m.first_var;
    auto val = [&](int slot) { return run.simulation->Value(v + slot, t); };
    const Eigen::Vector3d vel(val(physics::kDx), val(physics::kDy), val(physics::kDz));
    const Eigen::Vector3d w(val(physics::kW1), val(physics::kW2), val(physics::kW3));
    e += 0.5 * m.mass * vel.squaredNorm() + 0.5 * w.dot(m.inertia * w) +
         m.mass * 9.81 * val(physics::kY);
  }
  return e;
}

// Largest distance between the two points of any joint over the run.
double WorstJointGap(const pipeline::Run& run, double finish) {
  double worst = 0.0;
  const auto& sys = *run.equations;
  for (double t = 0.0; t <= finish; t += finish / 50) {
    for (const physics::Joint& j : sys.joints) {
      auto point = [&](int b, const Eigen::Vector3d& s) -> Eigen::Vector3d {
        const int v = sys.bodies[b].first_var;
        auto val = [&](int slot) { return run.simulation->Value(v + slot, t); };
        Eigen::Quaterniond q(val(physics::kQw), val(physics::kQx), val(physics::kQy),
                             val(physics::kQz));
        return Eigen::Vector3d(val(physics::kX), val(physics::kY), val(physics::kZ)) +
               q.normalized() * s;
      };
      const Eigen::Vector3d pa = point(j.body_a, j.s_a);
      Eigen::Vector3d pb;
      if (j.body_b >= 0)
        pb = point(j.body_b, j.s_b);
      else
        pb = Eigen::Vector3d(*sys.pool.ConstValue(j.p[0]), *sys.pool.ConstValue(j.p[1]),
                             *sys.pool.ConstValue(j.p[2]));
      worst = std::max(worst, (pa - pb).norm());
    }
  }
  return worst;
}

TEST(ExactJoint, ChainOfFiveConservesEnergyAndHoldsItsJoints) {
  const int n = 5;
  const double rtol = 1e-7;
  const pipeline::Run run = Simulate(Chain(n, 5.0), rtol, rtol);
  EXPECT_EQ(static_cast<int>(run.equations->joints.size()), n);
  const double e0 = ChainEnergy(run, n, 0.0);
  // The chain falls through a height of ~n²/2 · g: energy scale m g n²/2.
  const double scale = n * 9.81 * n / 2.0;
  for (double t = 0.5; t <= 5.0; t += 0.5)
    EXPECT_NEAR(ChainEnergy(run, n, t), e0, 100 * rtol * scale) << "t=" << t;
  // Drift is what integration leaves, pulled back by the stabilization:
  // within a few tolerances of the length scale.
  EXPECT_LT(WorstJointGap(run, 5.0), 100 * rtol * n);
}

TEST(ExactJoint, ClosedLoopIsRegularizedNotSingular) {
  // Four rods whose far end is pinned too: a closed loop with redundant
  // directions (the loop is straight and taut).
  const pipeline::Run run = Simulate(Chain(4, 2.0, /*closed_loop=*/true), 1e-6, 1e-6);
  EXPECT_LT(WorstJointGap(run, 2.0), 1e-3);
}

TEST(ExactJoint, AJointHitByABallMovesItsGroupAndKeepsMomentum) {
  // Two free rods joined end to end, a ball thrown at the second one: no
  // external force, so the total momentum is kept through the impact, and
  // the impulse reaches the first rod through the joint at once.
  const std::string text =
      std::string(testing::kBallShape) +
      "shape_set rod -desc {-sub {-pos {0 0 0} -vertices {{-0.5 -0.1 -0.1} {0.5 -0.1 -0.1} "
      "{-0.5 0.1 -0.1} {0.5 0.1 -0.1} {-0.5 -0.1 0.1} {0.5 -0.1 0.1} {-0.5 0.1 0.1} "
      "{0.5 0.1 0.1}}}}\n"
      "body r0 -shape rod -mass 1 -artbody c -ct 0 -init_pos {0.5 0 0}\n"
      "body r1 -shape rod -mass 1 -artbody c -ct 0 -init_pos {1.5 0 0}\n"
      "link -body1 r0 -offset1 {0.5 0 0} -body2 r1 -offset2 {-0.5 0 0}\n"
      "body ball -shape ball -mass 1 -ct 1 -init_pos {1.7 2 0} -init_dpos {0 -3 0}\n"
      "simulator -finish 1.5\n";
  const pipeline::Run run = Simulate(text, 1e-7, 1e-9);
  ASSERT_NE(run.collisions, nullptr);
  ASSERT_GE(run.collisions->impacts().size(), 1u);
  const double t_hit = run.collisions->impacts().front().t;
  auto momentum = [&](double t) {
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
    for (const char* name : {"r0", "r1", "ball"}) {
      const int v = run.equations->bodies[run.equations->FindBody(name)].first_var;
      p += Eigen::Vector3d(run.simulation->Value(v + physics::kDx, t),
                           run.simulation->Value(v + physics::kDy, t),
                           run.simulation->Value(v + physics::kDz, t));
    }
    return p;
  };
  EXPECT_LT((momentum(1.5) - Eigen::Vector3d(0, -3, 0)).norm(), 1e-6);
  // Right after the impact the first rod moves too (the joint carried the
  // impulse), and the joined points move together.
  const auto& sys = *run.equations;
  auto point_velocity = [&](const char* name, const Eigen::Vector3d& s, solver::Side side) {
    const int v = sys.bodies[sys.FindBody(name)].first_var;
    auto val = [&](int slot) { return run.simulation->Value(v + slot, t_hit, side); };
    const Eigen::Quaterniond q(val(physics::kQw), val(physics::kQx), val(physics::kQy),
                               val(physics::kQz));
    const Eigen::Vector3d w(val(physics::kW1), val(physics::kW2), val(physics::kW3));
    return Eigen::Vector3d(
        Eigen::Vector3d(val(physics::kDx), val(physics::kDy), val(physics::kDz)) +
        q.normalized() * w.cross(s));
  };
  const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
  EXPECT_LT(point_velocity("r0", zero, solver::Side::kLeft).norm(), 1e-9);
  EXPECT_GT(point_velocity("r0", zero, solver::Side::kRight).norm(), 0.01);
  const physics::Joint& j = sys.joints.front();
  EXPECT_LT((point_velocity("r0", j.s_a, solver::Side::kRight) -
             point_velocity("r1", j.s_b, solver::Side::kRight))
                .norm(),
            1e-9);
  EXPECT_LT(WorstJointGap(run, 1.5), 1e-4);
}

TEST(ExactJoint, LinkWithTightnessStaysASpring) {
  const std::string spring = testing::Pendulum(2.0, 0.5, 9.81, 1e4, 1.0);
  const pipeline::Run run = Simulate(spring, 1e-6, 1e-6);
  EXPECT_TRUE(run.equations->joints.empty());
  const std::string exact = RigidPendulum(2.0, 0.5, 1.0);
  EXPECT_EQ(Simulate(exact, 1e-6, 1e-6).equations->joints.size(), 1u);
}

TEST(MethodChoice, FreeFlightCostsABoundedNumberOfSteps) {
  // A thrown ball under gravity: the step grows geometrically until it spans
  // the run, so a run 100 times longer costs no more steps.
  const pipeline::Run short_run = Simulate(testing::Projectile(10.0), 1e-8, 1e-8);
  const pipeline::Run long_run = Simulate(testing::Projectile(1000.0), 1e-8, 1e-8);
  EXPECT_LE(long_run.simulation->totals().steps, short_run.simulation->totals().steps);
  for (int c = 0; c < long_run.simulation->component_count(); ++c)
    EXPECT_LE(long_run.simulation->component(c).counters().steps, 12) << "component " << c;
}

TEST(MethodChoice, StiffSpringGoesImplicitAndSoftMotionExplicit) {
  // A critically damped link with k = 1e8: eigenvalues ~ −1e4.
  const pipeline::Run stiff = Simulate(testing::DampedLink(1e8, 1.0, 0.1, 1.0), 1e-6, 1e-9);
  // Stiff steps are the L-stable ESDIRK's (esdirk.h; TR-BDF2 before it).
  EXPECT_GT(stiff.simulation->totals().esdirk_steps, 0);
  EXPECT_LT(stiff.simulation->totals().steps, 2000);
  const double x = stiff.simulation->Value(
      stiff.equations->bodies[stiff.equations->FindBody("d")].first_var + physics::kX, 1e-3);
  EXPECT_NEAR(x, testing::DampedLinkExact(1e8, 1.0, 0.1, 1e-3), 1e-6);
  // An undamped oscillator of frequency 1: explicit throughout.
  const pipeline::Run soft = Simulate(testing::Oscillator(1.0, 1.0, 10.0), 1e-8, 1e-10);
  EXPECT_EQ(soft.simulation->totals().esdirk_steps + soft.simulation->totals().trbdf2_steps, 0);
  const double xs = soft.simulation->Value(
      soft.equations->bodies[soft.equations->FindBody("o")].first_var + physics::kX, 10.0);
  EXPECT_NEAR(xs, std::cos(10.0), 1e-6);
}

TEST(MethodChoice, ExplicitPlaybackBetweenSamplesIsFourthOrder) {
  // cos t between samples of large steps: the continuous extension keeps
  // the interpolation error near the tolerance, not at Hermite's h⁴/384.
  const pipeline::Run run = Simulate(testing::Oscillator(1.0, 1.0, 10.0), 1e-6, 1e-8);
  const int v = run.equations->bodies[run.equations->FindBody("o")].first_var + physics::kX;
  double worst = 0.0;
  for (double t = 0.0; t <= 10.0; t += 0.01)
    worst = std::max(worst, std::abs(run.simulation->Value(v, t) - std::cos(t)));
  EXPECT_LT(worst, 10 * 1e-6);
}

}  // namespace
}  // namespace asgard

namespace asgard {
namespace {

TEST(NonFinite, AValueThatIsNotFiniteStopsTheRunNamingTheVariableTimeAndLine) {
  struct Case {
    const char* scene;
    const char* variable;
  };
  const Case cases[] = {
      // a force that divides by zero at the start
      {"body b -shape ball -init_pos {0 0 0}\n"
       "force -body b -x {1 / b.x} -y 0 -z 0\nsimulator -finish 1\n",
       "b.dx"},
      // an initial velocity that overflows once the force acts on it
      {"body b -shape ball -init_pos {1 0 0} -init_dpos {1e308 0 0}\n"
       "force -body b -x {b.dx * 1e10} -y 0 -z 0\nsimulator -finish 1\n",
       "b.dx"},
  };
  for (const Case& c : cases) {
    pipeline::RunOptions opts;
    const pipeline::Run run = pipeline::Simulate(std::string(testing::kBallShape) + c.scene, opts);
    EXPECT_FALSE(run.ok) << c.scene;
    EXPECT_NE(run.solver_error.find(c.variable), std::string::npos) << run.solver_error;
    EXPECT_NE(run.solver_error.find("line 2: body b"), std::string::npos) << run.solver_error;
    EXPECT_NE(run.solver_error.find("at t="), std::string::npos) << run.solver_error;
  }
}

}  // namespace
}  // namespace asgard
