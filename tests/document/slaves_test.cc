// dochost and its slaves under faults and load: a slave killed in the middle
// of a conversion is started again once (then the poster), the exit status
// says when OUT is not all the document asks, at most --slaves slaves run at
// once however many animations a document has, and a slave past its memory
// limit ends alone.  dochost runs as a child here while the test watches its
// asgard-core children in /proc (and kills some).
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "tests/common/sanitizer.h"
#include "tests/document/exec.h"

extern char** environ;

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

const std::string kDochost = std::string(ASGARD_BINARY_DIR) + "/host-shim/dochost";

fs::path Scratch(const std::string& name) {
  return asgard::testing::ScratchFolder("scratch_slaves", name);
}
using asgard::testing::FileText;

size_t Count(const std::string& text, const std::string& word) {
  size_t n = 0;
  for (size_t at = 0; (at = text.find(word, at)) != std::string::npos; at += word.size()) ++n;
  return n;
}

// A document of one paragraph and one animation per scene (scene braces
// escaped for the document reader by the caller).
std::string Document(const std::vector<std::string>& scenes) {
  std::string d = "DOCUMENT ARTICLE\n<ARTICLE>\n<TITLE>{Slaves}</TITLE>\n<BODY>\n";
  d += "<PARAGRAPH><TEXT>{The text before the animations.}</TEXT></PARAGRAPH>\n";
  for (const std::string& s : scenes)
    d += "<PARAGRAPH><DOCUMENT>\nDOCUMENT ANIMATION\n<ANIMATION>\n<ASGARD>{\n" + s +
         "}</ASGARD>\n</ANIMATION>\n</DOCUMENT></PARAGRAPH>\n";
  d +=
      "<PARAGRAPH><TEXT>{The text after the animations.}</TEXT></PARAGRAPH>\n</BODY>\n</ARTICLE>\n";
  return d;
}

const std::string kBall =
    "simulator -finish 0.5 -frames 4\nshape_set ball -desc \\{-sub \\{-sphere 0.5\\}\\}\n"
    "body b -shape ball -init_dpos \\{1 0 0\\}\n";
// About two and a half seconds of simulation on an idle machine (840 000
// ESDIRK steps of three balls on stiff links to moving points, 360 MB),
// longer than a slave takes to start and load even under AddressSanitizer: a
// kill after one second lands in the middle of the simulation, of the first
// start and of the restarted one.  (At half the time, about two seconds, a
// loaded run once saw only one of two kills land while the simulation was
// under way.)  The work is in the steps, not in their number: 1.8 million
// ballistic steps took this long until appending a sample stopped
// reallocating the waveform, and then half of it.  Each ball is held off its
// centre, so that its turning and its motion are one component of 13
// variables: held at its centre, the idle axis and spin of a ball are
// components of their own, and the same run took a fifth of the time.
const std::string kLong =
    "simulator -finish 28 -maxstep 0.0001 -collisions 0\n"
    "shape_set ball -desc \\{-sub \\{-sphere 0.2\\}\\}\n"
    "for \\{set i 0\\} \\{$i < 3\\} \\{incr i\\} \\{\n"
    "  body b$i -shape ball -init_pos [list [expr \\{$i - 0.1\\}] 0 0] -init_dpos \\{1 0 0\\}\n"
    "  link -body1 b$i -offset1 \\{0.1 0 0\\} -x \"$i + sin(t)\" -y 0 -z 0 -tightness 1e8\n\\}\n";

struct Watched {
  int status = -1;  // exit status, -1 after a signal
  std::string out;  // stdout and stderr
  int most_running = 0;
  int killed = 0;
};

// The live (not zombie) asgard-core children of `parent`.
std::vector<pid_t> Slaves(pid_t parent) {
  std::vector<pid_t> out;
  for (const auto& e : fs::directory_iterator("/proc")) {
    const std::string name = e.path().filename().string();
    if (name.empty() || name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::ifstream stat(e.path() / "stat");
    std::string line;
    if (!std::getline(stat, line)) continue;
    // pid (comm) state ppid ...: comm may hold spaces, so read after ')'.
    const size_t close = line.rfind(')'), open = line.find('(');
    if (close == std::string::npos || open == std::string::npos) continue;
    std::istringstream rest(line.substr(close + 2));
    char state = 0;
    long ppid = 0;
    rest >> state >> ppid;
    if (ppid == parent && state != 'Z' && line.substr(open + 1, close - open - 1) == "asgard-core")
      out.push_back(static_cast<pid_t>(std::stol(name)));
  }
  return out;
}

// Runs dochost with `args`, looking at its slaves every few milliseconds:
// counts the most running at once, and kills (SIGKILL) each of the first
// `kills` slaves once it has run for `kill_after`.
Watched RunDochost(const std::vector<std::string>& args, const fs::path& log, int kills = 0,
                   std::chrono::milliseconds kill_after = std::chrono::milliseconds(0)) {
  Watched w;
  std::vector<std::string> argv_s = {kDochost};
  argv_s.insert(argv_s.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : argv_s) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  pid_t pid = -1;
  const int rc = posix_spawn(&pid, kDochost.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) {
    ADD_FAILURE() << "cannot start dochost: " << rc;
    return w;
  }
  std::map<pid_t, Clock::time_point> seen;
  const auto deadline = Clock::now() + std::chrono::seconds(120);
  int status = 0;
  while (waitpid(pid, &status, WNOHANG) == 0) {
    if (Clock::now() > deadline) {
      kill(pid, SIGKILL);
      waitpid(pid, &status, 0);
      ADD_FAILURE() << "dochost did not end within 120 s";
      break;
    }
    const std::vector<pid_t> slaves = Slaves(pid);
    w.most_running = std::max(w.most_running, static_cast<int>(slaves.size()));
    for (pid_t s : slaves) {
      const auto first = seen.emplace(s, Clock::now()).first->second;
      if (w.killed < kills && Clock::now() - first >= kill_after && kill(s, SIGKILL) == 0) {
        ++w.killed;
        seen[s] = Clock::time_point::max();  // once
      }
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  w.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  w.out = FileText(log);
  return w;
}

// A slave program for --core that counts its starts (one line each in
// dir/starts) and makes the first `failing` of them exit while loading their
// text (asgard-core's exit-on-load test hook), then runs asgard-core.  Each
// start loads and simulates once, so the count is the simulations.
fs::path CountingCore(const fs::path& dir, int failing) {
  const fs::path script = dir / "core.sh", starts = dir / "starts";
  fs::remove(starts);
  std::ofstream(script) << "#!/bin/sh\necho start >> '" << starts.string() << "'\n"
                        << "if [ \"$(wc -l < '" << starts.string() << "')\" -le " << failing
                        << " ]; then ASGARD_CORE_FAULT=exit-on-load; export ASGARD_CORE_FAULT; fi\n"
                        << "exec '" << ASGARD_BINARY_DIR << "/core/app/asgard-core' \"$@\"\n";
  fs::permissions(script, fs::perms::owner_all);
  return script;
}
size_t Starts(const fs::path& dir) { return Count(FileText(dir / "starts"), "start"); }

std::string PdfText(const fs::path& pdf) {
  return asgard::testing::Exec("pdftotext " + pdf.string() + " -").out;
}

// Killed in the middle of the simulation a conversion waits for, the slave
// is started again once and the page gets its frame (before, the animation
// fell back to its poster, or to nothing, with exit status 0).
TEST(Slaves, ASlaveKilledMidConversionIsRestartedOnce) {
  const fs::path dir = Scratch("kill_once");
  std::ofstream(dir / "long.ens") << Document({kLong});
  const fs::path pdf = dir / "long.pdf";
  const Watched w = RunDochost({"convert", (dir / "long.ens").string(), "-o", pdf.string()},
                               dir / "log", 1, std::chrono::milliseconds(1000));
  ASSERT_EQ(w.killed, 1) << "the slave ended before it could be killed: " << w.out;
  EXPECT_EQ(w.status, 0) << w.out;
  EXPECT_NE(w.out.find("animation 1: asgard-core killed by signal 9"), std::string::npos) << w.out;
  EXPECT_NE(w.out.find("it was restarted once"), std::string::npos) << w.out;
  const std::string text = PdfText(pdf);
  EXPECT_NE(text.find("3 bodies, t = 0 .. 28 s"), std::string::npos) << text;
  EXPECT_NE(text.find("frame at t = 0.00 s"), std::string::npos) << "a live frame: " << text;
  EXPECT_NE(text.find("The text after the animations."), std::string::npos) << text;
}

// Killed again after its restart: the poster (here none: the caption says
// why), the reason on stderr, and exit status 3, not 0.
TEST(Slaves, ASlaveKilledTwiceFallsBackAndTheExitStatusSaysSo) {
  const fs::path dir = Scratch("kill_twice");
  std::ofstream(dir / "long.ens") << Document({kLong, kBall});
  const fs::path pdf = dir / "long.pdf";
  const Watched w = RunDochost({"convert", (dir / "long.ens").string(), "-o", pdf.string()},
                               dir / "log", 2, std::chrono::milliseconds(1000));
  ASSERT_EQ(w.killed, 2) << w.out;
  EXPECT_EQ(w.status, 3) << w.out;
  EXPECT_NE(w.out.find("it was restarted once"), std::string::npos) << w.out;
  EXPECT_NE(w.out.find("dochost: " + (dir / "long.ens").string() +
                       ": animation 1: asgard-core killed by signal 9"),
            std::string::npos)
      << w.out;
  const std::string text = PdfText(pdf);
  EXPECT_EQ(Count(text, "frame at t ="), 1u) << "only the second animation is live: " << text;
  EXPECT_NE(text.find("Animation 1 · asgard-core killed by signal 9"), std::string::npos) << text;
  EXPECT_NE(text.find("The text after the animations."), std::string::npos) << text;
}

// A slave that dies while loading its text is started again once (before,
// the node was never made, so nothing was restarted and the animation fell
// back at once) and the page gets its live frame.
TEST(Slaves, ASlaveThatDiesLoadingItsTextIsRestartedOnce) {
  const fs::path dir = Scratch("die_loading");
  std::ofstream(dir / "ball.ens") << Document({kBall});
  const fs::path pdf = dir / "ball.pdf";
  const Watched w = RunDochost({"convert", (dir / "ball.ens").string(), "-o", pdf.string(),
                                "--core", CountingCore(dir, 1).string()},
                               dir / "log");
  EXPECT_EQ(w.status, 0) << w.out;
  EXPECT_EQ(Starts(dir), 2u) << w.out;
  EXPECT_NE(w.out.find("animation 1: asgard-core exited with status 3 while answering 'load'; it "
                       "was restarted once"),
            std::string::npos)
      << w.out;
  EXPECT_EQ(Count(PdfText(pdf), "frame at t = 0.00 s"), 1u) << PdfText(pdf);
}

// Every slave dies loading: one restart, no more, then the poster the
// document keeps, the reason on stderr and exit status 3.
TEST(Slaves, ASlaveThatAlwaysDiesLoadingFallsBackToThePosterAfterOneRestart) {
  const fs::path dir = Scratch("die_loading_always");
  std::ofstream(dir / "ball.ens") << Document({kBall});
  // A poster in the document first (recompute stores one).
  const fs::path with_poster = dir / "poster.ens";
  const Watched r = RunDochost(
      {"verb", (dir / "ball.ens").string(), "recompute", "-o", with_poster.string(), "--quiet"},
      dir / "log");
  ASSERT_EQ(r.status, 0) << r.out;
  ASSERT_NE(FileText(with_poster).find("<POSTER>"), std::string::npos);
  const fs::path pdf = dir / "ball.pdf";
  const Watched w = RunDochost({"convert", with_poster.string(), "-o", pdf.string(), "--core",
                                CountingCore(dir, 1000).string()},
                               dir / "log");
  EXPECT_EQ(w.status, 3) << w.out;
  EXPECT_EQ(Starts(dir), 2u) << "started once and restarted once: " << w.out;
  EXPECT_NE(w.out.find("it was restarted once"), std::string::npos) << w.out;
  EXPECT_NE(w.out.find("dochost: " + with_poster.string() +
                       ": animation 1: asgard-core exited with status 3 while answering 'load'"),
            std::string::npos)
      << w.out;
  const std::string text = PdfText(pdf);
  EXPECT_EQ(Count(text, "frame at t ="), 0u) << text;
  EXPECT_NE(text.find("showing the last poster"), std::string::npos) << text;  // a line ends there
}

// Eight animations with --slaves 2: never more than two slaves at once
// (before, one per animation stayed up to the end), and every animation is
// drawn live, on the pages and in the HTML page.
TEST(Slaves, ManyAnimationsRunAtMostTheAllowedSlavesAtOnce) {
  const fs::path dir = Scratch("many");
  std::vector<std::string> scenes;
  for (int k = 0; k < 8; ++k)
    scenes.push_back(kBall + "# animation " + std::to_string(k + 1) + "\n");
  std::ofstream(dir / "many.ens") << Document(scenes);
  const fs::path pdf = dir / "many.pdf";
  const std::string core = CountingCore(dir, 0).string();
  const Watched p = RunDochost(
      {"convert", (dir / "many.ens").string(), "-o", pdf.string(), "--slaves", "2", "--core", core},
      dir / "log");
  EXPECT_EQ(p.status, 0) << p.out;
  EXPECT_GE(p.most_running, 1);
  EXPECT_LE(p.most_running, 2) << p.out;
  EXPECT_EQ(Count(PdfText(pdf), "frame at t = 0.00 s"), 8u) << PdfText(pdf);
  // Each animation simulated once (before, the six stopped to make room were
  // simulated again to be drawn: 14).
  EXPECT_EQ(Starts(dir), 8u) << p.out;

  const fs::path html = dir / "many.html";
  const Watched h = RunDochost({"convert", (dir / "many.ens").string(), "-o", html.string(),
                                "--slaves", "2", "--core", CountingCore(dir, 0).string()},
                               dir / "log");
  EXPECT_EQ(h.status, 0) << h.out;
  EXPECT_LE(h.most_running, 2) << h.out;
  EXPECT_EQ(Starts(dir), 8u) << h.out;
  const std::string page = FileText(html);
  // Each animation's frames (0, 1/4 and 1/2 s) are in the page.
  EXPECT_EQ(Count(page, "data:image/png;base64,"), 8u * 3) << h.out;

  EXPECT_EQ(asgard::testing::Exec(kDochost + " convert " + (dir / "many.ens").string() + " -o " +
                                  html.string() + " --slaves 0")
                .status,
            2);
}

// A slave that needs more memory than --slave-memory ends alone: its
// animation falls back (exit status 3, the reason on stderr) and the other
// animation and the text are drawn.  Before, the slave took what it wanted.
TEST(Slaves, ASlavePastItsMemoryLimitEndsAlone) {
  if (asgard::tests::kAddressSanitizer)
    GTEST_SKIP() << "the slave's memory limit is off under AddressSanitizer";
  const fs::path dir = Scratch("memory");
  // 400 MB of 10 MB strings: within the scene language's own 512 MB.
  const std::string greedy =
      "for \\{set i 0\\} \\{$i < 40\\} \\{incr i\\} \\{ lappend l [string repeat x 10000000] "
      "\\}\n" +
      kBall;
  std::ofstream(dir / "greedy.ens") << Document({greedy, kBall});
  const fs::path pdf = dir / "greedy.pdf";
  const Watched w = RunDochost(
      {"convert", (dir / "greedy.ens").string(), "-o", pdf.string(), "--slave-memory", "256"},
      dir / "log");
  EXPECT_EQ(w.status, 3) << w.out;
  EXPECT_NE(w.out.find("greedy.ens: animation 1: "), std::string::npos) << w.out;
  EXPECT_EQ(w.out.find("animation 2:"), std::string::npos) << w.out;
  const std::string text = PdfText(pdf);
  EXPECT_EQ(Count(text, "frame at t = 0.00 s"), 1u) << text;
  EXPECT_NE(text.find("The text after the animations."), std::string::npos) << text;

  // The same document with the default limit: both animations are drawn.
  const Watched d =
      RunDochost({"convert", (dir / "greedy.ens").string(), "-o", pdf.string()}, dir / "log");
  EXPECT_EQ(d.status, 0) << d.out;
  EXPECT_EQ(Count(PdfText(pdf), "frame at t = 0.00 s"), 2u);
}

}  // namespace
