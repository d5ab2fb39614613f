// asgard_bench: the benchmark suite (scripts/bench.sh runs it).
//
//   asgard_bench [--quick] [--out DIR] [--repeats N] [--timeout S] [--pair dp5|tsit5] [SUITE...]
//   asgard_bench --scene NAME   (a contact scene's script, for asgard simulate)
//
// Suites: workprec stiff fig57 fig511 skip stress contact articulated threads (default:
// all).  Each writes CSV files into DIR (default bench-out); bench/report.py
// turns them into SVG plots and docs/benchmarks.md.
#include <sys/stat.h>

#include <cstdlib>
#include <cstring>
#include <fstream>
#include <set>
#include <string>

#include "bench/peers.h"
#include "bench/suites.h"

int main(int argc, char** argv) {
  using namespace asgard::bench;
  Config cfg;
  std::set<std::string> suites;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) {
        Log("%s needs a value", a.c_str());
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--quick") {
      cfg.quick = true;
    } else if (a == "--out") {
      cfg.out_dir = next();
    } else if (a == "--repeats") {
      cfg.repeats = std::max(1, std::atoi(next().c_str()));
    } else if (a == "--timeout") {
      cfg.timeout = std::atof(next().c_str());
    } else if (a == "--pair") {
      const std::string v = next();
      if (v != "dp5" && v != "tsit5") {
        Log("--pair must be dp5 or tsit5");
        return 2;
      }
      cfg.pair = v == "dp5" ? asgard::solver::SolverOptions::Pair::kDormandPrince
                            : asgard::solver::SolverOptions::Pair::kTsitouras;
    } else if (a == "--scene") {
      return PrintContactScene(next()) ? 0 : 2;
    } else if (a == "-h" || a == "--help") {
      std::printf(
          "usage: asgard_bench [--quick] [--out DIR] [--repeats N] [--timeout S] [--pair "
          "dp5|tsit5]\n"
          "                    [SUITE...]\n"
          "       asgard_bench --scene NAME   print a contact scene's script (pile30, "
          "balls100_60s, ...,\n"
          "                                   pileN@SEED: N cubes from another seed)\n"
          "suites: workprec stiff fig57 fig511 skip stress contact articulated threads (default: "
          "all)\n");
      return 0;
    } else if (!a.empty() && a[0] == '-') {
      Log("unknown option %s", a.c_str());
      return 2;
    } else {
      suites.insert(a);
    }
  }
  if (cfg.quick && cfg.repeats == 5) cfg.repeats = 3;
  mkdir(cfg.out_dir.c_str(), 0755);
  {
    std::ofstream peers(cfg.out_dir + "/peers.txt");
    for (const auto& n : PeerNotes()) peers << n << "\n";
    std::ofstream mode(cfg.out_dir + "/mode.txt");
    mode << (cfg.quick ? "quick" : "full") << " repeats=" << cfg.repeats
         << " timeout=" << cfg.timeout;
    if (cfg.pair)
      mode << " pair="
           << (*cfg.pair == asgard::solver::SolverOptions::Pair::kTsitouras ? "tsit5" : "dp5");
    mode << "\n";
  }
  auto want = [&](const char* s) { return suites.empty() || suites.count(s) > 0; };
  if (want("workprec")) RunWorkPrecision(cfg);
  if (want("stiff")) RunStiffSweep(cfg);
  if (want("fig57")) RunFigure57(cfg);
  if (want("fig511")) RunFigure511(cfg);
  if (want("skip")) RunSkip(cfg);
  if (want("stress")) RunStress(cfg);
  if (want("contact")) RunContact(cfg);
  if (want("articulated")) RunArticulated(cfg);
  if (want("threads")) RunThreads(cfg);
  return 0;
}
