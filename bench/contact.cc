// Contact suite (issue 14): piles of cubes dropped at random rotations onto a
// floor, and balls bouncing in a closed box, run by Asgard (event-driven
// impacts, resting contact, sleep) and by Bullet in double precision at
// h = 1/240 on the same bodies.  Per run: CPU time, deepest penetration of
// the floor or walls at any 30 Hz frame, kinetic energy at the end, energy
// drift (balls, restitution 1) and Asgard's collision counters.  contact.csv
//
// Penetration is measured against the floor and walls only, where it is
// exact and cheap (the lowest vertex, or a ball's surface); the tests
// (tests/solver/collision_test.cc) check body–body overlap too.
#include "bench/contact.h"

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <random>
#include <sstream>

#include "bench/harness.h"
#include "bench/model.h"
#include "bench/suites.h"
#include "core/physics/equations.h"
#include "core/pipeline/pipeline.h"
#include "core/solver/collisions.h"
#ifdef ASGARD_BENCH_SESSION
#include "core/session/session.h"
#endif

namespace asgard::bench {

namespace {

// N cubes in columns on a grid 2 apart, 1.8 above one another (no two can
// touch at the start whatever their rotations: 1.8 > √3), rotations uniform
// in each component of the rotation vector over [−2, 2].
ContactScene Pile(int n, double t1, unsigned seed) {
  ContactScene s;
  s.name = "pile" + std::to_string(n);
  s.t1 = t1;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> jitter(-0.1, 0.1), turn(-2.0, 2.0);
  const int columns = std::max(1, static_cast<int>(std::ceil(std::sqrt(n / 10.0))));
  for (int i = 0; i < n; ++i) {
    const int col = i % (columns * columns), level = i / (columns * columns);
    ContactBody b;
    b.p = {(col % columns - (columns - 1) / 2.0) * 2.0 + jitter(rng), 1.0 + 1.8 * level,
           (col / columns - (columns - 1) / 2.0) * 2.0 + jitter(rng)};
    b.rot = {turn(rng), turn(rng), turn(rng)};
    s.bodies.push_back(b);
  }
  return s;
}

// N balls (radius 0.2) on a jittered grid in a closed box (interior 10³), no
// gravity, restitution 1, no friction, random velocities of speed ~2.
ContactScene BallsInBox(int n, double t1, unsigned seed) {
  ContactScene s;
  s.name = "balls" + std::to_string(n);
  s.t1 = t1;
  s.gravity = 0.0;
  s.restitution = 1.0;
  s.friction = 0.0;
  s.box = true;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> jitter(-0.1, 0.1);
  std::normal_distribution<double> speed(0.0, 1.15);
  const int side = static_cast<int>(std::ceil(std::cbrt(static_cast<double>(n)) - 1e-9));
  const double pitch = 2 * s.box_half / side;
  for (int i = 0; i < n; ++i) {
    const int c[3] = {i % side, (i / side) % side, i / (side * side)};
    ContactBody b;
    b.cube = false;
    b.radius = 0.2;
    for (int k = 0; k < 3; ++k) b.p[k] = -s.box_half + (c[k] + 0.5 + jitter(rng)) * pitch;
    b.v = {speed(rng), speed(rng), speed(rng)};
    s.bodies.push_back(b);
  }
  return s;
}

std::string SceneText(const ContactScene& s) {
  std::ostringstream t;
  t.precision(17);
  t << "shape_set cube -desc {-sub {-box {1 1 1}}}\n"
    << "shape_set ball -desc {-sub {-sphere 0.2}}\n";
  const std::string surface =
      " -restitution " + Num(s.restitution) + " -friction " + Num(s.friction);
  if (s.box) {
    const double w = s.box_half + 0.5, l = 2 * s.box_half + 2;
    t << "shape_set wx -desc {-sub {-box {1 " << l << " " << l << "}}}\n"
      << "shape_set wy -desc {-sub {-box {" << l << " 1 " << l << "}}}\n"
      << "shape_set wz -desc {-sub {-box {" << l << " " << l << " 1}}}\n";
    const char* names[6] = {"xlo", "xhi", "ylo", "yhi", "zlo", "zhi"};
    for (int k = 0; k < 6; ++k) {
      Eigen::Vector3d p = Eigen::Vector3d::Zero();
      p[k / 2] = k % 2 ? w : -w;
      t << "body " << names[k] << " -shape w"
        << "xyz"[k / 2] << " -static 1 -init_pos {" << p.x() << " " << p.y() << " " << p.z() << "}"
        << surface << "\n";
    }
  } else {
    t << "shape_set floor -desc {-sub {-box {60 1 60}}}\n"
      << "body floor -shape floor -static 1 -init_pos {0 -0.5 0}" << surface << "\n";
  }
  for (size_t i = 0; i < s.bodies.size(); ++i) {
    const ContactBody& b = s.bodies[i];
    t << "body c" << i << " -shape " << (b.cube ? "cube" : "ball") << " -mass 1 -init_pos {"
      << b.p.x() << " " << b.p.y() << " " << b.p.z() << "} -init_rot {" << b.rot.x() << " "
      << b.rot.y() << " " << b.rot.z() << "} -init_dpos {" << b.v.x() << " " << b.v.y() << " "
      << b.v.z() << "}" << surface << "\n";
    if (s.gravity != 0)
      t << "force -body c" << i << " -y {" << -s.gravity << " * c" << i
        << ".mass} -gravitational 1\n";
  }
  t << "simulator -finish " << s.t1 << "\n";
  return t.str();
}

double KineticEnergy(const ContactBody& shape, const Eigen::Vector3d& v, const Eigen::Vector3d& w) {
  // Unit mass; a unit cube's moment 1/6, a ball's 2/5 r².
  const double moment = shape.cube ? 1.0 / 6.0 : 0.4 * shape.radius * shape.radius;
  return 0.5 * v.squaredNorm() + 0.5 * moment * w.squaredNorm();
}

ContactResult RunAsgardContact(const ContactScene& s, double timeout) {
  const std::string text = SceneText(s);
  auto iso = RunIsolated(
      [&]() -> std::string {
        pipeline::Run run = pipeline::Simulate(text);
        if (!run.ok) return "error " + run.solver_error;
        const auto& eq = *run.equations;
        const auto& sim = *run.simulation;
        double deepest = 0.0, e0 = 0.0, e1 = 0.0;
        const auto times = pipeline::FrameTimes(eq.t0, eq.t1, 30.0);
        for (size_t i = 0; i < s.bodies.size(); ++i) {
          const int b = eq.FindBody("c" + std::to_string(i));
          for (double t : times) {
            const auto f = pipeline::SampleBody(eq, sim, b, t);
            deepest = std::max(deepest, FloorOrWallPenetration(
                                            s, s.bodies[i], {f.p[0], f.p[1], f.p[2]},
                                            Eigen::Quaterniond(f.q[0], f.q[1], f.q[2], f.q[3])));
          }
          for (int end = 0; end < 2; ++end) {
            const auto f = pipeline::SampleBody(eq, sim, b, end ? eq.t1 : eq.t0);
            const Eigen::Quaterniond q(f.q[0], f.q[1], f.q[2], f.q[3]);
            // BodyFrame's w is in body coordinates; energy does not care.
            (end ? e1 : e0) +=
                KineticEnergy(s.bodies[i], {f.v[0], f.v[1], f.v[2]}, {f.w[0], f.w[1], f.w[2]});
          }
        }
        const auto& c = run.collisions->counters();
        return Pack({run.seconds, deepest, e1, std::abs(e1 - e0) / std::max(e0, 1e-300),
                     static_cast<double>(c.impacts), static_cast<double>(c.windows),
                     static_cast<double>(c.broad_phase_pairs),
                     static_cast<double>(c.narrow_phase_queries),
                     static_cast<double>(c.distance_queries)});
      },
      timeout);
  ContactResult r;
  r.status = iso.status;
  if (iso.status != "ok") return r;
  if (iso.output.rfind("error ", 0) == 0) {
    r.status = "failed";
    r.error = iso.output.substr(6);
    return r;
  }
  const auto v = Unpack(iso.output);
  if (v.size() < 9) {
    r.status = "crash";
    return r;
  }
  r.cpu = v[0];
  r.max_penetration = v[1];
  r.final_kinetic = v[2];
  r.energy_drift = v[3];
  r.impacts = v[4];
  r.windows = v[5];
  r.broad_pairs = v[6];
  r.narrow_queries = v[7];
  r.distance_queries = v[8];
  return r;
}

// The suite's scenes.  The growth of the collision counters with body
// count: balls in the box for kGrowthSpan seconds, 10 → 100 → 1000; the
// report plots the Asgard rows of the balls scenes with this t1.  The
// issue's scenes, 100 and 1000 balls for 60 s, follow (about 30 s of the
// suite's 50, most of it Bullet's); quick and full runs are the same here.
// The pile of 100 runs twice: 5 s, while it still tumbles (every code's
// final kinetic energy is far from 0 there), and 16 s, to rest.
std::vector<ContactScene> ContactScenes() {
  constexpr double kGrowthSpan = 10.0;
  return {Pile(10, 5.0, 14),
          Pile(30, 5.0, 14),
          Pile(100, 5.0, 14),
          Pile(100, 16.0, 14),
          BallsInBox(10, kGrowthSpan, 14),
          BallsInBox(100, kGrowthSpan, 14),
          BallsInBox(1000, kGrowthSpan, 14),
          BallsInBox(100, 60.0, 14),
          BallsInBox(1000, 60.0, 14)};
}

// Edits of contact scenes through the editing model (issue 14: incremental
// re-simulation stays bit-exact): each case is a scene before and after one
// edit, from one that reaches nothing else to one that reaches every body.
struct EditCase {
  std::string name, what, before, after;
};

std::vector<EditCase> EditCases() {
  std::vector<EditCase> cases;
  const ContactScene pile = Pile(30, 5.0, 14);
  auto with_cube = [&](double x, double y) {
    ContactScene s = pile;
    ContactBody b;
    b.p = {x, y, 0.1};
    b.rot = {0.3, 0.2, 0.1};
    s.bodies.push_back(b);
    return SceneText(s);
  };
  cases.push_back({"pile30_far_cube", "a cube falling far from a pile of 30 moved 1 sideways",
                   with_cube(20, 40), with_cube(21, 40)});
  cases.push_back({"pile30_dropped_cube", "a cube dropped onto a pile of 30 from 24 instead of 25",
                   with_cube(0.1, 25), with_cube(0.1, 24)});
  ContactScene moved = pile;
  moved.bodies[5].p.x() += 0.05;
  cases.push_back({"pile30_cube_moved", "a cube of a pile of 30 placed 0.05 aside", SceneText(pile),
                   SceneText(moved)});
  const ContactScene balls = BallsInBox(100, 10.0, 14);
  ContactScene faster = balls;
  faster.bodies[5].v *= 1.1;
  cases.push_back({"balls100_velocity", "a ball of 100 in a box 10% faster, 10 s", SceneText(balls),
                   SceneText(faster)});
  return cases;
}

void RunContactEdits(const Config& cfg) {
  Csv csv(cfg.out_dir + "/contact_edits.csv",
          {"case", "what", "status", "full_s", "incremental_s", "full_steps", "incremental_steps",
           "events", "equal", "error"});
  for (const EditCase& c : EditCases()) {
    std::map<std::string, std::string> row = {{"case", c.name}, {"what", c.what}};
#ifndef ASGARD_BENCH_SESSION
    row["status"] = "not_measurable";
    row["error"] = "core/session (the editing model) is not built";
#else
    auto iso = RunIsolated(
        [&]() -> std::string {
          session::Session s(c.before);
          if (!s.Simulate()) return "error the run before the edit failed";
          s.UpdateText(c.after);
          if (!s.Simulate()) return "error the incremental run failed";
          session::Session scratch(c.after);
          if (!scratch.Simulate()) return "error the run from scratch failed";
          // Bit for bit: the events (times and bodies) and every variable at
          // every 30 Hz frame.
          const auto& got = s.run()->collisions->impacts();
          const auto& want = scratch.run()->collisions->impacts();
          bool equal = got.size() == want.size();
          for (size_t i = 0; equal && i < got.size(); ++i)
            equal = std::memcmp(&got[i].t, &want[i].t, sizeof(double)) == 0 &&
                    got[i].bodies == want[i].bodies;
          const auto& eq = *scratch.run()->equations;
          for (double t : pipeline::FrameTimes(eq.t0, eq.t1, 30.0))
            for (size_t v = 0; equal && v < eq.variables.size(); ++v) {
              const double a = s.run()->simulation->Value(static_cast<int>(v), t);
              const double b = scratch.run()->simulation->Value(static_cast<int>(v), t);
              equal = std::memcmp(&a, &b, sizeof a) == 0;
            }
          return Pack({scratch.last_stats().seconds, s.last_stats().seconds,
                       static_cast<double>(scratch.last_stats().steps),
                       static_cast<double>(s.last_stats().steps), static_cast<double>(want.size()),
                       equal ? 1.0 : 0.0});
        },
        cfg.timeout * 3);
    if (iso.status != "ok" || iso.output.rfind("error", 0) == 0) {
      row["status"] = iso.status == "ok" ? "failed" : iso.status;
      row["error"] = iso.output;
    } else {
      const auto v = Unpack(iso.output);
      row["status"] = "ok";
      row["full_s"] = Num(v[0]);
      row["incremental_s"] = Num(v[1]);
      row["full_steps"] = Num(v[2]);
      row["incremental_steps"] = Num(v[3]);
      row["events"] = Num(v[4]);
      row["equal"] = v[5] != 0 ? "yes" : "no";
      Log("contact edit %s: full %s s, incremental %s s, %s", c.name.c_str(), Num(v[0]).c_str(),
          Num(v[1]).c_str(), v[5] != 0 ? "bit-equal" : "DIFFERENT");
    }
#endif
    csv.Row(row);
  }
}

}  // namespace

double StepAndMeasure(
    const ContactScene& s, double h, const std::function<bool()>& step,
    const std::function<void(size_t, Eigen::Vector3d&, Eigen::Quaterniond&)>& pose,
    ContactResult& out) {
  const int steps = static_cast<int>(std::lround(s.t1 / h));
  const int per_frame = std::max(1, static_cast<int>(std::lround(1.0 / (30.0 * h))));
  double measuring = 0.0;
  for (int k = 1; k <= steps; ++k) {
    if (!step()) break;
    if (k % per_frame != 0 && k != steps) continue;
    const double p0 = ThreadCpuSeconds();
    Eigen::Vector3d p;
    Eigen::Quaterniond q;
    for (size_t i = 0; i < s.bodies.size(); ++i) {
      pose(i, p, q);
      out.max_penetration =
          std::max(out.max_penetration, FloorOrWallPenetration(s, s.bodies[i], p, q));
    }
    measuring += ThreadCpuSeconds() - p0;
  }
  return measuring;
}

double FloorOrWallPenetration(const ContactScene& s, const ContactBody& shape,
                              const Eigen::Vector3d& p, const Eigen::Quaterniond& q) {
  double deepest = 0.0;
  auto against = [&](const Eigen::Vector3d& x, double r) {
    if (s.box) {
      for (int k = 0; k < 3; ++k) deepest = std::max(deepest, std::abs(x[k]) + r - s.box_half);
    } else {
      deepest = std::max(deepest, r - x.y());
    }
  };
  if (!shape.cube) {
    against(p, shape.radius);
    return deepest;
  }
  const Eigen::Matrix3d R = q.normalized().toRotationMatrix();
  for (int c = 0; c < 8; ++c) {
    const Eigen::Vector3d corner(c & 1 ? 0.5 : -0.5, c & 2 ? 0.5 : -0.5, c & 4 ? 0.5 : -0.5);
    against(p + R * corner, 0.0);
  }
  return deepest;
}

std::string ContactSceneText(const std::string& name) {
  for (const ContactScene& s : ContactScenes())
    if (name == s.name || name == s.name + "_" + Num(s.t1) + "s") return SceneText(s);
  return "";
}

bool PrintContactScene(const std::string& name) {
  // pileN@SEED: a pile of N cubes for 5 s from another seed of the
  // generator (the piles' histories are chaotic: one pile's time says little,
  // several seeds together are the measure).
  int cubes = 0;
  unsigned seed = 0;
  char tail = 0;
  if (std::sscanf(name.c_str(), "pile%d@%u%c", &cubes, &seed, &tail) == 2 && cubes > 0 &&
      cubes <= 10000) {
    std::fputs(SceneText(Pile(cubes, 5.0, seed)).c_str(), stdout);
    return true;
  }
  for (const ContactScene& s : ContactScenes()) {
    const std::string label = s.name + "_" + Num(s.t1) + "s";
    if (name != s.name && name != label) continue;
    std::fputs(SceneText(s).c_str(), stdout);
    return true;
  }
  std::string names;
  for (const ContactScene& s : ContactScenes()) names += " " + s.name + "_" + Num(s.t1) + "s";
  Log("no contact scene %s; there are:%s (or the name before _, the first with it), and "
      "pileN@SEED",
      name.c_str(), names.c_str());
  return false;
}

void RunContact(const Config& cfg) {
  Csv csv(cfg.out_dir + "/contact.csv",
          {"scene", "code", "bodies", "t1", "status", "cpu_s", "max_penetration", "final_kinetic",
           "energy_drift", "impacts", "windows", "broad_pairs", "narrow_queries",
           "distance_queries", "error"});
  for (const ContactScene& s : ContactScenes()) {
    auto row = [&](const std::string& code, const ContactResult& r) {
      Log("contact %s %s: %s cpu %.3g s, penetration %.3g, final KE %.3g, drift %.3g",
          s.name.c_str(), code.c_str(), r.status.c_str(), r.cpu, r.max_penetration, r.final_kinetic,
          r.energy_drift);
      const bool ok = r.status == "ok";
      csv.Row({{"scene", s.name},
               {"code", code},
               {"bodies", Int(static_cast<long>(s.bodies.size()))},
               {"t1", Num(s.t1)},
               {"status", r.status},
               {"cpu_s", ok ? Num(r.cpu) : ""},
               {"max_penetration", ok ? Num(r.max_penetration) : ""},
               {"final_kinetic", ok ? Num(r.final_kinetic) : ""},
               {"energy_drift", ok && s.box ? Num(r.energy_drift) : ""},
               {"impacts", ok && code == "asgard" ? Num(r.impacts) : ""},
               {"windows", ok && code == "asgard" ? Num(r.windows) : ""},
               {"broad_pairs", ok && code == "asgard" ? Num(r.broad_pairs) : ""},
               {"narrow_queries", ok && code == "asgard" ? Num(r.narrow_queries) : ""},
               {"distance_queries", ok && code == "asgard" ? Num(r.distance_queries) : ""},
               {"error", r.error}});
    };
    row("asgard", RunAsgardContact(s, cfg.timeout));
#ifdef ASGARD_BENCH_BULLET
    row("bullet h=1/240", RunBulletContact(s, 1.0 / 240));
#endif
#ifdef ASGARD_BENCH_MUJOCO
    row("mujoco h=1/240", RunMujocoContact(s, 1.0 / 240));
#endif
  }
  RunContactEdits(cfg);
}

}  // namespace asgard::bench
