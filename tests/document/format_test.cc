// Document storage formats: the seed's memo, byte-exact round trips (property
// style, both flavours), located errors, atomic writes.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <random>

#include "formats/document/document.h"
#include "formats/document/file.h"
#include "formats/document/xml.h"

namespace asgard::document {
namespace {

std::string Sample(const std::string& name) {
  std::string bytes;
  EXPECT_TRUE(ReadFile(std::string(ASGARD_SOURCE_DIR) + "/samples/" + name, bytes, nullptr));
  return bytes;
}

const Node* Find(const std::vector<Node>& nodes, const std::string& tag) {
  for (const Node& n : nodes) {
    if (n.IsElement(tag)) return &n;
    if (const Node* f = Find(n.children, tag)) return f;
  }
  return nullptr;
}

TEST(Memo, ParsesTheTreeOfFigure62) {
  const std::string bytes = Sample("memo.ens");
  auto r = Parse(bytes);
  ASSERT_TRUE(r.ok()) << r.error.Format();
  EXPECT_EQ(r.document->Type(), "CMEMO");
  const Node* to = Find(r.document->nodes, "TO");
  ASSERT_NE(to, nullptr);
  EXPECT_EQ(to->children.at(0).Text(), "Whom it may concern");
  const Node* sub = Find(r.document->nodes, "DOCUMENT");
  ASSERT_NE(sub, nullptr);
  const Node* asgard = Find(sub->children, "ASGARD");
  ASSERT_NE(asgard, nullptr);
  const std::string scene = asgard->children.at(0).Text();
  EXPECT_NE(scene.find("shape_set ss1 -desc {-sub {-pos {0 0 0} -sphere 0.5}}"), std::string::npos);
  EXPECT_EQ(asgard->line, 10);
  EXPECT_EQ(Write(*r.document), bytes);
}

TEST(Memo, XmlRoundTripIsByteExactBothWays) {
  const std::string bytes = Sample("memo.ens");
  auto r = Parse(bytes);
  ASSERT_TRUE(r.ok());
  const std::string xml = WriteXml(*r.document);
  EXPECT_NE(xml.find("-desc {-sub {-pos"), std::string::npos) << xml;
  auto back = ParseXml(xml);
  ASSERT_TRUE(back.ok()) << back.error.Format();
  EXPECT_EQ(Write(*back.document), bytes);
  EXPECT_EQ(WriteXml(*back.document), xml);
  EXPECT_TRUE(LooksLikeXml(xml));
  EXPECT_FALSE(LooksLikeXml(bytes));
}

TEST(Memo, RicherSampleRoundTrips) {
  const std::string bytes = Sample("two-animations.ens");
  auto r = Parse(bytes);
  ASSERT_TRUE(r.ok()) << r.error.Format();
  EXPECT_EQ(Write(*r.document), bytes);
  auto x = ParseXml(WriteXml(*r.document));
  ASSERT_TRUE(x.ok()) << x.error.Format();
  EXPECT_EQ(Write(*x.document), bytes);
}

// Random text: braces, backslashes, tags, whitespace, non-ASCII, CR/LF.
std::string RandomText(std::mt19937& rng) {
  static const std::vector<std::string> pieces = {
      "{",          "}",          "\\",    "\\{",      "\\}", "\\\\", "<TAG>", "</TAG>",
      "<DOCUMENT>", "DOCUMENT X", " ",     "\n",       "\t",  "\r\n", "é",     "→",
      "日本",       "𝄞",          "&amp;", "<",        ">",   "\"",   "'",     "]]>",
      "a",          "set x 1",    "$y",    "[expr 2]", "\\n", "\x01", "\x7f"};
  std::uniform_int_distribution<int> len(0, 40), pick(0, static_cast<int>(pieces.size()) - 1);
  std::string s;
  for (int i = len(rng); i > 0; --i) s += pieces[pick(rng)];
  return s;
}

Document RandomDocument(std::mt19937& rng, std::vector<std::string>& texts) {
  std::uniform_int_distribution<int> coin(0, 3);
  auto space = [&]() { return Node::Space(coin(rng) ? "\n" : " \t\r\n  "); };
  std::vector<Node> body;
  for (int i = 0; i < 6; ++i) {
    texts.push_back(RandomText(rng));
    std::vector<Node> inner;
    if (coin(rng) == 0) inner.push_back(space());
    inner.push_back(Node::TextNode(texts.back()));
    if (coin(rng) == 0) {
      texts.push_back(RandomText(rng));
      std::vector<Node> sub = {
          space(), Node::Header("ANIMATION"), space(),
          Node::Element("ANIMATION", {Node::Element("ASGARD", {Node::TextNode(texts.back())})})};
      inner.push_back(Node::Element("DOCUMENT", std::move(sub)));
    }
    body.push_back(Node::Element(i % 2 ? "PARAGRAPH" : "TEXT", std::move(inner)));
    body.push_back(space());
  }
  Document d;
  d.nodes = {Node::Header("MEMO"), space(), Node::Element("MEMO", std::move(body)), space()};
  return d;
}

std::vector<std::string> Texts(const Document& d) {
  std::vector<std::string> out;
  ForEachNode(d.nodes, [&](const Node& n) {
    if (n.kind == NodeKind::kText) out.push_back(n.Text());
  });
  return out;
}

TEST(RoundTrip, RandomTextSurvivesEncodingByteForByte) {
  std::mt19937 rng(1994);
  for (int i = 0; i < 2000; ++i) {
    const std::string t = RandomText(rng);
    EXPECT_EQ(DecodeText(EncodeText(t)), t);
  }
}

TEST(RoundTrip, RandomDocumentsSurviveBothFlavours) {
  std::mt19937 rng(813);
  for (int i = 0; i < 300; ++i) {
    std::vector<std::string> texts;
    const Document d = RandomDocument(rng, texts);
    ASSERT_FALSE(CheckStructure(d).has_value()) << CheckStructure(d)->message;
    const std::string sgml = Write(d);
    auto p = Parse(sgml);
    ASSERT_TRUE(p.ok()) << p.error.Format() << "\n" << sgml;
    EXPECT_EQ(Write(*p.document), sgml);
    EXPECT_EQ(Texts(*p.document), texts);
    const std::string xml = WriteXml(*p.document);
    auto x = ParseXml(xml);
    ASSERT_TRUE(x.ok()) << x.error.Format() << "\n" << xml;
    EXPECT_EQ(Write(*x.document), sgml);
    EXPECT_EQ(Texts(*x.document), texts);
    EXPECT_EQ(WriteXml(*x.document), xml);
  }
}

TEST(RoundTrip, LenientEscapesAndOddSpacingAreKeptExactly) {
  const std::string bytes =
      "\r\n  DOCUMENT \t X\r\n<X>  <A>{puts \"a\\nb\" \\q \\{ }</A>\t{}<B></B>\n</X>\n\n";
  auto r = Parse(bytes);
  ASSERT_TRUE(r.ok()) << r.error.Format();
  EXPECT_EQ(Write(*r.document), bytes);
  EXPECT_EQ(Find(r.document->nodes, "A")->children[0].Text(), "puts \"a\\nb\" \\q { ");
  auto x = ParseXml(WriteXml(*r.document));
  ASSERT_TRUE(x.ok()) << x.error.Format();
  EXPECT_EQ(Write(*x.document), bytes);
}

struct Bad {
  std::string text;
  int line, column;  // column 0: not checked (libxml2's columns are approximate)
  std::string words;
};

// Each case fails to parse, at its line (and column), with its words.
template <typename ParseFn>
void ExpectLocated(const std::vector<Bad>& cases, ParseFn parse) {
  for (const Bad& b : cases) {
    auto r = parse(b.text);
    EXPECT_FALSE(r.ok()) << b.text;
    if (r.ok()) continue;
    EXPECT_EQ(r.error.line, b.line) << b.text << " → " << r.error.Format();
    if (b.column) {
      EXPECT_EQ(r.error.column, b.column) << b.text << " → " << r.error.Format();
    }
    EXPECT_GE(r.error.column, 1) << r.error.Format();
    EXPECT_NE(r.error.message.find(b.words), std::string::npos) << r.error.Format();
  }
}

TEST(Errors, MalformedInputIsLocated) {
  const std::vector<Bad> cases = {
      {"", 1, 1, "DOCUMENT <TYPE>"},
      {"DOCUMENT X\n<X>\n<A>{x}</B>\n</X>", 3, 7, "</B> does not close <A> (opened at 3:1)"},
      {"DOCUMENT X\n<X>\n  <A>{abc", 3, 6, "unterminated text"},
      {"DOCUMENT X\n<X>\n<A>{a{b}</A></X>", 3, 6, "unescaped '{'"},
      {"DOCUMENT X\n<X>\nhello</X>", 3, 1, "text content goes inside"},
      {"DOCUMENT X\n<Y></Y>", 2, 1, "does not match the document type X"},
      {"DOCUMENT X\n<X></X>\n<X></X>", 3, 1, "after the root element"},
      {"DOCUMENT X\n<X>\n<A>\n", 3, 1, "unterminated <A>"},
      {"DOCUMENT X\n<X><DOCUMENT>\n<A></A></DOCUMENT></X>", 3, 1, "DOCUMENT <TYPE>"},
      {"DOCUMENT X\n<X><A x=1></A></X>", 2, 6, "expected '>'"},
      {"DOCUMENTX\n<X></X>", 1, 9, "expected a space"},
      {"DOCUMENT X\n<X>}</X>", 2, 4, "unmatched '}'"},
      {"DOCUMENT X\n<X>\n<é>", 3, 2, "tag name"},
      {"\n\n  DOKUMENT X\n<X></X>", 3, 3, "expected a 'DOCUMENT <TYPE>' line but found"},
      {"DOCUMENT", 1, 9, "expected a space and the document type after DOCUMENT"},
      {"DOCUMENT X", 1, 11, "expected the root element <X> but the file ends"},
      {"DOCUMENT 9X\n<X></X>", 1, 10, "expected the document type but found"},
      {"DOCUMENT X;\n<X></X>", 1, 11, "after the document type"},
      {"DOCUMENT X\n</X>", 2, 1, "expected the root element <X> but found"},
      {"DOCUMENT X\n<X", 2, 3, "the file ends inside the tag <X"},
      {"DOCUMENT X\n<X></X", 2, 7, "expected '>' after </X"},
      {"DOCUMENT X\n<X></>", 2, 6, "expected a tag name after '</'"},
      {"DOCUMENT X\n<X><>", 2, 5, "expected a tag name after '<'"},
      {"DOCUMENT X\n<X>\n  <A>\n  {one}\n  {two\\}</A></X>", 5, 3,
       "unterminated text: the file ends before its closing '}'"},
      {"DOCUMENT X\n<X><DOCUMENT>\nDOCUMENT Y <Y></Y>", 2, 4,
       "unterminated <DOCUMENT>: the file ends before </DOCUMENT>"},
      {"DOCUMENT X\n<X><DOCUMENT>DOCUMENT Y <Y></Y> {t}</DOCUMENT></X>", 2, 33,
       "in <DOCUMENT> after its root element"},
      {"DOCUMENT X\n<X><DOCUMENT>DOCUMENT Y <Z></Z></DOCUMENT></X>", 2, 25,
       "the root element <Z> does not match the document type Y"},
      {"DOCUMENT X\n<X>\n\n\n      <A>{x}</A>\n<B>\n</X>", 7, 1, "</X> does not close <B>"},
  };
  ExpectLocated(cases, [](const std::string& t) { return Parse(t); });
}

TEST(Errors, ColumnsCountCharactersNotBytes) {
  auto r = Parse("DOCUMENT X\n<X><A>{é→}</A>x</X>");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error.line, 2);
  EXPECT_EQ(r.error.column, 15);
}

TEST(Errors, DeepNestingIsRefused) {
  std::string s = "DOCUMENT X\n<X>";
  for (int i = 0; i < 400; ++i) s += "<A>";
  auto r = Parse(s);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error.message.find("deeper"), std::string::npos);
}

TEST(Errors, XmlErrorsAreLocated) {
  auto r = ParseXml(
      "<?xml version=\"1.0\"?>\n<ens:file xmlns:ens=\"urn:asgard:ensemble-document\">\n"
      "<ens:header>DOCUMENT X</ens:header><X><A></B></X></ens:file>");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error.line, 3);
  EXPECT_GT(r.error.column, 1);
  auto s = ParseXml(
      "<?xml version=\"1.0\"?>\n<ens:file xmlns:ens=\"urn:asgard:ensemble-document\">\n"
      "<ens:header>DOCUMENT X</ens:header>\n<Y/></ens:file>");
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.error.line, 4);
  EXPECT_NE(s.error.message.find("does not match"), std::string::npos);
  auto t = ParseXml("<?xml version=\"1.0\"?><other/>");
  ASSERT_FALSE(t.ok());
  EXPECT_NE(t.error.message.find("ens:file"), std::string::npos);
}

// XML flavour: what libxml2 refuses, and well-formed XML that is not an
// Asgard document, each at its line and column.
TEST(Errors, XmlCatalogueIsLocated) {
  const std::string head =
      "<?xml version=\"1.0\"?>\n<ens:file xmlns:ens=\"urn:asgard:ensemble-document\">\n";
  const std::vector<Bad> cases = {
      {"", 1, 1, "Document is empty"},
      {"<?xml version=\"1.0\"?>\n<a>\n<b></a>", 3, 0, "mismatch"},
      {"<?xml version=\"1.0\"?>\n<a x=1/>", 2, 0, "AttValue"},
      {"<?xml version=\"1.0\"?>\n<a>&nosuch;</a>", 2, 0, "nosuch"},
      {"<?xml version=\"1.0\"?>\n<a>\xff\xfe</a>", 2, 0, "UTF-8"},
      {head + "<ens:header>DOCUMENT X</ens:header>\n<X>\n<A>\n</X></ens:file>", 6, 5,
       "Opening and ending tag mismatch: A line 5 and X"},
      {head + "<ens:header>DOCUMENT X</ens:header>\n<Y/></ens:file>", 4, 0, "does not match"},
      {head + "<X/></ens:file>", 3, 1, "<X> before the 'DOCUMENT <TYPE>' line"},
      // Found by fuzz_xml: an empty ens:file was refused at line 0.
      {head + "</ens:file>", 2, 1, "a document without its 'DOCUMENT <TYPE>' line"},
      {head + "<ens:header>DOCUMENT X</ens:header>\n</ens:file>", 2, 1,
       "a document without its root element"},
  };
  ExpectLocated(cases, [](const std::string& t) { return ParseXml(t); });
}

TEST(Files, AtomicWriteReplacesOrLeavesUntouched) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(ASGARD_BINARY_DIR) / "tests/document/scratch_files";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string path = (dir / "a.ens").string();
  std::string error;
  ASSERT_TRUE(WriteFileAtomic(path, "first", &error)) << error;
  ASSERT_TRUE(WriteFileAtomic(path, "second", &error)) << error;
  std::string bytes;
  ASSERT_TRUE(ReadFile(path, bytes, nullptr));
  EXPECT_EQ(bytes, "second");
  // A directory that cannot be written: the old file stays, no temporary is left.
  ::chmod(dir.c_str(), 0555);
  const bool wrote = WriteFileAtomic(path, "third", &error);
  ::chmod(dir.c_str(), 0755);
  if (::geteuid() != 0) {
    EXPECT_FALSE(wrote);
    EXPECT_NE(error.find("cannot write"), std::string::npos);
    ASSERT_TRUE(ReadFile(path, bytes, nullptr));
    EXPECT_EQ(bytes, "second");
  }
  int files = 0;
  for ([[maybe_unused]] auto& e : fs::directory_iterator(dir)) ++files;
  EXPECT_EQ(files, 1);
  EXPECT_FALSE(WriteFileAtomic((dir / "no/such/dir.ens").string(), "x", &error));
}

TEST(Files, LoadReportsFileLineAndColumn) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(ASGARD_BINARY_DIR) / "tests/document/scratch_load";
  fs::create_directories(dir);
  const std::string path = (dir / "bad.ens").string();
  ASSERT_TRUE(WriteFileAtomic(path, "DOCUMENT X\n<X>\n<A>{x}</B></X>", nullptr));
  auto r = LoadDocument(path);
  EXPECT_FALSE(r.document);
  EXPECT_EQ(r.error, path + ":3:7: error: </B> does not close <A> (opened at 3:1)");
}

TEST(Base64, RoundTripsAndRejectsJunk) {
  std::mt19937 rng(7);
  for (int n = 0; n < 70; ++n) {
    std::string s;
    for (int i = 0; i < n; ++i) s += static_cast<char>(rng() & 0xff);
    EXPECT_EQ(Base64Decode(Base64Encode(s, 76)), s);
  }
  EXPECT_EQ(Base64Encode("Man"), "TWFu");
  EXPECT_EQ(Base64Encode("Ma"), "TWE=");
  EXPECT_FALSE(Base64Decode("TW*u"));
}

}  // namespace
}  // namespace asgard::document
