// Document files.  Design: whole-file reads (documents are small next to the
// memory of any machine that renders them), atomic writes by temporary file +
// fsync + rename in the same directory (rename is atomic within a file
// system), and a plain RFC 4648 base64 for poster frames and XML payloads.
#include "formats/document/file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <vector>

#include "formats/document/xml.h"

namespace asgard::document {

namespace {

constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

}  // namespace

std::string Extension(std::string_view path) {
  const size_t dot = path.rfind('.'), slash = path.rfind('/');
  if (dot == std::string_view::npos || (slash != std::string_view::npos && dot < slash)) return "";
  std::string ext(path.substr(dot + 1));
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

bool ReadFile(const std::string& path, std::string& bytes, std::string* error) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    if (error) *error = "cannot read '" + path + "': " + std::strerror(errno);
    return false;
  }
  std::ostringstream s;
  s << in.rdbuf();
  if (in.bad()) {
    if (error) *error = "cannot read '" + path + "'";
    return false;
  }
  bytes = s.str();
  return true;
}

bool WriteFileAtomic(const std::string& requested, std::string_view bytes, std::string* error) {
  // An existing target is replaced as it was: through a symbolic link (the
  // link stays, its target gets the bytes), with its mode and owner; one with
  // several hard links, or that is not a regular file, is refused, since
  // replacing it would split the links.
  std::string path = requested;
  struct stat old {};
  bool exists = false;
  if (::lstat(requested.c_str(), &old) == 0) {
    if (S_ISLNK(old.st_mode)) {
      char* real = ::realpath(requested.c_str(), nullptr);
      if (real == nullptr) {
        if (error)
          *error = "cannot write '" + requested + "': it is a symbolic link to a missing file";
        return false;
      }
      path = real;
      std::free(real);
      if (::stat(path.c_str(), &old) != 0) {
        if (error) *error = "cannot write '" + requested + "': " + std::strerror(errno);
        return false;
      }
    }
    if (!S_ISREG(old.st_mode)) {
      if (error) *error = "cannot write '" + requested + "': not a regular file";
      return false;
    }
    if (old.st_nlink > 1) {
      if (error)
        *error = "cannot write '" + requested + "': it has " + std::to_string(old.st_nlink) +
                 " hard links, which replacing it would split; write to another file";
      return false;
    }
    exists = true;
  }
  const size_t slash = path.rfind('/');
  const std::string dir = slash == std::string::npos ? "." : path.substr(0, slash + 1);
  const std::string base = slash == std::string::npos ? path : path.substr(slash + 1);
  std::string tmpl = (slash == std::string::npos ? "" : dir) + "." + base + ".tmp.XXXXXX";
  std::vector<char> name(tmpl.begin(), tmpl.end());
  name.push_back('\0');
  const int fd = mkstemp(name.data());
  auto fail = [&](const std::string& what) {
    if (error) *error = "cannot write '" + path + "': " + what + ": " + std::strerror(errno);
    return false;
  };
  if (fd < 0) return fail("cannot create a temporary file");
  const std::string tmp(name.data());
  size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int saved = errno;
      ::close(fd);
      ::unlink(tmp.c_str());
      errno = saved;
      return fail("write failed");
    }
    done += static_cast<size_t>(n);
  }
  if (exists) {
    // Keeps the replaced file's mode and owner.
    ::fchmod(fd, old.st_mode & 07777);
    if ((old.st_uid != ::geteuid() || old.st_gid != ::getegid()) &&
        ::fchown(fd, old.st_uid, old.st_gid) != 0) {
      const int saved = errno;
      ::close(fd);
      ::unlink(tmp.c_str());
      errno = saved;
      return fail("cannot give the new file the owner of the old one");
    }
  } else {
    // A new file gets ordinary permissions (mkstemp makes it 0600).
    const mode_t mask = ::umask(0);
    ::umask(mask);
    ::fchmod(fd, 0666 & ~mask);
  }
  if (::fsync(fd) != 0 || ::close(fd) != 0) {
    const int saved = errno;
    ::unlink(tmp.c_str());
    errno = saved;
    return fail("flush failed");
  }
  if (::rename(tmp.c_str(), path.c_str()) != 0) {
    const int saved = errno;
    ::unlink(tmp.c_str());
    errno = saved;
    return fail("rename failed");
  }
  return true;
}

Flavour FlavourForPath(const std::string& path) {
  return Extension(path) == "xml" ? Flavour::kXml : Flavour::kSgml;
}

LoadResult LoadDocument(const std::string& path) {
  LoadResult r;
  std::string bytes, error;
  if (!ReadFile(path, bytes, &error)) {
    r.error = error;
    return r;
  }
  r.flavour = LooksLikeXml(bytes) ? Flavour::kXml : Flavour::kSgml;
  ParseResult parsed = r.flavour == Flavour::kXml ? ParseXml(bytes) : Parse(bytes);
  if (!parsed.ok()) {
    r.error = parsed.error.Format(path);
    return r;
  }
  r.document = std::move(parsed.document);
  return r;
}

bool SaveDocument(const Document& document, const std::string& path, std::string* error) {
  // A file that exists keeps its flavour, whatever its name says.
  Flavour flavour = FlavourForPath(path);
  std::ifstream in(path, std::ios::binary);
  if (in) {
    char head[512];
    in.read(head, sizeof head);
    flavour = LooksLikeXml(std::string_view(head, static_cast<size_t>(in.gcount())))
                  ? Flavour::kXml
                  : Flavour::kSgml;
  }
  const std::string bytes = flavour == Flavour::kXml ? WriteXml(document) : Write(document);
  return WriteFileAtomic(path, bytes, error);
}

std::string Base64Encode(std::string_view bytes, size_t line_length) {
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4 + (line_length ? bytes.size() / line_length + 1 : 0));
  size_t column = 0;
  auto put = [&](char c) {
    if (line_length && column == line_length) {
      out += '\n';
      column = 0;
    }
    out += c;
    ++column;
  };
  size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const uint32_t v = (uint32_t(uint8_t(bytes[i])) << 16) |
                       (uint32_t(uint8_t(bytes[i + 1])) << 8) | uint8_t(bytes[i + 2]);
    put(kAlphabet[v >> 18]);
    put(kAlphabet[(v >> 12) & 63]);
    put(kAlphabet[(v >> 6) & 63]);
    put(kAlphabet[v & 63]);
  }
  if (i < bytes.size()) {
    uint32_t v = uint32_t(uint8_t(bytes[i])) << 16;
    if (i + 1 < bytes.size()) v |= uint32_t(uint8_t(bytes[i + 1])) << 8;
    put(kAlphabet[v >> 18]);
    put(kAlphabet[(v >> 12) & 63]);
    put(i + 1 < bytes.size() ? kAlphabet[(v >> 6) & 63] : '=');
    put('=');
  }
  return out;
}

std::optional<std::string> Base64Decode(std::string_view text) {
  std::string out;
  out.reserve(text.size() * 3 / 4);
  uint32_t acc = 0;
  int bits = 0, pad = 0;
  for (char c : text) {
    int v;
    if (c >= 'A' && c <= 'Z')
      v = c - 'A';
    else if (c >= 'a' && c <= 'z')
      v = c - 'a' + 26;
    else if (c >= '0' && c <= '9')
      v = c - '0' + 52;
    else if (c == '+')
      v = 62;
    else if (c == '/')
      v = 63;
    else if (c == '=') {
      ++pad;
      continue;
    } else if (c == ' ' || c == '\n' || c == '\r' || c == '\t') {
      continue;
    } else {
      return std::nullopt;
    }
    if (pad) return std::nullopt;  // data after padding
    acc = (acc << 6) | static_cast<uint32_t>(v);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out += static_cast<char>((acc >> bits) & 0xff);
    }
  }
  if (pad > 2) return std::nullopt;
  return out;
}

}  // namespace asgard::document
