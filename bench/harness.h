// Shared machinery of the benchmark suite: CPU clocks, medians, CSV output,
// body trajectories sampled at 30 Hz and the common error metric, and
// isolated runs (a forked child with a time limit, so a hang or a crash in
// one case is reported, never silent, and never stops the suite).
#pragma once

#include <cmath>
#include <cstdio>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/solver/component.h"

namespace asgard::bench {

// CPU time of the calling thread, seconds.
double ThreadCpuSeconds();
double WallSeconds();

double Median(std::vector<double> v);

// One body's pose at one output frame.
struct Pose {
  double p[3] = {0, 0, 0};
  double q[4] = {1, 0, 0, 0};  // w x y z, unit
};
// Poses of every body at each frame time: poses[frame][body].
struct Trajectory {
  std::vector<double> times;
  std::vector<std::vector<Pose>> poses;
  bool empty() const { return times.empty(); }
};

// Frame times from t0 to t1 inclusive at `rate` per second.
std::vector<double> FrameTimes(double t0, double t1, double rate = 30.0);

// Angle of the rotation taking q to r (radians, in [0, π]).
double RotationAngle(const double* q, const double* r);

// The common error metric: max over frames and bodies of
// (|p − p_ref| + angle(q, q_ref) · radius_b) / scene_size.  Returns +inf when
// the trajectories do not match in shape or contain a NaN.
double TrajectoryError(const Trajectory& run, const Trajectory& ref,
                       const std::vector<double>& radii, double scene_size);

// Measurement record: name → value; written as CSV rows with a fixed header.
class Csv {
 public:
  Csv(const std::string& path, std::vector<std::string> columns);
  ~Csv();
  Csv(const Csv&) = delete;
  Csv& operator=(const Csv&) = delete;
  void Row(const std::map<std::string, std::string>& values);
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::vector<std::string> columns_;
  std::FILE* file_ = nullptr;
};

std::string Num(double v);
std::string Int(long v);

// Runs `fn` in a forked child with a time limit.  The child returns a text
// (e.g. serialised numbers) through a pipe.  status: "ok", "timeout" (killed
// after `seconds`), "crash" (signal or non-zero exit).
struct Isolated {
  std::string status;
  std::string output;
  double wall = 0.0;
};
Isolated RunIsolated(const std::function<std::string()>& fn, double seconds);

// Serialise a flat list of doubles (for RunIsolated) and back.
std::string Pack(const std::vector<double>& v);
std::vector<double> Unpack(const std::string& s);

// Options shared by every suite.
struct Config {
  bool quick = false;
  int repeats = 5;  // median of this many runs
  std::string out_dir = "bench-out";
  double timeout = 120.0;  // per isolated case
  // Asgard's explicit pair in the work-precision suites (--pair dp5|tsit5;
  // default: the solver's).
  std::optional<solver::SolverOptions::Pair> pair;
};

// Median CPU time of a case measured `first` seconds on its first run:
// `once` (which returns CPU seconds) is repeated up to `repeats` runs in all,
// fewer once `budget` seconds are spent.  `runs` gets the count.
double RepeatedCpu(int repeats, double budget, const std::function<double()>& once, double first,
                   double* runs);

// Logs a progress line to stderr.
void Log(const char* fmt, ...) __attribute__((format(printf, 1, 2)));

}  // namespace asgard::bench
