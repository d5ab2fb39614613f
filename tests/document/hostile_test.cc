// Hostile documents, files and protocol messages: each is refused with a
// located message (or handled without loss), never a crash, hang or silent
// change.  Issue 12's classes, one test each.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "core/protocol/protocol.h"
#include "formats/document/document.h"
#include "formats/document/file.h"
#include "formats/document/xml.h"
#include "tests/common/sanitizer.h"
#include "tests/document/exec.h"

namespace asgard::document {
namespace {

namespace fs = std::filesystem;
const std::string kCore = std::string(ASGARD_BINARY_DIR) + "/core/app/asgard-core";
const std::string kXmlHead =
    "<?xml version=\"1.0\"?>\n<ens:file xmlns:ens=\"urn:asgard:ensemble-document\">\n"
    "<ens:header>DOCUMENT X</ens:header>";

fs::path Scratch(const std::string& name) {
  const fs::path dir = fs::path(ASGARD_BINARY_DIR) / "tests/document/scratch_hostile" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string Read(const fs::path& p) {
  std::string s;
  ReadFile(p.string(), s, nullptr);
  return s;
}

// XML nested far deeper than the document model allows is refused with its
// line, without exhausting the stack (it did with XML_PARSE_HUGE).
TEST(HostileXml, NestingTensOfThousandsDeepIsRefusedWithALocation) {
  std::string s = kXmlHead + "\n<X>";
  for (int i = 0; i < 100000; ++i) s += "<A>";
  auto r = ParseXml(s);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error.line, 4);
  EXPECT_NE(r.error.message.find("depth"), std::string::npos) << r.error.Format();
}

// Entity declarations (billion laughs, quadratic blow-up) are refused before
// any expansion, with the declaration's line and column.
TEST(HostileXml, EntityBombsAreRefusedBeforeExpansion) {
  std::string laughs = "<?xml version=\"1.0\"?>\n<!DOCTYPE ens:file [\n<!ENTITY a \"lol\">\n";
  std::string prev = "a";
  for (int i = 0; i < 12; ++i) {
    const std::string name = "e" + std::to_string(i);
    laughs += "<!ENTITY " + name + " \"";
    for (int k = 0; k < 10; ++k) laughs += "&" + prev + ";";
    laughs += "\">\n";
    prev = name;
  }
  laughs +=
      "]>\n<ens:file xmlns:ens=\"urn:asgard:ensemble-document\">"
      "<ens:header>DOCUMENT X</ens:header><X><A><ens:text>&" +
      prev + ";</ens:text></A></X></ens:file>";
  auto r = ParseXml(laughs);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error.line, 2);
  EXPECT_EQ(r.error.column, 1);
  EXPECT_NE(r.error.message.find("document type declarations"), std::string::npos);

  const std::string quadratic =
      "<?xml version=\"1.0\"?><!DOCTYPE x [<!ENTITY big \"" + std::string(100000, 'x') + "\">]>";
  auto q = ParseXml(quadratic);
  ASSERT_FALSE(q.ok());
  EXPECT_EQ(q.error.column, 22);
}

// A reference to an entity nobody declared is an error with its place, not
// an empty text.
TEST(HostileXml, UndefinedEntityIsALocatedError) {
  auto r = ParseXml(kXmlHead + "\n<X><A><ens:text>a &nope; b</ens:text></A></X></ens:file>");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error.line, 4);
  EXPECT_NE(r.error.message.find("nope"), std::string::npos) << r.error.Format();
}

// Rewriting a file in place keeps what made it that file.
TEST(HostileFiles, InPlaceRewriteKeepsModeAndWritesThroughSymlinks) {
  const fs::path dir = Scratch("inplace");
  const std::string path = (dir / "private.ens").string();
  ASSERT_TRUE(WriteFileAtomic(path, "one", nullptr));
  ASSERT_EQ(::chmod(path.c_str(), 0600), 0);
  ASSERT_TRUE(WriteFileAtomic(path, "two", nullptr));
  struct stat st {};
  ASSERT_EQ(::stat(path.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 07777, 0600u);
  ::chmod(path.c_str(), 0640);
  ASSERT_TRUE(WriteFileAtomic(path, "three", nullptr));
  ASSERT_EQ(::stat(path.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 07777, 0640u);

  const fs::path link = dir / "link.ens";
  fs::create_symlink("private.ens", link);
  std::string error;
  ASSERT_TRUE(WriteFileAtomic(link.string(), "four", &error)) << error;
  EXPECT_TRUE(fs::is_symlink(link));
  EXPECT_EQ(Read(dir / "private.ens"), "four");

  fs::create_symlink("missing.ens", dir / "dangling.ens");
  EXPECT_FALSE(WriteFileAtomic((dir / "dangling.ens").string(), "x", &error));
  EXPECT_NE(error.find("symbolic link to a missing file"), std::string::npos) << error;
}

TEST(HostileFiles, HardLinkedFilesAreRefusedNotSplit) {
  const fs::path dir = Scratch("hardlink");
  const fs::path a = dir / "a.ens", b = dir / "b.ens";
  ASSERT_TRUE(WriteFileAtomic(a.string(), "one", nullptr));
  fs::create_hard_link(a, b);
  std::string error;
  EXPECT_FALSE(WriteFileAtomic(a.string(), "two", &error));
  EXPECT_NE(error.find("2 hard links"), std::string::npos) << error;
  EXPECT_EQ(Read(b), "one");
  EXPECT_EQ(Read(a), "one");
}

TEST(HostileFiles, AnExistingFileKeepsItsFlavour) {
  const fs::path dir = Scratch("flavour");
  auto doc = Parse("DOCUMENT X\n<X><A>{hello}</A></X>");
  ASSERT_TRUE(doc.ok());
  // An SGML file named .xml stays SGML; an XML file named .ens stays XML.
  const fs::path sgml = dir / "sgml.xml", xml = dir / "xml.ens";
  ASSERT_TRUE(WriteFileAtomic(sgml.string(), Write(*doc.document), nullptr));
  ASSERT_TRUE(WriteFileAtomic(xml.string(), WriteXml(*doc.document), nullptr));
  ASSERT_TRUE(SaveDocument(*doc.document, sgml.string(), nullptr));
  ASSERT_TRUE(SaveDocument(*doc.document, xml.string(), nullptr));
  EXPECT_FALSE(LooksLikeXml(Read(sgml)));
  EXPECT_TRUE(LooksLikeXml(Read(xml)));
  // A new file takes the flavour its name says.
  ASSERT_TRUE(SaveDocument(*doc.document, (dir / "new.xml").string(), nullptr));
  EXPECT_TRUE(LooksLikeXml(Read(dir / "new.xml")));
}

// --- dochost on documents that used to lose text -----------------------------

const std::string kDochost = std::string(ASGARD_BINARY_DIR) + "/host-shim/dochost";

using asgard::testing::Exec;
using Exit = asgard::testing::Result;

std::string Memo(const std::string& subject, const std::string& paragraph) {
  return "DOCUMENT CMEMO\n<CMEMO>\n<TO>{Whom it may concern}</TO>\n<SUBJECT>{" + subject +
         "}</SUBJECT>\n<BODY>\n<PARAGRAPH><TEXT>{" + paragraph +
         "}</TEXT></PARAGRAPH>\n</BODY>\n</CMEMO>\n";
}

// Runs of white space as one space (pdftotext breaks justified lines).
std::string Collapsed(const std::string& text) {
  std::string out;
  for (char c : text) {
    const bool space = c == ' ' || c == '\n' || c == '\f' || c == '\t';
    if (space && !out.empty() && out.back() == ' ') continue;
    out += space ? ' ' : c;
  }
  return out;
}

size_t Count(const std::string& text, const std::string& word) {
  size_t n = 0;
  for (size_t at = 0; (at = text.find(word, at)) != std::string::npos; at += word.size()) ++n;
  return n;
}

// A 1500-word paragraph printed 552 words: it now continues on the next
// pages, every word of it.
TEST(HostileDocuments, AParagraphLongerThanAPageBreaksAcrossPages) {
  const fs::path dir = Scratch("long");
  std::string words;
  for (int i = 0; i < 1500; ++i) words += (i ? " w" : "w") + std::to_string(i);
  std::ofstream(dir / "long.ens") << Memo("Long", words);
  const Exit r = Exec(kDochost + " convert " + (dir / "long.ens").string() + " -o " +
                      (dir / "long.pdf").string());
  ASSERT_EQ(r.status, 0) << r.out;
  const Exit text = Exec("pdftotext " + (dir / "long.pdf").string() + " -");
  ASSERT_EQ(text.status, 0);
  EXPECT_NE(text.out.find("w0 "), std::string::npos);
  EXPECT_NE(text.out.find("w1499"), std::string::npos) << "the paragraph's end is missing";
  EXPECT_EQ(Count(text.out, "w"), 1500u);
  EXPECT_GE(Count(text.out, "\f"), 3u) << "at least three pages";
}

// Invalid UTF-8 in a field dropped the whole field, and a NUL cut a text
// short: both now show U+FFFD in place and keep the rest.
TEST(HostileDocuments, InvalidUtf8AndNulAreShownReplacedNotDropped) {
  const fs::path dir = Scratch("utf8");
  std::ofstream(dir / "bad.ens", std::ios::binary) << Memo(
      "before\xff\xfe"
      "after",
      std::string("start") + '\0' + "end of the text");
  const Exit r = Exec(kDochost + " convert " + (dir / "bad.ens").string() + " -o " +
                      (dir / "bad.pdf").string());
  ASSERT_EQ(r.status, 0) << r.out;
  const Exit text = Exec("pdftotext " + (dir / "bad.pdf").string() + " -");
  EXPECT_NE(text.out.find("before\xef\xbf\xbd"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("after"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("start\xef\xbf\xbd"
                          "end of the text"),
            std::string::npos)
      << text.out;
}

// The hostile document of issue 12: an animation that tries every command a
// scene may not use, entity references meant as a bomb in its text, and a
// poster that claims gigapixels.  It converts within 30 s under a 2 GB
// address-space limit, each problem is reported, and the rest is intact.
TEST(HostileDocuments, TheHostileDocumentConvertsWithEveryProblemReported) {
  const fs::path dir = Scratch("hostile");
  // Every command is tried (each under catch: one that worked would end the
  // scene with "allowed: ..."), then the first again, uncaught, to be reported.
  // A file to delete and one to create show that none had an effect.
  const std::string victim = (dir / "victim").string(), pwned = (dir / "pwned").string();
  std::ofstream(victim) << "still here";
  std::string scene =
      "shape_set s -desc \\{-sub \\{-sphere 0.5\\}\\}\n"
      "body b -shape s\nsimulator -finish 1\nforeach c [list";
  for (const std::string& cmd : std::vector<std::string>{
           "exec touch " + pwned, "open " + pwned + " w", "file delete " + victim,
           "socket localhost 80", "source " + victim, "load libc.so", "cd /", "exit 3", "glob *",
           "pwd", "interp create x", "after 100000", "vwait forever", "update", "fconfigure stdout",
           "encoding system", "unload x", "puts hi"})
    scene += " \\{" + cmd + "\\}";
  scene += "] \\{\n  if \\{![catch $c]\\} \\{ error \"allowed: $c\" \\}\n\\}\nexec touch " + pwned +
           "\n";
  // A PNG header claiming 100000 x 100000 pixels (and nothing after it).
  std::string png = "\x89PNG\r\n\x1a\n";
  png += std::string("\0\0\0\x0dIHDR", 8);
  for (uint32_t v : {100000u, 100000u})
    for (int k = 3; k >= 0; --k) png += static_cast<char>((v >> (8 * k)) & 0xff);
  png += std::string("\x08\x06\0\0\0\0\0\0\0", 9);
  std::string bomb = "<!ENTITY lol \"lol\"> ";
  for (int i = 0; i < 200; ++i) bomb += "&lol9; ";
  const std::string doc =
      "DOCUMENT CMEMO\n<CMEMO>\n<TO>{Whom it may concern}</TO>\n<SUBJECT>{Hostile}</SUBJECT>\n"
      "<BODY>\n<PARAGRAPH><TEXT>{Before the animation. " +
      bomb +
      "}</TEXT></PARAGRAPH>\n"
      "<PARAGRAPH><DOCUMENT>\nDOCUMENT ANIMATION\n<ANIMATION>\n<ASGARD>{\n" +
      scene + "}</ASGARD>\n<POSTER>{" + Base64Encode(png) +
      "}</POSTER>\n</ANIMATION>\n</DOCUMENT>"
      "</PARAGRAPH>\n<PARAGRAPH><TEXT>{After the animation: the end.}</TEXT></PARAGRAPH>\n"
      "</BODY>\n</CMEMO>\n";
  std::ofstream(dir / "hostile.ens") << doc;
  const auto start = std::chrono::steady_clock::now();
  const Exit r = Exec(
      "bash -c '" + std::string(asgard::tests::kAddressSanitizer ? "" : "ulimit -v 2000000; ") +
      "exec timeout 60 " + kDochost + " convert --timeout 5 " + (dir / "hostile.ens").string() +
      " -o " + (dir / "hostile.pdf").string() + "'");
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(30));
  EXPECT_NE(r.status, -1) << r.out;
  EXPECT_NE(r.status, 124) << "timed out: " << r.out;
  EXPECT_EQ(r.status, 3) << "the animation and the poster are left out: " << r.out;
  EXPECT_NE(r.out.find("hostile.ens:"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("<POSTER>: ignored: the picture is 100000 × 100000 pixels"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("animation 1:"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("not available in scene scripts"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("allowed:"), std::string::npos) << r.out;
  EXPECT_EQ(Read(victim), "still here");
  EXPECT_FALSE(fs::exists(pwned));
  Exit text = Exec("pdftotext " + (dir / "hostile.pdf").string() + " -");
  text.out = Collapsed(text.out);
  EXPECT_NE(text.out.find("Before the animation."), std::string::npos) << text.out;
  EXPECT_EQ(Count(text.out, "&lol9;"), 200u) << "the text is shown as written";
  EXPECT_NE(text.out.find("After the animation: the end."), std::string::npos) << text.out;
}

// A slave killed while a page is exported is restarted once; the page gets
// its frames and stderr says what happened.
TEST(HostileDocuments, ASlaveKilledDuringHtmlExportIsRestartedOnceAndReported) {
  const fs::path dir = Scratch("restart");
  const std::string memo = std::string(ASGARD_SOURCE_DIR) + "/samples/memo.ens";
  const std::string html = (dir / "memo.html").string();
  const Exit once =
      Exec("ASGARD_CORE_FAULT=exit-on-frame ASGARD_CORE_FAULT_ONCE=" + (dir / "marker").string() +
           " " + kDochost + " convert " + memo + " -o " + html);
  EXPECT_EQ(once.status, 0) << once.out;
  EXPECT_NE(once.out.find("animation 1: asgard-core exited with status 9"), std::string::npos)
      << once.out;
  EXPECT_NE(once.out.find("it was restarted once"), std::string::npos) << once.out;
  EXPECT_GT(Count(Read(html), "data:image/png;base64,"), 10u) << "the frames are in the page";

  // Dying again after the restart: the poster, and the reason on stderr.
  const Exit always =
      Exec("ASGARD_CORE_FAULT=exit-on-frame " + kDochost + " convert " + memo + " -o " + html);
  EXPECT_EQ(always.status, 3) << "the page shows a poster, not the animation: " << always.out;
  EXPECT_NE(always.out.find("it was restarted once"), std::string::npos) << always.out;
  EXPECT_NE(always.out.find("dochost: " + memo + ": animation 1: asgard-core exited"),
            std::string::npos)
      << always.out;
}

// `recompute` said "recomputed" (exit 0) when the slave had died.
TEST(HostileDocuments, RecomputeWithADeadSlaveIsAnError) {
  const fs::path dir = Scratch("recompute");
  fs::copy_file(std::string(ASGARD_SOURCE_DIR) + "/samples/memo.ens", dir / "memo.ens");
  const std::string before = Read(dir / "memo.ens");
  const Exit r = Exec("ASGARD_CORE_FAULT=exit-on-frame " + kDochost + " verb " +
                      (dir / "memo.ens").string() + " recompute");
  EXPECT_EQ(r.status, 1) << r.out;
  EXPECT_EQ(r.out.find("animation 1: recomputed"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("not recomputed"), std::string::npos) << r.out;
  EXPECT_EQ(Read(dir / "memo.ens"), before) << "the document is left alone";
}

// --- asgard-core fed raw frames on standard input ---------------------------

std::string Frame(const std::string& body) {
  const auto head = protocol::EncodeLength(static_cast<uint32_t>(body.size()));
  return std::string(head.begin(), head.end()) + body;
}

struct CoreRun {
  int status = -1;    // exit status, or -signal
  std::string out;    // the answers' bodies, one a line
  std::string error;  // stderr
};

// Runs asgard-core on `frames` in the scratch folder `scratch` (its own per
// test: ctest runs tests in parallel, and a shared folder let one test read
// the other's output).
CoreRun RunCore(const std::string& scratch, const std::string& frames,
                const std::string& args = "") {
  const fs::path dir = Scratch(scratch);
  std::ofstream(dir / "in", std::ios::binary) << frames;
  const std::string cmd = kCore + " " + args + " < " + (dir / "in").string() + " > " +
                          (dir / "out").string() + " 2> " + (dir / "err").string();
  const int s = std::system(cmd.c_str());
  CoreRun r;
  r.status = WIFEXITED(s) ? WEXITSTATUS(s) : -1;
  const std::string raw = Read(dir / "out");
  for (size_t i = 0; i + 4 <= raw.size();) {
    const uint32_t n = protocol::DecodeLength(reinterpret_cast<const unsigned char*>(&raw[i]));
    r.out += raw.substr(i + 4, n) + "\n";
    i += 4 + n;
  }
  r.error = Read(dir / "err");
  return r;
}

TEST(HostileProtocol, DeeplyNestedMessageIsAnsweredWithAnError) {
  std::string deep = "{\"jsonrpc\":\"2.0\",\"id\":1,\"method\":\"load\",\"params\":{\"text\":";
  deep += std::string(1000000, '[') + std::string(1000000, ']') + "}}";
  const CoreRun r =
      RunCore("core_deep", Frame(deep) + Frame(R"({"jsonrpc":"2.0","id":2,"method":"shutdown"})"));
  EXPECT_EQ(r.status, 0) << r.error;
  EXPECT_NE(r.out.find("nested more than 64 deep"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"id\":2"), std::string::npos) << r.out;  // still answering
}

TEST(HostileProtocol, NestingDepthScanIgnoresBracketsInStrings) {
  EXPECT_EQ(protocol::JsonNestingDepth(R"({"a":"[[[[{{{{\"[[["})"), 1);
  EXPECT_EQ(protocol::JsonNestingDepth(R"([[{"a":[1]}]])"), 4);
  EXPECT_EQ(protocol::JsonNestingDepth(std::string(100, '[')), 65);  // stops past the limit
}

TEST(HostileProtocol, SharedMemoryLargerThanItsFileIsRefused) {
  const fs::path dir = Scratch("shm");
  const std::string file = (dir / "shm").string();
  std::ofstream(file) << std::string(4096, '\0');
  const std::string frames = Frame(R"({"jsonrpc":"2.0","id":1,"method":"shutdown"})");
  std::ofstream(dir / "in", std::ios::binary) << frames;
  const std::string cmd = kCore + " --shm-fd 5 --shm-size 1073741824 5<>" + file + " < " +
                          (dir / "in").string() + " > /dev/null 2> " + (dir / "err").string();
  const int s = std::system(cmd.c_str());
  ASSERT_TRUE(WIFEXITED(s)) << "killed by a signal";
  EXPECT_EQ(WEXITSTATUS(s), 2);
  EXPECT_NE(Read(dir / "err").find("larger than the shared frame memory"), std::string::npos)
      << Read(dir / "err");
}

// --- A catalogue of bad protocol messages -------------------------------------
//
// One asgard-core session (with 64 KB of shared frame memory) is sent every
// message below in order; each bad one must be answered with an error that
// names its place: the request (its id), the byte where the text stopped
// being JSON, the member of params, or the scene's line and column.  The
// session must keep answering after each.  Setup messages (`setup`) bring it
// into the state the next case needs.

struct ProtocolCase {
  const char* name;
  std::string body;
  std::string id;     // the answer's id, as JSON
  std::string words;  // in the error message (or, for the others, in the result)
  // kError: answered with a JSON-RPC error; kReported: bad input reported in
  // the result (a scene's diagnostics); kSetup: not a bad input.
  enum Kind { kError, kReported, kSetup } kind = kError;
};

std::string Req(int id, const std::string& method, const std::string& params = "") {
  return "{\"jsonrpc\":\"2.0\",\"id\":" + std::to_string(id) + ",\"method\":\"" + method + "\"" +
         (params.empty() ? "" : ",\"params\":" + params) + "}";
}

std::vector<ProtocolCase> ProtocolCatalogue() {
  const std::string bad_scene =
      R"({"text":"shape_set s -desc {-sub {-sphere 1}}\nbody b -shape nope\n"})";
  const std::string good_scene =
      R"({"text":"shape_set s -desc {-sub {-sphere 1}}\nbody b -shape s\nsimulator -finish 1\n"})";
  const std::string side = std::to_string(protocol::kMaxRenditionSide);
  const std::string open = R"({"rendition":0,"width":16,"height":16,"offset":0})";
  return {
      {"EmptyMessage", "", "null", "parse error at byte 1: the message is not JSON"},
      {"TruncatedObject", R"({"jsonrpc":"2.0","id":1,"method":)", "null",
       "parse error at byte 34:"},
      {"GarbageAfterAMember", R"({"id":2,"method":"load" x})", "null", "parse error at byte 25:"},
      {"InvalidUtf8InAString",
       "{\"id\":3,\"method\":\"lo\xff"
       "ad\"}",
       "null", "parse error at byte 21:"},
      {"NumberPastTheRangeOfADouble", R"({"jsonrpc":"2.0","id":4,"method":"ping","x":1e999})",
       "null", "parse error: the message cannot be read: number overflow parsing '1e999'"},
      // Found by fuzz_protocol: the exception escaped and ended the slave.
      {"AnOverflowingNumberAlone", "2222222.2220e22220008", "null",
       "parse error: the message cannot be read: number overflow parsing '2222222.2220e22220008'"},
      {"TrailingGarbage", R"({"id":4,"method":"ping"}}})", "null", "parse error at byte 25:"},
      {"NestedSixtyFiveDeep", std::string(65, '[') + std::string(65, ']'), "null",
       "nested more than 64 deep"},
      {"AnArrayIsNotARequest", "[1,2,3]", "null", "expected an object with a string 'method'"},
      {"NullIsNotARequest", "null", "null", "expected an object with a string 'method'"},
      {"RequestWithoutMethod", R"({"id":5})", "5", "expected an object with a string 'method'"},
      {"MethodThatIsANumber", R"({"id":6,"method":7})", "6",
       "expected an object with a string 'method'"},
      {"ParamsThatAreAnArray", R"({"id":7,"method":"load","params":[1]})", "7",
       "expected an object with a string 'method'"},
      {"UnknownMethod", Req(8, "fly"), "8", "unknown method 'fly'"},
      {"ObjectIdIsEchoed", R"({"id":{"a":1},"method":"fly"})", R"({"a":1})",
       "unknown method 'fly'"},
      {"LoadWithoutText", Req(9, "load", "{}"), "9", "invalid params: 'text' is missing"},
      {"LoadWithNumericText", Req(10, "load", R"({"text":5})"), "10",
       "invalid params: 'text' must be a string"},
      {"EditBeforeLoad", Req(11, "edit", R"({"element":"b","param":"-mass","values":[2]})"), "11",
       "no scene is loaded"},
      {"UndoBeforeLoad", Req(12, "undo"), "12", "no scene is loaded"},
      {"CommandWithoutLine", Req(13, "command", "{}"), "13", "invalid params: 'line' is missing"},
      {"CommandLineThatIsANumber", Req(14, "command", R"({"line":42})"), "14",
       "invalid params: 'line' must be a string"},
      {"UnknownCommand", Req(15, "command", R"({"line":"format c:"})"), "15",
       "unknown command 'format c:' (known: handles on|off, info, ping, player [RATE])"},
      {"OpenWithoutRendition", Req(16, "open_rendition", R"({"width":16,"height":16,"offset":0})"),
       "16", "invalid params: 'rendition' is missing"},
      {"OpenWithAHugeWidth",
       Req(17, "open_rendition", R"({"rendition":0,"width":1e300,"height":16,"offset":0})"), "17",
       "invalid params: 'width' must be an integer from 1 to " + side},
      {"OpenWithAFractionalWidth",
       Req(18, "open_rendition", R"({"rendition":0,"width":0.5,"height":16,"offset":0})"), "18",
       "invalid params: 'width' must be an integer from 1 to " + side},
      {"OpenWithAWidthThatIsAString",
       Req(19, "open_rendition", R"({"rendition":0,"width":"640","height":16,"offset":0})"), "19",
       "invalid params: 'width' must be an integer"},
      {"OpenWithANegativeHeight",
       Req(20, "open_rendition", R"({"rendition":0,"width":16,"height":-1,"offset":0})"), "20",
       "invalid params: 'height' must be an integer from 1 to " + side},
      {"OpenWithAnOffsetOfTwoToThe63",
       Req(45, "open_rendition",
           R"({"rendition":0,"width":16,"height":16,"offset":9223372036854775808.0})"),
       "45", "invalid params: 'offset' must be an integer from 0 to"},
      {"OpenWithANegativeOffset",
       Req(21, "open_rendition", R"({"rendition":0,"width":16,"height":16,"offset":-5})"), "21",
       "invalid params: 'offset' must be an integer from 0 to"},
      {"OpenPastTheSharedMemory",
       Req(22, "open_rendition", R"({"rendition":0,"width":16,"height":16,"offset":65000})"), "22",
       "invalid params: the rendition does not fit in shared memory"},
      {"OpenWithANegativeRendition",
       Req(23, "open_rendition", R"({"rendition":-1,"width":16,"height":16,"offset":0})"), "23",
       "invalid params: 'rendition' must be an integer from 0 to"},
      {"CloseWithARenditionThatIsAString", Req(24, "close_rendition", R"({"rendition":"a"})"), "24",
       "invalid params: 'rendition' must be an integer"},
      {"FrameOfARenditionNeverOpened", Req(25, "frame", R"({"rendition":3,"t":0})"), "25",
       "invalid params: no rendition 3"},
      {"OpenRendition", Req(26, "open_rendition", open), "26", "\"ok\":true", ProtocolCase::kSetup},
      {"FrameBeforeSimulate", Req(27, "frame", R"({"rendition":0,"t":0})"), "27",
       "the scene has not been simulated"},
      {"LoadASceneWithAnError", Req(28, "load", bad_scene), "28",
       R"({"column":15,"line":2,"message":"body 'b': unknown shape_set 'nope'"})",
       ProtocolCase::kReported},
      {"SimulateASceneWithAnError", Req(29, "simulate"), "29",
       "2:15: body 'b': unknown shape_set 'nope'"},
      {"LoadAGoodScene", Req(30, "load", good_scene), "30", "\"ok\":true", ProtocolCase::kSetup},
      {"EditWithoutValues", Req(31, "edit", R"({"element":"b","param":"-mass"})"), "31",
       "invalid params: edit needs element, param and values"},
      {"EditWithAValueThatIsAString",
       Req(32, "edit", R"({"element":"b","param":"-mass","values":["x"]})"), "32",
       "invalid params: values must be numbers"},
      {"EditOfAnUnknownElement",
       Req(33, "edit", R"({"element":"zz","param":"-mass","values":[2]})"), "33", "zz"},
      {"Simulate", Req(34, "simulate"), "34", "\"t1\":1.0", ProtocolCase::kSetup},
      {"FrameWithoutTime", Req(35, "frame", R"({"rendition":0})"), "35",
       "invalid params: 't' is missing"},
      {"FrameAtATimeThatIsAString", Req(36, "frame", R"({"rendition":0,"t":"now"})"), "36",
       "invalid params: 't' must be a number"},
      {"FrameWithHandlesThatAreAString",
       Req(38, "frame", R"({"rendition":0,"t":0,"handles":"yes"})"), "38",
       "invalid params: 'handles' must be true or false"},
      {"FrameWithWireThatIsANumber", Req(39, "frame", R"({"rendition":0,"t":0,"wire":1})"), "39",
       "invalid params: 'wire' must be true or false"},
      {"AFrameStillWorks", Req(40, "frame", R"({"rendition":0,"t":0.5,"wire":true})"), "40",
       "\"width\":16", ProtocolCase::kSetup},
  };
}

TEST(HostileProtocol, EveryBadMessageIsAnsweredWithItsPlace) {
  const fs::path dir = Scratch("catalogue");
  const std::string shm = (dir / "shm").string();
  std::ofstream(shm) << std::string(65536, '\0');
  const auto cases = ProtocolCatalogue();
  std::string frames;
  for (const auto& c : cases) frames += Frame(c.body);
  frames += Frame(Req(99, "shutdown"));
  const CoreRun r = RunCore("core_catalogue", frames, "--shm-fd 5 --shm-size 65536 5<>" + shm);
  EXPECT_EQ(r.status, 0) << r.error;
  std::vector<std::string> answers;
  std::istringstream lines(r.out);
  for (std::string line; std::getline(lines, line);)
    if (line.find("\"method\":\"progress\"") == std::string::npos) answers.push_back(line);
  ASSERT_EQ(answers.size(), cases.size() + 1) << r.out;
  int bad = 0;
  for (size_t i = 0; i < cases.size(); ++i) {
    const ProtocolCase& c = cases[i];
    const std::string& a = answers[i];
    bad += c.kind != ProtocolCase::kSetup;
    EXPECT_NE(a.find("\"id\":" + c.id), std::string::npos) << c.name << ": " << a;
    EXPECT_EQ(a.find("\"error\"") != std::string::npos, c.kind == ProtocolCase::kError)
        << c.name << ": " << a;
    EXPECT_NE(a.find(c.words), std::string::npos) << c.name << ": " << a;
  }
  EXPECT_EQ(bad, 43);  // and 5 setup messages
}

}  // namespace
}  // namespace asgard::document
