// The seed's experiments (section 5.2): Figure 5.7 (time-constant ratio,
// one component against partitioned), Figure 5.11 (the five algorithm
// variants of 5.2.4 against the number of idle objects), and "skip what a
// scene doesn't need" (idle subsystems; editing one object of N).
#include <sys/stat.h>

#include <cmath>
#include <ctime>
#include <sstream>
#include <string>
#include <vector>

#include "bench/model.h"
#include "bench/suites.h"
#include "core/lang/lang.h"
#ifdef ASGARD_BENCH_SESSION
#include "core/session/session.h"
#endif
#include <cstring>

namespace asgard::bench {

namespace {

struct Timed {
  std::string status = "ok";
  std::string error;
  double cpu = NAN;
  double runs = 0;
  double steps = 0, rejected = 0, components = 0, impacts = 0, truncated = 0;
};

// Median solver times of scenes over cfg.repeats rounds (fewer when long),
// in a child process with the suite's timeout.  Each round runs every scene
// once, in turn, so that a change of the machine's load or clock between
// rounds falls on all of them alike.
std::vector<Timed> MeasureInterleaved(const Config& cfg, const std::vector<std::string>& texts,
                                      const pipeline::RunOptions& o) {
  constexpr size_t kFields = 7;
  auto iso = RunIsolated(
      [&]() {
        std::vector<std::vector<double>> cpu(texts.size());
        std::vector<AsgardRun> first(texts.size());
        double spent = 0;
        for (int i = 0; i < cfg.repeats && spent < (cfg.quick ? 5.0 : 20.0); ++i) {
          for (size_t k = 0; k < texts.size(); ++k) {
            AsgardRun r = RunAsgard(texts[k], o, {});
            if (!r.ok) return "error " + r.error;
            if (i == 0) first[k] = r;
            cpu[k].push_back(r.cpu);
            spent += r.cpu;
          }
        }
        std::vector<double> packed;
        for (size_t k = 0; k < texts.size(); ++k) {
          const AsgardRun& f = first[k];
          packed.insert(
              packed.end(),
              {Median(cpu[k]), static_cast<double>(cpu[k].size()),
               static_cast<double>(f.counters.steps),
               static_cast<double>(f.counters.rejected_steps), static_cast<double>(f.components),
               static_cast<double>(f.impacts), static_cast<double>(f.counters.truncated_steps)});
        }
        return Pack(packed);
      },
      cfg.timeout);
  std::vector<Timed> out(texts.size());
  const auto v = iso.status == "ok" && iso.output.rfind("error ", 0) != 0 ? Unpack(iso.output)
                                                                          : std::vector<double>{};
  for (size_t k = 0; k < texts.size(); ++k) {
    Timed& t = out[k];
    t.status = iso.status;
    if (iso.status != "ok") continue;
    if (iso.output.rfind("error ", 0) == 0) {
      t.status = "failed";
      t.error = iso.output.substr(6);
      continue;
    }
    if (v.size() < kFields * texts.size()) {
      t.status = "crash";
      continue;
    }
    const double* f = v.data() + kFields * k;
    t.cpu = f[0], t.runs = f[1], t.steps = f[2], t.rejected = f[3], t.components = f[4];
    t.impacts = f[5], t.truncated = f[6];
  }
  return out;
}

Timed Measure(const Config& cfg, const std::string& text, const pipeline::RunOptions& o) {
  return MeasureInterleaved(cfg, {text}, o)[0];
}

std::map<std::string, std::string> Cols(const Timed& t) {
  return {{"cpu", Num(t.cpu)},
          {"runs", Num(t.runs)},
          {"steps", Num(t.steps)},
          {"rejected", Num(t.rejected)},
          {"components", Num(t.components)},
          {"impacts", Num(t.impacts)},
          {"truncated", Num(t.truncated)},
          {"status", t.status},
          {"error", t.error}};
}

const std::vector<std::string> kTimedCols = {
    "cpu", "runs", "steps", "rejected", "components", "impacts", "truncated", "status", "error"};

std::vector<std::string> With(std::vector<std::string> head) {
  head.insert(head.end(), kTimedCols.begin(), kTimedCols.end());
  return head;
}

// Figure 5.7: P pendulums, one r times faster (gravity × r², link stiffness
// × r², so it is a time-scaled copy of the others).
std::string Fig57Scene(int pendulums, double ratio, int only = -1) {
  std::ostringstream s;
  s << BallShape();
  for (int i = 0; i < pendulums; ++i) {
    if (only >= 0 && i != only) continue;
    const double pivot[3] = {3.0 * i, 0, 0};
    const double r2 = i == 0 ? ratio * ratio : 1.0;
    s << PendulumText("p" + std::to_string(i), pivot, 1.0, 0.5, 9.81 * r2, 1e4 * r2);
  }
  s << "simulator -finish 10\n";
  return s.str();
}

// Editing one object's initial state in an N-object scene through the
// editing model: incremental re-simulation against a from-scratch run, and
// a bit-for-bit comparison of every variable at every frame.
void RunEdit(const Config& cfg, Csv& csv) {
  const int n = cfg.quick ? 100 : 1000;
  auto add = [&](const char* variant, const Timed& t, const std::string& note) {
    auto row = Cols(t);
    row["case"] = "edit_one_of_" + std::to_string(n);
    row["variant"] = variant;
    if (!note.empty()) row["error"] = note;
    csv.Row(row);
  };
#ifndef ASGARD_BENCH_SESSION
  Timed te;
  te.status = "not_measurable";
  add("resimulate_vs_scratch", te, "core/session (the editing model) is not built");
#else
  std::ostringstream text;
  text << BallShape();
  for (int i = 0; i < n; ++i) {
    const double pivot[3] = {3.0 * (i % 32), 0.0, -3.0 * (i / 32)};
    text << PendulumText("p" + std::to_string(i), pivot, 1.0 + 0.5 * (i % 3), 0.3, 9.81, 1e4);
  }
  text << "simulator -finish 5\n";
  const std::string scene_text = text.str();
  auto iso = RunIsolated(
      [&]() {
        session::Session s(scene_text);
        if (!s.Simulate()) return std::string("error full run failed");
        const double full = s.last_stats().seconds;
        const long full_steps = s.last_stats().steps;
        std::vector<double> inc, reset, steps;
        bool equal = true;
        long compared = 0;
        const int edits = cfg.quick ? 2 : 3;
        for (int e = 0; e < edits; ++e) {
          const int target = (e * 337 + 5) % n;
          const std::string name = "p" + std::to_string(target);
          const int b = s.run()->equations->FindBody(name);
          const auto& bm = s.run()->equations->bodies[b];
          // Move the pendulum's shape origin a little (its initial position).
          const double x = bm.x0[0] + 0.01 * (e + 1), y = bm.x0[1], z = bm.x0[2];
          const auto r = s.SetParameter(name, "init_pos", {x, y, z});
          if (!r.ok) return std::string("error SetParameter failed");
          if (!s.Simulate()) return std::string("error incremental run failed");
          inc.push_back(s.last_stats().seconds);
          reset.push_back(s.last_stats().components_reset);
          steps.push_back(static_cast<double>(s.last_stats().steps));
          if (s.last_stats().rebuilt) return std::string("error the edit rebuilt the equations");
          // Bit-for-bit: a from-scratch run of the edited text.
          pipeline::Run scratch = pipeline::Simulate(s.text());
          const auto& eq = *scratch.equations;
          for (double t : FrameTimes(eq.t0, eq.t1))
            for (size_t v = 0; v < eq.variables.size(); ++v) {
              const double a = s.run()->simulation->Value(static_cast<int>(v), t);
              const double c = scratch.simulation->Value(static_cast<int>(v), t);
              ++compared;
              if (std::memcmp(&a, &c, sizeof a) != 0) equal = false;
            }
        }
        return Pack({full, static_cast<double>(full_steps), Median(inc), Median(reset),
                     Median(steps), equal ? 1.0 : 0.0, static_cast<double>(compared),
                     static_cast<double>(inc.size())});
      },
      cfg.timeout * 3);
  Timed full, incr;
  if (iso.status != "ok" || iso.output.rfind("error", 0) == 0) {
    full.status = incr.status = iso.status == "ok" ? "failed" : iso.status;
    add("full_run", full, iso.output);
    return;
  }
  const auto v = Unpack(iso.output);
  full.cpu = v[0], full.steps = v[1], full.runs = 1;
  incr.cpu = v[2], incr.components = v[3], incr.steps = v[4], incr.runs = v[7];
  add("full_run", full, "");
  add("incremental_after_edit", incr,
      std::string(v[5] != 0 ? "bit-for-bit equal" : "NOT bit-for-bit equal") +
          " to a from-scratch run (" + Num(v[6]) +
          " values compared); components_reset in 'components'");
  Log("  edit one of %d: full %s s, incremental %s s (%s%%), %s", n, Num(v[0]).c_str(),
      Num(v[2]).c_str(), Num(100 * v[2] / v[0]).c_str(), v[5] != 0 ? "bit-equal" : "DIFFERENT");
#endif
}

}  // namespace

void RunFigure57(const Config& cfg) {
  Csv csv(cfg.out_dir + "/fig57.csv", With({"ratio", "variant"}));
  const int P = 5;
  const std::vector<double> ratios = cfg.quick ? std::vector<double>{1, 10, 100}
                                               : std::vector<double>{1, 3, 10, 30, 100, 300, 1000};
  for (double r : ratios) {
    // Collisions off, as in the seed's experiment (and as for a lone body,
    // which never gets a collision monitor); "partitioned_collisions_on"
    // shows what the monitor costs when no pair can ever touch.
    pipeline::RunOptions part, one, coll;
    part.collisions = false;
    one = part;
    one.solver.partition = false;
    coll.collisions = true;
    const Timed tp = Measure(cfg, Fig57Scene(P, r), part);
    const Timed to = Measure(cfg, Fig57Scene(P, r), one);
    const Timed tc = Measure(cfg, Fig57Scene(P, r), coll);
    Timed sum;
    sum.cpu = 0;
    for (int i = 0; i < P; ++i) {
      const Timed ti = Measure(cfg, Fig57Scene(P, r, i), part);
      if (ti.status != "ok") sum.status = ti.status;
      sum.cpu += ti.cpu, sum.steps += ti.steps, sum.runs = ti.runs;
      sum.components += ti.components;
    }
    for (auto [name, t] : {std::pair<const char*, const Timed*>{"partitioned", &tp},
                           {"one_component", &to},
                           {"sum_alone", &sum},
                           {"partitioned_collisions_on", &tc}}) {
      auto row = Cols(*t);
      row["ratio"] = Num(r);
      row["variant"] = name;
      csv.Row(row);
    }
    Log("  fig5.7 ratio %-5s partitioned %-10s one component %-10s sum alone %-10s", Num(r).c_str(),
        Num(tp.cpu).c_str(), Num(to.cpu).c_str(), Num(sum.cpu).c_str());
  }
}

// Figure 5.11: pendulums A and B and a light ball that hits A twice and B
// once, plus n idle pendulums far away (never in a collision), swinging or
// hanging at rest.  Every link is an exact joint.
std::string Fig511Scene(int n, bool idle_at_rest = false) {
  std::ostringstream s;
  s << BallShape();
  const double pa[3] = {0, 3, 0}, pb[3] = {6, 3, 0};
  s << PendulumText("A", pa, 3.0, 0.0, 9.81, 0, 5.0)
    << PendulumText("B", pb, 3.0, 0.0, 9.81, 0, 5.0)
    << "body ball -shape ball -mass 1 -init_pos {3 0 0} -init_dpos {-4 0 0}\n";
  for (int i = 0; i < n; ++i) {
    const double pivot[3] = {3.0 * (i % 32), 10.0, -10.0 - 3.0 * (i / 32)};
    s << PendulumText("idle" + std::to_string(i), pivot, 1.0 + 0.5 * (i % 3),
                      idle_at_rest ? 0.0 : 0.3, 9.81, 0);
  }
  s << "simulator -finish 5\n";
  return s.str();
}

void RunFigure511(const Config& cfg) {
  Csv csv(cfg.out_dir + "/fig511.csv", With({"objects", "idle", "variant"}));
  const std::vector<int> ns =
      cfg.quick ? std::vector<int>{0, 10, 30} : std::vector<int>{0, 10, 30, 100, 300, 1000};
  struct Variant {
    const char* name;
    bool collisions, partition;
    solver::SolverOptions::Schedule schedule;
  };
  using S = solver::SolverOptions::Schedule;
  const Variant variants[] = {{"1_nocoll_one", false, false, S::kEventDriven},
                              {"2_nocoll_partitioned", false, true, S::kEventDriven},
                              {"3_coll_one", true, false, S::kEventDriven},
                              {"4_coll_partitioned_event", true, true, S::kEventDriven},
                              {"5_coll_partitioned_sequential", true, true, S::kSequential}};
  for (bool at_rest : {false, true})
    for (const Variant& v : variants) {
      bool gave_up = false;
      for (int n : ns) {
        pipeline::RunOptions o;
        o.collisions = v.collisions;
        o.solver.partition = v.partition;
        o.solver.schedule = v.schedule;
        Timed t;
        if (gave_up) {
          t.status = "skipped";
          t.error = "a smaller N already exceeded the time limit";
        } else {
          t = Measure(cfg, Fig511Scene(n, at_rest), o);
          gave_up = t.status == "timeout";
        }
        auto row = Cols(t);
        row["objects"] = Int(n + 3);
        row["idle"] = Int(n);
        row["variant"] = std::string(v.name) + (at_rest ? "_rest" : "");
        csv.Row(row);
        Log("  fig5.11 %-30s %-8s N=%-5d cpu %-10s impacts %-3s %s", v.name,
            at_rest ? "at rest" : "swinging", n, Num(t.cpu).c_str(), Num(t.impacts).c_str(),
            t.status.c_str());
      }
    }
}

namespace {

// Threads (SolverOptions::threads): each scene on one thread and on two,
// interleaved round by round in one child process.  The calling thread's
// CPU time no longer covers the work, so the solver phase is timed by the
// wall clock, with the CPU time of the whole process beside it; the first
// runs' waveforms and impacts are compared bit for bit.
bool SameResults(const pipeline::Run& a, const pipeline::Run& b) {
  if (!a.simulation || !b.simulation) return false;
  const solver::Simulation& sa = *a.simulation;
  const solver::Simulation& sb = *b.simulation;
  if (sa.component_count() != sb.component_count()) return false;
  for (int c = 0; c < sa.component_count(); ++c) {
    const auto& wa = sa.component(c).waveform();
    const auto& wb = sb.component(c).waveform();
    if (wa.size() != wb.size()) return false;
    const size_t bytes = static_cast<size_t>(wa.variable_count()) * sizeof(double);
    for (int k = 0; k < wa.size(); ++k)
      if (wa.time(k) != wb.time(k) || std::memcmp(wa.x(k), wb.x(k), bytes) != 0 ||
          std::memcmp(wa.f(k), wb.f(k), bytes) != 0 ||
          std::memcmp(wa.bubble(k), wb.bubble(k), bytes) != 0)
        return false;
  }
  if (!a.collisions != !b.collisions) return false;
  if (!a.collisions) return true;
  const auto& ia = a.collisions->impacts();
  const auto& ib = b.collisions->impacts();
  if (ia.size() != ib.size()) return false;
  for (size_t k = 0; k < ia.size(); ++k)
    if (ia[k].t != ib[k].t || ia[k].a != ib[k].a || ia[k].b != ib[k].b ||
        ia[k].impulse != ib[k].impulse)
      return false;
  return true;
}

double ProcessCpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

}  // namespace

void RunThreads(const Config& cfg) {
  Csv csv(cfg.out_dir + "/threads.csv", {"scene", "threads", "wall", "process_cpu", "runs", "steps",
                                         "components", "batches", "same", "status", "error"});
  struct Case {
    std::string name;
    std::string text;
    bool collisions;
  };
  std::vector<Case> cases = {
      {"fig511_1000_swinging_nocoll", Fig511Scene(1000), false},
      {"fig511_1000_swinging", Fig511Scene(1000), true},
      {"fig511_1000_rest", Fig511Scene(1000, true), true},
      {"fig511_100_swinging", Fig511Scene(100), true},
  };
  {
    const WpScene dp = DoublePendulumScene();
    std::string text = dp.text.substr(0, dp.text.rfind("simulator"));
    for (int i = 0; i < 99; ++i) {
      const double pivot[3] = {3.0 * (i % 10), 20.0, -10.0 - 3.0 * (i / 10)};
      text += PendulumText("idle" + std::to_string(i), pivot, 1.0, 0.0, 9.81, 0);
    }
    cases.push_back({"double_pendulum_plus_99_idle", text + "simulator -finish 10\n", false});
  }
  for (const char* name : {"balls100", "pile10"})
    if (std::string text = ContactSceneText(name); !text.empty())
      cases.push_back({name, text, true});
  for (const Case& c : cases) {
    constexpr size_t kFields =
        6;  // per thread count: wall, process CPU, runs, steps, components, batches
    auto iso = RunIsolated(
        [&]() -> std::string {
          std::vector<double> wall[2], cpu[2];
          pipeline::Run first[2];
          double spent = 0;
          for (int i = 0; i < cfg.repeats && spent < (cfg.quick ? 5.0 : 20.0); ++i)
            for (int k = 0; k < 2; ++k) {
              pipeline::RunOptions o;
              o.collisions = c.collisions;
              o.solver.threads = k + 1;
              pipeline::Run run = pipeline::Check(lang::Evaluate(c.text), o);
              const double c0 = ProcessCpuSeconds();
              pipeline::Solve(run, o);
              const double c1 = ProcessCpuSeconds();
              if (!run.ok) return "error " + run.solver_error;
              wall[k].push_back(run.seconds);
              cpu[k].push_back(c1 - c0);
              spent += run.seconds;
              if (i == 0) first[k] = std::move(run);
            }
          std::vector<double> packed;
          for (int k = 0; k < 2; ++k)
            packed.insert(packed.end(),
                          {Median(wall[k]), Median(cpu[k]), static_cast<double>(wall[k].size()),
                           static_cast<double>(first[k].simulation->totals().steps),
                           static_cast<double>(first[k].simulation->component_count()),
                           static_cast<double>(first[k].simulation->batches())});
          packed.push_back(SameResults(first[0], first[1]) ? 1.0 : 0.0);
          return Pack(packed);
        },
        cfg.timeout);
    const bool failed = iso.status == "ok" && iso.output.rfind("error ", 0) == 0;
    const std::vector<double> v =
        iso.status == "ok" && !failed ? Unpack(iso.output) : std::vector<double>{};
    for (int k = 0; k < 2; ++k) {
      std::map<std::string, std::string> row = {{"scene", c.name}, {"threads", Int(k + 1)}};
      row["status"] = failed ? "failed" : iso.status;
      if (failed) row["error"] = iso.output.substr(6);
      if (v.size() == 2 * kFields + 1) {
        const double* f = v.data() + kFields * static_cast<size_t>(k);
        row["wall"] = Num(f[0]);
        row["process_cpu"] = Num(f[1]);
        row["runs"] = Num(f[2]);
        row["steps"] = Num(f[3]);
        row["components"] = Num(f[4]);
        row["batches"] = Num(f[5]);
        row["same"] = v.back() == 1.0 ? "yes" : "no";
      } else if (iso.status == "ok" && !failed) {
        row["status"] = "crash";
      }
      csv.Row(row);
    }
    if (v.size() == 2 * kFields + 1)
      Log("  threads %-30s wall %s s on one thread, %s s on two (%sx); CPU %s s, %s s; same: %s",
          c.name.c_str(), Num(v[0]).c_str(), Num(v[kFields]).c_str(),
          Num(v[0] / v[kFields]).c_str(), Num(v[1]).c_str(), Num(v[kFields + 1]).c_str(),
          v.back() == 1.0 ? "yes" : "NO");
    else
      Log("  threads %-30s %s %s", c.name.c_str(), iso.status.c_str(), iso.output.c_str());
  }
}

void RunSkip(const Config& cfg) {
  Csv csv(cfg.out_dir + "/skip.csv", With({"case", "variant"}));
  // One active subsystem (the double pendulum) plus 99 independent idle
  // ones (pendulums hanging at rest), against the active one alone.
  const WpScene dp = DoublePendulumScene();
  std::string body = dp.text.substr(0, dp.text.rfind("simulator"));
  std::ostringstream idle;
  for (int i = 0; i < 99; ++i) {
    const double pivot[3] = {3.0 * (i % 10), 20.0, -10.0 - 3.0 * (i / 10)};
    idle << PendulumText("idle" + std::to_string(i), pivot, 1.0, 0.0, 9.81, 0);
  }
  const std::string alone = body + "simulator -finish 10\n";
  const std::string with = body + idle.str() + "simulator -finish 10\n";
  pipeline::RunOptions o;
  o.collisions = false;
  // A run takes a few milliseconds, where one run's noise (the timer, a
  // page fault, another process) is of the order of the 5% to be shown:
  // the median of many rounds (within the time budget), alone and with the
  // idle pendulums in turn.
  Config many = cfg;
  many.repeats = std::max(cfg.repeats, 101);
  const std::vector<Timed> pair = MeasureInterleaved(many, {alone, with}, o);
  const Timed& ta = pair[0];
  const Timed& tw = pair[1];
  pipeline::RunOptions one = o;
  one.solver.partition = false;
  const Timed t1 = Measure(cfg, with, one);
  for (auto [name, t] : {std::pair<const char*, const Timed*>{"active_alone", &ta},
                         {"active_plus_99_idle", &tw},
                         {"active_plus_99_idle_one_component", &t1}}) {
    auto row = Cols(*t);
    row["case"] = "idle_subsystems";
    row["variant"] = name;
    csv.Row(row);
  }
  Log("  skip: alone %s, +99 idle %s (ratio %s), one component %s", Num(ta.cpu).c_str(),
      Num(tw.cpu).c_str(), Num(tw.cpu / ta.cpu).c_str(), Num(t1.cpu).c_str());

  RunEdit(cfg, csv);
}

}  // namespace asgard::bench
