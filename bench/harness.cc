#include "bench/harness.h"

#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <cstdarg>
#include <cstring>
#include <limits>
#include <sstream>

namespace asgard::bench {

double ThreadCpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

double WallSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

double Median(std::vector<double> v) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

double RepeatedCpu(int repeats, double budget, const std::function<double()>& once, double first,
                   double* runs) {
  std::vector<double> cpu{first};
  double spent = first;
  while (static_cast<int>(cpu.size()) < repeats && spent < budget) {
    cpu.push_back(once());
    spent += cpu.back();
  }
  *runs = static_cast<double>(cpu.size());
  return Median(cpu);
}

std::vector<double> FrameTimes(double t0, double t1, double rate) {
  std::vector<double> t;
  const long n = std::lround(std::floor((t1 - t0) * rate + 1e-9));
  for (long k = 0; k <= n; ++k) t.push_back(t0 + static_cast<double>(k) / rate);
  if (t.back() < t1 - 1e-12) t.push_back(t1);
  return t;
}

double RotationAngle(const double* q, const double* r) {
  double d = 0.0, nq = 0.0, nr = 0.0;
  for (int i = 0; i < 4; ++i) {
    d += q[i] * r[i];
    nq += q[i] * q[i];
    nr += r[i] * r[i];
  }
  const double c = std::min(1.0, std::abs(d) / std::sqrt(nq * nr));
  // 2 acos(c) loses precision near c = 1; use the sine of the half angle.
  double s2 = 0.0;  // |q ∧ r|² = |q|²|r|² − (q·r)²  (Lagrange identity)
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) {
      const double m = q[i] * r[j] - q[j] * r[i];
      s2 += m * m;
    }
  return 2.0 * std::atan2(std::sqrt(s2 / (nq * nr)), c);
}

double TrajectoryError(const Trajectory& run, const Trajectory& ref,
                       const std::vector<double>& radii, double scene_size) {
  const double inf = std::numeric_limits<double>::infinity();
  if (run.times.size() != ref.times.size() || run.poses.size() != ref.poses.size()) return inf;
  double worst = 0.0;
  for (size_t f = 0; f < run.poses.size(); ++f) {
    if (run.poses[f].size() != ref.poses[f].size()) return inf;
    for (size_t b = 0; b < run.poses[f].size(); ++b) {
      const Pose& a = run.poses[f][b];
      const Pose& r = ref.poses[f][b];
      double d2 = 0.0;
      for (int i = 0; i < 3; ++i) d2 += (a.p[i] - r.p[i]) * (a.p[i] - r.p[i]);
      const double radius = b < radii.size() ? radii[b] : 0.0;
      const double e = std::sqrt(d2) + RotationAngle(a.q, r.q) * radius;
      if (!std::isfinite(e)) return inf;
      worst = std::max(worst, e);
    }
  }
  return worst / scene_size;
}

Csv::Csv(const std::string& path, std::vector<std::string> columns)
    : path_(path), columns_(std::move(columns)) {
  file_ = std::fopen(path.c_str(), "w");
  if (!file_) {
    Log("cannot write %s", path.c_str());
    return;
  }
  for (size_t i = 0; i < columns_.size(); ++i)
    std::fprintf(file_, "%s%s", i ? "," : "", columns_[i].c_str());
  std::fprintf(file_, "\n");
  std::fflush(file_);
}

Csv::~Csv() {
  if (file_) std::fclose(file_);
}

void Csv::Row(const std::map<std::string, std::string>& values) {
  if (!file_) return;
  for (size_t i = 0; i < columns_.size(); ++i) {
    auto it = values.find(columns_[i]);
    std::string v = it == values.end() ? "" : it->second;
    if (v.find_first_of(",\"\n") != std::string::npos) {
      std::string q = "\"";
      for (char c : v) q += c == '"' ? std::string("\"\"") : std::string(1, c == '\n' ? ' ' : c);
      v = q + "\"";
    }
    std::fprintf(file_, "%s%s", i ? "," : "", v.c_str());
  }
  std::fprintf(file_, "\n");
  std::fflush(file_);
}

std::string Num(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

std::string Int(long v) { return std::to_string(v); }

Isolated RunIsolated(const std::function<std::string()>& fn, double seconds) {
  Isolated r;
  int fds[2];
  if (pipe(fds) != 0) {
    r.status = "crash";
    r.output = "pipe failed";
    return r;
  }
  std::fflush(nullptr);
  const double start = WallSeconds();
  const pid_t pid = fork();
  if (pid == 0) {
    close(fds[0]);
    std::string out;
    try {
      out = fn();
    } catch (const std::exception& e) {
      out = std::string("exception: ") + e.what();
    }
    const char* p = out.data();
    size_t left = out.size();
    while (left > 0) {
      const ssize_t w = write(fds[1], p, left);
      if (w <= 0) break;
      p += w;
      left -= static_cast<size_t>(w);
    }
    close(fds[1]);
    _exit(0);
  }
  close(fds[1]);
  if (pid < 0) {
    close(fds[0]);
    r.status = "crash";
    r.output = "fork failed";
    return r;
  }
  bool timed_out = false;
  char buf[65536];
  for (;;) {
    const double left = seconds - (WallSeconds() - start);
    if (left <= 0) {
      timed_out = true;
      break;
    }
    pollfd p{fds[0], POLLIN, 0};
    const int rc = poll(&p, 1, static_cast<int>(std::min(left, 1.0) * 1000) + 1);
    if (rc < 0) continue;
    if (rc == 0) continue;
    const ssize_t n = read(fds[0], buf, sizeof buf);
    if (n <= 0) break;
    r.output.append(buf, static_cast<size_t>(n));
  }
  close(fds[0]);
  if (timed_out) kill(pid, SIGKILL);
  int status = 0;
  waitpid(pid, &status, 0);
  r.wall = WallSeconds() - start;
  if (timed_out) {
    r.status = "timeout";
  } else if (WIFEXITED(status) && WEXITSTATUS(status) == 0) {
    r.status = "ok";
  } else {
    r.status = "crash";
    if (WIFSIGNALED(status)) r.output = std::string("signal ") + strsignal(WTERMSIG(status));
  }
  return r;
}

std::string Pack(const std::vector<double>& v) {
  std::ostringstream s;
  s.precision(17);
  for (double x : v) s << x << ' ';
  return s.str();
}

std::vector<double> Unpack(const std::string& s) {
  std::vector<double> v;
  std::istringstream in(s);
  std::string w;
  while (in >> w) {
    if (w == "nan" || w == "-nan")
      v.push_back(std::numeric_limits<double>::quiet_NaN());
    else if (w == "inf")
      v.push_back(std::numeric_limits<double>::infinity());
    else if (w == "-inf")
      v.push_back(-std::numeric_limits<double>::infinity());
    else
      v.push_back(std::strtod(w.c_str(), nullptr));
  }
  return v;
}

void Log(const char* fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  std::vfprintf(stderr, fmt, ap);
  va_end(ap);
  std::fputc('\n', stderr);
}

}  // namespace asgard::bench
