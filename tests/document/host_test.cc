// The host side: plugin loading and refusal, storage through the real ASGARD
// medium (property style, both flavours), slave faults (SIGKILL mid
// simulation, a slave that stops answering, malformed answers), restart, and
// the host document's poster frames.
#include <gtest/gtest.h>
#include <signal.h>
#include <stdlib.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>

#include "formats/document/document.h"
#include "formats/document/file.h"
#include "formats/document/xml.h"
#include "host-shim/host_document.h"
#include "host-shim/html.h"
#include "host-shim/layout.h"
#include "host-shim/medium.h"
#include "tests/common/samples.h"

namespace asgard::host {
namespace {

const std::string kPlugins = std::string(ASGARD_BINARY_DIR) + "/medium-plugin";
const std::string kTestPlugins = std::string(ASGARD_BINARY_DIR) + "/tests/document/plugins";
const std::string kCore = std::string(ASGARD_BINARY_DIR) + "/core/app/asgard-core";

HostOptions Opts(const std::string& name, const std::string& core = "") {
  HostOptions o;
  o.name = name;
  o.slave_path = core;
  return o;
}

MediumRegistry& Registry() {
  static MediumRegistry registry({kTestPlugins, kPlugins});
  return registry;
}

Medium& Asgard() {
  std::string error;
  Medium* m = Registry().Find("ASGARD", &error);
  EXPECT_NE(m, nullptr) << error;
  return *m;
}

TEST(Plugins, TheAsgardMediumLoadsWithAllInterfaces) {
  Medium& m = Asgard();
  EXPECT_EQ(m.element(), "ASGARD");
  EXPECT_EQ(m.entry().abi_major, static_cast<uint32_t>(ASGARD_MEDIUM_ABI_MAJOR));
  EXPECT_NE(m.storage(), nullptr);
  EXPECT_NE(m.node(), nullptr);
  EXPECT_NE(m.presentation(), nullptr);
  EXPECT_NE(m.rendition(), nullptr);
  EXPECT_NE(m.node_rpc(), nullptr);  // ABI 1.1
}

TEST(Plugins, AnotherMajorVersionIsRefusedWithAClearMessage) {
  std::string error;
  EXPECT_EQ(Registry().Find("FUTURE", &error), nullptr);
  EXPECT_NE(error.find("medium_future.so"), std::string::npos) << error;
  EXPECT_NE(error.find("ABI 2.3"), std::string::npos) << error;
  EXPECT_NE(error.find("this host speaks ABI 1."), std::string::npos) << error;
  EXPECT_NE(error.find("major versions must match"), std::string::npos) << error;
}

TEST(Plugins, MissingPluginOrEntryPointIsReported) {
  std::string error;
  EXPECT_EQ(Registry().Find("NOENTRY", &error), nullptr);
  EXPECT_NE(error.find("has no entry point asgard_medium_get_entry()"), std::string::npos) << error;
  EXPECT_EQ(Registry().Find("NOWHERE", &error), nullptr);
  EXPECT_NE(error.find("no medium plugin for <NOWHERE>"), std::string::npos) << error;
}

TEST(Plugins, APluginReturningErrorsDoesNotStopTheHost) {
  const std::string bytes =
      "DOCUMENT M\n<M><P><DOCUMENT>\nDOCUMENT F\n<F><FAILING>{bad}</FAILING></F>\n</DOCUMENT>"
      "<DOCUMENT>\nDOCUMENT F\n<F><FAILING>{ok}</FAILING></F>\n</DOCUMENT></P></M>\n";
  auto parsed = document::Parse(bytes);
  ASSERT_TRUE(parsed.ok());
  std::vector<std::string> warnings;
  HostDocument doc(*parsed.document, Registry(), Opts("t.ens"), &warnings);
  ASSERT_EQ(doc.items().size(), 2u);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("refused on purpose"), std::string::npos) << warnings[0];
  EXPECT_EQ(doc.items()[0].medium, nullptr);
  Embedded& ok = doc.items()[1];
  ASSERT_NE(ok.medium, nullptr);
  EXPECT_FALSE(doc.Simulate(ok));
  EXPECT_NE(ok.message.find("no node today"), std::string::npos) << ok.message;
  EXPECT_FALSE(doc.SetText(ok, "new"));
  EXPECT_NE(ok.message.find("cannot encode"), std::string::npos);
  EXPECT_TRUE(doc.Frame(ok, ASGARD_DEVICE_PAGE, 10, 10, 0, 0).empty());
  // An ABI 1.0 medium takes no requests of its own: said, not a crash.
  std::string result;
  EXPECT_EQ(doc.Call(ok, "scene_state", "{}", &result), ASGARD_ERR_UNSUPPORTED);
  EXPECT_NE(ok.message.find("takes no requests of its own (medium ABI 1.1)"), std::string::npos)
      << ok.message;
  EXPECT_EQ(document::Write(doc.document()), bytes);
}

// ---- storage through the plugin ----

std::string Decode(const std::string& body, int32_t* status = nullptr) {
  asgard_bytes out{};
  asgard_error e{};
  const int32_t s = Asgard().storage()->decode(body.data(), body.size(), &out, &e);
  if (status) *status = s;
  return s == ASGARD_OK ? Asgard().Take(out) : std::string(e.message);
}
std::string Encode(const std::string& text) {
  asgard_bytes out{};
  asgard_error e{};
  EXPECT_EQ(Asgard().storage()->encode(text.data(), text.size(), &out, &e), ASGARD_OK);
  return Asgard().Take(out);
}

std::string RandomScene(std::mt19937& rng) {
  static const std::vector<std::string> pieces = {"{",
                                                  "}",
                                                  "\\",
                                                  "\\{",
                                                  "\\\\}",
                                                  "<ASGARD>",
                                                  "</ASGARD>",
                                                  "<DOCUMENT>",
                                                  "DOCUMENT X",
                                                  " ",
                                                  "\n",
                                                  "\t",
                                                  "\r\n",
                                                  "é",
                                                  "→",
                                                  "日本語",
                                                  "𝄞",
                                                  "&lt;",
                                                  "<",
                                                  ">",
                                                  "\"",
                                                  "]]>",
                                                  "body b -shape s -init_pos {0 0 0}",
                                                  "$x",
                                                  "[list a b]",
                                                  "\\n",
                                                  "# comment"};
  std::uniform_int_distribution<int> len(0, 60), pick(0, static_cast<int>(pieces.size()) - 1);
  std::string s;
  for (int i = len(rng); i > 0; --i) s += pieces[pick(rng)];
  return s;
}

TEST(Storage, FigureSixTwoDecodesToTheSceneWithBracesUnescaped) {
  auto parsed = document::Parse(ReadSample("memo.ens"));
  ASSERT_TRUE(parsed.ok());
  HostDocument doc(*parsed.document, Registry(), Opts("memo.ens"));
  ASSERT_EQ(doc.items().size(), 1u);
  EXPECT_EQ(doc.items()[0].element, "ASGARD");
  std::string figure62;
  ASSERT_TRUE(document::ReadFile(std::string(ASGARD_SOURCE_DIR) + "/samples/figure62.al", figure62,
                                 nullptr));
  const std::string scene = doc.items()[0].text;
  for (const char* line : {"shape_set ss1 -desc {-sub {-pos {0 0 0} -sphere 0.5}}",
                           "body b3 -artbody 1 -shape ss1 -init_pos {1 0 0} -init_dpos {0 1 0}",
                           "simulator -finish 3"}) {
    EXPECT_NE(scene.find(line), std::string::npos) << line;
    EXPECT_NE(figure62.find(line), std::string::npos) << line;
  }
}

TEST(Storage, RandomScenesSurviveByteForByteInBothFlavours) {
  std::mt19937 rng(6204);
  for (int i = 0; i < 300; ++i) {
    const std::string scene = RandomScene(rng);
    const std::string body = Encode(scene);
    ASSERT_EQ(Decode(body), scene);
    // Inside a whole document, through the SGML and the XML flavour.
    const std::string file = "DOCUMENT M\n<M><DOCUMENT>\nDOCUMENT ANIMATION\n<ANIMATION><ASGARD>" +
                             body + "</ASGARD></ANIMATION>\n</DOCUMENT></M>\n";
    auto parsed = document::Parse(file);
    ASSERT_TRUE(parsed.ok()) << parsed.error.Format();
    auto xml = document::ParseXml(document::WriteXml(*parsed.document));
    ASSERT_TRUE(xml.ok()) << xml.error.Format();
    EXPECT_EQ(document::Write(*xml.document), file);
    for (const auto* d : {&*parsed.document, &*xml.document}) {
      HostDocument doc(*d, Registry(), Opts("r.ens"));
      ASSERT_EQ(doc.items().size(), 1u);
      EXPECT_EQ(doc.items()[0].text, scene);
    }
  }
}

TEST(Storage, MalformedBodiesGetAClearError) {
  int32_t status = 0;
  EXPECT_NE(Decode("no braces", &status).find("must hold one {"), std::string::npos);
  EXPECT_EQ(status, ASGARD_ERR_SYNTAX);
  EXPECT_NE(Decode("{a{b}", &status).find("unescaped brace"), std::string::npos);
  EXPECT_EQ(Decode(" \n{x\\}y}\n"), "x}y");
}

// ---- nodes and slave faults ----

struct Node {
  asgard_node* node = nullptr;
  ~Node() {
    if (node) Asgard().node()->destroy(node);
  }
};

asgard_node_status Status(asgard_node* n) {
  asgard_node_status s{};
  s.struct_size = sizeof s;
  Asgard().node()->get_status(n, &s);
  return s;
}

int32_t Create(const std::string& text, Node& n, double timeout = 20) {
  asgard_node_options o{};
  o.struct_size = sizeof o;
  o.slave_path = kCore.c_str();
  o.timeout_seconds = timeout;
  asgard_error e{};
  return Asgard().node()->create(text.data(), text.size(), &o, &n.node, &e);
}

// About a second of ESDIRK steps (a ball on a stiff link to a moving point,
// 200 000 steps): progress messages (every 50 ms) arrive well before the end.
const std::string kLong = R"(simulator -finish 20 -maxstep 0.0001 -collisions 0
shape_set ball -desc {-sub {-sphere 0.2}}
body b -shape ball -init_dpos {0 1 0}
link -body1 b -offset1 {0 0 0} -x {sin(t)} -y 0 -z 0 -tightness 1e8
)";

std::string Scene() {
  std::string s;
  EXPECT_TRUE(
      document::ReadFile(std::string(ASGARD_SOURCE_DIR) + "/samples/figure62.al", s, nullptr));
  return s;
}

TEST(Slave, SimulatesAndServesTwoRenditionsFromOneProcess) {
  Node n;
  ASSERT_EQ(Create(Scene(), n), ASGARD_OK);
  asgard_error e{};
  ASSERT_EQ(Asgard().node()->simulate(n.node, nullptr, nullptr, &e), ASGARD_OK) << e.message;
  const asgard_node_status s = Status(n.node);
  EXPECT_EQ(s.state, ASGARD_NODE_SIMULATED);
  EXPECT_DOUBLE_EQ(s.t1, 3.0);
  asgard_rendition *a = nullptr, *b = nullptr;
  ASSERT_EQ(Asgard().rendition()->create(n.node, "v1", ASGARD_DEVICE_PAGE, 64, 48, &a, &e),
            ASGARD_OK);
  ASSERT_EQ(Asgard().rendition()->create(n.node, "v2", ASGARD_DEVICE_HTML, 32, 24, &b, &e),
            ASGARD_OK);
  asgard_frame f{};
  f.struct_size = sizeof f;
  ASSERT_EQ(Asgard().rendition()->frame(a, 0.0, &f, &e), ASGARD_OK) << e.message;
  EXPECT_EQ(f.width, 64);
  std::vector<uint8_t> first(f.pixels, f.pixels + 64 * 48 * 4);
  ASSERT_EQ(Asgard().rendition()->frame(a, 3.0, &f, &e), ASGARD_OK);
  EXPECT_NE(std::vector<uint8_t>(f.pixels, f.pixels + 64 * 48 * 4), first) << "the balls move";
  ASSERT_EQ(Asgard().rendition()->frame(b, 1.0, &f, &e), ASGARD_OK);
  EXPECT_EQ(f.width, 32);
  EXPECT_EQ(Status(n.node).pid, s.pid) << "one process serves every rendition";
  asgard_bytes reply{};
  ASSERT_EQ(Asgard().node()->command(n.node, "info", &reply, &e), ASGARD_OK);
  EXPECT_NE(Asgard().Take(reply).find("b2 b3"), std::string::npos);
  EXPECT_EQ(Asgard().node()->command(n.node, "frobnicate", &reply, &e), ASGARD_ERR_INVALID);
  EXPECT_NE(std::string(e.message).find("unknown command"), std::string::npos);
}

// A rendition draws the scene's view as it is at the frame's time: here a
// view whose -pos is an expression of time (seed 4.1.7) looks at (−t/2, 0,
// 0), so a still red ball at the origin moves right across the picture.
TEST(Slave, ARenditionDrawsAMovingViewAtEachTime) {
  Node n;
  ASSERT_EQ(Create("simulator -finish 1 -collisions 0\n"
                   "shape_set ball -desc {-sub {-sphere 0.5}}\n"
                   "body b -shape ball -static 1 -color red\n"
                   "view -rot {0 0 0} -center {0 0 0} -scale 0.5 -pos {{t / 2} 0 0}\n",
                   n),
            ASGARD_OK);
  asgard_error e{};
  ASSERT_EQ(Asgard().node()->simulate(n.node, nullptr, nullptr, &e), ASGARD_OK) << e.message;
  asgard_rendition* r = nullptr;
  ASSERT_EQ(Asgard().rendition()->create(n.node, "v", ASGARD_DEVICE_PAGE, 64, 48, &r, &e),
            ASGARD_OK);
  auto red_x = [&](double t) {
    asgard_frame f{};
    f.struct_size = sizeof f;
    EXPECT_EQ(Asgard().rendition()->frame(r, t, &f, &e), ASGARD_OK) << e.message;
    double sx = 0, count = 0;
    for (int y = 0; y < f.height; ++y)
      for (int x = 0; x < f.width; ++x) {
        const uint8_t* p = f.pixels + y * f.stride + 4 * x;
        if (p[0] > 120 && p[1] < 80 && p[2] < 80) sx += x, ++count;
      }
    EXPECT_GT(count, 20) << "the ball at t = " << t;
    return count > 0 ? sx / count : 0.0;
  };
  const double x0 = red_x(0), x1 = red_x(1);
  EXPECT_NEAR(x0, 31.5, 1.5) << "in the middle at t = 0";
  // The framing radius is the ball's, 0.5; at scale 0.5 the eye is 4 × 0.5 /
  // 0.5 = 4 units from the point looked at and the half height of 24 pixels
  // spans 4 · 1.06 tan(asin(1/4)) units there (render/view.cc), of which the
  // view moved 0.5 by t = 1.
  const double want = 0.5 / (4 * 1.06 * std::tan(std::asin(0.25))) * 24;
  EXPECT_NEAR(x1 - x0, want, 0.1 * want) << "moved right by 0.5 at t = 1";
}

TEST(Slave, SceneErrorsAreReportedWithLineAndColumn) {
  Node n;
  EXPECT_EQ(Create("simulator -finish 1\nbody b -shape nope\n", n), ASGARD_ERR_SCENE);
  ASSERT_NE(n.node, nullptr);
  const asgard_node_status s = Status(n.node);
  EXPECT_EQ(s.state, ASGARD_NODE_SCENE_ERROR);
  EXPECT_NE(std::string(s.message).find("2:"), std::string::npos) << s.message;
  asgard_error e{};
  EXPECT_EQ(Asgard().node()->update(n.node, Scene().data(), Scene().size(), nullptr, nullptr, &e),
            ASGARD_OK)
      << e.message;
  EXPECT_EQ(Status(n.node).state, ASGARD_NODE_SIMULATED);
}

void KillOnProgress(void* user, double fraction, const char*) {
  auto* n = static_cast<Node*>(user);
  const int pid = Status(n->node).pid;
  if (fraction > 0.02 && pid > 0) kill(pid, SIGKILL);
}

TEST(Slave, SigkillMidSimulationLeavesTheHostRunningAndRestartWorks) {
  Node n;
  ASSERT_EQ(Create(kLong, n), ASGARD_OK);
  asgard_error e{};
  EXPECT_EQ(Asgard().node()->simulate(n.node, KillOnProgress, &n, &e), ASGARD_ERR_SLAVE);
  EXPECT_NE(std::string(e.message).find("killed by signal 9"), std::string::npos) << e.message;
  asgard_node_status s = Status(n.node);
  EXPECT_EQ(s.state, ASGARD_NODE_CRASHED);
  EXPECT_EQ(s.pid, 0);
  // Calls on the dead node fail cleanly.
  asgard_bytes reply{};
  EXPECT_EQ(Asgard().node()->command(n.node, "ping", &reply, &e), ASGARD_ERR_SLAVE);
  asgard_bytes text{};
  ASSERT_EQ(Asgard().node()->get_text(n.node, &text, &e), ASGARD_OK);
  EXPECT_EQ(Asgard().Take(text), kLong) << "the node keeps its text";
  ASSERT_EQ(Asgard().node()->restart(n.node, &e), ASGARD_OK) << e.message;
  EXPECT_GT(Status(n.node).pid, 0);
  ASSERT_EQ(Asgard().node()->simulate(n.node, nullptr, nullptr, &e), ASGARD_OK) << e.message;
  EXPECT_EQ(Status(n.node).state, ASGARD_NODE_SIMULATED);
}

// Progress notifications reset the watchdog, but cannot extend a call past
// kOverallTimeoutFactor times the timeout: a simulation that progresses
// forever is stopped too.
TEST(Slave, ProgressCannotExtendACallPastItsOverallDeadline) {
  setenv("ASGARD_CORE_FAULT", "endless-progress-on-simulate", 1);
  Node n;
  const int32_t created = Create(Scene(), n, 0.5);
  unsetenv("ASGARD_CORE_FAULT");
  ASSERT_EQ(created, ASGARD_OK);
  asgard_error e{};
  const auto start = std::chrono::steady_clock::now();
  EXPECT_EQ(Asgard().node()->simulate(n.node, nullptr, nullptr, &e), ASGARD_ERR_TIMEOUT);
  const auto took = std::chrono::steady_clock::now() - start;
  // It ends (without the overall deadline the progress messages keep it
  // alive for ever), and not before the deadline; the upper bound leaves
  // room for a loaded machine.
  EXPECT_GE(took, std::chrono::milliseconds(1900));
  EXPECT_LT(took, std::chrono::seconds(30));
  EXPECT_NE(std::string(e.message).find("did not finish 'simulate' within 2 s"), std::string::npos)
      << e.message;
  EXPECT_EQ(Status(n.node).state, ASGARD_NODE_HUNG);
}

TEST(Slave, ASlaveThatStopsAnsweringIsStoppedByTheWatchdog) {
  setenv("ASGARD_CORE_FAULT", "hang-on-simulate", 1);
  Node n;
  const int32_t created = Create(Scene(), n, 0.5);
  unsetenv("ASGARD_CORE_FAULT");
  ASSERT_EQ(created, ASGARD_OK);
  const int pid = Status(n.node).pid;
  asgard_error e{};
  const auto start = std::chrono::steady_clock::now();
  EXPECT_EQ(Asgard().node()->simulate(n.node, nullptr, nullptr, &e), ASGARD_ERR_TIMEOUT);
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(5));
  EXPECT_NE(std::string(e.message).find("did not answer 'simulate' within 0.5 s"),
            std::string::npos)
      << e.message;
  EXPECT_EQ(Status(n.node).state, ASGARD_NODE_HUNG);
  EXPECT_NE(kill(pid, 0), 0) << "the hung slave was killed and reaped";
  ASSERT_EQ(Asgard().node()->restart(n.node, &e), ASGARD_OK) << e.message;
  EXPECT_EQ(Asgard().node()->simulate(n.node, nullptr, nullptr, &e), ASGARD_OK) << e.message;
}

TEST(Slave, AMalformedAnswerIsAProtocolErrorNotACrash) {
  setenv("ASGARD_CORE_FAULT", "garbage-on-frame", 1);
  Node n;
  const int32_t created = Create(Scene(), n);
  unsetenv("ASGARD_CORE_FAULT");
  ASSERT_EQ(created, ASGARD_OK);
  asgard_error e{};
  ASSERT_EQ(Asgard().node()->simulate(n.node, nullptr, nullptr, &e), ASGARD_OK);
  asgard_rendition* r = nullptr;
  ASSERT_EQ(Asgard().rendition()->create(n.node, "v", ASGARD_DEVICE_PAGE, 16, 16, &r, &e),
            ASGARD_OK);
  asgard_frame f{};
  f.struct_size = sizeof f;
  EXPECT_EQ(Asgard().rendition()->frame(r, 0, &f, &e), ASGARD_ERR_PROTOCOL);
  EXPECT_NE(std::string(e.message).find("not a JSON object"), std::string::npos) << e.message;
  EXPECT_EQ(Status(n.node).pid, 0);
  ASSERT_EQ(Asgard().node()->restart(n.node, &e), ASGARD_OK);
  ASSERT_EQ(Asgard().node()->simulate(n.node, nullptr, nullptr, &e), ASGARD_OK);
  EXPECT_EQ(Asgard().rendition()->frame(r, 0, &f, &e), ASGARD_OK) << e.message;
}

TEST(Slave, AMissingSlaveProgramIsAStatusNotACrash) {
  Node n;
  asgard_node_options o{};
  o.struct_size = sizeof o;
  o.slave_path = "/nonexistent/asgard-core";
  asgard_error e{};
  EXPECT_EQ(Asgard().node()->create("x", 1, &o, &n.node, &e), ASGARD_ERR_SLAVE);
  EXPECT_NE(std::string(e.message).find("cannot start"), std::string::npos) << e.message;
  EXPECT_EQ(n.node, nullptr) << "nothing started, nothing to restart";
}

// A slave that dies loading the text leaves a CRASHED node (before, no
// node: nothing the host could restart), and restart() brings it back.
TEST(Slave, ASlaveThatDiesLoadingLeavesACrashedNodeThatRestarts) {
  Node n;
  ASSERT_EQ(setenv("ASGARD_CORE_FAULT", "exit-on-load", 1), 0);
  const int32_t s = Create(Scene(), n);
  unsetenv("ASGARD_CORE_FAULT");
  EXPECT_EQ(s, ASGARD_ERR_SLAVE);
  ASSERT_NE(n.node, nullptr);
  EXPECT_EQ(Status(n.node).state, ASGARD_NODE_CRASHED);
  EXPECT_NE(std::string(Status(n.node).message).find("exited with status 3 while answering 'load'"),
            std::string::npos)
      << Status(n.node).message;
  asgard_error e{};
  ASSERT_EQ(Asgard().node()->restart(n.node, &e), ASGARD_OK) << e.message;
  ASSERT_EQ(Asgard().node()->simulate(n.node, nullptr, nullptr, &e), ASGARD_OK) << e.message;
  EXPECT_EQ(Status(n.node).state, ASGARD_NODE_SIMULATED);
}

// ---- the host document ----

TEST(HostDocument, KillingTheSlaveKeepsTheDocumentAndThePoster) {
  const std::string bytes = ReadSample("memo.ens");
  auto parsed = document::Parse(bytes);
  ASSERT_TRUE(parsed.ok());
  HostDocument doc(*parsed.document, Registry(), Opts("memo.ens", kCore));
  Embedded& item = doc.items()[0];
  ASSERT_TRUE(doc.Simulate(item)) << item.message;
  bool live = false;
  const Picture p = doc.Frame(item, ASGARD_DEVICE_PAGE, 90, 60, 1.0, 0, &live);
  ASSERT_TRUE(live);
  // The first death: the slave is restarted once and the frame drawn.
  kill(item.status.pid, SIGKILL);
  doc.Frame(item, ASGARD_DEVICE_PAGE, 90, 60, 2.0, 0, &live);
  EXPECT_TRUE(live);
  EXPECT_TRUE(item.restarted);
  EXPECT_NE(item.restart_reason.find("killed by signal 9"), std::string::npos)
      << item.restart_reason;
  const Picture p2 = doc.Frame(item, ASGARD_DEVICE_PAGE, 90, 60, 1.0, 0, &live);
  ASSERT_TRUE(live);
  // The second: no more restarts, the last frame is shown.
  kill(item.status.pid, SIGKILL);
  const Picture q = doc.Frame(item, ASGARD_DEVICE_PAGE, 90, 60, 2.0, 0, &live);
  EXPECT_FALSE(live);
  EXPECT_EQ(q.rgba, p2.rgba) << "the last frame is shown";
  EXPECT_EQ(p2.rgba, p.rgba);
  EXPECT_NE(item.message.find("killed by signal 9"), std::string::npos) << item.message;
  EXPECT_EQ(document::Write(doc.document()), bytes) << "the document is intact";
  ASSERT_TRUE(doc.Restart(item)) << item.message;
  doc.Frame(item, ASGARD_DEVICE_PAGE, 90, 60, 2.0, 0, &live);
  EXPECT_TRUE(live);
}

TEST(HostDocument, PosterFramesAreStoredAndReadBack) {
  const std::string bytes = ReadSample("memo.ens");
  auto parsed = document::Parse(bytes);
  ASSERT_TRUE(parsed.ok());
  std::string with_poster;
  Picture p;
  {
    HostDocument doc(*parsed.document, Registry(), Opts("memo.ens", kCore));
    Embedded& item = doc.items()[0];
    ASSERT_TRUE(doc.Simulate(item));
    p = doc.Frame(item, ASGARD_DEVICE_PAGE, 60, 40, 1.5, ASGARD_RENDITION_HANDLES);
    doc.SetPoster(item, p);
    doc.SetPoster(item, p);  // replaces, does not add a second one
    with_poster = document::Write(doc.document());
  }
  EXPECT_EQ(with_poster.find("<POSTER>"), with_poster.rfind("<POSTER>"));
  auto again = document::Parse(with_poster);
  ASSERT_TRUE(again.ok()) << again.error.Format();
  HostDocument doc(*again.document, Registry(), Opts("memo.ens"));
  ASSERT_EQ(doc.items().size(), 1u);
  EXPECT_TRUE(doc.items()[0].poster_from_document);
  EXPECT_EQ(doc.items()[0].poster.rgba, p.rgba);
  // Without the POSTER element the document is the memo again, byte for byte.
  const size_t a = with_poster.find("\n<POSTER>"), b = with_poster.find("</POSTER>") + 9;
  EXPECT_EQ(with_poster.substr(0, a) + with_poster.substr(b), bytes);
}

// Little-endian float32 and uint16 arrays from the player's base64.
std::vector<float> Floats(const std::string& base64) {
  const auto bytes = document::Base64Decode(base64);
  std::vector<float> out(bytes ? bytes->size() / 4 : 0);
  if (bytes) std::memcpy(out.data(), bytes->data(), out.size() * 4);
  return out;
}

TEST(HostDocument, ThePlayerDataIsTheSlavesMotionPacked) {
  auto parsed = document::Parse(ReadSample("memo.ens"));
  ASSERT_TRUE(parsed.ok());
  HostDocument doc(*parsed.document, Registry(), Opts("memo.ens", kCore));
  Embedded& item = doc.items()[0];
  ASSERT_TRUE(doc.Simulate(item)) << item.message;
  std::string reply, error;
  ASSERT_TRUE(doc.Command(item, "player 30", &reply)) << reply;
  const std::string packed = PlayerJson(reply, &error);
  ASSERT_FALSE(packed.empty()) << error;
  const auto data = nlohmann::json::parse(packed);
  // 0 .. 3 s at 30 frames a second; both balls move, so both have a track.
  ASSERT_EQ(data["n"], 91);
  EXPECT_EQ(data["t0"], 0.0);
  EXPECT_EQ(data["t1"], 3.0);
  ASSERT_EQ(data["bodies"].size(), 2u);
  EXPECT_EQ(data["bodies"][0]["name"], "b2");
  EXPECT_EQ(data["bodies"][0]["track"], 0);
  EXPECT_EQ(data["bodies"][1]["track"], 1);
  EXPECT_EQ(data["bodies"][1]["pieces"][0]["sphere"], nlohmann::json({0.0, 0.0, 0.0, 0.5}));
  // No force acts: b2 starts at (-1 0 0) with velocity (1 0 0), b3 at
  // (1 0 0) with (0 1 0), and neither turns; float32 keeps 7 digits.
  const std::vector<float> poses = Floats(data["poses"]);
  ASSERT_EQ(poses.size(), 91u * 2 * 7);
  for (int f = 0; f < 91; ++f) {
    const double t = f / 30.0;
    const float* b2 = &poses[(f * 2 + 0) * 7];
    const float* b3 = &poses[(f * 2 + 1) * 7];
    EXPECT_NEAR(b2[0], -1 + t, 1e-5) << "t = " << t;
    EXPECT_NEAR(b2[1], 0, 1e-5);
    EXPECT_NEAR(b3[0], 1, 1e-5);
    EXPECT_NEAR(b3[1], t, 1e-5) << "t = " << t;
    EXPECT_NEAR(b3[6], 1, 1e-6);  // w of the identity
  }
  EXPECT_TRUE(data["camera"].contains("eye") && data["camera"].contains("tan_half_fov"));
  // The rate must be a number in (0, 1000].
  EXPECT_FALSE(doc.Command(item, "player fast", &reply));
}

// b3's y in the slave's motion at t (memo: it starts at init_pos and moves
// at (0 1 0) with no force), read through the player data of `item`'s node.
double B3YAt(HostDocument& doc, Embedded& item, int frame) {
  std::string reply, error;
  EXPECT_TRUE(doc.Command(item, "player 30", &reply)) << reply;
  const std::string packed = PlayerJson(reply, &error);
  EXPECT_FALSE(packed.empty()) << error;
  if (packed.empty()) return NAN;
  const std::vector<float> poses = Floats(nlohmann::json::parse(packed)["poses"]);
  return poses.at(static_cast<size_t>((frame * 2 + 1) * 7 + 1));
}

// Issue 13: the editor's requests (ABI 1.1 node_rpc) go to the slave that
// draws the renditions: an edit and a simulate through it change what the
// renditions draw and the node's motion exactly, in the same process, and
// a restart after the slave dies loads the edited text.
TEST(HostDocument, TheEditorsRequestsGoToTheSlaveThatDrawsTheRenditions) {
  auto parsed = document::Parse(ReadSample("memo.ens"));
  ASSERT_TRUE(parsed.ok());
  HostDocument doc(*parsed.document, Registry(), Opts("memo.ens", kCore));
  Embedded& item = doc.items()[0];
  ASSERT_NE(item.medium->node_rpc(), nullptr);
  ASSERT_TRUE(doc.Simulate(item)) << item.message;
  bool live = false;
  const Picture before = doc.Frame(item, ASGARD_DEVICE_PAGE, 90, 60, 1.0, 0, &live);
  ASSERT_TRUE(live) << item.message;
  const int pid = item.status.pid;
  EXPECT_NEAR(B3YAt(doc, item, 30), 1.0, 1e-5);  // y = 0 + 1 · t at t = 1

  std::string r;
  ASSERT_EQ(
      doc.Call(item, "edit", R"({"element": "b3", "param": "init_pos", "values": [1, -1, 0]})", &r),
      ASGARD_OK)
      << item.message;
  const std::string edited = nlohmann::json::parse(r)["text"];
  EXPECT_NE(edited.find("-init_pos {1 -1 0}"), std::string::npos) << edited;
  asgard_bytes text{};
  asgard_error e{};
  ASSERT_EQ(Asgard().node()->get_text(item.node, &text, &e), ASGARD_OK);
  EXPECT_EQ(Asgard().Take(text), edited) << "the node follows the editor's text";
  EXPECT_EQ(item.status.state, ASGARD_NODE_LOADED) << "edited, not yet simulated";
  // Until the next simulate the renditions keep their last picture.
  const Picture waiting = doc.Frame(item, ASGARD_DEVICE_PAGE, 90, 60, 1.0, 0, &live);
  EXPECT_FALSE(live);
  EXPECT_EQ(waiting.rgba, before.rgba);

  ASSERT_EQ(doc.Call(item, "simulate", "{}", &r), ASGARD_OK) << item.message;
  EXPECT_TRUE(item.simulated);
  EXPECT_DOUBLE_EQ(item.t1, 3.0);
  const Picture after = doc.Frame(item, ASGARD_DEVICE_PAGE, 90, 60, 1.0, 0, &live);
  ASSERT_TRUE(live) << item.message;
  EXPECT_NE(after.rgba, before.rgba) << "b3 is drawn where the edit put it";
  EXPECT_NEAR(B3YAt(doc, item, 30), 0.0, 1e-5);  // y = -1 + 1 · t at t = 1
  EXPECT_EQ(item.status.pid, pid) << "one slave for the editor and the renditions";

  // The same picture as a host that was given the edited text.
  HostDocument fresh(*parsed.document, Registry(), Opts("memo.ens", kCore));
  ASSERT_TRUE(fresh.SetText(fresh.items()[0], edited)) << fresh.items()[0].message;
  EXPECT_EQ(fresh.Frame(fresh.items()[0], ASGARD_DEVICE_PAGE, 90, 60, 1.0, 0).rgba, after.rgba);

  // Bad requests are refused without harm; the node's own are not for this.
  EXPECT_EQ(doc.Call(item, "frame", "{}", &r), ASGARD_ERR_INVALID);
  EXPECT_EQ(doc.Call(item, "edit", "[1, 2]", &r), ASGARD_ERR_INVALID);
  EXPECT_NE(item.message.find("not a JSON object"), std::string::npos) << item.message;
  EXPECT_EQ(
      doc.Call(item, "edit", R"({"element": "nope", "param": "init_pos", "values": [0]})", &r),
      ASGARD_ERR_SCENE);
  EXPECT_EQ(item.status.pid, pid);

  // The slave dies: the next request starts a new one with the edited text.
  kill(pid, SIGKILL);
  EXPECT_EQ(doc.Call(item, "scene_state", "{}", &r), ASGARD_ERR_SLAVE);
  EXPECT_NE(item.message.find("killed by signal 9"), std::string::npos) << item.message;
  ASSERT_EQ(doc.Call(item, "scene_state", "{}", &r), ASGARD_OK) << item.message;
  EXPECT_NE(item.status.pid, pid);
  EXPECT_EQ(nlohmann::json::parse(r)["text"], edited);
  ASSERT_EQ(doc.Call(item, "simulate", "{}", &r), ASGARD_OK) << item.message;
  EXPECT_EQ(doc.Frame(item, ASGARD_DEVICE_PAGE, 90, 60, 1.0, 0, &live).rgba, after.rgba);
  EXPECT_TRUE(live);
}

// The text layer of the served pages (PageLines): a paragraph too long for
// a page comes back line by line, in reading order, every word once, each
// line inside the text column and below the one before; a field's label
// and its text are two pieces of one line, the label bold.
TEST(Layout, PageLinesGiveEveryWordOnceInOrderInsideTheColumn) {
  std::string words;
  for (int i = 0; i < 1500; ++i) words += "word" + std::to_string(i) + " ";
  const std::string text =
      "DOCUMENT CMEMO\n<CMEMO>\n<TO>{Whom it may concern}</TO>\n<BODY>\n"
      "<PARAGRAPH><TEXT>{" +
      words + "}</TEXT></PARAGRAPH>\n</BODY>\n</CMEMO>\n";
  auto parsed = document::Parse(text);
  ASSERT_TRUE(parsed.ok());
  HostDocument doc(*parsed.document, Registry(), Opts("t.ens"));
  const PageStyle style;
  const std::vector<Page> pages = Paginate(Blocks(doc), doc, style);
  ASSERT_GE(pages.size(), 2u);
  std::vector<std::string> read;
  bool label = false;
  for (const Page& page : pages) {
    double below = 0;
    for (const TextLine& l : PageLines(page)) {
      EXPECT_GE(l.x, style.margin - 0.5) << l.text;
      EXPECT_LE(l.x + l.w, style.width - style.margin + 0.5) << l.text;
      EXPECT_GT(l.w, 0) << l.text;
      EXPECT_GE(l.y, below - 0.01) << l.text;  // pieces of one line share its top
      EXPECT_GT(l.baseline, l.y) << l.text;
      EXPECT_LT(l.baseline, l.y + l.h) << l.text;
      below = l.y;
      if (l.text == "To:") {
        label = l.bold;
        continue;
      }
      std::istringstream in(l.text);
      for (std::string w; in >> w;) read.push_back(w);
    }
  }
  EXPECT_TRUE(label) << "the field's label is a bold piece of its own";
  ASSERT_EQ(read.size(), 1500u + 4u);
  EXPECT_EQ(read[0], "Whom");
  for (int i = 0; i < 1500; ++i)
    EXPECT_EQ(read[4 + static_cast<size_t>(i)], "word" + std::to_string(i));
}

TEST(Html, PlayerJsonPacksHullsKeepsStillBodiesToOnePoseAndRefusesBadData) {
  const std::string reply = R"({"bodies":[
    {"name":"floor</script>","pieces":[{"sphere":false,"color":[1,0,0],
      "vertices":[0,0,0, 1,0,0, 0,1,0, 0,0,1],"triangles":[0,2,1, 0,1,3, 0,3,2, 1,2,3]}]},
    {"name":"ball","pieces":[{"sphere":true,"center":[0,0,0],"radius":0.5,"color":[0,0,1]}]}],
    "lights":[],"times":[0,0.5,1],
    "poses":[[0,0,0,0,0,0,1, 0,0,0,0,0,0,1],[0,0,0,0,0,0,1, 0,1,0,0,0,0,1],[0,0,0,0,0,0,1, 0,2,0,0,0,0,1]],
    "camera":{"eye":[0,0,10],"target":[0,0,0],"up":[0,1,0],"tan_half_fov":0.3}})";
  std::string error;
  const std::string packed = PlayerJson(reply, &error);
  ASSERT_FALSE(packed.empty()) << error;
  EXPECT_EQ(packed.find("</"), std::string::npos) << "no </ inside a script element";
  const auto data = nlohmann::json::parse(packed);
  EXPECT_EQ(data["bodies"][0]["name"], "floor</script>");
  // The still floor: one pose, no track; the ball: the only track.
  EXPECT_FALSE(data["bodies"][0].contains("track"));
  EXPECT_EQ(data["bodies"][0]["pose"], nlohmann::json({0, 0, 0, 0, 0, 0, 1}));
  EXPECT_EQ(data["bodies"][1]["track"], 0);
  EXPECT_EQ(Floats(data["poses"]),
            (std::vector<float>{0, 0, 0, 0, 0, 0, 1, 0, 1, 0, 0, 0, 0, 1, 0, 2, 0, 0, 0, 0, 1}));
  const auto& hull = data["bodies"][0]["pieces"][0];
  EXPECT_EQ(Floats(hull["v"]), (std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1}));
  const auto indices = document::Base64Decode(hull["i"].get<std::string>());
  ASSERT_TRUE(indices && indices->size() == 24u);  // 12 uint16
  EXPECT_EQ(static_cast<uint8_t>((*indices)[2]), 2);
  EXPECT_FALSE(hull.contains("i32"));
  // Bad data: a sentence, never a crash.
  for (const std::string& bad :
       {std::string("not json"), std::string(R"({"times":[0,1]})"),
        std::string(R"({"bodies":[],"times":[0,0.1,1],"poses":[[],[],[]],"camera":{}})"),
        std::string(R"({"bodies":[{"name":"x","pieces":[{"sphere":false,"color":[1,1,1],)"
                    R"("vertices":[0,0,0],"triangles":[0,0,5]}]}],"times":[0],)"
                    R"("poses":[[0,0,0,0,0,0,1]],"camera":{}})")}) {
    error.clear();
    EXPECT_TRUE(PlayerJson(bad, &error).empty()) << bad;
    EXPECT_NE(error.find("the player data"), std::string::npos) << error;
  }
}

}  // namespace
}  // namespace asgard::host
