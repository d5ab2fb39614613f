// Work–precision diagrams: achieved error (common metric, 30 Hz frames)
// against CPU time, for Asgard, the ODE peers on Asgard's equations and the
// engines on the same scenes.
#include <cmath>

#include "bench/model.h"
#include "bench/peers.h"
#include "bench/suites.h"

namespace asgard::bench {

namespace {

const std::vector<std::string> kColumns = {
    "scene", "code",           "kind",   "param",  "error",    "error_rigid",
    "cpu",   "cpu_total",      "runs",   "steps",  "rejected", "rhs",
    "jac",   "factorizations", "newton", "status", "note"};

std::vector<double> Tolerances(const Config& cfg) {
  // Quick mode samples every second decade, down to 1e-8 so that each
  // frontier reaches an achieved error of 1e-6.
  if (cfg.quick) return {1e-2, 1e-4, 1e-6, 1e-8};
  return {1e-1, 1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8};
}

// Steps that divide the 1/30 s frame interval: about 1e-2 … 1e-5.
std::vector<double> Steps(const Config& cfg) {
  std::vector<int> m =
      cfg.quick ? std::vector<int>{3, 30, 300} : std::vector<int>{3, 10, 30, 100, 300, 1000, 3000};
  std::vector<double> h;
  for (int k : m) h.push_back(1.0 / 30.0 / k);
  return h;
}

struct Point {
  double error = NAN, error_rigid = NAN, cpu = NAN, cpu_total = NAN;
  double runs = 0, steps = 0, rejected = 0, rhs = 0, jac = 0, fact = 0, newton = 0;
  bool ok = false;
};

std::string Encode(const Point& p) {
  return Pack({p.ok ? 1.0 : 0.0, p.error, p.error_rigid, p.cpu, p.cpu_total, p.runs, p.steps,
               p.rejected, p.rhs, p.jac, p.fact, p.newton});
}
Point Decode(const std::vector<double>& v) {
  Point p;
  if (v.size() < 12) return p;
  p.ok = v[0] != 0;
  p.error = v[1], p.error_rigid = v[2], p.cpu = v[3], p.cpu_total = v[4], p.runs = v[5];
  p.steps = v[6], p.rejected = v[7], p.rhs = v[8], p.jac = v[9], p.fact = v[10], p.newton = v[11];
  return p;
}

// Repeats `once` (which returns CPU seconds) up to cfg.repeats times, fewer
// when a run is long (at most ~60 s in all); returns the median.
double MedianCpu(const Config& cfg, const std::function<double()>& once, double first,
                 double* runs) {
  return RepeatedCpu(cfg.repeats, cfg.quick ? 5.0 : 15.0, once, first, runs);
}

void Emit(Csv& csv, const std::string& scene, const std::string& code, const std::string& kind,
          double param, const Isolated& iso, const std::string& note) {
  Point p;
  std::string status = iso.status;
  if (iso.status == "ok") {
    p = Decode(Unpack(iso.output));
    if (!p.ok) status = "failed";
  }
  csv.Row({{"scene", scene},
           {"code", code},
           {"kind", kind},
           {"param", Num(param)},
           {"error", Num(p.error)},
           {"error_rigid", Num(p.error_rigid)},
           {"cpu", Num(p.cpu)},
           {"cpu_total", Num(p.cpu_total)},
           {"runs", Num(p.runs)},
           {"steps", Num(p.steps)},
           {"rejected", Num(p.rejected)},
           {"rhs", Num(p.rhs)},
           {"jac", Num(p.jac)},
           {"factorizations", Num(p.fact)},
           {"newton", Num(p.newton)},
           {"status", status},
           {"note", note}});
  Log("  %-20s %-18s %-9s %-8s err %-10s cpu %-10s %s", scene.c_str(), code.c_str(), kind.c_str(),
      Num(param).c_str(), Num(p.error).c_str(), Num(p.cpu).c_str(), status.c_str());
}

}  // namespace

void RunWorkPrecision(const Config& cfg) {
  Csv csv(cfg.out_dir + "/workprec.csv", kColumns);
  Csv refs(cfg.out_dir + "/references.csv",
           {"scene", "reference", "rigid_reference", "model_difference", "cross_check",
            "cross_check_difference"});
  std::vector<WpScene> scenes = {
      SimplePendulumScene(),         DoublePendulumScene(), TopScene(),
      ChainScene(cfg.quick ? 3 : 5), StiffLinkScene(1e8),   BallsInBoxScene(cfg.quick ? 4 : 8)};
  const auto ode_peers = OdePeers();
  const auto engines = EnginePeers();
  for (const WpScene& s : scenes) {
    Log("work-precision: %s", s.name.c_str());
    const auto frames = FrameTimes(0.0, s.t1);
    std::unique_ptr<TapeOde> ode;
    if (!s.collisions) ode = std::make_unique<TapeOde>(s.text);
    // Reference: exact, else CVODE at 1e-12, else odeint dopri5 at 1e-12.
    Trajectory ref, cross;
    std::string ref_name = s.exact_name, cross_name;
    if (s.exact) ref = s.exact(frames);
    for (const auto& p : ode_peers) {
      if (!ode || !ode->ok()) break;
      const bool primary = p.name == "cvode_bdf_klu";
      const bool second = p.name == "odeint_dopri5";
      if (!primary && !second) continue;
      const double rtol = primary ? 1e-12 : 1e-11;
      PeerRun r = p.run(*ode, rtol, primary ? 1e-14 : 1e-13, frames);
      if (!r.ok) continue;
      const std::string name = p.name + " rtol " + Num(rtol);
      if (ref.empty() && primary) {
        ref = r.traj, ref_name = name;
      } else if (cross.empty()) {
        cross = r.traj, cross_name = name;
      }
    }
    if (ref.empty()) {
      pipeline::RunOptions o;
      o.solver.rtol = 1e-11, o.solver.atol = 1e-13;
      o.collisions = s.collisions;
      AsgardRun r = RunAsgard(s.text, o, frames);
      ref = r.traj;
      ref_name = "Asgard rtol 1e-11 (no independent solver installed)";
    }
    Trajectory rigid;
    if (s.rigid) rigid = RigidChainReference(*s.rigid, frames);
    refs.Row(
        {{"scene", s.name},
         {"reference", ref_name},
         {"rigid_reference",
          s.rigid ? (s.rigid->bodies == 1 ? "elliptic closed form" : "rigid chain, RK4 h=2e-5")
                  : ""},
         {"model_difference", s.rigid ? Num(TrajectoryError(ref, rigid, s.radii, s.size)) : ""},
         {"cross_check", cross_name},
         {"cross_check_difference",
          cross.empty() ? "" : Num(TrajectoryError(cross, ref, s.radii, s.size))}});
    const Trajectory& engine_ref = s.rigid ? rigid : ref;

    // Asgard.
    const double setup = SetupCpu(s.text, 3);
    for (double tol : Tolerances(cfg)) {
      auto iso = RunIsolated(
          [&]() {
            pipeline::RunOptions o;
            o.solver.rtol = tol, o.solver.atol = tol;
            if (cfg.pair) o.solver.pair = *cfg.pair;
            o.use_scene_tolerances = false;
            o.collisions = s.collisions;
            AsgardRun r = RunAsgard(s.text, o, frames, setup);
            Point p;
            p.ok = r.ok;
            if (!r.ok) return Encode(p);
            p.error = TrajectoryError(r.traj, ref, s.radii, s.size);
            if (s.rigid) p.error_rigid = TrajectoryError(r.traj, rigid, s.radii, s.size);
            p.cpu = MedianCpu(
                cfg, [&]() { return RunAsgard(s.text, o, {}, setup).cpu; }, r.cpu, &p.runs);
            p.cpu_total = r.total_cpu;
            p.steps = r.counters.steps, p.rejected = r.counters.rejected_steps;
            p.rhs = r.counters.rhs_evaluations, p.jac = r.counters.jacobian_evaluations;
            p.fact = r.counters.factorizations, p.newton = r.counters.newton_iterations;
            return Encode(p);
          },
          cfg.timeout);
      Emit(csv, s.name, "asgard", "adaptive", tol, iso, "");
    }
    // ODE peers on the same equations.
    if (ode && ode->ok()) {
      for (const auto& peer : ode_peers) {
        for (double tol : Tolerances(cfg)) {
          auto iso = RunIsolated(
              [&]() {
                PeerRun r = peer.run(*ode, tol, tol, frames);
                Point p;
                p.ok = r.ok;
                if (!r.ok) return Encode(p);
                p.error = TrajectoryError(r.traj, ref, s.radii, s.size);
                if (s.rigid) p.error_rigid = TrajectoryError(r.traj, rigid, s.radii, s.size);
                p.cpu = MedianCpu(
                    cfg, [&]() { return peer.run(*ode, tol, tol, frames).cpu; }, r.cpu, &p.runs);
                p.cpu_total = r.cpu;
                p.steps = r.steps, p.rejected = r.rejected, p.rhs = r.rhs, p.jac = r.jac;
                p.fact = r.factorizations;
                return Encode(p);
              },
              cfg.timeout);
          Emit(csv, s.name, peer.name, "adaptive", tol, iso, "same equations");
        }
      }
    }
    // Engines on the same scene (their own joint model).
    for (const auto& eng : engines) {
      if (!eng.fits(s)) continue;
      for (double h : Steps(cfg)) {
        auto iso = RunIsolated(
            [&]() {
              PeerRun r = eng.run(s, h, frames);
              Point p;
              p.ok = r.ok;
              if (!r.ok) return Encode(p);
              p.error = TrajectoryError(r.traj, engine_ref, s.radii, s.size);
              p.error_rigid = p.error;
              p.cpu = MedianCpu(
                  cfg, [&]() { return eng.run(s, h, frames).cpu; }, r.cpu, &p.runs);
              p.cpu_total = r.cpu;
              p.steps = r.steps, p.rhs = r.rhs;
              return Encode(p);
            },
            cfg.timeout);
        Emit(csv, s.name, eng.name, "fixed", h, iso,
             s.rigid ? "rigid joints; error against the rigid model" : "same scene");
      }
    }
  }
}

void RunStiffSweep(const Config& cfg) {
  Csv csv(cfg.out_dir + "/stiff.csv",
          {"omega0", "k", "code", "tol", "error", "cpu", "runs", "steps", "rejected", "rhs", "jac",
           "factorizations", "status"});
  const std::vector<double> tols = cfg.quick ? std::vector<double>{1e-4, 1e-6}
                                             : std::vector<double>{1e-3, 1e-4, 1e-5, 1e-6, 1e-7};
  OdePeer cvode{"", nullptr};
  for (const auto& p : OdePeers())
    if (p.name == "cvode_bdf_klu") cvode = p;
  for (int e = 2; e <= 6; ++e) {
    const double w = std::pow(10.0, e), k = w * w;
    const WpScene s = StiffLinkScene(k);
    const auto frames = FrameTimes(0.0, s.t1);
    const Trajectory ref = s.exact(frames);
    TapeOde ode(s.text);
    const double setup = SetupCpu(s.text, 3);
    for (double tol : tols) {
      for (int code = 0; code < 2; ++code) {
        if (code == 1 && !cvode.run) continue;
        auto iso = RunIsolated(
            [&]() {
              Point p;
              if (code == 0) {
                pipeline::RunOptions o;
                o.solver.rtol = tol, o.solver.atol = tol;
                if (cfg.pair) o.solver.pair = *cfg.pair;
                AsgardRun r = RunAsgard(s.text, o, frames, setup);
                p.ok = r.ok;
                if (!r.ok) return Encode(p);
                p.error = TrajectoryError(r.traj, ref, s.radii, s.size);
                p.cpu = MedianCpu(
                    cfg, [&]() { return RunAsgard(s.text, o, {}, setup).cpu; }, r.cpu, &p.runs);
                p.steps = r.counters.steps, p.rejected = r.counters.rejected_steps;
                p.rhs = r.counters.rhs_evaluations, p.jac = r.counters.jacobian_evaluations;
                p.fact = r.counters.factorizations;
              } else {
                PeerRun r = cvode.run(ode, tol, tol, frames);
                p.ok = r.ok;
                if (!r.ok) return Encode(p);
                p.error = TrajectoryError(r.traj, ref, s.radii, s.size);
                p.cpu = MedianCpu(
                    cfg, [&]() { return cvode.run(ode, tol, tol, frames).cpu; }, r.cpu, &p.runs);
                p.steps = r.steps, p.rejected = r.rejected, p.rhs = r.rhs, p.jac = r.jac;
                p.fact = r.factorizations;
              }
              return Encode(p);
            },
            cfg.timeout);
        Point p;
        std::string status = iso.status;
        if (iso.status == "ok") {
          p = Decode(Unpack(iso.output));
          if (!p.ok) status = "failed";
        }
        csv.Row({{"omega0", Num(w)},
                 {"k", Num(k)},
                 {"code", code ? "cvode_bdf_klu" : "asgard"},
                 {"tol", Num(tol)},
                 {"error", Num(p.error)},
                 {"cpu", Num(p.cpu)},
                 {"runs", Num(p.runs)},
                 {"steps", Num(p.steps)},
                 {"rejected", Num(p.rejected)},
                 {"rhs", Num(p.rhs)},
                 {"jac", Num(p.jac)},
                 {"factorizations", Num(p.fact)},
                 {"status", status}});
        Log("  stiff w0=%-8s %-14s tol %-7s err %-10s cpu %-10s steps %s", Num(w).c_str(),
            code ? "cvode" : "asgard", Num(tol).c_str(), Num(p.error).c_str(), Num(p.cpu).c_str(),
            Num(p.steps).c_str());
      }
    }
  }
}

}  // namespace asgard::bench
