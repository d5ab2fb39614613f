// asgard: the command-line front end.
//
//   asgard check FILE
//   asgard simulate FILE [--until T] [--rtol R] [--atol A] [--out FILE.csv|FILE.json]
//                        [--stats] [--method auto|dp5|esdirk3|tr|trbdf2] [--pair dp5|tsit5]
//                        [--single] [--sequential] [--no-collisions] [--threads N] [--quiet]
//   asgard edit FILE --set ELEMENT.PARAM=VALUE ... [-o OUT] [--list]
//   asgard render FILE ... -o OUT       (render_cmd.cc)
//   asgard export FILE ... -o OUT       (render_cmd.cc)
//
// Each command evaluates the scene text once.
// Exit status: 0 success, 1 scene errors or solver failure, 2 usage errors.
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "core/app/cli.h"
#include "core/app/commands.h"
#include "core/lang/lang.h"
#include "core/pipeline/pipeline.h"
#include "core/session/session.h"
#include "web/server/launch.h"

namespace {

using asgard::app::ParseNumber;
using asgard::app::ReadFile;
using asgard::app::TakeFile;
using asgard::app::Usage;
using asgard::pipeline::Frames;

constexpr const char* kMainHelp =
    R"(asgard — physically-based 3D animation: simulate Asgard scene scripts

Usage:
  asgard check FILE            check a scene for errors
  asgard simulate FILE [...]   simulate a scene and write its trajectories
  asgard edit FILE --set ...   change parameters as a graphical editor would
  asgard render FILE [...]     draw frames, pictures and movies of a scene
  asgard export FILE [...]     write the scene for other programs (POV-Ray, glTF, ...)
  asgard studio FILE [--port P] edit the scene in the browser (http://127.0.0.1:P/)
  asgard help [COMMAND]        show help (also: asgard COMMAND --help)

Scene scripts are Tcl with Asgard's element commands; see docs/language.md.
)";

constexpr const char* kCheckHelp = R"(Usage: asgard check FILE

Evaluates the scene script FILE and forms its equations without simulating.
Each problem is printed as FILE:LINE:COL: error: message.
Exit status 0 when the scene has no errors, 1 otherwise.
)";

constexpr const char* kEditHelp = R"(Usage: asgard edit FILE --set ELEMENT.PARAM=VALUE ... [-o OUT]

Applies edits the way the graphical viewer does: each changes only the
literal numbers of the parameter in the text (comments and formatting stay),
or appends the option to its command when it is not written yet.

  ELEMENT   a name (b1, tr1) or kind#index for unnamed elements (force#0,
            link#1, lightsource#0, view#0), or simulator
  PARAM     an option without the dash: init_pos init_rot init_dpos init_drot
            mass offset offset1 offset2 pos dir points finish ...; for forces,
            torques and links "vector" sets -x -y -z together
  VALUE     numbers separated by spaces or commas

  -o OUT    write the edited scene to OUT (default: standard output)
  --list    list every parameter, whether it is editable, and why not

Exit status 0 on success, 1 when a parameter is read-only (the reason is
printed: made in a loop, computed by an expression, ...) or unknown, 2 on bad
usage.
)";

constexpr const char* kSimulateHelp = R"(Usage: asgard simulate FILE [options]

Simulates the scene script FILE and prints a summary.

Options:
  --until T         simulate to time T (default: the scene's simulator -finish)
  --rtol R          relative tolerance (default 1e-6, or the scene's -rtol; at most 0.1)
  --atol A          absolute tolerance (default 1e-9, or the scene's -atol)
  --out FILE        write body trajectories sampled at the frame rate
                    (simulator -frames, default 30 per second): .csv or .json
  --stats           print the components (their variables) and solver counters
  --method M        auto (default: the explicit pair where a component is not stiff,
                    the L-stable ESDIRK 3(2) where it is), dp5 (always the
                    explicit pair), esdirk3 (always the ESDIRK), tr (the
                    trapezoidal rule, TR-BDF2 where stiff), trbdf2
  --pair P          the explicit pair: tsit5 (Tsitouras 5(4), default) or
                    dp5 (Dormand-Prince 5(4))
  --single          solve all equations as one component (no partitioning)
  --sequential      run components to completion one after another
                    (no event-driven scheduling)
  --no-collisions   ignore collisions (default: the scene's simulator -collisions)
  --threads N       step up to N independent components at once, 1 to 4
                    (default: the machine's cores, at most 4); the results
                    are the same, bit for bit, whatever N
  --quiet           no summary
  -h, --help        this help

Exit status 0 on success, 1 on scene errors or solver failure, 2 on bad usage.
)";

void PrintDiagnostics(const std::string& file, std::vector<asgard::scene::Diagnostic> ds) {
  // In source order (scene errors and equation errors are found in two passes).
  std::stable_sort(ds.begin(), ds.end(), [](const auto& a, const auto& b) {
    return a.span.line != b.span.line ? a.span.line < b.span.line : a.span.column < b.span.column;
  });
  for (const auto& d : ds) std::cerr << asgard::lang::FormatDiagnostic(file, d) << "\n";
}

class ProgressBar {
 public:
  ProgressBar(double t0, double t1, bool enabled) : t0_(t0), t1_(t1), enabled_(enabled) {}
  void operator()(double t) {
    if (!enabled_) return;
    const int width = 40;
    const double frac = t1_ > t0_ ? std::clamp((t - t0_) / (t1_ - t0_), 0.0, 1.0) : 1.0;
    const int filled = static_cast<int>(frac * width);
    if (filled == last_ && frac < 1.0) return;
    last_ = filled;
    std::fprintf(stderr, "\r[%s%s] %5.1f%%  t = %.4g", std::string(filled, '#').c_str(),
                 std::string(width - filled, '.').c_str(), 100 * frac, t);
    if (frac >= 1.0) std::fprintf(stderr, "\n");
    std::fflush(stderr);
  }

 private:
  double t0_, t1_;
  bool enabled_;
  int last_ = -1;
};

constexpr const char* kFields[] = {"x",  "y",  "z",  "qw", "qx", "qy", "qz",
                                   "dx", "dy", "dz", "wx", "wy", "wz"};

void BodyValues(const asgard::pipeline::BodyFrame& f, double out[13]) {
  for (int a = 0; a < 3; ++a) out[a] = f.p[a];
  for (int a = 0; a < 4; ++a) out[3 + a] = f.q[a];
  for (int a = 0; a < 3; ++a) out[7 + a] = f.v[a];
  for (int a = 0; a < 3; ++a) out[10 + a] = f.w[a];
}

bool WriteCsv(const std::string& path, const Frames& frames) {
  std::ofstream out(path);
  if (!out) return false;
  out << "t";
  for (const auto& b : frames.bodies)
    for (const char* f : kFields) out << "," << b << "." << f;
  out << "\n" << std::setprecision(17);
  for (size_t k = 0; k < frames.times.size(); ++k) {
    out << frames.times[k];
    for (const auto& bf : frames.states[k]) {
      double v[13];
      BodyValues(bf, v);
      for (double x : v) out << "," << x;
    }
    out << "\n";
  }
  return static_cast<bool>(out);
}

nlohmann::json CountersJson(const asgard::solver::Counters& c) {
  nlohmann::json j = nlohmann::json::object();
  for (const auto& f : asgard::solver::kCounterFields) j[f.name] = c.*f.member;
  return j;
}

bool WriteJson(const std::string& path, const std::string& scene_file, const Frames& frames,
               const asgard::pipeline::Run& run) {
  nlohmann::json j;
  j["scene"] = scene_file;
  j["t0"] = run.equations->t0;
  j["t1"] = run.equations->t1;
  j["times"] = frames.times;
  j["bodies"] = nlohmann::json::array();
  for (size_t b = 0; b < frames.bodies.size(); ++b) {
    nlohmann::json body;
    body["name"] = frames.bodies[b];
    body["static"] = run.equations->bodies[b].is_static;
    for (int f = 0; f < 13; ++f) {
      std::vector<double> series;
      for (size_t k = 0; k < frames.times.size(); ++k) {
        double v[13];
        BodyValues(frames.states[k][b], v);
        series.push_back(v[f]);
      }
      body[kFields[f]] = series;
    }
    j["bodies"].push_back(body);
  }
  j["counters"] = CountersJson(run.simulation->totals());
  j["components"] = run.simulation->component_count();
  std::ofstream out(path);
  if (!out) return false;
  out << j.dump(1) << "\n";
  return static_cast<bool>(out);
}

void PrintCounters(std::ostream& out, const asgard::solver::Counters& c) {
  out << "  steps " << c.steps << " (rejected " << c.rejected_steps << ", at rest " << c.rest_steps
      << ", ballistic " << c.ballistic_steps << ", explicit " << c.explicit_steps << ", ESDIRK "
      << c.esdirk_steps << ", TR-BDF2 " << c.trbdf2_steps << ", method switches "
      << c.method_switches << "), rhs evaluations " << c.rhs_evaluations << ", jacobians "
      << c.jacobian_evaluations << ", factorizations " << c.factorizations << ", newton iterations "
      << c.newton_iterations << " (failures " << c.newton_failures << "), truncated steps "
      << c.truncated_steps << ", restarts " << c.restarts << "\n";
}

void PrintStats(const asgard::pipeline::Run& run) {
  const auto& sim = *run.simulation;
  const auto& eq = *run.equations;
  std::cout << "components: " << sim.component_count() << "\n";
  for (int c = 0; c < sim.component_count(); ++c) {
    const auto& comp = sim.component(c);
    std::cout << "  [" << c << "] {";
    const auto& vars = comp.variables();
    for (size_t j = 0; j < vars.size(); ++j) {
      if (j == 12 && vars.size() > 16) {
        std::cout << " ... " << vars.size() - 13 << " more ...";
        j = vars.size() - 1;
      }
      std::cout << (j ? " " : "") << eq.variables[vars[j]].name;
    }
    std::cout << "}";
    const auto& up = sim.partition().upstream[c];
    if (!up.empty()) {
      std::cout << " reads";
      for (int u : up) std::cout << " [" << u << "]";
    }
    const auto& k = comp.counters();
    std::cout << "  steps " << k.steps << " rejected " << k.rejected_steps << " rhs "
              << k.rhs_evaluations << " jac " << k.jacobian_evaluations << " lu "
              << k.factorizations << " newton " << k.newton_iterations << "\n";
  }
  std::cout << "totals:\n";
  PrintCounters(std::cout, sim.totals());
  std::cout << "threads: " << sim.options().threads << " (batches of runs on several at once "
            << sim.batches() << ")\n";
  if (run.collisions) {
    const auto& c = run.collisions->counters();
    std::cout << "collisions: windows " << c.windows << ", bodies boxed " << c.boxes
              << ", loose boxes " << c.loose_boxes << ", broad-phase pairs " << c.broad_phase_pairs
              << ", narrow-phase queries " << c.narrow_phase_queries << ", distance queries "
              << c.distance_queries << ", impacts " << run.collisions->impacts().size()
              << " (applied " << c.impacts << ", undone " << c.invalidated_impacts
              << "; island solves " << c.resting_events << " of " << c.contacts_solved
              << " contacts, landings answered in them " << c.impacts_absorbed << ", sleeps "
              << c.sleeps << ", wakes " << c.wakes << ")\n";
    for (const auto& imp : run.collisions->impacts())
      std::cout << "  t=" << imp.t << " " << eq.bodies[imp.a].name << " - " << eq.bodies[imp.b].name
                << " impulse " << imp.impulse << "\n";
  } else {
    std::cout << "collisions: off\n";
  }
}

int Edit(const std::vector<std::string>& args) {
  std::string file, out_path;
  bool list = false;
  std::vector<std::string> sets;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a == "-h" || a == "--help") {
      std::cout << kEditHelp;
      return 0;
    } else if (a == "--set") {
      if (i + 1 >= args.size()) return Usage("--set needs ELEMENT.PARAM=VALUE", kEditHelp);
      sets.push_back(args[++i]);
    } else if (a == "-o") {
      if (i + 1 >= args.size()) return Usage("-o needs a file name", kEditHelp);
      out_path = args[++i];
    } else if (a == "--list") {
      list = true;
    } else if (const int status = TakeFile("edit", a, file, kEditHelp); status >= 0) {
      return status;
    }
  }
  if (file.empty()) return Usage("edit: FILE is required", kEditHelp);
  if (sets.empty() && !list) return Usage("edit: nothing to do (give --set or --list)", kEditHelp);
  std::string text;
  if (!ReadFile(file, text)) return 1;
  asgard::session::Session session(text);
  if (list) {
    for (const auto& p : session.Parameters())
      std::cout << p.element << "." << p.param << " = {" << p.value << "}  "
                << (p.editable ? "editable" : "read-only: " + p.reason) << "\n";
    if (sets.empty()) return 0;
  }
  for (const auto& s : sets) {
    const size_t eq = s.find('='), dot = s.rfind('.', eq);
    if (eq == std::string::npos || dot == std::string::npos || dot == 0)
      return Usage("--set expects ELEMENT.PARAM=VALUE, got '" + s + "'", kEditHelp);
    std::vector<double> values;
    std::string v = s.substr(eq + 1);
    std::replace(v.begin(), v.end(), ',', ' ');
    std::istringstream in(v);
    std::string tok;
    while (in >> tok) {
      double d;
      if (!ParseNumber(tok, d))
        return Usage("'" + tok + "' is not a number in '" + s + "'", kEditHelp);
      values.push_back(d);
    }
    if (values.empty()) return Usage("no value in '" + s + "'", kEditHelp);
    const auto r = session.SetParameter(s.substr(0, dot), s.substr(dot + 1, eq - dot - 1), values);
    if (!r.ok) {
      std::cerr << "asgard: " << file << ": " << r.error << "\n";
      return 1;
    }
  }
  if (out_path.empty()) {
    std::cout << session.text();
    return 0;
  }
  // Write beside the target and rename, so a failure never leaves half a file.
  const std::string tmp = out_path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary);
    out << session.text();
    if (!out) {
      std::cerr << "asgard: cannot write '" << out_path << "'\n";
      std::remove(tmp.c_str());
      return 1;
    }
  }
  if (std::rename(tmp.c_str(), out_path.c_str()) != 0) {
    std::cerr << "asgard: cannot write '" << out_path << "'\n";
    std::remove(tmp.c_str());
    return 1;
  }
  return 0;
}

int Check(const std::vector<std::string>& args) {
  std::string file;
  for (const auto& a : args) {
    if (a == "-h" || a == "--help") {
      std::cout << kCheckHelp;
      return 0;
    }
    if (const int status = TakeFile("check", a, file, kCheckHelp); status >= 0) return status;
  }
  if (file.empty()) return Usage("check: FILE is required", kCheckHelp);
  std::string text;
  if (!ReadFile(file, text)) return 1;
  auto run = asgard::pipeline::Check(text);
  PrintDiagnostics(file, run.diagnostics);
  if (!run.ok) return 1;
  std::cout << file << ": ok (" << run.scene.bodies.size() << " bodies, "
            << run.equations->variables.size() << " state variables)\n";
  return 0;
}

int Simulate(const std::vector<std::string>& args) {
  std::string file, out_path;
  bool stats = false, quiet = false;
  asgard::pipeline::RunOptions opts;
  opts.solver.threads = asgard::solver::MachineThreads();
  std::optional<double> rtol, atol;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    auto value = [&](const char* name) -> std::optional<std::string> {
      if (i + 1 >= args.size()) return std::nullopt;
      (void)name;
      return args[++i];
    };
    if (a == "-h" || a == "--help") {
      std::cout << kSimulateHelp;
      return 0;
    } else if (a == "--until" || a == "--rtol" || a == "--atol") {
      auto v = value(a.c_str());
      double d;
      if (!v || !ParseNumber(*v, d)) return Usage(a + " needs a number", kSimulateHelp);
      if (a == "--until")
        opts.until = d;
      else if (d <= 0)
        return Usage(a + " must be positive", kSimulateHelp);
      else if (a == "--rtol")
        rtol = d;
      else
        atol = d;
    } else if (a == "--out") {
      auto v = value("--out");
      if (!v) return Usage("--out needs a file name", kSimulateHelp);
      out_path = *v;
      if (!out_path.ends_with(".csv") && !out_path.ends_with(".json"))
        return Usage("--out: the file name must end in .csv or .json", kSimulateHelp);
    } else if (a == "--method") {
      auto v = value("--method");
      if (v == "auto")
        opts.solver.method = asgard::solver::SolverOptions::Method::kAuto;
      else if (v == "tr")
        opts.solver.method = asgard::solver::SolverOptions::Method::kTrapezoidal;
      else if (v == "trbdf2")
        opts.solver.method = asgard::solver::SolverOptions::Method::kTrBdf2;
      else if (v == "esdirk3")
        opts.solver.method = asgard::solver::SolverOptions::Method::kEsdirk;
      else if (v == "dp5")
        opts.solver.method = asgard::solver::SolverOptions::Method::kExplicit;
      else
        return Usage("--method must be auto, dp5, esdirk3, tr or trbdf2", kSimulateHelp);
    } else if (a == "--pair") {
      auto v = value("--pair");
      if (v == "dp5")
        opts.solver.pair = asgard::solver::SolverOptions::Pair::kDormandPrince;
      else if (v == "tsit5")
        opts.solver.pair = asgard::solver::SolverOptions::Pair::kTsitouras;
      else
        return Usage("--pair must be dp5 or tsit5", kSimulateHelp);
    } else if (a == "--threads") {
      auto v = value("--threads");
      double d;
      if (!v || !ParseNumber(*v, d) || d != std::floor(d) || d < 1 || d > 4)
        return Usage("--threads needs a whole number from 1 to 4", kSimulateHelp);
      opts.solver.threads = static_cast<int>(d);
    } else if (a == "--stats") {
      stats = true;
    } else if (a == "--quiet") {
      quiet = true;
    } else if (a == "--no-collisions") {
      opts.collisions = false;
    } else if (a == "--single") {
      opts.solver.partition = false;
    } else if (a == "--sequential") {
      opts.solver.schedule = asgard::solver::SolverOptions::Schedule::kSequential;
    } else if (const int status = TakeFile("simulate", a, file, kSimulateHelp); status >= 0) {
      return status;
    }
  }
  if (file.empty()) return Usage("simulate: FILE is required", kSimulateHelp);
  std::string text;
  if (!ReadFile(file, text)) return 1;
  // The equations are formed (up to --until) before simulating, so that the
  // progress bar knows the interval.
  auto run = asgard::pipeline::Check(asgard::lang::Evaluate(text), opts);
  if (!run.ok) {
    PrintDiagnostics(file, run.diagnostics);
    return 1;
  }
  const double t0 = run.equations->t0, t1 = run.equations->t1;
  if (!(t1 > t0)) {
    std::cerr << "asgard: --until must be after the start time " << t0 << "\n";
    return 2;
  }
  ProgressBar bar(t0, t1, isatty(STDERR_FILENO) && !quiet);
  opts.progress = [&bar](double t) { bar(t); };
  // Command-line tolerances win over the scene's.
  if (rtol || atol) {
    opts.use_scene_tolerances = false;
    opts.solver.rtol = rtol.value_or(opts.solver.rtol);
    opts.solver.atol = atol.value_or(opts.solver.atol);
  }
  asgard::pipeline::Solve(run, opts);
  PrintDiagnostics(file, run.diagnostics);
  if (!run.solver_error.empty())
    std::cerr << "asgard: " << file << ": " << run.solver_error << "\n";
  if (!run.ok) return 1;
  const Frames frames = asgard::pipeline::SampleFrames(*run.equations, *run.simulation,
                                                       asgard::pipeline::FrameRate(run.scene));
  if (!out_path.empty()) {
    const bool ok = out_path.ends_with(".csv") ? WriteCsv(out_path, frames)
                                               : WriteJson(out_path, file, frames, run);
    if (!ok) {
      std::cerr << "asgard: cannot write '" << out_path << "'\n";
      return 1;
    }
  }
  if (!quiet) {
    const auto& eq = *run.equations;
    const auto totals = run.simulation->totals();
    std::cout << file << ": simulated t = " << eq.t0 << " .. " << eq.t1 << " in " << std::fixed
              << std::setprecision(3) << run.seconds << " s" << std::defaultfloat << "\n"
              << "  " << eq.bodies.size() << " bodies, " << eq.variables.size()
              << " state variables, " << run.simulation->component_count() << " components, "
              << totals.steps << " steps\n";
    std::cout << std::setprecision(6);
    for (size_t b = 0; b < frames.bodies.size(); ++b) {
      const auto& last = frames.states.back()[b];
      std::cout << "  " << frames.bodies[b] << " at t=" << frames.times.back() << ": position ("
                << last.p[0] << ", " << last.p[1] << ", " << last.p[2] << ") velocity ("
                << last.v[0] << ", " << last.v[1] << ", " << last.v[2] << ")\n";
    }
    if (!out_path.empty())
      std::cout << "  wrote " << frames.times.size() << " frames to " << out_path << "\n";
  }
  if (stats) PrintStats(run);
  return 0;
}

}  // namespace

int Main(int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty()) {
    std::cerr << kMainHelp;
    return 2;
  }
  const std::string cmd = args[0];
  args.erase(args.begin());
  if (cmd == "-h" || cmd == "--help" || cmd == "help") {
    if (!args.empty() && args[0] == "check")
      std::cout << kCheckHelp;
    else if (!args.empty() && args[0] == "simulate")
      std::cout << kSimulateHelp;
    else if (!args.empty() && args[0] == "edit")
      std::cout << kEditHelp;
    else if (!args.empty() && args[0] == "render")
      std::cout << asgard::app::kRenderHelp;
    else if (!args.empty() && args[0] == "export")
      std::cout << asgard::app::kExportHelp;
    else
      std::cout << kMainHelp;
    return 0;
  }
  if (cmd == "check") return Check(args);
  if (cmd == "simulate") return Simulate(args);
  if (cmd == "edit") return Edit(args);
  if (cmd == "render") return asgard::app::RenderCommand(args);
  if (cmd == "export") return asgard::app::ExportCommand(args);
  if (cmd == "studio") {  // the editor in the browser (web/server/launch.h)
    std::string file, error;
    asgard::serve::LaunchOptions lo;
    if (!asgard::serve::ParseLaunchArgs(args, &file, &lo, &error))
      return Usage("studio: " + error, asgard::serve::kServeUsage);
    return asgard::serve::ServeScene(file, lo);
  }
  return Usage("unknown command '" + cmd + "'", kMainHelp);
}

// Nothing escapes as a signal: running out of memory (a run asked for more
// frames or steps than fit) is an error message and exit status 1.
int main(int argc, char** argv) {
  // Scenes are evaluated on this thread, with nothing else running.
  asgard::lang::CapProcessMemoryDuringEvaluation(true);
  try {
    return Main(argc, argv);
  } catch (const std::bad_alloc&) {
    std::cerr << "asgard: error: out of memory (the run needs more memory than there is; "
                 "fewer frames, a larger -maxstep or a shorter -finish may help)\n";
  } catch (const std::length_error& e) {
    std::cerr << "asgard: error: out of memory (a result would be too large: " << e.what() << ")\n";
  } catch (const std::exception& e) {
    std::cerr << "asgard: internal error: " << e.what() << "\n";
  }
  return 1;
}
