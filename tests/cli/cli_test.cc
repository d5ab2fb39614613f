// The asgard command line: help, error format, exit status, outputs.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "tests/common/sanitizer.h"

namespace {

struct Result {
  int status;
  std::string out;  // stdout and stderr together
};

Result Asgard(const std::string& args) {
  const std::string cmd =
      std::string(ASGARD_BINARY_DIR) + "/core/app/asgard " + args + " 2>&1 </dev/null";
  FILE* p = popen(cmd.c_str(), "r");
  std::string out;
  char buf[4096];
  size_t n;
  while ((n = fread(buf, 1, sizeof buf, p)) > 0) out.append(buf, n);
  const int st = pclose(p);
  return {WIFEXITED(st) ? WEXITSTATUS(st) : -1, out};
}

std::string Sample(const std::string& name) {
  return std::string(ASGARD_SOURCE_DIR) + "/samples/" + name;
}

std::filesystem::path TempFile(const std::string& name, const std::string& text = "") {
  const auto dir =
      std::filesystem::temp_directory_path() / ("asgard_cli_" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  const auto path = dir / name;
  if (!text.empty()) std::ofstream(path) << text;
  return path;
}

TEST(Cli, HelpIsAvailableEverywhere) {
  for (const char* args : {"--help", "help", "check --help", "simulate --help", "help simulate"}) {
    const Result r = Asgard(args);
    EXPECT_EQ(r.status, 0) << args;
    EXPECT_NE(r.out.find("Usage"), std::string::npos) << args << ": " << r.out;
  }
  EXPECT_NE(Asgard("simulate --help").out.find("--until"), std::string::npos);
}

TEST(Cli, BadUsageExitsWithTwoAndSaysWhy) {
  Result r = Asgard("");
  EXPECT_EQ(r.status, 2);
  r = Asgard("frobnicate");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.out.find("unknown command 'frobnicate'"), std::string::npos);
  r = Asgard("simulate " + Sample("pendulum.al") + " --rtol abc");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.out.find("--rtol needs a number"), std::string::npos);
  r = Asgard("simulate " + Sample("pendulum.al") + " --out result.txt");
  EXPECT_EQ(r.status, 2);
  r = Asgard("simulate " + Sample("pendulum.al") + " --bogus");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.out.find("unknown option '--bogus'"), std::string::npos);
  for (const char* threads : {"0", "5", "1.5", "two"}) {
    r = Asgard("simulate " + Sample("pendulum.al") + " --threads " + threads);
    EXPECT_EQ(r.status, 2) << threads;
    EXPECT_NE(r.out.find("--threads needs a whole number from 1 to 4"), std::string::npos) << r.out;
  }
}

TEST(Cli, AnyNumberOfThreadsWritesTheSameTrajectories) {
  // Independent components on up to four threads: the same file, byte for
  // byte (the solver's results are the same bit for bit).
  const auto scene =
      TempFile("pendulums.al",
               "shape_set ball -desc {-sub {-pos {0 0 0} -sphere 0.5}}\n"
               "for {set i 0} {$i < 8} {incr i} {\n"
               "  set x [expr {3.0 * $i}]\n"
               "  body p$i -shape ball -init_pos [list [expr {$x + 0.1 * $i}] -1 0]\n"
               "  link -body1 p$i -offset1 [list [expr {-0.1 * $i}] 1 0] -x $x\n"
               "  force -body p$i -y -9.81 -gravitational 1\n"
               "}\n"
               "simulator -finish 3\n");
  std::string out[4];
  for (int threads = 1; threads <= 4; ++threads) {
    const auto csv = TempFile("threads" + std::to_string(threads) + ".csv");
    const Result r = Asgard("simulate " + scene.string() + " --stats --threads " +
                            std::to_string(threads) + " --out " + csv.string());
    ASSERT_EQ(r.status, 0) << r.out;
    EXPECT_NE(r.out.find("threads: " + std::to_string(threads)), std::string::npos) << r.out;
    std::ifstream in(csv);
    out[threads - 1].assign(std::istreambuf_iterator<char>(in), {});
    ASSERT_GT(out[threads - 1].size(), 1000u);
    EXPECT_EQ(out[threads - 1], out[0]) << threads;
  }
}

TEST(Cli, CheckReportsErrorsAsFileLineColumn) {
  const auto path = TempFile("bad.al",
                             "shape_set ball -desc {-sub {-pos {0 0 0} -sphere 1}}\n"
                             "body b -shape ball\n"
                             "  body c -shape ball -mass -2\n");
  const Result r = Asgard("check " + path.string());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.out.find(path.string() + ":3:"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("error:"), std::string::npos) << r.out;
}

TEST(Cli, CheckAcceptsTheSeedSamples) {
  for (const char* s : {"pendulum.al", "figure62.al"}) {
    const Result r = Asgard("check " + Sample(s));
    EXPECT_EQ(r.status, 0) << r.out;
    EXPECT_NE(r.out.find("ok"), std::string::npos);
  }
}

TEST(Cli, AMissingFileIsAnError) {
  const Result r = Asgard("check /nonexistent/scene.al");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.out.find("cannot read"), std::string::npos);
}

TEST(Cli, SimulateWritesCsvWithOneRowPerFrame) {
  const auto out = TempFile("p.csv");
  const Result r = Asgard("simulate " + Sample("pendulum.al") + " --out " + out.string());
  ASSERT_EQ(r.status, 0) << r.out;
  std::ifstream in(out);
  std::string header, line;
  std::getline(in, header);
  EXPECT_EQ(header.rfind("t,b1.x,b1.y,b1.z,b1.qw", 0), 0u) << header;
  int rows = 0;
  std::string last;
  while (std::getline(in, line)) {
    ++rows;
    last = line;
  }
  EXPECT_EQ(rows, 151);  // 5 s at 30 frames per second, both ends included
  EXPECT_EQ(last.rfind("5,", 0), 0u) << last;
}

TEST(Cli, SimulateWritesJsonAndHonoursUntil) {
  const auto out = TempFile("p.json");
  const Result r =
      Asgard("simulate " + Sample("pendulum.al") + " --until 1 --quiet --out " + out.string());
  ASSERT_EQ(r.status, 0) << r.out;
  std::ifstream in(out);
  const auto j = nlohmann::json::parse(in);
  EXPECT_EQ(j["t1"].get<double>(), 1.0);
  EXPECT_EQ(j["times"].back().get<double>(), 1.0);
  ASSERT_EQ(j["bodies"].size(), 3u);
  EXPECT_EQ(j["bodies"][0]["name"], "b1");
  EXPECT_EQ(j["bodies"][0]["x"].size(), j["times"].size());
  EXPECT_GT(j["counters"]["steps"].get<long>(), 0);
}

TEST(Cli, StatsListTheComponentsAndCounters) {
  const Result r = Asgard("simulate " + Sample("pendulum.al") + " --stats");
  ASSERT_EQ(r.status, 0) << r.out;
  // The two linked rods, and b3 fused: its axes, rates and rotation.
  EXPECT_NE(r.out.find("components: 2"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("{b3.x b3.y b3.z b3.dx b3.dy b3.dz b3.qw b3.qx b3.qy b3.qz b3.w1 b3.w2 "
                       "b3.w3}"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("rhs evaluations"), std::string::npos);
  EXPECT_NE(r.out.find("truncated steps"), std::string::npos);
}

TEST(Cli, AnEndlessLoopEndsWithAClearError) {
  const auto path = TempFile("loop.al", "set x 0\nwhile 1 {incr x}\n");
  const Result r = Asgard("simulate " + path.string());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.out.find(":2:"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("limit"), std::string::npos) << r.out;
}

// Running out of memory is an error message and exit status 1, not an abort
// by an escaping std::bad_alloc (10 million frames under a 600 MB limit).
TEST(Cli, OutOfMemoryIsAClearErrorNotASignal) {
  if (asgard::tests::kAddressSanitizer)
    GTEST_SKIP() << "an address-space limit cannot apply to an AddressSanitizer build";
  const auto path = TempFile("frames.al",
                             "shape_set s -desc {-sub {-sphere 1}}\n"
                             "body b -shape s -init_dpos {1 0 0}\n"
                             "simulator -finish 100000 -frames 100\n");
  const auto csv = TempFile("frames.csv");
  const std::string cmd = "ulimit -v 600000; " + std::string(ASGARD_BINARY_DIR) +
                          "/core/app/asgard simulate " + path.string() + " --out " + csv.string() +
                          " 2>&1";
  FILE* p = popen(("bash -c '" + cmd + "'").c_str(), "r");
  std::string out;
  char buf[4096];
  size_t n;
  while ((n = fread(buf, 1, sizeof buf, p)) > 0) out.append(buf, n);
  const int st = pclose(p);
  ASSERT_TRUE(WIFEXITED(st)) << out;
  EXPECT_EQ(WEXITSTATUS(st), 1) << out;
  EXPECT_NE(out.find("asgard: error: out of memory"), std::string::npos) << out;
}

// A list of 4000 references to one 400 kB string is cheap, but its text
// (1.6 GB) is made inside the substitution of `${l}s`, where no command's
// guard runs.  The tool lowers its data limit while a scene is evaluated, so
// that allocation fails at the memory limit (512 MB) and is reported at the
// line: the peak stays near the limit (it was 1.6 GB, in a scene `check`
// then reported as a mere oversized value).
TEST(Cli, MemoryAScriptTakesOutsideAnyCommandIsLimitedToo) {
  if (asgard::tests::kAddressSanitizer)
    GTEST_SKIP() << "a data-segment limit cannot apply to an AddressSanitizer build";
  const auto path = TempFile("shared.al",
                             "set x [string repeat x 400000]\n"
                             "for {set i 0} {$i < 4000} {incr i} {lappend l $x}\n"
                             "set y ${l}s\n");
  const auto log = TempFile("shared.log");
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    // One open file for both streams (two opens would overwrite each other).
    if (std::freopen(log.c_str(), "w", stdout) == nullptr || dup2(STDOUT_FILENO, STDERR_FILENO) < 0)
      _exit(126);
    const std::string tool = std::string(ASGARD_BINARY_DIR) + "/core/app/asgard";
    execl(tool.c_str(), tool.c_str(), "check", path.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  int st = 0;
  rusage usage{};
  ASSERT_EQ(wait4(pid, &st, 0, &usage), pid);
  std::stringstream out;
  out << std::ifstream(log).rdbuf();
  ASSERT_TRUE(WIFEXITED(st)) << out.str();
  EXPECT_EQ(WEXITSTATUS(st), 1) << out.str();
  EXPECT_NE(out.str().find(":3:1: error: scene exceeded its memory limit (512 MB"),
            std::string::npos)
      << out.str();
  // The limit, its 64 MB slack and the process itself; far below 1.6 GB.
  EXPECT_LT(usage.ru_maxrss, 700 * 1024) << "peak " << usage.ru_maxrss << " kB";
}

// Time spans that would never end, or need more frames than fit, are
// refused by check with the line and column of the option.
TEST(Cli, ImpossibleTimeSpansAreRefusedByCheck) {
  const auto path = TempFile("span.al", "simulator -start -1e308 -finish 1e308\n");
  const Result r = Asgard("check " + path.string());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.out.find("span.al:1:33: error: simulator: the time span"), std::string::npos)
      << r.out;
}

}  // namespace
