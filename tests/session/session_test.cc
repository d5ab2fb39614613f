// The editing model: text patches, editability, change analysis,
// incremental simulation, undo, views.
#include "core/session/session.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <map>
#include <set>
#include <sstream>

namespace asgard::session {
namespace {

const char* kBall = "shape_set ball -desc {-sub {-pos {0 0 0} -sphere 0.5}}\n";

void ExpectSameWaveforms(const solver::Simulation& a, const solver::Simulation& b) {
  ASSERT_EQ(a.component_count(), b.component_count());
  for (int c = 0; c < a.component_count(); ++c) {
    const auto& wa = a.component(c).waveform();
    const auto& wb = b.component(c).waveform();
    ASSERT_EQ(wa.size(), wb.size()) << "component " << c;
    const size_t bytes = wa.variable_count() * sizeof(double);
    for (int k = 0; k < wa.size(); ++k) {
      ASSERT_EQ(wa.time(k), wb.time(k)) << "component " << c << " sample " << k;
      ASSERT_EQ(std::memcmp(wa.x(k), wb.x(k), bytes), 0) << "component " << c << " sample " << k;
      ASSERT_EQ(std::memcmp(wa.f(k), wb.f(k), bytes), 0) << "component " << c << " sample " << k;
    }
  }
}

TEST(GraphicalEdit, MovingAStandaloneBodyChangesOnlyTheDigitsOfItsLiteral) {
  const std::string text = std::string(kBall) +
                           "# a comment\n"
                           "body b1 -shape ball   -init_pos {1 2 3}   ;# keep this comment\n"
                           "body b2 -shape ball -init_pos {4 5 6}\n";
  Session s(text);
  const auto r = s.SetParameter("b1", "init_pos", {1.25, 2, 3});
  ASSERT_TRUE(r.ok) << r.error;
  // The smallest change: ".25" inserted after the "1" of {1 2 3}.
  ASSERT_EQ(r.edits.size(), 1u);
  EXPECT_EQ(r.edits[0].text, ".25");
  EXPECT_EQ(r.edits[0].begin, r.edits[0].end);
  EXPECT_EQ(r.edits[0].begin, static_cast<int>(text.find("{1 2 3}")) + 2);
  EXPECT_EQ(r.edits[0].line, 3);
  std::string expected = text;
  expected.replace(expected.find("{1 2 3}") + 1, 1, "1.25");
  EXPECT_EQ(s.text(), expected);
  EXPECT_EQ(s.scene().FindBody("b1")->init_pos[0], 1.25);
}

TEST(GraphicalEdit, AnOptionNotWrittenYetIsAppendedToItsCommand) {
  Session s(std::string(kBall) + "body b1 -shape ball\n");
  ASSERT_TRUE(s.SetParameter("b1", "init_dpos", {0, 1, 0}).ok);
  EXPECT_EQ(s.text(), std::string(kBall) + "body b1 -shape ball -init_dpos {0 1 0}\n");
}

TEST(GraphicalEdit, ForceVectorsAndOffsetsBecomeTheirWords) {
  Session s(std::string(kBall) +
            "body b1 -shape ball\nforce -body b1 -x 0 -y -1 -z 0 -offset {0 0.5 0}\n");
  ASSERT_TRUE(s.SetParameter("force#0", "vector", {0, -9.81, 0}).ok);
  ASSERT_TRUE(s.SetParameter("force#0", "offset", {0.5, 0.5, 0}).ok);
  EXPECT_EQ(s.text(),
            std::string(kBall) +
                "body b1 -shape ball\nforce -body b1 -x 0 -y -9.81 -z 0 -offset {0.5 0.5 0}\n");
}

TEST(GraphicalEdit, TrajectoryKnotsKeepTheirListShape) {
  Session s(std::string(kBall) +
            "body b -shape ball\n"
            "trajectory tr -points {{0 0 0 0} {1 1 0 0}} -body b -state pos\n");
  ASSERT_TRUE(s.SetParameter("tr", "points", {0, 0, 0, 0, 1.5, 1, 2, 0}).ok);
  EXPECT_NE(s.text().find("-points {{0 0 0 0} {1.5 1 2 0}}"), std::string::npos) << s.text();
  ASSERT_EQ(s.scene().trajectories[0].knots.size(), 2u);
  EXPECT_EQ(s.scene().trajectories[0].knots[1].t, 1.5);
  EXPECT_FALSE(s.SetParameter("tr", "points", {0, 1, 2}).ok);
}

TEST(Editability, LoopsAndExpressionsAreReadOnlyWithTheirReason) {
  Session s(std::string(kBall) +
            "foreach i {1 2 3} { body obj_$i -shape ball -init_pos \"$i 0 0\" }\n"
            "set y 2\n"
            "body ex -shape ball -init_pos [list 0 $y 0]\n"
            "body f -shape ball -init_pos {0 0 1}\n");
  auto r = s.SetParameter("obj_2", "init_pos", {0, 0, 0});
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("made in a loop"), std::string::npos) << r.error;
  r = s.SetParameter("ex", "init_pos", {0, 0, 0});
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("computed by an expression"), std::string::npos) << r.error;
  bool found = false;
  for (const auto& p : s.Parameters()) {
    if (p.element == "f" && p.param == "init_pos") {
      found = true;
      EXPECT_TRUE(p.editable);
      EXPECT_TRUE(p.span.known());
    }
    if (p.element == "obj_1" && p.param == "init_pos") {
      EXPECT_EQ(p.reason, "made in a loop");
    }
  }
  EXPECT_TRUE(found);
}

TEST(Editability, ElementsSayWhetherTheirCommandCanTakeANewOption) {
  Session s(std::string(kBall) +
            "foreach i {1 2} { body obj_$i -shape ball }\n"
            "body f -shape ball\n"
            "lightsource -type point -pos {0 0 5}\n");
  std::map<std::string, ElementInfo> by_key;
  for (const auto& e : s.ElementInfos()) by_key[e.element] = e;
  ASSERT_EQ(by_key.count("f"), 1u);
  EXPECT_TRUE(by_key["f"].editable);
  EXPECT_EQ(by_key["f"].kind, scene::ElementKind::kBody);
  EXPECT_FALSE(by_key["obj_1"].editable);
  EXPECT_EQ(by_key["obj_1"].reason, "made in a loop");
  ASSERT_EQ(by_key.count("lightsource#0"), 1u);
  EXPECT_TRUE(by_key["lightsource#0"].editable);
  // f has no -init_rot yet: an editable element takes it (appended), a
  // read-only one refuses with the same reason.
  EXPECT_TRUE(s.SetParameter("f", "init_rot", {0, 0, 0.5}).ok);
  const auto r = s.SetParameter("obj_2", "init_rot", {0, 0, 0.5});
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("made in a loop"), std::string::npos) << r.error;
}

Change ChangeOf(const std::vector<ElementChange>& changes, scene::ElementKind kind,
                const std::string& name, int new_index = -1) {
  for (const auto& c : changes)
    if (c.kind == kind && c.name == name && (new_index < 0 || c.new_index == new_index))
      return c.change;
  ADD_FAILURE() << "no change record for " << name;
  return Change::kUnchanged;
}

TEST(ChangeAnalysis, RenameReorderAddAndDeleteAreClassified) {
  const std::string base = std::string(kBall) +
                           "body a -shape ball -init_pos {0 0 0}\n"
                           "body b -shape ball -init_pos {1 0 0}\n";
  Session s(base);
  auto ch = s.UpdateText(std::string(kBall) +
                         "body z -shape ball -init_pos {0 0 0}\n"
                         "body b -shape ball -init_pos {1 0 0}\n");
  EXPECT_EQ(ChangeOf(ch, scene::ElementKind::kBody, "z"), Change::kRenamed);
  EXPECT_EQ(ChangeOf(ch, scene::ElementKind::kBody, "b"), Change::kUnchanged);
  ch = s.UpdateText(std::string(kBall) +
                    "body b -shape ball -init_pos {1 0 0}\n"
                    "body z -shape ball -init_pos {0 0 0}\n");
  EXPECT_EQ(ChangeOf(ch, scene::ElementKind::kBody, "z"), Change::kUnchanged);
  EXPECT_EQ(ChangeOf(ch, scene::ElementKind::kBody, "b"), Change::kUnchanged);
  ch = s.UpdateText(std::string(kBall) + "body b -shape ball -init_pos {1 0 0}\n" +
                    "body c -shape ball\n");
  EXPECT_EQ(ChangeOf(ch, scene::ElementKind::kBody, "z"), Change::kRemoved);
  EXPECT_EQ(ChangeOf(ch, scene::ElementKind::kBody, "c"), Change::kAdded);
  ch = s.UpdateText(std::string(kBall) +
                    "body b -shape ball -init_pos {2 0 0}\nbody c -shape ball\n");
  EXPECT_EQ(ChangeOf(ch, scene::ElementKind::kBody, "b"), Change::kModified);
}

TEST(ChangeAnalysis, EditingOneOfTwoIdenticalUnnamedForcesIsAttributedToIt) {
  const std::string base = std::string(kBall) +
                           "body a -shape ball\n"
                           "force -body a -x 0 -y -1 -z 0\n"
                           "force -body a -x 0 -y -1 -z 0\n";
  Session s(base);
  std::string edited = base;
  edited.replace(edited.rfind("-y -1"), 5, "-y -2");
  const auto ch = s.UpdateText(edited);
  int modified = -1, unchanged = -1;
  for (const auto& c : ch) {
    if (c.kind != scene::ElementKind::kForce) continue;
    if (c.change == Change::kModified) modified = c.new_index;
    if (c.change == Change::kUnchanged) unchanged = c.new_index;
  }
  EXPECT_EQ(modified, 1);
  EXPECT_EQ(unchanged, 0);
  // And the other way round.
  std::string first = base;
  first.replace(first.find("-y -1"), 5, "-y -3");
  Session t(base);
  for (const auto& c : t.UpdateText(first)) {
    if (c.kind == scene::ElementKind::kForce) {
      EXPECT_EQ(c.change, c.new_index == 0 ? Change::kModified : Change::kUnchanged);
    }
  }
}

std::string Balls(int n) {
  std::string s = kBall;
  for (int i = 0; i < n; ++i)
    s += "body b" + std::to_string(i) + " -shape ball -init_pos {" + std::to_string(3 * i) +
         " 0 0} -init_dpos {0 1 0}\nforce -body b" + std::to_string(i) + " -x 0 -y {-9.81 * b" +
         std::to_string(i) + ".mass} -z {-b" + std::to_string(i) + ".z}\n";
  return s + "simulator -finish 2\n";
}

TEST(Incremental, MovingOneOfManyBodiesResetsOnlyItsComponentsAndMatchesFromScratch) {
  Session s(Balls(12));
  ASSERT_TRUE(s.Simulate());
  EXPECT_TRUE(s.last_stats().rebuilt);
  ASSERT_TRUE(s.SetParameter("b7", "init_pos", {21, 0.5, 0}).ok);
  ASSERT_TRUE(s.Simulate());
  const auto stats = s.last_stats();
  EXPECT_FALSE(stats.rebuilt);
  // Exactly the components holding b7's variables restart (nothing reads them).
  const auto& eq = *s.run()->equations;
  const auto& sim = *s.run()->simulation;
  std::set<int> own;
  for (int k = 0; k < physics::kBodySlots; ++k)
    own.insert(sim.component_of(eq.bodies[eq.FindBody("b7")].first_var + k));
  EXPECT_EQ(stats.components_reset, static_cast<int>(own.size()));
  EXPECT_EQ(own.size(), 1u);  // a free body is one fused component
  Session scratch(s.text());
  ASSERT_TRUE(scratch.Simulate());
  // The re-simulation took exactly the steps a from-scratch run spends on
  // those components, and no others.
  long own_steps = 0;
  for (int c : own) own_steps += scratch.run()->simulation->component(c).counters().steps;
  EXPECT_EQ(stats.steps, own_steps);
  EXPECT_LT(stats.steps, scratch.run()->simulation->totals().steps / 6);
  ExpectSameWaveforms(*s.run()->simulation, *scratch.run()->simulation);
}

TEST(Incremental, AnEditThatChangesWhoCollidesWithWhomMatchesFromScratch) {
  const std::string base = std::string(kBall) +
                           "body a -shape ball -mass 1 -init_pos {0 0 0} -init_dpos {1 0 0}\n"
                           "body b -shape ball -mass 1 -init_pos {3 0 0}\n"
                           "body c -shape ball -mass 1 -init_pos {3 5 0}\n"
                           "body idle -shape ball -init_pos {0 -9 0} -init_drot {0 0 1}\n"
                           "simulator -finish 4\n";
  Session s(base);
  ASSERT_TRUE(s.Simulate());
  ASSERT_EQ(s.run()->collisions->impacts().size(), 1u);  // a hits b
  // Aim a at c instead: a now misses b and hits c.
  ASSERT_TRUE(s.SetParameter("a", "init_dpos", {1, 5.0 / 3.0, 0}).ok);
  ASSERT_TRUE(s.Simulate());
  EXPECT_FALSE(s.last_stats().rebuilt);
  Session scratch(s.text());
  ASSERT_TRUE(scratch.Simulate());
  const auto& got = s.run()->collisions->impacts();
  const auto& want = scratch.run()->collisions->impacts();
  ASSERT_EQ(got.size(), want.size());
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0].b, 2);  // c
  EXPECT_EQ(got[0].t, want[0].t);
  ExpectSameWaveforms(*s.run()->simulation, *scratch.run()->simulation);
  // The idle body was never touched.
  const auto& sim = *s.run()->simulation;
  const int idle = s.run()->equations->bodies[3].first_var;
  EXPECT_EQ(sim.component(sim.component_of(idle + physics::kQw)).counters().truncated_steps, 0);
}

TEST(Incremental, EditingOneBodysForceKeepsEveryOtherComponentAndMatchesFromScratch) {
  Session s(Balls(8));
  ASSERT_TRUE(s.Simulate());
  // Change b3's force law (an equation, not an initial value).
  std::string text = s.text();
  const std::string old_force = "-z {-b3.z}";
  text.replace(text.find(old_force), old_force.size(), "-z {-4 * b3.z}");
  s.UpdateText(text);
  ASSERT_TRUE(s.Simulate());
  const auto stats = s.last_stats();
  EXPECT_TRUE(stats.rebuilt);  // the equations were formed anew ...
  // ... but only b3's (fused) component was recomputed, at exactly the steps
  // a from-scratch run spends on it.
  EXPECT_EQ(stats.components_reset, 1);
  Session scratch(s.text());
  ASSERT_TRUE(scratch.Simulate());
  ExpectSameWaveforms(*s.run()->simulation, *scratch.run()->simulation);
  const auto& se = *scratch.run()->equations;
  const auto& ss = *scratch.run()->simulation;
  const int c3 = ss.component_of(se.bodies[se.FindBody("b3")].first_var + physics::kZ);
  EXPECT_EQ(stats.steps, ss.component(c3).counters().steps);
  EXPECT_LT(stats.steps, ss.totals().steps);
}

// A stack of two cubes settling on a floor: its resting events jump a whole
// island (Impact::bodies, ::slow).  Removing a body declared before them
// renumbers every body; the events carried over must be renumbered too.
TEST(Incremental, RestingEventsCarriedOverAreRenumberedWithTheirIsland) {
  const std::string stack =
      "shape_set cube -desc {-sub {-box {1 1 1}}}\n"
      "shape_set floor -desc {-sub {-box {10 1 10}}}\n"
      "body floor -shape floor -static 1 -init_pos {0 -0.5 0} -restitution 0 -friction 0.5\n"
      "body c1 -shape cube -mass 1 -init_pos {0 0.6 0} -restitution 0 -friction 0.5\n"
      "force -body c1 -y {-9.81 * c1.mass} -gravitational 1\n"
      "body c2 -shape cube -mass 1 -init_pos {0 1.8 0} -restitution 0 -friction 0.5\n"
      "force -body c2 -y {-9.81 * c2.mass} -gravitational 1\n"
      "simulator -finish 1\n";
  const std::string idle = "body idle -shape cube -init_pos {8 5 0} -ct 0\n";
  Session s(idle + stack);
  ASSERT_TRUE(s.Simulate());
  s.UpdateText(stack);
  ASSERT_TRUE(s.Simulate());
  Session scratch(stack);
  ASSERT_TRUE(scratch.Simulate());
  const auto& got = s.run()->collisions->impacts();
  const auto& want = scratch.run()->collisions->impacts();
  ASSERT_EQ(got.size(), want.size());
  bool island = false;
  for (size_t i = 0; i < got.size(); ++i) {
    EXPECT_EQ(got[i].t, want[i].t) << i;
    EXPECT_EQ(got[i].a, want[i].a) << i;
    EXPECT_EQ(got[i].b, want[i].b) << i;
    EXPECT_EQ(got[i].bodies, want[i].bodies) << i;
    EXPECT_EQ(got[i].slow, want[i].slow) << i;
    island = island || want[i].bodies.size() > 2;
  }
  EXPECT_TRUE(island);  // the scene does make events of a whole island
  ExpectSameWaveforms(*s.run()->simulation, *scratch.run()->simulation);
}

// Unit cubes c0, c1, … of mass 1 (friction 0.5) under gravity on a static
// floor of the given side whose top is y = 0, and a cube `idle` flying at
// (idle_x, idle_y, 0) along z, far from them; the run lasts t1.
struct PlacedCube {
  double p[3], r[3];
};
std::string CubesAndAFlyingCube(double side, double floor_restitution,
                                const std::vector<PlacedCube>& cubes, double restitution,
                                double idle_x, double idle_y, double t1) {
  std::ostringstream text;
  text.precision(17);
  text << "shape_set cube -desc {-sub {-box {1 1 1}}}\n"
       << "shape_set floor -desc {-sub {-box {" << side << " 1 " << side << "}}}\n"
       << "body floor -shape floor -static 1 -init_pos {0 -0.5 0} -restitution "
       << floor_restitution << " -friction 0.5\n";
  for (size_t i = 0; i < cubes.size(); ++i) {
    const PlacedCube& c = cubes[i];
    text << "body c" << i << " -shape cube -mass 1 -init_pos {" << c.p[0] << " " << c.p[1] << " "
         << c.p[2] << "} -init_rot {" << c.r[0] << " " << c.r[1] << " " << c.r[2]
         << "} -restitution " << restitution << " -friction 0.5\n"
         << "force -body c" << i << " -y {-9.81 * c" << i << ".mass} -gravitational 1\n";
  }
  text << "body idle -shape cube -init_pos {" << idle_x << " " << idle_y
       << " 0} -init_dpos {0 0 1}\n"
       << "simulator -finish " << t1 << "\n";
  return text.str();
}

// Runs `before`, edits it into `after` (which computes `reset` components
// afresh: every other body and its events are carried over), and checks the
// edited run against a run of `after` from scratch: the same events, the
// same holds, the same waveforms bit for bit.  Returns the scratch run's
// events and the pairs they hold in all.
void ExpectCarriedEditMatchesScratch(const std::string& before, const std::string& after,
                                     size_t* events, size_t* held, int reset = 1) {
  Session s(before);
  ASSERT_TRUE(s.Simulate());
  s.UpdateText(after);
  ASSERT_TRUE(s.Simulate());
  EXPECT_EQ(s.last_stats().components_reset, reset);
  Session scratch(after);
  ASSERT_TRUE(scratch.Simulate());
  const auto& got = s.run()->collisions->impacts();
  const auto& want = scratch.run()->collisions->impacts();
  ASSERT_EQ(got.size(), want.size());
  *events = want.size();
  *held = 0;
  for (size_t i = 0; i < got.size(); ++i) {
    ASSERT_EQ(got[i].t, want[i].t) << i;
    ASSERT_EQ(got[i].bodies, want[i].bodies) << i;
    ASSERT_EQ(got[i].held, want[i].held) << i;
    *held += want[i].held.size();
  }
  ExpectSameWaveforms(*s.run()->simulation, *scratch.run()->simulation);
}

// A stack of cubes at rest on a floor holds its contact pairs from one
// resting event to the next (Impact::held).  An edit elsewhere carries the
// stack's whole train of events over into the new run, later ones included:
// a window's holds must be read from the events before its end, as the run
// from scratch read them, not from the stack's events later in the run
// (which held nothing there, so that a held pair was searched and struck).
TEST(Incremental, CarriedRestingEventsHoldTheirPairsAsInAFreshRun) {
  std::vector<PlacedCube> stack;
  for (int i = 0; i < 3; ++i) stack.push_back({{0.1 * i, 0.52 + 1.04 * i, 0}, {0, 0, 0}});
  auto scene = [&](double idle_x) { return CubesAndAFlyingCube(10, 0, stack, 0.2, idle_x, 5, 2); };
  size_t events = 0, held = 0;
  ExpectCarriedEditMatchesScratch(scene(8), scene(8.5), &events, &held);
  EXPECT_GT(held, 0u);  // the stack's events do hold pairs
}

// The contact suite's pile10: ten cubes dropped at random rotations.
std::vector<PlacedCube> Pile10() {
  return {{{0.0843786876887988, 1.0, 0.0318169783229551},
           {-0.5348703918322664, -1.403979560352818, -1.1948569917029368}},
          {{-0.05560118863556517, 2.8, -0.03611489024417863},
           {-0.5435209038497093, 0.15605067325681432, 0.7256989779148761}},
          {{0.006990063414279435, 4.6, -0.05050129246235571},
           {1.865308285261401, -1.3943108729963436, -1.1241612083528634}},
          {{-0.04109868531999997, 6.4, -0.030934060694065055},
           {1.9653402002288445, -1.0936610058393152, 1.9035751053720142}},
          {{-0.07763761315166487, 8.2, -0.06539918207050716},
           {1.1978968384676536, 1.6798865883377436, 0.13725283338961836}},
          {{-0.08068045553483105, 10.0, -0.07647553725628409},
           {-0.9396855815714225, 0.873859710229568, -1.3183911449070433}},
          {{0.09656229232845537, 11.8, -0.09463910916432045},
           {-1.9537414892142972, 1.6610036595373883, 1.5338881776961322}},
          {{-0.08371301825426, 13.6, 0.03935076368078197},
           {0.7599226236263132, 1.9336342936867266, 0.618318614726773}},
          {{-0.06203309379743289, 15.4, 0.06309845218038243},
           {-0.5499732658663434, -1.8405423080067909, 1.984571818556561}},
          {{0.03603485305788018, 17.2, 0.04706833606063876},
           {0.6448384630138015, -0.6915170087150595, 0.9218643623810996}}};
}

// A pile of ten cubes dropped at random rotations (the contact suite's
// pile10), and a cube flying far from it that an edit moves.  Two more
// things once made the edited run differ from the run from scratch: a
// search over a window read the bodies' poses as an event on the window's
// end (carried over, not yet found by the run from scratch) had left them;
// and a floor's pair was searched from the floor's latest event in the
// window, which depended on the order the window's events were found in.
TEST(Incremental, APileCarriedOverMatchesARunFromScratch) {
  const std::vector<PlacedCube> cubes = Pile10();
  auto scene = [&](double idle_x) {
    return CubesAndAFlyingCube(60, 0.5, cubes, 0.5, idle_x, 40, 5);
  };
  size_t events = 0, held = 0;
  ExpectCarriedEditMatchesScratch(scene(30), scene(31), &events, &held);
  EXPECT_GT(events, 500u);  // a settling pile's train of events, carried over
}

// The same pile, and a cube dropped onto it from a height an edit changes
// (the edit keeps the pile's events, and the dropped cube strikes it).  An
// event kept is taken as found only when the window check reaches it in
// time order (an impact of the dropped cube before it comes first and voids
// it), and a pile cube about to be searched against the dropped one, or to
// join an island with it, is cut back to the step before its next kept
// event, so that it has the motion the run from scratch has at that point.
// Before, a pair was searched from a kept event that the new impact came
// before, and the edited run missed it (1 723 events against 1 724).
TEST(Incremental, ACubeDroppedOntoACarriedPileMatchesARunFromScratch) {
  const std::string pile = CubesAndAFlyingCube(60, 0.5, Pile10(), 0.5, 30, 40, 5);
  auto scene = [&](double height) {
    std::ostringstream text;
    text << pile << "body drop -shape cube -mass 1 -init_pos {0.05 " << height
         << " 0.02} -init_rot {0.3 0.2 0.1} -restitution 0.5 -friction 0.5\n"
         << "force -body drop -y {-9.81 * drop.mass} -gravitational 1\n";
    return text.str();
  };
  size_t events = 0, held = 0;
  ExpectCarriedEditMatchesScratch(scene(22), scene(21), &events, &held);
  EXPECT_GT(events, 500u);  // a settling pile's train of events, carried over
}

// Balls in a closed box, no gravity: a ball made faster strikes others,
// which strike others in turn.  Each ball flies in one step from one
// impact to the next, so a kept impact's landing step reaches back to the
// ball's impact before; a ball recomputed from the edit on, whose kept
// impacts are voided one by one, and the balls it meets are cut back to
// those steps' starts before they are searched.  (A ball recomputed up to
// one impact once kept the landing step of its next, and was searched
// with it: an impact at t = 1.748 moved in its last digits.)
TEST(Incremental, ABallMadeFasterInABoxMatchesARunFromScratch) {
  auto scene = [](double speed) {
    std::ostringstream text;
    text.precision(17);
    text << kBall << "shape_set wall -desc {-sub {-box {1 8 8}}}\n";
    const char* axes[3] = {"{0 0 0}", "{0 0 1.5707963267948966}", "{0 1.5707963267948966 0}"};
    for (int k = 0; k < 6; ++k) {
      double p[3] = {0, 0, 0};
      p[k / 2] = k % 2 ? 3.5 : -3.5;
      text << "body w" << k << " -shape wall -static 1 -init_pos {" << p[0] << " " << p[1] << " "
           << p[2] << "} -init_rot " << axes[k / 2] << " -restitution 1 -friction 0\n";
    }
    unsigned state = 7;
    auto next = [&]() {
      state = state * 1103515245u + 12345u;
      return static_cast<double>((state >> 8) & 0xffff) / 65536.0 - 0.5;
    };
    for (int i = 0; i < 27; ++i) {
      const double v[3] = {4 * next(), 4 * next(), 4 * next()};
      text << "body b" << i << " -shape ball -mass 1 -init_pos {" << (i % 3 - 1) * 2 + 0.3 * next()
           << " " << (i / 3 % 3 - 1) * 2 + 0.3 * next() << " " << (i / 9 - 1) * 2 + 0.3 * next()
           << "} -init_dpos {" << (i == 4 ? speed : v[0]) << " " << v[1] << " " << v[2]
           << "} -restitution 1 -friction 0\n";
    }
    text << "simulator -finish 4\n";
    return text.str();
  };
  size_t events = 0, held = 0;
  ExpectCarriedEditMatchesScratch(scene(1.5), scene(1.8), &events, &held);
  EXPECT_GT(events, 40u);
}

// A change to what the collision monitor reads of a body, and not to its
// equations (its bounce, its friction, a static body's shape), keeps its
// motion up to its first event and voids its events from there.  Before,
// such a body counted as carried over with all its events, which had been
// answered with the old coefficients (and a floor narrowed under a pile
// still held it up).
TEST(Incremental, ABodysBounceFrictionOrShapeEditedVoidsItsEventsAsInAFreshRun) {
  const std::vector<PlacedCube> cubes = {{{0, 0.6, 0}, {0.2, 0.1, 0}},
                                         {{3, 1.5, 0}, {0.3, 0.4, 0.1}},
                                         {{3.2, 3.5, 0.1}, {-0.2, 0.5, 0.3}}};
  const std::string base = CubesAndAFlyingCube(20, 0.5, cubes, 0.5, 8, 5, 2);
  // `from` replaced by `to` in the first line that starts with `line`.
  auto edit = [&](const std::string& line, const std::string& from, const std::string& to) {
    std::string text = base;
    const size_t begin = text.find(line), at = text.find(from, begin);
    EXPECT_NE(begin, std::string::npos);
    EXPECT_LT(at, text.find('\n', begin));
    return text.replace(at, from.size(), to);
  };
  size_t events = 0, held = 0;
  ExpectCarriedEditMatchesScratch(base, edit("body c1 ", "-restitution 0.5", "-restitution 0.9"),
                                  &events, &held, 0);
  EXPECT_GT(events, 10u);
  ExpectCarriedEditMatchesScratch(base, edit("body c1 ", "-friction 0.5", "-friction 0.1"), &events,
                                  &held, 0);
  ExpectCarriedEditMatchesScratch(base, edit("shape_set floor", "{20 1 20}", "{7 1 20}"), &events,
                                  &held, 0);
}

TEST(Incremental, ImpactsBetweenUnchangedBodiesAreKeptAfterAnEquationEdit) {
  const std::string base = std::string(kBall) +
                           "body a -shape ball -mass 1 -init_pos {0 0 0} -init_dpos {1 0 0}\n"
                           "body b -shape ball -mass 1 -init_pos {3 0 0}\n"
                           "body c -shape ball -mass 1 -init_pos {0 10 0}\n"
                           "force -body c -x 0 -y 0 -z 0\n"
                           "simulator -finish 5\n";
  Session s(base);
  ASSERT_TRUE(s.Simulate());
  ASSERT_EQ(s.run()->collisions->impacts().size(), 1u);  // a hits b
  std::string text = s.text();
  text.replace(text.find("force -body c -x 0"), 18, "force -body c -x 1");
  s.UpdateText(text);
  ASSERT_TRUE(s.Simulate());
  // a and b were carried over with their impact; only c's x was recomputed.
  EXPECT_EQ(s.last_stats().components_reset, 1);  // c's {x, dx}
  Session scratch(s.text());
  ASSERT_TRUE(scratch.Simulate());
  const auto& got = s.run()->collisions->impacts();
  const auto& want = scratch.run()->collisions->impacts();
  ASSERT_EQ(got.size(), want.size());
  for (size_t i = 0; i < got.size(); ++i) {
    EXPECT_EQ(got[i].t, want[i].t);
    EXPECT_EQ(got[i].a, want[i].a);
    EXPECT_EQ(got[i].b, want[i].b);
  }
  ExpectSameWaveforms(*s.run()->simulation, *scratch.run()->simulation);
}

TEST(Undo, UndoingAGraphicalEditRestoresTextAndResultsExactly) {
  const std::string base = Balls(3) + "# trailing comment\n";
  Session s(base);
  ASSERT_TRUE(s.Simulate());
  Session original(base);
  ASSERT_TRUE(original.Simulate());
  ASSERT_TRUE(s.SetParameter("b1", "init_pos", {3.5, 0, 0}).ok);
  ASSERT_TRUE(s.Simulate());
  ASSERT_TRUE(s.Undo());
  EXPECT_EQ(s.text(), base);
  ASSERT_TRUE(s.Simulate());
  EXPECT_FALSE(s.last_stats().rebuilt);
  ExpectSameWaveforms(*s.run()->simulation, *original.run()->simulation);
  ASSERT_TRUE(s.Redo());
  EXPECT_NE(s.text().find("{3.5 0 0}"), std::string::npos);
  // A text edit and a graphical edit share one history.
  s.UpdateText(s.text() + "body extra -shape ball\n");
  ASSERT_TRUE(s.Undo());
  EXPECT_NE(s.text().find("{3.5 0 0}"), std::string::npos);
  ASSERT_TRUE(s.Undo());
  EXPECT_EQ(s.text(), base);
  EXPECT_FALSE(s.Undo());
}

TEST(Undo, TheStepsOfOneDragAreOneUndoStep) {
  const std::string base = Balls(3);
  Session s(base);
  ASSERT_TRUE(s.Simulate());
  // A drag: many edits of one parameter, then the simulation at its end.
  for (double x : {1.0, 1.5, 2.0, 2.5}) ASSERT_TRUE(s.SetParameter("b1", "init_pos", {x, 0, 0}).ok);
  ASSERT_TRUE(s.Simulate());
  const std::string after_first = s.text();
  // A second drag of the same handle is its own step, and so is a drag of
  // another parameter right after it (no simulation between).
  for (double x : {3.0, 3.5}) ASSERT_TRUE(s.SetParameter("b1", "init_pos", {x, 0, 0}).ok);
  const std::string after_second = s.text();
  ASSERT_TRUE(s.SetParameter("b1", "init_dpos", {0, 1, 0}).ok);
  ASSERT_TRUE(s.SetParameter("b1", "init_dpos", {0, 2, 0}).ok);
  ASSERT_TRUE(s.Undo());
  EXPECT_EQ(s.text(), after_second);
  ASSERT_TRUE(s.Undo());
  EXPECT_EQ(s.text(), after_first);
  ASSERT_TRUE(s.Undo());
  EXPECT_EQ(s.text(), base);
  EXPECT_FALSE(s.Undo());
  // After an undo the next edit starts a new step (redo history dropped).
  ASSERT_TRUE(s.SetParameter("b1", "init_pos", {9, 0, 0}).ok);
  ASSERT_TRUE(s.SetParameter("b1", "init_pos", {9.5, 0, 0}).ok);
  EXPECT_FALSE(s.CanRedo());
  ASSERT_TRUE(s.Undo());
  EXPECT_EQ(s.text(), base);
}

struct RecordingView : SessionView {
  std::string text;
  int edits = 0, scenes = 0, simulations = 0;
  void TextChanged(const std::vector<TextEdit>& e, const std::string&) override {
    // Apply the edits to our copy, as a language view would.
    for (auto it = e.rbegin(); it != e.rend(); ++it)
      text.replace(it->begin, it->end - it->begin, it->text);
    edits += static_cast<int>(e.size());
  }
  void SceneChanged(const std::vector<ElementChange>&) override { ++scenes; }
  void Simulated() override { ++simulations; }
};

TEST(Views, EveryViewIsNotifiedAndKeepsItsTextInStep) {
  const std::string base = Balls(2);
  Session s(base);
  RecordingView v1, v2;
  v1.text = v2.text = base;
  s.AddView(&v1);
  const int id2 = s.AddView(&v2);
  ASSERT_TRUE(s.SetParameter("b0", "init_pos", {0, 1, 0}).ok);
  s.UpdateText(s.text() + "body c -shape ball\n");
  ASSERT_TRUE(s.Simulate());
  EXPECT_EQ(v1.text, s.text());
  EXPECT_EQ(v2.text, s.text());
  EXPECT_EQ(v1.scenes, 2);
  EXPECT_EQ(v1.simulations, 1);
  s.RemoveView(id2);
  ASSERT_TRUE(s.SetParameter("b1", "init_pos", {0, 2, 0}).ok);
  EXPECT_EQ(v1.text, s.text());
  EXPECT_NE(v2.text, s.text());
}

TEST(CreateDelete, CommandsAreInsertedAfterTheirKindAndRemovedWithTheirLine) {
  const std::string base = std::string(kBall) +
                           "body a -shape ball\n"
                           "force -body a -x 0 -y -1 -z 0\n"
                           "simulator -finish 1\n";
  Session s(base);
  ASSERT_TRUE(s.CreateElement("force -body a -x 1 -y 0 -z 0").ok);
  EXPECT_EQ(s.text(), std::string(kBall) +
                          "body a -shape ball\n"
                          "force -body a -x 0 -y -1 -z 0\n"
                          "force -body a -x 1 -y 0 -z 0\n"
                          "simulator -finish 1\n");
  EXPECT_EQ(s.scene().forces.size(), 2u);
  ASSERT_TRUE(s.DeleteElement("force#0").ok);
  EXPECT_EQ(s.text(), std::string(kBall) +
                          "body a -shape ball\n"
                          "force -body a -x 1 -y 0 -z 0\n"
                          "simulator -finish 1\n");
  EXPECT_FALSE(s.DeleteElement("force#7").ok);
}

TEST(CreateDelete, DeletingABodyDeletesWhatNamesItAsOneUndoStep) {
  const std::string base = std::string(kBall) +
                           "body a -shape ball\n"
                           "body b -shape ball -init_pos {2 0 0}\n"
                           "trajectory tr -points {{0 0 0 0} {1 0 1 0}} -body a -state pos\n"
                           "trajectory free -points {{0 3 0 0} {1 3 1 0}}\n"
                           "link -body1 a -offset1 {0.5 0 0} -body2 b -tightness 10\n"
                           "link -body1 b -trajectory tr -tightness 10\n"
                           "link -body1 b -trajectory free -tightness 10\n"
                           "force -body a -x 0 -y -1 -z 0; force -body b -x 0 -y -1 -z 0\n"
                           "torque -body a -x 0 -y 0 -z 1\n"
                           "view chase -follow a\n"
                           "view along -trajectory tr\n"
                           "view side -rot {0 1.5 0}\n"
                           "simulator -finish 1\n";
  Session s(base);
  ASSERT_FALSE(s.scene().has_errors());
  // What the editor shows before it asks: each element's deleted_with is
  // what deleting it removes, in the same order.
  std::map<std::string, std::vector<std::string>> with;
  for (const ElementInfo& e : s.ElementInfos()) with[e.element] = e.deleted_with;
  EXPECT_EQ(with["free"], (std::vector<std::string>{"link#2"}));
  EXPECT_TRUE(with["b"].size() == 4 && with["side"].empty() && with["force#0"].empty());
  const EditResult r = s.DeleteElement("a");
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_EQ(r.removed, with["a"]);
  // The body, and what names it: its force, torque, link, trajectory and
  // view, and through the trajectory the link and view along it.
  EXPECT_EQ(s.text(), std::string(kBall) +
                          "body b -shape ball -init_pos {2 0 0}\n"
                          "trajectory free -points {{0 3 0 0} {1 3 1 0}}\n"
                          "link -body1 b -trajectory free -tightness 10\n"
                          "force -body b -x 0 -y -1 -z 0\n"
                          "view side -rot {0 1.5 0}\n"
                          "simulator -finish 1\n");
  EXPECT_FALSE(s.scene().has_errors());
  std::vector<std::string> removed = r.removed;
  std::sort(removed.begin(), removed.end());
  EXPECT_EQ(removed, (std::vector<std::string>{"along", "chase", "force#0", "link#0", "link#1",
                                               "torque#0", "tr"}));
  // One undo step brings all of it back.
  ASSERT_TRUE(s.Undo());
  EXPECT_EQ(s.text(), base);
  // Deleting a trajectory takes the link and view along it.
  ASSERT_TRUE(s.DeleteElement("free").ok);
  EXPECT_EQ(s.text().find("free"), std::string::npos);
  ASSERT_TRUE(s.Undo());
  EXPECT_EQ(s.text(), base);
  // Refused (nothing changes) when something that names the body cannot be
  // deleted here.
  Session looped(std::string(kBall) +
                 "body a -shape ball\n"
                 "foreach y {-1 -2} { force -body a -x 0 -y $y -z 0 }\n");
  const std::string before = looped.text();
  const EditResult refused = looped.DeleteElement("a");
  EXPECT_FALSE(refused.ok);
  EXPECT_NE(refused.error.find("made in a loop"), std::string::npos) << refused.error;
  EXPECT_EQ(looped.text(), before);
}

TEST(CreateDelete, ABracedWordIsReplacedWholeAndADragOfItIsOneUndoStep) {
  const std::string base = "shape_set s -desc {-sub {-sphere 0.5}}\nbody a -shape s\n";
  Session s(base);
  ASSERT_TRUE(s.SetWord("s", "desc", "-sub {-sphere 0.7}").ok);
  ASSERT_TRUE(s.SetWord("s", "desc", "-sub {-sphere 0.9}").ok);
  EXPECT_EQ(s.text(), "shape_set s -desc {-sub {-sphere 0.9}}\nbody a -shape s\n");
  EXPECT_DOUBLE_EQ(s.scene().shape_sets[0].pieces[0].radius, 0.9);
  ASSERT_TRUE(s.SetWord("s", "desc", "-sub {-sphere 0.9}").ok);  // the same word: no step
  ASSERT_TRUE(s.Undo());
  EXPECT_EQ(s.text(), base);
  // Unbalanced braces would end the word early: refused, nothing changes.
  const EditResult bad = s.SetWord("s", "desc", "-sub {-sphere 1} }");
  EXPECT_FALSE(bad.ok);
  EXPECT_NE(bad.error.find("unbalanced"), std::string::npos) << bad.error;
  EXPECT_EQ(s.text(), base);
  // A word that is not braced (a variable) is read-only.
  Session v("set d {-sub {-sphere 0.5}}\nshape_set s -desc $d\n");
  EXPECT_FALSE(v.SetWord("s", "desc", "-sub {-sphere 1}").ok);
}

TEST(Errors, AScriptWithErrorsStillAppliesItsValidPart) {
  Session s(std::string(kBall) + "body a -shape ball\nbody b -shape nosuch\nsimulator -finish 1\n");
  EXPECT_TRUE(s.scene().has_errors());
  ASSERT_TRUE(s.Simulate());
  EXPECT_EQ(s.run()->equations->bodies.size(), 1u);
}

}  // namespace
}  // namespace asgard::session

namespace asgard::session {
namespace {

// The initial values a trajectory sets at the start come from the evaluated
// scene: times computed in Tcl count as literal ones; an interval that
// starts after the run's start, or ends at it, sets nothing there.
TEST(PrescribedInitials, ComeFromTheEvaluatedTrajectories) {
  Session s(
      "shape_set ball -desc {-sub {-sphere 0.5}}\n"
      "foreach n {a b c d} { body $n -shape ball }\n"
      "set late 1\n"
      "simulator -start 0.5 -finish 3\n"
      "trajectory up -points {{0 0 0 0} {2 0 1 0}} -body a -state pos -from [expr {$late - 1}]\n"
      "trajectory spin -points {{0 0 0 1} {2 0 0 2}} -body b -state drot\n"
      "trajectory later -points {{0 0 0 0} {2 0 1 0}} -body c -state pos -from $late\n"
      "trajectory done -points {{0 0 0 0} {0.5 0 1 0}} -body d -state rot\n");
  ASSERT_FALSE(s.scene().has_errors()) << s.scene().diagnostics[0].message;
  std::vector<std::string> got;
  for (const PrescribedInitial& p : s.PrescribedInitials())
    got.push_back(p.body + "." + p.param + ": " + p.reason);
  EXPECT_EQ(got,
            (std::vector<std::string>{
                "a.init_pos: trajectory up prescribes its position from t = 0 to 2",
                "a.init_dpos: trajectory up prescribes its velocity from t = 0 to 2",
                "b.init_drot: trajectory spin prescribes its angular velocity from t = 0 to 2"}));
}

}  // namespace
}  // namespace asgard::session
