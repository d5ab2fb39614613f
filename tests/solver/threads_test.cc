// Several threads stepping independent components at once (simulation.h,
// "Threads") must give what one thread gives, bit for bit: every waveform,
// every impact, every error.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>

#include "core/pipeline/pipeline.h"
#include "tests/solver/reference_problems.h"
#include "tests/solver/same_waveforms.h"

namespace asgard {
namespace {

using SceneRun = pipeline::Run;

SceneRun SimulateWith(const std::string& text, int threads) {
  pipeline::RunOptions o;
  o.solver.threads = threads;
  SceneRun run = pipeline::Simulate(text, o);
  for (const auto& d : run.diagnostics) ADD_FAILURE() << d.span.line << ": " << d.message;
  return run;
}

void ExpectSameRuns(const SceneRun& a, const SceneRun& b) {
  ASSERT_TRUE(a.simulation && b.simulation);
  testing::ExpectSameWaveforms(*a.simulation, *b.simulation);
  ASSERT_EQ(a.collisions != nullptr, b.collisions != nullptr);
  if (!a.collisions) return;
  const auto& ia = a.collisions->impacts();
  const auto& ib = b.collisions->impacts();
  ASSERT_EQ(ia.size(), ib.size());
  for (size_t k = 0; k < ia.size(); ++k) {
    EXPECT_EQ(ia[k].t, ib[k].t) << k;
    EXPECT_EQ(ia[k].a, ib[k].a) << k;
    EXPECT_EQ(ia[k].b, ib[k].b) << k;
    EXPECT_EQ(ia[k].impulse, ib[k].impulse) << k;
  }
}

std::string Pendulum(const std::string& name, double px, double py, double pz, double len,
                     double theta, double mass = 1.0) {
  const double s = std::sin(theta), c = std::cos(theta);
  std::ostringstream t;
  t.precision(17);
  t << "body " << name << " -shape ball -mass " << mass << " -init_pos {" << px + len * s << " "
    << py - len * c << " " << pz << "}\nlink -body1 " << name << " -offset1 {" << -len * s << " "
    << len * c << " 0} -x " << px << " -y " << py << " -z " << pz << "\nforce -body " << name
    << " -x 0 -y -9.81 -z 0 -gravitational 1\n";
  return t.str();
}

// Figure 5.11's scene: a ball hits pendulum A twice and B once, beside n
// swinging pendulums that never touch anything.
std::string Figure511(int n) {
  std::string s = std::string(testing::kBallShape) + Pendulum("A", 0, 3, 0, 3, 0, 5) +
                  Pendulum("B", 6, 3, 0, 3, 0, 5) +
                  "body ball -shape ball -mass 1 -init_pos {3 0 0} -init_dpos {-4 0 0}\n";
  for (int i = 0; i < n; ++i)
    s += Pendulum("idle" + std::to_string(i), 3.0 * (i % 8), 10, -10.0 - 3.0 * (i / 8),
                  1.0 + 0.5 * (i % 3), 0.3);
  return s + "simulator -finish 5\n";
}

TEST(Threads, IndependentPendulumsAndImpactsComeOutAsWithOneThread) {
  const std::string text = Figure511(24);
  const SceneRun one = SimulateWith(text, 1);
  ASSERT_TRUE(one.ok) << one.solver_error;
  ASSERT_TRUE(one.collisions);
  ASSERT_GE(one.collisions->impacts().size(), 3u);
  EXPECT_EQ(one.simulation->batches(), 0);
  for (int threads : {2, 4}) {
    const SceneRun many = SimulateWith(text, threads);
    ASSERT_TRUE(many.ok) << many.solver_error;
    EXPECT_GT(many.simulation->batches(), 20) << threads;
    ExpectSameRuns(one, many);
  }
}

TEST(Threads, ReadersAreNeverBatchedWithWhatTheyRead) {
  // Pendulums read by other bodies' forces (f reads p0, g reads p0 and f,
  // h reads f), beside independent ones; without collisions every component
  // may run ahead.
  std::string text = testing::kBallShape;
  for (int i = 0; i < 6; ++i)
    text += Pendulum("p" + std::to_string(i), 4.0 * i, 0, 0, 1.0 + 0.25 * i, 0.4);
  text +=
      "body f -shape ball -mass 1 -init_pos {0 -5 0}\n"
      "force -body f -x {p0.x - f.x} -y 0 -z 0\n"
      "body g -shape ball -mass 1 -init_pos {0 -9 0}\n"
      "force -body g -x {p0.y} -y {f.x - g.y} -z 0\n"
      "body h -shape ball -mass 1 -init_pos {0 -13 0}\n"
      "force -body h -x {f.x - h.x} -y {p3.x} -z 0\n"
      "simulator -finish 4 -collisions 0\n";
  const SceneRun one = SimulateWith(text, 1);
  ASSERT_TRUE(one.ok) << one.solver_error;
  int readers = 0;
  for (const auto& up : one.simulation->partition().upstream) readers += !up.empty();
  ASSERT_GE(readers, 3);
  const SceneRun two = SimulateWith(text, 2);
  ASSERT_TRUE(two.ok) << two.solver_error;
  EXPECT_GT(two.simulation->batches(), 10);
  ExpectSameRuns(one, two);
}

TEST(Threads, StiffLinksAndTrajectoriesBuildTheirModesOnAnyThread) {
  // Stiff links (ESDIRK steps, Jacobians, factorizations) to moving points
  // and bodies a trajectory prescribes over an interval (modes built and
  // tapes shared during the run, under the build lock).
  std::ostringstream text;
  text << testing::kBallShape;
  for (int i = 0; i < 4; ++i)
    text << "body d" << i << " -shape ball -mass 1 -init_pos {" << 3 * i
         << " 0 0} -init_dpos {1 0 0}\nlink -body1 d" << i << " -offset1 {0 0 0} -x {" << 3 * i
         << " + sin(t)} -y {0.5 * cos(2 * t)} -z 0 -tightness 1e6\n";
  for (int i = 0; i < 4; ++i)
    text << "body t" << i << " -shape ball -mass 1 -init_pos {" << 3 * i << " 5 0}\ntrajectory tr"
         << i << " -body t" << i << " -from 0.5 -to 1.5 -points {{0.5 " << 3 * i << " 5 0} {1 "
         << 3 * i + 1 << " 6 0} {1.5 " << 3 * i + 2 << " 5 0}}\nforce -body t" << i
         << " -x 0 -y -9.81 -z 0 -gravitational 1\n";
  text << "simulator -finish 3 -collisions 0\n";
  const SceneRun one = SimulateWith(text.str(), 1);
  ASSERT_TRUE(one.ok) << one.solver_error;
  ASSERT_GT(one.simulation->totals().esdirk_steps, 100);
  const SceneRun two = SimulateWith(text.str(), 2);
  ASSERT_TRUE(two.ok) << two.solver_error;
  EXPECT_GT(two.simulation->batches(), 10);
  ExpectSameRuns(one, two);
}

TEST(Threads, APileOfCubesComesOutAsWithOneThread) {
  // Resting contact: island solves, holds and sleeps through the observer.
  std::ostringstream text;
  text << "shape_set cube -desc {-sub {-box {1 1 1}}}\n"
          "shape_set floor -desc {-sub {-box {20 1 20}}}\n"
          "body floor -shape floor -static 1 -init_pos {0 -0.5 0} -friction 0.5\n";
  for (int i = 0; i < 6; ++i)
    text << "body c" << i << " -shape cube -mass 1 -init_pos {" << 1.5 * (i % 3) << " "
         << 1.0 + 1.2 * (i / 3) << " " << 0.2 * i << "} -init_rot {" << 0.1 * i << " " << 0.05 * i
         << " 0.2} -friction 0.5 -restitution 0.3\nforce -body c" << i << " -y {-9.81 * c" << i
         << ".mass} -gravitational 1\n";
  text << "simulator -finish 1.5\n";
  const SceneRun one = SimulateWith(text.str(), 1);
  ASSERT_TRUE(one.ok) << one.solver_error;
  ASSERT_GE(one.collisions->impacts().size(), 6u);
  const SceneRun two = SimulateWith(text.str(), 2);
  ASSERT_TRUE(two.ok) << two.solver_error;
  EXPECT_GT(two.simulation->batches(), 0);
  ExpectSameRuns(one, two);
}

TEST(Threads, AFailureOnAWorkerIsReportedAsWithOneThread) {
  // The ninth pendulum's force divides by zero at t = 1: the run stops there
  // with the same message whichever thread stepped it.
  std::string text = testing::kBallShape;
  for (int i = 0; i < 8; ++i)
    text += Pendulum("p" + std::to_string(i), 4.0 * i, 0, 0, 1.0 + 0.25 * i, 0.4);
  text +=
      "body bad -shape ball -mass 1 -init_pos {0 -20 0}\n"
      "force -body bad -x {1 / (t - 1)} -y 0 -z 0\n"
      "simulator -finish 2 -collisions 0\n";
  const SceneRun one = SimulateWith(text, 1);
  ASSERT_FALSE(one.ok);
  ASSERT_FALSE(one.solver_error.empty());
  for (int threads : {2, 4}) {
    const SceneRun many = SimulateWith(text, threads);
    EXPECT_FALSE(many.ok);
    EXPECT_EQ(many.solver_error, one.solver_error) << threads;
    EXPECT_GT(many.simulation->batches(), 0) << threads;
  }
}

}  // namespace
}  // namespace asgard
