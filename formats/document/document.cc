// The SGML-like reader and writer.
//
// Design: a recursive-descent reader over the bytes with a cursor that counts
// lines and characters (UTF-8 continuation bytes do not advance the column).
// Every byte lands in exactly one node — whitespace between tags becomes a
// kSpace node, a text keeps its escaped bytes, a header its line — so the
// writer is plain concatenation and the round trip is exact by construction.
// The reader stops at the first problem and reports it with the line and
// column where it was found (and, for an unclosed element, where it opened).
// Nesting is limited to kMaxDepth levels so a hostile file cannot exhaust the
// stack.
#include "formats/document/document.h"

#include <sstream>

namespace asgard::document {

namespace {

constexpr int kMaxDepth = 256;

bool IsSpace(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f'; }
bool IsNameStart(char c) { return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || c == '_'; }
bool IsNameChar(char c) { return IsNameStart(c) || (c >= '0' && c <= '9') || c == '-' || c == '.'; }

std::string Describe(char c) {
  if (c == '\n') return "a line break";
  if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
    std::ostringstream s;
    s << "control character 0x" << std::hex << (static_cast<unsigned>(c) & 0xff);
    return s.str();
  }
  if (static_cast<unsigned char>(c) >= 0x80) return "a non-ASCII character";
  return std::string("'") + c + "'";
}

struct Failure {
  ParseError error;
};

class Reader {
 public:
  explicit Reader(std::string_view bytes) : s_(bytes) {}

  Document ReadDocument() {
    Document doc;
    ReadDocumentContent(doc.nodes, 0, nullptr);
    return doc;
  }

 private:
  bool AtEnd() const { return pos_ >= s_.size(); }
  char Peek(size_t ahead = 0) const { return pos_ + ahead < s_.size() ? s_[pos_ + ahead] : '\0'; }
  void Advance() {
    const char c = s_[pos_++];
    if (c == '\n') {
      ++line_;
      column_ = 1;
    } else if ((static_cast<unsigned char>(c) & 0xc0) != 0x80) {
      ++column_;
    }
  }
  [[noreturn]] void Fail(int line, int column, std::string message) const {
    throw Failure{ParseError{line, column, std::move(message)}};
  }
  [[noreturn]] void Fail(std::string message) const { Fail(line_, column_, std::move(message)); }

  Node Start(NodeKind kind) const {
    Node n;
    n.kind = kind;
    n.line = line_;
    n.column = column_;
    return n;
  }

  bool ReadSpace(std::vector<Node>& out) {
    if (AtEnd() || !IsSpace(Peek())) return false;
    Node n = Start(NodeKind::kSpace);
    const size_t begin = pos_;
    while (!AtEnd() && IsSpace(Peek())) Advance();
    n.raw = std::string(s_.substr(begin, pos_ - begin));
    out.push_back(std::move(n));
    return true;
  }

  std::string ReadName(const char* what) {
    if (AtEnd() || !IsNameStart(Peek()))
      Fail(std::string("expected ") + what +
           (AtEnd() ? " but the file ends" : " but found " + Describe(Peek())));
    const size_t begin = pos_;
    while (!AtEnd() && IsNameChar(Peek())) Advance();
    return std::string(s_.substr(begin, pos_ - begin));
  }

  // "DOCUMENT" [ \t]+ TYPE, then the end, whitespace or '<'.
  Node ReadHeader() {
    Node n = Start(NodeKind::kHeader);
    const size_t begin = pos_;
    if (s_.substr(pos_, 8) != "DOCUMENT")
      Fail(AtEnd() ? "expected a 'DOCUMENT <TYPE>' line but the file ends"
                   : "expected a 'DOCUMENT <TYPE>' line but found " + Describe(Peek()));
    for (int i = 0; i < 8; ++i) Advance();
    if (Peek() != ' ' && Peek() != '\t')
      Fail("expected a space and the document type after DOCUMENT");
    while (Peek() == ' ' || Peek() == '\t') Advance();
    n.name = ReadName("the document type");
    if (!AtEnd() && !IsSpace(Peek()) && Peek() != '<')
      Fail("unexpected " + Describe(Peek()) + " after the document type");
    n.raw = std::string(s_.substr(begin, pos_ - begin));
    return n;
  }

  // Spaces, the header, spaces, the root element, spaces; stops at the end of
  // the input (top level) or before "</" (inside <DOCUMENT>).
  void ReadDocumentContent(std::vector<Node>& out, int depth, const Node* owner) {
    ReadSpace(out);
    out.push_back(ReadHeader());
    const std::string type = out.back().name;
    ReadSpace(out);
    if (AtEnd()) Fail("expected the root element <" + type + "> but the file ends");
    if (Peek() != '<' || Peek(1) == '/')
      Fail("expected the root element <" + type + "> but found " + Describe(Peek()));
    const int line = line_, column = column_;
    out.push_back(ReadElement(depth + 1));
    if (out.back().name != type)
      Fail(line, column,
           "the root element <" + out.back().name + "> does not match the document type " + type);
    ReadSpace(out);
    if (owner == nullptr) {
      if (!AtEnd())
        Fail("unexpected " + Describe(Peek()) + " after the root element (a document has one)");
    } else if (AtEnd()) {
      Fail(owner->line, owner->column, "unterminated <DOCUMENT>: the file ends before </DOCUMENT>");
    } else if (!(Peek() == '<' && Peek(1) == '/')) {
      Fail("unexpected " + Describe(Peek()) + " in <DOCUMENT> after its root element");
    }
  }

  Node ReadElement(int depth) {
    if (depth > kMaxDepth) Fail("elements nested deeper than 256 levels");
    Node n = Start(NodeKind::kElement);
    Advance();  // '<'
    n.name = ReadName("a tag name after '<'");
    if (Peek() != '>')
      Fail(AtEnd() ? "the file ends inside the tag <" + n.name
                   : "expected '>' after <" + n.name + " but found " + Describe(Peek()));
    Advance();
    if (n.IsSubdocument()) {
      ReadDocumentContent(n.children, depth, &n);
    } else {
      ReadContent(n, depth);
    }
    // At "</".
    const int line = line_, column = column_;
    Advance();
    Advance();
    const std::string end = ReadName("a tag name after '</'");
    if (end != n.name)
      Fail(line, column,
           "</" + end + "> does not close <" + n.name + "> (opened at " + std::to_string(n.line) +
               ":" + std::to_string(n.column) + ")");
    if (Peek() != '>') Fail("expected '>' after </" + end);
    Advance();
    return n;
  }

  void ReadContent(Node& element, int depth) {
    for (;;) {
      if (ReadSpace(element.children)) continue;
      if (AtEnd())
        Fail(element.line, element.column,
             "unterminated <" + element.name + ">: the file ends before </" + element.name + ">");
      const char c = Peek();
      if (c == '<' && Peek(1) == '/') return;
      if (c == '<') {
        element.children.push_back(ReadElement(depth + 1));
      } else if (c == '{') {
        element.children.push_back(ReadText());
      } else if (c == '}') {
        Fail("unmatched '}' (write \\} for a brace inside a text)");
      } else {
        Fail("unexpected " + Describe(c) + " in <" + element.name +
             "> (text content goes inside {…})");
      }
    }
  }

  Node ReadText() {
    Node n = Start(NodeKind::kText);
    Advance();  // '{'
    const size_t begin = pos_;
    for (;;) {
      if (AtEnd())
        Fail(n.line, n.column, "unterminated text: the file ends before its closing '}'");
      const char c = Peek();
      if (c == '\\') {
        Advance();
        if (AtEnd()) continue;
        Advance();
      } else if (c == '{') {
        Fail("unescaped '{' inside a text (write \\{)");
      } else if (c == '}') {
        break;
      } else {
        Advance();
      }
    }
    n.raw = std::string(s_.substr(begin, pos_ - begin));
    Advance();  // '}'
    return n;
  }

  std::string_view s_;
  size_t pos_ = 0;
  int line_ = 1, column_ = 1;
};

void WriteNodes(const std::vector<Node>& nodes, std::string& out) {
  for (const Node& n : nodes) {
    switch (n.kind) {
      case NodeKind::kSpace:
      case NodeKind::kHeader:
        out += n.raw;
        break;
      case NodeKind::kText:
        out += '{';
        out += n.raw;
        out += '}';
        break;
      case NodeKind::kElement:
        out += '<' + n.name + '>';
        WriteNodes(n.children, out);
        out += "</" + n.name + '>';
        break;
    }
  }
}

std::optional<ParseError> At(const Node& n, std::string message) {
  return ParseError{n.line, n.column, std::move(message)};
}

std::optional<ParseError> CheckNodes(const std::vector<Node>& nodes, bool document,
                                     const Node* owner, int depth);

std::optional<ParseError> CheckNode(const Node& n, int depth) {
  if (depth > kMaxDepth) return At(n, "elements nested deeper than 256 levels");
  switch (n.kind) {
    case NodeKind::kSpace:
      if (n.raw.empty()) return At(n, "an empty space node");
      for (char c : n.raw)
        if (!IsSpace(c)) return At(n, "non-whitespace " + Describe(c) + " between tags");
      return std::nullopt;
    case NodeKind::kHeader: {
      auto parsed = Parse(n.raw + "\n<" + n.name + "></" + n.name + ">");
      if (!parsed.ok() || parsed.document->Type() != n.name)
        return At(n, "malformed header line '" + n.raw + "'");
      return std::nullopt;
    }
    case NodeKind::kText:
      for (size_t i = 0; i < n.raw.size(); ++i) {
        if (n.raw[i] == '\\') {
          if (++i == n.raw.size()) return At(n, "a text ends in a lone backslash");
        } else if (n.raw[i] == '{' || n.raw[i] == '}') {
          return At(n, "an unescaped brace in a text");
        }
      }
      return std::nullopt;
    case NodeKind::kElement:
      if (!IsTagName(n.name)) return At(n, "'" + n.name + "' is not a tag name");
      return CheckNodes(n.children, n.IsSubdocument(), &n, depth + 1);
  }
  return std::nullopt;
}

std::optional<ParseError> CheckNodes(const std::vector<Node>& nodes, bool document,
                                     const Node* owner, int depth) {
  int stage = 0;  // document: 0 before the header, 1 before the root, 2 after it
  std::string type;
  for (const Node& n : nodes) {
    if (auto e = CheckNode(n, depth)) return e;
    if (!document) {
      if (n.kind == NodeKind::kHeader) return At(n, "a DOCUMENT line outside <DOCUMENT>");
      continue;
    }
    if (n.kind == NodeKind::kSpace) continue;
    if (n.kind == NodeKind::kText) return At(n, "text directly inside a document");
    if (n.kind == NodeKind::kHeader) {
      if (stage != 0) return At(n, "a second DOCUMENT line");
      type = n.name, stage = 1;
    } else if (stage == 0) {
      return At(n, "<" + n.name + "> before the 'DOCUMENT <TYPE>' line");
    } else if (stage == 2) {
      return At(n, "a second root element <" + n.name + ">");
    } else if (n.name != type) {
      return At(n, "the root element <" + n.name + "> does not match the document type " + type);
    } else {
      stage = 2;
    }
  }
  if (document && stage != 2) {
    ParseError e = owner ? ParseError{owner->line, owner->column, ""} : ParseError{};
    e.message = stage == 0 ? "a document without its 'DOCUMENT <TYPE>' line"
                           : "a document without its root element";
    return e;
  }
  return std::nullopt;
}

}  // namespace

std::string Node::Text() const { return DecodeText(raw); }

Node Node::Element(std::string name, std::vector<Node> children) {
  Node n;
  n.kind = NodeKind::kElement;
  n.name = std::move(name);
  n.children = std::move(children);
  return n;
}
Node Node::Space(std::string whitespace) {
  Node n;
  n.kind = NodeKind::kSpace;
  n.raw = std::move(whitespace);
  return n;
}
Node Node::TextNode(std::string_view text) {
  Node n;
  n.kind = NodeKind::kText;
  n.raw = EncodeText(text);
  return n;
}
Node Node::Header(std::string type) {
  Node n;
  n.kind = NodeKind::kHeader;
  n.raw = "DOCUMENT " + type;
  n.name = std::move(type);
  return n;
}

const Node* Document::Root() const {
  for (const Node& n : nodes)
    if (n.kind == NodeKind::kElement) return &n;
  return nullptr;
}
Node* Document::Root() {
  for (Node& n : nodes)
    if (n.kind == NodeKind::kElement) return &n;
  return nullptr;
}
std::string Document::Type() const {
  for (const Node& n : nodes)
    if (n.kind == NodeKind::kHeader) return n.name;
  return "";
}

std::string ParseError::Format(std::string_view file) const {
  std::ostringstream s;
  s << (file.empty() ? "<input>" : file) << ":" << line << ":" << column << ": error: " << message;
  return s.str();
}

ParseResult Parse(std::string_view bytes) {
  ParseResult result;
  try {
    result.document = Reader(bytes).ReadDocument();
  } catch (const Failure& f) {
    result.error = f.error;
  }
  return result;
}

std::string Write(const Document& document) {
  std::string out;
  WriteNodes(document.nodes, out);
  return out;
}

std::string EncodeText(std::string_view text) {
  std::string out;
  out.reserve(text.size() + text.size() / 16);
  for (char c : text) {
    if (c == '{' || c == '}' || c == '\\') out += '\\';
    out += c;
  }
  return out;
}

std::string DecodeText(std::string_view raw) {
  std::string out;
  out.reserve(raw.size());
  for (size_t i = 0; i < raw.size(); ++i) {
    const char c = raw[i];
    if (c == '\\' && i + 1 < raw.size() &&
        (raw[i + 1] == '{' || raw[i + 1] == '}' || raw[i + 1] == '\\')) {
      out += raw[++i];
    } else {
      out += c;
    }
  }
  return out;
}

bool IsTagName(std::string_view name) {
  if (name.empty() || !IsNameStart(name[0])) return false;
  for (char c : name)
    if (!IsNameChar(c)) return false;
  return true;
}

std::optional<ParseError> CheckStructure(const Document& document) {
  return CheckNodes(document.nodes, true, nullptr, 0);
}

}  // namespace asgard::document
