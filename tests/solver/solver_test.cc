// Solver tests: accuracy against closed forms, step control, partitioning,
// stiffness, determinism and truncation.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>

#include "core/physics/trajectory.h"
#include "core/pipeline/pipeline.h"
#include "tests/common/samples.h"
#include "tests/solver/reference_problems.h"
#include "tests/solver/same_waveforms.h"

namespace asgard {
namespace {

using SceneRun = pipeline::Run;
using physics::BodySlot;

SceneRun SimulateOk(const std::string& text, solver::SolverOptions so = {}) {
  pipeline::RunOptions opts;
  opts.solver = so;
  SceneRun run = pipeline::Simulate(text, opts);
  for (const auto& d : run.diagnostics) ADD_FAILURE() << d.span.line << ": " << d.message;
  EXPECT_TRUE(run.ok) << run.solver_error;
  return run;
}

int Var(const SceneRun& run, const std::string& body, BodySlot slot) {
  const int b = run.equations->FindBody(body);
  EXPECT_GE(b, 0);
  return run.equations->bodies[b].first_var + slot;
}

double At(const SceneRun& run, const std::string& body, BodySlot slot, double t) {
  return run.simulation->Value(Var(run, body, slot), t);
}

solver::SolverOptions Tol(double rtol, double atol) {
  solver::SolverOptions so;
  so.rtol = rtol;
  so.atol = atol;
  return so;
}

TEST(Projectile, IsExactToRoundOffAndTakesAHandfulOfSteps) {
  const SceneRun run = SimulateOk(testing::Projectile(10.0));
  const int c = run.simulation->component_of(Var(run, "p", physics::kY));
  const auto& wave = run.simulation->component(c).waveform();
  // The step grows geometrically from its initial 1e-3 to cover the interval.
  EXPECT_LE(run.simulation->component(c).counters().steps, 12);
  EXPECT_EQ(run.simulation->component(c).counters().rejected_steps, 0);
  for (int k = 0; k < wave.size(); ++k) {
    const double t = wave.time(k);
    const double y = 20 * t - 0.5 * 9.81 * t * t;
    // Each step adds a few roundings of numbers of size |y| ≤ 500.
    EXPECT_NEAR(At(run, "p", physics::kY, t), y, 1e-11 * (1 + std::abs(y))) << "t=" << t;
    EXPECT_NEAR(At(run, "p", physics::kX, t), 3 * t, 1e-12 * (1 + 3 * t));
  }
  // Between samples the playback interpolant is exact for a quadratic too.
  for (double t = 0; t <= 10; t += 0.37) {
    EXPECT_NEAR(At(run, "p", physics::kY, t), 20 * t - 0.5 * 9.81 * t * t, 1e-10);
  }
}

TEST(Oscillator, MatchesCosineWithinTolerance) {
  const double k = 4.0, m = 1.0, w = std::sqrt(k / m);
  const SceneRun run = SimulateOk(testing::Oscillator(k, m, 20.0), Tol(1e-8, 1e-10));
  double max_err = 0;
  for (double t = 0; t <= 20; t += 0.01)
    max_err = std::max(max_err, std::abs(At(run, "o", physics::kX, t) - std::cos(w * t)));
  // Per-step error control on a neutrally stable problem: the local errors
  // (each ≤ rtol·|x| ≤ 1e-8) add up, so the global error is at most about
  // steps × rtol.
  const long steps = run.simulation->totals().steps;
  EXPECT_LT(max_err, 2.0 * steps * 1e-8) << steps << " steps";
  EXPECT_GT(max_err, 1e-12);  // it is a numerical solution, not a copy of the answer
}

TEST(DampedLink, MatchesTheCriticallyDampedClosedForm) {
  for (double k : {1e2, 1e4}) {
    const double m = 2.0;
    const SceneRun run = SimulateOk(testing::DampedLink(k, m, 1.0, 2.0), Tol(1e-8, 1e-10));
    double max_err = 0;
    for (double t = 0; t <= 2; t += 1e-3)
      max_err = std::max(
          max_err, std::abs(At(run, "d", physics::kX, t) - testing::DampedLinkExact(k, m, 1.0, t)));
    EXPECT_LT(max_err, 1e-6) << "k=" << k;
  }
}

// Times where x crosses zero going in the given direction, by bisection on
// the playback interpolant.
std::vector<double> Crossings(const SceneRun& run, int var, double t0, double t1, double dt) {
  std::vector<double> out;
  double a = t0, fa = run.simulation->Value(var, a);
  for (double b = t0 + dt; b <= t1; b += dt) {
    const double fb = run.simulation->Value(var, b);
    if (fa < 0 && fb >= 0) {
      double lo = a, hi = b;
      for (int i = 0; i < 60; ++i) {
        const double mid = 0.5 * (lo + hi);
        (run.simulation->Value(var, mid) < 0 ? lo : hi) = mid;
      }
      out.push_back(0.5 * (lo + hi));
    }
    a = b;
    fa = fb;
  }
  return out;
}

TEST(Pendulum, PeriodMatchesTheEllipticIntegral) {
  const double L = 1.0, g = 9.81, theta0 = 1.0;
  const double T = testing::PendulumPeriod(L, theta0, g);
  const SceneRun run = SimulateOk(testing::Pendulum(L, theta0, g, 1e7, 4 * T), Tol(1e-9, 1e-11));
  const auto zc = Crossings(run, Var(run, "m", physics::kX), 0, 4 * T, 1e-3);
  ASSERT_GE(zc.size(), 3u);
  const double measured = (zc.back() - zc.front()) / (zc.size() - 1);
  // The joint stretches by δ ≈ m(g + v²/L)/k ≈ 3e-6 L, which lengthens the
  // period by about δ/(2L) ≈ 1.5e-6; 1e-5 relative covers it and the solver.
  EXPECT_NEAR(measured / T, 1.0, 1e-5) << "measured " << measured << " expected " << T;
}

TEST(TorqueFreeTop, ConservesEnergyAndMomentumAndFlipsAtThePredictedPeriod) {
  const double I1 = 1, I2 = 2, I3 = 3;
  const double w0[3] = {0.01, 1.0, 0.02};
  const double T = testing::TopPeriod(I1, I2, I3, w0[0], w0[1], w0[2]);
  const SceneRun run =
      SimulateOk(testing::Top(I1, I2, I3, "0.01 1.0 0.02", 2.5 * T), Tol(1e-9, 1e-12));
  auto state = [&](double t, double w[3], Eigen::Vector3d& L) {
    for (int a = 0; a < 3; ++a) w[a] = At(run, "top", BodySlot(physics::kW1 + a), t);
    Eigen::Quaterniond q(At(run, "top", physics::kQw, t), At(run, "top", physics::kQx, t),
                         At(run, "top", physics::kQy, t), At(run, "top", physics::kQz, t));
    L = q.normalized().toRotationMatrix() * Eigen::Vector3d(I1 * w[0], I2 * w[1], I3 * w[2]);
  };
  double w[3];
  Eigen::Vector3d L0;
  state(0, w, L0);
  const double E0 = 0.5 * (I1 * w[0] * w[0] + I2 * w[1] * w[1] + I3 * w[2] * w[2]);
  double max_dE = 0, max_dL = 0;
  for (double t = 0; t <= 2.5 * T; t += T / 500) {
    Eigen::Vector3d L;
    state(t, w, L);
    const double E = 0.5 * (I1 * w[0] * w[0] + I2 * w[1] * w[1] + I3 * w[2] * w[2]);
    max_dE = std::max(max_dE, std::abs(E - E0) / E0);
    max_dL = std::max(max_dL, (L - L0).norm() / L0.norm());
  }
  // Local errors of at most rtol per step add up over the run.
  const double bound = 2.0 * run.simulation->totals().steps * 1e-9;
  EXPECT_LT(max_dE, bound);
  EXPECT_LT(max_dL, bound);
  // ω₂ flips sign twice per period.
  const auto zc = Crossings(run, Var(run, "top", physics::kW2), 0, 2.5 * T, T / 2000);
  ASSERT_GE(zc.size(), 2u);
  EXPECT_NEAR((zc[1] - zc[0]) / T, 1.0, 1e-4) << "T=" << T;
}

TEST(Trajectory, BodyFollowsItsCurveAndStepsLandOnTheKnots) {
  const std::string text = std::string(testing::kBallShape) +
                           "body b -shape ball -init_pos {0 0 0}\n"
                           "trajectory path -points {{1 0 0 0} {2 1 2 0} {3 3 2 1} {4 4 0 0}} "
                           "-body b -state pos\n"
                           "simulator -finish 6\n";
  const SceneRun run = SimulateOk(text);
  const auto& curve = *run.equations->curves[0];
  for (double t = 1.0; t <= 4.0; t += 0.05) {
    const Eigen::Vector3d p = curve.Value(t);
    for (int a = 0; a < 3; ++a)
      EXPECT_NEAR(At(run, "b", BodySlot(physics::kX + a), t), p[a], 1e-12) << "t=" << t;
  }
  // After the interval the body coasts with the curve's final velocity.
  const Eigen::Vector3d v = curve.Value(4.0, 1), p4 = curve.Value(4.0);
  for (int a = 0; a < 3; ++a)
    EXPECT_NEAR(At(run, "b", BodySlot(physics::kX + a), 6.0), p4[a] + 2 * v[a], 1e-9);
  // Samples exist exactly at the interval ends and the knots.
  const int c = run.simulation->component_of(Var(run, "b", physics::kX));
  const auto& wave = run.simulation->component(c).waveform();
  for (double knot : {1.0, 2.0, 3.0, 4.0}) {
    bool found = false;
    for (int k = 0; k < wave.size(); ++k) found |= wave.time(k) == knot;
    EXPECT_TRUE(found) << "no sample at t=" << knot;
  }
  // Before t=1 the body rests at the origin; at t=1 it jumps onto the curve.
  EXPECT_EQ(run.simulation->Value(Var(run, "b", physics::kX), 1.0, solver::Side::kLeft), 0.0);
}

TEST(Tolerance, AchievedErrorFallsWithTheRequestedToleranceOverFourDecades) {
  const double k = 4.0, w = 2.0;
  std::vector<double> errors;
  for (double tol : {1e-4, 1e-5, 1e-6, 1e-7, 1e-8}) {
    const SceneRun run = SimulateOk(testing::Oscillator(k, 1.0, 10.0), Tol(tol, tol * 1e-2));
    double err = 0;
    for (double t = 0; t <= 10; t += 0.01)
      err = std::max(err, std::abs(At(run, "o", physics::kX, t) - std::cos(w * t)));
    errors.push_back(err);
  }
  for (size_t i = 1; i < errors.size(); ++i) {
    // Per-step control of a second-order method: global error ∝ tol^(2/3),
    // a factor 4.6 per decade; require at least 3.
    EXPECT_GT(errors[i - 1] / errors[i], 3.0) << "decade " << i;
  }
}

TEST(Partition, ALoneSphereUnderGravitySplitsPerAxis) {
  // The seed's strongly connected components, before chains are fused.
  solver::SolverOptions so;
  so.fuse_chains = false;
  const SceneRun run = SimulateOk(testing::Projectile(1.0), so);
  const auto& sim = *run.simulation;
  for (BodySlot s : {physics::kX, physics::kY, physics::kZ, physics::kDx, physics::kDy,
                     physics::kDz, physics::kW1, physics::kW2, physics::kW3}) {
    EXPECT_EQ(sim.component(sim.component_of(Var(run, "p", s))).variables().size(), 1u);
  }
  // The quaternion's four rates read each other: one component of four.
  EXPECT_EQ(sim.component(sim.component_of(Var(run, "p", physics::kQw))).variables().size(), 4u);
  EXPECT_EQ(sim.component_count(), 10);
  // x reads dx: its component is downstream of dx's.
  const int cx = sim.component_of(Var(run, "p", physics::kX));
  const int cdx = sim.component_of(Var(run, "p", physics::kDx));
  EXPECT_EQ(sim.partition().upstream[cx], std::vector<int>{cdx});
}

// Projectile p's positions and vertical velocity agree between two runs.
void ExpectSameProjectile(const SceneRun& a, const SceneRun& b, double tol) {
  for (double t : {0.25, 0.5, 1.0})
    for (BodySlot s : {physics::kX, physics::kY, physics::kZ, physics::kDy})
      EXPECT_NEAR(At(a, "p", s, t), At(b, "p", s, t), tol) << t;
}

TEST(Partition, FusedChainsPairEachAxisWithItsRateAndTheSpinWithTheQuaternion) {
  // {dx} is read by {x} alone and {x} reads only {dx}: one component.  The
  // quaternion alone reads each of the three spin components: one more.
  // (Without per-body fusion, which would make the four one: next test.)
  solver::SolverOptions chains;
  chains.fuse_bodies = false;
  const SceneRun fused = SimulateOk(testing::Projectile(1.0), chains);
  const auto& sim = *fused.simulation;
  for (auto [a, b] : {std::pair{physics::kX, physics::kDx}, std::pair{physics::kY, physics::kDy},
                      std::pair{physics::kZ, physics::kDz}}) {
    const int c = sim.component_of(Var(fused, "p", a));
    EXPECT_EQ(sim.component_of(Var(fused, "p", b)), c);
    EXPECT_EQ(sim.component(c).variables().size(), 2u);
    EXPECT_TRUE(sim.partition().upstream[c].empty());
  }
  const int cq = sim.component_of(Var(fused, "p", physics::kQw));
  for (BodySlot s : {physics::kW1, physics::kW2, physics::kW3})
    EXPECT_EQ(sim.component_of(Var(fused, "p", s)), cq);
  EXPECT_EQ(sim.component(cq).variables().size(), 7u);
  EXPECT_EQ(sim.component_count(), 4);  // 3 axes, the rotation
  // The same motion as the unfused components, to the tolerance.
  solver::SolverOptions so;
  so.fuse_chains = false;
  const SceneRun apart = SimulateOk(testing::Projectile(1.0), so);
  ExpectSameProjectile(fused, apart, 1e-6);
}

TEST(Partition, AFreeBodyIsOneComponentAndABodyCoupledToAnotherIsNot) {
  // The projectile's axes and rotation form an island: one component of 13,
  // the same motion as apart.  b1 and b2 share their x axis through a mutual
  // force, so neither body fuses; b3's y reads b1's y (one way), which it
  // alone reads, so the two y chains are one component (chain fusion) and
  // neither b1 nor b3 is an island.  b4 is free: one component.
  const SceneRun one = SimulateOk(testing::Projectile(1.0));
  const auto& sim = *one.simulation;
  EXPECT_EQ(sim.component_count(), 1);
  EXPECT_EQ(sim.component(0).variables().size(), static_cast<size_t>(physics::kBodySlots));
  solver::SolverOptions apart_options;
  apart_options.fuse_bodies = false;
  const SceneRun apart = SimulateOk(testing::Projectile(1.0), apart_options);
  ExpectSameProjectile(one, apart, 1e-12);
  const std::string text = std::string(testing::kBallShape) + testing::Ball("b1", "-2 0 0") +
                           testing::Ball("b2", "2 1 0") + testing::Ball("b3", "0 5 0") +
                           testing::Ball("b4", "0 9 0") +
                           "force -body b1 -x {(b2.x - b1.x)} -y 0 -z 0\n"
                           "force -body b2 -x {(b1.x - b2.x)} -y 0 -z 0\n"
                           "force -body b3 -x 0 -y {b1.y - b3.y} -z 0\n"
                           "simulator -finish 1 -collisions 0\n";
  const SceneRun run = SimulateOk(text);
  const auto& s2 = *run.simulation;
  auto size_of = [&](const char* body, BodySlot slot) {
    return s2.component(s2.component_of(Var(run, body, slot))).variables().size();
  };
  EXPECT_EQ(size_of("b1", physics::kX), 4u);  // {x, dx} of b1 and b2
  EXPECT_EQ(size_of("b1", physics::kY), 4u);  // {y, dy} of b1 and b3
  EXPECT_EQ(size_of("b3", physics::kY), 4u);
  EXPECT_EQ(size_of("b3", physics::kX), 2u);
  EXPECT_EQ(size_of("b4", physics::kX), static_cast<size_t>(physics::kBodySlots));
  for (size_t c = 0; c < static_cast<size_t>(s2.component_count()); ++c)
    for (int u : s2.partition().upstream[c]) EXPECT_LT(u, static_cast<int>(c));
  // A body whose rows read only its own variables but which another body
  // reads is no island, whether the reader comes before or after it: s's x
  // chain joins r's, its y chain stays apart; the free body f is an island.
  for (bool reader_first : {true, false}) {
    const std::string r = testing::Ball("r", "0 0 0"), sb = testing::Ball("s", "0 4 0");
    const SceneRun one_way =
        SimulateOk(std::string(testing::kBallShape) + (reader_first ? r + sb : sb + r) +
                   testing::Ball("f", "0 8 0") +
                   "force -body r -x {s.x - r.x} -y 0 -z 0\nsimulator -finish 1 -collisions 0\n");
    const auto& s3 = *one_way.simulation;
    auto size3 = [&](const char* body, BodySlot slot) {
      return s3.component(s3.component_of(Var(one_way, body, slot))).variables().size();
    };
    EXPECT_EQ(size3("s", physics::kX), 4u) << reader_first;  // {x, dx} of r and s
    EXPECT_EQ(size3("s", physics::kY), 2u) << reader_first;
    EXPECT_EQ(size3("f", physics::kX), static_cast<size_t>(physics::kBodySlots)) << reader_first;
    for (size_t c = 0; c < static_cast<size_t>(s3.component_count()); ++c)
      for (int u : s3.partition().upstream[c]) EXPECT_LT(u, static_cast<int>(c)) << reader_first;
  }
}

TEST(Partition, ABodyOnAStiffSpringIsNotFusedSoItsIdleRowsStayOffTheImplicitPath) {
  // A ball held at its centre by a critically damped link to a fixed point,
  // x0 = 1: only its x axis moves.  A soft link (rate 1/s) leaves the body
  // one component; a stiff one (rate 1000/s, above the 50/s of
  // simulation.cc) keeps it apart, so that the x axis alone takes steps
  // (on the implicit path once the link's rate bounds them) and the idle
  // axes and the spin take one rest step each.
  const SceneRun soft = SimulateOk(testing::DampedLink(1.0, 1.0, 1.0, 1.0));
  EXPECT_EQ(soft.simulation->component_count(), 1);
  const SceneRun stiff = SimulateOk(testing::DampedLink(1e6, 1.0, 1.0, 0.05));
  const auto& sim = *stiff.simulation;
  EXPECT_EQ(sim.component_count(), 4);  // 3 axes, the rotation
  const int cx = sim.component_of(Var(stiff, "d", physics::kX));
  EXPECT_EQ(sim.component(cx).variables().size(), 2u);
  const solver::Counters c = sim.totals();
  EXPECT_EQ(c.rest_steps, 3);
  EXPECT_EQ(sim.component(cx).counters().steps, c.steps - c.rest_steps);
  // Apart and as one component, the closed form within 10 × rtol (1e-6).
  solver::SolverOptions single;
  single.partition = false;
  const SceneRun one = SimulateOk(testing::DampedLink(1e6, 1.0, 1.0, 0.05), single);
  EXPECT_EQ(one.simulation->component_count(), 1);
  const int v = Var(stiff, "d", physics::kX);
  for (double t : {0.001, 0.005, 0.02, 0.05}) {
    const double exact = testing::DampedLinkExact(1e6, 1.0, 1.0, t);
    EXPECT_NEAR(stiff.simulation->Value(v, t), exact, 1e-5) << t;
    EXPECT_NEAR(one.simulation->Value(v, t), exact, 1e-5) << t;
  }
}

TEST(Partition, ComponentsAreFusedOnlyWhereOneComponentAloneReadsThem) {
  // b1.x reads b1.dx; b2.x reads b2.dx and b1.x; 4 reads b2.x; 5 reads b1.x.
  // b1's dx is read by b1's x alone: they fuse.  b1's x is read by two, so
  // b2's x takes in neither it nor (as a reader of both) its own dx; 4 alone
  // reads b2's x and takes it in.
  const std::vector<std::vector<int>> reads = {
      /*0 b1.x*/ {1}, /*1 b1.dx*/ {}, /*2 b2.x*/ {3, 0},
      /*3 b2.dx*/ {}, /*4*/ {2},      /*5*/ {0}};
  const solver::Partition p = solver::PartitionEquations(reads, false, true);
  EXPECT_EQ(p.component_of[0], p.component_of[1]);
  EXPECT_NE(p.component_of[2], p.component_of[0]);
  EXPECT_NE(p.component_of[2], p.component_of[3]);
  EXPECT_EQ(p.component_of[4], p.component_of[2]);
  EXPECT_NE(p.component_of[5], p.component_of[0]);
  EXPECT_EQ(p.components.size(), 4u);
  // Components read by one reader alone join it: 0 and 1 feed only 2, 2 and
  // 3 feed only 4, so all five are one.  In `shared` 1 also feeds 3, so
  // neither 2 nor 3 takes it in, and nothing fuses.
  const std::vector<std::vector<int>> fan = {/*0*/ {}, /*1*/ {}, /*2 reads 0, 1*/ {0, 1}, /*3*/ {},
                                             /*4 reads 3, 2*/ {3, 2}};
  const solver::Partition q = solver::PartitionEquations(fan, false, true);
  EXPECT_EQ(q.components.size(), 1u);
  const std::vector<std::vector<int>> shared = {/*0*/ {}, /*1*/ {}, /*2 reads 0, 1*/ {0, 1},
                                                /*3 reads 1*/ {1}};
  const solver::Partition r = solver::PartitionEquations(shared, false, true);
  EXPECT_EQ(r.components.size(), 4u);
  // Dependency order still holds: every upstream precedes its reader.
  for (const solver::Partition* x : {&p, &q, &r})
    for (size_t c = 0; c < x->components.size(); ++c)
      for (int u : x->upstream[c]) EXPECT_LT(u, static_cast<int>(c));
}

TEST(Partition, TwoBodiesWithAMutualXForceShareOneXComponent) {
  const std::string text = std::string(testing::kBallShape) + testing::Ball("b1", "-2 0 0") +
                           testing::Ball("b2", "2 1 0") +
                           "force -body b1 -x {(b2.x - b1.x)} -y 0 -z 0\n"
                           "force -body b2 -x {(b1.x - b2.x)} -y 0 -z 0\n"
                           "simulator -finish 1\n";
  const SceneRun run = SimulateOk(text);
  const auto& sim = *run.simulation;
  const int c = sim.component_of(Var(run, "b1", physics::kX));
  std::vector<int> expected = {Var(run, "b1", physics::kX), Var(run, "b1", physics::kDx),
                               Var(run, "b2", physics::kX), Var(run, "b2", physics::kDx)};
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(sim.component(c).variables(), expected);
  EXPECT_NE(sim.component_of(Var(run, "b1", physics::kY)),
            sim.component_of(Var(run, "b2", physics::kY)));
  // b1's y axis is its own chain {y, dy}.
  EXPECT_EQ(sim.component(sim.component_of(Var(run, "b1", physics::kY))).variables().size(), 2u);
}

TEST(Partition, TheTwoRodLinkedPendulumFormsOneLargeComponent) {
  const SceneRun run = SimulateOk(ReadSample("pendulum.al"));
  const auto& sim = *run.simulation;
  const int c = sim.component_of(Var(run, "b1", physics::kX));
  EXPECT_EQ(c, sim.component_of(Var(run, "b2", physics::kX)));
  // Both rods' 13 state variables couple through the off-centre links.
  EXPECT_EQ(sim.component(c).variables().size(), 26u);
  // The free ball is not part of it.
  EXPECT_NE(c, sim.component_of(Var(run, "b3", physics::kX)));
}

TEST(StiffLink, NoRingingAndStepCountRoughlyFlatFromK1e2To1e8) {
  std::vector<long> steps;
  for (double k : {1e2, 1e4, 1e6, 1e8}) {
    const double m = 1.0, w = std::sqrt(k / m);
    // Simulate 50 time constants of the slowest link, scaled to each k.
    const double finish = 50.0 / w;
    const SceneRun run = SimulateOk(testing::DampedLink(k, m, 1.0, finish), Tol(1e-6, 1e-9));
    double min_x = 1, max_err = 0;
    for (double s = 0; s <= 50; s += 0.01) {
      const double t = s / w;
      const double x = At(run, "d", physics::kX, t);
      min_x = std::min(min_x, x);
      max_err = std::max(max_err, std::abs(x - testing::DampedLinkExact(k, m, 1.0, t)));
    }
    EXPECT_GT(min_x, -1e-6) << "ringing at k=" << k;  // critically damped: never overshoots
    EXPECT_LT(max_err, 1e-4) << "k=" << k;
    steps.push_back(run.simulation->totals().steps);
  }
  for (long s : steps) EXPECT_LT(s, 3 * steps.front()) << "steps " << s << " vs " << steps.front();
}

TEST(StiffLink, TheLStableMethodTakesOverOnceTheTransientHasDecayed) {
  // A stiff link over a long interval: once the transient has decayed the
  // steps are far longer than 1/ω, and they must be L-stable.  (While the
  // transient lasts the step is limited by accuracy, not stability, and the
  // component may take explicit steps there: the method is chosen per step
  // from the spectral radius, see component.h.)
  const SceneRun run = SimulateOk(testing::DampedLink(1e8, 1.0, 1.0, 10.0));
  const int c = run.simulation->component_of(Var(run, "d", physics::kX));
  const auto& comp = run.simulation->component(c);
  int late = 0;
  for (int k = 1; k < comp.waveform().size(); ++k) late += comp.waveform().time(k) > 0.05;
  EXPECT_LE(late, 40);
  // Those steps are the ESDIRK's (esdirk.h), which replaced TR-BDF2 there.
  EXPECT_GE(comp.counters().esdirk_steps, late);
}

TEST(MethodChoice, APendulumAtLooseToleranceStaysOnItsJointAndMostlyExplicit) {
  // An exact joint's stabilization (ρ ≈ 22) holds the explicit steps of a
  // pendulum to their stability limit at loose tolerance.  The ESDIRK's
  // steps there are no longer and cost three times as much, so the
  // component returns to explicit steps (component.cc, kExplicitStepCost).
  // A step may err by rtol of the ball's distance from the pivot (1) and
  // the joint's stabilization pulls the distance back, so it stays within
  // rtol of 1 (measured: 0.019 at rtol 0.1).
  const std::string text = testing::Pendulum(1.0, 1.0, 9.81, 0.0, 10.0);
  for (double rtol : {0.1, 0.05}) {
    const SceneRun run = SimulateOk(text, Tol(rtol, rtol));
    if (!run.ok) continue;
    double worst = 0;
    for (double t = 0; t <= 10; t += 0.01) {
      const double d = std::hypot(At(run, "m", physics::kX, t), At(run, "m", physics::kY, t),
                                  At(run, "m", physics::kZ, t));
      worst = std::max(worst, std::abs(d - 1.0));
    }
    EXPECT_LE(worst, rtol) << "rtol " << rtol;
    const solver::Counters c = run.simulation->totals();
    EXPECT_LE(4 * c.esdirk_steps, c.explicit_steps) << "rtol " << rtol;
  }
}

TEST(MethodChoice, ATolerancePastTheLoosestIsLoweredWithAWarningAtTheOption) {
  // A double pendulum at rtol 0.3 flew apart and failed at t = 1.15; the
  // solver takes 0.1 instead and says so at the option.
  const std::string text = std::string(testing::kBallShape) +
                           "body a -shape ball -mass 1 -init_pos {0.8414709848078965 "
                           "-0.5403023058681398 0}\n"
                           "body b -shape ball -mass 1 -init_pos {1.9784621762771326 "
                           "-2.0359411008618853 0}\n"
                           "link -body1 a -offset1 {-0.8414709848078965 0.5403023058681398 0} "
                           "-x 0 -y 0 -z 0\n"
                           "link -body1 b -offset1 {-0.29552020666133955 0.955336489125606 0} "
                           "-body2 a -offset2 {0.8414709848078965 -0.5403023058681398 0}\n"
                           "force -body a -x 0 -y -9.81 -z 0 -gravitational 1\n"
                           "force -body b -x 0 -y -9.81 -z 0 -gravitational 1\n"
                           "simulator -finish 3 -rtol 0.3 -atol 0.3\n";
  const SceneRun run = pipeline::Simulate(text);
  ASSERT_TRUE(run.ok) << run.solver_error;
  ASSERT_EQ(run.diagnostics.size(), 1u);
  const scene::Diagnostic& d = run.diagnostics[0];
  EXPECT_EQ(d.severity, scene::Severity::kWarning);
  EXPECT_NE(d.message.find("rtol 0.3"), std::string::npos) << d.message;
  EXPECT_EQ(d.span.line, 8);
  EXPECT_EQ(run.simulation->options().rtol, 0.1);
}

using testing::ExpectSameWaveforms;

TEST(Determinism, TwoRunsGiveBitIdenticalWaveforms) {
  const std::string text = ReadSample("pendulum.al");
  const SceneRun a = SimulateOk(text);
  const SceneRun b = SimulateOk(text);
  ExpectSameWaveforms(*a.simulation, *b.simulation);
}

TEST(Determinism, TruncateAndResumeReproducesTheFromScratchResultBitForBit) {
  const std::string text = ReadSample("pendulum.al");
  const SceneRun reference = SimulateOk(text);
  SceneRun run = SimulateOk(text);
  auto& sim = *run.simulation;
  // Cut every component somewhere in the middle, one after another, and resume.
  for (int c = 0; c < sim.component_count(); ++c) sim.Truncate(c, 0.37 + 0.1 * c);
  EXPECT_GT(sim.totals().truncated_steps, 0);
  ASSERT_TRUE(sim.Run()) << sim.error();
  ExpectSameWaveforms(*reference.simulation, sim);
}

TEST(Determinism, AStiffLinkReusingItsJacobianResumesBitForBit) {
  // ESDIRK steps hand their Jacobian on (SampleInfo::jac_from); a resumed
  // run must take the same Jacobian from the same sample, so cutting the
  // waveform anywhere — inside a run of reused Jacobians too — and resuming
  // gives the from-scratch waveform bit for bit.
  const std::string text =
      std::string(testing::kBallShape) +
      "body d -shape ball -mass 1 -init_pos {0 0 0} -init_dpos {1 0 0}\n"
      "link -body1 d -offset1 {0 0 0} -x {sin(t)} -y {0.5 * cos(2 * t)} -z 0 -tightness 1e8\n"
      "simulator -finish 6 -rtol 1e-6 -atol 1e-6\n";
  const SceneRun reference = SimulateOk(text);
  const solver::Counters c = reference.simulation->totals();
  ASSERT_GT(c.esdirk_steps, 100);
  ASSERT_LT(4 * c.jacobian_evaluations, c.steps);  // Jacobians are reused
  for (double cut : {0.001, 0.9, 2.345, 4.5}) {
    SceneRun run = SimulateOk(text);
    auto& sim = *run.simulation;
    for (int k = 0; k < sim.component_count(); ++k) sim.Truncate(k, cut);
    EXPECT_GT(sim.totals().truncated_steps, 0) << cut;
    ASSERT_TRUE(sim.Run()) << sim.error();
    ExpectSameWaveforms(*reference.simulation, sim);
  }
}

TEST(Determinism, RunsOfStepsWithoutAnObserverGiveTheStrictOrdersWaveforms) {
  // Without an after_step observer a component takes runs of steps ahead of
  // the one furthest behind; with one, the strict order; the sequential
  // schedule runs each to the end.  Three swinging pendulums of different
  // lengths (independent components) and readers (f reads p0, g reads p0
  // and f, h reads f) must come out bit for bit the same all three ways.
  std::ostringstream text;
  text << "shape_set ball -desc {-sub {-pos {0 0 0} -sphere 0.5}}\n";
  for (int i = 0; i < 3; ++i) {
    const double len = 1.0 + 0.5 * i, px = 4.0 * i, s = std::sin(0.4), c = std::cos(0.4);
    text << "body p" << i << " -shape ball -mass 1 -init_pos {" << px + len * s << " " << -len * c
         << " 0}\nlink -body1 p" << i << " -offset1 {" << -len * s << " " << len * c << " 0} -x "
         << px << " -y 0 -z 0\nforce -body p" << i << " -x 0 -y -9.81 -z 0 -gravitational 1\n";
  }
  text << "body f -shape ball -mass 1 -init_pos {0 -5 0}\n"
          "force -body f -x {p0.x - f.x} -y 0 -z 0\n"
          "body g -shape ball -mass 1 -init_pos {0 -9 0}\n"
          "force -body g -x {p0.y} -y {f.x - g.y} -z 0\n"
          "body h -shape ball -mass 1 -init_pos {0 -13 0}\n"
          "force -body h -x {f.x - h.x} -y 0 -z 0\nsimulator -finish 4\n";
  auto simulate = [&](bool observed, solver::SolverOptions::Schedule schedule) {
    pipeline::RunOptions o;
    o.collisions = false;
    o.prepare_only = true;
    o.solver.schedule = schedule;
    SceneRun run = pipeline::Check(text.str());
    EXPECT_TRUE(pipeline::Solve(run, o)) << run.solver_error;
    int steps = 0;
    if (observed) run.simulation->after_step = [&](solver::Simulation&, int) { ++steps; };
    EXPECT_TRUE(run.simulation->Run()) << run.simulation->error();
    if (observed) {
      EXPECT_EQ(steps, run.simulation->steps_this_run());
    }
    return run;
  };
  using S = solver::SolverOptions::Schedule;
  const SceneRun ahead = simulate(false, S::kEventDriven);
  const SceneRun strict = simulate(true, S::kEventDriven);
  const SceneRun sequential = simulate(false, S::kSequential);
  ASSERT_GE(ahead.simulation->component_count(), 5);
  int readers = 0;
  for (const auto& up : ahead.simulation->partition().upstream) readers += !up.empty();
  EXPECT_GE(readers, 2);
  ExpectSameWaveforms(*strict.simulation, *ahead.simulation);
  ExpectSameWaveforms(*strict.simulation, *sequential.simulation);
}

TEST(Scenes, TheSeedSamplesSimulate) {
  for (const char* name : {"pendulum.al", "figure62.al"}) {
    const SceneRun run = SimulateOk(ReadSample(name));
    EXPECT_EQ(run.simulation->time_reached(), run.equations->t1) << name;
  }
}

}  // namespace
}  // namespace asgard

namespace asgard {
namespace {

TEST(LinearSolvers, KluAndDenseLuGiveTheSameSolution) {
  const std::string text = ReadSample("pendulum.al");
  solver::SolverOptions dense, sparse;
  dense.dense_limit = 1000;
  sparse.dense_limit = 2;  // every component of more than 2 variables uses KLU
  const SceneRun a = SimulateOk(text, dense);
  const SceneRun b = SimulateOk(text, sparse);
  // Pivoting differs, so agreement is to round-off amplified by the steps,
  // far inside the 1e-6 tolerance.
  for (double t = 0; t <= 5; t += 0.05)
    for (const char* body : {"b1", "b2"})
      for (BodySlot s : {physics::kX, physics::kY, physics::kQz})
        EXPECT_NEAR(At(a, body, s, t), At(b, body, s, t), 1e-7) << body << " t=" << t;
}

}  // namespace
}  // namespace asgard
