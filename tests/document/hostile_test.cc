// Hostile documents, files and protocol messages: each is refused with a
// located message (or handled without loss), never a crash, hang or silent
// change.  Issue 12's classes, one test each.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "core/protocol/protocol.h"
#include "formats/document/document.h"
#include "formats/document/file.h"
#include "formats/document/xml.h"

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

CoreRun RunCore(const std::string& frames, const std::string& args = "") {
  const fs::path dir = Scratch("core");
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
  const CoreRun r = RunCore(Frame(deep) + Frame(R"({"jsonrpc":"2.0","id":2,"method":"shutdown"})"));
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

}  // namespace
}  // namespace asgard::document
