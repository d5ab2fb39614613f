// Document files: reading either flavour, writing atomically, base64.
//
// Writes never leave a half-written file behind: the bytes go to a temporary
// file in the target's directory, are flushed to disk, and the temporary is
// renamed over the target; on any failure the temporary is removed and the
// target is untouched.  An existing target keeps its mode and owner, a
// symbolic link is written through, and a file with several hard links (or
// not a regular file) is refused rather than split.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "formats/document/document.h"

namespace asgard::document {

enum class Flavour { kSgml, kXml };

bool ReadFile(const std::string& path, std::string& bytes, std::string* error);

// The extension of a file name, lower case, without the dot ("" when the last
// path component has none): what chooses an output format everywhere.
std::string Extension(std::string_view path);
bool WriteFileAtomic(const std::string& path, std::string_view bytes, std::string* error);

// Reads a document file; the flavour is chosen by the content (an XML
// declaration or '<ens:file'), so a misnamed file still reads.
struct LoadResult {
  std::optional<Document> document;
  Flavour flavour = Flavour::kSgml;
  std::string error;  // formatted "FILE:LINE:COL: error: message"
};
LoadResult LoadDocument(const std::string& path);
// Writes in the flavour the extension names (.xml: XML, anything else: SGML),
// or, when the file exists, in the flavour it has.
bool SaveDocument(const Document& document, const std::string& path, std::string* error);
Flavour FlavourForPath(const std::string& path);

std::string Base64Encode(std::string_view bytes, size_t line_length = 0);
// Skips whitespace; nullopt on any other character outside the alphabet.
std::optional<std::string> Base64Decode(std::string_view text);

}  // namespace asgard::document
