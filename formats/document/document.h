// Compound documents in the seed's SGML-like storage format (Figure 6.2).
//
//   DOCUMENT CMEMO                      ← header line: the document's type
//   <CMEMO>                             ← the root element, named after the type
//   <TO>{Whom it may concern}</TO>      ← {…} text content; \{ \} \\ escape
//   <PARAGRAPH><DOCUMENT>               ← a nested subdocument: same content model
//   DOCUMENT ANIMATION                     as a file (header line, one root element)
//   <ANIMATION><ASGARD>{…}</ASGARD></ANIMATION>
//   </DOCUMENT></PARAGRAPH>
//   </CMEMO>
//
// The tree keeps every byte: whitespace between tags is a kSpace node, a text
// keeps the bytes between its braces exactly as written (`raw`), and a header
// keeps its line as written.  Write(Parse(bytes)) == bytes for every input
// Parse accepts.  Decoding a text is lenient: only \{ \} \\ are escapes, any
// other backslash stands for itself; an unescaped '{' inside a text is an
// error (it would be ambiguous to a reader that does not count braces).
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace asgard::document {

enum class NodeKind { kElement, kText, kSpace, kHeader };

struct Node {
  NodeKind kind = NodeKind::kSpace;
  // kElement: the tag name; kHeader: the document type.
  std::string name;
  // kText: bytes between the braces as stored; kSpace: the whitespace;
  // kHeader: the header line as written ("DOCUMENT CMEMO").
  std::string raw;
  std::vector<Node> children;  // kElement
  int line = 0, column = 0;    // where the node starts (1-based; 0 when built in memory)

  // The decoded text of a kText node.
  std::string Text() const;
  bool IsElement(std::string_view tag) const { return kind == NodeKind::kElement && name == tag; }
  // A <DOCUMENT> element: its children are a header, a root element and spaces.
  bool IsSubdocument() const { return IsElement("DOCUMENT"); }

  static Node Element(std::string name, std::vector<Node> children = {});
  static Node Space(std::string whitespace);
  static Node TextNode(std::string_view text);  // encodes the text
  static Node Header(std::string type);
};

// A file: optional whitespace, the header line, whitespace, the root element,
// optional whitespace.
struct Document {
  std::vector<Node> nodes;

  const Node* Root() const;
  Node* Root();
  std::string Type() const;
};

struct ParseError {
  int line = 0, column = 0;  // 1-based; column counts characters (UTF-8 code points)
  std::string message;
  std::string Format(std::string_view file = {}) const;  // FILE:LINE:COL: error: message
};

struct ParseResult {
  std::optional<Document> document;
  ParseError error;
  bool ok() const { return document.has_value(); }
};

// Reads the SGML-like flavour.  Never throws.
ParseResult Parse(std::string_view bytes);
// Writes it back: byte-for-byte what was parsed, for a tree from Parse.
std::string Write(const Document& document);

// Text content codec: Encode escapes '{', '}' and '\' with a backslash;
// Decode undoes it (other backslashes stand for themselves).
std::string EncodeText(std::string_view text);
std::string DecodeText(std::string_view raw);

// Checks the content model of a tree built in memory or read from XML: a
// document (and every <DOCUMENT> element) holds spaces, exactly one header
// and exactly one root element named after the header's type, in that order;
// spaces are whitespace only; names are valid tag names; a text's raw bytes
// have no unescaped brace and do not end in a lone backslash.  Returns the
// first problem, located at the offending node.
std::optional<ParseError> CheckStructure(const Document& document);

bool IsTagName(std::string_view name);

// Depth-first walk over every node (elements before their children).
template <typename F>
void ForEachNode(std::vector<Node>& nodes, F&& f) {
  for (Node& n : nodes) {
    f(n);
    ForEachNode(n.children, f);
  }
}
template <typename F>
void ForEachNode(const std::vector<Node>& nodes, F&& f) {
  for (const Node& n : nodes) {
    f(n);
    ForEachNode(n.children, f);
  }
}

}  // namespace asgard::document
