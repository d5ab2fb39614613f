// The XML flavour of compound documents, read and written with libxml2.
//
//   <?xml version="1.0" encoding="UTF-8"?>
//   <ens:file xmlns:ens="urn:asgard:ensemble-document"><ens:header>DOCUMENT CMEMO</ens:header>
//   <CMEMO>
//   <TO><ens:text>Whom it may concern</ens:text></TO>
//   …
//   <ASGARD><ens:text>
//   shape_set ss1 -desc {-sub {-pos {0 0 0} -sphere 0.5}}
//   …</ens:text></ASGARD>
//
// Elements keep their tag names; whitespace between tags is XML character
// data; a header line is an ens:header element; a text is an ens:text element
// holding the *decoded* text (braces unescaped, XML-escaped by libxml2).  When
// the stored bytes are not the canonical escaping of that text (a lenient
// backslash such as `\n`), the exact bytes go in a `raw` attribute; when they
// cannot be XML at all (control characters, invalid UTF-8) the element has
// encoding="base64" and holds the stored bytes in base64.  So
// sgml → xml → sgml is byte-exact, and xml → sgml → xml too for files this
// writer made.  XML comments and processing instructions are ignored.
#pragma once

#include <string>
#include <string_view>

#include "formats/document/document.h"

namespace asgard::document {

inline constexpr const char* kXmlNamespace = "urn:asgard:ensemble-document";

std::string WriteXml(const Document& document);
// Errors carry the XML line and column (libxml2's) or the offending node's line.
ParseResult ParseXml(std::string_view bytes);

// True when the bytes look like XML rather than the SGML-like flavour.
bool LooksLikeXml(std::string_view bytes);

}  // namespace asgard::document
