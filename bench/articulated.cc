// Articulated bodies: a planar chain of 50 rods and a binary tree of 100 rods
// (every link an exact joint in Asgard, hinges in MuJoCo, point-to-point
// constraints in Bullet), and chains of 10 and 20 for Asgard's cost per step
// per body.  The same rigid model (RigidChain) builds every code's scene.
//
// Error: the work–precision metric (TrajectoryError, 30 Hz frames) against
// the rigid model integrated by RigidChainReference (absolute angles, mass
// matrix factored from the leaves, RK4 at a fine fixed step — independent of Asgard and of the
// engines), cross-checked against MuJoCo RK4 at a small step.  The span is
// short (a released chain is chaotic, so over long spans every error is O(1)).
// Times are thread CPU seconds (the machine may carry other load).
//
//   articulated.csv       one row per (scene, code, tolerance or step)
//   articulated_refs.csv  the references and their cross-check
#include <cmath>

#include "bench/model.h"
#include "bench/peers.h"
#include "bench/suites.h"

namespace asgard::bench {

namespace {

struct Result {
  bool ok = false;
  double error = NAN, cpu = NAN, runs = 0, steps = 0, rejected = 0, rhs = 0;
};

std::string Encode(const Result& r) {
  return Pack({r.ok ? 1.0 : 0.0, r.error, r.cpu, r.runs, r.steps, r.rejected, r.rhs});
}

Result Decode(const Isolated& iso) {
  Result r;
  const std::vector<double> v = iso.status == "ok" ? Unpack(iso.output) : std::vector<double>{};
  if (v.size() < 7) return r;
  r.ok = v[0] != 0;
  r.error = v[1], r.cpu = v[2], r.runs = v[3], r.steps = v[4], r.rejected = v[5], r.rhs = v[6];
  return r;
}

// Median CPU time over up to cfg.repeats runs (fewer when runs are long).
double MedianCpu(const Config& cfg, const std::function<double()>& once, double first,
                 double* runs) {
  return RepeatedCpu(cfg.repeats, cfg.quick ? 2.0 : 15.0, once, first, runs);
}

// Asgard's solver phase (what pipeline::Simulate times: the simulation's
// set-up and run; scene evaluation and equation forming excluded) in thread
// CPU seconds, which load from other processes does not inflate.
double SolveCpu(const std::string& text, const pipeline::RunOptions& options, pipeline::Run* run) {
  *run = pipeline::Check(text);
  const double c0 = ThreadCpuSeconds();
  pipeline::Solve(*run, options);
  return ThreadCpuSeconds() - c0;
}

struct Case {
  WpScene scene;
  bool peers;  // run the engines too (else Asgard alone, for its cost per body)
};

}  // namespace

void RunArticulated(const Config& cfg) {
  Csv csv(cfg.out_dir + "/articulated.csv",
          {"scene", "bodies", "t1", "code", "kind", "param", "error", "cpu", "runs", "steps",
           "rejected", "rhs", "status", "note"});
  Csv refs(cfg.out_dir + "/articulated_refs.csv",
           {"scene", "bodies", "t1", "size", "reference", "reference_cpu", "cross_check",
            "cross_check_difference"});
  const double t1 = 2.0;
  const double h_ref = cfg.quick ? 1e-4 : 2e-5;
  const int cross_m = cfg.quick ? 300 : 3000;  // MuJoCo RK4 at h = (1/30 s)/m
  const std::vector<double> tols =
      cfg.quick ? std::vector<double>{1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7}
                : std::vector<double>{1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8};
  std::vector<double> steps;  // divisors of the 1/30 s frame interval
  for (int m : cfg.quick ? std::vector<int>{1, 3, 10, 30, 100}
                         : std::vector<int>{1, 3, 10, 30, 100, 300, 1000})
    steps.push_back(1.0 / 30.0 / m);
  // Per case: quick mode keeps every case well under a minute in all.
  const double limit = cfg.quick ? std::min(cfg.timeout, 20.0) : cfg.timeout;
  const std::vector<Case> cases = {{ChainScene(10, t1), !cfg.quick},
                                   {ChainScene(20, t1), !cfg.quick},
                                   {ChainScene(50, t1), true},
                                   {TreeScene(100, t1), true}};
  // MuJoCo and Bullet (ODE is left out of this suite: not measured here).
  std::vector<EnginePeer> engines;
  for (const auto& e : EnginePeers())
    if (e.name != "ode") engines.push_back(e);
  for (const Case& c : cases) {
    const WpScene& s = c.scene;
    const int bodies = s.rigid->bodies;
    Log("articulated: %s (%d bodies, %g s)", s.name.c_str(), bodies, s.t1);
    const auto frames = FrameTimes(0.0, s.t1);
    const double c0 = ThreadCpuSeconds();
    const Trajectory ref = RigidChainReference(*s.rigid, frames, h_ref);
    const double ref_cpu = ThreadCpuSeconds() - c0;
    std::string cross_name;
    double cross_diff = NAN;
    for (const auto& e : engines) {
      if (e.name != "mujoco_rk4") continue;
      const double h = 1.0 / 30.0 / cross_m;
      PeerRun r = e.run(s, h, frames);
      if (!r.ok) continue;
      cross_name = "mujoco_rk4 h=" + Num(h);
      cross_diff = TrajectoryError(r.traj, ref, s.radii, s.size);
    }
    refs.Row({{"scene", s.name},
              {"bodies", Int(bodies)},
              {"t1", Num(s.t1)},
              {"size", Num(s.size)},
              {"reference", "rigid model, absolute angles, RK4 h=" + Num(h_ref)},
              {"reference_cpu", Num(ref_cpu)},
              {"cross_check", cross_name},
              {"cross_check_difference", Num(cross_diff)}});
    Log("  reference %.2f s CPU; %s differs by %s", ref_cpu, cross_name.c_str(),
        Num(cross_diff).c_str());

    auto emit = [&](const std::string& code, const std::string& kind, double param,
                    const Isolated& iso, const std::string& note) {
      const Result r = Decode(iso);
      const std::string status = iso.status != "ok" ? iso.status : r.ok ? "ok" : "failed";
      csv.Row({{"scene", s.name},
               {"bodies", Int(bodies)},
               {"t1", Num(s.t1)},
               {"code", code},
               {"kind", kind},
               {"param", Num(param)},
               {"error", Num(r.error)},
               {"cpu", Num(r.cpu)},
               {"runs", Num(r.runs)},
               {"steps", Num(r.steps)},
               {"rejected", Num(r.rejected)},
               {"rhs", Num(r.rhs)},
               {"status", status},
               {"note", note}});
      Log("  %-9s %-13s %-9s err %-10s cpu %-10s steps %-8s %s", s.name.c_str(), code.c_str(),
          Num(param).c_str(), Num(r.error).c_str(), Num(r.cpu).c_str(), Num(r.steps).c_str(),
          status.c_str());
    };

    for (double tol : tols) {
      auto iso = RunIsolated(
          [&]() {
            pipeline::RunOptions o;
            o.solver.rtol = tol, o.solver.atol = tol;
            o.use_scene_tolerances = false;
            o.collisions = false;
            pipeline::Run run;
            const double first = SolveCpu(s.text, o, &run);
            Result r;
            r.ok = run.ok;
            if (!run.ok) return Encode(r);
            r.error = TrajectoryError(SampleAsgard(run, frames), ref, s.radii, s.size);
            r.cpu = MedianCpu(
                cfg,
                [&]() {
                  pipeline::Run again;
                  return SolveCpu(s.text, o, &again);
                },
                first, &r.runs);
            const solver::Counters n = run.simulation->totals();
            r.steps = n.steps, r.rejected = n.rejected_steps, r.rhs = n.rhs_evaluations;
            return Encode(r);
          },
          limit);
      emit("asgard", "adaptive", tol, iso, "exact joints");
    }
    if (!c.peers) continue;
    for (const auto& e : engines) {
      if (!e.fits(s)) continue;
      for (double h : steps) {
        auto iso = RunIsolated(
            [&]() {
              const PeerRun p = e.run(s, h, frames);
              Result r;
              r.ok = p.ok;
              if (!p.ok) return Encode(r);
              r.error = TrajectoryError(p.traj, ref, s.radii, s.size);
              r.cpu = MedianCpu(
                  cfg, [&]() { return e.run(s, h, frames).cpu; }, p.cpu, &r.runs);
              r.steps = static_cast<double>(p.steps), r.rhs = static_cast<double>(p.rhs);
              return Encode(r);
            },
            limit);
        emit(e.name, "fixed", h, iso, "rigid joints");
      }
    }
  }
}

}  // namespace asgard::bench
