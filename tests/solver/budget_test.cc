// The run budget (solver::RunBudget): a scene that would take billions of
// impacts or steps, or more memory than allowed, ends with an error naming
// the time reached and the bodies — it never runs for hours.
#include <gtest/gtest.h>

#include <string>

#include "core/pipeline/pipeline.h"

namespace asgard {
namespace {

// A ball at 1e6 m/s between two walls 3 apart (faces at x = ±1, radius
// 0.1, restitution 1): an impact every 1.8e-6 s, 5.6e7 over the 100 s.
constexpr const char* kBallInABox =
    "shape_set ball -desc {-sub {-sphere 0.1}}\n"
    "shape_set wall -desc {-sub {-box {1 10 10}}}\n"
    "body b -shape ball -mass 1 -init_dpos {1e6 0 0} -restitution 1\n"
    "body w1 -shape wall -static 1 -init_pos {1.5 0 0}\n"
    "body w2 -shape wall -static 1 -init_pos {-1.5 0 0}\n"
    "simulator -finish 100\n";

TEST(RunBudget, ABodyAtAbsurdSpeedInAClosedBoxStopsAtTheImpactBudget) {
  pipeline::RunOptions opts;
  opts.budget.impacts = 500;
  const pipeline::Run run = pipeline::Simulate(kBallInABox, opts);
  ASSERT_FALSE(run.ok);
  ASSERT_TRUE(run.collisions);
  const auto& impacts = run.collisions->impacts();
  ASSERT_FALSE(impacts.empty());
  // Impact k (from 1) is at 0.9e-6 + (k − 1)·1.8e-6, alternately against w1
  // (odd k) and w2; the run stops at the 501st.
  EXPECT_EQ(run.collisions->counters().impacts, 501);
  const solver::Impact& last = impacts.back();
  EXPECT_NEAR(last.t, 0.9e-6 + 500 * 1.8e-6, 1e-9);
  const std::string& e = run.solver_error;
  EXPECT_NE(e.find("the run exceeded its budget of 500 impacts at t="), std::string::npos) << e;
  EXPECT_NE(e.find("of [0, 100]"), std::string::npos) << e;
  EXPECT_NE(e.find("the latest between bodies b (line 3) and w1 (line 4) at t=0.0009009"),
            std::string::npos)
      << e;
}

TEST(RunBudget, ABodyAtAbsurdSpeedInAClosedBoxStopsAtItsBudgetOfImpulses) {
  pipeline::RunOptions opts;
  opts.budget.impulses_per_body = 400;
  const pipeline::Run run = pipeline::Simulate(kBallInABox, opts);
  ASSERT_FALSE(run.ok);
  const int b = run.equations->FindBody("b");
  EXPECT_EQ(run.simulation->impulses_this_run(b), 401);
  // The 401st impact, against w1, at 0.9e-6 + 400 · 1.8e-6.
  EXPECT_NEAR(run.collisions->impacts().back().t, 0.0007209, 1e-9);
  const std::string& e = run.solver_error;
  EXPECT_EQ(e.rfind("line 3: body b: the run exceeded its budget of 400 impulses on body b at "
                    "t=0.0007209 of [0, 100]; the latest against w1 (line 4) at t=0.0007209",
                    0),
            0u)
      << e;
}

TEST(RunBudget, ARunOfTooManyStepsStopsNamingTheBodyAndItsLine) {
  pipeline::RunOptions opts;
  opts.budget.steps = 1000;
  // A spinning top under gravity: its 13 variables are coupled, so it steps
  // as few components; -maxstep 1e-4 needs 1e5 steps of each.
  const pipeline::Run run = pipeline::Simulate(
      "shape_set s -desc {-sub {-box {1 2 3}}}\n"
      "body top -shape s -init_drot {1 2 3}\n"
      "force -body top -y -10\n"
      "simulator -finish 10 -maxstep 1e-4\n",
      opts);
  ASSERT_FALSE(run.ok);
  const std::string& e = run.solver_error;
  EXPECT_EQ(e.rfind("line 2: body top: the run exceeded its budget of 1000 steps at t=", 0), 0u)
      << e;
  EXPECT_NE(e.find("body top took most of them"), std::string::npos) << e;
  EXPECT_EQ(run.simulation->steps_this_run(), 1001);
  // The scheduler advances the component furthest behind, so the components
  // share the 1001 steps evenly, each step at most -maxstep long.
  const int n = run.simulation->component_count();
  EXPECT_LE(run.simulation->time_reached(), 1001.0 / n * 1e-4 + 1e-12);
  EXPECT_GT(run.simulation->time_reached(), 0.0);
}

TEST(RunBudget, TrajectoryMemoryIsBounded) {
  pipeline::RunOptions opts;
  opts.budget.memory_mb = 0.5;
  const pipeline::Run run = pipeline::Simulate(
      "shape_set s -desc {-sub {-sphere 1}}\n"
      "body b -shape s -init_dpos {1 0 0}\n"
      "simulator -finish 100 -maxstep 1e-3\n",
      opts);
  ASSERT_FALSE(run.ok);
  const std::string& e = run.solver_error;
  EXPECT_NE(e.find("the run exceeded its memory budget (0.5 MB of trajectories) at t="),
            std::string::npos)
      << e;
  EXPECT_NE(e.find("line 2: body b:"), std::string::npos) << e;
  // Checked every 1024 steps: past the budget by less than 1024 samples of
  // the widest component (13 variables: time, x, f, bubble, SampleInfo).
  const double bytes = run.simulation->WaveformBytes();
  EXPECT_GT(bytes, 0.5 * 1048576);
  EXPECT_LT(bytes, 0.5 * 1048576 + 1024 * (8.0 * (1 + 3 * 13) + sizeof(solver::SampleInfo)));
}

// The budget is per Run: a session re-simulating after edits spends it
// afresh each time (the limits do not accumulate over an editing session).
TEST(RunBudget, EachRunSpendsTheBudgetAfresh) {
  pipeline::RunOptions opts;
  opts.budget.steps = 100000;
  opts.budget.impacts = 30;
  opts.budget.impulses_per_body = 30;
  pipeline::Run run = pipeline::Simulate(
      "shape_set ball -desc {-sub {-sphere 0.1}}\n"
      "shape_set wall -desc {-sub {-box {1 10 10}}}\n"
      "body b -shape ball -mass 1 -init_dpos {10 0 0} -restitution 1\n"
      "body w1 -shape wall -static 1 -init_pos {1.5 0 0}\n"
      "body w2 -shape wall -static 1 -init_pos {-1.5 0 0}\n"
      "simulator -finish 4\n",
      opts);
  // 1.8 between impacts at 10 m/s: the first at 0.09, then every 0.18, so
  // 22 in 4 s — within 30, twice.
  ASSERT_TRUE(run.ok) << run.solver_error;
  const long impacts = run.collisions->counters().impacts;
  EXPECT_EQ(impacts, 22);
  const int b = run.equations->FindBody("b");
  EXPECT_EQ(run.simulation->impulses_this_run(b), 22);
  const long steps = run.simulation->steps_this_run();
  for (int c = 0; c < run.simulation->component_count(); ++c) run.simulation->ResetToStart(c);
  ASSERT_TRUE(run.simulation->Run()) << run.simulation->error();
  EXPECT_EQ(run.collisions->counters().impacts, 2 * impacts);
  EXPECT_EQ(run.simulation->steps_this_run(), steps);
  EXPECT_EQ(run.simulation->impulses_this_run(b), 22);
}

}  // namespace
}  // namespace asgard
