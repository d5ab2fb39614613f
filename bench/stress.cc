// Numerical stress suite.  Every case runs in a child process with a time
// limit and ends in one of:
//   pass      the measured quantity meets its limit
//   miss      it does not (value and limit reported)
//   reported  the solver stopped with an error naming time and component
//   nan       a NaN or Inf reached the output without an error (a bug)
//   timeout   the time limit was hit (a hang is reported, never waited out)
//   crash     the child died
#include <Eigen/Dense>
#include <cmath>
#include <sstream>

#include "bench/model.h"
#include "bench/suites.h"
#include "tests/solver/reference_problems.h"

namespace asgard::bench {

namespace {

struct Outcome {
  double value = NAN;  // the measured quantity (≤ limit passes)
  std::string detail;
  bool solver_failed = false;
};

struct Case {
  std::string name;
  std::string metric;
  double limit;
  std::function<Outcome()> run;
};

pipeline::RunOptions Opts(double rtol = 1e-6, double atol = 1e-9) {
  pipeline::RunOptions o;
  o.solver.rtol = rtol;
  o.solver.atol = atol;
  o.use_scene_tolerances = false;
  return o;
}

bool HasNan(const pipeline::Run& run) {
  const auto& eq = *run.equations;
  for (size_t v = 0; v < eq.variables.size(); ++v)
    for (double t : {eq.t0, 0.5 * (eq.t0 + eq.t1), eq.t1})
      if (!std::isfinite(run.simulation->Value(static_cast<int>(v), t))) return true;
  return false;
}

// Simulates; on a solver error or NaN returns the outcome to report.
std::optional<Outcome> Failed(const pipeline::Run& run) {
  Outcome o;
  if (!run.ok) {
    o.solver_failed = true;
    o.detail = run.solver_error.empty() ? "scene errors" : run.solver_error;
    return o;
  }
  if (HasNan(run)) {
    o.value = NAN;
    o.detail = "NaN in the output without a solver error";
    return o;
  }
  return std::nullopt;
}

// Energy of bodies with isotropic or diagonal inertia under uniform gravity
// (−y) and links (zero rest length), from the simulation's state.
struct LinkSpec {
  int b1;
  Eigen::Vector3d off1;
  int b2;  // -1: world point
  Eigen::Vector3d off2;
  double k;
};
double Energy(const pipeline::Run& run, double t, double g, const std::vector<LinkSpec>& links) {
  const auto& eq = *run.equations;
  auto pose = [&](int b, Eigen::Vector3d& p, Eigen::Matrix3d& R) {
    const pipeline::BodyFrame f = pipeline::SampleBody(eq, *run.simulation, b, t);
    p = Eigen::Vector3d(f.p[0], f.p[1], f.p[2]);
    R = Eigen::Quaterniond(f.q[0], f.q[1], f.q[2], f.q[3]).toRotationMatrix();
    return f;
  };
  double e = 0;
  for (size_t b = 0; b < eq.bodies.size(); ++b) {
    Eigen::Vector3d p;
    Eigen::Matrix3d R;
    const pipeline::BodyFrame f = pose(static_cast<int>(b), p, R);
    const Eigen::Vector3d v(f.v[0], f.v[1], f.v[2]), w(f.w[0], f.w[1], f.w[2]);
    const Eigen::Vector3d wb = R.transpose() * w;
    e += 0.5 * eq.bodies[b].mass * v.squaredNorm() + 0.5 * wb.dot(eq.bodies[b].inertia * wb) +
         eq.bodies[b].mass * g * p.y();
  }
  for (const auto& l : links) {
    Eigen::Vector3d p1, p2;
    Eigen::Matrix3d R1, R2;
    pose(l.b1, p1, R1);
    Eigen::Vector3d a = p1 + R1 * l.off1, c = l.off2;
    if (l.b2 >= 0) {
      pose(l.b2, p2, R2);
      c = p2 + R2 * l.off2;
    }
    e += 0.5 * l.k * (a - c).squaredNorm();
  }
  return e;
}

// Relative energy drift over [0, T], written to energy.csv at 1 s intervals.
Outcome Drift(const std::string& name, const std::string& text, double g,
              const std::vector<LinkSpec>& links, double T, const std::string& csv_path) {
  pipeline::Run run = pipeline::Simulate(text, Opts());
  if (auto f = Failed(run)) return *f;
  const double e0 = Energy(run, 0, g, links);
  double worst = 0;
  std::ostringstream rows;
  for (int s = 0; s <= static_cast<int>(T); ++s) {
    const double d = std::abs(Energy(run, s, g, links) - e0) / std::abs(e0);
    worst = std::max(worst, d);
    rows << name << "," << s << "," << Num(d) << "\n";
  }
  if (std::FILE* f = std::fopen(csv_path.c_str(), "a")) {
    std::fputs(rows.str().c_str(), f);
    std::fclose(f);
  }
  Outcome o;
  o.value = worst;
  o.detail = "steps " + Int(run.simulation->totals().steps);
  return o;
}

std::string Real(double v) {
  std::ostringstream s;
  s.precision(17);
  s << v;
  return s.str();
}


// Largest distance between the two points of any exact joint at `samples`
// times over the run.
double WorstJointGap(const pipeline::Run& run, int samples) {
  const auto& eq = *run.equations;
  double worst = 0;
  for (int i = 0; i <= samples; ++i) {
    const double t = eq.t0 + (eq.t1 - eq.t0) * i / samples;
    for (const physics::Joint& j : eq.joints) {
      auto point = [&](int b, const Eigen::Vector3d& s) -> Eigen::Vector3d {
        const pipeline::BodyFrame f = pipeline::SampleBody(eq, *run.simulation, b, t);
        return Eigen::Vector3d(f.p[0], f.p[1], f.p[2]) +
               Eigen::Quaterniond(f.q[0], f.q[1], f.q[2], f.q[3]) * s;
      };
      Eigen::Vector3d pb;
      if (j.body_b >= 0) pb = point(j.body_b, j.s_b);
      else pb = Eigen::Vector3d(*eq.pool.ConstValue(j.p[0]), *eq.pool.ConstValue(j.p[1]),
                                *eq.pool.ConstValue(j.p[2]));
      worst = std::max(worst, (point(j.body_a, j.s_a) - pb).norm());
    }
  }
  return worst;
}

// n rods (1 × 0.1 × 0.1, mass 1) joined end to end by exact joints, the
// first pinned at the origin, released horizontally; with `closed` the last
// end is pinned too (a closed loop).
std::string JointedChain(int n, double finish, bool closed) {
  std::ostringstream t;
  t << "shape_set rod -desc {-sub {-box {1 0.1 0.1}}}\n";
  for (int i = 0; i < n; ++i) {
    t << "body r" << i << " -shape rod -mass 1 -artbody chain -ct 0 -init_pos {" << i + 0.5
      << " 0 0}\n";
    if (i == 0) t << "link -body1 r0 -offset1 {-0.5 0 0} -x 0 -y 0 -z 0\n";
    else t << "link -body1 r" << i << " -offset1 {-0.5 0 0} -body2 r" << i - 1
           << " -offset2 {0.5 0 0}\n";
    t << "force -body r" << i << " -x 0 -y -9.81 -z 0 -gravitational 1\n";
  }
  if (closed) t << "link -body1 r" << n - 1 << " -offset1 {0.5 0 0} -x " << n << " -y 0 -z 0\n";
  t << "simulator -finish " << finish << "\n";
  return t.str();
}

}  // namespace

void RunStress(const Config& cfg) {
  Csv csv(cfg.out_dir + "/stress.csv",
          {"case", "metric", "value", "limit", "status", "wall", "detail"});
  const std::string energy_path = cfg.out_dir + "/energy.csv";
  if (std::FILE* f = std::fopen(energy_path.c_str(), "w")) {
    std::fputs("case,t,relative_drift\n", f);
    std::fclose(f);
  }
  std::vector<Case> cases;

  // Stiffness ramp: driven critically damped link, k = 1e4 … 1e12 (ω0 to 1e6).
  for (int e = 4; e <= 12; e += 2) {
    const double k = std::pow(10.0, e);
    cases.push_back({"stiffness_k1e" + std::to_string(e), "max error / size", 1e-4, [k]() {
                       const WpScene s = StiffLinkScene(k);
                       const auto frames = FrameTimes(0, s.t1);
                       pipeline::Run run = pipeline::Simulate(s.text, Opts(1e-6, 1e-6));
                       if (auto f = Failed(run)) return *f;
                       Outcome o;
                       o.value = TrajectoryError(SampleAsgard(run, frames), s.exact(frames),
                                                 s.radii, s.size);
                       o.detail = "steps " + Int(run.simulation->totals().steps);
                       return o;
                     }});
  }
  // Mass ratios: two balls on a critically damped link; the relative
  // coordinate has the closed form with the reduced mass.
  for (int e = 0; e <= 6; e += 2) {
    const double M = std::pow(10.0, e);
    cases.push_back({"mass_ratio_1e" + std::to_string(e), "max |r - r_exact|", 1e-4, [M]() {
                       const double k = 1e4;
                       const std::string text =
                           BallShape() +
                           "body a -shape ball -mass 1 -init_pos {1 0 0} -ct 0\n"
                           "body b -shape ball -mass " +
                           Real(M) +
                           " -init_pos {0 0 0} -ct 0\n"
                           "link -body1 a -body2 b -tightness 1e4\nsimulator -finish 2\n";
                       pipeline::Run run = pipeline::Simulate(text, Opts());
                       if (auto f = Failed(run)) return *f;
                       const double mu = M / (1 + M), w = std::sqrt(k / mu);
                       double worst = 0;
                       for (double t : FrameTimes(0, 2, 300)) {
                         const double r =
                             run.simulation->Value(0, t) - run.simulation->Value(13, t);
                         worst = std::max(worst, std::abs(r - (1 + w * t) * std::exp(-w * t)));
                       }
                       Outcome o;
                       o.value = worst;
                       return o;
                     }});
  }
  // 1000 s energy drift.
  const double T = cfg.quick ? 100.0 : 1000.0;
  cases.push_back(
      {"energy_pendulum_" + Num(T) + "s", "max relative energy drift", 1e-2, [T, energy_path]() {
         const double pivot[3] = {0, 0, 0};
         const std::string text = BallShape() + PendulumText("m", pivot, 1.0, 1.0, 9.81, 1e6) +
                                  "simulator -finish " + Real(T) + "\n";
         return Drift("pendulum", text, 9.81,
                      {{0, {-std::sin(1.0), std::cos(1.0), 0}, -1, {0, 0, 0}, 1e6}}, T,
                      energy_path);
       }});
  cases.push_back({"energy_double_pendulum_" + Num(T) + "s", "max relative energy drift", 1e-2,
                   [T, energy_path]() {
                     WpScene s = DoublePendulumScene();
                     std::string text = s.text.substr(0, s.text.rfind("simulator")) +
                                        "simulator -finish " + Real(T) + "\n";
                     const Eigen::Vector3d u1(std::sin(1.0), -std::cos(1.0), 0),
                         u2(std::sin(0.3), -std::cos(0.3), 0);
                     return Drift("double_pendulum", text, 9.81,
                                  {}, T,  // exact joints store no energy
                                  energy_path);
                   }});
  cases.push_back(
      {"energy_top_" + Num(T) + "s", "max relative energy drift", 1e-3, [T, energy_path]() {
         WpScene s = TopScene();
         std::string text =
             s.text.substr(0, s.text.rfind("simulator")) + "simulator -finish " + Real(T) + "\n";
         return Drift("top", text, 0.0, {}, T, energy_path);
       }});
  // Exact joints under load for a long time: a chain of 20 swinging for
  // 100 s (energy drift relative to the chain's potential energy range), a
  // closed loop of four, and a joint hit by a ball.
  cases.push_back({"energy_chain20_100s", "max |E - E0| / (m g n^2 / 2)", 1e-2, [energy_path]() {
                     const int n = 20;
                     pipeline::Run run = pipeline::Simulate(JointedChain(n, 100.0, false), Opts());
                     if (auto f = Failed(run)) return *f;
                     const double scale = 9.81 * n * n / 2.0;
                     const double e0 = Energy(run, 0, 9.81, {});
                     double worst = 0;
                     std::ostringstream rows;
                     for (int s = 0; s <= 100; ++s) {
                       const double d = std::abs(Energy(run, s, 9.81, {}) - e0) / scale;
                       worst = std::max(worst, d);
                       rows << "chain20," << s << "," << Num(d) << "\n";
                     }
                     if (std::FILE* f = std::fopen(energy_path.c_str(), "a")) {
                       std::fputs(rows.str().c_str(), f);
                       std::fclose(f);
                     }
                     Outcome o;
                     o.value = worst;
                     o.detail = "steps " + Int(run.simulation->totals().steps) + ", joint gap " +
                                Num(WorstJointGap(run, 100));
                     return o;
                   }});
  cases.push_back({"closed_loop_four_links", "max joint gap / length", 1e-4, []() {
                     pipeline::Run run = pipeline::Simulate(JointedChain(4, 5.0, true), Opts());
                     if (auto f = Failed(run)) return *f;
                     Outcome o;
                     o.value = WorstJointGap(run, 200) / 4.0;
                     o.detail = "steps " + Int(run.simulation->totals().steps);
                     return o;
                   }});
  cases.push_back({"joint_hit_by_ball", "max joint gap / length", 1e-4, []() {
                     std::string text = JointedChain(3, 3.0, false);
                     text = text.substr(0, text.rfind("simulator")) + BallShape() +
                            "body ball -shape ball -mass 2 -ct 1 -init_pos {2.2 0.8 0} "
                            "-init_dpos {0 -10 0}\nsimulator -finish 3\n";
                     pipeline::Run run = pipeline::Simulate(text, Opts());
                     if (auto f = Failed(run)) return *f;
                     Outcome o;
                     o.value = WorstJointGap(run, 300) / 3.0;
                     o.detail = "impacts " + Int(run.collisions ? long(run.collisions->impacts().size()) : 0L);
                     return o;
                   }});
  // Dzhanibekov near the separatrix: flip period against the closed form.
  cases.push_back({"dzhanibekov_separatrix", "relative period error", 1e-2, []() {
                     const double w1 = 1e-3, w2 = 3, w3 = 1e-3;
                     const double P = testing::TopPeriod(1, 2, 2.5, w1, w2, w3);
                     const std::string text = BallShape() +
                                              "body top -shape ball -mass 1 -moment {1 2 2.5} "
                                              "-init_drot {0.001 3 0.001}\nsimulator -finish " +
                                              Real(3.3 * P) + "\n";
                     pipeline::Run run = pipeline::Simulate(text, Opts(1e-8, 1e-10));
                     if (auto f = Failed(run)) return *f;
                     // Upward zero crossings of body w2 are one period apart.
                     std::vector<double> ups;
                     const int var = physics::kW2;
                     double prev = run.simulation->Value(var, 0), tp = 0;
                     for (double t = P * 1e-4; t <= 3.3 * P; t += P * 1e-4) {
                       const double v = run.simulation->Value(var, t);
                       if (prev < 0 && v >= 0) ups.push_back(tp + (t - tp) * (-prev) / (v - prev));
                       prev = v, tp = t;
                     }
                     Outcome o;
                     if (ups.size() < 2) {
                       o.value = INFINITY;
                       o.detail = "fewer than two flips";
                       return o;
                     }
                     const double measured = (ups.back() - ups.front()) / (ups.size() - 1);
                     o.value = std::abs(measured - P) / P;
                     o.detail = "period " + Num(measured) + " vs " + Num(P);
                     return o;
                   }});
  cases.push_back({"spin_100_rad_s", "max relative energy drift (10 s)", 1e-4, [energy_path]() {
                     const std::string text = BallShape() +
                                              "body top -shape ball -mass 1 -moment {1 2 2.5} "
                                              "-init_drot {100 1 0.5}\nsimulator -finish 10\n";
                     return Drift("spin100", text, 0.0, {}, 10.0, energy_path);
                   }});
  // Grazing contact with a static ball: exact reflection about the normal.
  cases.push_back({"grazing_contact", "|v_final - v_exact| / |v|", 1e-3, []() {
                     const double b = 1.0 - 1e-6;  // impact parameter (sum of radii 1)
                     const std::string text =
                         BallShape() + "body s -shape ball -static 1 -init_pos {0 0 0}\n" +
                         "body m -shape ball -mass 1 -init_pos {-3 " + Real(b) +
                         " 0} -init_dpos {4 0 0}\nsimulator -finish 2\n";
                     pipeline::Run run = pipeline::Simulate(text, Opts());
                     if (auto f = Failed(run)) return *f;
                     const int m = run.equations->bodies[1].first_var;
                     const Eigen::Vector3d v(run.simulation->Value(m + 3, 2),
                                             run.simulation->Value(m + 4, 2), 0);
                     const Eigen::Vector3d n(-std::sqrt(1 - b * b), b, 0);  // at contact
                     const Eigen::Vector3d v0(4, 0, 0);
                     const Eigen::Vector3d ve = v0 - 2 * v0.dot(n) * n;
                     Outcome o;
                     o.value = (v - ve).norm() / 4;
                     o.detail = "vy " + Num(v.y()) + " exact " + Num(ve.y());
                     return o;
                   }});
  // Simultaneous impacts: two balls hit a resting middle ball at once.
  cases.push_back({"simultaneous_impacts", "max |v - v_exact| / v", 1e-3, []() {
                     const std::string text =
                         BallShape() +
                         "body l -shape ball -mass 1 -init_pos {-3 0 0} -init_dpos {2 0 0}\n"
                         "body c -shape ball -mass 1 -init_pos {0 0 0}\n"
                         "body r -shape ball -mass 1 -init_pos {3 0 0} -init_dpos {-2 0 0}\n"
                         "simulator -finish 3\n";
                     pipeline::Run run = pipeline::Simulate(text, Opts());
                     if (auto f = Failed(run)) return *f;
                     const double exact[3] = {-2, 0, 2};
                     double worst = 0;
                     std::string d;
                     for (int b = 0; b < 3; ++b) {
                       const double v = run.simulation->Value(13 * b + 3, 3);
                       worst = std::max(worst, std::abs(v - exact[b]) / 2);
                       d += Num(v) + " ";
                     }
                     Outcome o;
                     o.value = worst;
                     o.detail = "final vx " + d + "impacts " +
                                Int(static_cast<long>(run.collisions->impacts().size()));
                     return o;
                   }});
  // Thin plate at high speed: no tunnelling.
  cases.push_back({"thin_plate_1000_m_s", "|vx_final + 1000| (tunnelling: inf)", 1.0, []() {
                     const std::string text =
                         "shape_set small -desc {-sub {-sphere 0.1}}\n"
                         "shape_set plate -desc {-sub {-box {0.01 2 2}}}\n"
                         "body p -shape plate -static 1 -init_pos {0 0 0}\n"
                         "body b -shape small -mass 1 -init_pos {-1 0 0} -init_dpos {1000 0 0}\n"
                         "simulator -finish 0.01\n";
                     pipeline::Run run = pipeline::Simulate(text, Opts());
                     if (auto f = Failed(run)) return *f;
                     const int m = run.equations->bodies[1].first_var;
                     const double x = run.simulation->Value(m, 0.01);
                     const double vx = run.simulation->Value(m + 3, 0.01);
                     Outcome o;
                     o.value = x > 0 ? INFINITY : std::abs(vx + 1000);
                     o.detail = "x " + Num(x) + " vx " + Num(vx);
                     return o;
                   }});
  // Step-function force: x = t²/2 until t = 1, then 0.5 + (t − 1).
  cases.push_back({"step_force", "max |x - x_exact|", 1e-6, []() {
                     const std::string text = BallShape() +
                                              "body b -shape ball -mass 1\n"
                                              "force -body b -x {t < 1 ? 1 : 0} -y 0 -z 0\n"
                                              "simulator -finish 3\n";
                     pipeline::Run run = pipeline::Simulate(text, Opts());
                     if (auto f = Failed(run)) return *f;
                     double worst = 0;
                     for (double t : FrameTimes(0, 3, 300)) {
                       const double ex = t < 1 ? 0.5 * t * t : 0.5 + (t - 1);
                       worst = std::max(worst, std::abs(run.simulation->Value(0, t) - ex));
                     }
                     Outcome o;
                     o.value = worst;
                     o.detail = "restarts " + Int(run.simulation->totals().restarts);
                     return o;
                   }});
  // Bézier knots: a prescribed body passes its knots exactly; a body linked
  // to the same curve follows it.
  cases.push_back(
      {"bezier_knots", "max |x(knot) - knot|", 1e-9, []() {
         const std::string text =
             BallShape() +
             "trajectory tr -points {{0 0 0 0} {1 1 0 0} {2 1 1 0} {3 0 1 0}}\n"
             "trajectory pr -points {{0 0 0 0} {1 1 0 0} {2 1 1 0} {3 0 1 0}} "
             "-body a\n"
             "body a -shape ball -mass 1 -ct 0\n"
             "body f -shape ball -mass 1 -ct 0\n"
             "link -body1 f -trajectory tr -tightness 1e6\n"
             "simulator -finish 3\n";
         pipeline::Run run = pipeline::Simulate(text, Opts());
         if (auto f = Failed(run)) return *f;
         const double knots[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
         double worst = 0, follow = 0;
         for (int k = 0; k < 4; ++k)
           for (int a = 0; a < 2; ++a) {
             worst = std::max(worst, std::abs(run.simulation->Value(a, k) - knots[k][a]));
             follow = std::max(follow, std::abs(run.simulation->Value(13 + a, k) - knots[k][a]));
           }
         Outcome o;
         o.value = worst;
         o.detail = "linked follower max deviation at knots " + Num(follow);
         return o;
       }});
  // The same pendulum scaled ×1e3 and ×1e-3 (lengths and gravity scaled, so
  // the motion is the same in scene units): error relative to the scene.
  for (double scale : {1e3, 1e-3}) {
    cases.push_back({"scaled_x" + Num(scale), "max error / size vs unscaled", 1e-3, [scale]() {
                       auto text = [](double s) {
                         const double pivot[3] = {0, 0, 0};
                         return "shape_set ball -desc {-sub {-sphere " + Real(0.5 * s) + "}}\n" +
                                PendulumText("m", pivot, s, 1.0, 9.81 * s, 1e6) +
                                "simulator -finish 10\n";
                       };
                       const auto frames = FrameTimes(0, 10);
                       pipeline::RunOptions o;  // scene defaults: rtol 1e-6, atol 1e-9
                       pipeline::Run a = pipeline::Simulate(text(scale), o);
                       if (auto f = Failed(a)) return *f;
                       pipeline::Run ref = pipeline::Simulate(text(1.0), Opts(1e-10, 1e-12));
                       Trajectory ta = SampleAsgard(a, frames), tr = SampleAsgard(ref, frames);
                       for (auto& row : ta.poses)
                         for (auto& p : row)
                           for (double& x : p.p) x /= scale;
                       Outcome out;
                       out.value = TrajectoryError(ta, tr, {0.5}, 2.0);
                       out.detail = "steps " + Int(a.simulation->totals().steps);
                       return out;
                     }});
  }

  for (const Case& c : cases) {
    auto iso = RunIsolated(
        [&]() {
          const Outcome o = c.run();
          return (o.solver_failed ? std::string("F ") : std::string("V ")) + Pack({o.value}) +
                 "\n" + o.detail;
        },
        cfg.timeout);
    std::string status = iso.status, detail = iso.output;
    double value = NAN;
    if (iso.status == "ok") {
      const size_t nl = iso.output.find('\n');
      const std::string head = iso.output.substr(0, nl);
      detail = nl == std::string::npos ? "" : iso.output.substr(nl + 1);
      const auto v = Unpack(head.substr(2));
      value = v.empty() ? NAN : v[0];
      if (head[0] == 'F')
        status = "reported";
      else if (!std::isfinite(value) && std::isnan(value))
        status = "nan";
      else
        status = value <= c.limit ? "pass" : "miss";
    }
    csv.Row({{"case", c.name},
             {"metric", c.metric},
             {"value", Num(value)},
             {"limit", Num(c.limit)},
             {"status", status},
             {"wall", Num(iso.wall)},
             {"detail", detail}});
    Log("  stress %-28s %-8s %-12s (limit %s) %s", c.name.c_str(), status.c_str(),
        Num(value).c_str(), Num(c.limit).c_str(), detail.c_str());
  }
}

}  // namespace asgard::bench
