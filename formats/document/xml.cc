// The XML flavour through libxml2's tree API.
//
// Design: the writer builds an xmlDoc node for node and serialises it without
// indentation (formatting would add whitespace that is not in the document);
// libxml2 escapes '\r', tabs and newlines in attributes as character
// references, so every byte survives.  The reader parses with network access
// and external entities off, walks the tree back into Nodes, and then checks
// the content model with CheckStructure, so an XML file can hold nothing the
// SGML flavour cannot.  Parse errors are not printed (NOERROR, NOWARNING);
// the first one's line and column are read back from the context.  Without
// XML_PARSE_HUGE libxml2 keeps its own limits (nesting 256 deep, text nodes
// of 10 MB, entity amplification); a document type declaration, the only
// way to declare entities, is refused outright.
#include "formats/document/xml.h"

#include <libxml/parser.h>
#include <libxml/tree.h>

#include <algorithm>
#include <memory>

#include "formats/document/file.h"

namespace asgard::document {

namespace {

const xmlChar* X(const char* s) { return reinterpret_cast<const xmlChar*>(s); }
const char* C(const xmlChar* s) { return reinterpret_cast<const char*>(s); }

// Valid UTF-8 without the characters XML 1.0 cannot carry (C0 controls other
// than tab, newline and carriage return; U+FFFE, U+FFFF).
bool XmlSafe(std::string_view s) {
  for (size_t i = 0; i < s.size();) {
    const auto c = static_cast<unsigned char>(s[i]);
    if (c < 0x80) {
      if (c < 0x20 && c != '\t' && c != '\n' && c != '\r') return false;
      ++i;
      continue;
    }
    const size_t n = c >= 0xc2 && c <= 0xdf   ? 1
                     : c >= 0xe0 && c <= 0xef ? 2
                     : c >= 0xf0 && c <= 0xf4 ? 3
                                              : 0;
    if (n == 0 || i + n >= s.size()) return false;
    uint32_t cp = c & (0x3fu >> n);
    for (size_t k = 1; k <= n; ++k) {
      const auto d = static_cast<unsigned char>(s[i + k]);
      if ((d & 0xc0) != 0x80) return false;
      cp = (cp << 6) | (d & 0x3f);
    }
    const uint32_t min = n == 1 ? 0x80 : n == 2 ? 0x800 : 0x10000;
    if (cp < min || cp > 0x10ffff || (cp >= 0xd800 && cp <= 0xdfff) || cp == 0xfffe || cp == 0xffff)
      return false;
    i += n + 1;
  }
  return true;
}

void AddNodes(xmlNodePtr parent, xmlNsPtr ns, const std::vector<Node>& nodes) {
  for (const Node& n : nodes) {
    switch (n.kind) {
      case NodeKind::kSpace:
        xmlAddChild(parent, xmlNewTextLen(X(n.raw.c_str()), static_cast<int>(n.raw.size())));
        break;
      case NodeKind::kHeader:
        xmlNewTextChild(parent, ns, X("header"), nullptr);
        xmlAddChild(parent->last, xmlNewTextLen(X(n.raw.c_str()), static_cast<int>(n.raw.size())));
        break;
      case NodeKind::kText: {
        xmlNodePtr t = xmlNewChild(parent, ns, X("text"), nullptr);
        const std::string decoded = DecodeText(n.raw);
        if (!XmlSafe(n.raw)) {
          xmlSetProp(t, X("encoding"), X("base64"));
          xmlAddChild(t, xmlNewText(X(Base64Encode(n.raw).c_str())));
          break;
        }
        if (EncodeText(decoded) != n.raw) xmlSetProp(t, X("raw"), X(n.raw.c_str()));
        xmlAddChild(t, xmlNewTextLen(X(decoded.c_str()), static_cast<int>(decoded.size())));
        break;
      }
      case NodeKind::kElement: {
        // (xmlNewChild would give it the parent's namespace.)
        xmlNodePtr e =
            xmlAddChild(parent, xmlNewDocNode(parent->doc, nullptr, X(n.name.c_str()), nullptr));
        AddNodes(e, ns, n.children);
        break;
      }
    }
  }
}

struct DocDeleter {
  void operator()(xmlDocPtr d) const { xmlFreeDoc(d); }
};
struct CtxtDeleter {
  void operator()(xmlParserCtxtPtr c) const { xmlFreeParserCtxt(c); }
};

std::string Content(xmlNodePtr n) {
  xmlChar* c = xmlNodeGetContent(n);
  std::string s = c ? C(c) : "";
  xmlFree(c);
  return s;
}

bool IsOurs(xmlNodePtr n, const char* local) {
  return n->ns && n->ns->href && std::string_view(C(n->ns->href)) == kXmlNamespace &&
         std::string_view(C(n->name)) == local;
}

// Fills `out` from the children of `parent`; returns an error message (and
// sets `line`) on anything the document model cannot hold.
std::string ReadNodes(xmlNodePtr parent, std::vector<Node>& out, int& line) {
  for (xmlNodePtr x = parent->children; x; x = x->next) {
    Node n;
    n.line = static_cast<int>(xmlGetLineNo(x));
    n.column = 1;
    line = n.line;
    if (x->type == XML_COMMENT_NODE || x->type == XML_PI_NODE) continue;
    if (x->type == XML_TEXT_NODE || x->type == XML_CDATA_SECTION_NODE) {
      n.kind = NodeKind::kSpace;
      n.raw = x->content ? C(x->content) : "";
      if (n.raw.empty()) continue;
      if (!out.empty() && out.back().kind == NodeKind::kSpace) {
        out.back().raw += n.raw;
        continue;
      }
    } else if (x->type != XML_ELEMENT_NODE) {
      return "unsupported XML node (entity references are not allowed)";
    } else if (IsOurs(x, "header")) {
      n.kind = NodeKind::kHeader;
      n.raw = Content(x);
      // The type is the word after DOCUMENT; the structure check validates it.
      const size_t sp = n.raw.find_first_of(" \t");
      if (sp != std::string::npos) {
        const size_t b = n.raw.find_first_not_of(" \t", sp);
        if (b != std::string::npos) n.name = n.raw.substr(b);
      }
    } else if (IsOurs(x, "text")) {
      n.kind = NodeKind::kText;
      xmlChar* enc = xmlGetProp(x, X("encoding"));
      xmlChar* raw = xmlGetProp(x, X("raw"));
      const std::string content = Content(x);
      if (enc) {
        const bool b64 = std::string_view(C(enc)) == "base64";
        xmlFree(enc);
        if (raw) xmlFree(raw);
        if (!b64) return "ens:text: the only encoding is base64";
        auto bytes = Base64Decode(content);
        if (!bytes) return "ens:text: invalid base64";
        n.raw = *bytes;
      } else if (raw) {
        n.raw = C(raw);
        xmlFree(raw);
        if (DecodeText(n.raw) != content)
          return "ens:text: its raw attribute does not match its text";
      } else {
        n.raw = EncodeText(content);
      }
    } else if (x->ns && x->ns->href && std::string_view(C(x->ns->href)) == kXmlNamespace) {
      return std::string("unknown element ens:") + C(x->name);
    } else {
      if (x->ns) return std::string("element <") + C(x->name) + "> has a namespace";
      if (x->properties) return std::string("element <") + C(x->name) + "> has attributes";
      n.kind = NodeKind::kElement;
      n.name = C(x->name);
      if (auto e = ReadNodes(x, n.children, line); !e.empty()) return e;
    }
    out.push_back(std::move(n));
  }
  return "";
}

}  // namespace

std::string WriteXml(const Document& document) {
  std::unique_ptr<xmlDoc, DocDeleter> doc(xmlNewDoc(X("1.0")));
  xmlNodePtr root = xmlNewNode(nullptr, X("file"));
  xmlNsPtr ns = xmlNewNs(root, X(kXmlNamespace), X("ens"));
  xmlSetNs(root, ns);
  xmlDocSetRootElement(doc.get(), root);
  AddNodes(root, ns, document.nodes);
  xmlChar* mem = nullptr;
  int size = 0;
  xmlDocDumpFormatMemoryEnc(doc.get(), &mem, &size, "UTF-8", 0);
  std::string out(C(mem), static_cast<size_t>(size));
  xmlFree(mem);
  return out;
}

// The first error (not a warning) libxml2 reports while this thread
// parses (the reader resets the context it is given, so the record is
// found through a thread-local pointer, not the context).
struct FirstError {
  ParseError error;
  bool set = false;
  static thread_local FirstError* current;
  explicit FirstError() { current = this; }
  ~FirstError() { current = nullptr; }
  FirstError(const FirstError&) = delete;
  FirstError& operator=(const FirstError&) = delete;
  static void Record(void*, xmlErrorPtr e) {
    if (current && !current->set && e && e->level >= XML_ERR_ERROR) current->Take(e);
  }
  // Falls back to `last` when no error was recorded.
  void Use(const xmlError* last) {
    if (!set && last) Take(last);
    if (!set) error = ParseError{1, 1, "XML: not well-formed XML"};
  }
  void Take(const xmlError* e) {
    std::string message = e->message ? e->message : "not well-formed XML";
    while (!message.empty() && (message.back() == '\n' || message.back() == ' '))
      message.pop_back();
    error = ParseError{e->line > 0 ? e->line : 1, e->int2 > 0 ? e->int2 : 1, "XML: " + message};
    set = true;
  }
};
thread_local FirstError* FirstError::current = nullptr;

ParseResult ParseXml(std::string_view bytes) {
  ParseResult result;
  // The writer never declares a document type.  One in the input can only
  // declare entities, and entities are how XML files amplify (billion laughs,
  // quadratic blow-up), so it is refused before libxml2 sees the file.
  if (const size_t at = bytes.find("<!DOCTYPE"); at != std::string_view::npos) {
    int line = 1, column = 1;
    for (size_t i = 0; i < at; ++i) {
      if (bytes[i] == '\n') {
        ++line;
        column = 1;
      } else {
        ++column;
      }
    }
    result.error = ParseError{line, column,
                              "XML: document type declarations (and the entities they declare) "
                              "are not allowed in Asgard documents"};
    return result;
  }
  std::unique_ptr<xmlParserCtxt, CtxtDeleter> ctxt(xmlNewParserCtxt());
  if (!ctxt) {
    result.error = ParseError{1, 1, "out of memory"};
    return result;
  }
  // The first error is the cause; libxml2 goes on past it and its last
  // error is often a consequence ("Extra content at the end of the
  // document" after a bad attribute).  Errors come to this handler, not
  // stderr.
  FirstError first;
  ctxt->sax->serror = &FirstError::Record;
  ctxt->sax->initialized = XML_SAX2_MAGIC;
  std::unique_ptr<xmlDoc, DocDeleter> doc(xmlCtxtReadMemory(
      ctxt.get(), bytes.data(), static_cast<int>(bytes.size()), nullptr, nullptr,
      XML_PARSE_NONET | XML_PARSE_NOCDATA | XML_PARSE_NOERROR | XML_PARSE_NOWARNING));
  if (!doc || !ctxt->wellFormed) {
    first.Use(xmlCtxtGetLastError(ctxt.get()));
    result.error = first.error;
    return result;
  }
  xmlNodePtr root = xmlDocGetRootElement(doc.get());
  if (!root || !IsOurs(root, "file")) {
    result.error =
        ParseError{root ? static_cast<int>(xmlGetLineNo(root)) : 1, 1,
                   std::string("the root element must be ens:file in namespace ") + kXmlNamespace};
    return result;
  }
  Document d;
  int line = 1;
  if (auto e = ReadNodes(root, d.nodes, line); !e.empty()) {
    result.error = ParseError{line, 1, e};
    return result;
  }
  if (auto e = CheckStructure(d)) {
    result.error = *e;
    // What is missing at the top level is missing from the ens:file element.
    if (result.error.line < 1) result.error.line = static_cast<int>(xmlGetLineNo(root));
    result.error.line = std::max(result.error.line, 1);
    result.error.column = std::max(result.error.column, 1);
    return result;
  }
  result.document = std::move(d);
  return result;
}

bool LooksLikeXml(std::string_view bytes) {
  size_t i = 0;
  if (bytes.substr(0, 3) == "\xef\xbb\xbf") i = 3;
  while (i < bytes.size() &&
         (bytes[i] == ' ' || bytes[i] == '\n' || bytes[i] == '\r' || bytes[i] == '\t'))
    ++i;
  return bytes.substr(i, 5) == "<?xml" || bytes.substr(i, 9) == "<ens:file";
}

}  // namespace asgard::document
